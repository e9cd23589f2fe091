//! The case schema: every table and key of the TOML file as plain data, with its
//! default. Unknown keys are rejected by serde; values are checked in
//! [`super::validate`]. All quantities are SI.

use super::motion::{BodyMotion, FreeConfig, MotionChoice, PrescribedConfig};
use super::open_boundaries::OpenBoundaryConfig;
use super::shapes::{Role, ShapeConfig};
use crate::physics::kernel::KernelChoice;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

pub use super::diagnostics_options::*;
pub use super::scheme_options::*;

/// A whole case, as written in the TOML file.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Case {
    /// Run name, a plain file name: the default output folder is `<name>_out`.
    #[serde(default = "default_name")]
    pub name: String,
    /// 2 or 3.
    pub dimension: usize,
    pub particles: ParticlesConfig,
    pub fluid: FluidConfig,
    /// Boxes filled with fluid.
    #[serde(default)]
    pub fluid_block: Vec<FluidBlockConfig>,
    /// Tanks: wall layers around a box.
    #[serde(default)]
    pub tank: Vec<TankConfig>,
    /// Boxes filled with wall particles.
    #[serde(default)]
    pub wall: Vec<WallConfig>,
    /// Solids of any shape: fluid regions, walls and cuts.
    #[serde(default)]
    pub shape: Vec<ShapeConfig>,
    #[serde(default)]
    pub domain: Option<DomainConfig>,
    /// Inflow and outflow buffers at the ends of the domain.
    #[serde(default)]
    pub open_boundary: Vec<OpenBoundaryConfig>,
    #[serde(default)]
    pub initial: Option<InitialField>,
    /// A body force besides gravity, varying in space and time.
    #[serde(default)]
    pub forcing: Option<ForcingConfig>,
    /// Damping zones that absorb waves at the ends of a flume.
    #[serde(default)]
    pub absorber: Vec<AbsorberConfig>,
    #[serde(default)]
    pub scheme: SchemeConfig,
    pub time: TimeConfig,
    #[serde(default)]
    pub stability: StabilityConfig,
    #[serde(default)]
    pub diagnostics: DiagnosticsConfig,
    #[serde(default)]
    pub output: OutputConfig,
}

fn default_name() -> String {
    "case".into()
}

#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ParticlesConfig {
    /// Initial particle spacing Δx \[m\].
    pub spacing: f64,
    /// Smoothing length over spacing, h/Δx, in [1, 3]. The default, 2 with Wendland C2
    /// (support 4Δx, as in the δ-SPH papers), has the lowest error at equal wall time
    /// across the kernel study (docs/validation/kernel_study.md): at 1.33 the viscous
    /// profiles are 3-12% off at any Δx and a standing wave's period 4% short.
    #[serde(default = "default_h_over_dx")]
    pub h_over_dx: f64,
    /// The smoothing kernel.
    #[serde(default = "default_kernel")]
    pub kernel: KernelChoice,
}

fn default_h_over_dx() -> f64 {
    2.0
}
fn default_kernel() -> KernelChoice {
    KernelChoice::WendlandC2
}

#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FluidConfig {
    /// Reference density ρ0 [kg/m³].
    pub density: f64,
    /// Gravity vector [m/s²]. Default: zero.
    #[serde(default)]
    pub gravity: Option<Vec<f64>>,
    /// Numerical sound speed c0 [m/s]. Default: the rule of `sound_speed_factor`.
    #[serde(default)]
    pub sound_speed: Option<f64>,
    /// The factor of the sound-speed rule `c0 = factor · max(U, sqrt(Δp/ρ0))`, with U
    /// the `max_velocity` and `Δp = ρ0 |g| H`, H the fluid height.
    #[serde(default = "default_sound_speed_factor")]
    pub sound_speed_factor: f64,
    /// Background pressure p_b \[Pa\] added to the EOS (confined flows only).
    #[serde(default)]
    pub background_pressure: f64,
    /// U of the sound-speed rule [m/s]. Default: `max(|u0|, sqrt(2 |g| H))`.
    #[serde(default)]
    pub max_velocity: Option<f64>,
}

fn default_sound_speed_factor() -> f64 {
    10.0
}

