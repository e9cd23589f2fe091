//! The time series of a run: one [`Observer`] per group of columns, registered from
//! the case by [`observers`] in column order. A new diagnostic is one type that
//! implements [`Observer`] and one line in [`observers`]; what it reads from the run
//! comes through [`Measure`], which the simulation implements.

use super::budget::EnergyBudget;
use super::gauges::Gauge;
use super::sections::Section;
use super::sensors::Sensor;
use super::Energies;
use crate::boundary::bodies::{Body, Load};
use crate::case::{Case, MotionChoice};
use crate::motion::rigid::Pose;
use crate::particles::Vector;

/// What the columns read from the run at a row (collective in a split run: every
/// process computes every row).
pub trait Measure<const D: usize> {
    fn time(&self) -> f64;
    fn steps(&self) -> u64;
    fn dt(&self) -> f64;
    /// E_k, E_p and E_c of the fluid.
    fn energies(&self) -> Energies;
    fn budget(&self) -> Option<EnergyBudget>;
    /// The free bodies' mechanical energy (zero without any).
    fn free_bodies_energy(&self) -> f64;
    /// Largest `|ρ/ρ0 - 1|` over the fluid.
    fn max_density_variation(&self) -> f64;
    /// Fluid particles removed so far (left the domain).
    fn removed(&self) -> u64;
    /// Fluid particles created at inlets so far.
    fn created(&self) -> u64;
    /// Shepard-interpolated pressures at `points` (`None` where no fluid is in reach),
    /// with the pressures brought up to date first.
    fn probe_pressures(&mut self, points: &[Vector<D>]) -> Vec<Option<f64>>;
    /// Shepard-interpolated fluid velocities at `points` (`None` where no fluid is in
    /// reach).
    fn probe_velocities(&self, points: &[Vector<D>]) -> Vec<Option<Vector<D>>>;
    /// The fluid's kernel sum Γ at `points`.
    fn fluid_fractions(&self, points: &[Vector<D>]) -> Vec<f64>;
    /// The volume and mass flow densities through a section along `normal` at `points`
    /// ([`super::PointReader::flow_density`]).
    fn flow_densities(&self, points: &[Vector<D>], normal: &Vector<D>) -> Vec<[f64; 2]>;
    /// Largest fluid coordinate along `axis`.
    fn surge_front(&self, axis: usize) -> f64;
    /// The fluid's load on each body, in case order.
    fn loads(&mut self) -> Vec<Load<D>>;
    /// The pose of each moving body, in case order.
    fn body_poses(&self) -> Vec<Pose<D>>;
}

/// A group of time-series columns.
pub trait Observer<const D: usize>: Send + Sync {
    /// Appends the column names.
    fn header(&self, out: &mut Vec<String>);
    /// Appends the values now, one per column of [`Self::header`].
    fn values(&mut self, run: &mut dyn Measure<D>, out: &mut Vec<f64>);
    /// The state the columns carry from one row to the next (a filter's), for restart
    /// files; `None` when they carry none.
    fn memory(&self) -> Option<[f64; 4]> {
        None
    }
    /// Restores what [`Self::memory`] gave.
    fn recall(&mut self, _state: [f64; 4]) {}
}

/// The observers of a case, in column order.
pub fn observers<const D: usize>(case: &Case, bodies: &[Body]) -> Vec<Box<dyn Observer<D>>> {
    let diag = &case.diagnostics;
    let mut list: Vec<Box<dyn Observer<D>>> = vec![Box::new(Clock)];
    if diag.energy || diag.energy_budget {
        list.push(Box::new(EnergyColumns));
    }
    if diag.energy_budget {
        let motions = case.body_motions();
        let moves = |m: MotionChoice| motions.iter().any(|b| b.motion == m);
        list.push(Box::new(BudgetColumns {
            moving: moves(MotionChoice::Prescribed) || moves(MotionChoice::Free),
            free: moves(MotionChoice::Free),
            forcing: case.forcing.is_some() || !case.absorber.is_empty(),
        }));
    }
    list.push(Box::new(Conservation {
        created: !case.open_boundary.is_empty(),
    }));
    if !diag.probes.is_empty() {
        let points = (diag.probes.iter())
            .map(|probe| Vector::<D>::from_fn(|d, _| probe[d]))
            .collect();
        let velocity = diag.probe_velocity;
        list.push(Box::new(Probes { points, velocity }));
    }
    for s in &diag.sensors {
        let sensor = Sensor::new(s, case.dx(), case.series_interval());
        list.push(Box::new(sensor));
    }
    for g in &diag.gauges {
        list.push(Box::new(Gauge::<D>::new(case, g)));
    }
    for s in &diag.sections {
        list.push(Box::new(Section::<D>::new(s, case.dx())));
    }
    if let Some(axis) = diag.surge_front_axis {
        list.push(Box::new(SurgeFront { axis }));
    }
    if diag.loads {
        let names = bodies.iter().map(|b| b.name.clone()).collect();
        let dynamic = case.dynamic_force();
        list.push(Box::new(Loads { names, dynamic }));
    }
    if case.has_moving_bodies() {
        let names = crate::motion::moving_names(case, bodies);
        list.push(Box::new(BodyMotions { names }));
    }
    list
}

