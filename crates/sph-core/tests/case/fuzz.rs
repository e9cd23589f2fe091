//! Hostile input for the case parser, the validator and the particle builder:
//! arbitrary text, and valid cases with keys (scheme, geometry, domain, initial
//! fields, probes, sensors, shapes) mutated to arbitrary values, must give a
//! simulation or an error
//! whose message is one line, never a panic.

use proptest::prelude::*;
use sph_core::{Case, Simulation};

/// A dam break with every kind of geometry: a fluid block, a tank, a wall box, a
/// domain and probes.
const DAM_BREAK: &str = r#"
dimension = 2
[particles]
spacing = 0.05
[fluid]
density = 1000.0
gravity = [0.0, -9.81]
[[fluid_block]]
lo = [0.0, 0.0]
hi = [1.0, 0.5]
[[tank]]
lo = [0.0, 0.0]
hi = [2.0, 1.0]
[[wall]]
lo = [1.4, 0.0]
hi = [1.6, 0.3]
[domain]
lo = [-1.0, -1.0]
hi = [3.0, 2.0]
[scheme]
diffusion = "delta_sph"
[time]
end = 1.0
[diagnostics]
probes = [[2.0, 0.1]]
surge_front_axis = 0
[[diagnostics.sensors]]
name = "right"
centre = [2.0, 0.1]
normal = [-1.0, 0.0]
size = 0.05
cutoff = 10.0
[[shape]]
role = "wall"
polygon = [[1.65, 0.0], [1.95, 0.0], [1.95, 0.4]]
[[shape]]
role = "cut"
circle = { centre = [0.5, 0.25], radius = 0.1 }
"#;

/// A periodic box with an analytic initial field.
const TAYLOR_GREEN: &str = r#"
dimension = 2
[particles]
spacing = 0.05
h_over_dx = 2.0
[fluid]
density = 1.0
sound_speed = 10.0
[[fluid_block]]
lo = [0.0, 0.0]
hi = [1.0, 1.0]
hydrostatic = false
[domain]
lo = [0.0, 0.0]
hi = [1.0, 1.0]
periodic = [true, true]
[initial]
type = "taylor_green"
amplitude = 1.0
wavelength = 1.0
[scheme]
viscosity = "physical"
dynamic_viscosity = 0.01
[time]
end = 1.0
"#;

/// Key paths of the dam break: tables, then the key; a number indexes an array of tables.
const DAM_BREAK_KEYS: &[&str] = &[
    "name",
    "dimension",
    "particles.spacing",
    "particles.h_over_dx",
    "particles.kernel",
    "fluid.density",
    "fluid.gravity",
    "fluid.sound_speed",
    "fluid.background_pressure",
    "fluid.max_velocity",
    "fluid_block.0.lo",
    "fluid_block.0.hi",
    "fluid_block.0.velocity",
    "fluid_block.0.hydrostatic",
    "fluid_block.0.shape",
    "tank.0.lo",
    "tank.0.hi",
    "tank.0.layers",
    "tank.0.open",
    "tank.0.lid_velocity",
    "wall.0.lo",
    "wall.0.hi",
    "domain.lo",
    "domain.hi",
    "domain.periodic",
    "scheme.diffusion",
    "scheme.delta",
    "scheme.viscosity",
    "scheme.alpha",
    "scheme.cfl",
    "scheme.integrator",
    "scheme.shifting",
    "scheme.walls",
    "time.end",
    "time.max_steps",
    "time.output_interval",
    "stability.max_density_variation",
    "stability.max_mach",
    "diagnostics.probes",
    "diagnostics.surge_front_axis",
    "diagnostics.sensors.0.name",
    "diagnostics.sensors.0.normal",
    "diagnostics.sensors.0.size",
    "diagnostics.sensors.0.cutoff",
    "output.restart_interval",
    "output.compression",
    "shape.0.role",
    "shape.0.polygon",
    "shape.0.polygon.1",
    "shape.0.scale",
    "shape.0.layers",
    "shape.0.name",
    "shape.0.file",
    "shape.1.circle",
    "shape.1.circle.radius",
    "shape.1.box",
];