/// A box `[lo, hi]` filled with fluid on the lattice `lo + (k + ½)Δx`.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FluidBlockConfig {
    /// Lower corner \[m\]. The block shares the tanks' lattice when it is a multiple of Δx; a run
    /// gives a notice when its fluid starts closer than 0.9 Δx to a wall (off the walls' lattice).
    pub lo: Vec<f64>,
    /// Upper corner \[m\].
    pub hi: Vec<f64>,
    /// Initial velocity [m/s]. Default: at rest.
    #[serde(default)]
    pub velocity: Option<Vec<f64>>,
    /// Start from the hydrostatic density of a column whose free surface is the box top,
    /// or `surface`. Default: true.
    #[serde(default)]
    pub hydrostatic: Option<bool>,
    /// Height (along -g) of the free surface above this block's hydrostatic start, when
    /// it is not the block's own top: blocks stacked around a submerged wall share the
    /// surface of the top one (a submerged block then carries ρ0gV within 0.13%,
    /// `tests/physics/loads.rs`). Default: the box top.
    #[serde(default)]
    pub surface: Option<f64>,
    /// Fill the whole box, or only the ellipse (ellipsoid) inscribed in it. Default: box.
    #[serde(default)]
    pub shape: Option<Shape>,
}

/// A box `[lo, hi]` filled with wall particles on the lattice `lo + (k + ½)Δx`: a fixed
/// body whose load can be written.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct WallConfig {
    /// Lower corner \[m\]. The wall is at least the kernel support R thick along every axis.
    pub lo: Vec<f64>,
    /// Upper corner \[m\].
    pub hi: Vec<f64>,
    /// Name of the body in the loads' columns. Default: `wall<k>`.
    #[serde(default)]
    pub name: Option<String>,
    /// How the region moves: "fixed", "prescribed" (then its `prescribed` table
    /// gives the motion) or "free" (a floating body: its `free` table). Default: "fixed".
    #[serde(default)]
    pub motion: Option<MotionChoice>,
    /// The motion when `motion = "prescribed"`.
    #[serde(default)]
    pub prescribed: Option<PrescribedConfig>,
    /// The body when `motion = "free"`.
    #[serde(default)]
    pub free: Option<FreeConfig>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Shape {
    /// The whole box.
    Box,
    /// The ellipse (3D: ellipsoid) inscribed in the box: a disc when the box is square.
    Ellipsoid,
}

/// A tank: wall layers around the inner box `[lo, hi]`, except on the open faces.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct TankConfig {
    /// Lower corner of the inner box \[m\].
    pub lo: Vec<f64>,
    /// Upper corner of the inner box \[m\].
    pub hi: Vec<f64>,
    /// Number of wall particle layers; fewer than cover the kernel support
    /// (layers·Δx < R) are refused. Default: the fewest that cover it, `ceil(R/Δx)` (4
    /// at h/Δx = 2).
    #[serde(default)]
    pub layers: Option<usize>,
    /// Faces left open, among "-x", "+x", "-y", "+y", "-z", "+z". Default: the top face.
    #[serde(default)]
    pub open: Option<Vec<String>>,
    /// Velocity of the wall layers above the top face (the last axis): a lid sliding in
    /// its own plane, as in the lid-driven cavity. Its particles keep their places and
    /// carry this velocity into the continuity and (no-slip) viscous terms. The top face
    /// must be closed and the velocity tangential to it. Default: at rest.
    #[serde(default)]
    pub lid_velocity: Option<Vec<f64>>,
    /// Name of the body in the loads' columns. Default: `tank<k>`.
    #[serde(default)]
    pub name: Option<String>,
    /// How the region moves: "fixed" or "prescribed" (then its `prescribed` table
    /// gives the motion); a tank does not float ("free" is for walls and shapes).
    /// Default: "fixed".
    #[serde(default)]
    pub motion: Option<MotionChoice>,
    /// The motion when `motion = "prescribed"`.
    #[serde(default)]
    pub prescribed: Option<PrescribedConfig>,
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

