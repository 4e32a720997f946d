//! Windows and their planar geometry: distance along a window, the route to
//! the apex of the face it enters, the pairwise trimming of two windows on
//! one edge, and the unfolding of a cone of rays onto the next edge.

use mesh_kernel::glam::DVec2;

/// Relative margin by which a ray must be beaten before it is dropped: ties
/// (and rounding noise) keep the ray.
pub(super) const PRUNE_MARGIN: f64 = 1e-12;

/// A window on a half-edge, in that half-edge's frame (A = (0, 0),
/// B = (len, 0), its face above the axis): the interval `[b0, b1]` of the
/// edge, seen from `source` (below the axis, the unfolded source or
/// pseudo-source) at distance `sigma`. 40 bytes.
#[derive(Debug, Clone, Copy)]
pub(super) struct Window {
    pub b0: f64,
    pub b1: f64,
    pub source: DVec2,
    pub sigma: f64,
}

/// How a window reaches the apex C of the face it enters: its length
/// `distance`, the point `x` where it crosses the edge (the foot of the ray
/// to C, or the window end nearest to it when that ray misses the window,
/// the path then bends there), and `foot`, where the straight line from the
/// source to C crosses the edge line (which side of C each ray passes).
#[derive(Debug, Clone, Copy)]
pub(super) struct ApexRoute {
    pub distance: f64,
    pub x: f64,
    pub foot: f64,
}

impl Window {
    /// The distance at the point `x` of the edge line through this window:
    /// `sigma + |source - (x, 0)|`.
    #[inline]
    pub fn at(&self, x: f64) -> f64 {
        self.sigma + planar_norm(self.source.x - x, self.source.y)
    }

    /// Where the line from the source through `q` (above the axis) crosses
    /// the axis.
    #[inline]
    fn foot(&self, q: DVec2) -> f64 {
        let s = self.source;
        s.x + (q.x - s.x) * (-s.y) / (q.y - s.y)
    }

    /// The shortest path through this window to the apex `c`: straight when
    /// the ray to `c` crosses the window, else bent at the nearer end. O(1).
    pub fn apex_route(&self, c: DVec2) -> ApexRoute {
        let foot = self.foot(c);
        let x = foot.clamp(self.b0, self.b1);
        let distance =
            if x == foot { self.sigma + self.source.distance(c) } else { self.at(x) + c.distance(DVec2::new(x, 0.0)) };
        ApexRoute { distance, x, foot }
    }

    /// Mitchell, Mount and Papadimitriou's (1987) trimming of two windows on
    /// the same edge: where both cover a point, the one that reaches it
    /// longer (by more than [`PRUNE_MARGIN`]) is useless beyond it, since its
    /// rays there are beaten by a real path of the other. Each window loses
    /// the beaten pieces at its ends; returns whether each survives.
    ///
    /// The two distances are equal on a branch of a hyperbola with the two
    /// sources as foci, which meets the edge line at most twice (the roots of
    /// a quadratic); between those points one window wins throughout, which
    /// the midpoint decides. O(1).
    pub fn trim_pair(w1: &mut Window, w2: &mut Window) -> (bool, bool) {
        let (l, r) = (w1.b0.max(w2.b0), w1.b1.min(w2.b1));
        if !(r > l) {
            return (true, true);
        }
        let mut cuts = [l, r, r, r];
        let mut n = 1;
        for root in equal_distance_points(w1, w2) {
            if root > l && root < r {
                cuts[n] = root;
                n += 1;
            }
        }
        cuts[n] = r;
        if n == 3 && cuts[1] > cuts[2] {
            cuts.swap(1, 2);
        }
        // Which window loses on each piece: +1 the first, -1 the second.
        // Which window loses on each piece (+1 the first, -1 the second):
        // clearly at its midpoint and not clearly winning at its ends (a
        // root lost to rounding then keeps both).
        let beats = |x: f64| {
            let (d1, d2) = (w1.at(x), w2.at(x));
            if d2 < d1 * (1.0 - PRUNE_MARGIN) {
                -1i8
            } else if d1 < d2 * (1.0 - PRUNE_MARGIN) {
                1
            } else {
                0
            }
        };
        let mut loser = [0i8; 3];
        for k in 0..n {
            let winner = beats(0.5 * (cuts[k] + cuts[k + 1]));
            if winner != 0 && beats(cuts[k]) != -winner && beats(cuts[k + 1]) != -winner {
                loser[k] = -winner;
            }
        }
        // The squared equation loses digits near a double root: polish each
        // cut where the winner changes by Newton steps on d1 - d2 itself,
        // kept between the neighbouring midpoints.
        for k in 1..n {
            if loser[k - 1] != loser[k] {
                let (lo, hi) = (0.5 * (cuts[k - 1] + cuts[k]), 0.5 * (cuts[k] + cuts[k + 1]));
                cuts[k] = polish_root(w1, w2, cuts[k], lo, hi);
            }
        }
        let pieces = &cuts[..=n];
        let keep1 = trim_ends(w1, pieces, &loser[..n], 1);
        let keep2 = trim_ends(w2, pieces, &loser[..n], -1);
        (keep1, keep2)
    }

