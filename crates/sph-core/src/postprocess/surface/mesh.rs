//! The fluid's surface as a mesh: the level set `Γ_f(x) = level` (½ by default) of the
//! fluid's kernel sum `Γ_f(x) = Σ_f W(x - x_f) V_f`, the indicator the wave gauges
//! read ([`PointReader::fluid_fraction`]), sampled on a grid and contoured.
//!
//! - 2D: polylines, by marching squares with linear interpolation along the grid's
//!   edges (the `contour` crate of the georust project).
//! - 3D: triangles, by Naive Surface Nets (the `fast-surface-nets` crate): one vertex per
//!   grid cell the surface crosses, at the mean of the edge crossings, two triangles
//!   per crossed grid edge. Unlike marching cubes it has no ambiguous cases and its
//!   meshes are closed and free of slivers, at the cost of rounding sharp edges over a
//!   grid cell.
//!
//! Away from walls `Γ_f` falls from 1 to 0 across the free surface over a kernel
//! support, and its ½ level lies where the fluid's volume ends: half a spacing above
//! the top row of a lattice. Against a wall `Γ_f` is about ½ on the wall's surface, so
//! the mesh closes the fluid's volume along the wetted walls; each vertex carries the
//! walls' kernel sum `Γ_w` (`wall_fraction`, ½ on a wall's surface, 0 away from walls)
//! so that a viewer can keep the free surface alone (ParaView: Threshold
//! `wall_fraction` below 0.1).

use crate::diagnostics::PointReader;
use crate::error::{Result, SphError};
use crate::particles::{Kind, Vector};
use crate::physics::kernel::Smoothing;
use fast_surface_nets::ndshape::RuntimeShape;
use fast_surface_nets::{surface_nets, SurfaceNetsBuffer};
use rayon::prelude::*;

/// The most grid nodes a surface is sampled on: 10⁸ nodes of 8 bytes each.
pub const MAX_NODES: usize = 100_000_000;

/// A surface mesh: points, and cells listing point indices (2D: polylines, a closed
/// one ending on its first point's index; 3D: triangles).
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceMesh<const D: usize> {
    pub points: Vec<Vector<D>>,
    pub cells: Vec<Vec<u32>>,
    /// The walls' kernel sum Γ_w at each point.
    pub wall_fraction: Vec<f64>,
}

/// `Γ_f` at the nodes of a grid of spacing `step` from `lo`, `counts` nodes along each
/// axis, the first axis fastest.
#[derive(Debug, Clone)]
pub struct ColourGrid<const D: usize> {
    pub lo: Vector<D>,
    pub step: f64,
    pub counts: [usize; D],
    pub values: Vec<f64>,
}

impl<const D: usize> ColourGrid<D> {
    /// `Γ_f` of `reader` on a grid of spacing `step` over the fluid's bounding box grown
    /// by a kernel support and a node, so that the grid's edge is dry all round.
    /// Refused when the grid would have more than [`MAX_NODES`] nodes.
    pub fn sample<K: Smoothing + ?Sized>(reader: &PointReader<D, K>, step: f64) -> Result<Self> {
        let p = reader.particles;
        let fluid = (0..p.len()).filter(|&i| p.kind[i] == Kind::Fluid);
        let (lo, hi) = fluid.fold(
            (Vector::<D>::repeat(f64::MAX), Vector::<D>::repeat(f64::MIN)),
            |(lo, hi), i| (lo.inf(&p.x[i]), hi.sup(&p.x[i])),
        );
        if lo[0] > hi[0] {
            return Ok(Self {
                lo: Vector::zeros(),
                step,
                counts: [0; D],
                values: Vec::new(),
            });
        }
        let margin = reader.kernel.support_radius() + step;
        let lo = lo.add_scalar(-margin);
        let counts: [usize; D] =
            std::array::from_fn(|d| ((hi[d] + margin - lo[d]) / step).ceil() as usize + 1);
        let nodes = counts.iter().try_fold(1usize, |n, &c| n.checked_mul(c));
        if nodes.is_none_or(|n| n > MAX_NODES) {
            return Err(SphError::invalid(
                "spacing",
                step,
                format!(
                    "a grid spacing giving at most {MAX_NODES} nodes over the fluid (this \
                     one gives {counts:?} nodes along the axes); choose a coarser one"
                ),
            ));
        }
        let mut grid = Self {
            lo,
            step,
            counts,
            values: Vec::new(),
        };
        grid.values = (0..counts.iter().product::<usize>())
            .into_par_iter()
            .map(|k| reader.fluid_fraction(&grid.node(k)))
            .collect();
        Ok(grid)
    }

    /// The position of node `k`.
    fn node(&self, mut k: usize) -> Vector<D> {
        let mut x = self.lo;
        for d in 0..D {
            x[d] += (k % self.counts[d]) as f64 * self.step;
            k /= self.counts[d];
        }
        x
    }

