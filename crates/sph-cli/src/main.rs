//! `sph-cli`: runs and checks deltasph TOML cases.

use anyhow::Result;
use clap::{Parser, Subcommand};
use indicatif::{ProgressBar, ProgressStyle};
use signal_hook::consts::{SIGINT, SIGTERM};
use signal_hook::flag;
use sph_core::output::Output;
use sph_core::restart::{self, Schedule};
use sph_core::simulation::Counters;
use sph_core::{Case, Simulation, SphError};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Arc;
use std::time::Instant;

#[derive(Parser)]
#[command(
    name = "sph-cli",
    version,
    about = "Weakly-compressible δ-SPH solver: run and check TOML cases"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run a case (or continue one from a restart file) and write HDF5/XDMF snapshots,
    /// CSV time series and a restart file.
    Run {
        /// The case file (not with --restart).
        #[arg(required_unless_present = "restart", conflicts_with = "restart")]
        case: Option<PathBuf>,
        /// Output folder (default: `<case name>_out` in the current folder; with
        /// --restart, the restart file's folder).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Replace an existing non-empty output folder (with --restart: snapshots
        /// written after the restart point).
        #[arg(long)]
        force: bool,
        /// Continue the run saved in this restart file, bit for bit. Runs write
        /// `restart.h5` when they end and when SIGINT or SIGTERM stops them.
        #[arg(long, value_name = "FILE")]
        restart: Option<PathBuf>,
        /// End time [s], replacing the case's `time.end`.
        #[arg(long, value_name = "SECONDS")]
        until: Option<f64>,
        /// No progress bar.
        #[arg(long, short)]
        quiet: bool,
    },
    /// Validate a case without running it.
    Check {
        /// The case file.
        case: PathBuf,
    },
}

/// How a run ended other than by reaching its end time.
#[derive(Debug)]
struct Interrupted {
    signal: &'static str,
    code: u8,
    time: f64,
    step: u64,
    restart: PathBuf,
}

impl std::fmt::Display for Interrupted {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        write!(
            f,
            "interrupted by {} at t = {:.6} s (step {}); continue with: sph-cli run --restart {}",
            self.signal,
            self.time,
            self.step,
            self.restart.display()
        )
    }
}

impl std::error::Error for Interrupted {}

/// Exit codes: 0 success, 2 bad input or output problem, 3 the run went unstable,
/// 130 and 143 stopped by SIGINT and SIGTERM (a restart file was written).
fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Run {
            case,
            out,
            force,
            restart,
            until,
            quiet,
        } => {
            let options = RunOptions {
                out,
                force,
                until,
                quiet,
            };
            match (case, restart) {
                (_, Some(file)) => resume(&file, options),
                (Some(case), None) => run(&case, options),
                (None, None) => unreachable!("clap requires a case or --restart"),
            }
        }
        Command::Check { case } => check(&case),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            if let Some(stop) = e.downcast_ref::<Interrupted>() {
                return ExitCode::from(stop.code);
            }
            let unstable = matches!(
                e.downcast_ref::<SphError>(),
                Some(SphError::Unstable { .. })
            );
            ExitCode::from(if unstable { 3 } else { 2 })
        }
    }
}

fn check(path: &Path) -> Result<()> {
    let case = Case::from_file(path)?;
    let (n_fluid, n_total) = match case.dimension {
        2 => counts(Simulation::<2>::new(case.clone())?),
        _ => counts(Simulation::<3>::new(case.clone())?),
    };
    println!(
        "{}: valid {}D case '{}': {} fluid and {} wall particles",
        path.display(),
        case.dimension,
        case.name,
        n_fluid,
        n_total - n_fluid
    );
    Ok(())
}

fn counts<const D: usize>(sim: Simulation<D>) -> (usize, usize) {
    (sim.n_fluid(), sim.particles.len())
}

struct RunOptions {
    out: Option<PathBuf>,
    force: bool,
    until: Option<f64>,
    quiet: bool,
}

fn run(path: &Path, options: RunOptions) -> Result<()> {
    let mut case = Case::from_file(path)?;
    if let Some(end) = options.until {
        if !(end > 0.0 && end.is_finite()) {
            return Err(SphError::invalid("--until", end, "a positive end time in seconds").into());
        }
        case.time.end = end;
    }
    let out = (options.out.clone()).unwrap_or_else(|| PathBuf::from(format!("{}_out", case.name)));
    let output = Output::create(&out, options.force)?;
    output.write_text("case.toml", &std::fs::read_to_string(path)?)?;
    match case.dimension {
        2 => start(Simulation::<2>::new(case)?, output, &options),
        _ => start(Simulation::<3>::new(case)?, output, &options),
    }
}

