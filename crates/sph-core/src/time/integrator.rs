//! Time integration of `dw/dt = Q(w) + D(w)`, D the density-diffusion part.
//!
//! - [`Rk4`]: classical Runge-Kutta 4 with the diffusive term frozen at the start of
//!   the step (Antuono et al. 2010, CPC 181:532; docs/theory.md §6), so that the δ-SPH
//!   gradient pre-pass runs once per step, not four times:
//!   ```text
//!   w1 = w0 + Δt/2 [Q(w0) + D(w0)]      w2 = w0 + Δt/2 [Q(w1) + D(w0)]
//!   w3 = w0 + Δt   [Q(w2) + D(w0)]
//!   w  = w0 + Δt/6 [Q(w0) + 2Q(w1) + 2Q(w2) + Q(w3)] + Δt D(w0)
//!   ```
//! - [`Symplectic`]: the second-order symplectic predictor-corrector common in WCSPH
//!   codes (Monaghan 2005, Rep. Prog. Phys. 68:1703; DualSPHysics, Crespo et al. 2015):
//!   `u½ = u + Δt/2 a(w)`, `ρ½ = ρ + Δt/2 ρ̇(w)`, `x½ = x + Δt/2 u`, then
//!   `u' = u + Δt a(w½)`, `ρ' = ρ + Δt ρ̇(w½)`, `x' = x + Δt (u + u')/2`.
//!   Two force evaluations per step, diffusion in both.
//!
//! Where the scheme moves particles off the flow (δ-LES-SPH's δu, [`Rates::drift`]),
//! `dx/dt = u + δu` in every stage; the symplectic scheme takes δu at the midpoint.

use crate::boundary::open::OpenBoundaries;
use crate::distributed::Ranks;
use crate::domain::Domain;
use crate::forcing::Forcing;
use crate::motion::free::{FreeBody, Rate};
use crate::motion::Motions;
use crate::neighbours::NeighbourList;
use crate::particles::{Kind, Particles, Vector};
use crate::scheme::model::{Model, Powers, Rates};
use rayon::prelude::*;

/// What a step needs besides the particles.
pub struct Context<'a, const D: usize> {
    pub model: &'a mut dyn Model<D>,
    pub list: &'a NeighbourList<D>,
    pub domain: &'a Domain<D>,
    /// The open boundaries, when the case has any, and the time at the step's start
    /// (their inflow velocity is held over the step).
    pub open: Option<&'a OpenBoundaries<D>>,
    pub time: f64,
    /// The case's body force and absorbers, when it has any.
    pub forcing: Option<&'a Forcing<D>>,
    /// The moving bodies, placed at each evaluation's time, when the case has any; its
    /// free bodies take the fluid's load after each evaluation.
    pub motions: Option<&'a mut Motions<D>>,
    /// This process's share of a split run, whose halo is refreshed before each
    /// evaluation within a step (the state at a step's start is already refreshed).
    pub halo: Option<&'a Ranks<D>>,
}

impl<const D: usize> Context<'_, D> {
    /// The rates at the particles' state (see [`Model::evaluate`]), with the moving
    /// bodies placed and the buffer particles of open boundaries set before (the
    /// step's start has its bodies placed already), the open boundaries held after,
    /// the body force at the state's time, `elapsed` after the step's start, and the
    /// free bodies' rates from the fluid's load on them. In a split run the halo
    /// gets its owners' state first, unless the state is the step's start (`elapsed`
    /// zero), which the step before left refreshed.
    pub fn evaluate(
        &mut self,
        p: &mut Particles<D>,
        rates: &mut Rates<D>,
        with_diffusion: bool,
        elapsed: f64,
    ) {
        if let Some(halo) = self.halo.filter(|_| elapsed > 0.0) {
            halo.refresh(p);
        }
        if let Some(motions) = self.motions.as_deref().filter(|_| elapsed > 0.0) {
            motions.place(p, self.time + elapsed, self.domain);
        }
        if let Some(open) = self.open {
            self.model
                .prepare_open(open, p, self.list, self.domain, self.time);
        }
        self.model
            .evaluate(p, self.list, self.domain, rates, with_diffusion);
        if let Some(forcing) = self.forcing {
            forcing.add(p, self.time + elapsed, &mut rates.du);
        }
        if let Some(open) = self.open {
            open.hold(p, &mut rates.du, &mut rates.drho, &mut rates.drho_diff);
        }
        if let Some(motions) = self.motions.as_deref_mut().filter(|m| m.free_count() > 0) {
            let owners = motions.free_owners(p);
            let (n, origin) = (motions.free_count(), Vector::zeros());
            let loads = (self.model).wall_loads(p, self.list, self.domain, &owners, n, &origin);
            motions.take_loads(&loads);
        }
    }

    /// The energy budget's powers at the last evaluation (`None` when the scheme keeps
    /// no budget), the free bodies' included, and the forcing's at the state `p` of
    /// that evaluation (the step's start).
    pub fn powers(&self, p: &Particles<D>) -> Option<Powers> {
        let mut now = self.model.last_powers()?;
        now.bodies = self.motions.as_deref().map_or(0.0, Motions::free_power);
        now.forcing = self.forcing.map_or(0.0, |f| f.power(p, self.time));
        Some(now)
    }

    /// Applies `f` to every free body (the integrators advance them with the fluid).
    fn free_bodies(&mut self, f: impl FnMut(&mut FreeBody<D>)) {
        if let Some(motions) = self.motions.as_deref_mut() {
            motions.free_bodies().for_each(f);
        }
    }
}

