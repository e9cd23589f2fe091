//! Output a user can open: HDF5 particle snapshots indexed by an XDMF file (ParaView
//! and VisIt read the time series directly, [`snapshot`]), a CSV time series, restart
//! files, and the run folder that holds them.
//!
//! Nothing a user owns is touched: a run folder carries a manifest ([`manifest`]) of
//! the files deltasph wrote, a non-empty folder without one is never used, and
//! `--force` removes only the listed files. Every file is written atomically and
//! synced ([`atomic`]), so a run that is killed leaves only complete files.

pub mod atomic;
pub mod compression;
pub mod manifest;
pub mod polydata;
pub mod reading;
pub mod snapshot;

pub use compression::Compression;
pub use snapshot::{with_extras, write_indexed_snapshot, write_snapshot, Extras};

use crate::error::{Result, SphError};
use crate::io::restart::{self, Schedule};
use crate::particles::Particles;
use crate::simulation::Checkpoint;
use manifest::Manifest;
use snapshot::{xdmf, Entry};
use std::fs::{self, File};
use std::io::{BufWriter, ErrorKind, Write};
use std::path::{Path, PathBuf};

/// The newest restart file of a run folder.
pub const RESTART: &str = "restart.h5";
/// The restart file before it (restart files are kept in pairs).
pub const RESTART_PREVIOUS: &str = "restart.prev.h5";
const SERIES: &str = "timeseries.csv";
const INDEX: &str = "particles.xmf";

/// The output folder of one run.
pub struct Output {
    dir: PathBuf,
    manifest: Manifest,
    entries: Vec<Entry>,
    series: Option<BufWriter<File>>,
    compression: Compression,
}

impl Output {
    /// Creates the run folder `dir` (or takes an empty one). A non-empty folder is
    /// refused unless it is a deltasph run folder and `force` is given; then the files
    /// of the earlier run are removed and every other file is kept.
    pub fn create(dir: &Path, force: bool) -> Result<Self> {
        let manifest =
            match fs::metadata(dir) {
                Err(e) if e.kind() == ErrorKind::NotFound => {
                    fs::create_dir_all(dir).map_err(|e| SphError::output(dir, e))?;
                    Manifest::create(dir)?
                }
                Err(e) => return Err(SphError::output(dir, e)),
                Ok(m) if !m.is_dir() => {
                    return Err(SphError::output(dir, "exists and is not a folder"))
                }
                Ok(_) if manifest::is_empty(dir)? => Manifest::create(dir)?,
                Ok(_) => match Manifest::read(dir)? {
                    None => return Err(foreign_folder(dir)),
                    Some(_) if !force => return Err(SphError::output(
                        dir,
                        "holds an earlier run; pass --force to replace the files deltasph wrote \
                         there (other files are kept), or choose another --out",
                    )),
                    Some(mut m) => {
                        m.remove_all()?;
                        m
                    }
                },
            };
        Ok(Self {
            dir: dir.to_path_buf(),
            manifest,
            entries: Vec::new(),
            series: None,
            compression: Compression::default(),
        })
    }

    /// Reopens the folder of a run that continues from a restart written after its
    /// first `snapshots` snapshots: they stay listed in the XDMF index and the next one
    /// continues the numbering. Snapshots numbered from `snapshots` on (written past an
    /// older restart, or by the run after its last restart file before it was killed)
    /// are refused unless `force`, which removes them. A new or empty folder is started.
    pub fn resume(dir: &Path, snapshots: u64, force: bool) -> Result<Self> {
        let fresh = !dir.exists() || manifest::is_empty(dir)?;
        if fresh {
            return Self::create(dir, false);
        }
        let mut manifest = Manifest::read(dir)?.ok_or_else(|| foreign_folder(dir))?;
        let later: Vec<String> = (snapshots..)
            .map(snapshot_name)
            .take_while(|f| dir.join(f).exists())
            .collect();
        if let Some(first) = later.first() {
            if !force {
                return Err(SphError::output(
                    dir.join(first),
                    "snapshot from after the restart point exists; pass --force to replace the \
                     later snapshots, or choose another --out",
                ));
            }
            for f in &later {
                if !manifest.lists(f) {
                    return Err(SphError::output(
                        dir.join(f),
                        "was not written by deltasph; it is never removed",
                    ));
                }
                manifest.remove(f)?;
            }
        }
        let mut entries = Vec::new();
        for k in 0..snapshots {
            let file = snapshot_name(k);
            let path = dir.join(&file);
            if path.exists() {
                entries.push(Entry::read(&path, file)?);
            }
        }
        let mut out = Self {
            dir: dir.to_path_buf(),
            manifest,
            entries,
            series: None,
            compression: Compression::default(),
        };
        out.write_index()?;
        Ok(out)
    }

    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// Stores the snapshots and restart files written from now on as `compression` says
    /// (the default: [`Compression::default`]).
    pub fn set_compression(&mut self, compression: Compression) {
        self.compression = compression;
    }

