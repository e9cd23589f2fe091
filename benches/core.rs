//! Criterion benchmarks: kernel evaluation, neighbour-list build and one RK4 step of
//! the 2D dam break (δ-SPH, Wendland C2, h/Δx = 1.33) at about 10k and 100k particles,
//! and the writing of a snapshot of the 2D and 3D dam-break examples after their first
//! impact at each deflate level (sizes printed). Run with `cargo bench --bench core`.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use deltasph_suite::example_case;
use sph_core::domain::Domain;
use sph_core::neighbours::NeighbourList;
use sph_core::physics::kernel::{Kernel, QuinticSpline, WendlandC2};
use sph_core::Simulation;
use std::hint::black_box;

/// Δx giving about `n` fluid particles in the 2H × H column (H = 0.6 m).
fn spacing_for(n: f64) -> f64 {
    (0.72 / n).sqrt()
}

fn kernels(c: &mut Criterion) {
    let mut g = c.benchmark_group("kernel");
    let radii: Vec<f64> = (0..1000).map(|k| 2.0 * k as f64 / 1000.0).collect();
    g.throughput(Throughput::Elements(radii.len() as u64));
    let wc2 = WendlandC2::new(1.0, 2);
    g.bench_function("wendland_c2 W+gradient", |b| {
        b.iter(|| {
            radii
                .iter()
                .map(|&r| wc2.w(black_box(r)) + wc2.dw_over_r(black_box(r)))
                .sum::<f64>()
        })
    });
    let q = QuinticSpline::new(1.0, 2);
    g.bench_function("quintic W+gradient", |b| {
        b.iter(|| {
            radii
                .iter()
                .map(|&r| q.w(black_box(r)) + q.dw_over_r(black_box(r)))
                .sum::<f64>()
        })
    });
    g.finish();
}

fn neighbours(c: &mut Criterion) {
    let mut g = c.benchmark_group("neighbour_build");
    g.sample_size(10);
    for n in [10_000.0, 100_000.0] {
        let dx = spacing_for(n);
        let sim = Simulation::<2>::new(example_case(
            "dam_break_2d.toml",
            &[&format!("particles.spacing = {dx}")],
        ))
        .unwrap();
        let particles = sim.particles().clone();
        g.throughput(Throughput::Elements(particles.len() as u64));
        g.bench_with_input(BenchmarkId::from_parameter(n as u64), &particles, |b, p| {
            b.iter(|| {
                let mut p = p.clone();
                NeighbourList::build(&mut p, &Domain::open(), 2.66 * dx, 0.27 * dx)
            })
        });
    }
    g.finish();
}

fn rk4_step(c: &mut Criterion) {
    let mut g = c.benchmark_group("dam_break_2d_rk4_step");
    g.sample_size(10);
    for n in [10_000.0, 100_000.0] {
        let dx = spacing_for(n);
        let mut sim = Simulation::<2>::new(example_case(
            "dam_break_2d.toml",
            &[&format!("particles.spacing = {dx}")],
        ))
        .unwrap();
        g.throughput(Throughput::Elements(sim.n_fluid() as u64));
        g.bench_function(BenchmarkId::from_parameter(n as u64), |b| {
            b.iter(|| sim.step().unwrap())
        });
    }
    g.finish();
}

/// One snapshot of each dam-break example at t = 0.6 s (its flow past the first impact,
/// no longer a lattice) written at deflate levels 0 (none) to 9: the time here, the
/// file size on stderr.
fn snapshot_write(c: &mut Criterion) {
    let mut g = c.benchmark_group("snapshot_write");
    g.sample_size(10);
    let file = std::env::temp_dir().join(format!("deltasph-bench-{}.h5", std::process::id()));
    for example in ["dam_break_2d.toml", "dam_break_3d.toml"] {
        let case = example_case(example, &["time.end = 0.6"]);
        if case.dimension == 2 {
            bench_levels::<2>(&mut g, example, case, &file);
        } else {
            bench_levels::<3>(&mut g, example, case, &file);
        }
    }
    let _ = std::fs::remove_file(&file);
    g.finish();
}

fn bench_levels<const D: usize>(
    g: &mut criterion::BenchmarkGroup<criterion::measurement::WallTime>,
    example: &str,
    case: sph_core::case::Case,
    file: &std::path::Path,
) {
    use sph_core::io::output::{write_snapshot, Compression};
    let mut sim = Simulation::<D>::new(case).unwrap();
    while sim.time() < 0.6 {
        sim.step().unwrap();
    }
    let p = sim.particles();
    let stamp = (sim.time(), sim.counters().steps);
    for level in [0, 1, 2, 4, 6, 9] {
        let c = Compression::deflate(level);
        write_snapshot(file, p, &Default::default(), stamp, c).unwrap();
        let bytes = std::fs::metadata(file).unwrap().len();
        eprintln!(
            "{example} level {level}: {} particles, {bytes} bytes ({:.1} B/particle)",
            p.len(),
            bytes as f64 / p.len() as f64
        );
        g.throughput(Throughput::Elements(p.len() as u64));
        g.bench_function(format!("{example} level {level}"), |b| {
            b.iter(|| write_snapshot(file, p, &Default::default(), stamp, c).unwrap())
        });
    }
}

criterion_group!(benches, kernels, neighbours, rk4_step, snapshot_write);
criterion_main!(benches);
