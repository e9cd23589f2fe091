//! Open boundaries (inlet and outlet buffers): a uniform stream keeps its flow rate,
//! density and particle count over 20 flow-through times; a laminar channel fed with
//! the parabolic profile keeps it downstream, with the pressure gradient of Poiseuille
//! flow; particles created at the inlet get new ids.

use sph_core::{Case, Kind, Simulation};

fn build(text: &str) -> Simulation<2> {
    let case = Case::from_toml_str(text).unwrap_or_else(|e| panic!("{e}"));
    Simulation::<2>::new(case).unwrap_or_else(|e| panic!("{e}"))
}

/// The volume (or, `by_mass`, mass) flow rate through the section x = x0 per unit
/// depth, `Σ u_x V φ(x - x0) / Δx` (`m` for `V`) with the hat weight
/// `φ(s) = max(0, 1 - |s|/Δx)`: linear interpolation between the columns on either
/// side, exact for a lattice at any offset.
fn flow_rate(sim: &Simulation<2>, x0: f64, dx: f64, by_mass: bool) -> f64 {
    let p = sim.particles();
    (0..p.len())
        .filter(|&i| p.kind[i] == Kind::Fluid)
        .map(|i| {
            let hat = (1.0 - (p.x[i][0] - x0).abs() / dx).max(0.0);
            let amount = if by_mass { p.mass[i] } else { p.volume(i) };
            p.u[i][0] * amount * hat
        })
        .sum::<f64>()
        / dx
}

/// A stream at U = 1 m/s through a channel 1.2 m long and 0.4 m high, periodic across,
/// between an inlet and an outlet at p = 0 (Δx = 0.025, c0 = 10 U), for 20 flow-through
/// times (24 s): at every 0.2 s the flow rate through the middle within 1% of U H, the
/// density within 1% of ρ0 and the fluid count within one column (16) of the start
/// (all three measured exact to the print's precision); the inlet creates and the
/// outlet removes 20 channels' worth of particles (24 U/Δx columns), every new one
/// with an id of its own.
#[test]
fn a_uniform_stream_keeps_its_flow_rate_and_particles_for_20_flow_through_times() {
    let (dx, length, height, u) = (0.025, 1.2, 0.4, 1.0);
    let mut sim = build(&format!(
        "dimension = 2\n[particles]\nspacing = {dx}\n[fluid]\ndensity = 1000.0\n\
         sound_speed = 10.0\n[[fluid_block]]\nlo = [0.0, 0.0]\nhi = [{length}, {height}]\n\
         velocity = [{u}, 0.0]\nhydrostatic = false\n[domain]\nlo = [0.0, 0.0]\n\
         hi = [{length}, {height}]\nperiodic = [false, true]\n[scheme]\n\
         diffusion = \"delta_sph\"\n[[open_boundary]]\ntype = \"inlet\"\naxis = 0\nside = \"lo\"\n\
         velocity = [{u}, 0.0]\n[[open_boundary]]\ntype = \"outlet\"\naxis = 0\nside = \"hi\"\n\
         [time]\nend = 24.0\n"
    ));
    let n0 = sim.n_fluid() as f64;
    let first_ids = sim.particles().next_id;
    let (mut worst_q, mut worst_rho, mut worst_n): (f64, f64, f64) = (0.0, 0.0, 0.0);
    let mut t = 0.0;
    while t < 24.0 - 1e-9 {
        t += 0.2;
        while sim.time() < t * (1.0 - 1e-12) {
            sim.step_until(t).unwrap();
        }
        let q = flow_rate(&sim, 0.5 * length, dx, false);
        worst_q = worst_q.max((q / (u * height) - 1.0).abs());
        worst_rho = worst_rho.max(sim.max_density_variation());
        worst_n = worst_n.max((sim.n_fluid() as f64 - n0).abs());
    }
    let c = sim.counters();
    println!(
        "uniform stream: flow rate {:.3}%, density {:.3}%, count {worst_n} off {n0}, \
         created {}, removed {}",
        100.0 * worst_q,
        100.0 * worst_rho,
        c.created,
        c.removed
    );
    assert!(worst_q < 0.01, "flow rate off by {worst_q}");
    assert!(worst_rho < 0.01, "density off by {worst_rho}");
    assert!(worst_n <= height / dx, "{worst_n} particles gained or lost");
    // 20 flow-through times bring the channel's contents in 20 times, each with a new id
    let rows = height / dx;
    let expected = 24.0 * u / dx * rows;
    assert!(
        (c.created as f64 / expected - 1.0).abs() < 0.01,
        "{}",
        c.created
    );
    assert!(
        (c.removed as f64 / expected - 1.0).abs() < 0.01,
        "{}",
        c.removed
    );
    let p = sim.particles();
    assert_eq!(p.next_id as u64, first_ids as u64 + c.created);
    let mut ids = p.id.clone();
    ids.sort_unstable();
    ids.dedup();
    assert_eq!(ids.len(), p.len(), "an id used twice");
}

