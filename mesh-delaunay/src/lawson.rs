//! Lawson's edge flips (Lawson 1977; chapter section 2.2.2, Figure 2.2: an
//! arbitrary triangulation of a point set becomes the Delaunay one by edge
//! flips), with the length-based Delaunay test of mesh-kernel's intrinsic
//! flips ([`mesh_kernel::operators::is_delaunay_edge`]).

use glam::DVec2;
use mesh_kernel::operators::is_delaunay_edge;

use crate::error::{DelaunayError, Result};
use crate::frame::{orient, orient_sign, unit_of_points};
use crate::triangulate::{check_count, representatives};

/// No twin: a half-edge on the boundary.
const NONE: u32 = u32::MAX;

/// Options of [`lawson_flips`].
#[derive(Debug, Clone, PartialEq)]
pub struct LawsonOptions {
    /// Tolerance of the Delaunay test: an edge is flipped when its cotangent
    /// weight (half the sum of the cotangents of the two opposite angles) is
    /// below `-tolerance`, as in [`is_delaunay_edge`]. Default `1e-12`, so
    /// that co-circular points (weight 0 up to rounding) are left alone.
    pub tolerance: f64,
    /// The most flips allowed. Default `None`: n (n - 1) / 2 for n points,
    /// the bound of Lawson's theorem (an edge flipped away never comes back,
    /// by the lifting map of Edelsbrunner and Seidel 1986).
    pub max_flips: Option<usize>,
}

impl Default for LawsonOptions {
    fn default() -> Self {
        Self { tolerance: 1e-12, max_flips: None }
    }
}

/// The result of [`lawson_flips`].
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct LawsonFlips {
    /// The Delaunay triangulation, counter-clockwise triangles into the
    /// points, in the slots of the input triangles (triangle `f` of the
    /// output replaced triangle `f` of the input by flips).
    pub triangles: Vec<[u32; 3]>,
    /// How many edges were flipped.
    pub flips: usize,
    /// Non-Delaunay edges that were left because their quadrilateral is not
    /// strictly convex (a flip would fold it): only on nearly degenerate
    /// input.
    pub unflippable: usize,
}

/// A valid triangulation of the convex hull of `points` that is far from
/// Delaunay: points sorted by x (then y) are added one by one and joined
/// to every hull edge they see, Andrew's monotone chain (Andrew 1979) keeping
/// the upper and lower hull, so every point fans out to the hull of the
/// points before it. The starting triangulation of Figure 2.2's "arbitrary
/// -> Delaunay by edge flips". Duplicates are dropped (the first occurrence
/// is used, as in [`crate::Delaunay`]). O(n log n).
///
/// # Errors
///
/// [`DelaunayError::NonFinite`], [`DelaunayError::OutOfRange`],
/// [`DelaunayError::TooFewPoints`], [`DelaunayError::Collinear`] as
/// [`crate::delaunay`]; [`DelaunayError::InvalidTriangulation`] when
/// rounding in the orientation tests of nearly collinear points made the
/// sweep inconsistent (the result is checked).
pub fn sweep_triangulation(points: &[DVec2]) -> Result<Vec<[u32; 3]>> {
    check_count(points.len())?;
    let unit = unit_of_points(points)?;
    let p: Vec<DVec2> = points.iter().map(|q| *q / unit).collect();
    let (rep, duplicates) = representatives(points);
    let mut order: Vec<u32> = (0..points.len() as u32).filter(|&i| rep[i as usize] == i).collect();
    let distinct = order.len();
    if distinct < 3 {
        return Err(DelaunayError::TooFewPoints { distinct });
    }
    debug_assert_eq!(distinct + duplicates, points.len());
    order.sort_by(|&i, &j| {
        let (a, b) = (p[i as usize], p[j as usize]);
        a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y))
    });
    let at = |i: u32| p[i as usize];
    // The first point off the line of the first two.
    let Some(k) = (2..distinct).find(|&k| orient(at(order[0]), at(order[1]), at(order[k])) != 0.0) else {
        return Err(DelaunayError::Collinear { distinct });
    };
    let apex = order[k];
    let above = orient(at(order[0]), at(order[1]), at(apex)) > 0.0;
    let mut triangles = Vec::with_capacity(2 * distinct);
    for w in order[..k].windows(2) {
        triangles.push(if above { [w[0], w[1], apex] } else { [w[1], w[0], apex] });
    }
    let (mut lower, mut upper) = if above {
        let mut lower = order[..k].to_vec();
        lower.push(apex);
        (lower, vec![order[0], apex])
    } else {
        let mut upper = order[..k].to_vec();
        upper.push(apex);
        (vec![order[0], apex], upper)
    };
    for &q in &order[k + 1..] {
        while let [.., a, b] = lower[..] {
            if orient(at(a), at(b), at(q)) >= 0.0 {
                break;
            }
            triangles.push([a, q, b]);
            lower.pop();
        }
        lower.push(q);
        while let [.., a, b] = upper[..] {
            if orient(at(a), at(b), at(q)) <= 0.0 {
                break;
            }
            triangles.push([a, b, q]);
            upper.pop();
        }
        upper.push(q);
    }
    let _ = build_twins(&p, &triangles)?;
    Ok(triangles)
}

