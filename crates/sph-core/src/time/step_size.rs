//! Adaptive time step (SCHEME.md §6):
//! `Δt = min( CFL h/c0,  C_ν h²/max(ν, ν_model),  C_f sqrt(h/|a|max) )`,
//! the acoustic, viscous (Morris et al. 1997) and body-force (Monaghan 1992) limits;
//! `ν_model` is the largest diffusivity the scheme adds (δ-LES-SPH: `max(ν + ν_T, ν_δ)`,
//! LES.md §1), 0 for the others.

/// The case-settable coefficients and the fixed scales of a run.
#[derive(Debug, Clone, Copy)]
pub struct TimeStepControl {
    pub cfl: f64,
    pub viscous_cfl: f64,
    pub force_cfl: f64,
    pub h: f64,
    pub c0: f64,
    /// Kinematic viscosity the viscous term stands for (0 if inviscid).
    pub nu: f64,
}

impl TimeStepControl {
    /// The acoustic limit, an upper bound of every step.
    pub fn acoustic(&self) -> f64 {
        self.cfl * self.h / self.c0
    }

    /// The step for the largest acceleration `a_max` and the scheme's largest
    /// diffusivity `nu_model` [m²/s].
    pub fn dt(&self, a_max: f64, nu_model: f64) -> f64 {
        let mut dt = self.acoustic();
        let nu = self.nu.max(nu_model);
        if nu > 0.0 {
            dt = dt.min(self.viscous_cfl * self.h * self.h / nu);
        }
        if a_max > 0.0 {
            dt = dt.min(self.force_cfl * (self.h / a_max).sqrt());
        }
        dt
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_limit_can_bind() {
        let c = TimeStepControl {
            cfl: 1.5,
            viscous_cfl: 0.125,
            force_cfl: 0.25,
            h: 0.01,
            c0: 10.0,
            nu: 0.0,
        };
        assert_eq!(c.dt(0.0, 0.0), 1.5e-3);
        let visc = TimeStepControl { nu: 0.01, ..c };
        assert!((visc.dt(0.0, 0.0) - 0.125e-4 / 0.01).abs() < 1e-15);
        assert!((c.dt(0.0, 0.01) - 0.125e-4 / 0.01).abs() < 1e-15);
        assert!((c.dt(1e4, 0.0) - 0.25 * (1e-6f64).sqrt()).abs() < 1e-15);
    }
}
