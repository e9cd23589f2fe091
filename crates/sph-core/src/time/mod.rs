//! Time integration: the integrators ([`integrator`]) and the adaptive step size
//! ([`step_size`]).

pub mod integrator;
pub mod step_size;
