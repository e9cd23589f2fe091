//! Restart files: the complete state of a run, from which it continues bit for bit.
//!
//! Bit-for-bit continuation needs more than the physical state `(x, u, ρ)`:
//! - the particles in their current storage order (the pair sums run in list order,
//!   and floating-point addition is not associative), and the next free id;
//! - the neighbour lists, rebuilt from the positions of their last build and the same
//!   skin, so that the next list rebuild happens at the same step;
//! - the step count, time, last Δt, the acceleration that sizes the list skin, the
//!   energy budget and the counts of particles removed and created;
//! - the output schedule of the driver ([`Schedule`]).
//!
//! The file is HDF5 (`restart.h5` in a run folder, the one before it kept as
//! `restart.prev.h5`), written atomically and synced by [`crate::io::output::Output`]. It
//! carries the case as TOML, so it is self-contained. Reading checks every shape and
//! value it relies on: a damaged or foreign file is an error naming what is wrong.

use crate::diagnostics::{Excursion, Holder, WatchMemory};
use crate::error::{Result, SphError};
use crate::io::output::compression::Compression;
use crate::particles::{Kind, Particles, Vector};
use crate::simulation::{Checkpoint, Counters, EnergyBudget};
use hdf5::types::VarLenUnicode;
use std::borrow::Cow;
use std::path::Path;

/// Where the driver of a run stands in its output schedule.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Schedule {
    /// Time of the next particle snapshot.
    pub next_snapshot: f64,
    /// Time of the next time-series row.
    pub next_series: f64,
    /// Time of the next periodic restart file (infinite when the case asks for none).
    pub next_restart: f64,
    /// Snapshots written so far (the next one gets this index).
    pub snapshots: u64,
    /// `E_k + E_p + E_c` at the start of the run, for the closing summary.
    pub initial_energy: f64,
}

/// Writes `checkpoint` and `schedule` to `path` and syncs it to disk (the caller
/// renames it into place).
pub fn write_file<const D: usize>(
    path: &Path,
    checkpoint: &Checkpoint<'_, D>,
    schedule: &Schedule,
    compression: Compression,
) -> Result<()> {
    write_h5(path, checkpoint, schedule, compression).map_err(|e| SphError::output(path, e))?;
    std::fs::File::open(path)
        .and_then(|f| f.sync_all())
        .map_err(|e| SphError::output(path, e))
}

fn write_h5<const D: usize>(
    path: &Path,
    c: &Checkpoint<'_, D>,
    s: &Schedule,
    packing: Compression,
) -> hdf5::Result<()> {
    let file = hdf5::File::create(path)?;
    let p = &c.particles;
    let n = p.len();
    let vector = |name: &str, v: &[Vector<D>]| {
        (packing.create::<f64>(&file, name, n, D)?).write_raw(crate::particles::components(v))
    };
    vector("position", &p.x)?;
    vector("velocity", &p.u)?;
    vector("wall_viscous_velocity", &p.u_wall_visc)?;
    vector("list_positions", &c.list_positions)?;
    if let Some(v) = &c.particles.shift_velocity {
        vector("shifting_velocity", v)?;
    }
    crate::io::output::snapshot::write_scalars(&file, p, packing)?;
    (packing.create::<u8>(&file, "case_toml", c.case_toml.len(), 1)?)
        .write_raw(c.case_toml.as_bytes())?;
    let scalars = [
        ("time", c.time),
        ("dt", c.dt),
        ("skin", c.skin),
        ("last_acceleration", c.last_acceleration),
        ("next_snapshot", s.next_snapshot),
        ("next_series", s.next_series),
        ("next_restart", s.next_restart),
        ("initial_energy", s.initial_energy),
        ("removed_mass", c.counters.removed_mass),
    ];
    for (name, v) in scalars {
        file.new_attr::<f64>().create(name)?.write_scalar(&v)?;
    }
    let counts = [
        ("dimension", D as u64),
        ("steps", c.counters.steps),
        ("evaluations", c.counters.evaluations),
        ("rebuilds", c.counters.rebuilds),
        ("removed", c.counters.removed),
        ("created", c.counters.created),
        ("snapshots", s.snapshots),
        ("next_id", p.next_id as u64),
    ];
    for (name, v) in counts {
        file.new_attr::<u64>().create(name)?.write_scalar(&v)?;
    }
    if let Some(b) = &c.budget {
        let v = [
            b.dissipated,
            b.last.viscous,
            b.last.diffusive,
            b.last.wall,
            b.removed_energy,
            b.pending,
            b.last.moving,
            b.last.bodies,
            b.moving_work,
            b.last.forcing,
            b.forcing_work,
        ];
        file.new_attr::<f64>()
            .shape(v.len())
            .create("energy_budget")?
            .write_raw(&v)?;
    }
    write_records(&file, "sensor_filters", &c.sensor_filters)?;
    write_records(&file, "free_bodies", &c.free_bodies)?;
    write_records(&file, "absorbing_paddles", &c.absorbing_paddles)?;
    write_watch(&file, &c.density_watch)?;
    crate::io::output::snapshot::write_creator(&file)?;
    file.close()
}