/// Laminar flow between no-slip plates y = 0 and L = 1 (ρ0 = 1, ν = 0.1, U = 1 at the
/// centre: Re = U L/ν = 10), 4L long, fed by an inlet with the parabolic profile
/// u = 4U y(L-y)/L² and drained by an outlet at p = 0; started from that profile at
/// zero pressure (Δx = L/20, c0 = 10 U). At t = 8 (two flow-throughs; the start's
/// acoustic sloshing has died down) in the middle (x = 1.5-2.5):
/// - the mass flux `ρu/ρ_in` is the inlet profile within 0.5% of U RMS (measured 0.22%;
///   0.12% at L/Δx = 40). The speed itself is not: the density falls by G·4L/c0² ≈ 3%
///   along the channel, and the speed rises by as much to carry the same mass;
/// - the mass flow rate is `ρ_in 2UL/3` within 1% (measured +0.25%; +0.10% at 40);
/// - the pressure falls at the Poiseuille gradient G = 8ρ0νU/L² within 5% (measured
///   2.7% and 2.8% short at L/Δx = 20 and 40: flat in Δx, like the viscous operator's
///   error at fixed h/Δx in the start-up Couette test).
#[test]
fn a_channel_fed_with_the_poiseuille_profile_keeps_it_and_its_pressure_gradient() {
    let (dx, length, nu) = (0.05, 4.0, 0.1);
    let mut sim = build(&format!(
        "dimension = 2\n[particles]\nspacing = {dx}\n[fluid]\ndensity = 1.0\n\
         sound_speed = 10.0\n[[fluid_block]]\nlo = [0.0, 0.0]\nhi = [{length}, 1.0]\n\
         hydrostatic = false\n[[tank]]\nlo = [0.0, 0.0]\nhi = [{length}, 1.0]\n\
         open = [\"-x\", \"+x\"]\n[domain]\nlo = [0.0, -1.0]\nhi = [{length}, 2.0]\n\
         [initial]\ntype = \"expressions\"\nu = [\"4*y*(1-y)\", \"0\"]\n\
         [scheme]\ndiffusion = \"delta_sph\"\nviscosity = \"physical\"\n\
         dynamic_viscosity = {nu}\nwalls = \"no_slip\"\n\
         [[open_boundary]]\ntype = \"inlet\"\naxis = 0\nside = \"lo\"\nvelocity = [1.0, 0.0]\n\
         profile = \"parabolic\"\n[[open_boundary]]\ntype = \"outlet\"\naxis = 0\nside = \"hi\"\n\
         [time]\nend = 8.0\n"
    ));
    while sim.time() < 8.0 * (1.0 - 1e-12) {
        sim.step().unwrap();
    }
    sim.sync_pressure();
    let p = sim.particles();
    // weakly compressible: the density falls by G·4L/c0² ≈ 3% down the channel and
    // the speed rises to keep the mass flux, ρ u = ρ_in u_in(y), which is compared
    let inlet: Vec<f64> = (0..p.len())
        .filter(|&i| p.kind[i] == Kind::Fluid && p.x[i][0] < 0.2)
        .map(|i| p.rho[i])
        .collect();
    let rho_in = inlet.iter().sum::<f64>() / inlet.len() as f64;
    let middle: Vec<usize> = (0..p.len())
        .filter(|&i| p.kind[i] == Kind::Fluid && (1.5..2.5).contains(&p.x[i][0]))
        .collect();
    let profile_error = (middle.iter())
        .map(|&i| {
            let y = p.x[i][1];
            (p.u[i][0] * p.rho[i] / rho_in - 4.0 * y * (1.0 - y)).powi(2)
        })
        .sum::<f64>()
        / middle.len() as f64;
    let profile_error = profile_error.sqrt();
    let q = flow_rate(&sim, 2.0, dx, true) / rho_in;
    // least-squares slope of p against x over x = 1-3
    let fit: Vec<(f64, f64)> = (0..p.len())
        .filter(|&i| p.kind[i] == Kind::Fluid && (1.0..3.0).contains(&p.x[i][0]))
        .map(|i| (p.x[i][0], p.p[i]))
        .collect();
    let n = fit.len() as f64;
    let (mx, mp) = (
        fit.iter().map(|f| f.0).sum::<f64>() / n,
        fit.iter().map(|f| f.1).sum::<f64>() / n,
    );
    let slope = fit.iter().map(|f| (f.0 - mx) * (f.1 - mp)).sum::<f64>()
        / fit.iter().map(|f| (f.0 - mx).powi(2)).sum::<f64>();
    let g = 8.0 * nu;
    println!(
        "channel, L/Δx = {}: profile RMS {profile_error:.4} U, mass flow rate {q:.4} ρ_in (2/3), \
         dp/dx {slope:.4} against {:.4}",
        1.0 / dx,
        -g
    );
    assert!(profile_error < 0.005, "{profile_error}");
    assert!((q / (2.0 / 3.0) - 1.0).abs() < 0.01, "{q}");
    assert!((slope / -g - 1.0).abs() < 0.05, "{slope}");
}

