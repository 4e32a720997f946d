//! NURBS curves `C(u) = sum_i w_i P_i N_{i,p}(u) / sum_i w_i N_{i,p}(u)`, the
//! one-parameter case of eq. 2.3-2.4: evaluation, derivatives, curvature, knot
//! insertion and affine maps.

use glam::{DAffine3, DVec3, DVec4};

use crate::basis::{basis_derivatives_into, basis_values};
use crate::error::{check_param, NurbsError, Result};
use crate::knots::KnotVector;

/// A NURBS curve: a knot vector, control points and positive weights.
///
/// Points and weights are kept as given (so that they serialize back
/// unchanged) together with the homogeneous points `(w x, w y, w z, w)` that
/// evaluation uses.
#[derive(Debug, Clone, PartialEq)]
pub struct NurbsCurve {
    knots: KnotVector,
    points: Vec<DVec3>,
    weights: Vec<f64>,
    homogeneous: Vec<DVec4>,
}

impl NurbsCurve {
    /// Builds a curve after checking that there are as many control points and
    /// weights as the knots ask for, that points are finite and weights finite
    /// and positive. Cost O(n).
    ///
    /// # Errors
    /// `NurbsError::Count` when `points` or `weights` do not have one entry per control point of `knots`;
    /// `NurbsError::NonFiniteControlPoint` for a NaN or infinite point; `NurbsError::Weight` for a weight
    /// that is not finite and > 0.
    pub fn new(knots: KnotVector, points: Vec<DVec3>, weights: Vec<f64>) -> Result<Self> {
        check_count("control points", knots.control_count(), points.len())?;
        let homogeneous = homogeneous(&points, &weights)?;
        Ok(Self { knots, points, weights, homogeneous })
    }

    /// A polynomial B-spline curve (all weights 1). Cost O(n).
    ///
    /// # Errors
    /// As [`NurbsCurve::new`] (`NurbsError::Count`, `NurbsError::NonFiniteControlPoint`).
    pub fn non_rational(knots: KnotVector, points: Vec<DVec3>) -> Result<Self> {
        let weights = vec![1.0; points.len()];
        Self::new(knots, points, weights)
    }

    /// Builds a curve from homogeneous points `(w x, w y, w z, w)`.
    pub(crate) fn from_homogeneous(knots: KnotVector, homogeneous: Vec<DVec4>) -> Result<Self> {
        let (points, weights) = cartesian(&homogeneous);
        Self::new(knots, points, weights)
    }

    /// The knot vector (and degree).
    pub fn knots(&self) -> &KnotVector {
        &self.knots
    }

    /// Degree `p`.
    pub fn degree(&self) -> usize {
        self.knots.degree()
    }

    /// Control points `P_i`.
    pub fn control_points(&self) -> &[DVec3] {
        &self.points
    }

    /// Weights `w_i`.
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// Homogeneous control points `(w_i P_i, w_i)`.
    pub fn homogeneous_points(&self) -> &[DVec4] {
        &self.homogeneous
    }

    /// Parameter domain `[t_p, t_{n+1}]`.
    pub fn domain(&self) -> (f64, f64) {
        self.knots.domain()
    }

    /// The point `C(u)` (eq. 2.3-2.4 in one variable; Piegl & Tiller A4.1).
    /// Finite parameters outside the domain are clamped into it; NaN and
    /// infinities give [`NurbsError::NonFiniteParameter`]. Cost O(p^2).
    ///
    /// # Errors
    /// `NurbsError::NonFiniteParameter` for a NaN or infinite `u` (finite values are clamped to the domain).
    pub fn point(&self, u: f64) -> Result<DVec3> {
        check_param("u", u)?;
        let u = self.knots.clamp(u);
        let span = self.knots.span(u);
        let n = basis_values(&self.knots, span, u);
        let first = span - self.degree();
        let h: DVec4 = (0..=self.degree()).map(|j| self.homogeneous[first + j] * n[j]).sum();
        Ok(h.truncate() / h.w)
    }

