//! The stability guard: a run that goes unstable is stopped at the first particle
//! that shows it, with what went wrong; an impact's acoustic transient is let through
//! and reported.
//!
//! A weakly-compressible impact raises the density by about `U/c0` (the water hammer
//! `p = ρ0 c0 U`) until sound relieves it, within a few `h/c0` where the impact is
//! local: a cavity the single-phase model closes, a jet landing on water. In the 2D
//! dam break at c0 = 14√(gH), the cavity under the backward-plunging wave closes at
//! t = 1.99 s with a local speed of 8.6 m/s (2.5 times the dam break's √(2gH)):
//! `ρ/ρ0 - 1` reaches 0.28 at one particle, stays beyond 0.2 for three steps
//! (1.7 `h/c0`) and is back under 0.1 two steps later. A blow-up does not relieve
//! itself: an unstable scheme (a symplectic step three times its acoustic limit) sends
//! particles beyond the limit again and again, a few steps each, a few steps apart.
//! So an excursion beyond `stability.max_density_variation` lasts from the first step
//! beyond the limit to the last one that is not followed by `stability.transient`
//! acoustic times `h/c0` within it; it stops the run when it lasts longer than that
//! window, and is reported as a transient once the window has passed within the limit.
//! A non-finite state, a speed beyond `stability.max_mach · c0` or a density outside
//! `(0, 2ρ0)` stop the run at once.

use crate::particles::{Kind, Particles};
use rayon::prelude::*;

/// `|ρ/ρ0 - 1|` at which a run stops at once: a density vanished or doubled has no
/// weakly-compressible reading (and matches the water hammer of a Mach-1 impact).
pub const HARD_DENSITY_VARIATION: f64 = 1.0;

/// Transients reported one by one before the guard stops listing them.
const REPORTED: usize = 10;

/// The first fluid particle that is not finite, whose speed passed `max_speed` or
/// whose density left `(0, 2ρ0)`, with a description of what went wrong.
pub fn find_instability<const D: usize>(
    p: &Particles<D>,
    rho0: f64,
    max_speed: f64,
) -> Option<(usize, String)> {
    (0..p.len())
        .into_par_iter()
        .filter(|&i| p.kind[i] == Kind::Fluid)
        .find_map_first(|i| {
            let finite =
                p.x[i].iter().chain(p.u[i].iter()).all(|v| v.is_finite()) && p.rho[i].is_finite();
            if !finite {
                return Some((i, "non-finite position, velocity or density".to_string()));
            }
            let speed = p.u[i].norm();
            if speed > max_speed {
                let why = format!(
                    "speed {speed:.4e} m/s beyond the limit {max_speed:.4e} m/s (stability.max_mach × c0)"
                );
                return Some((i, why));
            }
            let var = p.rho[i] / rho0 - 1.0;
            (var.abs() >= HARD_DENSITY_VARIATION).then(|| {
                let why = format!(
                    "density variation ρ/ρ0 - 1 = {var:.4}: the density vanished or doubled"
                );
                (i, why)
            })
        })
}

/// The fluid particle with the largest `|ρ/ρ0 - 1|` and that variation (signed), if
/// there is fluid.
pub fn densest_excursion<const D: usize>(p: &Particles<D>, rho0: f64) -> Option<(usize, f64)> {
    (0..p.len())
        .into_par_iter()
        .filter(|&i| p.kind[i] == Kind::Fluid)
        .map(|i| (i, p.rho[i] / rho0 - 1.0))
        .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()).then(b.0.cmp(&a.0)))
}

/// The particle that holds a density excursion: its id, position (as text) and
/// `ρ/ρ0 - 1`.
#[derive(Debug, Clone, PartialEq)]
pub struct Holder {
    pub particle: u32,
    pub position: String,
    pub variation: f64,
}

/// What [`DensityWatch::observe`] concluded.
#[derive(Debug, PartialEq)]
pub enum Verdict {
    /// Nothing to report.
    Calm,
    /// An excursion beyond the limit ended within the window: the notice for the user.
    Transient(String),
    /// The excursion outlasted the window: its peak holder and the reason to stop.
    Unstable(Holder, String),
}

