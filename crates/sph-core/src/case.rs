//! The case file: a TOML schema read with serde (unknown keys rejected) and checked
//! value by value, so that every mistake is reported as one line naming the key,
//! the value and what was expected. All quantities are SI.

use crate::error::{Result, SphError};
use crate::kernel::KernelChoice;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// A whole case, as written in the TOML file.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Case {
    /// Free-form name, used for the default output folder.
    #[serde(default = "default_name")]
    pub name: String,
    /// 2 or 3.
    pub dimension: usize,
    pub particles: ParticlesConfig,
    pub fluid: FluidConfig,
    #[serde(default)]
    pub fluid_block: Vec<BoxConfig>,
    #[serde(default)]
    pub tank: Vec<TankConfig>,
    #[serde(default)]
    pub wall: Vec<BoxConfig>,
    #[serde(default)]
    pub domain: Option<DomainConfig>,
    #[serde(default)]
    pub initial: Option<InitialField>,
    #[serde(default)]
    pub scheme: SchemeConfig,
    pub time: TimeConfig,
    #[serde(default)]
    pub stability: StabilityConfig,
    #[serde(default)]
    pub diagnostics: DiagnosticsConfig,
}

fn default_name() -> String {
    "case".into()
}

#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ParticlesConfig {
    /// Initial particle spacing Δx [m].
    pub spacing: f64,
    /// Smoothing length over spacing, h/Δx.
    #[serde(default = "default_h_over_dx")]
    pub h_over_dx: f64,
    #[serde(default = "default_kernel")]
    pub kernel: KernelChoice,
}

fn default_h_over_dx() -> f64 {
    1.33
}
fn default_kernel() -> KernelChoice {
    KernelChoice::WendlandC2
}

#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FluidConfig {
    /// Reference density ρ0 [kg/m³].
    pub density: f64,
    /// Gravity vector [m/s²]; zero if absent.
    #[serde(default)]
    pub gravity: Option<Vec<f64>>,
    /// Numerical sound speed c0 [m/s]; from the rule `factor · max(U, sqrt(Δp/ρ0))` if absent.
    #[serde(default)]
    pub sound_speed: Option<f64>,
    #[serde(default = "default_sound_speed_factor")]
    pub sound_speed_factor: f64,
    /// Background pressure p_b [Pa] added to the EOS (confined flows only).
    #[serde(default)]
    pub background_pressure: f64,
    /// U_max for the sound-speed rule; default `max(|u0|, sqrt(2 |g| H))`, H the fluid height.
    #[serde(default)]
    pub max_velocity: Option<f64>,
}

fn default_sound_speed_factor() -> f64 {
    10.0
}

/// An axis-aligned box `[lo, hi]`, filled with particles on the lattice `lo + (k + ½)Δx`.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoxConfig {
    pub lo: Vec<f64>,
    pub hi: Vec<f64>,
    /// Initial velocity (fluid blocks only).
    #[serde(default)]
    pub velocity: Option<Vec<f64>>,
    /// Start from the hydrostatic density of a column whose free surface is the box top
    /// (fluid blocks only; default true).
    #[serde(default)]
    pub hydrostatic: Option<bool>,
    /// Fill the whole box, or only the ellipse (ellipsoid) inscribed in it (fluid
    /// blocks only; default box).
    #[serde(default)]
    pub shape: Option<Shape>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Shape {
    Box,
    /// The ellipse (3D: ellipsoid) inscribed in the box: a disc when the box is square.
    Ellipsoid,
}

/// A tank: wall layers around the inner box `[lo, hi]`, except on the open faces.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TankConfig {
    pub lo: Vec<f64>,
    pub hi: Vec<f64>,
    /// Number of wall particle layers.
    #[serde(default = "default_layers")]
    pub layers: usize,
    /// Faces left open, among "-x", "+x", "-y", "+y", "-z", "+z"; default the top face.
    #[serde(default)]
    pub open: Option<Vec<String>>,
    /// Velocity of the wall layers above the top face (the last axis): a lid sliding in
    /// its own plane, as in the lid-driven cavity. Its particles keep their places and
    /// carry this velocity into the continuity and (no-slip) viscous terms. The top face
    /// must be closed and the velocity tangential to it.
    #[serde(default)]
    pub lid_velocity: Option<Vec<f64>>,
}

