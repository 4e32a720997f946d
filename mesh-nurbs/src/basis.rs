//! B-spline basis functions `N_{i,k}(u)` by the Cox-de Boor recursion of
//! eq. 2.1-2.2 of the chapter, and their derivatives.
//!
//! On a knot span `[t_s, t_{s+1})` only the `p + 1` functions
//! `N_{s-p,p}, ..., N_{s,p}` are non-zero (local support). The span argument
//! of the functions here is meant to come from [`KnotVector::span`]; other
//! values are clamped into `p..=n` (wrong results, never a panic). The functions here
//! compute all of them in one triangular pass into fixed-size arrays of
//! [`MAX_DEGREE`]` + 1` entries (entry `j` holds `N_{s-p+j,p}`), so the hot
//! path never allocates.

use crate::error::{NurbsError, Result};
use crate::knots::KnotVector;

/// Largest supported degree. Fixed-size stack arrays of `MAX_DEGREE + 1`
/// entries hold the non-zero basis functions of one span; 7 keeps them small
/// enough to be moved without a `memcpy` call in the hot path (measured: the
/// bicubic point with tangents runs twice as fast as with room for degree 11),
/// and is above the degrees CAD data uses (rarely more than 5).
pub const MAX_DEGREE: usize = 7;

/// Capacity of the per-span arrays: `MAX_DEGREE + 1`.
pub const CAP: usize = MAX_DEGREE + 1;

/// One basis function `N_{i,p}(u)` straight from the recursion of eq. 2.1-2.2,
/// with `0/0` taken as `0`, evaluated as a triangular table over the degree
/// (Piegl & Tiller A2.4). At the last knot of the domain the step functions of
/// eq. 2.1 are closed on the right for the last non-empty span, so that the
/// basis still sums to one there. Returns 0 for `i` beyond the last function.
/// Parameters are clamped into the domain. Cost O(p^2). Meant as a reference;
/// [`basis_values`] gives all non-zero functions at once.
pub fn basis_function(kv: &KnotVector, i: usize, u: f64) -> f64 {
    let p = kv.degree();
    let t = kv.knots();
    if i >= kv.control_count() {
        return 0.0;
    }
    let u = kv.clamp(u);
    let last = kv.span(kv.domain().1);
    let at_end = u >= kv.domain().1;
    // Degree-0 functions N_{i+j,0}, j = 0..=p (eq. 2.1).
    let mut n = [0.0; CAP];
    for j in 0..=p {
        let k = i + j;
        let inside = t[k] <= u && u < t[k + 1];
        n[j] = if inside || (at_end && k == last) { 1.0 } else { 0.0 };
    }
    // Raise the degree (eq. 2.2): n[j] becomes N_{i+j,d}.
    for d in 1..=p {
        for j in 0..=p - d {
            let k = i + j;
            let left = ratio(u - t[k], t[k + d] - t[k]) * n[j];
            let right = ratio(t[k + d + 1] - u, t[k + d + 1] - t[k + 1]) * n[j + 1];
            n[j] = left + right;
        }
    }
    n[0]
}

/// `a / b` with the convention `x / 0 = 0` of eq. 2.2 (the numerator is a
/// distance to a knot of a zero-length interval, and the basis it multiplies
/// vanishes there).
#[inline]
fn ratio(a: f64, b: f64) -> f64 {
    if b == 0.0 {
        0.0
    } else {
        a / b
    }
}

/// All `p + 1` non-zero basis functions at `u` on knot span `span` (from
/// [`KnotVector::span`]): entry `j` is `N_{span-p+j,p}(u)` (Piegl & Tiller
/// A2.2, the triangular form of eq. 2.1-2.2). Denominators are never zero on a
/// non-empty span; their reciprocals are precomputed per span by
/// [`KnotVector`], so evaluation only multiplies. Cost O(p^2), no allocation.
#[inline]
pub fn basis_values(kv: &KnotVector, span: usize, u: f64) -> [f64; CAP] {
    let span = kv.clamp_span(span);
    let mut n = [0.0; CAP];
    match kv.degree() {
        1 => values_core::<2, 1>(kv, span, u, &mut n),
        2 => values_core::<3, 2>(kv, span, u, &mut n),
        3 => values_core::<4, 3>(kv, span, u, &mut n),
        _ => values_core::<CAP, 0>(kv, span, u, &mut n),
    }
    n
}

