//! What a run will cost, told before it starts (`sph-cli check`): the sound speed, the
//! first step, the steps to the end time and a rough wall time, so that absurd input
//! (gravity of 10³⁰, an end time in hours at a millimetre spacing) shows at once.

use super::Simulation;
use crate::case::IntegratorChoice;
use crate::scheme::model::Diffusivities;

/// Neighbour pairs one core evaluates per second, all included (2D, 3D), measured on the
/// dam breaks (2D example, h/Δx 1.33: 22 pairs a particle, 2.5·10⁶ particle-evaluations/s
/// a core; 3D at 10⁶ particles: 79 pairs, 3.5·10⁵).
const PAIRS_PER_CORE_SECOND: [f64; 2] = [5.5e7, 3.0e7];

/// Runs longer than this many seconds get a warning.
pub const LONG_RUN: f64 = 86_400.0;

/// The estimate of [`Simulation::cost`].
#[derive(Debug, Clone, Copy)]
pub struct Cost {
    /// Sound speed c0 [m/s].
    pub c0: f64,
    /// The kinematic viscosity the viscous term acts with [m²/s]: μ/ρ0 of the physical
    /// viscosity, `α h c0/(2(D + 2))` of the artificial one (`K = α h c0 ρ0` over the
    /// physical term's `2(D + 2) ρ0`), 0 without a viscous term.
    pub nu: f64,
    /// The first step \[s\]: the acoustic, viscous and gravity limits at the start.
    pub dt: f64,
    /// Steps from the start to the end time at that step.
    pub steps: f64,
    /// Wall time \[s\] on `cores` cores, from the measured pair rate.
    pub seconds: f64,
    pub cores: usize,
}

impl<const D: usize> Simulation<D> {
    /// The sound speed, the first step, the steps to `time.end` and a wall-time
    /// estimate on this machine's threads (see `PAIRS_PER_CORE_SECOND`).
    pub fn cost(&self) -> Cost {
        let control = self.time_step_control();
        let gravity = self.physics().gravity.norm();
        let nu = Diffusivities {
            momentum: control.nu,
            density: 0.0,
        };
        let dt = control.dt(gravity, nu);
        let steps = ((self.case.time.end - self.time()) / dt).max(0.0).ceil();
        let evaluations = match self.case.scheme.integrator {
            IntegratorChoice::Rk4 => 4.0,
            IntegratorChoice::Symplectic => 2.0,
        };
        let r = self.case.support() / self.case.dx();
        let pairs = if D == 2 {
            std::f64::consts::PI * r * r
        } else {
            4.0 / 3.0 * std::f64::consts::PI * r.powi(3)
        };
        let cores = rayon::current_num_threads();
        let rate = PAIRS_PER_CORE_SECOND[D - 2] * cores as f64;
        let seconds = steps * evaluations * self.n_fluid() as f64 * pairs / rate;
        Cost {
            c0: self.physics().eos.c0,
            nu: control.nu,
            dt,
            steps,
            seconds,
            cores,
        }
    }
}
