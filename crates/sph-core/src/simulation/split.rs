//! A simulation split over processes (see [`crate::distributed`]):
//! [`Simulation::new_split`] and [`Simulation::from_checkpoint_split`] keep this
//! process's share of a case or restart file, and
//! [`Simulation::view`] gathers the whole run on process 0 for output, which then
//! writes exactly what a serial run writes.

use super::{Checkpoint, Simulation};
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
        let mut local = Self::assemble(case)?.split_among(comm)?;
        local.state_changed();
        Ok(local)
    }

    /// [`Self::from_checkpoint`] split over the processes of `comm` as
    /// [`Self::new_split`] splits a case: every process reads the whole checkpoint's
    /// particles and keeps its own, on any number of processes. Collective.
    pub fn from_checkpoint_split(
        checkpoint: Checkpoint<D>,
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
            (view.particles, view.shift_velocity) = Default::default();
            self.view = Some(Box::new(view));
        }
        let passes = self.halo_passes();
        let ranks = Ranks::split(
            comm,
            &mut self.particles,
            self.shift_velocity.as_mut(),
            &self.domain,
            passes,
        );
        self.ranks = Some(ranks);
        let reach = self.reach(self.control.acoustic(), self.max_speed());
        self.rebuild(reach);
        Ok(self)
    }

    /// The pair passes whose results an evaluation or a step's start chains (see
    /// [`crate::distributed`]): the wall extrapolation or the δ-SPH gradient, then the
    /// pair loop; with shifting or tensile control, the free surface's three (the
    /// moments, the scan region, the neighbours on the surface). One pass fewer leaves
    /// a split dam break 1e-6 away from the serial run after 200 steps; with these it
    /// agrees to round-off (`crates/sph-cli/tests/mpi/main.rs`).
    fn halo_passes(&self) -> usize {
        let s = &self.case.scheme;
        let surface = s.shifting != crate::case::ShiftingChoice::None || s.tensile_control;
        2 + usize::from(surface)
    }

    /// This process's share of a split run (`None` when the run is not split).
    pub fn ranks(&self) -> Option<&Ranks<D>> {
        self.ranks.as_ref()
    }

    /// The largest of `value` over the processes of a split run (`value` itself when
    /// the run is not split). Collective.
    pub fn max_over_processes(&self, value: f64) -> f64 {
        self.global_max(value)
    }

    /// The whole run, for output and diagnostics: this simulation itself, or in a split
    /// run its particles gathered on process 0 in the order of their ids (with the
    /// lists built again for them, and the particles removed counted over all
    /// processes); `None` on the other processes. Collective in a split run.
    pub fn view(&mut self) -> Option<&mut Self> {
        if self.ranks.is_none() {
            return Some(self);
        }
        let ranks = self.ranks.as_ref()?;
        let gathered = ranks.gather(&self.particles, self.shift_velocity.as_deref());
        let mut removed = [self.counters.removed as f64];
        ranks.sum(&mut removed);
        let (particles, shift) = gathered?;
        let view = self.view.as_deref_mut()?;
        view.particles = particles;
        view.shift_velocity = shift;
        (view.time, view.dt) = (self.time, self.dt);
        view.last_acceleration = self.last_acceleration;
        let reach = view.reach(view.control.acoustic(), view.max_speed());
        view.rebuild(reach);
        view.counters = self.counters;
        view.counters.removed = removed[0] as u64;
        for (to, from) in view.sensors.iter_mut().zip(&self.sensors) {
            to.filter.clone_from(&from.filter);
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
    if case.scheme.turbulence == TurbulenceChoice::DeltaLes {
        return refuse("scheme.turbulence", "\"delta_les\"", "no δ-LES-SPH");
    }
    Ok(())
}
