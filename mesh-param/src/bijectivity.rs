//! Is the boundary of a parameterization a simple curve? Together with "no
//! flipped or collapsed face" this makes a map of a disk bijective: a
//! piecewise-linear map with positively oriented triangles whose boundary is
//! a simple closed curve covers every interior point exactly once (degree
//! argument).
//!
//! Segments are bucketed in a sparse grid of cells about one segment long
//! (sorted cell keys) and only segments sharing a cell are tested, so evenly
//! spaced boundaries cost O(n log n) instead of the O(n^2) of all pairs.

use glam::DVec2;

/// The first pair of boundary segments that intersect, as (loop, segment)
/// pairs (segment k of a loop joins points k and k + 1), or `None` when every
/// loop is a simple polygon and no two loops meet. Neighbouring segments of a
/// loop may share their common point but must not fold back onto each other;
/// all other contacts (crossing, touching, overlapping, coincident points)
/// count. Plain floating-point orientation tests. O(n log n) for boundaries
/// of evenly sized segments, O(n^2) in the worst case (many tiny segments
/// crowded into the cell of a long one).
pub fn first_boundary_intersection(loops: &[Vec<DVec2>]) -> Option<((usize, usize), (usize, usize))> {
    let segments: Vec<Segment> = loops
        .iter()
        .enumerate()
        .flat_map(|(l, pts)| {
            (0..pts.len()).map(move |k| Segment { a: pts[k], b: pts[(k + 1) % pts.len()], lp: l, k, len: pts.len() })
        })
        .collect();
    let n = segments.len();
    if n < 2 {
        return None;
    }
    let keyed = cell_keys(&segments);
    let mut start = 0;
    while start < keyed.len() {
        let key = keyed[start].0;
        let end = start + keyed[start..].iter().take_while(|(k, _)| *k == key).count();
        let bucket = &keyed[start..end];
        for (x, &(_, s)) in bucket.iter().enumerate() {
            for &(_, t) in &bucket[x + 1..] {
                let (s, t) = (&segments[s as usize], &segments[t as usize]);
                if s.meets(t) {
                    return Some(((s.lp, s.k), (t.lp, t.k)));
                }
            }
        }
        start = end;
    }
    None
}

/// `true` when every loop is a simple polygon and no two loops meet.
pub fn boundary_is_simple(loops: &[Vec<DVec2>]) -> bool {
    first_boundary_intersection(loops).is_none()
}

#[derive(Debug, Clone, Copy)]
struct Segment {
    a: DVec2,
    b: DVec2,
    lp: usize,
    k: usize,
    len: usize,
}

#[inline]
fn orient(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    (b - a).perp_dot(c - a)
}

/// `c`, known collinear with a b, lies on the closed segment a b.
#[inline]
fn within(a: DVec2, b: DVec2, c: DVec2) -> bool {
    c.x >= a.x.min(b.x) && c.x <= a.x.max(b.x) && c.y >= a.y.min(b.y) && c.y <= a.y.max(b.y)
}

impl Segment {
    fn meets(&self, other: &Segment) -> bool {
        if self.lp == other.lp && self.len > 1 {
            let (i, j) = (self.k, other.k);
            if (i + 1) % self.len == j {
                return folds_back(self.a, self.b, other.b);
            }
            if (j + 1) % self.len == i {
                return folds_back(other.a, other.b, self.b);
            }
        }
        let (p, q, r, s) = (self.a, self.b, other.a, other.b);
        let (d1, d2, d3, d4) = (orient(r, s, p), orient(r, s, q), orient(p, q, r), orient(p, q, s));
        if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0)) && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0)) {
            return true;
        }
        (d1 == 0.0 && within(r, s, p))
            || (d2 == 0.0 && within(r, s, q))
            || (d3 == 0.0 && within(p, q, r))
            || (d4 == 0.0 && within(p, q, s))
    }
}

/// Consecutive segments a b and b c overlap beyond b (or c coincides with b).
fn folds_back(a: DVec2, b: DVec2, c: DVec2) -> bool {
    c == b || a == b || (orient(a, b, c) == 0.0 && (c - b).dot(a - b) > 0.0)
}

