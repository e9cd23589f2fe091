//! Atomic file writes: the content goes to `<name>.partial`, is synced to disk, and
//! is renamed over `<name>`; then the folder is synced so that the rename itself
//! survives a crash. A reader (or a restart after a kill) sees the old file or the
//! new one, never a part of either. A failed write removes its partial file, which
//! gives back the space it took (a full disk).

use crate::error::{Result, SphError};
use std::fs::{self, File};
use std::path::{Path, PathBuf};

/// The suffix of the temporary file a write goes to before it is renamed into place.
pub const PARTIAL: &str = ".partial";

/// The temporary sibling a write of `path` goes to.
pub fn partial(path: &Path) -> PathBuf {
    let mut name = path.file_name().unwrap_or_default().to_os_string();
    name.push(PARTIAL);
    path.with_file_name(name)
}

/// Writes `f(tmp)` to the partial file of `path`, syncs it and renames it into place.
pub fn write<E: ToString>(
    path: &Path,
    f: impl FnOnce(&Path) -> std::result::Result<(), E>,
) -> Result<()> {
    let tmp = partial(path);
    let written = f(&tmp)
        .map_err(|e| e.to_string())
        .and_then(|_| sync_file(&tmp).map_err(|e| e.to_string()));
    if let Err(e) = written {
        let _ = fs::remove_file(&tmp);
        return Err(SphError::output(path, e));
    }
    fs::rename(&tmp, path).map_err(|e| SphError::output(path, e))?;
    sync_folder(path)
}

/// Syncs a finished file's content to disk.
fn sync_file(path: &Path) -> std::io::Result<()> {
    File::open(path)?.sync_all()
}

/// Syncs the folder holding `path`, so that a rename into it is durable.
pub fn sync_folder(path: &Path) -> Result<()> {
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    File::open(dir)
        .and_then(|d| d.sync_all())
        .map_err(|e| SphError::output(dir, e))
}
