//! What every fluid–fluid pair term of [`super::model::Scheme`] and
//! [`super::les::LesScheme`] starts from (docs/theory.md §1, §3): the separation
//! `x_ij = x_i - x_j` (minimum image along periodic axes), its length, `W'(r)/r` and
//! the kernel gradient weighted by the neighbour's volume, `∇_iW_ij V_j = x_ij W'(r)/r V_j`.

use crate::domain::Domain;
use crate::particles::Vector;
use crate::physics::diffusion::Pair;
use crate::physics::kernel::Kernel;

/// The kinematics of one pair, seen from particle i.
pub(crate) struct PairKinematics<const D: usize> {
    pub x_ij: Vector<D>,
    pub r2: f64,
    pub r: f64,
    /// `W'(r)/r`.
    pub f: f64,
    /// `∇_iW_ij V_j`.
    pub grad_w: Vector<D>,
}

impl<const D: usize> PairKinematics<D> {
    #[inline(always)]
    pub fn of<K: Kernel>(
        kernel: &K,
        domain: &Domain<D>,
        xi: &Vector<D>,
        xj: &Vector<D>,
        volume_j: f64,
    ) -> Self {
        let x_ij = domain.separation(xi, xj);
        let r2 = x_ij.norm_squared();
        let r = r2.sqrt();
        let f = kernel.dw_over_r(r);
        Self {
            x_ij,
            r2,
            r,
            f,
            grad_w: x_ij * (f * volume_j),
        }
    }

    /// The pair as the density-diffusion terms take it, with `1/(r² + η²)`.
    #[inline(always)]
    pub fn diffusion_pair(&self, inv_r2_reg: f64) -> Pair<'_, D> {
        Pair {
            x_ij: &self.x_ij,
            r: self.r,
            r2: self.r2,
            inv_r2_reg,
            f: self.f,
        }
    }
}
