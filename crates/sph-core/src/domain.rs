//! The computational box and its periodic directions.
//!
//! Periodic directions wrap pair distances by the minimum-image convention: positions
//! are kept in the box, so `x_ij` lies within one period and is brought to `|x_ij| <=
//! L/2` by adding or subtracting `L` once (a compare and a subtract, no rounding call in
//! the pair loops). A domain without periodic directions skips it altogether. Along the open (non-periodic)
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
    /// Half the period, infinite where the direction is open.
    half_period: Vector<D>,
    any_periodic: bool,
}

/// A point as `(x, y[, z])` with 5 significant digits, for messages.
pub fn point_text<const D: usize>(x: &Vector<D>) -> String {
    let parts: Vec<String> = x.iter().map(|v| format!("{v:.5}")).collect();
    format!("({})", parts.join(", "))
}

impl<const D: usize> Domain<D> {
    /// The box and its periodic axes, for messages: `(lo) – (hi)`, then
    /// `periodic along x, y` where any are.
    pub fn describe(&self) -> String {
        let mut text = format!("{} – {}", point_text(&self.lo), point_text(&self.hi));
        let periodic: Vec<&str> = (0..D)
            .filter(|&d| self.is_periodic(d))
            .map(|d| ["x", "y", "z"][d])
            .collect();
        if !periodic.is_empty() {
            text.push_str(&format!(", periodic along {}", periodic.join(", ")));
        }
        text
    }

    /// An unbounded domain with no periodic direction.
    pub fn open() -> Self {
        Self {
            lo: Vector::repeat(f64::NEG_INFINITY),
            hi: Vector::repeat(f64::INFINITY),
            period: Vector::zeros(),
            inv_period: Vector::zeros(),
            half_period: Vector::repeat(f64::INFINITY),
            any_periodic: false,
        }
    }

    /// A box `[lo, hi]` periodic along the directions flagged in `periodic`.
    pub fn new(lo: Vector<D>, hi: Vector<D>, periodic: [bool; D]) -> Self {
        let mut period = Vector::zeros();
        let mut inv_period = Vector::zeros();
        let mut half_period = Vector::repeat(f64::INFINITY);
        for d in 0..D {
            if periodic[d] {
                period[d] = hi[d] - lo[d];
                inv_period[d] = 1.0 / period[d];
                half_period[d] = 0.5 * period[d];
            }
        }
        Self {
            lo,
            hi,
            period,
            inv_period,
            half_period,
            any_periodic: periodic.iter().any(|&p| p),
        }
    }

    pub fn is_periodic(&self, d: usize) -> bool {
        self.period[d] > 0.0
    }

    /// `x_i - x_j` by minimum image along periodic directions, for positions within
    /// about one period of each other (those in the box, and moved by less than a
    /// period since they were wrapped).
    #[inline(always)]
    pub fn separation(&self, xi: &Vector<D>, xj: &Vector<D>) -> Vector<D> {
        let mut r = xi - xj;
        if self.any_periodic {
            for d in 0..D {
                let (l, half) = (self.period[d], self.half_period[d]);
                r[d] -= l * ((r[d] > half) as i32 - (r[d] < -half) as i32) as f64;
            }
        }
        r
    }

    /// Whether any direction is periodic.
    pub fn any_periodic(&self) -> bool {
        self.any_periodic
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
