//! Exact differential geometry of a NURBS surface at a parameter (section 2.5
//! of the chapter): normal, first and second fundamental forms (eq. 2.21-2.22),
//! Gaussian and mean curvature (eq. 2.23-2.24), principal curvatures and
//! directions.
//!
//! # Conventions
//!
//! - The normal is `n = s_u x s_v / |s_u x s_v|`. The shape constructors of
//!   [`crate::shapes`] orient closed surfaces so that it points outward.
//! - `L, M, N` are exactly eq. 2.22: `L = n . s_uu`, `M = n . s_uv`,
//!   `N = n . s_vv`, and `K` is exactly eq. 2.23.
//! - Curvatures are positive where the surface bends away from its normal
//!   (the workspace convention: a sphere of radius `r` with outward normals
//!   has `H = +1/r`, `k1 = k2 = 1/r`). With `L, M, N` as in eq. 2.22 that is
//!   `H = -(L G - 2 F M + E N) / (2 (E G - F^2))`, the negative of eq. 2.24
//!   as printed, and `k1, k2` are the eigenvalues of the shape operator
//!   `-I^{-1} II`, with `k1 >= k2`, `K = k1 k2` (eq. 2.19), `H = (k1 + k2)/2`
//!   (eq. 2.20).
//! - `(d1, d2, n)` is a right-handed orthonormal frame; `d1` is the principal
//!   direction of `k1`, `d2 = n x d1` that of `k2`. At umbilics (sphere,
//!   plane) every direction is principal and `d1` is `s_u` normalized.
//! - At a degenerate point (`|s_u x s_v|` vanishing: a sphere pole, a cone
//!   apex) `regular` is `false`, `point` and the derivatives are exact at the
//!   parameter, the normal is the exact limit along the iso-line through the
//!   point (from `s_uv`, see [`NurbsSurface::normal`]), and the forms,
//!   curvatures and directions are those at a parameter moved by 1e-4 of the
//!   domain towards its centre, with the directions projected onto the
//!   tangent plane of the limit normal (at a sphere pole: exact to about
//!   1e-8; at a cone apex, where the mean curvature is singular, large but
//!   finite). Nothing is ever NaN; where no limit exists the normal,
//!   directions and curvatures are zero.

use glam::{DVec2, DVec3};

use crate::error::Result;
use crate::surface::{unit_normal, NurbsSurface, SurfaceDerivatives};

/// Everything differential geometry says about a surface at one parameter.
/// Built by [`SurfaceFrame::new`]; see the module documentation for the sign
/// conventions.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SurfaceFrame {
    /// The parameter `(u, v)` (after clamping into the domain).
    pub uv: DVec2,
    /// `S(u, v)` and its partial derivatives up to order 2.
    pub derivatives: SurfaceDerivatives,
    /// Unit normal `s_u x s_v / |s_u x s_v|`.
    pub normal: DVec3,
    /// First fundamental form `E = s_u . s_u` (eq. 2.21).
    pub e: f64,
    /// First fundamental form `F = s_u . s_v` (eq. 2.21).
    pub f: f64,
    /// First fundamental form `G = s_v . s_v` (eq. 2.21).
    pub g: f64,
    /// Second fundamental form `L = n . s_uu` (eq. 2.22).
    pub l: f64,
    /// Second fundamental form `M = n . s_uv` (eq. 2.22).
    pub m: f64,
    /// Second fundamental form `N = n . s_vv` (eq. 2.22).
    pub n: f64,
    /// Gaussian curvature `K = (L N - M^2) / (E G - F^2)` (eq. 2.23).
    pub gaussian: f64,
    /// Mean curvature `H`, positive on a sphere with outward normal (eq. 2.24
    /// with the workspace sign, see the module documentation).
    pub mean: f64,
    /// Largest principal curvature `k1 = H + sqrt(H^2 - K)`.
    pub k1: f64,
    /// Smallest principal curvature `k2 = H - sqrt(H^2 - K)`.
    pub k2: f64,
    /// Unit principal direction of `k1`, tangent to the surface.
    pub d1: DVec3,
    /// Unit principal direction of `k2`: `n x d1`.
    pub d2: DVec3,
    /// `false` at a degenerate point, where normal, forms and curvatures are
    /// limits taken at a nearby parameter.
    pub regular: bool,
}

