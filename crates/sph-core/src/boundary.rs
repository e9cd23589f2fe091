//! Fixed dummy wall particles with extrapolated pressure (Adami, Hu & Adams 2012,
//! J. Comput. Phys. 231:7057):
//!
//! `p_w = [Σ_f p_f W_wf + (g - a_w)·Σ_f ρ_f (x_w - x_f) W_wf] / Σ_f W_wf`,
//! `ρ_w = ρ0 + p_w/c0²`, and for the viscous term the wall velocity seen by the
//! fluid is `2 u_w - ũ_w` with `ũ_w = Σ_f u_f W_wf / Σ_f W_wf` (no-slip). Free-slip
//! walls drop the wall-fluid viscous interaction instead. Walls do not accelerate
//! (`a_w = 0`): they are at rest or slide in their own plane with a constant `u_w`
//! (a lid); a wall particle with no fluid neighbour takes p = 0, ρ = ρ0, `u_w`.
//!
//! Walls push and never pull: the extrapolated `p_w` is clamped at zero, and in the
//! momentum equation a fluid particle's pressure counts against a wall only when
//! positive, `(p_w + max(p_i, 0))`. Otherwise a fluid particle in tension, typically a
//! splash particle that left the bulk expanded (ρ < ρ0, alone, so nothing restores
//! its density), is sucked into the wall it passes; a liquid cannot hold tension
//! against a wall without cavitating. In flows whose pressure stays positive (all
//! those with a background pressure) nothing changes. The energy budget's wall power
//! takes the difference into account (`P_W` with `p_w + max(p_i, 0) - p_i`).
//!
//! Measured trade-off: releasing the tension only for lone particles (no other fluid
//! within reach) still let fluid into the walls of the coarse 3D dam break and of the
//! symplectic 2D one; releasing it for all fluid holds every wall, but the thin run-up
//! sheet of a very coarse dam break (H/Δx = 12) with α = 0 then tears and trips the
//! density guard (docs/stability).

use crate::domain::Domain;
use crate::eos::LinearEos;
use crate::kernel::Kernel;
use crate::neighbours::NeighbourList;
use crate::particles::{Kind, Particles, Vector};
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
    let updates: Vec<(usize, f64, Vector<D>)> = (0..state.len())
        .into_par_iter()
        .filter(|&i| state.kind[i] == Kind::Wall)
        .map(|i| {
            let xw = state.x[i];
            let (mut sw, mut sp, mut srx, mut su) =
                (0.0, 0.0, Vector::<D>::zeros(), Vector::<D>::zeros());
            for &f in list.of(i) {
                let f = f as usize;
                let x_wf = domain.separation(&xw, &state.x[f]);
                let w = kernel.w(x_wf.norm());
                sw += w;
                sp += state.p[f] * w;
                srx += x_wf * (state.rho[f] * w);
                su += state.u[f] * w;
            }
            let uw = state.u[i];
            if sw > 0.0 {
                (
                    i,
                    ((sp + gravity.dot(&srx)) / sw).max(0.0),
                    uw * 2.0 - su / sw,
                )
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
