//! When the Verlet lists are rebuilt, and with what skin.
//!
//! A step whose particles may move by its reach `ρ` (see [`ListPolicy::reach`]) keeps
//! the lists while `δ + ρ ≤ s/2`, δ the largest displacement since the build and s
//! the skin: every pair closer than R then stays listed through the step. A rebuild
//! sizes the skin to [`SKIN_OVER_REACH`] times the step's reach, so that the lists
//! last a few steps (the steps cull them to what they use), never below
//! [`MIN_SKIN`]·R, and never so wide that minimum image stops being unique across a
//! periodic direction.

use crate::domain::Domain;

/// The smallest skin of the neighbour lists, as a fraction of the kernel support.
pub const MIN_SKIN: f64 = 0.1;

/// The skin is sized to this many times the reach of a step, so that the lists last
/// a few steps (the steps cull them to what they use).
pub const SKIN_OVER_REACH: f64 = 6.0;

/// The skin rule of a run: its kernel support and the widest skin its periodic
/// directions allow.
#[derive(Debug, Clone, Copy)]
pub struct ListPolicy {
    /// Kernel support R.
    pub support: f64,
    /// Widest skin: minimum image is unique while `R + s` stays below half of every
    /// period (infinite without periodic directions).
    pub max_skin: f64,
    /// The largest displacement a particle shift may add to a step (δ+-SPH's cap
    /// times h; zero without shifting).
    pub shift_cap: f64,
}

impl ListPolicy {
    pub fn new<const D: usize>(support: f64, domain: &Domain<D>, shift_cap: f64) -> Self {
        let max_skin = (0..D)
            .filter(|&d| domain.is_periodic(d))
            .map(|d| (0.5 * domain.period[d] - support) * (1.0 - 1e-9))
            .fold(f64::INFINITY, f64::min);
        Self {
            support,
            max_skin,
            shift_cap,
        }
    }

    /// Largest displacement a step of `dt` may add: `Δt (1.2|u|max + |a|max Δt)`, plus
    /// the shifting cap when particles are shifted.
    pub fn reach(&self, dt: f64, speed: f64, acceleration: f64) -> f64 {
        dt * (1.2 * speed + acceleration * dt) + self.shift_cap
    }

    /// The reach of the coming step, at least a twentieth of the support (a flow at
    /// rest still starts to move within the step).
    pub fn step_reach(&self, dt: f64, speed: f64, acceleration: f64) -> f64 {
        self.reach(dt, speed, acceleration)
            .max(0.5 * MIN_SKIN * self.support)
    }

    /// The skin of a rebuild before steps of reach `reach`.
    pub fn skin(&self, reach: f64) -> f64 {
        (MIN_SKIN * self.support)
            .max(SKIN_OVER_REACH * reach)
            .min(self.max_skin)
    }

    /// Whether lists of skin `skin`, whose particles moved by up to `moved` since
    /// their build, must be rebuilt before a step of reach `reach`.
    pub fn rebuild_due(&self, moved: f64, reach: f64, skin: f64) -> bool {
        moved + reach > 0.5 * skin
    }

    /// The longest step whose [`Self::reach`] stays within `room`: the root of
    /// `|a| Δt² + 1.2|u| Δt = room - shift`. It binds only when the skin could not be
    /// made wide enough (small periodic boxes), so that the lists never miss a pair.
    pub fn dt_within(&self, room: f64, speed: f64, acceleration: f64) -> f64 {
        let b = (room - self.shift_cap).max(0.0);
        let (v, a) = (1.2 * speed, acceleration);
        2.0 * b / (v + (v * v + 4.0 * a * b).sqrt()).max(f64::MIN_POSITIVE)
    }
}
