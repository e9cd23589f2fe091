//! Fluid particles found inside a wall: a failure count for the dummy-particle walls,
//! which do not forbid crossing.

use crate::case::{Case, MotionChoice};
use crate::geometry::solid::Solid;
use crate::particles::{Kind, Particles, Vector};
use rayon::prelude::*;

/// Fluid particles inside a wall: past the first layer of wall particles (more than
/// Δx/2 beyond a closed face of a tank, within its layers and below the last wall
/// particles at an open face, over which fluid may pass), or deeper than Δx/2 inside
/// a `[[wall]]` box or a `[[shape]]` wall (`wall_solids`, with their index in `case.shape`). Zero in a sound run;
/// dummy-particle walls do not forbid crossing, so this counts the failures. Moving
/// bodies are left out: their walls are no longer where the case builds them.
pub fn wall_crossings<const D: usize>(
    case: &Case,
    wall_solids: &[(usize, Solid)],
    p: &Particles<D>,
) -> usize {
    let dx = case.dx();
    let inside = |x: &Vector<D>, lo: &[f64], hi: &[f64], margin: f64| {
        (0..D).all(|d| x[d] > lo[d] + margin && x[d] < hi[d] - margin)
    };
    let fixed = |m: Option<MotionChoice>| m.unwrap_or_default() == MotionChoice::Fixed;
    let tanks: Vec<_> = (case.tank.iter())
        .filter(|t| fixed(t.motion))
        .map(|t| (t, t.open_faces(D)))
        .collect();
    let walls: Vec<_> = case.wall.iter().filter(|w| fixed(w.motion)).collect();
    let solids: Vec<_> = (wall_solids.iter())
        .filter(|(k, _)| fixed(case.shape[*k].motion))
        .collect();
    let in_tank_wall = |x: &Vector<D>, (t, open): &(&crate::case::TankConfig, Vec<(usize, i8)>)| {
        let pad = t.layer_count(case) as f64 * dx;
        let within_layers = (0..D).all(|d| x[d] > t.lo[d] - pad && x[d] < t.hi[d] + pad);
        let past_closed_face = (0..D).any(|d| {
            let below = x[d] < t.lo[d] - 0.5 * dx && !open.contains(&(d, -1));
            let above = x[d] > t.hi[d] + 0.5 * dx && !open.contains(&(d, 1));
            below || above
        });
        // above the last wall particles at an open face: passing over the wall's edge
        let beyond_open = open.iter().any(|&(d, s)| {
            if s > 0 {
                x[d] > t.hi[d] - 0.5 * dx
            } else {
                x[d] < t.lo[d] + 0.5 * dx
            }
        });
        within_layers && past_closed_face && !beyond_open
    };
    (0..p.len())
        .into_par_iter()
        .filter(|&i| p.kind[i] == Kind::Fluid)
        .filter(|&i| {
            let x = &p.x[i];
            tanks.iter().any(|tank| in_tank_wall(x, tank))
                || walls.iter().any(|w| inside(x, &w.lo, &w.hi, 0.5 * dx))
                || (solids.iter()).any(|(_, s)| s.signed_distance(x.as_slice()) < -0.5 * dx)
        })
        .count()
}
