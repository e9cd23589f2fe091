//! The volume, centroid and inertia of a wall region taken as a homogeneous solid, for
//! free bodies whose case gives a density or leaves out the centre of mass or the
//! inertia, and the draft at which such a body floats.
//!
//! One quadrature serves every geometry (boxes, circles, polygons, STL, SVG, DXF): a
//! grid of cubic cells of side `s` over the bounding box, each weighted by the part
//! of it inside the solid, estimated from the signed distance `φ` at its centre as
//! `clamp(1/2 - φ/s, 0, 1)` (exact for a face along the grid, second order for a
//! smooth surface), and each cell counted with its own inertia (`s²/6` per unit mass
//! about its centre in 3D, `s²/12` per in-plane axis in 2D). The sums give
//! `V = Σ w s^D`, `c = Σ w s^D x / V` and `I = Σ w s^D (|r|² 1 - r rᵀ)` about `c`, per
//! unit density.

use super::free::MassGuess;
use crate::geometry::solid::Solid;
use nalgebra::{Matrix3, Vector3};
use rayon::prelude::*;

type V3 = Vector3<f64>;

/// Cells along the longest side of the bounding box, by dimension: with the measured
/// error for a disc and a sphere (see the tests) below 1e-4 and 1e-3 of the volume.
const CELLS_2D: usize = 400;
const CELLS_3D: usize = 64;

/// A homogeneous solid's volume (2D: area) and inertia per unit density, and what
/// finds its draft.
pub struct Solidity {
    pub volume: f64,
    pub centroid: V3,
    /// About the centroid, per unit density.
    pub inertia: Matrix3<f64>,
    /// Each cell's height along `up` and the volume it holds.
    cells: Vec<(f64, f64)>,
    /// Cell side.
    side: f64,
    /// The height of the solid's lowest point along `up`.
    lowest: f64,
}

/// The geometry of a wall region: a box `[lo, hi]` or a solid of `[[shape]]`.
pub enum Region<'a> {
    Box(&'a [f64], &'a [f64]),
    Solid(&'a Solid),
}

impl Region<'_> {
    fn bounds(&self) -> (Vec<f64>, Vec<f64>) {
        match self {
            Region::Box(lo, hi) => (lo.to_vec(), hi.to_vec()),
            Region::Solid(s) => (s.lo.clone(), s.hi.clone()),
        }
    }

    /// The signed distance to the region's surface, negative inside.
    fn distance(&self, x: &[f64]) -> f64 {
        match self {
            Region::Box(lo, hi) => {
                let q: Vec<f64> = (0..lo.len())
                    .map(|d| (x[d] - 0.5 * (lo[d] + hi[d])).abs() - 0.5 * (hi[d] - lo[d]))
                    .collect();
                let outside = q.iter().map(|v| v.max(0.0).powi(2)).sum::<f64>().sqrt();
                outside + q.iter().copied().fold(f64::MIN, f64::max).min(0.0)
            }
            Region::Solid(s) => s.signed_distance(x),
        }
    }
}

impl Solidity {
    /// The quadrature of the module documentation over `region` of dimension `dim`,
    /// heights measured along the unit vector `up`.
    pub fn of(region: &Region, dim: usize, up: &V3) -> Self {
        let (lo, hi) = region.bounds();
        let longest = (0..dim).map(|d| hi[d] - lo[d]).fold(0.0, f64::max);
        let side = longest / if dim == 2 { CELLS_2D } else { CELLS_3D } as f64;
        let counts: Vec<usize> = (0..dim)
            .map(|d| (((hi[d] - lo[d]) / side).ceil() as usize).max(1))
            .collect();
        let total: usize = counts.iter().product();
        let cell = side.powi(dim as i32);
        let samples: Vec<(V3, f64)> = (0..total)
            .into_par_iter()
            .filter_map(|mut k| {
                let mut x = V3::zeros();
                for d in 0..dim {
                    x[d] = lo[d] + side * ((k % counts[d]) as f64 + 0.5);
                    k /= counts[d];
                }
                let w = (0.5 - region.distance(&x.as_slice()[..dim]) / side).clamp(0.0, 1.0);
                (w > 0.0).then_some((x, w * cell))
            })
            .collect();
        let volume: f64 = samples.iter().map(|(_, v)| v).sum();
        let centroid = samples.iter().map(|(x, v)| x * *v).sum::<V3>() / volume;
        let own = if dim == 2 {
            V3::new(1.0, 1.0, 2.0) * (side * side / 12.0)
        } else {
            V3::repeat(side * side / 6.0)
        };
        let inertia = (samples.iter())
            .map(|(x, v)| {
                let r = x - centroid;
                (Matrix3::identity() * r.norm_squared() - r * r.transpose()
                    + Matrix3::from_diagonal(&own))
                    * *v
            })
            .sum();
        let corners = (0..1usize << dim).map(|c| {
            (0..dim)
                .map(|d| up[d] * if c >> d & 1 == 0 { lo[d] } else { hi[d] })
                .sum::<f64>()
        });
        Self {
            volume,
            centroid,
            inertia,
            cells: samples.iter().map(|(x, v)| (up.dot(x), *v)).collect(),
            side,
            lowest: corners.fold(f64::MAX, f64::min),
        }
    }

