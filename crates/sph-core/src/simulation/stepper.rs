//! What advances a [`State`]: the resolved model, the integrator, the neighbour lists
//! and their rebuild policy, the step-size control, open boundaries, the body force
//! and a split run's share of the processes. [`Stepper::advance_to`] is one step.

use super::state::State;
use crate::boundary::open::OpenBoundaries;
use crate::case::{Case, IntegratorChoice, ShiftingChoice};
use crate::diagnostics::{self, budget::EnergyBudget};
use crate::diagnostics::{DensityWatch, Holder, Verdict};
use crate::distributed::Ranks;
use crate::domain::Domain;
use crate::error::{Result, SphError};
use crate::forcing::Forcing;
use crate::motion::Motions;
use crate::neighbours::{ListPolicy, NeighbourList};
use crate::particles::{Kind, Particles, Vector};
use crate::physics::free_surface::FreeSurface;
use crate::physics::shifting;
use crate::scheme::model::{Model, Rates};
use crate::time::integrator::{Context, Rk4, Symplectic, TimeIntegrator};
use crate::time::step_size::TimeStepControl;
use rayon::prelude::*;

/// The integrator's view of a stepper `$s` at time `$time` (a macro, so that the
/// fields are borrowed apart from the integrator that takes it).
macro_rules! context {
    ($s:expr, $time:expr) => {
        Context {
            model: $s.model.as_mut(),
            list: &$s.list,
            domain: &$s.domain,
            open: $s.open.as_ref(),
            time: $time,
            forcing: $s.forcing.as_ref(),
            motions: $s.motions.as_mut(),
            halo: $s.ranks.as_ref(),
        }
    };
}

/// The stepping machinery of a run (see the module documentation).
pub struct Stepper<const D: usize> {
    pub(super) model: Box<dyn Model<D>>,
    integrator: Box<dyn TimeIntegrator<D>>,
    pub(super) list: NeighbourList<D>,
    policy: ListPolicy,
    pub(super) control: TimeStepControl,
    /// The largest acceleration of the last step (or state set from outside), which
    /// sizes the reach of the next.
    pub(super) last_acceleration: f64,
    pub(super) domain: Domain<D>,
    /// Inflow and outflow buffers, when the case has any.
    pub(super) open: Option<OpenBoundaries<D>>,
    /// The body force besides gravity, when the case has one.
    pub(super) forcing: Option<Forcing<D>>,
    /// The moving bodies, when the case has any.
    pub(super) motions: Option<Motions<D>>,
    /// This process's share of a run split over several.
    pub(super) ranks: Option<Ranks<D>>,
    dx: f64,
    tensile_control: bool,
    /// `stability.max_mach`.
    max_mach: f64,
    /// The density guard, which lets an impact's transient through.
    pub(super) density_watch: DensityWatch,
    /// Whether the domain is the default box around the initial particles (no
    /// `[domain]` table): the first fluid it removes is reported in `notices`.
    default_domain: bool,
    /// Messages for the user, in the order they arose.
    pub(super) notices: Vec<String>,
}

impl<const D: usize> Stepper<D> {
    /// The stepper of a validated case, its model resolved, without lists yet.
    pub fn new(
        case: &Case,
        model: Box<dyn Model<D>>,
        control: TimeStepControl,
        domain: Domain<D>,
        open: Option<OpenBoundaries<D>>,
        forcing: Option<Forcing<D>>,
        motions: Option<Motions<D>>,
    ) -> Self {
        let integrator: Box<dyn TimeIntegrator<D>> = match case.scheme.integrator {
            IntegratorChoice::Rk4 => Box::<Rk4<D>>::default(),
            IntegratorChoice::Symplectic => Box::<Symplectic<D>>::default(),
        };
        let shifts = case.scheme.shifting == ShiftingChoice::DeltaPlus;
        let shift_cap = if shifts {
            shifting::CAP * case.h()
        } else {
            0.0
        };
        let stability = &case.stability;
        let density_watch = DensityWatch::new(
            stability.max_density_variation,
            stability.transient,
            case.h() / model.physics().eos.c0,
        );
        Self {
            policy: ListPolicy::new(model.support_radius(), &domain, shift_cap),
            model,
            integrator,
            list: NeighbourList::default(),
            control,
            last_acceleration: 0.0,
            domain,
            open,
            forcing,
            motions,
            ranks: None,
            dx: case.dx(),
            tensile_control: case.scheme.tensile_control,
            max_mach: stability.max_mach,
            density_watch,
            default_domain: case.domain.is_none(),
            notices: Vec::new(),
        }
    }

