//! Particle shifting of δ+-SPH (Sun, Colagrossi, Marrone & Zhang 2017, "The δplus-SPH
//! model: simple procedures for a further improvement of the SPH scheme", Comput.
//! Methods Appl. Mech. Engrg. 315:25; SCHEME.md §9).
//!
//! Between steps (at the start of each, with the Δt of the step before) every fluid
//! particle is displaced by
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
use crate::physics::free_surface::{self, FreeSurface, Moments};
use crate::physics::kernel::Kernel;
use rayon::prelude::*;

/// `R` of the anti-clustering term.
pub const ANTI_CLUSTERING: f64 = 0.2;
/// Below this `λ` a particle is not shifted.
pub const SPLASH_LAMBDA: f64 = 0.4;
/// The cap on `|δr_i|`, in units of h.
pub const CAP: f64 = 0.05;

/// One shift: the displacements `δr_i` (zero for walls) and the free surface they were
/// shaped by, at the state before the shift.
pub struct Shift<const D: usize> {
    pub dr: Vec<Vector<D>>,
    pub surface: FreeSurface<D>,
}

/// The displacements of one shift with `cfl_ma = U_max Δt / h`. A single pass over the
/// neighbours gathers the shifting sum and the free-surface [`Moments`] together.
pub fn shift<const D: usize, K: Kernel>(
    kernel: &K,
    dx: f64,
    particles: &Particles<D>,
    list: &NeighbourList<D>,
    domain: &Domain<D>,
    cfl_ma: f64,
) -> Shift<D> {
    let inv_w_dx = 1.0 / kernel.w(dx);
    let volume = particles.volumes();
    let (sums, moments): (Vec<Vector<D>>, Vec<Moments<D>>) = (0..particles.len())
        .into_par_iter()
        .map(|i| {
            let (mut sum, mut m) = (Vector::<D>::zeros(), Moments::zero());
            if particles.kind[i] != Kind::Fluid {
                return (sum, m);
            }
            let xi = particles.x[i];
            let mut add = |j: &u32| {
                let j = *j as usize;
                let x_ij = domain.separation(&xi, &particles.x[j]);
                let r = x_ij.norm();
                let w = kernel.w(r) * inv_w_dx;
                let grad_w = x_ij * (kernel.dw_over_r(r) * volume[j]);
                // beyond the support both vanish, and so does the pair's share
                m.add(&-x_ij, &grad_w);
                sum += grad_w * (1.0 + ANTI_CLUSTERING * (w * w) * (w * w));
            };
            list.fluid(i).iter().for_each(&mut add);
            list.walls(i).iter().for_each(&mut add);
            (sum, m)
        })
        .unzip();
    let surface = free_surface::classify(kernel, particles, list, domain, &moments);
    let scale = cfl_ma * (2.0 * kernel.h()).powi(2);
    let cap = CAP * kernel.h();
    let dr = (0..particles.len())
        .into_par_iter()
        .map(|i| {
            if particles.kind[i] != Kind::Fluid || surface.lambda[i] < SPLASH_LAMBDA {
                return Vector::zeros();
            }
            let mut dr = -sums[i] * scale;
            if surface.near[i] {
                let n = surface.normal[i];
                dr -= n * n.dot(&dr);
            }
            let len = dr.norm();
            if len > cap {
                dr *= cap / len;
            }
            dr
        })
        .collect();
    Shift { dr, surface }
}
