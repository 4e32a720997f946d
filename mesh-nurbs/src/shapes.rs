//! Exact NURBS shapes: circular arcs and circles (rational quadratic), lines,
//! surfaces of revolution, sphere, torus, cylinder, cone and bilinear patch.
//!
//! Closed surfaces are oriented so that the normal `s_u x s_v` points
//! outward. Surfaces of revolution turn about the `z` axis with `u` the angle
//! (counter-clockwise seen from `+z`) and `v` the profile parameter.

use std::f64::consts::{FRAC_PI_2, TAU};

use glam::{DAffine3, DMat3, DVec3};

use crate::curve::NurbsCurve;
use crate::error::{NurbsError, Result};
use crate::knots::KnotVector;
use crate::surface::NurbsSurface;

/// Circular arc of `radius` about `center` in the plane `z = center.z`, from
/// angle `start` to `end` (radians, counter-clockwise, `end - start` in
/// `(0, 2 pi]`), as a rational quadratic curve of one to four pieces of at
/// most 90 degrees (Piegl & Tiller A7.1): corner weights `cos(d/2)` for a
/// piece of angle `d`, knots doubled between pieces. Every point lies on the
/// circle to rounding. Cost O(1).
///
/// # Errors
/// `NurbsError::Shape` for a radius that is not finite and > 0, a non-finite center, or angles that do not
/// span (0, 2 pi].
pub fn arc(center: DVec3, radius: f64, start: f64, end: f64) -> Result<NurbsCurve> {
    check_positive("radius", radius)?;
    check_finite("center", center)?;
    let sweep = end - start;
    if !(start.is_finite() && end.is_finite() && sweep > 0.0 && sweep <= TAU) {
        return Err(NurbsError::Shape(format!("arc angles {start} .. {end} must span (0, 2 pi]")));
    }
    let pieces = (sweep / FRAC_PI_2).ceil().clamp(1.0, 4.0) as usize;
    let step = sweep / pieces as f64;
    let corner_weight = (0.5 * step).cos();
    let on_circle = |angle: f64, r: f64| center + DVec3::new(snap(angle.cos()), snap(angle.sin()), 0.0) * r;
    let mut points = vec![on_circle(start, radius)];
    let mut weights = vec![1.0];
    for k in 1..=pieces {
        let mid = start + (k as f64 - 0.5) * step;
        points.push(on_circle(mid, radius / corner_weight));
        weights.push(corner_weight);
        points.push(on_circle(start + k as f64 * step, radius));
        weights.push(1.0);
    }
    if sweep == TAU {
        // Close exactly, whatever the rounding of cos and sin.
        points[2 * pieces] = points[0];
    }
    let mut knots = vec![0.0; 3];
    for k in 1..pieces {
        let t = k as f64 / pieces as f64;
        knots.extend([t, t]);
    }
    knots.extend([1.0; 3]);
    NurbsCurve::new(KnotVector::new(2, knots)?, points, weights)
}

/// Full circle of `radius` about `center` in the plane `z = center.z`,
/// counter-clockwise from angle 0: four rational quadratic quarter arcs with
/// nine control points (weights `1, sqrt(2)/2, 1, ...`). Cost O(1).
///
/// # Errors
/// `NurbsError::Shape` for a radius that is not finite and > 0 or a non-finite center.
pub fn circle(center: DVec3, radius: f64) -> Result<NurbsCurve> {
    arc(center, radius, 0.0, TAU)
}

/// Straight segment from `a` to `b` as a degree-1 curve on `[0, 1]`. Cost O(1).
///
/// # Errors
/// `NurbsError::Shape` for a non-finite end.
pub fn line(a: DVec3, b: DVec3) -> Result<NurbsCurve> {
    check_finite("line end", a)?;
    check_finite("line end", b)?;
    NurbsCurve::non_rational(KnotVector::clamped_uniform(1, 2)?, vec![a, b])
}

