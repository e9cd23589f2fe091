//! The semi-discrete δ-SPH equations (Antuono et al. 2010, CPC 181:532; SCHEME.md §4-5):
//!
//! ```text
//! dρ_i/dt = -ρ_i Σ_j (u_j - u_i)·∇_iW_ij V_j  +  δ h c0 D_i
//! du_i/dt = g - (1/ρ_i) Σ_j (p_j + p_i) ∇_iW_ij V_j + (K/ρ_i) Σ_j π_ij ∇_iW_ij V_j
//! dx_i/dt = u_i,     p_i = c0² (ρ_i - ρ0)
//! ```
//!
//! [`Scheme`] is generic over the kernel, the density diffusion and the viscosity,
//! so that each combination gets its own pair loop and unused terms compile away.
//! It is reached through the object-safe [`Model`] trait, whose methods run once
//! per evaluation, never per pair. Pair loops gather per particle (Rayon over
//! particles, no shared writes).

use crate::boundary::extrapolate_walls;
use crate::domain::Domain;
use crate::neighbours::NeighbourList;
use crate::particles::{Kind, Particles, Vector};
use crate::physics::diffusion::DensityDiffusion;
use crate::physics::eos::LinearEos;
use crate::physics::free_surface::{self, FreeSurface};
use crate::physics::kernel::Kernel;
use crate::physics::renormalisation::density_gradient;
use crate::physics::shifting;
use crate::physics::viscosity::Viscosity;
use rayon::prelude::*;

/// Time derivatives of the particle state. `dx/dt = u` is not stored.
#[derive(Debug, Clone, Default)]
pub struct Rates<const D: usize> {
    /// Continuity without diffusion, `Q_ρ`.
    pub drho: Vec<f64>,
    /// Diffusive part `δ h c0 D_i` (zero when diffusion was not evaluated).
    pub drho_diff: Vec<f64>,
    /// Acceleration.
    pub du: Vec<Vector<D>>,
}

impl<const D: usize> Rates<D> {
    pub fn resize(&mut self, n: usize) {
        self.drho.resize(n, 0.0);
        self.drho_diff.resize(n, 0.0);
        self.du.resize(n, Vector::zeros());
    }

    /// Largest acceleration magnitude.
    pub fn max_acceleration(&self) -> f64 {
        self.du
            .par_iter()
            .map(|a| a.norm_squared())
            .reduce(|| 0.0, f64::max)
            .sqrt()
    }
}

/// Rates of change of the mechanical energy due to the dissipative terms (SCHEME.md §10).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Powers {
    /// Viscous power `P_V = Σ m_i u_i · (du_i/dt)_visc`, never positive.
    pub viscous: f64,
    /// Diffusive power `P_D = Σ m_i (p_i/ρ_i²) δ h c0 D_i`.
    pub diffusive: f64,
    /// Power exchanged with the dummy walls, `P_W = -Σ_i Σ_w V_i V_w p_w u_i·∇_iW_iw`.
    /// The extrapolated wall pressure is not derived from an energy, so the walls store
    /// and return energy like springs; the balance closes only with this term.
    pub wall: f64,
}

impl Powers {
    pub fn total(&self) -> f64 {
        self.viscous + self.diffusive + self.wall
    }
}

/// Physical constants every scheme shares.
#[derive(Debug, Clone, Copy)]
pub struct Physics<const D: usize> {
    pub eos: LinearEos,
    pub gravity: Vector<D>,
    /// 1 for no-slip walls (mirrored velocity in the viscous term), 0 for free-slip.
    pub wall_viscous_weight: f64,
}

