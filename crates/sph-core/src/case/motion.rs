//! How a wall region moves: `motion` and its `[<region>.prescribed]` table, shared by
//! `[[tank]]`, `[[wall]]` and `[[shape]]` walls.

use crate::waves::paddle::WaveMaker;
use crate::waves::spectrum::{Component, Jonswap};
use crate::waves::theory::{frequency, Paddle};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::f64::consts::PI;

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

/// A prescribed motion's table: a CSV file or its rows.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(untagged)]
pub enum MotionTable {
    /// The path of a CSV file.
    File(String),
    /// The rows: a time, then the displacements and rotation.
    Rows(Vec<Vec<f64>>),
}

impl MotionTable {
    /// How the table is shown in messages: the file's path quoted, or its row count.
    pub fn describe(&self) -> String {
        match self {
            Self::File(path) => format!("{path:?}"),
            Self::Rows(rows) => format!("{} rows", rows.len()),
        }
    }
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
    /// The motion as a table instead of `displacement` and `rotation`: rows of a time
    /// \[s\] (from 0 or before to the run's end), one displacement per axis \[m\] and
    /// optionally the rotation (2D the angle, 3D the rotation vector, \[rad\]). Either a
    /// CSV file (comma- or space-separated, `#` comments, an optional header line; a
    /// relative path is taken from the case file's folder) or the rows themselves,
    /// `[[t, x, y], ...]` (from Python, a 2D numpy array). Each column is interpolated by
    /// a natural cubic spline (continuous velocity and acceleration).
    #[serde(default)]
    pub table: Option<MotionTable>,
    /// Named values the expressions may use (besides `t`, `PI` and `π`).
    #[serde(default)]
    pub constants: Option<BTreeMap<String, f64>>,
    /// A wave maker instead of `displacement`, `rotation` or `table`: the paddle's
    /// motion along x from the waves it is to make (see `docs/theory.md` §14). Waves
    /// run toward +x. Default: none.
    #[serde(default)]
    pub waves: Option<WavesConfig>,
}

/// Which wave maker.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum PaddleChoice {
    /// The whole region moves along x.
    Piston,
    /// The region turns about the hinge `pivot` (about z in 2D, about y in 3D), so
    /// that its surface crossing moves along x.
    Flap,
}

/// A wave maker: regular waves (`height` with `period` or `wavelength`) or an
/// irregular sea (`spectrum`), made by a piston or a flap from Biesel's transfer
/// function, a piston's regular waves with Madsen's second-order correction. The
/// motion is ramped up over `ramp` (default two periods, or two peak periods).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct WavesConfig {
    /// "piston" or "flap" (which then turns about `pivot`, its hinge).
    pub paddle: PaddleChoice,
    /// Still-water depth at the paddle \[m\].
    pub depth: f64,
    /// A flap's hinge height above the bed \[m\] (negative: below it; the hinge's place
    /// is the table's `pivot`). Default: 0, hinged at the bed.
    #[serde(default)]
    pub hinge_height: Option<f64>,
    /// Regular waves: the height H \[m\], crest to trough.
    #[serde(default)]
    pub height: Option<f64>,
    /// Regular waves: the period T \[s\] (or give `wavelength`).
    #[serde(default)]
    pub period: Option<f64>,
    /// Regular waves: the wavelength L \[m\] (or give `period`).
    #[serde(default)]
    pub wavelength: Option<f64>,
    /// Regular waves: 1 (Biesel's linear motion) or 2 (a piston's second-order motion
    /// of Madsen 1971, which suppresses the free second harmonic). Default: 2 for a
    /// piston, 1 for a flap (its second order is not built).
    #[serde(default)]
    pub order: Option<u8>,
    /// An irregular sea instead of regular waves.
    #[serde(default)]
    pub spectrum: Option<SpectrumConfig>,
    /// How long the paddle makes waves \[s\]: after `duration` it ramps down over the
    /// ramp time and stops (a wave train). Default: the whole run.
    #[serde(default)]
    pub duration: Option<f64>,
    /// Active absorption at the paddle (after Schäffer & Klopman 2000): the paddle adds
    /// the motion that cancels what it would reflect of the waves coming back to it,
    /// read by a gauge just in front of it (`docs/theory.md` §14; exact at the (peak)
    /// frequency, partial elsewhere). Default: false.
    #[serde(default)]
    pub active_absorption: bool,
}

/// The defaults of an irregular sea: components, γ, band in units of `1/T_p`.
const COMPONENTS: usize = 200;
const GAMMA: f64 = 3.3;
const BAND: [f64; 2] = [0.5, 2.5];

