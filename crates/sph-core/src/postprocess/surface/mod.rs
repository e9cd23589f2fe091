//! The free surface of every snapshot of a finished run as a mesh ([`mesh`]), written
//! beside the run as VTK PolyData with a ParaView collection: `surface/surface.pvd`
//! and `surface/surface_NNNNNN.vtp`, numbered as the snapshots are.
//!
//! The tool writes only into a folder that is new, empty or holds its own files, and
//! replaces its own files only when asked; it never removes a file.

pub mod mesh;

pub use mesh::{ColourGrid, SurfaceMesh, MAX_NODES};

use super::frame::Frame;
use super::RunFolder;
use crate::error::{Result, SphError};
use crate::io::output::polydata::{self, Cells, PolyData};
use crate::physics::kernel::Smoothing;
use std::io::Read;
use std::path::{Path, PathBuf};

/// The collection file's name.
pub const COLLECTION: &str = "surface.pvd";
/// What the tool's `.vtp` files say of themselves in their header.
const WHAT: &str = "free-surface mesh";

/// What to extract and where to write it.
#[derive(Debug, Clone)]
pub struct Request {
    /// The grid spacing the colour field is sampled on \[m\]; the particle spacing when
    /// `None`.
    pub spacing: Option<f64>,
    /// The level of the fluid's kernel sum that is the surface, in (0, 1).
    pub level: f64,
    /// The folder to write into; `surface` in the run folder when `None`.
    pub out: Option<PathBuf>,
    /// Replace the tool's own earlier files there.
    pub overwrite: bool,
}

impl Default for Request {
    fn default() -> Self {
        Self {
            spacing: None,
            level: 0.5,
            out: None,
            overwrite: false,
        }
    }
}

/// What was written.
#[derive(Debug, Clone)]
pub struct Written {
    /// The collection file (open it in ParaView).
    pub collection: PathBuf,
    /// The mesh files, in time order.
    pub files: Vec<PathBuf>,
    /// The largest mesh's numbers of points and cells.
    pub largest: (usize, usize),
}

/// Extracts the free surface of every snapshot of `folder` and writes it.
pub fn write_surfaces(folder: &RunFolder, request: &Request) -> Result<Written> {
    match folder.case.dimension {
        2 => write_in::<2>(folder, request),
        _ => write_in::<3>(folder, request),
    }
}

fn write_in<const D: usize>(folder: &RunFolder, request: &Request) -> Result<Written> {
    let case = &folder.case;
    let step = request.spacing.unwrap_or(case.dx());
    if !(step.is_finite() && step > 0.0) {
        return Err(SphError::invalid("spacing", step, "a positive length [m]"));
    }
    if !(request.level > 0.0 && request.level < 1.0) {
        return Err(SphError::invalid(
            "level",
            request.level,
            "a level of the fluid's kernel sum between 0 and 1 (0.5: where its volume ends)",
        ));
    }
    let dir = request.out.clone().unwrap_or(folder.dir.join("surface"));
    prepare(&dir, request.overwrite)?;
    let kernel = case.particles.kernel.with_length(case.h(), D);
    let mut written = Written {
        collection: dir.join(COLLECTION),
        files: Vec::new(),
        largest: (0, 0),
    };
    let mut entries = Vec::new();
    for snapshot in &folder.snapshots {
        let frame = Frame::<D>::read(snapshot, case, kernel.support_radius())?;
        let mesh = frame_surface(&frame, kernel.as_ref(), step, request.level)?;
        let name = mesh_name(snapshot);
        let path = dir.join(&name);
        write_mesh(&path, &mesh, frame.time)?;
        let (n, m) = (mesh.points.len(), mesh.cells.len());
        written.largest = (written.largest.0.max(n), written.largest.1.max(m));
        entries.push((frame.time, name));
        written.files.push(path);
    }
    polydata::write_collection(&written.collection, &entries)?;
    Ok(written)
}

/// The surface of one snapshot: the `level` of the fluid's kernel sum (kernel
/// `kernel`), sampled on a grid of spacing `step`.
pub fn frame_surface<const D: usize>(
    frame: &Frame<D>,
    kernel: &dyn Smoothing,
    step: f64,
    level: f64,
) -> Result<SurfaceMesh<D>> {
    let reader = frame.reader(kernel);
    Ok(ColourGrid::sample(&reader, step)?.surface(level, &reader))
}

/// `surface_NNNNNN.vtp` for the snapshot `particles_NNNNNN.h5`.
fn mesh_name(snapshot: &Path) -> String {
    let stem = snapshot.file_stem().unwrap_or_default().to_string_lossy();
    format!("surface_{}.vtp", stem.trim_start_matches("particles_"))
}

/// Writes `mesh` as PolyData at `path` (2D points get z = 0).
fn write_mesh<const D: usize>(path: &Path, mesh: &SurfaceMesh<D>, time: f64) -> Result<()> {
    let points: Vec<[f64; 3]> = (mesh.points.iter())
        .map(|x| std::array::from_fn(|d| if d < D { x[d] } else { 0.0 }))
        .collect();
    PolyData {
        points: &points,
        cells: &mesh.cells,
        kind: if D == 2 {
            Cells::Lines
        } else {
            Cells::Polygons
        },
        point_data: &[("wall_fraction", &mesh.wall_fraction)],
        time,
    }
    .write(path, WHAT)
}

/// Makes `dir` ready: created when missing; refused when it holds a file the tool
/// did not write, or the tool's own files and `overwrite` is false.
fn prepare(dir: &Path, overwrite: bool) -> Result<()> {
    if !dir.exists() {
        return std::fs::create_dir_all(dir).map_err(|e| SphError::output(dir, e));
    }
    let entries = std::fs::read_dir(dir).map_err(|e| SphError::output(dir, e))?;
    let mut ours = false;
    for entry in entries {
        let path = entry.map_err(|e| SphError::output(dir, e))?.path();
        if !is_ours(&path) {
            return Err(SphError::output(
                dir,
                format!(
                    "holds {}, which the surface tool did not write; choose another \
                     folder (--out)",
                    path.file_name().unwrap_or_default().to_string_lossy()
                ),
            ));
        }
        ours = true;
    }
    if ours && !overwrite {
        return Err(SphError::output(
            dir,
            "holds the surfaces of an earlier extraction; pass --force (overwrite=True in \
             Python) to replace them",
        ));
    }
    Ok(())
}

/// Whether `path` is a file this tool wrote: the collection or a mesh file, named as
/// the tool names them and opening with its header (of any deltasph version).
fn is_ours(path: &Path) -> bool {
    let name = path.file_name().unwrap_or_default().to_string_lossy();
    let named = name == COLLECTION || (name.starts_with("surface_") && name.ends_with(".vtp"));
    let marker = b"<?xml version=\"1.0\"?>\n<!-- deltasph ";
    let mut head = [0u8; 36];
    let read = std::fs::File::open(path).and_then(|mut f| f.read_exact(&mut head));
    named && read.is_ok() && head.starts_with(marker)
}
