//! Free-surface meshes read from a run's snapshots (`sph-cli surface`): a hydrostatic
//! tank's surface is flat at its depth, in 2D and 3D. The lattice cases (a block, a
//! disc and a ball of fluid) are the unit tests of `sph_core::postprocess::surface::mesh`;
//! the files, their safety rules and ParaView are tested from the command line
//! (`crates/sph-cli/tests/end_to_end/surface.rs`) and Python (`tests/python/test_surface.py`).

use deltasph_suite::example_case;
use sph_core::io::output::{with_extras, Output};
use sph_core::postprocess::frame::Frame;
use sph_core::postprocess::surface::frame_surface;
use sph_core::postprocess::RunFolder;
use sph_core::Simulation;

/// Water at rest in a tank, `depth` deep at spacing `dx`, run to `end` into `dir` with
/// a snapshot at the start and at the end: the 2D hydrostatic example (1 m deep), or
/// the 3D dam break's tank with its water spread out at rest (0.3 m deep, along z).
fn hydrostatic_run<const D: usize>(dir: &std::path::Path, dx: f64, end: f64) -> RunFolder {
    let spacing = format!("particles.spacing = {dx}");
    let time = format!("time.end = {end}");
    let case = if D == 2 {
        example_case("hydrostatic_2d.toml", &[&spacing, &time])
    } else {
        let spread = [
            "fluid_block.0.hi = [1.6, 0.3, 0.3]",
            "fluid_block.0.hydrostatic = true",
        ];
        example_case(
            "dam_break_3d.toml",
            &[&spacing, &time, spread[0], spread[1]],
        )
    };
    let text = toml::to_string(&case).unwrap();
    let mut sim = Simulation::<D>::new(case).unwrap();
    let mut output = Output::create(dir, false).unwrap();
    output.write_text("case.toml", &text).unwrap();
    for at_end in [false, true] {
        while at_end && sim.time() < end * (1.0 - 1e-12) {
            sim.step().unwrap();
        }
        sim.sync_pressure();
        let step = sim.counters().steps;
        with_extras(&sim, |e| {
            output.snapshot(sim.particles(), e, sim.time(), step)
        })
        .unwrap();
    }
    RunFolder::open(dir).unwrap()
}

/// The heights of the surface's points that no wall reaches (Γ_w = 0) more than
/// `margin` from the tank's side walls, in the snapshot at `index`.
fn free_surface_heights<const D: usize>(folder: &RunFolder, index: usize, margin: f64) -> Vec<f64> {
    let case = &folder.case;
    let kernel = case.particles.kernel.with_length(case.h(), D);
    let frame = Frame::<D>::read(&folder.snapshots[index], case, kernel.support_radius()).unwrap();
    let mesh = frame_surface(&frame, kernel.as_ref(), case.dx(), 0.5).unwrap();
    let tank = &case.tank[0];
    (mesh.points.iter().zip(&mesh.wall_fraction))
        .filter(|(x, &w)| {
            w == 0.0 && (0..D - 1).all(|d| x[d] > tank.lo[d] + margin && x[d] < tank.hi[d] - margin)
        })
        .map(|(x, _)| x[D - 1])
        .collect()
}

/// Water `depth` deep at rest at spacing `dx`, run to `end` into `run`: the largest
/// distance of the free surface from the depth, relative to Δx, at the start and at
/// the end (points more than `margin` from the side walls).
fn flatness<const D: usize>(
    run: &std::path::Path,
    dx: f64,
    end: f64,
    depth: f64,
    margin: f64,
) -> [f64; 2] {
    let folder = hydrostatic_run::<D>(run, dx, end);
    [0, 1].map(|k| {
        let h = free_surface_heights::<D>(&folder, k, margin);
        assert!(
            h.len() > 10,
            "{D}D snapshot {k}: {} surface points",
            h.len()
        );
        let worst = h.iter().map(|y| (y - depth).abs()).fold(0.0, f64::max);
        println!(
            "{D}D snapshot {k}: {} points, worst {:.3} Δx off the depth",
            h.len(),
            worst / dx
        );
        worst / dx
    })
}

/// Measured (2D: H/Δx = 20, h/Δx = 2; 3D: H/Δx = 12, h/Δx = 1.33): the surface within
/// 0.002 Δx (2D) and 0.033 Δx (3D) of the depth at the start (the lattice's top row is
/// Δx/2 below it; the smaller kernel sums the lattice less evenly), and within
/// 0.021 Δx and 0.042 Δx after the water has stood for t·sqrt(g/H) = 6.3 and 2.9.
#[test]
fn a_hydrostatic_tanks_surface_is_flat_at_its_depth() {
    let dir = std::env::temp_dir().join(format!("deltasph_surface_{}", std::process::id()));
    let errors = [
        flatness::<2>(&dir.join("2d"), 0.05, 2.0, 1.0, 0.2),
        flatness::<3>(&dir.join("3d"), 0.025, 0.5, 0.3, 0.1),
    ];
    for (dim, [start, end]) in [2, 3].into_iter().zip(errors) {
        assert!(
            start < 0.1 && end < 0.1,
            "{dim}D: {start} Δx, then {end} Δx"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