/// The computational box. Along periodic axes particles wrap around; along the others
/// a fluid particle that leaves the box is removed from the run. Without a `[domain]`
/// the box is the particles' initial bounding box widened by its own size on every
/// side (see [`crate::geometry`]).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DomainConfig {
    /// Lower corner \[m\].
    pub lo: Vec<f64>,
    /// Upper corner \[m\].
    pub hi: Vec<f64>,
    /// Periodic flag per axis; a periodic axis needs the tanks' faces across it open.
    /// Default: none periodic.
    #[serde(default)]
    pub periodic: Option<Vec<bool>>,
}

impl DomainConfig {
    /// Whether axis `d` is periodic.
    pub fn is_periodic(&self, d: usize) -> bool {
        self.periodic
            .as_ref()
            .is_some_and(|p| p.get(d).copied().unwrap_or(false))
    }
}

/// An analytic initial field laid over the fluid blocks.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum InitialField {
    /// 2D Taylor-Green vortex on a periodic square of side `wavelength` (which must
    /// divide the periodic box):
    /// `u = U(-cos kx sin ky, sin kx cos ky)`, `p = -ρ0 U²/4 (cos 2kx + cos 2ky)`, `k = 2π/L`.
    TaylorGreen { amplitude: f64, wavelength: f64 },
    /// 2D elliptic drop (Monaghan 1994) of a disc of `radius` R centred at the origin:
    /// `u = (-A0 x, A0 y)` with `A0 = strain_rate`, `p = ρ0 A0² (R² - x² - y²)/2`;
    /// `radius` must be that of the fluid disc.
    EllipticDrop { strain_rate: f64, radius: f64 },
    /// 2D rotating square patch (Colagrossi 2005; Sun et al. 2017) of `side` L centred at
    /// the origin: `u = (ω y, -ω x)` with `ω = angular_velocity`, and the pressure that
    /// solves ∇²p = 2ρ0ω² with p = 0 on the edges (a series); `side` must be that of the
    /// fluid square.
    RotatingSquare { angular_velocity: f64, side: f64 },
    /// 2D linear standing wave, first sloshing mode of a tank `[0, length] × [0, depth]`
    /// (bottom y = 0), at the instant its surface is flat and its speed greatest:
    /// `η = A cos kx sin ωt` with `k = π/L`, `ω² = g k tanh kd`, from the potential
    /// `φ = B cosh ky cos kx cos ωt`, `B = A ω/(k sinh kd)`; the pressure is hydrostatic.
    StandingWave {
        amplitude: f64,
        length: f64,
        depth: f64,
    },
    /// Fields from expressions of the position (`x`, `y`, `z`), the named `constants` (a
    /// table), `rho0` and `g` (|gravity|), parsed by exmex in floating point (`1/2` is
    /// 0.5): `u` a list of one expression per component, and the pressure `p` or the
    /// density `rho`; what is not given stays as the fluid regions set it. An unknown
    /// variable, a parse error or a value that is not finite at a particle is refused in
    /// one line naming the key (and the particle).
    Expressions {
        #[serde(default)]
        constants: Option<std::collections::BTreeMap<String, f64>>,
        #[serde(default)]
        u: Option<Vec<String>>,
        #[serde(default)]
        p: Option<String>,
        #[serde(default)]
        rho: Option<String>,
    },
}

#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct TimeConfig {
    /// End time \[s\].
    pub end: f64,
    /// Interval between particle snapshots \[s\]; 0 writes only the first and last.
    #[serde(default)]
    pub output_interval: f64,
    /// Cap on the number of steps. Default: none.
    #[serde(default)]
    pub max_steps: Option<u64>,
}

#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct StabilityConfig {
    /// Largest admissible |ρ/ρ0 - 1| of a fluid particle for longer than an impact's
    /// transient (`transient`); a density outside (0, 2ρ0) stops the run at once.
    #[serde(default = "default_max_density_variation")]
    pub max_density_variation: f64,
    /// The longest time, in acoustic times of the kernel h/c0, that some fluid particle
    /// may stay beyond `max_density_variation` before the run is stopped: an impact's
    /// water hammer (a cavity closing, a jet landing) is relieved by sound within a few
    /// h/c0 and is let through with a notice; a blow-up is not. 0 stops at the first
    /// step beyond.
    #[serde(default = "default_transient")]
    pub transient: f64,
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
            transient: default_transient(),
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

fn default_transient() -> f64 {
    10.0
}

