//! One chart's remeshing: the polygon through its seam samples in the
//! parameter plane, split where it passes twice through one output vertex,
//! refined by sized constrained Delaunay refinement, and lifted onto the
//! input.

use std::collections::{HashMap, HashSet};

use glam::{DVec2, DVec3};
use mesh_delaunay::{refine_polygon_sized, PolygonDomain, RefineOptions};
use mesh_kernel::geometry;
use mesh_param::{Chart, ChartLayout};

use crate::error::{RemeshError, Result};
use crate::locate::UvGrid;
use crate::remesh::{RemeshOptions, SIZE_FACTOR};
use crate::seams::Seams;

/// Which output vertex each chart boundary point is, and its UV: the loop
/// through the seam samples.
pub(crate) fn chart_polygon(chart: &Chart, lp: &[u32], seams: &Seams) -> (Vec<DVec2>, Vec<u32>) {
    let (mut uv, mut ids) = (Vec::new(), Vec::new());
    for i in 0..lp.len() {
        let (ci, cj) = (lp[i] as usize, lp[(i + 1) % lp.len()] as usize);
        let (a, b) = (chart.vertices[ci].0, chart.vertices[cj].0);
        let (ua, ub) = (chart.uv[ci], chart.uv[cj]);
        if let Some(&id) = seams.vertex_out.get(&a) {
            uv.push(ua);
            ids.push(id);
        }
        if let Some(samples) = seams.edge_samples.get(&(a.min(b), a.max(b))) {
            if a < b {
                for &(t, id) in samples {
                    uv.push(ua.lerp(ub, t));
                    ids.push(id);
                }
            } else {
                for &(t, id) in samples.iter().rev() {
                    uv.push(ub.lerp(ua, t));
                    ids.push(id);
                }
            }
        }
    }
    (uv, ids)
}

/// An output triangle of a chart: output ids and parameter points.
pub(crate) type ChartTriangle = ([u32; 3], [DVec2; 3]);

/// A chart's parameter triangles and a grid over them, to lift parameter
/// points onto the input by barycentric interpolation.
pub(crate) struct Lifter<'a> {
    chart: &'a Chart,
    tris: Vec<[DVec2; 3]>,
    grid: UvGrid,
}

impl<'a> Lifter<'a> {
    /// The chart's parameter triangles and their grid. O(chart faces).
    pub(crate) fn new(chart: &'a Chart) -> Self {
        let tris: Vec<[DVec2; 3]> = chart.mesh.faces().iter().map(|t| t.map(|v| chart.uv[v as usize])).collect();
        let grid = UvGrid::new(&tris);
        Self { chart, tris, grid }
    }

    /// The chart face containing `x` (within 1e-9) and `x`'s barycentric
    /// coordinates in it.
    fn locate(&self, x: DVec2) -> Option<(usize, [f64; 3])> {
        self.grid.locate(&self.tris, x, 1e-9)
    }

    /// The point of the input at parameter point `x`.
    pub(crate) fn lift(&self, x: DVec2) -> Option<DVec3> {
        let (t, b) = self.locate(x)?;
        let cm = &self.chart.mesh;
        Some(cm.faces()[t].iter().zip(b).map(|(&v, w)| w * cm.positions()[v as usize]).sum())
    }
}

