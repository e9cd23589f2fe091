//! The `[[open_boundary]]` table: an inflow or outflow buffer at one end of the domain
//! along an open axis. Its run-time behaviour is in [`crate::boundary::open`].

use super::schema::Case;
use super::validate::{components, finite, positive};
use crate::error::{Result, SphError};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Inflow or outflow.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum OpenKind {
    /// Buffer particles move with a prescribed velocity; their density is extrapolated
    /// from the fluid; new particles enter at the buffer's far end.
    Inlet,
    /// Buffer particles keep the velocity they entered with and carry a prescribed
    /// pressure; they are removed past the domain's end.
    Outlet,
}

/// Which end of the domain along the axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Side {
    /// At `domain.lo[axis]`.
    Lo,
    /// At `domain.hi[axis]`.
    Hi,
}

/// The velocity profile across an inlet.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Profile {
    /// `velocity` everywhere.
    #[default]
    Uniform,
    /// Laminar (Poiseuille) flow across the fluid's section in the buffer, `velocity`
    /// at its centre: `4 s(1 - s)` between plates (2D, `s` from 0 to 1 across), the
    /// exact series solution in a rectangular duct (3D).
    Parabolic,
}

/// The velocity of an outlet buffer's particles.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum OutflowVelocity {
    /// The velocity a particle had when it entered the buffer (or at the start), kept
    /// until it leaves. A flow that starts at rest at the outlet is refused with it.
    #[default]
    Kept,
    /// The fluid's velocity at the point mirrored across the buffer's inner face
    /// (Shepard interpolation; zero normal gradient, Tafuni et al. 2018), set before
    /// every evaluation: the buffer follows what reaches it (a flow started from rest,
    /// vortices). The Shepard average flattens a sheared profile over the kernel's
    /// width (a Poiseuille channel's pressure gradient comes out 4.7% short at
    /// L/Δx = 20, against 2.7% with `kept`).
    Extrapolated,
}

/// One `[[open_boundary]]`: a buffer of particles from the domain's end along `axis`
/// to `width` inside it (buffer method; Federico et al. 2012, Eur. J. Mech. B 34:35).
/// The buffer starts full: the fluid blocks cover it.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct OpenBoundaryConfig {
    /// `inlet` or `outlet`.
    #[serde(rename = "type")]
    pub kind: OpenKind,
    /// The axis the flow crosses the boundary along (0 = x); not periodic, with
    /// `[domain]` bounds.
    pub axis: usize,
    /// Which end of the domain (`lo` or `hi`) along the axis.
    pub side: Side,
    /// The buffer's cross-section, one `[lo, hi]` interval [m] per transverse axis in
    /// axis order (one in 2D, two in 3D): a jet's nozzle on part of the domain's end.
    /// Default: the whole end.
    #[serde(default)]
    pub section: Option<Vec<[f64; 2]>>,
    /// Buffer width [m], at least the kernel support R. Default: R rounded up to whole
    /// spacings, plus one (the outermost layer is refilled at the lists' rebuilds).
    #[serde(default)]
    pub width: Option<f64>,
    /// Inflow velocity [m/s] (inlets only), pointing into the domain.
    #[serde(default)]
    pub velocity: Option<Vec<f64>>,
    /// Velocity profile across the inlet. Default: uniform.
    #[serde(default)]
    pub profile: Option<Profile>,
    /// Time over which the inflow velocity ramps up linearly from zero [s]. Default: 0.
    #[serde(default)]
    pub ramp: Option<f64>,
    /// Pressure of the outlet buffer [Pa] (outlets only). Default: 0.
    #[serde(default)]
    pub pressure: Option<f64>,
    /// The velocity of the outlet buffer's particles (outlets only). Default: kept.
    #[serde(default)]
    pub outflow_velocity: Option<OutflowVelocity>,
}

impl OpenBoundaryConfig {
    /// The buffer width in force: as given, or R rounded up to whole spacings plus one.
    pub fn width_in(&self, case: &Case) -> f64 {
        self.width
            .unwrap_or_else(|| ((case.support() / case.dx() - 1e-9).ceil() + 1.0) * case.dx())
    }

    /// +1 when the flow enters the domain along +axis at this end, -1 otherwise.
    pub fn inward(&self) -> f64 {
        match self.side {
            Side::Lo => 1.0,
            Side::Hi => -1.0,
        }
    }
}

impl Case {
    /// The checks of one `[[open_boundary]]` that need no particles.
    pub(super) fn check_open_boundary(&self, k: usize, b: &OpenBoundaryConfig) -> Result<()> {
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
    fn check_section(
        &self,
        key: &str,
        axis: usize,
        section: &[[f64; 2]],
        domain: &super::schema::DomainConfig,
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
    fn check_open_kind_keys(&self, key: &str, b: &OpenBoundaryConfig) -> Result<()> {
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
            super::validate::non_negative(&format!("{key}.ramp"), t)?;
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
