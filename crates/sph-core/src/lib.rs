//! deltasph core: a weakly-compressible SPH solver of the δ-SPH family
//! (Antuono, Colagrossi, Marrone et al.), dimension-generic (2D and 3D).
//!
//! The data flow of a run: [`case::Case`] (parsed and validated TOML) →
//! [`geometry::build`] (particles, EOS, domain) → [`scheme::resolve`] (options resolved
//! once into a monomorphised [`scheme::Scheme`]) → [`simulation::Simulation`] stepping
//! with a [`time::integrator`] → [`diagnostics`] and [`io`], driven to its end with its
//! run folder by [`run::Run`].
//!
//! Modules by concept, each depending only on those listed before it: [`particles`],
//! [`domain`] → [`decomposition`] → [`distributed`], [`neighbours`] → [`physics`] → [`boundary`] → [`waves`] → [`case`] → [`scheme`],
//! [`geometry`], [`forcing`], [`motion`] → [`time`], [`diagnostics`] → [`simulation`] → [`io`] → [`run`], [`postprocess`].

pub mod allocator;
pub mod boundary;
pub mod case;
pub mod decomposition;
pub mod diagnostics;
pub mod distributed;
pub mod domain;
pub mod error;
pub mod forcing;
pub mod geometry;
pub mod io;
pub mod motion;
pub mod neighbours;
pub mod particles;
pub mod physics;
pub mod postprocess;
pub mod run;
pub mod scheme;
pub mod simulation;
pub mod time;
pub mod waves;

pub use case::Case;
pub use error::{Result, SphError};
pub use particles::{Kind, Particles, Vector};
pub use simulation::Simulation;
