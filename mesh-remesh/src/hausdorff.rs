//! Distances between surfaces: the closest point on a triangle, a uniform
//! grid over a mesh's triangles for nearest-triangle queries, and the
//! sampled one-sided and symmetric Hausdorff distances.

use glam::DVec3;
use mesh_kernel::TriMesh;

/// The point of triangle `t` closest to `p` (Ericson 2005, "Real-Time
/// Collision Detection" 5.1.5: by the Voronoi regions of the vertices, the
/// edges and the face). Degenerate triangles are handled (the result is on
/// one of their edges). O(1).
pub fn closest_point_on_triangle(p: DVec3, [a, b, c]: [DVec3; 3]) -> DVec3 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return a + v * ab;
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return a + w * ac;
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return b + w * (c - b);
    }
    let denom = va + vb + vc;
    if denom.abs() <= f64::MIN_POSITIVE || !denom.is_finite() {
        // Degenerate (collinear) triangle: the closest of its edges.
        let seg = |u: DVec3, v: DVec3| {
            let d = v - u;
            let l = d.length_squared();
            if l > 0.0 {
                u + d * ((p - u).dot(d) / l).clamp(0.0, 1.0)
            } else {
                u
            }
        };
        return [seg(a, b), seg(b, c), seg(c, a)]
            .into_iter()
            .min_by(|x, y| x.distance_squared(p).total_cmp(&y.distance_squared(p)))
            .unwrap_or(a);
    }
    let v = vb / denom;
    let w = vc / denom;
    a + ab * v + ac * w
}

/// A uniform grid over a mesh's triangles, for the distance from a point
/// to the surface.
#[derive(Debug, Clone)]
pub struct TriangleGrid {
    triangles: Vec<[DVec3; 3]>,
    min: DVec3,
    cell: f64,
    dims: [usize; 3],
    start: Vec<u32>,
    items: Vec<u32>,
}

impl TriangleGrid {
    /// The grid over `mesh`'s faces (cells about 1.5 mean edge lengths wide,
    /// at most about 8 per triangle). `None`
    /// for a mesh without faces or with non-finite positions. O(F) for
    /// triangles of similar size.
    pub fn new(mesh: &TriMesh) -> Option<Self> {
        let triangles: Vec<[DVec3; 3]> = mesh.face_ids().map(|f| mesh.triangle(f)).collect();
        let first = *triangles.first()?.first()?;
        let (mut min, mut max) = (first, first);
        for p in triangles.iter().flatten() {
            min = min.min(*p);
            max = max.max(*p);
        }
        if !(min.is_finite() && max.is_finite()) {
            return None;
        }
        let size = (max - min).max(DVec3::splat(1e-300));
        let diag = size.length().max(1e-300);
        // Cells about the mean edge length (a few triangles each), at most
        // 4096 per axis and about 8 per triangle in all.
        let mean_edge = triangles.iter().map(|t| t[0].distance(t[1])).sum::<f64>() / triangles.len() as f64;
        let max_cells = (8 * triangles.len()).clamp(1 << 12, 1 << 24);
        let mut cell = (1.5 * mean_edge).max(diag / 4096.0).max(1e-300);
        let dims_for = |cell: f64| [0, 1, 2].map(|k| ((size[k] / cell).ceil() as usize).clamp(1, 4096));
        while dims_for(cell).iter().product::<usize>() > max_cells {
            cell *= 1.25;
        }
        let dims = dims_for(cell);
        let count = dims[0] * dims[1] * dims[2];
        let mut grid = Self { triangles, min, cell, dims, start: vec![0; count + 1], items: Vec::new() };
        let ranges: Vec<[[usize; 3]; 2]> = grid
            .triangles
            .iter()
            .map(|t| [grid.cell_of(t[0].min(t[1]).min(t[2])), grid.cell_of(t[0].max(t[1]).max(t[2]))])
            .collect();
        let each = |r: &[[usize; 3]; 2], f: &mut dyn FnMut(usize)| {
            for z in r[0][2]..=r[1][2] {
                for y in r[0][1]..=r[1][1] {
                    for x in r[0][0]..=r[1][0] {
                        f((z * dims[1] + y) * dims[0] + x);
                    }
                }
            }
        };
        for r in &ranges {
            each(r, &mut |c| grid.start[c + 1] += 1);
        }
        for c in 0..count {
            grid.start[c + 1] += grid.start[c];
        }
        let mut fill = grid.start.clone();
        let mut items = vec![0u32; grid.start[count] as usize];
        for (i, r) in ranges.iter().enumerate() {
            each(r, &mut |c| {
                items[fill[c] as usize] = i as u32;
                fill[c] += 1;
            });
        }
        grid.items = items;
        Some(grid)
    }

