//! Domain decomposition by recursive coordinate bisection (RCB; Berger & Bokhari 1987,
//! IEEE Trans. Comput. C-36:570) for runs split over P processes.
//!
//! The domain's box is cut by a plane across the longest extent of the particles it
//! holds, at the weighted quantile that gives each side its share of the processes
//! (⌊P/2⌋ and ⌈P/2⌉, so any P works, not only powers of two), and each side is cut
//! again until every process has a box. The weight is the work a particle brings:
//! 1 for fluid particles (the rows of the pair loops), 0 for walls (neighbours only).
//! A cut lies midway between two particle coordinates, never through a particle; on a
//! lattice it falls between two columns, so a box's share is exact to within a
//! column.
//!
//! A process needs, besides its own particles, the **halo**: every particle of the
//! others within the list radius of its box, at least the kernel support
//! (minimum image across periodic directions).

use crate::domain::Domain;
use crate::particles::{Kind, Particles, Vector};

/// The boxes of P processes and the cuts that made them.
#[derive(Debug, Clone)]
pub struct Decomposition<const D: usize> {
    nodes: Vec<Node>,
    boxes: Vec<Cell<D>>,
    /// The box that was cut.
    whole: Cell<D>,
}

/// A subdomain: the box `[lo, hi]` of one process.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cell<const D: usize> {
    pub lo: Vector<D>,
    pub hi: Vector<D>,
}

#[derive(Debug, Clone, Copy)]
enum Node {
    Leaf {
        rank: usize,
    },
    Cut {
        axis: usize,
        at: f64,
        below: usize,
        above: usize,
    },
}

impl<const D: usize> Cell<D> {
    /// The distance from `x` to the box (0 inside), by minimum image along the
    /// periodic directions of `domain`.
    pub fn distance(&self, x: &Vector<D>, domain: &Domain<D>) -> f64 {
        let centre = (self.lo + self.hi) * 0.5;
        let half = (self.hi - self.lo) * 0.5;
        let offset = domain.separation(x, &centre);
        (0..D)
            .map(|d| (offset[d].abs() - half[d]).max(0.0).powi(2))
            .sum::<f64>()
            .sqrt()
    }
}

impl<const D: usize> Decomposition<D> {
    /// Splits `domain` among `ranks` processes by the particles' positions, each fluid
    /// particle weighing 1 (see the module). `ranks` ≥ 1; a domain open along some
    /// direction is bounded there by the particles' extent.
    pub fn bisect(particles: &Particles<D>, domain: &Domain<D>, ranks: usize) -> Self {
        Self::bisect_points(&particles.x, &particles.kind, domain, ranks)
    }

    /// [`Self::bisect`] of the particles at `x` of kinds `kind`.
    pub fn bisect_points(x: &[Vector<D>], kind: &[Kind], domain: &Domain<D>, ranks: usize) -> Self {
        let ranks = ranks.max(1);
        let weights: Vec<f64> = (kind.iter())
            .map(|k| if *k == Kind::Fluid { 1.0 } else { 0.0 })
            .collect();
        let points: Vec<usize> = (0..x.len()).collect();
        let whole = Cell {
            lo: Vector::from_fn(|d, _| bound(domain.lo[d], x, d, f64::min)),
            hi: Vector::from_fn(|d, _| bound(domain.hi[d], x, d, f64::max)),
        };
        let mut split = Self {
            nodes: Vec::new(),
            boxes: vec![whole; ranks],
            whole,
        };
        split.cut(x, &weights, points, whole, 0..ranks);
        split
    }

    /// Cuts `cell`, holding the particles `points`, among the processes `ranks`;
    /// returns the index of the node made.
    fn cut(
        &mut self,
        x: &[Vector<D>],
        weights: &[f64],
        mut points: Vec<usize>,
        cell: Cell<D>,
        ranks: std::ops::Range<usize>,
    ) -> usize {
        let here = self.nodes.len();
        if ranks.len() == 1 {
            self.nodes.push(Node::Leaf { rank: ranks.start });
            self.boxes[ranks.start] = cell;
            return here;
        }
        self.nodes.push(Node::Leaf { rank: ranks.start });
        let axis = longest_axis(x, &points, &cell);
        points.sort_by(|&i, &j| x[i][axis].total_cmp(&x[j][axis]));
        let lower = ranks.len() / 2;
        let share = lower as f64 / ranks.len() as f64;
        let k = split_index(x, weights, &points, axis, share);
        let at = match (points.get(k.wrapping_sub(1)), points.get(k)) {
            (Some(&a), Some(&b)) => 0.5 * (x[a][axis] + x[b][axis]),
            _ => cell.lo[axis] + share * (cell.hi[axis] - cell.lo[axis]),
        };
        let above_points = points.split_off(k);
        let (mut below_cell, mut above_cell) = (cell, cell);
        below_cell.hi[axis] = at;
        above_cell.lo[axis] = at;
        let mid = ranks.start + lower;
        let below = self.cut(x, weights, points, below_cell, ranks.start..mid);
        let above = self.cut(x, weights, above_points, above_cell, mid..ranks.end);
        self.nodes[here] = Node::Cut {
            axis,
            at,
            below,
            above,
        };
        here
    }