/// A stream started from rest by an inlet ramped up over 1 s to U = 1 m/s (the
/// channel of the test above at Δx = 0.05, 0.8 m high), drained by an outlet whose
/// velocity is extrapolated from the fluid. Sampled every 0.1 s from t = 3 s
/// to 6 s (after the ramp, three flow-through times) in the middle and just upstream of
/// the outlet buffer: the mean flow rate within 0.5% of U H (measured MEAN), each
/// sample of the last second within 2% (measured LAST; the start leaves an acoustic
/// oscillation of the channel, 2.4% at t = 3 s, that decays), the density within 1% of
/// ρ0, the fluid count within a column of the start. With the outlet's velocity kept
/// instead (the default), its particles would keep the start's rest and block the
/// channel (the density passed 20% at t = 0.8 s before the start was checked): the
/// case is refused in one line.
#[test]
fn a_stream_started_from_rest_leaves_through_the_outlet() {
    let (dx, length, height, u) = (0.05, 1.2, 0.8, 1.0);
    let text = format!(
        "dimension = 2\n[particles]\nspacing = {dx}\n[fluid]\ndensity = 1000.0\n\
         sound_speed = 10.0\n[[fluid_block]]\nlo = [0.0, 0.0]\nhi = [{length}, {height}]\n\
         hydrostatic = false\n[domain]\nlo = [0.0, 0.0]\n\
         hi = [{length}, {height}]\nperiodic = [false, true]\n[scheme]\n\
         diffusion = \"delta_sph\"\n[[open_boundary]]\ntype = \"inlet\"\naxis = 0\nside = \"lo\"\n\
         velocity = [{u}, 0.0]\nramp = 1.0\n[[open_boundary]]\ntype = \"outlet\"\naxis = 0\n\
         side = \"hi\"\noutflow_velocity = \"extrapolated\"\n[time]\nend = 6.0\n"
    );
    let kept = Case::from_toml_str(&text.replace("outflow_velocity = \"extrapolated\"\n", ""))
        .and_then(Simulation::<2>::new)
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(
        kept.starts_with("open_boundary[1].outflow_velocity = kept: expected \"extrapolated\""),
        "{kept}"
    );
    let mut sim = build(&text);
    let n0 = sim.n_fluid() as f64;
    let width = sim.case().open_boundary[1].width_in(sim.case());
    let sections = [0.5 * length, length - width - 2.0 * dx];
    let (mut sum, mut samples, mut last): (f64, f64, f64) = (0.0, 0.0, 0.0);
    let (mut worst_rho, mut worst_n): (f64, f64) = (0.0, 0.0);
    for k in 1..=60 {
        let t = 0.1 * k as f64;
        while sim.time() < t * (1.0 - 1e-12) {
            sim.step_until(t).unwrap();
        }
        if t < 3.0 - 1e-9 {
            continue;
        }
        for x0 in sections {
            let q = flow_rate(&sim, x0, dx, false) / (u * height);
            (sum, samples) = (sum + q, samples + 1.0);
            if t > 5.0 - 1e-9 {
                last = last.max((q - 1.0).abs());
            }
        }
        worst_rho = worst_rho.max(sim.max_density_variation());
        worst_n = worst_n.max((sim.n_fluid() as f64 - n0).abs());
    }
    let mean = sum / samples - 1.0;
    println!(
        "stream from rest: mean flow rate {:+.3}%, last second within {:.3}%, density \
         {:.3}%, count {worst_n} off {n0}",
        100.0 * mean,
        100.0 * last,
        100.0 * worst_rho
    );
    assert!(mean.abs() < 0.005, "mean flow rate off by {mean}");
    assert!(last < 0.02, "flow rate off by {last} in the last second");
    assert!(worst_rho < 0.01, "density off by {worst_rho}");
    assert!(worst_n <= height / dx, "{worst_n} particles gained or lost");
}

