//! What the stepper, the integrators and the diagnostics ask of a resolved scheme: the
//! object-safe [`Model`] trait (its methods run once per evaluation, never per pair),
//! the rates it fills ([`Rates`]), its dissipated powers ([`Powers`]) and physical
//! constants ([`Physics`]), and the pressure helpers both schemes share. The schemes
//! are [`crate::scheme::delta_sph::Scheme`] and [`crate::scheme::les::LesScheme`].

use crate::boundary::bodies::Load;
use crate::boundary::open::OpenBoundaries;
use crate::domain::Domain;
use crate::neighbours::NeighbourList;
use crate::particles::{Kind, Particles, Vector};
use crate::physics::eos::LinearEos;
use crate::physics::free_surface::FreeSurface;
use crate::physics::kernel::Smoothing;
use crate::physics::shifting::Shift;
use rayon::prelude::*;

/// Time derivatives of the particle state. `dx/dt = u` is not stored.
#[derive(Debug, Clone, Default)]
pub struct Rates<const D: usize> {
    /// Continuity without diffusion, `Q_ρ`.
    pub drho: Vec<f64>,
    /// Diffusive part `δ h c0 D_i` (zero when diffusion was not evaluated).
    pub drho_diff: Vec<f64>,
    /// Acceleration.
    pub du: Vec<Vector<D>>,
    /// The shifting velocity δu that carries particles besides u (`dx/dt = u + δu`) in
    /// quasi-Lagrangian schemes (δ-LES-SPH); empty in the others.
    pub drift: Vec<Vector<D>>,
}

impl<const D: usize> Rates<D> {
    pub fn resize(&mut self, n: usize) {
        self.drho.resize(n, 0.0);
        self.drho_diff.resize(n, 0.0);
        self.du.resize(n, Vector::zeros());
    }

    /// The transport velocity of particle i besides its own velocity: δu, or zero.
    #[inline(always)]
    pub fn drift(&self, i: usize) -> Vector<D> {
        self.drift.get(i).copied().unwrap_or_else(Vector::zeros)
    }

    /// Largest acceleration magnitude, over the particles `owned` flags when given
    /// (a split run's own particles; its halo's rates are not all complete).
    pub fn max_acceleration(&self, owned: Option<&[bool]>) -> f64 {
        let own = |i: usize| owned.is_none_or(|o| o[i]);
        (self.du.par_iter().enumerate())
            .filter(|(i, _)| own(*i))
            .map(|(_, a)| a.norm_squared())
            .reduce(|| 0.0, f64::max)
            .sqrt()
    }
}

/// Rates of change of the mechanical energy of the fluid and the free bodies
/// (docs/theory.md §10). Wall pairs count at the velocity relative to the wall
/// (`u_iw = u_i - u_w`), and what a moving wall's own velocity carries is `moving`.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Powers {
    /// Viscous power `P_V = Σ m_i (u_i · (du_i/dt)_visc - Σ_w u_w · f^visc_iw)`, never
    /// positive with walls at rest.
    pub viscous: f64,
    /// Diffusive power `P_D = Σ m_i (p_i/ρ_i²) δ h c0 D_i`.
    pub diffusive: f64,
    /// Power exchanged with the dummy walls, `P_W = -Σ_i Σ_w V_i V_w p_w u_iw·∇_iW_iw`.
    /// The extrapolated wall pressure is not derived from an energy, so the walls store
    /// and return energy like springs; the balance closes only with this term.
    pub wall: f64,
    /// Power the moving walls deliver to the fluid, `P_M = Σ_i Σ_w F_iw·u_w` with
    /// `F_iw` the wall pair's force on fluid particle i, pressure and viscous
    /// (`-V_i V_w (p_w + p_i) ∇_iW_iw` and the no-slip term): zero with walls at rest.
    pub moving: f64,
    /// Power the fluid and the dampers deliver to the free bodies,
    /// `P_B = Σ_b (F_b·V_b + M_b·Ω_b) - Σ c (dL/dt)²`, filled in by the stepper (the
    /// scheme leaves it zero).
    pub bodies: f64,
    /// Power of the body force and the absorbers on the fluid,
    /// `P_F = Σ_i m_i u_i·f_i` with `f_i` the acceleration they add (an absorber's
    /// `-β w u_i` takes energy out), filled in by the stepper.
    pub forcing: f64,
}

impl Powers {
    pub fn total(&self) -> f64 {
        self.viscous + self.diffusive + self.wall + self.moving + self.bodies + self.forcing
    }
}

