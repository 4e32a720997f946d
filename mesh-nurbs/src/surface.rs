//! NURBS surfaces (eq. 2.3-2.4 of the chapter): evaluation, first and second
//! partial derivatives by the quotient rule on homogeneous coordinates, unit
//! normals, knot insertion and affine maps.

use glam::{DAffine3, DVec3, DVec4};

use crate::basis::{basis_derivatives_in, CAP};
use crate::curve::{cartesian, check_count, elevate_degree_line, homogeneous, insert_knot_line};
use crate::error::{check_param, NurbsError, Result};
use crate::knots::KnotVector;

/// A tensor-product NURBS surface
/// `S(u, v) = sum_ij w_ij P_ij N_{i,k}(u) N_{j,l}(v) / sum_rs w_rs N_{r,k}(u) N_{s,l}(v)`
/// (eq. 2.3-2.4).
///
/// The control net is stored row-major: point `(i, j)` (the `i`-th along `u`,
/// the `j`-th along `v`) is at index `i * count_v + j`. Points and weights
/// are kept as given, beside the homogeneous points `(w P, w)` used for
/// evaluation.
#[derive(Debug, Clone, PartialEq)]
pub struct NurbsSurface {
    knots_u: KnotVector,
    knots_v: KnotVector,
    points: Vec<DVec3>,
    weights: Vec<f64>,
    homogeneous: Vec<DVec4>,
}

/// A point of a surface and its partial derivatives up to second order. When
/// fewer orders were asked for, the others are zero.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SurfaceDerivatives {
    /// `S(u, v)`.
    pub point: DVec3,
    /// `s_u = dS/du`.
    pub su: DVec3,
    /// `s_v = dS/dv`.
    pub sv: DVec3,
    /// `s_uu = d^2 S / du^2`.
    pub suu: DVec3,
    /// `s_uv = d^2 S / du dv`.
    pub suv: DVec3,
    /// `s_vv = d^2 S / dv^2`.
    pub svv: DVec3,
}

/// The non-zero basis functions of one parameter value and their derivatives
/// of orders `0..N`, with the span they belong to.
#[derive(Debug, Clone, Copy)]
pub(crate) struct SpanBasis<const N: usize> {
    span: usize,
    ders: [[f64; CAP]; N],
}

impl<const N: usize> SpanBasis<N> {
    /// Basis at `t` (already checked finite); clamps into the domain.
    #[inline(always)]
    pub(crate) fn new(kv: &KnotVector, t: f64) -> Self {
        let t = kv.clamp(t);
        let span = kv.span(t);
        let mut basis = Self { span, ders: [[0.0; CAP]; N] };
        basis_derivatives_in(kv, span, t, &mut basis.ders);
        basis
    }
}

