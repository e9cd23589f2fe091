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
