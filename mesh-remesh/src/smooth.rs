//! Tangential smoothing on the input surface: each vertex moves toward the
//! centroid of its neighbours within its tangent plane and is projected
//! back onto the input, which evens out the triangles left thin where seams
//! meet (the smoothing step of isotropic remeshing, Botsch and Kobbelt
//! 2004).

use glam::DVec3;
use mesh_kernel::geometry::{self, NormalWeighting};
use mesh_kernel::{FaceId, TriMesh, VertexId};

use crate::hausdorff::TriangleGrid;

/// How far a vertex moves toward its tangential target in one iteration.
const DAMPING: f64 = 0.5;

/// Smooths `mesh` (an oriented manifold) tangentially, `iterations` times,
/// projecting every moved vertex onto `input` (through `grid`, built over
/// `input`'s faces). Boundary vertices stay. A move is kept only when:
/// - the projection lands within `h / 2` of the tangential target (not on
///   another sheet of a thin part);
/// - the input's normal there agrees with the vertex normal (a projection
///   onto the far side of a thin part points the other way);
/// - no more faces around the vertex point against the input's normal
///   there than before, and the smallest angle of its faces does not fall
///   below what it was or 20 degrees, whichever is less, unless the move
///   unfolds a face (a move never makes a fold or a worse sliver).
///
/// Returns the moves kept. O(iterations x (V + F) x a grid query).
pub(crate) fn tangential_smoothing(
    mesh: &mut TriMesh,
    input: &TriMesh,
    grid: &TriangleGrid,
    h: f64,
    iterations: usize,
) -> usize {
    let conn = mesh.connectivity().clone();
    let faces = mesh.faces().to_vec();
    let mut moves = 0;
    for _ in 0..iterations {
        let normals = geometry::vertex_normals(mesh, NormalWeighting::Area);
        let mut positions = mesh.positions().to_vec();
        let mut moved = false;
        for v in mesh.vertex_ids() {
            if conn.is_boundary_vertex(v) || conn.valence(v) < 3 {
                continue;
            }
            let p = positions[v.idx()];
            let n = normals[v.idx()];
            let (mut sum, mut count) = (DVec3::ZERO, 0.0);
            for u in conn.neighbors(v) {
                sum += positions[u.idx()];
                count += 1.0;
            }
            let step = sum / count - p;
            let target = p + DAMPING * (step - n * n.dot(step));
            let Some((q, f)) = grid.closest(target) else { continue };
            let n_in = geometry::triangle_normal(input.triangle(FaceId::new(f)));
            if q.distance(target) > 0.5 * h || n_in.dot(n) <= 0.0 {
                continue;
            }
            if fan_keeps_shape(&positions, &faces, &conn, v, q, n_in) {
                positions[v.idx()] = q;
                moves += 1;
                moved = true;
            }
        }
        // Finite by construction: closest points on finite triangles.
        if mesh.set_positions(positions).is_err() || !moved {
            break;
        }
    }
    moves
}

/// Whether moving `v` to `q` is no worse for its fan: no more faces turned
/// against the input's normal `n` at `q` than before (fewer is better
/// whatever the angles: it unfolds a fold), and otherwise a smallest angle
/// of at least `min(before, 20 degrees)`.
fn fan_keeps_shape(
    positions: &[DVec3],
    faces: &[[u32; 3]],
    conn: &mesh_kernel::Connectivity,
    v: VertexId,
    q: DVec3,
    n: DVec3,
) -> bool {
    let (mut before, mut after) = (f64::INFINITY, f64::INFINITY);
    let (mut folded_before, mut folded_after) = (0, 0);
    for f in conn.vertex_faces(v) {
        let t = faces[f.idx()];
        let old = t.map(|w| positions[w as usize]);
        let new = t.map(|w| if w == v.0 { q } else { positions[w as usize] });
        folded_before += usize::from(geometry::double_area_vector(old).dot(n) <= 0.0);
        folded_after += usize::from(geometry::double_area_vector(new).dot(n) <= 0.0);
        before = before.min(smallest_angle(old));
        after = after.min(smallest_angle(new));
    }
    folded_after < folded_before || (folded_after == folded_before && after >= before.min(20f64.to_radians()))
}

/// The smallest corner angle of a triangle, in radians (0 for a degenerate
/// one).
pub(crate) fn smallest_angle(t: [DVec3; 3]) -> f64 {
    geometry::triangle_angles(t).into_iter().fold(f64::INFINITY, f64::min)
}

#[cfg(test)]
mod tests {
    use super::*;
    use mesh_kernel::shapes;

    /// A flat grid with one interior vertex pushed sideways: smoothing
    /// brings it back toward the middle of its neighbours, on the plane.
    #[test]
    fn a_displaced_vertex_moves_back_on_the_plane() {
        let plane = shapes::grid(1.0, 1.0, 4, 4).unwrap();
        let grid = TriangleGrid::new(&plane).unwrap();
        let mut mesh = plane.clone();
        let v = mesh.positions().iter().position(|p| (p.x - 0.5).abs() < 1e-9 && (p.y - 0.5).abs() < 1e-9).unwrap();
        mesh.positions_mut()[v] += DVec3::new(0.08, 0.05, 0.0);
        let moved = tangential_smoothing(&mut mesh, &plane, &grid, 0.25, 10);
        assert!(moved > 0);
        let p = mesh.positions()[v];
        assert!(p.z.abs() < 1e-12, "{p}");
        assert!((p.x - 0.5).abs() < 0.02 && (p.y - 0.5).abs() < 0.02, "{p}");
        // Boundary vertices did not move.
        for (a, b) in mesh.positions().iter().zip(plane.positions()) {
            if a.x.abs() < 1e-12 || a.y.abs() < 1e-12 || (a.x - 1.0).abs() < 1e-12 || (a.y - 1.0).abs() < 1e-12 {
                assert_eq!(a, b);
            }
        }
    }

    /// On a sphere every kept vertex stays on the input surface.
    #[test]
    fn vertices_stay_on_the_input() {
        let sphere = shapes::icosphere(3).unwrap();
        let grid = TriangleGrid::new(&sphere).unwrap();
        let mut mesh = sphere.clone();
        for (i, p) in mesh.positions_mut().iter_mut().enumerate() {
            let t = DVec3::new((i as f64 * 0.7).sin(), (i as f64 * 1.3).cos(), 0.3).cross(*p) * 0.02;
            *p += t;
        }
        let before = mesh.positions().to_vec();
        let moved = tangential_smoothing(&mut mesh, &sphere, &grid, 0.15, 1);
        assert!(moved > 100, "{moved}");
        let mut on = 0;
        for (p, b) in mesh.positions().iter().zip(&before) {
            if p != b {
                assert!(grid.distance(*p) < 1e-12, "{}", grid.distance(*p));
                on += 1;
            }
        }
        assert_eq!(on, moved);
    }
}