/// Steps with some fluid particle beyond the limit, less than the window apart.
#[derive(Debug, Clone, PartialEq)]
pub struct Excursion {
    /// The first and the last step beyond the limit \[s\].
    pub start: f64,
    pub end: f64,
    /// Steps beyond the limit.
    pub steps: usize,
    pub peak: Holder,
}

/// What a restart file keeps of a [`DensityWatch`], so that a continued run stops, or
/// lets a transient through, at the step the uninterrupted one does: the transients
/// reported so far and the excursion under way.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct WatchMemory {
    pub reported: usize,
    pub open: Option<Excursion>,
}

/// Follows `max |ρ/ρ0 - 1|` step by step and tells an impact's transient from a
/// blow-up (see the module documentation).
#[derive(Debug, Clone)]
pub struct DensityWatch {
    /// `stability.max_density_variation`.
    limit: f64,
    /// The acoustic time of the kernel, `h/c0` \[s\].
    acoustic: f64,
    /// `stability.transient`: the longest excursion let through, in `h/c0`.
    transient: f64,
    /// The transients reported so far and the excursion under way.
    memory: WatchMemory,
}

impl DensityWatch {
    pub fn new(limit: f64, transient: f64, acoustic: f64) -> Self {
        Self {
            limit,
            acoustic,
            transient,
            memory: WatchMemory::default(),
        }
    }

    /// What a restart file keeps of this watch.
    pub fn memory(&self) -> WatchMemory {
        self.memory.clone()
    }

    /// Continues from a restart file's [`WatchMemory`].
    pub fn recall(&mut self, memory: WatchMemory) {
        self.memory = memory;
    }

    /// Takes the state at `time`: `variation` the largest `|ρ/ρ0 - 1|` over the fluid
    /// (all processes), `holder` finds the particle that holds it (called only beyond
    /// the limit; collective in a split run, as every process takes the same branch).
    pub fn observe(
        &mut self,
        time: f64,
        variation: f64,
        holder: impl FnOnce() -> Holder,
    ) -> Verdict {
        let window = self.transient * self.acoustic;
        if variation <= self.limit {
            let relieved = (self.memory.open.as_ref()).is_some_and(|e| time - e.end > window);
            return match self.memory.open.take_if(|_| relieved) {
                Some(e) => self.report(e),
                None => Verdict::Calm,
            };
        }
        let now = holder();
        let excursion = self.memory.open.get_or_insert_with(|| Excursion {
            start: time,
            end: time,
            steps: 0,
            peak: now.clone(),
        });
        excursion.end = time;
        excursion.steps += 1;
        if now.variation.abs() > excursion.peak.variation.abs() {
            excursion.peak = now;
        }
        let lasted = excursion.end - excursion.start;
        if lasted <= window {
            return Verdict::Calm;
        }
        let why = format!(
            "density variation ρ/ρ0 - 1 beyond the limit ±{} in {} over {lasted:.3e} s \
             since t = {:.6} s, longer than an impact's transient (stability.transient = {} \
             h/c0 = {window:.3e} s); peak {:.4}",
            self.limit,
            steps_text(excursion.steps),
            excursion.start,
            self.transient,
            excursion.peak.variation,
        );
        Verdict::Unstable(excursion.peak.clone(), why)
    }

    /// The notice for an excursion that ended within the window (none past the
    /// [`REPORTED`]th but one that says so).
    fn report(&mut self, e: Excursion) -> Verdict {
        self.memory.reported += 1;
        if self.memory.reported > REPORTED {
            return Verdict::Calm;
        }
        let lasted = e.end - e.start;
        let mut text = format!(
            "t = {:.5}–{:.5} s: ρ/ρ0 - 1 reached {:.4} at particle {} near {}, beyond ±{} in \
             {} over {lasted:.2e} s ({:.1} h/c0), then within it for {} h/c0: an impact's \
             acoustic transient (a cavity closing, a jet landing), let through \
             (stability.transient)",
            e.start,
            e.end,
            e.peak.variation,
            e.peak.particle,
            e.peak.position,
            self.limit,
            steps_text(e.steps),
            lasted / self.acoustic,
            self.transient,
        );
        if self.memory.reported == REPORTED {
            text.push_str("; further transients are not listed");
        }
        Verdict::Transient(text)
    }
}

