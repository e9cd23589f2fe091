//! The `[diagnostics]` table: what the time series records (energies and their budget,
//! probes, sensors, loads, the surge front) and the free surface in snapshots.

use super::checks::components;
use super::Case;
use crate::error::{Result, SphError};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

#[derive(Debug, Clone, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DiagnosticsConfig {
    /// Interval of the time series (energies, probes, front) \[s\]. Default:
    /// output_interval/10, or a 200th of the run without snapshots.
    #[serde(default)]
    pub interval: Option<f64>,
    /// Write the kinetic, potential and compressive energies E_k, E_p, E_c, their sum
    /// and max |Δρ/ρ0|.
    #[serde(default)]
    pub energy: bool,
    /// Also integrate the viscous, diffusive and wall powers (docs/theory.md §10), computed in
    /// the first evaluation of each step; with moving bodies the moving walls' power and
    /// work, with free bodies their power and energy, with a body force or absorbers
    /// their power and work.
    #[serde(default)]
    pub energy_budget: bool,
    /// Points of Shepard-interpolated pressure, inside the domain and not buried in a
    /// wall: columns `probe<k>_pressure`, NaN while no fluid is within the kernel support
    /// of the point.
    #[serde(default)]
    pub probes: Vec<Vec<f64>>,
    /// Also write each probe's Shepard-interpolated fluid velocity: columns
    /// `probe<k>_u`, `_v` (`_w`), NaN while no fluid is within the kernel support.
    #[serde(default)]
    pub probe_velocity: bool,
    /// Track the surge front: the largest fluid coordinate along this axis (0 = x).
    #[serde(default)]
    pub surge_front_axis: Option<usize>,
    /// Detect the free surface (Marrone et al. 2010) at each snapshot and write the
    /// flag, the normal and λ with it.
    #[serde(default)]
    pub free_surface: bool,
    /// Write each body's load (every tank, wall and wall shape): columns
    /// `<name>_pressure_fx …`, `<name>_viscous_fx …`, `<name>_moment_z` (3D: `_moment_x
    /// _y _z`) about `moment_point`. They are minus the wall terms of the fluid's momentum
    /// equation, so the loads sum to Σ m_i (g - du_i/dt) to round-off.
    #[serde(default)]
    pub loads: bool,
    /// The point moments are taken about. Default: the origin.
    #[serde(default)]
    pub moment_point: Option<Vec<f64>>,
    /// Reference scales of the force coefficients: with `loads`, each body's total
    /// force also as `<name>_cx …` = `F / (½ ρ U² A)`, `A = L` per unit width in 2D, `L²`
    /// in 3D.
    #[serde(default)]
    pub reference: Option<ReferenceConfig>,
    /// Pressure sensors as built: faces on a wall, averaged over their area and
    /// optionally low-pass filtered.
    #[serde(default)]
    pub sensors: Vec<SensorConfig>,
    /// Wave gauges: the free-surface elevation on vertical lines (see [`GaugeConfig`]).
    #[serde(default)]
    pub gauges: Vec<GaugeConfig>,
    /// Flow sections: the volume and mass flow through a segment (2D) or a
    /// parallelogram (3D) (see [`SectionConfig`]).
    #[serde(default)]
    pub sections: Vec<SectionConfig>,
    /// The still-water level \[m\] the gauges' elevations are measured from (vertical:
    /// y in 2D, z in 3D). Default: 0 (elevations are heights).
    #[serde(default)]
    pub still_level: Option<f64>,
}

/// The most samples on a gauge's line (Δx/4 apart).
pub const MAX_GAUGE_SAMPLES: usize = 100_000;

/// A wave gauge: column `<name>_elevation`, the height above `still_level` where the
/// fluid's kernel sum `Γ(z) = Σ_f W(x - x_f) V_f` falls through ½ on the vertical line
/// at `position`, searched from the top (Γ sampled every Δx/4, crossing interpolated
/// linearly). A dry gauge reads its `bottom`.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct GaugeConfig {
    /// Heads the column.
    pub name: String,
    /// Where the gauge stands \[m\]: x in 2D, (x, y) in 3D.
    pub position: Vec<f64>,
    /// Lowest point of the line \[m\]. Default: the domain's or the tanks' bottom.
    #[serde(default)]
    pub bottom: Option<f64>,
    /// Highest point of the line \[m\]. Default: the domain's or the tanks' top.
    #[serde(default)]
    pub top: Option<f64>,
}

/// The most sample points on a flow section (Δx/2 apart).
pub const MAX_SECTION_SAMPLES: usize = 1_000_000;

/// A flow section: columns `<name>_volume_flow` \[m³/s; m²/s per unit width in 2D\] and
/// `<name>_mass_flow` \[kg/s; kg/(s·m) in 2D\], the fluid's flow through the segment
/// from `corners[0]` to `corners[1]` (2D), or through the parallelogram at `corners[0]`
/// with sides to `corners[1]` and `corners[2]` (3D), counted positive along the normal:
/// to the right of the segment's direction (a segment drawn upwards counts flow in +x),
/// `(c1 - c0) × (c2 - c0)` in 3D. The flow densities `Σ_f (u_f·n) W V_f / (1 - Γ_w)`
/// and `Σ_f (u_f·n) W m_f / (1 - Γ_w)` (`Γ_w` the walls' kernel sum; zero inside a
/// wall, where `Γ_w >= ½`) are integrated over the section by the midpoint rule on
/// points Δx/2 apart: a section may reach into the air and into walls.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SectionConfig {
    /// Heads the columns.
    pub name: String,
    /// The corners \[m\]: two in 2D, three in 3D.
    pub corners: Vec<Vec<f64>>,
}

