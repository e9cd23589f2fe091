//! Run-time diagnostics: mechanical energy (Antuono et al. 2015, CMAME 289:209),
//! density variation, pressure probes and the surge front.
//!
//! - `E_k = Σ m_i |u_i|²/2`, `E_p = -Σ m_i g·x_i`, `E_c = Σ m_i c0² [ln(ρ_i/ρ0) + ρ0/ρ_i - 1]`
//!   over fluid particles. With K = 0 and δ = 0, `E_k + E_p + E_c` is conserved by the
//!   semi-discrete equations; otherwise it changes by `∫ (P_V + P_D) dt`.
//! - Probes interpolate the fluid pressure with a Shepard-normalised kernel sum,
//!   `p(x) = Σ_f p_f W(x - x_f) V_f / Σ_f W(x - x_f) V_f` (0 where no fluid is in reach).

use crate::case::Case;
use crate::domain::Domain;
use crate::eos::LinearEos;
use crate::equations::Model;
use crate::neighbours::NeighbourList;
use crate::particles::{Kind, Particles, Vector};
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
}

/// E_k, E_p and E_c of the fluid.
pub fn energies<const D: usize>(p: &Particles<D>, eos: &LinearEos, g: &Vector<D>) -> Energies {
    let fluid: Vec<bool> = p.kind.iter().map(|&k| k == Kind::Fluid).collect();
    energies_of(p, &fluid, eos, g)
}

/// E_k, E_p and E_c of the particles flagged in `which`.
pub fn energies_of<const D: usize>(
    p: &Particles<D>,
    which: &[bool],
    eos: &LinearEos,
    g: &Vector<D>,
) -> Energies {
    (0..p.len())
        .into_par_iter()
        .filter(|&i| which[i])
        .map(|i| {
            let m = p.mass[i];
            Energies {
                kinetic: 0.5 * m * p.u[i].norm_squared(),
                potential: -m * g.dot(&p.x[i]),
                internal: m * eos.internal_energy(p.rho[i]),
            }
        })
        .reduce(Energies::default, |a, b| Energies {
            kinetic: a.kinetic + b.kinetic,
            potential: a.potential + b.potential,
            internal: a.internal + b.internal,
        })
}

/// Largest `|ρ_i/ρ0 - 1|` over the fluid.
pub fn max_density_variation<const D: usize>(p: &Particles<D>, rho0: f64) -> f64 {
    (0..p.len())
        .into_par_iter()
        .filter(|&i| p.kind[i] == Kind::Fluid)
        .map(|i| (p.rho[i] / rho0 - 1.0).abs())
        .reduce(|| 0.0, f64::max)
}

/// Shepard-interpolated fluid pressure at `point`.
pub fn probe_pressure<const D: usize>(
    model: &dyn Model<D>,
    p: &Particles<D>,
    list: &NeighbourList<D>,
    domain: &Domain<D>,
    point: &Vector<D>,
) -> f64 {
    let r_max = model.support_radius();
    let (mut num, mut den) = (0.0, 0.0);
    list.for_candidates(point, |j| {
        if p.kind[j] != Kind::Fluid {
            return;
        }
        let r = domain.separation(point, &p.x[j]).norm();
        if r < r_max {
            let wv = model.w(r) * p.mass[j] / p.rho[j];
            num += p.p[j] * wv;
            den += wv;
        }
    });
    if den > 0.0 {
        num / den
    } else {
        0.0
    }
}

/// Largest fluid coordinate along `axis` (the leading edge of a surge).
pub fn surge_front<const D: usize>(p: &Particles<D>, axis: usize) -> f64 {
    (0..p.len())
        .into_par_iter()
        .filter(|&i| p.kind[i] == Kind::Fluid)
        .map(|i| p.x[i][axis])
        .reduce(|| f64::MIN, f64::max)
}

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

/// Fluid particles inside a wall: past the first layer of wall particles (more than
/// Δx/2 beyond a closed face of a tank, within its layers and below the last wall
/// particles at an open face, over which fluid may pass), or deeper than Δx/2 inside
/// a `[[wall]]` box. Zero in a sound run; dummy-particle walls do not forbid
/// crossing, so this counts the failures.
pub fn wall_crossings<const D: usize>(case: &Case, p: &Particles<D>) -> usize {
    let dx = case.dx();
    let inside = |x: &Vector<D>, lo: &[f64], hi: &[f64], margin: f64| {
        (0..D).all(|d| x[d] > lo[d] + margin && x[d] < hi[d] - margin)
    };
    let tanks: Vec<_> = case.tank.iter().map(|t| (t, t.open_faces(D))).collect();
    let in_tank_wall = |x: &Vector<D>, (t, open): &(&crate::case::TankConfig, Vec<(usize, i8)>)| {
        let pad = t.layer_count(case) as f64 * dx;
        let within_layers = (0..D).all(|d| x[d] > t.lo[d] - pad && x[d] < t.hi[d] + pad);
        let past_closed_face = (0..D).any(|d| {
            let below = x[d] < t.lo[d] - 0.5 * dx && !open.contains(&(d, -1));
            let above = x[d] > t.hi[d] + 0.5 * dx && !open.contains(&(d, 1));
            below || above
        });
        // above the last wall particles at an open face: passing over the wall's edge
        let beyond_open = open.iter().any(|&(d, s)| {
            if s > 0 {
                x[d] > t.hi[d] - 0.5 * dx
            } else {
                x[d] < t.lo[d] + 0.5 * dx
            }
        });
        within_layers && past_closed_face && !beyond_open
    };
    (0..p.len())
        .into_par_iter()
        .filter(|&i| p.kind[i] == Kind::Fluid)
        .filter(|&i| {
            let x = &p.x[i];
            tanks.iter().any(|tank| in_tank_wall(x, tank))
                || case.wall.iter().any(|w| inside(x, &w.lo, &w.hi, 0.5 * dx))
        })
        .count()
}
