//! Density diffusion: the `δ h c0 D_i` term added to the continuity equation,
//! `D_i = 2 Σ_j ψ_ij · ∇_i W_ij V_j` (fluid neighbours only).
//!
//! | variant | ψ_ij | hydrostatics at the free surface |
//! |---|---|---|
//! | none | 0 | — |
//! | Molteni & Colagrossi 2009 (CPC 180:861) | (ρ_j-ρ_i) (x_j-x_i)/r² | inconsistent |
//! | Ferrari et al. 2009 (Comput. Fluids 38:1203) | (ρ_j-ρ_i) (x_j-x_i)/(2h r) | inconsistent |
//! | δ-SPH, Antuono et al. 2010 (CPC 181:532) | [(ρ_j-ρ_i) - ½(⟨∇ρ⟩^L_j+⟨∇ρ⟩^L_i)·(x_j-x_i)] (x_j-x_i)/r² | consistent |
//!
//! With `∇_i W_ij = x_ij W'/r` and `x_j - x_i = -x_ij`, every ψ·∇W reduces to a scalar
//! times `F = W'/r`, computed in [`DensityDiffusion::psi_dot_grad`]. Each ψ is symmetric in
//! (i, j), so `Σ_i V_i D_i = 0`: the term moves mass-weighted density around without
//! creating any. `r²` carries the usual regularisation `r² + η²`, `η² = 0.01 h²`.

use crate::particles::Vector;

/// The geometry of one pair, computed once in the pair loop and shared by its terms.
#[derive(Debug, Clone, Copy)]
pub struct Pair<'a, const D: usize> {
    /// `x_i - x_j`.
    pub x_ij: &'a Vector<D>,
    pub r: f64,
    pub r2: f64,
    /// `1/(r² + η²)`.
    pub inv_r2_reg: f64,
    /// `W'(r)/r`.
    pub f: f64,
}

/// One density-diffusion variant; `NoDiffusion` makes the whole term vanish at compile time.
pub trait DensityDiffusion<const D: usize>: Copy + Send + Sync + 'static {
    /// False for [`NoDiffusion`]: the pair loop then drops the term.
    const ACTIVE: bool = true;
    /// Whether the renormalised density gradient ⟨∇ρ⟩^L must be computed first.
    const NEEDS_GRADIENT: bool = false;
    /// The coefficient δ.
    fn delta(&self) -> f64;
    /// `ψ_ij · ∇_i W_ij` for the pair `pair` (gradients ⟨∇ρ⟩^L of i and j when the
    /// variant needs them).
    fn psi_dot_grad(
        &self,
        rho_i: f64,
        rho_j: f64,
        grad_i: &Vector<D>,
        grad_j: &Vector<D>,
        pair: &Pair<D>,
    ) -> f64;
}

/// No density diffusion (standard WCSPH).
#[derive(Debug, Clone, Copy)]
pub struct NoDiffusion;

/// Molteni & Colagrossi (2009).
#[derive(Debug, Clone, Copy)]
pub struct MolteniColagrossi {
    pub delta: f64,
}

/// Ferrari, Dumbser, Toro & Armanini (2009), written with the factor 2 of `D_i`:
/// their original coefficient corresponds to δ = 0.5.
#[derive(Debug, Clone, Copy)]
pub struct Ferrari {
    pub delta: f64,
    pub h: f64,
}

/// δ-SPH of Antuono, Colagrossi, Marrone & Molteni (2010).
#[derive(Debug, Clone, Copy)]
pub struct DeltaSph {
    pub delta: f64,
}

impl<const D: usize> DensityDiffusion<D> for NoDiffusion {
    const ACTIVE: bool = false;
    fn delta(&self) -> f64 {
        0.0
    }
    #[inline(always)]
    fn psi_dot_grad(&self, _: f64, _: f64, _: &Vector<D>, _: &Vector<D>, _: &Pair<D>) -> f64 {
        0.0
    }
}

impl<const D: usize> DensityDiffusion<D> for MolteniColagrossi {
    fn delta(&self) -> f64 {
        self.delta
    }
    #[inline(always)]
    fn psi_dot_grad(
        &self,
        rho_i: f64,
        rho_j: f64,
        _: &Vector<D>,
        _: &Vector<D>,
        q: &Pair<D>,
    ) -> f64 {
        // (ρj-ρi)(-x_ij)·x_ij f / r² = -(ρj-ρi) f r²/r²_reg
        -(rho_j - rho_i) * q.f * q.r2 * q.inv_r2_reg
    }
}

