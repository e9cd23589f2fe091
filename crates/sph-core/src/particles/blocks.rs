//! Sums over the particles that give the same bits on any number of threads: the
//! particles are cut into fixed blocks of [`BLOCK`], each summed in order on one
//! thread, and the blocks' sums added in order. A rayon reduction splits the work
//! where threads steal it, so its rounding, and any result a run feeds back (a free
//! body's load) or writes (the energies), would change from run to run.

use rayon::prelude::*;
use std::ops::Range;

/// Particles per block: enough work per block for the thread pool, few blocks.
pub const BLOCK: usize = 1024;

/// `Σ_blocks block(range)` over the blocks of `0..n`, added in order from `zero`.
pub fn sum_in_blocks<T: Send>(
    n: usize,
    zero: impl Fn() -> T + Sync,
    block: impl Fn(Range<usize>) -> T + Sync,
    add: impl Fn(T, T) -> T,
) -> T {
    let sums: Vec<T> = (0..n.div_ceil(BLOCK))
        .into_par_iter()
        .map(|b| block(b * BLOCK..((b + 1) * BLOCK).min(n)))
        .collect();
    sums.into_iter().fold(zero(), add)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn block_sums_are_the_same_bits_on_any_number_of_threads() {
        let x: Vec<f64> = (0..50_000).map(|i| 1.0 / (1.0 + i as f64).sqrt()).collect();
        let sum = || sum_in_blocks(x.len(), || 0.0, |r| x[r].iter().sum(), |a, b| a + b);
        let one = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        let four = rayon::ThreadPoolBuilder::new()
            .num_threads(4)
            .build()
            .unwrap();
        let (a, b) = (one.install(sum), four.install(sum));
        assert_eq!(a.to_bits(), b.to_bits());
        let exact: f64 = x.iter().sum();
        assert!((a - exact).abs() < 1e-10 * exact, "{a} {exact}");
    }
}
