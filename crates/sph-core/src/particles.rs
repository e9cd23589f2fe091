//! Particle storage as a structure of arrays.
//!
//! Fluid and wall particles share the arrays and are told apart by [`Kind`]; the
//! neighbour search reorders every array by cell, and `id` keeps each particle's
//! original index so that outputs can be matched across snapshots.

use nalgebra::SVector;
use rayon::prelude::*;

/// A position, velocity or force in `D` dimensions.
pub type Vector<const D: usize> = SVector<f64, D>;

/// What a particle is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u8)]
pub enum Kind {
    /// Moves with the flow; carries the conservation equations.
    Fluid = 0,
    /// Fixed dummy wall particle (Adami et al. 2012): pressure extrapolated from the fluid.
    Wall = 1,
}

/// The particle state `w = (x, u, ρ)` plus the per-particle constants.
#[derive(Debug, Clone, Default)]
pub struct Particles<const D: usize> {
    pub x: Vec<Vector<D>>,
    pub u: Vec<Vector<D>>,
    pub rho: Vec<f64>,
    /// Pressure from the equation of state (fluid) or the wall extrapolation (walls).
    pub p: Vec<f64>,
    /// Constant masses `m_i = ρ_i(t0) V0`.
    pub mass: Vec<f64>,
    pub kind: Vec<Kind>,
    /// Stable identity of each particle: its index at creation, never reused.
    pub id: Vec<u32>,
    /// Velocity seen by the viscous term at walls: `2 u_wall - ũ` (no-slip); unused for fluid.
    pub u_wall_visc: Vec<Vector<D>>,
    /// The id the next particle created gets (ids of removed particles are not reused).
    pub next_id: u32,
}

impl<const D: usize> Particles<D> {
    pub fn len(&self) -> usize {
        self.x.len()
    }

    pub fn is_empty(&self) -> bool {
        self.x.is_empty()
    }

    /// Appends one particle with the next free id.
    pub fn push(&mut self, kind: Kind, x: Vector<D>, u: Vector<D>, rho: f64, mass: f64) {
        self.id.push(self.next_id);
        self.next_id += 1;
        self.x.push(x);
        self.u.push(u);
        self.rho.push(rho);
        self.p.push(0.0);
        self.mass.push(mass);
        self.kind.push(kind);
        self.u_wall_visc.push(Vector::zeros());
    }

    /// `V_i = m_i / ρ_i`.
    pub fn volume(&self, i: usize) -> f64 {
        self.mass[i] / self.rho[i]
    }

    /// `V_i = m_i/ρ_i` of every particle.
    pub fn volumes(&self) -> Vec<f64> {
        self.mass
            .par_iter()
            .zip(self.rho.par_iter())
            .map(|(&m, &rho)| m / rho)
            .collect()
    }

    pub fn n_fluid(&self) -> usize {
        self.kind.iter().filter(|&&k| k == Kind::Fluid).count()
    }

    /// Reorders every array so that new index `k` holds old particle `order[k]`.
    pub fn permute(&mut self, order: &[usize]) {
        permute(&mut self.x, order);
        permute(&mut self.u, order);
        permute(&mut self.rho, order);
        permute(&mut self.p, order);
        permute(&mut self.mass, order);
        permute(&mut self.kind, order);
        permute(&mut self.id, order);
        permute(&mut self.u_wall_visc, order);
    }
}

impl<const D: usize> Particles<D> {
    /// Keeps the particles whose `keep` flag is set, in their order.
    pub fn retain(&mut self, keep: &[bool]) {
        retain(&mut self.x, keep);
        retain(&mut self.u, keep);
        retain(&mut self.rho, keep);
        retain(&mut self.p, keep);
        retain(&mut self.mass, keep);
        retain(&mut self.kind, keep);
        retain(&mut self.id, keep);
        retain(&mut self.u_wall_visc, keep);
    }
}

/// Keeps `v[k]` where `keep[k]`.
pub fn retain<T>(v: &mut Vec<T>, keep: &[bool]) {
    debug_assert_eq!(v.len(), keep.len());
    let mut flags = keep.iter();
    v.retain(|_| *flags.next().unwrap_or(&false));
}

/// Gathers `v[order[k]]` into position `k`.
pub fn permute<T: Copy + Send + Sync>(v: &mut Vec<T>, order: &[usize]) {
    debug_assert_eq!(v.len(), order.len());
    *v = order.par_iter().map(|&k| v[k]).collect();
}