impl SectionConfig {
    /// The sides from the first corner to the others.
    pub fn sides(&self) -> Vec<Vec<f64>> {
        let origin = &self.corners[0];
        (self.corners[1..].iter())
            .map(|c| c.iter().zip(origin).map(|(a, b)| a - b).collect())
            .collect()
    }

    /// The sample points along each side: no further than Δx/2 apart.
    pub fn samples(&self, dx: f64) -> Vec<usize> {
        (self.sides().iter())
            .map(|side| {
                let length = side.iter().map(|c| c * c).sum::<f64>().sqrt();
                (length / (0.5 * dx)).ceil().max(1.0) as usize
            })
            .collect()
    }

    /// A section has D corners of D finite coordinates, spanning a segment (2D) or a
    /// parallelogram (3D) of non-zero size, sampled on at most [`MAX_SECTION_SAMPLES`]
    /// points; refused under `key`.
    pub fn check(&self, key: &str, dimension: usize, dx: f64) -> Result<()> {
        let shape = if dimension == 2 {
            "a segment"
        } else {
            "a parallelogram"
        };
        let refuse = |why: String| SphError::invalid(key, format!("{:?}", self.corners), why);
        if self.corners.len() != dimension {
            return Err(refuse(format!("{dimension} corners, spanning {shape}")));
        }
        for c in &self.corners {
            components(key, c, dimension)?;
        }
        let sides = self.sides();
        let flat = if dimension == 2 {
            sides[0].iter().all(|&c| c == 0.0)
        } else {
            let (a, b) = (&sides[0], &sides[1]);
            let cross = [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ];
            cross.iter().all(|&c| c == 0.0)
        };
        if flat {
            return Err(refuse(format!("corners spanning {shape} of non-zero size")));
        }
        let points = self
            .samples(dx)
            .iter()
            .try_fold(1usize, |n, &m| n.checked_mul(m));
        if points.is_none_or(|n| n > MAX_SECTION_SAMPLES) {
            return Err(refuse(format!(
                "{shape} sampled on at most {MAX_SECTION_SAMPLES} points Δx/2 apart"
            )));
        }
        Ok(())
    }
}

/// The scales of the force coefficients.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ReferenceConfig {
    /// U [m/s].
    pub velocity: f64,
    /// L \[m\].
    pub length: f64,
    /// ρ [kg/m³]. Default: the fluid's ρ0.
    #[serde(default)]
    pub density: Option<f64>,
}

/// A face sensor (a segment in 2D, a disc or rectangle in 3D): columns
/// `<name>_pressure` (the face average), `<name>_point` (the point value at its centre)
/// and, with a cut-off, `<name>_filtered`.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SensorConfig {
    /// Heads the sensor's columns: `<name>_pressure` (the probe pressure averaged over
    /// the face, on points at most Δx/4 apart, 5-64 across; where the face is dry it
    /// reads zero gauge pressure, as a transducer in air does) and `<name>_point` (the
    /// value at its centre).
    pub name: String,
    /// Centre of the face, on the wall \[m\].
    pub centre: Vec<f64>,
    /// Normal of the face (either sense).
    pub normal: Vec<f64>,
    /// Size of the face \[m\]: the length of the segment (2D), the diameter of the disc
    /// (3D), or the rectangle's side along `along` (3D, with `width`).
    pub size: f64,
    /// 3D: makes the face a rectangle, `size` long along `along` and `width` \[m\] across
    /// it. Default: a disc.
    #[serde(default)]
    pub width: Option<f64>,
    /// 3D rectangles: the direction of their `size` side (projected into the face's
    /// plane). Default: required with `width`.
    #[serde(default)]
    pub along: Option<Vec<f64>>,
    /// Cut-off frequency \[Hz\] of a second-order Butterworth low-pass filter on the face
    /// average, run at the series interval (below its Nyquist frequency): column
    /// `<name>_filtered`; its state is kept in restart files. Default: none.
    #[serde(default)]
    pub cutoff: Option<f64>,
}

impl Case {
    /// The vertical extent `[bottom, top]` of a gauge's line: its own, else the
    /// domain's, else the tanks' (`None` where none gives it).
    pub fn gauge_line(&self, gauge: &GaugeConfig) -> Option<[f64; 2]> {
        let v = self.dimension - 1;
        let (mut lo, mut hi) = match &self.domain {
            Some(d) => (d.lo.get(v).copied(), d.hi.get(v).copied()),
            None => (None, None),
        };
        if !self.tank.is_empty() {
            let low = self.tank.iter().filter_map(|t| t.lo.get(v).copied());
            let high = self.tank.iter().filter_map(|t| t.hi.get(v).copied());
            lo = lo.or(low.reduce(f64::min));
            hi = hi.or(high.reduce(f64::max));
        }
        Some([gauge.bottom.or(lo)?, gauge.top.or(hi)?])
    }
}
