//! Checks of the `[[open_boundary]]` tables: axis and side against the domain, the
//! section, the buffer width and the keys of its kind.

use crate::case::checks::{components, finite, non_negative, positive};
use crate::case::open_boundaries::*;
use crate::case::schema::{Case, DomainConfig};
use crate::error::{Result, SphError};

impl Case {
    /// The checks of one `[[open_boundary]]` that need no particles.
    pub(in crate::case) fn check_open_boundary(
        &self,
        k: usize,
        b: &OpenBoundaryConfig,
    ) -> Result<()> {
        let key = format!("open_boundary[{k}]");
        let d = self.dimension;
        if b.axis >= d {
            return Err(SphError::invalid(
                format!("{key}.axis"),
                b.axis,
                format!("an axis of the {d}D case (0 to {})", d - 1),
            ));
        }
        let Some(domain) = &self.domain else {
            return Err(SphError::invalid(
                "domain",
                "(not set)",
                format!("[domain] lo and hi: {key} sits at an end of the domain"),
            ));
        };
        if domain.is_periodic(b.axis) {
            return Err(SphError::invalid(
                format!("{key}.axis"),
                b.axis,
                "an axis that is not periodic (an open boundary ends the domain there)",
            ));
        }
        let width = b.width_in(self);
        positive(&format!("{key}.width"), width)?;
        if width < self.support() * (1.0 - 1e-9) {
            return Err(SphError::invalid(
                format!("{key}.width"),
                width,
                format!(
                    "a buffer at least the kernel support R = {:.4} m wide",
                    self.support()
                ),
            ));
        }
        let length = domain.hi[b.axis] - domain.lo[b.axis];
        if 2.0 * width >= length {
            return Err(SphError::invalid(
                format!("{key}.width"),
                width,
                format!("a buffer narrower than half the domain ({length} m along the axis)"),
            ));
        }
        if let Some(section) = &b.section {
            self.check_section(&key, b.axis, section, domain)?;
        }
        self.check_open_kind_keys(&key, b)
    }

    /// A section is one interval `lo < hi` per transverse axis, within the domain.
    pub(super) fn check_section(
        &self,
        key: &str,
        axis: usize,
        section: &[[f64; 2]],
        domain: &DomainConfig,
    ) -> Result<()> {
        let d = self.dimension;
        let key = format!("{key}.section");
        if section.len() != d - 1 {
            return Err(SphError::invalid(
                key,
                format!("{section:?}"),
                format!(
                    "{} [lo, hi] interval(s), one per axis across the flow",
                    d - 1
                ),
            ));
        }
        let across = (0..d).filter(|&a| a != axis);
        for (k, ([lo, hi], a)) in section.iter().zip(across).enumerate() {
            finite(&format!("{key}[{k}]"), *lo)?;
            finite(&format!("{key}[{k}]"), *hi)?;
            if !(lo < hi && *lo >= domain.lo[a] && *hi <= domain.hi[a]) {
                return Err(SphError::invalid(
                    format!("{key}[{k}]"),
                    format!("[{lo}, {hi}]"),
                    format!(
                        "an interval lo < hi along axis {a} within the domain, [{}, {}]",
                        domain.lo[a], domain.hi[a]
                    ),
                ));
            }
        }
        Ok(())
    }

    /// Inlets take a velocity (into the domain), a profile and a ramp; outlets a
    /// pressure and an outflow velocity.
    pub(super) fn check_open_kind_keys(&self, key: &str, b: &OpenBoundaryConfig) -> Result<()> {
        let misplaced = match b.kind {
            OpenKind::Inlet => [
                ("pressure", b.pressure.is_some()),
                ("outflow_velocity", b.outflow_velocity.is_some()),
            ]
            .into_iter()
            .find_map(|(what, set)| set.then_some(what)),
            OpenKind::Outlet => [
                ("velocity", b.velocity.is_some()),
                ("profile", b.profile.is_some()),
                ("ramp", b.ramp.is_some()),
            ]
            .into_iter()
            .find_map(|(what, set)| set.then_some(what)),
        };
        if let Some(what) = misplaced {
            return Err(SphError::invalid(
                format!("{key}.{what}"),
                "(set)",
                "velocity, profile and ramp for an inlet, pressure and outflow_velocity for \
                 an outlet",
            ));
        }
        if let Some(p) = b.pressure {
            finite(&format!("{key}.pressure"), p)?;
        }
        if let Some(t) = b.ramp {
            non_negative(&format!("{key}.ramp"), t)?;
        }
        if b.kind == OpenKind::Outlet {
            return Ok(());
        }
        let Some(v) = &b.velocity else {
            return Err(SphError::invalid(
                format!("{key}.velocity"),
                "(not set)",
                "the inflow velocity of the inlet [m/s]",
            ));
        };
        components(&format!("{key}.velocity"), v, self.dimension)?;
        if v[b.axis] * b.inward() <= 0.0 {
            return Err(SphError::invalid(
                format!("{key}.velocity"),
                format!("{v:?}"),
                format!(
                    "a velocity into the domain (component {} of sign {:+})",
                    b.axis,
                    b.inward()
                ),
            ));
        }
        Ok(())
    }
}
