//! Checks of the scheme's options, of the body force and of the absorbers: coefficients in range, the
//! viscosity a choice needs, and the flows δ-LES-SPH is offered for.

use crate::case::checks::{finite, non_negative, positive};
use crate::case::schema::*;
use crate::case::shapes::Role;
use crate::error::{Result, SphError};

impl Case {
    /// Each absorber's zone has a length and its rate is positive (gravity gives the
    /// default).
    pub(super) fn validate_absorbers(&self) -> Result<()> {
        for (k, a) in self.absorber.iter().enumerate() {
            finite(&format!("absorber[{k}].from"), a.from)?;
            finite(&format!("absorber[{k}].to"), a.to)?;
            if a.to == a.from {
                return Err(SphError::invalid(
                    format!("absorber[{k}].to"),
                    a.to,
                    "a zone of some length: `to` different from `from`",
                ));
            }
            positive(&format!("absorber[{k}].rate"), self.absorber_rate(a))?;
        }
        Ok(())
    }

    /// One expression per component and finite constants; the expressions themselves
    /// are parsed when the run is built.
    pub(super) fn validate_forcing(&self) -> Result<()> {
        let Some(forcing) = &self.forcing else {
            return Ok(());
        };
        let d = self.dimension;
        if forcing.acceleration.len() != d {
            return Err(SphError::invalid(
                "forcing.acceleration",
                format!("{:?}", forcing.acceleration),
                format!("{d} expressions, one per component"),
            ));
        }
        for (name, value) in forcing.constants.iter().flatten() {
            finite(&format!("forcing.constants.{name}"), *value)?;
        }
        Ok(())
    }

    pub(super) fn validate_scheme(&self) -> Result<()> {
        let s = &self.scheme;
        if !(0.0..=1.0).contains(&s.delta) {
            return Err(SphError::invalid(
                "scheme.delta",
                s.delta,
                "a value in [0, 1]",
            ));
        }
        match s.viscosity {
            ViscosityChoice::Artificial => non_negative("scheme.alpha", s.alpha())?,
            ViscosityChoice::Physical => match s.dynamic_viscosity {
                Some(mu) => positive("scheme.dynamic_viscosity", mu)?,
                None => {
                    return Err(SphError::invalid(
                        "scheme.dynamic_viscosity",
                        "(missing)",
                        "a positive viscosity μ in Pa·s when scheme.viscosity = \"physical\"",
                    ))
                }
            },
            ViscosityChoice::None => {}
        }
        let cfl = s.cfl();
        if !(cfl > 0.0 && cfl <= 3.0) {
            return Err(SphError::invalid(
                "scheme.cfl",
                cfl,
                "a Courant number in (0, 3]",
            ));
        }
        if let Some(c) = s.viscous_cfl {
            positive("scheme.viscous_cfl", c)?;
        }
        if let Some(c) = s.diffusion_cfl {
            positive("scheme.diffusion_cfl", c)?;
        }
        positive("scheme.force_cfl", s.force_cfl)?;
        if s.turbulence == TurbulenceChoice::DeltaLes {
            self.check_les()?;
        }
        Ok(())
    }

    /// δ-LES-SPH: its constants, and the flows it is offered for: periodic along every
    /// axis, without walls or open boundaries, with its own shifting and a physical (or
    /// no) molecular viscosity.
    pub(super) fn check_les(&self) -> Result<()> {
        let s = &self.scheme;
        let constants = [
            ("scheme.smagorinsky_constant", s.smagorinsky_constant),
            ("scheme.diffusion_constant", s.diffusion_constant),
            ("scheme.les_shifting", s.les_shifting),
        ];
        for (key, value) in constants {
            if let Some(v) = value {
                non_negative(key, v)?;
            }
        }
        for (key, value) in [
            ("scheme.les_length", s.les_length),
            ("scheme.les_velocity", s.les_velocity),
        ] {
            if let Some(v) = value {
                positive(key, v)?;
            }
        }
        let expected = |what: &str| {
            format!("{what} with scheme.turbulence = \"delta_les\" (offered for periodic flows without walls)")
        };
        if s.viscosity == ViscosityChoice::Artificial {
            return Err(SphError::invalid(
                "scheme.viscosity",
                "\"artificial\"",
                expected("\"physical\" or \"none\""),
            ));
        }
        if s.shifting != ShiftingChoice::None {
            return Err(SphError::invalid(
                "scheme.shifting",
                "\"delta_plus\"",
                expected("\"none\" (δ-LES-SPH shifts with its own δu)"),
            ));
        }
        let walls = !self.tank.is_empty()
            || !self.wall.is_empty()
            || self.shape.iter().any(|sh| sh.role == Role::Wall);
        if walls {
            return Err(SphError::invalid(
                "tank/wall/shape",
                "walls",
                expected("no walls"),
            ));
        }
        if !self.open_boundary.is_empty() {
            return Err(SphError::invalid(
                "open_boundary",
                self.open_boundary.len(),
                expected("none"),
            ));
        }
        let periodic = (self.domain.as_ref())
            .is_some_and(|dom| (0..self.dimension).all(|d| dom.is_periodic(d)));
        if !periodic {
            return Err(SphError::invalid(
                "domain.periodic",
                format!(
                    "{:?}",
                    self.domain.as_ref().and_then(|dom| dom.periodic.clone())
                ),
                expected("every axis periodic"),
            ));
        }
        Ok(())
    }
}
