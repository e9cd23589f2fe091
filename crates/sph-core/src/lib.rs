//! deltasph core: a weakly-compressible SPH solver of the δ-SPH family
//! (Antuono, Colagrossi, Marrone et al.), dimension-generic (2D and 3D).
//!
//! The data flow of a run: [`case::Case`] (parsed and validated TOML) →
//! [`geometry::build`] (particles, EOS, domain) → [`scheme::build_model`] (options
//! resolved once into a monomorphised [`equations::Scheme`]) → [`simulation::Simulation`]
//! stepping with an [`integrator`] → [`diagnostics`] and [`output`], driven to its end
//! with its run folder by [`run::Run`].

pub mod boundary;
pub mod case;
pub mod diagnostics;
pub mod diffusion;
pub mod domain;
pub mod eos;
pub mod equations;
pub mod error;
pub mod free_surface;
pub mod geometry;
pub mod integrator;
pub mod kernel;
pub mod neighbours;
pub mod output;
pub mod particles;
pub mod renormalisation;
pub mod restart;
pub mod run;
pub mod scheme;
pub mod shifting;
pub mod simulation;
pub mod timestep;
pub mod viscosity;

pub use case::Case;
pub use error::{Result, SphError};
pub use particles::{Kind, Particles, Vector};
pub use simulation::Simulation;
