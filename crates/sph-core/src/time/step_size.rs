//! Adaptive time step (docs/theory.md §6, §11.3):
//! `Δt = min( CFL h/c0,  C_ν h²/max(ν, ν_m),  C_ψ h²/ν_ρ,  C_f sqrt(h/|a|max) )`,
//! the acoustic, viscous (Morris et al. 1997), density-diffusion and body-force
//! (Monaghan 1992) limits; `ν_m` and `ν_ρ` are the largest momentum and density
//! diffusivities the scheme adds (δ-LES-SPH: `ν + ν_T` and `ν_δ`), 0 for the others.

use crate::scheme::model::Diffusivities;

/// The case-settable coefficients and the fixed scales of a run.
#[derive(Debug, Clone, Copy)]
pub struct TimeStepControl {
    pub cfl: f64,
    pub viscous_cfl: f64,
    /// `C_ψ` of the density-diffusion limit.
    pub diffusion_cfl: f64,
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
    /// diffusivities `model`.
    pub fn dt(&self, a_max: f64, model: Diffusivities) -> f64 {
        let mut dt = self.acoustic();
        let h2 = self.h * self.h;
        let nu = self.nu.max(model.momentum);
        if nu > 0.0 {
            dt = dt.min(self.viscous_cfl * h2 / nu);
        }
        if model.density > 0.0 {
            dt = dt.min(self.diffusion_cfl * h2 / model.density);
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
    use crate::case::{IntegratorChoice, SchemeConfig};
    use crate::physics::kernel::{CubicSpline, Gaussian, Kernel, QuinticSpline};
    use crate::physics::kernel::{WendlandC2, WendlandC4};
    use std::f64::consts::PI;

    #[test]
    fn each_limit_can_bind() {
        let c = TimeStepControl {
            cfl: 1.5,
            viscous_cfl: 0.125,
            diffusion_cfl: 0.25,
            force_cfl: 0.25,
            h: 0.01,
            c0: 10.0,
            nu: 0.0,
        };
        let none = Diffusivities::default();
        assert_eq!(c.dt(0.0, none), 1.5e-3);
        let visc = TimeStepControl { nu: 0.01, ..c };
        assert!((visc.dt(0.0, none) - 0.125e-4 / 0.01).abs() < 1e-15);
        let eddy = Diffusivities {
            momentum: 0.01,
            density: 0.0,
        };
        assert!((c.dt(0.0, eddy) - 0.125e-4 / 0.01).abs() < 1e-15);
        let diffusive = Diffusivities {
            momentum: 0.0,
            density: 0.02,
        };
        assert!((c.dt(0.0, diffusive) - 0.25e-4 / 0.02).abs() < 1e-15);
        assert!((c.dt(1e4, none) - 0.25 * (1e-6f64).sqrt()).abs() < 1e-15);
    }

    /// `λ h²/ν_ρ`, the largest eigenvalue of the density-diffusion operator
    /// `Σ_j 2(ρ_j - ρ_i)(-W'_ij/r_ij) V_j` on a 2D square lattice of spacing 1, over
    /// the wave vectors of the lattice's first Brillouin zone (41² of them).
    fn largest_diffusion_eigenvalue<K: Kernel>(h_over_dx: f64) -> f64 {
        let kernel = K::new(h_over_dx, 2);
        let reach = (kernel.radius().ceil()) as i64;
        let mut lattice = vec![];
        for i in -reach..=reach {
            for j in -reach..=reach {
                let r = ((i * i + j * j) as f64).sqrt();
                if r > 0.0 && r < kernel.radius() {
                    lattice.push((i as f64, j as f64, -kernel.dw_over_r(r)));
                }
            }
        }
        let n = 40;
        let mut largest = 0.0f64;
        for a in 0..=n {
            for b in 0..=n {
                let (kx, ky) = (PI * a as f64 / n as f64, PI * b as f64 / n as f64);
                let lambda: f64 = (lattice.iter())
                    .map(|&(x, y, f)| 2.0 * (1.0 - (kx * x + ky * y).cos()) * f)
                    .sum();
                largest = largest.max(lambda);
            }
        }
        largest * h_over_dx * h_over_dx
    }

    /// The default `C_ψ` keeps the density diffusion inside the integrators' stability
    /// intervals on the negative real axis (RK4 2.785, the symplectic scheme 2) for
    /// every kernel at h/Δx from 1 to 2, with at least 15% to spare: the binding
    /// case is Wendland C4 at h = 2Δx (λ h²/ν_ρ = 8.9).
    #[test]
    fn default_diffusion_number_is_stable_for_every_kernel() {
        let eigenvalues = [1.0, 1.3, 1.5, 2.0].map(|s| {
            [
                largest_diffusion_eigenvalue::<WendlandC2>(s),
                largest_diffusion_eigenvalue::<WendlandC4>(s),
                largest_diffusion_eigenvalue::<CubicSpline>(s),
                largest_diffusion_eigenvalue::<QuinticSpline>(s),
                largest_diffusion_eigenvalue::<Gaussian>(s),
            ]
        });
        let worst = eigenvalues.iter().flatten().fold(0.0f64, |a, &b| a.max(b));
        assert!(worst > 8.0 && worst < 10.0, "λ h²/ν_ρ = {worst}");
        let wendland_c2 = largest_diffusion_eigenvalue::<WendlandC2>(2.0);
        assert!((wendland_c2 - 6.81).abs() < 0.01, "{wendland_c2}");
        for (integrator, bound) in [
            (IntegratorChoice::Rk4, 2.785),
            (IntegratorChoice::Symplectic, 2.0),
        ] {
            let settings = SchemeConfig {
                integrator,
                ..SchemeConfig::default()
            };
            let used = settings.diffusion_cfl() * worst;
            assert!(used < 0.85 * bound, "{integrator:?}: {used} of {bound}");
        }
    }
}
