//! Subdivision surfaces by recursive 4-to-1 splitting (seed figure 2.13):
//! midpoint, Loop and modified butterfly.

use glam::DVec3;
use mesh_core::{shapes, MeshError, TriMesh};

use crate::error::Result;
use crate::filter::LevelFilter;
use crate::hierarchy::{check_size, split_faces};
use crate::scheme::{Scheme, WaveletKind};
use crate::topology::{manifold_topology, Topology};

/// Splits every triangle of `mesh` into four, `levels` times, placing the
/// vertices with `scheme`.
///
/// Output order (that of [`mesh_core::shapes::midpoint_subdivide`] at every
/// level): the old vertices first, in their order, then one new vertex per
/// [`mesh_core::Connectivity`] edge in edge order; the corner triangles of
/// face `f` at `4f`, `4f + 1`, `4f + 2`, the middle one at `4f + 3`. The
/// same numbering as [`crate::Hierarchy::from_base`] on the input faces.
///
/// The midpoint scheme accepts any mesh; Loop and butterfly need an oriented
/// manifold ([`MeshError::NonManifold`] otherwise). Isolated vertices are
/// kept where they are. Errors: [`MeshError::Empty`] without faces,
/// [`crate::WaveletError::InvalidOption`] beyond [`crate::hierarchy::MAX_FACES`].
/// Cost O(4^levels F), one connectivity build per level.
pub fn subdivide(mesh: &TriMesh, scheme: Scheme, levels: usize) -> Result<TriMesh> {
    if mesh.face_count() == 0 {
        return Err(MeshError::Empty.into());
    }
    check_size(mesh.face_count(), levels)?;
    let mut current = mesh.clone();
    for _ in 0..levels {
        current = split_once(&current, scheme)?;
    }
    Ok(current)
}

/// One level: the synthesis step of the lazy filter bank with zero wavelet
/// coefficients, on the lean topology (same numbering as
/// [`mesh_core::shapes::midpoint_subdivide`], which handles the midpoint
/// scheme on non-manifold meshes).
fn split_once(mesh: &TriMesh, scheme: Scheme) -> Result<TriMesh> {
    let topo = match Topology::new(mesh.vertex_count(), mesh.faces()) {
        Ok(t) => t,
        Err(_) if scheme == Scheme::Midpoint => {
            let (p, f) = shapes::midpoint_subdivide(mesh);
            return Ok(TriMesh::new(p, f)?);
        }
        Err(_) => manifold_topology(mesh.vertex_count(), mesh.faces())?,
    };
    let parents = topo.edges();
    let filter = LevelFilter::new(&topo, parents, scheme, WaveletKind::Lazy)?;
    let mut positions = Vec::with_capacity(mesh.vertex_count() + parents.len());
    positions.extend_from_slice(mesh.positions());
    positions.resize(mesh.vertex_count() + parents.len(), DVec3::ZERO);
    filter.synthesize(&mut positions)?;
    let faces = split_faces(&topo, mesh.faces(), mesh.vertex_count() as u32);
    Ok(TriMesh::new(positions, faces)?)
}
