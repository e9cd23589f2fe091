//! Criterion benchmarks: kernel evaluation, neighbour-list build and one RK4 step of
//! the 2D dam break (δ-SPH, Wendland C2, h/Δx = 1.33) at about 10k and 100k particles.
//! Run with `cargo bench --bench core`.

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

criterion_group!(benches, kernels, neighbours, rk4_step);
criterion_main!(benches);