    /// The mesh of the level `level` of the grid's values; its points carry the walls'
    /// kernel sum read by `reader`.
    pub fn surface<K: Smoothing + ?Sized>(
        &self,
        level: f64,
        reader: &PointReader<D, K>,
    ) -> SurfaceMesh<D> {
        let (points, cells) = if self.values.is_empty() {
            (Vec::new(), Vec::new())
        } else if D == 2 {
            self.isolines(level)
        } else {
            self.isosurface(level)
        };
        let wall_fraction = points.par_iter().map(|x| reader.wall_fraction(x)).collect();
        SurfaceMesh {
            points,
            cells,
            wall_fraction,
        }
    }

    /// 2D: the polylines along which the values cross `level` (marching squares).
    fn isolines(&self, level: f64) -> (Vec<Vector<D>>, Vec<Vec<u32>>) {
        // `contour` places value k at the centre of pixel k, (k + ½) steps from its origin
        let origin = self.lo.add_scalar(-0.5 * self.step);
        let builder = contour::ContourBuilder::new(self.counts[0], self.counts[1], true)
            .x_origin(origin[0])
            .y_origin(origin[1])
            .x_step(self.step)
            .y_step(self.step);
        let lines =
            (builder.lines(&self.values, &[level])).expect("the grid's values match its counts");
        let (mut points, mut cells) = (Vec::new(), Vec::new());
        for line in &lines[0].geometry().0 {
            // a closed ring (every one on a grid dry all round) ends on its first point:
            // listed once, its index repeated at the end
            let ring = &line.0;
            let closed = ring.len() > 1 && ring.first() == ring.last();
            let first = points.len() as u32;
            let own = if closed {
                &ring[..ring.len() - 1]
            } else {
                &ring[..]
            };
            points.extend(own.iter().map(|c| {
                let xy = [c.x, c.y];
                Vector::<D>::from_fn(|d, _| xy[d])
            }));
            let mut cell: Vec<u32> = (first..points.len() as u32).collect();
            if closed {
                cell.push(first);
            }
            cells.push(cell);
        }
        (points, cells)
    }