    /// `C(u)` and its derivatives of orders `1..=order`: entry `k` is
    /// `d^k C / du^k`, from the derivatives of the homogeneous curve by the
    /// quotient rule (Piegl & Tiller A3.2 and A4.2). Allocates two small vectors.
    /// Cost O(p^2 + order p + order^2).
    ///
    /// # Errors
    /// `NurbsError::NonFiniteParameter` for a NaN or infinite `u`.
    pub fn derivatives(&self, u: f64, order: usize) -> Result<Vec<DVec3>> {
        check_param("u", u)?;
        let u = self.knots.clamp(u);
        let p = self.degree();
        let span = self.knots.span(u);
        let mut basis = vec![0.0; (order + 1) * (p + 1)];
        basis_derivatives_into(&self.knots, span, u, order, &mut basis)?;
        let first = span - p;
        let homogeneous: Vec<DVec4> =
            (0..=order).map(|k| (0..=p).map(|j| self.homogeneous[first + j] * basis[k * (p + 1) + j]).sum()).collect();
        let mut out: Vec<DVec3> = Vec::with_capacity(order + 1);
        for k in 0..=order {
            let mut v = homogeneous[k].truncate();
            let mut binomial = 1.0;
            for i in 1..=k {
                binomial = binomial * (k + 1 - i) as f64 / i as f64;
                v -= out[k - i] * (binomial * homogeneous[i].w);
            }
            out.push(v / homogeneous[0].w);
        }
        Ok(out)
    }

    /// Unit tangent `C'(u) / |C'(u)|`, or zero where the derivative vanishes.
    /// Cost O(p^2).
    ///
    /// # Errors
    /// `NurbsError::NonFiniteParameter` for a NaN or infinite `u`.
    pub fn tangent(&self, u: f64) -> Result<DVec3> {
        let d = self.derivatives(u, 1)?;
        Ok(d[1].normalize_or_zero())
    }

    /// Curvature `|C' x C''| / |C'|^3` (eq. 2.17: the inverse radius of the
    /// osculating circle), 0 where `C'` vanishes. Cost O(p^2).
    ///
    /// # Errors
    /// `NurbsError::NonFiniteParameter` for a NaN or infinite `u`.
    pub fn curvature(&self, u: f64) -> Result<f64> {
        let d = self.derivatives(u, 2)?;
        let speed = d[1].length();
        if speed == 0.0 {
            return Ok(0.0);
        }
        Ok(d[1].cross(d[2]).length() / (speed * speed * speed))
    }

    /// The same curve with the knot `u` inserted `times` times (Boehm's
    /// algorithm, Piegl & Tiller A5.1): the shape and parameterization are
    /// unchanged. `u` must lie inside the open domain and its multiplicity stay
    /// at most the degree. Cost O(n + times p).
    ///
    /// # Errors
    /// `NurbsError::NonFiniteParameter` for a NaN or infinite `u`; `NurbsError::KnotInsertion` when `u` is
    /// outside the domain or the multiplicity would exceed the degree.
    pub fn insert_knot(&self, u: f64, times: usize) -> Result<Self> {
        let (knots, homogeneous) = insert_knot_line(&self.knots, &self.homogeneous, u, times)?;
        Self::from_homogeneous(knots, homogeneous)
    }

    /// The same curve with its degree raised by one, exactly (same points for
    /// the same parameters). Needs clamped knots (end knots of multiplicity
    /// `p + 1`). Method: split into Bezier pieces by knot insertion (A5.1),
    /// elevate each piece with `Q_i = i/(p+1) P_{i-1} + (1 - i/(p+1)) P_i` on
    /// homogeneous points, and join them; interior knots come out with
    /// multiplicity `p + 1` (no knot removal, so the result is exact but not
    /// minimal; A5.9 of Piegl & Tiller gives the minimal form).
    /// Cost O(n p).
    ///
    /// # Errors
    /// `NurbsError::NotClamped` for unclamped knots; `NurbsError::Degree` beyond the maximal degree.
    pub fn elevate_degree(&self) -> Result<Self> {
        let (knots, homogeneous) = elevate_degree_line(&self.knots, &self.homogeneous)?;
        Self::from_homogeneous(knots, homogeneous)
    }

    /// The image of the curve under an affine map (NURBS are affinely
    /// invariant: map the control points, keep the weights). Cost O(n).
    ///
    /// # Errors
    /// `NurbsError::NonFiniteControlPoint` when the map sends a control point to a non-finite position.
    pub fn transform(&self, map: &DAffine3) -> Result<Self> {
        let points = self.points.iter().map(|&p| map.transform_point3(p)).collect();
        Self::new(self.knots.clone(), points, self.weights.clone())
    }
}

/// Checks a count against what the knots ask for.
pub(crate) fn check_count(what: &'static str, expected: usize, found: usize) -> Result<()> {
    if expected == found {
        Ok(())
    } else {
        Err(NurbsError::Count { what, expected, found })
    }
}