/// What the integrators and diagnostics need from a resolved scheme.
pub trait Model<const D: usize>: Send + Sync {
    /// Fills `rates` at the current state: pressure from the EOS, wall extrapolation,
    /// the δ-SPH gradient pre-pass (only if the diffusion needs it and `with_diffusion`),
    /// then the pair loop. `rates.drho_diff` is written only when `with_diffusion`.
    fn evaluate(
        &mut self,
        particles: &mut Particles<D>,
        list: &NeighbourList<D>,
        domain: &Domain<D>,
        rates: &mut Rates<D>,
        with_diffusion: bool,
    );
    /// Pressure of the fluid (EOS) and of the walls (extrapolated) at the current
    /// state, without the pair loop: what output and probes need.
    fn update_pressure_field(
        &self,
        particles: &mut Particles<D>,
        list: &NeighbourList<D>,
        domain: &Domain<D>,
    );
    /// Free-surface detection (Marrone et al. 2010) at the current state.
    fn free_surface(
        &self,
        particles: &Particles<D>,
        list: &NeighbourList<D>,
        domain: &Domain<D>,
    ) -> FreeSurface<D>;
    /// Sets the particles (current order) where tensile instability control applies, or
    /// `None` to switch it off.
    fn set_tensile_control(&mut self, interior: Option<Vec<bool>>);
    /// δ+-SPH shifting displacements (see [`crate::physics::shifting`]), `cfl_ma = U_max Δt/h`.
    fn shift(
        &self,
        particles: &Particles<D>,
        list: &NeighbourList<D>,
        domain: &Domain<D>,
        surface: &FreeSurface<D>,
        dx: f64,
        cfl_ma: f64,
    ) -> Vec<Vector<D>>;
    /// Viscous and diffusive powers at the state of the last `evaluate` call.
    fn powers(
        &self,
        particles: &Particles<D>,
        list: &NeighbourList<D>,
        domain: &Domain<D>,
    ) -> Powers;
    /// Kernel value `W(r)`.
    fn w(&self, r: f64) -> f64;
    /// Kernel support radius R.
    fn support_radius(&self) -> f64;
    /// Whether any density diffusion is active.
    fn has_diffusion(&self) -> bool;
    fn physics(&self) -> &Physics<D>;
}

/// A fully resolved scheme: kernel `K`, density diffusion `Df`, viscosity `V`.
pub struct Scheme<const D: usize, K, Df, V> {
    pub kernel: K,
    pub diffusion: Df,
    pub viscosity: V,
    pub physics: Physics<D>,
    /// `δ h c0`, the prefactor of `D_i`.
    diffusion_scale: f64,
    /// `η² = 0.01 h²` regularising `1/r²`.
    eta2: f64,
    /// ⟨∇ρ⟩^L, allocated only when the diffusion needs it.
    grad: Vec<Vector<D>>,
    /// Tensile instability control (Sun et al. 2018): per particle, whether it is inside
    /// the fluid (not on or near the free surface); `None` when the control is off.
    interior: Option<Vec<bool>>,
}

/// Per-particle pair sums (before the prefactors).
struct Sums<const D: usize> {
    /// Σ (u_j - u_i)·∇W V_j
    divergence: f64,
    /// Σ (p_j + p_i) ∇W V_j
    pressure: Vector<D>,
    /// Σ π_ij ∇W V_j
    viscous: Vector<D>,
    /// Σ ψ_ij·∇W V_j over fluid neighbours
    diffusion: f64,
    /// Whether any fluid particle lies within the kernel support
    fluid_in_reach: bool,
}

impl<const D: usize, K: Kernel, Df: DensityDiffusion<D>, V: Viscosity> Scheme<D, K, Df, V> {
    pub fn new(kernel: K, diffusion: Df, viscosity: V, physics: Physics<D>) -> Self {
        let h = kernel.h();
        Self {
            kernel,
            diffusion,
            viscosity,
            physics,
            diffusion_scale: diffusion.delta() * h * physics.eos.c0,
            eta2: 0.01 * h * h,
            grad: Vec::new(),
            interior: None,
        }
    }

