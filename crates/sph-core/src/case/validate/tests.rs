use crate::case::tests::{error_of, MINIMAL};
use crate::case::Case;

/// A 3D rectangle sensor on the tank's +x face, with `extra` keys.
fn sensor_3d(extra: &str) -> String {
    MINIMAL
        .replace("dimension = 2", "dimension = 3")
        .replace("[0.0, -9.81]", "[0.0, 0.0, -9.81]")
        .replace("lo = [0.0, 0.0]", "lo = [0.0, 0.0, 0.0]")
        .replace("hi = [0.2, 0.1]", "hi = [0.2, 0.1, 0.1]")
        .replace("hi = [0.5, 0.3]", "hi = [0.5, 0.3, 0.3]")
        + "[[diagnostics.sensors]]\nname = \"s\"\ncentre = [0.5, 0.1, 0.05]\n\
           normal = [-1.0, 0.0, 0.0]\nsize = 0.02\n"
        + extra
}

#[test]
fn rectangle_sensors_need_a_width_and_a_direction_in_their_plane() {
    assert!(Case::from_toml_str(&sensor_3d("width = 0.01\nalong = [0.0, 0.0, 1.0]\n")).is_ok());
    let e = error_of(&sensor_3d("width = 0.01\n"));
    assert!(
        e.starts_with("diagnostics.sensors[0].width = 0.01: expected `along` with it"),
        "{e}"
    );
    let e = error_of(&sensor_3d("along = [0.0, 1.0, 0.0]\n"));
    assert!(
        e.starts_with("diagnostics.sensors[0].along = [0.0, 1.0, 0.0]: expected `width`"),
        "{e}"
    );
    let e = error_of(&sensor_3d("width = 0.01\nalong = [2.0, 0.0, 0.0]\n"));
    assert!(
        e.starts_with("diagnostics.sensors[0].along = [2.0, 0.0, 0.0]: expected a direction in the face's plane"),
        "{e}"
    );
    let e = error_of(&sensor_3d("width = -0.01\nalong = [0.0, 0.0, 1.0]\n"));
    assert!(e.starts_with("diagnostics.sensors[0].width = -0.01"), "{e}");
    let flat = MINIMAL.to_string()
        + "[[diagnostics.sensors]]\nname = \"s\"\ncentre = [0.5, 0.1]\n\
           normal = [-1.0, 0.0]\nsize = 0.02\nwidth = 0.01\n";
    let e = error_of(&flat);
    assert!(
        e.starts_with("diagnostics.sensors[0].width = 0.01: expected no width in 2D"),
        "{e}"
    );
}

#[test]
fn absurd_spacing_is_refused_before_building() {
    let e = error_of(&MINIMAL.replace("spacing = 0.01", "spacing = 1e-9"));
    assert!(
        e.starts_with("particles.spacing = 0.000000001: expected a spacing giving at most"),
        "{e}"
    );
}

#[test]
fn a_periodic_axis_names_the_tank_faces_to_open() {
    let periodic = MINIMAL.to_string()
        + "[domain]\nlo = [-0.1, -0.1]\nhi = [0.6, 0.5]\nperiodic = [true, false]\n";
    let e = error_of(&periodic);
    assert_eq!(
        e,
        "tank[0].open = [\"+y\"] (the default): expected the faces along periodic axis x open \
         (domain.periodic): add \"-x\" and \"+x\", e.g. open = [\"+y\", \"-x\", \"+x\"]"
    );
    let half = periodic.replace(
        "hi = [0.5, 0.3]",
        "hi = [0.5, 0.3]\nopen = [\"+y\", \"-x\"]",
    );
    let e = error_of(&half);
    assert!(
        e.contains("add \"+x\", e.g. open = [\"+y\", \"-x\", \"+x\"]"),
        "{e}"
    );
    let open = half.replace("\"-x\"]", "\"-x\", \"+x\"]");
    assert!(Case::from_toml_str(&open).is_ok());
}

#[test]
fn negative_spacing_is_refused() {
    let e = error_of(&MINIMAL.replace("spacing = 0.01", "spacing = -0.01"));
    assert_eq!(e, "particles.spacing = -0.01: expected a positive number");
}

