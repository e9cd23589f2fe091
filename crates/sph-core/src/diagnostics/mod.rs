//! Run-time diagnostics: mechanical energy (Antuono et al. 2015, CMAME 289:209),
//! density variation, pressure probes and the surge front.
//!
//! - `E_k = Σ m_i |u_i|²/2`, `E_p = -Σ m_i g·x_i`, `E_c = Σ m_i c0² [ln(ρ_i/ρ0) + ρ0/ρ_i - 1]`
//!   over fluid particles. With K = 0 and δ = 0, `E_k + E_p + E_c` is conserved by the
//!   semi-discrete equations; otherwise it changes by `∫ (P_V + P_D) dt`.
//! - Probes interpolate the fluid's pressure, velocity and density with a
//!   Shepard-normalised kernel sum ([`PointReader`]).
//! - Face sensors on the walls, averaged and low-pass filtered ([`sensors`]).
//! - Wave gauges: the free surface's elevation on vertical lines ([`gauges`]).
//! - Flow sections: the volume and mass flow through a segment or a parallelogram
//!   ([`sections`]).
//! - The stability guard (`guard`) and the count of fluid inside walls (`crossings`).

pub mod budget;
mod crossings;
pub mod gauges;
mod guard;
mod points;
pub mod sections;
pub mod sensors;
pub mod series;

pub use crossings::wall_crossings;
pub use guard::{
    densest_excursion, find_instability, DensityWatch, Excursion, Holder, Verdict, WatchMemory,
};
pub use points::PointReader;

use crate::particles::blocks::sum_in_blocks;
use crate::particles::{Kind, Particles, Vector};
use crate::physics::eos::LinearEos;
use rayon::prelude::*;

#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Energies {
    pub kinetic: f64,
    pub potential: f64,
    pub internal: f64,
}

impl Energies {
    pub fn total(&self) -> f64 {
        self.kinetic + self.potential + self.internal
    }

    fn add(self, o: Self) -> Self {
        Self {
            kinetic: self.kinetic + o.kinetic,
            potential: self.potential + o.potential,
            internal: self.internal + o.internal,
        }
    }
}

/// E_k, E_p and E_c of the fluid.
pub fn energies<const D: usize>(p: &Particles<D>, eos: &LinearEos, g: &Vector<D>) -> Energies {
    energies_of(p, |i| p.kind[i] == Kind::Fluid, eos, g)
}

/// E_k, E_p and E_c of the particles `i` for which `which(i)` holds (the same bits on
/// any number of threads).
pub fn energies_of<const D: usize>(
    p: &Particles<D>,
    which: impl Fn(usize) -> bool + Sync + Send,
    eos: &LinearEos,
    g: &Vector<D>,
) -> Energies {
    let block = |range: std::ops::Range<usize>| {
        range
            .filter(|&i| which(i))
            .fold(Energies::default(), |e, i| {
                let m = p.mass[i];
                e.add(Energies {
                    kinetic: 0.5 * m * p.u[i].norm_squared(),
                    potential: -m * g.dot(&p.x[i]),
                    internal: m * eos.internal_energy(p.rho[i]),
                })
            })
    };
    sum_in_blocks(p.len(), Energies::default, block, Energies::add)
}

/// Largest `|ρ_i/ρ0 - 1|` over the fluid.
pub fn max_density_variation<const D: usize>(p: &Particles<D>, rho0: f64) -> f64 {
    (0..p.len())
        .into_par_iter()
        .filter(|&i| p.kind[i] == Kind::Fluid)
        .map(|i| (p.rho[i] / rho0 - 1.0).abs())
        .reduce(|| 0.0, f64::max)
}

/// Largest fluid coordinate along `axis` (the leading edge of a surge).
pub fn surge_front<const D: usize>(p: &Particles<D>, axis: usize) -> f64 {
    (0..p.len())
        .into_par_iter()
        .filter(|&i| p.kind[i] == Kind::Fluid)
        .map(|i| p.x[i][axis])
        .reduce(|| f64::MIN, f64::max)
}
