//! The stability guard: a run that goes unstable is stopped at the first particle
//! that shows it, with what went wrong.

use crate::particles::{Kind, Particles};
use rayon::prelude::*;

/// The first fluid particle that is not finite, whose speed passed `max_speed` or
/// whose density left `[ρ0(1-l), ρ0(1+l)]`, with a description of what
/// went wrong.
pub fn find_instability<const D: usize>(
    p: &Particles<D>,
    rho0: f64,
    limit: f64,
    max_speed: f64,
) -> Option<(usize, String)> {
    (0..p.len())
        .into_par_iter()
        .filter(|&i| p.kind[i] == Kind::Fluid)
        .find_map_first(|i| {
            let finite =
                p.x[i].iter().chain(p.u[i].iter()).all(|v| v.is_finite()) && p.rho[i].is_finite();
            if !finite {
                return Some((i, "non-finite position, velocity or density".to_string()));
            }
            let speed = p.u[i].norm();
            if speed > max_speed {
                let why = format!(
                    "speed {speed:.4e} m/s beyond the limit {max_speed:.4e} m/s (stability.max_mach × c0)"
                );
                return Some((i, why));
            }
            let var = p.rho[i] / rho0 - 1.0;
            (var.abs() > limit).then(|| {
                (
                    i,
                    format!("density variation ρ/ρ0 - 1 = {var:.4} beyond the limit ±{limit}"),
                )
            })
        })
}
