//! Run folders from Python: the command line's folder (snapshots, XDMF index, time
//! series, case copy, restart files, under the same safety rules), written by the same
//! driver ([`sph_core::run::Run`]), and snapshots read back as numpy arrays.

use crate::errors::to_py;
use numpy::{PyArray1, PyArrayMethods};
use pyo3::exceptions::{PyKeyboardInterrupt, PyOSError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use sph_core::io::output::reading::{read_snapshot as read, Field};
use sph_core::io::output::Output;
use sph_core::io::restart::Schedule;
use sph_core::run::{Control, Ending, Run};
use sph_core::Simulation;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Duration;

/// The signal number a Ctrl-C stop is recorded under (SIGINT).
const SIGINT: usize = 2;

/// How long the driver runs detached before Python looks at Ctrl-C and progress.
const SLICE: Duration = Duration::from_millis(100);

/// Where a simulation writes its run folder, and the folder it may continue.
#[derive(Default)]
pub struct Folder {
    /// The folder `run(out=...)` opened last, with its schedule.
    run: Option<Run>,
    /// The folder and schedule of the restart file the simulation was built from.
    restart: Option<(PathBuf, Schedule)>,
}

/// What `run(out=...)` asks of the folder.
pub struct FolderOptions {
    pub out: PathBuf,
    pub force: bool,
    pub checkpoint_every: Option<Duration>,
}

fn same_folder(a: &Path, b: &Path) -> bool {
    match (a.canonicalize(), b.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => a == b,
    }
}

impl Folder {
    /// A simulation continued from the restart file `file`, whose folder it may go on
    /// writing.
    pub fn continuing(file: &Path, schedule: Schedule) -> Self {
        let dir = file
            .parent()
            .map_or_else(|| PathBuf::from("."), Path::to_path_buf);
        Self {
            run: None,
            restart: Some((dir, schedule)),
        }
    }

    /// The run of folder `out`: the one open, the restart file's folder continued, or
    /// a new folder with the case copy, the series header and the first snapshot.
    fn open<const D: usize>(
        &mut self,
        sim: &mut Simulation<D>,
        options: &FolderOptions,
    ) -> sph_core::Result<&mut Run> {
        let out = options.out.as_path();
        let open = self
            .run
            .as_ref()
            .is_some_and(|r| r.output.as_ref().is_some_and(|o| same_folder(o.dir(), out)));
        if !open {
            let run = match &self.restart {
                Some((dir, schedule)) if same_folder(dir, out) => {
                    let mut output = Output::resume(out, schedule.snapshots, options.force)?;
                    output.resume_series(&sim.series_header(), sim.time())?;
                    Run::resume(sim, Some(output), *schedule)
                }
                _ => {
                    let mut output = Output::create(out, options.force)?;
                    let case = toml::to_string(sim.case())
                        .map_err(|e| sph_core::SphError::output(out, e.to_string()))?;
                    output.write_text("case.toml", &case)?;
                    Run::start(sim, Some(output))?
                }
            };
            self.run = Some(run);
        }
        Ok(self.run.as_mut().expect("opened above"))
    }

    /// Drives `sim` to its end time in folder `options.out`, in slices between which
    /// Ctrl-C is honoured (a last snapshot and a restart file are written, then
    /// KeyboardInterrupt is raised) and `report(time, n_steps)` is called.
    pub fn drive<const D: usize>(
        &mut self,
        py: Python<'_>,
        sim: &mut Simulation<D>,
        options: &FolderOptions,
        report: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        let run = self.open(sim, options).map_err(|e| to_py(py, e))?;
        let stop = AtomicUsize::new(0);
        loop {
            let ending = py.detach(|| {
                run.drive(
                    sim,
                    &mut Control {
                        checkpoint_every: options.checkpoint_every,
                        stop: &stop,
                        on_step: &mut |_| {},
                        slice: Some(SLICE),
                    },
                )
            });
            match ending {
                Ending::Paused => {
                    if py.check_signals().is_err() {
                        // Ctrl-C: the next slice closes the run and ends as `Stopped`
                        stop.store(SIGINT, Ordering::Relaxed);
                    } else if let Some(report) = report {
                        report.call1((sim.time(), sim.counters().steps))?;
                    }
                }
                Ending::Finished { .. } => return Ok(()),
                Ending::Stopped { restart, .. } => {
                    return Err(PyKeyboardInterrupt::new_err(format!(
                        "interrupted at t = {:.6} s (step {}); continue with \
                         deltasph.Simulation.from_restart(\"{}\")",
                        sim.time(),
                        sim.counters().steps,
                        restart.display()
                    )))
                }
                Ending::Unstable { error, .. } => return Err(to_py(py, error)),
                Ending::OutputFailed { error, restart } => {
                    let what = match restart {
                        Ok(path) => format!("restart file written: {}", path.display()),
                        Err(e) => format!("no restart file could be written either ({e})"),
                    };
                    return Err(PyOSError::new_err(format!("{error}; {what}")));
                }
            }
        }
    }
}

/// Reads a snapshot (HDF5, as runs and ``write_snapshot`` write it): ``(time, step,
/// fields)``, the fields as numpy arrays, vectors (N, D), in the file's row order.
#[pyfunction]
pub fn read_snapshot<'py>(
    py: Python<'py>,
    path: PathBuf,
) -> PyResult<(f64, u64, Bound<'py, PyDict>)> {
    let snapshot = read(&path).map_err(|e| to_py(py, e))?;
    let fields = PyDict::new(py);
    for (name, field) in snapshot.fields {
        match field {
            Field::Float { values, columns: 1 } => {
                fields.set_item(name, PyArray1::from_vec(py, values))?
            }
            Field::Float { values, columns } => {
                let rows = values.len() / columns;
                let array = PyArray1::from_vec(py, values).reshape([rows, columns])?;
                fields.set_item(name, array)?
            }
            Field::Byte(v) => fields.set_item(name, PyArray1::from_vec(py, v))?,
            Field::Id(v) => fields.set_item(name, PyArray1::from_vec(py, v))?,
        }
    }
    Ok((snapshot.time, snapshot.step, fields))
}

/// The folder options of `run`, the checkpoint interval checked.
pub(crate) fn folder_options(
    out: PathBuf,
    force: bool,
    checkpoint_every: Option<f64>,
) -> PyResult<FolderOptions> {
    let checkpoint_every = match checkpoint_every {
        Some(s) if s.is_finite() && s > 0.0 => Some(Duration::from_secs_f64(s)),
        Some(s) => {
            return Err(PyValueError::new_err(format!(
                "checkpoint_every = {s}: expected a wall-clock interval above 0 s"
            )))
        }
        None => None,
    };
    Ok(FolderOptions {
        out,
        force,
        checkpoint_every,
    })
}
