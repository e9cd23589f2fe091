//! `sph-cli check`: a case validated and built without running it, with what each region
//! built, the domain, the memory the run will take and what it will cost.

use anyhow::Result;
use sph_core::case::{bytes_text, ViscosityChoice};
use sph_core::decomposition::Decomposition;
use sph_core::simulation::LONG_RUN;
use sph_core::{Case, Simulation};
use std::path::Path;

pub(crate) fn check(path: &Path, ranks: Option<u32>) -> Result<()> {
    let case = Case::from_file(path)?;
    let (summary, report) = match case.dimension {
        2 => describe::<2>(&case, ranks)?,
        _ => describe::<3>(&case, ranks)?,
    };
    println!(
        "{}: valid {}D case '{}': {summary}\n{report}",
        path.display(),
        case.dimension,
        case.name,
    );
    Ok(())
}

/// The particle counts, and the report of what each region built (and of the split
/// among `ranks` processes).
fn describe<const D: usize>(case: &Case, ranks: Option<u32>) -> Result<(String, String)> {
    let processes = ranks.unwrap_or(1) as usize;
    case.check_memory(processes)?;
    let setup = sph_core::geometry::build::<D>(case)?;
    let mut report = setup.report(case.dx(), case.support());
    let sim = Simulation::<D>::new(case.clone())?;
    if let Some(open) = sim.open_boundaries() {
        report.push_str(&open.describe(sim.particles()));
    }
    if let Some(motions) = sim.motions() {
        report.push_str(&motions.describe(case.time.end));
    }
    if let Some(ranks) = ranks {
        let (p, domain) = (sim.particles(), sim.domain());
        let split = Decomposition::bisect(p, domain, ranks as usize);
        report.push_str(&format!("split among {ranks} processes:\n"));
        report.push_str(&split.describe(p, domain, case.support()));
    }
    report.push_str(&domain_line(&sim));
    report.push_str(&memory_line(case, processes));
    report.push_str(&cost_lines(&sim));
    let (fluid, all) = (sim.n_fluid(), sim.particles().len());
    let summary = format!("{fluid} fluid and {} wall particles", all - fluid);
    Ok((summary, report))
}

/// The domain, and what becomes of fluid that leaves it.
fn domain_line<const D: usize>(sim: &Simulation<D>) -> String {
    let how = if sim.case().domain.is_none() {
        "default: the particles' box widened by half its extent on every side; fluid \
         leaving it is removed, with a notice the first time"
    } else {
        "[domain]; fluid leaving it is removed"
    };
    format!("domain: {} ({how})\n", sim.domain().describe())
}

/// The memory estimate against what the machine has.
fn memory_line(case: &Case, processes: usize) -> String {
    let size = case.size();
    let need = size.bytes_per_process(case.dimension, processes);
    let limit = match sph_core::case::memory_limit() {
        Ok(Some((bytes, source))) => format!("; {source}: {}", bytes_text(bytes)),
        _ => String::new(),
    };
    format!(
        "memory: about {} per process at the peak ({:.3e} particles, {:.0} neighbours \
         listed each){limit}\n",
        bytes_text(need),
        size.particles,
        size.listed
    )
}

/// Where c0 came from, as a line: given, or the rule's factor times the speed it
/// assumed for the flow (`c0/factor`: the rule takes the larger of that speed and
/// `sqrt(|g|H)`).
fn sound_speed_basis(case: &Case, c0: f64) -> String {
    let fluid = &case.fluid;
    if fluid.sound_speed.is_some() {
        return String::new();
    }
    let assumed = if fluid.max_velocity.is_some() {
        "fluid.max_velocity"
    } else {
        "√(2|g|H) over the fluid's height H, its initial speed, or an inlet's speed"
    };
    format!(
        "sound speed: c0 = {} × {:.4} m/s, the largest flow speed the rule assumed ({assumed}); \
         a local impact faster than that shows as a density transient; fluid.max_velocity or \
         fluid.sound_speed sets it\n",
        fluid.sound_speed_factor,
        c0 / fluid.sound_speed_factor
    )
}

/// Sound speed, first step, steps to the end and a wall-time estimate, with a warning
/// for a run of more than a day.
fn cost_lines<const D: usize>(sim: &Simulation<D>) -> String {
    let cost = sim.cost();
    let mut text = format!(
        "{}steps: c0 = {:.4} m/s, first Δt = {:.3e} s, about {:.3e} steps to t = {} s, \
         about {} on {} threads\n",
        sound_speed_basis(sim.case(), cost.c0),
        cost.c0,
        cost.dt,
        cost.steps,
        sim.case().time.end,
        duration_text(cost.seconds),
        cost.cores
    );
    text.push_str(&viscosity_line(sim.case(), cost.nu));
    if cost.seconds > LONG_RUN {
        text.push_str(&format!(
            "warning: this run would take more than a day ({}): check fluid.gravity, \
             fluid.sound_speed, particles.spacing and time.end\n",
            duration_text(cost.seconds)
        ));
    }
    text
}

/// The viscous term's kinematic viscosity; for the artificial one, that it scales with
/// c0 (docs/validation/impinging_jet.md: at fixed α a higher c0 slows the flow).
fn viscosity_line(case: &Case, nu: f64) -> String {
    match case.scheme.viscosity {
        ViscosityChoice::None => String::new(),
        ViscosityChoice::Physical => format!("viscosity: physical, ν = {nu:.3e} m²/s\n"),
        ViscosityChoice::Artificial => format!(
            "viscosity: artificial, α = {}: ν = α h c0/{} = {nu:.3e} m²/s, proportional to \
             c0 (to raise c0 at the same ν, lower scheme.alpha in proportion)\n",
            case.scheme.alpha(),
            2 * (case.dimension + 2)
        ),
    }
}

/// Seconds as a short duration.
fn duration_text(seconds: f64) -> String {
    match seconds {
        s if s < 120.0 => format!("{s:.0} s"),
        s if s < 7200.0 => format!("{:.0} min", s / 60.0),
        s if s < 2.0 * 86_400.0 => format!("{:.1} h", s / 3600.0),
        s => format!("{:.3e} days", s / 86_400.0),
    }
}
