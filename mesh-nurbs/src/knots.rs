//! Knot vectors `U = t_0 <= t_1 <= ... <= t_m` (chapter section 2.2.1): validation,
//! clamped and uniform constructors, span search.
//!
//! A knot vector of degree `p` for `n + 1` control points holds `m + 1 = n + p + 2`
//! knots; the curve is defined on the domain `[t_p, t_{n+1}]`.

use crate::basis::MAX_DEGREE;
use crate::error::{NurbsError, Result};

/// A validated knot vector together with its degree.
///
/// Invariants (checked by [`KnotVector::new`]): `1 <= degree <= MAX_DEGREE`,
/// every knot finite, knots non-decreasing (eq. 2.1 needs `t_i <= t_{i+1}`),
/// no knot repeated more than `degree + 1` times, at least `degree + 1` control
/// points, and a domain `[t_p, t_{n+1}]` of positive length.
#[derive(Debug, Clone, PartialEq)]
pub struct KnotVector {
    knots: Vec<f64>,
    degree: usize,
    /// Largest span index `i <= n` with `t_i < t_{n+1}`: the span of the domain end.
    last_span: usize,
    /// Per span `s = p..=n`, the reciprocals `1 / (t_{s+r+1} - t_{s+1-j+r})`
    /// for `j = 1..=p`, `r < j` (the denominators of eq. 2.2 on that span,
    /// which do not depend on `u`), so that evaluation never divides.
    inverse_differences: Vec<f64>,
}

impl KnotVector {
    /// Validates `knots` for a basis of `degree`. The number of control points
    /// is implied: `knots.len() - degree - 1`. Cost O(m).
    ///
    /// # Errors
    /// `NurbsError::Degree` outside 1..=`MAX_DEGREE`; `NurbsError::KnotCount` for fewer than 2 (degree + 1)
    /// knots; `NurbsError::NonFiniteKnot` / `NurbsError::DecreasingKnots` for bad values;
    /// `NurbsError::KnotMultiplicity` for a knot repeated more than degree + 1 times;
    /// `NurbsError::EmptyDomain` when the domain has zero length.
    pub fn new(degree: usize, knots: Vec<f64>) -> Result<Self> {
        if degree == 0 || degree > MAX_DEGREE {
            return Err(NurbsError::Degree { degree, max: MAX_DEGREE });
        }
        if knots.len() < 2 * (degree + 1) {
            let control_points = knots.len().saturating_sub(degree + 1);
            return Err(NurbsError::KnotCount { knots: knots.len(), degree, control_points });
        }
        check_values(&knots)?;
        check_multiplicity(&knots, degree)?;
        let n = knots.len() - degree - 2;
        let (start, end) = (knots[degree], knots[n + 1]);
        if start >= end {
            return Err(NurbsError::EmptyDomain { start, end });
        }
        // Exists since t_p < t_{n+1}.
        let last_span = (degree..=n).rev().find(|&i| knots[i] < end).unwrap_or(degree);
        let inverse_differences = inverse_differences(&knots, degree);
        Ok(Self { knots, degree, last_span, inverse_differences })
    }

    /// Validates `knots` and checks that they fit `control_points` control points.
    ///
    /// # Errors
    /// `NurbsError::KnotCount` unless there are `control_points + degree + 1` knots; the errors of
    /// [`KnotVector::new`].
    pub fn for_control_points(degree: usize, knots: Vec<f64>, control_points: usize) -> Result<Self> {
        if control_points.checked_add(degree + 1) != Some(knots.len()) {
            return Err(NurbsError::KnotCount { knots: knots.len(), degree, control_points });
        }
        Self::new(degree, knots)
    }

    /// Clamped (open) uniform knots on `[0, 1]`: `degree + 1` zeros, equally
    /// spaced interior knots, `degree + 1` ones. The curve interpolates its end
    /// control points. Cost O(n).
    ///
    /// # Errors
    /// `NurbsError::Degree` outside 1..=`MAX_DEGREE`; `NurbsError::KnotCount` for fewer than degree + 1
    /// control points.
    pub fn clamped_uniform(degree: usize, control_points: usize) -> Result<Self> {
        check_sizes(degree, control_points)?;
        let spans = control_points - degree;
        let mut knots = vec![0.0; degree + 1];
        knots.extend((1..spans).map(|i| i as f64 / spans as f64));
        knots.extend(std::iter::repeat_n(1.0, degree + 1));
        Self::new(degree, knots)
    }

