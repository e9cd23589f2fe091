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
    /// A rigid body moved by the fluid's load, gravity and its springs: the table
    /// `free` of the region (walls and wall shapes).
    Free,
}

/// How one wall region moves, as the case gives it.
#[derive(Debug, Clone)]
pub struct BodyMotion<'a> {
    /// The case key of the region: `tank[0]`, `wall[1]`, `shape[2]`.
    pub key: String,
    /// Its index in its table (`case.tank`, `case.wall` or `case.shape`).
    pub index: usize,
    pub motion: MotionChoice,
    pub prescribed: Option<&'a PrescribedConfig>,
    pub free: Option<&'a FreeConfig>,
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

/// A free (floating) rigid body: its mass properties, constraints, initial velocity
/// and springs. The fluid's force and moment on it are the wall pair terms that act on
/// the fluid, reversed (see `loads`); it advances within every stage of the fluid's
/// integrator. Mass properties not given follow from the region's geometry taken as
/// homogeneous: `mass` or `density` sets the scale, the centroid is the centre of mass.
#[derive(Debug, Clone, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FreeConfig {
    /// Mass \[kg\] (2D: per unit depth, kg/m). Give `mass` or `density`.
    #[serde(default)]
    pub mass: Option<f64>,
    /// Density of the homogeneous body \[kg/m³\]: its mass is this times the region's
    /// volume (2D: area). Give `mass` or `density`.
    #[serde(default)]
    pub density: Option<f64>,
    /// Centre of mass at t = 0 \[m\]. Default: the centroid of the region.
    #[serde(default)]
    pub centre_of_mass: Option<Vec<f64>>,
    /// Moment of inertia about the centre of mass \[kg m²\] (2D: per unit depth,
    /// kg m): in 2D one value, about z; in 3D three (about x, y, z, principal axes along
    /// them) or six (`Ixx, Iyy, Izz, Ixy, Ixz, Iyz`). Default: that of the homogeneous
    /// region of the same mass.
    #[serde(default)]
    pub inertia: Option<Vec<f64>>,
    /// A fixed point the body turns about (a hinge) \[m\]: its translation is locked and
    /// it rotates about this point under the moments of the fluid, gravity and
    /// springs. Default: none, the centre of mass moves freely.
    #[serde(default)]
    pub hinge: Option<Vec<f64>>,
    /// Degrees of freedom held fixed: "x", "y", "z" (translation of the centre of mass
    /// along the axis), "rx", "ry", "rz" (rotation about the axis; 2D has only "rz").
    /// Such as `["x", "rz"]` for heave only in 2D. Default: none locked.
    #[serde(default)]
    pub locked: Option<Vec<String>>,
    /// Velocity of the centre of mass (or hinge: zero) at t = 0 \[m/s\]. Default: at
    /// rest.
    #[serde(default)]
    pub velocity: Option<Vec<f64>>,
    /// Angular velocity at t = 0 \[rad/s\]: in 2D one value (about z), in 3D three.
    /// Default: none.
    #[serde(default)]
    pub angular_velocity: Option<Vec<f64>>,
    /// Linear springs with dampers from points of the body to fixed anchors (moorings).
    #[serde(default)]
    pub springs: Option<Vec<SpringConfig>>,
}

/// A linear spring and damper between a point fixed to a free body and a fixed
/// anchor: along the line from the anchor to the point, tension
/// `T = stiffness (L - rest_length) + damping dL/dt` (`L` the line's length).
#[derive(Debug, Clone, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SpringConfig {
    /// Where the spring holds the body at t = 0 \[m\].
    pub point: Vec<f64>,
    /// The fixed end \[m\].
    pub anchor: Vec<f64>,
    /// Stiffness \[N/m\] (2D: per unit depth, N/m²).
    pub stiffness: f64,
    /// Length without tension \[m\]. Default: the length at t = 0.
    #[serde(default)]
    pub rest_length: Option<f64>,
    /// Damping along the line \[N s/m\] (2D: per unit depth). Default: 0.
    #[serde(default)]
    pub damping: Option<f64>,
    /// Whether the line goes slack instead of pushing (a mooring line: no force while
    /// shorter than `rest_length`). Default: false, a spring both ways.
    #[serde(default)]
    pub slack: Option<bool>,
}
