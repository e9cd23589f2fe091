//! A simulation split over processes (see [`crate::distributed`]):
//! [`Simulation::new_split`] and [`Simulation::from_checkpoint_split`] keep this
//! process's share of a case or restart file, and
//! [`Simulation::view`] gathers the whole run on process 0 for output, which then
//! writes exactly what a serial run writes.

use super::{Checkpoint, Simulation, State};
use crate::case::{Case, TurbulenceChoice};
use crate::distributed::{Communicator, Ranks};
use crate::error::{Result, SphError};
use std::sync::Arc;

impl<const D: usize> Simulation<D> {
    /// Builds this process's share of a case split over the processes of `comm`
    /// (the whole run when there is one): every process builds the case's particles
    /// and keeps its own before the first list build, so that no process builds the
    /// whole run's lists or evaluates it. Collective. Process 0 also keeps the
    /// [`Self::view`] that output is written from.
    pub fn new_split(case: Case, comm: Arc<dyn Communicator>) -> Result<Self> {
        if comm.size() == 1 {
            return Self::new(case);
        }
        case.validate()?;
        case.check_memory(comm.size())?;
        let mut local = Self::assemble(case)?.split_among(comm)?;
        local.state_changed();
        Ok(local)
    }

    /// [`Self::from_checkpoint`] split over the processes of `comm` as
    /// [`Self::new_split`] splits a case: every process reads the whole checkpoint's
    /// particles and keeps its own, on any number of processes. Collective.
    pub fn from_checkpoint_split(
        checkpoint: Checkpoint<'_, D>,
        end: Option<f64>,
        comm: Arc<dyn Communicator>,
    ) -> Result<Self> {
        if comm.size() == 1 {
            return Self::from_checkpoint(checkpoint, end);
        }
        // the checkpoint carries the acceleration that sizes the first list skin
        Self::checkpointed(checkpoint, end)?.split_among(comm)
    }

    /// Keeps this process's share of the whole run held (which has no neighbour lists
    /// yet) and builds its lists with the halo; process 0 also keeps an empty copy of
    /// the run, the [`Self::view`] that the gathers fill. Collective.
    fn split_among(mut self, comm: Arc<dyn Communicator>) -> Result<Self> {
        check_splittable(&self)?;
        if comm.rank() == 0 {
            let mut view = Self::assemble(self.case.clone())?;
            view.state.particles = self.state.particles.empty_like();
            self.view = Some(Box::new(view));
        }
        let passes = self.stepper.model.neighbour_passes();
        let s = &mut self.stepper;
        let ranks = Ranks::split(comm, &mut self.state.particles, &s.domain, passes);
        s.ranks = Some(ranks);
        let reach = s.reach(s.max_speed(&self.state.particles));
        s.rebuild(&mut self.state, reach);
        Ok(self)
    }

    /// The whole run, for output and diagnostics: this simulation itself, or in a split
    /// run its particles gathered on process 0 in the order of their ids (with the
    /// lists built again for them, and the particles removed counted over all
    /// processes); `None` on the other processes. Collective in a split run.
    pub fn view(&mut self) -> Option<&mut Self> {
        let Some(ranks) = self.ranks() else {
            return Some(self);
        };
        let gathered = ranks.gather(&self.state.particles);
        let removed = self.removed();
        let removed_mass = self.removed_mass();
        let particles = gathered?;
        let view = self.view.as_deref_mut()?;
        view.state = State {
            particles,
            time: self.state.time,
            dt: self.state.dt,
            counters: Default::default(),
        };
        view.stepper.last_acceleration = self.stepper.last_acceleration;
        let reach = view
            .stepper
            .reach(view.stepper.max_speed(&view.state.particles));
        view.stepper.rebuild(&mut view.state, reach);
        view.state.counters = self.state.counters;
        view.state.counters.removed = removed;
        view.state.counters.removed_mass = removed_mass;
        for (to, from) in view.observers.iter_mut().zip(&self.observers) {
            if let Some(state) = from.memory() {
                to.recall(state);
            }
        }
        Some(view)
    }
}

/// What a split run cannot do yet, refused in one line.
fn check_splittable<const D: usize>(sim: &Simulation<D>) -> Result<()> {
    let case = &sim.case;
    let refuse = |key: &str, value: &str, why: &str| {
        Err(SphError::invalid(
            key,
            value,
            format!("{why} in a run over several processes (run this case on one)"),
        ))
    };
    if !case.open_boundary.is_empty() {
        return refuse(
            "open_boundary",
            &format!("{} boundaries", case.open_boundary.len()),
            "no open boundaries",
        );
    }
    if case.diagnostics.energy_budget {
        return refuse("diagnostics.energy_budget", "true", "no energy budget");
    }
    if case.has_moving_bodies() {
        return refuse("motion", "\"prescribed\"", "no moving bodies");
    }
    if case.scheme.turbulence == TurbulenceChoice::DeltaLes {
        return refuse("scheme.turbulence", "\"delta_les\"", "no δ-LES-SPH");
    }
    Ok(())
}
