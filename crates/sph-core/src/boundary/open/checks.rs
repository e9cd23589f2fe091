//! The open boundaries' checks against the particles at the start: an inlet's buffer
//! holds fluid (it is refilled from the rows it holds) and no wall across the inflow;
//! the fluid can reach each outlet, through cells of the lattice free of walls.

use super::{Buffer, Flow, OpenBoundaries};
use crate::domain::Domain;
use crate::error::{Result, SphError};
use crate::particles::{Kind, Particles, Vector};
use std::collections::VecDeque;

/// Beyond this many lattice cells in the domain the reachability of an outlet whose
/// buffer starts empty is not searched (50 MB of flags).
const MAX_CELLS: usize = 50_000_000;

impl<const D: usize> OpenBoundaries<D> {
    /// Every buffer's check, in case order.
    pub(super) fn check_start(&self, p: &Particles<D>, domain: &Domain<D>) -> Result<()> {
        for (k, b) in self.buffers.iter().enumerate() {
            let key = format!("open_boundary[{k}]");
            match b.flow {
                Flow::Inflow { .. } => check_inlet(&key, b, p, self.dx)?,
                Flow::Outflow { extrapolated, .. } => {
                    check_reachable(&key, b, p, domain, self.dx)?;
                    if !extrapolated {
                        check_moving(&key, b, p)?;
                    }
                }
            }
        }
        Ok(())
    }
}

/// An outlet that keeps its particles' velocity needs them leaving at the start: a
/// buffer whose fluid moves on average no faster than 1% of its fastest particle
/// outward (a flow started from rest, ramped up at the inlet) would stay where it is
/// and block the flow.
fn check_moving<const D: usize>(key: &str, b: &Buffer<D>, p: &Particles<D>) -> Result<()> {
    let outward: Vec<f64> = (0..p.len())
        .filter(|&i| p.kind[i] == Kind::Fluid && b.holds(&p.x[i]))
        .map(|i| -b.inward * p.u[i][b.axis])
        .collect();
    let fastest = p.u.iter().map(|u| u.norm()).fold(0.0, f64::max);
    let mean = outward.iter().sum::<f64>() / outward.len().max(1) as f64;
    if outward.is_empty() || mean > 0.01 * fastest.max(f64::MIN_POSITIVE) {
        return Ok(());
    }
    Err(SphError::invalid(
        format!("{key}.outflow_velocity"),
        "kept",
        format!(
            "\"extrapolated\" for an outlet whose fluid does not leave at the start (mean \
             outward speed {mean:.3e} m/s): kept, its particles would never leave"
        ),
    ))
}

fn rounded<const D: usize>(x: &Vector<D>) -> Vec<f64> {
    x.iter().map(|v| (v * 1e6).round() / 1e6).collect()
}

/// An inlet's buffer holds fluid, and no wall particle lies inside the fluid's
/// section there (walls beside the section, a channel's plates, are allowed).
fn check_inlet<const D: usize>(key: &str, b: &Buffer<D>, p: &Particles<D>, dx: f64) -> Result<()> {
    let (lo, hi) = super::section(b, p, dx);
    if (0..D).any(|d| lo[d] > hi[d]) {
        return Err(SphError::invalid(
            key,
            "no fluid in the inlet's buffer",
            "a buffer covered by a fluid block at the start (new particles enter \
             behind the rows it holds)",
        ));
    }
    let across = |x: &Vector<D>| (0..D).all(|d| d == b.axis || (lo[d] < x[d] && x[d] < hi[d]));
    let wall =
        (0..p.len()).find(|&i| p.kind[i] == Kind::Wall && b.holds(&p.x[i]) && across(&p.x[i]));
    match wall {
        Some(i) => Err(SphError::invalid(
            key,
            format!("a wall particle at {:?} inside the inlet", rounded(&p.x[i])),
            "an inlet free of walls across its inflow (move the wall, or the inlet's \
             side or section)",
        )),
        None => Ok(()),
    }
}

/// The fluid reaches an outlet when its buffer holds fluid, or when a path of
/// face-adjacent Δx cells free of wall particles (wrapping across periodic axes) leads
/// from a fluid particle's cell to a cell whose centre lies in the buffer.
fn check_reachable<const D: usize>(
    key: &str,
    b: &Buffer<D>,
    p: &Particles<D>,
    domain: &Domain<D>,
    dx: f64,
) -> Result<()> {
    let fluid = |i: &usize| p.kind[*i] == Kind::Fluid;
    if (0..p.len()).filter(fluid).any(|i| b.holds(&p.x[i])) {
        return Ok(());
    }
    let cells = Cells::<D>::new(domain, dx);
    if cells.len() > MAX_CELLS {
        return Ok(());
    }
    let mut state = vec![FREE; cells.len()];
    for i in (0..p.len()).filter(|i| !fluid(i)) {
        state[cells.index(&p.x[i])] = WALL;
    }
    let mut queue: VecDeque<usize> = (0..p.len())
        .filter(fluid)
        .map(|i| cells.index(&p.x[i]))
        .collect();
    for &c in &queue {
        state[c] = REACHED;
    }
    while let Some(c) = queue.pop_front() {
        if b.holds(&cells.centre(c)) {
            return Ok(());
        }
        cells.for_neighbours(c, domain, |n| {
            if state[n] == FREE {
                state[n] = REACHED;
                queue.push_back(n);
            }
        });
    }
    Err(SphError::invalid(
        key,
        "no way from the fluid to the outlet",
        "an outlet the fluid can reach: walls close every path to its buffer (open \
         the tank's face there, or move the outlet)",
    ))
}

const FREE: u8 = 0;
const WALL: u8 = 1;
const REACHED: u8 = 2;

/// The domain cut into cells of side Δx, numbered with axis 0 fastest.
struct Cells<const D: usize> {
    lo: Vector<D>,
    dx: f64,
    n: [usize; D],
}

impl<const D: usize> Cells<D> {
    fn new(domain: &Domain<D>, dx: f64) -> Self {
        let n =
            std::array::from_fn(|d| (((domain.hi[d] - domain.lo[d]) / dx).ceil() as usize).max(1));
        Self {
            lo: domain.lo,
            dx,
            n,
        }
    }

    fn len(&self) -> usize {
        self.n.iter().product()
    }

    fn index(&self, x: &Vector<D>) -> usize {
        (0..D).rev().fold(0, |acc, d| {
            let c = ((x[d] - self.lo[d]) / self.dx).floor().max(0.0) as usize;
            acc * self.n[d] + c.min(self.n[d] - 1)
        })
    }

    fn coords(&self, mut c: usize) -> [usize; D] {
        std::array::from_fn(|d| {
            let k = c % self.n[d];
            c /= self.n[d];
            k
        })
    }

    fn centre(&self, c: usize) -> Vector<D> {
        let k = self.coords(c);
        Vector::from_fn(|d, _| self.lo[d] + (k[d] as f64 + 0.5) * self.dx)
    }

    /// Calls `f` with each face neighbour of cell `c`.
    fn for_neighbours(&self, c: usize, domain: &Domain<D>, mut f: impl FnMut(usize)) {
        let k = self.coords(c);
        let mut stride = 1;
        for (d, &kd) in k.iter().enumerate() {
            let n = self.n[d];
            let periodic = domain.is_periodic(d);
            if kd + 1 < n {
                f(c + stride);
            } else if periodic && n > 1 {
                f(c + stride - n * stride);
            }
            if kd > 0 {
                f(c - stride);
            } else if periodic && n > 1 {
                f(c + (n - 1) * stride);
            }
            stride *= n;
        }
    }
}
