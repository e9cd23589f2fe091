//! The time-series row of a run: the columns its case asks for, and their values.

use super::Simulation;
use crate::diagnostics::sensors::Sensor;
use crate::particles::Vector;

/// The time-series columns a case asks for, and their values now.
impl<const D: usize> Simulation<D> {
    pub fn series_header(&self) -> Vec<String> {
        let mut h: Vec<String> = ["time", "step", "dt"].map(String::from).to_vec();
        let diag = &self.case.diagnostics;
        if diag.energy || diag.energy_budget {
            h.extend(["kinetic", "potential", "internal", "total"].map(String::from));
        }
        if self.budget.is_some() {
            h.extend(
                [
                    "work_of_dissipation_and_walls",
                    "viscous_power",
                    "diffusive_power",
                    "wall_power",
                    "removed_energy",
                ]
                .map(String::from),
            );
        }
        h.push("max_density_variation".into());
        h.push("removed".into());
        if !self.case.open_boundary.is_empty() {
            h.push("created".into());
        }
        h.extend((0..diag.probes.len()).map(|k| format!("probe{k}_pressure")));
        for s in &self.sensors {
            h.extend([format!("{}_pressure", s.name), format!("{}_point", s.name)]);
            if s.filter.is_some() {
                h.push(format!("{}_filtered", s.name));
            }
        }
        if diag.surge_front_axis.is_some() {
            h.push("surge_front".into());
        }
        if diag.loads {
            let coefficients = self.case.dynamic_force().is_some();
            for b in &self.bodies {
                h.extend(load_columns(&b.name, D, coefficients));
            }
        }
        h
    }

    /// One row matching [`Self::series_header`]; refreshes pressures when probes need
    /// them, and advances the sensors' filters by one reading. In a split run every
    /// process gets the whole run's row (collective).
    pub fn series_values(&mut self) -> Vec<f64> {
        let diag = self.case.diagnostics.clone();
        let mut v = vec![self.time, self.counters.steps as f64, self.dt];
        if diag.energy || diag.energy_budget {
            let e = self.energies();
            v.extend([e.kinetic, e.potential, e.internal, e.total()]);
        }
        if let Some(b) = self.budget {
            v.extend([
                b.work(),
                b.last.viscous,
                b.last.diffusive,
                b.last.wall,
                b.removed_energy,
            ]);
        }
        v.push(self.max_density_variation());
        v.push(self.removed() as f64);
        if !self.case.open_boundary.is_empty() {
            v.push(self.counters.created as f64);
        }
        if !diag.probes.is_empty() || !self.sensors.is_empty() {
            self.sync_pressure();
            let points: Vec<Vector<D>> = (diag.probes.iter())
                .map(|probe| Vector::<D>::from_fn(|d, _| probe[d]))
                .collect();
            let values = self.probe_pressures(&points);
            v.extend(values.iter().map(|p| p.unwrap_or(f64::NAN)));
        }
        let mut sensors = std::mem::take(&mut self.sensors);
        for s in &mut sensors {
            let mut points = s.points.clone();
            points.push(s.centre);
            // a sensor's face in air reads zero gauge pressure, as a transducer does
            let values: Vec<f64> = (self.probe_pressures(&points).iter())
                .map(|p| p.unwrap_or(0.0))
                .collect();
            let (face, centre) = (
                Sensor::<D>::mean(values[..s.points.len()].iter().copied()),
                values[s.points.len()],
            );
            v.extend([face, centre]);
            if let Some(filter) = &mut s.filter {
                v.push(filter.push(face));
            }
        }
        self.sensors = sensors;
        if let Some(axis) = diag.surge_front_axis {
            v.push(self.surge_front(axis));
        }
        if diag.loads {
            let dynamic = self.case.dynamic_force();
            for load in self.loads() {
                v.extend(load.pressure.iter().chain(load.viscous.iter()));
                if D == 2 {
                    v.push(load.moment[2]);
                } else {
                    v.extend(load.moment.iter());
                }
                if let Some(q) = dynamic {
                    v.extend(load.force().iter().map(|f| f / q));
                }
            }
        }
        v
    }
}

/// A body's load columns: `<name>_pressure_fx …`, `<name>_viscous_fx …`, then the
/// moment (`<name>_moment_z` in 2D, `_x _y _z` in 3D), then with reference scales the
/// force coefficients `<name>_cx …` of the total force.
fn load_columns(name: &str, dim: usize, coefficients: bool) -> Vec<String> {
    let axes = &["x", "y", "z"][..dim];
    let forces = ["pressure", "viscous"]
        .iter()
        .flat_map(|part| axes.iter().map(move |a| format!("{name}_{part}_f{a}")));
    let moments: &[&str] = if dim == 2 { &["z"] } else { &["x", "y", "z"] };
    let coefficients = axes
        .iter()
        .filter(|_| coefficients)
        .map(|a| format!("{name}_c{a}"));
    forces
        .chain(moments.iter().map(|a| format!("{name}_moment_{a}")))
        .chain(coefficients)
        .collect()
}
