//! The JONSWAP spectrum (Hasselmann et al. 1973) of an irregular sea and its
//! discretisation into the components a wave maker generates.
//!
//! `S(f) = α g² (2π)⁻⁴ f⁻⁵ exp(-5/4 (f_p/f)⁴) γ^r`, `r = exp(-(f - f_p)²/(2σ² f_p²))`,
//! `σ = 0.07` for `f ≤ f_p` and `0.09` above. The `N` components sit at the multiples
//! of `Δf = (f_max - f_min)/N` in `(f_min, f_min + NΔf]` (rounded up to a multiple),
//! so that the sea repeats exactly every `1/Δf`; component `n` has amplitude
//! `a_n = √(2 S(f_n) Δf)`, α set so that `4√m₀ = H_s` (`m₀ = Σ a_n²/2`), and a phase
//! drawn uniformly from the seed (ChaCha8, the same sea on every machine and version).

use rand_chacha::rand_core::{RngCore, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::PI;

/// One wave component: `a cos(kx - ωt - φ)` at the paddle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Component {
    pub amplitude: f64,
    /// ω \[rad/s\].
    pub omega: f64,
    pub phase: f64,
}

/// A JONSWAP sea.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jonswap {
    /// `H_s` \[m\].
    pub significant_height: f64,
    /// `T_p` \[s\].
    pub peak_period: f64,
    /// γ, the peak enhancement (1: Pierson-Moskowitz).
    pub gamma: f64,
}

impl Jonswap {
    /// `S(f)/α'`: the spectrum's shape, before it is scaled to `H_s`.
    fn shape(&self, f: f64) -> f64 {
        let fp = 1.0 / self.peak_period;
        let sigma = if f <= fp { 0.07 } else { 0.09 };
        let r = (-(f - fp).powi(2) / (2.0 * sigma * sigma * fp * fp)).exp();
        f.powi(-5) * (-1.25 * (fp / f).powi(4)).exp() * self.gamma.powf(r)
    }

    /// The spectral density \[m²/Hz\] at the `n` multiples of `Δf = (f_max - f_min)/n`
    /// from just above `f_min` \[Hz\], scaled so that `4√(Σ S Δf) = H_s`.
    pub fn densities(&self, n: usize, f_min: f64, f_max: f64) -> Vec<(f64, f64)> {
        let df = (f_max - f_min) / n as f64;
        let first = (f_min / df + 1e-9).floor() + 1.0;
        let f: Vec<f64> = (0..n).map(|i| (first + i as f64) * df).collect();
        let shape: Vec<f64> = f.iter().map(|&f| self.shape(f)).collect();
        let m0 = shape.iter().sum::<f64>() * df;
        let scale = (self.significant_height / 4.0).powi(2) / m0;
        f.into_iter()
            .zip(shape)
            .map(|(f, s)| (f, s * scale))
            .collect()
    }

    /// `n` components over `[f_min, f_max]`, phases from `seed`.
    pub fn components(&self, n: usize, f_min: f64, f_max: f64, seed: u64) -> Vec<Component> {
        let df = (f_max - f_min) / n as f64;
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        (self.densities(n, f_min, f_max).into_iter())
            .map(|(f, s)| Component {
                amplitude: (2.0 * s * df).sqrt(),
                omega: 2.0 * PI * f,
                phase: 2.0 * PI * (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64,
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The discretised sea has the significant height asked for (`4√m₀`, `m₀ = Σ a²/2`),
    /// its densest band at the peak, a peak γ times the Pierson-Moskowitz one of the same
    /// α, frequencies at multiples of Δf (a sea that repeats every 1/Δf), and the same
    /// phases for the same seed.
    #[test]
    fn the_discrete_sea_has_its_height_peak_and_seed() {
        let sea = Jonswap {
            significant_height: 0.1,
            peak_period: 1.5,
            gamma: 3.3,
        };
        let c = sea.components(200, 0.3, 2.0, 7);
        let m0: f64 = c.iter().map(|c| 0.5 * c.amplitude * c.amplitude).sum();
        assert!((4.0 * m0.sqrt() / 0.1 - 1.0).abs() < 1e-12);
        let peak = (c.iter()).max_by(|a, b| a.amplitude.total_cmp(&b.amplitude));
        let fp = peak.unwrap().omega / (2.0 * PI);
        assert!((fp * 1.5 - 1.0).abs() < 0.0085 * 1.5, "{fp}");
        let pm = Jonswap { gamma: 1.0, ..sea };
        let ratio = sea.shape(1.0 / 1.5) / pm.shape(1.0 / 1.5);
        assert!((ratio - 3.3).abs() < 1e-12);
        assert_eq!(c, sea.components(200, 0.3, 2.0, 7));
        assert_ne!(c[0].phase, sea.components(200, 0.3, 2.0, 8)[0].phase);
        assert!(c.iter().all(|c| (0.0..2.0 * PI).contains(&c.phase)));
        let df = 1.7 / 200.0;
        for c in &c {
            let multiple = c.omega / (2.0 * PI * df);
            assert!((multiple - multiple.round()).abs() < 1e-9, "{multiple}");
        }
        let f = |c: &Component| c.omega / (2.0 * PI);
        assert!(f(&c[0]) > 0.3 && (f(&c[199]) - 2.0).abs() < df);
    }
}
