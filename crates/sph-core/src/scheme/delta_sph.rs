//! The semi-discrete δ-SPH equations (Antuono et al. 2010, CPC 181:532; docs/theory.md §4-5):
//!
//! ```text
//! dρ_i/dt = -ρ_i Σ_j (u_j - u_i)·∇_iW_ij V_j  +  δ h c0 D_i
//! du_i/dt = g - (1/ρ_i) Σ_j (p_j + p_i) ∇_iW_ij V_j + (K/ρ_i) Σ_j π_ij ∇_iW_ij V_j
//! dx_i/dt = u_i,     p_i = c0² (ρ_i - ρ0)
//! ```
//!
//! [`Scheme`] is generic over the kernel, the density diffusion and the viscosity,
//! so that each combination gets its own pair loop and unused terms compile away.
//! It is reached through the object-safe [`crate::scheme::model::Model`] trait, whose methods run once
//! per evaluation, never per pair. Pair loops gather per particle (Rayon over
//! particles, no shared writes).

use super::model::kernel_model_methods;
use crate::boundary::bodies::Load;
use crate::boundary::extrapolate_walls;
use crate::domain::Domain;
use crate::neighbours::NeighbourList;
use crate::particles::blocks::{sum_in_blocks, BLOCK};
use crate::particles::{Kind, Particles, Vector};
use crate::physics::diffusion::DensityDiffusion;

use crate::physics::kernel::Kernel;
use crate::physics::renormalisation::density_gradient;
use crate::physics::shifting::{self, Shift};
use crate::physics::viscosity::Viscosity;
use crate::scheme::kinematics::PairKinematics;
use crate::scheme::model::{
    fluid_pressure, pressure_and_volume, tensile_pressure, Model, Physics, Powers, Rates,
};
use rayon::prelude::*;

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
    /// `V_j = m_j/ρ_j` of every particle, refreshed at each evaluation.
    volume: Vec<f64>,
    /// ⟨∇ρ⟩^L, allocated only when the diffusion needs it.
    grad: Vec<Vector<D>>,
    /// Whether `grad` was computed by the last shift, for the evaluation that follows it.
    grad_from_shift: bool,
    /// Tensile instability control (Sun et al. 2018): per particle, whether it is inside
    /// the fluid (not on or near the free surface); `None` when the control is off.
    interior: Option<Vec<bool>>,
    /// Whether the energy budget's powers are computed (in the evaluations with
    /// diffusion), and their last values.
    budget: bool,
    powers: Option<Powers>,
    /// Whether the run finds the free surface (shifting or tensile control).
    free_surface: bool,
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
    /// Σ_w p_w ∇W V_w over wall neighbours (for the wall power)
    wall_pressure: Vector<D>,
    /// What the walls' own velocities carry (for the powers; zero at rest)
    moving: MovingWallSums,
    /// Whether any fluid particle lies within the kernel support
    fluid_in_reach: bool,
}

/// The wall pair sums of the energy budget taken at the walls' velocities u_w: with
/// them the powers count wall pairs at the relative velocity, and the moving walls'
/// power apart (see [`Powers`]).
#[derive(Default)]
struct MovingWallSums {
    /// Σ_w (p_w + p_i) u_w·∇W V_w: the pressure pairs' share of `P_M`
    pair_pressure: f64,
    /// Σ_w p_w u_w·∇W V_w: the wall pressure's, taken out of `P_W`
    wall_pressure: f64,
    /// Σ_w π_iw u_w·∇W V_w: the no-slip pairs', moved from `P_V` to `P_M`
    viscous: f64,
}

/// One fluid-wall pair of the momentum equation (see [`Scheme::wall_pair`]).
struct WallPair<const D: usize> {
    j: usize,
    grad_w: Vector<D>,
    viscous: f64,
}

/// One fluid particle's rates and its share of the powers.
struct Row<const D: usize> {
    drho: f64,
    drho_diff: f64,
    du: Vector<D>,
}

