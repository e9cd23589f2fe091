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
//! It is reached through the object-safe [`Model`] trait, whose methods run once
//! per evaluation, never per pair. Pair loops gather per particle (Rayon over
//! particles, no shared writes).

use crate::boundary::bodies::Load;
use crate::boundary::extrapolate_walls;
use crate::domain::Domain;
use crate::neighbours::NeighbourList;
use crate::particles::{Kind, Particles, Vector};
use crate::physics::diffusion::{DensityDiffusion, Pair};
use crate::physics::eos::LinearEos;
use crate::physics::free_surface::{self, FreeSurface};
use crate::physics::kernel::Kernel;
use crate::physics::renormalisation::density_gradient;
use crate::physics::shifting::{self, Shift};
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
    /// The shifting velocity δu that carries particles besides u (`dx/dt = u + δu`) in
    /// quasi-Lagrangian schemes (δ-LES-SPH); empty in the others.
    pub drift: Vec<Vector<D>>,
}

impl<const D: usize> Rates<D> {
    pub fn resize(&mut self, n: usize) {
        self.drho.resize(n, 0.0);
        self.drho_diff.resize(n, 0.0);
        self.du.resize(n, Vector::zeros());
    }

    /// The transport velocity of particle i besides its own velocity: δu, or zero.
    #[inline(always)]
    pub fn drift(&self, i: usize) -> Vector<D> {
        self.drift.get(i).copied().unwrap_or_else(Vector::zeros)
    }

    /// Largest acceleration magnitude, over the particles `owned` flags when given
    /// (a split run's own particles; its halo's rates are not all complete).
    pub fn max_acceleration(&self, owned: Option<&[bool]>) -> f64 {
        let own = |i: usize| owned.is_none_or(|o| o[i]);
        (self.du.par_iter().enumerate())
            .filter(|(i, _)| own(*i))
            .map(|(_, a)| a.norm_squared())
            .reduce(|| 0.0, f64::max)
            .sqrt()
    }
}

/// Rates of change of the mechanical energy due to the dissipative terms (docs/theory.md §10).
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

/// The largest diffusivities [m²/s] a scheme adds to the case's viscosity.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Diffusivities {
    /// Of the momentum equation, the case's viscosity included (δ-LES-SPH: `ν + ν_T`).
    pub momentum: f64,
    /// Of the continuity equation (δ-LES-SPH: `ν_δ`).
    pub density: f64,
}

/// What the integrators and diagnostics need from a resolved scheme.
pub trait Model<const D: usize>: Send + Sync {
    /// Fills `rates` at the current state: pressure from the EOS, wall extrapolation,
    /// the δ-SPH gradient pre-pass (only if the diffusion needs it, `with_diffusion`, and
    /// the [`Model::shift`] just before did not compute the gradient),
    /// then the pair loop. `rates.drho_diff` is written only when `with_diffusion`, and
    /// so are the powers of the energy budget when the scheme carries one.
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
    /// δ+-SPH shifting displacements and the free surface at the current state (see
    /// [`crate::physics::shifting`]), `cfl_ma = U_max Δt/h`. When the diffusion needs
    /// δ-SPH's density gradient, the same pass computes it (pressures and walls refreshed
    /// first), and the next evaluation uses it instead of a pre-pass of its own.
    fn shift(
        &mut self,
        particles: &mut Particles<D>,
        list: &NeighbourList<D>,
        domain: &Domain<D>,
        dx: f64,
        cfl_ma: f64,
    ) -> Shift<D>;
    /// The viscous, diffusive and wall powers at the state of the last evaluation with
    /// diffusion (the first of each step), computed in its pair loop; `None` unless the
    /// scheme was built with the energy budget.
    fn last_powers(&self) -> Option<Powers>;
    /// The load of the fluid on each body at the current state (pressures and volumes
    /// refreshed first, as an evaluation does): minus the wall terms of the momentum
    /// equation, see [`crate::boundary::bodies`]. `body[j]` is the body of particle j
    /// (`None` for fluid), `centre` the moment point.
    fn wall_loads(
        &mut self,
        particles: &mut Particles<D>,
        list: &NeighbourList<D>,
        domain: &Domain<D>,
        body: &[Option<usize>],
        bodies: usize,
        centre: &Vector<D>,
    ) -> Vec<Load<D>>;
    /// Kernel value `W(r)`.
    fn w(&self, r: f64) -> f64;
    /// Kernel support radius R.
    fn support_radius(&self) -> f64;
    /// Whether any density diffusion is active.
    fn has_diffusion(&self) -> bool;
    /// The neighbour passes chained within an evaluation or a step's start, each
    /// reading the last one's results at its neighbours (see [`chained_passes`]): a
    /// split run's halo is this many list radii deep.
    fn neighbour_passes(&self) -> usize;
    fn physics(&self) -> &Physics<D>;
    /// The largest momentum diffusivity (the case's viscosity plus an eddy viscosity)
    /// and density diffusivity (a diffusion coefficient) of the last evaluation, for
    /// the limits of Δt; zero when the scheme adds none.
    fn diffusivities(&self) -> Diffusivities {
        Diffusivities::default()
    }
}