/// A fresh run: the series header, the first row and the first snapshot.
fn start<const D: usize>(
    mut sim: Simulation<D>,
    mut output: Output,
    options: &RunOptions,
) -> Result<()> {
    output.start_series(&sim.series_header())?;
    let row = sim.series_values();
    output.series_row(&row)?;
    write_state(&sim, &mut output)?;
    let every = intervals(&sim);
    let schedule = Schedule {
        next_snapshot: every.0,
        next_series: every.1,
        snapshots: 1,
        initial_energy: sim.energies().total(),
    };
    drive(sim, output, schedule, options.quiet)
}

fn resume(file: &Path, options: RunOptions) -> Result<()> {
    let dir = match options.out.clone() {
        Some(dir) => dir,
        None => file
            .parent()
            .map(Path::to_path_buf)
            .unwrap_or_else(|| PathBuf::from(".")),
    };
    match restart::dimension(file)? {
        2 => resume_in::<2>(file, &dir, options),
        3 => resume_in::<3>(file, &dir, options),
        d => Err(SphError::output(file, format!("dimension {d} is not 2 or 3")).into()),
    }
}

fn resume_in<const D: usize>(file: &Path, dir: &Path, options: RunOptions) -> Result<()> {
    let (checkpoint, schedule) = restart::read::<D>(file)?;
    let sim = Simulation::<D>::from_checkpoint(checkpoint, options.until)?;
    let mut output = Output::resume(dir, schedule.snapshots, options.force)?;
    output.resume_series(&sim.series_header(), sim.time)?;
    drive(sim, output, schedule, options.quiet)
}

/// Intervals of the snapshots and of the time-series rows.
fn intervals<const D: usize>(sim: &Simulation<D>) -> (f64, f64) {
    let end = sim.case.time.end;
    let snap_every = sim.case.time.output_interval;
    let series_every = sim
        .case
        .diagnostics
        .interval
        .unwrap_or(if snap_every > 0.0 {
            snap_every / 10.0
        } else {
            end / 200.0
        });
    (snap_every, series_every)
}

