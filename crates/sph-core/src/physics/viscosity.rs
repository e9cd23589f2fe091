//! Viscous term of the momentum equation:
//! `(K/ρ_i) Σ_j π_ij ∇_i W_ij V_j`, `π_ij = (u_j-u_i)·(x_j-x_i) / (|x_j-x_i|² + η²)`.
//!
//! - Artificial viscosity (Monaghan 1992, in the δ-SPH form of Antuono et al. 2010):
//!   `K = α h c0 ρ0`, α typically 0.01 to 0.1.
//! - Physical viscosity (Monaghan & Gingold 1983; Colagrossi et al. 2013):
//!   `K = 2(n+2) μ`, which yields `μ∇²u` for divergence-free flow in n dimensions.
//!
//! The term is central (along x_ij) and antisymmetric in the pair, so it conserves
//! linear and angular momentum; its power is never positive.

/// A viscous model; `Inviscid` removes the term from the pair loop at compile time.
pub trait Viscosity: Copy + Send + Sync + 'static {
    const ACTIVE: bool = true;
    /// The constant K.
    fn k(&self) -> f64;
}

/// No viscous term (K = 0).
#[derive(Debug, Clone, Copy)]
pub struct Inviscid;

/// A viscous term with constant K (artificial or physical: only K differs).
#[derive(Debug, Clone, Copy)]
pub struct Viscous {
    pub k: f64,
}

impl Viscosity for Inviscid {
    const ACTIVE: bool = false;
    fn k(&self) -> f64 {
        0.0
    }
}

impl Viscosity for Viscous {
    fn k(&self) -> f64 {
        self.k
    }
}

/// `K = α h c0 ρ0`.
pub fn artificial_k(alpha: f64, h: f64, c0: f64, rho0: f64) -> f64 {
    alpha * h * c0 * rho0
}

/// `K = 2(n+2) μ`.
pub fn physical_k(mu: f64, dim: usize) -> f64 {
    2.0 * (dim as f64 + 2.0) * mu
}

/// The kinematic viscosity a term with constant K stands for: `ν = K / (2(n+2) ρ0)`.
pub fn equivalent_nu(k: f64, dim: usize, rho0: f64) -> f64 {
    k / (2.0 * (dim as f64 + 2.0) * rho0)
}
