//! Boundary maps for the fixed-boundary methods: where the boundary loop of a
//! disk goes in the parameter plane. All shapes are convex and inscribed in
//! the unit square [0, 1]^2, traversed counter-clockwise (the boundary loop
//! of a counter-clockwise mesh has its faces on the left), so Tutte and
//! mean-value maps onto them are bijective.

use glam::{DVec2, DVec3};
use mesh_kernel::{TriMesh, VertexId};

use crate::error::{ParamError, Result};

/// How boundary vertices are spaced along the target curve.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum Spacing {
    /// Equal parameter steps per boundary edge.
    Uniform,
    /// Steps proportional to the 3D boundary edge lengths (chord length).
    #[default]
    ChordLength,
}

/// Where the boundary of a disk is mapped.
#[derive(Debug, Clone, PartialEq)]
pub enum BoundaryMap {
    /// The circle of radius 1/2 centred at (1/2, 1/2).
    Circle(Spacing),
    /// The unit square [0, 1]^2, its four corners at the boundary vertices
    /// closest to a quarter, half and three quarters of the boundary length
    /// from the loop's first vertex, sides spaced by chord length. Needs at
    /// least four boundary vertices. A face with all three corners on one
    /// side is flattened (zero area): prefer the circle for bijectivity.
    Square,
    /// User-given positions: every boundary vertex must be listed (interior
    /// vertices may be too, they are then fixed as well).
    Fixed(Vec<(VertexId, DVec2)>),
}

impl Default for BoundaryMap {
    fn default() -> Self {
        Self::Circle(Spacing::ChordLength)
    }
}

impl Spacing {
    /// Both spacings; their [`name`](Self::name)s are what [`FromStr`](std::str::FromStr)
    /// accepts and [`Display`](std::fmt::Display) writes.
    pub const ALL: [Self; 2] = [Self::ChordLength, Self::Uniform];

    /// The command-line name: `chord`, `uniform`.
    pub fn name(self) -> &'static str {
        match self {
            Self::ChordLength => "chord",
            Self::Uniform => "uniform",
        }
    }
}

impl BoundaryMap {
    /// The boundaries that a name selects (the circle with chord-length
    /// spacing, the square); [`BoundaryMap::Fixed`] carries positions and
    /// has no name to parse.
    pub const ALL: [Self; 2] = [Self::Circle(Spacing::ChordLength), Self::Square];

    /// The command-line name: `circle`, `square`, `fixed`.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Circle(_) => "circle",
            Self::Square => "square",
            Self::Fixed(_) => "fixed",
        }
    }
}

mesh_kernel::named_choice!(Spacing, "spacing", ParamError);
mesh_kernel::named_choice!(BoundaryMap, "boundary", ParamError);

/// Cumulative parameter t_k in [0, 1) of each vertex of a closed loop:
/// uniform, or by chord length (zero-length edges get a small positive share
/// so that distinct vertices never coincide). O(n).
pub fn loop_parameters(positions: &[DVec3], spacing: Spacing) -> Vec<f64> {
    let n = positions.len();
    if n == 0 {
        return Vec::new();
    }
    let mut steps: Vec<f64> = match spacing {
        Spacing::Uniform => vec![1.0; n],
        Spacing::ChordLength => (0..n).map(|k| positions[k].distance(positions[(k + 1) % n])).collect(),
    };
    let mean = steps.iter().sum::<f64>() / n as f64;
    let floor = if mean > 0.0 { 1e-3 * mean } else { 1.0 };
    steps.iter_mut().for_each(|s| *s = s.max(floor));
    let total: f64 = steps.iter().sum();
    let mut t = Vec::with_capacity(n);
    let mut acc = 0.0;
    for s in steps {
        t.push(acc / total);
        acc += s;
    }
    t
}

/// Boundary vertices placed on the circle of radius 1/2 centred at
/// (1/2, 1/2), counter-clockwise from angle 0. O(n).
pub fn circle(mesh: &TriMesh, boundary: &[VertexId], spacing: Spacing) -> Vec<DVec2> {
    let p: Vec<DVec3> = boundary.iter().map(|&v| mesh.position(v)).collect();
    loop_parameters(&p, spacing)
        .into_iter()
        .map(|t| {
            let a = std::f64::consts::TAU * t;
            DVec2::new(0.5 + 0.5 * a.cos(), 0.5 + 0.5 * a.sin())
        })
        .collect()
}