/// The uniform stream of 1 m by 0.8 m at Δx = 0.05, with its boundary tables and
/// `[domain]`.
fn stream(boundaries: &str, domain: &str) -> String {
    format!(
        "dimension = 2\n[particles]\nspacing = 0.05\n[fluid]\ndensity = 1000.0\n\
         sound_speed = 10.0\n[[fluid_block]]\nlo = [0.0, 0.0]\nhi = [1.0, 0.8]\n\
         velocity = [1.0, 0.0]\nhydrostatic = false\n{domain}[scheme]\n\
         diffusion = \"delta_sph\"\n{boundaries}[time]\nend = 1.0\n"
    )
}

const DOMAIN: &str = "[domain]\nlo = [0.0, 0.0]\nhi = [1.0, 0.8]\nperiodic = [false, true]\n";
const INLET: &str = "[[open_boundary]]\ntype = \"inlet\"\naxis = 0\nside = \"lo\"\n";
/// A wall box at the inlet end of the stream, 0.3 m up.
const WALL: &str = "[[wall]]\nlo = [0.0, 0.3]\nhi = [0.2, 0.5]\n";

/// The stream's fluid in two blocks, below and above [`WALL`]'s height.
fn around_a_wall(text: String) -> String {
    text.replace(
        "lo = [0.0, 0.0]\nhi = [1.0, 0.8]\nvelocity = [1.0, 0.0]\nhydrostatic = false\n",
        "lo = [0.0, 0.0]\nhi = [1.0, 0.3]\nvelocity = [1.0, 0.0]\nhydrostatic = false\n\
         [[fluid_block]]\nlo = [0.0, 0.5]\nhi = [1.0, 0.8]\nvelocity = [1.0, 0.0]\n\
         hydrostatic = false\n",
    )
}

/// A tank around the stream's fluid, with its `open` faces, inside a larger domain,
/// drained by an outlet at the domain's +x end.
fn enclosed(open: &str) -> String {
    stream(
        &format!(
            "[[tank]]\nlo = [0.0, 0.0]\nhi = [1.0, 0.8]\nopen = [{open}]\n[domain]\n\
             lo = [-0.5, -0.5]\nhi = [2.0, 1.5]\n{OUTLET}"
        ),
        "",
    )
}
const OUTLET: &str = "[[open_boundary]]\ntype = \"outlet\"\naxis = 0\nside = \"hi\"\n";

/// A run restarted half-way continues the uninterrupted one bit for bit, particles
/// created and removed in between included.
#[test]
fn an_open_channel_restarts_bit_for_bit() {
    let text = stream(&format!("{INLET}velocity = [1.0, 0.0]\n{OUTLET}"), DOMAIN);
    let mut whole = build(&text);
    while whole.time() < 0.5 * (1.0 - 1e-12) {
        whole.step_until(0.5).unwrap();
    }
    let checkpoint = whole.checkpoint().unwrap().into_owned();
    let run_to_end = |sim: &mut Simulation<2>| {
        while sim.time() < 1.0 * (1.0 - 1e-12) {
            sim.step().unwrap();
        }
    };
    run_to_end(&mut whole);
    let mut resumed = Simulation::<2>::from_checkpoint(checkpoint, None).unwrap();
    run_to_end(&mut resumed);
    let (a, b) = (whole.particles(), resumed.particles());
    assert!(whole.counters().created > 0 && whole.counters().removed > 0);
    assert_eq!(a.id, b.id);
    assert_eq!(a.next_id, b.next_id);
    assert_eq!(a.x, b.x);
    assert_eq!(a.u, b.u);
    assert_eq!(a.rho, b.rho);
    assert_eq!(whole.counters().created, resumed.counters().created);
}

