//! What a run writes and reads back: the run folder with its snapshots, index, time
//! series and manifest ([`output`]), restart files ([`restart`]), and the preview of a
//! case's initial particles ([`preview`]).

pub mod output;
pub mod preview;
pub mod restart;
