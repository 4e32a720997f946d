//! Data-parallel maps over index ranges, one policy for every crate: rayon
//! with the `rayon` feature for ranges of at least [`PARALLEL_FROM`] items
//! (split into tasks of at least [`MIN_TASK`] items), a plain loop
//! otherwise. Results are identical either way: each output depends only on
//! its index.

/// Items from which a map runs in parallel: below it, one loop is faster
/// than handing out tasks (per-face loops of ~10 ns per item).
pub const PARALLEL_FROM: usize = 1 << 12;

/// Smallest number of items in one parallel task.
pub const MIN_TASK: usize = 1 << 11;

/// `(0..n).map(f).collect()`, in parallel from [`PARALLEL_FROM`] items.
pub fn map<T: Send>(n: usize, f: impl Fn(usize) -> T + Sync + Send) -> Vec<T> {
    #[cfg(feature = "rayon")]
    if n >= PARALLEL_FROM {
        use rayon::prelude::*;
        return (0..n).into_par_iter().with_min_len(MIN_TASK).map(f).collect();
    }
    (0..n).map(f).collect()
}

/// Like [`map`], with one scratch value per task (created by `init`) for
/// buffers reused across items; tasks are 8 times smaller, for items that
/// each cost microseconds (per-vertex fits).
pub fn map_with<T: Send, S>(
    n: usize,
    init: impl Fn() -> S + Sync + Send,
    f: impl Fn(&mut S, usize) -> T + Sync + Send,
) -> Vec<T> {
    #[cfg(feature = "rayon")]
    if n >= PARALLEL_FROM / 8 {
        use rayon::prelude::*;
        return (0..n).into_par_iter().with_min_len(MIN_TASK / 8).map_init(init, f).collect();
    }
    let mut scratch = init();
    (0..n).map(|i| f(&mut scratch, i)).collect()
}

/// Runs both closures, in parallel with the `rayon` feature.
pub fn join<A: Send, B: Send>(a: impl FnOnce() -> A + Send, b: impl FnOnce() -> B + Send) -> (A, B) {
    #[cfg(feature = "rayon")]
    return rayon::join(a, b);
    #[cfg(not(feature = "rayon"))]
    (a(), b())
}
