//! Driving a run to its end with its output: the time series and snapshots on their
//! intervals, restart files on a simulated-time interval (`[output] restart_interval`)
//! and a wall-clock one, and an ending that keeps what was written.
//!
//! - At the end, or when a stop is requested (a signal, through [`Control::stop`]), a
//!   last snapshot and a restart file are written.
//! - A run that goes unstable writes a last snapshot of the state where it stopped,
//!   and no restart file (it would continue a blow-up).
//! - A failed snapshot or series write (a full disk) writes a restart file first, so
//!   the run can continue once there is room.
//!
//! Writing output and restart files changes nothing the next step depends on, so a run
//! gives the same bits whatever its output intervals, and a run continued from any of
//! its restart files is the uninterrupted run bit for bit.
//!
//! A run split over processes is driven alike on every process: output is written
//! from the whole run gathered on process 0 ([`Simulation::view`]), the only one with
//! a run folder, and the decisions that end the loop (a stop request, a failed write,
//! a restart file due on wall time) are agreed by all processes at every step.

use crate::error::{Result, SphError};
use crate::io::output::Output;
use crate::io::restart::Schedule;
use crate::simulation::{Counters, Simulation};
use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

/// How a front end steers a run.
pub struct Control<'a, const D: usize> {
    /// Wall-clock interval between restart files (none: only the simulated-time one).
    pub checkpoint_every: Option<Duration>,
    /// A stop request, checked between steps: the signal number that asked, 0 for none.
    pub stop: &'a AtomicUsize,
    /// Called after every step (progress display).
    pub on_step: &'a mut dyn FnMut(&Simulation<D>),
    /// Return [`Ending::Paused`] after this much wall time, for a front end that must
    /// look at its own events between slices (none: run to the end).
    pub slice: Option<Duration>,
}

/// How a run ended.
#[derive(Debug)]
pub enum Ending {
    /// It reached its end time or step cap; the restart file written last.
    Finished { restart: PathBuf },
    /// A stop was requested (`signal`); it wrote a last snapshot and a restart file.
    Stopped { signal: usize, restart: PathBuf },
    /// The slice of wall time ran out ([`Control::slice`]); `drive` again goes on.
    Paused,
    /// It went unstable; `snapshot` holds the state at which it stopped.
    Unstable {
        error: SphError,
        snapshot: Result<PathBuf>,
    },
    /// Writing output failed; a restart file was written first when it could be.
    OutputFailed {
        error: SphError,
        restart: Result<PathBuf>,
    },
}

/// The run folder of a simulation and its output schedule. The simulation is passed
/// to each call, so that the front end keeps it (and can read it between calls).
pub struct Run {
    /// The run folder (on process 0 of a split run; `None` on the others).
    pub output: Option<Output>,
    pub schedule: Schedule,
    /// Counters when this leg of the run started (a continued run counts from there).
    pub since: Counters,
    /// Wall time of the stepping loop so far.
    pub wall: Duration,
    /// Simulated time of the last time-series row.
    last_row: f64,
    /// When the last restart file was written (or the run started).
    last_restart: Instant,
}

impl Run {
    /// A fresh run: the series header, the first row and the first snapshot.
    pub fn start<const D: usize>(sim: &mut Simulation<D>, output: Option<Output>) -> Result<Self> {
        let (snap_every, series_every) = intervals(sim);
        let t = sim.time();
        let next_restart = t + sim.case().output.restart_interval.unwrap_or(f64::INFINITY);
        let header = sim.series_header();
        let schedule = Schedule {
            next_snapshot: t + snap_every,
            next_series: t + series_every,
            next_restart,
            snapshots: 0,
            initial_energy: sim.energies().total(),
        };
        let mut run = Self::resume(sim, output, schedule);
        let started = (run.output.as_mut()).map_or(Ok(()), |o| o.start_series(&header));
        agreed(started, sim)?;
        agreed(run.row(sim), sim)?;
        agreed(run.snapshot(sim), sim)?;
        Ok(run)
    }

    /// A run continued from a restart file's simulation and schedule, in its folder.
    pub fn resume<const D: usize>(
        sim: &Simulation<D>,
        mut output: Option<Output>,
        schedule: Schedule,
    ) -> Self {
        if let Some(o) = output.as_mut() {
            o.set_compression(sim.case().output.compression());
        }
        Self {
            since: sim.counters(),
            last_row: sim.time(),
            last_restart: Instant::now(),
            output,
            schedule,
            wall: Duration::ZERO,
        }
    }

    /// Writes a time-series row (computed by every process of a split run).
    fn row<const D: usize>(&mut self, sim: &mut Simulation<D>) -> Result<()> {
        let row = sim.series_values();
        (self.output.as_mut()).map_or(Ok(()), |output| output.series_row(&row))
    }

    /// Writes a snapshot, pressures refreshed (collective in a split run); the path is
    /// empty on the processes that write nothing.
    fn snapshot<const D: usize>(&mut self, sim: &mut Simulation<D>) -> Result<PathBuf> {
        let path = match (sim.view(), self.output.as_mut()) {
            (Some(view), Some(output)) => {
                view.sync_pressure();
                let view = &*view;
                let steps = view.counters().steps;
                crate::io::output::with_extras(view, |extras| {
                    output.snapshot(view.particles(), extras, view.time(), steps)
                })?
            }
            _ => PathBuf::new(),
        };
        self.schedule.snapshots += 1;
        Ok(path)
    }

