//! Local solvers of the Eikonal equation in one triangle (x, x1, x2), given
//! the values at x1 and x2 and the Gram matrix of e1 = x1 - x, e2 = x2 - x.
//! Each returns `+infinity` when it has no causal solution, which leaves the
//! edge updates to the caller.

use mesh_kernel::glam::DVec2;

/// Relative tolerance below which a triangle counts as degenerate.
const DEGENERATE: f64 = 1e-12;

/// The plane-wave update of eq. 2.33-2.34 (Kimmel and Sethian 1998): with
/// Q = G^-1 the inverse Gram matrix, a = (1, 1) and b = -(u1, u2), the
/// value U = U(x) solves (a^T Q a) U^2 + 2 (a^T Q b) U + b^T Q b = P^2
/// (the cross term's sign as it follows from nu = U a + b of eq. 2.33; the
/// chapter prints it with a minus). The larger root is kept when it is causal:
/// the upwind direction -grad U = c1 e1 + c2 e2, c = Q nu, points into the
/// triangle (c1, c2 >= 0) and U >= max(u1, u2). Computed relative to
/// min(u1, u2) to avoid cancellation. O(1).
#[inline]
pub(crate) fn plane_wave(u1: f64, u2: f64, g11: f64, g22: f64, g12: f64, p: f64) -> f64 {
    let det = g11 * g22 - g12 * g12;
    if !(det > DEGENERATE * g11 * g22) {
        return f64::INFINITY;
    }
    let base = u1.min(u2);
    let (w1, w2) = (u1 - base, u2 - base);
    // In units of 1/det: a^T adj(G) a, -(a^T adj(G) b), b^T adj(G) b.
    let alpha = g11 + g22 - 2.0 * g12;
    let beta = w1 * (g22 - g12) + w2 * (g11 - g12);
    let gamma = w1 * w1 * g22 - 2.0 * w1 * w2 * g12 + w2 * w2 * g11;
    let disc = beta * beta - alpha * (gamma - p * p * det);
    if !(disc >= 0.0 && alpha > 0.0) {
        return f64::INFINITY;
    }
    let w = (beta + disc.sqrt()) / alpha;
    let (n1, n2) = (w - w1, w - w2);
    // c = adj(G) nu >= 0: the characteristic enters through the edge x1 x2.
    if n1 < 0.0 || n2 < 0.0 || g22 * n1 - g12 * n2 < 0.0 || g11 * n2 - g12 * n1 < 0.0 {
        return f64::INFINITY;
    }
    base + w
}

/// The circular-front update: the front through x1 and x2 is taken as a
/// circle of signed radius `rho` (at the mean value of u1 and u2) about a
/// virtual centre laid out in the plane of the triangle: behind the edge
/// x1 x2 for a diverging front (`rho > 0`, the virtual point source of
/// Novotni and Klein 2002 when rho equals the distance), ahead of x for a
/// converging one (`rho < 0`). U(x) follows from the distance of x to that
/// centre. Causal when the centre-to-x line crosses the edge x1 x2 and
/// U >= max(u1, u2). Values are divided by the weight `p` for the geometry
/// and multiplied back. O(1).
#[inline]
pub(crate) fn circular_front(u1: f64, u2: f64, rho: f64, g11: f64, g22: f64, g12: f64, p: f64) -> Circular {
    use Circular::{Inconsistent, NonCausal};
    let det = g11 * g22 - g12 * g12;
    if !(det > DEGENERATE * g11 * g22 && p > 0.0 && rho != 0.0 && rho.is_finite()) {
        return Inconsistent;
    }
    let (w1, w2) = (u1 / p, u2 / p);
    let mean = 0.5 * (w1 + w2);
    let diverging = rho > 0.0;
    let radius = rho.abs();
    // Radii of the circles about the centre through x1 and x2.
    let (r1, r2) = if diverging {
        (radius + (w1 - mean), radius + (w2 - mean))
    } else {
        (radius - (w1 - mean), radius - (w2 - mean))
    };
    if !(r1 > 0.0 && r2 > 0.0) {
        return Inconsistent;
    }
    let l1 = g11.sqrt();
    let q1 = DVec2::new(l1, 0.0);
    let q2 = DVec2::new(g12 / l1, det.sqrt() / l1);
    let edge = q2 - q1;
    let len = edge.length();
    let along = (r1 * r1 - r2 * r2 + len * len) / (2.0 * len);
    let h2 = r1 * r1 - along * along;
    if !(h2 >= 0.0) {
        return Inconsistent; // the circles do not meet
    }
    let u = edge / len;
    // The normal of the edge pointing away from x (the origin); the centre
    // lies on that side for a diverging front, on x's side otherwise.
    let mut n = u.perp();
    if n.dot(q1) < 0.0 {
        n = -n;
    }
    let centre = q1 + along * u + h2.sqrt() * if diverging { n } else { -n };
    // The line from the centre through x must cross the edge: the direction
    // (centre for a diverging front, -centre for a converging one) lies in
    // the cone of e1 and e2.
    let dir = if diverging { centre } else { -centre };
    let cross = q1.perp_dot(q2);
    if q1.perp_dot(dir) * cross < 0.0 || dir.perp_dot(q2) * cross < 0.0 {
        return NonCausal;
    }
    let dist = centre.length();
    let (value, kappa) = if diverging {
        (mean - radius + dist, 1.0 / dist)
    } else {
        (mean + radius - dist, if dist > 0.0 { -1.0 / dist } else { 0.0 })
    };
    if !(value >= w1.max(w2)) {
        return NonCausal;
    }
    Circular::Value(p * value, kappa)
}

