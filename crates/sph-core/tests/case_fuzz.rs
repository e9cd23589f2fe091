//! Hostile input for the case parser and validator: arbitrary text, and valid cases
//! with keys mutated to arbitrary values, must give a valid case or a one-line error,
//! never a panic.

use proptest::prelude::*;
use sph_core::Case;

const VALID: &str = r#"
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
[scheme]
diffusion = "delta_sph"
[time]
end = 1.0
"#;

/// Every key path of the valid case, as (table, key).
const KEYS: &[(&str, &str)] = &[
    ("", "dimension"),
    ("particles", "spacing"),
    ("particles", "h_over_dx"),
    ("particles", "kernel"),
    ("fluid", "density"),
    ("fluid", "gravity"),
    ("fluid", "sound_speed"),
    ("fluid", "background_pressure"),
    ("scheme", "diffusion"),
    ("scheme", "delta"),
    ("scheme", "cfl"),
    ("scheme", "integrator"),
    ("scheme", "shifting"),
    ("time", "end"),
    ("time", "max_steps"),
    ("stability", "max_density_variation"),
];

/// Arbitrary TOML values: numbers of every sign and size, NaN and infinities, strings,
/// booleans, arrays and tables.
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
        Just("0.0".to_string()),
        Just("-1.0".to_string()),
        Just("1e308".to_string()),
        "[a-z_]{0,12}".prop_map(|s| format!("{s:?}")),
        any::<bool>().prop_map(|b| b.to_string()),
    ];
    leaf.prop_recursive(2, 8, 4, |inner| {
        prop_oneof![
            prop::collection::vec(inner.clone(), 0..4).prop_map(|v| format!("[{}]", v.join(", "))),
            inner.prop_map(|v| format!("{{ x = {v} }}")),
        ]
    })
}

fn single_line_error(text: &str) {
    match Case::from_toml_str(text) {
        Ok(case) => assert!(case.validate().is_ok()),
        Err(e) => {
            let message = e.to_string();
            assert!(!message.is_empty());
            assert!(
                !message.lines().next().unwrap().is_empty(),
                "empty first line: {message:?}"
            );
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn arbitrary_text_never_panics(text in "\\PC{0,400}") {
        single_line_error(&text);
    }

    #[test]
    fn mutated_values_never_panic(k in 0..KEYS.len(), v in value()) {
        let (table, key) = KEYS[k];
        let mut doc: toml::Table = VALID.parse().unwrap();
        let parsed: toml::Table = format!("v = {v}").parse().unwrap();
        let target = if table.is_empty() {
            &mut doc
        } else {
            doc.entry(table).or_insert_with(|| toml::Value::Table(Default::default()))
                .as_table_mut().unwrap()
        };
        target.insert(key.to_string(), parsed["v"].clone());
        let text = toml::to_string(&doc).unwrap();
        single_line_error(&text);
    }
}
