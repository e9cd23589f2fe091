//! The message passing a run over several processes needs, as a trait: the MPI binding
//! lives in the command line (behind its `mpi` feature), so that the core, the default
//! build and the Python wheel need no MPI library.

/// Collective operations over the processes of a run. Every process calls each of them
/// in the same order (they are collectives, as in MPI).
pub trait Communicator: Send + Sync {
    /// This process's index, `0..size()`.
    fn rank(&self) -> usize;

    /// The number of processes.
    fn size(&self) -> usize;

    /// Sends `send[q]` to process `q` (an empty message to those it has nothing for)
    /// and returns what each process sent this one, indexed by sender.
    fn all_to_all(&self, send: Vec<Vec<u8>>) -> Vec<Vec<u8>>;

    /// Replaces every entry of `values` by its largest value over the processes.
    fn max(&self, values: &mut [f64]);

    /// Replaces every entry of `values` by its sum over the processes.
    fn sum(&self, values: &mut [f64]);
}
