//! Packing chart rectangles into the unit square: each chart's bounding box
//! is turned to its smallest-area orientation (rotating calipers on the
//! convex hull, Freeman and Shapira 1975; Toussaint 1983), then all boxes are
//! scaled by one common factor, as large as fits, and placed by skyline
//! bottom-left packing (Jylanki 2010, "A thousand ways to pack the bin"),
//! tallest first, each box upright or turned by 90 degrees, whichever lands
//! lower. Boxes are kept `margin` apart and `margin / 2` from the sides.

use glam::DVec2;

use crate::error::{ParamError, Result};

/// An axis-aligned rectangle of the parameter plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UvRect {
    /// Lower-left corner.
    pub min: DVec2,
    /// Upper-right corner.
    pub max: DVec2,
}

impl UvRect {
    /// The bounding box of `points` (`None` for no point). O(n).
    pub fn around(points: &[DVec2]) -> Option<Self> {
        let first = *points.first()?;
        let (min, max) = points.iter().fold((first, first), |(lo, hi), q| (lo.min(*q), hi.max(*q)));
        Some(Self { min, max })
    }

    /// Width and height.
    pub fn size(&self) -> DVec2 {
        self.max - self.min
    }

    /// `true` when the two rectangles share an interior point or a piece of
    /// boundary (touching counts). O(1).
    pub fn meets(&self, other: &UvRect) -> bool {
        self.min.x <= other.max.x && other.min.x <= self.max.x && self.min.y <= other.max.y && other.min.y <= self.max.y
    }

    /// `true` when `q` lies in the closed rectangle. O(1).
    pub fn contains(&self, q: DVec2) -> bool {
        q.cmpge(self.min).all() && q.cmple(self.max).all()
    }
}

/// Where [`pack_rectangles`] put each rectangle.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct Packing {
    /// The common factor applied to every size.
    pub scale: f64,
    /// The margin kept between rectangles (`margin / 2` to the sides of the
    /// square); smaller than asked when the rectangles are too many for it.
    pub margin: f64,
    /// Each rectangle's place in the unit square, of size `scale * size`
    /// (width and height exchanged when turned).
    pub rects: Vec<UvRect>,
    /// Whether each rectangle was turned by 90 degrees.
    pub turned: Vec<bool>,
}

/// Packs rectangles of the given sizes (finite, non-negative) into the unit
/// square, all scaled by the largest common factor for which skyline
/// bottom-left packing fits them (bisection on the factor to a relative
/// 1e-4), `margin` apart (see the module documentation). `margin` is halved
/// until the rectangles fit at all (more than about 1 / margin^2 of them
/// cannot). Cost: O(n s) per trial packing with s skyline segments (s <= n,
/// usually far fewer), about 20 trials; a single rectangle is scaled in
/// closed form to span the square but the margin.
///
/// # Errors
/// `ParamError::InvalidOption` (`margin`) unless 0 <= margin < 0.5, (`sizes`) for a rectangle with a
/// non-finite or negative size or rectangles that do not fit the unit square.
pub fn pack_rectangles(sizes: &[DVec2], margin: f64) -> Result<Packing> {
    if !(margin.is_finite() && (0.0..0.5).contains(&margin)) {
        return Err(ParamError::InvalidOption {
            name: "margin",
            reason: format!("need 0 <= margin < 0.5, got {margin}"),
        });
    }
    if let Some(k) = sizes.iter().position(|s| !(s.is_finite() && s.min_element() >= 0.0)) {
        return Err(ParamError::InvalidOption {
            name: "sizes",
            reason: format!("rectangle {k} has size {}", sizes[k]),
        });
    }
    let mut order: Vec<usize> = (0..sizes.len()).collect();
    order.sort_by(|&a, &b| tallest_first(sizes[b]).total_cmp(&tallest_first(sizes[a])).then(a.cmp(&b)));
    let mut margin = margin;
    let mut best = skyline(sizes, &order, 0.0, margin);
    while best.is_none() && margin > 0.0 {
        margin = if margin < 1e-12 { 0.0 } else { 0.5 * margin };
        best = skyline(sizes, &order, 0.0, margin);
    }
    let mut best = best.ok_or_else(|| ParamError::InvalidOption {
        name: "sizes",
        reason: format!("{} rectangles do not fit the unit square", sizes.len()),
    })?;
    let largest = sizes.iter().map(|s| s.max_element()).fold(0.0, f64::max);
    if largest == 0.0 {
        return Ok(best);
    }
    if let [size] = sizes {
        // One box: its longer side spans the square but the margin.
        let scale = (1.0 - margin) / largest;
        let min = DVec2::splat(0.5 * margin);
        let rect = UvRect { min, max: (min + scale * *size).min(DVec2::splat(1.0 - 0.5 * margin)) };
        return Ok(Packing { scale, margin, rects: vec![rect], turned: vec![false] });
    }
    let (mut lo, mut hi) = (0.0, 1.0 / largest);
    // The largest factor that fits is at most 1 / largest side; bisect.
    for _ in 0..200 {
        if hi - lo <= 1e-4 * hi {
            break;
        }
        let mid = if lo == 0.0 { 0.5 * hi } else { 0.5 * (lo + hi) };
        match skyline(sizes, &order, mid, margin) {
            Some(p) => {
                lo = mid;
                best = p;
            }
            None => hi = mid,
        }
    }
    Ok(best)
}

