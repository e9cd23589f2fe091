//! The state of a run that output and restart files take: the particles, the time,
//! the last step and the counters.

use crate::particles::Particles;

/// Counters for throughput reports.
#[derive(Debug, Clone, Copy, Default)]
pub struct Counters {
    pub steps: u64,
    pub evaluations: u64,
    pub rebuilds: u64,
    /// Fluid particles removed because they left the domain.
    pub removed: u64,
    /// Their mass \[kg\] (per unit depth in 2D).
    pub removed_mass: f64,
    /// Fluid particles created at inlets.
    pub created: u64,
}

/// The particles and the clock of a run.
#[derive(Debug, Clone, Default)]
pub struct State<const D: usize> {
    /// In their current storage order (`id` names each one).
    pub particles: Particles<D>,
    /// Simulated time \[s\].
    pub time: f64,
    /// The last step \[s\] (0 before the first).
    pub dt: f64,
    pub counters: Counters,
}
