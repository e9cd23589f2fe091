//! The closure fields of δ-LES-SPH (Di Mascio, Antuono, Colagrossi & Marrone 2017,
//! Phys. Fluids 29:035102; Antuono, Marrone, Di Mascio & Colagrossi 2021, Phys. Fluids
//! 33:015102; docs/theory.md §11), gathered per particle in one neighbour pass:
//!
//! ```text
//! L_i   = [Σ_j (x_j - x_i) ⊗ ∇_iW_ij V_j]⁻¹
//! ∇u_i  = Σ_j (u_j - u_i) ⊗ (L_i ∇_iW_ij) V_j,   D_i = ½(∇u_i + ∇u_iᵀ),   ‖D_i‖ = √(2 D_i:D_i)
//! ν_T,i = (C_S l)² ‖D_i‖,   ν_δ,i = (C_δ l)² ‖D_i‖
//! ⟨∇ρ⟩_i = Σ_j (ρ_j - ρ_i) L_i ∇_iW_ij V_j
//! δũ_i  = -A_sh Σ_j [1 + R (W_ij/W(Δx))⁴] ∇_iW_ij V_j,   A_sh = a h U_max,   R = 0.2
//! δu_i  = δũ_i min(1, (U_max/2)/|δũ_i|)
//! ```
//!
//! The shifting prefactor is an open point of the papers (docs/theory.md §11.4): `a = 2` is
//! one public reading, `a = 4` the δ+-SPH shift `CFL·Ma (2h)²` per step as a velocity;
//! the default `a = 8` is what the Taylor-Green decay asks for (docs/validation/les.md:
//! the largest energy error over t ∈ [0, 1] at L/Δx = 50 and 100 is 22% and 7.2% with
//! a = 2, 8.6% and 2.8% with 4, 3.0% and 1.3% with 8).
//!
//! The pair terms that use them are in [`crate::scheme::les`]; there the eddy viscosity
//! and diffusivity of a pair are harmonic means, [`harmonic_mean`]. The sums run over
//! fluid neighbours: δ-LES-SPH is offered for periodic, wall-free flows (the case
//! checks refuse the rest).

use crate::domain::Domain;
use crate::neighbours::NeighbourList;
use crate::particles::{Kind, Particles, Vector};
use crate::physics::kernel::Kernel;
use crate::physics::renormalisation::{add_moment, guarded_inverse, symmetrise};
use crate::physics::shifting::ANTI_CLUSTERING;
use nalgebra::SMatrix;
use rayon::prelude::*;

/// The constants of the closure, resolved from the case.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Constants {
    /// C_S of the eddy viscosity.
    pub smagorinsky: f64,
    /// C_δ of the diffusion coefficient.
    pub diffusion: f64,
    /// The LES length l \[m\].
    pub length: f64,
    /// U_max [m/s] of the shifting and its cap.
    pub velocity: f64,
    /// The factor a of `A_sh = a h U_max`.
    pub shifting: f64,
    /// The lattice spacing Δx of the anti-clustering term.
    pub dx: f64,
}

/// Per-particle fields of one evaluation (zero for walls).
#[derive(Debug, Clone, Default)]
pub struct Fields<const D: usize> {
    /// Eddy viscosity ν_T [m²/s].
    pub nu_t: Vec<f64>,
    /// Diffusion coefficient ν_δ [m²/s].
    pub nu_delta: Vec<f64>,
    /// Renormalised density gradient ⟨∇ρ⟩.
    pub grad_rho: Vec<Vector<D>>,
    /// Capped shifting velocity δu.
    pub shift: Vec<Vector<D>>,
}

/// `‖D‖ = √(2 D:D)` of the strain rate `D = ½(G + Gᵀ)` of a velocity gradient G.
pub fn strain_rate_norm<const D: usize>(grad_u: &SMatrix<f64, D, D>) -> f64 {
    let strain = (grad_u + grad_u.transpose()) * 0.5;
    (2.0 * strain.component_mul(&strain).sum()).sqrt()
}

/// The harmonic mean `2ab/(a+b)` of two non-negative coefficients, 0 where both are 0
/// (no strain on either side).
#[inline(always)]
pub fn harmonic_mean(a: f64, b: f64) -> f64 {
    let sum = a + b;
    if sum > 0.0 {
        2.0 * a * b / sum
    } else {
        0.0
    }
}