impl TankConfig {
    /// The open faces as (axis, side ±1); the top face (last axis, +) by default.
    pub fn open_faces(&self, dim: usize) -> Vec<(usize, i8)> {
        match &self.open {
            Some(faces) => faces.iter().filter_map(|f| face_axis(f, dim)).collect(),
            None => vec![(dim - 1, 1)],
        }
    }
}

fn default_layers() -> usize {
    3
}

#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DomainConfig {
    pub lo: Vec<f64>,
    pub hi: Vec<f64>,
    pub periodic: Vec<bool>,
}

/// An analytic initial field laid over the fluid blocks.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum InitialField {
    /// 2D Taylor-Green vortex on a periodic square of side `wavelength`:
    /// `u = U(-cos kx sin ky, sin kx cos ky)`, `p = -ρ0 U²/4 (cos 2kx + cos 2ky)`, `k = 2π/L`.
    TaylorGreen { amplitude: f64, wavelength: f64 },
    /// 2D elliptic drop (Monaghan 1994) of a disc of `radius` R centred at the origin:
    /// `u = (-A0 x, A0 y)` with `A0 = strain_rate`, `p = ρ0 A0² (R² - x² - y²)/2`.
    EllipticDrop { strain_rate: f64, radius: f64 },
    /// 2D rotating square patch (Colagrossi 2005; Sun et al. 2017) of `side` L centred at
    /// the origin: `u = (ω y, -ω x)` with `ω = angular_velocity`, and the pressure that
    /// solves ∇²p = 2ρ0ω² with p = 0 on the edges (series in [`crate::geometry`]).
    RotatingSquare { angular_velocity: f64, side: f64 },
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DiffusionChoice {
    None,
    MolteniColagrossi,
    Ferrari,
    DeltaSph,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ViscosityChoice {
    None,
    Artificial,
    Physical,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum IntegratorChoice {
    /// Runge-Kutta 4 with the diffusive term frozen over the step.
    Rk4,
    /// Second-order symplectic predictor-corrector.
    Symplectic,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum WallCondition {
    FreeSlip,
    NoSlip,
}

#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SchemeConfig {
    #[serde(default = "default_diffusion")]
    pub diffusion: DiffusionChoice,
    /// δ of the diffusive term.
    #[serde(default = "default_delta")]
    pub delta: f64,
    #[serde(default = "default_viscosity")]
    pub viscosity: ViscosityChoice,
    /// α of the artificial viscosity.
    #[serde(default)]
    pub alpha: Option<f64>,
    /// Dynamic viscosity μ [Pa s] of the physical viscosity.
    #[serde(default)]
    pub dynamic_viscosity: Option<f64>,
    #[serde(default = "default_integrator")]
    pub integrator: IntegratorChoice,
    /// Courant number of `Δt = CFL h/c0`; default 1.5 (RK4) or 0.15 (symplectic).
    #[serde(default)]
    pub cfl: Option<f64>,
    /// Viscous limit `Δt <= C_ν h²/ν`.
    /// Viscous limit `Δt <= C_ν h²/ν`; default 0.125 (RK4) or 0.09 (symplectic).
    #[serde(default)]
    pub viscous_cfl: Option<f64>,
    /// Body-force limit `Δt <= C_f sqrt(h/|a|max)`.
    #[serde(default = "default_force_cfl")]
    pub force_cfl: f64,
    #[serde(default = "default_walls")]
    pub walls: WallCondition,
    /// Particle shifting after each step.
    #[serde(default = "default_shifting")]
    pub shifting: ShiftingChoice,
    /// Tensile instability control (Sun et al. 2018): `(p_j - p_i)` in the momentum
    /// equation for interior particles with negative pressure.
    #[serde(default)]
    pub tensile_control: bool,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ShiftingChoice {
    None,
    /// δ+-SPH shifting (Sun et al. 2017) with free-surface treatment.
    DeltaPlus,
}

fn default_shifting() -> ShiftingChoice {
    ShiftingChoice::None
}

impl Default for SchemeConfig {
    fn default() -> Self {
        Self {
            diffusion: default_diffusion(),
            delta: default_delta(),
            viscosity: default_viscosity(),
            alpha: None,
            dynamic_viscosity: None,
            integrator: default_integrator(),
            cfl: None,
            viscous_cfl: None,
            force_cfl: default_force_cfl(),
            walls: default_walls(),
            shifting: default_shifting(),
            tensile_control: false,
        }
    }
}

fn default_diffusion() -> DiffusionChoice {
    DiffusionChoice::DeltaSph
}
fn default_delta() -> f64 {
    0.1
}
fn default_viscosity() -> ViscosityChoice {
    ViscosityChoice::Artificial
}
fn default_integrator() -> IntegratorChoice {
    IntegratorChoice::Rk4
}
fn default_force_cfl() -> f64 {
    0.25
}
fn default_walls() -> WallCondition {
    WallCondition::FreeSlip
}

impl SchemeConfig {
    /// The Courant number in force. The defaults are the largest with which the 2D dam
    /// break (the most violent example) stays stable to t·sqrt(g/H) = 7 at H/Δx = 15-50:
    /// RK4 1.5; the symplectic scheme blows up in the run-up jet with 0.4, 0.25 and 0.2
    /// and holds with 0.15.
    pub fn cfl(&self) -> f64 {
        self.cfl.unwrap_or(match self.integrator {
            IntegratorChoice::Rk4 => 1.5,
            IntegratorChoice::Symplectic => 0.15,
        })
    }
    /// The viscous number `C_ν` in force. RK4 is stable on the negative real axis up to
    /// 2.785, the symplectic midpoint scheme up to 2, so its default is 0.125 · 2/2.785
    /// (0.125 is stable and 0.09 is needed in the 2D Poiseuille case).
    pub fn viscous_cfl(&self) -> f64 {
        self.viscous_cfl.unwrap_or(match self.integrator {
            IntegratorChoice::Rk4 => 0.125,
            IntegratorChoice::Symplectic => 0.09,
        })
    }
    /// α of the artificial viscosity (default 0.02).
    pub fn alpha(&self) -> f64 {
        self.alpha.unwrap_or(0.02)
    }
}

#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TimeConfig {
    /// End time [s].
    pub end: f64,
    /// Interval between particle snapshots [s]; 0 writes only the first and last.
    #[serde(default)]
    pub output_interval: f64,
    /// Optional cap on the number of steps.
    #[serde(default)]
    pub max_steps: Option<u64>,
}

#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StabilityConfig {
    /// Largest admissible |ρ/ρ0 - 1| before the run is stopped.
    #[serde(default = "default_max_density_variation")]
    pub max_density_variation: f64,
    /// Largest admissible Mach number |u|/c0 of a fluid particle. A weakly-compressible
    /// model is void long before Ma = 1; a particle that fast has been thrown out by a
    /// blow-up, and flying on it would stretch the neighbour grid without bound.
    #[serde(default = "default_max_mach")]
    pub max_mach: f64,
}

impl Default for StabilityConfig {
    fn default() -> Self {
        Self {
            max_density_variation: default_max_density_variation(),
            max_mach: default_max_mach(),
        }
    }
}

fn default_max_mach() -> f64 {
    1.0
}

fn default_max_density_variation() -> f64 {
    0.2
}

#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DiagnosticsConfig {
    /// Interval of the time series (energies, probes, front) [s]; default output_interval/10.
    #[serde(default)]
    pub interval: Option<f64>,
    /// Write E_k, E_p, E_c, their sum and max |Δρ/ρ0|.
    #[serde(default)]
    pub energy: bool,
    /// Also integrate the viscous and diffusive powers every step (one extra pair loop per step).
    #[serde(default)]
    pub energy_budget: bool,
    /// Pressure probes (Shepard interpolation from fluid particles).
    #[serde(default)]
    pub probes: Vec<Vec<f64>>,
    /// Track the surge front: the largest fluid coordinate along this axis (0 = x).
    #[serde(default)]
    pub surge_front_axis: Option<usize>,
    /// Detect the free surface (Marrone et al. 2010) at each snapshot and write the
    /// flag, the normal and λ with it.
    #[serde(default)]
    pub free_surface: bool,
}

