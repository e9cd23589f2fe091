//! Initial fields from expressions in the case file (`[initial] type = "expressions"`):
//! the velocity components, and the pressure or the density, as functions of the
//! position (`x`, `y`, and `z` in 3D), the named `constants`, `rho0` and `g` (the
//! magnitude of gravity), parsed once by `exmex` (floating point throughout: `1/2` is
//! 0.5) and evaluated at every fluid particle.
//!
//! Refused in one line naming the key: a text that does not parse, an unknown
//! variable (the known ones are listed), a constant that shadows a coordinate, and a
//! value that is not finite at some particle (a division by zero there), with the
//! particle's position.

use crate::case::{Case, InitialField};
use crate::error::{Result, SphError};
use crate::particles::Vector;
use exmex::prelude::*;

const COORDINATES: [&str; 3] = ["x", "y", "z"];

/// One parsed expression, with the value each of its variables takes from.
struct Compiled {
    key: String,
    text: String,
    expr: FlatEx<f64>,
    /// per variable, in exmex's (alphabetical) order
    slots: Vec<Slot>,
}

enum Slot {
    Coordinate(usize),
    Value(f64),
}

impl Compiled {
    fn new(key: String, text: &str, names: &[(String, f64)], dim: usize) -> Result<Self> {
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
            .map(|v| {
                if let Some(d) = COORDINATES[..dim].iter().position(|c| c == v) {
                    return Ok(Slot::Coordinate(d));
                }
                match names.iter().find(|(n, _)| n == v) {
                    Some((_, value)) => Ok(Slot::Value(*value)),
                    None => {
                        let mut known: Vec<&str> = COORDINATES[..dim].to_vec();
                        known.extend(names.iter().map(|(n, _)| n.as_str()));
                        Err(SphError::invalid(
                            &key,
                            format!("{text:?}"),
                            format!(
                                "an expression of known variables (unknown: {v}; known: {}; \
                                 add constants under initial.constants)",
                                known.join(", ")
                            ),
                        ))
                    }
                }
            })
            .collect::<Result<_>>()?;
        Ok(Compiled {
            key,
            text: text.to_string(),
            expr,
            slots,
        })
    }

    /// The value at `x`, finite or an error naming the point.
    fn at<const D: usize>(&self, x: &Vector<D>) -> Result<f64> {
        let values: Vec<f64> = self
            .slots
            .iter()
            .map(|s| match *s {
                Slot::Coordinate(d) => x[d],
                Slot::Value(v) => v,
            })
            .collect();
        let v = self.expr.eval(&values).unwrap_or(f64::NAN);
        if v.is_finite() {
            return Ok(v);
        }
        Err(SphError::invalid(
            &self.key,
            format!("{:?}", self.text),
            format!(
                "an expression finite at every fluid particle (it gives {v} at x = {:?})",
                x.as_slice()
            ),
        ))
    }
}

fn one_line(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// The parsed expressions of a case's `[initial]` table.
pub(super) struct ExpressionField {
    velocity: Option<Vec<Compiled>>,
    pressure: Option<Compiled>,
    density: Option<Compiled>,
}

impl ExpressionField {
    /// The field of a case whose `[initial] type = "expressions"` (validated: u has
    /// `dimension` components, at most one of p and rho); none for other cases.
    pub fn of(case: &Case, g: f64) -> Result<Option<Self>> {
        let Some(InitialField::Expressions {
            constants,
            u,
            p,
            rho,
        }) = &case.initial
        else {
            return Ok(None);
        };
        let dim = case.dimension;
        let mut names = vec![("rho0".to_string(), case.fluid.density), ("g".into(), g)];
        for (name, value) in constants.iter().flatten() {
            if COORDINATES.contains(&name.as_str()) || name == "rho0" || name == "g" {
                return Err(SphError::invalid(
                    format!("initial.constants.{name}"),
                    value,
                    "a constant whose name is not x, y, z, rho0 or g",
                ));
            }
            names.push((name.clone(), *value));
        }
        let compile = |key: String, text: &String| Compiled::new(key, text, &names, dim);
        Ok(Some(ExpressionField {
            velocity: u
                .as_ref()
                .map(|u| {
                    (u.iter().enumerate())
                        .map(|(d, text)| compile(format!("initial.u[{d}]"), text))
                        .collect::<Result<Vec<_>>>()
                })
                .transpose()?,
            pressure: p
                .as_ref()
                .map(|t| compile("initial.p".into(), t))
                .transpose()?,
            density: rho
                .as_ref()
                .map(|t| compile("initial.rho".into(), t))
                .transpose()?,
        }))
    }

    /// The velocity at `x`, when the field sets one.
    pub fn velocity<const D: usize>(&self, x: &Vector<D>) -> Result<Option<Vector<D>>> {
        let Some(components) = &self.velocity else {
            return Ok(None);
        };
        let mut u = Vector::<D>::zeros();
        for (d, c) in components.iter().enumerate() {
            u[d] = c.at(x)?;
        }
        Ok(Some(u))
    }

    /// The pressure and the density at `x` that the field sets (at most one of them).
    pub fn state<const D: usize>(&self, x: &Vector<D>) -> Result<(Option<f64>, Option<f64>)> {
        let p = self.pressure.as_ref().map(|e| e.at(x)).transpose()?;
        let rho = self.density.as_ref().map(|e| e.at(x)).transpose()?;
        Ok((p, rho))
    }
}