#[test]
fn bad_open_boundaries_are_refused_in_one_line() {
    let inlet = format!("{INLET}velocity = [1.0, 0.0]\n");
    let cases = [
        (
            stream(&format!("{inlet}width = 0.1\n"), DOMAIN),
            "open_boundary[0].width = 0.1: expected a buffer at least the kernel support R = 0.2000 m wide",
        ),
        (
            stream(&inlet, ""),
            "domain = (not set): expected [domain] lo and hi",
        ),
        (
            stream(&inlet.replace("axis = 0", "axis = 1"), DOMAIN),
            "open_boundary[0].axis = 1: expected an axis that is not periodic",
        ),
        (
            stream(&INLET.replace("side = \"lo\"", "side = \"lo\"\nvelocity = [2.0, 0.0]"), DOMAIN),
            "open_boundary[0].velocity = [2.0, 0.0]: expected an inflow speed of at most c0/10 = 1.0000 m/s",
        ),
        (
            stream(&INLET.replace("side = \"lo\"", "side = \"lo\"\nvelocity = [-0.5, 0.0]"), DOMAIN),
            "expected a velocity into the domain (component 0 of sign +1)",
        ),
        (
            stream(&format!("{OUTLET}velocity = [1.0, 0.0]\n"), DOMAIN),
            "open_boundary[0].velocity = (set): expected velocity, profile and ramp for an inlet, pressure and outflow_velocity for an outlet",
        ),
        (
            stream(INLET, DOMAIN),
            "open_boundary[0].velocity = (not set)",
        ),
        (
            stream(&format!("{inlet}section = [[0.1, 0.3], [0.0, 1.0]]\n"), DOMAIN),
            "open_boundary[0].section = [[0.1, 0.3], [0.0, 1.0]]: expected 1 [lo, hi] interval(s)",
        ),
        (
            stream(&format!("{inlet}section = [[0.5, 0.9]]\n"), DOMAIN),
            "open_boundary[0].section[0] = [0.5, 0.9]: expected an interval lo < hi along axis 1 within the domain, [0, 0.8]",
        ),
        (
            stream(&inlet, DOMAIN).replace("lo = [0.0, 0.0]\nhi = [1.0, 0.8]\nvelocity", "lo = [0.5, 0.0]\nhi = [1.0, 0.8]\nvelocity"),
            "open_boundary[0] = no fluid in the inlet's buffer: expected a buffer covered by a fluid block",
        ),
        (
            around_a_wall(stream(&format!("{inlet}{WALL}"), DOMAIN)),
            "open_boundary[0] = a wall particle at [0.025, 0.325] inside the inlet: expected an inlet free of walls",
        ),
        (
            enclosed(""),
            "open_boundary[0] = no way from the fluid to the outlet: expected an outlet the fluid can reach",
        ),
    ];
    for (text, expected) in cases {
        let e = match Case::from_toml_str(&text) {
            Err(e) => e.to_string(),
            Ok(case) => match Simulation::<2>::new(case) {
                Err(e) => e.to_string(),
                Ok(_) => panic!("built:\n{text}"),
            },
        };
        assert_eq!(e.lines().count(), 1, "{e}");
        assert!(e.contains(expected), "{e}\n expected: {expected}");
    }
    // the tank opened at its outlet side, and a wall beside an inlet's section, pass
    let open = enclosed("\"+x\"");
    let beside = around_a_wall(stream(
        &format!("{inlet}section = [[0.0, 0.3]]\n{WALL}"),
        DOMAIN,
    ));
    for text in [open, beside] {
        let case = Case::from_toml_str(&text).unwrap_or_else(|e| panic!("{e}"));
        Simulation::<2>::new(case).unwrap_or_else(|e| panic!("{e}\n{text}"));
    }
}
