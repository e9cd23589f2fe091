//! Renormalised density gradient (Randles & Libersky 1996; used by δ-SPH, Antuono et al. 2010):
//!
//! `⟨∇ρ⟩^L_i = Σ_j (ρ_j - ρ_i) L_i ∇_i W_ij V_j`,
//! `L_i = [ Σ_j (x_j - x_i) ⊗ ∇_i W_ij V_j ]⁻¹`.
//!
//! The correction makes the gradient exact for linear fields whatever the neighbour
//! set, which is what keeps δ-SPH hydrostatic at the free surface. Where the
//! matrix is nearly singular (isolated or nearly isolated particles) the inverse
//! is replaced by the identity. Wall particles take part with their extrapolated
//! density. Only fluid particles get a gradient; walls keep zero.

use crate::domain::Domain;
use crate::kernel::Kernel;
use crate::neighbours::NeighbourList;
use crate::particles::{Kind, Particles, Vector};
use nalgebra::SMatrix;
use rayon::prelude::*;

/// Below this determinant of the (dimensionless, ≈ I in the bulk) matrix the
/// renormalisation falls back to the identity.
const SINGULAR_DET: f64 = 1e-3;

/// `L_i = B_i⁻¹`, or the identity where the matrix cannot be trusted (2×2 and 3×3 by cofactors).
pub fn guarded_inverse<const D: usize>(b: &SMatrix<f64, D, D>) -> SMatrix<f64, D, D> {
    let mut inv = SMatrix::<f64, D, D>::zeros();
    let det = match D {
        2 => {
            let det = b[(0, 0)] * b[(1, 1)] - b[(0, 1)] * b[(1, 0)];
            inv[(0, 0)] = b[(1, 1)];
            inv[(0, 1)] = -b[(0, 1)];
            inv[(1, 0)] = -b[(1, 0)];
            inv[(1, 1)] = b[(0, 0)];
            det
        }
        3 => {
            // cofactor(r, c) with cyclic indices carries its sign for 3×3
            let cof = |r: usize, c: usize| {
                let (r1, r2, c1, c2) = ((r + 1) % 3, (r + 2) % 3, (c + 1) % 3, (c + 2) % 3);
                b[(r1, c1)] * b[(r2, c2)] - b[(r1, c2)] * b[(r2, c1)]
            };
            for r in 0..3 {
                for c in 0..3 {
                    inv[(c, r)] = cof(r, c);
                }
            }
            (0..3).map(|c| b[(0, c)] * cof(0, c)).sum()
        }
        _ => unreachable!("renormalisation is implemented for 2 and 3 dimensions"),
    };
    if det.abs() < SINGULAR_DET || !det.is_finite() {
        return SMatrix::identity();
    }
    inv / det
}

/// Fills `grad` with ⟨∇ρ⟩^L for every fluid particle (zero for walls).
pub fn density_gradient<const D: usize, K: Kernel>(
    kernel: &K,
    particles: &Particles<D>,
    list: &NeighbourList<D>,
    domain: &Domain<D>,
    grad: &mut Vec<Vector<D>>,
) {
    grad.resize(particles.len(), Vector::zeros());
    grad.par_iter_mut().enumerate().for_each(|(i, g)| {
        *g = Vector::zeros();
        if particles.kind[i] != Kind::Fluid {
            return;
        }
        let xi = particles.x[i];
        let rho_i = particles.rho[i];
        let mut b = SMatrix::<f64, D, D>::zeros();
        let mut sum = Vector::<D>::zeros();
        for &j in list.of(i) {
            let j = j as usize;
            let x_ij = domain.separation(&xi, &particles.x[j]);
            let f = kernel.dw_over_r(x_ij.norm());
            let vj = particles.mass[j] / particles.rho[j];
            let grad_w = x_ij * (f * vj);
            // (x_j - x_i) ⊗ ∇W V_j = -x_ij ⊗ ∇W V_j
            b -= x_ij * grad_w.transpose();
            sum += grad_w * (particles.rho[j] - rho_i);
        }
        *g = guarded_inverse(&b) * sum;
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Matrix2, Matrix3};

    #[test]
    fn inverse_matches_nalgebra_and_guards_singular_matrices() {
        let m2 = Matrix2::new(1.1, 0.2, -0.3, 0.9);
        assert!((guarded_inverse(&m2) * m2 - Matrix2::identity()).norm() < 1e-14);
        let m3 = Matrix3::new(1.0, 0.1, 0.2, -0.1, 0.8, 0.05, 0.3, 0.0, 1.2);
        assert!((guarded_inverse(&m3) - m3.try_inverse().unwrap()).norm() < 1e-13);
        let singular = Matrix2::new(1.0, 2.0, 0.5, 1.0);
        assert_eq!(guarded_inverse(&singular), Matrix2::identity());
    }
}