    /// The pair sums of fluid particle i; the diffusion sum only when `DIFF`.
    #[inline(always)]
    fn sums<const DIFF: bool>(
        &self,
        i: usize,
        p: &Particles<D>,
        list: &NeighbourList<D>,
        domain: &Domain<D>,
    ) -> Sums<D> {
        let xi = p.x[i];
        let ui = p.u[i];
        let (pi, rho_i) = (p.p[i], p.rho[i]);
        // Tensile instability control (Sun et al. 2018, SCHEME.md §9): an interior particle
        // in tension takes (p_j - p_i) instead of (p_j + p_i). Decided once per particle.
        let pi_pair = match &self.interior {
            Some(interior) if pi < 0.0 && interior[i] => -pi,
            _ => pi,
        };

        let zero = Vector::<D>::zeros();
        let grad_i = if DIFF && Df::NEEDS_GRADIENT {
            self.grad[i]
        } else {
            zero
        };
        let mut s = Sums {
            divergence: 0.0,
            pressure: zero,
            viscous: zero,
            diffusion: 0.0,
            fluid_in_reach: false,
        };
        for &j in list.of(i) {
            let j = j as usize;
            let x_ij = domain.separation(&xi, &p.x[j]);
            let r2 = x_ij.norm_squared();
            let f = self.kernel.dw_over_r(r2.sqrt());
            let vj = p.mass[j] / p.rho[j];
            let grad_w = x_ij * (f * vj);
            s.divergence += (p.u[j] - ui).dot(&grad_w);
            let fluid_j = p.kind[j] == Kind::Fluid;
            s.pressure += grad_w * (p.p[j] + pi_pair);
            s.fluid_in_reach |= fluid_j && f != 0.0;
            if V::ACTIVE {
                let (uv_j, weight) = if fluid_j {
                    (p.u[j], 1.0)
                } else {
                    (p.u_wall_visc[j], self.physics.wall_viscous_weight)
                };
                // π_ij = (u_j-u_i)·(x_j-x_i)/(r²+η²) = -(u_j-u_i)·x_ij/(r²+η²)
                let pi_ij = -(uv_j - ui).dot(&x_ij) / (r2 + self.eta2);
                s.viscous += grad_w * (pi_ij * weight);
            }
            if DIFF && Df::ACTIVE {
                let grad_j = if Df::NEEDS_GRADIENT {
                    self.grad[j]
                } else {
                    zero
                };
                let psi = self.diffusion.psi_dot_grad(
                    rho_i,
                    p.rho[j],
                    &grad_i,
                    &grad_j,
                    &x_ij,
                    r2,
                    r2 + self.eta2,
                    f,
                );
                s.diffusion += psi * vj * (fluid_j as u8 as f64);
            }
        }
        if !s.fluid_in_reach {
            // a lone particle: only walls are within reach, and they push it, never
            // pull it, nor stretch it below ρ0 (see `boundary`)
            s.pressure = self.wall_sum(i, p, list, domain, |p_w| (p_w + pi).max(0.0));
            if rho_i <= self.physics.eos.rho0 {
                s.divergence = s.divergence.min(0.0);
            }
        }
        s
    }

    fn pair_loop<const DIFF: bool>(
        &self,
        particles: &Particles<D>,
        list: &NeighbourList<D>,
        domain: &Domain<D>,
        rates: &mut Rates<D>,
    ) {
        let g = self.physics.gravity;
        let k = self.viscosity.k();
        let scale = 2.0 * self.diffusion_scale;
        rates
            .drho
            .par_iter_mut()
            .zip(rates.drho_diff.par_iter_mut())
            .zip(rates.du.par_iter_mut())
            .enumerate()
            .for_each(|(i, ((drho, drho_diff), du))| {
                if particles.kind[i] != Kind::Fluid {
                    (*drho, *du) = (0.0, Vector::zeros());
                    if DIFF {
                        *drho_diff = 0.0;
                    }
                    return;
                }
                let s = self.sums::<DIFF>(i, particles, list, domain);
                let rho_i = particles.rho[i];
                *drho = -rho_i * s.divergence;
                if DIFF {
                    *drho_diff = scale * s.diffusion;
                }
                let mut a = g - s.pressure / rho_i;
                if V::ACTIVE {
                    a += s.viscous * (k / rho_i);
                }
                *du = a;
            });
    }

    /// `Σ_w P(p_w) ∇_iW_iw V_w` over the wall neighbours of fluid particle i.
    fn wall_sum(
        &self,
        i: usize,
        p: &Particles<D>,
        list: &NeighbourList<D>,
        domain: &Domain<D>,
        pair_pressure: impl Fn(f64) -> f64,
    ) -> Vector<D> {
        list.of(i)
            .iter()
            .map(|&j| j as usize)
            .filter(|&j| p.kind[j] == Kind::Wall)
            .map(|j| {
                let x_ij = domain.separation(&p.x[i], &p.x[j]);
                let f = self.kernel.dw_over_r(x_ij.norm());
                x_ij * (f * pair_pressure(p.p[j]) * p.mass[j] / p.rho[j])
            })
            .sum()
    }

    /// The part of the wall pressure force on fluid particle i that the continuity
    /// equation does not balance, whose power is the wall power `P_W`: `Σ_w p_w ∇_iW_iw
    /// V_w`, or for a lone particle (as found by [`Self::sums`]) `Σ_w (max(p_w + p_i, 0)
    /// - p_i) ∇_iW_iw V_w`.
    fn wall_force(
        &self,
        i: usize,
        p: &Particles<D>,
        list: &NeighbourList<D>,
        domain: &Domain<D>,
        lone: bool,
    ) -> Vector<D> {
        let pi = p.p[i];
        if lone {
            self.wall_sum(i, p, list, domain, |p_w| (p_w + pi).max(0.0) - pi)
        } else {
            self.wall_sum(i, p, list, domain, |p_w| p_w)
        }
    }

