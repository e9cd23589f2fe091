//! Output a user can open: HDF5 particle snapshots indexed by an XDMF file (ParaView
//! and VisIt read the time series directly), and CSV time series.
//!
//! Every file is written under a temporary name and renamed into place, so a run
//! that is killed leaves only complete files. An existing, non-empty output folder
//! is never reused unless the caller explicitly allows it.

use crate::error::{Result, SphError};
use crate::free_surface::FreeSurface;
use crate::particles::Particles;
use std::fs::{self, File};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// Optional per-particle fields written with a snapshot, in the current particle order.
#[derive(Debug, Clone, Copy, Default)]
pub struct Extras<'a, const D: usize> {
    /// Free-surface flag, normal and λ.
    pub surface: Option<&'a FreeSurface<D>>,
    /// Velocity of the last δ+-SPH shift, δr/Δt.
    pub shift_velocity: Option<&'a [crate::Vector<D>]>,
}

/// One snapshot listed in the XDMF index.
#[derive(Debug, Clone)]
struct Entry {
    file: String,
    time: f64,
    n: usize,
    /// Whether the file holds the free-surface fields.
    surface: bool,
    /// Whether the file holds the shifting velocity.
    shift: bool,
}

impl Entry {
    fn new<const D: usize>(file: String, time: f64, n: usize, extras: &Extras<D>) -> Self {
        Self {
            file,
            time,
            n,
            surface: extras.surface.is_some(),
            shift: extras.shift_velocity.is_some(),
        }
    }
}

/// The output folder of one run.
pub struct Output {
    dir: PathBuf,
    entries: Vec<Entry>,
    series: Option<BufWriter<File>>,
}

impl Output {
    /// Creates `dir`; refuses a non-empty existing folder unless `overwrite`.
    pub fn create(dir: &Path, overwrite: bool) -> Result<Self> {
        if dir.exists() {
            let non_empty = fs::read_dir(dir)
                .map_err(|e| SphError::output(dir, e))?
                .next()
                .is_some();
            if non_empty && !overwrite {
                return Err(SphError::output(
                    dir,
                    "folder exists and is not empty; choose another --out or pass --force to overwrite",
                ));
            }
            if non_empty {
                fs::remove_dir_all(dir).map_err(|e| SphError::output(dir, e))?;
            }
        }
        fs::create_dir_all(dir).map_err(|e| SphError::output(dir, e))?;
        Ok(Self {
            dir: dir.to_path_buf(),
            entries: Vec::new(),
            series: None,
        })
    }

    /// Reopens the folder of a run that continues from a restart written after its
    /// first `snapshots` snapshots: they stay listed in the XDMF index and the next one
    /// continues the numbering. Snapshots numbered from `snapshots` on (written past an
    /// older restart) are refused unless `overwrite`, which removes them.
    pub fn resume(dir: &Path, snapshots: u64, overwrite: bool) -> Result<Self> {
        fs::create_dir_all(dir).map_err(|e| SphError::output(dir, e))?;
        let later: Vec<PathBuf> = (snapshots..)
            .map(|k| dir.join(snapshot_name(k)))
            .take_while(|f| f.exists())
            .collect();
        if let Some(first) = later.first() {
            if !overwrite {
                return Err(SphError::output(
                    first,
                    "snapshot from after the restart point exists; choose another --out or pass --force to replace the later snapshots",
                ));
            }
            for f in &later {
                fs::remove_file(f).map_err(|e| SphError::output(f, e))?;
            }
        }
        let mut entries = Vec::new();
        for k in 0..snapshots {
            let file = snapshot_name(k);
            let path = dir.join(&file);
            if path.exists() {
                entries.push(read_entry(&path, file)?);
            }
        }
        let out = Self {
            dir: dir.to_path_buf(),
            entries,
            series: None,
        };
        out.write_text("particles.xmf", &xdmf(&out.entries))?;
        Ok(out)
    }

    /// Continues `timeseries.csv` from a restart at `time`, dropping rows after it
    /// (written past an older restart), or starts it with `columns`.
    pub fn resume_series(&mut self, columns: &[String], time: f64) -> Result<()> {
        let path = self.dir.join("timeseries.csv");
        let Ok(text) = fs::read_to_string(&path) else {
            return self.start_series(columns);
        };
        let kept: Vec<&str> = text
            .lines()
            .enumerate()
            .filter(|(k, line)| {
                *k == 0
                    || line
                        .split(',')
                        .next()
                        .and_then(|t| t.parse::<f64>().ok())
                        .is_some_and(|t| t <= time * (1.0 + 1e-9))
            })
            .map(|(_, line)| line)
            .collect();
        self.write_text("timeseries.csv", &(kept.join("\n") + "\n"))?;
        let file = fs::OpenOptions::new()
            .append(true)
            .open(&path)
            .map_err(|e| SphError::output(&path, e))?;
        self.series = Some(BufWriter::new(file));
        Ok(())
    }

    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// Writes a text file atomically inside the folder.
    pub fn write_text(&self, name: &str, text: &str) -> Result<()> {
        atomic_write(&self.dir.join(name), |tmp| {
            fs::write(tmp, text).map_err(|e| e.to_string())
        })
    }