impl<const D: usize, K: Kernel, Df: DensityDiffusion<D>, V: Viscosity> Scheme<D, K, Df, V> {
    /// The scheme; `budget` asks for the powers of the energy budget.
    pub fn new(kernel: K, diffusion: Df, viscosity: V, physics: Physics<D>, budget: bool) -> Self {
        let h = kernel.h();
        Self {
            kernel,
            diffusion,
            viscosity,
            physics,
            diffusion_scale: diffusion.delta() * h * physics.eos.c0,
            eta2: 0.01 * h * h,
            volume: Vec::new(),
            grad: Vec::new(),
            grad_from_shift: false,
            interior: None,
            budget,
            powers: None,
            free_surface: false,
        }
    }

    /// The scheme of a run that finds the free surface at each step (shifting or
    /// tensile control), which chains one more neighbour pass.
    pub fn with_free_surface(mut self, on: bool) -> Self {
        self.free_surface = on;
        self
    }

    /// The pair sums of fluid particle i: its fluid neighbours, then its walls. The
    /// diffusion sum only when `DIFF`, the wall pressure sum only when `BUDGET`.
    #[inline(always)]
    fn sums<const DIFF: bool, const BUDGET: bool>(
        &self,
        i: usize,
        p: &Particles<D>,
        list: &NeighbourList<D>,
        domain: &Domain<D>,
    ) -> Sums<D> {
        let vol = &self.volume;
        let xi = p.x[i];
        let ui = p.u[i];
        let (pi, rho_i) = (p.p[i], p.rho[i]);
        let pi_pair = self.pair_pressure(i, pi);
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
            wall_pressure: zero,
            moving: MovingWallSums::default(),
            fluid_in_reach: false,
        };
        for &j in list.fluid(i) {
            let j = j as usize;
            let pair = PairKinematics::of(&self.kernel, domain, &xi, &p.x[j], vol[j]);
            let (x_ij, r2, f, grad_w) = (pair.x_ij, pair.r2, pair.f, pair.grad_w);
            let du = p.u[j] - ui;
            s.divergence += du.dot(&grad_w);
            s.pressure += grad_w * (p.p[j] + pi_pair);
            s.fluid_in_reach |= f != 0.0;
            let inv_r2_reg = if V::ACTIVE || (DIFF && Df::ACTIVE) {
                1.0 / (r2 + self.eta2)
            } else {
                0.0
            };
            if V::ACTIVE {
                // π_ij = (u_j-u_i)·(x_j-x_i)/(r²+η²) = -(u_j-u_i)·x_ij/(r²+η²)
                s.viscous -= grad_w * (du.dot(&x_ij) * inv_r2_reg);
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
                    &pair.diffusion_pair(inv_r2_reg),
                );
                s.diffusion += psi * vol[j];
            }
        }
        for &j in list.walls(i) {
            let w = self.wall_pair(i, j as usize, p, domain);
            s.divergence += (p.u[w.j] - ui).dot(&w.grad_w);
            s.pressure += w.grad_w * (p.p[w.j] + pi_pair);
            if BUDGET {
                s.wall_pressure += w.grad_w * p.p[w.j];
                let along = p.u[w.j].dot(&w.grad_w);
                s.moving.pair_pressure += along * (p.p[w.j] + pi_pair);
                s.moving.wall_pressure += along * p.p[w.j];
                s.moving.viscous += along * w.viscous;
            }
            if V::ACTIVE {
                s.viscous += w.grad_w * w.viscous;
            }
        }
        if !s.fluid_in_reach {
            // a lone particle: only walls are within reach, and they push it, never
            // pull it, nor stretch it below ρ0 (see `boundary`)
            let vol = &self.volume;
            let pair = |j: usize| (p.p[j] + pi).max(0.0);
            s.pressure = self.wall_sum(i, p, list, domain, |j, x, f| x * (f * pair(j) * vol[j]));
            if BUDGET {
                let own = self.wall_sum(i, p, list, domain, |j, x, f| x * (f * pi * vol[j]));
                s.wall_pressure = s.pressure - own;
                let along = |j: usize, x: Vector<D>, f: f64| p.u[j].dot(&(x * (f * vol[j])));
                s.moving.pair_pressure =
                    self.wall_sum(i, p, list, domain, |j, x, f| pair(j) * along(j, x, f));
                s.moving.wall_pressure = self.wall_sum(i, p, list, domain, |j, x, f| {
                    (pair(j) - pi) * along(j, x, f)
                });
            }
            if rho_i <= self.physics.eos.rho0 {
                s.divergence = s.divergence.min(0.0);
            }
        }
        s
    }

    /// The rates of every particle (zero for walls) and, when `BUDGET`, the powers,
    /// summed in fixed blocks (the same bits on any number of threads, see
    /// [`crate::particles::blocks`]).
    fn pair_loop<const DIFF: bool, const BUDGET: bool>(
        &self,
        particles: &Particles<D>,
        list: &NeighbourList<D>,
        domain: &Domain<D>,
        rates: &mut Rates<D>,
    ) -> Powers {
        let particle = |i: usize, drho: &mut f64, drho_diff: &mut f64, du: &mut Vector<D>| {
            self.particle_rates::<DIFF, BUDGET>(i, particles, list, domain, drho, drho_diff, du)
        };
        if !BUDGET {
            (rates.drho.par_iter_mut())
                .zip(rates.drho_diff.par_iter_mut())
                .zip(rates.du.par_iter_mut())
                .enumerate()
                .for_each(|(i, ((drho, drho_diff), du))| _ = particle(i, drho, drho_diff, du));
            return Powers::default();
        }
        let blocks: Vec<Powers> = (rates.drho.par_chunks_mut(BLOCK))
            .zip(rates.drho_diff.par_chunks_mut(BLOCK))
            .zip(rates.du.par_chunks_mut(BLOCK))
            .enumerate()
            .map(|(b, ((drho, drho_diff), du))| {
                (0..drho.len()).fold(Powers::default(), |sum, k| {
                    let i = b * BLOCK + k;
                    sum.add(particle(i, &mut drho[k], &mut drho_diff[k], &mut du[k]))
                })
            })
            .collect();
        blocks.into_iter().fold(Powers::default(), Powers::add)
    }

    /// The rates of particle i (zero for a wall) and, when `BUDGET`, its powers.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn particle_rates<const DIFF: bool, const BUDGET: bool>(
        &self,
        i: usize,
        particles: &Particles<D>,
        list: &NeighbourList<D>,
        domain: &Domain<D>,
        drho: &mut f64,
        drho_diff: &mut f64,
        du: &mut Vector<D>,
    ) -> Powers {
        if particles.kind[i] != Kind::Fluid {
            (*drho, *du) = (0.0, Vector::zeros());
            if DIFF {
                *drho_diff = 0.0;
            }
            return Powers::default();
        }
        let k = self.viscosity.k();
        let scale = 2.0 * self.diffusion_scale;
        let s = self.sums::<DIFF, BUDGET>(i, particles, list, domain);
        let row = self.row::<DIFF>(i, particles, &s, self.physics.gravity, k, scale);
        (*drho, *du) = (row.drho, row.du);
        if DIFF {
            *drho_diff = row.drho_diff;
        }
        if !BUDGET {
            return Powers::default();
        }
        let (m, rho, u) = (particles.mass[i], particles.rho[i], particles.u[i]);
        let moved = &s.moving;
        Powers {
            viscous: m * (u.dot(&s.viscous) - moved.viscous) * k / rho,
            diffusive: m * particles.p[i] / (rho * rho) * row.drho_diff,
            wall: -m / rho * (u.dot(&s.wall_pressure) - moved.wall_pressure),
            moving: m / rho * (moved.viscous * k - moved.pair_pressure),
            ..Powers::default()
        }
    }

    /// Continuity, its diffusive part and momentum of fluid particle i from its sums.
    #[inline(always)]
    fn row<const DIFF: bool>(
        &self,
        i: usize,
        p: &Particles<D>,
        s: &Sums<D>,
        g: Vector<D>,
        k: f64,
        scale: f64,
    ) -> Row<D> {
        let rho_i = p.rho[i];
        let mut du = g - s.pressure / rho_i;
        if V::ACTIVE {
            du += s.viscous * (k / rho_i);
        }
        Row {
            drho: -rho_i * s.divergence,
            drho_diff: if DIFF { scale * s.diffusion } else { 0.0 },
            du,
        }
    }

    /// The p_i of fluid particle i in its pair terms, see [`tensile_pressure`].
    #[inline(always)]
    fn pair_pressure(&self, i: usize, pi: f64) -> f64 {
        tensile_pressure(self.interior.as_deref(), i, pi)
    }

    /// `∇_iW_iw V_w` of fluid particle i and wall particle j, and the viscous factor
    /// `w_v π_iw` of the no-slip wall term (0 on free-slip walls or without viscosity).
    #[inline(always)]
    fn wall_pair(&self, i: usize, j: usize, p: &Particles<D>, domain: &Domain<D>) -> WallPair<D> {
        let x_ij = domain.separation(&p.x[i], &p.x[j]);
        let r2 = x_ij.norm_squared();
        let f = self.kernel.dw_over_r(r2.sqrt());
        let weight = self.physics.wall_viscous_weight;
        let viscous = if V::ACTIVE && weight != 0.0 {
            -(p.u_wall_visc[j] - p.u[i]).dot(&x_ij) / (r2 + self.eta2) * weight
        } else {
            0.0
        };
        WallPair {
            j,
            grad_w: x_ij * (f * self.volume[j]),
            viscous,
        }
    }

    /// Whether fluid particle i has another fluid particle within the kernel support.
    fn fluid_in_reach(
        &self,
        i: usize,
        p: &Particles<D>,
        list: &NeighbourList<D>,
        domain: &Domain<D>,
    ) -> bool {
        list.fluid(i).iter().any(|&j| {
            let r = domain.separation(&p.x[i], &p.x[j as usize]).norm();
            self.kernel.dw_over_r(r) != 0.0
        })
    }

    /// `Σ_w term(w, x_iw, F(r_iw))` over the wall neighbours w of fluid particle i
    /// (`∇_iW_iw = x_iw F(r_iw)`).
    fn wall_sum<T: std::iter::Sum>(
        &self,
        i: usize,
        p: &Particles<D>,
        list: &NeighbourList<D>,
        domain: &Domain<D>,
        term: impl Fn(usize, Vector<D>, f64) -> T,
    ) -> T {
        list.walls(i)
            .iter()
            .map(|&j| {
                let j = j as usize;
                let x_ij = domain.separation(&p.x[i], &p.x[j]);
                term(j, x_ij, self.kernel.dw_over_r(x_ij.norm()))
            })
            .sum()
    }

    /// What the pair terms read at the current state: fluid pressure from the EOS, the
    /// walls' extrapolated pressure and density, every particle's volume `m/ρ`.
    fn prepare(
        &mut self,
        particles: &mut Particles<D>,
        list: &NeighbourList<D>,
        domain: &Domain<D>,
    ) {
        self.update_pressure_and_volume(particles);
        let ph = self.physics;
        extrapolate_walls(&self.kernel, &ph.eos, &ph.gravity, particles, list, domain);
        // the walls' densities changed with their pressures
        for &w in list.wall_particles() {
            self.volume[w] = particles.mass[w] / particles.rho[w];
        }
    }

    /// Fluid pressure from the EOS and every particle's volume `m/ρ`.
    fn update_pressure_and_volume(&mut self, particles: &mut Particles<D>) {
        pressure_and_volume(particles, &self.physics.eos, &mut self.volume);
    }
}

