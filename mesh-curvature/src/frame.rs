//! Small dense algebra for curvature tensors: tangent frames, symmetric 2x2
//! eigen-decomposition, the minimal rotation between two normals and a tiny
//! least-squares solver. Everything is closed-form or O(n^3) on n <= 14.

use glam::DVec3;

/// An orthonormal tangent basis `(t1, t2)` of the plane orthogonal to the unit
/// vector `n`, with `t1 x t2 = n` (Duff et al. 2017, "Building an orthonormal
/// basis, revisited": branch-free, continuous except at one sign flip).
#[inline]
pub(crate) fn tangent_basis(n: DVec3) -> (DVec3, DVec3) {
    let sign = 1f64.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    let t1 = DVec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
    let t2 = DVec3::new(b, sign + n.y * n.y * a, -n.y);
    (t1, t2)
}

/// A symmetric 2x2 matrix `[[a, b], [b, c]]`: a second fundamental form in
/// some orthonormal tangent basis.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct Sym2 {
    pub a: f64,
    pub b: f64,
    pub c: f64,
}

impl Sym2 {
    #[inline]
    pub fn new(a: f64, b: f64, c: f64) -> Self {
        Self { a, b, c }
    }

    #[inline]
    pub fn scaled(self, s: f64) -> Self {
        Self::new(self.a * s, self.b * s, self.c * s)
    }

    #[inline]
    pub fn add(self, o: Self) -> Self {
        Self::new(self.a + o.a, self.b + o.b, self.c + o.c)
    }

    /// `II(x, y)` for tangent coordinates `x = (x0, x1)`, `y = (y0, y1)`.
    #[inline]
    pub fn form(self, x: [f64; 2], y: [f64; 2]) -> f64 {
        self.a * x[0] * y[0] + self.b * (x[0] * y[1] + x[1] * y[0]) + self.c * x[1] * y[1]
    }

    #[inline]
    pub fn is_finite(self) -> bool {
        self.a.is_finite() && self.b.is_finite() && self.c.is_finite()
    }

    /// Eigenvalues `l1 >= l2` and the unit eigenvector `(cos t, sin t)` of
    /// `l1`, robust for repeated eigenvalues (any direction is returned then).
    pub fn eigen(self) -> (f64, f64, [f64; 2]) {
        let half_diff = 0.5 * (self.a - self.c);
        let mean = 0.5 * (self.a + self.c);
        let radius = half_diff.hypot(self.b);
        let (l1, l2) = (mean + radius, mean - radius);
        if radius == 0.0 {
            return (l1, l2, [1.0, 0.0]);
        }
        // Angle of the major axis: tan(2t) = 2b / (a - c).
        let t = 0.5 * self.b.atan2(half_diff);
        (l1, l2, [t.cos(), t.sin()])
    }
}

/// The rotation taking unit vector `from` to unit vector `to` about their
/// common perpendicular, applied to `x` (identity when they coincide; a half
/// turn about an axis orthogonal to `from` when they are opposite).
#[inline]
pub(crate) fn rotate_between(from: DVec3, to: DVec3, x: DVec3) -> DVec3 {
    let c = from.dot(to);
    if c >= 1.0 {
        return x;
    }
    if c <= -1.0 + 1e-12 {
        // Opposite normals: half turn about a tangent axis of `from`.
        let (t, _) = tangent_basis(from);
        return 2.0 * t.dot(x) * t - x;
    }
    // Rodrigues with v = from x to, |v| = sin, R = I + [v] + [v]^2 / (1 + c).
    let v = from.cross(to);
    let vx = v.cross(x);
    x + vx + v.cross(vx) / (1.0 + c)
}

/// Solves the symmetric positive semi-definite system `A x = b` of size `N`
/// (the full matrix is read), in place (`b` becomes `x`). Returns `None`
/// when the matrix is numerically rank deficient: when, in a Cholesky
/// factorization with symmetric pivoting of the equilibrated matrix
/// `D^-1/2 A D^-1/2`, the largest remaining pivot falls below `tol` (the
/// squared sine of the angle between a column and the span of the others).
/// Pivoting makes this a reliable rank test whatever the scale of each
/// unknown. A plain `L D L^T` is tried first and kept when every pivot keeps
/// at least [`FAST_PIVOT`] of its diagonal entry, where pivoting would
/// change nothing.
///
/// Returns the conditioning of the last `watch` unknowns: the largest
/// diagonal entry `(A^-1)_kk` over them, which bounds how much a
/// perturbation of the least-squares data moves them (for `A = X^T X`,
/// `|dx_k| <= sqrt((A^-1)_kk) |dy|`). O(N^3), plus O(watch^3) for the test.
pub(crate) fn solve_spd<const N: usize>(a: &[[f64; N]; N], b: &mut [f64; N], tol: f64, watch: usize) -> Option<f64> {
    let mut x = *b;
    if let Some(spread) = ldlt_solve(a, &mut x, watch) {
        if x.iter().all(|v| v.is_finite()) {
            *b = x;
            return Some(spread);
        }
    }
    let mut scale = [0.0; N];
    for i in 0..N {
        let d = a[i][i];
        if !(d > 0.0 && d.is_finite()) {
            return None;
        }
        scale[i] = 1.0 / d.sqrt();
    }
    let mut m = [[0.0; N]; N];
    for i in 0..N {
        for j in 0..N {
            m[i][j] = a[i][j] * scale[i] * scale[j];
        }
        x[i] = b[i] * scale[i];
    }
    let spread = pivoted_cholesky_solve(&mut m, &mut x, tol, &scale, watch)?;
    for i in 0..N {
        b[i] = x[i] * scale[i];
    }
    b.iter().all(|v| v.is_finite()).then_some(spread)
}

