//! Laminar (Poiseuille) inflow profiles across an inlet's section, as fractions of the
//! centre-line velocity, with `s` running from 0 to 1 across each transverse extent.
//!
//! - Between two plates (2D): `u/u_c = 4 s (1 - s)`.
//! - In a rectangular duct (3D) of half-widths `a ≤ b`, centred coordinates `|η| ≤ a`,
//!   `|ζ| ≤ b` (White, Viscous Fluid Flow, 3rd ed., eq. 3-48; the solution of
//!   `∇²u = -G/μ` with u = 0 on the walls):
//!   ```text
//!   u ∝ Σ_{n odd} (-1)^((n-1)/2) n⁻³ [1 - cosh(nπζ/2a)/cosh(nπb/2a)] cos(nπη/2a)
//!   ```
//!   normalised by its centre value. Taking `a` the smaller half-width makes the cosh
//!   correction decay exponentially in n; the cosine series of the parabola converges
//!   as n⁻³ (the truncation below leaves < 10⁻⁵ of the centre value).

use std::f64::consts::PI;

/// Odd terms of the duct series: n = 1, 3, …, 2·TERMS - 1.
const TERMS: usize = 200;

/// `4 s (1 - s)`, `s` clamped to [0, 1].
pub fn channel(s: f64) -> f64 {
    let s = s.clamp(0.0, 1.0);
    4.0 * s * (1.0 - s)
}

/// The laminar profile across an inlet's section `[lo, hi]`, resolved once: the plates'
/// parabola across one transverse axis (2D), the duct series across two (3D).
pub enum Laminar {
    Channel {
        axis: usize,
        lo: f64,
        side: f64,
    },
    Duct {
        axes: [usize; 2],
        lo: [f64; 2],
        duct: Duct,
    },
}

impl Laminar {
    /// The profile across every axis but `axis` of the section `[lo, hi]`.
    pub fn across(axis: usize, lo: &[f64], hi: &[f64]) -> Self {
        let mut others = (0..lo.len()).filter(|&d| d != axis);
        let first = others.next().unwrap_or(0);
        match others.next() {
            None => Laminar::Channel {
                axis: first,
                lo: lo[first],
                side: hi[first] - lo[first],
            },
            Some(second) => Laminar::Duct {
                axes: [first, second],
                lo: [lo[first], lo[second]],
                duct: Duct::new([hi[first] - lo[first], hi[second] - lo[second]]),
            },
        }
    }

    /// The fraction of the centre-line velocity at position `x`.
    pub fn at(&self, x: &[f64]) -> f64 {
        match self {
            Laminar::Channel { axis, lo, side } => channel((x[*axis] - lo) / side),
            Laminar::Duct { axes, lo, duct } => {
                duct.at([0, 1].map(|k| (x[axes[k]] - lo[k]) / duct.sides[k]))
            }
        }
    }
}

/// A rectangular duct's profile, with its centre value computed once.
pub struct Duct {
    sides: [f64; 2],
    /// Index of the narrower side (η runs across it).
    narrow: usize,
    centre: f64,
}

impl Duct {
    /// The duct of side lengths `sides`.
    pub fn new(sides: [f64; 2]) -> Self {
        let narrow = if sides[0] <= sides[1] { 0 } else { 1 };
        let (a, b) = (0.5 * sides[narrow], 0.5 * sides[1 - narrow]);
        Duct {
            sides,
            narrow,
            centre: duct_series(0.0, 0.0, a, b),
        }
    }

    /// The profile at `s` ∈ [0, 1]² (clamped) across the two sides.
    pub fn at(&self, s: [f64; 2]) -> f64 {
        let s = s.map(|v| v.clamp(0.0, 1.0));
        let (narrow, wide) = (self.narrow, 1 - self.narrow);
        let (a, b) = (0.5 * self.sides[narrow], 0.5 * self.sides[wide]);
        let eta = (s[narrow] - 0.5) * self.sides[narrow];
        let zeta = (s[wide] - 0.5) * self.sides[wide];
        duct_series(eta, zeta, a, b) / self.centre
    }
}

/// The series of the module's formula at (η, ζ).
fn duct_series(eta: f64, zeta: f64, a: f64, b: f64) -> f64 {
    (0..TERMS)
        .map(|k| {
            let n = (2 * k + 1) as f64;
            let q = n * PI / (2.0 * a);
            let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
            sign / (n * n * n) * (1.0 - cosh_ratio(q * zeta.abs(), q * b)) * (q * eta).cos()
        })
        .sum()
}

/// `cosh(x)/cosh(y)` for 0 ≤ x ≤ y, without overflow at large arguments.
fn cosh_ratio(x: f64, y: f64) -> f64 {
    (x - y).exp() * (1.0 + (-2.0 * x).exp()) / (1.0 + (-2.0 * y).exp())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The duct profile solves ∇²u = const with u = 0 on the walls: the five-point
    /// Laplacian (second-order, h = 1/200) is the same at every interior point to
    /// 10⁻³ of its mean, and the walls are at rest.
    #[test]
    fn the_duct_profile_is_poiseuille_flow() {
        let sides = [1.0, 2.0];
        let h = 1.0 / 200.0;
        let duct = Duct::new(sides);
        let u = |y: f64, z: f64| duct.at([y / sides[0], z / sides[1]]);
        let laplacian = |y: f64, z: f64| {
            (u(y + h, z) + u(y - h, z) + u(y, z + h) + u(y, z - h) - 4.0 * u(y, z)) / (h * h)
        };
        let points: Vec<(f64, f64)> = [0.1, 0.3, 0.5, 0.8]
            .iter()
            .flat_map(|&y| [0.2, 0.7, 1.0, 1.6, 1.9].map(|z| (y, z)))
            .collect();
        let values: Vec<f64> = points.iter().map(|&(y, z)| laplacian(y, z)).collect();
        let mean = values.iter().sum::<f64>() / values.len() as f64;
        for v in &values {
            assert!((v / mean - 1.0).abs() < 1e-3, "{values:?}");
        }
        for (y, z) in [(0.0, 0.7), (1.0, 0.3), (0.4, 0.0), (0.6, 2.0)] {
            assert!(u(y, z).abs() < 1e-5, "u({y}, {z}) = {}", u(y, z));
        }
        assert!((u(0.5, 1.0) - 1.0).abs() < 1e-12);
    }

    /// The mean over a square duct is 0.4771 of the centre velocity (Shah & London
    /// 1978, Laminar Flow Forced Convection in Ducts: u_max/u_mean = 2.0962), and a
    /// wide duct's mid-plane is the plane channel's parabola.
    #[test]
    fn the_duct_profile_has_the_published_mean_and_the_channel_limit() {
        let m = 400;
        let square = Duct::new([1.0, 1.0]);
        let mean = (0..m)
            .flat_map(|i| (0..m).map(move |j| (i, j)))
            .map(|(i, j)| {
                let s = [(i as f64 + 0.5) / m as f64, (j as f64 + 0.5) / m as f64];
                square.at(s)
            })
            .sum::<f64>()
            / (m * m) as f64;
        assert!(
            (1.0 / mean - 2.0962).abs() < 1e-3,
            "u_max/u_mean = {}",
            1.0 / mean
        );
        let flat = Duct::new([1.0, 20.0]);
        for s in [0.1, 0.25, 0.4] {
            let wide = flat.at([s, 0.5]);
            assert!(
                (wide - channel(s)).abs() < 1e-6,
                "{wide} against {}",
                channel(s)
            );
        }
    }
}
