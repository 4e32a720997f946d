//! Products of a tall matrix with a narrow one (at most [`WIDEST`]
//! columns) on one thread: `a^T b` and `a c`, `a` n x k with contiguous
//! columns, the narrow side `b` or the output n x m with `m <= 4`.
//!
//! These are the products of the Krylov basis with a block of 4 vectors
//! (the eigensolver's block for up to 28 pairs) and of the harmonics with
//! 3 coordinates. They are bound by reading `a`, which a general matrix
//! product does not reach: faer copies `a` into its packed panels first.
//! Measured on one core of an AMD EPYC (Zen 3) VM at 470,274 rows, k = 35
//! and 4 narrow columns: `a^T b` 7.6-7.9 ms here against 10.3-10.5 with
//! faer, `w += a c` 10.4-12.5 ms against 17.4-20.8. Each chunk of [`ROWS`]
//! rows of the narrow side is kept in a local buffer that stays in L1 or
//! L2 while the columns of `a` stream past it, several at a time. From 5
//! narrow columns on, faer's kernel was as fast (8 columns: 21-23 ms
//! against 21, 14-15 against 13-14), and these products go to it.

use faer::reborrow::{Reborrow, ReborrowMut};
use faer::{MatMut, MatRef};

/// Most columns of the narrow side.
pub(crate) const WIDEST: usize = 4;

/// Rows of a chunk: its narrow side (at most `ROWS x 4` values, 32 KiB)
/// stays in L1 while the columns of `a` pass; 256 rows (more streams of
/// `a` open at once) ran `a^T b` at 13 GB/s against 17-18.
const ROWS: usize = 1024;

/// The columns of `a` as slices; `None` when one is not contiguous.
fn columns<'a>(a: MatRef<'a, f64>) -> Option<Vec<&'a [f64]>> {
    (0..a.ncols()).map(|j| a.col(j).try_as_col_major().map(|c| c.as_slice())).collect()
}

/// `out = a^T b` (a: n x k, b: n x m, out: k x m) when `b` is narrow and
/// both have contiguous columns; `false` (and `out` untouched) otherwise.
pub(crate) fn gram(out: MatMut<'_, f64>, a: MatRef<'_, f64>, b: MatRef<'_, f64>) -> bool {
    if b.ncols() > WIDEST {
        return false;
    }
    let (Some(a_cols), Some(b_cols)) = (columns(a), columns(b)) else { return false };
    macro_rules! by_width {
        ($($m:literal => $l:literal, $g:literal);*) => {
            match b.ncols() {
                $($m => gram_dispatch::<$m, $l, $g>(out, &a_cols, &b_cols, a.nrows()),)*
                _ => return false,
            }
        };
    }
    by_width!(1 => 1, 8; 2 => 2, 8; 3 => 4, 8; 4 => 4, 8);
    true
}

/// `out (+)= alpha a c` (a: n x k, c: k x m, out: n x m), and with
/// `gram` the Gram matrix `out^T out` of the result, when the output is
/// narrow and it and `a` have contiguous columns; `false` (and nothing
/// written) otherwise.
pub(crate) fn mul(
    out: MatMut<'_, f64>,
    add: bool,
    a: MatRef<'_, f64>,
    c: MatRef<'_, f64>,
    alpha: f64,
    gram: Option<MatMut<'_, f64>>,
) -> bool {
    if out.ncols() > WIDEST || (0..out.ncols()).any(|j| out.rb().col(j).try_as_col_major().is_none()) {
        return false;
    }
    let Some(a_cols) = columns(a) else { return false };
    macro_rules! by_width {
        ($($m:literal => $g:literal),*) => {
            match out.ncols() {
                $($m => mul_dispatch::<$m, $g>(out, add, &a_cols, c, alpha, gram),)*
                _ => return false,
            }
        };
    }
    by_width!(1 => 8, 2 => 8, 3 => 4, 4 => 4);
    true
}

fn gram_dispatch<const M: usize, const L: usize, const G: usize>(
    mut out: MatMut<'_, f64>,
    a: &[&[f64]],
    b: &[&[f64]],
    n: usize,
) {
    let b: [&[f64]; M] = std::array::from_fn(|m| b[m]);
    let mut sums = vec![[0.0; L]; a.len()];
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU supports AVX2, checked just above.
        unsafe { gram_avx2::<M, L, G>(&mut sums, a, &b, n) };
    } else {
        gram_portable::<M, L, G>(&mut sums, a, &b, n);
    }
    #[cfg(not(target_arch = "x86_64"))]
    gram_portable::<M, L, G>(&mut sums, a, &b, n);
    for (j, row) in sums.iter().enumerate() {
        for (m, &v) in row.iter().enumerate().take(M) {
            out[(j, m)] = v;
        }
    }
}

