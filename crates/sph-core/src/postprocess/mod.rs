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
pub mod surface;

use crate::case::Case;
use crate::error::{Result, SphError};
use std::path::{Path, PathBuf};

/// A run folder's case and snapshots.
#[derive(Debug, Clone)]
pub struct RunFolder {
    pub dir: PathBuf,
    pub case: Case,
    /// The snapshot files, in index (time) order.
    pub snapshots: Vec<PathBuf>,
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
            .map(|file| dir.join(file))
            .collect();
        Ok(Self {
            dir: dir.to_path_buf(),
            case,
            snapshots,
        })
    }
}

/// The snapshot files of an XDMF index as deltasph writes it: the names of its
/// `<Grid Name="FILE" GridType="Uniform">` lines, in time order.
fn listed_snapshots(index: &str) -> Vec<String> {
    (index.lines())
        .filter(|line| line.contains("GridType=\"Uniform\""))
        .filter_map(|line| {
            let start = line.find("Name=\"")? + "Name=\"".len();
            let len = line[start..].find('"')?;
            Some(line[start..start + len].to_string())
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_index_lists_files_in_order() {
        let index = "<Xdmf>\n <Grid Name=\"particles\" GridType=\"Collection\">\n   \
                     <Grid Name=\"particles_000000.h5\" GridType=\"Uniform\">\n    \
                     <Time Value=\"0.000000000e0\"/>\n   </Grid>\n   \
                     <Grid Name=\"particles_000001.h5\" GridType=\"Uniform\">\n    \
                     <Time Value=\"2.500000000e-2\"/>\n   </Grid>\n";
        assert_eq!(
            listed_snapshots(index),
            vec!["particles_000000.h5", "particles_000001.h5"]
        );
    }
}
