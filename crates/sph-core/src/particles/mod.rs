//! Particle storage as a structure of arrays.
//!
//! Fluid and wall particles share the arrays and are told apart by [`Kind`]; the
//! neighbour search reorders every array by cell, and `id` keeps each particle's
//! original index so that outputs can be matched across snapshots.
//!
//! Every per-particle column is a field of [`Particles`] and is listed once, in
//! [`Particles::columns_mut`]: reordering, thinning, appending and the messages
//! between processes handle each column through that list ([`column::Column`]). A
//! column only some runs need is an `Option<Vec<T>>`, `None` in the others.

pub mod blocks;
mod column;

pub use column::{permute, retain, Column, Value};

use nalgebra::SVector;
use rayon::prelude::*;

/// A position, velocity or force in `D` dimensions.
pub type Vector<const D: usize> = SVector<f64, D>;

/// The components of `v` in one flat slice (`x0, y0, x1, y1, …`), without a copy.
pub fn components<const D: usize>(v: &[Vector<D>]) -> &[f64] {
    bytemuck::cast_slice(v)
}

/// What a particle is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u8)]
pub enum Kind {
    /// Moves with the flow; carries the conservation equations.
    Fluid = 0,
    /// Fixed dummy wall particle (Adami et al. 2012): pressure extrapolated from the fluid.
    Wall = 1,
}

impl Kind {
    /// The kind stored as `byte` (`Kind as u8`); any other byte reads as fluid.
    pub fn from_byte(byte: u8) -> Self {
        if byte == Kind::Wall as u8 {
            Kind::Wall
        } else {
            Kind::Fluid
        }
    }
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
    /// `δr/Δt` of the last δ+-SPH shift (Sun et al. 2017), kept only when the case
    /// shifts particles.
    pub shift_velocity: Option<Vec<Vector<D>>>,
    /// Acceleration `a_w` of each wall particle of a moving body (zero for the others
    /// and for fluid), kept only when a body moves (see [`crate::motion`]).
    pub wall_acceleration: Option<Vec<Vector<D>>>,
    /// The id the next particle created gets (ids of removed particles are not reused).
    pub next_id: u32,
}

impl<const D: usize> Particles<D> {
    /// Every per-particle column: the one list a new column is added to.
    pub fn columns_mut(&mut self) -> [&mut dyn Column; 10] {
        [
            &mut self.x,
            &mut self.u,
            &mut self.rho,
            &mut self.p,
            &mut self.mass,
            &mut self.kind,
            &mut self.id,
            &mut self.u_wall_visc,
            &mut self.shift_velocity,
            &mut self.wall_acceleration,
        ]
    }

    /// [`Self::columns_mut`], to read.
    pub fn columns(&self) -> [&dyn Column; 10] {
        [
            &self.x,
            &self.u,
            &self.rho,
            &self.p,
            &self.mass,
            &self.kind,
            &self.id,
            &self.u_wall_visc,
            &self.shift_velocity,
            &self.wall_acceleration,
        ]
    }

    pub fn len(&self) -> usize {
        self.x.len()
    }

    pub fn is_empty(&self) -> bool {
        self.x.is_empty()
    }

    /// No particles, with the same optional columns as `self` and its `next_id`.
    pub fn empty_like(&self) -> Self {
        let mut empty = Self {
            next_id: self.next_id,
            ..Default::default()
        };
        for (to, from) in empty.columns_mut().into_iter().zip(self.columns()) {
            to.clear_like(from);
        }
        empty
    }

    /// Keeps the shifting velocity (zero until the first shift), or drops it.
    pub fn keep_shift_velocity(&mut self, keep: bool) {
        self.shift_velocity = keep.then(|| vec![Vector::zeros(); self.len()]);
    }

    /// Keeps the wall acceleration (zero until the bodies are placed), or drops it.
    pub fn keep_wall_acceleration(&mut self, keep: bool) {
        self.wall_acceleration = keep.then(|| vec![Vector::zeros(); self.len()]);
    }

    /// Appends one particle with the next free id (its other columns zero).
    pub fn push(&mut self, kind: Kind, x: Vector<D>, u: Vector<D>, rho: f64, mass: f64) {
        self.columns_mut()
            .into_iter()
            .for_each(|c| c.push_default());
        let i = self.len() - 1;
        (
            self.kind[i],
            self.x[i],
            self.u[i],
            self.rho[i],
            self.mass[i],
        ) = (kind, x, u, rho, mass);
        self.id[i] = self.next_id;
        self.next_id += 1;
    }

    /// Brings the optional columns to the particle count, after the required ones were
    /// edited from outside (new entries zero).
    pub fn fit_columns(&mut self) {
        let n = self.len();
        self.columns_mut().into_iter().for_each(|c| c.fit(n));
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

    /// Reorders every column so that new index `k` holds old particle `order[k]`.
    pub fn permute(&mut self, order: &[usize]) {
        self.columns_mut()
            .into_iter()
            .for_each(|c| c.permute(order));
    }

    /// Keeps the particles whose `keep` flag is set, in their order.
    pub fn retain(&mut self, keep: &[bool]) {
        self.columns_mut().into_iter().for_each(|c| c.retain(keep));
    }

    /// Appends particle `i`, every column, to a message (see [`Self::read_particle`]).
    pub fn write_particle(&self, i: usize, out: &mut Vec<u8>) {
        self.columns().into_iter().for_each(|c| c.write(i, out));
    }

    /// Appends the next particle of a message written by [`Self::write_particle`] from
    /// particles with the same optional columns.
    pub fn read_particle(&mut self, bytes: &mut &[u8]) {
        self.columns_mut().into_iter().for_each(|c| c.read(bytes));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_column_follows_push_permute_and_retain() {
        let mut p = Particles::<2>::default();
        p.keep_shift_velocity(true);
        for k in 0..4 {
            let v = Vector::<2>::new(k as f64, 0.0);
            p.push(Kind::Fluid, v, v, 1000.0 + k as f64, 1.0);
        }
        p.shift_velocity.as_mut().unwrap()[3] = Vector::<2>::new(3.0, 3.0);
        p.permute(&[3, 2, 1, 0]);
        p.retain(&[true, false, true, false]);
        let shift = p.shift_velocity.as_ref().unwrap();
        assert_eq!(
            (p.id.clone(), p.rho.clone()),
            (vec![3, 1], vec![1003.0, 1001.0])
        );
        assert_eq!(shift, &vec![Vector::<2>::new(3.0, 3.0), Vector::zeros()]);
        assert_eq!(p.columns().iter().filter(|c| c.present()).count(), 9);
    }

    #[test]
    fn an_absent_column_stays_absent() {
        let mut p = Particles::<3>::default();
        p.push(Kind::Wall, Vector::zeros(), Vector::zeros(), 1.0, 1.0);
        p.fit_columns();
        assert!(p.shift_velocity.is_none() && p.empty_like().shift_velocity.is_none());
    }
}
