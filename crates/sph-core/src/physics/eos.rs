//! Linear equation of state of weakly-compressible SPH: `p = c0² (ρ - ρ0) + p_b`.
//!
//! The background pressure `p_b` (Morris et al. 1997; Adami et al. 2013) is zero for
//! free-surface flows; confined flows such as the periodic Taylor-Green vortex use it
//! to keep p positive, which avoids the tensile instability of negative pressures.
//!
//! `c0` is chosen so that the Mach number stays near 0.1 and `|Δρ/ρ0|` near 1%:
//! `c0 = 10 max(U_max, sqrt(Δp_max/ρ0))` (Monaghan 1994; Antuono et al. 2010).

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinearEos {
    pub rho0: f64,
    pub c0: f64,
    /// Background pressure p_b.
    pub background: f64,
}

impl LinearEos {
    #[inline(always)]
    pub fn pressure(&self, rho: f64) -> f64 {
        self.c0 * self.c0 * (rho - self.rho0) + self.background
    }

    #[inline(always)]
    pub fn density(&self, p: f64) -> f64 {
        self.rho0 + (p - self.background) / (self.c0 * self.c0)
    }

    /// Specific compressible energy `e(ρ) = ∫_{ρ0}^{ρ} p(s)/s² ds
    /// = c0² [ln(ρ/ρ0) + ρ0/ρ - 1] + p_b (1/ρ0 - 1/ρ)` (Antuono et al. 2015, CMAME 289:209).
    pub fn internal_energy(&self, rho: f64) -> f64 {
        self.c0 * self.c0 * ((rho / self.rho0).ln() + self.rho0 / rho - 1.0)
            + self.background * (1.0 / self.rho0 - 1.0 / rho)
    }

    /// The sound-speed rule `c0 = factor · max(U_max, sqrt(Δp_max/ρ0))`.
    pub fn sound_speed_rule(factor: f64, u_max: f64, dp_max: f64, rho0: f64) -> f64 {
        factor * u_max.max((dp_max / rho0).sqrt())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn internal_energy_is_the_integral_of_p_over_rho_squared() {
        let eos = LinearEos {
            rho0: 1000.0,
            c0: 30.0,
            background: 2500.0,
        };
        for rho in [990.0, 1000.0, 1012.0] {
            let n = 20_000;
            let ds = (rho - eos.rho0) / n as f64;
            let quad: f64 = (0..n)
                .map(|k| {
                    let s = eos.rho0 + (k as f64 + 0.5) * ds;
                    eos.pressure(s) / (s * s) * ds
                })
                .sum();
            assert!((quad - eos.internal_energy(rho)).abs() < 1e-9 * (1.0 + quad.abs()));
        }
        assert_eq!(eos.density(eos.pressure(1003.0)), 1003.0);
    }
}
