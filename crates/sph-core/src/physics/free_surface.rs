//! Free-surface detection (Marrone, Colagrossi, Le Touzé & Graziani 2010, "Fast
//! free-surface detection and level-set function definition in SPH solvers",
//! J. Comput. Phys. 229:3652; docs/theory.md §8).
//!
//! - `λ_i`, the smallest eigenvalue of `B_i = Σ_j (x_j - x_i) ⊗ ∇_i W_ij V_j`, is about 1
//!   inside the fluid, about 0.5 at the surface and about 0 for an isolated particle.
//! - `λ_i <= 0.2`: surface. `λ_i > 0.75`: interior.
//! - In between, the scan-region test decides. With the normal `n_i = ν_i/|ν_i|`,
//!   `ν_i = -B_i⁻¹ ∇Γ_i`, `∇Γ_i = Σ_j ∇_i W_ij V_j`, and `T = x_i + h n_i`, a neighbour j
//!   occupies the region if `|x_ji| >= √2 h` and `|x_j - T| < h`, or if `|x_ji| < √2 h` and
//!   x_j lies in the 90° cone about n_i (in 2D, the diamond `|n·(x_j-T)| + |τ·(x_j-T)| < h`).
//!   An empty region means surface.
//! - The radii assume the support R = 2h and are scaled by R/2h for wider kernels.
//! - Wall particles take part in `B_i`, `∇Γ_i` and the scan region, so fluid along a
//!   wall is not taken for a free surface. Only fluid particles are classified.

use crate::domain::Domain;
use crate::neighbours::NeighbourList;
use crate::particles::{Kind, Particles, Vector};
use crate::physics::kernel::Kernel;
use crate::physics::renormalisation::{add_moment, guarded_inverse, symmetrise};
use nalgebra::{Matrix3, SMatrix};
use rayon::prelude::*;

/// `λ` at or below which a particle is on the surface without further test.
pub const SURFACE_LAMBDA: f64 = 0.2;
/// `λ` above which a particle is inside the fluid without further test.
pub const INTERIOR_LAMBDA: f64 = 0.75;

/// The classification of every particle, in the current particle order.
#[derive(Debug, Clone, Default)]
pub struct FreeSurface<const D: usize> {
    /// Smallest eigenvalue of `B_i` (0 for walls).
    pub lambda: Vec<f64>,
    /// Unit outward normal estimate `n_i` (zero for walls and where `∇Γ_i` vanishes).
    pub normal: Vec<Vector<D>>,
    /// Whether the particle is on the free surface (fluid only).
    pub on_surface: Vec<bool>,
    /// Whether the particle is on or near the surface: on it, `λ <= 0.75`, or with a
    /// surface particle within its kernel support (fluid only).
    pub near: Vec<bool>,
}

/// Smallest eigenvalue of a symmetric 2×2 or 3×3 matrix.
fn min_eigenvalue<const D: usize>(b: &SMatrix<f64, D, D>) -> f64 {
    match D {
        2 => {
            let (a, c, d) = (b[(0, 0)], b[(0, 1)], b[(1, 1)]);
            0.5 * (a + d) - (0.25 * (a - d).powi(2) + c * c).sqrt()
        }
        3 => Matrix3::from_fn(|r, c| b[(r, c)])
            .symmetric_eigenvalues()
            .min(),
        _ => unreachable!("free-surface detection is implemented for 2 and 3 dimensions"),
    }
}

/// The neighbour sums one particle's classification needs: `B_i` and `∇Γ_i`.
#[derive(Debug, Clone, Copy)]
pub struct Moments<const D: usize> {
    pub b: SMatrix<f64, D, D>,
    pub grad_gamma: Vector<D>,
}

impl<const D: usize> Moments<D> {
    pub fn zero() -> Self {
        Self {
            b: SMatrix::zeros(),
            grad_gamma: Vector::zeros(),
        }
    }

    /// Adds neighbour j at `x_ji = x_j - x_i` with `∇_i W_ij V_j = -x_ji f`,
    /// `f = W'(r)/r V_j` (only the upper triangle of `B_i`, see [`Moments::symmetrised`]).
    #[inline(always)]
    pub fn add_radial(&mut self, x_ji: &Vector<D>, f: f64) {
        add_moment(&mut self.b, x_ji, f);
        self.grad_gamma -= x_ji * f;
    }

