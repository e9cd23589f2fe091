//! `sph-cli`: runs and checks deltasph TOML cases.

use anyhow::Result;
use clap::{Parser, Subcommand};
use indicatif::{ProgressBar, ProgressStyle};
use sph_core::output::Output;
use sph_core::{Case, Simulation, SphError};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
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
    /// Run a case and write HDF5/XDMF snapshots and CSV time series.
    Run {
        /// The case file.
        case: PathBuf,
        /// Output folder (default: `<case name>_out` in the current folder).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Replace an existing non-empty output folder.
        #[arg(long)]
        force: bool,
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

/// Exit codes: 0 success, 2 bad input or output problem, 3 the run went unstable.
fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Run {
            case,
            out,
            force,
            quiet,
        } => run(&case, out, force, quiet),
        Command::Check { case } => check(&case),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
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

fn run(path: &Path, out: Option<PathBuf>, force: bool, quiet: bool) -> Result<()> {
    let case = Case::from_file(path)?;
    let out = out.unwrap_or_else(|| PathBuf::from(format!("{}_out", case.name)));
    let mut output = Output::create(&out, force)?;
    output.write_text("case.toml", &std::fs::read_to_string(path)?)?;
    match case.dimension {
        2 => drive(Simulation::<2>::new(case)?, &mut output, quiet),
        _ => drive(Simulation::<3>::new(case)?, &mut output, quiet),
    }
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

/// Steps to the end time, writing snapshots and time series on their intervals.
fn drive<const D: usize>(mut sim: Simulation<D>, output: &mut Output, quiet: bool) -> Result<()> {
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
    let max_steps = sim.case.time.max_steps.unwrap_or(u64::MAX);
    output.start_series(&sim.series_header())?;
    let row = sim.series_values();
    output.series_row(&row)?;
    let e0 = sim.energies();
    write_state(&sim, output)?;
    let (mut next_snap, mut next_series) = (snap_every, series_every);
    let bar = progress_bar(quiet);
    let start = Instant::now();
    let mut outcome = Ok(());
    while sim.time < end * (1.0 - 1e-12) && sim.counters.steps < max_steps {
        if let Err(e) = sim.step() {
            outcome = Err(e);
            break;
        }
        if sim.time >= next_series {
            let row = sim.series_values();
            output.series_row(&row)?;
            next_series += series_every;
        }
        if snap_every > 0.0 && sim.time >= next_snap && sim.time < end {
            sim.sync_pressure();
            write_state(&sim, output)?;
            next_snap += snap_every;
        }
        let steps_per_s = sim.counters.steps as f64 / start.elapsed().as_secs_f64();
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
    let last = write_state(&sim, output)?;
    summary(&sim, output, wall, e0);
    if let Err(e) = outcome {
        println!(
            "last snapshot   {} (the state at which the run stopped)",
            last.display()
        );
        return Err(e.into());
    }
    Ok(())
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
    e0: sph_core::diagnostics::Energies,
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
        n as f64 * c.steps as f64 / wall,
        n as f64 * c.evaluations as f64 / wall,
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
        e0.total(),
        e1.total(),
        e1.total() - e0.total()
    );
    if let Some(b) = sim.budget {
        println!("                ∫(P_V+P_D)dt = {:+.3e} J", b.dissipated);
    }
    println!(
        "output          {} (open particles.xmf in ParaView)",
        output.dir().display()
    );
}
