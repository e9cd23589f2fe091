//! A running simulation, the facade the CLI and Python drive: a [`State`] (particles
//! and clock) advanced by a [`Stepper`] (model, integrator, lists, step control, open
//! boundaries, body force, process split), watched by the case's time-series
//! observers ([`crate::diagnostics::series`]). `checkpoint` captures and restores
//! the state a step depends on; `split` runs it over several processes.

mod checkpoint;
mod cost;
mod measure;
mod probes;
mod split;
mod state;
mod stepper;

pub use crate::diagnostics::budget::EnergyBudget;
pub use checkpoint::Checkpoint;
pub use cost::{Cost, LONG_RUN};
pub use state::{Counters, State};
pub use stepper::Stepper;

use crate::boundary::bodies::{body_of, Body, Load};
use crate::boundary::open::OpenBoundaries;
use crate::case::{Case, ShiftingChoice};
use crate::diagnostics::series::{observers, Observer};
use crate::diagnostics::{self, Energies};
use crate::distributed::{owns_fluid, Ranks};
use crate::domain::Domain;
use crate::error::{Result, SphError};
use crate::forcing::Forcing;
use crate::geometry;
use crate::motion::{rigid::Pose, Motions};
use crate::particles::{Kind, Particles, Vector};
use crate::physics::free_surface::FreeSurface;
use crate::physics::viscosity::equivalent_nu;
use crate::scheme::model::{Physics, Rates};
use crate::scheme::resolve::{build_model, viscosity_k, wall_viscous_weight};
use crate::time::step_size::TimeStepControl;
use rayon::prelude::*;

/// A running case; its state is read through methods and changed by stepping (or by
/// [`Simulation::edit`], which keeps what depends on it consistent).
pub struct Simulation<const D: usize> {
    case: Case,
    state: State<D>,
    stepper: Stepper<D>,
    /// The energy budget, when the case asks for it.
    budget: Option<EnergyBudget>,
    /// The tanks and walls of the case, in case order (tanks first).
    bodies: Vec<Body>,
    /// The solids of the `[[shape]]` walls, for [`Self::wall_crossings`].
    wall_solids: Vec<(usize, geometry::solid::Solid)>,
    /// The time-series columns, in order.
    observers: Vec<Box<dyn Observer<D>>>,
    /// On process 0 of a split run: the whole run, gathered for output ([`Self::view`]).
    view: Option<Box<Simulation<D>>>,
}

impl<const D: usize> Simulation<D> {
    /// Builds particles and scheme from a case, which is validated first (a case built
    /// in code, or from Python, gets the checks of a case file), and refused before
    /// anything is built if it would not fit the machine's memory.
    pub fn new(case: Case) -> Result<Self> {
        case.validate()?;
        case.check_memory(1)?;
        let mut sim = Self::assemble(case)?;
        sim.stepper.rebuild(&mut sim.state, 0.0);
        sim.state_changed();
        Ok(sim)
    }

    /// The particles and scheme of a validated case, before the first list build.
    fn assemble(case: Case) -> Result<Self> {
        case.validate()?;
        let mut setup = geometry::build::<D>(&case)?;
        let physics = Physics {
            eos: setup.eos,
            gravity: setup.gravity,
            wall_viscous_weight: wall_viscous_weight(case.scheme.walls),
        };
        let k = viscosity_k(&case, &physics).unwrap_or(0.0);
        let control = TimeStepControl {
            cfl: case.scheme.cfl(),
            viscous_cfl: case.scheme.viscous_cfl(),
            diffusion_cfl: case.scheme.diffusion_cfl(),
            force_cfl: case.scheme.force_cfl,
            h: case.h(),
            c0: setup.eos.c0,
            nu: equivalent_nu(k, D, setup.eos.rho0),
        };
        let model = build_model::<D>(&case, physics);
        let shifts = case.scheme.shifting == ShiftingChoice::DeltaPlus;
        setup.particles.keep_shift_velocity(shifts);
        check_inflow_speeds(&case, setup.eos.c0)?;
        let open = OpenBoundaries::of(&case, &setup.particles, &setup.domain, &setup.eos)?;
        let forcing = Forcing::of(&case, &setup.particles)?;
        let motions = Motions::of(
            &case,
            &setup.bodies,
            &setup.particles,
            &setup.domain,
            &setup.wall_solids,
        )?;
        if let Some(motions) = &motions {
            setup.particles.keep_wall_acceleration(true);
            motions.place(&mut setup.particles, 0.0, &setup.domain);
        }
        let mut stepper = Stepper::new(&case, model, control, setup.domain, open, forcing, motions);
        (stepper.notices).extend(setup.off_lattice_notice(case.dx(), case.support()));
        Ok(Self {
            budget: case.diagnostics.energy_budget.then(EnergyBudget::default),
            observers: observers(&case, &setup.bodies),
            bodies: setup.bodies,
            wall_solids: setup.wall_solids,
            case,
            state: State {
                particles: setup.particles,
                ..Default::default()
            },
            stepper,
            view: None,
        })
    }

