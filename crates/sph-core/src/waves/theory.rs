//! Linear and second-order wave theory of a flume of constant depth `d`: the
//! dispersion relation, the wave makers' transfer functions (Biesel 1951), Stokes's
//! second-order bound harmonic and Madsen's (1971) second-order piston correction.
//!
//! Elevation of a regular wave of height `H` travelling toward +x, to second order:
//! `η = H/2 cos(kx - ωt) + A₂ cos 2(kx - ωt)`, with `ω² = g k tanh kd` and
//! `A₂ = k H²/16 · cosh kd (2 + cosh 2kd) / sinh³ kd`.

use std::f64::consts::PI;

/// The wavenumber `k` of angular frequency `omega` \[rad/s\] in depth `depth` \[m\]:
/// the root of `ω² = g k tanh kd` (Eckart's approximation, then Newton to round-off).
pub fn wavenumber(omega: f64, depth: f64, g: f64) -> f64 {
    let k0d = omega * omega * depth / g;
    let mut kd = k0d / k0d.tanh().sqrt();
    for _ in 0..50 {
        let (t, s) = (kd.tanh(), 1.0 / kd.cosh());
        let f = kd * t - k0d;
        let step = f / (t + kd * s * s);
        kd -= step;
        if step.abs() < 1e-15 * kd {
            break;
        }
    }
    kd / depth
}

/// The angular frequency of wavenumber `k` in depth `depth`: `ω = √(g k tanh kd)`.
pub fn frequency(k: f64, depth: f64, g: f64) -> f64 {
    (g * k * (k * depth).tanh()).sqrt()
}

/// The wavenumber of a wave of length `wavelength` \[m\].
pub fn wavenumber_of_length(wavelength: f64) -> f64 {
    2.0 * PI / wavelength
}

/// How a wave maker's surface displacement varies with height: a piston moves as one;
/// a flap turns about a hinge `hinge` \[m\] above the bed (negative: below it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Paddle {
    Piston,
    Flap { hinge: f64 },
}

impl Paddle {
    /// Biesel's transfer function `H/S` (wave height over the paddle's stroke at the
    /// still-water level) at `kd`, from the linear wave maker theory
    /// `H/S = 4 sinh kd / (sinh 2kd + 2kd) · k ∫₋d⁰ f(z) cosh k(z + d) dz`, `f` the
    /// paddle's displacement over its displacement at the still level:
    /// piston `H/S = 2 (cosh 2kd - 1) / (sinh 2kd + 2kd)`; flap hinged at `l` above the
    /// bed `k∫ = ((kd - kl) sinh kd - cosh kd + cosh kl) / (k(d - l))` (`kl` taken as 0
    /// below the bed, where the paddle's displacement is `(l₀ - l)/(d - l)` of the top's),
    /// which is `(kd sinh kd - cosh kd + 1)/kd` for a hinge at the bed.
    pub fn height_over_stroke(&self, k: f64, depth: f64) -> f64 {
        let kd = k * depth;
        let integral = match *self {
            Paddle::Piston => kd.sinh(),
            Paddle::Flap { hinge } => {
                let (kl, ka) = (k * hinge, k * (depth - hinge));
                let low = kl.max(0.0);
                let primitive = |s: f64| (s - kl) * s.sinh() - s.cosh();
                (primitive(kd) - primitive(low)) / ka
            }
        };
        4.0 * kd.sinh() * integral / ((2.0 * kd).sinh() + 2.0 * kd)
    }

    /// The surface elevation of the evanescent mode of wavenumber `k_m` (an
    /// [`evanescent_wavenumbers`] root) per unit displacement of the paddle at the still
    /// level: a paddle moving by `X(t)` raises `η_m = E_m e^{-k_m x} X(t)` near itself,
    /// `E_m = 4 sin k_m d / (sin 2k_m d + 2k_m d) · k_m ∫₋d⁰ f(z) cos k_m(z + d) dz`, the
    /// transfer of [`Self::height_over_stroke`] with `cosh` turned to `cos`: piston
    /// `k_m∫ = sin k_m d`; flap `((k_m d - k_m l) sin k_m d + cos k_m d - cos k_m l) /
    /// (k_m (d - l))`.
    pub fn evanescent_elevation(&self, k: f64, depth: f64) -> f64 {
        let kd = k * depth;
        let integral = match *self {
            Paddle::Piston => kd.sin(),
            Paddle::Flap { hinge } => {
                let (kl, ka) = (k * hinge, k * (depth - hinge));
                let low = kl.max(0.0);
                let primitive = |s: f64| (s - kl) * s.sin() + s.cos();
                (primitive(kd) - primitive(low)) / ka
            }
        };
        4.0 * kd.sin() * integral / ((2.0 * kd).sin() + 2.0 * kd)
    }