    /// Writes one HDF5 snapshot (with the extra fields given) and
    /// refreshes the XDMF index.
    pub fn snapshot<const D: usize>(
        &mut self,
        p: &Particles<D>,
        extras: &Extras<D>,
        time: f64,
        step: u64,
    ) -> Result<PathBuf> {
        let next = self
            .entries
            .last()
            .map_or(0, |e| snapshot_index(&e.file) + 1);
        let name = snapshot_name(next);
        let path = self.dir.join(&name);
        write_snapshot(&path, p, extras, time, step)?;
        self.entries.push(Entry::new(name, time, p.len(), extras));
        self.write_text("particles.xmf", &xdmf(&self.entries))?;
        Ok(path)
    }

    /// Starts the CSV time series `timeseries.csv` with the given column names.
    pub fn start_series(&mut self, columns: &[String]) -> Result<()> {
        let path = self.dir.join("timeseries.csv");
        let file = File::create(&path).map_err(|e| SphError::output(&path, e))?;
        let mut w = BufWriter::new(file);
        writeln!(w, "{}", columns.join(",")).map_err(|e| SphError::output(&path, e))?;
        self.series = Some(w);
        Ok(())
    }

    /// Appends one row (flushed, so a killed run keeps every row written).
    pub fn series_row(&mut self, values: &[f64]) -> Result<()> {
        let path = self.dir.join("timeseries.csv");
        if let Some(w) = self.series.as_mut() {
            let row: Vec<String> = values.iter().map(|v| format!("{v:.10e}")).collect();
            writeln!(w, "{}", row.join(","))
                .and_then(|_| w.flush())
                .map_err(|e| SphError::output(&path, e))?;
        }
        Ok(())
    }
}

fn snapshot_name(k: u64) -> String {
    format!("particles_{k:06}.h5")
}

fn snapshot_index(name: &str) -> u64 {
    name.trim_start_matches("particles_")
        .trim_end_matches(".h5")
        .parse()
        .unwrap_or(0)
}

/// The index entry of an existing snapshot file.
fn read_entry(path: &Path, file: String) -> Result<Entry> {
    let read = || -> hdf5::Result<Entry> {
        let h5 = hdf5::File::open(path)?;
        Ok(Entry {
            time: h5.attr("time")?.read_scalar()?,
            n: h5.dataset("id")?.size(),
            surface: h5.dataset("free_surface").is_ok(),
            shift: h5.dataset("shifting_velocity").is_ok(),
            file,
        })
    };
    read().map_err(|e| SphError::output(path, format!("unreadable snapshot ({e})")))
}

/// Writes `f(tmp)` to a temporary sibling of `path`, then renames it into place.
fn atomic_write(
    path: &Path,
    f: impl FnOnce(&Path) -> std::result::Result<(), String>,
) -> Result<()> {
    let tmp = path.with_extension(format!(
        "{}.partial",
        path.extension().and_then(|e| e.to_str()).unwrap_or("")
    ));
    f(&tmp).map_err(|e| SphError::output(path, e))?;
    fs::rename(&tmp, path).map_err(|e| SphError::output(path, e))
}

/// Positions and velocities padded to three components (what ParaView expects).
fn padded<const D: usize>(v: &[crate::Vector<D>]) -> Vec<f64> {
    v.iter()
        .flat_map(|x| (0..3).map(move |d| if d < D { x[d] } else { 0.0 }))
        .collect()
}

/// Writes one HDF5 snapshot: `position`, `velocity` (N×3), `density`, `pressure`,
/// `kind` (0 fluid, 1 wall), `id`; with the extras, also `free_surface` (1 on the free
/// surface), `normal` (N×3), `lambda` and `shifting_velocity` (N×3); attributes `time`,
/// `step`, `dimension`.
pub fn write_snapshot<const D: usize>(
    path: &Path,
    p: &Particles<D>,
    extras: &Extras<D>,
    time: f64,
    step: u64,
) -> Result<()> {
    atomic_write(path, |tmp| {
        write_h5(tmp, p, extras, time, step).map_err(|e| e.to_string())
    })
}

/// Writes a lone snapshot `path` (HDF5, as [`write_snapshot`]) and beside it an XDMF
/// index (`path` with the extension `.xmf`) that ParaView opens, the layout of a run
/// folder. Existing files are kept unless `overwrite`; returns the index's path.
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
        if file.exists() && !overwrite {
            return Err(SphError::output(
                file,
                "file exists; choose another name or pass overwrite=True",
            ));
        }
    }
    let name = path
        .file_name()
        .and_then(|n| n.to_str())
        .ok_or_else(|| SphError::output(path, "not a file name"))?;
    write_snapshot(path, p, extras, time, step)?;
    let entry = Entry::new(name.to_string(), time, p.len(), extras);
    atomic_write(&index, |tmp| {
        fs::write(tmp, xdmf(&[entry])).map_err(|e| e.to_string())
    })?;
    Ok(index)
}