/// The parts of a frame that depend on the normal and second derivatives.
#[derive(Debug, Clone, Copy, Default)]
struct Shape {
    normal: DVec3,
    e: f64,
    f: f64,
    g: f64,
    l: f64,
    m: f64,
    n: f64,
    gaussian: f64,
    mean: f64,
    k1: f64,
    k2: f64,
    d1: DVec3,
    d2: DVec3,
}

impl SurfaceFrame {
    /// The frame at `(u, v)`: derivatives up to order 2 (eq. 2.3-2.4 by the
    /// quotient rule), then eq. 2.21-2.24 and the eigen-decomposition of the
    /// shape operator. Finite parameters outside the domain are clamped; NaN and
    /// infinities are refused. Cost O(p^2 + q^2 + p q), no allocation.
    ///
    /// # Errors
    /// `NurbsError::NonFiniteParameter` for a NaN or infinite `u` or `v`.
    pub fn new(surface: &NurbsSurface, u: f64, v: f64) -> Result<Self> {
        let derivatives = surface.derivatives(u, v, 2)?;
        let uv = DVec2::new(surface.knots_u().clamp(u), surface.knots_v().clamp(v));
        Ok(Self::from_derivatives(surface, uv, derivatives))
    }

    /// The frame from derivatives already evaluated at `uv` (a clamped, finite
    /// parameter); re-evaluates near `uv` only at degenerate points.
    pub(crate) fn from_derivatives(surface: &NurbsSurface, uv: DVec2, derivatives: SurfaceDerivatives) -> Self {
        let (shape, regular) = match Shape::of(&derivatives) {
            Some(shape) => (shape, true),
            None => (Shape::limit(surface, uv, &derivatives), false),
        };
        let Shape { normal, e, f, g, l, m, n, gaussian, mean, k1, k2, d1, d2 } = shape;
        Self { uv, derivatives, normal, e, f, g, l, m, n, gaussian, mean, k1, k2, d1, d2, regular }
    }

    /// The point `S(u, v)`.
    pub fn point(&self) -> DVec3 {
        self.derivatives.point
    }

    /// Normal curvature in a tangent direction `t` (projected onto the tangent
    /// plane first): Euler's formula `k1 cos^2 a + k2 sin^2 a`, `a` the angle
    /// between `t` and `d1` (eq. 2.18). Zero for a direction along the normal.
    /// Cost O(1).
    pub fn normal_curvature(&self, t: DVec3) -> f64 {
        let t = t - self.normal * t.dot(self.normal);
        let len2 = t.length_squared();
        if len2 == 0.0 || !len2.is_finite() {
            return 0.0;
        }
        let c = t.dot(self.d1);
        let s = t.dot(self.d2);
        (self.k1 * c * c + self.k2 * s * s) / len2
    }
}

impl Shape {
    /// Eq. 2.21-2.24 at a regular point; `None` where `s_u x s_v` degenerates.
    fn of(d: &SurfaceDerivatives) -> Option<Self> {
        let normal = unit_normal(d.su, d.sv)?;
        let (e, f, g) = (d.su.dot(d.su), d.su.dot(d.sv), d.sv.dot(d.sv));
        let (l, m, n) = (normal.dot(d.suu), normal.dot(d.suv), normal.dot(d.svv));
        // E G - F^2 = |s_u x s_v|^2 (Lagrange), computed without cancellation.
        let det = d.su.cross(d.sv).length_squared();
        let gaussian = (l * n - m * m) / det;
        let mean = -(l * g - 2.0 * f * m + e * n) / (2.0 * det);
        let root = (mean * mean - gaussian).max(0.0).sqrt();
        let (k1, k2) = (mean + root, mean - root);
        let d1 = principal_direction(d, [e, f, g], [-l, -m, -n], k1);
        let d2 = normal.cross(d1);
        let shape = Self { normal, e, f, g, l, m, n, gaussian, mean, k1, k2, d1, d2 };
        shape.is_finite().then_some(shape)
    }

