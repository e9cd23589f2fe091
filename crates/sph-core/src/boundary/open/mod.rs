//! Open boundaries by the buffer method (Federico et al. 2012, Eur. J. Mech. B 34:35;
//! the mirrored extrapolation of Tafuni et al. 2018, CMAME 342:604).
//!
//! A buffer is the slab of the domain within `width ≥ R` of one of its ends along an
//! open axis, over the whole end or over a `section` of it (a jet's nozzle). Its particles are fluid particles that take part in every pair sum (so
//! the fluid next to the buffer sees a full kernel support), but whose state is set
//! rather than integrated:
//! - **inlet**: velocity prescribed, `u = U f(s) min(t/T, 1)` (profile f, uniform or
//!   Poiseuille's across plates or a rectangular duct, `profile`; ramp T, held
//!   over each step); density extrapolated from the fluid at the point mirrored across
//!   the buffer's inner face, `ρ_b = Σ_j ρ_j W(x_m - x_j) V_j / Σ_j W(x_m - x_j) V_j`
//!   over the fluid outside the buffers (zero normal gradient);
//! - **outlet**: density from the prescribed pressure (`ρ = ρ(p_out)` by the EOS);
//!   the velocity a particle had when it entered, kept, or (`outflow_velocity =
//!   "extrapolated"`) the fluid's at the mirrored point, as the inlet's density.
//!
//! Membership is by position, so it needs no per-particle flag and survives the
//! lists' reordering and a restart. Particles enter and leave when the neighbour
//! lists are rebuilt (every few steps): then an inlet row whose upstream-most particle
//! has moved a spacing Δx into the buffer gets a new particle (a new id) a spacing
//! behind it, and outlet particles past the domain's end are removed with every
//! particle that has left the domain. A row two spacings short is refilled at once,
//! with a rebuild; the default width, R plus a spacing, keeps the fluid's support in
//! the buffer full meanwhile.
//!
//! The start is checked (`checks`): an inlet holds fluid and no wall, an outlet can
//! be reached by the fluid, and one that keeps its particles' velocity does not start
//! at rest.

mod checks;
mod profile;

use crate::case::{Case, OpenKind, OutflowVelocity, Profile};
use crate::domain::Domain;
use crate::error::Result;
use crate::neighbours::NeighbourList;
use crate::particles::{Kind, Particles, Vector};
use crate::physics::eos::LinearEos;
use crate::physics::kernel::Kernel;
use rayon::prelude::*;
use std::collections::BTreeMap;

/// The case's buffers, resolved against its domain and particles.
pub struct OpenBoundaries<const D: usize> {
    buffers: Vec<Buffer<D>>,
    dx: f64,
}

struct Buffer<const D: usize> {
    axis: usize,
    /// The domain's end, where inflow enters and outflow leaves.
    end: f64,
    /// +1 when the domain lies towards +axis from `end`.
    inward: f64,
    width: f64,
    /// The section's bounds across the flow (infinite along `axis` and where the
    /// buffer spans the whole end).
    lo: Vector<D>,
    hi: Vector<D>,
    flow: Flow<D>,
}

enum Flow<const D: usize> {
    Inflow {
        velocity: Vector<D>,
        /// The laminar profile across the section, or none (uniform).
        profile: Option<profile::Laminar>,
        ramp: f64,
    },
    Outflow {
        density: f64,
        /// Whether the velocity is extrapolated from the fluid (or kept).
        extrapolated: bool,
    },
}

impl<const D: usize> Buffer<D> {
    /// Depth of `x` into the domain from its end, along the axis.
    fn depth(&self, x: &Vector<D>) -> f64 {
        (x[self.axis] - self.end) * self.inward
    }

    fn holds(&self, x: &Vector<D>) -> bool {
        self.depth(x) <= self.width && (0..D).all(|d| self.lo[d] <= x[d] && x[d] <= self.hi[d])
    }

    /// The point mirrored across the buffer's inner face.
    fn mirror(&self, x: &Vector<D>) -> Vector<D> {
        let mut m = *x;
        m[self.axis] = self.end + self.inward * (2.0 * self.width - self.depth(x));
        m
    }

    /// The inflow velocity at `x` and time `t`.
    fn inflow(&self, x: &Vector<D>, t: f64) -> Option<Vector<D>> {
        let Flow::Inflow {
            velocity,
            profile,
            ramp,
        } = &self.flow
        else {
            return None;
        };
        let ramped = if *ramp > 0.0 {
            (t / ramp).min(1.0)
        } else {
            1.0
        };
        let shape = profile.as_ref().map_or(1.0, |f| f.at(x.as_slice()));
        Some(velocity * (shape * ramped))
    }
}