fn write_h5<const D: usize>(
    path: &Path,
    p: &Particles<D>,
    extras: &Extras<D>,
    time: f64,
    step: u64,
) -> hdf5::Result<()> {
    let file = hdf5::File::create(path)?;
    let n = p.len();
    file.new_dataset::<f64>()
        .shape((n, 3))
        .create("position")?
        .write_raw(&padded(&p.x))?;
    file.new_dataset::<f64>()
        .shape((n, 3))
        .create("velocity")?
        .write_raw(&padded(&p.u))?;
    write_scalars(&file, p)?;
    if let Some(v) = extras.shift_velocity {
        file.new_dataset::<f64>()
            .shape((n, 3))
            .create("shifting_velocity")?
            .write_raw(&padded(v))?;
    }
    if let Some(s) = extras.surface {
        let flag: Vec<u8> = s.on_surface.iter().map(|&b| b as u8).collect();
        file.new_dataset::<u8>()
            .shape(n)
            .create("free_surface")?
            .write_raw(&flag)?;
        file.new_dataset::<f64>()
            .shape((n, 3))
            .create("normal")?
            .write_raw(&padded(&s.normal))?;
        file.new_dataset::<f64>()
            .shape(n)
            .create("lambda")?
            .write_raw(&s.lambda)?;
    }
    file.new_attr::<f64>().create("time")?.write_scalar(&time)?;
    file.new_attr::<u64>().create("step")?.write_scalar(&step)?;
    file.new_attr::<u32>()
        .create("dimension")?
        .write_scalar(&(D as u32))?;
    file.close()
}

/// Writes the per-particle `density`, `pressure`, `kind` (0 fluid, 1 wall) and `id`.
pub(crate) fn write_scalars<const D: usize>(
    file: &hdf5::File,
    p: &Particles<D>,
) -> hdf5::Result<()> {
    let n = p.len();
    for (name, v) in [("density", &p.rho), ("pressure", &p.p)] {
        file.new_dataset::<f64>()
            .shape(n)
            .create(name)?
            .write_raw(v)?;
    }
    let kind: Vec<u8> = p.kind.iter().map(|&k| k as u8).collect();
    file.new_dataset::<u8>()
        .shape(n)
        .create("kind")?
        .write_raw(&kind)?;
    file.new_dataset::<u32>()
        .shape(n)
        .create("id")?
        .write_raw(&p.id)?;
    Ok(())
}

fn xdmf(entries: &[Entry]) -> String {
    let mut s = String::from(
        "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n  \
         <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n",
    );
    for e in entries {
        let item = |name: &str, dims: &str, ty: &str, prec: usize| {
            format!(
                "<DataItem Dimensions=\"{dims}\" NumberType=\"{ty}\" Precision=\"{prec}\" \
                 Format=\"HDF\">{}:/{name}</DataItem>",
                e.file
            )
        };
        let (n, n3) = (e.n.to_string(), format!("{} 3", e.n));
        let scalar = |name: &str, ty: &str, prec: usize| {
            format!(
                "    <Attribute Name=\"{name}\" AttributeType=\"Scalar\" Center=\"Node\">{}</Attribute>\n",
                item(name, &n, ty, prec)
            )
        };
        s += &format!("   <Grid Name=\"{}\" GridType=\"Uniform\">\n", e.file);
        s += &format!("    <Time Value=\"{:.9e}\"/>\n", e.time);
        s += &format!(
            "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"{}\" NodesPerElement=\"1\"/>\n",
            e.n
        );
        s += &format!(
            "    <Geometry GeometryType=\"XYZ\">{}</Geometry>\n",
            item("position", &n3, "Float", 8)
        );
        s += &format!(
            "    <Attribute Name=\"velocity\" AttributeType=\"Vector\" Center=\"Node\">{}</Attribute>\n",
            item("velocity", &n3, "Float", 8)
        );
        s += &scalar("density", "Float", 8);
        s += &scalar("pressure", "Float", 8);
        s += &scalar("kind", "UChar", 1);
        s += &scalar("id", "UInt", 4);
        let vector = |name: &str| {
            format!(
                "    <Attribute Name=\"{name}\" AttributeType=\"Vector\" Center=\"Node\">{}</Attribute>\n",
                item(name, &n3, "Float", 8)
            )
        };
        if e.shift {
            s += &vector("shifting_velocity");
        }
        if e.surface {
            s += &scalar("free_surface", "UChar", 1);
            s += &scalar("lambda", "Float", 8);
            s += &vector("normal");
        }
        s += "   </Grid>\n";
    }
    s + "  </Grid>\n </Domain>\n</Xdmf>\n"
}
