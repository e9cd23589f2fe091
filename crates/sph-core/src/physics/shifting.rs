//! Particle shifting of δ+-SPH (Sun, Colagrossi, Marrone & Zhang 2017, "The δplus-SPH
//! model: simple procedures for a further improvement of the SPH scheme", Comput.
//! Methods Appl. Mech. Engrg. 315:25; docs/theory.md §9).
//!
//! Between steps (at the start of each, with the Δt of the step before) every fluid
//! particle is displaced by
//! `δr_i = -CFL·Ma (2h)² Σ_j [1 + R (W_ij/W(Δx))⁴] ∇_i W_ij V_j`, `R = 0.2`,
//! `CFL·Ma = U_max Δt/h`, with `V_j = m_j/ρ_j` (the form of the talk, docs/theory.md §9).
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
use crate::physics::renormalisation::guarded_inverse;
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

/// How strongly one shift acts: the lattice spacing Δx of the anti-clustering term and
/// `cfl_ma = CFL·Ma = U_max Δt / h`.
#[derive(Debug, Clone, Copy)]
pub struct Strength {
    pub dx: f64,
    pub cfl_ma: f64,
}

/// The displacements of one shift, `volume[j] = m_j/ρ_j`.
/// A single pass over the neighbours gathers the shifting sum and the free-surface
/// [`Moments`] together.
///
/// With `gradient`, the same pass also fills it with the renormalised density gradient
/// `⟨∇ρ⟩^L_i = B_i⁻¹ Σ_j (ρ_j - ρ_i) ∇_i W_ij V_j` of
/// [`crate::physics::renormalisation`] (whose `B_i` is the free surface's), at the state
/// before the shift: δ-SPH's diffusion then needs no pass of its own in the step's first
/// evaluation. The shift moves particles by at most 0.05 h and leaves densities as they
/// are, so the gradient it carries differs from the one at the shifted positions by
/// `O(|δr_i| ∇∇ρ)`, less than the frozen diffusion's lag over the step.
pub fn shift<const D: usize, K: Kernel>(
    kernel: &K,
    strength: Strength,
    particles: &Particles<D>,
    volume: &[f64],
    list: &NeighbourList<D>,
    domain: &Domain<D>,
    gradient: Option<&mut Vec<Vector<D>>>,
) -> Shift<D> {
    let inv_w_dx = 1.0 / kernel.w(strength.dx);
    let sums = match gradient {
        Some(grad) => {
            let sums = gather_all::<D, K, true>(kernel, inv_w_dx, particles, volume, list, domain);
            grad.clear();
            grad.par_extend(sums.par_iter().map(|g| g.density_gradient()));
            sums
        }
        None => gather_all::<D, K, false>(kernel, inv_w_dx, particles, volume, list, domain),
    };
    let moments: Vec<Moments<D>> = sums.par_iter().map(|g| g.moments).collect();
    let surface = free_surface::classify(kernel, particles, list, domain, &moments);
    let scale = strength.cfl_ma * (2.0 * kernel.h()).powi(2);
    let cap = CAP * kernel.h();
    let dr = (0..particles.len())
        .into_par_iter()
        .map(|i| {
            if particles.kind[i] != Kind::Fluid || surface.lambda[i] < SPLASH_LAMBDA {
                return Vector::zeros();
            }
            let mut dr = -sums[i].shifting * scale;
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

/// One fluid particle's neighbour sums: the shifting sum
/// `Σ_j [1 + R (W_ij/W(Δx))⁴] ∇_i W_ij V_j`, the free-surface [`Moments`] and, when
/// gathered, `Σ_j (ρ_j - ρ_i) ∇_i W_ij V_j` (zero for walls).
#[derive(Clone, Copy)]
struct Gathered<const D: usize> {
    shifting: Vector<D>,
    moments: Moments<D>,
    density: Vector<D>,
}

impl<const D: usize> Gathered<D> {
    /// Adds neighbour j at `x_ji` with `f = W'(r)/r V_j`, `w = W_ij/W(Δx)` and
    /// `drho = ρ_j - ρ_i`.
    #[inline(always)]
    fn add<const GRAD: bool>(&mut self, (x_ji, f, w, drho): (Vector<D>, f64, f64, f64)) {
        self.moments.add_radial(&x_ji, f);
        let grad_w = x_ji * -f;
        self.shifting += grad_w * (1.0 + ANTI_CLUSTERING * (w * w) * (w * w));
        if GRAD {
            self.density += grad_w * drho;
        }
    }

    fn density_gradient(&self) -> Vector<D> {
        guarded_inverse(&self.moments.b) * self.density
    }
}

/// The [`Gathered`] sums of every particle; the density sum only when `GRAD`.
fn gather_all<const D: usize, K: Kernel, const GRAD: bool>(
    kernel: &K,
    inv_w_dx: f64,
    particles: &Particles<D>,
    volume: &[f64],
    list: &NeighbourList<D>,
    domain: &Domain<D>,
) -> Vec<Gathered<D>> {
    (0..particles.len())
        .into_par_iter()
        .map(|i| gather::<D, K, GRAD>(kernel, inv_w_dx, i, particles, volume, list, domain))
        .collect()
}

/// The [`Gathered`] sums of particle i over its fluid neighbours and then its walls
/// (beyond the support every share vanishes).
#[inline(always)]
fn gather<const D: usize, K: Kernel, const GRAD: bool>(
    kernel: &K,
    inv_w_dx: f64,
    i: usize,
    particles: &Particles<D>,
    volume: &[f64],
    list: &NeighbourList<D>,
    domain: &Domain<D>,
) -> Gathered<D> {
    let mut g = Gathered {
        shifting: Vector::zeros(),
        moments: Moments::zero(),
        density: Vector::zeros(),
    };
    if particles.kind[i] != Kind::Fluid {
        return g;
    }
    let (xi, rho_i) = (particles.x[i], particles.rho[i]);
    let pair = |j: u32| {
        let j = j as usize;
        let x_ji = domain.separation(&particles.x[j], &xi);
        let r = x_ji.norm();
        // ∇_i W_ij V_j = x_ij W'(r)/r V_j = -x_ji f
        let f = kernel.dw_over_r(r) * volume[j];
        let drho = if GRAD { particles.rho[j] - rho_i } else { 0.0 };
        (x_ji, f, kernel.w(r) * inv_w_dx, drho)
    };
    for &j in list.fluid(i).iter().chain(list.walls(i)) {
        g.add::<GRAD>(pair(j));
    }
    g.moments = g.moments.symmetrised();
    g
}
