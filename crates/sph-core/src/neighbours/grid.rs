//! The cell grid of the neighbour search: cubic cells of side at least the list
//! radius, the particles counted into them and sorted by cell, so that the particles
//! of a cell are contiguous and neighbours sit close in memory.

use crate::domain::Domain;
use crate::particles::Vector;
use rayon::prelude::*;

#[derive(Debug, Clone)]
pub(super) struct Grid<const D: usize> {
    origin: Vector<D>,
    cell: Vector<D>,
    pub(super) dims: [usize; D],
    periodic: [bool; D],
    /// Particles of cell c are `cell_start[c]..cell_start[c+1]` (arrays are sorted by cell).
    pub(super) cell_start: Vec<usize>,
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
pub(super) const CELLS_PER_PARTICLE: usize = 4;
pub(super) const CELLS_ALLOWANCE: usize = 4096;

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
    pub(super) fn sorted(x: &[Vector<D>], domain: &Domain<D>, radius: f64) -> (Self, Vec<usize>) {
        let mut grid = Grid::new(x, domain, radius);
        let keys: Vec<usize> = x.par_iter().map(|p| grid.flat(&grid.coords(p))).collect();
        let order = counting_sort(&keys, grid.n_cells(), &mut grid.cell_start);
        (grid, order)
    }

    /// The particles of cell `cell` (the arrays are sorted by cell).
    #[inline(always)]
    pub(super) fn cell_range(&self, cell: usize) -> std::ops::Range<usize> {
        self.cell_start[cell]..self.cell_start[cell + 1]
    }

    /// Cell coordinates of a point, clamped into the grid (open directions) or wrapped (periodic).
    pub(super) fn coords(&self, p: &Vector<D>) -> [usize; D] {
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
    pub(super) fn for_adjacent(&self, c: &[usize; D], mut f: impl FnMut(usize)) {
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
