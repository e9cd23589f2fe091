//! The measure tool reads a finished run's snapshots as the run read itself: pressure
//! and velocity at points, the elevation on vertical lines and the flow through
//! sections equal the in-run probes, gauges and sections at the snapshot times (to round-off: the sums run in another order), dry
//! points read as dry in both, and the interpolated density and pressure obey the
//! linear equation of state as the particles do (one set of Shepard weights for all
//! fields).

use sph_core::case::SectionConfig;
use sph_core::diagnostics::sections::Section;
use sph_core::io::output::{with_extras, Output};
use sph_core::physics::eos::LinearEos;
use sph_core::postprocess::measure::{measure, Quantity, Request, Series};
use sph_core::postprocess::RunFolder;
use sph_core::{Case, Simulation, Vector};

/// A column of water collapsing in a tank (a gauge's line spans the tank's height).
fn case_text(dimension: usize) -> String {
    let (dx, lo, block, tank, g) = if dimension == 2 {
        (
            0.01,
            "[0.0, 0.0]",
            "[0.2, 0.3]",
            "[0.8, 0.5]",
            "[0.0, -9.81]",
        )
    } else {
        let (lo, block, tank) = ("[0.0, 0.0, 0.0]", "[0.2, 0.2, 0.3]", "[0.8, 0.2, 0.5]");
        (0.025, lo, block, tank, "[0.0, 0.0, -9.81]")
    };
    format!(
        "dimension = {dimension}\n[particles]\nspacing = {dx}\n[fluid]\ndensity = 1000.0\n\
         gravity = {g}\n[[fluid_block]]\nlo = {lo}\nhi = {block}\n\
         [[tank]]\nlo = {lo}\nhi = {tank}\n[time]\nend = 1.0\n"
    )
}

/// What the run itself reads at one snapshot.
struct InRun<const D: usize> {
    pressure: Vec<Option<f64>>,
    velocity: Vec<Option<Vector<D>>>,
    elevation: Vec<f64>,
    flow: Vec<[f64; 2]>,
}

/// Runs the case for `snapshots` snapshots `steps` steps apart into `dir`, and returns
/// what the run read at `points` and `lines` at each.
fn run<const D: usize>(
    dir: &std::path::Path,
    request: &Request,
    (snapshots, steps): (usize, usize),
) -> (Vec<InRun<D>>, LinearEos) {
    let (points, lines) = (&request.points, &request.elevations);
    let text = case_text(D);
    let mut sim = Simulation::<D>::new(Case::from_toml_str(&text).unwrap()).unwrap();
    let mut output = Output::create(dir, false).unwrap();
    output.write_text("case.toml", &text).unwrap();
    let at: Vec<Vector<D>> = points
        .iter()
        .map(|x| Vector::from_column_slice(x))
        .collect();
    let mut seen = Vec::new();
    for s in 0..snapshots {
        for _ in 0..if s == 0 { 0 } else { steps } {
            sim.step().unwrap();
        }
        sim.sync_pressure();
        let step = sim.counters().steps;
        with_extras(&sim, |e| {
            output.snapshot(sim.particles(), e, sim.time(), step)
        })
        .unwrap();
        seen.push(InRun {
            pressure: sim.probe_pressures(&at),
            velocity: sim.probe_velocities(&at),
            elevation: sim.wave_elevations(lines).unwrap(),
            flow: (request.sections.iter())
                .map(|corners| {
                    let config = SectionConfig {
                        name: "s".into(),
                        corners: corners.clone(),
                    };
                    let section = Section::<D>::new(&config, sim.case().dx());
                    section.flow(&sim.flow_densities(&section.points, &section.normal))
                })
                .collect(),
        });
    }
    (seen, sim.physics().eos)
}

fn series<'a>(all: &'a [Series], name: &str) -> &'a Series {
    all.iter().find(|s| s.name == name).unwrap()
}

/// `a` equals `b` to round-off (relative 1e-11 of `scale`), NaN matching `None`.
fn same(a: f64, b: Option<f64>, scale: f64, what: &str) {
    match b {
        None => assert!(a.is_nan(), "{what}: measured {a}, the run found no fluid"),
        Some(b) => assert!(
            (a - b).abs() <= 1e-11 * scale,
            "{what}: measured {a}, the run {b}"
        ),
    }
}

