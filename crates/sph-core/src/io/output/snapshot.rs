//! Particle snapshots: one HDF5 file per output time, and the XDMF index that
//! ParaView and VisIt open as a time series.
//!
//! Each snapshot holds `position`, `velocity` (N×3, z = 0 in 2D), `density`,
//! `pressure`, `mass`, `kind` (0 fluid, 1 wall), `id`, and `connectivity` (0..N-1): the index
//! describes the particles as N vertex cells through it (`Polyvertex`, one node per
//! element). Without the connectivity, ParaView's Xdmf3 reader (its default for
//! `.xmf`) builds the points but no cells, and its default Surface view is empty.
//! Optional fields: `free_surface`, `normal`, `lambda`, `shifting_velocity`.
//! Attributes: `time`, `step`, `dimension`, `creator` (`"deltasph <version>"`).

use super::atomic;
use super::compression::Compression;
use crate::error::{Result, SphError};
use crate::particles::Particles;
use crate::physics::free_surface::FreeSurface;
use crate::simulation::Simulation;
use hdf5::types::VarLenUnicode;
use std::borrow::Cow;
use std::fs;
use std::path::{Path, PathBuf};

/// What deltasph writes into the `creator` attribute of its HDF5 files and the first
/// comment of its XDMF files.
pub const CREATOR: &str = concat!("deltasph ", env!("CARGO_PKG_VERSION"));

/// Optional per-particle fields written with a snapshot, in the current particle order.
#[derive(Debug, Clone, Copy, Default)]
pub struct Extras<'a, const D: usize> {
    /// Free-surface flag, normal and λ.
    pub surface: Option<&'a FreeSurface<D>>,
    /// Velocity of the last δ+-SPH shift, δr/Δt.
    pub shift_velocity: Option<&'a [crate::Vector<D>]>,
}

/// Calls `f` with the extra snapshot fields `sim` has: the free surface (when the case
/// asks for it or shifts particles) and the shifting velocity.
pub fn with_extras<const D: usize, R>(sim: &Simulation<D>, f: impl FnOnce(&Extras<D>) -> R) -> R {
    let shift_velocity = sim.shift_velocity();
    let wanted = sim.case().diagnostics.free_surface || shift_velocity.is_some();
    let surface = wanted.then(|| sim.free_surface());
    f(&Extras {
        surface: surface.as_ref(),
        shift_velocity,
    })
}

/// One snapshot listed in the XDMF index.
#[derive(Debug, Clone)]
pub(super) struct Entry {
    pub file: String,
    pub time: f64,
    pub n: usize,
    /// Whether the file holds the free-surface fields.
    pub surface: bool,
    /// Whether the file holds the shifting velocity.
    pub shift: bool,
    /// Whether the file holds the masses (older snapshots do not).
    pub mass: bool,
}

impl Entry {
    pub fn new<const D: usize>(file: String, time: f64, n: usize, extras: &Extras<D>) -> Self {
        Self {
            file,
            time,
            n,
            surface: extras.surface.is_some(),
            shift: extras.shift_velocity.is_some(),
            mass: true,
        }
    }

    /// The index entry of an existing snapshot file.
    pub fn read(path: &Path, file: String) -> Result<Self> {
        let read = || -> hdf5::Result<Entry> {
            let h5 = hdf5::File::open(path)?;
            Ok(Entry {
                time: h5.attr("time")?.read_scalar()?,
                n: h5.dataset("id")?.size(),
                surface: h5.dataset("free_surface").is_ok(),
                shift: h5.dataset("shifting_velocity").is_ok(),
                mass: h5.dataset("mass").is_ok(),
                file,
            })
        };
        read().map_err(|e| SphError::output(path, format!("unreadable snapshot ({e})")))
    }
}

/// Writes one HDF5 snapshot atomically, its datasets stored as `compression` says.
pub fn write_snapshot<const D: usize>(
    path: &Path,
    p: &Particles<D>,
    extras: &Extras<D>,
    (time, step): (f64, u64),
    compression: Compression,
) -> Result<()> {
    atomic::write(path, |tmp| {
        write_h5(tmp, p, extras, (time, step), compression)
    })
}