#[test]
fn body_names_are_plain_and_unique() {
    let walls = |a: &str, b: &str| {
        MINIMAL.to_string()
            + &format!(
                "[[wall]]\nname = \"{a}\"\nlo = [0.3, 0.0]\nhi = [0.4, 0.1]\n\
                 [[wall]]\nname = \"{b}\"\nlo = [0.4, 0.0]\nhi = [0.5, 0.1]\n"
            )
    };
    assert!(Case::from_toml_str(&walls("step", "baffle_2")).is_ok());
    let e = error_of(&walls("step", "step"));
    assert!(
        e.starts_with(
            "wall[1].name = \"step\": expected a name no other body has (wall[0].name has it)"
        ),
        "{e}"
    );
    let e = error_of(&walls("tank0", "b"));
    assert!(
        e.starts_with("wall[0].name = \"tank0\": expected a name no other"),
        "{e}"
    );
    let e = error_of(&walls("a b", "c"));
    assert!(
        e.starts_with("wall[0].name = \"a b\": expected a letter"),
        "{e}"
    );
    let named = MINIMAL.replace("hi = [0.2, 0.1]", "hi = [0.2, 0.1]\nname = \"water\"");
    let e = error_of(&named);
    assert!(
        e.starts_with("fluid_block[0].name") && e.contains("unknown field"),
        "fluid blocks carry no load, so no name: {e}"
    );
}

#[test]
fn deflate_levels_beyond_9_are_refused() {
    let e = error_of(&format!("{MINIMAL}\n[output]\ncompression = 12\n"));
    assert_eq!(
        e,
        "output.compression = 12: expected a deflate level from 0 (none) to 9"
    );
    let e = error_of(&format!("{MINIMAL}\n[output]\ncompression = -1\n"));
    assert!(e.starts_with("output.compression"), "{e}");
}

#[test]
fn h_over_dx_out_of_range() {
    let e = error_of(&MINIMAL.replace("spacing = 0.01", "spacing = 0.01\nh_over_dx = 7"));
    assert!(e.starts_with("particles.h_over_dx = 7"), "{e}");
}

#[test]
fn wrong_component_count() {
    let e = error_of(&MINIMAL.replace("gravity = [0.0, -9.81]", "gravity = [0.0, 0.0, -9.81]"));
    assert!(
        e.starts_with("fluid.gravity = [0.0, 0.0, -9.81]: expected 2 components"),
        "{e}"
    );
}

#[test]
fn inverted_box() {
    let e = error_of(&MINIMAL.replace("hi = [0.2, 0.1]", "hi = [0.2, -0.1]"));
    assert!(e.starts_with("fluid_block[0].hi"), "{e}");
}

/// δ-LES-SPH is offered for periodic flows without walls: each other setting is
/// refused in one line naming its key.
#[test]
fn les_is_refused_where_it_is_not_offered() {
    let les = "[scheme]\nturbulence = \"delta_les\"\nviscosity = \"physical\"\n\
               dynamic_viscosity = 0.001";
    let e = error_of(&format!("{MINIMAL}\n{les}"));
    assert!(e.starts_with("tank/wall/shape = walls"), "{e}");
    let periodic = "[domain]\nlo = [0.0, 0.0]\nhi = [0.2, 0.1]\nperiodic = [true, true]";
    let open = MINIMAL.replace(
        "[[tank]]\n        lo = [0.0, 0.0]\n        hi = [0.5, 0.3]",
        "",
    );
    let e = error_of(&format!("{open}\n{les}"));
    assert!(e.starts_with("domain.periodic = None"), "{e}");
    let e = error_of(&format!(
        "{open}\n{les}\nshifting = \"delta_plus\"\n{periodic}"
    ));
    assert!(e.starts_with("scheme.shifting = \"delta_plus\""), "{e}");
    let e = error_of(&format!(
        "{open}\n{les}\nsmagorinsky_constant = -0.1\n{periodic}"
    ));
    assert!(e.starts_with("scheme.smagorinsky_constant = -0.1"), "{e}");
    let artificial = "[scheme]\nturbulence = \"delta_les\"";
    let e = error_of(&format!("{open}\n{artificial}\n{periodic}"));
    assert!(e.starts_with("scheme.viscosity = \"artificial\""), "{e}");
}

