//! The state a step depends on, captured for a restart file and restored from one:
//! [`Checkpoint`]. Continuing from it is the uninterrupted run bit for bit (see
//! [`crate::io::restart`] for what that takes).

use super::{Counters, EnergyBudget, Simulation};
use crate::case::Case;
use crate::error::{Result, SphError};
use crate::neighbours::NeighbourList;
use crate::particles::{Particles, Vector};

/// Everything of a [`Simulation`] that the next step depends on.
#[derive(Debug, Clone)]
pub struct Checkpoint<const D: usize> {
    pub case_toml: String,
    pub particles: Particles<D>,
    /// Positions at the last neighbour-list build, in the current order.
    pub list_positions: Vec<Vector<D>>,
    pub skin: f64,
    pub time: f64,
    pub dt: f64,
    pub counters: Counters,
    pub last_acceleration: f64,
    pub budget: Option<EnergyBudget>,
    pub shift_velocity: Option<Vec<Vector<D>>>,
    /// The state of each filtered sensor's low-pass filter, in sensor order.
    pub sensor_filters: Vec<[f64; 4]>,
}

impl<const D: usize> Simulation<D> {
    /// The state the next step depends on, for a restart file (see [`crate::io::restart`]).
    pub fn checkpoint(&self) -> Result<Checkpoint<D>> {
        let case_toml = toml::to_string(&self.case)
            .map_err(|e| SphError::output("restart", format!("case not serialisable: {e}")))?;
        Ok(Checkpoint {
            case_toml,
            particles: self.particles.clone(),
            list_positions: self.list.reference_positions().to_vec(),
            skin: self.list.skin(),
            time: self.time,
            dt: self.dt,
            counters: self.counters,
            last_acceleration: self.last_acceleration,
            budget: self.budget,
            shift_velocity: self.shift_velocity.clone(),
            sensor_filters: self
                .sensors
                .iter()
                .filter_map(|s| s.filter.map(|f| f.state))
                .collect(),
        })
    }

    /// Continues a run from `checkpoint`, to `end` when given, else to the case's end
    /// time. The next step is the one the checkpointed run would have taken, bit for bit.
    pub fn from_checkpoint(mut checkpoint: Checkpoint<D>, end: Option<f64>) -> Result<Self> {
        let list_positions = std::mem::take(&mut checkpoint.list_positions);
        let skin = checkpoint.skin;
        let mut sim = Self::checkpointed(checkpoint, end)?;
        let support = sim.model.support_radius();
        let kind = &sim.particles.kind;
        sim.list = NeighbourList::restore(kind, &sim.domain, support, skin, list_positions)
            .ok_or_else(|| {
                SphError::output(
                    "restart",
                    "particles are not in the order of their neighbour lists".to_string(),
                )
            })?;
        Ok(sim)
    }

    /// The state of `checkpoint` in a simulation of its case, without neighbour lists.
    pub(super) fn checkpointed(checkpoint: Checkpoint<D>, end: Option<f64>) -> Result<Self> {
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
        if walls(&c.particles) != walls(&sim.particles) {
            return Err(corrupt("its wall particles do not match its case"));
        }
        if sim.shift_velocity.is_some() {
            match &c.shift_velocity {
                Some(v) if v.len() == c.particles.len() => {}
                _ => {
                    return Err(corrupt(
                        "the case shifts particles but no shifting velocity is stored",
                    ))
                }
            }
            sim.shift_velocity = c.shift_velocity;
        }
        let filtered = sim.sensors.iter().filter(|s| s.filter.is_some()).count();
        if filtered != c.sensor_filters.len() {
            return Err(corrupt("its sensor filters do not match its case"));
        }
        let filters = sim.sensors.iter_mut().filter_map(|s| s.filter.as_mut());
        for (filter, state) in filters.zip(&c.sensor_filters) {
            filter.state = *state;
        }
        sim.particles = c.particles;
        sim.time = c.time;
        sim.dt = c.dt;
        sim.counters = c.counters;
        sim.last_acceleration = c.last_acceleration;
        sim.budget = c.budget;
        Ok(sim)
    }
}
