//! Answers read from a finished run folder: fields interpolated at points and wave
//! elevations from every snapshot ([`measure`]), with the rules of the in-run probes
//! and gauges ([`crate::diagnostics`]) applied to each snapshot ([`frame`]).
//!
//! A run folder is what a run writes: `case.toml` (the case as run), the snapshots
//! `particles_NNNNNN.h5` and their XDMF index `particles.xmf`, which lists them in time
//! order (a continued run's included).

pub mod frame;
pub mod measure;
pub mod points;

use crate::case::Case;
use crate::error::{Result, SphError};
use std::path::{Path, PathBuf};

/// A run folder's case and snapshots.
#[derive(Debug, Clone)]
pub struct RunFolder {
    pub dir: PathBuf,
    pub case: Case,
    /// The snapshot files with their times, in index order.
    pub snapshots: Vec<(PathBuf, f64)>,
}

impl RunFolder {
    /// Opens the run folder `dir`: its case and the snapshots its index lists.
    pub fn open(dir: &Path) -> Result<Self> {
        let index = dir.join("particles.xmf");
        let text = std::fs::read_to_string(&index).map_err(|e| {
            SphError::output(
                dir,
                format!(
                    "not a run folder: its index particles.xmf cannot be read ({e}); \
                     expected the folder that sph-cli run or Simulation.run(out=...) wrote"
                ),
            )
        })?;
        let case = Case::from_file(&dir.join("case.toml"))?;
        let snapshots = listed_snapshots(&text)
            .into_iter()
            .map(|(file, time)| (dir.join(file), time))
            .collect();
        Ok(Self {
            dir: dir.to_path_buf(),
            case,
            snapshots,
        })
    }
}

/// The snapshot files and times of an XDMF index as deltasph writes it: each
/// `<Grid Name="FILE" GridType="Uniform">` line followed by its `<Time Value="T"/>`.
fn listed_snapshots(index: &str) -> Vec<(String, f64)> {
    let attribute = |line: &str, key: &str| -> Option<String> {
        let start = line.find(&format!("{key}=\""))? + key.len() + 2;
        let len = line[start..].find('"')?;
        Some(line[start..start + len].to_string())
    };
    let mut lines = index.lines();
    let mut out = Vec::new();
    while let Some(line) = lines.next() {
        if !line.contains("GridType=\"Uniform\"") {
            continue;
        }
        let file = attribute(line, "Name");
        let time = lines
            .next()
            .and_then(|l| attribute(l, "Value"))
            .and_then(|t| t.parse().ok());
        if let (Some(file), Some(time)) = (file, time) {
            out.push((file, time));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_index_lists_files_and_times_in_order() {
        let index = "<Xdmf>\n <Grid Name=\"particles\" GridType=\"Collection\">\n   \
                     <Grid Name=\"particles_000000.h5\" GridType=\"Uniform\">\n    \
                     <Time Value=\"0.000000000e0\"/>\n   </Grid>\n   \
                     <Grid Name=\"particles_000001.h5\" GridType=\"Uniform\">\n    \
                     <Time Value=\"2.500000000e-2\"/>\n   </Grid>\n";
        assert_eq!(
            listed_snapshots(index),
            vec![
                ("particles_000000.h5".to_string(), 0.0),
                ("particles_000001.h5".to_string(), 0.025)
            ]
        );
    }
}