/// The most particles a case may ask for: 2^30, beyond the memory of any one machine
/// this solver runs on (about 300 bytes a particle).
pub const MAX_PARTICLES: f64 = 1_073_741_824.0;

impl Case {
    /// Reads and validates a case file.
    pub fn from_file(path: &Path) -> Result<Self> {
        let text = std::fs::read_to_string(path).map_err(|e| SphError::CaseFile {
            path: path.display().to_string(),
            message: e.to_string(),
        })?;
        Self::from_toml_str(&text).map_err(|e| match e {
            SphError::CaseFile { message, .. } => SphError::CaseFile {
                path: path.display().to_string(),
                message,
            },
            other => other,
        })
    }

    /// Parses and validates a case from TOML text.
    pub fn from_toml_str(text: &str) -> Result<Self> {
        let table: toml::Table = text.parse().map_err(|e: toml::de::Error| {
            let first = e.message().lines().next().unwrap_or("").to_string();
            let at = e
                .span()
                .map(|s| line_col(text, s.start))
                .unwrap_or_default();
            SphError::CaseFile {
                path: "<case>".into(),
                message: format!("TOML syntax{at}: {first}"),
            }
        })?;
        Self::from_table(table)
    }

    /// Deserialises a parsed TOML table (the Python front goes through here too).
    pub fn from_table(table: toml::Table) -> Result<Self> {
        let value = toml::Value::Table(table);
        let case: Case = serde_path_to_error::deserialize(value.clone())
            .map_err(|e| schema_error(&value, e.path().to_string(), e.inner().to_string()))?;
        case.validate()?;
        Ok(case)
    }

