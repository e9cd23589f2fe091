//! Checks of the `[initial]` analytic and expression fields: 2D-only fields, finite
//! amplitudes, positive sizes, gravity along -y for the standing wave, one expression
//! per velocity component and either a pressure or a density.

use crate::case::checks::{finite, only_2d, positive};
use crate::case::schema::*;
use crate::error::{Result, SphError};

impl Case {
    /// The `[initial]` table, when the case has one.
    pub(super) fn validate_initial(&self) -> Result<()> {
        let d = self.dimension;
        match &self.initial {
            Some(InitialField::TaylorGreen {
                amplitude,
                wavelength,
            }) => {
                only_2d(d, "taylor_green")?;
                finite("initial.amplitude", *amplitude)?;
                positive("initial.wavelength", *wavelength)?;
            }
            Some(InitialField::RotatingSquare {
                angular_velocity,
                side,
            }) => {
                only_2d(d, "rotating_square")?;
                finite("initial.angular_velocity", *angular_velocity)?;
                positive("initial.side", *side)?;
            }
            Some(InitialField::EllipticDrop {
                strain_rate,
                radius,
            }) => {
                only_2d(d, "elliptic_drop")?;
                finite("initial.strain_rate", *strain_rate)?;
                positive("initial.radius", *radius)?;
            }
            Some(InitialField::StandingWave {
                amplitude,
                length,
                depth,
            }) => {
                only_2d(d, "standing_wave")?;
                finite("initial.amplitude", *amplitude)?;
                positive("initial.length", *length)?;
                positive("initial.depth", *depth)?;
                let g = self.gravity();
                if g[0] != 0.0 || g[1].is_nan() || g[1] >= 0.0 {
                    return Err(SphError::invalid(
                        "fluid.gravity",
                        format!("{g:?}"),
                        "gravity along -y (initial.type = \"standing_wave\")",
                    ));
                }
            }
            Some(InitialField::Expressions {
                constants,
                u,
                p,
                rho,
                ..
            }) => {
                if let Some(u) = u {
                    if u.len() != d {
                        return Err(SphError::invalid(
                            "initial.u",
                            format!("{u:?}"),
                            format!("{d} expressions, one per velocity component"),
                        ));
                    }
                }
                if p.is_some() && rho.is_some() {
                    return Err(SphError::invalid(
                        "initial.rho",
                        "(set with initial.p)",
                        "either a pressure or a density expression, not both",
                    ));
                }
                for (name, value) in constants.iter().flatten() {
                    finite(&format!("initial.constants.{name}"), *value)?;
                }
            }
            None => {}
        }
        Ok(())
    }
}
