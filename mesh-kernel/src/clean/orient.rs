//! Consistent, outward orientation of the faces of each component.

use crate::ids::{FaceId, HalfedgeId};
use crate::mesh::TriMesh;

/// Decides which faces to flip so that every edge with two faces is
/// traversed in opposite directions by them, and closed patches enclose a
/// positive volume. A patch is a set of faces joined across two-face edges
/// (edges with three or more faces separate patches; see
/// [`super::CleanOptions::manifold`] to resolve them). Returns the flip flags
/// and the number of connected components holding a patch that admits no
/// consistent orientation (Moebius-like; such patches are left untouched).
/// Breadth-first over faces, O(F). The volume does not depend on where the
/// mesh lies or on its unit of length (cones from one of its vertices,
/// [`crate::geometry::cone_volume6`], in a power of two near its size).
pub fn orient_faces(mesh: &TriMesh) -> (Vec<bool>, usize) {
    let conn = mesh.connectivity();
    let nf = mesh.face_count();
    let mut flip = vec![false; nf];
    let mut seen = vec![false; nf];
    let mut unorientable = vec![false; conn.components().count];
    let mut queue = Vec::new();
    let mut component = Vec::new();
    for seed in 0..nf {
        if seen[seed] {
            continue;
        }
        seen[seed] = true;
        queue.clear();
        component.clear();
        queue.push(seed);
        let mut ok = true;
        let mut closed = true;
        while let Some(f) = queue.pop() {
            component.push(f);
            for k in 0..3 {
                let h = HalfedgeId::of_corner(FaceId::new(f), k);
                let e = conn.edge(h);
                let hs = conn.edge_halfedges(e);
                if hs.len() != 2 {
                    closed = false;
                    continue;
                }
                let g = if hs[0] == h { hs[1] } else { hs[0] };
                let nb = g.face().idx();
                // Same direction in the input means the faces disagree.
                let same_dir = conn.origin(g) == conn.origin(h);
                let want = flip[f] ^ same_dir;
                if seen[nb] {
                    if flip[nb] != want {
                        ok = false;
                    }
                } else {
                    seen[nb] = true;
                    flip[nb] = want;
                    queue.push(nb);
                }
            }
        }
        if !ok {
            unorientable[conn.components().face_component[seed] as usize] = true;
            for &f in &component {
                flip[f] = false;
            }
            continue;
        }
        // Closed patches enclose a positive volume.
        if closed && signed_volume(mesh, &component, &flip) < 0.0 {
            for &f in &component {
                flip[f] = !flip[f];
            }
        }
    }
    (flip, unorientable.iter().filter(|&&u| u).count())
}

/// The sign-bearing volume of a closed `component` with the faces `flip`
/// marks reversed (divergence theorem): cones from one of its vertices, in
/// a power of two near its size ([`crate::geometry::cone_volume6`]), so
/// that neither a distant origin (a scan in survey coordinates, whose
/// terms about the origin cancel) nor an extreme unit (cubes of `1e150`
/// overflow) changes its sign. O(faces of the component).
fn signed_volume(mesh: &TriMesh, component: &[usize], flip: &[bool]) -> f64 {
    let (p, faces) = (mesh.positions(), mesh.faces());
    let Some(&first) = component.first() else { return 0.0 };
    let apex = p[faces[first][0] as usize];
    let size = component
        .iter()
        .flat_map(|&f| faces[f])
        .fold(0.0_f64, |m, v| m.max((p[v as usize] - apex).abs().max_element()));
    if !(size > 0.0 && size.is_finite()) {
        return 0.0;
    }
    let unit = crate::geometry::power_of_two_near(size);
    component
        .iter()
        .map(|&f| {
            let v = crate::geometry::cone_volume6(faces[f].map(|v| p[v as usize]), apex, unit);
            if flip[f] {
                -v
            } else {
                v
            }
        })
        .sum()
}