impl<const D: usize> OpenBoundaries<D> {
    /// The buffers of `case` (validated), `None` when it has none; an error when an
    /// inlet holds no fluid or a wall, or the fluid cannot reach an outlet. A parabolic
    /// profile spans the fluid's section in the buffer, the particles' extent plus Δx/2.
    pub fn of(
        case: &Case,
        particles: &Particles<D>,
        domain: &Domain<D>,
        eos: &LinearEos,
    ) -> Result<Option<Self>> {
        if case.open_boundary.is_empty() {
            return Ok(None);
        }
        let dx = case.dx();
        let buffers: Vec<Buffer<D>> = case
            .open_boundary
            .iter()
            .map(|b| {
                let inward = b.inward();
                let end = if inward > 0.0 {
                    domain.lo[b.axis]
                } else {
                    domain.hi[b.axis]
                };
                let (mut lo, mut hi) = (
                    Vector::<D>::repeat(f64::NEG_INFINITY),
                    Vector::<D>::repeat(f64::INFINITY),
                );
                let across = (0..D).filter(|&d| d != b.axis);
                for (d, [l, h]) in across.zip(b.section.iter().flatten()) {
                    (lo[d], hi[d]) = (*l, *h);
                }
                let mut buffer = Buffer {
                    axis: b.axis,
                    end,
                    inward,
                    width: b.width_in(case),
                    lo,
                    hi,
                    flow: Flow::Outflow {
                        density: 0.0,
                        extrapolated: false,
                    },
                };
                buffer.flow = match b.kind {
                    OpenKind::Outlet => Flow::Outflow {
                        density: eos.density(b.pressure.unwrap_or(0.0)),
                        extrapolated: b.outflow_velocity.unwrap_or_default()
                            == OutflowVelocity::Extrapolated,
                    },
                    OpenKind::Inlet => Flow::Inflow {
                        velocity: Vector::from_iterator(b.velocity.iter().flatten().copied()),
                        profile: (b.profile == Some(Profile::Parabolic)).then(|| {
                            let (lo, hi) = section(&buffer, particles, dx);
                            profile::Laminar::across(b.axis, lo.as_slice(), hi.as_slice())
                        }),
                        ramp: b.ramp.unwrap_or(0.0),
                    },
                };
                buffer
            })
            .collect();
        let open = OpenBoundaries { buffers, dx };
        open.check_start(particles, domain)?;
        Ok(Some(open))
    }

    /// The buffer holding fluid particle `i`, if any.
    fn buffer_of(&self, p: &Particles<D>, i: usize) -> Option<&Buffer<D>> {
        (p.kind[i] == Kind::Fluid)
            .then(|| self.buffers.iter().find(|b| b.holds(&p.x[i])))
            .flatten()
    }

    /// Whether fluid particle `i` is in a buffer (its state is set, not integrated).
    pub fn in_buffer(&self, p: &Particles<D>, i: usize) -> bool {
        self.buffer_of(p, i).is_some()
    }

    /// One line per buffer: its kind, where it is, its width, where its inner face (the
    /// fluid's side) lies, and how many particles it holds now.
    pub fn describe(&self, p: &Particles<D>) -> String {
        let axes = ["x", "y", "z"];
        let mut text = String::new();
        for (k, b) in self.buffers.iter().enumerate() {
            let count = (0..p.len())
                .filter(|&i| p.kind[i] == Kind::Fluid && b.holds(&p.x[i]))
                .count();
            let kind = match b.flow {
                Flow::Inflow { .. } => "inlet",
                Flow::Outflow { .. } => "outlet",
            };
            let side = if b.inward > 0.0 { "lo" } else { "hi" };
            let axis = axes[b.axis];
            text.push_str(&format!(
                "  open_boundary[{k}]         {kind:<6} at {axis} {side} = {}: {} m wide, inner face \
                 at {axis} = {}, {count} particles\n",
                b.end,
                b.width,
                b.end + b.inward * b.width
            ));
        }
        text
    }

    /// Sets the buffer particles' state before an evaluation at time `t`: inflow
    /// velocity and extrapolated density at inlets, prescribed density at outlets.
    pub fn prepare<K: Kernel>(
        &self,
        p: &mut Particles<D>,
        list: &NeighbourList<D>,
        domain: &Domain<D>,
        kernel: &K,
        t: f64,
    ) {
        let state: Vec<Option<(Option<Vector<D>>, f64)>> = (0..p.len())
            .into_par_iter()
            .map(|i| {
                let buffer = self.buffer_of(p, i)?;
                let mirrored =
                    || self.extrapolate(p, list, domain, kernel, &buffer.mirror(&p.x[i]));
                Some(match buffer.flow {
                    Flow::Outflow {
                        density,
                        extrapolated,
                    } => {
                        let u = extrapolated.then(mirrored).flatten().map(|(_, u)| u);
                        (u, density)
                    }
                    Flow::Inflow { .. } => {
                        let rho = mirrored().map_or(p.rho[i], |(rho, _)| rho);
                        (buffer.inflow(&p.x[i], t), rho)
                    }
                })
            })
            .collect();
        p.u.par_iter_mut()
            .zip(p.rho.par_iter_mut())
            .zip(state.par_iter())
            .for_each(|((u, rho), s)| {
                if let Some((velocity, density)) = s {
                    if let Some(v) = velocity {
                        *u = *v;
                    }
                    *rho = *density;
                }
            });
    }

