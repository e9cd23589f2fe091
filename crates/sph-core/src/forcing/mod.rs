//! Terms of the fluid's momentum equation besides the pair forces and gravity, added
//! after each force evaluation: the case's body force field ([`field`]) and the
//! damping zones of wave flumes ([`absorber`]). A case with neither has no
//! [`Forcing`] and pays nothing.

pub mod absorber;
pub mod field;

use crate::case::Case;
use crate::error::Result;
use crate::particles::{Particles, Vector};
use absorber::Absorber;
use field::BodyForce;

/// The body force and the absorbers of a run.
pub struct Forcing<const D: usize> {
    field: Option<BodyForce<D>>,
    absorbers: Vec<Absorber>,
}

impl<const D: usize> Forcing<D> {
    /// The terms of `case` (none when it has neither a `[forcing]` nor an absorber).
    pub fn of(case: &Case, particles: &Particles<D>) -> Result<Option<Self>> {
        let field = BodyForce::of(case, particles)?;
        let absorbers: Vec<Absorber> = (case.absorber.iter())
            .map(|a| Absorber::new(case, a))
            .collect();
        Ok((field.is_some() || !absorbers.is_empty()).then_some(Self { field, absorbers }))
    }

    /// Adds the terms at time `t` to the fluid's rates `du`.
    pub fn add(&self, p: &Particles<D>, t: f64, du: &mut [Vector<D>]) {
        if let Some(field) = &self.field {
            field.add(p, t, du);
        }
        for a in &self.absorbers {
            a.add(p, du);
        }
    }
}
