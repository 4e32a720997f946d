//! Subdivision surfaces by recursive 4-to-1 splitting (the chapter's figure 2.13):
//! midpoint, Loop and modified butterfly.

use mesh_kernel::{par, shapes, MeshError, TriMesh};

use crate::error::Result;
use crate::hierarchy::{check_size, split_faces};
use crate::rules::{self, Scratch};
use crate::scheme::Scheme;
use crate::topology::manifold_topology;

/// Options of [`subdivide`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SubdivideOptions {
    /// How new vertices are placed (and old ones moved). Default: Loop.
    pub scheme: Scheme,
    /// How many times every triangle is split into four. Default: 1.
    pub levels: usize,
}

impl Default for SubdivideOptions {
    fn default() -> Self {
        Self { scheme: Scheme::Loop, levels: 1 }
    }
}

/// Splits every triangle of `mesh` into four, [`SubdivideOptions::levels`]
/// times, placing the vertices with [`SubdivideOptions::scheme`].
///
/// Output order (that of [`mesh_kernel::shapes::midpoint_subdivide`] at every
/// level): the old vertices first, in their order, then one new vertex per
/// [`mesh_kernel::Connectivity`] edge in edge order; the corner triangles of
/// face `f` at `4f`, `4f + 1`, `4f + 2`, the middle one at `4f + 3`. The
/// same numbering as [`crate::Hierarchy::from_base`] on the input faces.
///
/// The midpoint scheme accepts any mesh; Loop and butterfly need an oriented
/// manifold ([`MeshError::NonManifold`] otherwise). Isolated vertices are
/// kept where they are. Errors: [`MeshError::Empty`] without faces,
/// [`crate::WaveletError::InvalidOption`] beyond [`crate::hierarchy::MAX_FACES`].
/// Cost O(4^levels F), one connectivity build per level.
///
/// # Errors
/// `MeshError::Empty` without faces; `WaveletError::InvalidOption` (`levels`) when the result would exceed
/// `MAX_FACES`; `MeshError::NonManifold` for Loop and butterfly on a mesh that is not an oriented manifold.
pub fn subdivide(mesh: &TriMesh, options: &SubdivideOptions) -> Result<TriMesh> {
    let SubdivideOptions { scheme, levels } = *options;
    if mesh.face_count() == 0 {
        return Err(MeshError::Empty.into());
    }
    check_size(mesh.face_count(), levels)?;
    if levels == 0 {
        return Ok(mesh.clone());
    }
    let mut current = split_once(mesh, scheme)?;
    for _ in 1..levels {
        current = split_once(&current, scheme)?;
    }
    Ok(current)
}

/// One level: the midpoint scheme by
/// [`mesh_kernel::shapes::midpoint_subdivide`] (it needs only the edge
/// numbering, on any mesh), Loop and butterfly on the lean topology (same
/// numbering). The masks are those of the filter banks'
/// predict steps, applied directly; with zero coefficients the synthesis
/// step gives the same positions (tested through the matrix P).
fn split_once(mesh: &TriMesh, scheme: Scheme) -> Result<TriMesh> {
    if scheme == Scheme::Midpoint {
        // Only the edge numbering is needed, on any mesh.
        let (p, f) = shapes::midpoint_subdivide(mesh);
        return Ok(TriMesh::new(p, f)?);
    }
    let topo = manifold_topology(mesh.vertex_count(), mesh.faces())?;
    let (n, p) = (mesh.vertex_count(), mesh.positions());
    // The old vertices, then one new vertex per edge; each position
    // depends on its index only (in parallel through `par`).
    let scratch = || (Scratch::default(), Vec::with_capacity(16), Vec::with_capacity(2));
    let positions = par::map_with(n + topo.edge_count(), scratch, |(scratch, row, opposite), i| {
        if i < n {
            return match scheme {
                Scheme::Loop => rules::loop_even(&topo, p, i as u32),
                _ => p[i],
            };
        }
        let e = (i - n) as u32;
        let [a, b] = topo.edges()[e as usize];
        let (pa, pb) = (p[a as usize], p[b as usize]);
        match scheme {
            // Not reached (the midpoint scheme returned above); its rule, so
            // that the match names every scheme without a panic.
            Scheme::Midpoint => (pa + pb) * 0.5,
            Scheme::Loop => {
                // The mask of rules::odd_mask, inlined.
                topo.edge_opposites(e, opposite);
                match opposite[..] {
                    [c, d] => (pa + pb) * 0.375 + (p[c as usize] + p[d as usize]) * 0.125,
                    _ => (pa + pb) * 0.5,
                }
            }
            Scheme::Butterfly => {
                topo.edge_opposites(e, opposite);
                row.clear();
                rules::odd_mask(&topo, scheme, a, b, opposite, scratch, row);
                row.iter().map(|&(v, w)| p[v as usize] * w).sum()
            }
        }
    });
    let faces = split_faces(&topo, mesh.faces(), n as u32);
    Ok(TriMesh::new(positions, faces)?)
}
