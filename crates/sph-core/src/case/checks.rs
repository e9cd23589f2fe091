//! Value checks shared by the case's tables: each refuses a value in one line naming
//! the key, the value and what was expected.

use crate::error::{Result, SphError};

/// A name that can head time-series columns: a letter, then letters, digits or `_`.
pub(super) fn column_name(name: &str) -> bool {
    name.chars().next().is_some_and(|c| c.is_ascii_alphabetic())
        && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// A column name (see [`column_name`]) that none of the `earlier` ones of its kind
/// (`what`: "sensor", "gauge") has.
pub(super) fn own_column_name<'a>(
    key: &str,
    name: &str,
    mut earlier: impl Iterator<Item = &'a str>,
    what: &str,
) -> Result<()> {
    if column_name(name) && !earlier.any(|o| o == name) {
        return Ok(());
    }
    Err(SphError::invalid(
        key,
        format!("{name:?}"),
        format!("a name no other {what} has: a letter, then letters, digits or _"),
    ))
}

/// A name that is one plain path component: not empty, no separator, not `.` or
/// `..`, no control character, so that `<name>_out` stays inside the working folder.
pub(super) fn plain_file_name(key: &str, name: &str) -> Result<()> {
    let bad = name.is_empty()
        || name == "."
        || name == ".."
        || name.len() > 200
        || name
            .chars()
            .any(|c| c == '/' || c == '\\' || c.is_control());
    if bad {
        return Err(SphError::invalid(
            key,
            format!("{name:?}"),
            "a plain file name (no path separators, not empty, not \".\" or \"..\", \
             at most 200 bytes): the default output folder is <name>_out",
        ));
    }
    Ok(())
}

pub(super) fn positive(key: &str, v: f64) -> Result<()> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(SphError::invalid(key, v, "a positive number"))
    }
}

pub(super) fn non_negative(key: &str, v: f64) -> Result<()> {
    if v.is_finite() && v >= 0.0 {
        Ok(())
    } else {
        Err(SphError::invalid(key, v, "a number >= 0"))
    }
}

pub(super) fn finite(key: &str, v: f64) -> Result<()> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(SphError::invalid(key, v, "a finite number"))
    }
}

pub(super) fn components(key: &str, v: &[f64], d: usize) -> Result<()> {
    if v.len() != d {
        return Err(SphError::invalid(
            key,
            format!("{v:?}"),
            format!("{d} components (dimension = {d})"),
        ));
    }
    if v.iter().any(|c| !c.is_finite()) {
        return Err(SphError::invalid(
            key,
            format!("{v:?}"),
            "finite components",
        ));
    }
    Ok(())
}

pub(super) fn check_box(key: &str, lo: &[f64], hi: &[f64], d: usize) -> Result<()> {
    components(&format!("{key}.lo"), lo, d)?;
    components(&format!("{key}.hi"), hi, d)?;
    if lo.iter().zip(hi).any(|(a, b)| b <= a) {
        return Err(SphError::invalid(
            format!("{key}.hi"),
            format!("{hi:?}"),
            format!("every component above lo = {lo:?}"),
        ));
    }
    Ok(())
}

pub(super) fn only_2d(d: usize, field: &str) -> Result<()> {
    if d == 2 {
        Ok(())
    } else {
        Err(SphError::invalid(
            "initial.type",
            format!("\"{field}\""),
            "dimension = 2",
        ))
    }
}
