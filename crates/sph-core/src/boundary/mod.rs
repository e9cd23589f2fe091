//! Boundaries: fixed dummy wall particles with pressure extrapolated from the fluid
//! ([`walls`]), grouped into bodies whose loads are measured ([`bodies`]); inflow and
//! outflow buffers ([`open`]).

pub mod bodies;
pub mod open;
pub mod walls;

pub use walls::extrapolate_walls;
