//! Compressed HDF5 datasets: the shuffle filter (each value's bytes regrouped by
//! significance, so that the slowly varying exponent and high mantissa bytes of
//! neighbouring particles lie side by side) followed by deflate (zlib) at a chosen
//! level, in chunks of [`CHUNK_BYTES`]. Any HDF5 reader built with zlib (ParaView,
//! h5py, VisIt, `h5dump`) reads them without being told.

use hdf5::{Dataset, H5Type};

/// The deflate level a run uses unless `output.compression` says otherwise, chosen by
/// measurement (docs/running.md, "Compressed output"; zlib-ng, the zlib the static
/// HDF5 build links): on the dam breaks' snapshots past the first impact level 2 keeps
/// 59% (2D) and 33% (3D) of the bytes; level 1 (zlib-ng's quick mode) keeps 71% and 38%,
/// and levels 4–9 gain at most 4% more while writing 1.2–7× slower.
pub const DEFAULT_LEVEL: u8 = 2;

/// The largest chunk \[bytes\]: big enough that deflate sees long runs of similar values,
/// small enough that a reader of part of a file decompresses little beyond it.
pub const CHUNK_BYTES: usize = 1 << 20;

/// How HDF5 datasets are stored: the deflate level 1–9, or 0 for none.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Compression {
    level: u8,
}

impl Default for Compression {
    fn default() -> Self {
        Self::deflate(DEFAULT_LEVEL)
    }
}

impl Compression {
    /// No compression: contiguous datasets, as written before compression existed.
    pub const NONE: Self = Self { level: 0 };

    /// Shuffle and deflate at `level` (0 none, 1 fastest … 9 smallest; above 9 is 9).
    pub fn deflate(level: u8) -> Self {
        Self {
            level: level.min(9),
        }
    }

    /// Creates the dataset `name` of `rows` × `columns` values (`columns` 1: a vector
    /// of `rows`), compressed when this asks for it, the HDF5 library has deflate and
    /// there is something to compress.
    pub fn create<T: H5Type>(
        self,
        file: &hdf5::File,
        name: &str,
        rows: usize,
        columns: usize,
    ) -> hdf5::Result<Dataset> {
        let shape = if columns == 1 {
            vec![rows]
        } else {
            vec![rows, columns]
        };
        let mut builder = file.new_dataset::<T>();
        if self.level > 0 && rows > 0 && hdf5::filters::deflate_available() {
            let row_bytes = columns * std::mem::size_of::<T>();
            let mut chunk = shape.clone();
            chunk[0] = (CHUNK_BYTES / row_bytes.max(1)).clamp(1, rows);
            builder = builder.chunk(chunk).shuffle().deflate(self.level);
        }
        builder.shape(shape).create(name)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A file with one dataset written at `c`, read back.
    fn round_trip(c: Compression, values: &[f64], columns: usize) -> (Vec<f64>, u64, bool) {
        let path = std::env::temp_dir().join(format!(
            "deltasph-compression-{}-{}-{}-{columns}.h5",
            std::process::id(),
            c.level,
            values.len()
        ));
        {
            let file = hdf5::File::create(&path).unwrap();
            let ds = c.create::<f64>(&file, "v", values.len() / columns, columns);
            ds.unwrap().write_raw(values).unwrap();
        }
        let file = hdf5::File::open(&path).unwrap();
        let ds = file.dataset("v").unwrap();
        let filtered = !ds.filters().is_empty();
        let back = ds.read_raw::<f64>().unwrap();
        let size = std::fs::metadata(&path).unwrap().len();
        std::fs::remove_file(&path).unwrap();
        (back, size, filtered)
    }

    #[test]
    fn compressed_datasets_read_back_bit_for_bit_and_are_smaller() {
        assert!(
            hdf5::filters::deflate_available(),
            "the HDF5 build lacks zlib"
        );
        // a particle lattice's coordinates: what snapshots hold most of
        let lattice: Vec<f64> = (0..300_000)
            .map(|k| (k / 3) as f64 * 0.01 + (k % 3) as f64 * 1e-7)
            .collect();
        let (plain, plain_size, plain_filtered) = round_trip(Compression::NONE, &lattice, 3);
        let (packed, packed_size, filtered) = round_trip(Compression::default(), &lattice, 3);
        assert!(!plain_filtered && filtered);
        assert_eq!(plain, lattice);
        assert_eq!(packed, lattice);
        // 2.4 MB of doubles; shuffle + deflate keep under half of it
        assert!(
            (packed_size as f64) < 0.5 * plain_size as f64,
            "{packed_size} against {plain_size} bytes"
        );
        // more than one chunk, and a vector
        let (v, _, _) = round_trip(Compression::deflate(9), &lattice[..200_001], 1);
        assert_eq!(v, &lattice[..200_001]);
    }

    #[test]
    fn empty_datasets_are_written_without_filters() {
        let (v, _, filtered) = round_trip(Compression::default(), &[], 3);
        assert!(v.is_empty() && !filtered);
    }
}
