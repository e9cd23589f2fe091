//! Solid boundaries: fixed dummy wall particles with pressure extrapolated from the
//! fluid ([`walls`]).

pub mod walls;

pub use walls::extrapolate_walls;