/// Writes a lone snapshot `path` (HDF5, as [`write_snapshot`], compressed at the
/// default level) and beside it an XDMF
/// index (`path` with the extension `.xmf`) that ParaView opens, the layout of a run
/// folder. Existing files are refused unless `overwrite`, and even then only files
/// deltasph wrote are replaced; returns the index's path.
pub fn write_indexed_snapshot<const D: usize>(
    path: &Path,
    p: &Particles<D>,
    extras: &Extras<D>,
    time: f64,
    step: u64,
    overwrite: bool,
) -> Result<PathBuf> {
    let index = path.with_extension("xmf");
    if index == path {
        return Err(SphError::output(
            path,
            "a snapshot needs an extension other than .xmf (e.g. .h5)",
        ));
    }
    for file in [path, index.as_path()] {
        if !file.exists() {
            continue;
        }
        if !overwrite {
            return Err(SphError::output(
                file,
                "file exists; choose another name or pass overwrite=True",
            ));
        }
        if !written_by_deltasph(file) {
            return Err(SphError::output(
                file,
                "file exists and was not written by deltasph; it is never overwritten",
            ));
        }
    }
    let name = path
        .file_name()
        .and_then(|n| n.to_str())
        .ok_or_else(|| SphError::output(path, "not a file name"))?;
    write_snapshot(path, p, extras, (time, step), Compression::default())?;
    let entry = Entry::new(name.to_string(), time, p.len(), extras);
    atomic::write(&index, |tmp| fs::write(tmp, xdmf(&[entry])))?;
    Ok(index)
}

/// Whether `path` is an HDF5 or XDMF file that deltasph wrote (its `creator`
/// attribute, or the first comment of the index).
pub fn written_by_deltasph(path: &Path) -> bool {
    if path.extension().is_some_and(|e| e == "xmf") {
        let head = fs::read(path).unwrap_or_default();
        let head = String::from_utf8_lossy(&head[..head.len().min(200)]).into_owned();
        return head.contains(&format!("<!-- {CREATOR_MARK}"));
    }
    hdf5::File::open(path)
        .and_then(|f| f.attr("creator")?.read_scalar::<VarLenUnicode>())
        .is_ok_and(|c| c.as_str().starts_with(CREATOR_MARK))
}

/// What every version of deltasph puts first in its `creator` marks.
const CREATOR_MARK: &str = "deltasph";

/// Positions and velocities padded to three components (what ParaView expects); in 3D
/// the vectors themselves, without a copy.
fn padded<const D: usize>(v: &[crate::Vector<D>]) -> Cow<'_, [f64]> {
    if D == 3 {
        return Cow::Borrowed(crate::particles::components(v));
    }
    v.iter()
        .flat_map(|x| (0..3).map(move |d| if d < D { x[d] } else { 0.0 }))
        .collect()
}

fn write_h5<const D: usize>(
    path: &Path,
    p: &Particles<D>,
    extras: &Extras<D>,
    (time, step): (f64, u64),
    c: Compression,
) -> hdf5::Result<()> {
    let file = hdf5::File::create(path)?;
    let n = p.len();
    let vector = |name: &str, v: &[crate::Vector<D>]| {
        c.create::<f64>(&file, name, n, 3)?.write_raw(&*padded(v))
    };
    vector("position", &p.x)?;
    vector("velocity", &p.u)?;
    write_scalars(&file, p, c)?;
    let vertices: Vec<u32> = (0..n as u32).collect();
    c.create::<u32>(&file, "connectivity", n, 1)?
        .write_raw(&vertices)?;
    if let Some(v) = extras.shift_velocity {
        vector("shifting_velocity", v)?;
    }
    if let Some(s) = extras.surface {
        let flag: Vec<u8> = s.on_surface.iter().map(|&b| b as u8).collect();
        c.create::<u8>(&file, "free_surface", n, 1)?
            .write_raw(&flag)?;
        vector("normal", &s.normal)?;
        c.create::<f64>(&file, "lambda", n, 1)?
            .write_raw(&s.lambda)?;
    }
    file.new_attr::<f64>().create("time")?.write_scalar(&time)?;
    file.new_attr::<u64>().create("step")?.write_scalar(&step)?;
    file.new_attr::<u32>()
        .create("dimension")?
        .write_scalar(&(D as u32))?;
    write_creator(&file)?;
    file.close()
}