fn progress_bar(quiet: bool) -> ProgressBar {
    if quiet {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new(1000);
    bar.set_style(
        ProgressStyle::with_template("{bar:40} {percent:>3}% t = {msg} ETA {eta}")
            .expect("static template"),
    );
    bar
}

/// SIGINT and SIGTERM set a flag that the step loop reads between steps; a second
/// signal of either kind ends the process at once.
fn stop_signal() -> Result<Arc<AtomicUsize>> {
    let which = Arc::new(AtomicUsize::new(0));
    let pending = Arc::new(AtomicBool::new(false));
    for sig in [SIGINT, SIGTERM] {
        flag::register_conditional_shutdown(sig, 128 + sig, Arc::clone(&pending))?;
        flag::register(sig, Arc::clone(&pending))?;
        flag::register_usize(sig, Arc::clone(&which), sig as usize)?;
    }
    Ok(which)
}

/// Steps to the end time, writing snapshots and time series on their intervals, and a
/// restart file at the end or when a signal stops the run.
fn drive<const D: usize>(
    mut sim: Simulation<D>,
    mut output: Output,
    mut schedule: Schedule,
    quiet: bool,
) -> Result<()> {
    let signal = stop_signal()?;
    let end = sim.case.time.end;
    let (snap_every, series_every) = intervals(&sim);
    let max_steps = sim.case.time.max_steps.unwrap_or(u64::MAX);
    let bar = progress_bar(quiet);
    let start = Instant::now();
    let since = sim.counters;
    let mut outcome = Ok(());
    let mut last_row = sim.time;
    while sim.time < end * (1.0 - 1e-12)
        && sim.counters.steps < max_steps
        && signal.load(Ordering::Relaxed) == 0
    {
        if let Err(e) = sim.step() {
            outcome = Err(e);
            break;
        }
        if sim.time >= schedule.next_series {
            let row = sim.series_values();
            output.series_row(&row)?;
            schedule.next_series += series_every;
            last_row = sim.time;
        }
        if snap_every > 0.0 && sim.time >= schedule.next_snapshot && sim.time < end {
            sim.sync_pressure();
            write_state(&sim, &mut output)?;
            schedule.next_snapshot += snap_every;
            schedule.snapshots += 1;
        }
        let steps_per_s = (sim.counters.steps - since.steps) as f64 / start.elapsed().as_secs_f64();
        bar.set_position((1000.0 * sim.time / end) as u64);
        bar.set_message(format!(
            "{:.4} s, {} steps, {steps_per_s:.1} steps/s",
            sim.time, sim.counters.steps
        ));
    }
    bar.finish_and_clear();
    let wall = start.elapsed().as_secs_f64();
    if outcome.is_ok() {
        sim.sync_pressure();
    }
    let interrupted = signal.load(Ordering::Relaxed);
    if interrupted == 0 && sim.time > last_row {
        // the closing row (an interrupted run gets it when it reaches its end)
        let row = sim.series_values();
        output.series_row(&row)?;
    }
    let last = write_state(&sim, &mut output)?;
    schedule.snapshots += 1;
    summary(&sim, &output, wall, since, schedule.initial_energy);
    if let Err(e) = outcome {
        println!(
            "last snapshot   {} (the state at which the run stopped)",
            last.display()
        );
        return Err(e.into());
    }
    let restart_file = output.dir().join("restart.h5");
    restart::write(&restart_file, &sim.checkpoint()?, &schedule)?;
    println!("restart         {}", restart_file.display());
    match interrupted {
        0 => Ok(()),
        sig => Err(Interrupted {
            signal: if sig == SIGINT as usize {
                "SIGINT"
            } else {
                "SIGTERM"
            },
            code: 128 + sig as u8,
            time: sim.time,
            step: sim.counters.steps,
            restart: restart_file,
        }
        .into()),
    }
}

/// One snapshot, with the free surface and shifting velocity when the run has them.
fn write_state<const D: usize>(sim: &Simulation<D>, output: &mut Output) -> Result<PathBuf> {
    let steps = sim.counters.steps;
    Ok(sim.with_extras(|extras| output.snapshot(&sim.particles, extras, sim.time, steps))?)
}

fn summary<const D: usize>(
    sim: &Simulation<D>,
    output: &Output,
    wall: f64,
    since: Counters,
    initial_energy: f64,
) {
    let n = sim.n_fluid();
    let c = sim.counters;
    let e1 = sim.energies();
    println!("case            {} ({}D)", sim.case.name, D);
    println!(
        "particles       {} fluid, {} wall",
        n,
        sim.particles.len() - n
    );
    println!(
        "scheme          {:?} diffusion (δ = {}), {:?} viscosity, {:?}, CFL {}",
        sim.case.scheme.diffusion,
        sim.case.scheme.delta,
        sim.case.scheme.viscosity,
        sim.case.scheme.integrator,
        sim.case.scheme.cfl()
    );
    println!("sound speed     c0 = {:.4} m/s", sim.physics().eos.c0);
    println!(
        "simulated       t = {:.6} s in {} steps (last Δt = {:.3e} s)",
        sim.time, c.steps, sim.dt
    );
    println!("wall time       {wall:.2} s");
    println!(
        "throughput      {:.3e} particle-steps/s, {:.3e} particle-evaluations/s, {} list builds",
        n as f64 * (c.steps - since.steps) as f64 / wall,
        n as f64 * (c.evaluations - since.evaluations) as f64 / wall,
        c.rebuilds
    );
    println!(
        "neighbours      {:.1} listed per particle (fluid and wall, incl. skin)",
        sim.mean_neighbours()
    );
    println!("max |Δρ/ρ0|     {:.3e}", sim.max_density_variation());
    println!(
        "walls           {} fluid particles inside a wall at the end",
        sim.wall_crossings()
    );
    println!(
        "energy          E_k+E_p+E_c: {:.6e} → {:.6e} J (change {:+.3e})",
        initial_energy,
        e1.total(),
        e1.total() - initial_energy
    );
    if let Some(b) = sim.budget {
        println!("                ∫(P_V+P_D)dt = {:+.3e} J", b.dissipated);
    }
    println!(
        "output          {} (open particles.xmf in ParaView)",
        output.dir().display()
    );
}
