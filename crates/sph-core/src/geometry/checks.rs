//! Checks on the built particles: no fluid inside a wall or doubled by overlapping
//! blocks, and probes where fluid can reach.

use super::vector;
use crate::case::Case;
use crate::domain::Domain;
use crate::error::{Result, SphError};
use crate::particles::{Kind, Particles, Vector};
use std::collections::HashMap;

/// No fluid particle may sit closer than Δx/2 to another particle: a fluid particle
/// in a wall, or fluid blocks that overlap (doubled particles), is an input error.
pub(super) fn check_overlap<const D: usize>(particles: &Particles<D>, dx: f64) -> Result<()> {
    let cell = |x: &Vector<D>| -> [i64; D] { std::array::from_fn(|d| (x[d] / dx).floor() as i64) };
    let mut cells: HashMap<[i64; D], Vec<usize>> = HashMap::new();
    for i in 0..particles.len() {
        cells.entry(cell(&particles.x[i])).or_default().push(i);
    }
    let min = 0.5 * dx * (1.0 - 1e-6);
    for i in (0..particles.len()).filter(|&i| particles.kind[i] == Kind::Fluid) {
        let c = cell(&particles.x[i]);
        for m in 0..3usize.pow(D as u32) {
            let mut key = c;
            let mut rem = m;
            for k in key.iter_mut() {
                *k += (rem % 3) as i64 - 1;
                rem /= 3;
            }
            for &j in cells.get(&key).into_iter().flatten() {
                let r = (particles.x[i] - particles.x[j]).norm();
                if j != i && r < min {
                    return Err(overlap_error(particles, i, j, r));
                }
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
pub(super) fn check_probes<const D: usize>(case: &Case, domain: &Domain<D>) -> Result<()> {
    let support = case.support();
    for (k, probe) in case.diagnostics.probes.iter().enumerate() {
        let x: Vector<D> = vector(probe);
        let reason = if domain.escaped(&x) {
            Some(format!(
                "a point inside the domain lo = {:?}, hi = {:?} (domain.lo, domain.hi; without \
                 [domain], the particles' bounding box widened by half its size)",
                domain.lo.as_slice(),
                domain.hi.as_slice()
            ))
        } else {
            buried_in_wall(case, &x, support).map(|wall| {
                format!("a point fluid can reach, not deeper than the kernel support inside {wall}")
            })
        };
        if let Some(expected) = reason {
            return Err(SphError::invalid(
                format!("diagnostics.probes[{k}]"),
                format!("{probe:?}"),
                expected,
            ));
        }
    }
    Ok(())
}

/// The wall (`tank[k]` or `wall[k]`) inside which `x` lies deeper than `depth`.
fn buried_in_wall<const D: usize>(case: &Case, x: &Vector<D>, depth: f64) -> Option<String> {
    let inside = |lo: &Vector<D>, hi: &Vector<D>| (0..D).all(|d| x[d] > lo[d] && x[d] < hi[d]);
    for (k, t) in case.tank.iter().enumerate() {
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
    for (k, b) in case.wall.iter().enumerate() {
        let (lo, hi): (Vector<D>, Vector<D>) = (vector(&b.lo), vector(&b.hi));
        let margin = Vector::<D>::repeat(depth);
        if inside(&(lo + margin), &(hi - margin)) {
            return Some(format!("wall[{k}]"));
        }
    }
    None
}