/// Below this relative pivot, the plain factorization of [`solve_spd`]
/// hands over to the pivoted one.
const FAST_PIVOT: f64 = 1e-5;

/// `L D L^T` solve without pivoting (left-looking, no square roots: the
/// fastest form for these tiny systems); `false` when a pivot `d_j` falls
/// below [`FAST_PIVOT`] times `A_jj`.
fn ldlt_solve<const N: usize>(a: &[[f64; N]; N], b: &mut [f64; N], watch: usize) -> Option<f64> {
    let mut l = [[0.0; N]; N];
    let mut dinv = [0.0; N];
    for j in 0..N {
        // w_k = L_jk d_k = A_jk - sum_{m < k} w_m L_km.
        let mut w = [0.0; N];
        for k in 0..j {
            let mut s = a[j][k];
            for m in 0..k {
                s -= w[m] * l[k][m];
            }
            w[k] = s;
        }
        let mut dj = a[j][j];
        for k in 0..j {
            let ljk = w[k] * dinv[k];
            l[j][k] = ljk;
            dj -= w[k] * ljk;
        }
        if dj.is_nan() || dj <= FAST_PIVOT * a[j][j] {
            return None;
        }
        dinv[j] = 1.0 / dj;
    }
    for i in 0..N {
        let mut s = b[i];
        for k in 0..i {
            s -= l[i][k] * b[k];
        }
        b[i] = s;
    }
    for i in 0..N {
        b[i] *= dinv[i];
    }
    for i in (0..N).rev() {
        let bi = b[i];
        for k in 0..i {
            b[k] -= l[i][k] * bi;
        }
    }
    // (A^-1)_kk = sum_j (L^-1 e_k)_j^2 / d_j.
    let mut spread = 0.0f64;
    for k in N - watch.min(N)..N {
        let mut y = [0.0; N];
        y[k] = 1.0;
        let mut sum = dinv[k];
        for i in k + 1..N {
            let mut s = 0.0;
            for m in k..i {
                s -= l[i][m] * y[m];
            }
            y[i] = s;
            sum += s * s * dinv[i];
        }
        spread = spread.max(sum);
    }
    Some(spread)
}

/// `L L^T x = x` with `L` in the lower triangle of `m`, column-oriented so
/// that the inner loops are independent updates.
fn triangular_solves<const N: usize>(m: &[[f64; N]; N], x: &mut [f64; N]) {
    for k in 0..N {
        x[k] /= m[k][k];
        let xk = x[k];
        for i in k + 1..N {
            x[i] -= m[i][k] * xk;
        }
    }
    for i in (0..N).rev() {
        x[i] /= m[i][i];
        let xi = x[i];
        for k in 0..i {
            x[k] -= m[i][k] * xi;
        }
    }
}

