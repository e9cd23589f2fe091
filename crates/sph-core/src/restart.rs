//! Restart files: the complete state of a run, from which it continues bit for bit.
//!
//! Bit-for-bit continuation needs more than the physical state `(x, u, ρ)`:
//! - the particles in their current storage order (the pair sums run in list order,
//!   and floating-point addition is not associative);
//! - the neighbour lists, rebuilt from the positions of their last build and the same
//!   skin, so that the next list rebuild happens at the same step;
//! - the step count, time, last Δt, the acceleration that sizes the list skin and the
//!   energy budget;
//! - the output schedule of the driver ([`Schedule`]).
//!
//! The file is HDF5 (`restart.h5` in a run folder), written atomically. It carries the
//! case as TOML, so it is self-contained.

use crate::error::{Result, SphError};
use crate::particles::{Kind, Particles, Vector};
use crate::simulation::{Counters, EnergyBudget};
use std::path::Path;

/// Where the driver of a run stands in its output schedule.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Schedule {
    /// Time of the next particle snapshot.
    pub next_snapshot: f64,
    /// Time of the next time-series row.
    pub next_series: f64,
    /// Snapshots written so far (the next one gets this index).
    pub snapshots: u64,
    /// `E_k + E_p + E_c` at the start of the run, for the closing summary.
    pub initial_energy: f64,
}

/// Everything of a [`crate::Simulation`] that the next step depends on.
#[derive(Debug, Clone)]
pub struct Checkpoint<const D: usize> {
    pub case_toml: String,
    pub particles: Particles<D>,
    /// Positions at the last neighbour-list build, in the current order.
    pub list_positions: Vec<Vector<D>>,
    pub skin: f64,
    pub time: f64,
    pub dt: f64,
    pub counters: Counters,
    pub last_acceleration: f64,
    pub budget: Option<EnergyBudget>,
    pub shift_velocity: Option<Vec<Vector<D>>>,
}

fn flat<const D: usize>(v: &[Vector<D>]) -> Vec<f64> {
    v.iter().flat_map(|x| x.iter().copied()).collect()
}

fn vectors<const D: usize>(raw: &[f64]) -> Vec<Vector<D>> {
    raw.chunks_exact(D)
        .map(Vector::<D>::from_column_slice)
        .collect()
}

/// Writes `checkpoint` and `schedule` to `path` (atomically: a temporary file renamed).
pub fn write<const D: usize>(
    path: &Path,
    checkpoint: &Checkpoint<D>,
    schedule: &Schedule,
) -> Result<()> {
    let tmp = path.with_extension("h5.partial");
    write_h5(&tmp, checkpoint, schedule).map_err(|e| SphError::output(path, e))?;
    std::fs::rename(&tmp, path).map_err(|e| SphError::output(path, e))
}

fn write_h5<const D: usize>(path: &Path, c: &Checkpoint<D>, s: &Schedule) -> hdf5::Result<()> {
    let file = hdf5::File::create(path)?;
    let p = &c.particles;
    let n = p.len();
    let vector = |name: &str, v: &[Vector<D>]| {
        file.new_dataset::<f64>()
            .shape((n, D))
            .create(name)?
            .write_raw(&flat(v))
    };
    vector("position", &p.x)?;
    vector("velocity", &p.u)?;
    vector("wall_viscous_velocity", &p.u_wall_visc)?;
    vector("list_positions", &c.list_positions)?;
    if let Some(v) = &c.shift_velocity {
        vector("shifting_velocity", v)?;
    }
    crate::output::write_scalars(&file, p)?;
    file.new_dataset::<f64>()
        .shape(n)
        .create("mass")?
        .write_raw(&p.mass)?;
    file.new_dataset::<u8>()
        .shape(c.case_toml.len())
        .create("case_toml")?
        .write_raw(c.case_toml.as_bytes())?;
    let scalars = [
        ("time", c.time),
        ("dt", c.dt),
        ("skin", c.skin),
        ("last_acceleration", c.last_acceleration),
        ("next_snapshot", s.next_snapshot),
        ("next_series", s.next_series),
        ("initial_energy", s.initial_energy),
    ];
    for (name, v) in scalars {
        file.new_attr::<f64>().create(name)?.write_scalar(&v)?;
    }
    let counts = [
        ("dimension", D as u64),
        ("steps", c.counters.steps),
        ("evaluations", c.counters.evaluations),
        ("rebuilds", c.counters.rebuilds),
        ("snapshots", s.snapshots),
    ];
    for (name, v) in counts {
        file.new_attr::<u64>().create(name)?.write_scalar(&v)?;
    }
    if let Some(b) = &c.budget {
        let v = [b.dissipated, b.last.viscous, b.last.diffusive, b.last.wall];
        file.new_attr::<f64>()
            .shape(4)
            .create("energy_budget")?
            .write_raw(&v)?;
    }
    file.close()
}

