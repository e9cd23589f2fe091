//! `[[shape]]` geometry: polygons, STL surfaces and primitives as fluid, walls and
//! cuts, filled on the lattice `(k + ½)Δx`, and the one-line errors of bad shapes.

use sph_core::{Case, Kind, Simulation};
use std::path::PathBuf;

pub(crate) const HEAD_2D: &str =
    "dimension = 2\n[particles]\nspacing = 0.05\n[fluid]\ndensity = 1000.0\n\
                       sound_speed = 20.0\n[time]\nend = 0.1\n";
const HEAD_3D: &str = "dimension = 3\n[particles]\nspacing = 0.05\n[fluid]\ndensity = 1000.0\n\
                       sound_speed = 20.0\n[time]\nend = 0.1\n";

pub(crate) fn build<const D: usize>(text: &str) -> Simulation<D> {
    let case = Case::from_toml_str(text).unwrap_or_else(|e| panic!("{e}\n{text}"));
    Simulation::<D>::new(case).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

/// The one-line error a case gives, from parsing or from building.
pub(crate) fn error_of<const D: usize>(text: &str) -> String {
    let e = match Case::from_toml_str(text) {
        Err(e) => e.to_string(),
        Ok(case) => match Simulation::<D>::new(case) {
            Err(e) => e.to_string(),
            Ok(_) => panic!("built: {text}"),
        },
    };
    assert_eq!(e.lines().count(), 1, "{e}");
    e
}

pub(crate) fn positions<const D: usize>(sim: &Simulation<D>, kind: Kind) -> Vec<Vec<i64>> {
    let p = sim.particles();
    let mut out: Vec<Vec<i64>> = (0..p.len())
        .filter(|&i| p.kind[i] == kind)
        .map(|i| p.x[i].iter().map(|v| (v * 1e6).round() as i64).collect())
        .collect();
    out.sort();
    out
}

pub(crate) fn fluid_shape(geometry: &str) -> String {
    format!("[[shape]]\nrole = \"fluid\"\nhydrostatic = false\n{geometry}\n")
}

/// An L-shaped (concave) polygon, in either winding, holds exactly the lattice points
/// of the unit square less its upper right quarter: 400 - 100 at Δx = 0.05.
#[test]
fn a_concave_polygon_holds_exactly_its_lattice_points() {
    let l = [
        [0.0, 0.0],
        [1.0, 0.0],
        [1.0, 0.5],
        [0.5, 0.5],
        [0.5, 1.0],
        [0.0, 1.0],
    ];
    let ccw = format!("polygon = {l:?}");
    let mut reversed = l.to_vec();
    reversed.reverse();
    let cw = format!("polygon = {reversed:?}");
    for geometry in [ccw, cw] {
        let sim = build::<2>(&(HEAD_2D.to_string() + &fluid_shape(&geometry)));
        let p = sim.particles();
        assert_eq!(sim.n_fluid(), 300, "{geometry}");
        for x in &p.x {
            let inside = (0.0..1.0).contains(&x[0])
                && (0.0..1.0).contains(&x[1])
                && !(x[0] > 0.5 && x[1] > 0.5);
            assert!(inside, "{x:?}");
        }
    }
}

/// A U-shaped wall polygon four layers thick (Δx = 0.05, R = 4Δx) around a 1 × 0.5 m
/// box of water builds the particles of the `[[tank]]` with the same inner box.
#[test]
fn a_polygon_tank_builds_the_particles_of_the_box_tank() {
    let water = "[[fluid_block]]\nlo = [0.0, 0.0]\nhi = [1.0, 0.5]\n";
    let gravity = "gravity = [0.0, -9.81]\n";
    let head = HEAD_2D.replace("sound_speed = 20.0\n", gravity);
    let tank = build::<2>(&format!(
        "{head}{water}[[tank]]\nlo = [0.0, 0.0]\nhi = [1.0, 0.8]\n"
    ));
    let u = "[[-0.2, -0.2], [1.2, -0.2], [1.2, 0.8], [1.0, 0.8], [1.0, 0.0], [0.0, 0.0], \
             [0.0, 0.8], [-0.2, 0.8]]";
    let shape = build::<2>(&format!(
        "{head}{water}[[shape]]\nrole = \"wall\"\npolygon = {u}\n"
    ));
    assert_eq!(positions(&tank, Kind::Wall), positions(&shape, Kind::Wall));
    assert_eq!(
        positions(&tank, Kind::Fluid),
        positions(&shape, Kind::Fluid)
    );
    assert_eq!(shape.bodies()[0].name, "shape0");
}

/// Curved primitives hold their area or volume to within the lattice's error at
/// R/Δx = 8: a disc, a ball and a tilted cylinder (measured -1.5%, +0.3% and +0.3%).
#[test]
fn primitives_hold_their_area_and_volume() {
    let pi = std::f64::consts::PI;
    let (r, dx): (f64, f64) = (0.4, 0.05);
    let disc = build::<2>(
        &(HEAD_2D.to_string() + &fluid_shape("circle = { centre = [0.13, -0.4], radius = 0.4 }")),
    );
    let ball = build::<3>(
        &(HEAD_3D.to_string()
            + &fluid_shape("sphere = { centre = [0.0, 0.21, 0.0], radius = 0.4 }")),
    );
    let cylinder = build::<3>(
        &(HEAD_3D.to_string()
            + &fluid_shape(
                "cylinder = { base = [0.0, 0.0, 0.0], top = [0.6, 0.8, 0.0], radius = 0.4 }",
            )),
    );
    for (name, n, dim, exact) in [
        ("disc", disc.n_fluid(), 2, pi * r * r),
        ("ball", ball.n_fluid(), 3, 4.0 / 3.0 * pi * r * r * r),
        ("cylinder", cylinder.n_fluid(), 3, pi * r * r * 1.0),
    ] {
        let held = n as f64 * dx.powi(dim);
        println!(
            "{name}: {held:.5} against {exact:.5} ({:+.2}%)",
            100.0 * (held / exact - 1.0)
        );
        assert!(
            (held / exact - 1.0).abs() < 0.02,
            "{name}: {held} against {exact}"
        );
    }
}

/// A circular cut removes the fluid inside it, and only that.
#[test]
fn a_cut_removes_the_fluid_inside_it() {
    let block = "[[fluid_block]]\nlo = [0.0, 0.0]\nhi = [1.0, 1.0]\nhydrostatic = false\n";
    let cut = "[[shape]]\nrole = \"cut\"\ncircle = { centre = [0.5, 0.5], radius = 0.3 }\n";
    let sim = build::<2>(&format!("{HEAD_2D}{block}{cut}"));
    let p = sim.particles();
    let inside =
        |x: &sph_core::Vector<2>| ((x[0] - 0.5).powi(2) + (x[1] - 0.5).powi(2)).sqrt() < 0.3;
    assert!(p.x.iter().all(|x| !inside(x)));
    // 400 lattice points, of which those within 0.3 m of the centre go
    let removed = (0..400)
        .filter(|k| {
            let x = sph_core::Vector::<2>::new(
                (k % 20) as f64 * 0.05 + 0.025,
                (k / 20) as f64 * 0.05 + 0.025,
            );
            inside(&x)
        })
        .count();
    assert_eq!(sim.n_fluid(), 400 - removed);
    assert!(removed > 100, "{removed}");
}

/// A unit cube's 12 triangles, outward (counter-clockwise seen from outside) unless
/// `inverted`; `holed` leaves out the last one.
fn cube_triangles(side: f32, inverted: bool, holed: bool) -> Vec<stl_io::Triangle> {
    let v = |i: usize| {
        stl_io::Vertex::new([
            side * (i & 1) as f32,
            side * (i >> 1 & 1) as f32,
            side * (i >> 2 & 1) as f32,
        ])
    };
    let faces: [[usize; 3]; 12] = [
        [0, 2, 1],
        [1, 2, 3], // z = 0
        [4, 5, 6],
        [5, 7, 6], // z = 1
        [0, 1, 4],
        [1, 5, 4], // y = 0
        [2, 6, 3],
        [3, 6, 7], // y = 1
        [0, 4, 2],
        [2, 4, 6], // x = 0
        [1, 3, 5],
        [3, 7, 5], // x = 1
    ];
    let count = if holed { 11 } else { 12 };
    faces[..count]
        .iter()
        .map(|&[a, b, c]| {
            let t = if inverted { [a, c, b] } else { [a, b, c] };
            stl_io::Triangle {
                normal: stl_io::Normal::new([0.0, 0.0, 0.0]),
                vertices: t.map(v),
            }
        })
        .collect()
}

pub(crate) fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("deltasph-shapes-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

fn write_binary_stl(path: &PathBuf, triangles: &[stl_io::Triangle]) {
    let mut file = std::fs::File::create(path).unwrap();
    stl_io::write_stl(&mut file, triangles.iter()).unwrap();
}

/// A cube 0.5 m on a side holds 10³ lattice points at Δx = 0.05, from a binary or an
/// ASCII STL (the latter in millimetres, scale = 0.001), found beside the case file.
#[test]
fn an_stl_cube_holds_its_lattice_points() {
    let binary = scratch("cube.stl");
    write_binary_stl(&binary, &cube_triangles(0.5, false, false));
    let mut ascii = String::from("solid cube\n");
    for t in cube_triangles(500.0, false, false) {
        ascii += "facet normal 0 0 0\nouter loop\n";
        for v in t.vertices {
            ascii += &format!("vertex {} {} {}\n", v[0], v[1], v[2]);
        }
        ascii += "endloop\nendfacet\n";
    }
    ascii += "endsolid cube\n";
    std::fs::write(scratch("cube_mm.stl"), ascii).unwrap();
    for geometry in [
        "file = \"cube.stl\"",
        "file = \"cube_mm.stl\"\nscale = 0.001",
    ] {
        let case_path = scratch("cube.toml");
        std::fs::write(&case_path, HEAD_3D.to_string() + &fluid_shape(geometry)).unwrap();
        let case = Case::from_file(&case_path).unwrap();
        let sim = Simulation::<3>::new(case).unwrap();
        assert_eq!(sim.n_fluid(), 1000, "{geometry}");
    }
}

#[test]
fn broken_stl_surfaces_are_refused_in_one_line() {
    let inverted = scratch("inverted.stl");
    write_binary_stl(&inverted, &cube_triangles(0.5, true, false));
    let holed = scratch("holed.stl");
    write_binary_stl(&holed, &cube_triangles(0.5, false, true));
    let junk = scratch("junk.stl");
    std::fs::write(&junk, "solid nothing\nfacet oops\n").unwrap();
    for (path, expected) in [
        (&inverted, "inverted normals"),
        (&holed, "closed (watertight)"),
        (&junk, "an ASCII or binary STL file"),
        (&scratch("missing.stl"), "a readable STL file"),
    ] {
        let geometry = format!("file = {:?}", path.display().to_string());
        let e = error_of::<3>(&(HEAD_3D.to_string() + &fluid_shape(&geometry)));
        assert!(e.starts_with("shape[0].file = "), "{e}");
        assert!(e.contains(expected), "{e}");
    }
}

#[test]
fn bad_polygons_and_misplaced_keys_are_refused_in_one_line() {
    let vertices = scratch("bad_vertices.txt");
    std::fs::write(&vertices, "# x y\n0 0\n1 0\n1 one\n").unwrap();
    let block = "[[fluid_block]]\nlo = [0.0, 0.0]\nhi = [1.0, 1.0]\n";
    let wall = |geometry: &str| format!("{HEAD_2D}{block}[[shape]]\nrole = \"wall\"\n{geometry}\n");
    let cases = [
        (
            fluid_shape("polygon = [[0.0, 0.0], [1.0, 1.0], [1.0, 0.0], [0.0, 1.0]]"),
            "shape[0].polygon = edges 0 and 2 cross",
        ),
        (
            fluid_shape("polygon = [[0.0, 0.0], [1.0, 1.0], [0.0, 0.0]]"),
            "shape[0].polygon = 2 distinct vertices",
        ),
        (
            fluid_shape("polygon = [[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]]"),
            "enclosing no area",
        ),
        (
            fluid_shape(&format!("file = {:?}", vertices.display().to_string())),
            "(line 4: \"1 one\")",
        ),
        (
            fluid_shape("polygon = [[0.0, 0.0], [1.0, 0.0]]\ncircle = { centre = [0.0, 0.0], radius = 1.0 }"),
            "shape[0] = [\"polygon\", \"circle\"]: expected exactly one of",
        ),
        (
            fluid_shape("sphere = { centre = [0.0, 0.0, 0.0], radius = 1.0 }"),
            "shape[0].sphere = (set): expected a shape of a 2D case (sphere is 3D only)",
        ),
        (
            fluid_shape("circle = { centre = [0.0, 0.0], radius = 0.5 }\nname = \"drop\""),
            "shape[0].name = (set): expected no name for role = \"fluid\"",
        ),
        (
            wall("polygon = [[0.0, 1.0], [1000.0, 1.0], [1000.0, 1200.0], [0.0, 1200.0]]"),
            "unit mismatch suspected",
        ),
        (
            wall("polygon = [[0.3, 0.3], [0.7, 0.3], [0.7, 0.4], [0.3, 0.4]]"),
            "shape[0] = a wall at most 0.1500 m thick: expected a wall at least its depth",
        ),
        (
            wall("circle = { centre = [0.5, 0.5], radius = 0.5 }\nlayers = 2"),
            "shape[0].layers = 2: expected at least 4 layers",
        ),
        (
            format!("{HEAD_2D}[[shape]]\nrole = \"cut\"\ncircle = {{ centre = [0.5, 0.5], radius = 0.5 }}\n"),
            "at least one [[fluid_block]] or [[shape]] with role = \"fluid\"",
        ),
    ];
    for (text, expected) in cases {
        let text = if text.starts_with("dimension") {
            text
        } else {
            format!("{HEAD_2D}{text}")
        };
        let e = error_of::<2>(&text);
        assert!(e.contains(expected), "{e}\n expected: {expected}");
    }
}

/// Fluid off the walls' lattice gets a notice naming the distance and the pair: a
/// fluid block across a wall shape, its `lo` (−0.475) not a multiple of Δx, keeps fluid
/// on the shape's faces, half a spacing from the shape's particles on the lattice of
/// the origin; with `lo` on a multiple (−0.5) the closest fluid is a spacing away and
/// there is no notice.
#[test]
fn fluid_off_the_walls_lattice_gets_a_notice() {
    let case = |lo: f64| {
        format!(
            "{HEAD_2D}[[fluid_block]]\nlo = [{lo}, 0.0]\nhi = [0.5, 0.5]\n\
             [[shape]]\nrole = \"wall\"\nbox = {{ lo = [-0.3, -0.3], hi = [0.0, 0.6] }}\n"
        )
    };
    let off = build::<2>(&case(-0.475));
    assert_eq!(off.notices().len(), 1, "{:?}", off.notices());
    let notice = &off.notices()[0];
    assert!(
        notice.contains("0.50 Δx")
            && notice.contains("fluid_block[0]")
            && notice.contains("shape[0]"),
        "{notice}"
    );
    assert!(build::<2>(&case(-0.5)).notices().is_empty());
}
