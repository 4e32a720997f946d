//! mesh-kernel and mesh-io operations.

use std::path::Path;

use mesh_io::MeshData;
use mesh_kernel::geometry::{self, NormalWeighting};
use mesh_kernel::operators::{self, IntrinsicOptions, IntrinsicTriangulation, MassKind};
use mesh_kernel::TriMesh;

use super::Operation;

/// A copy of the mesh without its cached connectivity.
fn fresh(mesh: &TriMesh) -> TriMesh {
    // Positions and faces were validated when the mesh was built.
    TriMesh::new(mesh.positions().to_vec(), mesh.faces().to_vec()).expect("copy of a valid mesh")
}

/// The core operations, named as in peer_bench.py where they match.
pub fn operations<'a>(path: &'a Path, data: &'a MeshData) -> Vec<Operation<'a>> {
    let mesh = &data.mesh;
    vec![
        Operation::new("read", move || Ok(mesh_io::read(path)?)),
        Operation::new("connectivity", move || {
            let m = fresh(mesh);
            let _ = m.connectivity().is_manifold();
            Ok(m)
        }),
        Operation::new("boundary_loops", move || {
            let m = fresh(mesh);
            let n = m.connectivity().boundary_loops()?.len();
            Ok((m, n))
        }),
        Operation::new("normals_area", move || Ok(geometry::vertex_normals(mesh, NormalWeighting::Area))),
        Operation::new("cotan_laplacian", move || Ok(operators::cotan_laplacian(mesh))),
        Operation::new("mass_voronoi", move || Ok(operators::mass_matrix(mesh, MassKind::MixedVoronoi))),
        Operation::new("intrinsic_delaunay", move || {
            Ok(IntrinsicTriangulation::delaunay(mesh, &IntrinsicOptions::default())?.cotan_laplacian())
        }),
    ]
}
