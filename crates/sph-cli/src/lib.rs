//! The deltasph command line: runs, checks and previews TOML cases, and measures runs. The `sph-cli`
//! binary and the Python wheel's `deltasph` command are both [`main_with`].

use anyhow::Result;
use clap::{CommandFactory, FromArgMatches, Parser, Subcommand};
use indicatif::{ProgressBar, ProgressStyle};
use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM, SIGUSR1};
use signal_hook::flag;
use sph_core::io::output::Output;
use sph_core::io::restart;
use sph_core::run::{Control, Ending, Run};
use sph_core::{Case, Simulation, SphError};
use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize};
use std::sync::Arc;
use std::time::{Duration, Instant};

mod check;
mod measure;
mod processes;
mod summary;
mod surface;

use processes::Processes;

#[derive(Parser)]
#[command(
    name = "sph-cli",
    version,
    about = "Weakly-compressible δ-SPH solver: run and check TOML cases, measure their runs"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run a case (or continue one from a restart file) and write HDF5/XDMF snapshots,
    /// CSV time series and restart files.
    Run {
        /// The case file (not with --restart).
        #[arg(required_unless_present = "restart", conflicts_with = "restart")]
        case: Option<PathBuf>,
        /// Output folder (default: `<case name>_out` in the current folder; with
        /// --restart, the restart file's folder).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Replace the files of an earlier run in the output folder (files deltasph did
        /// not write are kept; a folder that is not a run folder is refused). With
        /// --restart: replace snapshots written after the restart point.
        #[arg(long)]
        force: bool,
        /// Continue the run saved in this restart file, bit for bit. Runs write
        /// `restart.h5` (the one before kept as `restart.prev.h5`) on the case's
        /// `output.restart_interval`, every --checkpoint-every, at the end, on a stop
        /// signal and when an output write fails.
        #[arg(long, value_name = "FILE")]
        restart: Option<PathBuf>,
        /// End time [s], replacing the case's `time.end`.
        #[arg(long, value_name = "SECONDS")]
        until: Option<f64>,
        /// Also write a restart file after this much wall time, e.g. `30min`, `2h`, `90s`.
        #[arg(long, value_name = "DURATION", value_parser = parse_duration)]
        checkpoint_every: Option<Duration>,
        /// No progress bar.
        #[arg(long, short)]
        quiet: bool,
    },
    /// Validate a case without running it, and report what it builds: particles and
    /// bounds of each fluid region and wall, and the closest fluid to a wall.
    Check {
        /// The case file.
        case: PathBuf,
        /// Also show how this many processes would split the case (recursive
        /// coordinate bisection on the fluid particles): each one's box, particles and
        /// halo within the kernel support, and the load imbalance.
        #[arg(long, value_name = "P", value_parser = clap::value_parser!(u32).range(1..=100_000))]
        ranks: Option<u32>,
    },
    /// Write the initial particles of a case (an HDF5/XDMF snapshot for ParaView and
    /// preview.png: 2D as it is, 3D as a side and a top view) without running it.
    Preview {
        /// The case file.
        case: PathBuf,
        /// Output folder (default: `<case name>_preview`).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Replace the files of an earlier preview or run in the output folder.
        #[arg(long)]
        force: bool,
    },
    /// Read pressure, velocity or density at points, the free-surface elevation on
    /// vertical lines and the flow through sections, from every snapshot of a finished
    /// run (the rules of the in-run probes, gauges and sections; NaN where no fluid is
    /// in reach) as CSV: a row per snapshot.
    Measure(measure::MeasureArgs),
    /// Write the fluid's free surface at every snapshot of a finished run as a mesh
    /// (2D: polylines; 3D: triangles), the ½ level of the fluid's kernel sum, into
    /// `RUN/surface/` as VTK PolyData with a ParaView collection (`surface.pvd`).
    Surface(surface::SurfaceArgs),
    /// Print the JSON Schema of the case file, for TOML editors (Taplo, Even Better
    /// TOML): save it and start a case file with `#:schema ./case.schema.json`.
    Schema,
}