    /// The number of processes.
    pub fn ranks(&self) -> usize {
        self.boxes.len()
    }

    /// The box of process `rank`.
    pub fn cell(&self, rank: usize) -> &Cell<D> {
        &self.boxes[rank]
    }

    /// The process that owns a particle at `x` (below a cut: the lower side).
    pub fn owner(&self, x: &Vector<D>) -> usize {
        let mut node = 0;
        loop {
            match self.nodes[node] {
                Node::Leaf { rank } => return rank,
                Node::Cut {
                    axis,
                    at,
                    below,
                    above,
                } => node = if x[axis] < at { below } else { above },
            }
        }
    }

    /// The distance from `x` to the region process `rank` owns: its box, open beyond
    /// the faces it shares with the whole box along non-periodic directions (a particle
    /// that moves out of the whole box stays with the process below or above the cuts),
    /// by minimum image along periodic ones.
    pub fn region_distance(&self, rank: usize, x: &Vector<D>, domain: &Domain<D>) -> f64 {
        let cell = &self.boxes[rank];
        let centre = (cell.lo + cell.hi) * 0.5;
        let offset = domain.separation(x, &centre);
        (0..D)
            .map(|d| {
                let gap = if domain.is_periodic(d) {
                    offset[d].abs() - 0.5 * (cell.hi[d] - cell.lo[d])
                } else {
                    let lo = if cell.lo[d] <= self.whole.lo[d] {
                        f64::NEG_INFINITY
                    } else {
                        cell.lo[d]
                    };
                    let hi = if cell.hi[d] >= self.whole.hi[d] {
                        f64::INFINITY
                    } else {
                        cell.hi[d]
                    };
                    (lo - x[d]).max(x[d] - hi)
                };
                gap.max(0.0).powi(2)
            })
            .sum::<f64>()
            .sqrt()
    }

    /// The particles that process `rank` needs from the others: those it does not own
    /// (`owners[i]` is particle i's, from [`Self::owner`]) within `radius` of its box.
    pub fn halo(
        &self,
        rank: usize,
        x: &[Vector<D>],
        owners: &[usize],
        domain: &Domain<D>,
        radius: f64,
    ) -> Vec<usize> {
        let cell = self.boxes[rank];
        (0..x.len())
            .filter(|&i| owners[i] != rank && cell.distance(&x[i], domain) < radius)
            .collect()
    }
}

/// Bytes of one halo particle in an exchange: position and velocity (D doubles each),
/// density and mass (doubles), id (8 bytes) and kind (1 byte).
pub fn halo_bytes(dimension: usize) -> usize {
    (2 * dimension + 2) * 8 + 9
}

impl<const D: usize> Decomposition<D> {
    /// One line per process (its box, fluid and wall particles, halo within `radius`
    /// and the bytes of one halo exchange), then the load imbalance (largest fluid
    /// share over the mean) and the halo's size against the particles owned.
    pub fn describe(&self, p: &Particles<D>, domain: &Domain<D>, radius: f64) -> String {
        let mut text = String::new();
        let (mut most, mut halo_total) = (0usize, 0usize);
        let fluid_total = p.kind.iter().filter(|k| **k == Kind::Fluid).count();
        let owners: Vec<usize> = p.x.iter().map(|x| self.owner(x)).collect();
        for rank in 0..self.ranks() {
            let owned: Vec<usize> = (0..p.len()).filter(|&i| owners[i] == rank).collect();
            let fluid = owned.iter().filter(|&&i| p.kind[i] == Kind::Fluid).count();
            let halo = self.halo(rank, &p.x, &owners, domain, radius).len();
            (most, halo_total) = (most.max(fluid), halo_total + halo);
            let cell = self.cell(rank);
            text.push_str(&format!(
                "  rank {rank:<4} box {:.4?} – {:.4?}: {fluid} fluid, {} wall, halo {halo} \
                 ({:.1} kB per exchange)\n",
                cell.lo.as_slice(),
                cell.hi.as_slice(),
                owned.len() - fluid,
                (halo * halo_bytes(D)) as f64 / 1e3,
            ));
        }
        let mean = fluid_total as f64 / self.ranks() as f64;
        text.push_str(&format!(
            "  imbalance {:.3} (largest fluid share over the mean), halo {halo_total} \
             particles = {:.1}% of all, within R = {radius:.4} m of each box\n",
            most as f64 / mean.max(1.0),
            100.0 * halo_total as f64 / p.len().max(1) as f64,
        ));
        text
    }
}

