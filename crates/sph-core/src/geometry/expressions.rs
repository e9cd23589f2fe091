//! Initial fields from expressions in the case file (`[initial] type = "expressions"`):
//! the velocity components, and the pressure or the density, as functions of the
//! position (`x`, `y`, and `z` in 3D), the named `constants`, `rho0` and `g` (the
//! magnitude of gravity), parsed once ([`crate::case::expression`]) and evaluated at
//! every fluid particle. Besides the parse errors, a value that is not finite at some
//! particle (a division by zero there) is refused in one line with the particle's
//! position.

use crate::case::expression::{named_values, Compiled, Variables};
use crate::case::{Case, InitialField};
use crate::error::Result;
use crate::particles::Vector;

/// The value of `expr` at fluid particle `x`, or the error naming the particle.
fn at<const D: usize>(expr: &Compiled, x: &Vector<D>) -> Result<f64> {
    expr.finite_at(x.as_slice(), 0.0, "every fluid particle")
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
        let variables = Variables {
            dimension: case.dimension,
            time: false,
        };
        let builtin = [("rho0", case.fluid.density), ("g", g)];
        let names = named_values("initial", &builtin, constants.as_ref(), variables)?;
        let compile = |key: String, text: &String| Compiled::new(key, text, &names, variables);
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
            u[d] = at(c, x)?;
        }
        Ok(Some(u))
    }

    /// The pressure and the density at `x` that the field sets (at most one of them).
    pub fn state<const D: usize>(&self, x: &Vector<D>) -> Result<(Option<f64>, Option<f64>)> {
        let p = self.pressure.as_ref().map(|e| at(e, x)).transpose()?;
        let rho = self.density.as_ref().map(|e| at(e, x)).transpose()?;
        Ok((p, rho))
    }
}