    /// Limits at a degenerate point (see the module documentation).
    fn limit(surface: &NurbsSurface, uv: DVec2, d: &SurfaceDerivatives) -> Self {
        let Some(normal) = surface.limit_normal(uv.x, uv.y, d) else {
            return Self::default();
        };
        let (u, v) = surface.nudge(uv.x, uv.y);
        let mut shape = Shape::of(&surface.derivatives_at::<3>(u, v)).unwrap_or_default();
        shape.normal = normal;
        shape.d1 = (shape.d1 - normal * shape.d1.dot(normal)).normalize_or_zero();
        shape.d2 = normal.cross(shape.d1);
        shape
    }

    fn is_finite(&self) -> bool {
        let scalars = [self.e, self.f, self.g, self.l, self.m, self.n, self.gaussian, self.mean, self.k1, self.k2];
        scalars.iter().all(|x| x.is_finite()) && self.normal.is_finite() && self.d1.is_finite()
    }
}

/// Unit 3D direction `x0 s_u + x1 s_v` of the null vector of
/// `II' - k I` (`II' = -II`, the sign convention of the module), taken from
/// its better-conditioned row; `s_u` normalized at umbilics.
fn principal_direction(d: &SurfaceDerivatives, [e, f, g]: [f64; 3], [l, m, n]: [f64; 3], k: f64) -> DVec3 {
    let rows = [DVec2::new(l - k * e, m - k * f), DVec2::new(m - k * f, n - k * g)];
    let scale = l.abs() + m.abs() + n.abs() + k.abs() * (e + f.abs() + g);
    let row = if rows[0].length_squared() >= rows[1].length_squared() { rows[0] } else { rows[1] };
    let fallback = d.su.normalize_or_zero();
    if row.length() <= 1e-10 * scale {
        return fallback;
    }
    // (x0, x1) = (-b, a) solves a x0 + b x1 = 0.
    let dir = d.su * -row.y + d.sv * row.x;
    let dir = dir.normalize_or_zero();
    if dir == DVec3::ZERO {
        fallback
    } else {
        dir
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::knots::KnotVector;

    #[test]
    fn paraboloid_patch_curvatures() {
        // z = a x^2 + b y^2 as a degree-2 Bezier patch over [-1, 1]^2: exact.
        let (a, b) = (0.5, -0.25);
        let knots = KnotVector::clamped_uniform(2, 3).unwrap();
        let mut pts = Vec::new();
        for i in 0..3 {
            for j in 0..3 {
                let x = -1.0 + i as f64;
                let y = -1.0 + j as f64;
                // Bezier control heights of x^2 on [-1,1]: 1, -1, 1.
                let hx = if i == 1 { -1.0 } else { 1.0 };
                let hy = if j == 1 { -1.0 } else { 1.0 };
                pts.push(DVec3::new(x, y, a * hx + b * hy));
            }
        }
        let s = NurbsSurface::non_rational(knots.clone(), knots, pts).unwrap();
        let fr = SurfaceFrame::new(&s, 0.5, 0.5).unwrap();
        assert!(fr.regular);
        assert!((fr.point() - DVec3::ZERO).length() < 1e-15);
        assert!((fr.normal - DVec3::Z).length() < 1e-15);
        // The surface bends towards +z (its normal) along x: negative curvature
        // in the workspace convention; towards -z along y: positive.
        assert!((fr.k1 - 2.0 * 0.25).abs() < 1e-12, "{}", fr.k1);
        assert!((fr.k2 + 2.0 * 0.5).abs() < 1e-12, "{}", fr.k2);
        assert!((fr.d1.cross(DVec3::Y)).length() < 1e-12);
        assert!((fr.gaussian - fr.k1 * fr.k2).abs() < 1e-12);
        assert!((fr.mean - 0.5 * (fr.k1 + fr.k2)).abs() < 1e-12);
        assert!((fr.normal_curvature(DVec3::X) - fr.k2).abs() < 1e-12);
        assert!((fr.normal_curvature(DVec3::new(1.0, 1.0, 0.0)) - fr.mean).abs() < 1e-12);
    }
}