/// Triangulates one chart, given its polygon (parameter points and output
/// ids, [`chart_polygon`]): its output triangles (new vertices appended to
/// `seams.positions`).
pub(crate) fn chart_triangles(
    c: usize,
    chart: &Chart,
    (outer, ids): (Vec<DVec2>, Vec<u32>),
    seams: &mut Seams,
    options: &RemeshOptions,
) -> Result<Vec<ChartTriangle>> {
    let fail = |reason: String| RemeshError::ChartFailed { chart: c, reason };
    if chart.layout == ChartLayout::FacesApart {
        return Err(fail("the chart could not be flattened (laid out face by face)".into()));
    }
    if chart.distortion.flipped_faces > 0 || !chart.distortion.boundary_simple {
        return Err(fail(format!(
            "its map folds ({} flipped faces, simple boundary: {})",
            chart.distortion.flipped_faces, chart.distortion.boundary_simple
        )));
    }
    let cm = &chart.mesh;
    let lifter = Lifter::new(chart);
    let tris = &lifter.tris;
    let signed: f64 = tris.iter().map(|t| (t[1] - t[0]).perp_dot(t[2] - t[0])).sum();
    // Parameter scale per chart vertex: the smallest singular value of the
    // map (UV length per surface length in the most shortened direction)
    // of its faces, weighted by area, so that no 3D edge exceeds the size
    // in any direction.
    let n = cm.vertex_count();
    let (mut uv_area, mut area, mut sigma) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    for (t, f) in tris.iter().zip(cm.faces()) {
        let a_uv = 0.5 * (t[1] - t[0]).perp_dot(t[2] - t[0]).abs();
        let p = f.map(|v| cm.positions()[v as usize]);
        let a3 = geometry::triangle_area(p);
        let s = smallest_singular_value(p, *t);
        for &v in f {
            uv_area[v as usize] += a_uv;
            area[v as usize] += a3;
            if s.is_finite() {
                sigma[v as usize] += a3 * s;
            }
        }
    }
    let total = (uv_area.iter().sum::<f64>() / area.iter().sum::<f64>()).sqrt();
    let chart_scale = if total.is_finite() && total > 0.0 { total } else { 1.0 };
    let scale: Vec<f64> = (0..n)
        .map(|v| {
            let s = sigma[v] / area[v];
            if s.is_finite() && s > 0.0 {
                s
            } else {
                chart_scale
            }
        })
        .collect();
    let h = options.edge_length * SIZE_FACTOR;
    let lift = |x: DVec2| lifter.lift(x);
    let pieces = split_polygon(outer, ids, options.edge_length, &lift, &mut seams.positions)
        .map_err(|x| fail(format!("the parameter point {x} of a chord lies in no triangle of the chart")))?;
    let mut out: Vec<([u32; 3], [DVec2; 3])> = Vec::new();
    for (outer, ids) in pieces {
        let floor = SizeFloor::new(&outer);
        let size = |x: DVec2| {
            let s = match lifter.locate(x) {
                Some((t, b)) => h * cm.faces()[t].iter().zip(b).map(|(&v, w)| w * scale[v as usize]).sum::<f64>(),
                None => h * chart_scale,
            };
            s.max(floor.at(x))
        };
        let budget = options.max_vertices.saturating_sub(seams.positions.len());
        let refine = RefineOptions {
            min_angle: options.min_angle,
            max_area: None,
            max_added_vertices: budget,
            keep_boundary: true,
        };
        let domain = PolygonDomain { outer, holes: Vec::new() };
        let r = refine_polygon_sized(&domain, size, &refine)
            .map_err(|source| RemeshError::Delaunay { chart: c, source })?;
        if !r.complete {
            return Err(RemeshError::TooManyVertices {
                edge_length: options.edge_length,
                estimated: seams.positions.len() + r.points.len(),
                limit: options.max_vertices,
            });
        }
        if r.input_vertices != ids.len() {
            return Err(fail("the refinement changed the boundary".into()));
        }
        // Lift the new points.
        let mut index = ids;
        for &x in &r.points[r.input_vertices..] {
            let p = lift(x).ok_or_else(|| fail(format!("the parameter point {x} lies in no triangle of the chart")))?;
            index.push(seams.positions.len() as u32);
            seams.positions.push(p);
        }
        for t in &r.triangles {
            let (mut tri, mut uv) = (t.map(|v| index[v as usize]), t.map(|v| r.points[v as usize]));
            if signed < 0.0 {
                tri.swap(1, 2);
                uv.swap(1, 2);
            }
            if tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] {
                return Err(fail("an output triangle joins two copies of one output vertex".into()));
            }
            out.push((tri, uv));
        }
    }
    Ok(out)
}