/// The dimension of the run stored in `path`.
pub fn dimension(path: &Path) -> Result<usize> {
    let read = || -> hdf5::Result<u64> { hdf5::File::open(path)?.attr("dimension")?.read_scalar() };
    read()
        .map(|d| d as usize)
        .map_err(|e| SphError::output(path, format!("not a deltasph restart file ({e})")))
}

/// Reads a restart file written by [`write`] for a `D`-dimensional run.
pub fn read<const D: usize>(path: &Path) -> Result<(Checkpoint<D>, Schedule)> {
    let bad = |e: hdf5::Error| SphError::output(path, format!("not a deltasph restart file ({e})"));
    if dimension(path)? != D {
        return Err(SphError::output(path, format!("not a {D}D restart file")));
    }
    read_h5(path).map_err(bad)
}

fn read_h5<const D: usize>(path: &Path) -> hdf5::Result<(Checkpoint<D>, Schedule)> {
    let file = hdf5::File::open(path)?;
    let f64s = |name: &str| -> hdf5::Result<Vec<f64>> { file.dataset(name)?.read_raw() };
    let vecs = |name: &str| -> hdf5::Result<Vec<Vector<D>>> { Ok(vectors(&f64s(name)?)) };
    let scalar = |name: &str| -> hdf5::Result<f64> { file.attr(name)?.read_scalar() };
    let count = |name: &str| -> hdf5::Result<u64> { file.attr(name)?.read_scalar() };
    let kind = file
        .dataset("kind")?
        .read_raw::<u8>()?
        .into_iter()
        .map(|k| if k == 0 { Kind::Fluid } else { Kind::Wall })
        .collect();
    let particles = Particles {
        x: vecs("position")?,
        u: vecs("velocity")?,
        rho: f64s("density")?,
        p: f64s("pressure")?,
        mass: f64s("mass")?,
        kind,
        id: file.dataset("id")?.read_raw()?,
        u_wall_visc: vecs("wall_viscous_velocity")?,
    };
    let case_bytes: Vec<u8> = file.dataset("case_toml")?.read_raw()?;
    let budget = match file.attr("energy_budget") {
        Ok(a) => {
            let v: Vec<f64> = a.read_raw()?;
            let mut b = EnergyBudget {
                dissipated: v[0],
                ..Default::default()
            };
            (b.last.viscous, b.last.diffusive, b.last.wall) = (v[1], v[2], v[3]);
            Some(b)
        }
        Err(_) => None,
    };
    let checkpoint = Checkpoint {
        case_toml: String::from_utf8_lossy(&case_bytes).into_owned(),
        particles,
        list_positions: vecs("list_positions")?,
        skin: scalar("skin")?,
        time: scalar("time")?,
        dt: scalar("dt")?,
        counters: Counters {
            steps: count("steps")?,
            evaluations: count("evaluations")?,
            rebuilds: count("rebuilds")?,
        },
        last_acceleration: scalar("last_acceleration")?,
        budget,
        shift_velocity: file
            .dataset("shifting_velocity")
            .ok()
            .map(|d| d.read_raw().map(|v: Vec<f64>| vectors(&v)))
            .transpose()?,
    };
    let schedule = Schedule {
        next_snapshot: scalar("next_snapshot")?,
        next_series: scalar("next_series")?,
        snapshots: count("snapshots")?,
        initial_energy: scalar("initial_energy")?,
    };
    Ok((checkpoint, schedule))
}
