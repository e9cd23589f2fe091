//! Neighbour search: a cell-linked list (`grid`) turned into per-particle Verlet
//! lists, culled at every step to the pairs the step can use.
//!
//! - **Build.** Particles are binned into cubic cells of side `>= R + s` (R the kernel
//!   support, s a skin), the arrays are reordered by cell so that neighbours sit close
//!   in memory, and each particle gathers the particles closer than `R + s` from its
//!   own and the 3^D adjacent cells (wrapped along periodic directions). The rows are
//!   built and kept in blocks of `CHUNK` particles (`RowBlock`), one parallel task
//!   each, so that no list is ever copied into a second buffer. Each row holds the
//!   fluid neighbours first, then the walls: the pair loops run the two parts
//!   separately, with no per-pair branch on the kind. Wall particles keep only fluid
//!   neighbours (they interact with the fluid, for the pressure extrapolation, never
//!   with each other).
//! - **Validity.** The lists hold every pair closer than `R + s - 2δ` while no particle
//!   has moved more than δ since the build; [`NeighbourList::max_displacement`] gives δ.
//! - **Culling.** A step whose particles move by at most `ρ` (its reach) can only use
//!   pairs closer than `R + 2ρ` at its start. [`NeighbourList::cull`] moves those to
//!   the front of each part of the row (fluid, walls), in place, so that the gradient
//!   pass and every stage of the step skip the skin: a larger skin then costs a cheap
//!   distance test per listed pair and step instead of a full pair evaluation in every
//!   pass, and the lists are rebuilt less often. Culling in place keeps one copy of the
//!   rows; the culled part is kept in increasing index order, so that it (and the order
//!   of every pair sum) depends only on the positions, not on the culls before it: a
//!   restarted run, which builds its lists again, sums in the same order.

mod grid;
mod policy;

pub use policy::{ListPolicy, MIN_SKIN, SKIN_OVER_REACH};

use crate::domain::Domain;
use crate::particles::{Kind, Particles, Vector};
use grid::Grid;
use rayon::prelude::*;

/// Particles per block of rows: the unit of the parallel build and culling.
const CHUNK: usize = 256;

/// Verlet lists in blocks of rows, and the cell grid they came from.
#[derive(Debug, Clone, Default)]
pub struct NeighbourList<const D: usize> {
    /// Particle i's row is row `i % CHUNK` of block `i / CHUNK`.
    blocks: Vec<RowBlock>,
    /// List radius `R + s`.
    radius: f64,
    /// Skin `s`.
    skin: f64,
    grid: Grid<D>,
    /// Positions at the last build, for the displacement bound.
    x_ref: Vec<Vector<D>>,
    /// The wall particles, in order.
    walls: Vec<usize>,
}

/// The rows of [`CHUNK`] consecutive particles in compressed-row form; each part of a
/// row (fluid, walls) holds its culled entries first, in increasing index order.
#[derive(Debug, Clone, Default)]
struct RowBlock {
    /// Row k is `indices[start[k]..start[k + 1]]`: fluid neighbours before
    /// `wall_start[k]`, wall neighbours after.
    start: Vec<u32>,
    wall_start: Vec<u32>,
    indices: Vec<u32>,
    /// How many entries of each row's fluid and wall parts the last cull kept.
    fluid_len: Vec<u32>,
    wall_len: Vec<u32>,
}