/// (cell, segment) pairs sorted by cell, for a sparse grid whose cells are
/// about one segment long (at least 1/32 of the longest segment, so that no
/// segment covers more than about a thousand cells).
fn cell_keys(segments: &[Segment]) -> Vec<(u64, u32)> {
    let finite = segments.iter().flat_map(|s| [s.a, s.b]).filter(|p| p.is_finite());
    let (lo, hi) = finite.fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(lo, hi), p| (lo.min(p), hi.max(p)));
    // Lengths are measured in units of the extent, so that no square
    // underflows or overflows whatever the unit of the coordinates.
    let extent = (hi - lo).max_element();
    let unit = if extent > 0.0 && extent.is_finite() { 1.0 / extent } else { 1.0 };
    let local = |p: DVec2| (p - lo) * unit;
    let lengths = segments.iter().map(|s| local(s.a).distance(local(s.b))).filter(|l| l.is_finite());
    let (sum, longest) = lengths.fold((0.0, 0.0f64), |(s, m), l| (s + l, m.max(l)));
    let mean = sum / segments.len() as f64;
    let cell = mean.max(longest / 32.0).max(1.0 / f64::from(1u32 << 20));
    let index = |x: f64| -> u64 {
        let i = (x / cell).floor();
        if i.is_finite() && i > 0.0 {
            (i as u64).min(1 << 21)
        } else {
            0
        }
    };
    let mut keyed = Vec::with_capacity(2 * segments.len());
    for (k, s) in segments.iter().enumerate() {
        let (a, b) = (local(s.a), local(s.b));
        if !(a.is_finite() && b.is_finite()) {
            // No cell range for a point that is not one; such a segment
            // meets nothing.
            keyed.push((0, k as u32));
            continue;
        }
        let (a, b) = (a.min(b), a.max(b));
        for x in index(a.x)..=index(b.x) {
            for y in index(a.y)..=index(b.y) {
                keyed.push(((x << 32) | y, k as u32));
            }
        }
    }
    keyed.sort_unstable();
    keyed
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use std::f64::consts::TAU;

    fn circle(n: usize) -> Vec<DVec2> {
        (0..n).map(|k| DVec2::from_angle(TAU * k as f64 / n as f64)).collect()
    }

    /// All pairs, the reference.
    fn brute_force(loops: &[Vec<DVec2>]) -> bool {
        let segs: Vec<Segment> = loops
            .iter()
            .enumerate()
            .flat_map(|(l, p)| {
                (0..p.len()).map(move |k| Segment { a: p[k], b: p[(k + 1) % p.len()], lp: l, k, len: p.len() })
            })
            .collect();
        (0..segs.len()).all(|i| (i + 1..segs.len()).all(|j| !segs[i].meets(&segs[j])))
    }

    #[test]
    fn circles_are_simple() {
        for n in [3, 4, 10, 1000, 100_000] {
            assert!(boundary_is_simple(&[circle(n)]), "{n}");
        }
    }

    #[test]
    fn the_unit_of_length_does_not_matter_and_non_finite_points_stay_bounded() {
        // At 1e-300 every squared length underflows; the grid must still be
        // about one segment per cell (before, this asked for gigabytes).
        let eight = [DVec2::ZERO, DVec2::new(1.0, 1.0), DVec2::new(1.0, 0.0), DVec2::new(0.0, 1.0)];
        for scale in [1e-300, 1e-150, 1.0, 1e150, 1e300] {
            let c: Vec<DVec2> = circle(1000).into_iter().map(|p| p * scale).collect();
            assert!(cell_keys(&segments_of(&c)).len() < 40 * c.len(), "{scale}");
            assert!(boundary_is_simple(&[c]), "{scale}");
            assert!(!boundary_is_simple(&[eight.iter().map(|p| *p * scale).collect()]), "{scale}");
        }
        let mut c = circle(1000);
        c[10] = DVec2::new(f64::NAN, 0.5);
        c[500] = DVec2::new(f64::INFINITY, 0.0);
        assert!(cell_keys(&segments_of(&c)).len() < 40 * c.len());
    }

    fn segments_of(p: &[DVec2]) -> Vec<Segment> {
        (0..p.len()).map(|k| Segment { a: p[k], b: p[(k + 1) % p.len()], lp: 0, k, len: p.len() }).collect()
    }

    #[test]
    fn figure_eight_is_not() {
        let eight = vec![DVec2::ZERO, DVec2::new(1.0, 1.0), DVec2::new(1.0, 0.0), DVec2::new(0.0, 1.0)];
        assert!(!boundary_is_simple(&[eight]));
    }

    #[test]
    fn touching_and_folding_are_caught() {
        // A vertex touching a far edge.
        let touch =
            vec![DVec2::ZERO, DVec2::new(2.0, 0.0), DVec2::new(2.0, 2.0), DVec2::new(1.0, 0.0), DVec2::new(0.0, 2.0)];
        assert!(!boundary_is_simple(&[touch]));
        // Folding back along the previous edge.
        let fold = vec![DVec2::ZERO, DVec2::new(2.0, 0.0), DVec2::new(1.0, 0.0), DVec2::new(1.0, 1.0)];
        assert!(!boundary_is_simple(&[fold]));
        // Two coincident points.
        let mut dup = circle(12);
        dup[7] = dup[3];
        assert!(!boundary_is_simple(&[dup]));
        // Two nested circles do not meet; two overlapping ones do.
        let small: Vec<DVec2> = circle(50).iter().map(|p| 0.5 * *p).collect();
        assert!(boundary_is_simple(&[circle(60), small.clone()]));
        let shifted: Vec<DVec2> = small.iter().map(|p| *p + DVec2::new(0.8, 0.0)).collect();
        assert!(!boundary_is_simple(&[circle(60), shifted]));
    }

    proptest! {
        #[test]
        fn grid_agrees_with_all_pairs(pts in prop::collection::vec((-1.0f64..1.0, -1.0f64..1.0), 3..40)) {
            let poly: Vec<DVec2> = pts.iter().map(|&(x, y)| DVec2::new(x, y)).collect();
            prop_assert_eq!(boundary_is_simple(std::slice::from_ref(&poly)), brute_force(&[poly]));
        }

        #[test]
        fn jittered_star_polygons(n in 3usize..300, amp in 0.0f64..0.9, seed in 0u64..1000) {
            // A star-shaped polygon (radius varies, angle increases): simple.
            let poly: Vec<DVec2> = (0..n).map(|k| {
                let r = 1.0 + amp * ((k as f64 * 12.9898 + seed as f64).sin() * 0.5);
                r * DVec2::from_angle(TAU * k as f64 / n as f64)
            }).collect();
            prop_assert!(boundary_is_simple(&[poly]));
        }
    }
}
