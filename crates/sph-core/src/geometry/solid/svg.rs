//! 2D outlines from SVG drawings: one `<path>`, `<polygon>`, `<polyline>` or `<rect>`
//! element, picked by its `id` when the drawing has more than one. The XML is read by
//! `roxmltree`, the path data and transforms by `svgtypes` (arcs become cubic
//! curves), and curves are flattened into chords by `kurbo` to a given tolerance.
//!
//! SVG's y axis points down the page; the outline is mirrored to y up, so that the
//! shape in the case looks as it does in the drawing. The element's own `transform`
//! and those of the groups around it are applied first.

use super::outline::closed_chords;
use crate::error::{Result, SphError};
use kurbo::{Affine, BezPath};
use std::str::FromStr;

/// The elements an outline can come from.
const OUTLINE_TAGS: [&str; 4] = ["path", "polygon", "polyline", "rect"];
/// Containers whose elements are not drawn where they stand.
const UNDRAWN: [&str; 6] = ["defs", "clipPath", "mask", "symbol", "marker", "pattern"];

/// The vertices of the closed outline of `path`, flattened to chords within
/// `tolerance` (in the drawing's user units, after its transforms).
pub(super) fn read(
    key: &str,
    path: &str,
    outline: Option<&str>,
    tolerance: f64,
) -> Result<Vec<[f64; 2]>> {
    let refuse = |expected: String| SphError::invalid(key, format!("{path:?}"), expected);
    let text =
        std::fs::read_to_string(path).map_err(|e| refuse(format!("a readable SVG file ({e})")))?;
    let document = roxmltree::Document::parse(&text)
        .map_err(|e| refuse(format!("an SVG (XML) file ({e})")))?;
    let element = pick(&document, outline).map_err(refuse)?;
    let drawn =
        outline_path(element).map_err(|e| refuse(format!("{} ({e})", describe(element))))?;
    let placed = Affine::FLIP_Y * transform(element).map_err(refuse)? * drawn;
    closed_chords(&placed, tolerance).map_err(|e| refuse(format!("{}: {e}", describe(element))))
}

/// The one outline element of the drawing, or the one whose id is `outline`.
fn pick<'a>(
    document: &'a roxmltree::Document,
    outline: Option<&str>,
) -> std::result::Result<roxmltree::Node<'a, 'a>, String> {
    let candidates: Vec<_> = document
        .descendants()
        .filter(|n| OUTLINE_TAGS.contains(&n.tag_name().name()))
        .filter(|n| {
            !n.ancestors()
                .any(|a| UNDRAWN.contains(&a.tag_name().name()))
        })
        .collect();
    let chosen: Vec<_> = match outline {
        Some(id) => candidates
            .iter()
            .copied()
            .filter(|n| n.attribute("id") == Some(id))
            .collect(),
        None => candidates.clone(),
    };
    let found = candidates
        .iter()
        .map(|n| describe(*n))
        .collect::<Vec<_>>()
        .join(", ");
    match (chosen.len(), outline) {
        (1, _) => Ok(chosen[0]),
        (0, None) => Err(
            "an SVG drawing with a path, polygon, polyline or rect element \
                          (found none)"
                .into(),
        ),
        (0, Some(id)) => Err(format!(
            "a path, polygon, polyline or rect element with id = {id:?} (found: {found})"
        )),
        (n, _) => Err(format!(
            "one outline element, or outline = \"<id>\" naming one (found {n}: {found})"
        )),
    }
}

/// `path#id`, or the tag alone when the element has no id.
fn describe(n: roxmltree::Node) -> String {
    match n.attribute("id") {
        Some(id) => format!("{}#{id}", n.tag_name().name()),
        None => n.tag_name().name().to_string(),
    }
}

/// The element's outline in its own coordinates.
fn outline_path(n: roxmltree::Node) -> std::result::Result<BezPath, String> {
    let attribute = |name: &str| {
        n.attribute(name)
            .ok_or_else(|| format!("it has no {name} attribute"))
    };
    match n.tag_name().name() {
        "path" => path_data(attribute("d")?),
        "rect" => {
            let number = |name: &str| -> std::result::Result<f64, String> {
                let text = attribute(name)?;
                svgtypes::Number::from_str(text)
                    .map(|v| v.0)
                    .map_err(|_| format!("{name} = {text:?} is not a plain number"))
            };
            let (x, y) = (number("x").unwrap_or(0.0), number("y").unwrap_or(0.0));
            let (w, h) = (number("width")?, number("height")?);
            Ok(kurbo::Shape::to_path(
                &kurbo::Rect::new(x, y, x + w, y + h),
                0.0,
            ))
        }
        tag => {
            let mut points = svgtypes::PointsParser::from(attribute("points")?);
            let mut bez = BezPath::new();
            if let Some((x, y)) = points.next() {
                bez.move_to((x, y));
            }
            points.for_each(|(x, y)| bez.line_to((x, y)));
            if tag == "polygon" {
                bez.close_path();
            }
            Ok(bez)
        }
    }
}

/// Path data (`d`), made absolute, arcs turned into cubic curves.
fn path_data(d: &str) -> std::result::Result<BezPath, String> {
    use svgtypes::SimplePathSegment as S;
    let mut bez = BezPath::new();
    for segment in svgtypes::SimplifyingPathParser::from(d) {
        match segment.map_err(|e| format!("path data: {e}"))? {
            S::MoveTo { x, y } => bez.move_to((x, y)),
            S::LineTo { x, y } => bez.line_to((x, y)),
            S::CurveTo {
                x1,
                y1,
                x2,
                y2,
                x,
                y,
            } => bez.curve_to((x1, y1), (x2, y2), (x, y)),
            S::Quadratic { x1, y1, x, y } => bez.quad_to((x1, y1), (x, y)),
            S::ClosePath => bez.close_path(),
        }
    }
    Ok(bez)
}

/// The product of the `transform` attributes from the root down to `n`.
fn transform(n: roxmltree::Node) -> std::result::Result<Affine, String> {
    let mut total = Affine::IDENTITY;
    for node in n.ancestors() {
        if let Some(text) = node.attribute("transform") {
            let t = svgtypes::Transform::from_str(text)
                .map_err(|e| format!("a valid transform on {} ({e})", describe(node)))?;
            total = Affine::new([t.a, t.b, t.c, t.d, t.e, t.f]) * total;
        }
    }
    Ok(total)
}
