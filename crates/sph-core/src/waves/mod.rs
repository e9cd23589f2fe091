//! Water waves in a numerical flume: linear and second-order wave theory
//! ([`theory`]), the JONSWAP sea ([`spectrum`]), the wave maker's motion that makes
//! them ([`paddle`]) and the paddle's absorption of the waves that come back to it
//! ([`active_absorption`]).

pub mod active_absorption;
pub mod paddle;
pub mod spectrum;
pub mod theory;