    /// The sums with the lower triangle of `B_i` filled from the upper one.
    pub fn symmetrised(mut self) -> Self {
        symmetrise(&mut self.b);
        self
    }
}

/// Detects the free surface at the current state.
pub fn detect<const D: usize, K: Kernel>(
    kernel: &K,
    particles: &Particles<D>,
    list: &NeighbourList<D>,
    domain: &Domain<D>,
) -> FreeSurface<D> {
    let volume = particles.volumes();
    let moments: Vec<Moments<D>> = (0..particles.len())
        .into_par_iter()
        .map(|i| {
            let mut m = Moments::zero();
            if particles.kind[i] != Kind::Fluid {
                return m;
            }
            let xi = particles.x[i];
            for j in list.of(i) {
                // ∇_i W_ij = x_ij W'(r)/r = -x_ji W'(r)/r, zero beyond the support
                let x_ji = domain.separation(&particles.x[j], &xi);
                m.add_radial(&x_ji, kernel.dw_over_r(x_ji.norm()) * volume[j]);
            }
            m.symmetrised()
        })
        .collect();
    classify(kernel, particles, list, domain, &moments)
}

/// Classifies every fluid particle from its [`Moments`] (walls get `λ = 0`, no normal,
/// and are neither on nor near the surface). Only the particles with
/// `0.2 < λ <= 0.75` scan their neighbours; `near` is spread from the surface
/// particles to the fluid within their support (the lists are symmetric).
pub fn classify<const D: usize, K: Kernel>(
    kernel: &K,
    particles: &Particles<D>,
    list: &NeighbourList<D>,
    domain: &Domain<D>,
    moments: &[Moments<D>],
) -> FreeSurface<D> {
    let (support, h) = (kernel.radius(), kernel.h());
    let scale = support / (2.0 * h);
    let (near, reach) = (std::f64::consts::SQRT_2 * h * scale, h * scale);
    let rows: Vec<(f64, Vector<D>, bool)> = (0..particles.len())
        .into_par_iter()
        .map(|i| {
            if particles.kind[i] != Kind::Fluid {
                return (0.0, Vector::zeros(), false);
            }
            let m = &moments[i];
            let lambda = min_eigenvalue(&m.b);
            let nu = -(guarded_inverse(&m.b) * m.grad_gamma);
            let n = if nu.norm() > 0.0 {
                nu.normalize()
            } else {
                Vector::zeros()
            };
            let xi = particles.x[i];
            let on_surface = lambda <= SURFACE_LAMBDA
                || (lambda <= INTERIOR_LAMBDA
                    && !list.of(i).any(|j| {
                        let x_ji = domain.separation(&particles.x[j], &xi);
                        x_ji.norm() < support && occupies(&x_ji, &n, near, reach)
                    }));
            (lambda, n, on_surface)
        })
        .collect();
    let mut out = FreeSurface::default();
    for (lambda, n, s) in rows {
        out.lambda.push(lambda);
        out.normal.push(n);
        out.on_surface.push(s);
    }
    out.near = (0..particles.len())
        .map(|i| particles.kind[i] == Kind::Fluid && out.lambda[i] <= INTERIOR_LAMBDA)
        .collect();
    for i in (0..particles.len()).filter(|&i| out.on_surface[i]) {
        for &j in list.fluid(i) {
            let j = j as usize;
            if domain.separation(&particles.x[j], &particles.x[i]).norm() < support {
                out.near[j] = true;
            }
        }
    }
    out
}

/// Whether a neighbour at `x_ji` from particle i lies in i's scan region about `n`.
fn occupies<const D: usize>(x_ji: &Vector<D>, n: &Vector<D>, near: f64, reach: f64) -> bool {
    let r = x_ji.norm();
    if r >= near {
        return (x_ji - n * reach).norm() < reach;
    }
    if D == 2 {
        // the square (diamond) with vertices x_i, T + h n and T ± h τ
        let (a, b) = (n.dot(x_ji) - reach, n[0] * x_ji[1] - n[1] * x_ji[0]);
        return a.abs() + b.abs() < reach;
    }
    // 3D: the 90° cone about n
    r > 0.0 && n.dot(x_ji) > r * std::f64::consts::FRAC_1_SQRT_2
}
