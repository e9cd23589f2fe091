//! Run-time diagnostics: mechanical energy (Antuono et al. 2015, CMAME 289:209),
//! density variation, pressure probes and the surge front.
//!
//! - `E_k = Σ m_i |u_i|²/2`, `E_p = -Σ m_i g·x_i`, `E_c = Σ m_i c0² [ln(ρ_i/ρ0) + ρ0/ρ_i - 1]`
//!   over fluid particles. With K = 0 and δ = 0, `E_k + E_p + E_c` is conserved by the
//!   semi-discrete equations; otherwise it changes by `∫ (P_V + P_D) dt`.
//! - Probes interpolate the fluid's pressure, velocity and density with a
//!   Shepard-normalised kernel sum, `p(x) = Σ_f p_f W(x - x_f) V_f / Σ_f W(x - x_f) V_f`,
//!   `V_f = m_f/ρ_f` (none where no fluid is in reach).
//! - Face sensors on the walls, averaged and low-pass filtered ([`sensors`]).
//! - Wave gauges: the free surface's elevation on vertical lines ([`gauges`]).
//! - Flow sections: the volume and mass flow through a segment or a parallelogram
//!   ([`sections`]).
//! - The stability guard (`guard`) and the count of fluid inside walls (`crossings`).

pub mod budget;
mod crossings;
pub mod gauges;
mod guard;
pub mod sections;
pub mod sensors;
pub mod series;

pub use crossings::wall_crossings;
pub use guard::{
    densest_excursion, find_instability, DensityWatch, Excursion, Holder, Verdict, WatchMemory,
};

use crate::domain::Domain;
use crate::neighbours::NeighbourList;
use crate::particles::blocks::sum_in_blocks;
use crate::particles::{Kind, Particles, Vector};
use crate::physics::eos::LinearEos;
use crate::physics::kernel::Smoothing;
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

/// Calls `f(j, W(x - x_j) V_j)` for every particle `j` (fluid and wall) within the
/// kernel support of `point`.
fn for_near<const D: usize>(
    kernel: &(impl Smoothing + ?Sized),
    p: &Particles<D>,
    list: &NeighbourList<D>,
    domain: &Domain<D>,
    point: &Vector<D>,
    mut f: impl FnMut(usize, f64),
) {
    let r_max = kernel.support_radius();
    list.for_candidates(point, |j| {
        let r = domain.separation(point, &p.x[j]).norm();
        if r < r_max {
            f(j, kernel.w(r) * p.mass[j] / p.rho[j]);
        }
    });
}

/// [`for_near`] over the fluid particles only.
fn for_fluid_near<const D: usize>(
    kernel: &(impl Smoothing + ?Sized),
    p: &Particles<D>,
    list: &NeighbourList<D>,
    domain: &Domain<D>,
    point: &Vector<D>,
    mut f: impl FnMut(usize, f64),
) {
    for_near(kernel, p, list, domain, point, |j, wv| {
        if p.kind[j] == Kind::Fluid {
            f(j, wv)
        }
    });
}

/// The volume and mass flow densities through a section at `point` along the unit
/// `normal`: `[Σ_f (u_f·n) W_f V_f, Σ_f (u_f·n) W_f m_f] / (1 - Γ_w)`, with
/// `Γ_w = Σ_w W_w V_w` the walls' kernel sum; zero inside a wall (`Γ_w >= ½`).
///
/// Dividing by `1 - Γ_w` restores the kernel's share that the walls take next to
/// them (where `Γ_f + Γ_w ≈ 1` the fluid's share counts fully), while at a free
/// surface the fluid's taper `Γ_f` from 1 to 0 stays: integrated across a flat surface
/// it gives the depth to the surface plane, as the gauges read it.
pub fn flow_density<const D: usize>(
    kernel: &(impl Smoothing + ?Sized),
    p: &Particles<D>,
    list: &NeighbourList<D>,
    domain: &Domain<D>,
    point: &Vector<D>,
    normal: &Vector<D>,
) -> [f64; 2] {
    let (mut volume, mut mass, mut walls) = (0.0, 0.0, 0.0);
    for_near(kernel, p, list, domain, point, |j, wv| match p.kind[j] {
        Kind::Fluid => {
            let un = p.u[j].dot(normal) * wv;
            volume += un;
            mass += un * p.rho[j];
        }
        Kind::Wall => walls += wv,
    });
    if walls >= 0.5 {
        return [0.0; 2];
    }
    [volume / (1.0 - walls), mass / (1.0 - walls)]
}

