//! The normal-cycle curvature tensor of Cohen-Steiner and Morvan 2003
//! ("Restricted Delaunay triangulations and normal cycle"), averaged over a
//! neighbourhood.
//!
//! Each edge `e` carries the tensor `beta(e) |e| e_hat e_hat^T` with `beta`
//! its signed dihedral angle. Summed over a region `B` (here the union of the
//! mixed Voronoi cells of the neighbourhood's vertices, which holds half of
//! every edge at each of its vertices) and divided by the area of `B`, it
//! approximates the averaged shape operator rotated by a quarter turn in the
//! tangent plane: an edge along the axis of a cylinder carries the bending
//! around it.

use glam::DVec3;
use mesh_kernel::geometry::dihedral_angles;
use mesh_kernel::TriMesh;

use crate::frame::Sym2;
use crate::neighborhood::{Adjacency, Gatherer, Neighborhood};
use crate::status::{topological_status, VertexStatus};
use crate::tensor::LocalTensor;
use mesh_kernel::geometry::NormalWeighting;
use mesh_kernel::operators::MassKind;
use mesh_kernel::par;

/// A symmetric 3x3 matrix stored as (xx, yy, zz, xy, xz, yz).
type Sym3 = [f64; 6];

#[inline]
fn add_outer(t: &mut Sym3, w: f64, e: DVec3) {
    t[0] += w * e.x * e.x;
    t[1] += w * e.y * e.y;
    t[2] += w * e.z * e.z;
    t[3] += w * e.x * e.y;
    t[4] += w * e.x * e.z;
    t[5] += w * e.y * e.z;
}

#[inline]
fn bilinear(t: &Sym3, a: DVec3, b: DVec3) -> f64 {
    t[0] * a.x * b.x
        + t[1] * a.y * b.y
        + t[2] * a.z * b.z
        + t[3] * (a.x * b.y + a.y * b.x)
        + t[4] * (a.x * b.z + a.z * b.x)
        + t[5] * (a.y * b.z + a.z * b.y)
}

/// Per-vertex edge tensors: half of each incident edge's
/// `beta |e| e_hat e_hat^T`. O(E).
fn vertex_edge_tensors(mesh: &TriMesh) -> Vec<Sym3> {
    let beta = dihedral_angles(mesh);
    let p = mesh.positions();
    let mut t = vec![[0.0; 6]; mesh.vertex_count()];
    for (e, [a, b]) in mesh.connectivity().edges().iter().enumerate() {
        let d = p[b.idx()] - p[a.idx()];
        let len = d.length();
        if len.is_nan() || len <= 0.0 || beta[e] == 0.0 {
            continue;
        }
        // beta |e| e_hat e_hat^T = (beta / |e|) d d^T, half to each end.
        let w = 0.5 * beta[e] / len;
        add_outer(&mut t[a.idx()], w, d);
        add_outer(&mut t[b.idx()], w, d);
    }
    t
}

/// The normal-cycle estimator over `nbh`. O(sum of neighbourhood sizes).
pub(crate) fn estimate(mesh: &TriMesh, normals: NormalWeighting, nbh: Neighborhood) -> Vec<LocalTensor> {
    let nv = mesh.geometry().vertex_normals(normals);
    let tensors = vertex_edge_tensors(mesh);
    let area = mesh.geometry().lumped_mass(MassKind::MixedVoronoi);
    let adj = Adjacency::new(mesh);
    let status = topological_status(mesh);
    let p = mesh.positions();
    par::map_with(mesh.vertex_count(), Gatherer::default, |g, i| {
        let n = nv[i];
        if status[i] == VertexStatus::Isolated || n == DVec3::ZERO {
            let s = if status[i] == VertexStatus::Isolated { status[i] } else { VertexStatus::Degenerate };
            return LocalTensor::empty(n, s);
        }
        g.gather(&adj, p, i, nbh);
        let mut t = [0.0; 6];
        let mut a = 0.0;
        for &u in &g.vertices {
            let u = u as usize;
            for k in 0..6 {
                t[k] += tensors[u][k];
            }
            a += area[u];
        }
        let mut local = LocalTensor::new(n, Sym2::default(), status[i]);
        if a.is_nan() || a <= 0.0 {
            local.status = VertexStatus::Degenerate;
            return local;
        }
        // Quarter turn: the curvature along t1 is the edge tensor along n x t1 = t2.
        let (tt1, tt12, tt2) =
            (bilinear(&t, local.t1, local.t1), bilinear(&t, local.t1, local.t2), bilinear(&t, local.t2, local.t2));
        local.form = Sym2::new(tt2, -tt12, tt1).scaled(1.0 / a);
        local
    })
}