    /// Uniform (unclamped, equally spaced) knots, scaled so that the domain
    /// `[t_p, t_{n+1}]` is `[0, 1]`. Cost O(n).
    ///
    /// # Errors
    /// `NurbsError::Degree` outside 1..=`MAX_DEGREE`; `NurbsError::KnotCount` for fewer than degree + 1
    /// control points.
    pub fn uniform(degree: usize, control_points: usize) -> Result<Self> {
        check_sizes(degree, control_points)?;
        let spans = (control_points - degree) as f64;
        let knots = (0..control_points + degree + 1).map(|i| (i as f64 - degree as f64) / spans).collect();
        Self::new(degree, knots)
    }

    /// Degree `p` of the basis.
    #[inline]
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The knots `t_0..=t_m`.
    #[inline]
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// Number of control points `n + 1 = m - p`.
    #[inline]
    pub fn control_count(&self) -> usize {
        self.knots.len() - self.degree - 1
    }

    /// The parameter domain `[t_p, t_{n+1}]`.
    #[inline]
    pub fn domain(&self) -> (f64, f64) {
        (self.knots[self.degree], self.knots[self.control_count()])
    }

    /// Clamps a parameter into the domain (NaN is left as is; callers check it).
    #[inline]
    pub fn clamp(&self, u: f64) -> f64 {
        let (a, b) = self.domain();
        if u < a {
            a
        } else if u > b {
            b
        } else {
            u
        }
    }

    /// The knot span `i` with `t_i <= u < t_{i+1}` and `p <= i <= n`, by binary
    /// search (Piegl & Tiller, The NURBS Book, A2.1). At the last knot of the
    /// domain it returns the last non-empty span, so that the basis is the
    /// limit from the left there. Parameters outside the domain are clamped.
    /// Cost O(log m).
    #[inline]
    pub fn span(&self, u: f64) -> usize {
        let n = self.control_count() - 1;
        let (_, end) = self.domain();
        if u >= end {
            return self.last_span;
        }
        // Number of interior knots t_{p+1..=n} that are <= u.
        self.degree + self.knots[self.degree + 1..=n].partition_point(|&t| t <= u)
    }

    /// `span` clamped into the valid range `p..=n`.
    #[inline]
    pub(crate) fn clamp_span(&self, span: usize) -> usize {
        span.clamp(self.degree, self.control_count() - 1)
    }

    /// Reciprocal knot differences of a non-empty span (see the field); entry
    /// `j (j - 1) / 2 + r` is `1 / (t_{s+r+1} - t_{s+1-j+r})`.
    #[inline]
    pub(crate) fn inverse_differences(&self, span: usize) -> &[f64] {
        let per_span = self.degree * (self.degree + 1) / 2;
        let start = (span - self.degree) * per_span;
        &self.inverse_differences[start..start + per_span]
    }

    /// Multiplicity of the value `u` in the knot vector (exact comparison). Cost O(log m).
    pub fn multiplicity(&self, u: f64) -> usize {
        let lo = self.knots.partition_point(|&t| t < u);
        let hi = self.knots.partition_point(|&t| t <= u);
        hi - lo
    }

    /// The distinct knot values inside the domain, in increasing order
    /// (breakpoints between polynomial pieces, ends included). Cost O(m).
    pub fn breakpoints(&self) -> Vec<f64> {
        let (a, b) = self.domain();
        let mut out: Vec<f64> = Vec::new();
        for &t in &self.knots {
            if t >= a && t <= b && out.last() != Some(&t) {
                out.push(t);
            }
        }
        out
    }
}

/// Table of [`KnotVector::inverse_differences`] for every span (0 where a
/// difference vanishes: empty spans, never evaluated).
fn inverse_differences(knots: &[f64], p: usize) -> Vec<f64> {
    let n = knots.len() - p - 2;
    let mut out = Vec::with_capacity((n + 1 - p) * p * (p + 1) / 2);
    for s in p..=n {
        for j in 1..=p {
            for r in 0..j {
                let d = knots[s + r + 1] - knots[s + 1 - j + r];
                out.push(if d > 0.0 { 1.0 / d } else { 0.0 });
            }
        }
    }
    out
}

