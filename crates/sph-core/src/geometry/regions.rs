//! The particles of the `[[shape]]` solids, on the lattice `(k + ½)Δx` counted from
//! the origin: fluid on the points inside a fluid shape; wall particles on the points
//! inside a wall shape no deeper than `layers·Δx` below its surface; fluid removed
//! inside a cut or a wall shape. Walls go on the lattice rather than along the surface
//! normal so that fluid and wall particles split one lattice between them: the same
//! spacing and volume everywhere, corners and curves included, with neither gaps nor
//! overlaps at the wetted surface (which the lattice resolves to within Δx/2). Fluid
//! blocks share that lattice when their `lo` is a multiple of Δx; off it, fluid
//! closer than Δx/2 to a wall particle is refused when the case is built.
//!
//! Refused here: a shape too large for the lattice's particle budget, one 100 times
//! the size of the rest of the case (suspected unit mismatch), a wall thinner than
//! its wall depth (fluid on its two sides would see each other), a fluid shape or
//! wall that holds no lattice point.

use super::solid::{self, Solid};
use crate::case::{Case, Role, MAX_PARTICLES};
use crate::error::{Result, SphError};
use crate::particles::Vector;

/// Lattice points closer than this fraction of Δx to a surface are on it, and go to
/// the fluid: into a fluid shape, out of a wall or cut. So the points a flank runs
/// through are all treated alike, whatever the rounding of their distance.
const ON_SURFACE: f64 = 1e-9;

/// Whether `x` lies inside the solid, off its surface.
fn inside(solid: &Solid, x: &[f64], dx: f64) -> bool {
    solid.signed_distance(x) < -ON_SURFACE * dx
}

/// Whether `x` lies inside the solid or on its surface.
fn inside_or_on(solid: &Solid, x: &[f64], dx: f64) -> bool {
    solid.signed_distance(x) < ON_SURFACE * dx
}

/// The solids of a case's shapes, by role.
pub(super) struct Shapes {
    /// (index in `case.shape`, solid)
    pub fluid: Vec<(usize, Solid)>,
    pub walls: Vec<(usize, Solid)>,
    pub cuts: Vec<Solid>,
}

impl Shapes {
    /// Builds and checks every shape of the case.
    pub fn build(case: &Case) -> Result<Self> {
        let mut shapes = Shapes {
            fluid: Vec::new(),
            walls: Vec::new(),
            cuts: Vec::new(),
        };
        let reference = reference_size(case);
        for (k, config) in case.shape.iter().enumerate() {
            let solid = solid::build(case, k)?;
            check_size(case, k, &solid, reference)?;
            match config.role {
                Role::Fluid => shapes.fluid.push((k, solid)),
                Role::Wall => shapes.walls.push((k, solid)),
                Role::Cut => shapes.cuts.push(solid),
            }
        }
        Ok(shapes)
    }

    /// Whether a fluid particle at `x` stays: outside every cut and wall shape.
    pub fn keeps_fluid<const D: usize>(&self, x: &Vector<D>, dx: f64) -> bool {
        let cuts = self.cuts.iter();
        !cuts
            .chain(self.walls.iter().map(|(_, w)| w))
            .any(|s| inside(s, x.as_slice(), dx))
    }
}

/// The lattice points `(k + ½)Δx` inside a solid or on its surface.
pub(super) fn fluid_points<const D: usize>(
    case: &Case,
    k: usize,
    solid: &Solid,
) -> Result<Vec<Vector<D>>> {
    let dx = case.dx();
    let points: Vec<Vector<D>> = lattice_over::<D>(solid, dx)
        .into_iter()
        .filter(|x| inside_or_on(solid, x.as_slice(), dx))
        .collect();
    if points.is_empty() {
        return Err(empty_shape(case, k, solid));
    }
    Ok(points)
}

/// The wall particles of a wall shape: lattice points inside it, less than
/// `layers·Δx` below its surface. The shape must be at least that thick.
pub(super) fn wall_points<const D: usize>(
    case: &Case,
    k: usize,
    solid: &Solid,
) -> Result<Vec<Vector<D>>> {
    let dx = case.dx();
    let depth = case.shape[k].layer_count(case) as f64 * dx;
    let mut deepest = f64::MIN;
    let mut points = Vec::new();
    for x in lattice_over::<D>(solid, dx) {
        let d = -solid.signed_distance(x.as_slice());
        if d > ON_SURFACE * dx {
            deepest = deepest.max(d);
            if d < depth {
                points.push(x);
            }
        }
    }
    if points.is_empty() {
        return Err(empty_shape(case, k, solid));
    }
    // the deepest lattice point lies within Δx of the medial axis: the solid is at
    // most 2(deepest + Δx) thick
    let thickness = 2.0 * (deepest + dx);
    if thickness < depth * (1.0 - 1e-6) {
        return Err(SphError::invalid(
            format!("shape[{k}]"),
            format!("a wall at most {thickness:.4} m thick"),
            format!(
                "a wall at least its depth, layers·Δx = {depth:.4} m, thick: fluid on its two \
                 sides would see each other through it (thicken it or make it a cut)"
            ),
        ));
    }
    Ok(points)
}