/// Right-looking Cholesky with symmetric (diagonal) pivoting of a full
/// symmetric matrix, then the solve; `None` when the largest remaining
/// pivot is below `tol`.
fn pivoted_cholesky_solve<const N: usize>(
    m: &mut [[f64; N]; N],
    x: &mut [f64; N],
    tol: f64,
    scale: &[f64; N],
    watch: usize,
) -> Option<f64> {
    let mut perm = [0usize; N];
    for (k, p) in perm.iter_mut().enumerate() {
        *p = k;
    }
    for k in 0..N {
        let mut best = k;
        for q in k + 1..N {
            if m[q][q] > m[best][best] {
                best = q;
            }
        }
        if m[best][best].is_nan() || m[best][best] <= tol {
            return None;
        }
        if best != k {
            m.swap(k, best);
            for row in m.iter_mut() {
                row.swap(k, best);
            }
            perm.swap(k, best);
        }
        let d = m[k][k].sqrt();
        m[k][k] = d;
        for i in k + 1..N {
            m[i][k] /= d;
        }
        for j in k + 1..N {
            let ljk = m[j][k];
            for i in j..N {
                m[i][j] -= m[i][k] * ljk;
            }
            // Keep the upper triangle in step so that row swaps stay symmetric.
            for i in j + 1..N {
                m[j][i] = m[i][j];
            }
        }
    }
    let mut y = [0.0; N];
    for i in 0..N {
        y[i] = x[perm[i]];
    }
    triangular_solves(m, &mut y);
    for i in 0..N {
        x[perm[i]] = y[i];
    }
    // (A^-1)_kk = scale_k^2 |L^-1 e_q|^2 with q the pivoted position of k.
    let mut spread = 0.0f64;
    for (k, sk) in scale.iter().enumerate().skip(N - watch.min(N)) {
        let q = perm.iter().position(|&p| p == k).unwrap_or(0);
        let mut y = [0.0; N];
        y[q] = 1.0 / m[q][q];
        let mut sum = y[q] * y[q];
        for i in q + 1..N {
            let mut s = 0.0;
            for c in q..i {
                s -= m[i][c] * y[c];
            }
            y[i] = s / m[i][i];
            sum += y[i] * y[i];
        }
        spread = spread.max(sum * sk * sk);
    }
    Some(spread)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn basis_is_orthonormal() {
        for n in [DVec3::Z, -DVec3::Z, DVec3::X, DVec3::new(1.0, -2.0, 0.3).normalize(), DVec3::new(0.0, 1e-17, -1.0)] {
            let n = n.normalize();
            let (t1, t2) = tangent_basis(n);
            assert!((t1.length() - 1.0).abs() < 1e-14 && (t2.length() - 1.0).abs() < 1e-14);
            assert!(t1.dot(t2).abs() < 1e-14 && t1.dot(n).abs() < 1e-14);
            assert!((t1.cross(t2) - n).length() < 1e-14);
        }
    }

    #[test]
    fn eigen_of_rotated_diagonal() {
        let (l1, l2, t) = (3.0, -1.0, 0.7f64);
        let (c, s) = (t.cos(), t.sin());
        let m = Sym2::new(l1 * c * c + l2 * s * s, (l1 - l2) * c * s, l1 * s * s + l2 * c * c);
        let (a, b, v) = m.eigen();
        assert!((a - l1).abs() < 1e-14 && (b - l2).abs() < 1e-14);
        assert!((v[0] * c + v[1] * s).abs() > 1.0 - 1e-14);
    }

    #[test]
    fn rotation_takes_from_to_to() {
        let a = DVec3::new(0.3, 0.4, 0.8).normalize();
        for b in [DVec3::new(-0.2, 0.9, 0.1).normalize(), a, -a] {
            assert!((rotate_between(a, b, a) - b).length() < 1e-12);
            let x = DVec3::new(1.0, 2.0, 3.0);
            assert!((rotate_between(a, b, x).length() - x.length()).abs() < 1e-12);
        }
    }

    #[test]
    fn cholesky_solves_and_refuses_singular() {
        let a = [[4.0, 2.0, 0.0], [2.0, 3.0, 1.0], [0.0, 1.0, 2.0]];
        let mut b = [2.0, 5.0, 3.0];
        solve_spd(&a, &mut b, 1e-14, 0).unwrap();
        let x = b;
        let a = [[4.0, 2.0, 0.0], [2.0, 3.0, 1.0], [0.0, 1.0, 2.0]];
        for i in 0..3 {
            let r: f64 = (0..3).map(|j| a[i][j] * x[j]).sum();
            assert!((r - [2.0, 5.0, 3.0][i]).abs() < 1e-12);
        }
        let s = [[1.0, 1.0], [1.0, 1.0]];
        assert!(solve_spd(&s, &mut [1.0, 2.0], 1e-12, 0).is_none());
        // Badly scaled but regular: equilibration makes it easy.
        let s = [[1e-20, 0.0], [0.0, 1e20]];
        let mut b = [1e-20, 1e20];
        solve_spd(&s, &mut b, 1e-12, 0).unwrap();
        assert!((b[0] - 1.0).abs() < 1e-14 && (b[1] - 1.0).abs() < 1e-14);
        // Rank deficient only after pivoting exposes it: columns 0 and 2 equal.
        let s = [[2.0, 1.0, 2.0], [1.0, 3.0, 1.0], [2.0, 1.0, 2.0]];
        assert!(solve_spd(&s, &mut [1.0, 1.0, 1.0], 1e-12, 0).is_none());
    }

    #[test]
    fn spread_is_the_inverse_diagonal() {
        // A^-1 = [[3, -2, 1], [-2, 2, -1], [1, -1, 1]] (det 1).
        let a = [[1.0, 1.0, 0.0], [1.0, 2.0, 1.0], [0.0, 1.0, 2.0]];
        for (watch, expected) in [(0, 0.0), (1, 1.0), (2, 2.0), (3, 3.0)] {
            let spread = solve_spd(&a, &mut [1.0, 0.0, 0.0], 1e-14, watch).unwrap();
            assert!((spread - expected).abs() < 1e-12, "watch {watch}: {spread}");
        }
        // The same through the pivoted path: a pivot below FAST_PIVOT.
        let eps = 1e-7;
        let a = [[1.0, 1.0], [1.0, 1.0 + eps]];
        let spread = solve_spd(&a, &mut [0.0, 1.0], 1e-14, 2).unwrap();
        assert!((spread / ((1.0 + eps) / eps) - 1.0).abs() < 1e-6, "{spread}");
    }
}
