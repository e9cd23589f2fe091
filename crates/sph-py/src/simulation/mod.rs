//! `deltasph.Simulation`: one running case, 2D or 3D, stepped from Python with the
//! interpreter released; its state read and set through numpy arrays.

use crate::arrays;
use crate::config;
use crate::edits::{set_density, set_velocities};
use crate::errors::to_py;
use crate::folder::{folder_options, Folder};
use crate::measures;
use crate::stepping::Target;
use numpy::{PyArray1, PyArray2};
use pyo3::exceptions::{PyFileNotFoundError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use sph_core::io::restart;
use sph_core::{Case, Simulation};
use std::path::PathBuf;

/// The `kind` of a row whose particle left the domain.
const REMOVED: u8 = 255;

/// Rows of the state arrays: one per id ever given.
pub(crate) fn rows<const D: usize>(s: &Simulation<D>) -> usize {
    s.particles().next_id as usize
}

/// The solver, with its dimension resolved at construction.
enum Solver {
    Two(Simulation<2>),
    Three(Simulation<3>),
}

/// Runs `$body` with `$s` bound to the `Simulation<D>` inside a [`Solver`].
macro_rules! each {
    ($solver:expr, $s:ident => $body:expr) => {
        match $solver {
            Solver::Two($s) => $body,
            Solver::Three($s) => $body,
        }
    };
}

mod driving;

/// A weakly-compressible δ-SPH simulation.
///
/// Build it from a dict with the keys of the TOML case file (see docs/case_file.md), or with :meth:`Simulation.from_toml`. State arrays are copies in
/// particle-id order: row ``i`` is always the particle created ``i``-th.
#[pyclass(module = "deltasph", name = "Simulation")]
pub struct PySimulation {
    solver: Solver,
    /// Whether stored pressures (and wall densities) match the current positions.
    pressure_fresh: bool,
    /// The run folder of `run(out=...)`.
    folder: Folder,
    /// The guard's message once it has stopped the run.
    failed: Option<String>,
    /// The solver's notices already raised as Python warnings.
    notices_shown: usize,
}

#[pymethods]
impl PySimulation {
    /// Builds a simulation from a dict mirroring the TOML case file, key for key.
    ///
    /// Raises ConfigError (a ValueError) for a bad value and ConfigKeyError (also a
    /// KeyError) for an unknown or missing key, with the command line's message.
    #[new]
    fn new(py: Python<'_>, config: &Bound<'_, PyAny>) -> PyResult<Self> {
        let Ok(dict) = config.cast::<PyDict>() else {
            return Err(PyTypeError::new_err(format!(
                "config: got {}, expected a dict with the keys of a case file \
                 (or use Simulation.from_toml(path))",
                config.get_type().name()?
            )));
        };
        let table = config::table(dict, "")?;
        let case = Case::from_table(table).map_err(|e| to_py(py, e))?;
        Self::build(py, case)
    }

    /// Builds a simulation from a TOML case file.
    #[staticmethod]
    fn from_toml(py: Python<'_>, path: PathBuf) -> PyResult<Self> {
        if !path.is_file() {
            return Err(PyFileNotFoundError::new_err(format!(
                "{}: no such case file",
                path.display()
            )));
        }
        let case = Case::from_file(&path).map_err(|e| to_py(py, e))?;
        Self::build(py, case)
    }

    /// The case as TOML text (every key, defaults filled in): what reproduces this run.
    fn to_toml(&self) -> PyResult<String> {
        toml::to_string(self.case()).map_err(|e| PyValueError::new_err(e.to_string()))
    }

    /// Advances to simulated time ``until`` [s] (default: the case's ``time.end``),
    /// the last step shortened to land on it; stops early at ``time.max_steps``.
    ///
    /// The interpreter is released while the solver runs; Ctrl-C raises
    /// KeyboardInterrupt between steps and leaves a consistent state. ``progress``:
    /// True for a progress bar (tqdm when installed), or a callable
    /// ``progress(time, n_steps)`` called about ten times a second. Raises
    /// InstabilityError if the run blows up; the state at that moment is kept.
    ///
    /// With ``out``, writes the command line's run folder there, by the same rules:
    /// snapshots every ``output_interval`` [s] (default: the case's
    /// ``time.output_interval``) indexed by ``particles.xmf``, ``timeseries.csv``,
    /// ``case.toml`` and restart files (on ``output.restart_interval``, every
    /// ``checkpoint_every`` seconds of wall time, and at the end). A folder that holds
    /// an earlier run is refused unless ``force`` (even then only deltasph's files are
    /// replaced); later calls with the same ``out`` continue it, and so does the
    /// folder of the restart file a simulation was built from. Ctrl-C writes a last
    /// snapshot and a restart file before KeyboardInterrupt; a blow-up writes a last
    /// snapshot.
    #[pyo3(signature = (until=None, progress=None, *, out=None, output_interval=None, force=false, checkpoint_every=None))]
    #[allow(clippy::too_many_arguments)]
    fn run(
        &mut self,
        py: Python<'_>,
        until: Option<f64>,
        progress: Option<Bound<'_, PyAny>>,
        out: Option<PathBuf>,
        output_interval: Option<f64>,
        force: bool,
        checkpoint_every: Option<f64>,
    ) -> PyResult<()> {
        let until = until.unwrap_or(self.case().time.end);
        if !until.is_finite() {
            return Err(PyValueError::new_err(format!(
                "until = {until}: expected a finite time in seconds"
            )));
        }
        if until < self.time() {
            return Err(PyValueError::new_err(format!(
                "until = {until} s: expected a time no earlier than the simulation's, \
                 t = {} s (a run cannot go back in time)",
                self.time()
            )));
        }
        let folder = match out {
            Some(out) => Some(folder_options(out, force, checkpoint_every)?),
            None if output_interval.is_some() || force || checkpoint_every.is_some() => {
                return Err(PyValueError::new_err(
                    "output_interval, force and checkpoint_every: expected them only with \
                     out=<run folder>",
                ))
            }
            None => None,
        };
        let target = Target::Time {
            until,
            max_steps: self.case().time.max_steps.unwrap_or(u64::MAX),
        };
        let helpers = py.import("deltasph._progress")?;
        let report = helpers.call_method1("reporter", (progress, self.time(), until))?;
        let report_ref = (!report.is_none()).then_some(&report);
        self.check_not_failed()?;
        let outcome = match folder {
            Some(options) => self.drive_folder(py, until, output_interval, &options, report_ref),
            None => self.drive(py, target, report_ref),
        };
        helpers.call_method1("close", (report,))?;
        self.settle(py, outcome)
    }

    /// Continues the run saved in a restart file (``restart.h5`` of a run folder), bit
    /// for bit, to ``until`` [s] when given (else the case's end time). ``run`` with
    /// ``out`` set to the restart file's folder goes on writing that folder, as
    /// ``sph-cli run --restart`` does.
    #[staticmethod]
    #[pyo3(signature = (path, until=None))]
    fn from_restart(py: Python<'_>, path: PathBuf, until: Option<f64>) -> PyResult<Self> {
        if !path.is_file() {
            return Err(PyFileNotFoundError::new_err(format!(
                "{}: no such restart file",
                path.display()
            )));
        }
        let built = py.detach(|| -> sph_core::Result<_> {
            Ok(match restart::dimension(&path)? {
                2 => {
                    let (checkpoint, schedule) = restart::read::<2>(&path)?;
                    (
                        Solver::Two(Simulation::from_checkpoint(checkpoint, until)?),
                        schedule,
                    )
                }
                _ => {
                    let (checkpoint, schedule) = restart::read::<3>(&path)?;
                    (
                        Solver::Three(Simulation::from_checkpoint(checkpoint, until)?),
                        schedule,
                    )
                }
            })
        });
        let (solver, schedule) = built.map_err(|e| to_py(py, e))?;
        Ok(Self::holding(
            solver,
            false,
            Folder::continuing(&path, schedule),
        ))
    }

    /// Advances exactly ``n`` steps (default 1), with the interpreter released.
    #[pyo3(signature = (n=None))]
    fn step(&mut self, py: Python<'_>, n: Option<Bound<'_, PyAny>>) -> PyResult<()> {
        let n: u64 = match n {
            None => 1,
            Some(n) => match n.extract::<u64>() {
                Ok(n) => n,
                Err(_) if n.extract::<i64>().is_ok_and(|k| k < 0) => {
                    return Err(PyValueError::new_err(format!(
                        "n = {n}: expected a number of steps, 0 or more"
                    )))
                }
                Err(e) => return Err(e),
            },
        };
        self.check_not_failed()?;
        let Some(last) = self.n_steps().checked_add(n) else {
            return Err(PyValueError::new_err(format!(
                "n = {n}: expected a step count below {} (2^64 minus the steps taken)",
                u64::MAX - self.n_steps()
            )));
        };
        let target = Target::Steps(last);
        let outcome = self.drive(py, target, None);
        self.settle(py, outcome)
    }

    /// The stability guard's message if it stopped this simulation (its state arrays
    /// then hold the blown-up state, kept for inspection), else None.
    #[getter]
    fn failed(&self) -> Option<String> {
        self.failed.clone()
    }

    /// Mass [kg] of the fluid removed so far because it left the domain (per metre of
    /// depth in 2D).
    #[getter]
    fn removed_mass(&self) -> f64 {
        each!(&self.solver, s => s.removed_mass())
    }

    /// Simulated time [s].
    #[getter]
    fn time(&self) -> f64 {
        each!(&self.solver, s => s.time())
    }

    /// The last time step [s] (0 before the first step).
    #[getter]
    fn dt(&self) -> f64 {
        each!(&self.solver, s => s.dt())
    }

    /// Steps taken so far.
    #[getter]
    fn n_steps(&self) -> u64 {
        each!(&self.solver, s => s.counters().steps)
    }

    /// 2 or 3.
    #[getter]
    fn dimension(&self) -> usize {
        self.case().dimension
    }

    /// The case's name.
    #[getter]
    fn name(&self) -> String {
        self.case().name.clone()
    }

    /// Fluid particles removed so far because they left the domain (their rows in the
    /// state arrays hold NaN, kind 255).
    #[getter]
    fn n_removed(&self) -> u64 {
        each!(&self.solver, s => s.removed())
    }

    /// Fluid particles created so far at inlets (each with a new id, a new row).
    #[getter]
    fn n_created(&self) -> u64 {
        each!(&self.solver, s => s.counters().created)
    }

    /// Number of particles in the run, fluid and wall (the state arrays have a row
    /// for every id ever given: this plus ``n_removed``).
    #[getter]
    fn n_particles(&self) -> usize {
        each!(&self.solver, s => s.particles().len())
    }

    /// Number of fluid particles.
    #[getter]
    fn n_fluid(&self) -> usize {
        each!(&self.solver, s => s.n_fluid())
    }

    /// Numerical sound speed c0 [m/s].
    #[getter]
    fn sound_speed(&self) -> f64 {
        each!(&self.solver, s => s.physics().eos.c0)
    }

    /// Reference density ρ0 [kg/m³].
    #[getter]
    fn reference_density(&self) -> f64 {
        each!(&self.solver, s => s.physics().eos.rho0)
    }

    /// Smoothing length h [m].
    #[getter]
    fn smoothing_length(&self) -> f64 {
        self.case().h()
    }

    /// Initial particle spacing Δx [m].
    #[getter]
    fn spacing(&self) -> f64 {
        self.case().dx()
    }

    /// Positions [m], float64 array (N, D), a copy.
    #[getter]
    fn positions<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        each!(&self.solver, s => arrays::vectors(py, &s.particles().id, rows(s), &s.particles().x))
    }

    /// Velocities [m/s], float64 array (N, D), a copy. Wall rows hold the walls'
    /// prescribed velocities: zero, or ``tank.lid_velocity`` for a sliding lid.
    #[getter]
    fn velocities<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        each!(&self.solver, s => arrays::vectors(py, &s.particles().id, rows(s), &s.particles().u))
    }

    /// Density [kg/m³], float64 array (N,), a copy; walls carry their extrapolated value.
    #[getter]
    fn density<'py>(&mut self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.fresh_pressure();
        each!(&self.solver, s => arrays::scalars(py, &s.particles().id, rows(s), &s.particles().rho, (f64::NAN, |v| v)))
    }

    /// Pressure [Pa], float64 array (N,), a copy: the EOS for fluid, the
    /// extrapolation of Adami et al. (2012) for walls.
    #[getter]
    fn pressure<'py>(&mut self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.fresh_pressure();
        each!(&self.solver, s => arrays::scalars(py, &s.particles().id, rows(s), &s.particles().p, (f64::NAN, |v| v)))
    }

    /// Mass [kg] (per unit depth in 2D), float64 array (N,), a copy.
    #[getter]
    fn mass<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        each!(&self.solver, s => arrays::scalars(py, &s.particles().id, rows(s), &s.particles().mass, (f64::NAN, |v| v)))
    }

    /// Particle kind, uint8 array (N,): 0 fluid (deltasph.FLUID), 1 wall (deltasph.WALL).
    #[getter]
    fn kind<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<u8>> {
        each!(&self.solver, s => arrays::scalars(py, &s.particles().id, rows(s), &s.particles().kind, (REMOVED, |k| k as u8)))
    }

    /// Fluid particles inside a wall now: past the first layer of wall particles of a
    /// closed tank face, or deeper than Δx/2 in a ``[[wall]]`` box. Zero in a sound run.
    fn wall_crossings(&self) -> usize {
        each!(&self.solver, s => s.wall_crossings())
    }

    /// Energies [J] (per unit depth in 2D): of the fluid ``kinetic``, ``potential``,
    /// ``internal`` (compressible, docs/theory.md §10) and ``total`` (their sum);
    /// ``bodies``, the free bodies' kinetic, potential and spring energy (0 without
    /// any); ``dissipated``, the energy taken out so far by viscosity, density
    /// diffusion, the walls and the bodies' dampers net of what moving walls put in,
    /// -∫(P_V + P_D + P_W + P_M + P_B) dt, so that ``total + bodies + dissipated`` stays
    /// constant; ``moving_work``, the moving walls' work on the fluid ∫P_M dt (free
    /// bodies' walls included). The last two are None
    /// unless the case sets ``diagnostics.energy_budget = true``.
    fn energies<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        each!(&self.solver, s => measures::energies(py, s))
    }

    /// The fluid's load on each body (every tank and wall, by name, in case order) at
    /// the current state: ``{name: {"pressure": (D,), "viscous": (D,), "moment": (3,)}}``
    /// in N (per unit width in 2D) and N m about ``diagnostics.moment_point``. The
    /// loads are minus the wall terms of the fluid's momentum equation.
    fn loads<'py>(&mut self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let dict = each!(&mut self.solver, s => measures::loads(py, s))?;
        self.pressure_fresh = true;
        Ok(dict)
    }

    /// The moving bodies now (``motion = "prescribed"``), by name:
    /// ``{name: {"position": (D,), "rotation": (1,) or (3,), "velocity": (D,),
    /// "angular_velocity": (1,) or (3,)}}``: the pivot's position [m] and velocity
    /// [m/s], the rotation [rad] (2D the angle about z, 3D the rotation vector) and the
    /// angular velocity [rad/s]. Empty when every body is fixed.
    fn body_motions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        each!(&self.solver, s => measures::body_motions(py, s))
    }

    /// The prescribed motions (wave makers included) at ``times`` (array-like of
    /// seconds, any times, not only the run's), by body name:
    /// ``{name: {"position": (M, D), "rotation": (M, 1) or (M, 3), "velocity": (M, D),
    /// "angular_velocity": (M, 1) or (M, 3)}}``, as :meth:`body_motions` gives them
    /// now. Free bodies are left out (their motion is not known ahead); an absorbing
    /// wave maker's correction is its current one, extrapolated.
    fn prescribed_motion<'py>(
        &self,
        py: Python<'py>,
        times: Vec<f64>,
    ) -> PyResult<Bound<'py, PyDict>> {
        each!(&self.solver, s => measures::prescribed_motion(py, s, times))
    }

    /// The free surface's elevation [m] above ``diagnostics.still_level`` now, as wave
    /// gauges read it (where the fluid's kernel sum crosses 1/2 on a vertical line; a
    /// dry line reads its bottom): ``positions`` are x values (2D) or (x, y) rows
    /// (3D); returns (M,). The lines run over the domain's or the tanks' height
    /// (ValueError where the case gives neither).
    fn wave_elevation<'py>(
        &self,
        py: Python<'py>,
        positions: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        each!(&self.solver, s => measures::wave_elevation(py, s, positions))
    }

    /// Pressure [Pa] interpolated (Shepard) from the fluid at ``points``: array-like
    /// (M, D), returning (M,); or one point (D,), returning (1,). A point with no
    /// fluid within the kernel support reads NaN (no fluid there, which is not zero
    /// pressure; ``numpy.nan_to_num`` turns it into zero gauge pressure). A point
    /// no fluid can ever reach (outside the domain, or deeper than the kernel support
    /// inside a wall) raises ValueError.
    fn probe_pressure<'py>(
        &mut self,
        py: Python<'py>,
        points: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        self.fresh_pressure();
        each!(&self.solver, s => measures::probe_pressure(py, s, points))
    }

    /// Fluid velocity [m/s] interpolated (Shepard) from the fluid at ``points``:
    /// array-like (M, D) or one point (D,), returning (M, D); NaN rows where no fluid
    /// is within the kernel support, ValueError where none can ever be (as
    /// :meth:`probe_pressure`).
    fn probe_velocity<'py>(
        &self,
        py: Python<'py>,
        points: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        each!(&self.solver, s => measures::probe_velocity(py, s, points))
    }

    /// Free-surface detection (Marrone et al. 2010) at the current state, in id order:
    /// ``on_surface`` (bool, N), ``normal`` (unit outward normal estimate, N × D; zero
    /// for walls) and ``lambda`` (smallest eigenvalue of the renormalisation matrix,
    /// about 1 inside, 0.5 at the surface).
    fn free_surface<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        each!(&self.solver, s => measures::free_surface(py, s))
    }

    /// Sets the fluid velocities [m/s] from a float64 array (N, D) in id order (as
    /// ``velocities`` returns it). Wall rows must hold the walls' own velocities, as
    /// ``velocities`` returns them (zero, or a lid's sliding velocity): wall motion
    /// comes from the case, not from this call.
    fn set_velocities(&mut self, velocities: &Bound<'_, PyAny>) -> PyResult<()> {
        each!(&mut self.solver, s => set_velocities(s, velocities))?;
        self.pressure_fresh = true;
        Ok(())
    }

    /// Sets all densities [kg/m³] from a positive float64 array (N,) in id order.
    /// Wall rows are accepted but recomputed from the fluid (Adami extrapolation).
    fn set_density(&mut self, density: &Bound<'_, PyAny>) -> PyResult<()> {
        each!(&mut self.solver, s => set_density(s, density))?;
        self.pressure_fresh = true;
        Ok(())
    }

    /// Writes the state to ``path`` (HDF5, the layout of the command line's
    /// snapshots) and an XDMF index beside it (``path`` with ``.xmf``) for ParaView.
    /// Existing files are kept (OSError) unless ``overwrite``; even then only files
    /// that deltasph wrote are replaced, never another program's. Returns the index path.
    #[pyo3(signature = (path, overwrite=false))]
    fn write_snapshot(
        &mut self,
        py: Python<'_>,
        path: PathBuf,
        overwrite: bool,
    ) -> PyResult<PathBuf> {
        self.fresh_pressure();
        each!(&self.solver, s => sph_core::io::output::with_extras(s, |extras| {
            sph_core::io::output::write_indexed_snapshot(
                &path,
                s.particles(),
                extras,
                s.time(),
                s.counters().steps,
                overwrite,
            )
        }))
        .map_err(|e| to_py(py, e))
    }

    fn __repr__(&self) -> String {
        format!(
            "Simulation('{}', {}D, {} fluid + {} wall particles, t = {:.6} s, {} steps{})",
            self.name(),
            self.dimension(),
            self.n_fluid(),
            self.n_particles() - self.n_fluid(),
            self.time(),
            self.n_steps(),
            if self.failed.is_some() {
                ", failed"
            } else {
                ""
            }
        )
    }
}
