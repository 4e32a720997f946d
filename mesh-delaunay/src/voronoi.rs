//! The Voronoi diagram, dual of the Delaunay triangulation (chapter section
//! 2.2.2, Figure 2.2; Voronoi 1908, Delaunay 1934): the cell of a site is the
//! set of points closer to it than to any other site, here clipped to a box.

use glam::DVec2;

use crate::error::{DelaunayError, Result};
use crate::frame::{circumcenter, unit_of_points};
use crate::triangulate::Delaunay;

/// Options of [`voronoi`].
#[derive(Debug, Clone, PartialEq)]
pub struct VoronoiOptions {
    /// The clipping box `[min, max]`. Default `None`: the points' bounding
    /// box enlarged on every side by `margin` times its larger side.
    pub bounds: Option<[DVec2; 2]>,
    /// Margin of the default box, a fraction of the larger side of the
    /// points' bounding box. Default `0.1`.
    pub margin: f64,
}

impl Default for VoronoiOptions {
    fn default() -> Self {
        Self { bounds: None, margin: 0.1 }
    }
}

/// The Voronoi diagram of a [`Delaunay`] triangulation's points, clipped to
/// a box.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct Voronoi {
    /// One cell per input point: a convex polygon, counter-clockwise, without
    /// repeated closing vertex. Empty for a duplicate point (its
    /// representative has the cell) and for a site whose cell misses the box.
    /// Unbounded cells (of hull points) end at the box.
    pub cells: Vec<Vec<DVec2>>,
    /// The Voronoi vertices: the circumcentre of each Delaunay triangle, in
    /// the order of `triangles`, equidistant from its three sites (they may
    /// lie outside the box).
    pub vertices: Vec<DVec2>,
    /// The clipping box `[min, max]`.
    pub bounds: [DVec2; 2],
}

/// The Voronoi cells of `d`'s points clipped to a box: each cell is the box
/// cut by the bisector half-planes of its Delaunay neighbours (the cell of a
/// site is the intersection of those half-planes, because the Delaunay graph
/// contains every Voronoi neighbour), by Sutherland-Hodgman clipping, so
/// unbounded cells of hull points come out as bounded polygons without a
/// special case. O(sum of degree x cell size), O(n) for spread points.
///
/// # Errors
///
/// [`DelaunayError::InvalidOption`] for a box that is not finite or has
/// `min >= max` on an axis, or a negative or non-finite margin;
/// [`DelaunayError::NonFinite`] / [`DelaunayError::OutOfRange`] for points
/// that cannot be triangulated; [`DelaunayError::InvalidTriangulation`] for
/// an index out of range.
pub fn voronoi(d: &Delaunay, options: &VoronoiOptions) -> Result<Voronoi> {
    let n = d.points.len();
    if !(options.margin.is_finite() && options.margin >= 0.0) {
        return Err(DelaunayError::InvalidOption { name: "margin", reason: format!("{} is not >= 0", options.margin) });
    }
    if d.triangles.iter().any(|t| t.iter().any(|&v| v as usize >= n)) {
        return Err(DelaunayError::InvalidTriangulation { reason: "an index is out of range".into() });
    }
    let bounds = match options.bounds {
        Some([lo, hi]) => {
            if !(lo.is_finite() && hi.is_finite() && lo.x < hi.x && lo.y < hi.y) {
                return Err(DelaunayError::InvalidOption {
                    name: "bounds",
                    reason: format!("[{lo}, {hi}] is not a finite box with min < max"),
                });
            }
            [lo, hi]
        }
        None => {
            let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
            for p in &d.points {
                lo = lo.min(*p);
                hi = hi.max(*p);
            }
            // Halves first: hi - lo may overflow, hi / 2 - lo / 2 cannot.
            let side = (hi * 0.5 - lo * 0.5).max_element() * 2.0;
            let m = DVec2::splat(options.margin * side);
            if !(lo.is_finite() && hi.is_finite() && side > 0.0 && (lo - m).is_finite() && (hi + m).is_finite()) {
                return Err(DelaunayError::InvalidOption {
                    name: "bounds",
                    reason: "the points' bounding box with its margin is empty or not finite".into(),
                });
            }
            [lo - m, hi + m]
        }
    };
    // Work in a unit where nothing overflows: a power of two near the
    // largest coordinate of the points and the box (exact).
    let mut all = d.points.clone();
    all.extend(bounds);
    let unit = unit_of_points(&all)?;
    let p: Vec<DVec2> = d.points.iter().map(|q| *q / unit).collect();
    let [lo, hi] = bounds.map(|b| b / unit);
    let neighbours = neighbour_lists(n, &d.triangles);
    let mut cells = Vec::with_capacity(n);
    let mut buffer = Vec::new();
    for i in 0..n {
        let nb = &neighbours.1[neighbours.0[i] as usize..neighbours.0[i + 1] as usize];
        if d.representative.get(i).is_some_and(|&r| r as usize != i) || nb.is_empty() {
            cells.push(Vec::new());
            continue;
        }
        let mut cell = vec![lo, DVec2::new(hi.x, lo.y), hi, DVec2::new(lo.x, hi.y)];
        for &j in nb {
            let normal = p[j as usize] - p[i];
            let mid = 0.5 * (p[j as usize] + p[i]);
            clip(&cell, mid, normal, &mut buffer);
            std::mem::swap(&mut cell, &mut buffer);
            if cell.is_empty() {
                break;
            }
        }
        cells.push(cell.into_iter().map(|q| q * unit).collect());
    }
    let vertices = d
        .triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| p[v as usize]);
            circumcenter(a, b, c).map(|o| o * unit).unwrap_or(DVec2::NAN)
        })
        .collect::<Vec<_>>();
    if vertices.iter().any(|v| !v.is_finite()) {
        return Err(DelaunayError::InvalidTriangulation { reason: "a triangle has no finite circumcentre".into() });
    }
    Ok(Voronoi { cells, vertices, bounds })
}

