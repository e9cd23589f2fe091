//! The measure tool: pressure, velocity and density interpolated at points, the
//! free-surface elevation on vertical lines, and the volume and mass flow through
//! sections, from every snapshot of a run folder.
//!
//! Each value follows the in-run rule exactly ([`crate::diagnostics`]): the
//! Shepard-normalised kernel sum over the fluid, `f(x) = Σ_j f_j W(x - x_j) V_j /
//! Σ_j W(x - x_j) V_j` with `V_j = m_j/ρ_j`, and the gauges' crossing of `Γ = ½` on a
//! vertical line, and the sections' flow densities ([`crate::diagnostics::sections`]).
//! A point with no fluid within the kernel support (dry, or inside a
//! wall) has no value: NaN, an empty reading and not a zero. A dry line reads its
//! bottom, as an in-run gauge does.

use super::frame::{Frame, SnapshotReader};
use super::points::MAX_POINTS;
use super::RunFolder;
use crate::case::SectionConfig;
use crate::diagnostics::gauges::Gauge;
use crate::diagnostics::sections::Section;
use crate::error::{Result, SphError};
use crate::io::output::atomic;
use crate::particles::Vector;
use crate::physics::kernel::Smoothing;
use rayon::prelude::*;
use std::path::Path;

/// How the header of every CSV file the measure tool writes starts (the only files it
/// replaces): the clock, then the first point's or line's column.
const CSV_MARKS: [&str; 3] = [
    "time,step,point0_",
    "time,step,line0_",
    "time,step,section0_",
];

/// The most values one measurement holds (snapshots × points × components): 2 GB.
const MAX_VALUES: usize = 250_000_000;

/// A field read at points.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    Pressure,
    Velocity,
    Density,
}

impl Quantity {
    pub const ALL: [Quantity; 3] = [Quantity::Pressure, Quantity::Velocity, Quantity::Density];

    pub fn name(self) -> &'static str {
        match self {
            Quantity::Pressure => "pressure",
            Quantity::Velocity => "velocity",
            Quantity::Density => "density",
        }
    }

    /// The quantity called `name`.
    pub fn parse(name: &str) -> Result<Self> {
        (Self::ALL.into_iter().find(|q| q.name() == name))
            .ok_or_else(|| SphError::invalid("fields", name, "pressure, velocity or density"))
    }

    fn components(self, dimension: usize) -> usize {
        match self {
            Quantity::Velocity => dimension,
            _ => 1,
        }
    }
}

/// What to measure.
#[derive(Debug, Clone, Default)]
pub struct Request {
    /// The points the quantities are read at, each with the case's dimension.
    pub points: Vec<Vec<f64>>,
    pub quantities: Vec<Quantity>,
    /// The vertical lines the elevation is read on: x in 2D, (x, y) in 3D.
    pub elevations: Vec<Vec<f64>>,
    /// The corners of the flow sections (see [`SectionConfig`]).
    pub sections: Vec<Vec<Vec<f64>>>,
}

/// One measured quantity: `values[(s * count + k) * components + c]` is component c
/// at point (or line) k in snapshot s.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// `pressure`, `velocity`, `density`, `elevation`, `volume_flow` or `mass_flow`.
    pub name: &'static str,
    /// Points (or lines) per snapshot.
    pub count: usize,
    pub components: usize,
    pub values: Vec<f64>,
}

impl Series {
    fn new(name: &'static str, count: usize, components: usize) -> Self {
        Self {
            name,
            count,
            components,
            values: Vec::new(),
        }
    }
}

/// The measured series, a row per snapshot.
#[derive(Debug, Clone)]
pub struct Measurement {
    pub dimension: usize,
    /// Each snapshot's time \[s\] and step.
    pub times: Vec<f64>,
    pub steps: Vec<u64>,
    pub request: Request,
    pub series: Vec<Series>,
}

/// Measures `request` at every snapshot of `folder`.
pub fn measure(folder: &RunFolder, request: &Request) -> Result<Measurement> {
    match folder.case.dimension {
        2 => measure_in::<2>(folder, request),
        _ => measure_in::<3>(folder, request),
    }
}