    /// Value checks beyond types; geometry checks that need particles happen when building.
    pub fn validate(&self) -> Result<()> {
        let d = self.dimension;
        if d != 2 && d != 3 {
            return Err(SphError::invalid("dimension", d, "2 or 3"));
        }
        positive("particles.spacing", self.particles.spacing)?;
        let ratio = self.particles.h_over_dx;
        if !(1.0..=3.0).contains(&ratio) {
            return Err(SphError::invalid(
                "particles.h_over_dx",
                ratio,
                "a value in [1, 3]",
            ));
        }
        positive("fluid.density", self.fluid.density)?;
        if let Some(g) = &self.fluid.gravity {
            components("fluid.gravity", g, d)?;
        }
        if let Some(c0) = self.fluid.sound_speed {
            positive("fluid.sound_speed", c0)?;
        }
        positive("fluid.sound_speed_factor", self.fluid.sound_speed_factor)?;
        non_negative("fluid.background_pressure", self.fluid.background_pressure)?;
        if let Some(u) = self.fluid.max_velocity {
            non_negative("fluid.max_velocity", u)?;
        }
        if self.fluid_block.is_empty() {
            return Err(SphError::invalid(
                "fluid_block",
                "[]",
                "at least one [[fluid_block]]",
            ));
        }
        for (k, b) in self.fluid_block.iter().enumerate() {
            check_box(&format!("fluid_block[{k}]"), &b.lo, &b.hi, d)?;
            if let Some(v) = &b.velocity {
                components(&format!("fluid_block[{k}].velocity"), v, d)?;
            }
        }
        for (k, b) in self.wall.iter().enumerate() {
            check_box(&format!("wall[{k}]"), &b.lo, &b.hi, d)?;
            if b.velocity.is_some() || b.hydrostatic.is_some() || b.shape.is_some() {
                return Err(SphError::invalid(
                    format!("wall[{k}]"),
                    "velocity/hydrostatic/shape",
                    "only lo and hi (walls are fixed boxes)",
                ));
            }
        }
        for (k, t) in self.tank.iter().enumerate() {
            check_box(&format!("tank[{k}]"), &t.lo, &t.hi, d)?;
            if t.layers == 0 {
                return Err(SphError::invalid(
                    format!("tank[{k}].layers"),
                    0,
                    "at least 1",
                ));
            }
            for face in t.open.iter().flatten() {
                if face_axis(face, d).is_none() {
                    let faces = &["-x", "+x", "-y", "+y", "-z", "+z"][..2 * d];
                    return Err(SphError::invalid(
                        format!("tank[{k}].open"),
                        format!("{face:?}"),
                        format!("faces among {faces:?}"),
                    ));
                }
            }
            if let Some(v) = &t.lid_velocity {
                let key = format!("tank[{k}].lid_velocity");
                components(&key, v, d)?;
                let top = ["+x", "+y", "+z"][d - 1];
                let top_open = t.open_faces(d).contains(&(d - 1, 1));
                if top_open || v[d - 1] != 0.0 {
                    return Err(SphError::invalid(
                        key,
                        format!("{v:?}"),
                        format!(
                            "a velocity tangential to a closed top face (set open without \"{top}\" \
                             and the last component to 0)"
                        ),
                    ));
                }
            }
        }
        if let Some(dom) = &self.domain {
            check_box("domain", &dom.lo, &dom.hi, d)?;
            if dom.periodic.len() != d {
                return Err(SphError::invalid(
                    "domain.periodic",
                    format!("{:?}", dom.periodic),
                    format!("{d} booleans (dimension = {d})"),
                ));
            }
        }
        match &self.initial {
            Some(InitialField::TaylorGreen {
                amplitude,
                wavelength,
            }) => {
                only_2d(d, "taylor_green")?;
                finite("initial.amplitude", *amplitude)?;
                positive("initial.wavelength", *wavelength)?;
            }
            Some(InitialField::RotatingSquare {
                angular_velocity,
                side,
            }) => {
                only_2d(d, "rotating_square")?;
                finite("initial.angular_velocity", *angular_velocity)?;
                positive("initial.side", *side)?;
            }
            Some(InitialField::EllipticDrop {
                strain_rate,
                radius,
            }) => {
                only_2d(d, "elliptic_drop")?;
                finite("initial.strain_rate", *strain_rate)?;
                positive("initial.radius", *radius)?;
            }
            None => {}
        }
        self.check_particle_count()?;
        self.validate_scheme()?;
        positive("time.end", self.time.end)?;
        non_negative("time.output_interval", self.time.output_interval)?;
        positive(
            "stability.max_density_variation",
            self.stability.max_density_variation,
        )?;
        positive("stability.max_mach", self.stability.max_mach)?;
        if let Some(i) = self.diagnostics.interval {
            positive("diagnostics.interval", i)?;
        }
        for (k, p) in self.diagnostics.probes.iter().enumerate() {
            components(&format!("diagnostics.probes[{k}]"), p, d)?;
        }
        if let Some(a) = self.diagnostics.surge_front_axis {
            if a >= d {
                return Err(SphError::invalid(
                    "diagnostics.surge_front_axis",
                    a,
                    format!("an axis index below {d}"),
                ));
            }
        }
        Ok(())
    }

