//! Water waves in a numerical flume: linear and second-order wave theory
//! ([`theory`]), the JONSWAP sea ([`spectrum`]) and the wave maker's motion that makes
//! them ([`paddle`]).

pub mod paddle;
pub mod spectrum;
pub mod theory;