/// A chart's polygon, split into polygons that pass through each output
/// vertex at most once (or twice, joined by a chord's samples).
///
/// A chart's boundary loop passes twice through an input vertex where the
/// chart touches itself there (a pinch) and along a cut inside the chart
/// (both sides of the cut have the same seam samples). The two copies are
/// distinct points of the parameter plane but one output vertex, so a
/// triangle joining them would collapse. Each such pair is joined by a
/// straight chord (inside the polygon, which is convex: its points lie in
/// order on the chart's convex boundary), sampled into at least 3 segments
/// (2 would give both sides the same pair of faces) of about `h` in 3D
/// (lifted with `lift`); the polygon is cut along the chord into two, which
/// share the chord's samples, and each part is split again until no pair is
/// left. A triangle then cannot join two copies: the chord's samples lie
/// between them. O(n^2) in the loop's length in the worst case (a long
/// cut), O(n) for a pinch.
///
/// Returns the parameter point that could not be lifted on failure.
fn split_polygon(
    uv: Vec<DVec2>,
    ids: Vec<u32>,
    h: f64,
    lift: &dyn Fn(DVec2) -> Option<DVec3>,
    positions: &mut Vec<DVec3>,
) -> std::result::Result<Vec<Polygon>, DVec2> {
    let mut joined: HashSet<(usize, usize)> = HashSet::new();
    let mut work: Vec<Vec<Point>> =
        vec![uv.into_iter().zip(ids).enumerate().map(|(i, (x, id))| (x, id, Some(i))).collect()];
    let mut done = Vec::new();
    while let Some(polygon) = work.pop() {
        let Some((i, j)) = repeated_pair(&polygon, &joined) else {
            done.push((polygon.iter().map(|p| p.0).collect(), polygon.iter().map(|p| p.1).collect()));
            continue;
        };
        let (a, b) = (polygon[i], polygon[j]);
        if let (Some(ia), Some(ib)) = (a.2, b.2) {
            joined.insert((ia.min(ib), ia.max(ib)));
        }
        // The chord from a to b, lifted at 32 points to measure it in 3D.
        let mut length = 0.0;
        let mut prev = positions[a.1 as usize];
        for k in 1..=32 {
            let x = a.0.lerp(b.0, k as f64 / 32.0);
            let p = if k == 32 { positions[b.1 as usize] } else { lift(x).ok_or(x)? };
            length += prev.distance(p);
            prev = p;
        }
        let n = (length / h).round();
        let n = if n.is_finite() { (n as usize).clamp(3, 1 << 16) } else { 3 };
        let mut chord = Vec::with_capacity(n - 1);
        for k in 1..n {
            let x = a.0.lerp(b.0, k as f64 / n as f64);
            chord.push((x, positions.len() as u32, None));
            positions.push(lift(x).ok_or(x)?);
        }
        // polygon[i..=j] then the chord back from b to a; polygon[j..] and
        // polygon[..=i] then the chord from a to b.
        let mut first: Vec<Point> = polygon[i..=j].to_vec();
        first.extend(chord.iter().rev());
        let mut second: Vec<Point> = polygon[j..].iter().chain(&polygon[..=i]).copied().collect();
        second.extend(chord.iter());
        work.push(first);
        work.push(second);
    }
    Ok(done)
}

/// A polygon: its parameter points and their output ids.
type Polygon = (Vec<DVec2>, Vec<u32>);

/// A polygon point: its UV, output id, and index in the chart's loop (None
/// for a chord sample).
type Point = (DVec2, u32, Option<usize>);