fn check_sizes(degree: usize, control_points: usize) -> Result<()> {
    if degree == 0 || degree > MAX_DEGREE {
        return Err(NurbsError::Degree { degree, max: MAX_DEGREE });
    }
    if control_points <= degree || control_points > u32::MAX as usize {
        let knots = control_points.saturating_add(degree + 1);
        return Err(NurbsError::KnotCount { knots, degree, control_points });
    }
    Ok(())
}

fn check_values(knots: &[f64]) -> Result<()> {
    if let Some(index) = knots.iter().position(|t| !t.is_finite()) {
        return Err(NurbsError::NonFiniteKnot { index, value: knots[index] });
    }
    if let Some(index) = (1..knots.len()).find(|&i| knots[i] < knots[i - 1]) {
        return Err(NurbsError::DecreasingKnots { index, value: knots[index], previous: knots[index - 1] });
    }
    Ok(())
}

fn check_multiplicity(knots: &[f64], degree: usize) -> Result<()> {
    let mut run = 1;
    for i in 1..knots.len() {
        run = if knots[i] == knots[i - 1] { run + 1 } else { 1 };
        if run > degree + 1 {
            return Err(NurbsError::KnotMultiplicity { value: knots[i], multiplicity: run, max: degree + 1 });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clamped_uniform_layout() {
        let kv = KnotVector::clamped_uniform(3, 6).unwrap();
        assert_eq!(kv.knots(), &[0.0, 0.0, 0.0, 0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0, 1.0, 1.0, 1.0]);
        assert_eq!(kv.domain(), (0.0, 1.0));
        assert_eq!(kv.control_count(), 6);
    }

    #[test]
    fn uniform_domain_is_unit() {
        let kv = KnotVector::uniform(2, 5).unwrap();
        let (a, b) = kv.domain();
        assert!((a - 0.0).abs() < 1e-15 && (b - 1.0).abs() < 1e-15);
    }

    #[test]
    fn span_search() {
        let kv = KnotVector::new(2, vec![0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 4.0, 4.0, 5.0, 5.0, 5.0]).unwrap();
        assert_eq!(kv.span(0.0), 2);
        assert_eq!(kv.span(0.5), 2);
        assert_eq!(kv.span(1.0), 3);
        assert_eq!(kv.span(2.5), 4);
        assert_eq!(kv.span(4.0), 7);
        assert_eq!(kv.span(4.999), 7);
        assert_eq!(kv.span(5.0), 7);
        assert_eq!(kv.span(7.0), 7);
        assert_eq!(kv.span(-1.0), 2);
    }

    #[test]
    fn last_span_skips_empty_spans() {
        let kv = KnotVector::new(2, vec![0.0, 0.0, 0.0, 1.0, 2.0, 2.0, 3.0, 4.0]).unwrap();
        assert_eq!(kv.domain(), (0.0, 2.0));
        assert_eq!(kv.span(2.0), 3);
    }

    #[test]
    fn rejects_bad_knots() {
        assert!(matches!(
            KnotVector::new(2, vec![0.0, 0.0, 1.0, 0.5, 1.0, 1.0]),
            Err(NurbsError::DecreasingKnots { .. })
        ));
        assert!(matches!(KnotVector::new(1, vec![0.0, f64::NAN, 1.0, 1.0]), Err(NurbsError::NonFiniteKnot { .. })));
        assert!(matches!(KnotVector::new(3, vec![0.0; 4]), Err(NurbsError::KnotCount { .. })));
        assert!(matches!(KnotVector::new(1, vec![0.0, 0.0, 0.0, 1.0]), Err(NurbsError::KnotMultiplicity { .. })));
        assert!(KnotVector::new(1, vec![0.0, 1.0, 2.0, 3.0]).is_ok());
        assert!(matches!(KnotVector::new(0, vec![0.0, 1.0]), Err(NurbsError::Degree { .. })));
        assert!(matches!(KnotVector::new(1, vec![1.0, 1.0, 1.0, 2.0]), Err(NurbsError::KnotMultiplicity { .. })));
        assert!(matches!(KnotVector::new(1, vec![0.0, 1.0, 1.0, 3.0]), Err(NurbsError::EmptyDomain { .. })));
        assert!(matches!(
            KnotVector::for_control_points(1, vec![0.0, 0.0, 1.0, 1.0], 3),
            Err(NurbsError::KnotCount { .. })
        ));
        assert!(matches!(KnotVector::clamped_uniform(3, 3), Err(NurbsError::KnotCount { .. })));
    }
}
