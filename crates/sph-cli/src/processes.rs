//! The processes of a run launched by `mpirun` or `srun`: MPI through rsmpi (the `mpi`
//! feature), behind the core's [`Communicator`]. A build without the feature refuses
//! to start under a launcher, instead of running the whole case once per process.

use anyhow::{bail, Result};
use sph_core::distributed::Communicator;
use std::sync::Arc;

/// Environment variables that MPI launchers set in the processes they start (Open
/// MPI's mpirun, PMI and PMIx, as used by MPICH's and Slurm's launchers).
const LAUNCHER_VARIABLES: [&str; 3] = ["OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"];

fn launched() -> bool {
    LAUNCHER_VARIABLES
        .iter()
        .any(|v| std::env::var_os(v).is_some())
}

/// The processes of this run: `None` when it was not started by an MPI launcher (or
/// by one, on a single process). MPI stays initialised while the handle lives.
pub struct Processes {
    #[cfg(feature = "mpi")]
    _universe: Option<mpi::environment::Universe>,
    pub comm: Option<Arc<dyn Communicator>>,
}

impl Processes {
    /// Whether this is process 0 (or the only one).
    pub fn is_first(&self) -> bool {
        self.comm.as_ref().is_none_or(|c| c.rank() == 0)
    }

    /// Returns once every process has called it.
    pub fn wait_for_all(&self) {
        if let Some(comm) = &self.comm {
            comm.max(&mut [0.0]);
        }
    }
}

#[cfg(not(feature = "mpi"))]
pub fn join() -> Result<Processes> {
    if launched() {
        bail!(
            "started by an MPI launcher, but this sph-cli was built without MPI: build it \
             with `cargo build --release -p sph-cli --features mpi` (needs libopenmpi-dev)"
        );
    }
    Ok(Processes { comm: None })
}

#[cfg(feature = "mpi")]
pub fn join() -> Result<Processes> {
    use mpi::environment::Threading;
    if !launched() {
        return Ok(Processes {
            _universe: None,
            comm: None,
        });
    }
    // the steps run on a thread of the Rayon pool, one call at a time
    let Some((universe, threading)) = mpi::initialize_with_threading(Threading::Serialized) else {
        bail!("MPI was initialised already");
    };
    if threading < Threading::Serialized {
        bail!("the MPI library does not allow calls from a thread other than the main one");
    }
    let world = universe.world();
    let comm: Option<Arc<dyn Communicator>> = (mpi::traits::Communicator::size(&world) > 1)
        .then(|| Arc::new(world::World(world)) as Arc<dyn Communicator>);
    Ok(Processes {
        _universe: Some(universe),
        comm,
    })
}

#[cfg(feature = "mpi")]
mod world {
    use mpi::collective::SystemOperation;
    use mpi::datatype::{Partition, PartitionMut};
    use mpi::topology::SimpleCommunicator;
    use mpi::traits::{Communicator as _, CommunicatorCollectives};
    use mpi::Count;

    /// MPI's world communicator.
    pub struct World(pub SimpleCommunicator);

    // SAFETY: MPI is initialised with MPI_THREAD_SERIALIZED or more, and the run calls
    // the communicator from one thread at a time (the thread stepping the simulation).
    unsafe impl Send for World {}
    unsafe impl Sync for World {}

    /// The offsets of blocks of `counts` laid end to end.
    fn offsets(counts: &[Count]) -> Vec<Count> {
        counts
            .iter()
            .scan(0, |at, &c| {
                let here = *at;
                *at += c;
                Some(here)
            })
            .collect()
    }

    impl sph_core::distributed::Communicator for World {
        fn rank(&self) -> usize {
            self.0.rank() as usize
        }

        fn size(&self) -> usize {
            self.0.size() as usize
        }

        fn all_to_all(&self, send: Vec<Vec<u8>>) -> Vec<Vec<u8>> {
            let send_counts: Vec<Count> = send.iter().map(|m| m.len() as Count).collect();
            let mut recv_counts = vec![0 as Count; send.len()];
            self.0
                .all_to_all_into(&send_counts[..], &mut recv_counts[..]);
            // one byte more than the messages: two empty buffers would share the same
            // dangling address, which MPI refuses as aliased
            let mut flat = send.concat();
            flat.push(0);
            let total: usize = recv_counts.iter().map(|&c| c as usize).sum();
            let mut recv = vec![0u8; total + 1];
            let (send_at, recv_at) = (offsets(&send_counts), offsets(&recv_counts));
            {
                let out = Partition::new(&flat[..], &send_counts[..], &send_at[..]);
                let mut into = PartitionMut::new(&mut recv[..], &recv_counts[..], &recv_at[..]);
                self.0.all_to_all_varcount_into(&out, &mut into);
            }
            (recv_at.iter().zip(&recv_counts))
                .map(|(&at, &n)| recv[at as usize..(at + n) as usize].to_vec())
                .collect()
        }

        fn max(&self, values: &mut [f64]) {
            let mine = values.to_vec();
            self.0
                .all_reduce_into(&mine[..], values, SystemOperation::max());
        }

        fn sum(&self, values: &mut [f64]) {
            let mine = values.to_vec();
            self.0
                .all_reduce_into(&mine[..], values, SystemOperation::sum());
        }
    }
}