/// Two points of `polygon` with the same output id that are not yet joined
/// by a chord, nearest along the loop first. O(n).
fn repeated_pair(polygon: &[Point], joined: &HashSet<(usize, usize)>) -> Option<(usize, usize)> {
    let mut seen: HashMap<u32, Vec<usize>> = HashMap::new();
    let mut best: Option<(usize, usize)> = None;
    for (j, p) in polygon.iter().enumerate() {
        let earlier = seen.entry(p.1).or_default();
        for &i in earlier.iter() {
            let is_joined = match (polygon[i].2, p.2) {
                (Some(a), Some(b)) => joined.contains(&(a.min(b), a.max(b))),
                _ => false,
            };
            if !is_joined && best.is_none_or(|(bi, bj)| j - i < bj - bi) {
                best = Some((i, j));
            }
        }
        earlier.push(j);
    }
    best
}

/// A lower bound of the size near the polygon's edges: each edge's length
/// (plus 1%) within that length of its midpoint, on a grid of at most
/// 64 x 64 cells. With the boundary kept, an edge longer than the size
/// would exempt every triangle at its ends from the size bound (the
/// refinement cannot shorten it); the seam samples are placed in 3D, and
/// the map's anisotropy can make a segment longer in the plane than the
/// isotropic size there. The floor lets the triangles along the seam be as
/// long as the seam's segments, and no longer.
struct SizeFloor {
    min: DVec2,
    cell: f64,
    n: [usize; 2],
    floor: Vec<f64>,
}

impl SizeFloor {
    fn new(polygon: &[DVec2]) -> Self {
        let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
        for p in polygon {
            lo = lo.min(*p);
            hi = hi.max(*p);
        }
        let extent = (hi - lo).max_element();
        if !(extent.is_finite() && extent > 0.0) {
            return Self { min: DVec2::ZERO, cell: 1.0, n: [1, 1], floor: vec![0.0] };
        }
        let cell = extent / 64.0;
        let n = [((hi.x - lo.x) / cell) as usize + 1, ((hi.y - lo.y) / cell) as usize + 1].map(|k| k.min(65));
        let mut floor = Self { min: lo, cell, n, floor: vec![0.0; n[0] * n[1]] };
        for i in 0..polygon.len() {
            let (a, b) = (polygon[i], polygon[(i + 1) % polygon.len()]);
            let (mid, u) = (0.5 * (a + b), a.distance(b));
            let (x0, y0) = floor.cell_of(mid - DVec2::splat(u));
            let (x1, y1) = floor.cell_of(mid + DVec2::splat(u));
            for y in y0..=y1 {
                for x in x0..=x1 {
                    let f = &mut floor.floor[y * n[0] + x];
                    *f = f.max(1.01 * u);
                }
            }
        }
        floor
    }

    fn cell_of(&self, p: DVec2) -> (usize, usize) {
        let q = (p - self.min) / self.cell;
        let c = |v: f64, n: usize| if v.is_nan() { 0 } else { (v.max(0.0) as usize).min(n - 1) };
        (c(q.x, self.n[0]), c(q.y, self.n[1]))
    }

    fn at(&self, p: DVec2) -> f64 {
        let (x, y) = self.cell_of(p);
        self.floor[y * self.n[0] + x]
    }
}