/// Validates points and weights and builds the homogeneous points `(w P, w)`.
pub(crate) fn homogeneous(points: &[DVec3], weights: &[f64]) -> Result<Vec<DVec4>> {
    check_count("weights", points.len(), weights.len())?;
    if let Some(index) = points.iter().position(|p| !p.is_finite()) {
        return Err(NurbsError::NonFiniteControlPoint { index });
    }
    if let Some(index) = weights.iter().position(|w| !(w.is_finite() && *w > 0.0)) {
        return Err(NurbsError::Weight { index, value: weights[index] });
    }
    let out: Vec<DVec4> = points.iter().zip(weights).map(|(&p, &w)| (p * w).extend(w)).collect();
    if let Some(index) = out.iter().position(|h| !h.is_finite()) {
        return Err(NurbsError::NonFiniteControlPoint { index });
    }
    Ok(out)
}

/// Splits homogeneous points back into points and weights.
pub(crate) fn cartesian(homogeneous: &[DVec4]) -> (Vec<DVec3>, Vec<f64>) {
    homogeneous.iter().map(|h| (h.truncate() / h.w, h.w)).unzip()
}

/// Boehm knot insertion on one line of homogeneous control points (Piegl &
/// Tiller A5.1). Returns the new knot vector and control points.
pub(crate) fn insert_knot_line(
    kv: &KnotVector,
    pw: &[DVec4],
    u: f64,
    times: usize,
) -> Result<(KnotVector, Vec<DVec4>)> {
    let (span, s) = check_insertion(kv, u, times)?;
    let p = kv.degree();
    let t = kv.knots();
    let r = times;
    let np = pw.len() - 1;
    let mut knots = Vec::with_capacity(t.len() + r);
    knots.extend_from_slice(&t[..=span]);
    knots.extend(std::iter::repeat_n(u, r));
    knots.extend_from_slice(&t[span + 1..]);
    let mut q = vec![DVec4::ZERO; np + r + 1];
    q[..=span - p].copy_from_slice(&pw[..=span - p]);
    q[span - s + r..].copy_from_slice(&pw[span - s..]);
    let mut tmp: Vec<DVec4> = pw[span - p..=span - s].to_vec();
    let mut l = span - p;
    for j in 1..=r {
        l = span - p + j;
        for i in 0..=p - j - s {
            let alpha = (u - t[l + i]) / (t[i + span + 1] - t[l + i]);
            tmp[i] = tmp[i + 1] * alpha + tmp[i] * (1.0 - alpha);
        }
        q[l] = tmp[0];
        q[span + r - j - s] = tmp[p - j - s];
    }
    if l + 1 < span - s {
        q[l + 1..span - s].copy_from_slice(&tmp[1..span - s - l]);
    }
    Ok((KnotVector::new(p, knots)?, q))
}

/// Degree elevation by one of a line of homogeneous points on clamped knots
/// (Bezier decomposition, per-piece elevation, joining).
pub(crate) fn elevate_degree_line(kv: &KnotVector, pw: &[DVec4]) -> Result<(KnotVector, Vec<DVec4>)> {
    let p = kv.degree();
    let t = kv.knots();
    let (a, b) = kv.domain();
    if t[0] != a || t[t.len() - 1] != b {
        return Err(NurbsError::NotClamped { operation: "degree elevation" });
    }
    // Bezier decomposition: every interior knot to multiplicity p.
    let mut knots = kv.clone();
    let mut line = pw.to_vec();
    let bp = kv.breakpoints();
    for &u in &bp[1..bp.len() - 1] {
        let s = knots.multiplicity(u);
        if s < p {
            (knots, line) = insert_knot_line(&knots, &line, u, p - s)?;
        }
    }
    let pieces = bp.len() - 1;
    let mut out = Vec::with_capacity(pieces * (p + 1) + 1);
    out.push(line[0]);
    for piece in line.windows(p + 1).step_by(p) {
        for i in 1..=p {
            let alpha = i as f64 / (p + 1) as f64;
            out.push(piece[i - 1] * alpha + piece[i] * (1.0 - alpha));
        }
        out.push(piece[p]);
    }
    let mut new_knots = vec![a; p + 2];
    for &u in &bp[1..bp.len() - 1] {
        new_knots.extend(std::iter::repeat_n(u, p + 1));
    }
    new_knots.extend(std::iter::repeat_n(b, p + 2));
    Ok((KnotVector::new(p + 1, new_knots)?, out))
}