    pub fn case(&self) -> &Case {
        &self.case
    }

    /// The particles and clock of the run.
    pub fn state(&self) -> &State<D> {
        &self.state
    }

    /// The case's inflow and outflow buffers, if it has any.
    pub fn open_boundaries(&self) -> Option<&OpenBoundaries<D>> {
        self.stepper.open.as_ref()
    }

    /// Moves the end time (`time.end`) to `end`, as the command line's `--until` does.
    /// Only the length of the last step depends on it.
    pub fn set_end(&mut self, end: f64) -> Result<()> {
        if !(end.is_finite() && end > self.state.time) {
            return Err(SphError::invalid(
                "until",
                end,
                format!("a time after the simulation's, t = {} s", self.state.time),
            ));
        }
        self.case.time.end = end;
        Ok(())
    }

    /// Sets the snapshot interval (`time.output_interval`, s; 0: snapshots only at the
    /// start and the end). The steps do not depend on it.
    pub fn set_output_interval(&mut self, every: f64) -> Result<()> {
        if !(every.is_finite() && every >= 0.0) {
            return Err(SphError::invalid(
                "output_interval",
                every,
                "a snapshot interval of 0 s or more",
            ));
        }
        self.case.time.output_interval = every;
        Ok(())
    }

    /// The particles in their current storage order (`id` names each one).
    pub fn particles(&self) -> &Particles<D> {
        &self.state.particles
    }

    pub fn domain(&self) -> &Domain<D> {
        &self.stepper.domain
    }

    /// Simulated time \[s\].
    pub fn time(&self) -> f64 {
        self.state.time
    }

    /// The last step \[s\] (0 before the first).
    pub fn dt(&self) -> f64 {
        self.state.dt
    }

    pub fn counters(&self) -> Counters {
        self.state.counters
    }

    /// The energy budget, when the case asks for it.
    pub fn budget(&self) -> Option<EnergyBudget> {
        self.budget
    }

    /// δr/Δt of the last shift, when the case shifts particles.
    pub fn shift_velocity(&self) -> Option<&[Vector<D>]> {
        self.state.particles.shift_velocity.as_deref()
    }

    /// Edits the particles from outside the stepping (a front end setting velocities
    /// or densities, a test placing particles), then rebuilds the lists and re-derives
    /// what depends on the state ([`Self::state_changed`]).
    pub fn edit(&mut self, f: impl FnOnce(&mut Particles<D>)) {
        f(&mut self.state.particles);
        self.state.particles.fit_columns();
        let domain = self.stepper.domain;
        (self.state.particles.x.iter_mut()).for_each(|x| domain.wrap(x));
        let reach = (self.stepper).reach(self.stepper.max_speed(&self.state.particles));
        self.stepper.rebuild(&mut self.state, reach);
        self.state_changed();
    }

    pub fn physics(&self) -> &Physics<D> {
        self.stepper.model.physics()
    }

    pub fn time_step_control(&self) -> &TimeStepControl {
        &self.stepper.control
    }

    /// Mean neighbours per particle (fluid and walls): in the lists, and in the rows
    /// the last step used.
    pub fn mean_neighbours(&self) -> (f64, f64) {
        self.stepper.list.mean_neighbours()
    }

    /// The largest of `value` over the processes of a split run (`value` itself when
    /// the run is not split). Collective.
    pub fn max_over_processes(&self, value: f64) -> f64 {
        self.stepper.global_max(value)
    }

    /// This process's share of a split run (`None` when the run is not split).
    pub fn ranks(&self) -> Option<&Ranks<D>> {
        self.stepper.ranks.as_ref()
    }

    /// Re-derives what depends on the state after it was set from outside the stepping
    /// (construction, or velocities and densities edited by a front end): pressures, the
    /// acceleration that sizes the list skin and the energy-budget powers.
    pub fn state_changed(&mut self) {
        (self.stepper).state_changed(&mut self.state, self.budget.as_mut());
    }

    /// The rates `dρ/dt` (without and with diffusion) and `du/dt` at the current state,
    /// in the current particle order.
    pub fn rates(&mut self) -> Rates<D> {
        self.stepper.rates(&mut self.state)
    }

    /// Advances one step, shortened to land on the case's end time when it would pass it.
    /// On blow-up returns [`SphError::Unstable`] and leaves the (non-finite or runaway)
    /// state in place for a final snapshot.
    pub fn step(&mut self) -> Result<()> {
        self.step_until(self.case.time.end)
    }

