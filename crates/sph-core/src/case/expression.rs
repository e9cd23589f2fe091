//! Expressions in the case file (initial fields, body forces): texts parsed once by
//! `exmex` (floating point throughout: `1/2` is 0.5; `PI` and `π` are known) into
//! functions of the position (`x`, `y`, and `z` in 3D), optionally the time `t`, and
//! named values (the table's `constants` and what the caller adds, such as `rho0`).
//!
//! Refused in one line naming the key: a text that does not parse, an unknown
//! variable (the known ones are listed) and a constant that shadows a coordinate, the
//! time or a built-in name.

use crate::error::{Result, SphError};
use exmex::prelude::*;
use std::collections::BTreeMap;

const COORDINATES: [&str; 3] = ["x", "y", "z"];

/// The name of the time variable of time-dependent expressions.
const TIME: &str = "t";

/// The variables an expression may use besides its constants.
#[derive(Debug, Clone, Copy)]
pub struct Variables {
    /// 2 or 3: `x`, `y` (and `z`).
    pub dimension: usize,
    /// Whether `t` is known.
    pub time: bool,
}

impl Variables {
    fn names(&self) -> Vec<&'static str> {
        let mut names = COORDINATES[..self.dimension].to_vec();
        if self.time {
            names.push(TIME);
        }
        names
    }
}

/// The named values of a table's expressions: `builtin` (such as `rho0`) and the
/// table's `constants`, whose key is `<table>.constants`. A constant may not take
/// the name of a variable or of a built-in value.
pub fn named_values(
    table: &str,
    builtin: &[(&str, f64)],
    constants: Option<&BTreeMap<String, f64>>,
    variables: Variables,
) -> Result<Vec<(String, f64)>> {
    let mut names: Vec<(String, f64)> = builtin.iter().map(|(n, v)| (n.to_string(), *v)).collect();
    let reserved: Vec<&str> = variables
        .names()
        .into_iter()
        .chain(builtin.iter().map(|(n, _)| *n))
        .collect();
    for (name, value) in constants.into_iter().flatten() {
        if reserved.contains(&name.as_str()) {
            return Err(SphError::invalid(
                format!("{table}.constants.{name}"),
                value,
                format!("a constant whose name is not {}", reserved.join(", ")),
            ));
        }
        names.push((name.clone(), *value));
    }
    Ok(names)
}

/// One parsed expression, with the value each of its variables takes.
pub struct Compiled {
    key: String,
    text: String,
    expr: FlatEx<f64>,
    /// whether `t` is a variable
    timed: bool,
    /// per variable, in exmex's (alphabetical) order
    slots: Vec<Slot>,
}

#[derive(Clone, Copy)]
enum Slot {
    Coordinate(usize),
    Time,
    Value(f64),
}

impl Compiled {
    /// Parses the expression `text` of the case key `key`.
    pub fn new(
        key: String,
        text: &str,
        names: &[(String, f64)],
        variables: Variables,
    ) -> Result<Self> {
        let expr = exmex::parse::<f64>(text).map_err(|e| {
            SphError::invalid(
                &key,
                format!("{text:?}"),
                format!("an expression ({})", one_line(&e.to_string())),
            )
        })?;
        let slots = expr
            .var_names()
            .iter()
            .map(|v| slot(v, names, variables))
            .collect::<std::result::Result<_, _>>()
            .map_err(|unknown| {
                let mut known = variables.names();
                known.extend(names.iter().map(|(n, _)| n.as_str()));
                SphError::invalid(
                    &key,
                    format!("{text:?}"),
                    format!(
                        "an expression of known variables (unknown: {unknown}; known: {}; \
                         add constants under {}.constants)",
                        known.join(", "),
                        key.split(['.', '[']).next().unwrap_or_default(),
                    ),
                )
            })?;
        Ok(Compiled {
            key,
            text: text.to_string(),
            expr,
            timed: variables.time,
            slots,
        })
    }

    /// The exact derivative in time `∂/∂t` (exmex's symbolic differentiation); zero
    /// for an expression without `t`.
    pub fn time_derivative(&self) -> Result<Self> {
        let at = self.slots.iter().position(|s| matches!(s, Slot::Time));
        let expr = match at {
            Some(at) => self.expr.clone().partial(at),
            None => exmex::parse::<f64>("0"),
        }
        .map_err(|e| {
            SphError::invalid(
                &self.key,
                format!("{:?}", self.text),
                format!("an expression exmex can differentiate in t ({e})"),
            )
        })?;
        let slots = match at {
            Some(_) => self.slots.clone(),
            None => Vec::new(),
        };
        Ok(Compiled {
            key: self.key.clone(),
            text: format!("d/dt {}", self.text),
            expr,
            timed: self.timed,
            slots,
        })
    }

    /// The value at position `x` and time `t` (NaN where exmex fails); `values` is
    /// scratch space, reused between calls.
    pub fn value(&self, x: &[f64], t: f64, values: &mut Vec<f64>) -> f64 {
        values.clear();
        values.extend(self.slots.iter().map(|s| match *s {
            Slot::Coordinate(d) => x[d],
            Slot::Time => t,
            Slot::Value(v) => v,
        }));
        self.expr.eval(values).unwrap_or(f64::NAN)
    }

    /// The value at `x` and `t`, finite or an error naming the point (`where_` says
    /// which points must give finite values, such as "every fluid particle").
    pub fn finite_at(&self, x: &[f64], t: f64, where_: &str) -> Result<f64> {
        let v = self.value(x, t, &mut Vec::new());
        if v.is_finite() {
            return Ok(v);
        }
        let at = if self.timed {
            format!("x = {x:?}, t = {t}")
        } else {
            format!("x = {x:?}")
        };
        Err(SphError::invalid(
            &self.key,
            format!("{:?}", self.text),
            format!("an expression finite at {where_} (it gives {v} at {at})"),
        ))
    }
}

/// What variable `v` stands for, or its name when it is unknown.
fn slot(
    v: &str,
    names: &[(String, f64)],
    variables: Variables,
) -> std::result::Result<Slot, String> {
    if let Some(d) = COORDINATES[..variables.dimension]
        .iter()
        .position(|c| *c == v)
    {
        return Ok(Slot::Coordinate(d));
    }
    if variables.time && v == TIME {
        return Ok(Slot::Time);
    }
    match names.iter().find(|(n, _)| n == v) {
        Some((_, value)) => Ok(Slot::Value(*value)),
        None => Err(v.to_string()),
    }
}

fn one_line(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}