    fn update_pressure(&self, particles: &mut Particles<D>) {
        let eos = self.physics.eos;
        particles
            .p
            .par_iter_mut()
            .zip(particles.rho.par_iter())
            .zip(particles.kind.par_iter())
            .for_each(|((p, &rho), &kind)| {
                if kind == Kind::Fluid {
                    *p = eos.pressure(rho);
                }
            });
    }
}

impl<const D: usize, K: Kernel, Df: DensityDiffusion<D>, V: Viscosity> Model<D>
    for Scheme<D, K, Df, V>
{
    fn evaluate(
        &mut self,
        particles: &mut Particles<D>,
        list: &NeighbourList<D>,
        domain: &Domain<D>,
        rates: &mut Rates<D>,
        with_diffusion: bool,
    ) {
        rates.resize(particles.len());
        self.update_pressure_field(particles, list, domain);
        if with_diffusion && Df::ACTIVE {
            if Df::NEEDS_GRADIENT {
                let mut grad = std::mem::take(&mut self.grad);
                density_gradient(&self.kernel, particles, list, domain, &mut grad);
                self.grad = grad;
            }
            self.pair_loop::<true>(particles, list, domain, rates);
        } else {
            self.pair_loop::<false>(particles, list, domain, rates);
        }
    }

    fn update_pressure_field(
        &self,
        particles: &mut Particles<D>,
        list: &NeighbourList<D>,
        domain: &Domain<D>,
    ) {
        self.update_pressure(particles);
        let ph = self.physics;
        extrapolate_walls(&self.kernel, &ph.eos, &ph.gravity, particles, list, domain);
    }

    fn free_surface(
        &self,
        particles: &Particles<D>,
        list: &NeighbourList<D>,
        domain: &Domain<D>,
    ) -> FreeSurface<D> {
        free_surface::detect(&self.kernel, particles, list, domain)
    }

    fn set_tensile_control(&mut self, interior: Option<Vec<bool>>) {
        self.interior = interior;
    }

    fn shift(
        &self,
        particles: &Particles<D>,
        list: &NeighbourList<D>,
        domain: &Domain<D>,
        surface: &FreeSurface<D>,
        dx: f64,
        cfl_ma: f64,
    ) -> Vec<Vector<D>> {
        shifting::displacements(&self.kernel, dx, particles, list, domain, surface, cfl_ma)
    }

    fn powers(
        &self,
        particles: &Particles<D>,
        list: &NeighbourList<D>,
        domain: &Domain<D>,
    ) -> Powers {
        let k = self.viscosity.k();
        let scale = 2.0 * self.diffusion_scale;
        let has_grad = !Df::NEEDS_GRADIENT || self.grad.len() == particles.len();
        (0..particles.len())
            .into_par_iter()
            .filter(|&i| particles.kind[i] == Kind::Fluid)
            .map(|i| {
                let s = if Df::ACTIVE && has_grad {
                    self.sums::<true>(i, particles, list, domain)
                } else {
                    self.sums::<false>(i, particles, list, domain)
                };
                let (m, rho, p) = (particles.mass[i], particles.rho[i], particles.p[i]);
                Powers {
                    viscous: m * particles.u[i].dot(&s.viscous) * k / rho,
                    diffusive: m * p / (rho * rho) * scale * s.diffusion,
                    wall: -m / rho
                        * particles.u[i].dot(&self.wall_force(
                            i,
                            particles,
                            list,
                            domain,
                            !s.fluid_in_reach,
                        )),
                }
            })
            .reduce(Powers::default, |a, b| Powers {
                viscous: a.viscous + b.viscous,
                diffusive: a.diffusive + b.diffusive,
                wall: a.wall + b.wall,
            })
    }

    fn w(&self, r: f64) -> f64 {
        self.kernel.w(r)
    }

    fn support_radius(&self) -> f64 {
        self.kernel.radius()
    }

    fn has_diffusion(&self) -> bool {
        Df::ACTIVE
    }

    fn physics(&self) -> &Physics<D> {
        &self.physics
    }
}