/// Shepard-interpolated fluid pressure at `point`, `Σ_j p_j W_ij V_j / Σ_j W_ij V_j`
/// over the fluid within the kernel support; `None` where no fluid is in reach (a dry
/// point has no SPH pressure, which is not the same as zero pressure).
pub fn probe_pressure<const D: usize>(
    kernel: &(impl Smoothing + ?Sized),
    p: &Particles<D>,
    list: &NeighbourList<D>,
    domain: &Domain<D>,
    point: &Vector<D>,
) -> Option<f64> {
    shepard(kernel, p, list, domain, point, |j| [p.p[j]]).map(|[v]| v)
}

/// Shepard-interpolated fluid velocity at `point`, `Σ_j u_j W_ij V_j / Σ_j W_ij V_j`;
/// `None` where no fluid is in reach.
pub fn probe_velocity<const D: usize>(
    kernel: &(impl Smoothing + ?Sized),
    p: &Particles<D>,
    list: &NeighbourList<D>,
    domain: &Domain<D>,
    point: &Vector<D>,
) -> Option<Vector<D>> {
    let u = shepard(kernel, p, list, domain, point, |j| {
        std::array::from_fn(|d| p.u[j][d])
    });
    u.map(|u: [f64; D]| Vector::from(u))
}

/// Shepard-interpolated fluid density at `point`, `Σ_j ρ_j W_ij V_j / Σ_j W_ij V_j`;
/// `None` where no fluid is in reach.
pub fn probe_density<const D: usize>(
    kernel: &(impl Smoothing + ?Sized),
    p: &Particles<D>,
    list: &NeighbourList<D>,
    domain: &Domain<D>,
    point: &Vector<D>,
) -> Option<f64> {
    shepard(kernel, p, list, domain, point, |j| [p.rho[j]]).map(|[v]| v)
}

/// `Σ_j f_j W_ij V_j / Σ_j W_ij V_j` over the fluid within the kernel support of
/// `point`; `None` where none is.
fn shepard<const D: usize, const N: usize>(
    kernel: &(impl Smoothing + ?Sized),
    p: &Particles<D>,
    list: &NeighbourList<D>,
    domain: &Domain<D>,
    point: &Vector<D>,
    f: impl Fn(usize) -> [f64; N],
) -> Option<[f64; N]> {
    let (mut num, mut den) = ([0.0; N], 0.0);
    for_fluid_near(kernel, p, list, domain, point, |j, wv| {
        for (n, v) in num.iter_mut().zip(f(j)) {
            *n += v * wv;
        }
        den += wv;
    });
    (den > 0.0).then(|| num.map(|n| n / den))
}

/// The fluid's kernel sum `Γ(x) = Σ_f W(x - x_f) V_f` at `point` (0 where no fluid is
/// in reach).
pub fn fluid_fraction<const D: usize>(
    kernel: &(impl Smoothing + ?Sized),
    p: &Particles<D>,
    list: &NeighbourList<D>,
    domain: &Domain<D>,
    point: &Vector<D>,
) -> f64 {
    let mut sum = 0.0;
    for_fluid_near(kernel, p, list, domain, point, |_, wv| sum += wv);
    sum
}

/// Largest fluid coordinate along `axis` (the leading edge of a surge).
pub fn surge_front<const D: usize>(p: &Particles<D>, axis: usize) -> f64 {
    (0..p.len())
        .into_par_iter()
        .filter(|&i| p.kind[i] == Kind::Fluid)
        .map(|i| p.x[i][axis])
        .reduce(|| f64::MIN, f64::max)
}