    fn cell_of(&self, p: DVec3) -> [usize; 3] {
        let q = (p - self.min) / self.cell;
        [0, 1, 2].map(|k| if q[k].is_nan() { 0 } else { (q[k].max(0.0) as usize).min(self.dims[k] - 1) })
    }

    /// The distance from `p` to the nearest triangle ([`TriangleGrid::closest`]);
    /// infinite for a grid without triangles.
    pub fn distance(&self, p: DVec3) -> f64 {
        self.closest(p).map_or(f64::INFINITY, |(q, _)| q.distance(p))
    }

    /// The nearest point to `p` on the triangles and its triangle's index
    /// (a face of the mesh the grid was built from): cells in growing shells
    /// around `p`'s cell until the nearest triangle found is closer than the
    /// next shell can be. `None` only for a non-finite `p`. O(triangles in
    /// the shells visited).
    pub fn closest(&self, p: DVec3) -> Option<(DVec3, usize)> {
        let c = self.cell_of(p);
        let mut best: Option<(f64, DVec3, usize)> = None;
        let max_r = self.dims.iter().copied().max().unwrap_or(1);
        for r in 0..=max_r {
            // Every point of a cell at Chebyshev ring r is at least r - 1
            // cells from p (anywhere in its cell), and at least p's
            // distance to the grid's box when p is outside it.
            let reach = ((r as f64 - 1.0).max(0.0) * self.cell).max(self.outside_distance(p));
            if best.is_some_and(|b| b.0 <= reach) && r > 0 {
                break;
            }
            let lo = c.map(|x| x as isize - r as isize);
            let hi = c.map(|x| x as isize + r as isize);
            for z in lo[2].max(0)..=hi[2].min(self.dims[2] as isize - 1) {
                for y in lo[1].max(0)..=hi[1].min(self.dims[1] as isize - 1) {
                    for x in lo[0].max(0)..=hi[0].min(self.dims[0] as isize - 1) {
                        let on_shell = [x, y, z].iter().zip(lo.iter().zip(&hi)).any(|(v, (l, h))| v == l || v == h);
                        if r > 0 && !on_shell {
                            continue;
                        }
                        // Skip a cell farther than the nearest point found.
                        let lo_corner = self.min + DVec3::new(x as f64, y as f64, z as f64) * self.cell;
                        let gap = (lo_corner - p).max(p - lo_corner - DVec3::splat(self.cell)).max(DVec3::ZERO);
                        if best.is_some_and(|b| gap.length() > b.0) {
                            continue;
                        }
                        let cell = (z as usize * self.dims[1] + y as usize) * self.dims[0] + x as usize;
                        for &i in &self.items[self.start[cell] as usize..self.start[cell + 1] as usize] {
                            let q = closest_point_on_triangle(p, self.triangles[i as usize]);
                            let d = q.distance(p);
                            if best.is_none_or(|b| d < b.0) {
                                best = Some((d, q, i as usize));
                            }
                        }
                    }
                }
            }
        }
        best.filter(|b| b.0.is_finite()).map(|b| (b.1, b.2))
    }