fn measure_in<const D: usize>(folder: &RunFolder, request: &Request) -> Result<Measurement> {
    let case = &folder.case;
    let readers = Readers::<D>::new(folder, request)?;
    let mut series = readers.series();
    let kernel = case.particles.kernel.with_length(case.h(), D);
    let (mut times, mut steps) = (Vec::new(), Vec::new());
    for path in &folder.snapshots {
        let frame = Frame::<D>::read(path, case, kernel.support_radius())?;
        for (s, row) in series.iter_mut().zip(readers.rows(&frame, kernel.as_ref())) {
            s.values.extend(row);
        }
        times.push(frame.time);
        steps.push(frame.step);
    }
    Ok(Measurement {
        dimension: D,
        times,
        steps,
        request: request.clone(),
        series,
    })
}

/// What a request reads in each snapshot, checked and built once.
struct Readers<const D: usize> {
    points: Vec<Vector<D>>,
    quantities: Vec<Quantity>,
    gauges: Vec<Gauge<D>>,
    sections: Vec<Section<D>>,
}

impl<const D: usize> Readers<D> {
    /// The readers of `request` in the run of `folder`, refused when the values of all
    /// its snapshots would not fit in [`MAX_VALUES`].
    fn new(folder: &RunFolder, request: &Request) -> Result<Self> {
        let case = &folder.case;
        let readers = Self {
            points: points_of::<D>(&request.points)?,
            quantities: request.quantities.clone(),
            gauges: (request.elevations.iter().enumerate())
                .map(|(k, x)| Gauge::<D>::at(case, x, &format!("elevation[{k}]")))
                .collect::<Result<Vec<_>>>()?,
            sections: sections_of::<D>(&request.sections, case.dx())?,
        };
        let per_snapshot: usize = (readers.series().iter())
            .map(|s| s.count * s.components)
            .sum();
        let snapshots = folder.snapshots.len();
        if per_snapshot.saturating_mul(snapshots) > MAX_VALUES {
            return Err(SphError::invalid(
                "points",
                format!("{per_snapshot} values at each of {snapshots} snapshots"),
                format!("at most {MAX_VALUES} values in all (fewer points or fields)"),
            ));
        }
        Ok(readers)
    }

    /// The series, empty, in the order of [`Self::rows`].
    fn series(&self) -> Vec<Series> {
        let mut series: Vec<Series> = (self.quantities.iter())
            .map(|q| Series::new(q.name(), self.points.len(), q.components(D)))
            .collect();
        if !self.gauges.is_empty() {
            series.push(Series::new("elevation", self.gauges.len(), 1));
        }
        if !self.sections.is_empty() {
            series.push(Series::new("volume_flow", self.sections.len(), 1));
            series.push(Series::new("mass_flow", self.sections.len(), 1));
        }
        series
    }

    /// Each series' values in `frame`.
    fn rows(&self, frame: &Frame<D>, kernel: &dyn Smoothing) -> Vec<Vec<f64>> {
        let reader = frame.reader(kernel);
        let mut rows: Vec<Vec<f64>> = (self.quantities.iter())
            .map(|q| read_points(&reader, *q, &self.points))
            .collect();
        if !self.gauges.is_empty() {
            let gauges = self.gauges.par_iter();
            rows.push(gauges.map(|g| elevation(&reader, g)).collect());
        }
        if !self.sections.is_empty() {
            let flows: Vec<[f64; 2]> = (self.sections.iter()).map(|s| flow(&reader, s)).collect();
            rows.push(flows.iter().map(|f| f[0]).collect());
            rows.push(flows.iter().map(|f| f[1]).collect());
        }
        rows
    }
}

/// The elevation gauge `g` reads in a snapshot.
fn elevation<const D: usize>(reader: &SnapshotReader<D>, g: &Gauge<D>) -> f64 {
    let gamma: Vec<f64> = g.points.iter().map(|x| reader.fluid_fraction(x)).collect();
    g.elevation(&gamma)
}

/// The volume and mass flow through section `s` in a snapshot.
fn flow<const D: usize>(reader: &SnapshotReader<D>, s: &Section<D>) -> [f64; 2] {
    let densities: Vec<[f64; 2]> = (s.points.par_iter())
        .map(|x| reader.flow_density(x, &s.normal))
        .collect();
    s.flow(&densities)
}

