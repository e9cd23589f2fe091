//! Support shared by the physics test suite (`tests/`) and the benchmarks (`benches/`):
//! loading the example cases with overrides, and small fitting helpers.

use sph_core::Case;
use std::path::{Path, PathBuf};

/// Path of a file under `examples/`.
pub fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples")
        .join(name)
}

/// Path of a reference data file under `docs/validation/data/` (sources and grades in its README).
pub fn refdata(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("docs/validation/data")
        .join(name)
}

/// Loads an example case after applying `overrides`, TOML snippets of the form
/// `"table.key = value"` (or `"key = value"` at the top level); a number in the path
/// indexes an array of tables (`"tank.0.hi = [1.0, 2.0]"`).
pub fn example_case(name: &str, overrides: &[&str]) -> Case {
    let text = std::fs::read_to_string(example(name)).expect("example case exists");
    let mut root = toml::Value::Table(text.parse().expect("example case is valid TOML"));
    for o in overrides {
        let (path, value) = o.split_once('=').expect("override is key = value");
        let value: toml::Table = format!("v = {}", value.trim())
            .parse()
            .expect("override value parses");
        let keys: Vec<&str> = path.trim().split('.').collect();
        let mut node = &mut root;
        for k in &keys[..keys.len() - 1] {
            node = match k.parse::<usize>() {
                Ok(index) => &mut node.as_array_mut().expect("indexed path is an array")[index],
                Err(_) => node
                    .as_table_mut()
                    .expect("override path runs through tables")
                    .entry(k.to_string())
                    .or_insert_with(|| toml::Value::Table(Default::default())),
            };
        }
        node.as_table_mut()
            .expect("override target is a table")
            .insert(keys[keys.len() - 1].to_string(), value["v"].clone());
    }
    let toml::Value::Table(table) = root else {
        unreachable!("the root stays a table")
    };
    Case::from_table(table).unwrap_or_else(|e| panic!("{name} with {overrides:?}: {e}"))
}

/// Reads a CSV file whose comment lines start with `#`; returns the header and rows.
pub fn read_csv(path: &Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty());
    let header = lines
        .next()
        .expect("header")
        .split(',')
        .map(|s| s.trim().to_string())
        .collect();
    let rows = lines
        .map(|l| {
            l.split(',')
                .map(|v| v.trim().parse().expect("number"))
                .collect()
        })
        .collect();
    (header, rows)
}

/// Least-squares slope of `y` against `x`.
pub fn slope(x: &[f64], y: &[f64]) -> f64 {
    let n = x.len() as f64;
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let sxy: f64 = x.iter().zip(y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = x.iter().map(|a| (a - mx).powi(2)).sum();
    sxy / sxx
}

/// The times at which `x(t)`, read as linear between samples, crosses `level`: every
/// crossing, or (with `rising_only`) the up-crossings alone.
pub fn crossings(t: &[f64], x: &[f64], level: f64, rising_only: bool) -> Vec<f64> {
    (1..x.len())
        .filter(|&i| (x[i - 1] < level) != (x[i] < level) && (!rising_only || x[i - 1] < level))
        .map(|i| t[i - 1] + (t[i] - t[i - 1]) * (level - x[i - 1]) / (x[i] - x[i - 1]))
        .collect()
}