/// Span and multiplicity of a knot to insert, or why it cannot be inserted.
fn check_insertion(kv: &KnotVector, u: f64, times: usize) -> Result<(usize, usize)> {
    let refuse = |reason: String| Err(NurbsError::KnotInsertion { value: u, times, reason });
    let (a, b) = kv.domain();
    if !(u > a && u < b) {
        return refuse(format!("the knot must lie inside the open domain ({a}, {b})"));
    }
    if times == 0 {
        return refuse("insert at least once".into());
    }
    let s = kv.multiplicity(u);
    if s + times > kv.degree() {
        return refuse(format!("multiplicity would be {} > degree {}", s + times, kv.degree()));
    }
    Ok((kv.span(u), s))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cubic() -> NurbsCurve {
        let kv = KnotVector::new(3, vec![0.0, 0.0, 0.0, 0.0, 0.4, 0.7, 1.0, 1.0, 1.0, 1.0]).unwrap();
        let pts = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 2.0, 0.5),
            DVec3::new(2.0, -1.0, 1.0),
            DVec3::new(3.0, 0.5, -0.5),
            DVec3::new(4.0, 2.0, 0.0),
            DVec3::new(5.0, 0.0, 1.0),
        ];
        NurbsCurve::new(kv, pts, vec![1.0, 2.0, 0.5, 1.5, 1.0, 0.8]).unwrap()
    }

    #[test]
    fn interpolates_ends_and_matches_derivatives_order_zero() {
        let c = cubic();
        assert!((c.point(0.0).unwrap() - DVec3::ZERO).length() < 1e-15);
        assert!((c.point(1.0).unwrap() - DVec3::new(5.0, 0.0, 1.0)).length() < 1e-14);
        for s in 0..=20 {
            let u = s as f64 / 20.0;
            assert!((c.point(u).unwrap() - c.derivatives(u, 0).unwrap()[0]).length() < 1e-14);
        }
    }

    #[test]
    fn derivatives_match_finite_differences() {
        let c = cubic();
        let h = 1e-5;
        for &u in &[0.1, 0.33, 0.5, 0.85] {
            let d = c.derivatives(u, 2).unwrap();
            let (pm, p0, pp) = (c.point(u - h).unwrap(), c.point(u).unwrap(), c.point(u + h).unwrap());
            assert!((d[1] - (pp - pm) / (2.0 * h)).length() < 1e-7 * d[1].length().max(1.0));
            assert!((d[2] - (pp - 2.0 * p0 + pm) / (h * h)).length() < 1e-3 * d[2].length().max(1.0));
        }
    }

    #[test]
    fn knot_insertion_keeps_the_curve() {
        let c = cubic();
        for (u, times) in [(0.2, 1), (0.4, 2), (0.55, 3), (0.7, 1)] {
            let d = c.insert_knot(u, times).unwrap();
            assert_eq!(d.control_points().len(), c.control_points().len() + times);
            for s in 0..=40 {
                let x = s as f64 / 40.0;
                assert!((c.point(x).unwrap() - d.point(x).unwrap()).length() < 1e-13);
            }
        }
        assert!(c.insert_knot(0.4, 3).is_err());
        assert!(c.insert_knot(0.0, 1).is_err());
        assert!(c.insert_knot(f64::NAN, 1).is_err());
    }

    #[test]
    fn degree_elevation_keeps_the_curve() {
        let c = cubic();
        let mut e = c.elevate_degree().unwrap();
        for _ in 0..2 {
            assert_eq!(e.degree(), c.degree() + 1);
            for s in 0..=50 {
                let x = s as f64 / 50.0;
                assert!((c.point(x).unwrap() - e.point(x).unwrap()).length() < 1e-13);
                assert!((c.derivatives(x, 1).unwrap()[1] - e.derivatives(x, 1).unwrap()[1]).length() < 1e-10);
            }
            let twice = e.elevate_degree().unwrap();
            assert_eq!(twice.degree(), e.degree() + 1);
            e = twice.clone();
            if e.degree() == 5 {
                break;
            }
        }
        let open = NurbsCurve::non_rational(KnotVector::uniform(2, 4).unwrap(), vec![DVec3::ZERO; 4]).unwrap();
        assert!(matches!(open.elevate_degree(), Err(NurbsError::NotClamped { .. })));
    }

    #[test]
    fn refuses_bad_input() {
        let kv = KnotVector::clamped_uniform(1, 2).unwrap();
        let pts = vec![DVec3::ZERO, DVec3::X];
        assert!(matches!(NurbsCurve::new(kv.clone(), pts.clone(), vec![1.0, 0.0]), Err(NurbsError::Weight { .. })));
        assert!(matches!(NurbsCurve::new(kv.clone(), pts.clone(), vec![1.0]), Err(NurbsError::Count { .. })));
        assert!(matches!(
            NurbsCurve::new(kv.clone(), vec![DVec3::ZERO, DVec3::NAN], vec![1.0, 1.0]),
            Err(NurbsError::NonFiniteControlPoint { index: 1 })
        ));
        let c = NurbsCurve::non_rational(kv, pts).unwrap();
        assert!(matches!(c.point(f64::INFINITY), Err(NurbsError::NonFiniteParameter { .. })));
        assert_eq!(c.point(2.0).unwrap(), DVec3::X);
    }
}
