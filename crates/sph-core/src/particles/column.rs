//! A per-particle column, and what every column does when the particles are
//! reordered, thinned, appended to or sent to another process: [`Column`]. A column is
//! a `Vec<T>` (every run has it) or an `Option<Vec<T>>` (only the runs that need it,
//! `None` costing nothing); `T` is a [`Value`], so that it travels as bytes.

use super::{Kind, Vector};
use rayon::prelude::*;

/// A fixed-size value of a column, written to and read from native-endian bytes (the
/// processes of a run share a machine type).
pub trait Value: Copy + Send + Sync {
    /// The entry of a particle that has no value yet.
    fn zero() -> Self;
    fn put(&self, out: &mut Vec<u8>);
    fn get(bytes: &mut &[u8]) -> Self;
}

/// Splits `N` bytes off the front of `bytes`.
fn take<const N: usize>(bytes: &mut &[u8]) -> [u8; N] {
    let (head, rest) = bytes.split_at(N);
    *bytes = rest;
    head.try_into().expect("split at N")
}

impl Value for f64 {
    fn zero() -> Self {
        0.0
    }
    fn put(&self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_ne_bytes());
    }
    fn get(bytes: &mut &[u8]) -> Self {
        f64::from_ne_bytes(take(bytes))
    }
}

impl Value for u32 {
    fn zero() -> Self {
        0
    }
    fn put(&self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_ne_bytes());
    }
    fn get(bytes: &mut &[u8]) -> Self {
        u32::from_ne_bytes(take(bytes))
    }
}

impl Value for Kind {
    fn zero() -> Self {
        Kind::Fluid
    }
    fn put(&self, out: &mut Vec<u8>) {
        out.push(*self as u8);
    }
    fn get(bytes: &mut &[u8]) -> Self {
        Kind::from_byte(take::<1>(bytes)[0])
    }
}

impl<const D: usize> Value for Vector<D> {
    fn zero() -> Self {
        Vector::zeros()
    }
    fn put(&self, out: &mut Vec<u8>) {
        self.iter().for_each(|c| c.put(out));
    }
    fn get(bytes: &mut &[u8]) -> Self {
        Vector::from_fn(|_, _| f64::get(bytes))
    }
}

/// What every per-particle column does; object safe, so that
/// [`super::Particles::columns_mut`] lists the columns in one place.
pub trait Column: Send + Sync {
    /// Whether the run keeps this column (always, for a required one).
    fn present(&self) -> bool;
    /// Empties the column, kept (or not) like `like`.
    fn clear_like(&mut self, like: &dyn Column);
    /// Reorders so that new index `k` holds old `order[k]`.
    fn permute(&mut self, order: &[usize]);
    /// Keeps the entries whose `keep` flag is set, in their order.
    fn retain(&mut self, keep: &[bool]);
    /// Appends a default entry.
    fn push_default(&mut self);
    /// An optional column follows the particle count `n` (new entries default); a
    /// required one is left as it is.
    fn fit(&mut self, n: usize);
    /// Appends entry `i` to a message.
    fn write(&self, i: usize, out: &mut Vec<u8>);
    /// Appends the next entry of a message.
    fn read(&mut self, bytes: &mut &[u8]);
}

impl<T: Value> Column for Vec<T> {
    fn present(&self) -> bool {
        true
    }
    fn clear_like(&mut self, _: &dyn Column) {
        self.clear();
    }
    fn permute(&mut self, order: &[usize]) {
        permute(self, order);
    }
    fn retain(&mut self, keep: &[bool]) {
        retain(self, keep);
    }
    fn push_default(&mut self) {
        self.push(T::zero());
    }
    fn fit(&mut self, _: usize) {}
    fn write(&self, i: usize, out: &mut Vec<u8>) {
        self[i].put(out);
    }
    fn read(&mut self, bytes: &mut &[u8]) {
        self.push(T::get(bytes));
    }
}

impl<T: Value> Column for Option<Vec<T>> {
    fn present(&self) -> bool {
        self.is_some()
    }
    fn clear_like(&mut self, like: &dyn Column) {
        *self = like.present().then(Vec::new);
    }
    fn permute(&mut self, order: &[usize]) {
        if let Some(v) = self {
            permute(v, order);
        }
    }
    fn retain(&mut self, keep: &[bool]) {
        if let Some(v) = self {
            retain(v, keep);
        }
    }
    fn push_default(&mut self) {
        if let Some(v) = self {
            v.push(T::zero());
        }
    }
    fn fit(&mut self, n: usize) {
        if let Some(v) = self {
            v.resize(n, T::zero());
        }
    }
    fn write(&self, i: usize, out: &mut Vec<u8>) {
        if let Some(v) = self {
            v[i].put(out);
        }
    }
    fn read(&mut self, bytes: &mut &[u8]) {
        if let Some(v) = self {
            v.push(T::get(bytes));
        }
    }
}

/// Keeps `v[k]` where `keep[k]`.
pub fn retain<T>(v: &mut Vec<T>, keep: &[bool]) {
    debug_assert_eq!(v.len(), keep.len());
    let mut flags = keep.iter();
    v.retain(|_| *flags.next().unwrap_or(&false));
}

/// Gathers `v[order[k]]` into position `k`.
pub fn permute<T: Copy + Send + Sync>(v: &mut Vec<T>, order: &[usize]) {
    debug_assert_eq!(v.len(), order.len());
    *v = order.par_iter().map(|&k| v[k]).collect();
}
