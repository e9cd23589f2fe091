//! The semi-discrete equations as one resolved type per combination of options
//! ([`model`]), and the one place where a case's options become those types
//! ([`resolve`]).

pub mod delta_sph;
mod kinematics;
pub mod les;
pub mod model;
pub mod resolve;

pub use delta_sph::Scheme;
pub use model::{Model, Physics, Powers, Rates};
