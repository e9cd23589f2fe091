//! Closed 2D polygons: read from a vertex list, checked (at least three distinct
//! vertices, an area, no edge crossing another) and wound counter-clockwise, the
//! orientation parry's oriented polyline takes for a solid interior.

use super::Solid;
use crate::error::{Result, SphError};
use parry2d_f64::math::{Pose, Vector};
use parry2d_f64::shape::{Polyline, PolylineFlags};
use parry2d_f64::utils::segments_intersection2d;

/// Reads a vertex list: one `x y` or `x, y` pair a line; blank lines and `#`
/// comments are skipped.
pub(super) fn read(key: &str, path: &str) -> Result<Vec<[f64; 2]>> {
    let text = std::fs::read_to_string(path).map_err(|e| {
        SphError::invalid(
            key,
            format!("{path:?}"),
            format!("a readable vertex file ({e})"),
        )
    })?;
    let mut vertices = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
        }
        let values: Vec<f64> = line
            .split(|c: char| c == ',' || c.is_whitespace())
            .filter(|t| !t.is_empty())
            .map(str::parse)
            .collect::<std::result::Result<_, _>>()
            .unwrap_or_default();
        match values[..] {
            [x, y] if x.is_finite() && y.is_finite() => vertices.push([x, y]),
            _ => {
                return Err(SphError::invalid(
                    key,
                    format!("{path:?}"),
                    format!(
                        "one x, y pair of finite numbers a line (line {}: {line:?})",
                        n + 1
                    ),
                ))
            }
        }
    }
    Ok(vertices)
}

/// The solid bounded by the closed polygon through `vertices` (either winding; a last
/// vertex equal to the first is dropped).
pub(super) fn solid(key: &str, mut vertices: Vec<[f64; 2]>) -> Result<Solid> {
    if vertices.len() > 1 && vertices.first() == vertices.last() {
        vertices.pop();
    }
    vertices.dedup();
    if vertices.len() < 3 {
        return Err(SphError::invalid(
            key,
            format!("{} distinct vertices", vertices.len()),
            "a closed polygon of at least 3 distinct vertices",
        ));
    }
    let extent = extent(&vertices);
    let area = signed_area(&vertices);
    if collinear(&vertices, extent) {
        return Err(no_area(key, vertices.len()));
    }
    if let Some((a, b)) = crossing_edges(&vertices, 1e-12 * extent) {
        return Err(SphError::invalid(
            key,
            format!("edges {a} and {b} cross"),
            format!(
                "a polygon whose edges meet only at shared vertices (edge {a} runs from vertex \
                 {a} at {:?}, edge {b} from vertex {b} at {:?})",
                vertices[a], vertices[b]
            ),
        ));
    }
    if area.abs() <= 1e-12 * extent * extent {
        return Err(no_area(key, vertices.len()));
    }
    if area < 0.0 {
        vertices.reverse();
    }
    let n = vertices.len() as u32;
    let points = vertices.iter().map(|v| Vector::new(v[0], v[1])).collect();
    let indices = (0..n).map(|i| [i, (i + 1) % n]).collect();
    let polyline = Polyline::with_flags(points, Some(indices), PolylineFlags::ORIENTED);
    Ok(Solid::plane(Box::new(polyline), Pose::IDENTITY))
}

fn no_area(key: &str, n: usize) -> SphError {
    SphError::invalid(
        key,
        format!("{n} vertices enclosing no area"),
        "a closed polygon enclosing an area (its vertices are collinear)",
    )
}

/// Whether every vertex lies on the line through the first two.
fn collinear(v: &[[f64; 2]], extent: f64) -> bool {
    let (a, b) = (v[0], v[1]);
    v.iter().all(|p| {
        let cross = (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
        cross.abs() <= 1e-12 * extent * extent
    })
}

/// Shoelace area, positive for counter-clockwise winding.
fn signed_area(v: &[[f64; 2]]) -> f64 {
    let n = v.len();
    (0..n)
        .map(|i| {
            let (a, b) = (v[i], v[(i + 1) % n]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum::<f64>()
        / 2.0
}

fn extent(v: &[[f64; 2]]) -> f64 {
    let span = |d: usize| {
        let values = v.iter().map(|p| p[d]);
        values.clone().fold(f64::MIN, f64::max) - values.fold(f64::MAX, f64::min)
    };
    span(0).max(span(1))
}

/// The first pair of edges (by their first vertex) that meet anywhere but at the
/// vertex two neighbouring edges share. Every pair is tested: O(n²), a fraction of a
/// second for the thousands of vertices a 2D section has.
fn crossing_edges(v: &[[f64; 2]], eps: f64) -> Option<(usize, usize)> {
    let n = v.len();
    let point = |i: usize| Vector::new(v[i % n][0], v[i % n][1]);
    for a in 0..n {
        for b in a + 1..n {
            let neighbours = b == a + 1 || (a == 0 && b == n - 1);
            let meet = segments_intersection2d(point(a), point(a + 1), point(b), point(b + 1), eps);
            let crossing = match meet {
                None => false,
                // neighbours share one vertex; anything more is an overlap
                Some(parry2d_f64::utils::SegmentsIntersection::Point { .. }) => !neighbours,
                Some(_) => true,
            };
            if crossing {
                return Some((a, b));
            }
        }
    }
    None
}