/// Flips the non-Delaunay interior edges of a triangulation of `points`
/// until none is left (Lawson 1977). An edge a b between triangles
/// (a, b, c) and (b, a, d) is tested by
/// [`is_delaunay_edge`]`(|ab|, |bc|, |ca|, |ad|, |db|, tolerance)`, the test
/// of mesh-kernel's intrinsic flips, and flipped to c d only when the quad
/// a d b c is strictly convex (both new triangles counter-clockwise), so
/// that no flip folds the triangulation. Each flip queues the four outer
/// edges of its quad. A triangulation of the convex hull of the points
/// (every point a vertex) ends as a Delaunay triangulation, which for
/// points in general position is the one of [`crate::delaunay`]; for a
/// triangulation of a non-convex region the flips give the constrained
/// Delaunay triangulation of that region. O(flips + T), O(n^2) flips at
/// worst.
///
/// # Errors
///
/// [`DelaunayError::InvalidTriangulation`] when `triangles` is not a valid
/// triangulation: an index out of range or repeated in a triangle, a
/// triangle that is not counter-clockwise, an edge shared by more than two
/// triangles or twice in one direction; [`DelaunayError::FlipLimit`] when
/// `max_flips` is reached; [`DelaunayError::InvalidOption`] for a negative
/// or non-finite tolerance; [`DelaunayError::NonFinite`] /
/// [`DelaunayError::OutOfRange`] for points that cannot be triangulated.
pub fn lawson_flips(points: &[DVec2], triangles: &[[u32; 3]], options: &LawsonOptions) -> Result<LawsonFlips> {
    if !(options.tolerance.is_finite() && options.tolerance >= 0.0) {
        return Err(DelaunayError::InvalidOption {
            name: "tolerance",
            reason: format!("{} is not a finite value >= 0", options.tolerance),
        });
    }
    check_count(points.len())?;
    if triangles.len() > (u32::MAX / 3) as usize {
        return Err(DelaunayError::InvalidTriangulation { reason: "too many triangles for u32 half-edges".into() });
    }
    let unit = unit_of_points(points)?;
    let p: Vec<DVec2> = points.iter().map(|q| *q / unit).collect();
    let mut tri = triangles.to_vec();
    let mut twin = build_twins(&p, &tri)?;
    let n = points.len();
    let max_flips = options.max_flips.unwrap_or(n.saturating_mul(n.saturating_sub(1)) / 2);
    let mut queued = vec![false; twin.len()];
    let mut stack: Vec<u32> = Vec::new();
    for h in 0..twin.len() as u32 {
        if twin[h as usize] != NONE && h < twin[h as usize] {
            stack.push(h);
            queued[h as usize] = true;
        }
    }
    let (mut flips, mut unflippable) = (0usize, 0usize);
    while let Some(h) = stack.pop() {
        queued[h as usize] = false;
        let t = twin[h as usize];
        if t == NONE {
            // The slot now holds a boundary edge (moved by a flip).
            continue;
        }
        let (f0, k0, f1, k1) = ((h / 3) as usize, (h % 3) as usize, (t / 3) as usize, (t % 3) as usize);
        let (a, b, c) = (tri[f0][k0], tri[f0][(k0 + 1) % 3], tri[f0][(k0 + 2) % 3]);
        let d = tri[f1][(k1 + 2) % 3];
        let [pa, pb, pc, pd] = [a, b, c, d].map(|v| p[v as usize]);
        if locally_delaunay([pa, pb, pc, pd], options.tolerance) {
            continue;
        }
        if orient_sign(pd, pc, pa, 1e-14) <= 0 || orient_sign(pc, pd, pb, 1e-14) <= 0 {
            unflippable += 1;
            continue;
        }
        if flips >= max_flips {
            return Err(DelaunayError::FlipLimit { flips });
        }
        flips += 1;
        let he = |f: usize, k: usize| (3 * f + k % 3) as u32;
        let (h_bc, h_ca, h_ad, h_db) = (he(f0, k0 + 1), he(f0, k0 + 2), he(f1, k1 + 1), he(f1, k1 + 2));
        let outer = [h_ca, h_ad, h_db, h_bc].map(|x| twin[x as usize]);
        tri[f0] = rotate([d, c, a], k0);
        tri[f1] = rotate([c, d, b], k1);
        // New slots of the outer edges: c->a and a->d in f0, d->b and b->c in f1.
        let slots = [he(f0, k0 + 1), he(f0, k0 + 2), he(f1, k1 + 1), he(f1, k1 + 2)];
        for (slot, o) in slots.into_iter().zip(outer) {
            twin[slot as usize] = o;
            if o != NONE {
                twin[o as usize] = slot;
                let key = slot.min(o);
                if !queued[key as usize] {
                    queued[key as usize] = true;
                    stack.push(key);
                }
            }
        }
    }
    if unflippable > 0 {
        // A left edge may have become flippable after its neighbours moved:
        // count only those still failing the test.
        unflippable = (0..twin.len())
            .filter(|&h| {
                let t = twin[h];
                if t == NONE || (h as u32) > t {
                    return false;
                }
                let (f0, k0, f1, k1) = (h / 3, h % 3, (t / 3) as usize, (t % 3) as usize);
                let (a, b, c) = (tri[f0][k0], tri[f0][(k0 + 1) % 3], tri[f0][(k0 + 2) % 3]);
                let d = tri[f1][(k1 + 2) % 3];
                !locally_delaunay([a, b, c, d].map(|v| p[v as usize]), options.tolerance)
            })
            .count();
    }
    Ok(LawsonFlips { triangles: tri, flips, unflippable })
}

