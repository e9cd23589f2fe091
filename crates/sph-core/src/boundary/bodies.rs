//! Bodies: each `[[tank]]` and `[[wall]]` of a case is a solid whose load the fluid
//! exerts through the wall pair terms.
//!
//! A body's load is minus the wall part of the fluid's momentum equation, summed over
//! the body's wall particles w and their fluid neighbours i:
//!
//! `F_p = Σ_i Σ_w (m_i/ρ_i) (p_w + p_i) ∇_iW_iw V_w`,
//! `F_v = -Σ_i Σ_w (m_i/ρ_i) K π_iw ∇_iW_iw V_w` (no-slip walls only),
//!
//! with the same pair pressure as the fluid sees (tensile control, lone particles: see
//! [`super::walls`]), so that Σ_b (F_p + F_v) = Σ_i m_i (g - du_i/dt) to round-off (the
//! fluid pairs cancel). The moment about a point c is `Σ (x_w - c) × F_iw`; each pair
//! force acts along x_iw, so any point of that line gives the same moment. Bodies are
//! fixed; the type names particles by id, so that moving bodies can keep theirs.

use crate::particles::Vector;
use nalgebra::Vector3;
use std::ops::{Add, Range};

/// A solid of the case: its name and the ids of its wall particles.
#[derive(Debug, Clone, PartialEq)]
pub struct Body {
    pub name: String,
    pub ids: Range<u32>,
}

/// The load of the fluid on one body.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Load<const D: usize> {
    /// Pressure force \[N\] (per unit width in 2D).
    pub pressure: Vector<D>,
    /// Viscous force \[N\] (zero on free-slip walls).
    pub viscous: Vector<D>,
    /// Moment of the whole force about the case's moment point [N m]; in 2D only its z
    /// component is non-zero.
    pub moment: Vector3<f64>,
}

impl<const D: usize> Default for Load<D> {
    fn default() -> Self {
        Self {
            pressure: Vector::zeros(),
            viscous: Vector::zeros(),
            moment: Vector3::zeros(),
        }
    }
}

impl<const D: usize> Add for Load<D> {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self {
            pressure: self.pressure + o.pressure,
            viscous: self.viscous + o.viscous,
            moment: self.moment + o.moment,
        }
    }
}

impl<const D: usize> Load<D> {
    /// Pressure force plus viscous force.
    pub fn force(&self) -> Vector<D> {
        self.pressure + self.viscous
    }

    /// Adds the pair force `pressure + viscous` acting at `arm` from the moment point.
    pub fn add_pair(&mut self, pressure: Vector<D>, viscous: Vector<D>, arm: &Vector<D>) {
        self.pressure += pressure;
        self.viscous += viscous;
        self.moment += lift(arm).cross(&lift(&(pressure + viscous)));
    }
}

/// A D-vector as a 3-vector (zero beyond D).
fn lift<const D: usize>(v: &Vector<D>) -> Vector3<f64> {
    Vector3::from_fn(|d, _| if d < D { v[d] } else { 0.0 })
}

/// Index of the body that holds particle `id`, if any (bodies sorted by id).
pub fn body_of(bodies: &[Body], id: u32) -> Option<usize> {
    let k = bodies.partition_point(|b| b.ids.end <= id);
    (k < bodies.len() && bodies[k].ids.contains(&id)).then_some(k)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bodies_are_found_by_id() {
        let bodies = [
            Body {
                name: "a".into(),
                ids: 10..20,
            },
            Body {
                name: "b".into(),
                ids: 20..25,
            },
        ];
        let found: Vec<Option<usize>> = [0, 9, 10, 19, 20, 24, 25]
            .map(|id| body_of(&bodies, id))
            .to_vec();
        assert_eq!(
            found,
            [None, None, Some(0), Some(0), Some(1), Some(1), None]
        );
    }

    #[test]
    fn the_moment_is_the_cross_product_in_the_plane() {
        let mut load = Load::<2>::default();
        load.add_pair(
            Vector::<2>::new(0.0, 2.0),
            Vector::<2>::new(1.0, 0.0),
            &Vector::<2>::new(3.0, 0.0),
        );
        // (3, 0) × (1, 2) = 6
        assert_eq!(load.moment, Vector3::new(0.0, 0.0, 6.0));
        assert_eq!(load.force(), Vector::<2>::new(1.0, 2.0));
    }
}