#[test]
fn physical_viscosity_needs_mu() {
    let e = error_of(&format!("{MINIMAL}\n[scheme]\nviscosity = \"physical\""));
    assert!(e.starts_with("scheme.dynamic_viscosity = (missing)"), "{e}");
}

#[test]
fn bad_open_face() {
    let e = error_of(&MINIMAL.replace("hi = [0.5, 0.3]", "hi = [0.5, 0.3]\nopen = [\"+z\"]"));
    assert!(e.starts_with("tank[0].open = \"+z\""), "{e}");
}

#[test]
fn name_must_be_a_plain_file_name() {
    for bad in ["../x", "/tmp/x", "a/b", "..", "", "a\\\\b"] {
        let e = error_of(&format!("name = {bad:?}\n{MINIMAL}"));
        assert!(
            e.starts_with(&format!("name = {bad:?}: expected a plain file name")),
            "{e}"
        );
    }
    assert!(Case::from_toml_str(&format!("name = \"dam-break_2\"\n{MINIMAL}")).is_ok());
}

#[test]
fn wall_layers_must_cover_the_support() {
    // h/Δx = 2: R = 4Δx, three layers are too few; unset, the default is four
    let text = MINIMAL.replace("spacing = 0.01", "spacing = 0.01\nh_over_dx = 2.0");
    let e = error_of(&text.replace("hi = [0.5, 0.3]", "hi = [0.5, 0.3]\nlayers = 3"));
    assert!(
        e.starts_with("tank[0].layers = 3: expected at least 4 layers"),
        "{e}"
    );
    let case = Case::from_toml_str(&text).unwrap();
    assert_eq!(case.tank[0].layer_count(&case), 4);
}

#[test]
fn thin_wall_boxes_are_refused() {
    let wall = "\n[[wall]]\nlo = [0.3, 0.0]\nhi = [0.32, 0.2]\n";
    let e = error_of(&format!("{MINIMAL}{wall}"));
    assert!(
        e.starts_with("wall[0] = lo = [0.3, 0.0], hi = [0.32, 0.2]: expected a box at least"),
        "{e}"
    );
}

/// MINIMAL with a baffle `[[wall]]` carrying `keys` (after its box) and `table` as
/// its `prescribed` table when given.
fn moving_baffle(keys: &str, table: Option<&str>) -> String {
    let mut text =
        MINIMAL.to_string() + "[[wall]]\nlo = [0.3, 0.0]\nhi = [0.4, 0.1]\n" + keys + "\n";
    if let Some(table) = table {
        text += &format!("[wall.prescribed]\n{table}\n");
    }
    text
}

#[test]
fn motions_agree_with_their_tables_and_the_dimension() {
    let ok = moving_baffle(
        "motion = \"prescribed\"",
        Some("displacement = [\"0.01*sin(t)\", \"0\"]\nrotation = [\"0\"]\npivot = [0.35, 0.05]"),
    );
    assert!(Case::from_toml_str(&ok).is_ok());
    let refused = [
        (
            moving_baffle("motion = \"prescribed\"", None),
            "wall[0].motion = \"prescribed\": expected a table wall[0].prescribed",
        ),
        (
            moving_baffle("", Some("displacement = [\"t\", \"0\"]")),
            "wall[0].prescribed = a table: expected motion = \"prescribed\"",
        ),
        (
            moving_baffle("motion = \"prescribed\"", Some("displacement = [\"t\"]")),
            "wall[0].prescribed.displacement = 1 expressions: expected one expression per axis",
        ),
        (
            moving_baffle(
                "motion = \"prescribed\"",
                Some("rotation = [\"t\", \"0\", \"0\"]"),
            ),
            "wall[0].prescribed.rotation = 3 expressions: expected one expression: the angle",
        ),
        (
            moving_baffle("motion = \"prescribed\"", Some("rotation = [\"t\"]")),
            "wall[0].prescribed.pivot = none: expected the point the body turns about",
        ),
        (
            moving_baffle(
                "motion = \"prescribed\"",
                Some("table = \"paddle.csv\"\ndisplacement = [\"t\", \"0\"]"),
            ),
            "wall[0].prescribed.table = \"paddle.csv\": expected either a table or",
        ),
        (
            moving_baffle("motion = \"prescribed\"", Some("ramp = -1.0")),
            "wall[0].prescribed.ramp = -1",
        ),
    ];
    for (text, start) in refused {
        let e = error_of(&text);
        assert!(e.starts_with(start), "{e}\nexpected to start with: {start}");
    }
}

