//! Products of tall-skinny matrices (n rows, tens to hundreds of columns),
//! split by rows across threads.
//!
//! faer parallelizes a product over its (small) output, which for
//! `V^T W` with `V` n x 400 and `W` n x 8 leaves the threads fighting over
//! a 400 x 8 result; measured on a 2-core x86-64 VM it ran 5-8 times slower
//! than one thread. Splitting the long dimension instead gives each thread a
//! contiguous slab of rows and a sequential faer kernel; partial Gram
//! matrices are summed at the end.

use faer::linalg::matmul::matmul;
use faer::reborrow::{Reborrow, ReborrowMut};
use faer::{Accum, Mat, MatMut, MatRef, Par};

/// Below this many multiply-adds a product stays on one thread.
const PARALLEL_WORK: usize = 1 << 20;

fn slabs(n: usize, work: usize) -> usize {
    if work < PARALLEL_WORK {
        return 1;
    }
    #[cfg(feature = "rayon")]
    {
        rayon::current_num_threads().clamp(1, n.max(1))
    }
    #[cfg(not(feature = "rayon"))]
    {
        let _ = n;
        1
    }
}

/// `out = a^T b` (a: n x k, b: n x m, out: k x m).
pub(crate) fn gram(out: MatMut<'_, f64>, a: MatRef<'_, f64>, b: MatRef<'_, f64>) {
    let n = a.nrows();
    let parts = slabs(n, n * a.ncols() * b.ncols());
    #[cfg(feature = "rayon")]
    if parts > 1 {
        use rayon::prelude::*;
        let (k, m) = (a.ncols(), b.ncols());
        let sum = a
            .par_row_partition(parts)
            .zip(b.par_row_partition(parts))
            .map(|(a, b)| {
                let mut part = Mat::zeros(k, m);
                matmul(part.as_mut(), Accum::Replace, a.transpose(), b, 1.0, Par::Seq);
                part
            })
            .reduce(|| Mat::zeros(k, m), |x, y| x + y);
        let mut out = out;
        out.copy_from(&sum);
        return;
    }
    let _ = parts;
    matmul(out, Accum::Replace, a.transpose(), b, 1.0, Par::Seq);
}

/// `out = beta_out + alpha a c` with `beta` Replace or Add (a: n x k,
/// c: k x m, out: n x m).
pub(crate) fn mul(out: MatMut<'_, f64>, accum: Accum, a: MatRef<'_, f64>, c: MatRef<'_, f64>, alpha: f64) {
    let n = a.nrows();
    let parts = slabs(n, n * a.ncols() * c.ncols());
    #[cfg(feature = "rayon")]
    if parts > 1 {
        use rayon::prelude::*;
        out.par_row_partition_mut(parts).zip(a.par_row_partition(parts)).for_each(|(o, a)| {
            matmul(o, accum, a, c, alpha, Par::Seq);
        });
        return;
    }
    let _ = parts;
    matmul(out, accum, a, c, alpha, Par::Seq);
}

/// `v[:, ..p] = v S` in place (v: n x s, S: s x p, p <= s), by slabs of
/// rows so that only a small buffer is needed.
pub(crate) fn rotate_in_place(v: MatMut<'_, f64>, s: MatRef<'_, f64>) {
    let n = v.nrows();
    let parts = slabs(n, n * s.nrows() * s.ncols());
    let rotate = |mut slab: MatMut<'_, f64>| {
        const CHUNK: usize = 512;
        let (rows, p) = (slab.nrows(), s.ncols());
        let mut tmp = Mat::zeros(CHUNK.min(rows), p);
        let mut r0 = 0;
        while r0 < rows {
            let len = CHUNK.min(rows - r0);
            let mut t = tmp.as_mut().subrows_mut(0, len);
            matmul(t.rb_mut(), Accum::Replace, slab.rb().subrows(r0, len), s, 1.0, Par::Seq);
            slab.rb_mut().submatrix_mut(r0, 0, len, p).copy_from(t.rb());
            r0 += len;
        }
    };
    #[cfg(feature = "rayon")]
    if parts > 1 {
        use rayon::prelude::*;
        v.par_row_partition_mut(parts).for_each(rotate);
        return;
    }
    let _ = parts;
    rotate(v);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_faer_on_large_and_small_shapes() {
        for (n, k, m) in [(7, 3, 2), (40_000, 40, 8)] {
            let a = Mat::from_fn(n, k, |i, j| ((i * 3 + j * 7) % 13) as f64 - 6.0);
            let b = Mat::from_fn(n, m, |i, j| ((i * 5 + j) % 7) as f64 - 3.0);
            let mut g = Mat::zeros(k, m);
            gram(g.as_mut(), a.as_ref(), b.as_ref());
            let want = a.transpose() * &b;
            assert!((&g - &want).norm_max() < 1e-9 * want.norm_max().max(1.0));
            let c = Mat::from_fn(k, m, |i, j| (i + 2 * j) as f64 * 0.25);
            let mut out = b.clone();
            mul(out.as_mut(), Accum::Add, a.as_ref(), c.as_ref(), -1.0);
            let want = &b - &a * &c;
            assert!((&out - &want).norm_max() < 1e-9 * want.norm_max().max(1.0));
            let s = Mat::from_fn(k, k - 1, |i, j| ((i * j) % 5) as f64 - 2.0);
            let mut v = a.clone();
            rotate_in_place(v.as_mut(), s.as_ref());
            let want = &a * &s;
            assert!((v.as_ref().subcols(0, k - 1) - &want).norm_max() < 1e-9 * want.norm_max().max(1.0));
        }
    }
}