/// Sort key: the longer side, then the area (boxes may be turned).
fn tallest_first(s: DVec2) -> f64 {
    s.max_element() + 1e-9 * s.min_element()
}

/// One skyline segment: from `x` to the next segment's `x` (or 1) at height `y`.
#[derive(Debug, Clone, Copy)]
struct Segment {
    x: f64,
    y: f64,
}

/// Skyline bottom-left packing at factor `scale`, or `None` if a box does
/// not fit the unit square. O(n s).
fn skyline(sizes: &[DVec2], order: &[usize], scale: f64, margin: f64) -> Option<Packing> {
    let mut sky = vec![Segment { x: 0.0, y: 0.0 }];
    let mut rects = vec![UvRect { min: DVec2::ZERO, max: DVec2::ZERO }; sizes.len()];
    let mut turned = vec![false; sizes.len()];
    for &k in order {
        let upright = scale * sizes[k] + DVec2::splat(margin);
        let mut best: Option<(f64, f64, usize, bool)> = None;
        for (w, h, turn) in [(upright.x, upright.y, false), (upright.y, upright.x, true)] {
            if let Some((top, x, i)) = lowest_fit(&sky, w, h) {
                if best.is_none_or(|b| (top, x) < (b.0, b.1)) {
                    best = Some((top, x, i, turn));
                }
            }
        }
        let (top, x, i, turn) = best?;
        let (w, h) = if turn { (upright.y, upright.x) } else { (upright.x, upright.y) };
        raise(&mut sky, i, x + w, top);
        let half = DVec2::splat(0.5 * margin);
        rects[k] = UvRect { min: DVec2::new(x, top - h) + half, max: DVec2::new(x + w, top) - half };
        turned[k] = turn;
    }
    Some(Packing { scale, margin, rects, turned })
}

/// The lowest place for a w x h box on the skyline: (top, x, first segment).
fn lowest_fit(sky: &[Segment], w: f64, h: f64) -> Option<(f64, f64, usize)> {
    let mut best: Option<(f64, f64, usize)> = None;
    for i in 0..sky.len() {
        let x = sky[i].x;
        if x + w > 1.0 {
            break;
        }
        let mut y = 0.0f64;
        for s in &sky[i..] {
            if s.x >= x + w {
                break;
            }
            y = y.max(s.y);
        }
        let top = y + h;
        if top <= 1.0 && best.is_none_or(|b| top < b.0) {
            best = Some((top, x, i));
        }
    }
    best
}

/// Raises the skyline to `top` from segment `i`'s start to `end`.
fn raise(sky: &mut Vec<Segment>, i: usize, end: f64, top: f64) {
    let x = sky[i].x;
    if end <= x {
        return;
    }
    // The last segment that starts before `end`: it continues after `end`
    // unless the next one starts right there.
    let mut j = i;
    while j + 1 < sky.len() && sky[j + 1].x < end {
        j += 1;
    }
    let next_x = sky.get(j + 1).map_or(1.0, |s| s.x);
    let mut replacement = vec![Segment { x, y: top }];
    if end < next_x {
        replacement.push(Segment { x: end, y: sky[j].y });
    }
    sky.splice(i..=j, replacement);
    // Merge neighbours of equal height.
    sky.dedup_by(|later, earlier| later.y == earlier.y);
}

