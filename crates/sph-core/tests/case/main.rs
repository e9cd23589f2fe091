//! What a case builds before its first step, and what it does with hostile input:
//! shapes as fluid, walls and cuts ([`shapes`]), outlines from SVG and DXF drawings
//! ([`drawings`]), initial fields from expressions ([`expressions`]), and arbitrary or
//! mutated case files ([`fuzz`]). One test binary for all: each test binary builds
//! the whole solver again, which is most of the suite's build time.

mod drawings;
mod expressions;
mod fuzz;
mod shapes;
