//! Checks on moving bodies: each region's `motion` agrees with its `prescribed` table,
//! the table's entries have the case's dimension, and what moving bodies cannot do
//! yet is refused in one line.

use crate::case::checks::{components, non_negative};
use crate::case::motion::{MotionChoice, PrescribedConfig};
use crate::case::schema::*;
use crate::error::{Result, SphError};

impl Case {
    /// Every region's motion, then what a case with moving bodies may not combine.
    pub(super) fn validate_motions(&self) -> Result<()> {
        for (key, motion, table) in self.body_motions() {
            match (motion, table) {
                (MotionChoice::Prescribed, Some(table)) => self.check_prescribed(&key, table)?,
                (MotionChoice::Prescribed, None) => {
                    return Err(SphError::invalid(
                        format!("{key}.motion"),
                        "\"prescribed\"",
                        format!("a table {key}.prescribed giving the motion beside it"),
                    ))
                }
                (MotionChoice::Fixed, Some(_)) => {
                    return Err(SphError::invalid(
                        format!("{key}.prescribed"),
                        "a table",
                        "motion = \"prescribed\" beside it (without it the region is fixed)",
                    ))
                }
                (MotionChoice::Fixed, None) => {}
            }
        }
        for (k, s) in self.shape.iter().enumerate() {
            if s.role != crate::case::Role::Wall && (s.motion.is_some() || s.prescribed.is_some()) {
                return Err(SphError::invalid(
                    format!("shape[{k}].motion"),
                    format!("{:?}", s.motion.unwrap_or_default()),
                    "no motion on a fluid shape (fluid moves with the flow; only walls take a motion)",
                ));
            }
        }
        if !self.has_moving_bodies() {
            return Ok(());
        }
        for (k, t) in self.tank.iter().enumerate() {
            if t.lid_velocity.is_some() && t.motion.unwrap_or_default() != MotionChoice::Fixed {
                return Err(SphError::invalid(
                    format!("tank[{k}].lid_velocity"),
                    format!("{:?}", t.lid_velocity.as_deref().unwrap_or_default()),
                    "no sliding lid on a moving tank (a [[wall]] above it can carry its own motion)",
                ));
            }
        }
        if self.diagnostics.energy_budget {
            return Err(SphError::invalid(
                "diagnostics.energy_budget",
                "true",
                "no energy budget in a case with moving bodies yet (it has no term for the \
                 power the moving walls supply)",
            ));
        }
        Ok(())
    }

    /// The lengths and ranges of one `prescribed` table.
    fn check_prescribed(&self, key: &str, m: &PrescribedConfig) -> Result<()> {
        let d = self.dimension;
        let key = format!("{key}.prescribed");
        if m.table.is_some() && (m.displacement.is_some() || m.rotation.is_some()) {
            return Err(SphError::invalid(
                format!("{key}.table"),
                format!("{:?}", m.table.as_deref().unwrap_or_default()),
                "either a table or displacement and rotation expressions, not both",
            ));
        }
        if let Some(texts) = &m.displacement {
            count(
                &format!("{key}.displacement"),
                texts,
                d,
                "one expression per axis",
            )?;
        }
        if let Some(texts) = &m.rotation {
            let (n, what) = match d {
                2 => (1, "one expression: the angle about z"),
                _ => (3, "three expressions: the rotation vector"),
            };
            count(&format!("{key}.rotation"), texts, n, what)?;
            if m.pivot.is_none() {
                return Err(SphError::invalid(
                    format!("{key}.pivot"),
                    "none",
                    "the point the body turns about, beside a rotation",
                ));
            }
        }
        if let Some(pivot) = &m.pivot {
            components(&format!("{key}.pivot"), pivot, d)?;
        }
        if let Some(ramp) = m.ramp {
            non_negative(&format!("{key}.ramp"), ramp)?;
        }
        Ok(())
    }
}

/// `texts` holds `n` expressions.
fn count(key: &str, texts: &[String], n: usize, what: &str) -> Result<()> {
    if texts.len() == n {
        return Ok(());
    }
    Err(SphError::invalid(
        key,
        format!("{} expressions", texts.len()),
        what,
    ))
}