const TAYLOR_GREEN_KEYS: &[&str] = &[
    "domain.lo",
    "domain.hi",
    "domain.periodic",
    "initial.type",
    "initial.amplitude",
    "initial.wavelength",
    "initial.radius",
    "initial.side",
    "fluid_block.0.lo",
    "fluid_block.0.hi",
    "fluid_block.0.shape",
    "scheme.dynamic_viscosity",
];

/// Arbitrary TOML values: numbers of every sign and size, NaN and infinities, strings,
/// booleans, arrays (among them points of plausible size) and tables.
fn value() -> impl Strategy<Value = String> {
    let leaf = prop_oneof![
        any::<i64>().prop_map(|v| v.to_string()),
        any::<f64>().prop_map(|v| {
            if v.is_nan() {
                "nan".to_string()
            } else if v.is_infinite() {
                if v > 0.0 { "inf" } else { "-inf" }.to_string()
            } else {
                format!("{v:e}")
            }
        }),
        (-3.0..3.0f64).prop_map(|v| format!("{v:?}")),
        (1usize..8).prop_map(|v| v.to_string()),
        Just("0.0".to_string()),
        Just("-1.0".to_string()),
        Just("1e308".to_string()),
        "[a-z_+-]{0,12}".prop_map(|s| format!("{s:?}")),
        any::<bool>().prop_map(|b| b.to_string()),
    ];
    let point = prop::collection::vec(-3.0..3.0f64, 1..4).prop_map(|v| {
        let items: Vec<String> = v.iter().map(|c| format!("{c:?}")).collect();
        format!("[{}]", items.join(", "))
    });
    let arbitrary = leaf.prop_recursive(2, 8, 4, |inner| {
        prop_oneof![
            prop::collection::vec(inner.clone(), 0..4).prop_map(|v| format!("[{}]", v.join(", "))),
            inner.prop_map(|v| format!("{{ x = {v} }}")),
        ]
    });
    prop_oneof![3 => arbitrary, 1 => point.clone(), 1 => point.prop_map(|p| format!("[{p}]"))]
}

/// An upper estimate of the lattice points of a parsed case's boxes, to keep the
/// builds of the test small.
fn lattice_points(case: &Case) -> f64 {
    let dx = case.particles.spacing;
    let count = |lo: &[f64], hi: &[f64], pad: f64| -> f64 {
        lo.iter()
            .zip(hi)
            .map(|(l, h)| ((h - l + 2.0 * pad) / dx).abs() + 1.0)
            .product()
    };
    let fluid: f64 = case
        .fluid_block
        .iter()
        .map(|b| count(&b.lo, &b.hi, 0.0))
        .sum();
    let tanks: f64 = case
        .tank
        .iter()
        .map(|t| count(&t.lo, &t.hi, t.layer_count(case) as f64 * dx))
        .sum();
    let walls: f64 = case.wall.iter().map(|b| count(&b.lo, &b.hi, 0.0)).sum();
    fluid + tanks + walls
}

fn one_line(e: impl std::fmt::Display) {
    let message = e.to_string();
    assert!(!message.trim().is_empty(), "an empty message");
    assert_eq!(message.lines().count(), 1, "not one line: {message:?}");
}

/// Parses, validates and (when small enough) builds the case: a simulation, or an
/// error whose message is one line.
fn accepted_or_one_line_error(text: &str) {
    let case = match Case::from_toml_str(text) {
        Ok(case) => case,
        Err(e) => return one_line(e),
    };
    if lattice_points(&case) > 50_000.0 {
        return;
    }
    let built = match case.dimension {
        2 => Simulation::<2>::new(case).map(|_| ()),
        _ => Simulation::<3>::new(case).map(|_| ()),
    };
    if let Err(e) = built {
        one_line(e);
    }
}