/// Moves the entries `j` of `part` for which `near(j)` holds to its front, in
/// increasing order, and returns how many there are; the first `sorted` entries are
/// in increasing order (the last call's near entries), `far` is scratch room as long
/// as `part`. The near entries are compacted in place and the others gathered in
/// `far`, both branch-free, so the near ones among the first `sorted` stay in order;
/// from one step to the next only a few pairs enter the radius, and only those are
/// sorted into place.
fn keep_sorted(
    part: &mut [u32],
    sorted: usize,
    far: &mut [u32],
    near: impl Fn(u32) -> bool,
) -> usize {
    let (mut m, mut q, len) = (0, 0, part.len());
    let mut compact = |range: std::ops::Range<usize>| {
        for e in range {
            let j = part[e];
            let keep = near(j);
            part[m] = j;
            far[q] = j;
            m += usize::from(keep);
            q += usize::from(!keep);
        }
        m
    };
    let in_order = compact(0..sorted);
    compact(sorted..len);
    part[m..].copy_from_slice(&far[..q]);
    for k in in_order.max(1)..m {
        let v = part[k];
        let mut p = k;
        while p > 0 && part[p - 1] > v {
            part[p] = part[p - 1];
            p -= 1;
        }
        part[p] = v;
    }
    m
}

impl<const D: usize> NeighbourList<D> {
    /// Reorders `particles` by cell and builds the lists with radius `support + skin`.
    /// Returns the permutation: new index k holds old particle `order[k]`.
    pub fn build(
        particles: &mut Particles<D>,
        domain: &Domain<D>,
        support: f64,
        skin: f64,
    ) -> (Self, Vec<usize>) {
        Self::build_rows(particles, domain, support, skin, |_, _| true)
    }

    /// [`Self::build`], with rows only for the particles whose position and kind
    /// `listed` accepts (the others' rows are empty: the part of a split run's halo
    /// whose results its own particles do not read).
    pub fn build_rows(
        particles: &mut Particles<D>,
        domain: &Domain<D>,
        support: f64,
        skin: f64,
        listed: impl Fn(&Vector<D>, Kind) -> bool + Sync,
    ) -> (Self, Vec<usize>) {
        let radius = support + skin;
        let (grid, order) = Grid::sorted(&particles.x, domain, radius);
        particles.permute(&order);
        let (x, kind) = (&particles.x, &particles.kind);
        let list = Self::gather(x, kind, domain, grid, radius, skin, listed);
        (list, order)
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
        Some(Self::gather(
            &reference,
            kind,
            domain,
            grid,
            radius,
            skin,
            |_, _| true,
        ))
    }

    /// The Verlet rows of the particles at `x` (sorted by cell in `grid`) that `listed`
    /// accepts, empty rows for the others; all kept.
    fn gather(
        x: &[Vector<D>],
        kind: &[Kind],
        domain: &Domain<D>,
        grid: Grid<D>,
        radius: f64,
        skin: f64,
        listed: impl Fn(&Vector<D>, Kind) -> bool + Sync,
    ) -> Self {
        let n = x.len();
        let r2 = radius * radius;
        let blocks: Vec<RowBlock> = (0..n.div_ceil(CHUNK))
            .into_par_iter()
            .map(|c| {
                let rows = c * CHUNK..((c + 1) * CHUNK).min(n);
                let mut block = RowBlock {
                    start: Vec::with_capacity(rows.len() + 1),
                    wall_start: Vec::with_capacity(rows.len()),
                    indices: Vec::with_capacity(rows.len() * 48),
                    fluid_len: Vec::with_capacity(rows.len()),
                    wall_len: Vec::with_capacity(rows.len()),
                };
                block.start.push(0);
                let mut walls = Vec::with_capacity(32);
                for i in rows {
                    let (xi, wall_i) = (&x[i], kind[i] == Kind::Wall);
                    if listed(xi, kind[i]) {
                        grid.for_adjacent(&grid.coords(xi), |cell| {
                            for j in grid.cell_range(cell) {
                                if j == i || domain.separation(xi, &x[j]).norm_squared() >= r2 {
                                    continue;
                                }
                                match kind[j] {
                                    Kind::Fluid => block.indices.push(j as u32),
                                    Kind::Wall if !wall_i => walls.push(j as u32),
                                    Kind::Wall => {}
                                }
                            }
                        });
                    }
                    let (s, w) = (
                        block.start[block.start.len() - 1] as usize,
                        block.indices.len(),
                    );
                    // cells visited in increasing order give sorted rows (a periodic
                    // wrap does not)
                    for part in [&mut block.indices[s..w], &mut walls[..]] {
                        if !part.is_sorted() {
                            part.sort_unstable();
                        }
                    }
                    block.wall_start.push(w as u32);
                    block.indices.extend_from_slice(&walls);
                    block.start.push(block.indices.len() as u32);
                    block.fluid_len.push((w - s) as u32);
                    block.wall_len.push(walls.len() as u32);
                    walls.clear();
                }
                block.indices.shrink_to_fit();
                block
            })
            .collect();
        Self {
            blocks,
            radius,
            skin,
            grid,
            x_ref: x.to_vec(),
            walls: (0..n).filter(|&i| kind[i] == Kind::Wall).collect(),
        }
    }

