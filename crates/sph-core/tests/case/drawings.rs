//! 2D outlines from drawings: SVG elements (with their group transforms and SVG's
//! downward y axis) and DXF polylines (with bulged arcs) hold the lattice points of
//! the polygon or circle they draw, and bad drawings are refused in one line.

use super::shapes::{build, error_of, fluid_shape, positions, scratch, HEAD_2D};
use dxf::entities::{Entity, EntityType, Line, LwPolyline};
use sph_core::{Case, Kind, Simulation};

/// The L of `a_concave_polygon_holds_exactly_its_lattice_points`, in metres, y up.
const L: [[f64; 2]; 6] = [
    [0.0, 0.0],
    [1.0, 0.0],
    [1.0, 0.5],
    [0.5, 0.5],
    [0.5, 1.0],
    [0.0, 1.0],
];

/// Builds the 2D case of one fluid shape whose file is `name`, written beside the
/// case file (so the relative name resolves from the case's folder).
fn from_drawing(name: &str, keys: &str) -> Simulation<2> {
    let case_path = scratch(&format!("{name}.toml"));
    let geometry = format!("file = {name:?}\n{keys}");
    std::fs::write(&case_path, HEAD_2D.to_string() + &fluid_shape(&geometry)).unwrap();
    let case = Case::from_file(&case_path).unwrap_or_else(|e| panic!("{e}"));
    Simulation::<2>::new(case).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn svg(body: &str) -> String {
    format!("<?xml version=\"1.0\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\">\n{body}\n</svg>\n")
}

/// A DXF drawing of closed or open lightweight polylines, each `(layer, vertices
/// (x, y, bulge), closed)`, with a stray LINE entity.
fn write_dxf(name: &str, lines: &[(&str, Vec<[f64; 3]>, bool)]) {
    let mut drawing = dxf::Drawing::new();
    // LWPOLYLINE exists from R14 on; the crate's default, R12, would leave it out
    drawing.header.version = dxf::enums::AcadVersion::R2000;
    drawing.add_entity(Entity::new(EntityType::Line(Line::default())));
    for (layer, vertices, closed) in lines {
        let mut polyline = LwPolyline::default();
        polyline.set_is_closed(*closed);
        polyline.vertices = vertices
            .iter()
            .map(|&[x, y, bulge]| dxf::LwPolylineVertex {
                x,
                y,
                bulge,
                ..Default::default()
            })
            .collect();
        let mut entity = Entity::new(EntityType::LwPolyline(polyline));
        entity.common.layer = layer.to_string();
        drawing.add_entity(entity);
    }
    drawing.save_file(scratch(name)).unwrap();
}

/// The L drawn in millimetres in an SVG path (relative moves, inside a translated
/// group, y down), as an SVG polygon, and as a DXF polyline picked by its layer among
/// two, builds exactly the particles of the inline polygon.
#[test]
fn drawn_outlines_hold_the_particles_of_the_polygon() {
    let inline = build::<2>(&(HEAD_2D.to_string() + &fluid_shape(&format!("polygon = {L:?}"))));
    let expected = positions(&inline, Kind::Fluid);
    assert_eq!(expected.len(), 300);
    let path = "<g transform=\"translate(0 -1000)\"><path id=\"hull\" \
                d=\"M 0 1000 h 1000 v -500 h -500 v -500 h -500 z\"/></g>\
                <path id=\"deck\" d=\"M 5000 5000 h 10 v 10 z\"/>";
    std::fs::write(scratch("l_path.svg"), svg(path)).unwrap();
    let points: Vec<String> = L.iter().map(|v| format!("{},{}", v[0], -v[1])).collect();
    let polygon = format!("<polygon points=\"{}\"/>", points.join(" "));
    std::fs::write(scratch("l_polygon.svg"), svg(&polygon)).unwrap();
    let mm: Vec<[f64; 3]> = L.iter().map(|v| [1e3 * v[0], 1e3 * v[1], 0.0]).collect();
    let square = vec![[5e3, 5e3, 0.0], [6e3, 5e3, 0.0], [6e3, 6e3, 0.0]];
    write_dxf("l.dxf", &[("deck", square, true), ("hull", mm, true)]);
    for (name, keys) in [
        ("l_path.svg", "outline = \"hull\"\nscale = 0.001"),
        ("l_polygon.svg", ""),
        ("l.dxf", "outline = \"hull\"\nscale = 0.001"),
    ] {
        let drawn = from_drawing(name, keys);
        assert_eq!(positions(&drawn, Kind::Fluid), expected, "{name}");
    }
}

/// Curves flattened within Δx/100: a disc drawn with two SVG arcs, and a half disc
/// drawn as a DXF polyline of one bulged segment (bulge 1, a half turn
/// counter-clockwise) and its chord, hold the lattice points of the exact disc or
/// half disc but for at most two within Δx/100 of the curve (the chords lie inside
/// it).
#[test]
fn drawn_arcs_hold_the_lattice_points_of_their_circle() {
    let (c, r) = ([0.13, 0.4], 0.4);
    let disc = build::<2>(
        &(HEAD_2D.to_string()
            + &fluid_shape(&format!("circle = {{ centre = {c:?}, radius = {r} }}"))),
    );
    let exact = positions(&disc, Kind::Fluid);
    let arcs = format!(
        "<path d=\"M {x0} {y} A {r} {r} 0 0 1 {x1} {y} A {r} {r} 0 0 1 {x0} {y} Z\"/>",
        x0 = c[0] + r,
        x1 = c[0] - r,
        y = -c[1]
    );
    std::fs::write(scratch("disc.svg"), svg(&arcs)).unwrap();
    let half = vec![[c[0], c[1] - r, 1.0], [c[0], c[1] + r, 0.0]];
    write_dxf("half_disc.dxf", &[("0", half, true)]);
    let right_half: Vec<Vec<i64>> = exact
        .iter()
        .filter(|x| x[0] as f64 * 1e-6 > c[0])
        .cloned()
        .collect();
    for (name, expected) in [("disc.svg", &exact), ("half_disc.dxf", &right_half)] {
        let drawn = positions(&from_drawing(name, ""), Kind::Fluid);
        assert!(
            drawn.iter().all(|x| expected.contains(x)),
            "{name}: a point outside the curve"
        );
        let missing = expected.len() - drawn.len();
        println!(
            "{name}: {} of {} lattice points",
            drawn.len(),
            expected.len()
        );
        assert!(missing <= 2, "{name}: {missing} lattice points missing");
        assert!(expected.len() > 80, "{name}: {}", expected.len());
    }
}

#[test]
fn bad_drawings_are_refused_in_one_line() {
    let two = "<path id=\"hull\" d=\"M 0 0 h 1 v -1 z\"/><g><path id=\"deck\" d=\"M 0 0 h 1 v -1 z\"/></g>\
               <defs><path id=\"unused\" d=\"M 0 0 h 1 z\"/></defs>";
    let files = [
        ("two.svg", svg(two)),
        ("open.svg", svg("<path d=\"M 0 0 L 1 0 L 1 -1\"/>")),
        (
            "holed.svg",
            svg("<path d=\"M 0 0 h 1 v -1 h -1 z M 0.2 -0.2 h 0.1 v -0.1 z\"/>"),
        ),
        ("junk.svg", "<svg><path d=\"M 0 0\"></svg>".to_string()),
        ("bad_data.svg", svg("<path d=\"M 0 0 L 1 x\"/>")),
        ("plain.txt", "0 0\n1 0\n1 1\n".to_string()),
    ];
    for (name, text) in &files {
        std::fs::write(scratch(name), text).unwrap();
    }
    write_dxf(
        "open.dxf",
        &[(
            "hull",
            vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]],
            false,
        )],
    );
    write_dxf("empty.dxf", &[]);
    let cases = [
        ("two.svg", "", "expected one outline element, or outline = \"<id>\" naming one (found 2: path#hull, path#deck)"),
        ("two.svg", "outline = \"keel\"", "with id = \"keel\" (found: path#hull, path#deck)"),
        ("open.svg", "", "path: a closed outline (it ends 1.414214 from its start"),
        ("holed.svg", "", "(it has 2 subpaths; draw each outline as its own shape"),
        ("junk.svg", "", "expected an SVG (XML) file"),
        ("bad_data.svg", "", "path (path data:"),
        ("open.dxf", "", "a polyline on layer \"hull\": a closed outline"),
        ("empty.dxf", "", "a DXF drawing with a 2D polyline (LWPOLYLINE or POLYLINE; found none)"),
        ("open.dxf", "outline = \"deck\"", "a 2D polyline on layer \"deck\" (found polylines on the layers: \"hull\")"),
        ("plain.txt", "outline = \"hull\"", "shape[0].outline = (set): expected a file = \"*.svg\" or \"*.dxf\""),
    ];
    for (name, keys, expected) in cases {
        let path = scratch(name).display().to_string();
        let text = HEAD_2D.to_string() + &fluid_shape(&format!("file = {path:?}\n{keys}"));
        let e = error_of::<2>(&text);
        assert!(e.starts_with("shape[0]."), "{e}");
        assert!(e.contains(expected), "{name}: {e}\n expected: {expected}");
    }
}
