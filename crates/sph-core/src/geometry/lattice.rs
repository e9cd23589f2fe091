//! Particles on the lattice `lo + (k + ½)Δx`: fluid blocks (whole boxes, or the
//! ellipses inscribed in them) and the layers of dummy particles of tanks and wall
//! boxes.

use super::vector;
use crate::case::{Case, FluidBlockConfig, Shape};
use crate::particles::Vector;

/// Lattice points `lo + (k + ½)Δx` filling `[lo, hi]`, with the count per axis rounded.
pub(super) fn lattice<const D: usize>(lo: &Vector<D>, hi: &Vector<D>, dx: f64) -> Vec<Vector<D>> {
    let n: Vec<usize> = (0..D)
        .map(|d| ((hi[d] - lo[d]) / dx).round().max(0.0) as usize)
        .collect();
    let total: usize = n.iter().product();
    (0..total)
        .map(|mut k| {
            let mut x = *lo;
            for d in 0..D {
                x[d] += ((k % n[d]) as f64 + 0.5) * dx;
                k /= n[d];
            }
            x
        })
        .collect()
}

/// The lattice points of a fluid block: the whole box, or those inside the inscribed
/// ellipse (ellipsoid).
pub(super) fn block_points<const D: usize>(b: &FluidBlockConfig, dx: f64) -> Vec<Vector<D>> {
    let (lo, hi): (Vector<D>, Vector<D>) = (vector(&b.lo), vector(&b.hi));
    let mut points = lattice(&lo, &hi, dx);
    if b.shape == Some(Shape::Ellipsoid) {
        let (centre, half) = ((lo + hi) / 2.0, (hi - lo) / 2.0);
        points.retain(|x| (x - centre).component_div(&half).norm_squared() < 1.0);
    }
    points
}

pub(super) fn corners<const D: usize>(lo: &Vector<D>, hi: &Vector<D>) -> Vec<Vector<D>> {
    (0..1usize << D)
        .map(|m| Vector::from_fn(|d, _| if m >> d & 1 == 1 { hi[d] } else { lo[d] }))
        .collect()
}

/// Wall particles with their (fixed or sliding-lid) velocities, one list per body:
/// the tanks, then the wall boxes, in case order.
pub(super) fn wall_points<const D: usize>(case: &Case) -> Vec<Vec<(Vector<D>, Vector<D>)>> {
    let dx = case.dx();
    let mut bodies = Vec::new();
    for t in &case.tank {
        let (lo, hi): (Vector<D>, Vector<D>) = (vector(&t.lo), vector(&t.hi));
        let pad = Vector::<D>::repeat(t.layer_count(case) as f64 * dx);
        let open = t.open_faces(D);
        let lid: Vector<D> = t
            .lid_velocity
            .as_deref()
            .map(vector)
            .unwrap_or_else(Vector::zeros);
        bodies.push(
            lattice(&(lo - pad), &(hi + pad), dx)
                .into_iter()
                .filter(|x| {
                    let outside = (0..D).any(|d| x[d] < lo[d] || x[d] > hi[d]);
                    let beyond_open =
                        open.iter()
                            .any(|&(d, s)| if s > 0 { x[d] > hi[d] } else { x[d] < lo[d] });
                    outside && !beyond_open
                })
                .map(|x| {
                    let above = x[D - 1] > hi[D - 1];
                    (x, if above { lid } else { Vector::zeros() })
                })
                .collect(),
        );
    }
    for b in &case.wall {
        let box_points = lattice(&vector(&b.lo), &vector(&b.hi), dx);
        bodies.push(
            box_points
                .into_iter()
                .map(|x| (x, Vector::zeros()))
                .collect(),
        );
    }
    bodies
}
