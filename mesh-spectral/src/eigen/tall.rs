//! Products of tall-skinny matrices (n rows, tens to hundreds of columns),
//! split by rows across threads.
//!
//! faer parallelizes a product over its (small) output, which for
//! `V^T W` with `V` n x 400 and `W` n x 8 leaves the threads fighting over
//! a 400 x 8 result; measured on a 2-core x86-64 VM it ran 5-8 times slower
//! than one thread. Splitting the long dimension instead gives each thread a
//! contiguous slab of rows and a sequential faer kernel; partial Gram
//! matrices are summed at the end.
//!
//! Within a slab the rows go to the kernels in chunks:
//! - `V^T W` by chunks of [`GRAM_ROWS`] rows, as `(W^T V)^T` (faer's
//!   kernel is faster with the narrow factor on the left);
//! - `W (+)= V C` to the AVX-512 kernel of [`super::tile`] where it
//!   applies, otherwise to faer in chunks whose part of the wide factor
//!   fits in a core's L2 cache ([`chunk_rows`]): on 40,962 rows, with V
//!   480 columns wide and W 32, faer given the whole height ran at 19
//!   GFlop/s on one core (Intel Xeon, Emerald Rapids), given chunks of
//!   128 rows at 41.

use std::borrow::Cow;

use faer::linalg::matmul::matmul;
use faer::reborrow::{Reborrow, ReborrowMut};
use faer::{Accum, Mat, MatMut, MatRef, Par};

use super::{narrow, tile};

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

/// Column j of `q` as a slice (copied only if it is not contiguous).
pub(crate) fn column<'a>(q: MatRef<'a, f64>, j: usize) -> Cow<'a, [f64]> {
    match q.col(j).try_as_col_major() {
        Some(c) => Cow::Borrowed(c.as_slice()),
        None => Cow::Owned(q.col(j).iter().copied().collect()),
    }
}

/// Rows per call of faer's kernel: about 512 KiB of a `width`-column
/// factor, between 128 and 4096 rows.
fn chunk_rows(width: usize) -> usize {
    ((1 << 16) / width.max(1)).clamp(128, 4096)
}

/// Rows per chunk of [`mul_gram`] with the AVX-512 kernel: whole tiles of
/// 24 rows, the chunk's output (240 KiB at 32 columns) still in L2
/// for its Gram matrix.
const TILE_ROWS: usize = 960;

/// Rows per call of faer's kernel in [`gram_seq`].
const GRAM_ROWS: usize = 1024;

/// `out = a^T b` on one thread, by chunks of [`GRAM_ROWS`] rows, as
/// `(b^T a)^T` when `b` is the narrower: faer's kernel runs faster with
/// the narrow factor on the left. Measured on one core of an Intel Xeon
/// (AVX-512) VM, `V^T W` with `W` 32 columns wide: at 470,274 rows and
/// `V` 504 columns 35.5 GFlop/s as `V^T W` by chunks of 130 rows, 31.0
/// as `(W^T V)^T` by 128, 51.9 by 1024; at 40,962 rows and 100 columns
/// 42.1 against 57.0; never slower on the widths 8 to 32 and bases of
/// 40 to 504 columns measured, the same for square products.
fn gram_seq(mut out: MatMut<'_, f64>, a: MatRef<'_, f64>, b: MatRef<'_, f64>) {
    if narrow::gram(out.rb_mut(), a, b) {
        return;
    }
    let n = a.nrows();
    let transposed = b.ncols() < a.ncols();
    let mut flipped = Mat::zeros(if transposed { b.ncols() } else { 0 }, if transposed { a.ncols() } else { 0 });
    out.fill(0.0);
    for r0 in (0..n).step_by(GRAM_ROWS) {
        let len = GRAM_ROWS.min(n - r0);
        let (a, b) = (a.subrows(r0, len), b.subrows(r0, len));
        if transposed {
            matmul(flipped.as_mut(), Accum::Add, b.transpose(), a, 1.0, Par::Seq);
        } else {
            matmul(out.rb_mut(), Accum::Add, a.transpose(), b, 1.0, Par::Seq);
        }
    }
    if transposed {
        out.copy_from(flipped.transpose());
    }
}