/// A damping zone along x: every fluid particle's velocity relaxes toward rest,
/// `du/dt = -β w(ξ) u`, with `ξ = (x - from)/(to - from)` and the weight
/// `w = 10ξ³ - 15ξ⁴ + 6ξ⁵` rising smoothly from 0 at `from` to 1 at `to` (1 beyond,
/// 0 before), so that waves entering it are damped without reflecting from its start
/// (make it at least one wavelength long).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct AbsorberConfig {
    /// Where the damping starts \[m\] (x).
    pub from: f64,
    /// Where it reaches its full rate \[m\] (x; below `from` for a zone toward -x).
    pub to: f64,
    /// The full rate β \[1/s\]. Default: `√(2π g / |to - from|)`, the frequency of a
    /// deep-water wave as long as the zone.
    #[serde(default)]
    pub rate: Option<f64>,
}

impl Case {
    /// The full rate β of an absorber (its own or the default).
    pub fn absorber_rate(&self, a: &AbsorberConfig) -> f64 {
        let g = self.gravity().iter().map(|g| g * g).sum::<f64>().sqrt();
        a.rate
            .unwrap_or_else(|| (2.0 * std::f64::consts::PI * g / (a.to - a.from).abs()).sqrt())
    }
}

/// A body force per unit mass [m/s²] on the fluid, added to gravity: one expression per
/// component, of the position (`x`, `y`, and `z` in 3D), the time `t`, `rho0` and the
/// named `constants` (exmex syntax, as in `[initial]`; `PI` is π). For example the
/// forced cell array of Antuono et al. (2021), `A r(t) (sin kx cos ky, -cos kx sin ky)`.
/// Evaluated at every fluid particle in every force evaluation, at the stage's time.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ForcingConfig {
    /// Named values for the expressions (a table), such as `{ A = 1.3, k = 25.13 }`.
    #[serde(default)]
    pub constants: Option<std::collections::BTreeMap<String, f64>>,
    /// The acceleration [m/s²] added to every fluid particle, one expression per
    /// component, of the position (`x`, `y`, `z`), the time `t`, `rho0` and the
    /// `constants`, evaluated at each force evaluation's time (exmex syntax: `PI`, `min`,
    /// `max`, `signum`, `sin`, ...). Finite at every fluid particle at t = 0, or refused.
    pub acceleration: Vec<String>,
}

/// What a run writes besides snapshots and the time series.
#[derive(Debug, Clone, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct OutputConfig {
    /// Simulated-time interval between restart files \[s\]. Default: none (a restart file
    /// is still written at the end, on a stop signal and on a failed write).
    #[serde(default)]
    pub restart_interval: Option<f64>,
    /// The deflate level of the snapshots and restart files (with the shuffle filter;
    /// ParaView, VisIt and h5py read them as they are): 1 fastest to 9 smallest, 0 for
    /// none. Default: 2, measured on the dam-break examples: snapshots 43% (2D) and 70%
    /// (3D) smaller, restart files 37% and 67%, run time unchanged within its noise;
    /// levels 4–9 shrink the files by at most 4% more and write up to 7× slower.
    #[serde(default)]
    pub compression: Option<u8>,
}

impl OutputConfig {
    /// How the run's HDF5 files are stored.
    pub fn compression(&self) -> crate::io::output::Compression {
        self.compression
            .map_or_else(Default::default, crate::io::output::Compression::deflate)
    }
}

