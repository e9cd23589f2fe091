//! Terms of the fluid's momentum equation besides the pair forces and gravity, added
//! after each force evaluation: the case's body force field ([`field`]) and the
//! damping zones of wave flumes ([`absorber`]). A case with neither has no
//! [`Forcing`] and pays nothing.

pub mod absorber;
pub mod field;

use crate::case::Case;
use crate::error::Result;
use crate::particles::{Kind, Particles, Vector};
use absorber::Absorber;
use field::BodyForce;
use rayon::prelude::*;

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

    /// Their power on the fluid at time `t`, `P_F = Σ_i m_i u_i·f_i` (the energy
    /// budget's term; computed only when a budget is kept).
    pub fn power(&self, p: &Particles<D>, t: f64) -> f64 {
        let mut f = vec![Vector::<D>::zeros(); p.len()];
        self.add(p, t, &mut f);
        (0..p.len())
            .into_par_iter()
            .filter(|&i| p.kind[i] == Kind::Fluid)
            .map(|i| p.mass[i] * p.u[i].dot(&f[i]))
            .sum()
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