    /// Shepard interpolation of the density and the velocity of the fluid outside the
    /// buffers at `x`.
    fn extrapolate<K: Kernel>(
        &self,
        p: &Particles<D>,
        list: &NeighbourList<D>,
        domain: &Domain<D>,
        kernel: &K,
        x: &Vector<D>,
    ) -> Option<(f64, Vector<D>)> {
        let radius = kernel.radius();
        let (mut num, mut den, mut velocity) = (0.0, 0.0, Vector::<D>::zeros());
        list.for_candidates(x, |j| {
            if p.kind[j] != Kind::Fluid || self.buffers.iter().any(|b| b.holds(&p.x[j])) {
                return;
            }
            let r = domain.separation(x, &p.x[j]).norm();
            if r < radius {
                let wv = kernel.w(r) * p.mass[j] / p.rho[j];
                num += p.rho[j] * wv;
                velocity += p.u[j] * wv;
                den += wv;
            }
        });
        (den > 0.0).then(|| (num / den, velocity / den))
    }

    /// Zeroes the rates of the buffer particles (acceleration, continuity and its
    /// diffusive part): their state is what [`Self::prepare`] sets, and they move with
    /// their velocity.
    pub fn hold(
        &self,
        p: &Particles<D>,
        du: &mut [Vector<D>],
        drho: &mut [f64],
        drho_diff: &mut [f64],
    ) {
        du.par_iter_mut()
            .zip(drho.par_iter_mut())
            .zip(drho_diff.par_iter_mut())
            .enumerate()
            .for_each(|(i, ((du, drho), diff))| {
                if self.in_buffer(p, i) {
                    (*du, *drho, *diff) = (Vector::zeros(), 0.0, 0.0);
                }
            });
    }

    /// Whether an inlet row's upstream-most particle lies two spacings or more inside
    /// the domain's end: the buffer's outer layers then need [`Self::refill`] before
    /// the next step, without waiting for the next neighbour-list build.
    pub fn refill_due(&self, p: &Particles<D>) -> bool {
        self.inlets().any(|buffer| {
            rows(buffer, p, self.dx)
                .values()
                .any(|&i| buffer.depth(&p.x[i]) >= 2.0 * self.dx)
        })
    }

    /// Fills each inlet row up to the domain's end: a row (particles of one
    /// transverse lattice position) whose upstream-most particle lies a spacing or more
    /// inside gets new particles a spacing apart behind it, with its velocity and
    /// density and the mass `ρ Δx^D`. Returns how many were created.
    pub fn refill(&self, p: &mut Particles<D>) -> usize {
        let before = p.len();
        for buffer in self.inlets() {
            // a lattice cell's worth of fluid at the buffer's density: the mass flux
            // in is ρ_b u, as the prescribed velocity at that density makes it
            let cell = self.dx.powi(D as i32);
            for i in rows(buffer, p, self.dx).into_values() {
                let mut x = p.x[i];
                while buffer.depth(&x) >= self.dx {
                    x[buffer.axis] -= buffer.inward * self.dx;
                    let (u, rho) = (p.u[i], p.rho[i]);
                    p.push(Kind::Fluid, x, u, rho, rho * cell);
                }
            }
        }
        p.len() - before
    }

    fn inlets(&self) -> impl Iterator<Item = &Buffer<D>> {
        (self.buffers.iter()).filter(|b| matches!(b.flow, Flow::Inflow { .. }))
    }
}

/// The upstream-most particle of each row of `buffer`, by the row's transverse
/// lattice indices.
fn rows<const D: usize>(
    buffer: &Buffer<D>,
    p: &Particles<D>,
    dx: f64,
) -> BTreeMap<Vec<i64>, usize> {
    let mut first: BTreeMap<Vec<i64>, usize> = BTreeMap::new();
    for i in (0..p.len()).filter(|&i| p.kind[i] == Kind::Fluid && buffer.holds(&p.x[i])) {
        let row: Vec<i64> = (0..D)
            .filter(|&d| d != buffer.axis)
            .map(|d| (p.x[i][d] / dx).floor() as i64)
            .collect();
        let entry = first.entry(row).or_insert(i);
        if buffer.depth(&p.x[i]) < buffer.depth(&p.x[*entry]) {
            *entry = i;
        }
    }
    first
}

/// The fluid's section in the buffer: the particles' transverse extent, widened by
/// Δx/2 to the faces of the lattice cells they stand in.
fn section<const D: usize>(
    buffer: &Buffer<D>,
    p: &Particles<D>,
    dx: f64,
) -> (Vector<D>, Vector<D>) {
    let mut lo = Vector::<D>::repeat(f64::INFINITY);
    let mut hi = Vector::<D>::repeat(f64::NEG_INFINITY);
    for i in (0..p.len()).filter(|&i| p.kind[i] == Kind::Fluid && buffer.holds(&p.x[i])) {
        lo = lo.inf(&p.x[i]);
        hi = hi.sup(&p.x[i]);
    }
    (lo.add_scalar(-0.5 * dx), hi.add_scalar(0.5 * dx))
}
