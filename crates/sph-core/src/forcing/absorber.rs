//! Damping zones that absorb waves at a flume's end (the relaxation of velocities
//! used by DualSPHysics, Altomare et al. 2017, Coast. Eng. 127:37, here as a term of
//! the momentum equation so that every integrator advances it):
//!
//! `du_i/dt += -β w(ξ_i) u_i`, `ξ = (x - from)/(to - from)` clamped to [0, 1],
//! `w = 10ξ³ - 15ξ⁴ + 6ξ⁵`,
//!
//! whose weight rises from 0 with zero slope and curvature, so that the zone's start
//! reflects little. A wave crossing the zone loses its velocity at the rate β w.

use crate::case::{AbsorberConfig, Case};
use crate::particles::{Kind, Particles, Vector};
use rayon::prelude::*;

/// One damping zone.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Absorber {
    from: f64,
    to: f64,
    /// β \[1/s\].
    rate: f64,
}

impl Absorber {
    /// The zone of `config` (validated) in `case`.
    pub fn new(case: &Case, config: &AbsorberConfig) -> Self {
        Self {
            from: config.from,
            to: config.to,
            rate: case.absorber_rate(config),
        }
    }

    /// `β w(ξ)` at `x` (the first coordinate).
    pub fn damping(&self, x: f64) -> f64 {
        let xi = ((x - self.from) / (self.to - self.from)).clamp(0.0, 1.0);
        self.rate * xi * xi * xi * (10.0 - 15.0 * xi + 6.0 * xi * xi)
    }

    /// Adds `-β w u` to the rates `du` of the fluid particles.
    pub fn add<const D: usize>(&self, p: &Particles<D>, du: &mut [Vector<D>]) {
        du.par_iter_mut()
            .enumerate()
            .filter(|(i, _)| p.kind[*i] == Kind::Fluid)
            .for_each(|(i, a)| *a -= p.u[i] * self.damping(p.x[i][0]));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The weight is 0 before the zone, 1 at and beyond its end, ½ at its middle, and
    /// rises with zero slope at both ends, toward +x or -x.
    #[test]
    fn the_weight_rises_smoothly_across_the_zone() {
        for (from, to) in [(2.0, 4.0), (4.0, 2.0)] {
            let a = Absorber {
                from,
                to,
                rate: 3.0,
            };
            assert_eq!(a.damping(from - (to - from)), 0.0);
            assert_eq!(a.damping(to + (to - from)), 3.0);
            assert!((a.damping(3.0) - 1.5).abs() < 1e-15);
            let e = 1e-6 * (to - from);
            assert!(a.damping(from + e) < 1e-15 && (3.0 - a.damping(to - e)) < 1e-15);
        }
    }
}
