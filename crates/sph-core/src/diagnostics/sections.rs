//! Flow sections: the volume and mass flow through a segment (2D) or a parallelogram
//! (3D), `Q = ∫_S q(x) dA` with the flow densities `q` of [`super::PointReader::flow_density`],
//! integrated by the midpoint rule on points no further than Δx/2 apart (the densities
//! vary over the kernel's support, 2h ≥ 2.7Δx).

use crate::case::SectionConfig;
use crate::particles::Vector;

/// One section's sample points and normal.
#[derive(Debug, Clone)]
pub struct Section<const D: usize> {
    pub name: String,
    /// The midpoints the flow densities are read at.
    pub points: Vec<Vector<D>>,
    /// The unit normal flow is counted along.
    pub normal: Vector<D>,
    /// The area (2D: length) each point stands for.
    pub weight: f64,
}

impl<const D: usize> Section<D> {
    /// The section of `config` (validated) for particle spacing `dx`.
    pub fn new(config: &SectionConfig, dx: f64) -> Self {
        let origin = Vector::<D>::from_column_slice(&config.corners[0]);
        let sides: Vec<Vector<D>> = (config.sides().iter())
            .map(|s| Vector::from_column_slice(s))
            .collect();
        let scaled_normal = if D == 2 {
            Vector::<D>::from_fn(|d, _| [sides[0][1], -sides[0][0]][d])
        } else {
            let (a, b) = (&sides[0], &sides[1]);
            Vector::<D>::from_fn(|d, _| {
                let (i, j) = ((d + 1) % 3, (d + 2) % 3);
                a[i] * b[j] - a[j] * b[i]
            })
        };
        let counts = config.samples(dx);
        let total: usize = counts.iter().product();
        let points = (0..total)
            .map(|mut flat| {
                let mut x = origin;
                for (side, &m) in sides.iter().zip(&counts) {
                    let k = flat % m;
                    flat /= m;
                    x += side * ((k as f64 + 0.5) / m as f64);
                }
                x
            })
            .collect();
        Self {
            name: config.name.clone(),
            points,
            normal: scaled_normal.normalize(),
            weight: scaled_normal.norm() / total as f64,
        }
    }

    /// `[volume, mass]` flow from the flow densities at [`Self::points`].
    pub fn flow(&self, densities: &[[f64; 2]]) -> [f64; 2] {
        let sum = densities
            .iter()
            .fold([0.0; 2], |[v, m], [dv, dm]| [v + dv, m + dm]);
        sum.map(|s| s * self.weight)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn config(corners: &[&[f64]]) -> SectionConfig {
        SectionConfig {
            name: "s".into(),
            corners: corners.iter().map(|c| c.to_vec()).collect(),
        }
    }

    /// A segment drawn upwards counts flow in +x; its midpoints are Δx/2 apart at most
    /// and stand for its whole length.
    #[test]
    fn a_segment_is_sampled_along_its_length_with_the_right_hand_normal() {
        let s = Section::<2>::new(&config(&[&[1.0, 0.0], &[1.0, 0.3]]), 0.02);
        assert_eq!(s.points.len(), 30);
        assert!((s.normal - Vector::<2>::new(1.0, 0.0)).norm() < 1e-15);
        assert!((s.weight * 30.0 - 0.3).abs() < 1e-15);
        assert!((s.points[0][1] - 0.005).abs() < 1e-15 && (s.points[29][1] - 0.295).abs() < 1e-12);
        // a uniform density q integrates to q × length
        let [v, m] = s.flow(&vec![[2.0, 2000.0]; 30]);
        assert!((v - 0.6).abs() < 1e-12 && (m - 600.0).abs() < 1e-9);
    }

    /// A parallelogram's normal is `(c1 - c0) × (c2 - c0)`, and its points stand for its
    /// area `|(c1 - c0) × (c2 - c0)|`.
    #[test]
    fn a_parallelogram_is_sampled_over_its_area() {
        let s = Section::<3>::new(
            &config(&[&[0.5, 0.0, 0.0], &[0.5, 0.2, 0.0], &[0.5, 0.1, 0.1]]),
            0.05,
        );
        assert_eq!(s.points.len(), 8 * 6);
        assert!((s.normal - Vector::<3>::new(1.0, 0.0, 0.0)).norm() < 1e-15);
        assert!((s.weight * 48.0 - 0.02).abs() < 1e-15);
        let centroid = s.points.iter().sum::<Vector<3>>() / 48.0;
        assert!((centroid - Vector::<3>::new(0.5, 0.15, 0.05)).norm() < 1e-12);
    }
}
