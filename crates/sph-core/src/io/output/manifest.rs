//! The manifest of a run folder, `.deltasph-run`: the names of the files deltasph
//! wrote there, one per line after a comment line. A folder with a manifest is a run
//! folder; `--force` removes the files it lists and nothing else, and deltasph never
//! writes over a file it does not list.
//!
//! A name is recorded before its file is first written (appended and synced), so a
//! run killed at any moment leaves no file of its own unlisted. Only plain names (one
//! path component) are ever removed, whatever a hand-edited manifest says.

use super::atomic::PARTIAL;
use crate::error::{Result, SphError};
use std::collections::BTreeSet;
use std::fs::{self, File, OpenOptions};
use std::io::{ErrorKind, Write};
use std::path::{Path, PathBuf};

/// The manifest's file name.
pub const MANIFEST: &str = ".deltasph-run";

const HEADER: &str = "# deltasph run folder: the files listed below were written by deltasph; \
                      `sph-cli run --force` removes these and nothing else";

/// The files deltasph wrote in one folder.
#[derive(Debug)]
pub struct Manifest {
    dir: PathBuf,
    names: BTreeSet<String>,
}

/// Whether `name` is one plain path component (what a manifest may list).
fn plain(name: &str) -> bool {
    !name.is_empty()
        && name != "."
        && name != ".."
        && !name.contains(['/', '\\'])
        && !name.chars().any(char::is_control)
}

impl Manifest {
    /// The manifest of `dir`, or `None` when the folder has none.
    pub fn read(dir: &Path) -> Result<Option<Self>> {
        let path = dir.join(MANIFEST);
        let text = match fs::read_to_string(&path) {
            Ok(text) => text,
            Err(e) if e.kind() == ErrorKind::NotFound => return Ok(None),
            Err(e) => return Err(SphError::output(&path, e)),
        };
        let names = text
            .lines()
            .filter(|l| !l.starts_with('#'))
            .filter(|l| plain(l))
            .map(String::from)
            .collect();
        Ok(Some(Self {
            dir: dir.to_path_buf(),
            names,
        }))
    }

    /// Starts an empty manifest in `dir` (replacing any earlier one).
    pub fn create(dir: &Path) -> Result<Self> {
        let manifest = Self {
            dir: dir.to_path_buf(),
            names: BTreeSet::new(),
        };
        manifest.rewrite()?;
        Ok(manifest)
    }

    /// Whether deltasph wrote `name` in this folder.
    pub fn lists(&self, name: &str) -> bool {
        self.names.contains(name)
    }

    /// Records `name` before it is written. Refuses a file that exists and is not
    /// listed: it is the user's, and nothing is written over it.
    pub fn claim(&mut self, name: &str) -> Result<()> {
        if self.names.contains(name) {
            return Ok(());
        }
        let path = self.dir.join(name);
        if !plain(name) || path.exists() {
            return Err(SphError::output(
                &path,
                "exists and was not written by deltasph (it is not in the folder's \
                 .deltasph-run); nothing was overwritten",
            ));
        }
        let manifest = self.dir.join(MANIFEST);
        let append = || -> std::io::Result<()> {
            let mut f = OpenOptions::new().append(true).open(&manifest)?;
            writeln!(f, "{name}")?;
            f.sync_data()
        };
        append().map_err(|e| SphError::output(&manifest, e))?;
        self.names.insert(name.to_string());
        Ok(())
    }

    /// Removes the listed file `name` (and its partial write) and drops it from the list.
    pub fn remove(&mut self, name: &str) -> Result<()> {
        if self.names.remove(name) {
            remove_if_present(&self.dir.join(name))?;
            remove_if_present(&self.dir.join(format!("{name}{PARTIAL}")))?;
            self.rewrite()?;
        }
        Ok(())
    }

    /// Removes every listed file (and partial writes of them), and empties the list.
    /// Anything else in the folder stays. Returns how many files were removed.
    pub fn remove_all(&mut self) -> Result<usize> {
        let mut removed = 0;
        for name in std::mem::take(&mut self.names) {
            removed += remove_if_present(&self.dir.join(&name))? as usize;
            remove_if_present(&self.dir.join(format!("{name}{PARTIAL}")))?;
        }
        self.rewrite()?;
        Ok(removed)
    }

    fn rewrite(&self) -> Result<()> {
        let mut text = format!("{HEADER}\n");
        for name in &self.names {
            text += name;
            text.push('\n');
        }
        super::atomic::write(&self.dir.join(MANIFEST), |tmp| fs::write(tmp, &text))
    }
}

/// Removes a regular file or link if there is one; never a folder.
fn remove_if_present(path: &Path) -> Result<bool> {
    match fs::symlink_metadata(path) {
        Ok(m) if !m.is_dir() => fs::remove_file(path)
            .map(|_| true)
            .map_err(|e| SphError::output(path, e)),
        Ok(_) => Ok(false),
        Err(e) if e.kind() == ErrorKind::NotFound => Ok(false),
        Err(e) => Err(SphError::output(path, e)),
    }
}

/// Whether a folder holds anything at all.
pub fn is_empty(dir: &Path) -> Result<bool> {
    Ok(fs::read_dir(dir)
        .map_err(|e| SphError::output(dir, e))?
        .next()
        .is_none())
}

/// Opens `path` for appending (the time series continued after a restart).
pub fn open_append(path: &Path) -> Result<File> {
    OpenOptions::new()
        .append(true)
        .open(path)
        .map_err(|e| SphError::output(path, e))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("manifest-{}-{name}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn removes_only_what_it_lists() {
        let dir = scratch("only");
        let mut m = Manifest::create(&dir).unwrap();
        m.claim("a.h5").unwrap();
        fs::write(dir.join("a.h5"), "x").unwrap();
        fs::write(dir.join("notes.txt"), "mine").unwrap();
        assert!(
            m.claim("notes.txt").is_err(),
            "a user's file is never claimed"
        );
        assert_eq!(m.remove_all().unwrap(), 1);
        assert!(!dir.join("a.h5").exists());
        assert_eq!(fs::read_to_string(dir.join("notes.txt")).unwrap(), "mine");
    }

    #[test]
    fn a_tampered_manifest_cannot_reach_outside_the_folder() {
        let dir = scratch("tamper");
        let outside = dir.join("outside.txt");
        fs::write(&outside, "keep").unwrap();
        let run = dir.join("run");
        fs::create_dir_all(run.join("sub")).unwrap();
        fs::write(
            run.join(MANIFEST),
            format!("{HEADER}\n../outside.txt\n{}\nsub\n", outside.display()),
        )
        .unwrap();
        let mut m = Manifest::read(&run).unwrap().unwrap();
        m.remove_all().unwrap();
        assert!(outside.exists() && run.join("sub").is_dir());
    }
}
