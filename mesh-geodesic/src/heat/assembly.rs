//! Assembly of the heat method's matrices (Crane, Weischedel and Wardetzky
//! 2013): the shifted heat operator, identity rows for Dirichlet and
//! pinned vertices, and the pieces of the Laplacian that need one pinned
//! vertex each.

use mesh_kernel::sprs::CsMat;
use mesh_kernel::{TriMesh, VertexId};

use super::face::FaceGradient;

/// The largest heat value that leaves room for the triangular solves:
/// 2^1000 over the largest diagonal entry of the Cholesky factor (at most
/// the square root of the largest diagonal entry of `a`), which bounds the
/// forward solve's intermediate values.
pub(crate) fn heat_ceiling(a: &CsMat<f64>) -> f64 {
    let diagonal = a.diag().data().iter().fold(1.0f64, |m, x| m.max(*x));
    2f64.powi(1000) / diagonal.sqrt()
}

/// `true` when the intrinsic half-edge lengths are the mesh's own (no
/// mollification happened).
pub(crate) fn unchanged_lengths(mesh: &TriMesh, lengths: &[f64]) -> bool {
    let p = mesh.positions();
    mesh.faces().iter().zip(lengths.chunks_exact(3)).all(|(f, l)| {
        (0..3).all(|k| mesh_kernel::geometry::norm(p[f[(k + 1) % 3] as usize] - p[f[k] as usize]) == l[k])
    })
}

/// `diag(mass) + t L` with 1 on the diagonal of isolated vertices. Same
/// pattern as `L`, whose diagonal entries are all stored.
pub(crate) fn shifted(laplacian: &CsMat<f64>, t: f64, mass: &[f64], isolated: &[bool]) -> CsMat<f64> {
    let mut a = laplacian.clone();
    let indptr = a.indptr().to_proper().into_owned();
    let indices = a.indices().to_vec();
    let data = a.data_mut();
    for row in 0..mass.len() {
        for k in indptr[row]..indptr[row + 1] {
            let value = t * data[k];
            data[k] = if indices[k] == row {
                if isolated[row] {
                    1.0
                } else {
                    value + mass[row]
                }
            } else {
                value
            };
        }
    }
    a
}

/// `a` with the rows and columns of `mask` replaced by the identity, the
/// removed entries kept as explicit zeros (same pattern).
pub(crate) fn with_identity_rows(a: &CsMat<f64>, mask: &[bool]) -> CsMat<f64> {
    let mut out = a.clone();
    let indptr = out.indptr().to_proper().into_owned();
    let indices = out.indices().to_vec();
    let data = out.data_mut();
    for row in 0..mask.len() {
        for k in indptr[row]..indptr[row + 1] {
            let col = indices[k];
            if mask[row] || mask[col] {
                data[k] = if row == col { 1.0 } else { 0.0 };
            }
        }
    }
    out
}

/// Pins one vertex per connected piece of the triangles that carry a
/// gradient (the null space of the Laplacian is one constant per piece).
/// Returns the pinned vertices and the number of pieces.
pub(crate) fn pin_pieces(n: usize, faces: &[FaceGradient]) -> (Vec<u32>, usize) {
    let labels = piece_labels(n, faces);
    let mut seen = vec![false; n];
    let mut pinned = Vec::new();
    for v in 0..n {
        let root = labels[v];
        if root != u32::MAX && !seen[root as usize] {
            seen[root as usize] = true;
            pinned.push(v as u32);
        }
    }
    let pieces = pinned.len();
    (pinned, pieces)
}

/// Union-find root of each vertex over the faces with a gradient;
/// `u32::MAX` for vertices in none.
fn piece_labels(n: usize, faces: &[FaceGradient]) -> Vec<u32> {
    let mut parent: Vec<u32> = (0..n as u32).collect();
    let mut used = vec![false; n];
    fn find(parent: &mut [u32], mut i: u32) -> u32 {
        while parent[i as usize] != i {
            let p = parent[parent[i as usize] as usize];
            parent[i as usize] = p;
            i = p;
        }
        i
    }
    for f in faces.iter().filter(|f| f.w.is_some()) {
        let [a, b, c] = f.vertices;
        for v in [a, b, c] {
            used[v as usize] = true;
        }
        for (x, y) in [(a, b), (a, c)] {
            let (rx, ry) = (find(&mut parent, x), find(&mut parent, y));
            if rx != ry {
                parent[rx.max(ry) as usize] = rx.min(ry);
            }
        }
    }
    (0..n as u32).map(|v| if used[v as usize] { find(&mut parent, v) } else { u32::MAX }).collect()
}

/// A vertex whose Laplacian piece differs from its component's (for the
/// error message).
pub(crate) fn first_split_vertex(faces: &[FaceGradient], n: usize, component: &[u32]) -> VertexId {
    let labels = piece_labels(n, faces);
    let mut piece_of_component: Vec<u32> = vec![u32::MAX; n];
    for v in 0..n {
        let c = component[v];
        if c == u32::MAX {
            continue;
        }
        if labels[v] == u32::MAX {
            return VertexId::new(v);
        }
        let slot = &mut piece_of_component[c as usize];
        if *slot == u32::MAX {
            *slot = labels[v];
        } else if *slot != labels[v] {
            return VertexId::new(v);
        }
    }
    VertexId::INVALID
}
