//! Neighbour search: a cell-linked list turned into per-particle Verlet lists.
//!
//! Particles are binned into cubic cells of side `>= R + s` (R the kernel support,
//! s a skin), the arrays are reordered by cell so that neighbours sit close in
//! memory, and each particle gathers the indices of all particles closer than
//! `R + s` from its own and the 3^D adjacent cells (wrapped along periodic
//! directions). The lists stay valid while no particle has moved more than `s/2`
//! since the build; [`NeighbourList::needs_rebuild`] checks that bound. Pairs in
//! the skin contribute nothing because every kernel vanishes beyond R.
//!
//! Wall particles only keep fluid neighbours: they interact with the fluid
//! (pressure extrapolation) but never with each other.

use crate::domain::Domain;
use crate::particles::{Kind, Particles, Vector};
use rayon::prelude::*;

/// Verlet lists in compressed-row form plus the cell grid they came from.
#[derive(Debug, Clone, Default)]
pub struct NeighbourList<const D: usize> {
    /// `indices[offsets[i]..offsets[i+1]]` are the neighbours of particle i.
    pub offsets: Vec<usize>,
    pub indices: Vec<u32>,
    /// List radius `R + s`.
    pub radius: f64,
    /// Skin `s`.
    pub skin: f64,
    grid: Grid<D>,
    /// Positions at the last build, for the displacement bound.
    x_ref: Vec<Vector<D>>,
}

#[derive(Debug, Clone)]
struct Grid<const D: usize> {
    origin: Vector<D>,
    cell: Vector<D>,
    dims: [usize; D],
    periodic: [bool; D],
    /// Particles of cell c are `cell_start[c]..cell_start[c+1]` (arrays are sorted by cell).
    cell_start: Vec<usize>,
}

impl<const D: usize> Default for Grid<D> {
    fn default() -> Self {
        Self {
            origin: Vector::zeros(),
            cell: Vector::repeat(1.0),
            dims: [1; D],
            periodic: [false; D],
            cell_start: vec![0, 0],
        }
    }
}

/// The most cells a grid may have per particle (plus a fixed allowance): a scene whose
/// particles are scattered over a large box gets wider cells instead of memory that
/// grows with the box.
const CELLS_PER_PARTICLE: usize = 4;
const CELLS_ALLOWANCE: usize = 4096;

impl<const D: usize> Grid<D> {
    /// Cells of side at least `radius` covering the particles: the whole period along
    /// periodic directions, the particles' extent along the others.
    fn new(x: &[Vector<D>], domain: &Domain<D>, radius: f64) -> Self {
        let mut origin = Vector::zeros();
        let mut extent = Vector::zeros();
        let mut periodic = [false; D];
        for d in 0..D {
            if domain.is_periodic(d) {
                origin[d] = domain.lo[d];
                extent[d] = domain.period[d];
                periodic[d] = true;
            } else {
                let (lo, hi) = x.iter().fold((f64::MAX, f64::MIN), |(lo, hi), p| {
                    (lo.min(p[d]), hi.max(p[d]))
                });
                origin[d] = lo;
                extent[d] = (hi - lo).max(0.0);
            }
        }
        let budget = (CELLS_PER_PARTICLE * x.len() + CELLS_ALLOWANCE) as f64;
        let mut side = radius;
        loop {
            let dims = Self::dims_for(&extent, &periodic, side);
            if dims.iter().map(|&n| n as f64).product::<f64>() <= budget {
                let cell = Vector::from_fn(|d, _| {
                    if periodic[d] {
                        extent[d] / dims[d] as f64
                    } else {
                        side
                    }
                });
                return Self {
                    origin,
                    cell,
                    dims,
                    periodic,
                    cell_start: Vec::new(),
                };
            }
            side *= 1.5;
        }
    }

    /// Cells per axis for cells of side at least `side`: along a periodic direction a
    /// whole number of cells fills the period (one cell when the period is shorter
    /// than two sides; the stencil then visits each cell once).
    fn dims_for(extent: &Vector<D>, periodic: &[bool; D], side: f64) -> [usize; D] {
        std::array::from_fn(|d| {
            let n = (extent[d] / side).floor();
            if periodic[d] {
                n.max(1.0) as usize
            } else {
                n as usize + 1
            }
        })
    }