impl<const D: usize, K: Kernel, Df: DensityDiffusion<D>, V: Viscosity> Model<D>
    for Scheme<D, K, Df, V>
{
    kernel_model_methods!();

    fn evaluate(
        &mut self,
        particles: &mut Particles<D>,
        list: &NeighbourList<D>,
        domain: &Domain<D>,
        rates: &mut Rates<D>,
        with_diffusion: bool,
    ) {
        rates.resize(particles.len());
        self.prepare(particles, list, domain);
        let grad_from_shift = std::mem::take(&mut self.grad_from_shift);
        if with_diffusion && Df::NEEDS_GRADIENT && !grad_from_shift {
            let mut grad = std::mem::take(&mut self.grad);
            density_gradient(
                &self.kernel,
                particles,
                &self.volume,
                list,
                domain,
                &mut grad,
            );
            self.grad = grad;
        }
        match (with_diffusion && Df::ACTIVE, with_diffusion && self.budget) {
            (true, true) => {
                self.powers = Some(self.pair_loop::<true, true>(particles, list, domain, rates))
            }
            (true, false) => _ = self.pair_loop::<true, false>(particles, list, domain, rates),
            (false, true) => {
                self.powers = Some(self.pair_loop::<false, true>(particles, list, domain, rates))
            }
            (false, false) => _ = self.pair_loop::<false, false>(particles, list, domain, rates),
        }
    }

    fn update_pressure_field(
        &self,
        particles: &mut Particles<D>,
        list: &NeighbourList<D>,
        domain: &Domain<D>,
    ) {
        fluid_pressure(particles, &self.physics.eos);
        let ph = self.physics;
        extrapolate_walls(&self.kernel, &ph.eos, &ph.gravity, particles, list, domain);
    }

    fn shift(
        &mut self,
        particles: &mut Particles<D>,
        list: &NeighbourList<D>,
        domain: &Domain<D>,
        dx: f64,
        cfl_ma: f64,
    ) -> Shift<D> {
        let strength = shifting::Strength { dx, cfl_ma };
        if !Df::NEEDS_GRADIENT {
            let volume = particles.volumes();
            return shifting::shift(
                &self.kernel,
                strength,
                particles,
                &volume,
                list,
                domain,
                None,
            );
        }
        self.prepare(particles, list, domain);
        let mut grad = std::mem::take(&mut self.grad);
        let shift = shifting::shift(
            &self.kernel,
            strength,
            particles,
            &self.volume,
            list,
            domain,
            Some(&mut grad),
        );
        (self.grad, self.grad_from_shift) = (grad, true);
        shift
    }

    fn wall_loads(
        &mut self,
        particles: &mut Particles<D>,
        list: &NeighbourList<D>,
        domain: &Domain<D>,
        body: &[Option<usize>],
        bodies: usize,
        centre: &Vector<D>,
    ) -> Vec<Load<D>> {
        self.prepare(particles, list, domain);
        let p: &Particles<D> = particles;
        let k = self.viscosity.k();
        // the same bits on any number of threads: a free body's motion, and so the
        // run, depends on them
        let block = |range: std::ops::Range<usize>| {
            let mut loads = vec![Load::default(); bodies];
            for i in range.filter(|&i| p.kind[i] == Kind::Fluid) {
                let (pi, scale) = (p.p[i], p.mass[i] / p.rho[i]);
                let lone = !self.fluid_in_reach(i, p, list, domain);
                let pi_pair = self.pair_pressure(i, pi);
                for &j in list.walls(i) {
                    let w = self.wall_pair(i, j as usize, p, domain);
                    let Some(b) = body[w.j] else { continue };
                    let pair = if lone {
                        (p.p[w.j] + pi).max(0.0)
                    } else {
                        p.p[w.j] + pi_pair
                    };
                    let viscous = if V::ACTIVE {
                        -w.grad_w * (w.viscous * k * scale)
                    } else {
                        Vector::zeros()
                    };
                    let arm = domain.separation(&p.x[w.j], centre);
                    loads[b].add_pair(w.grad_w * (pair * scale), viscous, &arm);
                }
            }
            loads
        };
        let zero = || vec![Load::default(); bodies];
        sum_in_blocks(p.len(), zero, block, |a: Vec<Load<D>>, b| {
            a.into_iter().zip(b).map(|(x, y)| x + y).collect()
        })
    }

    fn has_diffusion(&self) -> bool {
        Df::ACTIVE
    }
}