/// Physical constants every scheme shares.
#[derive(Debug, Clone, Copy)]
pub struct Physics<const D: usize> {
    pub eos: LinearEos,
    pub gravity: Vector<D>,
    /// 1 for no-slip walls (mirrored velocity in the viscous term), 0 for free-slip.
    pub wall_viscous_weight: f64,
}

/// The largest diffusivities [m²/s] a scheme adds to the case's viscosity.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Diffusivities {
    /// Of the momentum equation, the case's viscosity included (δ-LES-SPH: `ν + ν_T`).
    pub momentum: f64,
    /// Of the continuity equation (δ-LES-SPH: `ν_δ`).
    pub density: f64,
}

/// What the integrators and diagnostics need from a resolved scheme.
pub trait Model<const D: usize>: Send + Sync {
    /// Fills `rates` at the current state: pressure from the EOS, wall extrapolation,
    /// the δ-SPH gradient pre-pass (only if the diffusion needs it, `with_diffusion`, and
    /// the [`Model::shift`] just before did not compute the gradient),
    /// then the pair loop. `rates.drho_diff` is written only when `with_diffusion`, and
    /// so are the powers of the energy budget when the scheme carries one.
    fn evaluate(
        &mut self,
        particles: &mut Particles<D>,
        list: &NeighbourList<D>,
        domain: &Domain<D>,
        rates: &mut Rates<D>,
        with_diffusion: bool,
    );
    /// Pressure of the fluid (EOS) and of the walls (extrapolated) at the current
    /// state, without the pair loop: what output and probes need.
    fn update_pressure_field(
        &self,
        particles: &mut Particles<D>,
        list: &NeighbourList<D>,
        domain: &Domain<D>,
    );
    /// Free-surface detection (Marrone et al. 2010) at the current state.
    fn free_surface(
        &self,
        particles: &Particles<D>,
        list: &NeighbourList<D>,
        domain: &Domain<D>,
    ) -> FreeSurface<D>;
    /// Sets the particles (current order) where tensile instability control applies, or
    /// `None` to switch it off.
    fn set_tensile_control(&mut self, interior: Option<Vec<bool>>);
    /// δ+-SPH shifting displacements and the free surface at the current state (see
    /// [`crate::physics::shifting`]), `cfl_ma = U_max Δt/h`. When the diffusion needs
    /// δ-SPH's density gradient, the same pass computes it (pressures and walls refreshed
    /// first), and the next evaluation uses it instead of a pre-pass of its own.
    fn shift(
        &mut self,
        particles: &mut Particles<D>,
        list: &NeighbourList<D>,
        domain: &Domain<D>,
        dx: f64,
        cfl_ma: f64,
    ) -> Shift<D>;
    /// The viscous, diffusive and wall powers at the state of the last evaluation with
    /// diffusion (the first of each step), computed in its pair loop; `None` unless the
    /// scheme was built with the energy budget.
    fn last_powers(&self) -> Option<Powers>;
    /// The load of the fluid on each body at the current state (pressures and volumes
    /// refreshed first, as an evaluation does): minus the wall terms of the momentum
    /// equation, see [`crate::boundary::bodies`]. `body[j]` is the body of particle j
    /// (`None` for fluid), `centre` the moment point.
    fn wall_loads(
        &mut self,
        particles: &mut Particles<D>,
        list: &NeighbourList<D>,
        domain: &Domain<D>,
        body: &[Option<usize>],
        bodies: usize,
        centre: &Vector<D>,
    ) -> Vec<Load<D>>;
    /// Kernel value `W(r)`.
    fn w(&self, r: f64) -> f64;
    /// Sets the open boundaries' buffer particles before an evaluation at time `t`
    /// ([`OpenBoundaries::prepare`], with this model's kernel).
    fn prepare_open(
        &self,
        open: &OpenBoundaries<D>,
        particles: &mut Particles<D>,
        list: &NeighbourList<D>,
        domain: &Domain<D>,
        t: f64,
    );
    /// Kernel support radius R.
    fn support_radius(&self) -> f64;
    /// Whether any density diffusion is active.
    fn has_diffusion(&self) -> bool;
    /// The neighbour passes chained within an evaluation or a step's start, each
    /// reading the last one's results at its neighbours (see [`chained_passes`]): a
    /// split run's halo is this many list radii deep.
    fn neighbour_passes(&self) -> usize;
    fn physics(&self) -> &Physics<D>;
    /// The largest momentum diffusivity (the case's viscosity plus an eddy viscosity)
    /// and density diffusivity (a diffusion coefficient) of the last evaluation, for
    /// the limits of Δt; zero when the scheme adds none.
    fn diffusivities(&self) -> Diffusivities {
        Diffusivities::default()
    }
}

