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
    vec![
        Operation::new("gaussian_curvature", move || Ok(gaussian_curvature(mesh, &GaussianOptions::default())?)),
        Operation::new("mean_curvature", move || Ok(mean_curvature(mesh, &MeanOptions::default())?)),
        Operation::new("principal_curvature", move || Ok(curvature_tensor(mesh, &TensorOptions::default())?)),
        Operation::new("principal_curvature_rusinkiewicz", move || Ok(curvature_tensor(mesh, &rusinkiewicz)?)),
    ]
}