impl WavesConfig {
    /// The wave maker of this (validated) table under gravity `g` \[m/s²\].
    pub fn maker(&self, g: f64) -> WaveMaker {
        let paddle = match self.paddle {
            PaddleChoice::Piston => Paddle::Piston,
            PaddleChoice::Flap => Paddle::Flap {
                hinge: self.hinge_height.unwrap_or(0.0),
            },
        };
        let components = match &self.spectrum {
            Some(sea) => sea.components(),
            None => vec![Component {
                amplitude: 0.5 * self.height.unwrap_or(0.0),
                omega: self.angular_frequency(g),
                phase: 0.0,
            }],
        };
        WaveMaker {
            paddle,
            depth: self.depth,
            components,
            second_order: self.height.filter(|_| self.order() == 2),
        }
    }

    /// ω of regular waves from their period or wavelength (0 without either).
    pub fn angular_frequency(&self, g: f64) -> f64 {
        match (self.period, self.wavelength) {
            (Some(t), _) => 2.0 * PI / t,
            (None, Some(l)) => frequency(2.0 * PI / l, self.depth, g),
            (None, None) => 0.0,
        }
    }

    /// The order of regular waves' generation (2 for a piston unless set).
    pub fn order(&self) -> u8 {
        self.order.unwrap_or(match self.paddle {
            PaddleChoice::Piston => 2,
            PaddleChoice::Flap => 1,
        })
    }

    /// The waves in words: regular waves' kd, wavelength and the paddle's stroke (a
    /// flap's at the still level), or the sea's band and components.
    pub fn describe(&self, g: f64) -> String {
        let maker = self.maker(g);
        let paddle = match self.paddle {
            PaddleChoice::Piston => "piston",
            PaddleChoice::Flap => "flap",
        };
        if let Some(sea) = &self.spectrum {
            let ([lo, hi], n) = (sea.band(), maker.components.len());
            return format!(
                "waves: {paddle}, JONSWAP H_s = {} m, T_p = {} s, {n} components over \
                 [{lo:.4}, {hi:.4}] Hz (the signal repeats every {:.4e} s)",
                sea.significant_height,
                sea.peak_period,
                n as f64 / (hi - lo),
            );
        }
        let omega = self.angular_frequency(g);
        let k = crate::waves::theory::wavenumber(omega, self.depth, g);
        let height = self.height.unwrap_or(0.0);
        format!(
            "waves: {paddle}, H = {height} m, T = {:.4} s, order {}: kd = {:.4}, L = {:.4} m, \
             H/L = {:.2}%, stroke {:.4e} m at the still level",
            2.0 * PI / omega,
            self.order(),
            k * self.depth,
            2.0 * PI / k,
            100.0 * height * k / (2.0 * PI),
            height / maker.paddle.height_over_stroke(k, self.depth)
        )
    }

    /// The paddle's stroke at the still level \[m\]: regular waves' `H/(H/S)`, a sea's
    /// `2 H_s/(H/S)` at its peak (about the largest the sea asks for).
    pub fn stroke(&self, g: f64) -> f64 {
        let maker = self.maker(g);
        let omega = 2.0 * PI / self.period(g);
        let k = crate::waves::theory::wavenumber(omega, self.depth, g);
        let height = match &self.spectrum {
            Some(sea) => 2.0 * sea.significant_height,
            None => self.height.unwrap_or(0.0),
        };
        height / maker.paddle.height_over_stroke(k, self.depth)
    }

    /// The (peak) period: the default ramp is two of them.
    pub fn period(&self, g: f64) -> f64 {
        match &self.spectrum {
            Some(sea) => sea.peak_period,
            None => 2.0 * PI / self.angular_frequency(g),
        }
    }
}

impl SpectrumConfig {
    /// The band generated \[Hz\] (the default filled in).
    pub fn band(&self) -> [f64; 2] {
        (self.frequencies).unwrap_or(BAND.map(|f| f / self.peak_period))
    }

    /// The sea's linear components (defaults filled in).
    pub fn components(&self) -> Vec<Component> {
        let band = self.band();
        let jonswap = Jonswap {
            significant_height: self.significant_height,
            peak_period: self.peak_period,
            gamma: self.gamma.unwrap_or(GAMMA),
        };
        let n = self.components.unwrap_or(COMPONENTS);
        jonswap.components(n, band[0], band[1], self.seed.unwrap_or(0))
    }
}

/// A JONSWAP sea made as a sum of linear components with random phases.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SpectrumConfig {
    /// Significant wave height `H_s = 4√m₀` \[m\].
    pub significant_height: f64,
    /// Peak period `T_p` \[s\].
    pub peak_period: f64,
    /// Peak enhancement γ (1: Pierson-Moskowitz). Default: 3.3.
    #[serde(default)]
    pub gamma: Option<f64>,
    /// Number of components, equally spaced in frequency (the signal repeats after
    /// `components/(f_max - f_min)`). Default: 200.
    #[serde(default)]
    pub components: Option<usize>,
    /// Seed of the random phases (the same sea for the same seed). Default: 0.
    #[serde(default)]
    pub seed: Option<u64>,
    /// Lowest and highest frequency generated \[Hz\]. Default: `[0.5/T_p, 2.5/T_p]`.
    #[serde(default)]
    pub frequencies: Option<[f64; 2]>,
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