    /// Writes a restart file (collective in a split run); the path is empty on the
    /// processes that write nothing.
    fn write_restart<const D: usize>(&mut self, sim: &mut Simulation<D>) -> Result<PathBuf> {
        match (sim.view(), self.output.as_mut()) {
            (Some(view), Some(output)) => output.write_restart(&view.checkpoint()?, &self.schedule),
            _ => Ok(PathBuf::new()),
        }
    }

    /// The series row and snapshot due after the step just taken.
    fn record<const D: usize>(
        &mut self,
        sim: &mut Simulation<D>,
        series_every: f64,
        snap_every: f64,
    ) -> Result<bool> {
        let mut wrote_row = false;
        if sim.time() >= self.schedule.next_series {
            self.row(sim)?;
            self.schedule.next_series += series_every;
            wrote_row = true;
        }
        let end = sim.case().time.end;
        if snap_every > 0.0 && sim.time() >= self.schedule.next_snapshot && sim.time() < end {
            self.snapshot(sim)?;
            self.schedule.next_snapshot += snap_every;
        }
        Ok(wrote_row)
    }

    /// Whether a restart file is due, on simulated time or on wall time.
    fn restart_due<const D: usize>(&mut self, sim: &Simulation<D>, control: &Control<D>) -> bool {
        let on_time = sim.time() >= self.schedule.next_restart;
        if on_time {
            let every = sim.case().output.restart_interval.unwrap_or(f64::INFINITY);
            while self.schedule.next_restart <= sim.time() {
                self.schedule.next_restart += every;
            }
        }
        let on_wall_time =
            (control.checkpoint_every).is_some_and(|every| self.last_restart.elapsed() >= every);
        on_time || sim.max_over_processes(f64::from(u8::from(on_wall_time))) > 0.0
    }

    /// Steps to the end time (or step cap, or a stop request), writing output on its
    /// intervals, and ends as [`Ending`] says.
    pub fn drive<const D: usize>(
        &mut self,
        sim: &mut Simulation<D>,
        control: &mut Control<D>,
    ) -> Ending {
        let end = sim.case().time.end;
        let (snap_every, series_every) = intervals(sim);
        let max_steps = sim.case().time.max_steps.unwrap_or(u64::MAX);
        let start = Instant::now();
        let flag = control.stop;
        // a stop request on any process stops them all
        let stop = |sim: &Simulation<D>| {
            sim.max_over_processes(flag.load(Ordering::Relaxed) as f64) as usize
        };
        while sim.time() < end * (1.0 - 1e-12) && sim.counters().steps < max_steps && stop(sim) == 0
        {
            if control.slice.is_some_and(|slice| start.elapsed() >= slice) {
                self.wall += start.elapsed();
                return Ending::Paused;
            }
            if let Err(error) = sim.step() {
                self.wall += start.elapsed();
                return Ending::Unstable {
                    error,
                    snapshot: self.snapshot(sim),
                };
            }
            match agreed(self.record(sim, series_every, snap_every), sim) {
                Ok(true) => self.last_row = sim.time(),
                Ok(false) => {}
                Err(error) => return self.output_failed(sim, error, start),
            }
            if self.restart_due(sim, control) {
                let written = self.write_restart(sim);
                if let Err(error) = agreed(written, sim) {
                    self.wall += start.elapsed();
                    return Ending::OutputFailed {
                        restart: Err(error.clone()),
                        error,
                    };
                }
                self.last_restart = Instant::now();
            }
            (control.on_step)(sim);
        }
        self.wall += start.elapsed();
        let signal = stop(sim);
        let closing = (|| -> Result<PathBuf> {
            if signal == 0 && sim.time() > self.last_row {
                // the closing row (a stopped run gets it when it reaches its end)
                agreed(self.row(sim), sim)?;
            }
            agreed(self.snapshot(sim), sim)?;
            agreed(self.write_restart(sim), sim)
        })();
        match (closing, signal) {
            (Ok(restart), 0) => Ending::Finished { restart },
            (Ok(restart), signal) => Ending::Stopped { signal, restart },
            (Err(error), _) => Ending::OutputFailed {
                restart: Err(error.clone()),
                error,
            },
        }
    }

    /// A write failed (its partial file is gone): the older of the two restart files
    /// makes room for a new one, which is written before the run stops.
    fn output_failed<const D: usize>(
        &mut self,
        sim: &mut Simulation<D>,
        error: SphError,
        start: Instant,
    ) -> Ending {
        self.wall += start.elapsed();
        if let Some(output) = self.output.as_mut() {
            output.drop_previous_restart();
        }
        Ending::OutputFailed {
            error,
            restart: self.write_restart(sim),
        }
    }
}

/// `result`, failed on every process of a split run when it failed on any (there, on
/// process 0: the only one that writes). Collective in a split run.
pub fn agreed<const D: usize, T>(result: Result<T>, sim: &Simulation<D>) -> Result<T> {
    let failed_anywhere = sim.max_over_processes(f64::from(u8::from(result.is_err()))) > 0.0;
    match result {
        Ok(_) if failed_anywhere => Err(SphError::output(
            "process 0",
            "writing the run's output failed there (see its message)",
        )),
        other => other,
    }
}

/// Intervals of the snapshots and of the time-series rows.
pub fn intervals<const D: usize>(sim: &Simulation<D>) -> (f64, f64) {
    let case = sim.case();
    (case.time.output_interval, case.series_interval())
}