impl<const D: usize> DensityDiffusion<D> for Ferrari {
    fn delta(&self) -> f64 {
        self.delta
    }
    #[inline(always)]
    fn psi_dot_grad(
        &self,
        rho_i: f64,
        rho_j: f64,
        _: &Vector<D>,
        _: &Vector<D>,
        q: &Pair<D>,
    ) -> f64 {
        // (ρj-ρi)(-x_ij)·x_ij f/(2h r) = -(ρj-ρi) f r/(2h)
        -(rho_j - rho_i) * q.f * q.r / (2.0 * self.h)
    }
}

impl<const D: usize> DensityDiffusion<D> for DeltaSph {
    const NEEDS_GRADIENT: bool = true;
    fn delta(&self) -> f64 {
        self.delta
    }
    #[inline(always)]
    fn psi_dot_grad(
        &self,
        rho_i: f64,
        rho_j: f64,
        grad_i: &Vector<D>,
        grad_j: &Vector<D>,
        q: &Pair<D>,
    ) -> f64 {
        // [(ρj-ρi) + ½(gi+gj)·x_ij] (-x_ij)·x_ij f / r²
        let jump = rho_j - rho_i + 0.5 * (grad_i + grad_j).dot(q.x_ij);
        -jump * q.f * q.r2 * q.inv_r2_reg
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// ψ_ij·∇_iW_ij must equal ψ_ji·∇_jW_ji (both ψ and ∇W flip sign), which gives Σ V_i D_i = 0.
    #[test]
    fn every_variant_is_pair_symmetric() {
        let gi = Vector::<2>::new(0.3, -1.2);
        let gj = Vector::<2>::new(-0.7, 0.4);
        let x = Vector::<2>::new(0.013, -0.021);
        let mx = -x;
        let r2 = x.norm_squared();
        let pair = |x_ij, reg: f64| Pair {
            x_ij,
            r: r2.sqrt(),
            r2,
            inv_r2_reg: 1.0 / (r2 * reg),
            f: -17.0,
        };
        let check = |a: f64, b: f64| assert!((a - b).abs() < 1e-12 * a.abs().max(1.0), "{a} {b}");
        let mc = MolteniColagrossi { delta: 0.1 };
        check(
            mc.psi_dot_grad(1000.0, 1003.0, &gi, &gj, &pair(&x, 1.1)),
            -mc.psi_dot_grad(1003.0, 1000.0, &gj, &gi, &pair(&mx, 1.1)),
        );
        let fe = Ferrari {
            delta: 0.1,
            h: 0.02,
        };
        check(
            fe.psi_dot_grad(1000.0, 1003.0, &gi, &gj, &pair(&x, 1.0)),
            -fe.psi_dot_grad(1003.0, 1000.0, &gj, &gi, &pair(&mx, 1.0)),
        );
        let ds = DeltaSph { delta: 0.1 };
        check(
            ds.psi_dot_grad(1000.0, 1003.0, &gi, &gj, &pair(&x, 1.0)),
            -ds.psi_dot_grad(1003.0, 1000.0, &gj, &gi, &pair(&mx, 1.0)),
        );
    }

    /// For a linear density field with its exact gradient, the δ-SPH ψ vanishes pair by pair;
    /// the Molteni-Colagrossi ψ does not.
    #[test]
    fn delta_sph_vanishes_on_a_linear_field() {
        let g = Vector::<2>::new(0.0, -11.0);
        let xi = Vector::<2>::new(0.1, 0.3);
        let xj = Vector::<2>::new(0.12, 0.29);
        let rho = |x: &Vector<2>| 1000.0 + g.dot(x);
        let x_ij = xi - xj;
        let r2 = x_ij.norm_squared();
        let pair = Pair {
            x_ij: &x_ij,
            r: r2.sqrt(),
            r2,
            inv_r2_reg: 1.0 / r2,
            f: -3.0,
        };
        let ds = DeltaSph { delta: 0.1 };
        let v = ds.psi_dot_grad(rho(&xi), rho(&xj), &g, &g, &pair);
        assert!(v.abs() < 1e-10, "{v}");
        let mc = MolteniColagrossi { delta: 0.1 };
        assert!(mc.psi_dot_grad(rho(&xi), rho(&xj), &g, &g, &pair).abs() > 0.01);
    }
}