/// `out (+)= alpha a c` on one thread, by chunks of rows.
fn mul_seq(mut out: MatMut<'_, f64>, accum: Accum, a: MatRef<'_, f64>, c: MatRef<'_, f64>, alpha: f64) {
    let add = matches!(accum, Accum::Add);
    if narrow::mul(out.rb_mut(), add, a, c, alpha, None) {
        return;
    }
    if tile::Coefficients::new(c, alpha).is_some_and(|k| tile::apply(out.rb_mut(), add, a, &k)) {
        return;
    }
    let (n, chunk) = (a.nrows(), chunk_rows(a.ncols()));
    for r0 in (0..n).step_by(chunk) {
        let len = chunk.min(n - r0);
        matmul(out.rb_mut().subrows_mut(r0, len), accum, a.subrows(r0, len), c, alpha, Par::Seq);
    }
}

/// `out = sum over slabs of part(rows, slab's out)` (out: k x m), the
/// slabs of `n` rows on the threads when `work` multiply-adds call for it;
/// `part` overwrites its output with the slab's share.
fn sum_over_slabs(
    mut out: MatMut<'_, f64>,
    n: usize,
    work: usize,
    part: impl Fn(std::ops::Range<usize>, MatMut<'_, f64>) + Sync,
) {
    let parts = slabs(n, work);
    #[cfg(feature = "rayon")]
    if parts > 1 {
        use rayon::prelude::*;
        let (k, m, rows) = (out.nrows(), out.ncols(), n.div_ceil(parts));
        let sum = (0..parts)
            .into_par_iter()
            .map(|p| {
                let mut share = Mat::zeros(k, m);
                part(n.min(p * rows)..n.min((p + 1) * rows), share.as_mut());
                share
            })
            .reduce(|| Mat::zeros(k, m), |x, y| x + y);
        out.copy_from(&sum);
        return;
    }
    let _ = parts;
    part(0..n, out.rb_mut());
}

/// `out = a^T b` (a: n x k, b: n x m, out: k x m).
pub(crate) fn gram(out: MatMut<'_, f64>, a: MatRef<'_, f64>, b: MatRef<'_, f64>) {
    let n = a.nrows();
    sum_over_slabs(out, n, n * a.ncols() * b.ncols(), |r, share| {
        gram_seq(share, a.subrows(r.start, r.len()), b.subrows(r.start, r.len()));
    });
}

/// `out = a^T diag(w) a` (a: n x k, w: n weights, out: k x k), without
/// forming `diag(w) a`: each chunk of rows is weighted in a small buffer.
pub(crate) fn gram_weighted(out: MatMut<'_, f64>, a: MatRef<'_, f64>, w: &[f64]) {
    let (n, k) = (a.nrows(), a.ncols());
    debug_assert_eq!(w.len(), n, "one weight per row");
    sum_over_slabs(out, n, n * k * k, |rows, mut share| {
        let chunk = chunk_rows(k);
        let mut weighted = Mat::zeros(chunk.min(rows.len()), k);
        share.fill(0.0);
        for r0 in rows.clone().step_by(chunk) {
            let len = chunk.min(rows.end - r0);
            let mut buf = weighted.as_mut().subrows_mut(0, len);
            for j in 0..k {
                let (src, dst) = (a.col(j).subrows(r0, len), buf.rb_mut().col_mut(j));
                for ((d, s), wi) in dst.iter_mut().zip(src.iter()).zip(&w[r0..r0 + len]) {
                    *d = s * wi;
                }
            }
            matmul(share.rb_mut(), Accum::Add, a.subrows(r0, len).transpose(), buf.rb(), 1.0, Par::Seq);
        }
    });
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
            mul_seq(o, accum, a, c, alpha);
        });
        return;
    }
    let _ = parts;
    mul_seq(out, accum, a, c, alpha);
}

