//! Test helpers: the shared real meshes (read with the test kit's minimal
//! OFF / OBJ reader, so these tests do not depend on another crate's state)
//! and ground truth on analytic shapes.
#![allow(dead_code)]

use mesh_kernel::glam::DVec3;
use mesh_kernel::{TriMesh, VertexId};

/// Every shared mesh by file name, read with the test kit's minimal reader;
/// empty when the data is absent (see `mesh_testkit::data`).
pub fn data_meshes() -> Vec<(String, TriMesh)> {
    mesh_testkit::shared_meshes().into_iter().map(|(name, raw)| (name.to_string(), tri_mesh(raw))).collect()
}

/// The validated mesh of raw arrays.
pub fn tri_mesh(raw: mesh_testkit::RawMesh) -> TriMesh {
    TriMesh::new(raw.positions.into_iter().map(DVec3::from).collect(), raw.faces).unwrap()
}

/// Two meshes side by side as one (the second's indices shifted), plus
/// `isolated` unreferenced vertices at the end.
pub fn union(a: &TriMesh, b: &TriMesh, isolated: usize) -> TriMesh {
    let mut positions = a.positions().to_vec();
    positions.extend(b.positions().iter().map(|p| *p + DVec3::new(10.0, 0.0, 0.0)));
    let shift = a.vertex_count() as u32;
    let mut faces = a.faces().to_vec();
    faces.extend(b.faces().iter().map(|f| f.map(|v| v + shift)));
    positions.extend((0..isolated).map(|i| DVec3::new(-5.0, i as f64, 0.0)));
    TriMesh::new(positions, faces).unwrap()
}

/// Great-circle distance on the unit sphere from vertex `source`.
pub fn sphere_truth(mesh: &TriMesh, source: VertexId) -> Vec<f64> {
    let p0 = mesh.position(source).normalize();
    mesh.positions().iter().map(|p| p.normalize().dot(p0).clamp(-1.0, 1.0).acos()).collect()
}

/// Largest and mean absolute difference.
pub fn errors(d: &[f64], truth: &[f64]) -> (f64, f64) {
    let (mut max, mut sum) = (0.0f64, 0.0);
    for (a, b) in d.iter().zip(truth) {
        let e = (a - b).abs();
        max = max.max(e);
        sum += e;
    }
    (max, sum / d.len() as f64)
}

/// Convergence order between two refinements of ratio 2 in mesh size.
pub fn order(coarse: f64, fine: f64) -> f64 {
    (coarse / fine).log2()
}
