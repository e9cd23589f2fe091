//! What the TOML parser and serde report, turned into one line naming the key.

use crate::error::SphError;

/// A TOML syntax error with its line and column.
pub(super) fn syntax_error(text: &str, e: &toml::de::Error) -> SphError {
    let first = e.message().lines().next().unwrap_or("").to_string();
    let at = e
        .span()
        .map(|s| line_col(text, s.start))
        .unwrap_or_default();
    SphError::CaseFile {
        path: "<case>".into(),
        message: format!("TOML syntax{at}: {first}"),
    }
}

/// Looks a dotted path like `scheme.delta` or `fluid_block[0].lo` up in the parsed table.
/// One line naming the key: a missing key is named in full (`particles.spacing =
/// (missing): missing field, a required key`), other errors show the value found.
pub(super) fn schema_error(root: &toml::Value, path: String, inner: String) -> SphError {
    let message = inner.lines().next().unwrap_or("").to_string();
    let missing = message
        .strip_prefix("missing field `")
        .and_then(|rest| rest.split('`').next());
    if let Some(field) = missing {
        let key = if path == "." {
            field.to_string()
        } else {
            format!("{path}.{field}")
        };
        return SphError::Schema {
            key,
            value: "(missing)".into(),
            message: "missing field, a required key".into(),
        };
    }
    let value = lookup(root, &path)
        .map(|v| v.to_string().replace('\n', " "))
        .unwrap_or_else(|| "(missing)".into());
    SphError::Schema {
        key: path,
        value,
        message,
    }
}

fn lookup<'a>(v: &'a toml::Value, path: &str) -> Option<&'a toml::Value> {
    let mut cur = v;
    for part in path.split('.') {
        let (name, index) = match part.find('[') {
            Some(b) => (
                &part[..b],
                part[b + 1..part.len() - 1].parse::<usize>().ok(),
            ),
            None => (part, None),
        };
        if !name.is_empty() {
            cur = cur.get(name)?;
        }
        if let Some(k) = index {
            cur = cur.get(k)?;
        }
    }
    Some(cur)
}

fn line_col(text: &str, offset: usize) -> String {
    let before = text.get(..offset.min(text.len())).unwrap_or(text);
    let line = before.matches('\n').count() + 1;
    let col = before.len() - before.rfind('\n').map(|p| p + 1).unwrap_or(0) + 1;
    format!(" at line {line}, column {col}")
}