/// Per moving body: `<name>_x`, `_y` (`_z`) the pivot's position, the rotation
/// (2D `<name>_angle`; 3D `_rx`, `_ry`, `_rz`, the rotation vector), the pivot's
/// velocity `_u`, `_v` (`_w`) and the angular velocity (2D `_omega`; 3D `_omega_x`,
/// `_omega_y`, `_omega_z`).
struct BodyMotions {
    names: Vec<String>,
}

impl<const D: usize> Observer<D> for BodyMotions {
    fn header(&self, out: &mut Vec<String>) {
        let (axes, velocities) = (&["x", "y", "z"][..D], &["u", "v", "w"][..D]);
        let (rotation, omega): (&[&str], &[&str]) = match D {
            2 => (&["angle"], &["omega"]),
            _ => (&["rx", "ry", "rz"], &["omega_x", "omega_y", "omega_z"]),
        };
        for name in &self.names {
            let all = axes.iter().chain(rotation).chain(velocities).chain(omega);
            out.extend(all.map(|c| format!("{name}_{c}")));
        }
    }
    fn values(&mut self, run: &mut dyn Measure<D>, out: &mut Vec<f64>) {
        let turned: &[usize] = if D == 2 { &[2] } else { &[0, 1, 2] };
        for pose in run.body_poses() {
            out.extend(pose.pivot.iter());
            out.extend(turned.iter().map(|&k| pose.phi[k]));
            out.extend(pose.velocity.iter());
            out.extend(turned.iter().map(|&k| pose.omega[k]));
        }
    }
}

/// `time`, `step`, `dt`.
struct Clock;

impl<const D: usize> Observer<D> for Clock {
    fn header(&self, out: &mut Vec<String>) {
        out.extend(["time", "step", "dt"].map(String::from));
    }
    fn values(&mut self, run: &mut dyn Measure<D>, out: &mut Vec<f64>) {
        out.extend([run.time(), run.steps() as f64, run.dt()]);
    }
}

/// `kinetic`, `potential`, `internal`, `total`.
struct EnergyColumns;

impl<const D: usize> Observer<D> for EnergyColumns {
    fn header(&self, out: &mut Vec<String>) {
        out.extend(["kinetic", "potential", "internal", "total"].map(String::from));
    }
    fn values(&mut self, run: &mut dyn Measure<D>, out: &mut Vec<f64>) {
        let e = run.energies();
        out.extend([e.kinetic, e.potential, e.internal, e.total()]);
    }
}

/// The energy budget's work and powers (see [`super::budget`]); with moving bodies the
/// moving walls' power, with free bodies their power and energy, and with a body force
/// or absorbers their power and work (within the total work). The closure is
/// `total + free_bodies_energy + removed_energy - work_of_dissipation_and_walls`.
struct BudgetColumns {
    moving: bool,
    free: bool,
    /// Whether a body force or an absorber works on the fluid.
    forcing: bool,
}

impl<const D: usize> Observer<D> for BudgetColumns {
    fn header(&self, out: &mut Vec<String>) {
        out.extend(
            [
                "work_of_dissipation_and_walls",
                "viscous_power",
                "diffusive_power",
                "wall_power",
                "removed_energy",
            ]
            .map(String::from),
        );
        if self.moving {
            out.extend(["moving_wall_power", "moving_wall_work"].map(String::from));
        }
        if self.free {
            out.extend(["free_body_power", "free_bodies_energy"].map(String::from));
        }
        if self.forcing {
            out.extend(["forcing_power", "forcing_work"].map(String::from));
        }
    }
    fn values(&mut self, run: &mut dyn Measure<D>, out: &mut Vec<f64>) {
        let b = run.budget().unwrap_or_default();
        out.extend([
            b.work(),
            b.last.viscous,
            b.last.diffusive,
            b.last.wall,
            b.removed_energy,
        ]);
        if self.moving {
            out.extend([b.last.moving, b.work_of_moving_walls()]);
        }
        if self.free {
            out.extend([b.last.bodies, run.free_bodies_energy()]);
        }
        if self.forcing {
            out.extend([b.last.forcing, b.work_of_forcing()]);
        }
    }
}

/// `max_density_variation`, `removed`, and `created` with open boundaries.
struct Conservation {
    created: bool,
}

impl<const D: usize> Observer<D> for Conservation {
    fn header(&self, out: &mut Vec<String>) {
        out.extend(["max_density_variation", "removed"].map(String::from));
        if self.created {
            out.push("created".into());
        }
    }
    fn values(&mut self, run: &mut dyn Measure<D>, out: &mut Vec<f64>) {
        out.extend([run.max_density_variation(), run.removed() as f64]);
        if self.created {
            out.push(run.created() as f64);
        }
    }
}

/// `probe<k>_pressure`: NaN where no fluid is in reach.
struct Probes<const D: usize> {
    points: Vec<Vector<D>>,
    /// Also `probe<k>_u`, `_v` (`_w`).
    velocity: bool,
}

