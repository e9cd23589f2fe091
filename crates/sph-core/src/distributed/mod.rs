//! Runs split over P processes (hybrid MPI + threads): each process holds the
//! particles of its region of a [`Decomposition`] (its *own* particles, which it
//! advances) and a **halo**, copies of the other processes' particles near its region,
//! which it reads.
//!
//! - **Halo depth.** An evaluation is a chain of pair passes, each reading its
//!   neighbours' results of the pass before (the δ-SPH gradient before the pair loop,
//!   the wall extrapolation before both, the free surface before shifting). Instead of
//!   an exchange between passes, the halo reaches `passes × (R + s)` from the region
//!   (R the kernel support, s the list skin): a process evaluates its halo too, and a
//!   halo particle's result is right as far inwards as the passes so far have reached,
//!   so its own particles' results are exact. One message per evaluation, at the cost
//!   of a deeper halo (measured in `docs/scaling.md`).
//! - **Refresh.** Before each evaluation within a step, and at the end of every step
//!   (and after a shift), the halo particles get their owners' state `(x, u, ρ)`; so
//!   between steps every particle a process holds is its owner's.
//! - **Migration.** At list rebuilds the halo is dropped, particles that left a region
//!   move to its new owner, and the halo is gathered again; when the fluid shares are
//!   out of balance by more than [`REBALANCE`] the domain is bisected again first.
//! - **Agreement.** Δt, the list rebuilds and the stability guard are decided from
//!   maxima over all processes, which are exact: a split run takes the serial run's
//!   steps. The pair sums run in a different order (the cell grids differ), so states
//!   agree to round-off, not bit for bit.

mod communicator;
mod records;

pub use communicator::Communicator;

use crate::decomposition::Decomposition;
use crate::domain::Domain;
use crate::particles::{permute, Kind, Particles, Vector};
use rayon::prelude::*;
use records::{get_state, put_state, state_len, Reader, Writer};
use std::sync::{Arc, Mutex};
use std::time::Instant;

/// The largest fluid share over the mean that a list rebuild accepts before the domain
/// is bisected again.
pub const REBALANCE: f64 = 1.1;

/// What a process sent and how long it waited, for the run's report.
#[derive(Debug, Clone, Copy, Default)]
pub struct Traffic {
    /// Halo refreshes, the bytes this process sent in them, and the wall time spent
    /// packing and unpacking their records (the exchange itself is in `seconds`).
    pub refreshes: u64,
    pub refresh_bytes: u64,
    pub refresh_seconds: f64,
    /// Particles this process sent at list rebuilds, to their new owners and as halo.
    pub migrated: u64,
    pub halo_sent: u64,
    /// Times the domain was bisected again.
    pub rebalances: u64,
    /// Wall time in communication (every exchange and reduction, with the waiting for
    /// the slowest process in them), seconds.
    pub seconds: f64,
}

/// A process's share of a split run: the decomposition, which particles it owns and
/// the halo's message plan.
pub struct Ranks<const D: usize> {
    comm: Arc<dyn Communicator>,
    split: Decomposition<D>,
    /// Pair passes the halo covers (see the module).
    passes: usize,
    /// How far from this process's region the particles get neighbour rows at the
    /// current lists: `(passes - 1) × (R + s)`.
    listed_width: f64,
    /// Per particle held, in storage order: whether this process owns it.
    owned: Vec<bool>,
    /// Per process: the own particles whose state it holds as halo, in message order.
    send: Vec<Vec<usize>>,
    /// Per particle held, in storage order: for a halo particle, the process that
    /// owns it and the place of its record in that process's refresh message.
    source: Vec<Option<(u32, u32)>>,
    traffic: Mutex<Traffic>,
}

impl<const D: usize> Ranks<D> {
    /// Splits the particles of a whole run, built alike on every process: keeps this
    /// process's own (and their shifting velocities). The halo comes with the first
    /// list build ([`Self::redistribute`]).
    pub fn split(
        comm: Arc<dyn Communicator>,
        p: &mut Particles<D>,
        domain: &Domain<D>,
        passes: usize,
    ) -> Self {
        let split = Decomposition::bisect(p, domain, comm.size());
        let rank = comm.rank();
        let keep: Vec<bool> = p.x.par_iter().map(|x| split.owner(x) == rank).collect();
        p.retain(&keep);
        let size = comm.size();
        Self {
            comm,
            split,
            passes,
            listed_width: 0.0,
            owned: vec![true; p.len()],
            send: vec![Vec::new(); size],
            source: vec![None; p.len()],
            traffic: Mutex::new(Traffic::default()),
        }
    }

    pub fn rank(&self) -> usize {
        self.comm.rank()
    }

    pub fn size(&self) -> usize {
        self.comm.size()
    }

