//! What a case builds before its first step: shapes as fluid, walls and cuts
//! ([`shapes`]), and initial fields from expressions ([`expressions`]). One test
//! binary for both, as they share the build.

mod expressions;
mod shapes;