impl<const D: usize> Smoothing for dyn Model<D> + '_ {
    fn w(&self, r: f64) -> f64 {
        Model::w(self, r)
    }
    fn support_radius(&self) -> f64 {
        Model::support_radius(self)
    }
}

/// The neighbour passes a scheme chains: the wall extrapolation or the δ-SPH
/// gradient (δ-LES-SPH: the velocity and density gradients), then the pair loop;
/// with shifting or tensile control (`free_surface`), the free surface's
/// moments, scan region and surface neighbours add one more radius. One pass fewer
/// leaves a split dam break 1e-6 away from the serial run after 200 steps; with these
/// it agrees to round-off (`crates/sph-cli/tests/mpi/main.rs`).
pub fn chained_passes(free_surface: bool) -> usize {
    2 + usize::from(free_surface)
}

/// Fluid pressure from the EOS and every particle's volume `m/ρ` into `volume`.
pub(crate) fn pressure_and_volume<const D: usize>(
    particles: &mut Particles<D>,
    eos: &LinearEos,
    volume: &mut Vec<f64>,
) {
    fluid_pressure(particles, eos);
    volume.resize(particles.len(), 0.0);
    volume
        .par_iter_mut()
        .zip(particles.mass.par_iter())
        .zip(particles.rho.par_iter())
        .for_each(|((v, &m), &rho)| *v = m / rho);
}

/// The p_i of fluid particle i in its pair terms. Tensile instability control (Sun et
/// al. 2018, docs/theory.md §9): where `interior` is given, an interior particle in tension
/// takes (p_j - p_i) instead of (p_j + p_i). Decided once per particle.
#[inline(always)]
pub(crate) fn tensile_pressure(interior: Option<&[bool]>, i: usize, pi: f64) -> f64 {
    match interior {
        Some(interior) if pi < 0.0 && interior[i] => -pi,
        _ => pi,
    }
}

/// `p_i = p(ρ_i)` for every fluid particle.
pub(crate) fn fluid_pressure<const D: usize>(particles: &mut Particles<D>, eos: &LinearEos) {
    particles
        .p
        .par_iter_mut()
        .zip(particles.rho.par_iter())
        .zip(particles.kind.par_iter())
        .for_each(|((p, &rho), &kind)| {
            if kind == Kind::Fluid {
                *p = eos.pressure(rho);
            }
        });
}

impl Powers {
    pub(crate) fn add(self, other: Self) -> Self {
        Self {
            viscous: self.viscous + other.viscous,
            diffusive: self.diffusive + other.diffusive,
            wall: self.wall + other.wall,
            moving: self.moving + other.moving,
            bodies: self.bodies + other.bodies,
            forcing: self.forcing + other.forcing,
        }
    }
}

/// The [`Model`] methods every kernel scheme answers alike from its fields `kernel`,
/// `physics`, `interior` (tensile control), `powers` (the last budget powers) and
/// `free_surface` (whether it detects the surface): expanded inside each scheme's
/// `impl Model`, so that they are written once.
macro_rules! kernel_model_methods {
    () => {
        fn free_surface(
            &self,
            particles: &$crate::particles::Particles<D>,
            list: &$crate::neighbours::NeighbourList<D>,
            domain: &$crate::domain::Domain<D>,
        ) -> $crate::physics::free_surface::FreeSurface<D> {
            $crate::physics::free_surface::detect(&self.kernel, particles, list, domain)
        }

        fn set_tensile_control(&mut self, interior: Option<Vec<bool>>) {
            self.interior = interior;
        }

        fn last_powers(&self) -> Option<$crate::scheme::Powers> {
            self.powers
        }

        fn w(&self, r: f64) -> f64 {
            self.kernel.w(r)
        }

        fn prepare_open(
            &self,
            open: &$crate::boundary::open::OpenBoundaries<D>,
            particles: &mut $crate::particles::Particles<D>,
            list: &$crate::neighbours::NeighbourList<D>,
            domain: &$crate::domain::Domain<D>,
            t: f64,
        ) {
            open.prepare(particles, list, domain, &self.kernel, t);
        }

        fn support_radius(&self) -> f64 {
            self.kernel.radius()
        }

        fn neighbour_passes(&self) -> usize {
            $crate::scheme::model::chained_passes(self.free_surface)
        }

        fn physics(&self) -> &$crate::scheme::Physics<D> {
            &self.physics
        }
    };
}
pub(crate) use kernel_model_methods;