/// The stability guard's memory: `density_watch_reported`, and for an excursion under
/// way `density_watch_excursion` (start, end, steps, peak particle, peak variation) and
/// `density_watch_position` (the peak's position as text).
fn write_watch(file: &hdf5::File, w: &WatchMemory) -> hdf5::Result<()> {
    (file.new_attr::<u64>().create("density_watch_reported")?)
        .write_scalar(&(w.reported as u64))?;
    let Some(e) = &w.open else {
        return Ok(());
    };
    let record = [
        e.start,
        e.end,
        e.steps as f64,
        e.peak.particle as f64,
        e.peak.variation,
    ];
    write_records(file, "density_watch_excursion", &[record])?;
    let text: VarLenUnicode =
        (e.peak.position.parse()).unwrap_or_else(|_| "(unknown)".parse().expect("no NUL"));
    (file
        .new_attr::<VarLenUnicode>()
        .create("density_watch_position")?)
    .write_scalar(&text)
}

/// Fixed-length records as one flat attribute, none when there are no records.
fn write_records<const N: usize>(
    file: &hdf5::File,
    name: &str,
    records: &[[f64; N]],
) -> hdf5::Result<()> {
    if records.is_empty() {
        return Ok(());
    }
    let v: Vec<f64> = records.iter().flatten().copied().collect();
    file.new_attr::<f64>()
        .shape(v.len())
        .create(name)?
        .write_raw(&v)
}

/// The dimension of the run stored in `path`.
pub fn dimension(path: &Path) -> Result<usize> {
    let read = || -> hdf5::Result<u64> { hdf5::File::open(path)?.attr("dimension")?.read_scalar() };
    match read() {
        Ok(d @ (2 | 3)) => Ok(d as usize),
        Ok(d) => Err(SphError::output(
            path,
            format!("dimension {d} is not 2 or 3"),
        )),
        Err(e) => Err(SphError::output(
            path,
            format!("not a deltasph restart file ({e})"),
        )),
    }
}

/// Reads a restart file written by [`write_file`] for a `D`-dimensional run.
pub fn read<const D: usize>(path: &Path) -> Result<(Checkpoint<'static, D>, Schedule)> {
    if dimension(path)? != D {
        return Err(SphError::output(path, format!("not a {D}D restart file")));
    }
    let file = hdf5::File::open(path).map_err(|e| SphError::output(path, e))?;
    let reader = Reader { file: &file, path };
    reader.read()
}

/// Reads and checks the datasets of one restart file.
struct Reader<'a> {
    file: &'a hdf5::File,
    path: &'a Path,
}