/// A time integrator. `begin` evaluates the rates at the start of the step (the time
/// step is chosen from them), `advance` completes the step.
pub trait TimeIntegrator<const D: usize>: Send + Sync {
    /// Force evaluations (pair loops) per step.
    fn evaluations_per_step(&self) -> usize;
    fn begin(&mut self, particles: &mut Particles<D>, cx: &mut Context<D>) -> &Rates<D>;
    fn advance(&mut self, dt: f64, particles: &mut Particles<D>, cx: &mut Context<D>);
}

/// The state `w = (x, u, ρ)` at the start of a step.
#[derive(Default)]
struct Saved<const D: usize> {
    x: Vec<Vector<D>>,
    u: Vec<Vector<D>>,
    rho: Vec<f64>,
}

/// The velocity that carries a particle: its own for fluid, zero for walls, which are
/// at rest or slide in their own plane (a lid) and so keep their places.
#[inline]
fn transport<const D: usize>(kind: Kind, u: Vector<D>) -> Vector<D> {
    if kind == Kind::Fluid {
        u
    } else {
        Vector::zeros()
    }
}

impl<const D: usize> Saved<D> {
    fn save(&mut self, p: &Particles<D>) {
        self.x.clone_from(&p.x);
        self.u.clone_from(&p.u);
        self.rho.clone_from(&p.rho);
    }
}

/// RK4 with frozen diffusion.
#[derive(Default)]
pub struct Rk4<const D: usize> {
    w0: Saved<D>,
    rates: Rates<D>,
    /// Weighted sums Q(w0) + 2Q(w1) + 2Q(w2) + Q(w3), per component.
    acc_x: Vec<Vector<D>>,
    acc_u: Vec<Vector<D>>,
    acc_rho: Vec<f64>,
    /// D(w0), frozen over the step.
    diff0: Vec<f64>,
}

impl<const D: usize> Rk4<D> {
    /// Saves the start state `w0` and starts the sums with `Q(w0)`, then moves the state
    /// to `w0 + c [Q(w0) + D(w0)]`, in one pass.
    fn first_stage(&mut self, p: &mut Particles<D>, c: f64) {
        let n = p.len();
        self.w0.x.resize(n, Vector::zeros());
        self.acc_x.resize(n, Vector::zeros());
        self.w0.u.resize(n, Vector::zeros());
        self.acc_u.resize(n, Vector::zeros());
        self.w0.rho.resize(n, 0.0);
        self.acc_rho.resize(n, 0.0);
        self.diff0.resize(n, 0.0);
        let (r, kind) = (&self.rates, &p.kind);
        p.x.par_iter_mut()
            .zip(p.u.par_iter_mut())
            .zip(p.rho.par_iter_mut())
            .zip(self.w0.x.par_iter_mut())
            .zip(self.w0.u.par_iter_mut())
            .zip(self.w0.rho.par_iter_mut())
            .zip(self.acc_x.par_iter_mut())
            .zip(self.acc_u.par_iter_mut())
            .zip(self.acc_rho.par_iter_mut())
            .zip(self.diff0.par_iter_mut())
            .enumerate()
            .for_each(
                |(i, (((((((((x, u), rho), x0), u0), rho0), ax), au), ar), d0))| {
                    (*x0, *u0, *rho0) = (*x, *u, *rho);
                    let uk = transport(kind[i], *u) + r.drift(i);
                    (*ax, *au, *ar, *d0) = (uk, r.du[i], r.drho[i], r.drho_diff[i]);
                    *x += uk * c;
                    *u += r.du[i] * c;
                    *rho += (r.drho[i] + r.drho_diff[i]) * c;
                },
            );
    }

