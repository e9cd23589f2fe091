//! The JSON Schema (draft 2020-12) of the case file, derived from the case types by
//! schemars, so it cannot drift from what the parser accepts: TOML editors (Taplo,
//! Even Better TOML) use it to complete keys and flag unknown ones as the user types.
//! Value ranges and cross-key rules stay with `super::validate`.

use super::Case;
use serde_json::Value;

/// The schema as pretty-printed JSON, ending in a newline.
pub fn case_schema() -> String {
    let mut schema = schemars::schema_for!(Case).to_value();
    schema["title"] = "deltasph case file (TOML)".into();
    without_nulls(&mut schema);
    unescape_brackets(&mut schema);
    let text = serde_json::to_string_pretty(&schema).expect("a schema serialises");
    text + "\n"
}

/// Doc comments write units as `\[m\]` so that rustdoc does not read them as links;
/// the descriptions the user reads show `[m]`.
fn unescape_brackets(value: &mut Value) {
    match value {
        Value::String(text) if text.contains('\\') => {
            *text = text.replace("\\[", "[").replace("\\]", "]");
        }
        Value::Object(map) => map.values_mut().for_each(unescape_brackets),
        Value::Array(items) => items.iter_mut().for_each(unescape_brackets),
        _ => {}
    }
}

/// TOML has no null: an optional key is one that may be left out. Drops the `null`
/// alternatives schemars gives `Option` fields, and `null` defaults.
fn without_nulls(value: &mut Value) {
    let is_null_type = |v: &Value| v.get("type").is_some_and(|t| t == "null");
    match value {
        Value::Object(map) => {
            if let Some(Value::Array(choices)) = map.get("anyOf") {
                let kept: Vec<Value> = choices
                    .iter()
                    .filter(|c| !is_null_type(c))
                    .cloned()
                    .collect();
                if kept.len() == 1 {
                    map.remove("anyOf");
                    if let Value::Object(only) = &kept[0] {
                        for (k, v) in only {
                            map.entry(k.clone()).or_insert_with(|| v.clone());
                        }
                    }
                }
            }
            if let Some(Value::Array(types)) = map.get_mut("type") {
                types.retain(|t| t != "null");
                if types.len() == 1 {
                    let only = types[0].clone();
                    map.insert("type".into(), only);
                }
            }
            if let Some(Value::Object(default)) = map.get_mut("default") {
                default.retain(|_, v| !v.is_null());
            }
            map.retain(|k, v| !(k == "default" && v.is_null()));
            map.values_mut().for_each(without_nulls);
        }
        Value::Array(items) => items.iter_mut().for_each(without_nulls),
        _ => {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_schema_names_every_table_and_refuses_unknown_keys() {
        let schema: serde_json::Value = serde_json::from_str(&case_schema()).unwrap();
        let properties = schema["properties"].as_object().unwrap();
        for table in [
            "particles",
            "fluid",
            "fluid_block",
            "tank",
            "wall",
            "shape",
            "scheme",
        ] {
            assert!(properties.contains_key(table), "{table}");
        }
        assert_eq!(schema["additionalProperties"], false);
        let required: Vec<&str> = schema["required"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_str().unwrap())
            .collect();
        assert!(required.contains(&"dimension") && required.contains(&"particles"));
        assert!(!required.contains(&"name"), "name has a default");
        assert!(!case_schema().contains("null"), "TOML has no null");
    }
}
