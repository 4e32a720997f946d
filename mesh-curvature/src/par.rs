//! Data-parallel maps over index ranges: rayon with the default `rayon`
//! feature, a plain loop without it. Results are identical either way
//! (each output depends only on its index).

/// Minimum number of items per rayon task: below this, splitting costs more
/// than it saves.
const MIN_CHUNK: usize = 2048;

/// `(0..n).map(f).collect()`, in parallel when the `rayon` feature is on.
#[cfg(feature = "rayon")]
pub(crate) fn map<T: Send>(n: usize, f: impl Fn(usize) -> T + Sync + Send) -> Vec<T> {
    use rayon::prelude::*;
    (0..n).into_par_iter().with_min_len(MIN_CHUNK).map(f).collect()
}

/// `(0..n).map(f).collect()`, in parallel when the `rayon` feature is on.
#[cfg(not(feature = "rayon"))]
pub(crate) fn map<T: Send>(n: usize, f: impl Fn(usize) -> T + Sync + Send) -> Vec<T> {
    let _ = MIN_CHUNK;
    (0..n).map(f).collect()
}

/// Like [`map`], with one scratch value per worker (created by `init`) for
/// buffers reused across items.
#[cfg(feature = "rayon")]
pub(crate) fn map_with<T: Send, S>(
    n: usize,
    init: impl Fn() -> S + Sync + Send,
    f: impl Fn(&mut S, usize) -> T + Sync + Send,
) -> Vec<T> {
    use rayon::prelude::*;
    (0..n).into_par_iter().with_min_len(MIN_CHUNK / 8).map_init(init, f).collect()
}

/// Like [`map`], with one scratch value per worker (created by `init`) for
/// buffers reused across items.
#[cfg(not(feature = "rayon"))]
pub(crate) fn map_with<T: Send, S>(
    n: usize,
    init: impl Fn() -> S + Sync + Send,
    f: impl Fn(&mut S, usize) -> T + Sync + Send,
) -> Vec<T> {
    let mut scratch = init();
    (0..n).map(|i| f(&mut scratch, i)).collect()
}

/// Runs both closures, in parallel when the `rayon` feature is on.
#[cfg(feature = "rayon")]
pub(crate) fn join<A: Send, B: Send>(a: impl FnOnce() -> A + Send, b: impl FnOnce() -> B + Send) -> (A, B) {
    rayon::join(a, b)
}

/// Runs both closures, in parallel when the `rayon` feature is on.
#[cfg(not(feature = "rayon"))]
pub(crate) fn join<A: Send, B: Send>(a: impl FnOnce() -> A + Send, b: impl FnOnce() -> B + Send) -> (A, B) {
    (a(), b())
}
