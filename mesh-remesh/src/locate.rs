//! Point location in a chart's parameter domain: a uniform grid over its
//! UV triangles, and barycentric coordinates.

use glam::DVec2;

/// A uniform grid over a set of plane triangles: each cell lists the
/// triangles whose bounding box meets it. About one triangle per cell.
#[derive(Debug, Clone)]
pub struct UvGrid {
    min: DVec2,
    cell: f64,
    nx: usize,
    ny: usize,
    /// `start[c]..start[c + 1]` indexes `items` for cell c.
    start: Vec<u32>,
    items: Vec<u32>,
}

/// Barycentric coordinates of `p` in the triangle `t` (`None` for a
/// triangle without area). O(1).
pub fn barycentric(t: [DVec2; 3], p: DVec2) -> Option<[f64; 3]> {
    let d = (t[1] - t[0]).perp_dot(t[2] - t[0]);
    if d == 0.0 || !d.is_finite() {
        return None;
    }
    let b1 = (p - t[0]).perp_dot(t[2] - t[0]) / d;
    let b2 = (t[1] - t[0]).perp_dot(p - t[0]) / d;
    Some([1.0 - b1 - b2, b1, b2])
}

impl UvGrid {
    /// The grid over `triangles` (about one triangle per cell). O(T) for
    /// triangles of similar size.
    pub fn new(triangles: &[[DVec2; 3]]) -> Self {
        let mut min = DVec2::splat(f64::INFINITY);
        let mut max = DVec2::splat(f64::NEG_INFINITY);
        for p in triangles.iter().flatten().filter(|p| p.is_finite()) {
            min = min.min(*p);
            max = max.max(*p);
        }
        if !(min.is_finite() && max.is_finite()) {
            return Self { min: DVec2::ZERO, cell: 1.0, nx: 1, ny: 1, start: vec![0, 0], items: Vec::new() };
        }
        let size = (max - min).max(DVec2::splat(f64::MIN_POSITIVE));
        let n = triangles.len().clamp(1, 1 << 22) as f64;
        let cell = (size.x * size.y / n).sqrt().max(size.max_element() / 4096.0).max(f64::MIN_POSITIVE);
        let nx = ((size.x / cell).ceil() as usize).clamp(1, 4096);
        let ny = ((size.y / cell).ceil() as usize).clamp(1, 4096);
        let mut grid = Self { min, cell, nx, ny, start: vec![0; nx * ny + 1], items: Vec::new() };
        let ranges: Vec<Option<[usize; 4]>> = triangles.iter().map(|t| grid.range(t)).collect();
        for [x0, x1, y0, y1] in ranges.iter().flatten() {
            for y in *y0..=*y1 {
                for x in *x0..=*x1 {
                    grid.start[y * nx + x + 1] += 1;
                }
            }
        }
        for c in 0..nx * ny {
            grid.start[c + 1] += grid.start[c];
        }
        let mut fill = grid.start.clone();
        grid.items = vec![0; grid.start[nx * ny] as usize];
        for (i, r) in ranges.iter().enumerate() {
            let Some([x0, x1, y0, y1]) = *r else { continue };
            for y in y0..=y1 {
                for x in x0..=x1 {
                    let c = y * nx + x;
                    grid.items[fill[c] as usize] = i as u32;
                    fill[c] += 1;
                }
            }
        }
        grid
    }

    fn cell_of(&self, p: DVec2) -> (usize, usize) {
        let q = (p - self.min) / self.cell;
        let clamp = |v: f64, n: usize| if v.is_nan() { 0 } else { (v.max(0.0) as usize).min(n - 1) };
        (clamp(q.x, self.nx), clamp(q.y, self.ny))
    }

    fn range(&self, t: &[DVec2; 3]) -> Option<[usize; 4]> {
        if !t.iter().all(|p| p.is_finite()) {
            return None;
        }
        let lo = t[0].min(t[1]).min(t[2]);
        let hi = t[0].max(t[1]).max(t[2]);
        let (x0, y0) = self.cell_of(lo);
        let (x1, y1) = self.cell_of(hi);
        Some([x0, x1, y0, y1])
    }

    /// The triangle of `triangles` (the ones the grid was built on) that
    /// contains `p`, with its barycentric coordinates: the triangle of the
    /// cell whose smallest coordinate is largest, accepted when that is at
    /// least `-tolerance` (then clamped to the triangle). `None` when no
    /// triangle contains `p`. O(triangles per cell).
    pub fn locate(&self, triangles: &[[DVec2; 3]], p: DVec2, tolerance: f64) -> Option<(usize, [f64; 3])> {
        if !p.is_finite() {
            return None;
        }
        let (x, y) = self.cell_of(p);
        let c = y * self.nx + x;
        let mut best: Option<(usize, [f64; 3])> = None;
        for &i in &self.items[self.start[c] as usize..self.start[c + 1] as usize] {
            let Some(b) = barycentric(triangles[i as usize], p) else { continue };
            let worst = b[0].min(b[1]).min(b[2]);
            if best.is_none_or(|(_, bb)| worst > bb[0].min(bb[1]).min(bb[2])) {
                best = Some((i as usize, b));
            }
        }
        let (i, b) = best?;
        if b[0].min(b[1]).min(b[2]) < -tolerance {
            return None;
        }
        let c = b.map(|x| x.max(0.0));
        let s = c[0] + c[1] + c[2];
        Some((i, c.map(|x| x / s)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn locates_points_of_a_grid_of_triangles() {
        let mut tris = Vec::new();
        for i in 0..10 {
            for j in 0..10 {
                let o = DVec2::new(i as f64, j as f64);
                tris.push([o, o + DVec2::X, o + DVec2::ONE]);
                tris.push([o, o + DVec2::ONE, o + DVec2::Y]);
            }
        }
        let g = UvGrid::new(&tris);
        for k in 0..500 {
            let p = DVec2::new((k as f64 * 0.618).fract() * 10.0, (k as f64 * 0.377).fract() * 10.0);
            let (t, b) = g.locate(&tris, p, 1e-12).unwrap();
            let q = tris[t][0] * b[0] + tris[t][1] * b[1] + tris[t][2] * b[2];
            assert!((q - p).length() < 1e-12);
        }
        assert!(g.locate(&tris, DVec2::new(10.5, 3.0), 1e-9).is_none());
        assert!(g.locate(&tris, DVec2::NAN, 1e-9).is_none());
    }
}