    /// Adds `weight · Q(w_k)` to the sums and moves the state to `w0 + c Q(w_k) + Δt D(w0)·c/Δt`.
    fn stage(&mut self, p: &mut Particles<D>, weight: f64, c: f64) {
        let w0 = &self.w0;
        let r = &self.rates;
        let kind = &p.kind;
        p.x.par_iter_mut()
            .zip(p.u.par_iter_mut())
            .zip(p.rho.par_iter_mut())
            .zip(self.acc_x.par_iter_mut())
            .zip(self.acc_u.par_iter_mut())
            .zip(self.acc_rho.par_iter_mut())
            .enumerate()
            .for_each(|(i, (((((x, u), rho), ax), au), ar))| {
                let uk = transport(kind[i], *u) + r.drift(i);
                *ax += uk * weight;
                *au += r.du[i] * weight;
                *ar += r.drho[i] * weight;
                *x = w0.x[i] + uk * c;
                *u = w0.u[i] + r.du[i] * c;
                *rho = w0.rho[i] + (r.drho[i] + self.diff0[i]) * c;
            });
    }
}

impl<const D: usize> TimeIntegrator<D> for Rk4<D> {
    fn evaluations_per_step(&self) -> usize {
        4
    }

    fn begin(&mut self, p: &mut Particles<D>, cx: &mut Context<D>) -> &Rates<D> {
        cx.evaluate(p, &mut self.rates, true, 0.0);
        &self.rates
    }

    fn advance(&mut self, dt: f64, p: &mut Particles<D>, cx: &mut Context<D>) {
        self.first_stage(p, 0.5 * dt);
        cx.free_bodies(|b| {
            (b.start, b.sum) = (b.state, b.rate);
            b.state = b.start.advanced(&b.rate, 0.5 * dt);
        });
        cx.evaluate(p, &mut self.rates, false, 0.5 * dt);
        for c in [0.5 * dt, dt] {
            self.stage(p, 2.0, c);
            cx.free_bodies(|b| {
                b.sum = b.sum + b.rate * 2.0;
                b.state = b.start.advanced(&b.rate, c);
            });
            cx.evaluate(p, &mut self.rates, false, c);
        }
        cx.free_bodies(|b| b.state = b.start.advanced(&(b.sum + b.rate), dt / 6.0));
        let (w0, r, kind) = (&self.w0, &self.rates, &p.kind);
        let (ax, au, ar, d0) = (&self.acc_x, &self.acc_u, &self.acc_rho, &self.diff0);
        let s = dt / 6.0;
        p.x.par_iter_mut()
            .zip(p.u.par_iter_mut())
            .zip(p.rho.par_iter_mut())
            .enumerate()
            .for_each(|(i, ((x, u), rho))| {
                *x = w0.x[i] + (ax[i] + transport(kind[i], *u) + r.drift(i)) * s;
                *rho = w0.rho[i] + (ar[i] + r.drho[i]) * s + d0[i] * dt;
                *u = w0.u[i] + (au[i] + r.du[i]) * s;
            });
    }
}

/// Second-order symplectic predictor-corrector.
#[derive(Default)]
pub struct Symplectic<const D: usize> {
    w0: Saved<D>,
    rates: Rates<D>,
}

impl<const D: usize> TimeIntegrator<D> for Symplectic<D> {
    fn evaluations_per_step(&self) -> usize {
        2
    }

    fn begin(&mut self, p: &mut Particles<D>, cx: &mut Context<D>) -> &Rates<D> {
        cx.evaluate(p, &mut self.rates, true, 0.0);
        &self.rates
    }

    fn advance(&mut self, dt: f64, p: &mut Particles<D>, cx: &mut Context<D>) {
        self.w0.save(p);
        let half = 0.5 * dt;
        let (r, kind) = (&self.rates, &p.kind);
        p.x.par_iter_mut()
            .zip(p.u.par_iter_mut())
            .zip(p.rho.par_iter_mut())
            .enumerate()
            .for_each(|(i, ((x, u), rho))| {
                *x += (transport(kind[i], *u) + r.drift(i)) * half;
                *u += r.du[i] * half;
                *rho += (r.drho[i] + r.drho_diff[i]) * half;
            });
        cx.free_bodies(|b| {
            b.start = b.state;
            b.state = b.start.advanced(&b.rate, half);
        });
        cx.evaluate(p, &mut self.rates, true, half);
        // V' = V + Δt A½ and X' = X + Δt (V + V')/2, as for the fluid
        cx.free_bodies(|b| {
            let (s, r) = (&b.start, b.rate);
            let rate = Rate {
                velocity: s.velocity + r.acceleration * half,
                omega: s.omega + r.alpha * half,
                ..r
            };
            b.state = b.start.advanced(&rate, dt);
        });
        let (w0, r, kind) = (&self.w0, &self.rates, &p.kind);
        p.x.par_iter_mut()
            .zip(p.u.par_iter_mut())
            .zip(p.rho.par_iter_mut())
            .enumerate()
            .for_each(|(i, ((x, u), rho))| {
                *u = w0.u[i] + r.du[i] * dt;
                *rho = w0.rho[i] + (r.drho[i] + r.drho_diff[i]) * dt;
                let carried = transport(kind[i], w0.u[i]) + transport(kind[i], *u);
                *x = w0.x[i] + carried * half + r.drift(i) * dt;
            });
    }
}