/// `base` with the value at `path` replaced by `value` (TOML text).
fn mutated(base: &str, path: &str, value: &str) -> String {
    let mut doc = toml::Value::Table(base.parse().unwrap());
    let parsed: toml::Table = format!("v = {value}").parse().unwrap();
    let keys: Vec<&str> = path.split('.').collect();
    let mut node = &mut doc;
    for k in &keys[..keys.len() - 1] {
        node = match k.parse::<usize>() {
            Ok(i) => &mut node.as_array_mut().unwrap()[i],
            Err(_) => node
                .as_table_mut()
                .unwrap()
                .entry(k.to_string())
                .or_insert_with(|| toml::Value::Table(Default::default())),
        };
    }
    let last = keys[keys.len() - 1];
    match last.parse::<usize>() {
        Ok(i) => node.as_array_mut().unwrap()[i] = parsed["v"].clone(),
        Err(_) => {
            node.as_table_mut()
                .unwrap()
                .insert(last.to_string(), parsed["v"].clone());
        }
    }
    toml::to_string(&doc).unwrap()
}

/// `base` with the number or numbers at `path` scaled by `factors` and shifted by
/// `offsets` (component by component): values of the right type, near valid ones.
fn perturbed(base: &str, path: &str, factors: &[f64], offsets: &[f64]) -> String {
    let doc: toml::Value = toml::Value::Table(base.parse().unwrap());
    let mut node = &doc;
    for k in path.split('.') {
        node = match k.parse::<usize>() {
            Ok(i) => &node[i],
            Err(_) => &node[k],
        };
    }
    let shift = |k: usize, v: f64| v * factors[k % factors.len()] + offsets[k % offsets.len()];
    let value = match node {
        toml::Value::Array(items) => {
            let items: Vec<String> = items
                .iter()
                .enumerate()
                .map(|(k, v)| format!("{:?}", shift(k, v.as_float().unwrap_or(0.0))))
                .collect();
            format!("[{}]", items.join(", "))
        }
        toml::Value::Float(v) => format!("{:?}", shift(0, *v)),
        toml::Value::Integer(v) => format!("{}", shift(0, *v as f64).round() as i64),
        other => other.to_string(),
    };
    mutated(base, path, &value)
}

/// The numeric keys of the dam break that [`perturbed`] changes.
const NUMERIC_KEYS: &[&str] = &[
    "particles.spacing",
    "fluid.density",
    "fluid.gravity",
    "fluid_block.0.lo",
    "fluid_block.0.hi",
    "tank.0.lo",
    "tank.0.hi",
    "wall.0.lo",
    "wall.0.hi",
    "domain.lo",
    "domain.hi",
    "diagnostics.probes.0",
    "diagnostics.sensors.0.centre",
    "shape.0.polygon.0",
    "shape.0.polygon.2",
    "shape.1.circle.centre",
    "shape.1.circle.radius",
    "time.end",
];

#[test]
fn the_bases_build() {
    for base in [DAM_BREAK, TAYLOR_GREEN] {
        Simulation::<2>::new(Case::from_toml_str(base).unwrap()).unwrap();
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1500))]

    #[test]
    fn arbitrary_text_never_panics(text in "\\PC{0,400}") {
        accepted_or_one_line_error(&text);
    }

    #[test]
    fn mutated_dam_breaks_never_panic(k in 0..DAM_BREAK_KEYS.len(), v in value()) {
        accepted_or_one_line_error(&mutated(DAM_BREAK, DAM_BREAK_KEYS[k], &v));
    }

    #[test]
    fn perturbed_geometry_never_panics(
        k in 0..NUMERIC_KEYS.len(),
        factors in prop::collection::vec(0.2..3.0f64, 3),
        offsets in prop::collection::vec(-0.6..0.6f64, 3),
    ) {
        accepted_or_one_line_error(&perturbed(DAM_BREAK, NUMERIC_KEYS[k], &factors, &offsets));
    }

    #[test]
    fn mutated_periodic_cases_never_panic(k in 0..TAYLOR_GREEN_KEYS.len(), v in value()) {
        accepted_or_one_line_error(&mutated(TAYLOR_GREEN, TAYLOR_GREEN_KEYS[k], &v));
    }
}