/// Boundary vertices placed on the unit square (see [`BoundaryMap::Square`]).
/// O(n).
///
/// # Errors
/// `ParamError::InvalidOption` (`boundary`) for a loop of fewer than 4 vertices.
pub fn square(mesh: &TriMesh, boundary: &[VertexId]) -> Result<Vec<DVec2>> {
    let n = boundary.len();
    if n < 4 {
        return Err(ParamError::InvalidOption {
            name: "boundary",
            reason: format!("a square boundary needs at least 4 boundary vertices, the loop has {n}"),
        });
    }
    let p: Vec<DVec3> = boundary.iter().map(|&v| mesh.position(v)).collect();
    let t = loop_parameters(&p, Spacing::ChordLength);
    // Corner c at the vertex nearest to t = c / 4, strictly after the previous
    // corner and leaving room for the remaining ones.
    let mut corners = [0usize; 5];
    for c in 1..4 {
        let target = c as f64 / 4.0;
        let lo = corners[c - 1] + 1;
        let hi = n - (4 - c);
        let mut best = lo;
        for k in lo..=hi {
            if (t[k] - target).abs() < (t[best] - target).abs() {
                best = k;
            }
        }
        corners[c] = best;
    }
    corners[4] = n;
    let square = [DVec2::new(0.0, 0.0), DVec2::new(1.0, 0.0), DVec2::new(1.0, 1.0), DVec2::new(0.0, 1.0)];
    let mut uv = vec![DVec2::ZERO; n];
    for side in 0..4 {
        let (a, b) = (corners[side], corners[side + 1]);
        let (start, end) = (t[a], if b == n { 1.0 } else { t[b] });
        let span = end - start;
        for k in a..b {
            let s = (t[k] - start) / span;
            uv[k] = square[side].lerp(square[(side + 1) % 4], s);
        }
    }
    Ok(uv)
}

#[cfg(test)]
mod tests {
    use super::*;
    use mesh_kernel::shapes;

    fn loop_of(m: &TriMesh) -> Vec<VertexId> {
        m.connectivity().boundary_loops().unwrap()[0].vertices.clone()
    }

    /// Twice the signed area of a closed polygon.
    fn signed_area2(q: &[DVec2]) -> f64 {
        (0..q.len()).map(|k| q[k].perp_dot(q[(k + 1) % q.len()])).sum()
    }

    #[test]
    fn circle_is_counter_clockwise_and_on_the_circle() {
        let m = shapes::disk(5, 2).unwrap();
        let b = loop_of(&m);
        for spacing in [Spacing::Uniform, Spacing::ChordLength] {
            let uv = circle(&m, &b, spacing);
            assert!(uv.iter().all(|q| ((*q - DVec2::splat(0.5)).length() - 0.5).abs() < 1e-15));
            assert!(signed_area2(&uv) > 0.0);
            // The unit disk's boundary is evenly spaced: both spacings agree
            // up to the loop's starting angle.
            let a0 = (b[0].idx(), uv[1] - uv[0]);
            assert!((a0.1.length() - (uv[2] - uv[1]).length()).abs() < 1e-12);
        }
    }

    #[test]
    fn chord_length_follows_edge_lengths() {
        let p = [DVec3::ZERO, DVec3::X, DVec3::new(3.0, 0.0, 0.0), DVec3::new(3.0, 0.0, 0.0)];
        let t = loop_parameters(&p, Spacing::ChordLength);
        // Steps 1, 2, 0 (floored to 1e-3 * mean), 3.
        let floor = 1e-3 * 6.0 / 4.0;
        let total = 6.0 + floor;
        assert!((t[1] - 1.0 / total).abs() < 1e-15);
        assert!((t[2] - 3.0 / total).abs() < 1e-15);
        assert!(t[3] > t[2]);
    }

    #[test]
    fn square_has_corners_and_straight_sides() {
        let m = shapes::disk(6, 4).unwrap();
        let b = loop_of(&m);
        let uv = square(&m, &b).unwrap();
        for c in [DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y] {
            assert!(uv.contains(&c), "corner {c} missing");
        }
        assert!(uv.iter().all(|q| q.x.min(q.y).min(1.0 - q.x).min(1.0 - q.y).abs() < 1e-15));
        assert!((signed_area2(&uv) - 2.0).abs() < 1e-12);
        let tri = TriMesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y], vec![[0, 1, 2]]).unwrap();
        assert!(square(&tri, &loop_of(&tri)).is_err());
    }
}