    /// 3D: the triangles of the surface where the values cross `level` (Naive Surface
    /// Nets; the field's sign is negative inside, where the values exceed `level`).
    fn isosurface(&self, level: f64) -> (Vec<Vector<D>>, Vec<Vec<u32>>) {
        let dims: [u32; 3] = std::array::from_fn(|d| self.counts[d] as u32);
        // the shape orders nodes as the grid does, the first axis fastest
        let shape = RuntimeShape::<u32, 3>::new(dims);
        let sdf: Vec<f32> = self.values.iter().map(|v| (level - v) as f32).collect();
        let mut buffer = SurfaceNetsBuffer::default();
        surface_nets(&sdf, &shape, [0; 3], dims.map(|n| n - 1), &mut buffer);
        let points = (buffer.positions.iter())
            .map(|v| Vector::<D>::from_fn(|d, _| self.lo[d] + f64::from(v[d]) * self.step))
            .collect();
        let cells = buffer.indices.chunks(3).map(|t| t.to_vec()).collect();
        (points, cells)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::domain::Domain;
    use crate::neighbours::NeighbourList;
    use crate::particles::Particles;
    use crate::physics::kernel::KernelChoice;

    const DX: f64 = 0.02;

    /// The mesh of the ½ level of `particles` (Wendland C2, h = 2Δx) on a grid of
    /// spacing `step`.
    fn mesh_of<const D: usize>(mut particles: Particles<D>, step: f64) -> SurfaceMesh<D> {
        let kernel = KernelChoice::WendlandC2.with_length(2.0 * DX, D);
        let domain = Domain::new(Vector::repeat(-1.0), Vector::repeat(2.0), [false; D]);
        let support = kernel.support_radius();
        let (list, _) =
            NeighbourList::build_rows(&mut particles, &domain, support, 0.0, |_, _| false);
        let reader = PointReader {
            kernel: kernel.as_ref(),
            particles: &particles,
            list: &list,
            domain: &domain,
        };
        ColourGrid::sample(&reader, step)
            .unwrap()
            .surface(0.5, &reader)
    }

    /// Lattice particles (cell centres of spacing Δx) of `kind` in the box `lo`–`hi`
    /// for which `inside` holds, added to `particles`.
    fn fill<const D: usize>(
        particles: &mut Particles<D>,
        kind: Kind,
        lo: [f64; D],
        hi: [f64; D],
        inside: impl Fn(&Vector<D>) -> bool,
    ) {
        let n: [usize; D] = std::array::from_fn(|d| ((hi[d] - lo[d]) / DX).round() as usize);
        for k in 0..n.iter().product::<usize>() {
            let mut rest = k;
            let x = Vector::<D>::from_fn(|d, _| {
                let i = rest % n[d];
                rest /= n[d];
                lo[d] + (i as f64 + 0.5) * DX
            });
            if inside(&x) {
                particles.push(kind, x, Vector::zeros(), 1000.0, 1000.0 * DX.powi(D as i32));
            }
        }
    }

    /// The free surface of a block of water 0.3 deep on a floor of three wall layers:
    /// the mesh's points more than two supports from the sides, above the floor's
    /// reach (Γ_w = 0).
    fn top_of_block<const D: usize>(step: f64) -> Vec<f64> {
        let mut p = Particles::<D>::default();
        let (lo, hi) = (
            [0.0; D],
            std::array::from_fn(|d| if d == D - 1 { 0.3 } else { 0.6 }),
        );
        fill(&mut p, Kind::Fluid, lo, hi, |_| true);
        let floor_hi = std::array::from_fn(|d| if d == D - 1 { 0.0 } else { 0.6 });
        let floor_lo = std::array::from_fn(|d| if d == D - 1 { -3.0 * DX } else { 0.0 });
        fill(&mut p, Kind::Wall, floor_lo, floor_hi, |_| true);
        let mesh = mesh_of(p, step);
        (mesh.points.iter().zip(&mesh.wall_fraction))
            .filter(|(x, &w)| w == 0.0 && (0..D - 1).all(|d| (x[d] - 0.3).abs() < 0.14))
            .map(|(x, _)| x[D - 1])
            .collect()
    }

    #[test]
    fn a_block_of_water_has_a_flat_surface_where_its_volume_ends() {
        // the top row of particles is at 0.3 - Δx/2, the volume ends at 0.3
        for (dim, step) in [(2, DX), (2, 0.5 * DX), (3, DX)] {
            let tops = if dim == 2 {
                top_of_block::<2>(step)
            } else {
                top_of_block::<3>(step)
            };
            assert!(tops.len() > 5, "{dim}D: {} points", tops.len());
            let worst = tops.iter().map(|y| (y - 0.3).abs()).fold(0.0, f64::max);
            println!(
                "{dim}D block, grid step {step}: top within {:.2e} of 0.3",
                worst
            );
            assert!(worst < 0.1 * DX, "{dim}D, step {step}: {worst}");
        }
    }

    /// The distances of the mesh's points from the centre (0.5, 0.5, ...) of a disc or
    /// ball of fluid of radius `r` filled on the lattice.
    fn radii<const D: usize>(r: f64, step: f64) -> Vec<f64> {
        let mut p = Particles::<D>::default();
        let centre = Vector::<D>::repeat(0.5);
        fill(&mut p, Kind::Fluid, [0.0; D], [1.0; D], |x| {
            (x - centre).norm() < r
        });
        let mesh = mesh_of(p, step);
        mesh.points.iter().map(|x| (x - centre).norm()).collect()
    }

    #[test]
    fn a_disc_and_a_ball_of_water_have_round_surfaces_of_their_radius() {
        // the lattice's fill of a circle holds its area to O(Δx^1.5) (Gauss's circle
        // problem); the kernel sum's ½ level of a convex body sits slightly inside it
        // (measured -0.03 Δx in 2D, -0.10 Δx in 3D at R = 10Δx, h = 2Δx), and the
        // points scatter by the fill's staircase: worst 0.15 Δx (2D), 0.19 Δx (3D)
        for (dim, step) in [(2, DX), (2, 0.5 * DX), (3, DX)] {
            let r = 0.2;
            let radii = if dim == 2 {
                radii::<2>(r, step)
            } else {
                radii::<3>(r, step)
            };
            let mean = radii.iter().sum::<f64>() / radii.len() as f64;
            let worst = radii.iter().map(|q| (q - r).abs()).fold(0.0, f64::max);
            println!(
                "{dim}D ball r = 10Δx, grid step {step}: mean radius {:+.3} Δx off, worst {:.3} Δx",
                (mean - r) / DX,
                worst / DX
            );
            assert!((mean - r).abs() < 0.15 * DX, "{dim}D: mean radius {mean}");
            assert!(worst < 0.25 * DX, "{dim}D: worst {worst}");
        }
    }

    #[test]
    fn a_dry_grid_gives_an_empty_mesh_and_a_huge_one_is_refused() {
        let mut p = Particles::<2>::default();
        fill(&mut p, Kind::Wall, [0.0, 0.0], [0.2, 0.2], |_| true);
        assert!(mesh_of(p, DX).points.is_empty());
        let mut p = Particles::<3>::default();
        fill(&mut p, Kind::Fluid, [0.0; 3], [0.2; 3], |_| true);
        let kernel = KernelChoice::WendlandC2.with_length(2.0 * DX, 3);
        let domain = Domain::new(Vector::repeat(-1.0), Vector::repeat(2.0), [false; 3]);
        let (list, _) = NeighbourList::build_rows(&mut p, &domain, 0.08, 0.0, |_, _| false);
        let reader = PointReader {
            kernel: kernel.as_ref(),
            particles: &p,
            list: &list,
            domain: &domain,
        };
        let e = ColourGrid::sample(&reader, 1e-4).unwrap_err().to_string();
        assert!(e.contains("spacing") && e.contains("coarser"), "{e}");
    }
}