    /// Refuses a spacing that would ask for more particles than any machine holds
    /// (before a single one is built): fluid blocks, tanks and wall boxes counted as
    /// lattice boxes.
    fn check_particle_count(&self) -> Result<()> {
        let dx = self.dx();
        let cells = |lo: &[f64], hi: &[f64], pad: f64| -> f64 {
            lo.iter()
                .zip(hi)
                .map(|(l, h)| ((h - l + 2.0 * pad) / dx).round().max(0.0))
                .product()
        };
        let fluid: f64 = self
            .fluid_block
            .iter()
            .map(|b| cells(&b.lo, &b.hi, 0.0))
            .sum();
        let tanks: f64 = self
            .tank
            .iter()
            .map(|t| cells(&t.lo, &t.hi, t.layers as f64 * dx) - cells(&t.lo, &t.hi, 0.0))
            .sum();
        let walls: f64 = self.wall.iter().map(|b| cells(&b.lo, &b.hi, 0.0)).sum();
        let total = fluid + tanks + walls;
        if total > MAX_PARTICLES {
            return Err(SphError::invalid(
                "particles.spacing",
                self.particles.spacing,
                format!(
                    "a spacing giving at most {MAX_PARTICLES:.1e} particles (this one gives \
                     about {total:.1e})"
                ),
            ));
        }
        Ok(())
    }

    fn validate_scheme(&self) -> Result<()> {
        let s = &self.scheme;
        if !(0.0..=1.0).contains(&s.delta) {
            return Err(SphError::invalid(
                "scheme.delta",
                s.delta,
                "a value in [0, 1]",
            ));
        }
        match s.viscosity {
            ViscosityChoice::Artificial => non_negative("scheme.alpha", s.alpha())?,
            ViscosityChoice::Physical => match s.dynamic_viscosity {
                Some(mu) => positive("scheme.dynamic_viscosity", mu)?,
                None => {
                    return Err(SphError::invalid(
                        "scheme.dynamic_viscosity",
                        "(missing)",
                        "a positive viscosity μ in Pa·s when scheme.viscosity = \"physical\"",
                    ))
                }
            },
            ViscosityChoice::None => {}
        }
        let cfl = s.cfl();
        if !(cfl > 0.0 && cfl <= 3.0) {
            return Err(SphError::invalid(
                "scheme.cfl",
                cfl,
                "a Courant number in (0, 3]",
            ));
        }
        if let Some(c) = s.viscous_cfl {
            positive("scheme.viscous_cfl", c)?;
        }
        positive("scheme.force_cfl", s.force_cfl)
    }