    /// The wall particles (their indices in the current order).
    pub fn wall_particles(&self) -> &[usize] {
        &self.walls
    }

    /// Keeps, in every row, the listed neighbours closer than `radius` at positions
    /// `x`: the pairs a step whose particles move by at most `(radius - R)/2` can use.
    /// `radius` must not exceed `R + s - 2δ` (δ the displacement since the build), so
    /// that no pair closer than it is missing from the Verlet rows.
    pub fn cull(&mut self, x: &[Vector<D>], domain: &Domain<D>, radius: f64) {
        let r2 = radius * radius;
        self.blocks
            .par_iter_mut()
            .enumerate()
            .for_each(|(c, block)| {
                let RowBlock {
                    start,
                    wall_start,
                    indices,
                    fluid_len,
                    wall_len,
                } = block;
                let longest = start.windows(2).map(|r| r[1] - r[0]).max();
                let mut far = vec![0; longest.unwrap_or(0) as usize];
                for k in 0..fluid_len.len() {
                    let xi = &x[c * CHUNK + k];
                    let near = |j: u32| domain.separation(xi, &x[j as usize]).norm_squared() < r2;
                    let (s, w, e) = (
                        start[k] as usize,
                        wall_start[k] as usize,
                        start[k + 1] as usize,
                    );
                    let (fluid, walls) = indices[s..e].split_at_mut(w - s);
                    fluid_len[k] = keep_sorted(fluid, fluid_len[k] as usize, &mut far, near) as u32;
                    wall_len[k] = keep_sorted(walls, wall_len[k] as usize, &mut far, near) as u32;
                }
            });
    }

    /// List radius `R + s`.
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// Skin `s`.
    pub fn skin(&self) -> f64 {
        self.skin
    }

    /// Positions at the last build, in the current order.
    pub fn reference_positions(&self) -> &[Vector<D>] {
        &self.x_ref
    }

    /// Particle i's block of rows and its row there.
    #[inline(always)]
    fn row(&self, i: usize) -> (&RowBlock, usize) {
        (&self.blocks[i / CHUNK], i % CHUNK)
    }

    /// Fluid neighbours of particle i (culled).
    #[inline(always)]
    pub fn fluid(&self, i: usize) -> &[u32] {
        let (block, k) = self.row(i);
        let s = block.start[k] as usize;
        &block.indices[s..s + block.fluid_len[k] as usize]
    }

    /// Wall neighbours of particle i (culled; none for a wall particle).
    #[inline(always)]
    pub fn walls(&self, i: usize) -> &[u32] {
        let (block, k) = self.row(i);
        let s = block.wall_start[k] as usize;
        &block.indices[s..s + block.wall_len[k] as usize]
    }

