//! The `[[open_boundary]]` table: an inflow or outflow buffer at one end of the domain
//! along an open axis. Its run-time behaviour is in [`crate::boundary::open`].

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
    /// The buffer's cross-section, one `[lo, hi]` interval \[m\] per transverse axis in
    /// axis order (one in 2D, two in 3D): a jet's nozzle on part of the domain's end.
    /// Default: the whole end.
    #[serde(default)]
    pub section: Option<Vec<[f64; 2]>>,
    /// Buffer width \[m\], at least the kernel support R. Default: R rounded up to whole
    /// spacings, plus one (the outermost layer is refilled at the lists' rebuilds), so
    /// that it follows `h_over_dx`: set it where the inner face must stay put (a
    /// nozzle's stand-off); `sph-cli check` prints where each inner face lies.
    #[serde(default)]
    pub width: Option<f64>,
    /// Inflow velocity [m/s] (inlets only), pointing into the domain.
    #[serde(default)]
    pub velocity: Option<Vec<f64>>,
    /// Velocity profile across the inlet. Default: uniform.
    #[serde(default)]
    pub profile: Option<Profile>,
    /// Time over which the inflow velocity ramps up linearly from zero \[s\]. Default: 0.
    #[serde(default)]
    pub ramp: Option<f64>,
    /// Pressure of the outlet buffer \[Pa\] (outlets only). Default: 0.
    #[serde(default)]
    pub pressure: Option<f64>,
    /// The velocity of the outlet buffer's particles (outlets only). Default: kept.
    #[serde(default)]
    pub outflow_velocity: Option<OutflowVelocity>,
}

impl OpenBoundaryConfig {
    /// +1 when the flow enters the domain along +axis at this end, -1 otherwise.
    pub fn inward(&self) -> f64 {
        match self.side {
            Side::Lo => 1.0,
            Side::Hi => -1.0,
        }
    }
}
