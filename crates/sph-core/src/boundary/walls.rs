//! Dummy wall particles with extrapolated pressure (Adami, Hu & Adams 2012,
//! J. Comput. Phys. 231:7057):
//!
//! `p_w = [Σ_f p_f W_wf + (g - a_w)·Σ_f ρ_f (x_w - x_f) W_wf] / Σ_f W_wf`,
//! `ρ_w = ρ0 + p_w/c0²`, and for the viscous term the wall velocity seen by the
//! fluid is `2 u_w - ũ_w` with `ũ_w = Σ_f u_f W_wf / Σ_f W_wf` (no-slip). Free-slip
//! walls drop the wall-fluid viscous interaction instead. Fixed walls do not
//! accelerate (`a_w = 0`): they are at rest or slide in their own plane with a
//! constant `u_w` (a lid); the walls of a moving body carry the `u_w` and `a_w` of its
//! motion (see [`crate::motion`]). A wall particle with no fluid neighbour takes p = 0,
//! ρ = ρ0, `u_w`.
//!
//! The extrapolated `p_w` is clamped at zero: a wall does not pull on the fluid.
//!
//! Walls push lone particles and never pull or stretch them. A lone particle (no other
//! fluid within the kernel support) feels `max(p_w + p_i, 0)` from each wall particle
//! instead of `(p_w + p_i)`, and the walls may compress it (dρ/dt > 0 as it approaches
//! them, which builds the pressure that stops it) but not expand it below ρ0. Such a
//! particle, a splash that left the bulk expanded (ρ < ρ0), keeps its density, since no
//! fluid around it can restore it; its tension, extrapolated to the walls as well,
//! pulled it into the top edge of a wall it skimmed (dam break, H/Δx = 20).
//!
//! Fluid in contact with the bulk keeps `(p_w + p_i)` with its own `p_i`: the run-up
//! sheet of a dam break is in slight tension along the wall. Dropping a negative `p_i`
//! against walls for all fluid was tried and measured: the sheet then tears, and the
//! dam break of `examples/dam_break_2d.toml` (H/Δx = 50, α = 0.02) trips the density
//! guard at t·sqrt(g/H) ≈ 5.5. Releasing only lone particles without clamping `p_w`
//! still let fluid into the walls of the coarse 3D and symplectic 2D dam breaks. The
//! energy budget's wall power accounts for the lone-particle force; the lone
//! particle's withheld expansion is not in the budget.

use crate::domain::Domain;
use crate::neighbours::NeighbourList;
use crate::particles::{Particles, Vector};
use crate::physics::eos::LinearEos;
use crate::physics::kernel::Kernel;
use rayon::prelude::*;

/// Updates pressure, density and viscous velocity of every wall particle from the fluid.
pub fn extrapolate_walls<const D: usize, K: Kernel>(
    kernel: &K,
    eos: &LinearEos,
    gravity: &Vector<D>,
    particles: &mut Particles<D>,
    list: &NeighbourList<D>,
    domain: &Domain<D>,
) {
    let state: &Particles<D> = particles;
    let updates: Vec<(usize, f64, Vector<D>)> = list
        .wall_particles()
        .par_iter()
        .map(|&i| {
            let xw = state.x[i];
            let (mut sw, mut sp, mut srx, mut su) =
                (0.0, 0.0, Vector::<D>::zeros(), Vector::<D>::zeros());
            for &f in list.fluid(i) {
                let f = f as usize;
                let x_wf = domain.separation(&xw, &state.x[f]);
                let w = kernel.w(x_wf.norm());
                sw += w;
                sp += state.p[f] * w;
                srx += x_wf * (state.rho[f] * w);
                su += state.u[f] * w;
            }
            let uw = state.u[i];
            let g = match &state.wall_acceleration {
                Some(a) => gravity - a[i],
                None => *gravity,
            };
            if sw > 0.0 {
                (i, ((sp + g.dot(&srx)) / sw).max(0.0), uw * 2.0 - su / sw)
            } else {
                (i, 0.0, uw)
            }
        })
        .collect();
    for (i, p, u_visc) in updates {
        particles.p[i] = p;
        particles.rho[i] = eos.density(p);
        particles.u_wall_visc[i] = u_visc;
    }
}
