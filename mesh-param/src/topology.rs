//! Topology checks: parameterization by a fixed or free boundary needs a
//! topological disk (one connected component, one boundary loop, Euler
//! characteristic chi = 1, eq. 2.6-2.7).

use mesh_kernel::{BoundaryLoop, TriMesh};

use crate::error::{ParamError, Result};

/// What a manifold mesh is, topologically (eq. 2.7: chi = 2 (c - g) - b).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Topology {
    /// Connected components (unreferenced vertices are not counted).
    pub components: usize,
    /// Boundary loops.
    pub boundary_loops: usize,
    /// Euler characteristic chi = V - E + F over referenced vertices.
    pub euler_characteristic: i64,
    /// Genus from eq. 2.7 (summed over components).
    pub genus: u64,
}

impl Topology {
    /// Topology of `mesh`. Fails with [`mesh_kernel::MeshError::NonManifold`]
    /// (wrapped) on non-manifold input. O(V + F), cached by the mesh.
    ///
    /// # Errors
    /// `ParamError::Mesh` (`MeshError::NonManifold`) when the mesh is not an oriented manifold.
    pub fn of(mesh: &TriMesh) -> Result<Self> {
        let conn = mesh.manifold_connectivity()?;
        let boundary_loops = conn.boundary_loops()?.len();
        let components = conn.components().count;
        let euler_characteristic = conn.euler_characteristic();
        let twice = 2 * components as i64 - boundary_loops as i64 - euler_characteristic;
        Ok(Self { components, boundary_loops, euler_characteristic, genus: (twice.max(0) / 2) as u64 })
    }

    /// `true` for a topological disk: one component, one boundary loop, chi = 1.
    pub fn is_disk(&self) -> bool {
        self.components == 1 && self.boundary_loops == 1 && self.euler_characteristic == 1
    }

    /// A short description, e.g. "a closed surface of genus 3",
    /// "a surface of genus 0 with 7 boundary loops", "2 connected components".
    pub fn describe(&self) -> String {
        let (g, b) = (self.genus, self.boundary_loops);
        match (self.components, b) {
            (0, _) => "a mesh without faces".to_string(),
            (c, _) if c > 1 => {
                format!("{c} connected components (chi = {}, {b} boundary loops)", self.euler_characteristic)
            }
            (_, 0) => format!("a closed surface of genus {g}"),
            (_, 1) => format!("a surface of genus {g} with one boundary loop"),
            _ => format!("a surface of genus {g} with {b} boundary loops"),
        }
    }
}

/// The boundary loop of a disk, or [`ParamError::NotADisk`] saying what the
/// mesh is instead (non-manifold input gives the wrapped mesh error listing
/// the defects). O(V + F).
///
/// # Errors
/// `ParamError::Mesh` (`MeshError::NonManifold`) when the mesh is not an oriented manifold;
/// `ParamError::NotADisk` describing the topology found otherwise.
pub fn require_disk(mesh: &TriMesh) -> Result<&BoundaryLoop> {
    let topology = Topology::of(mesh)?;
    if !topology.is_disk() {
        return Err(ParamError::NotADisk { found: topology.describe() });
    }
    let loops = mesh.connectivity().boundary_loops()?;
    loops.first().ok_or_else(|| ParamError::NotADisk { found: topology.describe() })
}

#[cfg(test)]
mod tests {
    use super::*;
    use mesh_kernel::shapes;

    #[test]
    fn disk_is_a_disk() {
        let m = shapes::disk(3, 1).unwrap();
        assert_eq!(require_disk(&m).unwrap().vertices.len(), 18);
    }

    #[test]
    fn others_say_what_they_are() {
        let msg = |m: TriMesh| require_disk(&m).unwrap_err().to_string();
        assert!(msg(shapes::icosphere(1).unwrap()).contains("closed surface of genus 0"));
        assert!(msg(shapes::torus(2.0, 0.5, 8, 4).unwrap()).contains("closed surface of genus 1"));
        assert!(msg(shapes::cylinder(1.0, 1.0, 8, 2).unwrap()).contains("genus 0 with 2 boundary loops"));
        // Two disjoint triangles.
        let p = (0..6).map(|i| glam::DVec3::new(i as f64, (i % 3 == 2) as u8 as f64, 0.0)).collect();
        let two = TriMesh::new(p, vec![[0, 1, 2], [3, 4, 5]]).unwrap();
        assert!(msg(two).contains("2 connected components"));
        let empty = TriMesh::new(vec![], vec![]).unwrap();
        assert!(msg(empty).contains("without faces"));
    }

    #[test]
    fn non_manifold_is_the_mesh_error() {
        let p = (0..5).map(|i| glam::DVec3::new(i as f64, (i * i) as f64, 0.0)).collect();
        let bowtie = TriMesh::new(p, vec![[0, 1, 2], [0, 3, 4]]).unwrap();
        assert!(matches!(require_disk(&bowtie), Err(ParamError::Mesh(_))));
    }
}