/// The rotation angle (radians) that turns `points` so that their
/// axis-aligned bounding box has the least area: rotating calipers over the
/// convex hull (Freeman and Shapira 1975: an edge of the hull lies on a side
/// of the smallest box; Toussaint 1983: the three other calipers only move
/// forward). 0 for fewer than three hull points. O(n log n) for the hull,
/// O(h) for the calipers.
pub fn min_area_rotation(points: &[DVec2]) -> f64 {
    let hull = convex_hull(points);
    let h = hull.len();
    if h < 3 {
        return 0.0;
    }
    let at = |k: usize| hull[k % h];
    // The hull is strictly convex, so along any direction the values around
    // it rise to one maximum (shared by at most two vertices) and fall:
    // caliper `k` moves forward while the next value is not smaller.
    let advance = |mut k: usize, f: &dyn Fn(DVec2) -> f64| {
        for _ in 0..h {
            if f(at(k + 1)) < f(at(k)) {
                break;
            }
            k += 1;
        }
        k
    };
    // Counter-clockwise from edge i: the farthest point along the edge
    // (right), from the edge (far), back along the edge (left).
    let (mut far, mut right, mut left) = (0, 0, 0);
    let mut best = (f64::INFINITY, 0.0);
    for i in 0..h {
        let u = (at(i + 1) - at(i)).normalize_or_zero();
        if u == DVec2::ZERO {
            continue;
        }
        let n = u.perp();
        far = advance(far.max(i + 1), &|q| n.dot(q));
        right = advance(right.max(i + 1), &|q| u.dot(q));
        left = advance(left.max(far), &|q| -u.dot(q));
        let width = u.dot(at(right)) - u.dot(at(left));
        let height = n.dot(at(far)) - n.dot(at(i));
        if width * height < best.0 {
            best = (width * height, -u.y.atan2(u.x));
        }
    }
    best.1
}

/// Convex hull, counter-clockwise, by Andrew's monotone chain (1979).
/// O(n log n).
fn convex_hull(points: &[DVec2]) -> Vec<DVec2> {
    let mut p: Vec<DVec2> = points.iter().copied().filter(|q| q.is_finite()).collect();
    p.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    p.dedup();
    if p.len() < 3 {
        return p;
    }
    let mut lower = half_hull(p.iter());
    let upper = half_hull(p.iter().rev());
    lower.pop();
    lower.extend_from_slice(&upper[..upper.len() - 1]);
    lower
}

