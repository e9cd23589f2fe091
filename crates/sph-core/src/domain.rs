//! The computational box and its periodic directions.
//!
//! Periodic directions wrap pair distances by the minimum-image convention:
//! `x_ij ← x_ij - L round(x_ij / L)`. Non-periodic directions carry `L = 0`, so
//! the same branch-free expression leaves them untouched. Along the open (non-periodic)
//! directions the box bounds the flow: a fluid particle beyond it has left the flow
//! ([`Domain::escaped`]) and is removed from the run.

use crate::particles::Vector;

#[derive(Debug, Clone, Copy)]
pub struct Domain<const D: usize> {
    /// Lower corner of the box.
    pub lo: Vector<D>,
    /// Upper corner of the box.
    pub hi: Vector<D>,
    /// Period along each direction, 0 where the direction is open.
    pub period: Vector<D>,
    inv_period: Vector<D>,
}

impl<const D: usize> Domain<D> {
    /// An unbounded domain with no periodic direction.
    pub fn open() -> Self {
        Self {
            lo: Vector::repeat(f64::NEG_INFINITY),
            hi: Vector::repeat(f64::INFINITY),
            period: Vector::zeros(),
            inv_period: Vector::zeros(),
        }
    }

    /// A box `[lo, hi]` periodic along the directions flagged in `periodic`.
    pub fn new(lo: Vector<D>, hi: Vector<D>, periodic: [bool; D]) -> Self {
        let mut period = Vector::zeros();
        let mut inv_period = Vector::zeros();
        for d in 0..D {
            if periodic[d] {
                period[d] = hi[d] - lo[d];
                inv_period[d] = 1.0 / period[d];
            }
        }
        Self {
            lo,
            hi,
            period,
            inv_period,
        }
    }

    pub fn is_periodic(&self, d: usize) -> bool {
        self.period[d] > 0.0
    }

    /// `x_i - x_j` by minimum image along periodic directions.
    #[inline(always)]
    pub fn separation(&self, xi: &Vector<D>, xj: &Vector<D>) -> Vector<D> {
        let mut r = xi - xj;
        for d in 0..D {
            r[d] -= self.period[d] * (r[d] * self.inv_period[d]).round();
        }
        r
    }

    /// Whether `x` lies beyond the box along an open direction (false for a
    /// non-finite coordinate, which is the stability guard's to report).
    pub fn escaped(&self, x: &Vector<D>) -> bool {
        (0..D).any(|d| self.period[d] == 0.0 && (x[d] < self.lo[d] || x[d] > self.hi[d]))
    }

    /// Brings a position back into the periodic box.
    pub fn wrap(&self, x: &mut Vector<D>) {
        for d in 0..D {
            if self.period[d] > 0.0 {
                let s = x[d] - self.lo[d];
                x[d] = self.lo[d] + s - self.period[d] * (s * self.inv_period[d]).floor();
            }
        }
    }
}
