//! `sph-cli measure`: fields at points, wave elevations and flows through sections read
//! from every snapshot of a finished run ([`sph_core::postprocess::measure`]), as CSV on standard output or in
//! a file.

use anyhow::Result;
use clap::Args;
use sph_core::postprocess::measure::{measure, Quantity, Request};
use sph_core::postprocess::{points, RunFolder};
use sph_core::SphError;
use std::path::PathBuf;

/// Where and what to measure.
#[derive(Args)]
pub(crate) struct MeasureArgs {
    /// The run folder (what `run` wrote: case.toml, particles.xmf and the snapshots).
    run: PathBuf,
    /// Points listed in a file, one per line, coordinates separated by commas or blanks
    /// (`#` starts a comment line).
    #[arg(long, value_name = "FILE")]
    points: Option<PathBuf>,
    /// N points evenly spaced from A to B, ends included, e.g. `--line 0.5,0 0.5,0.6 25`
    /// (repeatable).
    #[arg(long, num_args = 3, value_names = ["A", "B", "N"])]
    line: Vec<String>,
    /// The nodes of the box LO–HI with COUNTS nodes along each axis, the first axis
    /// varying fastest, e.g. `--grid 0,0 1,0.5 21,11`.
    #[arg(long, num_args = 3, value_names = ["LO", "HI", "COUNTS"])]
    grid: Vec<String>,
    /// The free-surface elevation on the vertical line at X (2D) or X,Y (3D), as a
    /// wave gauge reads it (repeatable).
    #[arg(long, value_name = "X[,Y]")]
    elevation: Vec<String>,
    /// The volume and mass flow through the segment between two corners (2D; flow to
    /// the right of the first-to-second direction counts positive: a segment drawn
    /// upwards counts flow in +x) or the parallelogram at the first of three corners
    /// (3D; normal (c1 - c0) × (c2 - c0)), e.g. `--section 1.0,0 1.0,0.6` (repeatable).
    #[arg(long, num_args = 2..=3, value_name = "CORNER")]
    section: Vec<String>,
    /// The fields read at the points: pressure, velocity, density (comma-separated).
    #[arg(long, value_delimiter = ',', default_value = "pressure")]
    fields: Vec<String>,
    /// Loads on the walls: not recomputed from snapshots (they hold neither the walls'
    /// extrapolated state nor the moving walls' accelerations that the loads need);
    /// says where the run recorded them, or how to record them.
    #[arg(long)]
    loads: bool,
    /// Write the CSV here instead of standard output.
    #[arg(long, short, value_name = "FILE")]
    out: Option<PathBuf>,
    /// Replace an earlier output of the measure tool at --out.
    #[arg(long)]
    force: bool,
}

pub(crate) fn run(args: MeasureArgs) -> Result<()> {
    let folder = RunFolder::open(&args.run)?;
    if args.loads {
        return Err(loads_message(&folder).into());
    }
    let mut points = match &args.points {
        Some(file) => points::read_file(file)?,
        None => Vec::new(),
    };
    for spec in args.line.chunks(3) {
        let n = count("--line", &spec[2])?;
        points.extend(points::line(
            &coordinates("--line", &spec[0])?,
            &coordinates("--line", &spec[1])?,
            n,
        )?);
    }
    for spec in args.grid.chunks(3) {
        let counts = (spec[2].split(','))
            .map(|c| count("--grid", c.trim()))
            .collect::<Result<Vec<usize>>>()?;
        let (lo, hi) = (
            coordinates("--grid", &spec[0])?,
            coordinates("--grid", &spec[1])?,
        );
        points.extend(points::grid(&lo, &hi, &counts)?);
    }
    let elevations = (args.elevation.iter())
        .map(|x| coordinates("--elevation", x))
        .collect::<Result<Vec<_>>>()?;
    let dimension = folder.case.dimension;
    if !args.section.len().is_multiple_of(dimension) {
        let given = args.section.join(" ");
        let expected = format!("{dimension} corners per section (the case is {dimension}D)");
        return Err(SphError::invalid("--section", given, expected).into());
    }
    let sections = (args.section.chunks(dimension))
        .map(|corners| {
            corners
                .iter()
                .map(|c| coordinates("--section", c))
                .collect()
        })
        .collect::<Result<Vec<Vec<Vec<f64>>>>>()?;
    if points.is_empty() && elevations.is_empty() && sections.is_empty() {
        return Err(SphError::invalid(
            "measure",
            "no points",
            "--points, --line, --grid, --elevation or --section",
        )
        .into());
    }
    let quantities = if points.is_empty() {
        Vec::new()
    } else {
        (args.fields.iter().map(|f| Quantity::parse(f.trim())))
            .collect::<sph_core::Result<Vec<_>>>()?
    };
    let request = Request {
        points,
        quantities,
        elevations,
        sections,
    };
    let measurement = measure(&folder, &request)?;
    match &args.out {
        Some(path) => {
            measurement.write_csv(path, args.force)?;
            eprintln!(
                "wrote {} ({} snapshots)",
                path.display(),
                measurement.times.len()
            );
        }
        None => print!("{}", measurement.to_csv()),
    }
    Ok(())
}

/// The comma-separated numbers of `text`, given to `key`.
fn coordinates(key: &str, text: &str) -> Result<Vec<f64>> {
    let values: std::result::Result<Vec<f64>, _> =
        text.split(',').map(|v| v.trim().parse()).collect();
    Ok(values
        .map_err(|_| SphError::invalid(key, text, "numbers separated by commas, e.g. 0.5,0.1"))?)
}

/// A whole number of points of at least 1, given to `key`.
fn count(key: &str, text: &str) -> Result<usize> {
    let n: Option<usize> = text.parse().ok().filter(|&n| n >= 1);
    Ok(n.ok_or_else(|| SphError::invalid(key, text, "a whole number of points, at least 1"))?)
}

/// Why `--loads` reads nothing: where the run's own loads are, or how to record them.
fn loads_message(folder: &RunFolder) -> SphError {
    let series = folder.dir.join("timeseries.csv");
    let header = std::fs::read_to_string(&series).unwrap_or_default();
    let header = header.lines().next().unwrap_or_default();
    let recorded: Vec<&str> = (header.split(','))
        .filter(|c| c.ends_with("_pressure_fx"))
        .collect();
    let expected = if recorded.is_empty() {
        "a run that records them: loads need the wall state of the run itself, which \
         snapshots do not hold; set `loads = true` under [diagnostics] and run the case \
         again"
            .to_string()
    } else {
        format!(
            "the loads the run recorded: columns {} (and the viscous and moment columns \
             beside them) in {}",
            recorded.join(", "),
            series.display()
        )
    };
    SphError::invalid("--loads", "from snapshots", expected)
}