/// The minimal case with a free `[[wall]]` baffle, `table` its `[wall.free]` table.
fn free_baffle(table: &str) -> String {
    moving_baffle("motion = \"free\"", None) + "[wall.free]\n" + table + "\n"
}

#[test]
fn free_bodies_need_a_mass_and_consistent_constraints() {
    let ok = free_baffle(
        "density = 500.0\nlocked = [\"x\", \"rz\"]\nvelocity = [0.0, 0.1]\n\
         [[wall.free.springs]]\npoint = [0.35, 0.1]\nanchor = [0.35, 0.5]\nstiffness = 100.0",
    );
    assert!(Case::from_toml_str(&ok).is_ok(), "{}", error_of(&ok));
    let refused = [
        (
            moving_baffle("motion = \"free\"", None),
            "wall[0].motion = \"free\": expected a table wall[0].free giving its mass",
        ),
        (
            moving_baffle("", None) + "[wall.free]\nmass = 1.0\n",
            "wall[0].free = a table: expected motion = \"free\" beside it",
        ),
        (
            free_baffle("locked = [\"x\"]"),
            "wall[0].free.mass = none: expected the body's mass, or its density",
        ),
        (
            free_baffle("mass = 1.0\ndensity = 500.0"),
            "wall[0].free.density = a density beside a mass: expected either",
        ),
        (free_baffle("mass = -1.0"), "wall[0].free.mass = -1"),
        (
            free_baffle("mass = 1.0\ninertia = [0.0]"),
            "wall[0].free.inertia = [0.0]: expected one positive value (about z)",
        ),
        (
            free_baffle("mass = 1.0\nlocked = [\"z\"]"),
            "wall[0].free.locked = \"z\": expected distinct names among [\"x\", \"y\", \"rz\"]",
        ),
        (
            free_baffle("mass = 1.0\nlocked = [\"x\", \"x\"]"),
            "wall[0].free.locked = \"x\": expected distinct names",
        ),
        (
            free_baffle("mass = 1.0\nlocked = [\"y\"]\nvelocity = [0.0, 1.0]"),
            "wall[0].free.velocity = [0.0, 1.0]: expected no velocity along y, which is held",
        ),
        (
            free_baffle("mass = 1.0\nhinge = [0.35, 0.1]\nvelocity = [1.0, 0.0]"),
            "wall[0].free.velocity = [1.0, 0.0]: expected no velocity along x, which is held",
        ),
        (
            free_baffle("mass = 1.0\nlocked = [\"rz\"]\nangular_velocity = [2.0]"),
            "wall[0].free.angular_velocity = [2.0]: expected no rotation about rz",
        ),
        (
            free_baffle("mass = 1.0\nangular_velocity = [1.0, 2.0, 3.0]"),
            "wall[0].free.angular_velocity = [1.0, 2.0, 3.0]: expected 1 component(s)",
        ),
        (
            free_baffle(
                "mass = 1.0\n[[wall.free.springs]]\npoint = [0.35, 0.1]\n\
                 anchor = [0.35, 0.1]\nstiffness = 1.0",
            ),
            "wall[0].free.springs[0].anchor = [0.35, 0.1]: expected an anchor apart",
        ),
        (
            MINIMAL.to_string() + "[[tank]]\nlo = [0.0, 0.0]\nhi = [1.0, 1.0]\nmotion = \"free\"\n",
            "tank[1].motion = \"free\": expected \"fixed\" or \"prescribed\" (a tank",
        ),
    ];
    for (text, start) in refused {
        let e = error_of(&text);
        assert!(e.starts_with(start), "{e}\nexpected to start with: {start}");
    }
    // a 3D inertia tensor that is not positive definite
    let tensor = crate::motion::free::inertia_tensor(&[1.0, 1.0, 1.0, 2.0, 0.0, 0.0]);
    assert!(tensor.symmetric_eigenvalues().min() < 0.0);
}

