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
}

/// How a run ended.
#[derive(Debug)]
pub enum Ending {
    /// It reached its end time or step cap; the restart file written last.
    Finished { restart: PathBuf },
    /// A stop was requested (`signal`); it wrote a last snapshot and a restart file.
    Stopped { signal: usize, restart: PathBuf },
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

/// A simulation with its run folder and output schedule.
pub struct Run<const D: usize> {
    pub sim: Simulation<D>,
    pub output: Output,
    pub schedule: Schedule,
    /// Counters when this leg of the run started (a continued run counts from there).
    pub since: Counters,
    /// Wall time of the stepping loop so far.
    pub wall: Duration,
}

impl<const D: usize> Run<D> {
    /// A fresh run: the series header, the first row and the first snapshot.
    pub fn start(sim: Simulation<D>, mut output: Output) -> Result<Self> {
        output.start_series(&sim.series_header())?;
        let (snap_every, series_every) = intervals(&sim);
        let schedule = Schedule {
            next_snapshot: snap_every,
            next_series: series_every,
            next_restart: sim.case().output.restart_interval.unwrap_or(f64::INFINITY),
            snapshots: 0,
            initial_energy: sim.energies().total(),
        };
        let mut run = Self::resume(sim, output, schedule);
        let row = run.sim.series_values();
        run.output.series_row(&row)?;
        run.snapshot()?;
        Ok(run)
    }

    /// A run continued from a restart file's simulation and schedule, in its folder.
    pub fn resume(sim: Simulation<D>, output: Output, schedule: Schedule) -> Self {
        Self {
            since: sim.counters(),
            sim,
            output,
            schedule,
            wall: Duration::ZERO,
        }
    }

    fn snapshot(&mut self) -> Result<PathBuf> {
        let (sim, output) = (&self.sim, &mut self.output);
        let steps = sim.counters().steps;
        let path = crate::io::output::with_extras(sim, |extras| {
            output.snapshot(sim.particles(), extras, sim.time(), steps)
        })?;
        self.schedule.snapshots += 1;
        Ok(path)
    }

    fn write_restart(&mut self) -> Result<PathBuf> {
        let checkpoint = self.sim.checkpoint()?;
        self.output.write_restart(&checkpoint, &self.schedule)
    }

    /// The series row and snapshot due after the step just taken.
    fn record(&mut self, series_every: f64, snap_every: f64) -> Result<bool> {
        let mut wrote_row = false;
        if self.sim.time() >= self.schedule.next_series {
            let row = self.sim.series_values();
            self.output.series_row(&row)?;
            self.schedule.next_series += series_every;
            wrote_row = true;
        }
        let end = self.sim.case().time.end;
        if snap_every > 0.0
            && self.sim.time() >= self.schedule.next_snapshot
            && self.sim.time() < end
        {
            self.sim.sync_pressure();
            self.snapshot()?;
            self.schedule.next_snapshot += snap_every;
        }
        Ok(wrote_row)
    }

    /// Whether a restart file is due, on simulated time or on wall time.
    fn restart_due(&mut self, control: &Control<D>, last: Instant) -> bool {
        let on_time = self.sim.time() >= self.schedule.next_restart;
        if on_time {
            let every = self
                .sim
                .case()
                .output
                .restart_interval
                .unwrap_or(f64::INFINITY);
            while self.schedule.next_restart <= self.sim.time() {
                self.schedule.next_restart += every;
            }
        }
        on_time
            || control
                .checkpoint_every
                .is_some_and(|every| last.elapsed() >= every)
    }

    /// Steps to the end time (or step cap, or a stop request), writing output on its
    /// intervals, and ends as [`Ending`] says.
    pub fn drive(&mut self, control: &mut Control<D>) -> Ending {
        let end = self.sim.case().time.end;
        let (snap_every, series_every) = intervals(&self.sim);
        let max_steps = self.sim.case().time.max_steps.unwrap_or(u64::MAX);
        let start = Instant::now();
        let mut last_restart = Instant::now();
        let mut last_row = self.sim.time();
        let flag = control.stop;
        let stop = || flag.load(Ordering::Relaxed);
        while self.sim.time() < end * (1.0 - 1e-12)
            && self.sim.counters().steps < max_steps
            && stop() == 0
        {
            if let Err(error) = self.sim.step() {
                self.wall += start.elapsed();
                return Ending::Unstable {
                    error,
                    snapshot: self.snapshot(),
                };
            }
            match self.record(series_every, snap_every) {
                Ok(true) => last_row = self.sim.time(),
                Ok(false) => {}
                Err(error) => return self.output_failed(error, start),
            }
            if self.restart_due(control, last_restart) {
                if let Err(error) = self.write_restart() {
                    self.wall += start.elapsed();
                    return Ending::OutputFailed {
                        restart: Err(error.clone()),
                        error,
                    };
                }
                last_restart = Instant::now();
            }
            (control.on_step)(&self.sim);
        }
        self.wall += start.elapsed();
        self.sim.sync_pressure();
        let signal = stop();
        let closing = (|| -> Result<PathBuf> {
            if signal == 0 && self.sim.time() > last_row {
                // the closing row (a stopped run gets it when it reaches its end)
                let row = self.sim.series_values();
                self.output.series_row(&row)?;
            }
            self.snapshot()?;
            self.write_restart()
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
    fn output_failed(&mut self, error: SphError, start: Instant) -> Ending {
        self.wall += start.elapsed();
        self.output.drop_previous_restart();
        Ending::OutputFailed {
            error,
            restart: self.write_restart(),
        }
    }
}

/// Intervals of the snapshots and of the time-series rows.
pub fn intervals<const D: usize>(sim: &Simulation<D>) -> (f64, f64) {
    let case = sim.case();
    (case.time.output_interval, case.series_interval())
}