/// [`gram_portable`] compiled for AVX2 (same operations in the same order).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn gram_avx2<const M: usize, const L: usize, const G: usize>(
    sums: &mut [[f64; L]],
    a: &[&[f64]],
    b: &[&[f64]; M],
    n: usize,
) {
    gram_portable::<M, L, G>(sums, a, b, n);
}

/// `sums[j] = sum_i a_j[i] b[i]`: per chunk of rows, `b`'s rows gathered
/// into a buffer of `L >= M` lanes (the lanes past `M` stay zero, so that
/// a row is whole vector registers), then `G` columns of `a` at a time
/// against it (`G` independent sums hide the latency of the additions).
#[inline(always)]
fn gram_portable<const M: usize, const L: usize, const G: usize>(
    sums: &mut [[f64; L]],
    a: &[&[f64]],
    b: &[&[f64]; M],
    n: usize,
) {
    let mut buf = [[0.0; L]; ROWS];
    for r0 in (0..n).step_by(ROWS) {
        let len = ROWS.min(n - r0);
        let rows = &mut buf[..len];
        for (m, col) in b.iter().enumerate() {
            for (row, &v) in rows.iter_mut().zip(&col[r0..r0 + len]) {
                row[m] = v;
            }
        }
        let rows = &buf[..len];
        let mut j = 0;
        macro_rules! groups {
            ($($g:tt),*) => {$(
                while a.len() - j >= $g {
                    add_gram::<L, $g>(&mut sums[j..j + $g], std::array::from_fn(|g| &a[j + g][r0..r0 + len]), rows);
                    j += $g;
                }
            )*};
        }
        groups!(G, 4, 2, 1);
    }
}

/// `sums[g] += sum_i cols[g][i] rows[i]`.
#[inline(always)]
fn add_gram<const M: usize, const G: usize>(sums: &mut [[f64; M]], cols: [&[f64]; G], rows: &[[f64; M]]) {
    let len = rows.len();
    assert!(sums.len() == G && cols.iter().all(|c| c.len() == len));
    let mut acc = [[0.0; M]; G];
    for i in 0..len {
        let row = rows[i];
        for g in 0..G {
            let x = cols[g][i];
            for m in 0..M {
                acc[g][m] += x * row[m];
            }
        }
    }
    for (s, a) in sums.iter_mut().zip(&acc) {
        for m in 0..M {
            s[m] += a[m];
        }
    }
}

fn mul_dispatch<const M: usize, const G: usize>(
    mut out: MatMut<'_, f64>,
    add: bool,
    a: &[&[f64]],
    c: MatRef<'_, f64>,
    alpha: f64,
    gram: Option<MatMut<'_, f64>>,
) {
    let n = out.nrows();
    // Per output column, the coefficients of the columns of `a` scaled by
    // alpha.
    let coef: [Vec<f64>; M] = std::array::from_fn(|m| (0..a.len()).map(|j| alpha * c[(j, m)]).collect());
    let mut outs: Vec<&mut [f64]> = Vec::with_capacity(M);
    let mut rest = out.rb_mut();
    for _ in 0..M {
        let (first, tail) = rest.split_at_col_mut(1);
        // Checked contiguous by the caller.
        outs.push(first.col_mut(0).try_as_col_major_mut().map(|c| c.as_slice_mut()).unwrap_or_default());
        rest = tail;
    }
    let Ok(mut outs) = <[&mut [f64]; M]>::try_from(outs) else { return };
    let mut g = [[0.0; M]; M];
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU supports AVX2, checked just above.
        unsafe { mul_avx2::<M, G>(&mut outs, add, a, &coef, gram.is_some().then_some(&mut g), n) };
    } else {
        mul_portable::<M, G>(&mut outs, add, a, &coef, gram.is_some().then_some(&mut g), n);
    }
    #[cfg(not(target_arch = "x86_64"))]
    mul_portable::<M, G>(&mut outs, add, a, &coef, gram.is_some().then_some(&mut g), n);
    if let Some(mut gram) = gram {
        for (i, row) in g.iter().enumerate() {
            for (j, &v) in row.iter().enumerate() {
                gram[(i, j)] = v;
            }
        }
    }
}

/// [`mul_portable`] compiled for AVX2 (same operations in the same order).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn mul_avx2<const M: usize, const G: usize>(
    outs: &mut [&mut [f64]; M],
    add: bool,
    a: &[&[f64]],
    coef: &[Vec<f64>; M],
    gram: Option<&mut [[f64; M]; M]>,
    n: usize,
) {
    mul_portable::<M, G>(outs, add, a, coef, gram, n);
}

