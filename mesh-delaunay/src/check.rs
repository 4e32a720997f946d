//! The empty-circumcircle property (Delaunay 1934; chapter section 2.2.2):
//! no point lies strictly inside the circumcircle of a triangle.

use glam::DVec2;

use crate::error::{DelaunayError, Result};
use crate::frame::{circumcenter, orient, unit_of_points};

/// What [`check_empty_circumcircles`] found.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct CircumcircleCheck {
    /// Triangles whose circumcircle holds a point strictly inside (beyond the
    /// tolerance).
    pub violations: usize,
    /// The first violation found: (triangle, point).
    pub first_violation: Option<(usize, u32)>,
    /// Triangles that are not counter-clockwise or have no finite
    /// circumcircle (zero area).
    pub degenerate: usize,
    /// The smallest ratio `|q - o| / R` over violating points (1 when there
    /// is none): how deep the worst point lies inside.
    pub worst_ratio: f64,
}

impl CircumcircleCheck {
    /// `true` when no triangle is degenerate and no circumcircle holds a
    /// point.
    pub fn is_delaunay(&self) -> bool {
        self.violations == 0 && self.degenerate == 0
    }
}

/// Checks that no point of `points` lies strictly inside the circumcircle
/// of any triangle: point q violates triangle (a, b, c) with circumcentre o
/// and radius R when `|q - o| < R (1 - tolerance)` (a relative tolerance;
/// co-circular points sit on the circle and pass with any tolerance of a
/// few ulps, e.g. `1e-9`). Every point counts, including points no triangle
/// uses and duplicates (which lie on the circle of their twin's triangles).
/// Points are bucketed in a uniform grid, so the cost is O(n + sum over
/// triangles of the points in the circumcircle's bounding box), near O(n)
/// for well-spread points.
///
/// # Errors
///
/// [`DelaunayError::InvalidTriangulation`] for an index out of range,
/// [`DelaunayError::InvalidOption`] for a tolerance outside `[0, 1)`,
/// [`DelaunayError::NonFinite`] / [`DelaunayError::OutOfRange`] for points
/// that cannot be triangulated.
pub fn check_empty_circumcircles(
    points: &[DVec2],
    triangles: &[[u32; 3]],
    tolerance: f64,
) -> Result<CircumcircleCheck> {
    if !(0.0..1.0).contains(&tolerance) {
        return Err(DelaunayError::InvalidOption {
            name: "tolerance",
            reason: format!("{tolerance} is not in [0, 1)"),
        });
    }
    if let Some(t) = triangles.iter().position(|t| t.iter().any(|&v| v as usize >= points.len())) {
        return Err(DelaunayError::InvalidTriangulation {
            reason: format!("triangle {t} has an index >= the {} points", points.len()),
        });
    }
    let unit = unit_of_points(points)?;
    let p: Vec<DVec2> = points.iter().map(|q| *q / unit).collect();
    let grid = Grid::new(&p);
    let mut out = CircumcircleCheck { violations: 0, first_violation: None, degenerate: 0, worst_ratio: 1.0 };
    for (t, tri) in triangles.iter().enumerate() {
        let [a, b, c] = tri.map(|v| p[v as usize]);
        let Some(o) = circumcenter(a, b, c).filter(|_| orient(a, b, c) > 0.0) else {
            out.degenerate += 1;
            continue;
        };
        let r = (a - o).length().max((b - o).length()).max((c - o).length());
        let limit = r * (1.0 - tolerance);
        let mut violated = false;
        grid.for_each_in(o - DVec2::splat(r), o + DVec2::splat(r), |q| {
            if tri.contains(&q) {
                return;
            }
            let d = (p[q as usize] - o).length();
            if d < limit {
                out.worst_ratio = out.worst_ratio.min(d / r);
                if !violated {
                    violated = true;
                    out.first_violation = out.first_violation.or(Some((t, q)));
                }
            }
        });
        out.violations += usize::from(violated);
    }
    Ok(out)
}

/// Points bucketed in a uniform grid of about one point per cell.
struct Grid {
    min: DVec2,
    cell: f64,
    dims: [usize; 2],
    start: Vec<u32>,
    items: Vec<u32>,
}

impl Grid {
    fn new(p: &[DVec2]) -> Self {
        let (mut min, mut max) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
        for q in p {
            min = min.min(*q);
            max = max.max(*q);
        }
        if p.is_empty() {
            (min, max) = (DVec2::ZERO, DVec2::ZERO);
        }
        let extent = (max - min).max_element();
        let side = (p.len() as f64).sqrt().ceil().max(1.0);
        let cell = if extent > 0.0 { extent / side } else { 1.0 };
        let dim = |e: f64| ((e / cell).floor() as usize + 1).min(1 << 16);
        let dims = [dim(max.x - min.x), dim(max.y - min.y)];
        let mut grid = Self { min, cell, dims, start: vec![0; dims[0] * dims[1] + 1], items: vec![0; p.len()] };
        let cells: Vec<usize> = p.iter().map(|q| grid.cell_of(*q)).collect();
        for &c in &cells {
            grid.start[c + 1] += 1;
        }
        for i in 0..dims[0] * dims[1] {
            grid.start[i + 1] += grid.start[i];
        }
        let mut fill = grid.start.clone();
        for (i, &c) in cells.iter().enumerate() {
            grid.items[fill[c] as usize] = i as u32;
            fill[c] += 1;
        }
        grid
    }

    fn coord(&self, x: f64, axis: usize) -> usize {
        let v = ((x - self.min[axis]) / self.cell).floor();
        if v > 0.0 {
            (v as usize).min(self.dims[axis] - 1)
        } else {
            0
        }
    }

    fn cell_of(&self, q: DVec2) -> usize {
        self.coord(q.y, 1) * self.dims[0] + self.coord(q.x, 0)
    }

    fn for_each_in(&self, lo: DVec2, hi: DVec2, mut f: impl FnMut(u32)) {
        let (x0, x1) = (self.coord(lo.x, 0), self.coord(hi.x, 0));
        let (y0, y1) = (self.coord(lo.y, 1), self.coord(hi.y, 1));
        for y in y0..=y1 {
            let row = y * self.dims[0];
            for &q in &self.items[self.start[row + x0] as usize..self.start[row + x1 + 1] as usize] {
                f(q);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_point_inside_a_circumcircle_is_found() {
        let p = [DVec2::new(0.0, 0.0), DVec2::new(1.0, 0.0), DVec2::new(0.0, 1.0), DVec2::new(0.9, 0.9)];
        // (0, 1, 2)'s circumcircle is centred at (0.5, 0.5) with radius 0.707: (0.9, 0.9) is inside.
        let c = check_empty_circumcircles(&p, &[[0, 1, 2]], 1e-9).expect("valid");
        assert_eq!((c.violations, c.first_violation, c.degenerate), (1, Some((0, 3)), 0));
        assert!(!c.is_delaunay());
        let c = check_empty_circumcircles(&p, &[[0, 1, 3], [0, 3, 2]], 1e-9).expect("valid");
        assert!(c.is_delaunay(), "{c:?}");
        let c = check_empty_circumcircles(&p, &[[0, 2, 1]], 1e-9).expect("valid");
        assert_eq!(c.degenerate, 1);
        assert!(check_empty_circumcircles(&p, &[[0, 1, 4]], 1e-9).is_err());
    }
}
