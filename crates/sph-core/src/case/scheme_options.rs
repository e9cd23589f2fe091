//! The `[scheme]` table: density diffusion, viscosity, integrator and its step limits,
//! wall condition, shifting, tensile control and the δ-LES-SPH closure (docs/theory.md
//! §4-§11).

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum DiffusionChoice {
    /// No density diffusion (standard WCSPH).
    None,
    /// Molteni & Colagrossi (2009).
    MolteniColagrossi,
    /// Ferrari et al. (2009).
    Ferrari,
    /// δ-SPH (Antuono et al. 2010), with the renormalised density gradient.
    DeltaSph,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum ViscosityChoice {
    /// No viscous term.
    None,
    /// Monaghan's artificial viscosity `K = α h c0 ρ0`, with `alpha`.
    Artificial,
    /// Physical viscosity, with `dynamic_viscosity`.
    Physical,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum IntegratorChoice {
    /// Runge-Kutta 4 with the diffusive term frozen over the step.
    Rk4,
    /// Second-order symplectic predictor-corrector.
    Symplectic,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum WallCondition {
    /// The walls exert no shear.
    FreeSlip,
    /// The viscous term sees the walls' velocity mirrored (Adami et al. 2012).
    NoSlip,
}

#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SchemeConfig {
    /// The density diffusion of the continuity equation.
    #[serde(default = "default_diffusion")]
    pub diffusion: DiffusionChoice,
    /// δ of the diffusive term.
    #[serde(default = "default_delta")]
    pub delta: f64,
    /// The viscous term.
    #[serde(default = "default_viscosity")]
    pub viscosity: ViscosityChoice,
    /// α of the artificial viscosity `K = α h c0 ρ0`. Default: 0.02.
    #[serde(default)]
    pub alpha: Option<f64>,
    /// Dynamic viscosity μ [Pa s] of the physical viscosity. Default: required with
    /// `physical`.
    #[serde(default)]
    pub dynamic_viscosity: Option<f64>,
    /// The time integrator.
    #[serde(default = "default_integrator")]
    pub integrator: IntegratorChoice,
    /// Courant number of `Δt = CFL h/c0`. Default: 1.5 (rk4) or 0.25 (symplectic).
    #[serde(default)]
    pub cfl: Option<f64>,
    /// Viscous limit `Δt <= C_ν h²/ν`. Default: 0.125 (rk4) or 0.09 (symplectic).
    #[serde(default)]
    pub viscous_cfl: Option<f64>,
    /// Density-diffusion limit `Δt <= C_ψ h²/max ν_δ` of `delta_les`. Default: 0.25
    /// (rk4) or 0.18 (symplectic), 80% of the stability bound of the worst kernel
    /// (Wendland C4 at h = 2Δx, whose diffusion eigenvalue reaches 8.9 ν_δ/h²).
    #[serde(default)]
    pub diffusion_cfl: Option<f64>,
    /// Body-force limit `Δt <= C_f sqrt(h/|a|max)`.
    #[serde(default = "default_force_cfl")]
    pub force_cfl: f64,
    /// The wall condition of the viscous term.
    #[serde(default = "default_walls")]
    pub walls: WallCondition,
    /// Particle shifting after each step; `delta_plus` writes `shifting_velocity`.
    #[serde(default = "default_shifting")]
    pub shifting: ShiftingChoice,
    /// Tensile instability control (Sun et al. 2018): `(p_j - p_i)` in the momentum
    /// equation for interior particles with negative pressure (momentum is then not
    /// conserved exactly).
    #[serde(default)]
    pub tensile_control: bool,
    /// Turbulence closure: `delta_les` turns viscosity and density diffusion into LES
    /// closures and moves particles quasi-Lagrangianly (δ-LES-SPH, docs/theory.md §11).
    #[serde(default = "default_turbulence")]
    pub turbulence: TurbulenceChoice,
    /// C_S of the eddy viscosity `ν_T = (C_S l)² ‖D‖` (`delta_les`). Default: 0.12.
    #[serde(default)]
    pub smagorinsky_constant: Option<f64>,
    /// C_δ of the density-diffusion coefficient `ν_δ = (C_δ l)² ‖D‖` (`delta_les`).
    /// Default: 6.
    #[serde(default)]
    pub diffusion_constant: Option<f64>,
    /// The LES length l \[m\] (`delta_les`). Default: the particle spacing Δx.
    #[serde(default)]
    pub les_length: Option<f64>,
    /// U_max [m/s], the flow speed that sizes the quasi-Lagrangian shifting
    /// `A_sh = a h U_max` and caps `|δu| <= U_max/2` (`delta_les`). Default: c0/10.
    #[serde(default)]
    pub les_velocity: Option<f64>,
    /// The factor a of the shifting prefactor `A_sh = a h U_max` (`delta_les`; 0 leaves
    /// the particles on the flow). Default: 8, from the Taylor-Green decay
    /// (docs/validation/les.md).
    #[serde(default)]
    pub les_shifting: Option<f64>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum TurbulenceChoice {
    /// No closure: the viscosity and diffusion chosen above.
    None,
    /// δ-LES-SPH (Di Mascio et al. 2017; Antuono et al. 2021).
    DeltaLes,
}

fn default_turbulence() -> TurbulenceChoice {
    TurbulenceChoice::None
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum ShiftingChoice {
    /// No shifting.
    None,
    /// δ+-SPH shifting (Sun et al. 2017), tangential near the free surface and capped
    /// at 0.05h.
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
            diffusion_cfl: None,
            force_cfl: default_force_cfl(),
            walls: default_walls(),
            shifting: default_shifting(),
            tensile_control: false,
            turbulence: default_turbulence(),
            smagorinsky_constant: None,
            diffusion_constant: None,
            les_length: None,
            les_velocity: None,
            les_shifting: None,
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
    /// The Courant number in force. RK4: 1.5, the largest with which the 2D dam break
    /// (the most violent example) stays stable to t·sqrt(g/H) = 7 at H/Δx = 15-50. The
    /// symplectic scheme: 0.25. It holds with 0.25, 0.3 and 0.4 at H/Δx = 15, 20 and 30
    /// and with 0.25 and 0.3 at 50, where 0.4 reaches the end through a 10% density
    /// spike and 0.6 stops unstable at t = 0.69 s (its walls stopped pulling lone
    /// particles into them, which had once limited it to 0.15).
    pub fn cfl(&self) -> f64 {
        self.cfl.unwrap_or(match self.integrator {
            IntegratorChoice::Rk4 => 1.5,
            IntegratorChoice::Symplectic => 0.25,
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
    /// The density-diffusion number `C_ψ` in force (δ-LES-SPH's `ν_δ` limit): 0.25 for
    /// RK4, 0.18 for the symplectic scheme, below 0.85 of the stability intervals
    /// (2.785 and 2) over the largest diffusion eigenvalue of every kernel (tested in
    /// `time::step_size`).
    pub fn diffusion_cfl(&self) -> f64 {
        self.diffusion_cfl.unwrap_or(match self.integrator {
            IntegratorChoice::Rk4 => 0.25,
            IntegratorChoice::Symplectic => 0.18,
        })
    }
    /// α of the artificial viscosity (default 0.02).
    pub fn alpha(&self) -> f64 {
        self.alpha.unwrap_or(0.02)
    }
}