/// The neighbour passes a scheme chains: the wall extrapolation or the δ-SPH
/// gradient (δ-LES-SPH: the velocity and density gradients), then the pair loop;
/// with shifting or tensile control (`free_surface`), the free surface's
/// moments, scan region and surface neighbours add one more radius. One pass fewer
/// leaves a split dam break 1e-6 away from the serial run after 200 steps; with these
/// it agrees to round-off (`crates/sph-cli/tests/mpi/main.rs`).
pub fn chained_passes(free_surface: bool) -> usize {
    2 + usize::from(free_surface)
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
    /// Whether any fluid particle lies within the kernel support
    fluid_in_reach: bool,
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
            fluid_in_reach: false,
        };
        for &j in list.fluid(i) {
            let j = j as usize;
            let x_ij = domain.separation(&xi, &p.x[j]);
            let r2 = x_ij.norm_squared();
            let r = r2.sqrt();
            let f = self.kernel.dw_over_r(r);
            let grad_w = x_ij * (f * vol[j]);
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
                let pair = Pair {
                    x_ij: &x_ij,
                    r,
                    r2,
                    inv_r2_reg,
                    f,
                };
                let psi = self
                    .diffusion
                    .psi_dot_grad(rho_i, p.rho[j], &grad_i, &grad_j, &pair);
                s.diffusion += psi * vol[j];
            }
        }
        for &j in list.walls(i) {
            let w = self.wall_pair(i, j as usize, p, domain);
            s.divergence += (p.u[w.j] - ui).dot(&w.grad_w);
            s.pressure += w.grad_w * (p.p[w.j] + pi_pair);
            if BUDGET {
                s.wall_pressure += w.grad_w * p.p[w.j];
            }
            if V::ACTIVE {
                s.viscous += w.grad_w * w.viscous;
            }
        }
        if !s.fluid_in_reach {
            // a lone particle: only walls are within reach, and they push it, never
            // pull it, nor stretch it below ρ0 (see `boundary`)
            s.pressure = self.wall_sum(i, p, list, domain, |p_w| (p_w + pi).max(0.0));
            if BUDGET {
                s.wall_pressure = s.pressure - self.wall_sum(i, p, list, domain, |_| pi);
            }
            if rho_i <= self.physics.eos.rho0 {
                s.divergence = s.divergence.min(0.0);
            }
        }
        s
    }

    /// The rates of every particle (zero for walls) and, when `BUDGET`, the powers.
    fn pair_loop<const DIFF: bool, const BUDGET: bool>(
        &self,
        particles: &Particles<D>,
        list: &NeighbourList<D>,
        domain: &Domain<D>,
        rates: &mut Rates<D>,
    ) -> Powers {
        let g = self.physics.gravity;
        let k = self.viscosity.k();
        let scale = 2.0 * self.diffusion_scale;
        rates
            .drho
            .par_iter_mut()
            .zip(rates.drho_diff.par_iter_mut())
            .zip(rates.du.par_iter_mut())
            .enumerate()
            .map(|(i, ((drho, drho_diff), du))| {
                if particles.kind[i] != Kind::Fluid {
                    (*drho, *du) = (0.0, Vector::zeros());
                    if DIFF {
                        *drho_diff = 0.0;
                    }
                    return Powers::default();
                }
                let s = self.sums::<DIFF, BUDGET>(i, particles, list, domain);
                let row = self.row::<DIFF>(i, particles, &s, g, k, scale);
                (*drho, *du) = (row.drho, row.du);
                if DIFF {
                    *drho_diff = row.drho_diff;
                }
                if BUDGET {
                    let (m, rho, u) = (particles.mass[i], particles.rho[i], particles.u[i]);
                    Powers {
                        viscous: m * u.dot(&s.viscous) * k / rho,
                        diffusive: m * particles.p[i] / (rho * rho) * row.drho_diff,
                        wall: -m / rho * u.dot(&s.wall_pressure),
                    }
                } else {
                    Powers::default()
                }
            })
            .reduce(Powers::default, Powers::add)
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

    /// `Σ_w P(p_w) ∇_iW_iw V_w` over the wall neighbours of fluid particle i.
    fn wall_sum(
        &self,
        i: usize,
        p: &Particles<D>,
        list: &NeighbourList<D>,
        domain: &Domain<D>,
        pair_pressure: impl Fn(f64) -> f64,
    ) -> Vector<D> {
        list.walls(i)
            .iter()
            .map(|&j| {
                let j = j as usize;
                let x_ij = domain.separation(&p.x[i], &p.x[j]);
                let f = self.kernel.dw_over_r(x_ij.norm());
                x_ij * (f * pair_pressure(p.p[j]) * self.volume[j])
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

/// Fluid pressure from the EOS and every particle's volume `m/ρ` into `volume`.
pub(crate) fn pressure_and_volume<const D: usize>(
    particles: &mut Particles<D>,
    eos: &LinearEos,
    volume: &mut Vec<f64>,
) {
    fluid_pressure(particles, eos);
    volume.resize(particles.len(), 0.0);
    volume
        .par_iter_mut()
        .zip(particles.mass.par_iter())
        .zip(particles.rho.par_iter())
        .for_each(|((v, &m), &rho)| *v = m / rho);
}

/// The p_i of fluid particle i in its pair terms. Tensile instability control (Sun et
/// al. 2018, docs/theory.md §9): where `interior` is given, an interior particle in tension
/// takes (p_j - p_i) instead of (p_j + p_i). Decided once per particle.
#[inline(always)]
pub(crate) fn tensile_pressure(interior: Option<&[bool]>, i: usize, pi: f64) -> f64 {
    match interior {
        Some(interior) if pi < 0.0 && interior[i] => -pi,
        _ => pi,
    }
}

/// `p_i = p(ρ_i)` for every fluid particle.
pub(crate) fn fluid_pressure<const D: usize>(particles: &mut Particles<D>, eos: &LinearEos) {
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

impl Powers {
    pub(crate) fn add(self, other: Self) -> Self {
        Self {
            viscous: self.viscous + other.viscous,
            diffusive: self.diffusive + other.diffusive,
            wall: self.wall + other.wall,
        }
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

    fn last_powers(&self) -> Option<Powers> {
        self.powers
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
        (0..p.len())
            .into_par_iter()
            .filter(|&i| p.kind[i] == Kind::Fluid)
            .fold(
                || vec![Load::default(); bodies],
                |mut loads, i| {
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
                    loads
                },
            )
            .reduce(
                || vec![Load::default(); bodies],
                |a, b| a.into_iter().zip(b).map(|(x, y)| x + y).collect(),
            )
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

    fn neighbour_passes(&self) -> usize {
        chained_passes(self.free_surface)
    }

    fn physics(&self) -> &Physics<D> {
        &self.physics
    }
}
