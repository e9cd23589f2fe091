//! A running simulation: particles, neighbour lists, the resolved scheme and the
//! integrator, advanced step by step. The CLI (and any other front) drives this type;
//! [`checkpoint`] captures and restores its state, [`series`] gives its time-series
//! rows.

mod checkpoint;
mod series;
mod split;

pub use checkpoint::Checkpoint;

use crate::boundary::bodies::{body_of, Body, Load};
use crate::boundary::open::OpenBoundaries;
use crate::case::{Case, IntegratorChoice, ShiftingChoice};
use crate::diagnostics::sensors::Sensor;
use crate::diagnostics::{self, Energies};
use crate::distributed::{owns_fluid, Ranks};
use crate::domain::Domain;
use crate::error::{Result, SphError};
use crate::forcing::BodyForce;
use crate::geometry;
use crate::neighbours::NeighbourList;
use crate::particles::{Kind, Particles, Vector};
use crate::physics::free_surface::FreeSurface;
use crate::physics::viscosity::equivalent_nu;
use crate::scheme::model::{Model, Physics, Powers, Rates};
use crate::scheme::resolve::{build_model, viscosity_k, wall_viscous_weight};
use crate::time::integrator::{Context, Rk4, Symplectic, TimeIntegrator};
use crate::time::step_size::TimeStepControl;
use rayon::prelude::*;

/// The smallest skin of the neighbour lists, as a fraction of the kernel support.
const MIN_SKIN: f64 = 0.1;

/// The skin is sized to this many times the reach of a step, so that the lists last
/// a few steps (the steps cull them to what they use).
const SKIN_OVER_REACH: f64 = 6.0;

/// Counters for throughput reports.
#[derive(Debug, Clone, Copy, Default)]
pub struct Counters {
    pub steps: u64,
    pub evaluations: u64,
    pub rebuilds: u64,
    /// Fluid particles removed because they left the domain.
    pub removed: u64,
    /// Fluid particles created at inlets.
    pub created: u64,
}

/// The running energy budget of SCHEME.md §10 (only when the case asks for it):
/// `E_k + E_p + E_c + removed_energy - work()` stays at its initial value.
///
/// The powers come from the first evaluation of each step (at its start state), so
/// the trapezoidal rule closes an interval at the start of the next step; until then
/// the last step counts by its left rectangle, `pending · P(start)`.
#[derive(Debug, Clone, Copy, Default)]
pub struct EnergyBudget {
    /// `∫ (P_V + P_D + P_W) dt` by the trapezoidal rule up to the start of the last step.
    pub dissipated: f64,
    /// `E_k + E_p + E_c` the removed particles carried out of the domain.
    pub removed_energy: f64,
    /// The powers at the start of the last step.
    pub last: Powers,
    /// The length of the last step, whose closing power is not known yet (0 before the
    /// first step).
    pub pending: f64,
}

impl EnergyBudget {
    /// `∫ (P_V + P_D + P_W) dt` through the end of the last step.
    pub fn work(&self) -> f64 {
        self.dissipated + self.pending * self.last.total()
    }

    /// Closes the pending interval with the powers `now` at the start of a step.
    fn advance(&mut self, now: Powers) {
        self.dissipated += 0.5 * self.pending * (self.last.total() + now.total());
        self.last = now;
        self.pending = 0.0;
    }
}

/// A running case; its state is read through methods and changed by stepping (or by
/// [`Simulation::edit`], which keeps what depends on it consistent).
pub struct Simulation<const D: usize> {
    case: Case,
    particles: Particles<D>,
    domain: Domain<D>,
    time: f64,
    dt: f64,
    counters: Counters,
    budget: Option<EnergyBudget>,
    /// δr/Δt of the last shift, when the case shifts particles (δ+-SPH).
    shift_velocity: Option<Vec<Vector<D>>>,
    model: Box<dyn Model<D>>,
    integrator: Box<dyn TimeIntegrator<D>>,
    list: NeighbourList<D>,
    control: TimeStepControl,
    max_skin: f64,
    last_acceleration: f64,
    bodies: Vec<Body>,
    /// The face sensors of the series, with their filters' state.
    sensors: Vec<Sensor<D>>,
    /// Inflow and outflow buffers, when the case has any.
    open: Option<OpenBoundaries<D>>,
    /// The body force besides gravity, when the case has one.
    forcing: Option<BodyForce<D>>,
    /// This process's share of a run split over several ([`Self::distribute`]).
    ranks: Option<Ranks<D>>,
    /// On process 0 of a split run: the whole run, gathered for output ([`Self::view`]).
    view: Option<Box<Simulation<D>>>,
}