/// MINIMAL with a wave maker `[wall]` whose `waves` table holds `waves`, and `extra`.
fn wave_maker(waves: &str, extra: &str) -> String {
    MINIMAL.to_string()
        + "[[wall]]\nlo = [0.3, 0.0]\nhi = [0.34, 0.3]\nmotion = \"prescribed\"\n\
           [wall.prescribed]\n"
        + extra
        + "[wall.prescribed.waves]\n"
        + waves
}

#[test]
fn wave_makers_are_checked_in_one_line() {
    let regular = "paddle = \"piston\"\ndepth = 0.1\nheight = 0.01\nperiod = 1.0\n";
    assert!(Case::from_toml_str(&wave_maker(regular, "")).is_ok());
    for (waves, extra, expected) in [
        (
            "paddle = \"piston\"\ndepth = 0.1\nheight = 0.09\nperiod = 1.0\n",
            "",
            "wall[0].prescribed.waves.height = 0.09: expected a height below the breaking \
             limit 0.142 L tanh(kd) = 7.7",
        ),
        (
            "paddle = \"piston\"\ndepth = 0.1\nheight = 0.01\n",
            "",
            "wall[0].prescribed.waves.period = None with wavelength None: expected one of \
             period and wavelength",
        ),
        (
            "paddle = \"flap\"\ndepth = 0.1\nheight = 0.01\nperiod = 1.0\n",
            "",
            "wall[0].prescribed.waves.paddle = \"flap\": expected the flap's hinge as the \
             table's pivot",
        ),
        (
            "paddle = \"flap\"\ndepth = 0.1\nheight = 0.01\nperiod = 1.0\norder = 2\n",
            "pivot = [0.3, 0.0]\n",
            "wall[0].prescribed.waves.order = 2: expected 1, or 2 for a piston",
        ),
        (
            regular,
            "displacement = [\"0\", \"0\"]\n",
            "wall[0].prescribed.displacement = given: expected either a wave maker",
        ),
        (
            "paddle = \"piston\"\ndepth = 0.1\nheight = 0.01\n\
             spectrum = { significant_height = 0.01, peak_period = 1.0 }\n",
            "",
            "wall[0].prescribed.waves.height = given: expected regular-wave keys or a spectrum",
        ),
        (
            "paddle = \"piston\"\ndepth = 0.1\n\
             spectrum = { significant_height = 0.01, peak_period = 1.0, frequencies = [2.0, 1.0] }\n",
            "",
            "wall[0].prescribed.waves.spectrum.frequencies = [2, 1]: expected [f_min, f_max]",
        ),
        (
            "paddle = \"piston\"\ndepth = 0.1\nheight = 0.01\nperiod = 1.0\nduration = -2.0\n",
            "",
            "wall[0].prescribed.waves.duration = -2: expected a positive",
        ),
    ] {
        let e = error_of(&wave_maker(waves, extra));
        assert!(e.starts_with(expected), "{e}\n expected: {expected}");
    }
}

#[test]
fn gauges_and_absorbers_are_checked_in_one_line() {
    let gauge = |g: &str| MINIMAL.to_string() + "[[diagnostics.gauges]]\n" + g;
    assert!(Case::from_toml_str(&gauge("name = \"g\"\nposition = [0.1]\n")).is_ok());
    for (text, expected) in [
        (
            gauge("name = \"g\"\nposition = [0.1, 0.2]\n"),
            "diagnostics.gauges[0].position = [0.1, 0.2]: expected 1",
        ),
        (
            gauge("name = \"g\"\nposition = [0.1]\nbottom = 0.2\ntop = 0.1\n"),
            "diagnostics.gauges[0].top = 0.1: expected a top above the bottom 0.2",
        ),
        (
            gauge("name = \"g\"\nposition = [0.1]\nbottom = 0.0\ntop = 1e6\n"),
            "diagnostics.gauges[0].top = 1000000: expected a line from the bottom 0 of at most",
        ),
        (
            MINIMAL.to_string() + "[[absorber]]\nfrom = 0.3\nto = 0.3\n",
            "absorber[0].to = 0.3: expected a zone of some length",
        ),
        (
            MINIMAL.to_string() + "[[absorber]]\nfrom = 0.3\nto = 0.5\nrate = -1.0\n",
            "absorber[0].rate = -1: expected a positive number",
        ),
    ] {
        let e = error_of(&text);
        assert!(e.starts_with(expected), "{e}\n expected: {expected}");
    }
}
