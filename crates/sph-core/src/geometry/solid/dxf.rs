//! 2D outlines from DXF drawings (read by the `dxf` crate): one closed 2D polyline
//! (`LWPOLYLINE`, or a `POLYLINE` that is neither 3D nor a mesh), picked by its layer
//! when the drawing has more than one. Bulged segments are circular arcs: a bulge b
//! between two vertices spans the included angle θ = 4 atan b, counter-clockwise for
//! b > 0, on a circle of radius r = c (1 + b²) / (4 |b|) for the chord c (the DXF
//! reference's definition).

use super::outline::closed_chords;
use dxf::entities::EntityType;
use kurbo::{Arc, BezPath, Point, SvgArc, Vec2};

use crate::error::{Result, SphError};

/// One polyline of the drawing: its layer, its vertices with their bulges, and
/// whether it is flagged closed.
struct Polyline {
    layer: String,
    vertices: Vec<(Point, f64)>,
    closed: bool,
}

/// The vertices of the closed polyline of `path`, arcs flattened to chords within
/// `tolerance` (in the drawing's units).
pub(super) fn read(
    key: &str,
    path: &str,
    outline: Option<&str>,
    tolerance: f64,
) -> Result<Vec<[f64; 2]>> {
    let refuse = |expected: String| SphError::invalid(key, format!("{path:?}"), expected);
    let drawing =
        dxf::Drawing::load_file(path).map_err(|e| refuse(format!("a readable DXF file ({e})")))?;
    let polylines = polylines(&drawing);
    let line = pick(&polylines, outline).map_err(refuse)?;
    let drawn = outline_path(line, tolerance);
    closed_chords(&drawn, tolerance)
        .map_err(|e| refuse(format!("a polyline on layer {:?}: {e}", line.layer)))
}

/// The drawing's 2D polylines, in the order they are stored.
fn polylines(drawing: &dxf::Drawing) -> Vec<Polyline> {
    drawing
        .entities()
        .filter_map(|e| {
            let layer = e.common.layer.clone();
            match &e.specific {
                EntityType::LwPolyline(p) => Some(Polyline {
                    layer,
                    vertices: p
                        .vertices
                        .iter()
                        .map(|v| (Point::new(v.x, v.y), v.bulge))
                        .collect(),
                    closed: p.is_closed(),
                }),
                EntityType::Polyline(p) if !p.is_3d_polyline() && !p.is_polyface_mesh() => {
                    Some(Polyline {
                        layer,
                        vertices: p
                            .vertices()
                            .map(|v| (Point::new(v.location.x, v.location.y), v.bulge))
                            .collect(),
                        closed: p.is_closed(),
                    })
                }
                _ => None,
            }
        })
        .collect()
}

/// The one polyline of the drawing, or the one on layer `outline`.
fn pick<'a>(
    lines: &'a [Polyline],
    outline: Option<&str>,
) -> std::result::Result<&'a Polyline, String> {
    let chosen: Vec<&Polyline> = lines
        .iter()
        .filter(|l| outline.is_none_or(|name| l.layer == name))
        .collect();
    let layers = lines
        .iter()
        .map(|l| format!("{:?}", l.layer))
        .collect::<Vec<_>>()
        .join(", ");
    match (&chosen[..], outline) {
        ([one], _) => Ok(*one),
        ([], None) => {
            Err("a DXF drawing with a 2D polyline (LWPOLYLINE or POLYLINE; found none)".into())
        }
        ([], Some(name)) => Err(format!(
            "a 2D polyline on layer {name:?} (found polylines on the layers: {layers})"
        )),
        (_, _) => Err(format!(
            "one 2D polyline, or outline = \"<layer>\" naming a layer with one (found {} on the \
             layers: {layers})",
            chosen.len()
        )),
    }
}

/// The polyline as a path: straight segments, and arcs where a vertex has a bulge.
/// A closed polyline returns to its first vertex (through the last vertex's bulge).
fn outline_path(line: &Polyline, tolerance: f64) -> BezPath {
    let mut bez = BezPath::new();
    let Some(&(start, _)) = line.vertices.first() else {
        return bez;
    };
    bez.move_to(start);
    let n = line.vertices.len();
    let segments = if line.closed { n } else { n - 1 };
    for i in 0..segments {
        let (from, bulge) = line.vertices[i];
        let to = line.vertices[(i + 1) % n].0;
        match bulge_arc(from, to, bulge) {
            Some(arc) => bez.extend(arc.append_iter(0.1 * tolerance)),
            None => bez.line_to(to),
        }
    }
    if line.closed {
        bez.close_path();
    }
    bez
}

/// The circular arc from `from` to `to` with bulge `b` (None when straight).
fn bulge_arc(from: Point, to: Point, b: f64) -> Option<Arc> {
    let chord = from.distance(to);
    if b == 0.0 || chord == 0.0 {
        return None;
    }
    let radius = chord * (1.0 + b * b) / (4.0 * b.abs());
    Arc::from_svg_arc(&SvgArc {
        from,
        to,
        radii: Vec2::new(radius, radius),
        x_rotation: 0.0,
        large_arc: b.abs() > 1.0,
        sweep: b > 0.0,
    })
}
