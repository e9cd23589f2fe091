//! How `run` and `step` advance a simulation: towards a target in slices of wall time,
//! between which Python's Ctrl-C and progress callbacks are served.

use sph_core::{Simulation, SphError};
use std::time::{Duration, Instant};

/// How long the solver runs detached before it looks at Ctrl-C and reports progress.
const SLICE: Duration = Duration::from_millis(100);

/// Where a call to `run` or `step` stops.
#[derive(Clone, Copy)]
pub(crate) enum Target {
    /// At time `until` (the last step shortened to land on it), or at `max_steps`.
    Time { until: f64, max_steps: u64 },
    /// After exactly this step count.
    Steps(u64),
}

impl Target {
    fn reached<const D: usize>(&self, s: &Simulation<D>) -> bool {
        match *self {
            Target::Time { until, max_steps } => {
                s.time() >= until * (1.0 - 1e-12) || s.counters().steps >= max_steps
            }
            Target::Steps(n) => s.counters().steps >= n,
        }
    }

    fn limit<const D: usize>(&self, s: &Simulation<D>) -> f64 {
        match *self {
            Target::Time { until, .. } => until,
            Target::Steps(_) => s.case().time.end,
        }
    }
}

/// Steps towards `target` for at most [`SLICE`] of wall time; `Ok(true)` once reached.
pub(crate) fn advance<const D: usize>(
    s: &mut Simulation<D>,
    target: Target,
) -> Result<bool, SphError> {
    let start = Instant::now();
    while !target.reached(s) {
        s.step_until(target.limit(s))?;
        if start.elapsed() >= SLICE {
            return Ok(target.reached(s));
        }
    }
    Ok(true)
}
