//! Solid boundaries: fixed dummy wall particles with pressure extrapolated from the
//! fluid ([`walls`]), grouped into bodies whose loads are measured ([`bodies`]).

pub mod bodies;
pub mod walls;

pub use walls::extrapolate_walls;
