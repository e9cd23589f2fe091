//! A simulation split over processes (see [`crate::distributed`]):
//! [`Simulation::distribute`] keeps this process's share of a whole run, and
//! [`Simulation::view`] gathers the whole run on process 0 for output, which then
//! writes exactly what a serial run writes.

use super::Simulation;
use crate::case::TurbulenceChoice;
use crate::distributed::{Communicator, Ranks};
use crate::error::{Result, SphError};
use std::sync::Arc;

impl<const D: usize> Simulation<D> {
    /// Splits a whole run, built alike on every process (from its case or restart
    /// file), over the processes of `comm` by recursive coordinate bisection, and keeps
    /// this process's share. Collective. On process 0 the whole run stays as the
    /// [`Self::view`] that output is written from.
    pub fn distribute(self, comm: Arc<dyn Communicator>) -> Result<Self> {
        check_splittable(&self)?;
        if comm.size() == 1 {
            return Ok(self);
        }
        let (mut local, view) = if comm.rank() == 0 {
            let mut local = Self::new(self.case.clone())?;
            local.particles = self.particles.clone();
            local.shift_velocity.clone_from(&self.shift_velocity);
            (local.time, local.dt) = (self.time, self.dt);
            (local.counters, local.last_acceleration) = (self.counters, self.last_acceleration);
            (local, Some(Box::new(self)))
        } else {
            (self, None)
        };
        let passes = local.halo_passes();
        let ranks = Ranks::split(
            comm,
            &mut local.particles,
            local.shift_velocity.as_mut(),
            &local.domain,
            passes,
        );
        local.ranks = Some(ranks);
        local.view = view;
        let reach = local.reach(local.control.acoustic(), local.max_speed());
        local.rebuild(reach);
        Ok(local)
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