    /// The largest fluid or wall speed (over all processes of a split run).
    pub(super) fn max_speed(&self, p: &Particles<D>) -> f64 {
        let local = (p.u.par_iter())
            .map(|u| u.norm_squared())
            .reduce(|| 0.0, f64::max)
            .sqrt();
        self.global_max(local)
    }

    /// The largest of `value` over the processes of a split run (`value` otherwise).
    pub(super) fn global_max(&self, value: f64) -> f64 {
        self.ranks.as_ref().map_or(value, |r| r.max(value))
    }

    /// Gives a split run's halo its owners' state (nothing otherwise).
    fn refresh_halo(&self, p: &mut Particles<D>) {
        if let Some(r) = &self.ranks {
            r.refresh(p);
        }
    }

    /// The reach of a step of the acoustic limit at speed `speed` (see
    /// [`ListPolicy::reach`]).
    pub(super) fn reach(&self, speed: f64) -> f64 {
        (self.policy).reach(self.control.acoustic(), speed, self.last_acceleration)
    }

    /// Moves the fluid particles by the δ+-SPH shifting of the last step (none before
    /// the first), `speed` their largest speed, and returns the free surface it was
    /// shaped by.
    fn shift(&mut self, state: &mut State<D>, speed: f64) -> FreeSurface<D> {
        let dt = state.dt;
        let cfl_ma = speed * dt / self.control.h;
        let p = &mut state.particles;
        let mut shift = (self.model).shift(p, &self.list, &self.domain, self.dx, cfl_ma);
        if let Some(open) = &self.open {
            (shift.dr.par_iter_mut().enumerate())
                .filter(|(i, _)| open.in_buffer(p, *i))
                .for_each(|(_, dr)| *dr = Vector::zeros());
        }
        if let (true, Some(velocity)) = (dt > 0.0, p.shift_velocity.as_mut()) {
            let domain = self.domain;
            (p.x.par_iter_mut())
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

    /// Rebuilds lists (and reorders particles by cell) with a skin covering `reach`;
    /// a split run first moves particles between processes and renews its halo.
    pub(super) fn rebuild(&mut self, state: &mut State<D>, reach: f64) {
        let support = self.policy.support;
        let skin = self.policy.skin(reach);
        let p = &mut state.particles;
        // the old lists go before the new ones are built: never two sets in memory
        self.list = NeighbourList::default();
        if let Some(r) = self.ranks.as_mut() {
            r.redistribute(p, &self.domain, support + skin);
        }
        let domain = &self.domain;
        let (list, order) = match self.ranks.as_ref() {
            Some(r) => {
                NeighbourList::build_rows(p, domain, support, skin, |x, k| r.listed(x, k, domain))
            }
            None => NeighbourList::build(p, domain, support, skin),
        };
        if let Some(r) = self.ranks.as_mut() {
            r.reorder(&order);
        }
        self.list = list;
        state.counters.rebuilds += 1;
    }

    /// Re-derives what depends on the state after it was set from outside the stepping:
    /// the acceleration that sizes the list skin and the energy-budget powers.
    pub(super) fn state_changed(
        &mut self,
        state: &mut State<D>,
        budget: Option<&mut EnergyBudget>,
    ) {
        let owned = self.ranks.as_ref().map(|r| r.owned().to_vec());
        let local = self.rates(state).max_acceleration(owned.as_deref());
        self.last_acceleration = self.global_max(local);
        let now = context!(self, state.time).powers(&state.particles);
        if let (Some(b), Some(now)) = (budget, now) {
            b.restart_from(now);
        }
    }

    /// The rates `dρ/dt` (without and with diffusion) and `du/dt` at the current state,
    /// in the current particle order.
    pub(super) fn rates(&mut self, state: &mut State<D>) -> Rates<D> {
        let mut rates = Rates::default();
        let mut cx = context!(self, state.time);
        cx.evaluate(&mut state.particles, &mut rates, true, 0.0);
        rates
    }

    /// Advances `state` by one step, shortened to land on `limit` when it would pass
    /// it; `budget` (when the case keeps one) takes the step's powers and the energy
    /// of the particles removed.
    pub(super) fn advance_to(
        &mut self,
        state: &mut State<D>,
        mut budget: Option<&mut EnergyBudget>,
        limit: f64,
    ) -> Result<()> {
        let speed = self.max_speed(&state.particles);
        let reach =
            (self.policy).step_reach(self.control.acoustic(), speed, self.last_acceleration);
        let x = &state.particles.x;
        let mut moved = self.global_max(self.list.max_displacement(x, &self.domain));
        let due = (self.policy).rebuild_due(moved, reach, self.list.skin());
        let refill_due = (self.open.as_ref()).is_some_and(|o| o.refill_due(&state.particles));
        if due || refill_due {
            // particles enter and leave when the lists are rebuilt anyway
            self.remove_escaped(state, budget.as_deref_mut());
            self.refill(state);
            self.rebuild(state, reach);
            moved = 0.0;
        }
        // no particle moves farther than `room` in this step (Δt is bounded below for
        // it when the skin was capped): the step uses the pairs within R + 2 room
        let room = reach.min(0.5 * self.list.skin() - moved);
        let support = self.policy.support;
        (self.list).cull(&state.particles.x, &self.domain, support + 2.0 * room);
        self.surface_terms(state, speed);
        let dt_lists = (self.policy).dt_within(room, speed, self.last_acceleration);
        let owned = self.ranks.as_ref().map(|r| r.owned());
        let mut cx = context!(self, state.time);
        let local = (self.integrator.begin(&mut state.particles, &mut cx)).max_acceleration(owned);
        let local = local.max(wall_acceleration(&state.particles));
        let a_max = cx.halo.map_or(local, |r| r.max(local));
        if let (Some(b), Some(now)) = (budget.as_deref_mut(), cx.powers(&state.particles)) {
            b.advance(now);
        }
        let bodies_dt = cx.motions.as_ref().map_or(f64::INFINITY, |m| m.max_dt());
        let mut dt = (self.control)
            .dt(a_max, cx.model.diffusivities())
            .min(dt_lists)
            .min(bodies_dt);
        let remaining = limit - state.time;
        if remaining > 0.0 && remaining < dt * (1.0 + 1e-9) {
            dt = remaining;
        }
        self.integrator.advance(dt, &mut state.particles, &mut cx);
        let domain = self.domain;
        (state.particles.x.par_iter_mut()).for_each(|x| domain.wrap(x));
        if let Some(motions) = &self.motions {
            motions.place(&mut state.particles, state.time + dt, &domain);
        }
        self.refresh_halo(&mut state.particles);
        self.last_acceleration = a_max;
        state.dt = dt;
        state.time += dt;
        state.counters.steps += 1;
        state.counters.evaluations += self.integrator.evaluations_per_step() as u64;
        if let Some(b) = budget {
            b.pending = dt;
        }
        self.check_contact(state)?;
        self.check_stability(state)
    }

    /// Stops a run whose free body reaches into another body (see
    /// [`crate::motion::contact`]).
    fn check_contact(&self, state: &State<D>) -> Result<()> {
        let Some(touch) =
            (self.motions.as_ref()).and_then(|m| m.touch(&state.particles, 0.5 * self.dx))
        else {
            return Ok(());
        };
        Err(SphError::Unstable {
            time: state.time,
            step: state.counters.steps,
            particle: touch.particle,
            position: format!("{:?}", touch.position.as_slice()),
            reason: format!(
                "the walls of the free body {} reached {} ({:.2} spacings apart): contact \
                 between bodies is not modelled",
                touch.free,
                touch.other,
                touch.distance / self.dx
            ),
        })
    }

    /// The shift of the last step (δ+-SPH), and tensile control from the same free
    /// surface; nothing when the case has neither.
    fn surface_terms(&mut self, state: &mut State<D>, speed: f64) {
        let surface = if state.particles.shift_velocity.is_some() {
            let surface = self.shift(state, speed);
            self.refresh_halo(&mut state.particles);
            Some(surface)
        } else {
            (self.tensile_control).then(|| self.free_surface(&state.particles))
        };
        if let Some(surface) = surface.filter(|_| self.tensile_control) {
            let interior = surface.near.iter().map(|near| !near).collect();
            self.model.set_tensile_control(Some(interior));
        }
    }

    /// Free-surface flags, normals and `λ` (Marrone et al. 2010), in the current order.
    pub(super) fn free_surface(&self, p: &Particles<D>) -> FreeSurface<D> {
        self.model.free_surface(p, &self.list, &self.domain)
    }

    /// Creates the particles that enter at inlets (see [`OpenBoundaries::refill`]).
    fn refill(&mut self, state: &mut State<D>) {
        let Some(open) = &self.open else {
            return;
        };
        let created = open.refill(&mut state.particles);
        state.counters.created += created as u64;
    }

    /// Removes the fluid particles that left the domain along an open direction (their
    /// energy goes to the budget's `removed_energy`), before a list rebuild: until then
    /// they move on with the flow beyond the domain's bounds.
    fn remove_escaped(&mut self, state: &mut State<D>, budget: Option<&mut EnergyBudget>) {
        let (p, domain) = (&state.particles, &self.domain);
        let keep: Vec<bool> = (0..p.len())
            .into_par_iter()
            .map(|i| p.kind[i] != Kind::Fluid || !domain.escaped(&p.x[i]))
            .collect();
        let gone = keep.iter().filter(|&&k| !k).count();
        if gone == 0 {
            return;
        }
        if let Some(b) = budget {
            let ph = self.model.physics();
            let leaving = |i: usize| !keep[i];
            b.removed_energy += diagnostics::energies_of(p, leaving, &ph.eos, &ph.gravity).total();
        }
        let leaving: Vec<usize> = (0..p.len()).filter(|&i| !keep[i]).collect();
        let mass: f64 = leaving.iter().map(|&i| p.mass[i]).sum();
        if self.default_domain && state.counters.removed == 0 {
            let centre = leaving.iter().map(|&i| p.x[i]).sum::<Vector<D>>() / gone as f64;
            self.notices.push(format!(
                "t = {:.6} s: {gone} fluid particles ({mass:.4e} kg) left the default domain \
                 {} near {} and were removed; a [domain] table sets where fluid may go",
                state.time,
                self.domain.describe(),
                crate::domain::point_text(&centre),
            ));
        }
        state.particles.retain(&keep);
        state.counters.removed += gone as u64;
        state.counters.removed_mass += mass;
    }

    /// The stability guard (see [`diagnostics::guard`]); in a split run every process
    /// stops with the report of the first process that found a blow-up.
    fn check_stability(&mut self, state: &State<D>) -> Result<()> {
        let eos = self.model.physics().eos;
        let p = &state.particles;
        let unstable = |h: Holder, reason: String| SphError::Unstable {
            time: state.time,
            step: state.counters.steps,
            particle: h.particle,
            position: h.position,
            reason,
        };
        let found = diagnostics::find_instability(p, eos.rho0, self.max_mach * eos.c0);
        let found = found.map(|(i, reason)| (holder(p, i, eos.rho0), reason));
        if let Some((h, reason)) = first_found(self.ranks.as_ref(), found) {
            return Err(unstable(h, reason));
        }
        let variation = self.global_max(diagnostics::max_density_variation(p, eos.rho0));
        let ranks = self.ranks.as_ref();
        let held_by = || {
            let local = diagnostics::densest_excursion(p, eos.rho0)
                .filter(|&(_, v)| v.abs() == variation)
                .map(|(i, _)| (holder(p, i, eos.rho0), String::new()));
            let nowhere = Holder {
                particle: u32::MAX,
                position: "(not found)".into(),
                variation,
            };
            first_found(ranks, local).map_or(nowhere, |(h, _)| h)
        };
        match self.density_watch.observe(state.time, variation, held_by) {
            Verdict::Calm => Ok(()),
            Verdict::Transient(notice) => {
                // every process of a split run sees the same transient: one tells it
                if self.ranks.as_ref().is_none_or(|r| r.rank() == 0) {
                    self.notices.push(notice);
                }
                Ok(())
            }
            Verdict::Unstable(h, reason) => Err(unstable(h, reason)),
        }
    }
}

/// The largest acceleration of a moving body's wall particle (zero without moving
/// bodies), which bounds Δt and the lists' reach as the fluid's does.
fn wall_acceleration<const D: usize>(p: &Particles<D>) -> f64 {
    (p.wall_acceleration.as_ref()).map_or(0.0, |a| {
        (a.par_iter().map(|a| a.norm_squared()))
            .reduce(|| 0.0, f64::max)
            .sqrt()
    })
}

/// Particle `i`'s id, position and density variation.
fn holder<const D: usize>(p: &Particles<D>, i: usize, rho0: f64) -> Holder {
    Holder {
        particle: p.id[i],
        position: crate::domain::point_text(&p.x[i]),
        variation: p.rho[i] / rho0 - 1.0,
    }
}

/// The first process's finding, on every process of a split run (this process's
/// otherwise).
fn first_found<const D: usize>(
    ranks: Option<&Ranks<D>>,
    found: Option<(Holder, String)>,
) -> Option<(Holder, String)> {
    let Some(ranks) = ranks else {
        return found;
    };
    let text = found.map(|(h, reason)| {
        format!(
            "{}\t{}\t{:e}\t{reason}",
            h.particle, h.position, h.variation
        )
    });
    let text = ranks.first_text(text)?;
    let mut fields = text.splitn(4, '\t');
    let mut next = || fields.next().unwrap_or_default().to_string();
    let (particle, position, variation) = (next(), next(), next());
    let holder = Holder {
        particle: particle.parse().unwrap_or(u32::MAX),
        position,
        variation: variation.parse().unwrap_or(f64::NAN),
    };
    Some((holder, next()))
}