    /// Per particle held, in storage order: whether this process owns it.
    pub fn owned(&self) -> &[bool] {
        &self.owned
    }

    /// The halo particles held.
    pub fn halo_len(&self) -> usize {
        self.source.iter().filter(|s| s.is_some()).count()
    }

    pub fn decomposition(&self) -> &Decomposition<D> {
        &self.split
    }

    pub fn traffic(&self) -> Traffic {
        *self.traffic.lock().expect("traffic lock")
    }

    fn timed<T>(&self, f: impl FnOnce(&dyn Communicator) -> T) -> T {
        let start = Instant::now();
        let out = f(self.comm.as_ref());
        self.traffic.lock().expect("traffic lock").seconds += start.elapsed().as_secs_f64();
        out
    }

    /// The largest of `value` over the processes.
    pub fn max(&self, value: f64) -> f64 {
        let mut v = [value];
        self.timed(|c| c.max(&mut v));
        v[0]
    }

    /// Sums `values` entry by entry over the processes.
    pub fn sum(&self, values: &mut [f64]) {
        self.timed(|c| c.sum(values));
    }

    fn exchange(&self, send: Vec<Vec<u8>>) -> Vec<Vec<u8>> {
        self.timed(|c| c.all_to_all(send))
    }

    /// The first of the processes' `text` (in rank order) when any has one, the same
    /// on every process: the report of an instability, which any process may find.
    pub fn first_text(&self, text: Option<String>) -> Option<String> {
        if self.max(f64::from(u8::from(text.is_some()))) == 0.0 {
            return None;
        }
        let bytes = text.unwrap_or_default().into_bytes();
        let got = self.exchange(vec![bytes; self.size()]);
        got.into_iter()
            .find(|b| !b.is_empty())
            .map(|b| String::from_utf8_lossy(&b).into_owned())
    }

    /// Before a list rebuild of radius `radius`: drops the halo, bisects the domain
    /// again when the shares are out of balance, moves the particles that left this
    /// process's region to their owners and gathers the new halo (after the own
    /// particles).
    pub fn redistribute(&mut self, p: &mut Particles<D>, domain: &Domain<D>, radius: f64) {
        let own = std::mem::take(&mut self.owned);
        p.retain(&own);
        self.rebalance(p, domain);
        self.migrate(p);
        self.gather_halo(p, domain, self.passes as f64 * radius);
        self.listed_width = (self.passes - 1) as f64 * radius;
    }

    /// Whether a particle of kind `kind` at `x` needs neighbour rows: every wall (their
    /// rows, fluid only, feed the cheap pressure extrapolation), and the fluid within
    /// `(passes - 1) × (R + s)` of this process's region, the own particles and the
    /// inner part of the halo, whose results the own particles read. The fluid rows of
    /// the outer halo, the costly ones, would only be discarded.
    pub fn listed(&self, x: &Vector<D>, kind: Kind, domain: &Domain<D>) -> bool {
        kind == Kind::Wall || self.split.region_distance(self.rank(), x, domain) < self.listed_width
    }

    /// Bisects the domain again, from every process's particles, when the largest
    /// fluid share exceeds the mean by more than [`REBALANCE`].
    fn rebalance(&mut self, p: &Particles<D>, domain: &Domain<D>) {
        let (rank, size) = (self.rank(), self.size());
        let mut fluid = vec![0.0; size];
        fluid[rank] = p.n_fluid() as f64;
        self.sum(&mut fluid);
        let mean = fluid.iter().sum::<f64>() / size as f64;
        if fluid.iter().all(|&f| f <= REBALANCE * mean) {
            return;
        }
        let mut w = Writer::default();
        (0..p.len()).for_each(|i| w.position(p, i));
        let got = self.exchange(vec![w.0; size]);
        let (mut x, mut kind) = (Vec::new(), Vec::new());
        for bytes in &got {
            let mut r = Reader::new(bytes);
            while !r.is_empty() {
                r.position(&mut x, &mut kind);
            }
        }
        self.split = Decomposition::bisect_points(&x, &kind, domain, size);
        self.traffic.lock().expect("traffic lock").rebalances += 1;
    }

    /// Sends the particles that left this process's region to their owners and takes
    /// in those that entered it.
    fn migrate(&mut self, p: &mut Particles<D>) {
        let rank = self.rank();
        let owners: Vec<usize> = p.x.par_iter().map(|x| self.split.owner(x)).collect();
        let mut out: Vec<Writer> = (0..self.size()).map(|_| Writer::default()).collect();
        let mut moved = 0;
        for (i, &q) in owners.iter().enumerate().filter(|(_, &q)| q != rank) {
            out[q].particle(p, i);
            moved += 1;
        }
        let keep: Vec<bool> = owners.iter().map(|&q| q == rank).collect();
        p.retain(&keep);
        for bytes in self.exchange(out.into_iter().map(|w| w.0).collect()) {
            let mut r = Reader::new(&bytes);
            while !r.is_empty() {
                r.particle(p);
            }
        }
        self.traffic.lock().expect("traffic lock").migrated += moved;
    }