impl Case {
    /// The motion of every body (in the order of [`Self::body_names`]) with the case
    /// key of its region (`tank[0]`, `wall[1]`, `shape[2]`).
    pub fn body_motions(&self) -> Vec<BodyMotion<'_>> {
        let tanks = (self.tank.iter().enumerate()).map(|(k, t)| BodyMotion {
            key: format!("tank[{k}]"),
            index: k,
            motion: t.motion.unwrap_or_default(),
            prescribed: t.prescribed.as_ref(),
            free: None,
        });
        let walls = (self.wall.iter().enumerate()).map(|(k, w)| BodyMotion {
            key: format!("wall[{k}]"),
            index: k,
            motion: w.motion.unwrap_or_default(),
            prescribed: w.prescribed.as_ref(),
            free: w.free.as_ref(),
        });
        let shapes = (self.shape.iter().enumerate())
            .filter(|(_, s)| s.role == Role::Wall)
            .map(|(k, s)| BodyMotion {
                key: format!("shape[{k}]"),
                index: k,
                motion: s.motion.unwrap_or_default(),
                prescribed: s.prescribed.as_ref(),
                free: s.free.as_ref(),
            });
        tanks.chain(walls).chain(shapes).collect()
    }

    /// Whether any wall region moves.
    pub fn has_moving_bodies(&self) -> bool {
        (self.body_motions().iter()).any(|b| b.motion != MotionChoice::Fixed)
    }

    /// The bodies' names in build order, tanks, walls, then wall shapes, each with the
    /// key that sets it (`tank[k].name`; the default `tank<k>`, `wall<k>`, `shape<k>`).
    pub fn body_names(&self) -> Vec<(String, String)> {
        let tanks = self.tank.iter().enumerate().map(|(k, t)| {
            (
                format!("tank[{k}].name"),
                t.name.clone().unwrap_or(format!("tank{k}")),
            )
        });
        let walls = self.wall.iter().enumerate().map(|(k, w)| {
            (
                format!("wall[{k}].name"),
                w.name.clone().unwrap_or(format!("wall{k}")),
            )
        });
        let shapes = self
            .shape
            .iter()
            .enumerate()
            .filter(|(_, s)| s.role == Role::Wall)
            .map(|(k, s)| {
                (
                    format!("shape[{k}].name"),
                    s.name.clone().unwrap_or(format!("shape{k}")),
                )
            });
        tanks.chain(walls).chain(shapes).collect()
    }

    /// `½ ρ U² A` of the force coefficients, when the case gives reference scales.
    pub fn dynamic_force(&self) -> Option<f64> {
        let r = self.diagnostics.reference.as_ref()?;
        let rho = r.density.unwrap_or(self.fluid.density);
        Some(0.5 * rho * r.velocity * r.velocity * r.length.powi(self.dimension as i32 - 1))
    }

    /// The point loads' moments are taken about (the origin by default).
    pub fn moment_point(&self) -> Vec<f64> {
        self.diagnostics
            .moment_point
            .clone()
            .unwrap_or_else(|| vec![0.0; self.dimension])
    }

    /// Interval of the time-series rows: `diagnostics.interval`, else a tenth of the
    /// snapshot interval, else a 200th of the run.
    pub fn series_interval(&self) -> f64 {
        let snapshots = self.time.output_interval;
        self.diagnostics.interval.unwrap_or(if snapshots > 0.0 {
            snapshots / 10.0
        } else {
            self.time.end / 200.0
        })
    }

    /// Initial particle spacing Δx.
    pub fn dx(&self) -> f64 {
        self.particles.spacing
    }

    /// Smoothing length h.
    pub fn h(&self) -> f64 {
        self.particles.h_over_dx * self.particles.spacing
    }

    /// Kernel support radius R = κh.
    pub fn support(&self) -> f64 {
        self.h() * self.particles.kernel.support()
    }

    /// Gravity vector as a slice of `dimension` components.
    pub fn gravity(&self) -> Vec<f64> {
        self.fluid
            .gravity
            .clone()
            .unwrap_or_else(|| vec![0.0; self.dimension])
    }

    /// The fewest wall layers whose depth covers the kernel support, `ceil(R/Δx)`.
    pub fn min_wall_layers(&self) -> usize {
        (self.support() / self.dx() - 1e-9).ceil().max(1.0) as usize
    }
}

impl TankConfig {
    /// Wall layers of this tank: as given, or [`Case::min_wall_layers`].
    pub fn layer_count(&self, case: &Case) -> usize {
        self.layers.unwrap_or_else(|| case.min_wall_layers())
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

impl ShapeConfig {
    /// Wall layers of this shape: as given, or [`Case::min_wall_layers`].
    pub fn layer_count(&self, case: &Case) -> usize {
        self.layers.unwrap_or_else(|| case.min_wall_layers())
    }
}

impl OpenBoundaryConfig {
    /// The buffer width in force: as given, or R rounded up to whole spacings plus one.
    pub fn width_in(&self, case: &Case) -> f64 {
        self.width
            .unwrap_or_else(|| ((case.support() / case.dx() - 1e-9).ceil() + 1.0) * case.dx())
    }
}
