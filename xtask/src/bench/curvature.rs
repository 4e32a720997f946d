//! mesh-curvature operations, named as in peer_bench.py where they match
//! (`gaussian_curvature`, `principal_curvature`).

use std::path::Path;

use mesh_curvature::{
    curvature_tensor, gaussian_curvature, mean_curvature, GaussianOptions, MeanOptions, TensorMethod, TensorOptions,
};
use mesh_io::MeshData;

use super::Operation;

/// The curvature operations on the (connectivity-cached) mesh.
pub fn operations<'a>(_path: &'a Path, data: &'a MeshData) -> Vec<Operation<'a>> {
    let mesh = &data.mesh;
    let _ = mesh.connectivity();
    let rusinkiewicz = TensorOptions { method: TensorMethod::Rusinkiewicz, ..Default::default() };
    // Every run starts without the derived quantities a previous run left in
    // the mesh's cache (angles, masses, Laplacian), as a peer computes them.
    let (mut gauss_mesh, mut mean_mesh) = (mesh.clone(), mesh.clone());
    // Integrated, geodesic and pointwise curvature, area (8 bytes each) and status.
    let gauss_bytes = super::core::face_pass_bytes(mesh, 33);
    vec![
        Operation::new("gaussian_curvature", move || {
            gauss_mesh.forget_geometry();
            Ok(gaussian_curvature(&gauss_mesh, &GaussianOptions::default())?)
        })
        .moving(gauss_bytes),
        Operation::new("mean_curvature", move || {
            mean_mesh.forget_geometry();
            Ok(mean_curvature(&mean_mesh, &MeanOptions::default())?)
        }),
        Operation::new("principal_curvature", move || Ok(curvature_tensor(mesh, &TensorOptions::default())?)),
        Operation::new("principal_curvature_rusinkiewicz", move || Ok(curvature_tensor(mesh, &rusinkiewicz)?)),
    ]
}
