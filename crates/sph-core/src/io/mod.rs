//! What a run writes and reads back: the run folder with its snapshots, index, time
//! series and manifest ([`output`]), and restart files ([`restart`]).

pub mod output;
pub mod restart;
