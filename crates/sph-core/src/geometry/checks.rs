//! Checks on the built particles: no fluid inside a wall or doubled by overlapping
//! blocks, and probes where fluid can reach.

use super::solid::Solid;
use super::vector;
use crate::case::{Case, MotionChoice};
use crate::domain::Domain;
use crate::error::{Result, SphError};
use crate::particles::{Kind, Particles, Vector};
use std::collections::HashMap;

/// The particles by cell of a uniform grid, for the searches of the checks here.
pub(super) struct CellIndex<const D: usize> {
    cell: f64,
    cells: HashMap<[i64; D], Vec<usize>>,
}

impl<const D: usize> CellIndex<D> {
    /// Indexes the particles for which `keep` holds, in cells of side `cell`.
    pub fn new(particles: &Particles<D>, cell: f64, keep: impl Fn(usize) -> bool) -> Self {
        let mut index = CellIndex {
            cell,
            cells: HashMap::new(),
        };
        for i in (0..particles.len()).filter(|&i| keep(i)) {
            let key = index.key(&particles.x[i]);
            index.cells.entry(key).or_default().push(i);
        }
        index
    }

    fn key(&self, x: &Vector<D>) -> [i64; D] {
        std::array::from_fn(|d| (x[d] / self.cell).floor() as i64)
    }

    /// The indexed particles in the 3^D cells around `x`: all those within one cell
    /// side of it, and some further.
    pub fn near(&self, x: &Vector<D>) -> impl Iterator<Item = usize> + '_ {
        let c = self.key(x);
        (0..3usize.pow(D as u32)).flat_map(move |m| {
            let mut key = c;
            let mut rem = m;
            for k in key.iter_mut() {
                *k += (rem % 3) as i64 - 1;
                rem /= 3;
            }
            self.cells.get(&key).into_iter().flatten().copied()
        })
    }
}

/// No fluid particle may sit closer than Δx/2 to another particle: a fluid particle
/// in a wall, or fluid blocks that overlap (doubled particles), is an input error.
pub(super) fn check_overlap<const D: usize>(particles: &Particles<D>, dx: f64) -> Result<()> {
    let index = CellIndex::new(particles, dx, |_| true);
    let min = 0.5 * dx * (1.0 - 1e-6);
    for i in (0..particles.len()).filter(|&i| particles.kind[i] == Kind::Fluid) {
        for j in index.near(&particles.x[i]) {
            let r = (particles.x[i] - particles.x[j]).norm();
            if j != i && r < min {
                return Err(overlap_error(particles, i, j, r));
            }
        }
    }
    Ok(())
}

fn overlap_error<const D: usize>(p: &Particles<D>, i: usize, j: usize, r: f64) -> SphError {
    let (other, what) = match p.kind[j] {
        Kind::Wall => ("wall particle", "fluid clear of walls"),
        Kind::Fluid => ("fluid particle", "fluid blocks that do not overlap"),
    };
    SphError::invalid(
        "fluid_block",
        format!("a fluid particle at {:?}", p.x[i].as_slice()),
        format!(
            "{what} (it lies {r:.3e} m from the {other} at {:?}; keep at least Δx/2)",
            p.x[j].as_slice()
        ),
    )
}

/// A probe must lie where fluid can be: inside the domain along its open directions and
/// not deeper than the kernel support inside a wall, or it can never read a pressure.
pub(super) fn check_probes<const D: usize>(
    case: &Case,
    domain: &Domain<D>,
    wall_solids: &[(usize, Solid)],
) -> Result<()> {
    for (k, probe) in case.diagnostics.probes.iter().enumerate() {
        if let Some(expected) = probe_refusal(case, domain, wall_solids, &vector(probe)) {
            return Err(SphError::invalid(
                format!("diagnostics.probes[{k}]"),
                format!("{probe:?}"),
                expected,
            ));
        }
    }
    Ok(())
}

/// Why no fluid can ever reach `x` (what a probe point was expected to be), or `None`
/// where fluid can: outside the domain, or deeper than the kernel support inside a
/// tank's closed face, a `[[wall]]` box or a `[[shape]]` wall (`wall_solids`, with their
/// index in `case.shape`).
pub fn probe_refusal<const D: usize>(
    case: &Case,
    domain: &Domain<D>,
    wall_solids: &[(usize, Solid)],
    x: &Vector<D>,
) -> Option<String> {
    if domain.escaped(x) {
        return Some(format!(
            "a point inside the domain lo = {:?}, hi = {:?} (domain.lo, domain.hi; without \
             [domain], the particles' bounding box widened by half its size)",
            domain.lo.as_slice(),
            domain.hi.as_slice()
        ));
    }
    buried_in_wall(case, wall_solids, x, case.support()).map(|wall| {
        format!("a point fluid can reach, not deeper than the kernel support inside {wall}")
    })
}

/// The fixed wall (`tank[k]`, `wall[k]` or `shape[k]`) inside which `x` lies deeper
/// than `depth` (a moving wall leaves where it was built).
fn buried_in_wall<const D: usize>(
    case: &Case,
    wall_solids: &[(usize, Solid)],
    x: &Vector<D>,
    depth: f64,
) -> Option<String> {
    let inside = |lo: &Vector<D>, hi: &Vector<D>| (0..D).all(|d| x[d] > lo[d] && x[d] < hi[d]);
    let fixed = |m: Option<MotionChoice>| m.unwrap_or_default() == MotionChoice::Fixed;
    for (k, t) in case
        .tank
        .iter()
        .enumerate()
        .filter(|(_, t)| fixed(t.motion))
    {
        let (lo, hi): (Vector<D>, Vector<D>) = (vector(&t.lo), vector(&t.hi));
        let pad = Vector::<D>::repeat(t.layer_count(case) as f64 * case.dx());
        let open = t.open_faces(D);
        let beyond_closed_face = (0..D).any(|d| {
            (x[d] < lo[d] - depth && !open.contains(&(d, -1)))
                || (x[d] > hi[d] + depth && !open.contains(&(d, 1)))
        });
        if inside(&(lo - pad), &(hi + pad)) && beyond_closed_face {
            return Some(format!("tank[{k}]"));
        }
    }
    for (k, b) in case
        .wall
        .iter()
        .enumerate()
        .filter(|(_, b)| fixed(b.motion))
    {
        let (lo, hi): (Vector<D>, Vector<D>) = (vector(&b.lo), vector(&b.hi));
        let margin = Vector::<D>::repeat(depth);
        if inside(&(lo + margin), &(hi - margin)) {
            return Some(format!("wall[{k}]"));
        }
    }
    wall_solids
        .iter()
        .filter(|(k, _)| fixed(case.shape[*k].motion))
        .find(|(_, solid)| solid.signed_distance(x.as_slice()) < -depth)
        .map(|(k, _)| format!("shape[{k}]"))
}