impl Reader<'_> {
    fn corrupt(&self, what: impl std::fmt::Display) -> SphError {
        SphError::output(self.path, format!("damaged restart file: {what}"))
    }

    fn dataset<T: hdf5::H5Type>(&self, name: &str, shape: &[usize]) -> Result<Vec<T>> {
        let ds = self
            .file
            .dataset(name)
            .map_err(|e| self.corrupt(format!("no dataset {name} ({e})")))?;
        if ds.shape() != shape {
            return Err(self.corrupt(format!(
                "dataset {name} has shape {:?}, expected {shape:?}",
                ds.shape()
            )));
        }
        ds.read_raw::<T>().map_err(|e| {
            self.corrupt(format!(
                "dataset {name} unreadable as the expected type ({e})"
            ))
        })
    }

    fn vectors<const D: usize>(&self, name: &str, n: usize) -> Result<Vec<Vector<D>>> {
        let raw: Vec<f64> = self.dataset(name, &[n, D])?;
        Ok(raw
            .chunks_exact(D)
            .map(Vector::<D>::from_column_slice)
            .collect())
    }

    fn attr<T: hdf5::H5Type>(&self, name: &str) -> Result<T> {
        self.file
            .attr(name)
            .and_then(|a| a.read_scalar::<T>())
            .map_err(|e| self.corrupt(format!("attribute {name} ({e})")))
    }

    fn read<const D: usize>(&self) -> Result<(Checkpoint<'static, D>, Schedule)> {
        let n = self
            .file
            .dataset("id")
            .map_err(|e| self.corrupt(format!("no dataset id ({e})")))?
            .size();
        let kind = self
            .dataset::<u8>("kind", &[n])?
            .into_iter()
            .map(|k| match k {
                0 => Ok(Kind::Fluid),
                1 => Ok(Kind::Wall),
                other => Err(self.corrupt(format!("particle kind {other} (expected 0 or 1)"))),
            })
            .collect::<Result<Vec<_>>>()?;
        let id: Vec<u32> = self.dataset("id", &[n])?;
        let next_id = match self.attr::<u64>("next_id") {
            Ok(v) => u32::try_from(v).map_err(|_| self.corrupt(format!("next_id {v}")))?,
            Err(_) => id.iter().max().map_or(0, |m| m + 1),
        };
        if id.iter().any(|&i| i >= next_id) {
            return Err(self.corrupt("a particle id at or above next_id"));
        }
        let particles = Particles {
            x: self.vectors("position", n)?,
            u: self.vectors("velocity", n)?,
            rho: self.dataset("density", &[n])?,
            p: self.dataset("pressure", &[n])?,
            mass: self.dataset("mass", &[n])?,
            kind,
            id,
            u_wall_visc: self.vectors("wall_viscous_velocity", n)?,
            shift_velocity: match self.file.dataset("shifting_velocity") {
                Ok(_) => Some(self.vectors("shifting_velocity", n)?),
                Err(_) => None,
            },
            // a function of time: the motions set it again at the restart time
            wall_acceleration: None,
            next_id,
        };
        let case_bytes: Vec<u8> = self
            .file
            .dataset("case_toml")
            .and_then(|d| d.read_raw())
            .map_err(|e| self.corrupt(format!("no case ({e})")))?;
        let case_toml = String::from_utf8(case_bytes)
            .map_err(|_| self.corrupt("the case text is not UTF-8"))?;
        let checkpoint = Checkpoint {
            case_toml,
            particles: Cow::Owned(particles),
            list_positions: Cow::Owned(self.vectors("list_positions", n)?),
            skin: self.attr("skin")?,
            time: self.attr("time")?,
            dt: self.attr("dt")?,
            counters: Counters {
                steps: self.attr("steps")?,
                evaluations: self.attr("evaluations")?,
                rebuilds: self.attr("rebuilds")?,
                removed: self.attr("removed").unwrap_or(0),
                created: self.attr("created").unwrap_or(0),
                removed_mass: self.attr("removed_mass").unwrap_or(0.0),
            },
            last_acceleration: self.attr("last_acceleration")?,
            budget: self.budget()?,
            sensor_filters: self.records("sensor_filters")?,
            free_bodies: self.records("free_bodies")?,
            absorbing_paddles: self.records("absorbing_paddles")?,
            density_watch: self.watch()?,
        };
        let schedule = Schedule {
            next_snapshot: self.attr("next_snapshot")?,
            next_series: self.attr("next_series")?,
            next_restart: self.attr("next_restart").unwrap_or(f64::INFINITY),
            snapshots: self.attr("snapshots")?,
            initial_energy: self.attr("initial_energy")?,
        };
        Ok((checkpoint, schedule))
    }

    /// The guard's memory of [`write_watch`] (a fresh one in files written before it).
    fn watch(&self) -> Result<WatchMemory> {
        let reported = self.attr::<u64>("density_watch_reported").unwrap_or(0) as usize;
        let open = match self.records::<5>("density_watch_excursion")?.as_slice() {
            [] => None,
            [[start, end, steps, particle, variation]] => Some(Excursion {
                start: *start,
                end: *end,
                steps: *steps as usize,
                peak: Holder {
                    particle: *particle as u32,
                    position: self
                        .attr::<VarLenUnicode>("density_watch_position")?
                        .to_string(),
                    variation: *variation,
                },
            }),
            _ => return Err(self.corrupt("density_watch_excursion holds more than one")),
        };
        Ok(WatchMemory { reported, open })
    }

    /// The records of [`write_records`] (none when the attribute is absent).
    fn records<const N: usize>(&self, name: &str) -> Result<Vec<[f64; N]>> {
        let Ok(a) = self.file.attr(name) else {
            return Ok(Vec::new());
        };
        let v: Vec<f64> = a
            .read_raw()
            .map_err(|e| self.corrupt(format!("attribute {name} ({e})")))?;
        if !v.len().is_multiple_of(N) {
            return Err(self.corrupt(format!("{name} holds {} values, not {N} a record", v.len())));
        }
        Ok(v.chunks(N).map(|c| std::array::from_fn(|k| c[k])).collect())
    }

    fn budget(&self) -> Result<Option<EnergyBudget>> {
        let Ok(a) = self.file.attr("energy_budget") else {
            return Ok(None);
        };
        let v: Vec<f64> = a
            .read_raw()
            .map_err(|e| self.corrupt(format!("attribute energy_budget ({e})")))?;
        // 6 in files written before moving walls and free bodies had powers, 9 before
        // the body force and the absorbers had
        if ![6, 9, 11].contains(&v.len()) {
            return Err(self.corrupt(format!(
                "energy_budget holds {} values, expected 11",
                v.len()
            )));
        }
        let mut b = EnergyBudget {
            dissipated: v[0],
            removed_energy: v[4],
            pending: v[5],
            ..Default::default()
        };
        (b.last.viscous, b.last.diffusive, b.last.wall) = (v[1], v[2], v[3]);
        if let [moving, bodies, work, ..] = v[6..] {
            (b.last.moving, b.last.bodies, b.moving_work) = (moving, bodies, work);
        }
        if let [forcing, work] = v[9..] {
            (b.last.forcing, b.forcing_work) = (forcing, work);
        }
        Ok(Some(b))
    }
}