fn parse_duration(text: &str) -> std::result::Result<Duration, String> {
    let d = humantime::parse_duration(text)
        .map_err(|e| format!("{e}: expected a duration such as 30min, 2h or 90s"))?;
    if d.is_zero() {
        return Err("expected a duration above zero".into());
    }
    Ok(d)
}

/// The signals that end a run with a restart file: Ctrl-C, a kill, a closed terminal,
/// and the pre-emption warning of batch schedulers.
const STOP_SIGNALS: [i32; 4] = [SIGINT, SIGTERM, SIGHUP, SIGUSR1];

fn signal_name(sig: usize) -> &'static str {
    match sig as i32 {
        SIGINT => "SIGINT",
        SIGTERM => "SIGTERM",
        SIGHUP => "SIGHUP",
        SIGUSR1 => "SIGUSR1",
        _ => "a signal",
    }
}

/// An ending that is not a success: the message and the exit code.
#[derive(Debug)]
struct Failure {
    message: String,
    code: u8,
}

impl std::fmt::Display for Failure {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for Failure {}

/// Runs the command line `args` (the program's own name first) as `program`, the
/// name its help and messages use, with `after_help` at the end of its help. Returns
/// the exit code: 0 success, 2 bad input or output problem, 3 the run went unstable,
/// 128 + n when signal n stopped it (a restart file was written).
pub fn main_with(program: &str, args: Vec<OsString>, after_help: Option<&str>) -> u8 {
    sph_core::allocator::return_large_buffers();
    let mut command = Cli::command()
        .name(program.to_string())
        .bin_name(program.to_string());
    if let Some(text) = after_help {
        command = command.after_help(text.to_string());
    }
    let cli = match command
        .try_get_matches_from(args)
        .and_then(|m| Cli::from_arg_matches(&m))
    {
        Ok(cli) => cli,
        Err(e) => {
            let _ = e.print();
            return if e.use_stderr() { 2 } else { 0 };
        }
    };
    let result = match cli.command {
        Command::Run {
            case,
            out,
            force,
            restart,
            until,
            checkpoint_every,
            quiet,
        } => {
            let options = RunOptions {
                program: program.to_string(),
                out,
                force,
                until,
                checkpoint_every,
                quiet,
            };
            processes::join().and_then(|procs| {
                let result = match (case, restart) {
                    (_, Some(file)) => resume(&file, options, &procs),
                    (Some(case), None) => run(&case, options, &procs),
                    (None, None) => unreachable!("clap requires a case or --restart"),
                };
                // process 0 reports, and no process ends before it has: a launcher
                // stops the others as soon as one ends with an error
                let result = result.map_err(|e| {
                    if procs.is_first() {
                        eprintln!("error: {e}");
                    }
                    without_message(e)
                });
                procs.wait_for_all();
                result
            })
        }
        Command::Check { case, ranks } => check::check(&case, ranks),
        Command::Measure(args) => measure::run(args),
        Command::Surface(args) => surface::run(args),
        Command::Preview { case, out, force } => preview(&case, out, force),
        Command::Schema => {
            print!("{}", sph_core::case::json_schema::case_schema());
            Ok(())
        }
    };
    match result {
        Ok(()) => 0,
        Err(e) => {
            let message = e.to_string();
            if !message.is_empty() {
                eprintln!("error: {message}");
            }
            e.downcast_ref::<Failure>()
                .map_or(2, |failure| failure.code)
        }
    }
}

/// `e` without its message, once reported.
fn without_message(e: anyhow::Error) -> anyhow::Error {
    let code = e.downcast_ref::<Failure>().map_or(2, |f| f.code);
    Failure {
        message: String::new(),
        code,
    }
    .into()
}

fn preview(path: &Path, out: Option<PathBuf>, force: bool) -> Result<()> {
    let case = Case::from_file(path)?;
    let dir = out.unwrap_or_else(|| PathBuf::from(format!("{}_preview", case.name)));
    let written = match case.dimension {
        2 => preview_into(Simulation::<2>::new(case)?, &dir, force)?,
        _ => preview_into(Simulation::<3>::new(case)?, &dir, force)?,
    };
    for path in written {
        println!("wrote {}", path.display());
    }
    Ok(())
}

fn preview_into<const D: usize>(
    sim: Simulation<D>,
    dir: &Path,
    force: bool,
) -> Result<Vec<PathBuf>> {
    let mut output = Output::create(dir, force)?;
    Ok(sph_core::io::preview::write(&sim, &mut output)?)
}

struct RunOptions {
    /// The command's name, for the commands the messages suggest.
    program: String,
    out: Option<PathBuf>,
    force: bool,
    until: Option<f64>,
    checkpoint_every: Option<Duration>,
    quiet: bool,
}

fn run(path: &Path, options: RunOptions, procs: &Processes) -> Result<()> {
    let mut case = Case::from_file(path)?;
    if let Some(end) = options.until {
        if !(end > 0.0 && end.is_finite()) {
            return Err(SphError::invalid("--until", end, "a positive end time in seconds").into());
        }
        case.time.end = end;
    }
    let out = (options.out.clone()).unwrap_or_else(|| PathBuf::from(format!("{}_out", case.name)));
    // build first: a case that does not build leaves no folder behind
    let text = std::fs::read_to_string(path)?;
    match case.dimension {
        2 => start(built::<2>(case, procs)?, &out, &text, &options, procs),
        _ => start(built::<3>(case, procs)?, &out, &text, &options, procs),
    }
}

/// The simulation of a case: this process's share when the run is split over several
/// (built without the whole run's lists), the whole run otherwise.
fn built<const D: usize>(case: Case, procs: &Processes) -> Result<Simulation<D>> {
    Ok(match &procs.comm {
        Some(comm) => Simulation::new_split(case, Arc::clone(comm))?,
        None => Simulation::new(case)?,
    })
}

fn start<const D: usize>(
    mut sim: Simulation<D>,
    out: &Path,
    case_text: &str,
    options: &RunOptions,
    procs: &Processes,
) -> Result<()> {
    let output = procs.is_first().then(|| -> sph_core::Result<Output> {
        let mut output = Output::create(out, options.force)?;
        output.write_text("case.toml", case_text)?;
        Ok(output)
    });
    let output = sph_core::run::agreed(output.transpose(), &sim)?;
    let run = Run::start(&mut sim, output)?;
    drive(sim, run, options, procs)
}

fn resume(file: &Path, options: RunOptions, procs: &Processes) -> Result<()> {
    let dir = match options.out.clone() {
        Some(dir) => dir,
        None => file
            .parent()
            .map(Path::to_path_buf)
            .unwrap_or_else(|| PathBuf::from(".")),
    };
    match restart::dimension(file)? {
        2 => resume_in::<2>(file, &dir, options, procs),
        _ => resume_in::<3>(file, &dir, options, procs),
    }
}

/// Continues a run from a restart file, on any number of processes (every process
/// reads the file and keeps its share).
fn resume_in<const D: usize>(
    file: &Path,
    dir: &Path,
    options: RunOptions,
    procs: &Processes,
) -> Result<()> {
    let (checkpoint, schedule) = restart::read::<D>(file)?;
    let sim = match &procs.comm {
        Some(comm) => {
            Simulation::from_checkpoint_split(checkpoint, options.until, Arc::clone(comm))?
        }
        None => Simulation::from_checkpoint(checkpoint, options.until)?,
    };
    let output = procs.is_first().then(|| -> sph_core::Result<Output> {
        let mut output = Output::resume(dir, schedule.snapshots, options.force)?;
        output.resume_series(&sim.series_header(), sim.time())?;
        Ok(output)
    });
    let output = sph_core::run::agreed(output.transpose(), &sim)?;
    let run = Run::resume(&sim, output, schedule);
    drive(sim, run, &options, procs)
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

/// The stop signals set a flag that the step loop reads between steps; a second
/// signal of any of them ends the process at once.
fn stop_signal() -> Result<Arc<AtomicUsize>> {
    let which = Arc::new(AtomicUsize::new(0));
    let pending = Arc::new(AtomicBool::new(false));
    for sig in STOP_SIGNALS {
        flag::register_conditional_shutdown(sig, 128 + sig, Arc::clone(&pending))?;
        flag::register(sig, Arc::clone(&pending))?;
        flag::register_usize(sig, Arc::clone(&which), sig as usize)?;
    }
    Ok(which)
}

/// Drives the run, prints the summary and turns its ending into the exit status.
fn drive<const D: usize>(
    mut sim: Simulation<D>,
    mut run: Run,
    options: &RunOptions,
    procs: &Processes,
) -> Result<()> {
    let signal = stop_signal()?;
    let bar = progress_bar(options.quiet || !procs.is_first());
    let start = Instant::now();
    let first_step = sim.counters().steps;
    let end = sim.case().time.end;
    let mut shown = 0;
    let mut on_step = |sim: &Simulation<D>| {
        for notice in &sim.notices()[shown..] {
            bar.suspend(|| eprintln!("notice: {notice}"));
        }
        shown = sim.notices().len();
        let steps = sim.counters().steps - first_step;
        let steps_per_s = steps as f64 / start.elapsed().as_secs_f64();
        bar.set_position((1000.0 * sim.time() / end) as u64);
        bar.set_message(format!(
            "{:.4} s, {} steps, {steps_per_s:.1} steps/s",
            sim.time(),
            sim.counters().steps
        ));
    };
    let ending = run.drive(
        &mut sim,
        &mut Control {
            checkpoint_every: options.checkpoint_every,
            stop: &signal,
            on_step: &mut on_step,
            slice: None,
        },
    );
    bar.finish_and_clear();
    let processes = summary::process_report(&sim, run.wall.as_secs_f64());
    if let Some(view) = sim.view() {
        summary::summary(view, &run);
        print!("{}", processes.unwrap_or_default());
    }
    let (time, step) = (sim.time(), sim.counters().steps);
    let failure = |code: u8, message: String| Err(Failure { message, code }.into());
    match ending {
        Ending::Finished { restart } => {
            if procs.is_first() {
                println!("restart         {}", restart.display());
            }
            Ok(())
        }
        Ending::Stopped { signal, restart } => {
            if procs.is_first() {
                println!("restart         {}", restart.display());
            }
            failure(
                128 + signal as u8,
                format!(
                    "interrupted by {} at t = {time:.6} s (step {step}); continue with: \
                     {} run --restart {}",
                    signal_name(signal),
                    options.program,
                    restart.display()
                ),
            )
        }
        Ending::Paused => unreachable!("a run without a slice is never paused"),
        Ending::Unstable { error, snapshot } => {
            match snapshot {
                _ if !procs.is_first() => {}
                Ok(path) => println!(
                    "last snapshot   {} (the state at which the run stopped)",
                    path.display()
                ),
                Err(e) => println!("last snapshot   not written: {e}"),
            }
            failure(3, error.to_string())
        }
        Ending::OutputFailed { error, restart } => {
            let what = match restart {
                Ok(path) => format!(
                    "restart file written at t = {time:.6} s (step {step}): once there is room, \
                     continue with: {} run --restart {} --force",
                    options.program,
                    path.display()
                ),
                Err(e) => format!("no restart file could be written either ({e})"),
            };
            failure(2, format!("{error}; {what}"))
        }
    }
}
