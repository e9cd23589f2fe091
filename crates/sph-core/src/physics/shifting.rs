//! Particle shifting of δ+-SPH (Sun, Colagrossi, Marrone & Zhang 2017, "The δplus-SPH
//! model: simple procedures for a further improvement of the SPH scheme", Comput.
//! Methods Appl. Mech. Engrg. 315:25; SCHEME.md §9).
//!
//! After each step every fluid particle is displaced by
//! `δr_i = -CFL·Ma (2h)² Σ_j [1 + R (W_ij/W(Δx))⁴] ∇_i W_ij V_j`, `R = 0.2`,
//! `CFL·Ma = U_max Δt/h`, with `V_j = m_j/ρ_j` (the form of the talk and SCHEME.md).
//! The sum runs over fluid and wall neighbours, so walls push particles away.
//!
//! Near the free surface (detected by [`crate::physics::free_surface`]):
//! - particles with `λ_i < 0.4` (splashes, nearly isolated) are not shifted;
//! - surface particles, particles with `λ_i <= 0.75`, and particles with a surface
//!   particle among their neighbours keep only the tangential part `(I - n_i⊗n_i) δr_i`,
//!   so shifting does not move the free surface.
//!
//! Every displacement is capped at `|δr_i| <= 0.05 h`. Velocity and density are not
//! corrected for the displacement (the δ+-SPH choice).

use crate::domain::Domain;
use crate::neighbours::NeighbourList;
use crate::particles::{Kind, Particles, Vector};
use crate::physics::free_surface::FreeSurface;
use crate::physics::kernel::Kernel;
use rayon::prelude::*;

/// `R` of the anti-clustering term.
pub const ANTI_CLUSTERING: f64 = 0.2;
/// Below this `λ` a particle is not shifted.
pub const SPLASH_LAMBDA: f64 = 0.4;
/// The cap on `|δr_i|`, in units of h.
pub const CAP: f64 = 0.05;

/// The displacements `δr_i` of one shift (zero for walls); `cfl_ma = U_max Δt / h`.
pub fn displacements<const D: usize, K: Kernel>(
    kernel: &K,
    dx: f64,
    particles: &Particles<D>,
    list: &NeighbourList<D>,
    domain: &Domain<D>,
    surface: &FreeSurface<D>,
    cfl_ma: f64,
) -> Vec<Vector<D>> {
    let h = kernel.h();
    let w_dx = kernel.w(dx);
    let scale = cfl_ma * (2.0 * h).powi(2);
    (0..particles.len())
        .into_par_iter()
        .map(|i| {
            if particles.kind[i] != Kind::Fluid || surface.lambda[i] < SPLASH_LAMBDA {
                return Vector::zeros();
            }
            let xi = particles.x[i];
            let mut sum = Vector::<D>::zeros();
            for j in list.of(i) {
                let x_ij = domain.separation(&xi, &particles.x[j]);
                let r = x_ij.norm();
                let w = kernel.w(r);
                if w == 0.0 {
                    continue;
                }
                let weight = 1.0 + ANTI_CLUSTERING * (w / w_dx).powi(4);
                sum += x_ij * (kernel.dw_over_r(r) * particles.volume(j) * weight);
            }
            let mut dr = -sum * scale;
            if surface.near[i] {
                let n = surface.normal[i];
                dr -= n * n.dot(&dr);
            }
            let cap = CAP * h;
            let len = dr.norm();
            if len > cap {
                dr *= cap / len;
            }
            dr
        })
        .collect()
}
