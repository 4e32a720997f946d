//! Pieces of a mesh as meshes of their own: any subset of faces, one
//! connected component, the largest component. Each [`SubMesh`] remembers
//! where its vertices and faces came from, so per-vertex results computed on
//! the piece can be scattered back onto the whole mesh.
//!
//! Scans arrive in many components (the full-resolution Stanford dragon has
//! 151); spectral analysis, parameterization and the like are usually wanted
//! on the main piece, or piece by piece.

use crate::connectivity::Components;
use crate::error::{MeshError, Result};
use crate::ids::{FaceId, VertexId};
use crate::mesh::TriMesh;

/// A mesh cut out of a parent mesh, with the maps back to the parent.
#[derive(Debug, Clone)]
pub struct SubMesh {
    /// The piece, with its vertices renumbered in order of first use by its faces.
    pub mesh: TriMesh,
    /// The parent vertex of each vertex of the piece.
    pub vertices: Vec<VertexId>,
    /// The parent face of each face of the piece.
    pub faces: Vec<FaceId>,
}

impl SubMesh {
    /// Spreads per-vertex values of the piece onto the parent's vertices,
    /// writing `fill` wherever the piece has no vertex. `values` must have
    /// one entry per vertex of the piece. Cost O(V_parent).
    ///
    /// # Errors
    /// [`MeshError::Dimension`] when `values` has not one entry per vertex of the piece, or the
    /// parent is smaller than the piece's largest vertex.
    pub fn scatter<T: Clone>(&self, values: &[T], parent_vertex_count: usize, fill: T) -> Result<Vec<T>> {
        if values.len() != self.vertices.len() {
            return Err(MeshError::Dimension(format!(
                "{} values for a piece of {} vertices",
                values.len(),
                self.vertices.len()
            )));
        }
        if self.vertices.iter().any(|v| v.idx() >= parent_vertex_count) {
            return Err(MeshError::Dimension(format!("the parent has only {parent_vertex_count} vertices")));
        }
        let mut out = vec![fill; parent_vertex_count];
        for (v, x) in self.vertices.iter().zip(values) {
            out[v.idx()] = x.clone();
        }
        Ok(out)
    }
}

impl Components {
    /// Number of faces in each component. Cost O(F).
    pub fn face_counts(&self) -> Vec<usize> {
        let mut counts = vec![0usize; self.count];
        for &c in &self.face_component {
            counts[c as usize] += 1;
        }
        counts
    }

    /// The component with the most faces (the lowest index among equals), or
    /// `None` when the mesh has no faces.
    pub fn largest(&self) -> Option<usize> {
        let counts = self.face_counts();
        (0..counts.len()).max_by_key(|&c| (counts[c], std::cmp::Reverse(c)))
    }
}

impl TriMesh {
    /// The faces `faces` (in the given order) and the vertices they use, as a
    /// mesh of their own. Errors on a face index out of range or a repeated
    /// face. Cost O(V + F).
    ///
    /// # Errors
    /// [`MeshError::InvalidOption`] for a face index out of range.
    pub fn submesh(&self, faces: &[FaceId]) -> Result<SubMesh> {
        let mut new_index = vec![u32::MAX; self.vertex_count()];
        let mut seen = vec![false; self.face_count()];
        let mut vertices = Vec::new();
        let mut tris = Vec::with_capacity(faces.len());
        for &f in faces {
            if f.idx() >= self.face_count() {
                return Err(MeshError::InvalidOption {
                    name: "faces",
                    reason: format!("face {f} does not exist (the mesh has {} faces)", self.face_count()),
                });
            }
            if std::mem::replace(&mut seen[f.idx()], true) {
                return Err(MeshError::InvalidOption { name: "faces", reason: format!("face {f} is listed twice") });
            }
            let tri = self.faces()[f.idx()].map(|v| {
                let slot = &mut new_index[v as usize];
                if *slot == u32::MAX {
                    *slot = vertices.len() as u32;
                    vertices.push(VertexId(v));
                }
                *slot
            });
            tris.push(tri);
        }
        let positions = vertices.iter().map(|&v| self.position(v)).collect();
        Ok(SubMesh { mesh: TriMesh::new(positions, tris)?, vertices, faces: faces.to_vec() })
    }

