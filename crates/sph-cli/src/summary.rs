//! The summary a run prints at its end, and the per-process report of a split run.

use sph_core::case::{ShiftingChoice, TurbulenceChoice};
use sph_core::run::Run;
use sph_core::Simulation;

/// The scheme of the summary: the closure or the diffusion, shifting, tensile control,
/// viscosity, integrator and CFL number, and whether a body force drives the flow.
fn scheme_line<const D: usize>(sim: &Simulation<D>) -> String {
    let case = sim.case();
    let s = &case.scheme;
    let mut parts = vec![if s.turbulence == TurbulenceChoice::DeltaLes {
        let les = sph_core::scheme::resolve::les_constants(case, sim.physics().eos.c0);
        format!(
            "δ-LES-SPH (C_S = {}, C_δ = {}, l = {} m, U_max = {} m/s)",
            les.smagorinsky, les.diffusion, les.length, les.velocity
        )
    } else {
        format!("{:?} diffusion (δ = {})", s.diffusion, s.delta)
    }];
    if s.shifting != ShiftingChoice::None {
        parts.push(format!("{:?} shifting", s.shifting));
    }
    if s.tensile_control {
        parts.push("tensile control".into());
    }
    parts.push(format!("{:?} viscosity", s.viscosity));
    parts.push(format!("{:?}, CFL {}", s.integrator, s.cfl()));
    if case.forcing.is_some() {
        parts.push("body force from [forcing]".into());
    }
    parts.join(", ")
}

/// Per process of a split run: its fluid particles and halo, the particles it handed
/// to other processes at list rebuilds, the halo refreshes and
/// their bytes, and its time in communication against the run's `wall` time; then the
/// load imbalance (`None` when the run is not split). Collective.
pub(crate) fn process_report<const D: usize>(sim: &Simulation<D>, wall: f64) -> Option<String> {
    const FIELDS: usize = 8;
    let ranks = sim.ranks()?;
    let (rank, size) = (ranks.rank(), ranks.size());
    let t = ranks.traffic();
    let own = (0..sim.particles().len()).filter(|&i| ranks.owned()[i]);
    let fluid = own
        .filter(|&i| sim.particles().kind[i] == sph_core::Kind::Fluid)
        .count();
    let mut table = vec![0.0; FIELDS * size];
    table[FIELDS * rank..][..FIELDS].copy_from_slice(&[
        fluid as f64,
        ranks.halo_len() as f64,
        t.refreshes as f64,
        t.refresh_bytes as f64,
        t.seconds,
        t.rebalances as f64,
        t.migrated as f64,
        t.refresh_seconds,
    ]);
    ranks.sum(&mut table);
    let rows: Vec<&[f64]> = table.chunks(FIELDS).collect();
    let mean = rows.iter().map(|r| r[0]).sum::<f64>() / size as f64;
    let most = rows.iter().map(|r| r[0]).fold(0.0, f64::max);
    let mut text = format!(
        "processes       {size} (recursive coordinate bisection, rebalanced {} times); \
         imbalance {:.3} at the end (largest fluid share over the mean)\n",
        rows[0][5],
        most / mean.max(1.0)
    );
    for (r, row) in rows.iter().enumerate() {
        text.push_str(&format!(
            "  process {r:<4} {:.0} fluid, halo {:.0}, {:.0} sent to other processes; {:.0} halo \
             refreshes of {:.1} kB sent ({:.3} ms each to pack and unpack); communication {:.2} s of {wall:.2} s \
             ({:.1}%)\n",
            row[0],
            row[1],
            row[6],
            row[2],
            row[3] / row[2].max(1.0) / 1e3,
            1e3 * row[7] / row[2].max(1.0),
            row[4],
            100.0 * row[4] / wall.max(1e-12),
        ));
    }
    Some(text)
}

pub(crate) fn summary<const D: usize>(sim: &Simulation<D>, run: &Run) {
    let since = run.since;
    let wall = run.wall.as_secs_f64();
    let n = sim.n_fluid();
    let c = sim.counters();
    let e1 = sim.energies();
    let initial_energy = run.schedule.initial_energy;
    println!("case            {} ({}D)", sim.case().name, D);
    println!(
        "particles       {} fluid, {} wall",
        n,
        sim.particles().len() - n
    );
    println!("scheme          {}", scheme_line(sim));
    println!("sound speed     c0 = {:.4} m/s", sim.physics().eos.c0);
    println!(
        "simulated       t = {:.6} s in {} steps (last Δt = {:.3e} s)",
        sim.time(),
        c.steps,
        sim.dt()
    );
    println!("wall time       {wall:.2} s");
    println!(
        "throughput      {:.3e} particle-steps/s, {:.3e} particle-evaluations/s, {} list builds",
        n as f64 * (c.steps - since.steps) as f64 / wall,
        n as f64 * (c.evaluations - since.evaluations) as f64 / wall,
        c.rebuilds
    );
    let (listed, used) = sim.mean_neighbours();
    println!(
        "neighbours      {listed:.1} listed per particle (fluid and wall, with the skin), \
         {used:.1} in the rows of the last step"
    );
    println!("max |Δρ/ρ0|     {:.3e}", sim.max_density_variation());
    println!(
        "walls           {} fluid particles inside a wall at the end",
        sim.wall_crossings()
    );
    println!(
        "removed         {} fluid particles ({:.4e} kg) left the domain {}",
        sim.removed(),
        sim.removed_mass(),
        sim.domain().describe()
    );
    if !sim.case().open_boundary.is_empty() {
        println!(
            "created         {} fluid particles entered at inlets",
            sim.counters().created
        );
    }
    println!(
        "energy          E_k+E_p+E_c: {:.6e} → {:.6e} J (change {:+.3e})",
        initial_energy,
        e1.total(),
        e1.total() - initial_energy
    );
    if let Some(b) = sim.budget() {
        println!(
            "                ∫(P_V+P_D+P_W+P_M+P_B)dt = {:+.3e} J, carried out by removed particles {:+.3e} J",
            b.work(),
            b.removed_energy
        );
        if sim.case().has_moving_bodies() {
            println!(
                "                of which the moving walls' work ∫P_M dt = {:+.3e} J",
                b.work_of_moving_walls()
            );
        }
        if let Some(m) = sim.motions().filter(|m| m.free_count() > 0) {
            println!(
                "                free bodies' energy E_b = {:.6e} J now (free_bodies_energy in the time series)",
                m.free_energy()
            );
        }
        let caveats = sim.budget_caveats();
        if !caveats.is_empty() {
            println!(
                "                the budget is incomplete: {}",
                caveats.join("; ")
            );
        }
    }
    if let Some(output) = &run.output {
        println!(
            "output          {} (open particles.xmf in ParaView)",
            output.dir().display()
        );
    }
}
