//! `w (+)= alpha v c` for a tall `v` (n x t) and a narrow `c` (t x m, m
//! up to 32) with AVX-512: the update of a block by the Krylov basis in
//! every orthogonalization.
//!
//! faer packs `v` into panels and runs a kernel tuned for products of
//! every shape; here the output has a few dozen columns and `v` hundreds,
//! and a tile of 24 rows by 8 output columns is kept in 24 registers while
//! the columns of `v` pass: per column of `v`, three loads, eight
//! broadcasts of `c` and 24 multiply-adds. `v` is read where it is (no
//! copy), the next tile's rows asked for ahead. Measured on one core of an
//! Intel Xeon (AVX-512) VM at 470,274 rows, `v` 504 columns and `c` 32:
//! 40-41 GFlop/s against faer's 27-31 by chunks of rows; `c` 8 columns
//! wide, 15.7-16.6 against 8.7-9.2. With 40 columns in `v` faer was as
//! fast or faster (28 against 31 GFlop/s, 100 columns: 33 against 32), so
//! products shallower than [`MIN_DEPTH`] stay with faer; so do those wider
//! than [`MAX_WIDTH`], where faer's kernel, which reuses each value of `v`
//! across many more columns, ran at 55-68 GFlop/s against 36-53 (`v` 436
//! columns, `c` 240).

use faer::{MatMut, MatRef};

/// Fewest columns of `v` for which the kernel is used.
pub(crate) const MIN_DEPTH: usize = 80;

/// Most columns of `c` for which the kernel is used.
pub(crate) const MAX_WIDTH: usize = 32;

/// Output columns per tile (one register of 8 values per row group).
const COLS: usize = 8;

/// `alpha c` row by row (`t x m`, each row padded with zeros to a
/// multiple of 8 values), ready for [`apply`].
pub(crate) struct Coefficients {
    rows: Vec<f64>,
    depth: usize,
    width: usize,
    /// `width` rounded up to a multiple of [`COLS`]: the length of a row.
    padded: usize,
}

impl Coefficients {
    /// `None` where the kernel does not apply: no AVX-512, `c` without
    /// columns, wider than [`MAX_WIDTH`] or shallower than [`MIN_DEPTH`].
    pub(crate) fn new(c: MatRef<'_, f64>, alpha: f64) -> Option<Self> {
        let (depth, width) = (c.nrows(), c.ncols());
        if !available() || width == 0 || width > MAX_WIDTH || depth < MIN_DEPTH {
            return None;
        }
        let padded = width.next_multiple_of(COLS);
        let rows = (0..depth)
            .flat_map(|i| (0..padded).map(move |j| if j < width { alpha * c[(i, j)] } else { 0.0 }))
            .collect();
        Some(Self { rows, depth, width, padded })
    }
}

