//! Input checks shared by every entry point, the unit the points are
//! triangulated in, and the small planar formulas (orientation,
//! circumcentre) the modules share.

use glam::DVec2;
use mesh_kernel::geometry::power_of_two_near;

use crate::error::{DelaunayError, Result};

/// A power of two near the largest coordinate magnitude (`unit <= largest
/// < 2 unit`; 1 when every coordinate is zero), after checking that every
/// coordinate is finite and that every coordinate divided by it is in the
/// range of spade's exact predicates. Division by a power of two is exact,
/// so the triangulation of the scaled points is that of the points. O(n).
///
/// # Errors
///
/// [`DelaunayError::NonFinite`], [`DelaunayError::OutOfRange`].
pub(crate) fn unit_of_points(points: &[DVec2]) -> Result<f64> {
    let mut largest = 0.0_f64;
    for (index, p) in points.iter().enumerate() {
        if !p.is_finite() {
            return Err(DelaunayError::NonFinite { index });
        }
        largest = largest.max(p.x.abs()).max(p.y.abs());
    }
    let unit = if largest > 0.0 { power_of_two_near(largest) } else { 1.0 };
    for (index, p) in points.iter().enumerate() {
        for c in [p.x / unit, p.y / unit] {
            if let Err(e) = spade::validate_coordinate(c) {
                return Err(DelaunayError::OutOfRange { index, reason: format!("{e:?}") });
            }
        }
    }
    Ok(unit)
}

/// Twice the signed area of (a, b, c): positive when counter-clockwise.
#[inline]
pub(crate) fn orient(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    (b - a).perp_dot(c - a)
}

/// Orientation with a relative threshold: +1 when (a, b, c) is
/// counter-clockwise by more than `rel` times the product of two edge
/// lengths, -1 when clockwise by as much, 0 otherwise (nearly collinear).
#[inline]
pub(crate) fn orient_sign(a: DVec2, b: DVec2, c: DVec2, rel: f64) -> i32 {
    let d = orient(a, b, c);
    let scale = (b - a).length() * (c - a).length();
    if d > rel * scale {
        1
    } else if d < -rel * scale {
        -1
    } else {
        0
    }
}

/// Circumcentre of (a, b, c), computed relative to `a`; `None` when the
/// triangle is degenerate (the centre is not finite).
#[inline]
pub(crate) fn circumcenter(a: DVec2, b: DVec2, c: DVec2) -> Option<DVec2> {
    let (u, v) = (b - a, c - a);
    let d = 2.0 * u.perp_dot(v);
    if d == 0.0 {
        return None;
    }
    let (uu, vv) = (u.length_squared(), v.length_squared());
    let o = a + DVec2::new(v.y * uu - u.y * vv, u.x * vv - v.x * uu) / d;
    o.is_finite().then_some(o)
}

/// Area of the triangle (a, b, c), signed (positive counter-clockwise).
#[inline]
pub(crate) fn signed_area(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    0.5 * orient(a, b, c)
}

/// Signed area of a closed polygon (shoelace, positive counter-clockwise).
pub(crate) fn polygon_area(poly: &[DVec2]) -> f64 {
    let n = poly.len();
    if n < 3 {
        return 0.0;
    }
    let o = poly[0];
    (1..n - 1).map(|i| signed_area(o, poly[i], poly[i + 1])).sum()
}

/// Whether `p` is strictly inside the closed polygon (even-odd rule; points
/// on the boundary may go either way).
pub(crate) fn point_in_polygon(p: DVec2, poly: &[DVec2]) -> bool {
    let mut inside = false;
    let n = poly.len();
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        if (a.y > p.y) != (b.y > p.y) {
            let x = a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
            if p.x < x {
                inside = !inside;
            }
        }
    }
    inside
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn circumcentre_is_equidistant_and_degenerate_is_none() {
        let (a, b, c) = (DVec2::new(0.0, 0.0), DVec2::new(4.0, 0.0), DVec2::new(1.0, 3.0));
        let o = circumcenter(a, b, c).expect("a proper triangle");
        let r = (o - a).length();
        assert!(((o - b).length() - r).abs() < 1e-12 && ((o - c).length() - r).abs() < 1e-12);
        assert!(circumcenter(a, b, DVec2::new(8.0, 0.0)).is_none());
    }

    #[test]
    fn units_and_range() {
        assert_eq!(unit_of_points(&[DVec2::new(3.0, -5.0)]), Ok(4.0));
        assert_eq!(unit_of_points(&[DVec2::ZERO]), Ok(1.0));
        assert!(matches!(unit_of_points(&[DVec2::new(f64::NAN, 0.0)]), Err(DelaunayError::NonFinite { index: 0 })));
        let spread = [DVec2::new(1.0, 0.0), DVec2::new(1e-50, 0.0)];
        assert!(matches!(unit_of_points(&spread), Err(DelaunayError::OutOfRange { index: 1, .. })));
        assert_eq!(unit_of_points(&[DVec2::new(1e300, -1e290)]).map(|u| u > 1e299), Ok(true));
    }

    #[test]
    fn polygon_area_and_inside() {
        let sq = [DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y];
        assert_eq!(polygon_area(&sq), 1.0);
        assert!(point_in_polygon(DVec2::splat(0.5), &sq) && !point_in_polygon(DVec2::splat(1.5), &sq));
    }
}