    /// Writes a text file atomically inside the folder.
    pub fn write_text(&mut self, name: &str, text: &str) -> Result<()> {
        self.write_bytes(name, text.as_bytes()).map(|_| ())
    }

    /// Writes a file atomically inside the folder; returns its path.
    pub fn write_bytes(&mut self, name: &str, bytes: &[u8]) -> Result<PathBuf> {
        self.manifest.claim(name)?;
        let path = self.dir.join(name);
        atomic::write(&path, |tmp| fs::write(tmp, bytes))?;
        Ok(path)
    }

    fn write_index(&mut self) -> Result<()> {
        let text = xdmf(&self.entries);
        self.write_text(INDEX, &text)
    }

    /// Writes one HDF5 snapshot (with the extra fields given) and refreshes the XDMF
    /// index; returns the snapshot's path.
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
        self.manifest.claim(&name)?;
        write_snapshot(&path, p, extras, (time, step), self.compression)?;
        self.entries.push(Entry::new(name, time, p.len(), extras));
        self.write_index()?;
        Ok(path)
    }

    /// Starts the CSV time series `timeseries.csv` with the given column names.
    pub fn start_series(&mut self, columns: &[String]) -> Result<()> {
        self.write_text(SERIES, &format!("{}\n", columns.join(",")))?;
        self.series = Some(BufWriter::new(manifest::open_append(
            &self.dir.join(SERIES),
        )?));
        Ok(())
    }

    /// Continues `timeseries.csv` from a restart at `time`, dropping rows after it
    /// (written past an older restart, or after the restart by a killed run) and rows
    /// cut short by a failed write, or starts it with `columns`.
    pub fn resume_series(&mut self, columns: &[String], time: f64) -> Result<()> {
        let path = self.dir.join(SERIES);
        let Ok(text) = fs::read_to_string(&path) else {
            return self.start_series(columns);
        };
        let width = columns.len();
        let kept: Vec<&str> = text
            .lines()
            .enumerate()
            .filter(|(k, line)| {
                let fields: Vec<&str> = line.split(',').collect();
                *k == 0
                    || (fields.len() == width
                        && fields.iter().all(|f| f.parse::<f64>().is_ok())
                        && fields[0]
                            .parse::<f64>()
                            .is_ok_and(|t| t <= time * (1.0 + 1e-9)))
            })
            .map(|(_, line)| line)
            .collect();
        self.write_text(SERIES, &(kept.join("\n") + "\n"))?;
        self.series = Some(BufWriter::new(manifest::open_append(&path)?));
        Ok(())
    }

    /// Appends one row (flushed, so a killed run keeps every row written).
    pub fn series_row(&mut self, values: &[f64]) -> Result<()> {
        let path = self.dir.join(SERIES);
        if let Some(w) = self.series.as_mut() {
            let row: Vec<String> = values.iter().map(|v| format!("{v:.10e}")).collect();
            writeln!(w, "{}", row.join(","))
                .and_then(|_| w.flush())
                .map_err(|e| SphError::output(&path, e))?;
        }
        Ok(())
    }

    /// Removes `restart.prev.h5`, to make room for a restart file on a full disk (the
    /// newer `restart.h5` stays).
    pub fn drop_previous_restart(&mut self) {
        let _ = fs::remove_file(self.dir.join(RESTART_PREVIOUS));
    }

    /// Writes a restart file as the folder's newest, `restart.h5`, keeping the one it
    /// replaces as `restart.prev.h5`. At every moment `restart.h5` is a complete file.
    pub fn write_restart<const D: usize>(
        &mut self,
        checkpoint: &Checkpoint<'_, D>,
        schedule: &Schedule,
    ) -> Result<PathBuf> {
        self.manifest.claim(RESTART)?;
        self.manifest.claim(RESTART_PREVIOUS)?;
        let (newest, previous) = (self.dir.join(RESTART), self.dir.join(RESTART_PREVIOUS));
        let tmp = atomic::partial(&newest);
        if let Err(e) = restart::write_file(&tmp, checkpoint, schedule, self.compression) {
            let _ = fs::remove_file(&tmp);
            return Err(e);
        }
        if newest.exists() {
            // `restart.h5` stays in place while its copy becomes the previous one
            let keep = atomic::partial(&previous);
            let _ = fs::remove_file(&keep);
            fs::hard_link(&newest, &keep)
                .or_else(|_| fs::copy(&newest, &keep).map(|_| ()))
                .and_then(|_| fs::rename(&keep, &previous))
                .map_err(|e| SphError::output(&previous, e))?;
        }
        fs::rename(&tmp, &newest).map_err(|e| SphError::output(&newest, e))?;
        atomic::sync_folder(&newest)?;
        Ok(newest)
    }
}

fn foreign_folder(dir: &Path) -> SphError {
    SphError::output(
        dir,
        "is not empty and is not a deltasph run folder (it has no .deltasph-run manifest); \
         nothing there was touched: choose another --out",
    )
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