fn empty_shape(case: &Case, k: usize, solid: &Solid) -> SphError {
    SphError::invalid(
        format!("shape[{k}]"),
        format!("bounds {:?} to {:?}", solid.lo, solid.hi),
        format!(
            "a shape holding at least one lattice point (k + ½)·Δx, Δx = {} m",
            case.dx()
        ),
    )
}

/// The lattice points `(k + ½)Δx` in the solid's bounding box.
fn lattice_over<const D: usize>(solid: &Solid, dx: f64) -> Vec<Vector<D>> {
    let first: Vec<i64> = solid
        .lo
        .iter()
        .map(|l| (l / dx - 0.5).floor() as i64)
        .collect();
    let last: Vec<i64> = solid
        .hi
        .iter()
        .map(|h| (h / dx - 0.5).ceil() as i64)
        .collect();
    let n: Vec<usize> = (0..D).map(|d| (last[d] - first[d] + 1) as usize).collect();
    let total: usize = n.iter().product();
    (0..total)
        .map(|mut m| {
            Vector::from_fn(|d, _| {
                let k = first[d] + (m % n[d]) as i64;
                m /= n[d];
                (k as f64 + 0.5) * dx
            })
        })
        .collect()
}

/// The size the shapes are compared with: the domain's diagonal, or that of the box
/// holding the fluid blocks, tanks and wall boxes; none if the case has only shapes.
fn reference_size(case: &Case) -> Option<(f64, &'static str)> {
    let diagonal = |lo: &[f64], hi: &[f64]| {
        lo.iter()
            .zip(hi)
            .map(|(l, h)| (h - l).powi(2))
            .sum::<f64>()
            .sqrt()
    };
    if let Some(dom) = &case.domain {
        return Some((diagonal(&dom.lo, &dom.hi), "the domain"));
    }
    let boxes = case
        .fluid_block
        .iter()
        .map(|b| (&b.lo, &b.hi))
        .chain(case.wall.iter().map(|b| (&b.lo, &b.hi)))
        .chain(case.tank.iter().map(|t| (&t.lo, &t.hi)));
    let (mut lo, mut hi) = (
        vec![f64::MAX; case.dimension],
        vec![f64::MIN; case.dimension],
    );
    let mut any = false;
    for (l, h) in boxes {
        any = true;
        for d in 0..case.dimension {
            lo[d] = lo[d].min(l[d]);
            hi[d] = hi[d].max(h[d]);
        }
    }
    any.then(|| (diagonal(&lo, &hi), "the fluid blocks, tanks and walls"))
}

/// A shape 100 times larger than the rest of the case was almost surely drawn in
/// other units; one whose bounding box holds more lattice points than the particle
/// budget cannot be built.
fn check_size(case: &Case, k: usize, solid: &Solid, reference: Option<(f64, &str)>) -> Result<()> {
    let size = solid.size();
    let bounds = format!("bounds {:?} to {:?}", solid.lo, solid.hi);
    if let Some((other, what)) = reference.filter(|(r, _)| size > 100.0 * r) {
        return Err(SphError::invalid(
            format!("shape[{k}]"),
            bounds,
            format!(
                "a shape of about the case's size ({size:.4} m across against {other:.4} m for \
                 {what}: unit mismatch suspected; scale = 0.001 reads a file in millimetres)"
            ),
        ));
    }
    let cells: f64 = solid
        .lo
        .iter()
        .zip(&solid.hi)
        .map(|(l, h)| ((h - l) / case.dx()).ceil() + 1.0)
        .product();
    // (a bounding box beyond f64's range gives no finite count: refused too)
    if cells.is_nan() || cells > MAX_PARTICLES {
        return Err(SphError::invalid(
            format!("shape[{k}]"),
            bounds,
            format!(
                "a shape whose bounding box holds at most {MAX_PARTICLES:.1e} lattice points at \
                 Δx = {} m (it holds {cells:.1e}; check its units and scale)",
                case.dx()
            ),
        ));
    }
    Ok(())
}
