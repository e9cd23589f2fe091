//! Bodies that touch. Contact between bodies is not modelled: the walls of two bodies
//! do not push on each other, so a free body that reaches another would pass through
//! it. A case whose free body starts overlapping another body is refused, and a run
//! stops, with the bodies named, when a free body's wall particles come within half a
//! spacing of another body's (walls that touch face to face sit one spacing apart).

use crate::particles::{Kind, Particles, Vector};
use std::collections::HashMap;
use std::ops::Range;

/// Where a free body reaches into another body.
#[derive(Debug, Clone, PartialEq)]
pub struct Touch<const D: usize> {
    /// The free body's particle and where it is.
    pub particle: u32,
    pub position: Vector<D>,
    /// The two bodies' names, the free one first.
    pub free: String,
    pub other: String,
    pub distance: f64,
}

/// The first place where a wall particle of one of the `free` bodies (ids, name) is
/// closer than `gap` to a wall particle of any other body of `bodies` (ids, name).
pub fn first_touch<const D: usize>(
    p: &Particles<D>,
    free: &[(Range<u32>, String)],
    bodies: &[(Range<u32>, String)],
    gap: f64,
) -> Option<Touch<D>> {
    let walls: Vec<usize> = (0..p.len()).filter(|&i| p.kind[i] == Kind::Wall).collect();
    for (ids, name) in free {
        let own: Vec<usize> = (walls.iter().copied())
            .filter(|&i| ids.contains(&p.id[i]))
            .collect();
        let (lo, hi) = (own.iter()).fold(
            (Vector::<D>::repeat(f64::MAX), Vector::<D>::repeat(f64::MIN)),
            |(lo, hi), &i| (lo.inf(&p.x[i]), hi.sup(&p.x[i])),
        );
        let cell =
            |x: &Vector<D>| -> [i64; D] { std::array::from_fn(|d| (x[d] / gap).floor() as i64) };
        let mut grid: HashMap<[i64; D], Vec<usize>> = HashMap::new();
        for &i in &own {
            grid.entry(cell(&p.x[i])).or_default().push(i);
        }
        let near = |x: &Vector<D>| (0..D).all(|d| x[d] > lo[d] - gap && x[d] < hi[d] + gap);
        for &j in walls
            .iter()
            .filter(|&&j| !ids.contains(&p.id[j]) && near(&p.x[j]))
        {
            let c = cell(&p.x[j]);
            for k in 0..3usize.pow(D as u32) {
                let key: [i64; D] =
                    std::array::from_fn(|d| c[d] + (k / 3usize.pow(d as u32) % 3) as i64 - 1);
                for &i in grid.get(&key).into_iter().flatten() {
                    let distance = (p.x[i] - p.x[j]).norm();
                    if distance < gap {
                        let other = (bodies.iter())
                            .find(|(r, _)| r.contains(&p.id[j]))
                            .map_or("a wall".to_string(), |(_, n)| n.clone());
                        return Some(Touch {
                            particle: p.id[i],
                            position: p.x[i],
                            free: name.clone(),
                            other,
                            distance,
                        });
                    }
                }
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn walls_closer_than_the_gap_are_found_and_face_to_face_walls_are_not() {
        let mut p = Particles::<2>::default();
        // a body of two particles, and a wall one spacing (0.1) below it
        for x in [0.0, 0.1] {
            p.push(
                Kind::Wall,
                Vector::<2>::new(x, 0.0),
                Vector::zeros(),
                1.0,
                1.0,
            );
        }
        for x in [0.0, 0.1] {
            p.push(
                Kind::Wall,
                Vector::<2>::new(x, -0.1),
                Vector::zeros(),
                1.0,
                1.0,
            );
        }
        let free = vec![(0..2, "shape[0]".to_string())];
        let bodies = vec![
            (0..2, "shape[0]".to_string()),
            (2..4, "tank[0]".to_string()),
        ];
        assert_eq!(first_touch(&p, &free, &bodies, 0.05), None);
        p.x[3] = Vector::<2>::new(0.12, -0.02);
        let touch = first_touch(&p, &free, &bodies, 0.05).unwrap();
        assert_eq!((touch.particle, touch.other.as_str()), (1, "tank[0]"));
        assert!((touch.distance - 0.02_f64.hypot(0.02)).abs() < 1e-15);
    }
}
