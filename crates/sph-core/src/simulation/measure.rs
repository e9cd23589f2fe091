//! The time-series row of a run: its observers' columns
//! ([`crate::diagnostics::series`]), measured on the simulation through [`Row`].

use super::{EnergyBudget, Simulation};
use crate::boundary::bodies::Load;
use crate::diagnostics::series::Measure;
use crate::diagnostics::Energies;
use crate::motion::rigid::Pose;
use crate::particles::Vector;

impl<const D: usize> Simulation<D> {
    /// The names of the time-series columns the case asks for.
    pub fn series_header(&self) -> Vec<String> {
        let mut h = Vec::new();
        self.observers.iter().for_each(|o| o.header(&mut h));
        h
    }

    /// One row matching [`Self::series_header`]; refreshes pressures when probes need
    /// them, and advances the sensors' filters by one reading. In a split run every
    /// process gets the whole run's row (collective).
    pub fn series_values(&mut self) -> Vec<f64> {
        let mut observers = std::mem::take(&mut self.observers);
        let mut row = Row {
            sim: self,
            synced: false,
        };
        let mut v = Vec::new();
        observers
            .iter_mut()
            .for_each(|o| o.values(&mut row, &mut v));
        self.observers = observers;
        v
    }
}

/// The simulation as one row's observers see it: the pressures are brought up to date
/// once, by the first probe.
struct Row<'a, const D: usize> {
    sim: &'a mut Simulation<D>,
    synced: bool,
}

impl<const D: usize> Measure<D> for Row<'_, D> {
    fn time(&self) -> f64 {
        self.sim.time()
    }
    fn steps(&self) -> u64 {
        self.sim.counters().steps
    }
    fn dt(&self) -> f64 {
        self.sim.dt()
    }
    fn energies(&self) -> Energies {
        self.sim.energies()
    }
    fn budget(&self) -> Option<EnergyBudget> {
        self.sim.budget()
    }
    fn free_bodies_energy(&self) -> f64 {
        (self.sim.motions()).map_or(0.0, crate::motion::Motions::free_energy)
    }
    fn max_density_variation(&self) -> f64 {
        self.sim.max_density_variation()
    }
    fn removed(&self) -> u64 {
        self.sim.removed()
    }
    fn created(&self) -> u64 {
        self.sim.counters().created
    }
    fn probe_pressures(&mut self, points: &[Vector<D>]) -> Vec<Option<f64>> {
        if !self.synced {
            self.sim.sync_pressure();
            self.synced = true;
        }
        self.sim.probe_pressures(points)
    }
    fn probe_velocities(&self, points: &[Vector<D>]) -> Vec<Option<Vector<D>>> {
        self.sim.probe_velocities(points)
    }
    fn fluid_fractions(&self, points: &[Vector<D>]) -> Vec<f64> {
        self.sim.fluid_fractions(points)
    }
    fn flow_densities(&self, points: &[Vector<D>], normal: &Vector<D>) -> Vec<[f64; 2]> {
        self.sim.flow_densities(points, normal)
    }
    fn surge_front(&self, axis: usize) -> f64 {
        self.sim.surge_front(axis)
    }
    fn loads(&mut self) -> Vec<Load<D>> {
        self.sim.loads()
    }
    fn body_poses(&self) -> Vec<Pose<D>> {
        self.sim.body_poses()
    }
}
