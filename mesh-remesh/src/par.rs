//! Parallel loops with the `rayon` feature, sequential ones without.

/// The largest `f(x)` over `items` (`-inf` for none; NaN is ignored).
pub(crate) fn max_map<T: Sync>(items: &[T], f: impl Fn(&T) -> f64 + Sync + Send) -> f64 {
    #[cfg(feature = "rayon")]
    {
        use rayon::prelude::*;
        items.par_iter().map(f).reduce(|| f64::NEG_INFINITY, f64::max)
    }
    #[cfg(not(feature = "rayon"))]
    {
        items.iter().map(f).fold(f64::NEG_INFINITY, f64::max)
    }
}