/// `outs (+)= sum_j a_j coef[.][j]`, per chunk of rows in a buffer of the
/// chunk's output columns (a local array, which the compiler knows no
/// other slice aliases, so the rows are done four or eight at a time), `G`
/// columns of `a` at a time; the chunk's share of the Gram matrix of the
/// result is added while it is in the buffer.
#[inline(always)]
fn mul_portable<const M: usize, const G: usize>(
    outs: &mut [&mut [f64]; M],
    add: bool,
    a: &[&[f64]],
    coef: &[Vec<f64>; M],
    mut gram: Option<&mut [[f64; M]; M]>,
    n: usize,
) {
    let mut buf = [[0.0; ROWS]; M];
    for r0 in (0..n).step_by(ROWS) {
        let len = ROWS.min(n - r0);
        for (b, col) in buf.iter_mut().zip(outs.iter()) {
            if add {
                b[..len].copy_from_slice(&col[r0..r0 + len]);
            } else {
                b[..len].fill(0.0);
            }
        }
        let mut j = 0;
        macro_rules! groups {
            ($($g:tt),*) => {$(
                while a.len() - j >= $g {
                    let k: [[f64; $g]; M] = std::array::from_fn(|m| std::array::from_fn(|g| coef[m][j + g]));
                    add_products::<M, $g>(&mut buf, len, std::array::from_fn(|g| &a[j + g][r0..r0 + len]), &k);
                    j += $g;
                }
            )*};
        }
        groups!(G, 4, 2, 1);
        for (b, col) in buf.iter().zip(outs.iter_mut()) {
            col[r0..r0 + len].copy_from_slice(&b[..len]);
        }
        if let Some(g) = gram.as_deref_mut() {
            for p in 0..M {
                for q in p..M {
                    let d = dot(&buf[p][..len], &buf[q][..len]);
                    g[p][q] += d;
                    if q != p {
                        g[q][p] += d;
                    }
                }
            }
        }
    }
}

/// `buf[m][i] += sum_g cols[g][i] k[m][g]` for the first `len` rows.
#[inline(always)]
fn add_products<const M: usize, const G: usize>(
    buf: &mut [[f64; ROWS]; M],
    len: usize,
    cols: [&[f64]; G],
    k: &[[f64; G]; M],
) {
    assert!(len <= ROWS && cols.iter().all(|c| c.len() == len));
    for i in 0..len {
        let x: [f64; G] = std::array::from_fn(|g| cols[g][i]);
        for m in 0..M {
            let mut s = 0.0;
            for g in 0..G {
                s += x[g] * k[m][g];
            }
            buf[m][i] += s;
        }
    }
}

/// A dot product with four sums: vectorizes, and is less sensitive to
/// cancellation than one.
#[inline(always)]
pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut acc = [0.0; 4];
    let (ca, ra) = a.split_at(a.len() / 4 * 4);
    let (cb, rb) = b.split_at(ca.len());
    for (x, y) in ca.chunks_exact(4).zip(cb.chunks_exact(4)) {
        for k in 0..4 {
            acc[k] += x[k] * y[k];
        }
    }
    let tail: f64 = ra.iter().zip(rb).map(|(x, y)| x * y).sum();
    acc[0] + acc[1] + acc[2] + acc[3] + tail
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::Mat;

    #[test]
    fn narrow_products_match_faer() {
        for (n, k, m) in [(5, 3, 1), (700, 11, 4), (2100, 9, 2), (513, 2, 3)] {
            let a = Mat::from_fn(n, k, |i, j| ((i * 3 + j * 7) % 13) as f64 - 6.0);
            let b = Mat::from_fn(n, m, |i, j| ((i * 5 + j) % 7) as f64 - 3.0);
            let mut g = Mat::zeros(k, m);
            assert!(gram(g.as_mut(), a.as_ref(), b.as_ref()));
            let want = a.transpose() * &b;
            assert!((&g - &want).norm_max() < 1e-9 * want.norm_max().max(1.0), "{n} {k} {m}");
            let c = Mat::from_fn(k, m, |i, j| (i + 2 * j) as f64 * 0.25);
            for add in [false, true] {
                let mut out = b.clone();
                let mut gg = Mat::zeros(m, m);
                assert!(mul(out.as_mut(), add, a.as_ref(), c.as_ref(), -1.5, Some(gg.as_mut())));
                let want = if add { &b - (&a * &c) * 1.5 } else { (&a * &c) * -1.5 };
                assert!((&out - &want).norm_max() < 1e-9 * want.norm_max().max(1.0), "{n} {k} {m} {add}");
                let wg = want.transpose() * &want;
                assert!((&gg - &wg).norm_max() < 1e-9 * wg.norm_max().max(1.0));
            }
        }
        // Too wide, or not contiguous: left to the caller.
        let a = Mat::<f64>::zeros(10, 3);
        let wide = Mat::<f64>::zeros(10, 5);
        assert!(!gram(Mat::zeros(3, 5).as_mut(), a.as_ref(), wide.as_ref()));
        assert!(!mul(Mat::zeros(10, 5).as_mut(), true, a.as_ref(), Mat::zeros(3, 5).as_ref(), 1.0, None));
        let rows = Mat::<f64>::zeros(2, 10);
        assert!(!gram(Mat::zeros(3, 2).as_mut(), a.as_ref(), rows.as_ref().transpose()));
    }
}