    /// How far `p` is outside the grid's box (0 inside).
    fn outside_distance(&self, p: DVec3) -> f64 {
        let max = self.min + DVec3::new(self.dims[0] as f64, self.dims[1] as f64, self.dims[2] as f64) * self.cell;
        (self.min - p).max(p - max).max(DVec3::ZERO).length()
    }
}

/// Sample points of a mesh's surface: its vertices, and per face the
/// centroid and the three points halfway from it to the corners.
pub fn surface_samples(mesh: &TriMesh) -> Vec<DVec3> {
    let mut out: Vec<DVec3> = mesh.positions().to_vec();
    for f in mesh.face_ids() {
        let [a, b, c] = mesh.triangle(f);
        let g = (a + b + c) / 3.0;
        out.extend([g, 0.5 * (g + a), 0.5 * (g + b), 0.5 * (g + c)]);
    }
    out
}

/// The largest distance from a sample of `from` ([`surface_samples`]) to
/// the surface of `to`: the one-sided Hausdorff distance, sampled (a lower
/// bound of the true one, within about a sample spacing times the surface's
/// slope). `None` when either mesh has no faces or non-finite positions.
/// O(samples x triangles per query).
pub fn one_sided_hausdorff(from: &TriMesh, to: &TriMesh) -> Option<f64> {
    let grid = TriangleGrid::new(to)?;
    if from.face_count() == 0 {
        return None;
    }
    let samples = surface_samples(from);
    // NaN (none expected) is ignored by f64::max.
    let d = mesh_kernel::par::map(samples.len(), |i| grid.distance(samples[i]))
        .into_iter()
        .fold(f64::NEG_INFINITY, f64::max);
    d.is_finite().then_some(d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closest_points_by_region() {
        let t = [DVec3::ZERO, DVec3::X, DVec3::Y];
        let cases = [
            (DVec3::new(0.2, 0.2, 1.0), DVec3::new(0.2, 0.2, 0.0)),
            (DVec3::new(-1.0, -1.0, 0.0), DVec3::ZERO),
            (DVec3::new(2.0, -0.5, 0.0), DVec3::X),
            (DVec3::new(0.5, -1.0, 3.0), DVec3::new(0.5, 0.0, 0.0)),
            (DVec3::new(1.0, 1.0, 0.0), DVec3::new(0.5, 0.5, 0.0)),
            (DVec3::new(-2.0, 0.5, 0.0), DVec3::new(0.0, 0.5, 0.0)),
        ];
        for (p, q) in cases {
            assert!(closest_point_on_triangle(p, t).distance(q) < 1e-12, "{p} -> {q}");
        }
        // Collinear triangle.
        let flat = [DVec3::ZERO, DVec3::X, 2.0 * DVec3::X];
        let q = closest_point_on_triangle(DVec3::new(1.5, 1.0, 0.0), flat);
        assert!(q.distance(DVec3::new(1.5, 0.0, 0.0)) < 1e-12);
    }

    #[test]
    fn grid_distance_matches_brute_force() {
        let m = mesh_kernel::shapes::torus(2.0, 0.5, 24, 12).unwrap();
        let g = TriangleGrid::new(&m).unwrap();
        let mut rng = mesh_kernel::random::SplitMix64::new(3);
        for _ in 0..300 {
            let p = DVec3::new(4.0 * rng.signed(), 4.0 * rng.signed(), 2.0 * rng.signed());
            let brute = m
                .face_ids()
                .map(|f| closest_point_on_triangle(p, m.triangle(f)).distance(p))
                .fold(f64::INFINITY, f64::min);
            assert!((g.distance(p) - brute).abs() < 1e-12, "{p}");
        }
        let far = DVec3::new(40.0, 0.0, 0.0);
        let brute = m
            .face_ids()
            .map(|f| closest_point_on_triangle(far, m.triangle(f)).distance(far))
            .fold(f64::INFINITY, f64::min);
        assert!((g.distance(far) - brute).abs() < 1e-12);
    }
}