    /// The mass properties of the solid with `density` throughout.
    pub fn guess(&self, density: f64) -> MassGuess {
        MassGuess {
            mass: density * self.volume,
            centre_of_mass: self.centroid,
            inertia: self.inertia * density,
        }
    }

    /// How deep a body of this shape and mass `mass` floats upright in fluid of
    /// density `rho0` (the draft below its lowest point, where `ρ0 V_below = m`),
    /// or `None` when it is denser than the fluid and sinks. Each cell's volume is
    /// spread over its height.
    pub fn draft(&self, mass: f64, rho0: f64) -> Option<f64> {
        let target = mass / rho0;
        if target >= self.volume {
            return None;
        }
        let below = |level: f64| -> f64 {
            (self.cells.iter())
                .map(|(h, v)| v * ((level - h) / self.side + 0.5).clamp(0.0, 1.0))
                .sum()
        };
        let (mut a, mut b) = (
            self.lowest,
            self.cells.iter().map(|c| c.0).fold(f64::MIN, f64::max) + self.side,
        );
        for _ in 0..60 {
            let mid = 0.5 * (a + b);
            if below(mid) < target {
                a = mid;
            } else {
                b = mid;
            }
        }
        Some(0.5 * (a + b) - self.lowest)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::case::Case;

    #[test]
    fn a_box_is_exact_and_floats_at_its_archimedes_draft() {
        let (lo, hi) = ([0.1, 0.2], [0.5, 0.3]);
        let s = Solidity::of(&Region::Box(&lo, &hi), 2, &V3::y());
        let (v, w, h) = (0.04, 0.4, 0.1);
        assert!((s.volume / v - 1.0).abs() < 1e-12, "{}", s.volume);
        assert!((s.centroid - V3::new(0.3, 0.25, 0.0)).norm() < 1e-12);
        // polar moment of a rectangle about its centre: A (w² + h²)/12
        assert!((s.inertia[(2, 2)] - v * (w * w + h * h) / 12.0).abs() < 1e-12 * v);
        // half the fluid's density: half the height under water
        let draft = s.draft(0.5 * 1000.0 * v, 1000.0).unwrap();
        assert!((draft - 0.05).abs() < 1e-9, "{draft}");
        assert!(s.draft(1.1 * 1000.0 * v, 1000.0).is_none());
    }

    /// The case with one wall shape, built to its solid.
    fn solid(dimension: usize, shape: &str) -> Solid {
        let (lo, hi) = match dimension {
            2 => ("2.0, 2.0", "2.1, 2.1"),
            _ => ("2.0, 2.0, 2.0", "2.1, 2.1, 2.1"),
        };
        let text = format!(
            "dimension = {dimension}\n[particles]\nspacing = 0.01\n[fluid]\ndensity = 1000.0\n\
             [time]\nend = 1.0\n[[fluid_block]]\nlo = [{lo}]\nhi = [{hi}]\n[[shape]]\nrole = \"wall\"\n{shape}\n"
        );
        let case = Case::from_toml_str(&text).unwrap();
        crate::geometry::solid::build(&case, 0).unwrap()
    }

    #[test]
    fn a_disc_and_a_sphere_come_within_the_stated_errors() {
        use std::f64::consts::PI;
        let disc = solid(2, "circle = { centre = [1.0, 2.0], radius = 0.5 }");
        let s = Solidity::of(&Region::Solid(&disc), 2, &V3::y());
        let area = PI * 0.25;
        assert!(
            (s.volume / area - 1.0).abs() < 1e-4,
            "{}",
            s.volume / area - 1.0
        );
        assert!((s.centroid - V3::new(1.0, 2.0, 0.0)).norm() < 1e-6);
        let polar = area * 0.25 / 2.0;
        assert!((s.inertia[(2, 2)] / polar - 1.0).abs() < 1e-4);
        let ball = solid(3, "sphere = { centre = [0.0, 0.0, 0.0], radius = 0.5 }");
        let s = Solidity::of(&Region::Solid(&ball), 3, &V3::z());
        let volume = 4.0 / 3.0 * PI * 0.125;
        assert!(
            (s.volume / volume - 1.0).abs() < 1e-3,
            "{}",
            s.volume / volume - 1.0
        );
        let i = 0.4 * volume * 0.25;
        assert!((s.inertia[(0, 0)] / i - 1.0).abs() < 2e-3);
        // a sphere of half the fluid's density floats half immersed
        let draft = s.draft(0.5 * volume, 1.0).unwrap();
        assert!((draft - 0.5).abs() < 2e-3, "{draft}");
    }
}