    /// Connected component `component` (numbered as in
    /// [`crate::Connectivity::components`]) as a mesh of its own. Cost O(V + F).
    ///
    /// # Errors
    /// [`MeshError::InvalidOption`] for a component index past the count.
    pub fn component(&self, component: usize) -> Result<SubMesh> {
        let components = self.connectivity().components();
        if component >= components.count {
            return Err(MeshError::InvalidOption {
                name: "component",
                reason: format!("the mesh has {} component(s), not {}", components.count, component + 1),
            });
        }
        let faces: Vec<FaceId> = (0..self.face_count())
            .filter(|&f| components.face_component[f] as usize == component)
            .map(FaceId::new)
            .collect();
        self.submesh(&faces)
    }

    /// The connected component with the most faces ([`Components::largest`])
    /// as a mesh of its own. Errors on a mesh without faces. Cost O(V + F).
    ///
    /// # Errors
    /// [`MeshError::Empty`] for a mesh without faces.
    pub fn largest_component(&self) -> Result<SubMesh> {
        let largest = self.connectivity().components().largest().ok_or(MeshError::Empty)?;
        self.component(largest)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    /// Two triangles sharing an edge, a lone triangle, an unreferenced vertex.
    fn pieces() -> TriMesh {
        let p = |x: f64, y: f64| DVec3::new(x, y, 0.0);
        let positions = vec![
            p(0.0, 0.0),
            p(1.0, 0.0),
            p(0.0, 1.0),
            p(1.0, 1.0),
            p(5.0, 5.0),
            p(6.0, 5.0),
            p(5.0, 6.0),
            p(9.0, 9.0),
        ];
        TriMesh::new(positions, vec![[4, 5, 6], [0, 1, 2], [1, 3, 2]]).unwrap()
    }

    #[test]
    fn largest_component_and_maps() {
        let mesh = pieces();
        let c = mesh.connectivity().components();
        assert_eq!(c.count, 2);
        assert_eq!(c.face_counts().iter().sum::<usize>(), 3);
        let big = mesh.largest_component().unwrap();
        assert_eq!((big.mesh.vertex_count(), big.mesh.face_count()), (4, 2));
        assert_eq!(big.faces, vec![FaceId(1), FaceId(2)]);
        for (i, &v) in big.vertices.iter().enumerate() {
            assert_eq!(big.mesh.position(VertexId::new(i)), mesh.position(v));
        }
        for (f, &pf) in big.faces.iter().enumerate() {
            let here = big.mesh.faces()[f].map(|v| big.vertices[v as usize].0);
            assert_eq!(here, mesh.faces()[pf.idx()]);
        }
        let back = big.scatter(&[1.0, 2.0, 3.0, 4.0], mesh.vertex_count(), f64::NAN).unwrap();
        assert_eq!(back[0..4], [1.0, 2.0, 3.0, 4.0]);
        assert!(back[4..].iter().all(|x| x.is_nan()));
        assert!(big.scatter(&[1.0], mesh.vertex_count(), 0.0).is_err());
    }

    #[test]
    fn bad_selections_are_errors() {
        let mesh = pieces();
        assert!(mesh.submesh(&[FaceId(7)]).is_err());
        assert!(mesh.submesh(&[FaceId(1), FaceId(1)]).is_err());
        assert!(mesh.component(2).is_err());
        let empty = TriMesh::new(vec![DVec3::ZERO], vec![]).unwrap();
        assert!(matches!(empty.largest_component(), Err(MeshError::Empty)));
        assert_eq!(mesh.submesh(&[]).unwrap().mesh.vertex_count(), 0);
    }
}