    /// The grid for positions `x` and the stable order that sorts them by cell.
    fn sorted(x: &[Vector<D>], domain: &Domain<D>, radius: f64) -> (Self, Vec<usize>) {
        let mut grid = Grid::new(x, domain, radius);
        let keys: Vec<usize> = x.iter().map(|p| grid.flat(&grid.coords(p))).collect();
        let order = counting_sort(&keys, grid.n_cells(), &mut grid.cell_start);
        (grid, order)
    }

    /// Cell coordinates of a point, clamped into the grid (open directions) or wrapped (periodic).
    fn coords(&self, p: &Vector<D>) -> [usize; D] {
        let mut c = [0usize; D];
        for d in 0..D {
            let k = ((p[d] - self.origin[d]) / self.cell[d]).floor() as i64;
            let n = self.dims[d] as i64;
            c[d] = if self.periodic[d] {
                k.rem_euclid(n)
            } else {
                k.clamp(0, n - 1)
            } as usize;
        }
        c
    }

    fn flat(&self, c: &[usize; D]) -> usize {
        let mut idx = 0;
        for d in (0..D).rev() {
            idx = idx * self.dims[d] + c[d];
        }
        idx
    }

    fn n_cells(&self) -> usize {
        self.dims.iter().product()
    }

    /// Calls `f(cell)` for the cell of `c` and its (up to 3^D) distinct neighbours.
    /// Along a periodic direction of fewer than three cells the wrapped offsets meet,
    /// and each cell is visited once.
    fn for_adjacent(&self, c: &[usize; D], mut f: impl FnMut(usize)) {
        let total = 3usize.pow(D as u32);
        'outer: for m in 0..total {
            let mut nc = [0usize; D];
            let mut rem = m;
            for d in 0..D {
                let off = (rem % 3) as i64 - 1;
                rem /= 3;
                let k = c[d] as i64 + off;
                let n = self.dims[d] as i64;
                if self.periodic[d] {
                    // offsets -1, 0, +1 name distinct cells only when n >= 3
                    if (n == 1 && off != 0) || (n == 2 && off == 1) {
                        continue 'outer;
                    }
                    nc[d] = k.rem_euclid(n) as usize;
                } else if k < 0 || k >= n {
                    continue 'outer;
                } else {
                    nc[d] = k as usize;
                }
            }
            f(self.flat(&nc));
        }
    }
}

impl<const D: usize> NeighbourList<D> {
    /// Reorders `particles` by cell (applying the same permutation to `extra` arrays
    /// through `reorder`) and builds the lists with radius `support + skin`.
    /// Returns the permutation: new index k holds old particle `order[k]`.
    pub fn build(
        particles: &mut Particles<D>,
        domain: &Domain<D>,
        support: f64,
        skin: f64,
    ) -> (Self, Vec<usize>) {
        let radius = support + skin;
        let (grid, order) = Grid::sorted(&particles.x, domain, radius);
        particles.permute(&order);
        let lists = gather_lists(particles, domain, &grid, radius);
        let list = Self::from_lists(lists, radius, skin, grid, particles.x.clone());
        (list, order)
    }

    /// Packs per-particle lists into compressed rows.
    fn from_lists(
        lists: Vec<Vec<u32>>,
        radius: f64,
        skin: f64,
        grid: Grid<D>,
        x_ref: Vec<Vector<D>>,
    ) -> Self {
        let mut offsets = Vec::with_capacity(lists.len() + 1);
        offsets.push(0);
        for l in &lists {
            offsets.push(offsets.last().unwrap() + l.len());
        }
        Self {
            offsets,
            indices: lists.concat(),
            radius,
            skin,
            grid,
            x_ref,
        }
    }

    /// Builds again the lists of an earlier [`Self::build`] whose positions were
    /// `reference` (a restarted run). The particles (of kinds `kind`) must still be in
    /// the order that build left them, so the rebuilt lists match it entry for entry;
    /// returns `None` when they are not.
    pub fn restore(
        kind: &[Kind],
        domain: &Domain<D>,
        support: f64,
        skin: f64,
        reference: Vec<Vector<D>>,
    ) -> Option<Self> {
        let radius = support + skin;
        let (grid, order) = Grid::sorted(&reference, domain, radius);
        if order.iter().enumerate().any(|(k, &o)| k != o) {
            return None;
        }
        let probe = Particles {
            x: reference,
            kind: kind.to_vec(),
            ..Default::default()
        };
        let lists = gather_lists(&probe, domain, &grid, radius);
        Some(Self::from_lists(lists, radius, skin, grid, probe.x))
    }