    /// Advances one step, shortened to land on `limit` when it would pass it.
    ///
    /// The step runs on a thread of the Rayon pool, so that its parallel loops start
    /// from inside the pool instead of each waking it from outside.
    pub fn step_until(&mut self, limit: f64) -> Result<()> {
        let (stepper, state, budget) = (&mut self.stepper, &mut self.state, self.budget.as_mut());
        rayon::scope(|_| stepper.advance_to(state, budget, limit))?;
        self.absorb_reflections()
    }

    /// Gives the absorbing wave makers their gauges' readings at the step's end and
    /// places their paddles with the corrected velocity (see
    /// [`crate::waves::active_absorption`]).
    fn absorb_reflections(&mut self) -> Result<()> {
        let Some(lines) = (self.motions())
            .map(|m| m.absorbing_lines())
            .filter(|l| !l.is_empty())
        else {
            return Ok(());
        };
        let elevations = self.wave_elevations(&lines)?;
        let (t, domain) = (self.state.time, self.stepper.domain);
        if let Some(motions) = self.stepper.motions.as_mut() {
            motions.absorb(t, &elevations);
            motions.place(&mut self.state.particles, t, &domain);
        }
        Ok(())
    }

    /// Why the energy budget of this case does not close, when it does not: terms that
    /// change the energy without a power term in the budget (empty when it closes).
    pub fn budget_caveats(&self) -> Vec<&'static str> {
        let case = &self.case;
        let mut why = Vec::new();
        if case.scheme.walls == crate::case::WallCondition::NoSlip {
            why.push("the no-slip wall term makes P_V not sign-definite");
        }
        if self.shift_velocity().is_some() {
            why.push("particle shifting moves particles without a power term");
        }
        if case.scheme.tensile_control {
            why.push("tensile instability control is not energy-conserving");
        }
        if case.scheme.turbulence == crate::case::TurbulenceChoice::DeltaLes {
            why.push("δ-LES-SPH's shifting velocity δu moves particles without a power term");
        }
        if self.stepper.open.is_some() {
            why.push("open boundaries set the buffers' state and add fluid without a flux term");
        }
        let g = self.physics().gravity;
        if (0..D).any(|d| self.domain().is_periodic(d) && g[d] != 0.0) {
            why.push("gravity along a periodic axis: E_p jumps when particles wrap");
        }
        why
    }

    /// Fluid particles removed so far because they left the domain (by all processes
    /// of a split run; collective there).
    pub fn removed(&self) -> u64 {
        let removed = self.state.counters.removed;
        let Some(ranks) = self.ranks() else {
            return removed;
        };
        let mut removed = [removed as f64];
        ranks.sum(&mut removed);
        removed[0] as u64
    }

    /// The mass \[kg\] of the fluid removed so far because it left the domain (per unit
    /// depth in 2D; over all processes of a split run, collective there).
    pub fn removed_mass(&self) -> f64 {
        let mut mass = [self.state.counters.removed_mass];
        if let Some(ranks) = self.ranks() {
            ranks.sum(&mut mass);
        }
        mass[0]
    }

    /// Messages for the user, in the order they arose (this process's, in a split
    /// run): fluid that starts off the walls' lattice (closer than 0.9 Δx to a wall),
    /// and the first removal of fluid by a default domain (one that no `[domain]`
    /// table set), with the count, the mass and where.
    pub fn notices(&self) -> &[String] {
        &self.stepper.notices
    }

    /// The tanks and walls of the case, in case order (tanks first).
    pub fn bodies(&self) -> &[Body] {
        &self.bodies
    }

    /// The fluid's load on each body at the current state, as in [`Self::bodies`]
    /// (see [`crate::boundary::bodies`]); refreshes the pressures.
    pub fn loads(&mut self) -> Vec<Load<D>> {
        let owned = self.ranks().map(|r| r.owned());
        let p = &self.state.particles;
        let body: Vec<Option<usize>> = (0..p.len())
            .into_par_iter()
            .map(|i| {
                let (id, kind) = (p.id[i], p.kind[i]);
                // a split run's walls count on the process that owns them
                let own = owned.is_none_or(|o| o[i]);
                (kind == Kind::Wall && own)
                    .then(|| body_of(&self.bodies, id))
                    .flatten()
            })
            .collect();
        let point = self.case.moment_point();
        let centre = Vector::<D>::from_fn(|d, _| point[d]);
        let s = &mut self.stepper;
        let loads = s.model.wall_loads(
            &mut self.state.particles,
            &s.list,
            &s.domain,
            &body,
            self.bodies.len(),
            &centre,
        );
        match self.ranks() {
            Some(ranks) => summed_loads(ranks, loads),
            None => loads,
        }
    }

    /// Brings pressures (fluid and walls) up to date with the current state. Call
    /// before writing output or reading pressure after steps. It changes nothing the
    /// next step depends on, so a run gives the same bits whether or not it is called.
    pub fn sync_pressure(&mut self) {
        let s = &mut self.stepper;
        (s.model).update_pressure_field(&mut self.state.particles, &s.list, &s.domain);
    }

    /// E_k, E_p and E_c of the fluid (of the whole run when it is split; collective).
    pub fn energies(&self) -> Energies {
        let ph = self.physics();
        let p = &self.state.particles;
        let Some(ranks) = self.ranks() else {
            return diagnostics::energies(p, &ph.eos, &ph.gravity);
        };
        let own = |i| owns_fluid(Some(ranks), p, i);
        let e = diagnostics::energies_of(p, own, &ph.eos, &ph.gravity);
        let mut sums = [e.kinetic, e.potential, e.internal];
        ranks.sum(&mut sums);
        let [kinetic, potential, internal] = sums;
        Energies {
            kinetic,
            potential,
            internal,
        }
    }

    /// Largest `|ρ/ρ0 - 1|` over the fluid (of the whole run; collective when split).
    pub fn max_density_variation(&self) -> f64 {
        let rho0 = self.physics().eos.rho0;
        let local = diagnostics::max_density_variation(&self.state.particles, rho0);
        self.max_over_processes(local)
    }

    /// The pose of every moving body now, in case order (none without moving bodies).
    pub fn body_poses(&self) -> Vec<Pose<D>> {
        (self.stepper.motions.as_ref()).map_or(Vec::new(), |m| m.poses(self.state.time))
    }

    /// The moving bodies, when the case has any.
    pub fn motions(&self) -> Option<&Motions<D>> {
        self.stepper.motions.as_ref()
    }

    /// The names of the moving bodies, in the order of [`Self::body_poses`].
    pub fn moving_body_names(&self) -> Vec<String> {
        crate::motion::moving_names(&self.case, &self.bodies)
    }

    /// Free-surface flags, normals and `λ` (Marrone et al. 2010), in the current order.
    pub fn free_surface(&self) -> FreeSurface<D> {
        self.stepper.free_surface(&self.state.particles)
    }

    /// Fluid particles inside a wall now (see [`diagnostics::wall_crossings`]).
    pub fn wall_crossings(&self) -> usize {
        diagnostics::wall_crossings(&self.case, &self.wall_solids, &self.state.particles)
    }

    /// Largest fluid coordinate along `axis` (of the whole run; collective when split).
    pub fn surge_front(&self, axis: usize) -> f64 {
        self.max_over_processes(diagnostics::surge_front(&self.state.particles, axis))
    }

    pub fn n_fluid(&self) -> usize {
        self.state.particles.n_fluid()
    }
}

