//! Smoothing kernels `W(r; h) = α_n f(q)`, `q = r/h`, and their gradients.
//!
//! | kernel | support | f(q) | α (2D) · h² | α (3D) · h³ |
//! |---|---|---|---|---|
//! | Wendland C2 (Wendland 1995) | 2h | (1-q/2)⁴(2q+1) | 7/(4π) | 21/(16π) |
//! | Wendland C4 | 2h | (1-q/2)⁶(35q²/12+3q+1) | 9/(4π) | 495/(256π) |
//! | cubic spline (Monaghan & Lattanzio 1985) | 2h | 1-1.5q²+0.75q³ / 0.25(2-q)³ | 10/(7π) | 1/π |
//! | quintic spline (Morris 1997) | 3h | (3-q)⁵-6(2-q)⁵+15(1-q)⁵ | 7/(478π) | 1/(120π) |
//! | truncated Gaussian | 3h | exp(-q²), renormalised on the support | 1/[π(1-e⁻⁹)] | 1/[π^{3/2} erf 3 - 6π e⁻⁹] |
//!
//! Every kernel exposes `W(r)` and `W'(r)/r`, so that `∇_i W_ij = x_ij · W'(r)/r`
//! (which points from i towards j, since `W' <= 0`). Writing the gradient through
//! `W'/r` keeps it finite at `r = 0`.

use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// A radial, compactly supported smoothing kernel with a fixed smoothing length.
///
/// Implementors are small `Copy` values built once per run; the pair loops are
/// generic over them, so each kernel gets its own monomorphised loop.
pub trait Kernel: Copy + Send + Sync + 'static {
    /// Support radius in units of h (`R = SUPPORT · h`).
    const SUPPORT: f64;
    /// The kernel with smoothing length `h` normalised in `dim` dimensions (2 or 3).
    fn new(h: f64, dim: usize) -> Self;
    /// Smoothing length.
    fn h(&self) -> f64;
    /// `W(r)`; zero for `r >= R`.
    fn w(&self, r: f64) -> f64;
    /// `W'(r)/r`, finite at `r = 0`; zero for `r >= R`.
    fn dw_over_r(&self, r: f64) -> f64;
    /// Support radius `R = SUPPORT · h`.
    fn radius(&self) -> f64 {
        Self::SUPPORT * self.h()
    }
}

/// The kernel a case asks for; resolved once into a [`Kernel`] type.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum KernelChoice {
    /// Wendland C2, support 2h.
    WendlandC2,
    /// Wendland C4, support 2h.
    WendlandC4,
    /// Cubic B-spline, support 2h.
    CubicSpline,
    /// Quintic B-spline, support 3h.
    QuinticSpline,
    /// Gaussian truncated at 3h.
    Gaussian,
}

impl KernelChoice {
    /// Support radius in units of h.
    pub fn support(self) -> f64 {
        match self {
            KernelChoice::WendlandC2 => WendlandC2::SUPPORT,
            KernelChoice::WendlandC4 => WendlandC4::SUPPORT,
            KernelChoice::CubicSpline => CubicSpline::SUPPORT,
            KernelChoice::QuinticSpline => QuinticSpline::SUPPORT,
            KernelChoice::Gaussian => Gaussian::SUPPORT,
        }
    }

    /// The kernel with smoothing length `h` in `dim` dimensions behind a trait object,
    /// for code outside the pair loops (reading snapshots back), where an indirect call
    /// per evaluation costs nothing that matters.
    pub fn with_length(self, h: f64, dim: usize) -> Box<dyn Smoothing> {
        match self {
            KernelChoice::WendlandC2 => Box::new(WendlandC2::new(h, dim)),
            KernelChoice::WendlandC4 => Box::new(WendlandC4::new(h, dim)),
            KernelChoice::CubicSpline => Box::new(CubicSpline::new(h, dim)),
            KernelChoice::QuinticSpline => Box::new(QuinticSpline::new(h, dim)),
            KernelChoice::Gaussian => Box::new(Gaussian::new(h, dim)),
        }
    }
}

/// What interpolation at a point needs of a kernel: `W(r)` and its support radius. A
/// scheme's model provides it, and so does every [`Kernel`].
pub trait Smoothing: Send + Sync {
    /// `W(r)`; zero for `r >= R`.
    fn w(&self, r: f64) -> f64;
    /// The support radius R.
    fn support_radius(&self) -> f64;
}

impl<K: Kernel> Smoothing for K {
    fn w(&self, r: f64) -> f64 {
        Kernel::w(self, r)
    }
    fn support_radius(&self) -> f64 {
        self.radius()
    }
}

/// `α = a_dim / h^dim`, with `a = (a_2d, a_3d)`.
fn normalisation(h: f64, dim: usize, a: (f64, f64)) -> f64 {
    match dim {
        2 => a.0 / (h * h),
        3 => a.1 / (h * h * h),
        _ => panic!("kernels are normalised for 2 and 3 dimensions, not {dim}"),
    }
}

