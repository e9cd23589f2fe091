//! A floating body in regular waves: the NTNU ship section (Sundsdal, Greco, Hanssen &
//! Lugni 2025) free in sway, heave and roll in a flap-made beam sea, against the
//! experiment's response amplitudes (docs/validation/floating_bodies.md §4c; the
//! full-size record is `examples/validation/floating_section_waves.py`).

use crate::waves::{harmonics, series_columns, split, wave};
use deltasph_suite::{example_case, read_csv, refdata};
use nalgebra::Complex;
use sph_core::waves::theory::wavenumber;
use std::f64::consts::PI;

/// `examples/validation/floating_section_waves.toml` at draft/Δx = 5 in the experiment's
/// longest waves (T = 1.516 s, H = 0.04 m, kd = 1.84), 6 periods after the waves reach
/// the section and come back to the gauges; over the last 4, the first harmonics of
/// heave and roll over the incident amplitude (from gauges r1-r3 in front of the
/// section, split into incident and reflected waves), against the experiment's run
/// 3012 (`docs/validation/data/floating_section_experiment.csv`). Measured (§4c): heave
/// +9% here, +4% over the last 4 of 8 periods and +6.6% over 6 of 12, +0.9% at
/// draft/Δx = 10; roll +10% here (+14% before the flap's absorption followed its slope
/// over T/20, docs/theory.md §14; the longer runs are from before), +13% and +4%, and
/// −18% at draft/Δx = 10 (the roll,
/// lightly damped near its resonance at 1.26 s, still beats with its own period over
/// these windows). The bounds: 15% on heave, 25% on roll; the incident wave within 10%
/// of the paddle's target (+1%). Sway, which the springs let drift at its 7.5 s
/// period, is left to the full-size study.
#[test]
fn the_ntnu_section_rides_long_waves_as_measured() {
    let (period, height, depth) = (1.516, 0.04, 1.0);
    let omega = 2.0 * PI / period;
    let k = wavenumber(omega, depth, 9.81);
    let group = 0.5 * omega / k * (1.0 + 2.0 * k * depth / (2.0 * k * depth).sinh());
    // to the section at 3 m and back to the first gauge at 1.3 m, then 6 periods
    let end = (6.0 - 1.3) / group + 6.0 * period;
    let case = example_case(
        "validation/floating_section_waves.toml",
        &[
            "particles.spacing = 0.04",
            // the flap's frame the kernel support (0.2 m) thick
            "wall.0.lo = [-0.2, -0.1]",
            &format!("wall.1.prescribed.waves.period = {period}"),
            &format!("wall.1.prescribed.waves.height = {height}"),
            "time.output_interval = 0.0",
            &format!("time.end = {end}"),
        ],
    );
    let gauges: Vec<f64> = (case.diagnostics.gauges.iter())
        .filter(|g| g.name.starts_with('r'))
        .map(|g| g.position[0])
        .collect();
    let (t, names, columns) = series_columns(case, end - 4.0 * period, &|h| {
        h.ends_with("_elevation") || h == "section_y" || h == "section_angle"
    });
    let first = |h: &str| -> Complex<f64> {
        let c = names.iter().position(|n| n == h).expect(h);
        harmonics(&t, &columns[c], omega)[0]
    };
    let at_gauges: Vec<Complex<f64>> = ["r1", "r2", "r3"]
        .iter()
        .map(|g| first(&format!("{g}_elevation")))
        .collect();
    let (incident, _) = split(&at_gauges, &wave(k, &gauges), &wave(-k, &gauges));
    let zeta = incident.norm();
    let heave = first("section_y").norm() / zeta;
    let roll = first("section_angle").norm() / (k * zeta);
    let (header, rows) = read_csv(&refdata("floating_section_experiment.csv"));
    let column = |name: &str| header.iter().position(|h| h == name).expect(name);
    let measured = (rows.iter())
        .find(|r| r[column("test")] == 3012.0)
        .expect("run 3012");
    let (heave_exp, roll_exp) = (measured[column("heave")], measured[column("roll")]);
    println!(
        "NTNU section in waves, T = {period} s, draft/Δx = 5: incident amplitude {zeta:.5} m; \
         heave {heave:.3} (experiment {heave_exp:.3}), roll/(k ζ) {roll:.3} (experiment {roll_exp:.3})"
    );
    assert!((zeta / (0.5 * height) - 1.0).abs() < 0.1, "ζ_a {zeta}");
    assert!((heave / heave_exp - 1.0).abs() < 0.15, "heave {heave}");
    assert!((roll / roll_exp - 1.0).abs() < 0.25, "roll {roll}");
}