    /// Every neighbour of particle i (culled): the fluid ones, then the walls.
    #[inline(always)]
    pub fn of(&self, i: usize) -> impl Iterator<Item = usize> + '_ {
        self.fluid(i)
            .iter()
            .chain(self.walls(i))
            .map(|&j| j as usize)
    }

    /// Mean number of neighbours per particle in the Verlet lists, and in the culled rows.
    pub fn mean_neighbours(&self) -> (f64, f64) {
        let n = self.x_ref.len().max(1) as f64;
        let (listed, active) = self.blocks.iter().fold((0, 0), |(l, a), b| {
            let kept: u64 = b
                .fluid_len
                .iter()
                .chain(&b.wall_len)
                .map(|&c| c as u64)
                .sum();
            (l + b.indices.len() as u64, a + kept)
        });
        (listed as f64 / n, active as f64 / n)
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

    /// Calls `f(j)` for every particle in the cells that may hold particles within
    /// `R + s/2` of `point` (a superset: the caller measures distances).
    pub fn for_candidates(&self, point: &Vector<D>, mut f: impl FnMut(usize)) {
        let c = self.grid.coords(point);
        self.grid.for_adjacent(&c, |cell| {
            for j in self.grid.cell_range(cell) {
                f(j);
            }
        });
    }
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
        let total = assert_brute_force(&p, &domain, &list, support + 0.01);
        assert!(total > 10 * p.len(), "the test set must have many pairs");
    }

    /// Asserts that every row holds exactly the pairs closer than `radius` (no wall-wall
    /// pairs), found by testing all pairs; returns the number of pairs listed.
    fn assert_brute_force<const D: usize>(
        p: &Particles<D>,
        domain: &Domain<D>,
        list: &NeighbourList<D>,
        radius: f64,
    ) -> usize {
        let mut total = 0;
        for i in 0..p.len() {
            let mut brute: Vec<u32> = (0..p.len())
                .filter(|&j| {
                    j != i
                        && !(p.kind[i] == Kind::Wall && p.kind[j] == Kind::Wall)
                        && domain.separation(&p.x[i], &p.x[j]).norm_squared() < radius * radius
                })
                .map(|j| j as u32)
                .collect();
            let mut got: Vec<u32> = list.of(i).map(|j| j as u32).collect();
            brute.sort_unstable();
            got.sort_unstable();
            assert_eq!(got, brute, "radius {radius}, particle {i}");
            total += got.len();
        }
        total
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
            assert_brute_force(&p, &domain, &list, support + skin);
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
            cells <= grid::CELLS_PER_PARTICLE * 200 + grid::CELLS_ALLOWANCE,
            "{cells} cells"
        );
        for i in 0..p.len() {
            let brute = (0..p.len())
                .filter(|&j| j != i && !(p.kind[i] == Kind::Wall && p.kind[j] == Kind::Wall))
                .filter(|&j| (p.x[i] - p.x[j]).norm() < 0.06)
                .count();
            assert_eq!(list.of(i).count(), brute, "particle {i}");
        }
    }

    #[test]
    fn minimum_image_wraps_across_the_box() {
        let domain = Domain::<2>::new(Vector::zeros(), Vector::repeat(1.0), [true, false]);
        let s = domain.separation(&Vector::<2>::new(0.99, 0.5), &Vector::<2>::new(0.01, 0.2));
        assert!((s[0] + 0.02).abs() < 1e-12 && (s[1] - 0.3).abs() < 1e-12);
    }

    /// Rows list fluid neighbours before walls, and culling keeps exactly the pairs
    /// within the culling radius at the current positions.
    #[test]
    fn culling_keeps_the_pairs_within_its_radius() {
        let mut p = random_set::<2>(3000, 13);
        let domain = Domain::new(Vector::zeros(), Vector::repeat(1.0), [true, false]);
        let (mut list, _) = NeighbourList::build(&mut p, &domain, 0.05, 0.03);
        for i in 0..p.len() {
            assert!(list
                .fluid(i)
                .iter()
                .all(|&j| p.kind[j as usize] == Kind::Fluid));
            assert!(list
                .walls(i)
                .iter()
                .all(|&j| p.kind[j as usize] == Kind::Wall));
        }
        let mut rng = SmallRng::seed_from_u64(14);
        for x in p.x.iter_mut() {
            *x += Vector::<2>::from_fn(|_, _| 0.005 * (rng.random::<f64>() - 0.5));
            domain.wrap(x);
        }
        list.cull(&p.x, &domain, 0.06);
        for i in 0..p.len() {
            let mut brute: Vec<u32> = (0..p.len())
                .filter(|&j| {
                    j != i
                        && !(p.kind[i] == Kind::Wall && p.kind[j] == Kind::Wall)
                        && domain.separation(&p.x[i], &p.x[j]).norm() < 0.06
                })
                .map(|j| j as u32)
                .collect();
            let mut got: Vec<u32> = list.of(i).map(|j| j as u32).collect();
            brute.sort_unstable();
            got.sort_unstable();
            assert_eq!(got, brute, "particle {i}");
        }
        let (listed, active) = list.mean_neighbours();
        assert!(active < 0.7 * listed, "{active} of {listed}");
    }

    /// The culled rows depend on the positions only: after culls at several positions,
    /// they equal, entry for entry, the rows of lists built again from the same build
    /// positions and culled once (what a restarted run does), in increasing order.
    #[test]
    fn culled_rows_do_not_depend_on_earlier_culls() {
        let mut p = random_set::<2>(3000, 21);
        let domain = Domain::new(Vector::zeros(), Vector::repeat(1.0), [true, false]);
        let (mut list, _) = NeighbourList::build(&mut p, &domain, 0.05, 0.03);
        let reference = list.reference_positions().to_vec();
        let mut rng = SmallRng::seed_from_u64(22);
        for _ in 0..4 {
            for x in p.x.iter_mut() {
                *x += Vector::<2>::from_fn(|_, _| 0.004 * (rng.random::<f64>() - 0.5));
                domain.wrap(x);
            }
            list.cull(&p.x, &domain, 0.06);
        }
        let mut again = NeighbourList::restore(&p.kind, &domain, 0.05, 0.03, reference).unwrap();
        again.cull(&p.x, &domain, 0.06);
        for i in 0..p.len() {
            assert_eq!(list.fluid(i), again.fluid(i), "particle {i}");
            assert_eq!(list.walls(i), again.walls(i), "particle {i}");
            assert!(list.fluid(i).is_sorted() && list.walls(i).is_sorted());
        }
    }

    #[test]
    fn displacement_since_the_build() {
        let mut p = random_set::<2>(200, 7);
        let domain = Domain::open();
        let (list, _) = NeighbourList::build(&mut p, &domain, 0.1, 0.02);
        assert_eq!(list.max_displacement(&p.x, &domain), 0.0);
        p.x[5][0] += 0.011;
        assert!((list.max_displacement(&p.x, &domain) - 0.011).abs() < 1e-12);
    }

    /// Rows built for some particles only (a split run's own particles and inner halo)
    /// are the full build's rows there, and empty elsewhere.
    #[test]
    fn rows_built_for_some_particles_are_the_full_rows() {
        let domain = Domain::new(Vector::zeros(), Vector::repeat(1.0), [true, false]);
        let listed = |x: &Vector<2>, kind: Kind| kind == Kind::Wall || x[0] < 0.4;
        let (mut all, mut some) = (random_set::<2>(3000, 7), random_set::<2>(3000, 7));
        let (full, _) = NeighbourList::build(&mut all, &domain, 0.06, 0.01);
        let (part, _) = NeighbourList::build_rows(&mut some, &domain, 0.06, 0.01, listed);
        assert_eq!(all.x, some.x, "the same reordering");
        let mut empty = 0;
        for i in 0..all.len() {
            if listed(&all.x[i], all.kind[i]) {
                assert_eq!(part.fluid(i), full.fluid(i), "particle {i}");
                assert_eq!(part.walls(i), full.walls(i), "particle {i}");
            } else {
                assert_eq!(part.of(i).count(), 0, "particle {i}");
                empty += usize::from(full.of(i).count() > 0);
            }
        }
        assert!(empty > 1000, "the test must drop many rows ({empty})");
    }
}