/// A2.2 with scratch arrays of capacity `C > p`. Degrees 1 to 3 are
/// dispatched with `P = p` so that the loops have compile-time bounds (and
/// unroll); `P = 0` reads the degree at run time.
#[inline(always)]
fn values_core<const C: usize, const P: usize>(kv: &KnotVector, span: usize, u: f64, n: &mut [f64; CAP]) {
    let p = if P > 0 { P } else { kv.degree() };
    let t = kv.knots();
    let inv = kv.inverse_differences(span);
    let mut left = [0.0; C];
    let mut right = [0.0; C];
    n[0] = 1.0;
    for j in 1..=p {
        left[j] = u - t[span + 1 - j];
        right[j] = t[span + j] - u;
        let mut saved = 0.0;
        for r in 0..j {
            // 1 / (right[r + 1] + left[j - r]), precomputed per span.
            let temp = n[r] * inv[j * (j - 1) / 2 + r];
            n[r] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        n[j] = saved;
    }
}

/// The non-zero basis functions and their derivatives of orders `0..N` at `u`
/// (Piegl & Tiller A2.3): `out[k][j] = d^k/du^k N_{span-p+j,p}(u)`.
/// Orders above `p` are zero. Cost O(p^2 + N p), no allocation.
#[inline]
pub fn basis_derivatives<const N: usize>(kv: &KnotVector, span: usize, u: f64) -> [[f64; CAP]; N] {
    let mut out = [[0.0; CAP]; N];
    basis_derivatives_in(kv, span, u, &mut out);
    out
}

/// [`basis_derivatives`] into an array of the caller (entries beyond `p` are
/// left as they are).
#[inline]
pub(crate) fn basis_derivatives_in<const N: usize>(kv: &KnotVector, span: usize, u: f64, out: &mut [[f64; CAP]; N]) {
    let span = kv.clamp_span(span);
    derivatives_core(kv, span, u, N.saturating_sub(1), |k, j, value| out[k][j] = value);
}

/// Same as [`basis_derivatives`] for a run-time order `n`, into a caller
/// buffer laid out row by row: `out[k * (p + 1) + j]` for `k = 0..=n`.
/// Returns [`NurbsError::Count`] when `out` is shorter than `(n + 1)(p + 1)`.
/// Cost O(p^2 + n p), no allocation.
///
/// # Errors
/// `NurbsError::Count` when `out` is shorter than `(n + 1) * (degree + 1)` values.
pub fn basis_derivatives_into(kv: &KnotVector, span: usize, u: f64, n: usize, out: &mut [f64]) -> Result<()> {
    let stride = kv.degree() + 1;
    let needed = (n + 1) * stride;
    if out.len() < needed {
        return Err(NurbsError::Count { what: "basis derivative buffer length", expected: needed, found: out.len() });
    }
    out[..needed].fill(0.0);
    let span = kv.clamp_span(span);
    derivatives_core(kv, span, u, n, |k, j, value| out[k * stride + j] = value);
    Ok(())
}

/// A2.3 of Piegl & Tiller: the triangle `ndu` holds the basis functions of all
/// degrees up to `p` (upper part) and the reciprocal knot differences (lower
/// part); the
/// derivatives are combinations of lower-degree functions. Writes orders
/// `0..=min(n, p)` through `write(order, j, value)`.
#[inline(always)]
fn derivatives_core(kv: &KnotVector, span: usize, u: f64, n: usize, write: impl FnMut(usize, usize, f64)) {
    match kv.degree() {
        1 => derivatives_sized::<2, 1>(kv, span, u, n, write),
        2 => derivatives_sized::<3, 2>(kv, span, u, n, write),
        3 => derivatives_sized::<4, 3>(kv, span, u, n, write),
        _ => derivatives_sized::<CAP, 0>(kv, span, u, n, write),
    }
}

/// A2.3 with scratch tables of capacity `C > p`, degree `P` fixed at compile
/// time (or read at run time when `P = 0`), like [`values_core`].
#[inline(always)]
fn derivatives_sized<const C: usize, const P: usize>(
    kv: &KnotVector,
    span: usize,
    u: f64,
    n: usize,
    mut write: impl FnMut(usize, usize, f64),
) {
    let p = if P > 0 { P } else { kv.degree() };
    let t = kv.knots();
    let inv = kv.inverse_differences(span);
    let mut ndu = [[0.0; C]; C];
    let mut left = [0.0; C];
    let mut right = [0.0; C];
    ndu[0][0] = 1.0;
    for j in 1..=p {
        left[j] = u - t[span + 1 - j];
        right[j] = t[span + j] - u;
        let mut saved = 0.0;
        for r in 0..j {
            // The lower triangle keeps reciprocals of the knot differences, so
            // the derivative pass below multiplies instead of dividing.
            ndu[j][r] = inv[j * (j - 1) / 2 + r];
            let temp = ndu[r][j - 1] * ndu[j][r];
            ndu[r][j] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        ndu[j][j] = saved;
    }
    for j in 0..=p {
        write(0, j, ndu[j][p]);
    }
    let n = n.min(p);
    if n == 0 {
        return;
    }
    let mut a = [[0.0; C]; 2];
    let p_i = p as isize;
    for r in 0..=p {
        let (mut s1, mut s2) = (0usize, 1usize);
        a[0][0] = 1.0;
        let r_i = r as isize;
        // Product p (p-1) ... (p-k+1) applied as we go.
        let mut factor = p as f64;
        for k in 1..=n {
            let k_i = k as isize;
            let rk = r_i - k_i;
            let pk = p_i - k_i;
            let mut d = 0.0;
            if rk >= 0 {
                a[s2][0] = a[s1][0] * ndu[(pk + 1) as usize][rk as usize];
                d = a[s2][0] * ndu[rk as usize][pk as usize];
            }
            let j1 = if rk >= -1 { 1 } else { -rk };
            let j2 = if r_i - 1 <= pk { k_i - 1 } else { p_i - r_i };
            for j in j1..=j2 {
                let j = j as usize;
                let idx = (rk + j as isize) as usize;
                a[s2][j] = (a[s1][j] - a[s1][j - 1]) * ndu[(pk + 1) as usize][idx];
                d += a[s2][j] * ndu[idx][pk as usize];
            }
            if r_i <= pk {
                a[s2][k] = -a[s1][k - 1] * ndu[(pk + 1) as usize][r];
                d += a[s2][k] * ndu[r][pk as usize];
            }
            write(k, r, d * factor);
            factor *= (p - k) as f64;
            std::mem::swap(&mut s1, &mut s2);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_match_reference_recursion() {
        let kv = KnotVector::new(3, vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.5, 0.5, 0.8, 1.0, 1.0, 1.0, 1.0]).unwrap();
        for s in 0..=100 {
            let u = s as f64 / 100.0;
            let span = kv.span(u);
            let n = basis_values(&kv, span, u);
            for i in 0..kv.control_count() {
                let expected = if i + 3 >= span && i <= span { n[i + 3 - span] } else { 0.0 };
                assert!((basis_function(&kv, i, u) - expected).abs() < 1e-14, "i {i} u {u}");
            }
        }
    }

    #[test]
    fn derivatives_row_zero_is_values() {
        let kv = KnotVector::clamped_uniform(4, 9).unwrap();
        for s in 0..=50 {
            let u = s as f64 / 50.0;
            let span = kv.span(u);
            let v = basis_values(&kv, span, u);
            let d = basis_derivatives::<3>(&kv, span, u);
            for j in 0..=4 {
                assert!((v[j] - d[0][j]).abs() < 1e-15);
            }
        }
    }

    #[test]
    fn buffer_variant_checks_length_and_zeroes_high_orders() {
        let kv = KnotVector::clamped_uniform(2, 4).unwrap();
        let mut short = [0.0; 5];
        assert!(basis_derivatives_into(&kv, 2, 0.2, 1, &mut short).is_err());
        let mut buf = [7.0; 12];
        basis_derivatives_into(&kv, 2, 0.2, 3, &mut buf).unwrap();
        assert!(buf[9..12].iter().all(|&x| x == 0.0));
        let fixed = basis_derivatives::<3>(&kv, 2, 0.2);
        for k in 0..3 {
            for j in 0..3 {
                assert!((fixed[k][j] - buf[k * 3 + j]).abs() < 1e-15);
            }
        }
    }
}