    /// Initial particle spacing Δx.
    pub fn dx(&self) -> f64 {
        self.particles.spacing
    }

    /// Smoothing length h.
    pub fn h(&self) -> f64 {
        self.particles.h_over_dx * self.particles.spacing
    }

    /// Gravity vector as a slice of `dimension` components.
    pub fn gravity(&self) -> Vec<f64> {
        self.fluid
            .gravity
            .clone()
            .unwrap_or_else(|| vec![0.0; self.dimension])
    }
}

/// The axis and side (`+1`/`-1`) a face name like "+y" stands for.
pub fn face_axis(face: &str, dim: usize) -> Option<(usize, i8)> {
    let mut ch = face.chars();
    let sign = match ch.next()? {
        '+' => 1,
        '-' => -1,
        _ => return None,
    };
    let axis = match ch.next()? {
        'x' => 0,
        'y' => 1,
        'z' => 2,
        _ => return None,
    };
    (ch.next().is_none() && axis < dim).then_some((axis, sign))
}

fn positive(key: &str, v: f64) -> Result<()> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(SphError::invalid(key, v, "a positive number"))
    }
}

fn non_negative(key: &str, v: f64) -> Result<()> {
    if v.is_finite() && v >= 0.0 {
        Ok(())
    } else {
        Err(SphError::invalid(key, v, "a number >= 0"))
    }
}

fn finite(key: &str, v: f64) -> Result<()> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(SphError::invalid(key, v, "a finite number"))
    }
}

fn components(key: &str, v: &[f64], d: usize) -> Result<()> {
    if v.len() != d {
        return Err(SphError::invalid(
            key,
            format!("{v:?}"),
            format!("{d} components (dimension = {d})"),
        ));
    }
    if v.iter().any(|c| !c.is_finite()) {
        return Err(SphError::invalid(
            key,
            format!("{v:?}"),
            "finite components",
        ));
    }
    Ok(())
}

fn check_box(key: &str, lo: &[f64], hi: &[f64], d: usize) -> Result<()> {
    components(&format!("{key}.lo"), lo, d)?;
    components(&format!("{key}.hi"), hi, d)?;
    if lo.iter().zip(hi).any(|(a, b)| b <= a) {
        return Err(SphError::invalid(
            format!("{key}.hi"),
            format!("{hi:?}"),
            format!("every component above lo = {lo:?}"),
        ));
    }
    Ok(())
}

/// Looks a dotted path like `scheme.delta` or `fluid_block[0].lo` up in the parsed table.
/// One line naming the key: a missing key is named in full (`particles.spacing =
/// (missing): missing field, a required key`), other errors show the value found.
fn schema_error(root: &toml::Value, path: String, inner: String) -> SphError {
    let message = inner.lines().next().unwrap_or("").to_string();
    let missing = message
        .strip_prefix("missing field `")
        .and_then(|rest| rest.split('`').next());
    if let Some(field) = missing {
        let key = if path == "." {
            field.to_string()
        } else {
            format!("{path}.{field}")
        };
        return SphError::Schema {
            key,
            value: "(missing)".into(),
            message: "missing field, a required key".into(),
        };
    }
    let value = lookup(root, &path)
        .map(|v| v.to_string())
        .unwrap_or_else(|| "(missing)".into());
    SphError::Schema {
        key: path,
        value,
        message,
    }
}

fn only_2d(d: usize, field: &str) -> Result<()> {
    if d == 2 {
        Ok(())
    } else {
        Err(SphError::invalid(
            "initial.type",
            format!("\"{field}\""),
            "dimension = 2",
        ))
    }
}

fn lookup<'a>(v: &'a toml::Value, path: &str) -> Option<&'a toml::Value> {
    let mut cur = v;
    for part in path.split('.') {
        let (name, index) = match part.find('[') {
            Some(b) => (
                &part[..b],
                part[b + 1..part.len() - 1].parse::<usize>().ok(),
            ),
            None => (part, None),
        };
        if !name.is_empty() {
            cur = cur.get(name)?;
        }
        if let Some(k) = index {
            cur = cur.get(k)?;
        }
    }
    Some(cur)
}