/// Surface of revolution of `profile` about the `z` axis by `angle` radians
/// (`(0, 2 pi]`), `u` along the turn and `v` along the profile (Piegl & Tiller
/// A8.1). Each profile control point `(x, y, z)` with weight `w` is turned along
/// the unit arc of [`arc`]: control point `c_k (x + i y)` in complex notation,
/// height `z`, weight `w_k w`. The normal `s_u x s_v` points away from the axis
/// where the profile rises (`dz/dv > 0`) on the `x > 0` side. Cost O(n).
///
/// # Errors
/// `NurbsError::Shape` for an angle outside (0, 2 pi]; `NurbsError::NonFiniteControlPoint` if the profile has
/// non-finite control points.
pub fn revolve(profile: &NurbsCurve, angle: f64) -> Result<NurbsSurface> {
    let turn = arc(DVec3::ZERO, 1.0, 0.0, angle)?;
    let mut points = Vec::with_capacity(turn.control_points().len() * profile.control_points().len());
    let mut weights = Vec::with_capacity(points.capacity());
    for (c, &wc) in turn.control_points().iter().zip(turn.weights()) {
        for (p, &wp) in profile.control_points().iter().zip(profile.weights()) {
            points.push(DVec3::new(c.x * p.x - c.y * p.y, c.y * p.x + c.x * p.y, p.z));
            weights.push(wc * wp);
        }
    }
    NurbsSurface::new(turn.knots().clone(), profile.knots().clone(), points, weights)
}

/// Sphere of `radius` about `center`, outward normal: a half circle from the
/// south pole to the north pole (in the `xz` plane) revolved about the `z`
/// axis. Degrees (2, 2), 9 x 5 control points; poles at `v = 0` and `v = 1`.
/// `K = 1/r^2`, `H = 1/r`. Cost O(1).
///
/// # Errors
/// `NurbsError::Shape` for a radius that is not finite and > 0 or a non-finite center.
pub fn sphere(center: DVec3, radius: f64) -> Result<NurbsSurface> {
    check_finite("center", center)?;
    let half = arc(DVec3::ZERO, radius, -FRAC_PI_2, FRAC_PI_2)?;
    translated(revolve(&into_xz(&half)?, TAU)?, center)
}

/// Ring torus about the `z` axis through `center`: tube of radius `minor`
/// whose centre circle has radius `major > minor > 0`. `u` turns about the
/// axis, `v` around the tube (counter-clockwise in the `xz` half plane from
/// the outer equator, `v = 0`). With `theta` the tube angle at `v`,
/// `K = cos theta / (r (R + r cos theta))`, principal curvatures `1/r` and
/// `cos theta / (R + r cos theta)`. Degrees (2, 2), 9 x 9 control points.
/// Cost O(1).
///
/// # Errors
/// `NurbsError::Shape` for radii that are not finite and > 0, a major radius not above the minor one, or a
/// non-finite center.
pub fn torus(center: DVec3, major: f64, minor: f64) -> Result<NurbsSurface> {
    check_finite("center", center)?;
    check_positive("minor radius", minor)?;
    if !(major > minor && major.is_finite()) {
        return Err(NurbsError::Shape(format!("major radius {major} must exceed the minor radius {minor}")));
    }
    let tube = circle(DVec3::new(major, 0.0, 0.0), minor)?;
    translated(revolve(&into_xz(&tube)?, TAU)?, center)
}

/// Open cylinder of `radius` about the `z` axis from `base` to `base + height
/// z`, outward normal. Degrees (2, 1); `v` runs from the bottom rim to the top
/// rim. Cost O(1).
///
/// # Errors
/// `NurbsError::Shape` for a radius or height that is not finite and > 0 or a non-finite base.
pub fn cylinder(base: DVec3, radius: f64, height: f64) -> Result<NurbsSurface> {
    check_positive("radius", radius)?;
    check_positive("height", height)?;
    let side = line(DVec3::new(radius, 0.0, 0.0), DVec3::new(radius, 0.0, height))?;
    translated(revolve(&side, TAU)?, base)
}

/// Open cone about the `z` axis: base circle of `radius` at `base`, apex at
/// `base + height z` (`v = 1`), outward normal. At the apex the surface is
/// singular: frames there are flagged non-regular (see [`crate::frame`]).
/// Degrees (2, 1). Cost O(1).
///
/// # Errors
/// `NurbsError::Shape` for a radius or height that is not finite and > 0 or a non-finite base.
pub fn cone(base: DVec3, radius: f64, height: f64) -> Result<NurbsSurface> {
    check_positive("radius", radius)?;
    check_positive("height", height)?;
    let side = line(DVec3::new(radius, 0.0, 0.0), DVec3::new(0.0, 0.0, height))?;
    translated(revolve(&side, TAU)?, base)
}