/// Keeps the part of the convex polygon `poly` where `(x - mid) . normal <=
/// 0` (Sutherland and Hodgman 1974), into `out`.
fn clip(poly: &[DVec2], mid: DVec2, normal: DVec2, out: &mut Vec<DVec2>) {
    out.clear();
    let n = poly.len();
    for k in 0..n {
        let (a, b) = (poly[k], poly[(k + 1) % n]);
        let (da, db) = ((a - mid).dot(normal), (b - mid).dot(normal));
        if da <= 0.0 {
            out.push(a);
        }
        if (da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0) {
            let t = da / (da - db);
            out.push(a + (b - a) * t);
        }
    }
}

/// The neighbours of every vertex in a triangulation, CSR (offsets, items),
/// sorted and without repeats. O(n + T log).
pub(crate) fn neighbour_lists(n: usize, triangles: &[[u32; 3]]) -> (Vec<u32>, Vec<u32>) {
    let mut count = vec![0u32; n + 1];
    for t in triangles {
        for k in 0..3 {
            count[t[k] as usize + 1] += 2;
        }
    }
    for i in 0..n {
        count[i + 1] += count[i];
    }
    let mut fill = count.clone();
    let mut items = vec![0u32; count[n] as usize];
    for t in triangles {
        for k in 0..3 {
            let (a, b) = (t[k] as usize, t[(k + 1) % 3]);
            items[fill[a] as usize] = b;
            fill[a] += 1;
            items[fill[b as usize] as usize] = a as u32;
            fill[b as usize] += 1;
        }
    }
    let mut offsets = vec![0u32; n + 1];
    let mut out = Vec::with_capacity(items.len() / 2);
    for i in 0..n {
        let s = &mut items[count[i] as usize..count[i + 1] as usize];
        s.sort_unstable();
        for (k, &v) in s.iter().enumerate() {
            if k == 0 || s[k - 1] != v {
                out.push(v);
            }
        }
        offsets[i + 1] = out.len() as u32;
    }
    (offsets, out)
}
