//! The case file: a TOML schema read with serde (unknown keys rejected, `schema`) and
//! checked value by value (`validate`), so that every mistake is reported as one line
//! naming the key, the value and what was expected (`toml_errors` for what serde and
//! the TOML parser report). All quantities are SI.

mod checks;
mod diagnostics_options;
pub mod expression;
pub mod json_schema;
pub(crate) mod motion;
mod open_boundaries;
mod schema;
mod scheme_options;
mod shapes;
mod size;
mod toml_errors;
mod validate;

pub use motion::*;
pub use open_boundaries::*;
pub use schema::*;
pub use shapes::*;
pub use size::{bytes_text, memory_limit, SizeEstimate, MAX_PARTICLES, MEMORY_VARIABLE};

use crate::error::{Result, SphError};
use std::path::Path;

/// The file of a prescribed motion's table, if it is one (not rows).
fn table_file(m: &mut Option<PrescribedConfig>) -> Option<&mut String> {
    match m.as_mut()?.table.as_mut()? {
        MotionTable::File(path) => Some(path),
        MotionTable::Rows(_) => None,
    }
}

impl Case {
    /// Reads and validates a case file.
    pub fn from_file(path: &Path) -> Result<Self> {
        let text = std::fs::read_to_string(path).map_err(|e| SphError::CaseFile {
            path: path.display().to_string(),
            message: e.to_string(),
        })?;
        let mut case = Self::from_toml_str(&text).map_err(|e| match e {
            SphError::CaseFile { message, .. } => SphError::CaseFile {
                path: path.display().to_string(),
                message,
            },
            other => other,
        })?;
        case.resolve_shape_files(path.parent().unwrap_or(Path::new("")));
        Ok(case)
    }

    /// Makes the shapes' and motion tables' relative file paths relative to `folder`
    /// (the case file's),
    /// so that the case reads the same files from any working folder, and again from
    /// its restart file.
    fn resolve_shape_files(&mut self, folder: &Path) {
        let folder = std::path::absolute(folder).unwrap_or_else(|_| folder.to_path_buf());
        let shapes =
            (self.shape.iter_mut()).flat_map(|s| [s.file.as_mut(), table_file(&mut s.prescribed)]);
        let tables = (self.tank.iter_mut().map(|t| table_file(&mut t.prescribed)))
            .chain(self.wall.iter_mut().map(|w| table_file(&mut w.prescribed)));
        for file in shapes.chain(tables).flatten() {
            if Path::new(file.as_str()).is_relative() {
                *file = folder.join(&*file).display().to_string();
            }
        }
    }

    /// Parses and validates a case from TOML text.
    pub fn from_toml_str(text: &str) -> Result<Self> {
        let table: toml::Table = text
            .parse()
            .map_err(|e: toml::de::Error| toml_errors::syntax_error(text, &e))?;
        Self::from_table(table)
    }

    /// Deserialises a parsed TOML table (the Python front goes through here too).
    pub fn from_table(table: toml::Table) -> Result<Self> {
        check_section_types(&table)?;
        let value = toml::Value::Table(table);
        let case: Case = serde_path_to_error::deserialize(value.clone()).map_err(|e| {
            toml_errors::schema_error(&value, e.path().to_string(), e.inner().to_string())
        })?;
        case.validate()?;
        Ok(case)
    }
}

/// The sections that are one table, and those that are arrays of tables.
const TABLES: [&str; 10] = [
    "output",
    "particles",
    "fluid",
    "domain",
    "initial",
    "forcing",
    "scheme",
    "time",
    "stability",
    "diagnostics",
];
const TABLE_ARRAYS: [&str; 6] = [
    "fluid_block",
    "tank",
    "wall",
    "shape",
    "open_boundary",
    "absorber",
];

/// Refuses a section of the wrong type by its name (serde would read `particles =
/// [1, 2]` as the struct's fields in order, and blame whatever key failed next).
fn check_section_types(table: &toml::Table) -> Result<()> {
    for (key, value) in table {
        let wrong = if TABLES.contains(&key.as_str()) {
            (!value.is_table()).then_some("a table ([section] with its keys)")
        } else if TABLE_ARRAYS.contains(&key.as_str()) {
            let tables = value
                .as_array()
                .is_some_and(|a| a.iter().all(|v| v.is_table()));
            (!tables).then_some("an array of tables ([[section]] blocks)")
        } else {
            None
        };
        if let Some(expected) = wrong {
            return Err(SphError::invalid(key.as_str(), value.to_string(), expected));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    pub(super) const MINIMAL: &str = r#"
        dimension = 2
        [particles]
        spacing = 0.01
        [fluid]
        density = 1000.0
        gravity = [0.0, -9.81]
        [[fluid_block]]
        lo = [0.0, 0.0]
        hi = [0.2, 0.1]
        [[tank]]
        lo = [0.0, 0.0]
        hi = [0.5, 0.3]
        [time]
        end = 0.1
    "#;

    pub(super) fn error_of(text: &str) -> String {
        Case::from_toml_str(text).unwrap_err().to_string()
    }

    #[test]
    fn minimal_case_parses_with_defaults() {
        let c = Case::from_toml_str(MINIMAL).unwrap();
        assert_eq!(c.scheme.diffusion, DiffusionChoice::DeltaSph);
        assert_eq!(c.scheme.cfl(), 1.5);
        assert!((c.h() - 0.02).abs() < 1e-12);
        // R = 2h = 4 Δx: four layers cover it
        assert_eq!(c.tank[0].layer_count(&c), 4);
    }

    #[test]
    fn unknown_key_is_named() {
        let e = error_of(&MINIMAL.replace("spacing = 0.01", "spacing = 0.01\nspacingg = 2"));
        assert!(e.starts_with("particles.spacingg"), "{e}");
        assert!(e.contains("unknown field"), "{e}");
        assert_eq!(e.lines().count(), 1, "{e}");
    }

    #[test]
    fn wrong_type_names_key_and_value() {
        let e = error_of(&MINIMAL.replace("end = 0.1", "end = \"soon\""));
        assert!(e.starts_with("time.end = \"soon\": invalid type"), "{e}");
    }

    #[test]
    fn unknown_kernel_lists_choices() {
        let e = error_of(&MINIMAL.replace("spacing = 0.01", "spacing = 0.01\nkernel = \"sinc\""));
        assert!(e.starts_with("particles.kernel = \"sinc\""), "{e}");
        assert!(e.contains("wendland_c2"), "{e}");
    }

    #[test]
    fn syntax_error_has_a_position() {
        let e = error_of("dimension = = 2");
        assert!(e.contains("line 1"), "{e}");
    }
}
