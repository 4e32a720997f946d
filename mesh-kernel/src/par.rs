//! Parallel maps over element indices: rayon for large meshes when the
//! `rayon` feature is on, a plain loop otherwise (same results either way).

/// Below this many elements a sequential loop is faster than spawning work.
#[cfg(feature = "rayon")]
const PARALLEL_THRESHOLD: usize = 1 << 14;

/// `(0..n).map(f).collect()`, in parallel for large `n`.
pub(crate) fn map_indexed<T: Send>(n: usize, f: impl Fn(usize) -> T + Sync + Send) -> Vec<T> {
    #[cfg(feature = "rayon")]
    if n >= PARALLEL_THRESHOLD {
        use rayon::prelude::*;
        return (0..n).into_par_iter().map(f).collect();
    }
    (0..n).map(f).collect()
}
