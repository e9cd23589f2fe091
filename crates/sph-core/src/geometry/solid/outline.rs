//! Outlines drawn as paths (from SVG or DXF files) turned into the vertex list of a
//! polygon: curves flattened into chords by `kurbo` within a tolerance, and exactly
//! one closed outline required.

use kurbo::{BezPath, PathEl, Point};

/// The vertices of the path's one closed subpath, curves flattened to `tolerance`.
pub(super) fn closed_chords(
    path: &BezPath,
    tolerance: f64,
) -> std::result::Result<Vec<[f64; 2]>, String> {
    let mut subpaths: Vec<(Vec<Point>, bool)> = Vec::new();
    kurbo::flatten(path, tolerance, |element| match element {
        PathEl::MoveTo(p) => subpaths.push((vec![p], false)),
        PathEl::LineTo(p) => {
            if let Some((points, _)) = subpaths.last_mut() {
                points.push(p);
            }
        }
        PathEl::ClosePath => {
            if let Some((_, closed)) = subpaths.last_mut() {
                *closed = true;
            }
        }
        _ => {}
    });
    let [(points, closed)] = &subpaths[..] else {
        return Err(format!(
            "one closed outline (it has {} subpaths; draw each outline as its own shape, \
             holes with role = \"cut\")",
            subpaths.len()
        ));
    };
    let (first, last) = (points[0], points[points.len() - 1]);
    let gap = first.distance(last);
    if !closed && gap > tolerance {
        return Err(format!(
            "a closed outline (it ends {gap:.6} from its start: a path needs Z or its start \
             point again, a polyline its first point again)"
        ));
    }
    // points that differ by round-off (an arc ending on its start) are one vertex
    let same = |a: Point, b: Point| a.distance(b) <= 1e-6 * tolerance;
    let mut vertices: Vec<Point> = Vec::with_capacity(points.len());
    for &p in points {
        if vertices.last().is_none_or(|&q| !same(p, q)) {
            vertices.push(p);
        }
    }
    if vertices.len() > 1 && same(vertices[0], vertices[vertices.len() - 1]) {
        vertices.pop();
    }
    Ok(vertices.iter().map(|p| [p.x, p.y]).collect())
}
