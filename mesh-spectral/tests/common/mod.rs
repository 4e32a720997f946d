//! Helpers shared by the integration tests.
#![allow(dead_code)]

use mesh_kernel::operators::{self, MassKind};
use mesh_kernel::TriMesh;
use mesh_spectral::Eigenpairs;
use sprs::CsMat;

/// Cotangent Laplacian and mixed Voronoi lumped masses.
pub fn pencil(mesh: &TriMesh) -> (CsMat<f64>, Vec<f64>) {
    (operators::cotan_laplacian(mesh), masses(mesh))
}

/// Lumped mixed Voronoi masses.
pub fn masses(mesh: &TriMesh) -> Vec<f64> {
    operators::lumped_mass(mesh, MassKind::MixedVoronoi)
}

/// Largest entry of `|X^T M X - I|`.
pub fn orthonormality_error(pairs: &Eigenpairs, mass: &[f64]) -> f64 {
    let k = pairs.len();
    let mut worst: f64 = 0.0;
    for i in 0..k {
        for j in 0..=i {
            let dot: f64 = pairs.vector(i).iter().zip(pairs.vector(j)).zip(mass).map(|((a, b), m)| a * b * m).sum();
            let want = if i == j { 1.0 } else { 0.0 };
            worst = worst.max((dot - want).abs());
        }
    }
    worst
}

/// Sizes of runs of values closer than `rel` (relative to the value + 1).
pub fn clusters(values: &[f64], rel: f64) -> Vec<usize> {
    let mut out = vec![1];
    for w in values.windows(2) {
        if (w[1] - w[0]).abs() <= rel * (w[1].abs() + 1.0) {
            *out.last_mut().unwrap() += 1;
        } else {
            out.push(1);
        }
    }
    out
}

/// A shared real mesh, `None` when the data is absent (see `mesh_testkit::data`).
pub fn data_mesh(name: &str) -> Option<TriMesh> {
    let path = mesh_testkit::shared_file(name)?;
    Some(mesh_io::read(&path).expect("shared test mesh reads").mesh)
}

/// Two meshes side by side as one (the second's indices shifted).
pub fn union(a: &TriMesh, b: &TriMesh) -> TriMesh {
    let mut p = a.positions().to_vec();
    p.extend_from_slice(b.positions());
    let off = a.vertex_count() as u32;
    let mut f = a.faces().to_vec();
    f.extend(b.faces().iter().map(|t| t.map(|v| v + off)));
    TriMesh::new(p, f).unwrap()
}