fn line_col(text: &str, offset: usize) -> String {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let col = before.len() - before.rfind('\n').map(|p| p + 1).unwrap_or(0) + 1;
    format!(" at line {line}, column {col}")
}

#[cfg(test)]
mod tests {
    use super::*;

    const MINIMAL: &str = r#"
        dimension = 2
        [particles]
        spacing = 0.01
        [fluid]
        density = 1000.0
        gravity = [0.0, -9.81]
        [[fluid_block]]
        lo = [0.0, 0.0]
        hi = [0.2, 0.1]
        [[tank]]
        lo = [0.0, 0.0]
        hi = [0.5, 0.3]
        [time]
        end = 0.1
    "#;

    fn error_of(text: &str) -> String {
        Case::from_toml_str(text).unwrap_err().to_string()
    }

    #[test]
    fn absurd_spacing_is_refused_before_building() {
        let e = error_of(&MINIMAL.replace("spacing = 0.01", "spacing = 1e-9"));
        assert!(
            e.starts_with("particles.spacing = 0.000000001: expected a spacing giving at most"),
            "{e}"
        );
    }

    #[test]
    fn minimal_case_parses_with_defaults() {
        let c = Case::from_toml_str(MINIMAL).unwrap();
        assert_eq!(c.scheme.diffusion, DiffusionChoice::DeltaSph);
        assert_eq!(c.scheme.cfl(), 1.5);
        assert!((c.h() - 0.0133).abs() < 1e-12);
    }

    #[test]
    fn unknown_key_is_named() {
        let e = error_of(&MINIMAL.replace("spacing = 0.01", "spacing = 0.01\nspacingg = 2"));
        assert!(
            e.starts_with("particles.spacingg") || e.contains("spacingg"),
            "{e}"
        );
        assert!(e.contains("unknown field"), "{e}");
        assert_eq!(e.lines().count(), 1, "{e}");
    }

    #[test]
    fn wrong_type_names_key_and_value() {
        let e = error_of(&MINIMAL.replace("end = 0.1", "end = \"soon\""));
        assert!(e.starts_with("time.end = \"soon\": invalid type"), "{e}");
    }

    #[test]
    fn negative_spacing_is_refused() {
        let e = error_of(&MINIMAL.replace("spacing = 0.01", "spacing = -0.01"));
        assert_eq!(e, "particles.spacing = -0.01: expected a positive number");
    }

    #[test]
    fn h_over_dx_out_of_range() {
        let e = error_of(&MINIMAL.replace("spacing = 0.01", "spacing = 0.01\nh_over_dx = 7"));
        assert!(e.starts_with("particles.h_over_dx = 7"), "{e}");
    }

    #[test]
    fn wrong_component_count() {
        let e = error_of(&MINIMAL.replace("gravity = [0.0, -9.81]", "gravity = [0.0, 0.0, -9.81]"));
        assert!(
            e.starts_with("fluid.gravity = [0.0, 0.0, -9.81]: expected 2 components"),
            "{e}"
        );
    }

    #[test]
    fn inverted_box() {
        let e = error_of(&MINIMAL.replace("hi = [0.2, 0.1]", "hi = [0.2, -0.1]"));
        assert!(e.starts_with("fluid_block[0].hi"), "{e}");
    }

    #[test]
    fn unknown_kernel_lists_choices() {
        let e = error_of(&MINIMAL.replace("spacing = 0.01", "spacing = 0.01\nkernel = \"sinc\""));
        assert!(e.starts_with("particles.kernel = \"sinc\""), "{e}");
        assert!(e.contains("wendland_c2"), "{e}");
    }

    #[test]
    fn syntax_error_has_a_position() {
        let e = error_of("dimension = = 2");
        assert!(e.contains("line 1"), "{e}");
    }

    #[test]
    fn physical_viscosity_needs_mu() {
        let e = error_of(&format!("{MINIMAL}\n[scheme]\nviscosity = \"physical\""));
        assert!(e.starts_with("scheme.dynamic_viscosity = (missing)"), "{e}");
    }

    #[test]
    fn bad_open_face() {
        let e = error_of(&MINIMAL.replace("hi = [0.5, 0.3]", "hi = [0.5, 0.3]\nopen = [\"+z\"]"));
        assert!(e.starts_with("tank[0].open = \"+z\""), "{e}");
    }
}
