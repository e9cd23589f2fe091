//! What a case builds, in the words of `sph-cli check`: each region's particle count
//! and bounding box, and the closest approach of fluid to a wall (with a notice when
//! it is off the walls' lattice).

use super::checks::CellIndex;
use super::Setup;
use crate::particles::{Kind, Vector};
use std::fmt::Write;
use std::ops::Range;

/// A part of the initial particle set named by the key that made it (`fluid_block[0]`,
/// `shape[2]`, `tank[0]`...), with the ids of its particles.
#[derive(Debug, Clone)]
pub struct Region {
    pub key: String,
    /// The body's name (walls only).
    pub name: Option<String>,
    pub kind: Kind,
    pub ids: Range<u32>,
}

impl<const D: usize> Setup<D> {
    /// The regions, one a line with count and bounds, then the smallest distance
    /// between a fluid and a wall particle (Δx on the lattice; less means fluid off the
    /// walls' lattice) with the pair of regions where it occurs.
    pub fn report(&self, dx: f64, support: f64) -> String {
        let p = &self.particles;
        let mut text = String::new();
        for r in &self.regions {
            let ids = r.ids.start as usize..r.ids.end as usize;
            let (mut lo, mut hi) = (Vector::<D>::repeat(f64::MAX), Vector::<D>::repeat(f64::MIN));
            for x in &p.x[ids.clone()] {
                lo = lo.inf(x);
                hi = hi.sup(x);
            }
            let label = match &r.name {
                Some(name) => format!("{} ({name})", r.key),
                None => r.key.clone(),
            };
            let kind = if r.kind == Kind::Fluid {
                "fluid"
            } else {
                "wall"
            };
            let _ = writeln!(
                text,
                "  {label:<24} {kind:<5} {:>9} particles, from {:?} to {:?}",
                ids.len(),
                rounded(&lo),
                rounded(&hi)
            );
        }
        let _ = writeln!(text, "  {}", self.closest_wall(dx, support));
        text
    }

    /// The closest fluid-wall pair within one kernel support.
    fn closest_wall(&self, dx: f64, support: f64) -> String {
        match self.closest_fluid_to_wall(support) {
            None => format!("no fluid within a kernel support ({support:.4} m) of a wall"),
            Some((r, i, j)) => format!(
                "closest fluid to a wall: {r:.4} m ({:.2} Δx), {}",
                r / dx,
                self.pair(i, j)
            ),
        }
    }

    /// A notice when some fluid starts closer than 0.9 Δx to a wall particle: on one
    /// lattice the closest is Δx, so the fluid is off the walls' lattice (a fluid
    /// block whose `lo` is not a multiple of Δx beside a shape, or a tank on another
    /// offset), which biases the wall's pressure and load (by 5% on a floating
    /// section's buoyancy at half a spacing, docs/validation/floating_bodies.md §4).
    pub fn off_lattice_notice(&self, dx: f64, support: f64) -> Option<String> {
        let (r, i, j) = self.closest_fluid_to_wall(support)?;
        (r < 0.9 * dx).then(|| {
            format!(
                "fluid starts {:.2} Δx from a wall ({}): off the walls' lattice, which biases \
                 the pressure and load there; put the fluid block's lo on a multiple of Δx",
                r / dx,
                self.pair(i, j)
            )
        })
    }

    /// The smallest distance from a fluid particle to a wall particle, if within
    /// `support`, and the pair.
    fn closest_fluid_to_wall(&self, support: f64) -> Option<(f64, usize, usize)> {
        let p = &self.particles;
        let walls = CellIndex::new(p, support, |i| p.kind[i] == Kind::Wall);
        let mut best: Option<(f64, usize, usize)> = None;
        for i in (0..p.len()).filter(|&i| p.kind[i] == Kind::Fluid) {
            for j in walls.near(&p.x[i]) {
                let r = (p.x[i] - p.x[j]).norm();
                if best.is_none_or(|(b, _, _)| r < b) {
                    best = Some((r, i, j));
                }
            }
        }
        best.filter(|(r, _, _)| *r <= support)
    }

    /// "`region` at `x` to `region` at `x`" of a fluid and a wall particle.
    fn pair(&self, i: usize, j: usize) -> String {
        let x = &self.particles.x;
        format!(
            "{} at {:?} to {} at {:?}",
            self.region_of(i),
            rounded(&x[i]),
            self.region_of(j),
            rounded(&x[j])
        )
    }

    fn region_of(&self, i: usize) -> &str {
        let id = self.particles.id[i];
        self.regions
            .iter()
            .find(|r| r.ids.contains(&id))
            .map_or("?", |r| r.key.as_str())
    }
}

fn rounded<const D: usize>(x: &Vector<D>) -> Vec<f64> {
    x.iter().map(|v| (v * 1e6).round() / 1e6).collect()
}
