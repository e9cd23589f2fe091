//! Reading a snapshot back: its fields by name, vectors cut to the case's dimension
//! (the file pads them to three components for ParaView). The layout is the one
//! [`super::snapshot`] writes.

use crate::error::{Result, SphError};
use std::path::Path;

/// One field of a snapshot, a row per particle in the file's order.
#[derive(Debug, Clone, PartialEq)]
pub enum Field {
    /// Floating-point values, `columns` per particle (1, or the dimension).
    Float { values: Vec<f64>, columns: usize },
    /// Flags and kinds (0 fluid, 1 wall; 0/1 free surface).
    Byte(Vec<u8>),
    /// Particle ids.
    Id(Vec<u32>),
}

/// A snapshot read back.
#[derive(Debug, Clone)]
pub struct Snapshot {
    pub time: f64,
    pub step: u64,
    pub dimension: usize,
    /// The fields present, in a fixed order (`position` first).
    pub fields: Vec<(&'static str, Field)>,
}

impl Snapshot {
    /// The field called `name`, if the file holds it.
    pub fn field(&self, name: &str) -> Option<&Field> {
        self.fields.iter().find(|f| f.0 == name).map(|f| &f.1)
    }
}

const VECTORS: [&str; 4] = ["position", "velocity", "shifting_velocity", "normal"];
const SCALARS: [&str; 4] = ["density", "pressure", "mass", "lambda"];
const BYTES: [&str; 2] = ["kind", "free_surface"];

/// Reads the snapshot `path` (a file of a run folder or of `write_indexed_snapshot`).
pub fn read_snapshot(path: &Path) -> Result<Snapshot> {
    read(path).map_err(|e| SphError::output(path, format!("unreadable snapshot ({e})")))
}

fn read(path: &Path) -> hdf5::Result<Snapshot> {
    let file = hdf5::File::open(path)?;
    let dimension = file.attr("dimension")?.read_scalar::<u32>()? as usize;
    let mut fields = Vec::new();
    for name in VECTORS {
        if let Ok(data) = file.dataset(name) {
            let padded: Vec<f64> = data.read_raw()?;
            let values = padded
                .chunks_exact(3)
                .flat_map(|row| row[..dimension].to_vec())
                .collect();
            fields.push((
                name,
                Field::Float {
                    values,
                    columns: dimension,
                },
            ));
        }
    }
    for name in SCALARS {
        if let Ok(data) = file.dataset(name) {
            fields.push((
                name,
                Field::Float {
                    values: data.read_raw()?,
                    columns: 1,
                },
            ));
        }
    }
    for name in BYTES {
        if let Ok(data) = file.dataset(name) {
            fields.push((name, Field::Byte(data.read_raw()?)));
        }
    }
    fields.push(("id", Field::Id(file.dataset("id")?.read_raw()?)));
    Ok(Snapshot {
        time: file.attr("time")?.read_scalar()?,
        step: file.attr("step")?.read_scalar()?,
        dimension,
        fields,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Case, Simulation};

    #[test]
    fn a_snapshot_reads_back_as_written() {
        let case = Case::from_toml_str(
            "dimension = 2\n[particles]\nspacing = 0.02\n[fluid]\ndensity = 1000.0\n\
             gravity = [0.0, -9.81]\n[[fluid_block]]\nlo = [0.0, 0.0]\nhi = [0.2, 0.1]\n\
             [[tank]]\nlo = [0.0, 0.0]\nhi = [0.3, 0.2]\n[time]\nend = 0.01\n",
        )
        .unwrap();
        let mut sim = Simulation::<2>::new(case).unwrap();
        sim.step().unwrap();
        sim.sync_pressure();
        let dir = std::env::temp_dir().join(format!("reading-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("s.h5");
        let p = sim.particles();
        super::super::write_indexed_snapshot(&path, p, &Default::default(), sim.time(), 1, true)
            .unwrap();
        let snapshot = read_snapshot(&path).unwrap();
        std::fs::remove_dir_all(&dir).unwrap();
        assert_eq!(
            (snapshot.time, snapshot.step, snapshot.dimension),
            (sim.time(), 1, 2)
        );
        let field = |name: &str| snapshot.field(name).unwrap();
        let xy: Vec<f64> = p.x.iter().flat_map(|x| [x[0], x[1]]).collect();
        assert_eq!(
            field("position"),
            &Field::Float {
                values: xy,
                columns: 2
            }
        );
        let pressure = Field::Float {
            values: p.p.clone(),
            columns: 1,
        };
        assert_eq!(field("pressure"), &pressure);
        assert_eq!(field("id"), &Field::Id(p.id.clone()));
        let kinds: Vec<u8> = p.kind.iter().map(|&k| k as u8).collect();
        assert_eq!(field("kind"), &Field::Byte(kinds));
        assert!(
            snapshot.fields.iter().all(|f| f.0 != "normal"),
            "no field is made up"
        );
    }
}