/// What [`circular_front`] found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Circular {
    /// U at x and the flat-space curvature of the front there (1 / its
    /// radius, negative when converging).
    Value(f64, f64),
    /// The characteristic does not come through the triangle: no update.
    NonCausal,
    /// No circle fits the data (degenerate triangle, radii inconsistent
    /// with the values): the plane wave is the fallback.
    Inconsistent,
}

/// Geodesic curvature of a front of curvature `kappa` after it advanced by
/// `delta` in flat space (1/kappa grows by delta); `+infinity` stands for a
/// point source. A converging front that reaches its focus becomes flat (0)
/// rather than flipping sign.
#[inline]
pub(crate) fn advance_curvature(kappa: f64, delta: f64) -> f64 {
    if kappa == f64::INFINITY {
        return if delta > 0.0 { 1.0 / delta } else { f64::INFINITY };
    }
    let denom = 1.0 + kappa * delta;
    if denom > 1e-3 && kappa.is_finite() {
        kappa / denom
    } else {
        0.0
    }
}

/// Mean front radius of two vertices (`rho = 1/kappa` averaged), or `None`
/// when the two fronts do not bend the same way or are nearly flat (then a
/// plane wave is the right model).
#[inline]
pub(crate) fn mean_radius(k1: f64, k2: f64, scale: f64) -> Option<f64> {
    let same = (k1 > 0.0 && k2 > 0.0) || (k1 < 0.0 && k2 < 0.0);
    if !same {
        return None;
    }
    let rho = 0.5 * (1.0 / k1 + 1.0 / k2);
    (rho.is_finite() && rho != 0.0 && rho.abs() < 1e3 * scale).then_some(rho)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plane_wave_is_exact_on_linear_fields() {
        // U = y with x at the origin, x1 = (-1, -1), x2 = (1, -1).
        assert!(plane_wave(-1.0, -1.0, 2.0, 2.0, 0.0, 1.0).abs() < 1e-15);
        // Oblique wave U = (3 x + 4 y) / 5 coming through a skewed acute
        // triangle (the upwind direction (-0.6, -0.8) lies between a and b).
        let f = |q: DVec2| (3.0 * q.x + 4.0 * q.y) / 5.0;
        let (a, b) = (DVec2::new(-0.9, -1.0), DVec2::new(0.2, -1.1));
        let u = plane_wave(f(a), f(b), a.length_squared(), b.length_squared(), a.dot(b), 1.0);
        assert!(u.abs() < 1e-14, "{u}");
        // The weight P scales the slope (eq. 2.32).
        assert!((plane_wave(0.0, 0.0, 2.0, 2.0, 0.0, 3.0) - 3.0).abs() < 1e-14);
    }

    #[test]
    fn plane_wave_refuses_non_causal_and_degenerate() {
        // A wave from outside the triangle's cone.
        let (a, b) = (DVec2::new(0.2, -1.0), DVec2::new(1.0, -1.0));
        assert!(plane_wave(a.x, b.x, a.length_squared(), b.length_squared(), a.dot(b), 1.0).is_infinite());
        assert!(plane_wave(0.0, 0.0, 1.0, 4.0, 2.0, 1.0).is_infinite());
        // |u1 - u2| above P |x1 - x2|: no real root.
        assert!(plane_wave(0.0, 5.0, 1.0, 1.0, 0.0, 1.0).is_infinite());
    }

    #[test]
    fn circular_front_is_exact_for_point_sources() {
        // Source at s, triangle x = origin, x1, x2 on the source's side.
        let s = DVec2::new(0.3, -2.0);
        let (a, b) = (DVec2::new(-0.4, -0.9), DVec2::new(0.8, -0.8));
        let (ua, ub) = ((a - s).length(), (b - s).length());
        let rho = 0.5 * (ua + ub);
        let Circular::Value(u, k) = circular_front(ua, ub, rho, a.length_squared(), b.length_squared(), a.dot(b), 1.0)
        else {
            panic!("no value")
        };
        assert!((u - s.length()).abs() < 1e-14, "{u} vs {}", s.length());
        assert!((k - 1.0 / s.length()).abs() < 1e-14);
    }

    #[test]
    fn circular_front_is_exact_for_converging_circles() {
        // U = 5 - |y - c| with c beyond x: a front converging on c.
        let c = DVec2::new(0.2, 1.5);
        let f = |q: DVec2| 5.0 - (q - c).length();
        let (a, b) = (DVec2::new(-0.5, -0.8), DVec2::new(0.7, -0.9));
        let rho = -(5.0 - 0.5 * (f(a) + f(b)));
        let Circular::Value(u, k) =
            circular_front(f(a), f(b), rho, a.length_squared(), b.length_squared(), a.dot(b), 1.0)
        else {
            panic!("no value")
        };
        assert!((u - f(DVec2::ZERO)).abs() < 1e-13, "{u} vs {}", f(DVec2::ZERO));
        assert!((k + 1.0 / c.length()).abs() < 1e-13);
    }

    #[test]
    fn curvature_advances_like_a_circle() {
        assert_eq!(advance_curvature(f64::INFINITY, 2.0), 0.5);
        assert!((advance_curvature(0.5, 2.0) - 0.25).abs() < 1e-15);
        assert_eq!(advance_curvature(-1.0, 1.0), 0.0);
        assert_eq!(mean_radius(1.0, -1.0, 1.0), None);
        assert_eq!(mean_radius(0.5, 0.25, 10.0), Some(3.0));
    }
}