    /// The evanescent modes' elevation per unit paddle displacement at angular frequency
    /// `omega`, `x` \[m\] in front of the paddle: `Σ_m E_m e^{-k_m x}` (see
    /// [`Self::evanescent_elevation`]), summed until the terms fall below 10⁻¹² (at
    /// most [`EVANESCENT_MODES`] modes). `x` > 0: at the paddle itself the sum converges
    /// only slowly.
    pub fn near_field(&self, omega: f64, depth: f64, g: f64, x: f64) -> f64 {
        let modes = ((27.6 * depth / (PI * x)).ceil() as usize + 1).min(EVANESCENT_MODES);
        (evanescent_wavenumbers(omega, depth, g, modes).iter())
            .map(|&k| self.evanescent_elevation(k, depth) * (-k * x).exp())
            .sum()
    }
}

/// The most evanescent modes [`Paddle::near_field`] sums.
pub const EVANESCENT_MODES: usize = 2000;

/// The first `n` evanescent wavenumbers `k_m` of angular frequency `omega` in depth
/// `depth`: the roots of `ω² = -g k tan kd`, one in each `((m - ½)π, mπ)/d`, found by
/// bisection of `kd sin kd + (ω²d/g) cos kd` (which changes sign across each).
pub fn evanescent_wavenumbers(omega: f64, depth: f64, g: f64, n: usize) -> Vec<f64> {
    let k0d = omega * omega * depth / g;
    let f = |x: f64| x * x.sin() + k0d * x.cos();
    (1..=n)
        .map(|m| {
            let (mut lo, mut hi) = ((m as f64 - 0.5) * PI, m as f64 * PI);
            let sign_lo = f(lo).signum();
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if f(mid).signum() == sign_lo {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            0.5 * (lo + hi) / depth
        })
        .collect()
}

/// The amplitude `A₂` of Stokes's second-order bound harmonic of a wave of height `H`
/// and wavenumber `k` in depth `d`: `k H²/16 · cosh kd (2 + cosh 2kd)/sinh³ kd`.
pub fn bound_second_harmonic(height: f64, k: f64, depth: f64) -> f64 {
    let kd = k * depth;
    k * height * height / 16.0 * kd.cosh() * (2.0 + (2.0 * kd).cosh()) / kd.sinh().powi(3)
}

/// The amplitude of the second-harmonic piston motion that suppresses the free second
/// harmonic of a regular wave (Madsen 1971): the piston moves
/// `X = S/2 sin ωt + X₂ sin 2ωt` with
/// `X₂ = H²/(32 d) · (3 cosh kd / sinh³ kd - 2/m₁)`, `m₁ = H/S` Biesel's piston transfer.
pub fn madsen_second_order_stroke(height: f64, k: f64, depth: f64) -> f64 {
    let kd = k * depth;
    let m1 = Paddle::Piston.height_over_stroke(k, depth);
    height * height / (32.0 * depth) * (3.0 * kd.cosh() / kd.sinh().powi(3) - 2.0 / m1)
}

#[cfg(test)]
mod tests {
    use super::*;

    const G: f64 = 9.81;

    /// ω² = g k tanh kd holds to round-off from deep to shallow water, and the limits:
    /// deep `k = ω²/g`, shallow `k = ω/√(gd)`.
    #[test]
    fn the_wavenumber_solves_the_dispersion_relation() {
        for kd in [0.01, 0.1, 0.5, 1.0, 3.0, 10.0, 40.0] {
            let d = 0.7;
            let omega = frequency(kd / d, d, G);
            let k = wavenumber(omega, d, G);
            assert!((k * d / kd - 1.0).abs() < 1e-13, "kd {kd}: {}", k * d);
        }
        let deep = wavenumber(6.0, 100.0, G);
        assert!((deep / (36.0 / G) - 1.0).abs() < 1e-12);
        let shallow = wavenumber(0.01, 1.0, G);
        assert!((shallow / (0.01 / G.sqrt()) - 1.0).abs() < 1e-4);
    }

    /// The transfer functions against their closed forms and limits: the piston's
    /// `2(cosh 2kd - 1)/(sinh 2kd + 2kd)` → `kd` in shallow water and 2 in deep water;
    /// the flap at the bed `4 sinh kd (kd sinh kd - cosh kd + 1)/(kd (sinh 2kd + 2kd))`
    /// → `kd/2` shallow, 2 deep; a flap hinged far below the bed moves as a piston.
    #[test]
    fn biesel_transfer_functions_have_their_closed_forms_and_limits() {
        let d = 1.0;
        for kd in [0.05, 0.5, 1.0, 2.0, 5.0] {
            let k = kd / d;
            let piston = Paddle::Piston.height_over_stroke(k, d);
            let closed = 2.0 * ((2.0 * kd).cosh() - 1.0) / ((2.0 * kd).sinh() + 2.0 * kd);
            assert!((piston / closed - 1.0).abs() < 1e-13, "{kd}");
            let flap = Paddle::Flap { hinge: 0.0 }.height_over_stroke(k, d);
            let closed = 4.0 * kd.sinh() * (kd * kd.sinh() - kd.cosh() + 1.0)
                / (kd * ((2.0 * kd).sinh() + 2.0 * kd));
            assert!((flap / closed - 1.0).abs() < 1e-13, "{kd}");
            let far = Paddle::Flap { hinge: -1e7 }.height_over_stroke(k, d);
            assert!((far / piston - 1.0).abs() < 1e-6, "{kd}");
        }
        let shallow = Paddle::Piston.height_over_stroke(1e-3, d);
        assert!((shallow / 1e-3 - 1.0).abs() < 1e-6);
        let flap_shallow = Paddle::Flap { hinge: 0.0 }.height_over_stroke(1e-3, d);
        assert!((flap_shallow / 5e-4 - 1.0).abs() < 1e-6);
        for paddle in [Paddle::Piston, Paddle::Flap { hinge: 0.0 }] {
            assert!((paddle.height_over_stroke(30.0, d) - 2.0).abs() < 0.07);
        }
        // a flap hinged higher up moves less water: a smaller height per stroke
        let high = Paddle::Flap { hinge: 0.5 }.height_over_stroke(1.0, d);
        assert!(high < Paddle::Flap { hinge: 0.0 }.height_over_stroke(1.0, d));
    }

    /// Linear wave maker theory's modes add up to the paddle's own velocity profile at
    /// the paddle (x = 0): `f(z) = F cosh k(z + d)/sinh kd + Σ_m E_m cos k_m(z + d)/sin k_m d`
    /// (from `u = ∂φ/∂x` of each mode, `F` = H/S and `E_m` the evanescent elevations), for
    /// a piston (f = 1) and a flap (f linear above its hinge, 0 below); the evanescent
    /// wavenumbers solve their dispersion relation.
    #[test]
    fn progressive_and_evanescent_modes_rebuild_the_paddle_motion() {
        let (d, omega) = (0.5, 2.0 * PI / 1.625);
        let k = wavenumber(omega, d, G);
        let modes = evanescent_wavenumbers(omega, d, G, 4000);
        for (m, &km) in modes.iter().enumerate().take(50) {
            let x = km * d;
            assert!(((m as f64 + 0.5) * PI..(m as f64 + 1.0) * PI).contains(&x));
            assert!((omega * omega + G * km * x.tan()).abs() < 1e-9 * omega * omega);
        }
        let flap = Paddle::Flap { hinge: 0.1 };
        for (paddle, z, f) in [
            (Paddle::Piston, -0.25, 1.0),
            (Paddle::Piston, -0.05, 1.0),
            (flap, -0.2, 0.2 / 0.4),
            (flap, -0.45, 0.0),
        ] {
            let progressive =
                paddle.height_over_stroke(k, d) * (k * (z + d)).cosh() / (k * d).sinh();
            let evanescent: f64 = (modes.iter())
                .map(|&km| {
                    paddle.evanescent_elevation(km, d) * (km * (z + d)).cos() / (km * d).sin()
                })
                .sum();
            assert!(
                (progressive + evanescent - f).abs() < 2e-3,
                "{paddle:?} z = {z}: {progressive} + {evanescent}"
            );
        }
        // the near field decays away from the paddle and its sum has converged
        let near = Paddle::Piston.near_field(omega, d, G, 0.1);
        let far = Paddle::Piston.near_field(omega, d, G, 0.5);
        assert!(near > 0.0 && far < 0.1 * near, "{near} {far}");
        let direct: f64 = (modes.iter())
            .map(|&km| Paddle::Piston.evanescent_elevation(km, d) * (-km * 0.1).exp())
            .sum();
        assert!((near - direct).abs() < 1e-12, "{near} {direct}");
    }

    /// Stokes's bound harmonic in deep water is `k a²/2` (a = H/2), and Madsen's
    /// correction tends to `-H²/(32 d)` (`m₁ → 2`, the bound term's share vanishing).
    #[test]
    fn second_order_terms_have_their_deep_water_limits() {
        let (h, k) = (0.02, 2.0);
        let a = 0.5 * h;
        let deep = bound_second_harmonic(h, k, 50.0);
        assert!((deep / (0.5 * k * a * a) - 1.0).abs() < 1e-12, "{deep}");
        let m = madsen_second_order_stroke(h, k, 50.0);
        assert!((m / (-h * h / (32.0 * 50.0)) - 1.0).abs() < 1e-12, "{m}");
    }
}
