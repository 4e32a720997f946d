//! Per-face second fundamental form fitted to normal differences, averaged
//! to the vertices (Rusinkiewicz 2004, "Estimating curvatures and their
//! derivatives on triangle meshes").

use glam::DVec3;
use mesh_kernel::TriMesh;

use crate::frame::{rotate_between, solve_spd, Sym2};
use crate::status::{topological_status, VertexStatus};
use crate::tensor::LocalTensor;
use mesh_kernel::geometry::NormalWeighting;
use mesh_kernel::operators::mixed_voronoi_corners;
use mesh_kernel::par;

/// The tensor of one face in its own frame, and the weight of each corner.
#[derive(Debug, Clone, Copy)]
struct FaceTensor {
    normal: DVec3,
    u: DVec3,
    v: DVec3,
    form: Sym2,
    corner_weight: [f64; 3],
}

/// Least-squares fit of the shape operator of a face: along each edge `e`
/// (from corner `i` to corner `j`), `S e = n_j - n_i` in the face's tangent
/// frame (eq. 2.27-2.28 discretized: the directional derivative of the normal
/// is the tensor applied to the direction). `None` for zero-area faces.
fn face_tensor(p: [DVec3; 3], n: [DVec3; 3]) -> Option<FaceTensor> {
    let cross = (p[1] - p[0]).cross(p[2] - p[0]);
    let normal = cross.normalize_or_zero();
    let u = (p[1] - p[0]).normalize_or_zero();
    if normal == DVec3::ZERO || u == DVec3::ZERO {
        return None;
    }
    let v = normal.cross(u);
    let mut m = [[0.0; 3]; 3];
    let mut rhs = [0.0; 3];
    for k in 0..3 {
        let (i, j) = (k, (k + 1) % 3);
        let e = p[j] - p[i];
        let dn = n[j] - n[i];
        let (eu, ev) = (e.dot(u), e.dot(v));
        let (du, dv) = (dn.dot(u), dn.dot(v));
        // Rows [eu, ev, 0] . (a, b, c) = du and [0, eu, ev] . (a, b, c) = dv.
        m[0][0] += eu * eu;
        m[0][1] += eu * ev;
        m[1][1] += ev * ev + eu * eu;
        m[1][2] += eu * ev;
        m[2][2] += ev * ev;
        rhs[0] += eu * du;
        rhs[1] += ev * du + eu * dv;
        rhs[2] += ev * dv;
    }
    m[1][0] = m[0][1];
    m[2][1] = m[1][2];
    solve_spd(&m, &mut rhs, 1e-12, 0)?;
    let form = Sym2::new(rhs[0], rhs[1], rhs[2]);
    Some(FaceTensor { normal, u, v, form, corner_weight: mixed_voronoi_corners(p) })
}

/// The face tensor expressed in the vertex frame `(t1, t2)` of normal `n`:
/// the frame is rotated onto the face plane, then the form evaluated on it.
fn to_vertex_frame(face: &FaceTensor, n: DVec3, t1: DVec3) -> Sym2 {
    // A rotation maps t2 = n x t1 to n_f x R t1: one rotation suffices.
    let r1 = rotate_between(n, face.normal, t1);
    let r2 = face.normal.cross(r1);
    let x = [r1.dot(face.u), r1.dot(face.v)];
    let y = [r2.dot(face.u), r2.dot(face.v)];
    Sym2::new(face.form.form(x, x), face.form.form(x, y), face.form.form(y, y))
}

/// Rusinkiewicz's estimator: per-face tensors, then a mixed-Voronoi weighted
/// average at each vertex over its incident faces. O(V + F), parallel.
pub(crate) fn estimate(mesh: &TriMesh, normals: NormalWeighting) -> Vec<LocalTensor> {
    let nv = mesh.geometry().vertex_normals(normals);
    let p = mesh.positions();
    let faces = mesh.faces();
    let per_face: Vec<Option<FaceTensor>> = par::map(faces.len(), |f| {
        let [a, b, c] = faces[f].map(|v| v as usize);
        face_tensor([p[a], p[b], p[c]], [nv[a], nv[b], nv[c]])
    });
    let conn = mesh.connectivity();
    let status = topological_status(mesh);
    par::map(mesh.vertex_count(), |i| {
        let n = nv[i];
        if status[i] == VertexStatus::Isolated || n == DVec3::ZERO {
            let s = if status[i] == VertexStatus::Isolated { status[i] } else { VertexStatus::Degenerate };
            return LocalTensor::empty(n, s);
        }
        let mut local = LocalTensor::new(n, Sym2::default(), status[i]);
        let (mut sum, mut weight) = (Sym2::default(), 0.0);
        for h in conn.outgoing(mesh_kernel::VertexId::new(i)) {
            if let Some(face) = &per_face[h.face().idx()] {
                let w = face.corner_weight[h.corner()];
                sum = sum.add(to_vertex_frame(face, n, local.t1).scaled(w));
                weight += w;
            }
        }
        if weight > 0.0 {
            local.form = sum.scaled(1.0 / weight);
        } else {
            local.status = VertexStatus::Degenerate;
        }
        local
    })
}