    /// Sends each process the own particles within `width` of its region and appends
    /// those the others send as this one's halo.
    fn gather_halo(&mut self, p: &mut Particles<D>, domain: &Domain<D>, width: f64) {
        let (rank, n_own) = (self.rank(), p.len());
        let split = &self.split;
        self.send = (0..self.size())
            .map(|q| {
                let near =
                    |&i: &usize| q != rank && split.region_distance(q, &p.x[i], domain) < width;
                (0..n_own).into_par_iter().filter(near).collect()
            })
            .collect();
        let out: Vec<Vec<u8>> = (self.send.iter())
            .map(|list| {
                let mut w = Writer::default();
                list.iter().for_each(|&i| w.particle(p, i));
                w.0
            })
            .collect();
        let sent = self.send.iter().map(Vec::len).sum::<usize>() as u64;
        self.source = vec![None; n_own];
        for (q, bytes) in self.exchange(out).into_iter().enumerate() {
            let mut r = Reader::new(&bytes);
            let mut k = 0;
            while !r.is_empty() {
                r.particle(p);
                self.source.push(Some((q as u32, k)));
                k += 1;
            }
        }
        self.owned = self.source.iter().map(Option::is_none).collect();
        self.traffic.lock().expect("traffic lock").halo_sent += sent;
    }

    /// Follows a reordering of the particles held (new index k holds old `order[k]`).
    pub fn reorder(&mut self, order: &[usize]) {
        permute(&mut self.owned, order);
        permute(&mut self.source, order);
        let mut new_index = vec![0; order.len()];
        for (k, &old) in order.iter().enumerate() {
            new_index[old] = k;
        }
        for list in self.send.iter_mut() {
            list.iter_mut().for_each(|i| *i = new_index[*i]);
        }
    }

    /// Gives the halo particles their owners' state `(x, u, ρ)`: records of a fixed
    /// size, written and read in parallel over the particles.
    pub fn refresh(&self, p: &mut Particles<D>) {
        let start = Instant::now();
        let len = state_len::<D>();
        let out: Vec<Vec<u8>> = (self.send.iter())
            .map(|list| {
                let mut bytes = vec![0u8; list.len() * len];
                (bytes.par_chunks_mut(len).zip(list.par_iter()))
                    .for_each(|(record, &i)| put_state(record, p, i));
                bytes
            })
            .collect();
        let bytes = out.iter().map(Vec::len).sum::<usize>() as u64;
        let mut seconds = start.elapsed().as_secs_f64();
        let got = self.exchange(out);
        let start = Instant::now();
        (p.x.par_iter_mut().zip(p.u.par_iter_mut()))
            .zip(p.rho.par_iter_mut().zip(self.source.par_iter()))
            .for_each(|((x, u), (rho, source))| {
                if let Some((q, k)) = *source {
                    let at = k as usize * len;
                    (*x, *u, *rho) = get_state(&got[q as usize][at..at + len]);
                }
            });
        let mut t = self.traffic.lock().expect("traffic lock");
        t.refreshes += 1;
        t.refresh_bytes += bytes;
        seconds += start.elapsed().as_secs_f64();
        t.refresh_seconds += seconds;
    }

    /// Every process's own particles, gathered on process 0 in the order of their
    /// ids; `None` on the others.
    pub fn gather(&self, p: &Particles<D>) -> Option<Particles<D>> {
        let mut w = Writer::default();
        (0..p.len())
            .filter(|&i| self.owned[i])
            .for_each(|i| w.particle(p, i));
        let mut out = vec![Vec::new(); self.size()];
        out[0] = w.0;
        let got = self.exchange(out);
        if self.rank() != 0 {
            return None;
        }
        let mut all = p.empty_like();
        for bytes in &got {
            let mut r = Reader::new(bytes);
            while !r.is_empty() {
                r.particle(&mut all);
            }
        }
        let mut order: Vec<usize> = (0..all.len()).collect();
        order.sort_unstable_by_key(|&i| all.id[i]);
        all.permute(&order);
        Some(all)
    }
}

/// Whether particle `i` is a fluid particle this process owns (all of them, in a run
/// that is not split).
pub fn owns_fluid<const D: usize>(ranks: Option<&Ranks<D>>, p: &Particles<D>, i: usize) -> bool {
    p.kind[i] == Kind::Fluid && ranks.is_none_or(|r| r.owned[i])
}
