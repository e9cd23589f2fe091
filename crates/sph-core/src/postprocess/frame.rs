//! One snapshot made ready for interpolation at points: its particles sorted into the
//! cells of a grid, as a run's neighbour search sorts them, so that the in-run probe,
//! gauge and section rules of [`crate::diagnostics`] read it as they read the running
//! simulation.
//!
//! The interpolation needs each particle's volume `V = m/ρ`: snapshots hold `mass`
//! since the measure tool exists; older ones are refused with the reason.

use crate::case::Case;
use crate::diagnostics::PointReader;
use crate::domain::Domain;
use crate::error::{Result, SphError};
use crate::io::output::reading::{read_snapshot, Field, Snapshot};
use crate::neighbours::NeighbourList;
use crate::particles::{Kind, Particles, Vector};
use crate::physics::kernel::Smoothing;
use std::path::Path;

/// A snapshot read at points, with a kernel chosen at run time.
pub type SnapshotReader<'a, const D: usize> = PointReader<'a, D, dyn Smoothing + 'a>;

/// A snapshot's particles, sorted for point queries.
pub struct Frame<const D: usize> {
    pub time: f64,
    pub step: u64,
    particles: Particles<D>,
    /// The cell grid only (no neighbour rows: points are not particles).
    cells: NeighbourList<D>,
    domain: Domain<D>,
}

impl<const D: usize> Frame<D> {
    /// Reads the snapshot `path` of a run of `case`, for a kernel of support `support`.
    pub fn read(path: &Path, case: &Case, support: f64) -> Result<Self> {
        let snapshot = read_snapshot(path)?;
        if snapshot.dimension != D {
            return Err(SphError::output(
                path,
                format!("a {}D snapshot in a run of a {D}D case", snapshot.dimension),
            ));
        }
        let mut particles = particles_of(&snapshot).map_err(|e| SphError::output(path, e))?;
        let domain = domain_of(case, &particles);
        let (cells, _) =
            NeighbourList::build_rows(&mut particles, &domain, support, 0.0, |_, _| false);
        Ok(Self {
            time: snapshot.time,
            step: snapshot.step,
            particles,
            cells,
            domain,
        })
    }

    /// The snapshot read at points with `kernel`, by the in-run rules.
    pub fn reader<'a>(&'a self, kernel: &'a dyn Smoothing) -> SnapshotReader<'a, D> {
        PointReader {
            kernel,
            particles: &self.particles,
            list: &self.cells,
            domain: &self.domain,
        }
    }
}

/// The particles of `snapshot` with the fields the probes read.
fn particles_of<const D: usize>(snapshot: &Snapshot) -> std::result::Result<Particles<D>, String> {
    let floats = |name: &str| match snapshot.field(name) {
        Some(Field::Float { values, .. }) => Ok(values.as_slice()),
        _ => Err(format!(
            "the snapshot has no `{name}` field{}",
            if name == "mass" {
                " (written before snapshots stored masses: run the case again to measure it)"
            } else {
                ""
            }
        )),
    };
    let (x, u) = (floats("position")?, floats("velocity")?);
    let (rho, p, mass) = (floats("density")?, floats("pressure")?, floats("mass")?);
    let Some(Field::Byte(kind)) = snapshot.field("kind") else {
        return Err("the snapshot has no `kind` field".into());
    };
    let vector = |v: &[f64], i: usize| Vector::<D>::from_column_slice(&v[i * D..(i + 1) * D]);
    let mut particles = Particles::default();
    for (i, &k) in kind.iter().enumerate() {
        let kind = if k == Kind::Fluid as u8 {
            Kind::Fluid
        } else {
            Kind::Wall
        };
        particles.push(kind, vector(x, i), vector(u, i), rho[i], mass[i]);
        let last = particles.len() - 1;
        particles.p[last] = p[i];
    }
    Ok(particles)
}

/// The case's `[domain]` (its periodic axes wrap distances); without one, distances do
/// not wrap and any box holding the particles serves.
fn domain_of<const D: usize>(case: &Case, particles: &Particles<D>) -> Domain<D> {
    if let Some(d) = &case.domain {
        let corner = |v: &[f64]| Vector::<D>::from_fn(|k, _| v[k]);
        let periodic = std::array::from_fn(|k| d.is_periodic(k));
        return Domain::new(corner(&d.lo), corner(&d.hi), periodic);
    }
    if particles.is_empty() {
        return Domain::new(Vector::zeros(), Vector::repeat(1.0), [false; D]);
    }
    let (lo, hi) = particles.x.iter().fold(
        (Vector::<D>::repeat(f64::MAX), Vector::<D>::repeat(f64::MIN)),
        |(lo, hi), x| (lo.inf(x), hi.sup(x)),
    );
    Domain::new(lo, hi, [false; D])
}