fn available() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("avx512f")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// `out (+)= v c` with `c` from [`Coefficients::new`] (`alpha` included);
/// `false` (nothing written) when the shapes do not match or a column of
/// `out` or `v` is not contiguous.
pub(crate) fn apply(out: MatMut<'_, f64>, add: bool, v: MatRef<'_, f64>, c: &Coefficients) -> bool {
    let n = out.nrows();
    let fits = v.nrows() == n && v.ncols() == c.depth && out.ncols() == c.width;
    let contiguous = |rows: isize, cols: isize| (rows == 1 || n <= 1) && cols >= n.max(1) as isize;
    if fits && n == 0 {
        return true;
    }
    if !fits || !contiguous(out.row_stride(), out.col_stride()) || !contiguous(v.row_stride(), v.col_stride()) {
        return false;
    }
    #[cfg(target_arch = "x86_64")]
    {
        let (ldw, ldv) = (out.col_stride() as usize, v.col_stride() as usize);
        let (w, v) = (out.as_ptr_mut(), v.as_ptr());
        // SAFETY: `Coefficients` exists only where the CPU has AVX-512;
        // `out` (n x width) and `v` (n x depth) have unit row strides and
        // column strides `ldw`, `ldv` of at least n, so every element
        // `w + r + j ldw` (r < n, j < width) and `v + r + i ldv` (i < depth)
        // the kernel touches lies in them, and `out` is borrowed mutably.
        unsafe {
            if add {
                product::<true>(w, ldw, v, ldv, c, n)
            } else {
                product::<false>(w, ldw, v, ldv, c, n)
            }
        };
        true
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// Tiles of 24 rows, then of 8, then the last rows one by one.
///
/// # Safety
/// AVX-512F; `w` and `v` as in [`apply`].
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
unsafe fn product<const ADD: bool>(w: *mut f64, ldw: usize, v: *const f64, ldv: usize, c: &Coefficients, n: usize) {
    let (t, m, stride, ct) = (c.depth, c.width, c.padded, c.rows.as_ptr());
    let mut r0 = 0;
    while r0 + 24 <= n {
        for j0 in (0..m).step_by(COLS) {
            let cols = (m - j0).min(COLS);
            tile::<3, ADD>(w.add(r0 + j0 * ldw), ldw, cols, v.add(r0), ldv, ct.add(j0), stride, t, j0 == 0);
        }
        r0 += 24;
    }
    while r0 + 8 <= n {
        for j0 in (0..m).step_by(COLS) {
            let cols = (m - j0).min(COLS);
            tile::<1, ADD>(w.add(r0 + j0 * ldw), ldw, cols, v.add(r0), ldv, ct.add(j0), stride, t, false);
        }
        r0 += 8;
    }
    for r in r0..n {
        for j in 0..m {
            let mut s = 0.0;
            for i in 0..t {
                s += *v.add(r + i * ldv) * *ct.add(i * stride + j);
            }
            let out = w.add(r + j * ldw);
            *out = if ADD { *out + s } else { s };
        }
    }
}

/// One tile: `w[.. 8 R, .. cols] (+)= v[.. 8 R, .. t] ct[.. t, .. cols]`
/// (`cols` at most 8), with `ct`'s rows `stride` apart and 8 values long
/// (zeros past `cols`); `ahead` asks for the next tile's rows of `v` (into
/// L2) and of `w` (into L1) while this one is computed.
///
/// # Safety
/// AVX-512F; `8 R` rows of `cols` columns of `w` (stride `ldw`) readable
/// and writable, of `t` columns of `v` (stride `ldv`) readable, `t` rows
/// of 8 values of `ct`.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
#[inline]
unsafe fn tile<const R: usize, const ADD: bool>(
    w: *mut f64,
    ldw: usize,
    cols: usize,
    v: *const f64,
    ldv: usize,
    ct: *const f64,
    stride: usize,
    t: usize,
    ahead: bool,
) {
    use std::arch::x86_64::*;
    let mut acc = [[_mm512_setzero_pd(); COLS]; R];
    for i in 0..t {
        let col = v.add(i * ldv);
        let a: [__m512d; R] = std::array::from_fn(|r| _mm512_loadu_pd(col.add(8 * r)));
        if ahead {
            for r in 0..R {
                _mm_prefetch::<_MM_HINT_T1>(col.wrapping_add(8 * (R + r)).cast::<i8>());
            }
        }
        let coef = ct.add(i * stride);
        for j in 0..COLS {
            let cj = _mm512_set1_pd(*coef.add(j));
            for r in 0..R {
                acc[r][j] = _mm512_fmadd_pd(a[r], cj, acc[r][j]);
            }
        }
    }
    // A constant bound and a test inside, so that the loop unrolls and
    // the accumulators stay in registers.
    for j in 0..COLS {
        if j >= cols {
            break;
        }
        let out = w.add(j * ldw);
        if ahead {
            for r in 0..R {
                _mm_prefetch::<_MM_HINT_T0>(out.wrapping_add(8 * (R + r)).cast::<i8>());
            }
        }
        for r in 0..R {
            let p = out.add(8 * r);
            let x = if ADD { _mm512_add_pd(_mm512_loadu_pd(p), acc[r][j]) } else { acc[r][j] };
            _mm512_storeu_pd(p, x);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::Mat;

    #[test]
    fn matches_the_plain_product_on_every_row_remainder() {
        let Some(_) = Coefficients::new(Mat::<f64>::zeros(MIN_DEPTH, 8).as_ref(), 1.0) else {
            return; // no AVX-512 here: faer does these products
        };
        let d = MIN_DEPTH;
        for (n, t, m) in
            [(0, d, 8), (7, d, 5), (8, d + 6, 16), (31, d, 8), (100, d + 1, 21), (1000, 130, 32), (57, d, 27)]
        {
            let v = Mat::from_fn(n + 3, t, |i, j| ((i * 7 + j * 3) % 11) as f64 - 5.0);
            let v = v.as_ref().subrows(2, n);
            let c = Mat::from_fn(t, m, |i, j| ((i + 2 * j) % 5) as f64 * 0.25 - 0.5);
            let start = Mat::from_fn(n, m, |i, j| ((i * 5 + j) % 7) as f64 - 3.0);
            let k = Coefficients::new(c.as_ref(), -2.0).unwrap();
            for add in [true, false] {
                let mut out = start.clone();
                assert!(apply(out.as_mut(), add, v, &k));
                let product = v * &c * faer::Scale(-2.0);
                let expect = if add { &start + &product } else { product };
                let err =
                    (0..m).flat_map(|j| (0..n).map(move |i| (i, j))).map(|(i, j)| (out[(i, j)] - expect[(i, j)]).abs());
                assert!(err.fold(0.0, f64::max) < 1e-9, "n {n} t {t} m {m} add {add}");
            }
        }
        let c = Mat::<f64>::zeros(d, 8);
        let k = Coefficients::new(c.as_ref(), 1.0).unwrap();
        let v = Mat::<f64>::zeros(10, d);
        assert!(!apply(Mat::zeros(10, 16).as_mut(), true, v.as_ref(), &k));
        assert!(!apply(Mat::zeros(9, 8).as_mut(), true, v.as_ref(), &k));
        let rows = Mat::<f64>::zeros(d, 10);
        assert!(!apply(Mat::zeros(10, 8).as_mut(), true, rows.as_ref().transpose(), &k));
        assert!(Coefficients::new(Mat::<f64>::zeros(d - 1, 8).as_ref(), 1.0).is_none());
        assert!(Coefficients::new(Mat::<f64>::zeros(d, 0).as_ref(), 1.0).is_none());
        assert!(Coefficients::new(Mat::<f64>::zeros(d, MAX_WIDTH + 1).as_ref(), 1.0).is_none());
    }
}