    /// Positions at the last build, in the current order.
    pub fn reference_positions(&self) -> &[Vector<D>] {
        &self.x_ref
    }

    /// Neighbours of particle i (within `R + s` at the last build).
    #[inline(always)]
    pub fn of(&self, i: usize) -> &[u32] {
        &self.indices[self.offsets[i]..self.offsets[i + 1]]
    }

    /// Mean number of listed neighbours per particle.
    pub fn mean_neighbours(&self) -> f64 {
        self.indices.len() as f64 / (self.offsets.len() - 1).max(1) as f64
    }

    /// The largest displacement of a particle since the build (infinite when the
    /// particle set changed since).
    pub fn max_displacement(&self, x: &[Vector<D>], domain: &Domain<D>) -> f64 {
        if self.x_ref.len() != x.len() {
            return f64::INFINITY;
        }
        x.par_iter()
            .zip(self.x_ref.par_iter())
            .map(|(a, b)| domain.separation(a, b).norm_squared())
            .reduce(|| 0.0, f64::max)
            .sqrt()
    }

    /// True when some particle may have moved more than `s/2` since the build,
    /// counting a further `lookahead` that the coming step may add.
    pub fn needs_rebuild(&self, x: &[Vector<D>], domain: &Domain<D>, lookahead: f64) -> bool {
        self.max_displacement(x, domain) + lookahead > 0.5 * self.skin
    }

    /// Calls `f(j)` for every particle in the cells that may hold particles within
    /// `R + s/2` of `point` (a superset: the caller measures distances).
    pub fn for_candidates(&self, point: &Vector<D>, mut f: impl FnMut(usize)) {
        let c = self.grid.coords(point);
        self.grid.for_adjacent(&c, |cell| {
            for j in self.grid.cell_start[cell]..self.grid.cell_start[cell + 1] {
                f(j);
            }
        });
    }
}

/// Stable counting sort of particle indices by cell key; fills `cell_start`.
fn counting_sort(keys: &[usize], n_cells: usize, cell_start: &mut Vec<usize>) -> Vec<usize> {
    let mut count = vec![0usize; n_cells + 1];
    for &k in keys {
        count[k + 1] += 1;
    }
    for c in 0..n_cells {
        count[c + 1] += count[c];
    }
    *cell_start = count.clone();
    let mut order = vec![0usize; keys.len()];
    for (i, &k) in keys.iter().enumerate() {
        order[count[k]] = i;
        count[k] += 1;
    }
    order
}