/// `1 step`, `3 steps`.
fn steps_text(steps: usize) -> String {
    match steps {
        1 => "1 step".to_string(),
        n => format!("{n} steps"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn holder(variation: f64) -> Holder {
        Holder {
            particle: 7,
            position: "[1.0, 2.0]".into(),
            variation,
        }
    }

    /// `observe` at steps `dt` apart from t = 0 (h/c0 = 1), every holder at the
    /// variation of its step.
    fn watch(steps: &[f64], dt: f64) -> Vec<Verdict> {
        let mut watch = DensityWatch::new(0.2, 10.0, 1.0);
        (steps.iter().enumerate())
            .map(|(k, &v)| watch.observe(dt * k as f64, v.abs(), || holder(v)))
            .collect()
    }

    /// The dam break's cavity closing, step by step (Δt = 1.5 h/c0): three steps beyond
    /// 0.2, then within it: one notice naming the peak once 10 h/c0 have passed.
    #[test]
    fn an_impact_transient_is_reported_once_relieved() {
        let mut steps = vec![0.1, 0.216, 0.283, 0.212, 0.098, 0.094];
        steps.extend([0.05; 6]);
        let verdicts = watch(&steps, 1.5);
        let notices: Vec<(usize, &String)> = (verdicts.iter().enumerate())
            .filter_map(|(k, v)| match v {
                Verdict::Transient(text) => Some((k, text)),
                Verdict::Calm => None,
                Verdict::Unstable(..) => panic!("{verdicts:?}"),
            })
            .collect();
        // the last step beyond the limit at t = 4.5, relieved past t = 14.5
        assert_eq!(notices.len(), 1, "{verdicts:?}");
        let (k, text) = notices[0];
        assert_eq!(k, 10);
        assert!(text.starts_with("t = 1.50000–4.50000 s: ρ/ρ0 - 1 reached 0.2830 at particle 7"));
        assert!(
            text.contains("in 3 steps over 3.00e0 s (3.0 h/c0)"),
            "{text}"
        );
    }

    /// Held beyond the limit for 8 steps (10.5 h/c0 > 10): stopped, at the peak.
    #[test]
    fn a_held_excursion_stops_the_run() {
        let steps = [0.21, 0.25, -0.3, 0.26, 0.24, 0.23, 0.22, 0.21];
        let verdicts = watch(&steps, 1.5);
        assert!(
            verdicts[..7].iter().all(|v| *v == Verdict::Calm),
            "{verdicts:?}"
        );
        let Verdict::Unstable(peak, why) = &verdicts[7] else {
            panic!("{verdicts:?}");
        };
        assert_eq!(peak.variation, -0.3);
        assert!(
            why.contains("in 8 steps over 1.050e1 s since t = 0.000000 s"),
            "{why}"
        );
    }

    /// An unstable scheme's pattern: a step or two beyond the limit, a few steps
    /// within, again and again. Each return comes within the window, so the excursion
    /// runs on and stops the run once it spans more than 10 h/c0.
    #[test]
    fn recurring_short_excursions_stop_the_run() {
        let steps: Vec<f64> = (0..20).map(|k| [0.25, 0.1, 0.15, 0.05][k % 4]).collect();
        let verdicts = watch(&steps, 1.0);
        let first = verdicts.iter().position(|v| *v != Verdict::Calm);
        assert_eq!(first, Some(12), "{verdicts:?}");
        assert!(matches!(verdicts[12], Verdict::Unstable(..)));
    }

    #[test]
    fn transients_past_the_tenth_are_not_listed() {
        // a one-step spike every 15 h/c0
        let steps: Vec<f64> = (0..400)
            .map(|k| if k % 15 == 0 { 0.3 } else { 0.1 })
            .collect();
        let notices: Vec<String> = (watch(&steps, 1.0).into_iter())
            .filter_map(|v| match v {
                Verdict::Transient(text) => Some(text),
                Verdict::Calm => None,
                Verdict::Unstable(..) => panic!("a spike every 15 h/c0 stopped the run"),
            })
            .collect();
        assert_eq!(notices.len(), REPORTED);
        assert!(notices[REPORTED - 1].ends_with("further transients are not listed"));
    }
}