/// The request's sections, each checked as a case's (`sections[k]`).
fn sections_of<const D: usize>(corners: &[Vec<Vec<f64>>], dx: f64) -> Result<Vec<Section<D>>> {
    (corners.iter().enumerate())
        .map(|(k, corners)| {
            let config = SectionConfig {
                name: format!("section{k}"),
                corners: corners.clone(),
            };
            config.check(&format!("sections[{k}]"), D, dx)?;
            Ok(Section::new(&config, dx))
        })
        .collect()
}

/// The request's points as vectors, each checked: D finite coordinates.
fn points_of<const D: usize>(points: &[Vec<f64>]) -> Result<Vec<Vector<D>>> {
    if points.len() > MAX_POINTS {
        return Err(SphError::invalid(
            "points",
            format!("{} points", points.len()),
            format!("at most {MAX_POINTS}"),
        ));
    }
    (points.iter().enumerate())
        .map(|(k, x)| {
            if x.len() != D || !x.iter().all(|v| v.is_finite()) {
                return Err(SphError::invalid(
                    format!("points[{k}]"),
                    format!("{x:?}"),
                    format!("{D} finite coordinates (the case is {D}D)"),
                ));
            }
            Ok(Vector::<D>::from_column_slice(x))
        })
        .collect()
}

/// `q` at each of `points`, its components in a row; NaN where no fluid is in reach.
fn read_points<const D: usize>(
    reader: &SnapshotReader<D>,
    q: Quantity,
    points: &[Vector<D>],
) -> Vec<f64> {
    let rows: Vec<Vec<f64>> = points
        .par_iter()
        .map(|x| match q {
            Quantity::Pressure => vec![reader.pressure(x).unwrap_or(f64::NAN)],
            Quantity::Density => vec![reader.density(x).unwrap_or(f64::NAN)],
            Quantity::Velocity => match reader.velocity(x) {
                Some(u) => u.iter().copied().collect(),
                None => vec![f64::NAN; D],
            },
        })
        .collect();
    rows.concat()
}

impl Measurement {
    /// The CSV columns: `time`, `step`, then per quantity and point k `point<k>_pressure`,
    /// `point<k>_u` … `point<k>_density`, then `line<k>_elevation`, then
    /// `section<k>_volume_flow` and `section<k>_mass_flow`.
    pub fn header(&self) -> Vec<String> {
        let components = &["u", "v", "w"][..self.dimension];
        let mut out = vec!["time".to_string(), "step".to_string()];
        for s in &self.series {
            for k in 0..s.count {
                match s.name {
                    "velocity" => out.extend(components.iter().map(|c| format!("point{k}_{c}"))),
                    "elevation" => out.push(format!("line{k}_elevation")),
                    flow @ ("volume_flow" | "mass_flow") => out.push(format!("section{k}_{flow}")),
                    name => out.push(format!("point{k}_{name}")),
                }
            }
        }
        out
    }

    /// The measurement as CSV, as `timeseries.csv` is laid out: the header, then a row
    /// per snapshot (full precision; NaN where a point had no fluid). The points
    /// themselves are the request's, in column order.
    pub fn to_csv(&self) -> String {
        let mut out = self.header().join(",") + "\n";
        for (s, (time, step)) in self.times.iter().zip(&self.steps).enumerate() {
            let mut row = vec![format!("{time:e}"), step.to_string()];
            for series in &self.series {
                let width = series.count * series.components;
                let values = &series.values[s * width..(s + 1) * width];
                row.extend(values.iter().map(|v| format!("{v:e}")));
            }
            out += &(row.join(",") + "\n");
        }
        out
    }

    /// Writes [`Self::to_csv`] to `path` atomically. An existing file is refused unless
    /// `overwrite`, and even then only a file the measure tool wrote is replaced.
    pub fn write_csv(&self, path: &Path, overwrite: bool) -> Result<()> {
        if path.exists() {
            let head = std::fs::read(path).unwrap_or_default();
            let ours = CSV_MARKS.iter().any(|m| head.starts_with(m.as_bytes()));
            let why = match (overwrite, ours) {
                (false, _) => Some(
                    "file exists; choose another name, or pass --force (overwrite=True in Python)",
                ),
                (true, false) => Some(
                    "file exists and was not written by the measure tool; it is never overwritten",
                ),
                (true, true) => None,
            };
            if let Some(why) = why {
                return Err(SphError::output(path, why));
            }
        }
        let text = self.to_csv();
        atomic::write(path, |tmp| std::fs::write(tmp, &text))
    }
}
