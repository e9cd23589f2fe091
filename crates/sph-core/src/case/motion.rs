//! How a wall region moves: `motion` and its `[<region>.prescribed]` table, shared by
//! `[[tank]]`, `[[wall]]` and `[[shape]]` walls.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// How a wall region moves.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum MotionChoice {
    /// At rest (a tank's lid may still slide in its plane).
    #[default]
    Fixed,
    /// A rigid motion given as functions of time: the table `prescribed` of the region.
    Prescribed,
}

/// A prescribed rigid motion: the region's particles keep their places relative to
/// a reference point (the pivot), which moves by `displacement(t)` while the region
/// turns about it by `rotation(t)`. Every wall particle's velocity `V + Ω×r` and
/// acceleration `A + α×r + Ω×(Ω×r)` follow from the expressions' exact time
/// derivatives and enter the wall model.
#[derive(Debug, Clone, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PrescribedConfig {
    /// Position of the pivot at t = 0 \[m\]. Needed with `rotation`. Default: the
    /// origin.
    #[serde(default)]
    pub pivot: Option<Vec<f64>>,
    /// Displacement of the pivot \[m\], one expression of the time `t` per axis, zero at
    /// t = 0 (the region is built where the case puts it), such as `"0.05*sin(2*PI*t)"`.
    /// Default: none.
    #[serde(default)]
    pub displacement: Option<Vec<String>>,
    /// Rotation about the pivot \[rad\], zero at t = 0: in 2D one expression of `t`, the
    /// angle counter-clockwise; in 3D three, the rotation vector (axis times angle).
    /// Default: none.
    #[serde(default)]
    pub rotation: Option<Vec<String>>,
    /// Ramp time \[s\]: the motion is multiplied by the smooth step
    /// `10τ³ - 15τ⁴ + 6τ⁵`, τ = t/ramp, until `t = ramp`, so that it starts from rest
    /// and its velocity and acceleration have no jump. Default: 0, no ramp.
    #[serde(default)]
    pub ramp: Option<f64>,
    /// A CSV file of the motion instead of `displacement` and `rotation`: a column of
    /// times \[s\] from 0 (or before) to the run's end, then one displacement column
    /// per axis \[m\], then optionally the rotation (2D the angle, 3D the rotation vector,
    /// \[rad\]); comma- or space-separated, `#` comments, an optional header line.
    /// Each column is interpolated by a natural cubic spline (continuous velocity and
    /// acceleration). A relative path is taken from the case file's folder.
    #[serde(default)]
    pub table: Option<String>,
    /// Named values the expressions may use (besides `t`, `PI` and `π`).
    #[serde(default)]
    pub constants: Option<BTreeMap<String, f64>>,
}
