//! Turns the case's scheme options into a monomorphised [`Scheme`] behind `dyn Model`:
//! the only place where options are matched. Everything below runs without a
//! per-pair branch on them.

use std::any::Any;

use crate::case::{
    Case, DiffusionChoice, ShiftingChoice, TurbulenceChoice, ViscosityChoice, WallCondition,
};
use crate::physics::diffusion::{
    DeltaSph, DensityDiffusion, Ferrari, MolteniColagrossi, NoDiffusion,
};
use crate::physics::kernel::{
    CubicSpline, Gaussian, Kernel, KernelChoice, QuinticSpline, WendlandC2, WendlandC4,
};
use crate::physics::les;
use crate::physics::viscosity::{artificial_k, physical_k, Inviscid, Viscosity, Viscous};
use crate::scheme::delta_sph::Scheme;
use crate::scheme::les::LesScheme;
use crate::scheme::model::{Model, Physics};

/// Whether a case finds the free surface at each step: δ+-SPH shifting or tensile
/// control.
fn finds_free_surface(case: &Case) -> bool {
    case.scheme.shifting != ShiftingChoice::None || case.scheme.tensile_control
}

/// Builds the model a case asks for, with physical constants already resolved.
///
/// The model types (every kernel × diffusion × viscosity, and δ-LES-SPH) are compiled
/// once, here, for 2D and 3D, by the two non-generic builders below: a generic call
/// would compile all of them again in every crate that starts a simulation (the solver,
/// the Python module and each test binary). `D` is 2 or 3 (checked by the case); the
/// casts through `Any` are resolved at compile time.
pub fn build_model<const D: usize>(case: &Case, physics: Physics<D>) -> Box<dyn Model<D>> {
    let physics: Box<dyn Any> = Box::new(physics);
    let model: Box<dyn Any> = match physics.downcast::<Physics<2>>() {
        Ok(physics) => Box::new(build_model_2d(case, *physics)),
        Err(physics) => Box::new(build_model_3d(
            case,
            *physics.downcast().expect("simulations are 2D or 3D"),
        )),
    };
    *model
        .downcast::<Box<dyn Model<D>>>()
        .expect("the model has the simulation's dimension")
}

/// [`build_model`] in 2D, compiled in this crate only.
fn build_model_2d(case: &Case, physics: Physics<2>) -> Box<dyn Model<2>> {
    build_model_of(case, physics)
}

/// [`build_model`] in 3D, compiled in this crate only.
fn build_model_3d(case: &Case, physics: Physics<3>) -> Box<dyn Model<3>> {
    build_model_of(case, physics)
}

fn build_model_of<const D: usize>(case: &Case, physics: Physics<D>) -> Box<dyn Model<D>> {
    let h = case.h();
    match case.particles.kernel {
        KernelChoice::WendlandC2 => with_kernel(case, physics, WendlandC2::new(h, D)),
        KernelChoice::WendlandC4 => with_kernel(case, physics, WendlandC4::new(h, D)),
        KernelChoice::CubicSpline => with_kernel(case, physics, CubicSpline::new(h, D)),
        KernelChoice::QuinticSpline => with_kernel(case, physics, QuinticSpline::new(h, D)),
        KernelChoice::Gaussian => with_kernel(case, physics, Gaussian::new(h, D)),
    }
}

fn with_kernel<const D: usize, K: Kernel>(
    case: &Case,
    physics: Physics<D>,
    kernel: K,
) -> Box<dyn Model<D>> {
    let s = &case.scheme;
    if s.turbulence == TurbulenceChoice::DeltaLes {
        let mu = match s.viscosity {
            ViscosityChoice::Physical => s.dynamic_viscosity.unwrap_or(0.0),
            _ => 0.0,
        };
        let budget = case.diagnostics.energy_budget;
        let les = LesScheme::new(
            kernel,
            les_constants(case, physics.eos.c0),
            physics,
            mu,
            budget,
        );
        return Box::new(les.with_free_surface(finds_free_surface(case)));
    }
    let delta = s.delta;
    match s.diffusion {
        DiffusionChoice::None => with_diffusion(case, physics, kernel, NoDiffusion),
        DiffusionChoice::MolteniColagrossi => {
            with_diffusion(case, physics, kernel, MolteniColagrossi { delta })
        }
        DiffusionChoice::Ferrari => with_diffusion(
            case,
            physics,
            kernel,
            Ferrari {
                delta,
                h: kernel.h(),
            },
        ),
        DiffusionChoice::DeltaSph => with_diffusion(case, physics, kernel, DeltaSph { delta }),
    }
}

fn with_diffusion<const D: usize, K: Kernel, Df: DensityDiffusion<D>>(
    case: &Case,
    physics: Physics<D>,
    kernel: K,
    diffusion: Df,
) -> Box<dyn Model<D>> {
    match viscosity_k(case, &physics) {
        None => finish(case, physics, kernel, diffusion, Inviscid),
        Some(k) => finish(case, physics, kernel, diffusion, Viscous { k }),
    }
}

fn finish<const D: usize, K: Kernel, Df: DensityDiffusion<D>, V: Viscosity>(
    case: &Case,
    physics: Physics<D>,
    kernel: K,
    diffusion: Df,
    viscosity: V,
) -> Box<dyn Model<D>> {
    let budget = case.diagnostics.energy_budget;
    let scheme = Scheme::new(kernel, diffusion, viscosity, physics, budget);
    Box::new(scheme.with_free_surface(finds_free_surface(case)))
}

/// The δ-LES-SPH constants of a case, defaults filled in (docs/theory.md §11): C_S = 0.12,
/// C_δ = 6, l = Δx, U_max = c0/10, shifting factor a = 8 (see [`les`]).
pub fn les_constants(case: &Case, c0: f64) -> les::Constants {
    let s = &case.scheme;
    let dx = case.particles.spacing;
    les::Constants {
        smagorinsky: s.smagorinsky_constant.unwrap_or(0.12),
        diffusion: s.diffusion_constant.unwrap_or(6.0),
        length: s.les_length.unwrap_or(dx),
        velocity: s.les_velocity.unwrap_or(0.1 * c0),
        shifting: s.les_shifting.unwrap_or(8.0),
        dx,
    }
}

/// The viscous constant K, or `None` when the case has no viscous term.
pub fn viscosity_k<const D: usize>(case: &Case, physics: &Physics<D>) -> Option<f64> {
    let s = &case.scheme;
    let k = match s.viscosity {
        ViscosityChoice::None => 0.0,
        ViscosityChoice::Artificial => {
            artificial_k(s.alpha(), case.h(), physics.eos.c0, physics.eos.rho0)
        }
        ViscosityChoice::Physical => physical_k(s.dynamic_viscosity.unwrap_or(0.0), D),
    };
    (k > 0.0).then_some(k)
}

/// 1 for no-slip walls, 0 for free-slip (see [`Physics::wall_viscous_weight`]).
pub fn wall_viscous_weight(walls: WallCondition) -> f64 {
    match walls {
        WallCondition::NoSlip => 1.0,
        WallCondition::FreeSlip => 0.0,
    }
}