impl<const D: usize> Simulation<D> {
    /// Builds particles and scheme from a case, which is validated first (a case built
    /// in code, or from Python, gets the checks of a case file).
    pub fn new(case: Case) -> Result<Self> {
        let mut sim = Self::assemble(case)?;
        sim.rebuild(0.0);
        sim.state_changed();
        Ok(sim)
    }

    /// The particles and scheme of a validated case, before the first list build.
    fn assemble(case: Case) -> Result<Self> {
        case.validate()?;
        let setup = geometry::build::<D>(&case)?;
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
        let integrator: Box<dyn TimeIntegrator<D>> = match case.scheme.integrator {
            IntegratorChoice::Rk4 => Box::<Rk4<D>>::default(),
            IntegratorChoice::Symplectic => Box::<Symplectic<D>>::default(),
        };
        // minimum image is unique while the list radius stays below half of every period
        let support = model.support_radius();
        let max_skin = (0..D)
            .filter(|&d| setup.domain.is_periodic(d))
            .map(|d| (0.5 * setup.domain.period[d] - support) * (1.0 - 1e-9))
            .fold(f64::INFINITY, f64::min);
        let budget = case.diagnostics.energy_budget.then(EnergyBudget::default);
        let shift_velocity = (case.scheme.shifting == ShiftingChoice::DeltaPlus)
            .then(|| vec![Vector::zeros(); setup.particles.len()]);
        let sensors = (case.diagnostics.sensors.iter())
            .map(|s| Sensor::new(s, case.dx(), case.series_interval()))
            .collect();
        check_inflow_speeds(&case, setup.eos.c0)?;
        let open = OpenBoundaries::of(&case, &setup.particles, &setup.domain, &setup.eos)?;
        let forcing = BodyForce::of(&case, &setup.particles)?;
        Ok(Self {
            case,
            particles: setup.particles,
            domain: setup.domain,
            time: 0.0,
            dt: 0.0,
            counters: Counters::default(),
            budget,
            shift_velocity,
            model,
            integrator,
            list: NeighbourList::default(),
            control,
            max_skin,
            last_acceleration: 0.0,
            bodies: setup.bodies,
            sensors,
            open,
            forcing,
            ranks: None,
            view: None,
        })
    }

    pub fn case(&self) -> &Case {
        &self.case
    }

    /// The case's inflow and outflow buffers, if it has any.
    pub fn open_boundaries(&self) -> Option<&OpenBoundaries<D>> {
        self.open.as_ref()
    }