fn measure_reads_what_the_run_read<const D: usize>(
    points: Vec<Vec<f64>>,
    lines: Vec<Vec<f64>>,
    sections: Vec<Vec<Vec<f64>>>,
) {
    let dir = std::env::temp_dir().join(format!("measure-{D}d-{}", std::process::id()));
    let request = Request {
        points,
        quantities: Quantity::ALL.to_vec(),
        elevations: lines,
        sections,
    };
    let (seen, eos) = run::<D>(&dir, &request, (3, 40));
    let folder = RunFolder::open(&dir).unwrap();
    let m = measure(&folder, &request).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(m.steps, vec![0, 40, 80]);
    let (p, u, rho) = (
        series(&m.series, "pressure"),
        series(&m.series, "velocity"),
        series(&m.series, "density"),
    );
    let elevation = series(&m.series, "elevation");
    let flows = [
        series(&m.series, "volume_flow"),
        series(&m.series, "mass_flow"),
    ];
    let n = request.points.len();
    let mut dry = 0;
    for (s, run) in seen.iter().enumerate() {
        for k in 0..n {
            let what = format!("snapshot {s}, point {k}");
            same(
                p.values[s * n + k],
                run.pressure[k],
                3000.0,
                &format!("{what} pressure"),
            );
            for d in 0..D {
                let along = run.velocity[k].map(|v| v[d]);
                same(
                    u.values[(s * n + k) * D + d],
                    along,
                    1.0,
                    &format!("{what} velocity"),
                );
            }
            dry += usize::from(run.pressure[k].is_none());
            let (pk, rk) = (p.values[s * n + k], rho.values[s * n + k]);
            assert_eq!(pk.is_nan(), rk.is_nan(), "{what}: dry for one field only");
            if !pk.is_nan() {
                let from_rho = eos.pressure(rk);
                assert!(
                    (pk - from_rho).abs() < 1e-9 * 3000.0,
                    "{what}: p {pk}, p(ρ) {from_rho}"
                );
            }
        }
        for (k, &e) in run.elevation.iter().enumerate() {
            let measured = elevation.values[s * run.elevation.len() + k];
            same(
                measured,
                Some(e),
                1.0,
                &format!("snapshot {s}, line {k} elevation"),
            );
        }
        for (k, flow) in run.flow.iter().enumerate() {
            for (c, (series, scale)) in flows.iter().zip([1.0, 1000.0]).enumerate() {
                let measured = series.values[s * run.flow.len() + k];
                same(
                    measured,
                    Some(flow[c]),
                    scale,
                    &format!("snapshot {s}, section {k}"),
                );
            }
            let moving = s > 0 && flow[0].abs() > 1e-3;
            assert!(
                s == 0 || moving,
                "snapshot {s}: the foot carries flow ({flow:?})"
            );
        }
    }
    assert!(
        dry > 0 && dry < n * seen.len(),
        "{dry} dry readings: the set must hold both"
    );
}

/// Points in the column, in the collapsing front, above the water (dry) and inside the
/// floor; lines through the column and ahead of it.
#[test]
fn the_measure_tool_reads_2d_snapshots_as_the_run_read_itself() {
    let points = [
        [0.05, 0.05],
        [0.15, 0.2],
        [0.25, 0.02],
        [0.1, 0.45],
        [0.3, -0.02],
    ];
    let lines = vec![vec![0.1], vec![0.3]];
    // across the collapsing column's foot, from inside the floor to the air
    let sections = vec![vec![vec![0.22, -0.02], vec![0.22, 0.4]]];
    measure_reads_what_the_run_read::<2>(points.map(|p| p.to_vec()).to_vec(), lines, sections);
}

#[test]
fn the_measure_tool_reads_3d_snapshots_as_the_run_read_itself() {
    let points = [
        [0.05, 0.1, 0.05],
        [0.15, 0.05, 0.2],
        [0.25, 0.1, 0.02],
        [0.1, 0.1, 0.45],
    ];
    let lines = vec![vec![0.1, 0.1], vec![0.3, 0.05]];
    let foot = [
        [0.22, -0.02, -0.02],
        [0.22, 0.22, -0.02],
        [0.22, -0.02, 0.4],
    ];
    let sections = vec![foot.map(|c| c.to_vec()).to_vec()];
    measure_reads_what_the_run_read::<3>(points.map(|p| p.to_vec()).to_vec(), lines, sections);
}