/// Marks an HDF5 file as deltasph's.
pub(crate) fn write_creator(file: &hdf5::File) -> hdf5::Result<()> {
    let creator: VarLenUnicode = CREATOR.parse().expect("the creator text has no NUL");
    file.new_attr::<VarLenUnicode>()
        .create("creator")?
        .write_scalar(&creator)
}

/// Writes the per-particle `density`, `pressure`, `mass`, `kind` (0 fluid, 1 wall) and
/// `id`.
pub(crate) fn write_scalars<const D: usize>(
    file: &hdf5::File,
    p: &Particles<D>,
    c: Compression,
) -> hdf5::Result<()> {
    let n = p.len();
    for (name, v) in [("density", &p.rho), ("pressure", &p.p), ("mass", &p.mass)] {
        c.create::<f64>(file, name, n, 1)?.write_raw(v)?;
    }
    let kind: Vec<u8> = p.kind.iter().map(|&k| k as u8).collect();
    c.create::<u8>(file, "kind", n, 1)?.write_raw(&kind)?;
    c.create::<u32>(file, "id", n, 1)?.write_raw(&p.id)?;
    Ok(())
}

/// The XDMF 3 index of `entries`: a temporal collection of N-vertex grids.
pub(super) fn xdmf(entries: &[Entry]) -> String {
    let mut s = format!(
        "<?xml version=\"1.0\" ?>\n<!-- {CREATOR}: particle snapshots, one vertex cell per \
         particle -->\n<Xdmf Version=\"3.0\">\n <Domain>\n  \
         <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n"
    );
    for e in entries {
        s += &grid(e);
    }
    s + "  </Grid>\n </Domain>\n</Xdmf>\n"
}

fn grid(e: &Entry) -> String {
    let item = |name: &str, dims: &str, ty: &str, prec: usize| {
        format!(
            "<DataItem Dimensions=\"{dims}\" NumberType=\"{ty}\" Precision=\"{prec}\" \
             Format=\"HDF\">{}:/{name}</DataItem>",
            e.file
        )
    };
    let (n, n3) = (e.n.to_string(), format!("{} 3", e.n));
    let attribute = |name: &str, kind: &str, dims: &str, ty: &str, prec: usize| {
        format!(
            "    <Attribute Name=\"{name}\" AttributeType=\"{kind}\" Center=\"Node\">{}</Attribute>\n",
            item(name, dims, ty, prec)
        )
    };
    let scalar = |name: &str, ty: &str, prec: usize| attribute(name, "Scalar", &n, ty, prec);
    let vector = |name: &str| attribute(name, "Vector", &n3, "Float", 8);
    let mut s = format!("   <Grid Name=\"{}\" GridType=\"Uniform\">\n", e.file);
    s += &format!("    <Time Value=\"{:.9e}\"/>\n", e.time);
    s += &format!(
        "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"{}\" NodesPerElement=\"1\">{}</Topology>\n",
        e.n,
        item("connectivity", &n, "UInt", 4)
    );
    s += &format!(
        "    <Geometry GeometryType=\"XYZ\">{}</Geometry>\n",
        item("position", &n3, "Float", 8)
    );
    s += &vector("velocity");
    s += &scalar("density", "Float", 8);
    s += &scalar("pressure", "Float", 8);
    if e.mass {
        s += &scalar("mass", "Float", 8);
    }
    s += &scalar("kind", "UChar", 1);
    s += &scalar("id", "UInt", 4);
    if e.shift {
        s += &vector("shifting_velocity");
    }
    if e.surface {
        s += &scalar("free_surface", "UChar", 1);
        s += &scalar("lambda", "Float", 8);
        s += &vector("normal");
    }
    s + "   </Grid>\n"
}