/// The smallest singular value of the linear map from the surface triangle
/// `p` (in its own plane) to the parameter triangle `q`; NaN for a
/// degenerate triangle. O(1).
fn smallest_singular_value(p: [DVec3; 3], q: [DVec2; 3]) -> f64 {
    let (e1, e2) = (p[1] - p[0], p[2] - p[0]);
    let l = e1.length();
    let normal = e1.cross(e2);
    let (x, y) = (e1 / l, normal.cross(e1).normalize());
    // Plane coordinates: (l, 0) and (e2.x, e2.y).
    let (bx, by) = (e2.dot(x), e2.dot(y));
    let det = l * by;
    let (u1, u2) = (q[1] - q[0], q[2] - q[0]);
    // J = [u1 u2] [[l, bx], [0, by]]^-1.
    let inv = [[1.0 / l, -bx / det], [0.0, 1.0 / det]];
    let (a, b) = (u1.x * inv[0][0] + u2.x * inv[1][0], u1.x * inv[0][1] + u2.x * inv[1][1]);
    let (c, d) = (u1.y * inv[0][0] + u2.y * inv[1][0], u1.y * inv[0][1] + u2.y * inv[1][1]);
    let e = a * a + b * b + c * c + d * d;
    let dd = a * d - b * c;
    ((e - (e * e - 4.0 * dd * dd).max(0.0).sqrt()) / 2.0).max(0.0).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area(p: &[DVec2]) -> f64 {
        0.5 * (0..p.len()).map(|i| p[i].perp_dot(p[(i + 1) % p.len()])).sum::<f64>()
    }

    /// A polygon through one output vertex twice (a pinch): two polygons
    /// joined by a chord of at least 3 segments, sharing its samples, with
    /// the same total area, and no triangle can join the two copies.
    #[test]
    fn a_pinched_polygon_is_split_along_a_chord() {
        let uv: Vec<DVec2> = (0..8).map(|k| DVec2::from_angle(k as f64 * std::f64::consts::TAU / 8.0)).collect();
        let ids = vec![0, 1, 2, 3, 0, 4, 5, 6];
        // Both copies of id 0, (1, 0) and (-1, 0), lift to the same point.
        let lift = |x: DVec2| Some(DVec3::new(x.x * x.x, x.y, 0.0));
        let mut positions: Vec<DVec3> = ids.iter().zip(&uv).take(7).map(|(_, x)| lift(*x).unwrap()).collect();
        positions[0] = DVec3::X;
        for (i, &id) in ids.iter().enumerate().skip(5) {
            positions[id as usize] = lift(uv[i]).unwrap();
        }
        let before = positions.len();
        let pieces = split_polygon(uv.clone(), ids, 0.3, &lift, &mut positions).unwrap();
        assert_eq!(pieces.len(), 2);
        let added = positions.len() - before;
        assert!(added >= 2, "{added}");
        let total: f64 = pieces.iter().map(|(p, _)| area(p)).sum();
        assert!((total - area(&uv)).abs() < 1e-12, "{total}");
        for (p, ids) in &pieces {
            assert!(area(p) > 0.1);
            // Every chord sample is in both pieces.
            for id in before as u32..positions.len() as u32 {
                assert!(ids.contains(&id));
            }
            // The copies of 0 are never neighbours along a piece.
            let n = ids.len();
            assert!((0..n).all(|i| ids[i] != ids[(i + 1) % n]));
        }
        // Chord samples lie on the straight chord, lifted.
        for p in &positions[before..] {
            assert!(p.y.abs() < 1e-12 && p.x <= 1.0, "{p}");
        }
    }

    /// Both sides of a cut carry the same samples: the polygon is split into
    /// bands, none of which passes twice through an output vertex unjoined.
    #[test]
    fn a_cut_is_split_into_bands() {
        // A circle with a cut from id 1 through 2 to the tip 3, then back.
        let uv: Vec<DVec2> = (0..8).map(|k| DVec2::from_angle(k as f64 * std::f64::consts::TAU / 8.0)).collect();
        let ids = vec![0, 1, 2, 3, 2, 1, 4, 5];
        let lift = |x: DVec2| Some(x.extend(0.0));
        let mut positions: Vec<DVec3> = (0..6).map(|_| DVec3::ZERO).collect();
        let pieces = split_polygon(uv.clone(), ids, 0.5, &lift, &mut positions).unwrap();
        assert_eq!(pieces.len(), 3);
        let total: f64 = pieces.iter().map(|(p, _)| area(p)).sum();
        assert!((total - area(&uv)).abs() < 1e-12);
        assert!(pieces.iter().all(|(p, _)| area(p) > 0.0));
    }
}