/// `loads` of this process's walls summed over the processes, body by body.
fn summed_loads<const D: usize>(ranks: &Ranks<D>, loads: Vec<Load<D>>) -> Vec<Load<D>> {
    let mut flat: Vec<f64> = (loads.iter())
        .flat_map(|l| {
            l.pressure
                .iter()
                .chain(l.viscous.iter())
                .chain(l.moment.iter())
                .copied()
                .collect::<Vec<_>>()
        })
        .collect();
    ranks.sum(&mut flat);
    flat.chunks(2 * D + 3)
        .map(|c| Load {
            pressure: Vector::from_fn(|d, _| c[d]),
            viscous: Vector::from_fn(|d, _| c[D + d]),
            moment: nalgebra::Vector3::new(c[2 * D], c[2 * D + 1], c[2 * D + 2]),
        })
        .collect()
}

/// Inflow speeds within the weakly compressible limit, |U| ≤ c0/10 (Mach 0.1, density
/// variations of about 1%).
fn check_inflow_speeds(case: &Case, c0: f64) -> Result<()> {
    for (k, b) in case.open_boundary.iter().enumerate() {
        let speed = b
            .velocity
            .iter()
            .flatten()
            .map(|v| v * v)
            .sum::<f64>()
            .sqrt();
        if speed > 0.1 * c0 {
            return Err(SphError::invalid(
                format!("open_boundary[{k}].velocity"),
                format!("{:?}", b.velocity.as_deref().unwrap_or_default()),
                format!(
                    "an inflow speed of at most c0/10 = {:.4} m/s (Mach 0.1; raise \
                     fluid.sound_speed or fluid.max_velocity)",
                    0.1 * c0
                ),
            ));
        }
    }
    Ok(())
}