/// The Delaunay test of the edge a b between (a, b, c) and (b, a, d):
/// [`is_delaunay_edge`] on the four points' distances, except when one of
/// the two triangles is collinear up to rounding (relative 1e-14). Its
/// lengths then satisfy the triangle inequality only by rounding, Heron's
/// area comes out 0 and the length test calls the edge Delaunay whatever
/// the angle at the sliver's apex; the coordinates still say on which side
/// the apex lies, so the cotangents come from them: `dot / |cross|` at c
/// and at d (found by the proptest: a sliver of three points collinear up
/// to rounding was left with the fourth point inside its neighbour's
/// circumcircle, and no flag).
fn locally_delaunay([pa, pb, pc, pd]: [DVec2; 4], tolerance: f64) -> bool {
    let sliver = orient_sign(pa, pb, pc, 1e-14) == 0 || orient_sign(pb, pa, pd, 1e-14) == 0;
    if !sliver {
        let len = |x: DVec2, y: DVec2| (x - y).length();
        return is_delaunay_edge(len(pa, pb), len(pb, pc), len(pc, pa), len(pa, pd), len(pd, pb), tolerance);
    }
    let cot = |o: DVec2, u: DVec2, v: DVec2| {
        let (x, y) = (u - o, v - o);
        x.dot(y) / x.perp_dot(y).abs()
    };
    let weight = 0.5 * (cot(pc, pa, pb) + cot(pd, pb, pa));
    // NaN (an apex on a or b: duplicates are dropped before) counts as Delaunay.
    weight.is_nan() || weight >= -tolerance
}

/// `[x, y, z]` placed so that `x` is at slot `k`.
fn rotate(v: [u32; 3], k: usize) -> [u32; 3] {
    let mut out = [0; 3];
    for i in 0..3 {
        out[(k + i) % 3] = v[i];
    }
    out
}

