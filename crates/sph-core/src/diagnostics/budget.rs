//! The running energy budget (Antuono et al. 2015, CMAME 289:209; docs/theory.md,
//! energy balance), kept only when the case asks for it:
//! `E_k + E_p + E_c + E_b + removed_energy - work()` stays at its initial value
//! (`E_b` the free bodies' mechanical energy).
//!
//! The powers come from the first evaluation of each step (at its start state), so
//! the trapezoidal rule closes an interval at the start of the next step; until then
//! the last step counts by its left rectangle, `pending · P(start)`.

use crate::scheme::model::Powers;

#[derive(Debug, Clone, Copy, Default)]
pub struct EnergyBudget {
    /// `∫ (P_V + P_D + P_W + P_M + P_B + P_F) dt` by the trapezoidal rule up to the start of
    /// the last step.
    pub dissipated: f64,
    /// `∫ P_M dt` alone, the same way: the work of the moving walls on the fluid.
    pub moving_work: f64,
    /// `∫ P_F dt` alone, the same way: the work of the body force and the absorbers.
    pub forcing_work: f64,
    /// `E_k + E_p + E_c` the removed particles carried out of the domain.
    pub removed_energy: f64,
    /// The powers at the start of the last step.
    pub last: Powers,
    /// The length of the last step, whose closing power is not known yet (0 before the
    /// first step).
    pub pending: f64,
}

impl EnergyBudget {
    /// `∫ (P_V + P_D + P_W + P_M + P_B + P_F) dt` through the end of the last step.
    pub fn work(&self) -> f64 {
        self.dissipated + self.pending * self.last.total()
    }

    /// `∫ P_M dt` through the end of the last step.
    pub fn work_of_moving_walls(&self) -> f64 {
        self.moving_work + self.pending * self.last.moving
    }

    /// `∫ P_F dt` through the end of the last step.
    pub fn work_of_forcing(&self) -> f64 {
        self.forcing_work + self.pending * self.last.forcing
    }

    /// Closes the pending interval with the powers `now` at the start of a step.
    pub fn advance(&mut self, now: Powers) {
        self.dissipated += 0.5 * self.pending * (self.last.total() + now.total());
        self.moving_work += 0.5 * self.pending * (self.last.moving + now.moving);
        self.forcing_work += 0.5 * self.pending * (self.last.forcing + now.forcing);
        self.last = now;
        self.pending = 0.0;
    }

    /// Starts over from the powers `now` of a state set from outside the stepping.
    pub fn restart_from(&mut self, now: Powers) {
        (self.last, self.pending) = (now, 0.0);
    }
}
