//! The state a step depends on, captured for a restart file and restored from one:
//! [`Checkpoint`]. Continuing from it is the uninterrupted run bit for bit (see
//! [`crate::io::restart`] for what that takes).

use super::{Counters, EnergyBudget, Simulation, State};
use crate::case::Case;
use crate::diagnostics::WatchMemory;
use crate::error::{Result, SphError};
use crate::motion::free::RECORD;
use crate::neighbours::NeighbourList;
use crate::particles::{Particles, Vector};
use std::borrow::Cow;

/// What a restart file says of sensor filters that do not match its case.
const FILTERS: &str = "its sensor filters do not match its case";

/// Everything of a [`Simulation`] that the next step depends on. Taken from a running
/// simulation it borrows the particles and list positions (a restart file is written
/// from them without a copy); read from a file it owns them.
#[derive(Debug, Clone)]
pub struct Checkpoint<'a, const D: usize> {
    pub case_toml: String,
    pub particles: Cow<'a, Particles<D>>,
    /// Positions at the last neighbour-list build, in the current order.
    pub list_positions: Cow<'a, [Vector<D>]>,
    pub skin: f64,
    pub time: f64,
    pub dt: f64,
    pub counters: Counters,
    pub last_acceleration: f64,
    pub budget: Option<EnergyBudget>,
    /// The state of each filtered sensor's low-pass filter, in sensor order.
    pub sensor_filters: Vec<[f64; 4]>,
    /// The state of each free body (see [`crate::motion::free::FreeBody::record`]), in case order.
    pub free_bodies: Vec<[f64; RECORD]>,
    /// The state of each absorbing wave maker (see
    /// [`crate::waves::active_absorption::Record`]), in case order.
    pub absorbing_paddles: Vec<crate::waves::active_absorption::Record>,
    /// The stability guard's transients reported and excursion under way.
    pub density_watch: WatchMemory,
}

impl<const D: usize> Checkpoint<'_, D> {
    /// The checkpoint with its own copy of what it borrows, to outlive its simulation.
    pub fn into_owned(self) -> Checkpoint<'static, D> {
        Checkpoint {
            particles: Cow::Owned(self.particles.into_owned()),
            list_positions: Cow::Owned(self.list_positions.into_owned()),
            case_toml: self.case_toml,
            skin: self.skin,
            time: self.time,
            dt: self.dt,
            counters: self.counters,
            last_acceleration: self.last_acceleration,
            budget: self.budget,
            sensor_filters: self.sensor_filters,
            free_bodies: self.free_bodies,
            absorbing_paddles: self.absorbing_paddles,
            density_watch: self.density_watch,
        }
    }
}

impl<const D: usize> Simulation<D> {
    /// The state the next step depends on, for a restart file (see [`crate::io::restart`]);
    /// it borrows the particles and the list positions.
    pub fn checkpoint(&self) -> Result<Checkpoint<'_, D>> {
        let case_toml = toml::to_string(&self.case)
            .map_err(|e| SphError::output("restart", format!("case not serialisable: {e}")))?;
        Ok(Checkpoint {
            case_toml,
            particles: Cow::Borrowed(&self.state.particles),
            list_positions: Cow::Borrowed(self.stepper.list.reference_positions()),
            skin: self.stepper.list.skin(),
            time: self.state.time,
            dt: self.state.dt,
            counters: self.state.counters,
            last_acceleration: self.stepper.last_acceleration,
            budget: self.budget,
            sensor_filters: self.observers.iter().filter_map(|o| o.memory()).collect(),
            free_bodies: (self.stepper.motions.as_ref()).map_or(Vec::new(), |m| m.free_records()),
            absorbing_paddles: (self.stepper.motions.as_ref())
                .map_or(Vec::new(), |m| m.absorption_records()),
            density_watch: self.stepper.density_watch.memory(),
        })
    }

    /// Continues a run from `checkpoint`, to `end` when given, else to the case's end
    /// time. The next step is the one the checkpointed run would have taken, bit for bit.
    pub fn from_checkpoint(mut checkpoint: Checkpoint<'_, D>, end: Option<f64>) -> Result<Self> {
        let list_positions = std::mem::take(&mut checkpoint.list_positions).into_owned();
        let skin = checkpoint.skin;
        let mut sim = Self::checkpointed(checkpoint, end)?;
        let s = &mut sim.stepper;
        let (support, kind) = (s.model.support_radius(), &sim.state.particles.kind);
        s.list = NeighbourList::restore(kind, &s.domain, support, skin, list_positions)
            .ok_or_else(|| {
                SphError::output(
                    "restart",
                    "particles are not in the order of their neighbour lists".to_string(),
                )
            })?;
        Ok(sim)
    }

    /// The state of `checkpoint` in a simulation of its case, without neighbour lists.
    pub(super) fn checkpointed(checkpoint: Checkpoint<'_, D>, end: Option<f64>) -> Result<Self> {
        let mut case = Case::from_toml_str(&checkpoint.case_toml)?;
        if let Some(end) = end {
            if end.is_nan() || end <= checkpoint.time {
                return Err(SphError::invalid(
                    "time.end",
                    end,
                    format!("a time after the restart time {} s", checkpoint.time),
                ));
            }
            case.time.end = end;
        }
        let mut sim = Self::assemble(case)?;
        let c = checkpoint;
        let corrupt = |what: &str| SphError::output("restart", what.to_string());
        let walls = |p: &Particles<D>| p.len() - p.n_fluid();
        if walls(&c.particles) != walls(&sim.state.particles) {
            return Err(corrupt("its wall particles do not match its case"));
        }
        let mut particles = c.particles.into_owned();
        match (
            &sim.state.particles.shift_velocity,
            &particles.shift_velocity,
        ) {
            (None, _) => particles.shift_velocity = None,
            (Some(_), None) => {
                return Err(corrupt(
                    "the case shifts particles but no shifting velocity is stored",
                ))
            }
            (Some(_), Some(_)) => {}
        }
        let mut memories = c.sensor_filters.iter();
        for o in sim.observers.iter_mut().filter(|o| o.memory().is_some()) {
            let state = memories.next().ok_or_else(|| corrupt(FILTERS))?;
            o.recall(*state);
        }
        if memories.next().is_some() {
            return Err(corrupt(FILTERS));
        }
        if let Some(motions) = sim.stepper.motions.as_mut() {
            if motions.free_count() != c.free_bodies.len() {
                return Err(corrupt("its free bodies do not match its case"));
            }
            for (body, record) in motions.free_bodies().zip(&c.free_bodies) {
                body.restore(record);
            }
            if !motions.restore_absorption(&c.absorbing_paddles) {
                return Err(corrupt("its absorbing wave makers do not match its case"));
            }
            particles.keep_wall_acceleration(true);
            motions.place(&mut particles, c.time, &sim.stepper.domain);
        } else if !c.free_bodies.is_empty() || !c.absorbing_paddles.is_empty() {
            return Err(corrupt("its moving bodies do not match its case"));
        }
        sim.state = State {
            particles,
            time: c.time,
            dt: c.dt,
            counters: c.counters,
        };
        sim.stepper.last_acceleration = c.last_acceleration;
        sim.stepper.density_watch.recall(c.density_watch);
        sim.budget = c.budget;
        Ok(sim)
    }
}