/// Checks the triangulation and returns the twin of every half-edge
/// (`3 f + k` runs from corner k to corner k + 1 of triangle f), `NONE` on
/// the boundary. O(T log T).
fn build_twins(p: &[DVec2], tri: &[[u32; 3]]) -> Result<Vec<u32>> {
    let bad = |reason: String| Err(DelaunayError::InvalidTriangulation { reason });
    for (f, t) in tri.iter().enumerate() {
        if t.iter().any(|&v| v as usize >= p.len()) {
            return bad(format!("triangle {f} has an index >= the {} points", p.len()));
        }
        if t[0] == t[1] || t[1] == t[2] || t[2] == t[0] {
            return bad(format!("triangle {f} repeats a vertex"));
        }
        let [a, b, c] = t.map(|v| p[v as usize]);
        if orient(a, b, c) <= 0.0 {
            return bad(format!("triangle {f} is not counter-clockwise (or has zero area)"));
        }
    }
    let mut keyed: Vec<(u32, u32, u32)> = Vec::with_capacity(3 * tri.len());
    for (f, t) in tri.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            keyed.push((a.min(b), a.max(b), (3 * f + k) as u32));
        }
    }
    keyed.sort_unstable();
    let mut twin = vec![NONE; keyed.len()];
    let mut i = 0;
    while i < keyed.len() {
        let mut j = i + 1;
        while j < keyed.len() && keyed[j].0 == keyed[i].0 && keyed[j].1 == keyed[i].1 {
            j += 1;
        }
        match j - i {
            1 => {}
            2 => {
                let (h, g) = (keyed[i].2, keyed[i + 1].2);
                let from = |x: u32| tri[(x / 3) as usize][(x % 3) as usize];
                if from(h) == from(g) {
                    return bad(format!("edge {}-{} is used twice in one direction", keyed[i].0, keyed[i].1));
                }
                twin[h as usize] = g;
                twin[g as usize] = h;
            }
            m => return bad(format!("edge {}-{} is shared by {m} triangles", keyed[i].0, keyed[i].1)),
        }
        i = j;
    }
    Ok(twin)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_flip_turns_the_long_diagonal() {
        // A kite whose diagonal 0-2 is the long one: the Delaunay one is 1-3.
        let p = [DVec2::new(-2.0, 0.0), DVec2::new(0.0, -0.5), DVec2::new(2.0, 0.0), DVec2::new(0.0, 0.5)];
        let r = lawson_flips(&p, &[[0, 1, 2], [0, 2, 3]], &LawsonOptions::default()).expect("valid");
        assert_eq!(r.flips, 1);
        let mut t: Vec<[u32; 3]> = r.triangles.iter().map(|t| canonical(*t)).collect();
        t.sort();
        assert_eq!(t, vec![[0, 1, 3], [1, 2, 3]]);
    }

    fn canonical(t: [u32; 3]) -> [u32; 3] {
        let k = (0..3).min_by_key(|&k| t[k]).unwrap_or(0);
        [t[k], t[(k + 1) % 3], t[(k + 2) % 3]]
    }

    #[test]
    fn invalid_triangulations_are_refused() {
        let p = [DVec2::ZERO, DVec2::X, DVec2::Y, DVec2::ONE];
        let o = LawsonOptions::default();
        for bad in [vec![[0, 2, 1]], vec![[0, 1, 1]], vec![[0, 1, 7]], vec![[0, 1, 2], [0, 1, 3]]] {
            assert!(matches!(lawson_flips(&p, &bad, &o), Err(DelaunayError::InvalidTriangulation { .. })), "{bad:?}");
        }
        let limited = LawsonOptions { max_flips: Some(0), ..LawsonOptions::default() };
        let kite = [DVec2::new(-2.0, 0.0), DVec2::new(0.0, -0.5), DVec2::new(2.0, 0.0), DVec2::new(0.0, 0.5)];
        assert_eq!(lawson_flips(&kite, &[[0, 1, 2], [0, 2, 3]], &limited), Err(DelaunayError::FlipLimit { flips: 0 }));
    }
}