/// The domain's bound `limit` along `d`, or the particles' extent where it is infinite.
fn bound<const D: usize>(limit: f64, x: &[Vector<D>], d: usize, pick: fn(f64, f64) -> f64) -> f64 {
    if limit.is_finite() {
        return limit;
    }
    x.iter()
        .map(|p| p[d])
        .fold(pick(f64::INFINITY, f64::NEG_INFINITY), pick)
}

/// The axis of the largest extent of `points` (of `cell` when there are none).
fn longest_axis<const D: usize>(x: &[Vector<D>], points: &[usize], cell: &Cell<D>) -> usize {
    let extent = |d: usize| {
        let (lo, hi) = points
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &i| {
                (l.min(x[i][d]), h.max(x[i][d]))
            });
        if points.is_empty() {
            cell.hi[d] - cell.lo[d]
        } else {
            hi - lo
        }
    };
    (0..D)
        .max_by(|&a, &b| extent(a).total_cmp(&extent(b)))
        .unwrap_or(0)
}

/// Where to split `points` (sorted along `axis`) so that the part below holds the
/// fraction `share` of their weight as nearly as the coordinates allow: the index of
/// the first point above, never between two points at the same coordinate.
fn split_index<const D: usize>(
    x: &[Vector<D>],
    weights: &[f64],
    points: &[usize],
    axis: usize,
    share: f64,
) -> usize {
    let total: f64 = points.iter().map(|&i| weights[i]).sum();
    let target = share * total;
    // candidate splits: where the coordinate changes; pick the one nearest the target
    let mut best = (f64::INFINITY, points.len() / 2);
    let mut below = 0.0;
    for k in 1..points.len() {
        below += weights[points[k - 1]];
        if x[points[k]][axis] > x[points[k - 1]][axis] {
            let miss = (below - target).abs();
            if miss < best.0 {
                best = (miss, k);
            }
        }
    }
    best.1
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector2;

    /// A lattice of `n × m` fluid particles of spacing 1 in `[0, n] × [0, m]`, with a
    /// column of walls at x = -0.5.
    fn lattice(n: usize, m: usize) -> Particles<2> {
        let mut p = Particles::<2>::default();
        for i in 0..n {
            for j in 0..m {
                let x = Vector2::new(i as f64 + 0.5, j as f64 + 0.5);
                p.push(Kind::Fluid, x, Vector2::zeros(), 1.0, 1.0);
            }
        }
        for j in 0..m {
            let x = Vector2::new(-0.5, j as f64 + 0.5);
            p.push(Kind::Wall, x, Vector2::zeros(), 1.0, 1.0);
        }
        p
    }

    fn domain(periodic: [bool; 2]) -> Domain<2> {
        Domain::new(Vector2::new(-1.0, 0.0), Vector2::new(40.0, 30.0), periodic)
    }

    #[test]
    fn every_particle_has_one_owner_and_the_shares_are_within_a_column() {
        let p = lattice(40, 30);
        for ranks in 1..=7 {
            let split = Decomposition::bisect(&p, &domain([false; 2]), ranks);
            let mut fluid = vec![0usize; ranks];
            for i in 0..p.len() {
                let owner = split.owner(&p.x[i]);
                let cell = split.cell(owner);
                assert!((0..2).all(|d| cell.lo[d] <= p.x[i][d] && p.x[i][d] <= cell.hi[d]));
                if p.kind[i] == Kind::Fluid {
                    fluid[owner] += 1;
                }
            }
            assert_eq!(fluid.iter().sum::<usize>(), 1200);
            // the cuts fall between rows of 30 (or columns of 40) particles; each level
            // of cuts can miss the share by half a row
            let fair = 1200.0 / ranks as f64;
            let levels = (ranks as f64).log2().ceil();
            for f in &fluid {
                assert!(
                    (*f as f64 - fair).abs() <= 20.0 * levels,
                    "{ranks}: {fluid:?}"
                );
            }
        }
    }

    #[test]
    fn the_halo_holds_every_foreign_neighbour_and_nothing_farther() {
        let p = lattice(40, 30);
        let radius = 2.5;
        for periodic in [[false, false], [true, true]] {
            let dom = domain(periodic);
            let split = Decomposition::bisect(&p, &dom, 4);
            let owners: Vec<usize> = p.x.iter().map(|x| split.owner(x)).collect();
            for rank in 0..4 {
                let halo = split.halo(rank, &p.x, &owners, &dom, radius);
                let owned: Vec<usize> = (0..p.len()).filter(|&i| owners[i] == rank).collect();
                for j in (0..p.len()).filter(|&j| owners[j] != rank) {
                    let near = owned
                        .iter()
                        .any(|&i| dom.separation(&p.x[i], &p.x[j]).norm() < radius);
                    if near {
                        assert!(halo.contains(&j), "rank {rank} misses particle {j}");
                    }
                }
                let cell = split.cell(rank);
                assert!(halo.iter().all(|&j| cell.distance(&p.x[j], &dom) < radius));
            }
        }
    }
}