/// `δũ` capped at `|δu| <= cap`.
#[inline(always)]
fn capped<const D: usize>(shift: Vector<D>, cap: f64) -> Vector<D> {
    let norm = shift.norm();
    if norm > cap {
        shift * (cap / norm)
    } else {
        shift
    }
}

/// The raw pair sums of one particle.
struct Sums<const D: usize> {
    /// `Σ_j (x_j - x_i) ⊗ ∇_iW_ij V_j`.
    moment: SMatrix<f64, D, D>,
    /// `Σ_j (u_j - u_i) ⊗ ∇_iW_ij V_j`.
    velocity: SMatrix<f64, D, D>,
    /// `Σ_j (ρ_j - ρ_i) ∇_iW_ij V_j`.
    density: Vector<D>,
    /// `Σ_j [1 + R (W_ij/W(Δx))⁴] ∇_iW_ij V_j`.
    shifting: Vector<D>,
}

/// One evaluation's fields at the current state; `volume[j] = m_j/ρ_j`, `h` the
/// smoothing length.
pub fn compute<const D: usize, K: Kernel>(
    kernel: &K,
    c: &Constants,
    particles: &Particles<D>,
    volume: &[f64],
    list: &NeighbourList<D>,
    domain: &Domain<D>,
    fields: &mut Fields<D>,
) {
    let n = particles.len();
    fields.nu_t.resize(n, 0.0);
    fields.nu_delta.resize(n, 0.0);
    fields.grad_rho.resize(n, Vector::zeros());
    fields.shift.resize(n, Vector::zeros());
    let eddy = (c.smagorinsky * c.length).powi(2);
    let diffusive = (c.diffusion * c.length).powi(2);
    let a_sh = c.shifting * kernel.h() * c.velocity;
    let cap = 0.5 * c.velocity;
    let w_dx = kernel.w(c.dx);
    fields
        .nu_t
        .par_iter_mut()
        .zip(fields.nu_delta.par_iter_mut())
        .zip(fields.grad_rho.par_iter_mut())
        .zip(fields.shift.par_iter_mut())
        .enumerate()
        .for_each(|(i, (((nu_t, nu_delta), grad_rho), shift))| {
            if particles.kind[i] != Kind::Fluid {
                (*nu_t, *nu_delta) = (0.0, 0.0);
                (*grad_rho, *shift) = (Vector::zeros(), Vector::zeros());
                return;
            }
            let s = sums(kernel, w_dx, i, particles, volume, list, domain);
            let l = guarded_inverse(&s.moment);
            // ∇u = Σ du ⊗ (L ∇W V) = (Σ du ⊗ ∇W V) Lᵀ, and L is symmetric
            let strain = strain_rate_norm(&(s.velocity * l));
            (*nu_t, *nu_delta) = (eddy * strain, diffusive * strain);
            *grad_rho = l * s.density;
            *shift = capped(s.shifting * -a_sh, cap);
        });
}