    /// Moves the end time (`time.end`) to `end`, as the command line's `--until` does.
    /// Only the length of the last step depends on it.
    pub fn set_end(&mut self, end: f64) -> Result<()> {
        if !(end.is_finite() && end > self.time) {
            return Err(SphError::invalid(
                "until",
                end,
                format!("a time after the simulation's, t = {} s", self.time),
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
        &self.particles
    }

    pub fn domain(&self) -> &Domain<D> {
        &self.domain
    }

    /// Simulated time [s].
    pub fn time(&self) -> f64 {
        self.time
    }

    /// The last step [s] (0 before the first).
    pub fn dt(&self) -> f64 {
        self.dt
    }

    pub fn counters(&self) -> Counters {
        self.counters
    }

    /// The energy budget, when the case asks for it.
    pub fn budget(&self) -> Option<EnergyBudget> {
        self.budget
    }

    /// δr/Δt of the last shift, when the case shifts particles.
    pub fn shift_velocity(&self) -> Option<&[Vector<D>]> {
        self.shift_velocity.as_deref()
    }

    /// Edits the particles from outside the stepping (a front end setting velocities
    /// or densities, a test placing particles), then rebuilds the lists and re-derives
    /// what depends on the state ([`Self::state_changed`]).
    pub fn edit(&mut self, f: impl FnOnce(&mut Particles<D>)) {
        f(&mut self.particles);
        if let Some(v) = self.shift_velocity.as_mut() {
            v.resize(self.particles.len(), Vector::zeros());
        }
        let domain = self.domain;
        self.particles.x.iter_mut().for_each(|x| domain.wrap(x));
        let reach = self.reach(self.control.acoustic(), self.max_speed());
        self.rebuild(reach);
        self.state_changed();
    }

    pub fn physics(&self) -> &Physics<D> {
        self.model.physics()
    }

    pub fn time_step_control(&self) -> &TimeStepControl {
        &self.control
    }

    /// Mean neighbours per particle (fluid and walls): in the lists, and in the rows
    /// the last step used.
    pub fn mean_neighbours(&self) -> (f64, f64) {
        self.list.mean_neighbours()
    }

    /// The largest fluid or wall speed (over all processes of a split run).
    fn max_speed(&self) -> f64 {
        let local = (self.particles.u.par_iter())
            .map(|u| u.norm_squared())
            .reduce(|| 0.0, f64::max)
            .sqrt();
        self.global_max(local)
    }

    /// The largest of `value` over the processes of a split run (`value` otherwise).
    fn global_max(&self, value: f64) -> f64 {
        self.ranks.as_ref().map_or(value, |r| r.max(value))
    }

    /// Gives a split run's halo its owners' state (nothing otherwise).
    fn refresh_halo(&mut self) {
        if let Some(r) = &self.ranks {
            r.refresh(&mut self.particles);
        }
    }

    /// Largest displacement a step of `dt` may add: `Δt (1.2|u|max + |a|max Δt)`, plus
    /// the shifting cap when particles are shifted.
    fn reach(&self, dt: f64, speed: f64) -> f64 {
        dt * (1.2 * speed + self.last_acceleration * dt) + self.shift_cap()
    }

    fn shift_cap(&self) -> f64 {
        if self.shift_velocity.is_some() {
            crate::physics::shifting::CAP * self.case.h()
        } else {
            0.0
        }
    }

    /// The longest step whose [`Self::reach`] stays within `room`: the root of
    /// `|a| Δt² + 1.2|u| Δt = room - shift`. It binds only when the skin could not be
    /// made wide enough (small periodic boxes), so that the lists never miss a pair.
    fn dt_within(&self, room: f64, speed: f64) -> f64 {
        let b = (room - self.shift_cap()).max(0.0);
        let (v, a) = (1.2 * speed, self.last_acceleration);
        2.0 * b / (v + (v * v + 4.0 * a * b).sqrt()).max(f64::MIN_POSITIVE)
    }

    /// Moves the fluid particles by the δ+-SPH shifting of the last step (none before
    /// the first), `speed` their largest speed, and returns the free surface it was
    /// shaped by.
    fn shift(&mut self, speed: f64) -> FreeSurface<D> {
        let dt = self.dt;
        let cfl_ma = speed * dt / self.case.h();
        let mut shift = self.model.shift(
            &mut self.particles,
            &self.list,
            &self.domain,
            self.case.dx(),
            cfl_ma,
        );
        if let Some(open) = &self.open {
            let p = &self.particles;
            (shift.dr.par_iter_mut().enumerate())
                .filter(|(i, _)| open.in_buffer(p, *i))
                .for_each(|(_, dr)| *dr = Vector::zeros());
        }
        if let (true, Some(velocity)) = (dt > 0.0, self.shift_velocity.as_mut()) {
            let domain = self.domain;
            self.particles
                .x
                .par_iter_mut()
                .zip(velocity.par_iter_mut())
                .zip(shift.dr.par_iter())
                .for_each(|((x, v), d)| {
                    *x += d;
                    domain.wrap(x);
                    *v = d / dt;
                });
        }
        shift.surface
    }

    /// Rebuilds lists (and reorders particles by cell) with a skin covering `reach`.
    fn rebuild(&mut self, reach: f64) {
        let support = self.model.support_radius();
        let skin = (MIN_SKIN * support)
            .max(SKIN_OVER_REACH * reach)
            .min(self.max_skin);
        if let Some(r) = self.ranks.as_mut() {
            let shift = self.shift_velocity.as_mut();
            r.redistribute(&mut self.particles, shift, &self.domain, support + skin);
        }
        let (p, domain) = (&mut self.particles, &self.domain);
        let (list, order) = match self.ranks.as_ref() {
            Some(r) => {
                NeighbourList::build_rows(p, domain, support, skin, |x, k| r.listed(x, k, domain))
            }
            None => NeighbourList::build(p, domain, support, skin),
        };
        if let Some(v) = self.shift_velocity.as_mut() {
            crate::particles::permute(v, &order);
        }
        if let Some(r) = self.ranks.as_mut() {
            r.reorder(&order);
        }
        self.list = list;
        self.counters.rebuilds += 1;
    }

    /// Re-derives what depends on the state after it was set from outside the stepping
    /// (construction, or velocities and densities edited by a front end): pressures, the
    /// acceleration that sizes the list skin and the energy-budget powers.
    pub fn state_changed(&mut self) {
        let owned = self.ranks.as_ref().map(|r| r.owned().to_vec());
        let local = self.rates().max_acceleration(owned.as_deref());
        self.last_acceleration = self.global_max(local);
        if let (Some(b), Some(now)) = (self.budget.as_mut(), self.model.last_powers()) {
            (b.last, b.pending) = (now, 0.0);
        }
    }

    /// The rates `dρ/dt` (without and with diffusion) and `du/dt` at the current state,
    /// in the current particle order.
    pub fn rates(&mut self) -> Rates<D> {
        let mut rates = Rates::default();
        let mut cx = Context {
            model: self.model.as_mut(),
            list: &self.list,
            domain: &self.domain,
            open: self.open.as_ref(),
            time: self.time,
            forcing: self.forcing.as_ref(),
            halo: self.ranks.as_ref(),
        };
        cx.evaluate(&mut self.particles, &mut rates, true, 0.0);
        rates
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
        rayon::scope(|_| self.advance_to(limit))
    }

    fn advance_to(&mut self, limit: f64) -> Result<()> {
        // the reach of this step, at least a twentieth of the support (a flow at rest
        // still starts to move within the step)
        let speed = self.max_speed();
        let support = self.model.support_radius();
        let reach = self
            .reach(self.control.acoustic(), speed)
            .max(0.5 * MIN_SKIN * support);
        let mut moved =
            self.global_max(self.list.max_displacement(&self.particles.x, &self.domain));
        let due = moved + reach > 0.5 * self.list.skin();
        let refill_due = (self.open.as_ref()).is_some_and(|o| o.refill_due(&self.particles));
        if due || refill_due {
            // particles enter and leave when the lists are rebuilt anyway
            self.remove_escaped();
            self.refill();
            self.rebuild(reach);
            moved = 0.0;
        }
        // no particle moves farther than `room` in this step (Δt is bounded below for
        // it when the skin was capped): the step uses the pairs within R + 2 room
        let room = reach.min(0.5 * self.list.skin() - moved);
        self.list
            .cull(&self.particles.x, &self.domain, support + 2.0 * room);
        // the shift of the last step, and tensile control from the same free surface
        let surface = if self.shift_velocity.is_some() {
            let surface = self.shift(speed);
            self.refresh_halo();
            Some(surface)
        } else {
            self.case
                .scheme
                .tensile_control
                .then(|| self.free_surface())
        };
        if let Some(surface) = surface.filter(|_| self.case.scheme.tensile_control) {
            let interior = surface.near.iter().map(|near| !near).collect();
            self.model.set_tensile_control(Some(interior));
        }
        let dt_lists = self.dt_within(room, speed);
        let mut cx = Context {
            model: self.model.as_mut(),
            list: &self.list,
            domain: &self.domain,
            open: self.open.as_ref(),
            time: self.time,
            forcing: self.forcing.as_ref(),
            halo: self.ranks.as_ref(),
        };
        let owned = self.ranks.as_ref().map(|r| r.owned());
        let local = (self.integrator.begin(&mut self.particles, &mut cx)).max_acceleration(owned);
        let a_max = self.ranks.as_ref().map_or(local, |r| r.max(local));
        if let (Some(b), Some(now)) = (self.budget.as_mut(), cx.model.last_powers()) {
            b.advance(now);
        }
        let mut dt = (self.control)
            .dt(a_max, cx.model.diffusivities())
            .min(dt_lists);
        let remaining = limit - self.time;
        if remaining > 0.0 && remaining < dt * (1.0 + 1e-9) {
            dt = remaining;
        }
        self.integrator.advance(dt, &mut self.particles, &mut cx);
        let domain = self.domain;
        self.particles.x.par_iter_mut().for_each(|x| domain.wrap(x));
        self.refresh_halo();
        self.last_acceleration = a_max;
        self.dt = dt;
        self.time += dt;
        self.counters.steps += 1;
        self.counters.evaluations += self.integrator.evaluations_per_step() as u64;
        if let Some(b) = self.budget.as_mut() {
            b.pending = dt;
        }
        self.check_stability()
    }

    /// Creates the particles that enter at inlets (see [`OpenBoundaries::refill`]).
    fn refill(&mut self) {
        let Some(open) = &self.open else {
            return;
        };
        let created = open.refill(&mut self.particles);
        if let Some(v) = self.shift_velocity.as_mut() {
            v.resize(self.particles.len(), Vector::zeros());
        }
        self.counters.created += created as u64;
    }

    /// Removes the fluid particles that left the domain along an open direction (their
    /// energy goes to the budget's `removed_energy`), before a list rebuild: until then
    /// they move on with the flow beyond the domain's bounds.
    fn remove_escaped(&mut self) {
        let (p, domain) = (&self.particles, &self.domain);
        let keep: Vec<bool> = (0..p.len())
            .into_par_iter()
            .map(|i| p.kind[i] != Kind::Fluid || !domain.escaped(&p.x[i]))
            .collect();
        let gone = keep.iter().filter(|&&k| !k).count();
        if gone == 0 {
            return;
        }
        if let Some(b) = self.budget.as_mut() {
            let ph = self.model.physics();
            let leaving: Vec<bool> = keep.iter().map(|k| !k).collect();
            b.removed_energy +=
                diagnostics::energies_of(&self.particles, &leaving, &ph.eos, &ph.gravity).total();
        }
        self.particles.retain(&keep);
        if let Some(v) = self.shift_velocity.as_mut() {
            crate::particles::retain(v, &keep);
        }
        self.counters.removed += gone as u64;
    }

    /// Why the energy budget of this case does not close, when it does not: terms that
    /// change the energy without a power term in the budget (empty when it closes).
    pub fn budget_caveats(&self) -> Vec<&'static str> {
        let case = &self.case;
        let mut why = Vec::new();
        if case.tank.iter().any(|t| t.lid_velocity.is_some()) {
            why.push("a sliding lid does work on the fluid that no power term counts");
        }
        if case.scheme.walls == crate::case::WallCondition::NoSlip {
            why.push("the no-slip wall term makes P_V not sign-definite");
        }
        if self.shift_velocity.is_some() {
            why.push("particle shifting moves particles without a power term");
        }
        if case.scheme.tensile_control {
            why.push("tensile instability control is not energy-conserving");
        }
        if case.scheme.turbulence == crate::case::TurbulenceChoice::DeltaLes {
            why.push("δ-LES-SPH's shifting velocity δu moves particles without a power term");
        }
        if self.forcing.is_some() {
            why.push("the body force of [forcing] does work that no power term counts");
        }
        if self.open.is_some() {
            why.push("open boundaries set the buffers' state and add fluid without a flux term");
        }
        let g = self.physics().gravity;
        if (0..D).any(|d| self.domain.is_periodic(d) && g[d] != 0.0) {
            why.push("gravity along a periodic axis: E_p jumps when particles wrap");
        }
        why
    }

    /// Fluid particles removed so far because they left the domain (by all processes
    /// of a split run; collective there).
    pub fn removed(&self) -> u64 {
        let Some(ranks) = &self.ranks else {
            return self.counters.removed;
        };
        let mut removed = [self.counters.removed as f64];
        ranks.sum(&mut removed);
        removed[0] as u64
    }

    fn check_stability(&self) -> Result<()> {
        let eos = self.physics().eos;
        let guard = &self.case.stability;
        let max_speed = guard.max_mach * eos.c0;
        let limit = guard.max_density_variation;
        let found = diagnostics::find_instability(&self.particles, eos.rho0, limit, max_speed);
        let Some(ranks) = &self.ranks else {
            return found.map_or(Ok(()), |(i, reason)| Err(self.unstable(i, reason)));
        };
        // every process stops, with the same report (the first process's that found one)
        let text = found.map(|(i, reason)| {
            format!(
                "{}\t{:?}\t{reason}",
                self.particles.id[i],
                self.particles.x[i].as_slice()
            )
        });
        let Some(text) = ranks.first_text(text) else {
            return Ok(());
        };
        let mut fields = text.splitn(3, '\t');
        let mut next = || fields.next().unwrap_or_default().to_string();
        Err(SphError::Unstable {
            time: self.time,
            step: self.counters.steps,
            particle: next().parse().unwrap_or(u32::MAX),
            position: next(),
            reason: next(),
        })
    }

    fn unstable(&self, i: usize, reason: String) -> SphError {
        SphError::Unstable {
            time: self.time,
            step: self.counters.steps,
            particle: self.particles.id[i],
            position: format!("{:?}", self.particles.x[i].as_slice()),
            reason,
        }
    }

    /// Brings pressures (fluid and walls) up to date with the current state. Call
    /// before writing output or reading pressure after steps. It changes nothing the
    /// next step depends on, so a run gives the same bits whether or not it is called.
    /// The tanks and walls of the case, in case order (tanks first).
    pub fn bodies(&self) -> &[Body] {
        &self.bodies
    }

    /// The fluid's load on each body at the current state, as in [`Self::bodies`]
    /// (see [`crate::boundary::bodies`]); refreshes the pressures.
    pub fn loads(&mut self) -> Vec<Load<D>> {
        let owned = self.ranks.as_ref().map(|r| r.owned());
        let body: Vec<Option<usize>> = (0..self.particles.len())
            .into_par_iter()
            .map(|i| {
                let (id, kind) = (self.particles.id[i], self.particles.kind[i]);
                // a split run's walls count on the process that owns them
                let own = owned.is_none_or(|o| o[i]);
                (kind == Kind::Wall && own)
                    .then(|| body_of(&self.bodies, id))
                    .flatten()
            })
            .collect();
        let point = self.case.moment_point();
        let centre = Vector::<D>::from_fn(|d, _| point[d]);
        let loads = self.model.wall_loads(
            &mut self.particles,
            &self.list,
            &self.domain,
            &body,
            self.bodies.len(),
            &centre,
        );
        match &self.ranks {
            Some(ranks) => summed_loads(ranks, loads),
            None => loads,
        }
    }

    pub fn sync_pressure(&mut self) {
        self.model
            .update_pressure_field(&mut self.particles, &self.list, &self.domain);
    }

    /// E_k, E_p and E_c of the fluid (of the whole run when it is split; collective).
    pub fn energies(&self) -> Energies {
        let ph = self.physics();
        let Some(ranks) = &self.ranks else {
            return diagnostics::energies(&self.particles, &ph.eos, &ph.gravity);
        };
        let p = &self.particles;
        let own: Vec<bool> = (0..p.len())
            .map(|i| owns_fluid(Some(ranks), p, i))
            .collect();
        let e = diagnostics::energies_of(p, &own, &ph.eos, &ph.gravity);
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
        self.global_max(diagnostics::max_density_variation(&self.particles, rho0))
    }

    /// Shepard-interpolated pressures at `points` (see [`Self::probe_pressure`]): in a
    /// split run each point's from the process whose region holds it, which holds all
    /// the fluid in reach of it (collective).
    pub fn probe_pressures(&self, points: &[Vector<D>]) -> Vec<Option<f64>> {
        let Some(ranks) = &self.ranks else {
            return points.iter().map(|x| self.probe_pressure(x)).collect();
        };
        let mine = |x: &Vector<D>| ranks.decomposition().owner(x) == ranks.rank();
        let mut sums: Vec<f64> = (points.iter())
            .flat_map(
                |x| match mine(x).then(|| self.probe_pressure(x)).flatten() {
                    Some(p) => [p, 1.0],
                    None => [0.0, 0.0],
                },
            )
            .collect();
        ranks.sum(&mut sums);
        sums.chunks(2)
            .map(|c| (c[1] > 0.0).then_some(c[0]))
            .collect()
    }

    /// Shepard-interpolated pressure at `point` (call [`Self::sync_pressure`] first);
    /// `None` where no fluid is within the kernel support.
    pub fn probe_pressure(&self, point: &Vector<D>) -> Option<f64> {
        diagnostics::probe_pressure(
            self.model.as_ref(),
            &self.particles,
            &self.list,
            &self.domain,
            point,
        )
    }

    /// Free-surface flags, normals and `λ` (Marrone et al. 2010), in the current order.
    pub fn free_surface(&self) -> FreeSurface<D> {
        self.model
            .free_surface(&self.particles, &self.list, &self.domain)
    }

    /// Fluid particles inside a wall now (see [`diagnostics::wall_crossings`]).
    pub fn wall_crossings(&self) -> usize {
        diagnostics::wall_crossings(&self.case, &self.particles)
    }

    /// Largest fluid coordinate along `axis` (of the whole run; collective when split).
    pub fn surge_front(&self, axis: usize) -> f64 {
        self.global_max(diagnostics::surge_front(&self.particles, axis))
    }

    pub fn n_fluid(&self) -> usize {
        self.particles.n_fluid()
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
