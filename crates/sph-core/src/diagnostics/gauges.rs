//! Wave gauges: the free-surface elevation on a vertical line, where the fluid's
//! kernel sum `Γ(z) = Σ_f W(x - x_f) V_f` falls through ½ (Γ is 1 inside the fluid and
//! ½ on a flat free surface's plane, where half the kernel's support is wet).
//!
//! Γ is sampled every Δx/4 from the line's top down; the first sample at or above ½
//! and the one above it bound the crossing, placed by linear interpolation. A line
//! with no sample at ½ is dry: the gauge reads its bottom.

use crate::case::{Case, GaugeConfig};
use crate::error::{Result, SphError};
use crate::particles::Vector;

/// One gauge's line.
#[derive(Debug, Clone)]
pub struct Gauge<const D: usize> {
    pub name: String,
    /// The samples, from the bottom up.
    pub points: Vec<Vector<D>>,
    /// The level elevations are measured from.
    still_level: f64,
}

impl<const D: usize> Gauge<D> {
    /// The gauge of `config` (validated) in `case`.
    pub fn new(case: &Case, config: &GaugeConfig) -> Self {
        let [bottom, top] = case.gauge_line(config).unwrap_or([0.0, 0.0]);
        let n = ((top - bottom) / (0.25 * case.dx())).ceil().max(1.0) as usize;
        let dz = (top - bottom) / n as f64;
        let points = (0..=n)
            .map(|k| {
                let z = bottom + k as f64 * dz;
                Vector::from_fn(|d, _| if d + 1 == D { z } else { config.position[d] })
            })
            .collect();
        Self {
            name: config.name.clone(),
            points,
            still_level: case.diagnostics.still_level.unwrap_or(0.0),
        }
    }

    /// A gauge on the vertical line at `position` (x in 2D, (x, y) in 3D), spanning the
    /// case's `[domain]` or `[[tank]]` height; refused, naming `key`, where the position
    /// is not D - 1 finite coordinates or the case gives no vertical extent.
    pub fn at(case: &Case, position: &[f64], key: &str) -> Result<Self> {
        let config = GaugeConfig {
            name: key.to_string(),
            position: position.to_vec(),
            bottom: None,
            top: None,
        };
        let finite = position.iter().all(|v| v.is_finite());
        if position.len() + 1 != D || !finite || case.gauge_line(&config).is_none() {
            return Err(SphError::invalid(
                key,
                format!("{position:?}"),
                format!(
                    "{} coordinate(s) of a vertical line within a [domain] or [[tank]]",
                    D - 1
                ),
            ));
        }
        Ok(Self::new(case, &config))
    }

    /// The elevation above the still level from Γ at [`Self::points`].
    pub fn elevation(&self, gamma: &[f64]) -> f64 {
        let z = |k: usize| self.points[k][D - 1];
        let surface = match gamma.iter().rposition(|&g| g >= 0.5) {
            None => z(0),
            Some(k) if k + 1 == gamma.len() => z(k),
            Some(k) => {
                let s = (gamma[k] - 0.5) / (gamma[k] - gamma[k + 1]);
                z(k) + s * (z(k + 1) - z(k))
            }
        };
        surface - self.still_level
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A crossing between two samples is placed by linear interpolation; a line wet to
    /// its top reads its top, a dry one its bottom; a droplet's Γ below ½ is ignored.
    #[test]
    fn the_crossing_is_interpolated_and_dry_lines_read_their_bottom() {
        let gauge = Gauge::<2> {
            name: "g".into(),
            points: (0..5)
                .map(|k| Vector::<2>::new(1.0, 0.1 * k as f64))
                .collect(),
            still_level: 0.15,
        };
        let e = gauge.elevation(&[1.0, 1.0, 0.7, 0.2, 0.3]);
        assert!((e - (0.2 + 0.1 * 0.4 - 0.15)).abs() < 1e-12, "{e}");
        assert!((gauge.elevation(&[1.0; 5]) - 0.25).abs() < 1e-12);
        assert!((gauge.elevation(&[0.0; 5]) + 0.15).abs() < 1e-12);
    }
}
