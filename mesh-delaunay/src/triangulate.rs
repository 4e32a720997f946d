//! The Delaunay triangulation of a planar point set (chapter section 2.2.2,
//! Figure 2.2), on spade's `DelaunayTriangulation` (exact orientation and
//! in-circle predicates after Shewchuk 1997).

use glam::DVec2;
use spade::{DelaunayTriangulation, HasPosition, Point2, Triangulation};

use crate::error::{DelaunayError, Result};
use crate::frame::unit_of_points;

/// A Delaunay triangulation of planar points: no point lies strictly inside
/// the circumcircle of any triangle.
///
/// **Duplicate points**: of several points with equal coordinates (`-0.0`
/// equals `0.0`) the one with the smallest index is kept and stands for the
/// others; `representative[i]` is the kept index for every input index `i`
/// (`representative[i] == i` for a kept point), and only kept indices occur
/// in `triangles`.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct Delaunay {
    /// The input points, unchanged.
    pub points: Vec<DVec2>,
    /// Triangles as indices into `points`, counter-clockwise.
    pub triangles: Vec<[u32; 3]>,
    /// For each input index, the index of the point kept for its position.
    pub representative: Vec<u32>,
    /// How many input points are duplicates of a kept point.
    pub duplicates: usize,
}

/// A vertex of spade's triangulation that remembers its input index.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Site {
    pub(crate) position: Point2<f64>,
    pub(crate) index: u32,
}

impl HasPosition for Site {
    type Scalar = f64;

    fn position(&self) -> Point2<f64> {
        self.position
    }
}

/// For each input index, the smallest index with the same coordinates, and
/// the number of duplicates. O(n log n).
pub(crate) fn representatives(points: &[DVec2]) -> (Vec<u32>, usize) {
    // `+ 0.0` turns -0.0 into 0.0, so that the two sort together.
    let key = |i: u32| {
        let p = points[i as usize];
        (p.x + 0.0, p.y + 0.0)
    };
    let mut order: Vec<u32> = (0..points.len() as u32).collect();
    order.sort_by(|&i, &j| {
        let (a, b) = (key(i), key(j));
        a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)).then(i.cmp(&j))
    });
    let mut rep: Vec<u32> = (0..points.len() as u32).collect();
    let mut duplicates = 0;
    for w in 1..order.len() {
        let (prev, cur) = (order[w - 1], order[w]);
        if key(prev) == key(cur) {
            rep[cur as usize] = rep[prev as usize];
            duplicates += 1;
        }
    }
    (rep, duplicates)
}

/// Checks the point count fits the `u32` indices of the outputs.
pub(crate) fn check_count(n: usize) -> Result<()> {
    if n > u32::MAX as usize {
        return Err(DelaunayError::InvalidOption {
            name: "points",
            reason: format!("{n} points; at most {} are indexed by u32", u32::MAX),
        });
    }
    Ok(())
}

/// The Delaunay triangulation of `points` (chapter section 2.2.2, Figure
/// 2.2): spade's bulk loading of the distinct points, divided exactly by a
/// power of two near their largest coordinate so that any finite scale
/// works. For co-circular points (a regular polygon, a grid) the Delaunay
/// triangulation is not unique and spade picks one. Duplicates: see
/// [`Delaunay`]. O(n log n) expected.
///
/// ```
/// use glam::DVec2;
/// let square = [DVec2::new(0.0, 0.0), DVec2::new(1.0, 0.0), DVec2::new(1.0, 1.0), DVec2::new(0.0, 1.0)];
/// let d = mesh_delaunay::delaunay(&square)?;
/// assert_eq!(d.triangles.len(), 2);
/// # Ok::<(), mesh_delaunay::DelaunayError>(())
/// ```
///
/// # Errors
///
/// [`DelaunayError::NonFinite`] for a NaN or infinite coordinate,
/// [`DelaunayError::OutOfRange`] for coordinates spread over more than
/// 2^142 (see [`DelaunayError::OutOfRange`]), [`DelaunayError::TooFewPoints`]
/// for fewer than 3 distinct points, [`DelaunayError::Collinear`] when all
/// points lie on one line, [`DelaunayError::InvalidOption`] for more than
/// `u32::MAX` points.
pub fn delaunay(points: &[DVec2]) -> Result<Delaunay> {
    check_count(points.len())?;
    let unit = unit_of_points(points)?;
    let (representative, duplicates) = representatives(points);
    let distinct = points.len() - duplicates;
    if distinct < 3 {
        return Err(DelaunayError::TooFewPoints { distinct });
    }
    let sites: Vec<Site> = (0..points.len() as u32)
        .filter(|&i| representative[i as usize] == i)
        .map(|i| {
            let p = points[i as usize] / unit;
            Site { position: Point2::new(p.x, p.y), index: i }
        })
        .collect();
    let dt = DelaunayTriangulation::<Site>::bulk_load(sites)
        .map_err(|e| DelaunayError::Backend { reason: format!("bulk load refused a checked point: {e:?}") })?;
    let triangles: Vec<[u32; 3]> = dt.inner_faces().map(|f| f.vertices().map(|v| v.data().index)).collect();
    if triangles.is_empty() {
        return Err(DelaunayError::Collinear { distinct });
    }
    Ok(Delaunay { points: points.to_vec(), triangles, representative, duplicates })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn duplicates_map_to_the_first_occurrence() {
        let p = [DVec2::new(0.0, 0.0), DVec2::new(1.0, 0.0), DVec2::new(-0.0, 0.0), DVec2::new(0.0, 1.0), DVec2::X];
        let (rep, dup) = representatives(&p);
        assert_eq!((rep, dup), (vec![0, 1, 0, 3, 1], 2));
    }
}
