//! What a case builds before its first step: shapes as fluid, walls and cuts
//! ([`shapes`]), outlines from SVG and DXF drawings ([`drawings`]), and initial
//! fields from expressions ([`expressions`]). One test binary for all, as they share
//! the build.

mod drawings;
mod expressions;
mod shapes;
