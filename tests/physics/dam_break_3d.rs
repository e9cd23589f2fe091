//! 3D dam break (coarse): the run stays stable, its energy balance closes
//! (E_k + E_p + E_c minus the integrated viscous, diffusive and wall powers stays
//! constant), it loses mechanical energy overall, and the surge front advances no
//! faster than the shallow-water (Ritter) front speed 2·sqrt(gH), at more than half of it.

use deltasph_suite::example_case;
use sph_core::Simulation;

#[test]
fn three_dimensional_dam_break_is_stable_and_physical() {
    let (h, g, l0) = (0.3f64, 9.81, 0.6);
    let case = example_case(
        "dam_break_3d.toml",
        &[
            "particles.spacing = 0.03",
            "diagnostics.energy_budget = true",
        ],
    );
    let mut sim = Simulation::<3>::new(case).unwrap();
    let front0 = sim.surge_front(0);
    let e0 = sim.energies().total();
    while sim.time() < 0.3 {
        sim.step().unwrap();
    }
    let e1 = sim.energies().total();
    let residual = (e1 - sim.budget().unwrap().work() - e0).abs();
    assert!(
        e1 < e0,
        "mechanical energy must decrease overall: {e0} → {e1}"
    );
    assert!(
        residual < 0.02 * (e0 - e1),
        "energy balance residual {residual} against a loss of {}",
        e0 - e1
    );
    let advance = sim.surge_front(0) - front0;
    let ritter = 2.0 * (g * h).sqrt() * sim.time();
    println!(
        "front advanced {advance:.3} m in {:.3} s; Ritter bound {ritter:.3} m",
        sim.time()
    );
    assert!(advance <= ritter + 0.03, "front faster than 2 sqrt(gH)");
    assert!(advance > 0.5 * ritter, "front too slow: {advance}");
    assert!(sim.max_density_variation() < 0.05);
    assert!(sim.energies().total() < e0 && (l0 - front0).abs() < 0.03);
}