/// Bilinear patch through four corners: `S(0,0) = p00`, `S(1,0) = p10`,
/// `S(0,1) = p01`, `S(1,1) = p11` (degrees (1, 1)). Cost O(1).
///
/// # Errors
/// `NurbsError::NonFiniteControlPoint` for a non-finite corner.
pub fn bilinear(p00: DVec3, p10: DVec3, p01: DVec3, p11: DVec3) -> Result<NurbsSurface> {
    let k = KnotVector::clamped_uniform(1, 2)?;
    NurbsSurface::non_rational(k.clone(), k, vec![p00, p01, p10, p11])
}

/// Maps a curve drawn in the `xy` plane into the `xz` plane: `(x, y, z) ->
/// (x, -z, y)`, exactly (no rounding from a rotation angle).
fn into_xz(curve: &NurbsCurve) -> Result<NurbsCurve> {
    curve.transform(&DAffine3::from_mat3(DMat3::from_cols(DVec3::X, DVec3::Z, DVec3::NEG_Y)))
}

fn translated(surface: NurbsSurface, offset: DVec3) -> Result<NurbsSurface> {
    if offset == DVec3::ZERO {
        return Ok(surface);
    }
    surface.transform(&DAffine3::from_translation(offset))
}

/// cos and sin of multiples of pi/2 are not exactly 0 and 1 in floating point:
/// snap values within rounding of 0 so that poles sit exactly on the axis.
fn snap(x: f64) -> f64 {
    if x.abs() < 4.0 * f64::EPSILON {
        0.0
    } else {
        x
    }
}

fn check_positive(name: &str, x: f64) -> Result<()> {
    if x.is_finite() && x > 0.0 {
        Ok(())
    } else {
        Err(NurbsError::Shape(format!("{name} must be finite and > 0, got {x}")))
    }
}

fn check_finite(name: &str, p: DVec3) -> Result<()> {
    if p.is_finite() {
        Ok(())
    } else {
        Err(NurbsError::Shape(format!("{name} must be finite, got {p}")))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arcs_lie_on_their_circle() {
        for (a, b) in [(0.0, 0.3), (0.2, 2.0), (-1.0, 3.0), (0.5, 0.5 + TAU)] {
            let c = arc(DVec3::new(1.0, -2.0, 0.5), 3.0, a, b).unwrap();
            for s in 0..=200 {
                let p = c.point(s as f64 / 200.0).unwrap();
                assert!(((p - DVec3::new(1.0, -2.0, 0.5)).length() - 3.0).abs() < 1e-14);
            }
            let end = c.point(1.0).unwrap() - DVec3::new(1.0, -2.0, 0.5);
            assert!((end - DVec3::new(b.cos(), b.sin(), 0.0) * 3.0).length() < 1e-14);
        }
        assert!(arc(DVec3::ZERO, 1.0, 1.0, 1.0).is_err());
        assert!(arc(DVec3::ZERO, -1.0, 0.0, 1.0).is_err());
        assert!(arc(DVec3::ZERO, 1.0, 0.0, 7.0).is_err());
    }

    #[test]
    fn shapes_refuse_bad_dimensions() {
        assert!(sphere(DVec3::ZERO, 0.0).is_err());
        assert!(sphere(DVec3::NAN, 1.0).is_err());
        assert!(torus(DVec3::ZERO, 1.0, 1.0).is_err());
        assert!(torus(DVec3::ZERO, f64::INFINITY, 1.0).is_err());
        assert!(cylinder(DVec3::ZERO, 1.0, -1.0).is_err());
        assert!(cone(DVec3::ZERO, f64::NAN, 1.0).is_err());
    }

    #[test]
    fn sphere_poles_are_exact() {
        let s = sphere(DVec3::ZERO, 2.0).unwrap();
        for k in 0..=8 {
            let u = k as f64 / 8.0;
            assert!((s.point(u, 0.0).unwrap() - DVec3::new(0.0, 0.0, -2.0)).length() < 1e-15);
            assert!((s.point(u, 1.0).unwrap() - DVec3::new(0.0, 0.0, 2.0)).length() < 1e-15);
        }
        assert!((s.normal(0.1, 0.5).unwrap() - s.point(0.1, 0.5).unwrap() / 2.0).length() < 1e-14);
        assert!((s.normal(0.3, 0.0).unwrap() + DVec3::Z).length() < 1e-14);
    }
}