/// The pair sums of fluid particle i over its fluid neighbours, with
/// `∇_iW_ij V_j = -x_ji f`, `f = W'(r)/r V_j`.
#[inline(always)]
fn sums<const D: usize, K: Kernel>(
    kernel: &K,
    w_dx: f64,
    i: usize,
    p: &Particles<D>,
    volume: &[f64],
    list: &NeighbourList<D>,
    domain: &Domain<D>,
) -> Sums<D> {
    let (xi, ui, rho_i) = (p.x[i], p.u[i], p.rho[i]);
    let mut s = Sums {
        moment: SMatrix::zeros(),
        velocity: SMatrix::zeros(),
        density: Vector::zeros(),
        shifting: Vector::zeros(),
    };
    for &j in list.fluid(i) {
        let j = j as usize;
        let x_ji = domain.separation(&p.x[j], &xi);
        let r = x_ji.norm();
        let f = kernel.dw_over_r(r) * volume[j];
        let grad = x_ji * -f;
        add_moment(&mut s.moment, &x_ji, f);
        s.velocity += (p.u[j] - ui) * grad.transpose();
        s.density += grad * (p.rho[j] - rho_i);
        let ratio = kernel.w(r) / w_dx;
        s.shifting += grad * (1.0 + ANTI_CLUSTERING * ratio.powi(4));
    }
    symmetrise(&mut s.moment);
    s
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::physics::kernel::WendlandC2;
    use std::f64::consts::PI;

    /// A periodic unit square on an n×n lattice (ρ = 1, h = 2Δx) with velocity `u(x)`.
    pub(crate) fn periodic_square(
        n: usize,
        u: impl Fn(&Vector<2>) -> Vector<2>,
    ) -> (Particles<2>, NeighbourList<2>, Domain<2>, WendlandC2) {
        let dx = 1.0 / n as f64;
        let domain = Domain::new(Vector::zeros(), Vector::repeat(1.0), [true, true]);
        let kernel = WendlandC2::new(2.0 * dx, 2);
        let mut p = Particles::<2>::default();
        for k in 0..n * n {
            let x = Vector::<2>::new((k % n) as f64 + 0.5, (k / n) as f64 + 0.5) * dx;
            p.push(Kind::Fluid, x, u(&x), 1.0, dx * dx);
        }
        let (list, _) = NeighbourList::build(&mut p, &domain, kernel.radius(), 0.0);
        (p, list, domain, kernel)
    }

    pub(crate) fn constants(n: usize) -> Constants {
        Constants {
            smagorinsky: 0.12,
            diffusion: 6.0,
            length: 1.0 / n as f64,
            velocity: 1.0,
            shifting: 8.0,
            dx: 1.0 / n as f64,
        }
    }

    /// The largest error of ‖D‖ against 2πU|cos 2πy| for u = (U sin 2πy, 0), over 2πU.
    fn strain_error(n: usize) -> f64 {
        let (p, list, domain, kernel) =
            periodic_square(n, |x| Vector::<2>::new((2.0 * PI * x[1]).sin(), 0.0));
        let c = constants(n);
        let mut fields = Fields::default();
        compute(&kernel, &c, &p, &p.volumes(), &list, &domain, &mut fields);
        let eddy = (c.smagorinsky * c.length).powi(2);
        (p.x.iter().zip(&fields.nu_t))
            .map(|(x, nu_t)| (nu_t / eddy - 2.0 * PI * (2.0 * PI * x[1]).cos().abs()).abs())
            .fold(0.0, f64::max)
            / (2.0 * PI)
    }

    /// ‖D‖ = √(2 D:D) of a shear u = (U sin 2πy, 0) is 2πU|cos 2πy| (the √2 convention:
    /// the other one is off by 41%). The renormalised gradient on the lattice (Wendland
    /// C2, h = 2Δx) underestimates the sine's slope at second order: measured 5.38e-3 at
    /// L/Δx = 64 and 1.35e-3 at 128 (ratio 3.99). The 10⁻³ target at 64 is below this
    /// discretisation error; the test holds 6e-3 at 64 and the order.
    #[test]
    fn strain_rate_norm_of_a_shear_converges_at_second_order() {
        let (coarse, fine) = (strain_error(64), strain_error(128));
        assert!(coarse < 6e-3, "error {coarse:e} at L/Δx = 64");
        assert!(
            coarse / fine > 3.5,
            "errors {coarse:e}, {fine:e}: order below 2"
        );
    }

    /// At zero strain (a uniform stream) ν_T = ν_δ = 0 and their harmonic means are 0, not
    /// NaN; the shifting velocity of a lattice vanishes.
    #[test]
    fn uniform_flow_has_no_closure_and_no_shift() {
        let (p, list, domain, kernel) = periodic_square(32, |_| Vector::<2>::new(0.7, -0.2));
        let mut fields = Fields::default();
        compute(
            &kernel,
            &constants(32),
            &p,
            &p.volumes(),
            &list,
            &domain,
            &mut fields,
        );
        assert!(fields
            .nu_t
            .iter()
            .chain(&fields.nu_delta)
            .all(|&v| v.abs() < 1e-12));
        assert!(fields.shift.iter().all(|s| s.norm() < 1e-12));
        assert_eq!(harmonic_mean(0.0, 0.0), 0.0);
        assert_eq!(harmonic_mean(2.0, 0.0), 0.0);
        assert!((harmonic_mean(1.0, 3.0) - 1.5).abs() < 1e-15);
    }

    /// The cap: a large shifting sum is cut to |δu| = U_max/2, its direction kept.
    #[test]
    fn shifting_velocity_is_capped() {
        let v = capped(Vector::<2>::new(3.0, 4.0), 0.5);
        assert!((v - Vector::<2>::new(0.3, 0.4)).norm() < 1e-15);
        assert_eq!(
            capped(Vector::<2>::new(0.1, 0.0), 0.5),
            Vector::<2>::new(0.1, 0.0)
        );
    }
}
