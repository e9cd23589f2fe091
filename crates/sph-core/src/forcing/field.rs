//! A body force field besides gravity, from the case's `[forcing]` expressions:
//! `du_i/dt += f(x_i, t)` on every fluid particle, at the time of each force
//! evaluation (the stage's time in RK4). It drives forced flows such as the forced cell
//! array of Antuono et al. (2021, Phys. Fluids 33:015102),
//! `f = A r(t) (sin kx cos ky, -cos kx sin ky)`, and costs nothing in a case without one.

use crate::case::expression::{named_values, Compiled, Variables};
use crate::case::Case;
use crate::error::Result;
use crate::particles::{Kind, Particles, Vector};
use rayon::prelude::*;

/// The parsed acceleration field, one expression per component.
pub struct BodyForce<const D: usize> {
    components: Vec<Compiled>,
}

impl<const D: usize> BodyForce<D> {
    /// The field of a case with `[forcing]` (none otherwise), checked to be finite at
    /// every fluid particle of `particles` at t = 0.
    pub fn of(case: &Case, particles: &Particles<D>) -> Result<Option<Self>> {
        let Some(forcing) = &case.forcing else {
            return Ok(None);
        };
        let variables = Variables {
            dimension: D,
            time: true,
        };
        let builtin = [("rho0", case.fluid.density)];
        let names = named_values("forcing", &builtin, forcing.constants.as_ref(), variables)?;
        let components = (forcing.acceleration.iter().enumerate())
            .map(|(d, text)| {
                Compiled::new(
                    format!("forcing.acceleration[{d}]"),
                    text,
                    &names,
                    variables,
                )
            })
            .collect::<Result<Vec<_>>>()?;
        for (x, _) in (particles.x.iter().zip(&particles.kind)).filter(|(_, k)| **k == Kind::Fluid)
        {
            for c in &components {
                c.finite_at(x.as_slice(), 0.0, "every fluid particle")?;
            }
        }
        Ok(Some(Self { components }))
    }

    /// The acceleration at `x` and time `t`; `scratch` is reused between calls.
    pub fn at(&self, x: &Vector<D>, t: f64, scratch: &mut Vec<f64>) -> Vector<D> {
        Vector::<D>::from_fn(|d, _| self.components[d].value(x.as_slice(), t, scratch))
    }

    /// Adds the acceleration at time `t` to the rates `du` of the fluid particles.
    pub fn add(&self, p: &Particles<D>, t: f64, du: &mut [Vector<D>]) {
        du.par_iter_mut()
            .enumerate()
            .filter(|(i, _)| p.kind[*i] == Kind::Fluid)
            .for_each_init(Vec::new, |scratch, (i, a)| {
                *a += self.at(&p.x[i], t, scratch)
            });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn forced(acceleration: &str) -> Result<Option<BodyForce<2>>> {
        let case = Case::from_toml_str(&format!(
            "dimension = 2\n[particles]\nspacing = 0.05\n[fluid]\ndensity = 1.0\n\
             sound_speed = 10.0\n[[fluid_block]]\nlo = [0.0, 0.0]\nhi = [1.0, 1.0]\n\
             [domain]\nlo = [0.0, 0.0]\nhi = [1.0, 1.0]\nperiodic = [true, true]\n\
             [forcing]\nconstants = {{ A = 2.0 }}\nacceleration = {acceleration}\n\
             [time]\nend = 1.0\n"
        ))?;
        let setup = crate::geometry::build::<2>(&case)?;
        BodyForce::of(&case, &setup.particles)
    }

    #[test]
    fn the_field_is_evaluated_at_position_and_time() {
        let f = forced("[\"A*t*sin(PI*x)\", \"-rho0*y\"]").unwrap().unwrap();
        let a = f.at(&Vector::<2>::new(0.5, 0.25), 3.0, &mut Vec::new());
        assert!(
            (a[0] - 6.0).abs() < 1e-14 && (a[1] + 0.25).abs() < 1e-14,
            "{a}"
        );
    }

    #[test]
    fn bad_fields_are_refused_in_one_line() {
        for (acceleration, expected) in [
            (
                "[\"0\"]",
                "forcing.acceleration = [\"0\"]: expected 2 expressions",
            ),
            (
                "[\"B*x\", \"0\"]",
                "forcing.acceleration[0] = \"B*x\": expected an expression of known \
                 variables (unknown: B; known: x, y, t, rho0, A; add constants under \
                 forcing.constants)",
            ),
            (
                "[\"0\", \"1/(x - 0.025)\"]",
                "forcing.acceleration[1] = \"1/(x - 0.025)\": expected an expression finite \
                 at every fluid particle (it gives inf at x = [0.025, 0.025], t = 0)",
            ),
        ] {
            let e = forced(acceleration).err().unwrap().to_string();
            assert!(e.starts_with(expected), "{e}\n expected: {expected}");
        }
    }
}