macro_rules! kernel_struct {
    ($(#[$doc:meta])* $name:ident) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy)]
        pub struct $name {
            h: f64,
            inv_h: f64,
            alpha: f64,
        }
    };
}

kernel_struct!(
    /// Wendland C2: `f(q) = (1-q/2)⁴(2q+1)`, `f'(q)/q = -5(1-q/2)³`.
    WendlandC2
);
kernel_struct!(
    /// Wendland C4: `f(q) = (1-q/2)⁶(35q²/12+3q+1)`, `f'(q)/q = -(14/3)(1+5q/2)(1-q/2)⁵`.
    WendlandC4
);
kernel_struct!(
    /// Cubic B-spline (M4) with support 2h.
    CubicSpline
);
kernel_struct!(
    /// Quintic B-spline (M6) with support 3h.
    QuinticSpline
);
kernel_struct!(
    /// Gaussian `exp(-q²)` truncated at 3h and renormalised to unit mass on its support.
    /// It jumps by about e⁻⁹ of its peak at the edge of the support.
    Gaussian
);

impl Kernel for WendlandC2 {
    const SUPPORT: f64 = 2.0;
    fn new(h: f64, dim: usize) -> Self {
        let alpha = normalisation(h, dim, (7.0 / (4.0 * PI), 21.0 / (16.0 * PI)));
        Self {
            h,
            inv_h: 1.0 / h,
            alpha,
        }
    }
    fn h(&self) -> f64 {
        self.h
    }
    #[inline(always)]
    fn w(&self, r: f64) -> f64 {
        let q = r * self.inv_h;
        let s = (1.0 - 0.5 * q).max(0.0);
        self.alpha * s.powi(4) * (2.0 * q + 1.0)
    }
    #[inline(always)]
    fn dw_over_r(&self, r: f64) -> f64 {
        let q = r * self.inv_h;
        let s = (1.0 - 0.5 * q).max(0.0);
        -5.0 * self.alpha * s * s * s * self.inv_h * self.inv_h
    }
}

impl Kernel for WendlandC4 {
    const SUPPORT: f64 = 2.0;
    fn new(h: f64, dim: usize) -> Self {
        let alpha = normalisation(h, dim, (9.0 / (4.0 * PI), 495.0 / (256.0 * PI)));
        Self {
            h,
            inv_h: 1.0 / h,
            alpha,
        }
    }
    fn h(&self) -> f64 {
        self.h
    }
    #[inline(always)]
    fn w(&self, r: f64) -> f64 {
        let q = r * self.inv_h;
        let s = (1.0 - 0.5 * q).max(0.0);
        self.alpha * s.powi(6) * (35.0 / 12.0 * q * q + 3.0 * q + 1.0)
    }
    #[inline(always)]
    fn dw_over_r(&self, r: f64) -> f64 {
        let q = r * self.inv_h;
        let s = (1.0 - 0.5 * q).max(0.0);
        -14.0 / 3.0 * self.alpha * (1.0 + 2.5 * q) * s.powi(5) * self.inv_h * self.inv_h
    }
}

impl Kernel for CubicSpline {
    const SUPPORT: f64 = 2.0;
    fn new(h: f64, dim: usize) -> Self {
        let alpha = normalisation(h, dim, (10.0 / (7.0 * PI), 1.0 / PI));
        Self {
            h,
            inv_h: 1.0 / h,
            alpha,
        }
    }
    fn h(&self) -> f64 {
        self.h
    }
    #[inline(always)]
    fn w(&self, r: f64) -> f64 {
        let q = r * self.inv_h;
        let f = if q < 1.0 {
            1.0 - 1.5 * q * q + 0.75 * q * q * q
        } else {
            0.25 * (2.0 - q).max(0.0).powi(3)
        };
        self.alpha * f
    }
    #[inline(always)]
    fn dw_over_r(&self, r: f64) -> f64 {
        let q = r * self.inv_h;
        let f_over_q = if q < 1.0 {
            -3.0 + 2.25 * q
        } else {
            -0.75 * (2.0 - q).max(0.0).powi(2) / q
        };
        self.alpha * f_over_q * self.inv_h * self.inv_h
    }
}

impl Kernel for QuinticSpline {
    const SUPPORT: f64 = 3.0;
    fn new(h: f64, dim: usize) -> Self {
        let alpha = normalisation(h, dim, (7.0 / (478.0 * PI), 1.0 / (120.0 * PI)));
        Self {
            h,
            inv_h: 1.0 / h,
            alpha,
        }
    }
    fn h(&self) -> f64 {
        self.h
    }
    #[inline(always)]
    fn w(&self, r: f64) -> f64 {
        let q = r * self.inv_h;
        let a = (3.0 - q).max(0.0).powi(5);
        let b = (2.0 - q).max(0.0).powi(5);
        let c = (1.0 - q).max(0.0).powi(5);
        self.alpha * (a - 6.0 * b + 15.0 * c)
    }
    #[inline(always)]
    fn dw_over_r(&self, r: f64) -> f64 {
        let q = r * self.inv_h;
        // f'(0) = 0 and f''(0) = -120: use the limit below q = 1e-6.
        let f_over_q = if q < 1e-6 {
            -120.0
        } else {
            let a = (3.0 - q).max(0.0).powi(4);
            let b = (2.0 - q).max(0.0).powi(4);
            let c = (1.0 - q).max(0.0).powi(4);
            (-5.0 * a + 30.0 * b - 75.0 * c) / q
        };
        self.alpha * f_over_q * self.inv_h * self.inv_h
    }
}

/// `erf(3)`, needed for the 3D normalisation of the truncated Gaussian.
const ERF_3: f64 = 0.999_977_909_503_001_4;

impl Kernel for Gaussian {
    const SUPPORT: f64 = 3.0;
    fn new(h: f64, dim: usize) -> Self {
        let e9 = (-9.0f64).exp();
        let a2 = 1.0 / (PI * (1.0 - e9));
        let a3 = 1.0 / (PI.powf(1.5) * ERF_3 - 6.0 * PI * e9);
        let alpha = normalisation(h, dim, (a2, a3));
        Self {
            h,
            inv_h: 1.0 / h,
            alpha,
        }
    }
    fn h(&self) -> f64 {
        self.h
    }
    #[inline(always)]
    fn w(&self, r: f64) -> f64 {
        let q = r * self.inv_h;
        if q < 3.0 {
            self.alpha * (-q * q).exp()
        } else {
            0.0
        }
    }
    #[inline(always)]
    fn dw_over_r(&self, r: f64) -> f64 {
        let q = r * self.inv_h;
        if q < 3.0 {
            -2.0 * self.alpha * (-q * q).exp() * self.inv_h * self.inv_h
        } else {
            0.0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// ∫ W dV by the midpoint rule in polar/spherical shells: `∫ W(r) s_n r^{n-1} dr`.
    fn mass<K: Kernel>(k: &K, dim: usize) -> f64 {
        let n = 200_000;
        let dr = k.radius() / n as f64;
        let shell = if dim == 2 { 2.0 * PI } else { 4.0 * PI };
        (0..n)
            .map(|i| {
                let r = (i as f64 + 0.5) * dr;
                k.w(r) * shell * r.powi(dim as i32 - 1) * dr
            })
            .sum()
    }

    /// Cartesian quadrature on a lattice, independent of the radial form.
    fn lattice_mass<K: Kernel>(k: &K, dim: usize) -> f64 {
        let n = 120;
        let d = 2.0 * k.radius() / n as f64;
        let c = |i: usize| -k.radius() + (i as f64 + 0.5) * d;
        let mut s = 0.0;
        for i in 0..n {
            for j in 0..n {
                if dim == 2 {
                    s += k.w((c(i).powi(2) + c(j).powi(2)).sqrt()) * d * d;
                } else {
                    for l in 0..n {
                        let r = (c(i).powi(2) + c(j).powi(2) + c(l).powi(2)).sqrt();
                        s += k.w(r) * d * d * d;
                    }
                }
            }
        }
        s
    }

    fn check<K: Kernel>() {
        for dim in [2, 3] {
            let k = K::new(0.37, dim);
            let m = mass(&k, dim);
            assert!((m - 1.0).abs() < 1e-8, "radial mass {m} in {dim}D");
            let lm = lattice_mass(&k, dim);
            assert!((lm - 1.0).abs() < 2e-3, "lattice mass {lm} in {dim}D");
            // ∇W against a centred finite difference of W, away from the Gaussian's edge jump.
            for i in 1..60 {
                let r = k.radius() * i as f64 / 60.0 * 0.98;
                let eps = 1e-6 * k.h();
                let fd = (k.w(r + eps) - k.w(r - eps)) / (2.0 * eps);
                let an = k.dw_over_r(r) * r;
                let scale = k.w(0.0) / k.h();
                assert!(
                    (fd - an).abs() < 1e-6 * scale,
                    "dW/dr at r={r}: analytic {an} vs finite difference {fd}"
                );
            }
            assert_eq!(k.w(k.radius() * 1.0001), 0.0);
            assert_eq!(k.dw_over_r(k.radius() * 1.0001), 0.0);
        }
    }

    #[test]
    fn wendland_c2() {
        check::<WendlandC2>();
    }
    #[test]
    fn wendland_c4() {
        check::<WendlandC4>();
    }
    #[test]
    fn cubic_spline() {
        check::<CubicSpline>();
    }
    #[test]
    fn quintic_spline() {
        check::<QuinticSpline>();
    }
    #[test]
    fn gaussian() {
        check::<Gaussian>();
    }

    #[test]
    fn gradient_is_finite_at_the_origin() {
        assert!((WendlandC2::new(1.0, 2).dw_over_r(0.0) + 35.0 / (4.0 * PI)).abs() < 1e-14);
        assert!(QuinticSpline::new(1.0, 3).dw_over_r(0.0).is_finite());
        assert!(CubicSpline::new(1.0, 3).dw_over_r(0.0).is_finite());
    }
}
