//! The discrete operators and closures of the δ-SPH family, each with its formula and
//! paper: smoothing kernels, the equation of state, viscosity, density diffusion, the
//! renormalised gradient, free-surface detection and particle shifting. They know
//! nothing of the case file; [`crate::scheme`] assembles them into equations.

pub mod diffusion;
pub mod eos;
pub mod free_surface;
pub mod kernel;
pub mod les;
pub mod renormalisation;
pub mod shifting;
pub mod viscosity;