    /// The cone of rays from the source through the points `q0` and `q1` of
    /// this face (in the window's frame), on the face's edge whose twin runs
    /// from `from` to `to` (in the window's frame): the interval it covers
    /// and the source, in the twin's frame (origin at `from`, the face
    /// below). O(1).
    pub fn onto_edge(&self, from: DVec2, to: DVec2, len: f64, q0: DVec2, q1: DVec2) -> (f64, f64, DVec2) {
        let u = (to - from) / len;
        let n = DVec2::new(-u.y, u.x);
        let local = |p: DVec2| DVec2::new((p - from).dot(u), (p - from).dot(n));
        let s = local(self.source);
        let hit = |q: DVec2| {
            let q = local(q);
            if q.y.abs() < 1e-300 || q.y - s.y <= 0.0 {
                q.x // on the edge line already (the apex), or parallel
            } else {
                s.x + (q.x - s.x) * (-s.y) / (q.y - s.y)
            }
        };
        let (x0, x1) = (hit(q0), hit(q1));
        (x0.min(x1), x0.max(x1), DVec2::new(s.x, s.y.min(0.0)))
    }
}

/// `sqrt(x^2 + y^2)` without `hypot`'s overflow guard (which took half of
/// the run time): `exact_distance` first brings the mesh to a length unit
/// within 2^-100 .. 2^100 (`mesh_kernel::units::normalized`), so squares
/// neither overflow nor underflow.
#[inline]
fn planar_norm(x: f64, y: f64) -> f64 {
    (x * x + y * y).sqrt()
}

/// The points of the edge line where two windows' distances may be equal:
/// the real roots of the quadratic obtained by squaring
/// `sigma1 + |s1 p| = sigma2 + |s2 p|` twice (spurious roots only add a cut).
fn equal_distance_points(w1: &Window, w2: &Window) -> [f64; 2] {
    // Coordinates centred on the second source's foot.
    let x1 = w1.source.x - w2.source.x;
    let (y1, y2) = (w1.source.y, w2.source.y);
    let a = w2.sigma - w1.sigma; // |s1 p| = |s2 p| + a
    let alpha = -x1;
    let beta = 0.5 * (x1 * x1 + y1 * y1 - y2 * y2 - a * a);
    let (qa, qb, qc) = (a * a - alpha * alpha, -2.0 * alpha * beta, a * a * y2 * y2 - beta * beta);
    // Equal sigmas (a = 0) make a double root; rounding can push its
    // discriminant below zero.
    let disc = qb * qb - 4.0 * qa * qc;
    let disc = if disc < 0.0 && disc > -1e-12 * (qb * qb + (4.0 * qa * qc).abs()) { 0.0 } else { disc };
    if !(disc >= 0.0) {
        return [f64::NAN; 2];
    }
    let q = -0.5 * (qb + disc.sqrt().copysign(qb));
    [q / qa + w2.source.x, qc / q + w2.source.x]
}

/// Newton steps on `d1(x) - d2(x)` from `x`, staying strictly inside
/// `(lo, hi)`.
fn polish_root(w1: &Window, w2: &Window, mut x: f64, lo: f64, hi: f64) -> f64 {
    for _ in 0..3 {
        let (r1, r2) = (planar_norm(x - w1.source.x, w1.source.y), planar_norm(x - w2.source.x, w2.source.y));
        let f = w1.sigma + r1 - w2.sigma - r2;
        let df = (x - w1.source.x) / r1 - (x - w2.source.x) / r2;
        let next = x - f / df;
        if !(next > lo && next < hi) || next == x {
            break;
        }
        x = next;
    }
    x
}

/// Shrinks `w` by the pieces (between consecutive `cuts`) it loses
/// (`loser[k] == me`) at its own ends; `false` when nothing is left.
fn trim_ends(w: &mut Window, cuts: &[f64], loser: &[i8], me: i8) -> bool {
    let n = loser.len();
    let lost_prefix = loser.iter().take_while(|&&l| l == me).count();
    if cuts[0] <= w.b0 && lost_prefix == n && cuts[n] >= w.b1 {
        return false;
    }
    if cuts[0] <= w.b0 && lost_prefix > 0 {
        w.b0 = cuts[lost_prefix];
    }
    let lost_suffix = loser.iter().rev().take_while(|&&l| l == me).count();
    if cuts[n] >= w.b1 && lost_suffix > 0 {
        w.b1 = cuts[n - lost_suffix];
    }
    w.b1 > w.b0
}

#[cfg(test)]
mod tests {
    use super::*;
    use mesh_kernel::random::SplitMix64;

    /// Every point a window loses is reached more shortly by the other
    /// window there, on random pairs (brute force on a fine sampling).
    #[test]
    fn trimming_only_drops_beaten_points() {
        let mut rng = SplitMix64::new(7);
        let mut worst = 0.0f64;
        for _ in 0..20_000 {
            let mut random_window = || {
                let (a, b) = (rng.unit(), rng.unit());
                let source = DVec2::new(3.0 * rng.unit() - 1.0, -2.0 * rng.unit() - 1e-3);
                Window { b0: a.min(b), b1: a.max(b), source, sigma: rng.unit() }
            };
            let (o1, o2) = (random_window(), random_window());
            let (mut w1, mut w2) = (o1, o2);
            let (k1, k2) = Window::trim_pair(&mut w1, &mut w2);
            for i in 0..=400 {
                let p = i as f64 / 400.0;
                let lost =
                    |o: &Window, w: &Window, kept: bool| o.b0 <= p && p <= o.b1 && (!kept || p < w.b0 || p > w.b1);
                let covers = |o: &Window| o.b0 <= p && p <= o.b1;
                if lost(&o1, &w1, k1) {
                    worst = worst.max(if covers(&o2) { o2.at(p) - o1.at(p) } else { f64::INFINITY });
                }
                if lost(&o2, &w2, k2) {
                    worst = worst.max(if covers(&o1) { o1.at(p) - o2.at(p) } else { f64::INFINITY });
                }
            }
        }
        assert!(worst < 1e-9, "a lost point was better by {worst:e}");
    }
}