/// One chain of the monotone-chain hull: left turns only.
fn half_hull<'a>(points: impl Iterator<Item = &'a DVec2>) -> Vec<DVec2> {
    let mut chain: Vec<DVec2> = Vec::new();
    for &q in points {
        while let [.., a, b] = chain[..] {
            if (b - a).perp_dot(q - a) > 0.0 {
                break;
            }
            chain.pop();
        }
        chain.push(q);
    }
    chain
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn check(p: &Packing, sizes: &[DVec2]) {
        let unit = UvRect { min: DVec2::ZERO, max: DVec2::ONE };
        for (k, r) in p.rects.iter().enumerate() {
            assert!(unit.contains(r.min) && unit.contains(r.max), "{k}: {r:?}");
            let s = if p.turned[k] { DVec2::new(sizes[k].y, sizes[k].x) } else { sizes[k] };
            assert!((r.size() - p.scale * s).abs().max_element() <= 1e-12, "{k}");
            for (j, q) in p.rects.iter().enumerate().skip(k + 1) {
                let grown =
                    UvRect { min: r.min - DVec2::splat(0.999 * p.margin), max: r.max + DVec2::splat(0.999 * p.margin) };
                assert!(!grown.meets(q) || p.margin == 0.0 && !overlap_interior(r, q), "{k} {j}");
            }
        }
    }

    fn overlap_interior(a: &UvRect, b: &UvRect) -> bool {
        a.min.x < b.max.x && b.min.x < a.max.x && a.min.y < b.max.y && b.min.y < a.max.y
    }

    #[test]
    fn one_square_fills_the_square_but_its_margin() {
        let p = pack_rectangles(&[DVec2::splat(2.0)], 0.01).unwrap();
        assert!((p.scale * 2.0 - 0.99).abs() < 1e-15);
        check(&p, &[DVec2::splat(2.0)]);
    }

    #[test]
    fn four_equal_squares_fill_a_two_by_two_grid() {
        let sizes = vec![DVec2::ONE; 4];
        let p = pack_rectangles(&sizes, 0.0).unwrap();
        assert!((p.scale - 0.5).abs() < 1e-4, "{}", p.scale);
        check(&p, &sizes);
    }

    #[test]
    fn long_boxes_are_turned_and_margins_shrink_when_needed() {
        let sizes = [DVec2::new(4.0, 1.0), DVec2::new(1.0, 4.0), DVec2::new(1.0, 4.0), DVec2::new(4.0, 1.0)];
        let p = pack_rectangles(&sizes, 0.0).unwrap();
        // Four 4 x 1 strips stack into a square.
        assert!((p.scale - 0.25).abs() < 1e-4, "{}", p.scale);
        check(&p, &sizes);
        let many = vec![DVec2::ONE; 10_000];
        let p = pack_rectangles(&many, 0.05).unwrap();
        assert!(p.margin < 0.01 && p.scale > 0.0);
        check(&p, &many);
        assert!(pack_rectangles(&[DVec2::ONE], 0.7).is_err());
        assert!(pack_rectangles(&[DVec2::new(f64::NAN, 1.0)], 0.0).is_err());
        assert_eq!(pack_rectangles(&[], 0.01).unwrap().rects.len(), 0);
    }

    #[test]
    fn min_area_rotation_aligns_a_tilted_rectangle() {
        let rot = DVec2::from_angle(0.3);
        let pts: Vec<DVec2> = [(0.0, 0.0), (3.0, 0.0), (3.0, 1.0), (0.0, 1.0), (1.5, 0.5)]
            .iter()
            .map(|&(x, y)| rot.rotate(DVec2::new(x, y)))
            .collect();
        let back = DVec2::from_angle(min_area_rotation(&pts));
        let turned: Vec<DVec2> = pts.iter().map(|q| back.rotate(*q)).collect();
        let s = UvRect::around(&turned).unwrap().size();
        assert!((s.x * s.y - 3.0).abs() < 1e-12, "{s}");
        assert_eq!(min_area_rotation(&[DVec2::ZERO, DVec2::X]), 0.0);
    }

    /// All hull edges tried with full scans, the reference.
    fn brute_force_area(points: &[DVec2]) -> f64 {
        let hull = convex_hull(points);
        (0..hull.len())
            .map(|k| {
                let rot = DVec2::from_angle(-(hull[(k + 1) % hull.len()] - hull[k]).to_angle());
                let turned: Vec<DVec2> = hull.iter().map(|q| rot.rotate(*q)).collect();
                let s = UvRect::around(&turned).unwrap().size();
                s.x * s.y
            })
            .fold(f64::INFINITY, f64::min)
    }

    proptest! {
        #[test]
        fn random_boxes_never_overlap(
            sizes in prop::collection::vec((0.0f64..10.0, 0.0f64..10.0), 1..60),
            margin in 0.0f64..0.02,
        ) {
            let sizes: Vec<DVec2> = sizes.iter().map(|&(w, h)| DVec2::new(w, h)).collect();
            let p = pack_rectangles(&sizes, margin).unwrap();
            check(&p, &sizes);
        }

        #[test]
        fn calipers_agree_with_all_edges(pts in prop::collection::vec((-1.0f64..1.0, -1.0f64..1.0), 3..80)) {
            let pts: Vec<DVec2> = pts.iter().map(|&(x, y)| DVec2::new(x, y)).collect();
            prop_assume!(convex_hull(&pts).len() >= 3);
            let rot = DVec2::from_angle(min_area_rotation(&pts));
            let turned: Vec<DVec2> = pts.iter().map(|q| rot.rotate(*q)).collect();
            let s = UvRect::around(&turned).unwrap().size();
            let best = brute_force_area(&pts);
            prop_assert!((s.x * s.y - best).abs() <= 1e-12 * best.max(1.0), "{} vs {best}", s.x * s.y);
        }

        #[test]
        fn random_boxes_cover_much_of_the_square(sizes in prop::collection::vec((0.1f64..10.0, 0.1f64..10.0), 10..60)) {
            let sizes: Vec<DVec2> = sizes.iter().map(|&(w, h)| DVec2::new(w, h)).collect();
            let p = pack_rectangles(&sizes, 0.0).unwrap();
            // Skyline packing of boxes sorted by height wastes well under 1/2.
            let area: f64 = sizes.iter().map(|s| s.x * s.y).sum::<f64>() * p.scale * p.scale;
            prop_assert!(area > 0.5, "{area}");
        }
    }
}
