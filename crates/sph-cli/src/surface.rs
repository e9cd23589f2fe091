//! `sph-cli surface`: the free surface of every snapshot of a finished run as meshes
//! ([`sph_core::postprocess::surface`]).

use anyhow::Result;
use clap::Args;
use sph_core::postprocess::surface::{write_surfaces, Request};
use sph_core::postprocess::RunFolder;
use std::path::PathBuf;

/// Which run, and how to contour it.
#[derive(Args)]
pub(crate) struct SurfaceArgs {
    /// The run folder (what `run` wrote: case.toml, particles.xmf and the snapshots).
    run: PathBuf,
    /// The spacing of the grid the fluid's kernel sum is sampled on [m] (default: the
    /// particle spacing; half of it smooths curved surfaces a little more, at 4× (2D)
    /// or 8× (3D) the work).
    #[arg(long, value_name = "METRES")]
    spacing: Option<f64>,
    /// The level of the kernel sum that is the surface: 0.5 is where the fluid's
    /// volume ends.
    #[arg(long, default_value_t = 0.5)]
    level: f64,
    /// The folder to write into (default: `surface` in the run folder).
    #[arg(long, short)]
    out: Option<PathBuf>,
    /// Replace the meshes of an earlier `surface` in that folder.
    #[arg(long)]
    force: bool,
}

pub(crate) fn run(args: SurfaceArgs) -> Result<()> {
    let folder = RunFolder::open(&args.run)?;
    let request = Request {
        spacing: args.spacing,
        level: args.level,
        out: args.out,
        overwrite: args.force,
    };
    let written = write_surfaces(&folder, &request)?;
    eprintln!(
        "wrote {} meshes (the largest: {} points, {} cells); open {} in ParaView \
         (Threshold on wall_fraction below 0.1 keeps the free surface alone)",
        written.files.len(),
        written.largest.0,
        written.largest.1,
        written.collection.display()
    );
    Ok(())
}