/// [`mul`], and `gram = out^T out` of the result, each chunk of rows added
/// to the Gram matrix while it is still in cache (one pass over `out` less
/// than [`mul`] then [`gram`]).
pub(crate) fn mul_gram(
    out: MatMut<'_, f64>,
    accum: Accum,
    a: MatRef<'_, f64>,
    c: MatRef<'_, f64>,
    alpha: f64,
    mut gram: MatMut<'_, f64>,
) {
    let (n, m) = (a.nrows(), c.ncols());
    let parts = slabs(n, n * a.ncols() * m);
    let add = matches!(accum, Accum::Add);
    let coefficients = tile::Coefficients::new(c, alpha);
    let slab = |mut out: MatMut<'_, f64>, a: MatRef<'_, f64>, mut share: MatMut<'_, f64>| {
        if narrow::mul(out.rb_mut(), add, a, c, alpha, Some(share.rb_mut())) {
            return;
        }
        let chunk = if coefficients.is_some() { TILE_ROWS } else { chunk_rows(a.ncols()) };
        share.fill(0.0);
        for r0 in (0..a.nrows()).step_by(chunk) {
            let len = chunk.min(a.nrows() - r0);
            let mut o = out.rb_mut().subrows_mut(r0, len);
            let a = a.subrows(r0, len);
            if !coefficients.as_ref().is_some_and(|k| tile::apply(o.rb_mut(), add, a, k)) {
                matmul(o.rb_mut(), accum, a, c, alpha, Par::Seq);
            }
            matmul(share.rb_mut(), Accum::Add, o.rb().transpose(), o.rb(), 1.0, Par::Seq);
        }
    };
    #[cfg(feature = "rayon")]
    if parts > 1 {
        use rayon::prelude::*;
        let sum = out
            .par_row_partition_mut(parts)
            .zip(a.par_row_partition(parts))
            .map(|(o, a)| {
                let mut share = Mat::zeros(m, m);
                slab(o, a, share.as_mut());
                share
            })
            .reduce(|| Mat::zeros(m, m), |x, y| x + y);
        gram.copy_from(&sum);
        return;
    }
    let _ = parts;
    slab(out, a, gram);
}

/// `v[:, ..p] = v S` in place (v: n x s, S: s x p, p <= s), by chunks of
/// 256 rows so that only a small buffer is needed. (With 512 rows, whose
/// buffer columns are 4 KiB apart, faer's kernel ran at 52-55 GFlop/s on
/// one core for `S` 436 x 240 and 69-71 for 536 x 336 or 300 x 200, with
/// 256 rows at 68-70 on all three.)
pub(crate) fn rotate_in_place(v: MatMut<'_, f64>, s: MatRef<'_, f64>) {
    let n = v.nrows();
    let parts = slabs(n, n * s.nrows() * s.ncols());
    let rotate = |mut slab: MatMut<'_, f64>| {
        const CHUNK: usize = 256;
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
            let w: Vec<f64> = (0..n).map(|i| (i % 9) as f64 * 0.5).collect();
            let mut g = Mat::zeros(k, k);
            gram_weighted(g.as_mut(), a.as_ref(), &w);
            let want = a.transpose() * Mat::from_fn(n, k, |i, j| w[i] * a[(i, j)]);
            assert!((&g - &want).norm_max() < 1e-9 * want.norm_max().max(1.0));
            let mut out = b.clone();
            let mut g = Mat::zeros(m, m);
            mul_gram(out.as_mut(), Accum::Add, a.as_ref(), c.as_ref(), -1.0, g.as_mut());
            let want = &b - &a * &c;
            assert!((&out - &want).norm_max() < 1e-9 * want.norm_max().max(1.0));
            let want = want.transpose() * &want;
            assert!((&g - &want).norm_max() < 1e-9 * want.norm_max().max(1.0));
            let s = Mat::from_fn(k, k - 1, |i, j| ((i * j) % 5) as f64 - 2.0);
            let mut v = a.clone();
            rotate_in_place(v.as_mut(), s.as_ref());
            let want = &a * &s;
            assert!((v.as_ref().subcols(0, k - 1) - &want).norm_max() < 1e-9 * want.norm_max().max(1.0));
        }
    }
}