/// Binomial coefficients up to 2 (the orders of [`SurfaceDerivatives`]).
const BINOMIAL: [[f64; 3]; 3] = [[1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [1.0, 2.0, 1.0]];

impl NurbsSurface {
    /// Builds a surface from knot vectors in `u` and `v`, a row-major control
    /// net (`count_u * count_v` points, see the type) and positive weights.
    /// Cost O(count_u count_v).
    ///
    /// # Errors
    /// `NurbsError::Count` when `points` or `weights` do not have `count_u * count_v` entries;
    /// `NurbsError::NonFiniteControlPoint`; `NurbsError::Weight` for a weight that is not finite and > 0.
    pub fn new(knots_u: KnotVector, knots_v: KnotVector, points: Vec<DVec3>, weights: Vec<f64>) -> Result<Self> {
        let expected = knots_u.control_count().saturating_mul(knots_v.control_count());
        check_count("control points (count_u * count_v)", expected, points.len())?;
        let homogeneous = homogeneous(&points, &weights)?;
        Ok(Self { knots_u, knots_v, points, weights, homogeneous })
    }

    /// A polynomial tensor-product B-spline surface (all weights 1).
    ///
    /// # Errors
    /// As [`NurbsSurface::new`] (`NurbsError::Count`, `NurbsError::NonFiniteControlPoint`).
    pub fn non_rational(knots_u: KnotVector, knots_v: KnotVector, points: Vec<DVec3>) -> Result<Self> {
        let weights = vec![1.0; points.len()];
        Self::new(knots_u, knots_v, points, weights)
    }

    /// A surface from a user control grid `grid[i][j]` (`i` along `u`) with
    /// weights of the same shape, and clamped uniform knots of the given
    /// degrees. Cost O(count_u count_v).
    ///
    /// # Errors
    /// `NurbsError::Count` for ragged rows or weights that do not match the grid; the errors of
    /// [`KnotVector::clamped_uniform`] and [`NurbsSurface::new`].
    pub fn from_grid(degree_u: usize, degree_v: usize, grid: &[Vec<DVec3>], weights: &[Vec<f64>]) -> Result<Self> {
        let count_u = grid.len();
        let count_v = grid.first().map_or(0, Vec::len);
        check_count("weight rows", count_u, weights.len())?;
        for (row, wrow) in grid.iter().zip(weights) {
            check_count("points in a control grid row", count_v, row.len())?;
            check_count("weights in a control grid row", count_v, wrow.len())?;
        }
        let knots_u = KnotVector::clamped_uniform(degree_u, count_u)?;
        let knots_v = KnotVector::clamped_uniform(degree_v, count_v)?;
        Self::new(knots_u, knots_v, grid.concat(), weights.concat())
    }

    pub(crate) fn from_homogeneous(knots_u: KnotVector, knots_v: KnotVector, h: Vec<DVec4>) -> Result<Self> {
        let (points, weights) = cartesian(&h);
        Self::new(knots_u, knots_v, points, weights)
    }

    /// Knot vector (and degree) in `u`.
    pub fn knots_u(&self) -> &KnotVector {
        &self.knots_u
    }

    /// Knot vector (and degree) in `v`.
    pub fn knots_v(&self) -> &KnotVector {
        &self.knots_v
    }

    /// Number of control points along `u`.
    pub fn count_u(&self) -> usize {
        self.knots_u.control_count()
    }

    /// Number of control points along `v`.
    pub fn count_v(&self) -> usize {
        self.knots_v.control_count()
    }

    /// Control points, row-major (`i * count_v + j`).
    pub fn control_points(&self) -> &[DVec3] {
        &self.points
    }

    /// Weights, row-major like the control points.
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// Homogeneous control points `(w P, w)`, row-major.
    pub fn homogeneous_points(&self) -> &[DVec4] {
        &self.homogeneous
    }

    /// Parameter domain in `u`.
    pub fn domain_u(&self) -> (f64, f64) {
        self.knots_u.domain()
    }

    /// Parameter domain in `v`.
    pub fn domain_v(&self) -> (f64, f64) {
        self.knots_v.domain()
    }

    /// Diagonal of the bounding box of the control points (the surface lies in
    /// their convex hull). Cost O(n).
    pub fn control_box_diagonal(&self) -> f64 {
        let lo = self.points.iter().copied().fold(DVec3::INFINITY, DVec3::min);
        let hi = self.points.iter().copied().fold(DVec3::NEG_INFINITY, DVec3::max);
        (hi - lo).length()
    }

    /// The point `S(u, v)` (eq. 2.3-2.4; Piegl & Tiller A4.3). Finite
    /// parameters outside the domain are clamped into it; NaN and infinities
    /// give [`NurbsError::NonFiniteParameter`]. Cost O(p^2 + q^2 + p q).
    ///
    /// # Errors
    /// `NurbsError::NonFiniteParameter` for a NaN or infinite `u` or `v`.
    pub fn point(&self, u: f64, v: f64) -> Result<DVec3> {
        Ok(self.derivatives(u, v, 0)?.point)
    }

    /// `S(u, v)` and its partial derivatives up to `order` (0, 1 or 2): the
    /// homogeneous derivatives `A^(k,l)` of the numerator and `w^(k,l)` of the
    /// denominator of eq. 2.4 (Piegl & Tiller A3.6), then the quotient rule
    /// `S^(k,l) = (A^(k,l) - sum binom w^(i,j) S^(k-i,l-j)) / w` (A4.4).
    /// Cost O(p^2 + q^2 + p q (order + 1)^2), no allocation.
    ///
    /// # Errors
    /// `NurbsError::NonFiniteParameter` for a NaN or infinite `u` or `v`; `NurbsError::InvalidOption`
    /// (`order`) above 2.
    pub fn derivatives(&self, u: f64, v: f64, order: usize) -> Result<SurfaceDerivatives> {
        check_param("u", u)?;
        check_param("v", v)?;
        match order {
            0 => Ok(self.derivatives_at::<1>(u, v)),
            1 => Ok(self.derivatives_at::<2>(u, v)),
            2 => Ok(self.derivatives_at::<3>(u, v)),
            _ => Err(NurbsError::InvalidOption { name: "order", reason: format!("{order} > 2") }),
        }
    }

    /// `[S, s_u, s_v]` at `(u, v)`: the first-order case of
    /// [`Self::derivatives`] in a smaller return value, for the hot loops of
    /// callers that need no second derivatives. Cost O(p^2 + q^2 + p q).
    ///
    /// # Errors
    /// `NurbsError::NonFiniteParameter` for a NaN or infinite `u` or `v`.
    #[inline]
    pub fn point_and_tangents(&self, u: f64, v: f64) -> Result<[DVec3; 3]> {
        check_param("u", u)?;
        check_param("v", v)?;
        let bu = SpanBasis::<2>::new(&self.knots_u, u);
        let bv = SpanBasis::<2>::new(&self.knots_v, v);
        let s = rational_derivatives(&self.homogeneous_derivatives(&bu, &bv));
        Ok([s[0][0], s[1][0], s[0][1]])
    }

    /// Unit normal `n = s_u x s_v / |s_u x s_v|` (section 2.5). At a degenerate
    /// point it is the limit from inside the domain along the iso-line through
    /// the point (the limit normal); zero if there is none.
    /// Cost O(p^2 + q^2 + p q).
    ///
    /// # Errors
    /// `NurbsError::NonFiniteParameter` for a NaN or infinite `u` or `v`.
    pub fn normal(&self, u: f64, v: f64) -> Result<DVec3> {
        let d = self.derivatives(u, v, 1)?;
        if let Some(n) = unit_normal(d.su, d.sv) {
            return Ok(n);
        }
        let d = self.derivatives(u, v, 2)?;
        Ok(self.limit_normal(self.knots_u.clamp(u), self.knots_v.clamp(v), &d).unwrap_or(DVec3::ZERO))
    }

    /// Normal at a degenerate point where one first derivative vanishes (a
    /// pole, an apex), as the limit from inside the domain: if `s_u = 0` on the
    /// side `v = v0`, then `s_u(u, v0 + e) = e s_uv + O(e^2)` and the normal is
    /// `sign(e) s_uv x s_v` normalized (symmetrically when `s_v = 0`). Falls
    /// back to the normal at a parameter moved inside by [`Self::nudge`].
    /// `d` must hold second derivatives at `(u, v)`. Cost O(1), or one
    /// evaluation for the fall-back.
    pub(crate) fn limit_normal(&self, u: f64, v: f64, d: &SurfaceDerivatives) -> Option<DVec3> {
        let (nu, nv) = self.nudge(u, v);
        let taylor = if d.su.length_squared() <= d.sv.length_squared() {
            d.suv.cross(d.sv) * (nv - v).signum()
        } else {
            d.su.cross(d.suv) * (nu - u).signum()
        };
        let n = taylor.normalize_or_zero();
        if n != DVec3::ZERO {
            return Some(n);
        }
        let near = self.derivatives_at::<2>(nu, nv);
        unit_normal(near.su, near.sv)
    }

    /// Derivatives of orders `< N` (clamped finite parameters).
    #[inline(always)]
    pub(crate) fn derivatives_at<const N: usize>(&self, u: f64, v: f64) -> SurfaceDerivatives {
        let bu = SpanBasis::<N>::new(&self.knots_u, u);
        let bv = SpanBasis::<N>::new(&self.knots_v, v);
        self.derivatives_with(&bu, &bv)
    }

    /// Derivatives of orders `< N` from precomputed bases (grids reuse them).
    #[inline(always)]
    pub(crate) fn derivatives_with<const N: usize>(&self, bu: &SpanBasis<N>, bv: &SpanBasis<N>) -> SurfaceDerivatives {
        let a = self.homogeneous_derivatives(bu, bv);
        let s = rational_derivatives(&a);
        let get = |k: usize, l: usize| if k < N && l < N && k + l < N { s[k][l] } else { DVec3::ZERO };
        SurfaceDerivatives {
            point: get(0, 0),
            su: get(1, 0),
            sv: get(0, 1),
            suu: get(2, 0),
            suv: get(1, 1),
            svv: get(0, 2),
        }
    }

    /// `A^(k,l)` (and `w^(k,l)` in the last coordinate) for `k + l < N`
    /// (Piegl & Tiller A3.6 on homogeneous points).
    /// Dispatches the common degrees to loops of compile-time length.
    #[inline(always)]
    fn homogeneous_derivatives<const N: usize>(&self, bu: &SpanBasis<N>, bv: &SpanBasis<N>) -> [[DVec4; N]; N] {
        match (self.knots_u.degree(), self.knots_v.degree()) {
            (3, 3) => self.contract::<N, 4, 4>(bu, bv),
            (2, 2) => self.contract::<N, 3, 3>(bu, bv),
            (2, 1) => self.contract::<N, 3, 2>(bu, bv),
            (1, 1) => self.contract::<N, 2, 2>(bu, bv),
            _ => self.contract::<N, 0, 0>(bu, bv),
        }
    }

    /// `sum_ij N^(k)_i(u) N^(l)_j(v) P^w_ij` over the `(p+1) x (q+1)` active
    /// control points; `P1 = p + 1` and `Q1 = q + 1` when known at compile
    /// time, 0 for run-time degrees.
    #[inline(always)]
    fn contract<const N: usize, const P1: usize, const Q1: usize>(
        &self,
        bu: &SpanBasis<N>,
        bv: &SpanBasis<N>,
    ) -> [[DVec4; N]; N] {
        let (p, q) = (self.knots_u.degree(), self.knots_v.degree());
        let p1 = if P1 > 0 { P1 } else { p + 1 };
        let q1 = if Q1 > 0 { Q1 } else { q + 1 };
        let nv = self.count_v();
        let (fu, fv) = (bu.span - p, bv.span - q);
        let mut a = [[DVec4::ZERO; N]; N];
        for i in 0..p1 {
            let start = (fu + i) * nv + fv;
            let row = &self.homogeneous[start..start + q1];
            let mut tmp = [DVec4::ZERO; N];
            for j in 0..q1 {
                for l in 0..N {
                    tmp[l] += row[j] * bv.ders[l][j];
                }
            }
            for k in 0..N {
                for l in 0..N - k {
                    a[k][l] += tmp[l] * bu.ders[k][i];
                }
            }
        }
        a
    }

    /// The same surface with the knot `u` inserted `times` times in the `u`
    /// direction (Boehm, Piegl & Tiller A5.3): shape and parameterization are
    /// unchanged. Cost O(count_u count_v + times p count_v).
    ///
    /// # Errors
    /// `NurbsError::NonFiniteParameter`, or `NurbsError::KnotInsertion` when `u` is outside the domain or the
    /// multiplicity would exceed the degree.
    pub fn insert_knot_u(&self, u: f64, times: usize) -> Result<Self> {
        self.map_columns(|column| insert_knot_line(&self.knots_u, column, u, times))
    }

    /// The same surface with the knot `v` inserted `times` times in the `v`
    /// direction (Boehm, Piegl & Tiller A5.3). Cost as [`Self::insert_knot_u`].
    ///
    /// # Errors
    /// `NurbsError::NonFiniteParameter`, or `NurbsError::KnotInsertion` when `v` is outside the domain or the
    /// multiplicity would exceed the degree.
    pub fn insert_knot_v(&self, v: f64, times: usize) -> Result<Self> {
        self.map_rows(|row| insert_knot_line(&self.knots_v, row, v, times))
    }

    /// The same surface with its degree in `u` raised by one, exactly (see
    /// [`crate::NurbsCurve::elevate_degree`]; needs clamped knots in `u`).
    /// Cost O(count_u count_v p).
    ///
    /// # Errors
    /// `NurbsError::NotClamped` for unclamped knots; `NurbsError::Degree` beyond the maximal degree.
    pub fn elevate_degree_u(&self) -> Result<Self> {
        self.map_columns(|column| elevate_degree_line(&self.knots_u, column))
    }

    /// The same surface with its degree in `v` raised by one, exactly (needs
    /// clamped knots in `v`). Cost O(count_u count_v q).
    ///
    /// # Errors
    /// `NurbsError::NotClamped` for unclamped knots; `NurbsError::Degree` beyond the maximal degree.
    pub fn elevate_degree_v(&self) -> Result<Self> {
        self.map_rows(|row| elevate_degree_line(&self.knots_v, row))
    }

    /// Applies a knot-vector-changing operation to every column (fixed `j`,
    /// the `u` direction) of the homogeneous net.
    fn map_columns(&self, op: impl Fn(&[DVec4]) -> Result<(KnotVector, Vec<DVec4>)>) -> Result<Self> {
        let (nu, nv) = (self.count_u(), self.count_v());
        let mut lines = Vec::with_capacity(nv);
        for j in 0..nv {
            let column: Vec<DVec4> = (0..nu).map(|i| self.homogeneous[i * nv + j]).collect();
            lines.push(op(&column)?);
        }
        let (knots, columns) = split_lines(lines)?;
        let new_nu = columns[0].len();
        let out = (0..new_nu * nv).map(|k| columns[k % nv][k / nv]).collect();
        Self::from_homogeneous(knots, self.knots_v.clone(), out)
    }

    /// Applies a knot-vector-changing operation to every row (fixed `i`, the
    /// `v` direction) of the homogeneous net.
    fn map_rows(&self, op: impl Fn(&[DVec4]) -> Result<(KnotVector, Vec<DVec4>)>) -> Result<Self> {
        let lines = self.homogeneous.chunks_exact(self.count_v()).map(op).collect::<Result<Vec<_>>>()?;
        let (knots, rows) = split_lines(lines)?;
        Self::from_homogeneous(self.knots_u.clone(), knots, rows.concat())
    }

    /// The image of the surface under an affine map (map the control points,
    /// keep the weights). A map with negative determinant flips the normals.
    /// Cost O(n).
    ///
    /// # Errors
    /// `NurbsError::NonFiniteControlPoint` when the map sends a control point to a non-finite position.
    pub fn transform(&self, map: &DAffine3) -> Result<Self> {
        let points = self.points.iter().map(|&p| map.transform_point3(p)).collect();
        Self::new(self.knots_u.clone(), self.knots_v.clone(), points, self.weights.clone())
    }

    /// The same surface with `u` and `v` swapped, which flips the normal
    /// (use it to turn inward normals outward). Cost O(n).
    ///
    /// # Errors
    /// None for a valid surface (the result type is that of [`NurbsSurface::new`]).
    pub fn swap_uv(&self) -> Result<Self> {
        let (nu, nv) = (self.count_u(), self.count_v());
        let index = |k: usize| (k % nu) * nv + k / nu;
        let points = (0..nu * nv).map(|k| self.points[index(k)]).collect();
        let weights = (0..nu * nv).map(|k| self.weights[index(k)]).collect();
        Self::new(self.knots_v.clone(), self.knots_u.clone(), points, weights)
    }

    /// A parameter moved by 1e-4 of each domain length towards the centre of
    /// the domain: where limits at a degenerate point are taken. (Closer,
    /// the first derivatives lose digits to cancellation in the quotient rule:
    /// the error of the curvature grows like `1e-16 / step^2`.)
    pub(crate) fn nudge(&self, u: f64, v: f64) -> (f64, f64) {
        (nudge_in(self.domain_u(), u), nudge_in(self.domain_v(), v))
    }
}

/// The common knot vector of lines transformed alike, and the lines.
fn split_lines(lines: Vec<(KnotVector, Vec<DVec4>)>) -> Result<(KnotVector, Vec<Vec<DVec4>>)> {
    let knots = lines.first().map(|l| l.0.clone());
    let knots = knots.ok_or(NurbsError::Count { what: "control point lines", expected: 1, found: 0 })?;
    Ok((knots, lines.into_iter().map(|l| l.1).collect()))
}

fn nudge_in((a, b): (f64, f64), t: f64) -> f64 {
    let t = t.clamp(a, b);
    let step = 1e-4 * (b - a);
    if t < 0.5 * (a + b) {
        t + step
    } else {
        t - step
    }
}

/// `s_u x s_v` normalized, or `None` where it is degenerate relative to the
/// size of the derivatives (poles, apexes, collapsed edges).
#[inline]
pub(crate) fn unit_normal(su: DVec3, sv: DVec3) -> Option<DVec3> {
    let c = su.cross(sv);
    let len = c.length();
    // |su x sv| > 1e-10 (|su|^2 + |sv|^2): scale-invariant, and it also catches
    // a derivative that is only rounding noise (|su| ~ 1e-16 |sv| at a pole,
    // in a random direction). NaN fails it.
    if len > 1e-10 * (su.length_squared() + sv.length_squared()) && len > 0.0 {
        Some(c / len)
    } else {
        None
    }
}

/// Quotient rule for rational derivatives (Piegl & Tiller A4.4).
#[inline(always)]
fn rational_derivatives<const N: usize>(a: &[[DVec4; N]; N]) -> [[DVec3; N]; N] {
    let mut s = [[DVec3::ZERO; N]; N];
    let inv_w = 1.0 / a[0][0].w;
    for k in 0..N {
        for l in 0..N - k {
            let mut v = a[k][l].truncate();
            for j in 1..=l {
                v -= s[k][l - j] * (BINOMIAL[l][j] * a[0][j].w);
            }
            for i in 1..=k {
                v -= s[k - i][l] * (BINOMIAL[k][i] * a[i][0].w);
                let mut v2 = DVec3::ZERO;
                for j in 1..=l {
                    v2 += s[k - i][l - j] * (BINOMIAL[l][j] * a[i][j].w);
                }
                v -= v2 * BINOMIAL[k][i];
            }
            s[k][l] = v * inv_w;
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A rational bicubic patch with irregular knots and weights.
    pub(crate) fn wavy() -> NurbsSurface {
        let ku = KnotVector::new(3, vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.6, 1.0, 1.0, 1.0, 1.0]).unwrap();
        let kv = KnotVector::new(2, vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0]).unwrap();
        let mut pts = Vec::new();
        let mut w = Vec::new();
        for i in 0..6 {
            for j in 0..4 {
                let (x, y) = (i as f64, j as f64);
                pts.push(DVec3::new(x, y, (0.7 * x).sin() * (1.3 * y).cos()));
                w.push(1.0 + 0.3 * ((i * 7 + j * 3) % 5) as f64);
            }
        }
        NurbsSurface::new(ku, kv, pts, w).unwrap()
    }

    #[test]
    fn corners_interpolate() {
        let s = wavy();
        let p = s.control_points();
        assert!((s.point(0.0, 0.0).unwrap() - p[0]).length() < 1e-14);
        assert!((s.point(1.0, 1.0).unwrap() - p[p.len() - 1]).length() < 1e-14);
    }

    #[test]
    fn derivatives_match_finite_differences() {
        let s = wavy();
        let h = 1e-5;
        let pt = |u: f64, v: f64| s.point(u, v).unwrap();
        for &(u, v) in &[(0.2, 0.3), (0.45, 0.7), (0.8, 0.1), (0.61, 0.52)] {
            let d = s.derivatives(u, v, 2).unwrap();
            let su = (pt(u + h, v) - pt(u - h, v)) / (2.0 * h);
            let sv = (pt(u, v + h) - pt(u, v - h)) / (2.0 * h);
            assert!((d.su - su).length() < 1e-7 * d.su.length().max(1.0));
            assert!((d.sv - sv).length() < 1e-7 * d.sv.length().max(1.0));
            let h2 = 1e-4;
            let dsu = |u: f64, v: f64| s.derivatives(u, v, 1).unwrap().su;
            let dsv = |u: f64, v: f64| s.derivatives(u, v, 1).unwrap().sv;
            assert!((d.suu - (dsu(u + h2, v) - dsu(u - h2, v)) / (2.0 * h2)).length() < 1e-5 * d.suu.length().max(1.0));
            assert!((d.suv - (dsu(u, v + h2) - dsu(u, v - h2)) / (2.0 * h2)).length() < 1e-5 * d.suv.length().max(1.0));
            assert!((d.svv - (dsv(u, v + h2) - dsv(u, v - h2)) / (2.0 * h2)).length() < 1e-5 * d.svv.length().max(1.0));
        }
    }

    #[test]
    fn order_zero_and_one_agree_with_order_two() {
        let s = wavy();
        let d2 = s.derivatives(0.37, 0.71, 2).unwrap();
        let d1 = s.derivatives(0.37, 0.71, 1).unwrap();
        assert!((d1.point - d2.point).length() < 1e-15 && (d1.su - d2.su).length() < 1e-13);
        assert_eq!(d1.suu, DVec3::ZERO);
        assert!(s.derivatives(0.1, 0.1, 3).is_err());
        assert!(s.point(f64::NAN, 0.0).is_err());
    }

    #[test]
    fn swap_uv_flips_normal() {
        let s = wavy();
        let t = s.swap_uv().unwrap();
        assert!((s.point(0.3, 0.6).unwrap() - t.point(0.6, 0.3).unwrap()).length() < 1e-14);
        assert!((s.normal(0.3, 0.6).unwrap() + t.normal(0.6, 0.3).unwrap()).length() < 1e-12);
    }
}