impl<const D: usize> Observer<D> for Probes<D> {
    fn header(&self, out: &mut Vec<String>) {
        out.extend((0..self.points.len()).map(|k| format!("probe{k}_pressure")));
        if self.velocity {
            for k in 0..self.points.len() {
                out.extend(["u", "v", "w"][..D].iter().map(|c| format!("probe{k}_{c}")));
            }
        }
    }
    fn values(&mut self, run: &mut dyn Measure<D>, out: &mut Vec<f64>) {
        let values = run.probe_pressures(&self.points);
        out.extend(values.iter().map(|p| p.unwrap_or(f64::NAN)));
        if self.velocity {
            for u in run.probe_velocities(&self.points) {
                out.extend(u.unwrap_or(Vector::repeat(f64::NAN)).iter());
            }
        }
    }
}

/// `<name>_pressure` (the face average), `<name>_point` (at its centre) and, with a
/// filter, `<name>_filtered`; the filter advances by one reading a row.
impl<const D: usize> Observer<D> for Sensor<D> {
    fn header(&self, out: &mut Vec<String>) {
        out.extend([
            format!("{}_pressure", self.name),
            format!("{}_point", self.name),
        ]);
        if self.filter.is_some() {
            out.push(format!("{}_filtered", self.name));
        }
    }
    fn values(&mut self, run: &mut dyn Measure<D>, out: &mut Vec<f64>) {
        let mut points = self.points.clone();
        points.push(self.centre);
        // a sensor's face in air reads zero gauge pressure, as a transducer does
        let values: Vec<f64> = (run.probe_pressures(&points).iter())
            .map(|p| p.unwrap_or(0.0))
            .collect();
        let n = self.points.len();
        let face = Sensor::<D>::mean(values[..n].iter().copied());
        out.extend([face, values[n]]);
        if let Some(filter) = &mut self.filter {
            out.push(filter.push(face));
        }
    }
    fn memory(&self) -> Option<[f64; 4]> {
        self.filter.map(|f| f.state)
    }
    fn recall(&mut self, state: [f64; 4]) {
        if let Some(f) = &mut self.filter {
            f.state = state;
        }
    }
}

/// `<name>_elevation`: the free surface's height above the still level.
impl<const D: usize> Observer<D> for Gauge<D> {
    fn header(&self, out: &mut Vec<String>) {
        out.push(format!("{}_elevation", self.name));
    }
    fn values(&mut self, run: &mut dyn Measure<D>, out: &mut Vec<f64>) {
        out.push(self.elevation(&run.fluid_fractions(&self.points)));
    }
}

/// `<name>_volume_flow`, `<name>_mass_flow`: the flow through the section.
impl<const D: usize> Observer<D> for Section<D> {
    fn header(&self, out: &mut Vec<String>) {
        out.extend(["volume_flow", "mass_flow"].map(|c| format!("{}_{c}", self.name)));
    }
    fn values(&mut self, run: &mut dyn Measure<D>, out: &mut Vec<f64>) {
        out.extend(self.flow(&run.flow_densities(&self.points, &self.normal)));
    }
}

/// `surge_front`: the largest fluid coordinate along an axis.
struct SurgeFront {
    axis: usize,
}

impl<const D: usize> Observer<D> for SurgeFront {
    fn header(&self, out: &mut Vec<String>) {
        out.push("surge_front".into());
    }
    fn values(&mut self, run: &mut dyn Measure<D>, out: &mut Vec<f64>) {
        out.push(run.surge_front(self.axis));
    }
}

/// Each body's load: `<name>_pressure_fx …`, `<name>_viscous_fx …`, the moment
/// (`<name>_moment_z` in 2D, `_x _y _z` in 3D), then with reference scales the force
/// coefficients `<name>_cx …` of the total force.
struct Loads {
    names: Vec<String>,
    /// `ρ U² L^(D-1) / 2`, when the case gives reference scales.
    dynamic: Option<f64>,
}

impl<const D: usize> Observer<D> for Loads {
    fn header(&self, out: &mut Vec<String>) {
        let axes = &["x", "y", "z"][..D];
        let moments: &[&str] = if D == 2 { &["z"] } else { &["x", "y", "z"] };
        for name in &self.names {
            for part in ["pressure", "viscous"] {
                out.extend(axes.iter().map(|a| format!("{name}_{part}_f{a}")));
            }
            out.extend(moments.iter().map(|a| format!("{name}_moment_{a}")));
            if self.dynamic.is_some() {
                out.extend(axes.iter().map(|a| format!("{name}_c{a}")));
            }
        }
    }
    fn values(&mut self, run: &mut dyn Measure<D>, out: &mut Vec<f64>) {
        for load in run.loads() {
            out.extend(load.pressure.iter().chain(load.viscous.iter()));
            if D == 2 {
                out.push(load.moment[2]);
            } else {
                out.extend(load.moment.iter());
            }
            if let Some(q) = self.dynamic {
                out.extend(load.force().iter().map(|f| f / q));
            }
        }
    }
}