fn gather_lists<const D: usize>(
    particles: &Particles<D>,
    domain: &Domain<D>,
    grid: &Grid<D>,
    radius: f64,
) -> Vec<Vec<u32>> {
    let r2 = radius * radius;
    (0..particles.len())
        .into_par_iter()
        .map(|i| {
            let xi = &particles.x[i];
            let wall_i = particles.kind[i] == Kind::Wall;
            let mut list = Vec::with_capacity(64);
            grid.for_adjacent(&grid.coords(xi), |cell| {
                for j in grid.cell_start[cell]..grid.cell_start[cell + 1] {
                    if j == i || (wall_i && particles.kind[j] == Kind::Wall) {
                        continue;
                    }
                    if domain.separation(xi, &particles.x[j]).norm_squared() < r2 {
                        list.push(j as u32);
                    }
                }
            });
            list
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::rngs::SmallRng;
    use rand::{Rng, SeedableRng};

    fn random_set<const D: usize>(n: usize, seed: u64) -> Particles<D> {
        let mut rng = SmallRng::seed_from_u64(seed);
        let mut p = Particles::default();
        for _ in 0..n {
            let x = Vector::<D>::from_fn(|_, _| rng.random::<f64>());
            let kind = if rng.random::<f64>() < 0.2 {
                Kind::Wall
            } else {
                Kind::Fluid
            };
            p.push(kind, x, Vector::zeros(), 1.0, 1.0);
        }
        p
    }

    fn check<const D: usize>(periodic: [bool; D], seed: u64) {
        let mut p = random_set::<D>(if D == 2 { 3000 } else { 4000 }, seed);
        let domain = Domain::new(Vector::zeros(), Vector::repeat(1.0), periodic);
        let support = if D == 2 { 0.06 } else { 0.12 };
        let (list, _) = NeighbourList::build(&mut p, &domain, support, 0.01);
        let r2 = (support + 0.01f64).powi(2);
        let mut total = 0;
        for i in 0..p.len() {
            let mut brute: Vec<u32> = (0..p.len())
                .filter(|&j| {
                    j != i
                        && !(p.kind[i] == Kind::Wall && p.kind[j] == Kind::Wall)
                        && domain.separation(&p.x[i], &p.x[j]).norm_squared() < r2
                })
                .map(|j| j as u32)
                .collect();
            let mut got = list.of(i).to_vec();
            brute.sort_unstable();
            got.sort_unstable();
            assert_eq!(got, brute, "particle {i}");
            total += got.len();
        }
        assert!(total > 10 * p.len(), "the test set must have many pairs");
    }

    #[test]
    fn matches_brute_force_2d_open() {
        check::<2>([false, false], 1);
    }
    #[test]
    fn matches_brute_force_2d_periodic() {
        check::<2>([true, true], 2);
    }
    #[test]
    fn matches_brute_force_2d_mixed() {
        check::<2>([true, false], 3);
    }
    #[test]
    fn matches_brute_force_3d_open() {
        check::<3>([false, false, false], 4);
    }
    #[test]
    fn matches_brute_force_3d_periodic() {
        check::<3>([true, true, true], 5);
    }

    /// A list radius above a third of the period (two cells, or one) along a periodic
    /// axis: every pair once, by minimum image.
    #[test]
    fn matches_brute_force_with_two_and_one_periodic_cells() {
        for (support, skin) in [(0.3, 0.1), (0.45, 0.04)] {
            let mut p = random_set::<2>(400, 9);
            let domain = Domain::new(Vector::zeros(), Vector::repeat(1.0), [true, true]);
            let (list, _) = NeighbourList::build(&mut p, &domain, support, skin);
            let r2 = (support + skin) * (support + skin);
            for i in 0..p.len() {
                let mut brute: Vec<u32> = (0..p.len())
                    .filter(|&j| {
                        j != i
                            && !(p.kind[i] == Kind::Wall && p.kind[j] == Kind::Wall)
                            && domain.separation(&p.x[i], &p.x[j]).norm_squared() < r2
                    })
                    .map(|j| j as u32)
                    .collect();
                let mut got = list.of(i).to_vec();
                brute.sort_unstable();
                got.sort_unstable();
                assert_eq!(got, brute, "radius {}, particle {i}", support + skin);
            }
        }
    }

    /// Particles scattered far apart get wide cells, not a grid as large as their box.
    #[test]
    fn sparse_particles_keep_the_grid_small() {
        let mut p = random_set::<3>(200, 11);
        for (k, x) in p.x.iter_mut().enumerate().take(4) {
            *x *= 1.0e4 * (k + 1) as f64;
        }
        let (list, _) = NeighbourList::build(&mut p, &Domain::open(), 0.05, 0.01);
        let cells: usize = list.grid.dims.iter().product();
        assert!(
            cells <= CELLS_PER_PARTICLE * 200 + CELLS_ALLOWANCE,
            "{cells} cells"
        );
        for i in 0..p.len() {
            let brute = (0..p.len())
                .filter(|&j| j != i && !(p.kind[i] == Kind::Wall && p.kind[j] == Kind::Wall))
                .filter(|&j| (p.x[i] - p.x[j]).norm() < 0.06)
                .count();
            assert_eq!(list.of(i).len(), brute, "particle {i}");
        }
    }

    #[test]
    fn minimum_image_wraps_across_the_box() {
        let domain = Domain::<2>::new(Vector::zeros(), Vector::repeat(1.0), [true, false]);
        let s = domain.separation(&Vector::<2>::new(0.99, 0.5), &Vector::<2>::new(0.01, 0.2));
        assert!((s[0] + 0.02).abs() < 1e-12 && (s[1] - 0.3).abs() < 1e-12);
    }

    #[test]
    fn rebuild_is_requested_after_half_a_skin() {
        let mut p = random_set::<2>(200, 7);
        let domain = Domain::open();
        let (list, _) = NeighbourList::build(&mut p, &domain, 0.1, 0.02);
        assert!(!list.needs_rebuild(&p.x, &domain, 0.0));
        p.x[5][0] += 0.011;
        assert!(list.needs_rebuild(&p.x, &domain, 0.0));
    }
}
