//! The nested meshes K^0 ⊂ K^1 ⊂ ... ⊂ K^J of recursive 4-to-1 splitting
//! (the chapter's section 2.8, figure 2.13) with the parent/child relations the filter
//! banks need.
//!
//! Vertices are numbered hierarchically: the `n_j` vertices of K^j are the
//! first `n_j` of K^{j+1}, followed by the `n_{j+1} - n_j` *odd* vertices
//! that split the edges of K^j. Each odd vertex knows its parent edge. Built
//! either top-down from a base mesh ([`Hierarchy::from_base`], the order of
//! [`mesh_kernel::shapes::midpoint_subdivide`]: one odd vertex per
//! [`mesh_kernel::Connectivity`] edge in edge order, faces `4f..4f+3`) or bottom-up from a
//! fine mesh by [`crate::detect()`], in which case it remembers where every
//! vertex came from.

use std::sync::OnceLock;

use glam::DVec3;
use mesh_kernel::{par, MeshError, TriMesh};

use crate::error::{Result, WaveletError};
use crate::topology::{manifold_topology, Topology};

/// Largest face count a hierarchy may reach (about 1.3e8 triangles).
pub const MAX_FACES: usize = 1 << 27;

/// The topology of K^0..K^J with hierarchical vertex numbering.
pub struct Hierarchy {
    counts: Vec<usize>,
    faces: Vec<Vec<[u32; 3]>>,
    parents: Vec<Vec<[u32; 2]>>,
    to_input: Option<Vec<u32>>,
    topology: Vec<OnceLock<Topology<'static>>>,
}

impl Hierarchy {
    /// Assembles a hierarchy from its parts, checking sizes and indices:
    /// `faces[j]` are the faces of K^j over `counts[j]` vertices,
    /// `parents[j][i]` the endpoints in K^j of the edge split by vertex
    /// `counts[j] + i`, and `to_input` (if any) a permutation of `0..n_J`.
    /// Cost O(n_J + F_J).
    pub fn new(
        counts: Vec<usize>,
        faces: Vec<Vec<[u32; 3]>>,
        parents: Vec<Vec<[u32; 2]>>,
        to_input: Option<Vec<u32>>,
    ) -> Result<Self> {
        let levels = counts.len().checked_sub(1).ok_or_else(|| WaveletError::Dimension("no level".into()))?;
        if faces.len() != levels + 1 || parents.len() != levels {
            return Err(WaveletError::Dimension(format!(
                "{} vertex counts, {} face lists and {} parent lists",
                counts.len(),
                faces.len(),
                parents.len()
            )));
        }
        for j in 0..=levels {
            let n = counts[j];
            if faces[j].iter().flatten().any(|&v| v as usize >= n) {
                return Err(WaveletError::Dimension(format!("a face of level {j} refers to a vertex >= {n}")));
            }
            if faces[j].iter().any(|&[a, b, c]| a == b || b == c || c == a) {
                return Err(WaveletError::Dimension(format!("a face of level {j} repeats a vertex")));
            }
            if j < levels {
                if counts[j + 1] != n + parents[j].len() {
                    return Err(WaveletError::Dimension(format!("level {} vertex count is not n_j + odd", j + 1)));
                }
                if parents[j].iter().flatten().any(|&v| v as usize >= n) {
                    return Err(WaveletError::Dimension(format!("a parent edge of level {j} is out of range")));
                }
            }
        }
        if let Some(p) = &to_input {
            let n = counts[levels];
            let mut seen = vec![false; n];
            if p.len() != n || p.iter().any(|&i| (i as usize) >= n || std::mem::replace(&mut seen[i as usize], true)) {
                return Err(WaveletError::Dimension("the input order is not a permutation".into()));
            }
        }
        let topology = (0..levels).map(|_| OnceLock::new()).collect();
        Ok(Self { counts, faces, parents, to_input, topology })
    }

    /// Splits the base mesh K^0 (`vertex_count` vertices, `faces`, an oriented
    /// manifold) `levels` times with the vertex and face order of
    /// [`mesh_kernel::shapes::midpoint_subdivide`]. Cost O(4^levels F_0).
    ///
    /// # Errors
    /// `MeshError::Empty` without faces; the `MeshError` of `TriMesh::new` for faces out of range or
    /// repeating a vertex; `WaveletError::InvalidOption` (`levels`) when the finest level would exceed
    /// `MAX_FACES`; `MeshError::NonManifold` when the base mesh is not an oriented manifold.
    pub fn from_base(vertex_count: usize, faces: &[[u32; 3]], levels: usize) -> Result<Self> {
        if faces.is_empty() {
            return Err(MeshError::Empty.into());
        }
        // The checks of TriMesh: indices in range, no repeated vertex.
        TriMesh::new(vec![DVec3::ZERO; vertex_count], faces.to_vec())?;
        check_size(faces.len(), levels)?;
        let mut counts = vec![vertex_count];
        let mut all_faces = vec![faces.to_vec()];
        let mut parents = Vec::with_capacity(levels);
        let mut topology = Vec::with_capacity(levels);
        for j in 0..levels {
            let topo = manifold_topology(counts[j], &all_faces[j])?.into_owned();
            let fine = split_faces(&topo, &all_faces[j], counts[j] as u32);
            parents.push(topo.edges().to_vec());
            counts.push(counts[j] + topo.edge_count());
            all_faces.push(fine);
            let cell = OnceLock::new();
            let _ = cell.set(topo);
            topology.push(cell);
        }
        Ok(Self { counts, faces: all_faces, parents, to_input: None, topology })
    }

    /// The finest level J (number of 4-to-1 splits above the base mesh).
    pub fn levels(&self) -> usize {
        self.counts.len() - 1
    }

    fn check_level(&self, level: usize, finest: usize) -> Result<()> {
        if level > finest {
            return Err(WaveletError::LevelOutOfRange { level, levels: self.levels() });
        }
        Ok(())
    }

    /// Number of vertices `n_j` of K^j, `j <= J`.
    ///
    /// # Errors
    /// `WaveletError::LevelOutOfRange` when `level > levels()`.
    pub fn vertex_count(&self, level: usize) -> Result<usize> {
        self.check_level(level, self.levels())?;
        Ok(self.counts[level])
    }

    /// Faces of K^j (`j <= J`) over the first `n_j` hierarchical vertices.
    ///
    /// # Errors
    /// `WaveletError::LevelOutOfRange` when `level > levels()`.
    pub fn faces(&self, level: usize) -> Result<&[[u32; 3]]> {
        self.check_level(level, self.levels())?;
        Ok(&self.faces[level])
    }

    /// For `level < J`: the endpoints (in K^level) of the edge split by odd
    /// vertex `n_level + i`, for each `i`, in the sorted order of the edges.
    ///
    /// # Errors
    /// `WaveletError::LevelOutOfRange` when `level` is 0 or greater than `levels()`.
    pub fn parents(&self, level: usize) -> Result<&[[u32; 2]]> {
        if level >= self.levels() {
            return Err(WaveletError::LevelOutOfRange { level, levels: self.levels() });
        }
        Ok(&self.parents[level])
    }

    pub(crate) fn count(&self, level: usize) -> usize {
        self.counts[level]
    }

    pub(crate) fn faces_of(&self, level: usize) -> &[[u32; 3]] {
        &self.faces[level]
    }

    /// Half-edge topology of K^j for `j < J`, built on first use in O(F_j)
    /// and cached; an error if K^j is not an oriented manifold.
    pub(crate) fn topology(&self, level: usize) -> Result<&Topology<'static>> {
        let cell = &self.topology[level];
        if cell.get().is_none() {
            let _ = cell.set(manifold_topology(self.counts[level], &self.faces[level])?.into_owned());
        }
        cell.get().ok_or_else(|| WaveletError::Dimension(format!("no topology for level {level}")))
    }

    /// Index in the mesh this hierarchy was detected from of each hierarchical
    /// vertex; `None` when they coincide (hierarchies built by subdivision).
    pub fn to_input(&self) -> Option<&[u32]> {
        self.to_input.as_deref()
    }

    /// Index of hierarchical vertex `h` in the input mesh (`None` beyond n_J).
    pub fn input_index(&self, h: usize) -> Option<usize> {
        (h < self.counts[self.levels()]).then(|| self.input_of(h))
    }

    #[inline]
    pub(crate) fn input_of(&self, h: usize) -> usize {
        self.to_input.as_ref().map_or(h, |p| p[h] as usize)
    }

    /// Where each vertex of K^j goes in an output mesh of level j: vertices
    /// keep the relative order they have in the input mesh, so the output at
    /// level J has exactly the input order. Cost O(n_J).
    ///
    /// # Errors
    /// `WaveletError::LevelOutOfRange` when `level > levels()`.
    pub fn output_order(&self, level: usize) -> Result<Vec<u32>> {
        self.check_level(level, self.levels())?;
        Ok(self.order_of(level))
    }

    pub(crate) fn order_of(&self, level: usize) -> Vec<u32> {
        let n = self.counts[level];
        let Some(p) = &self.to_input else {
            return (0..n as u32).collect();
        };
        // Rank the input indices of the first n vertices with a counting pass.
        let total = self.counts[self.levels()];
        let mut present = vec![u32::MAX; total];
        for (h, &i) in p[..n].iter().enumerate() {
            present[i as usize] = h as u32;
        }
        let mut order = vec![0u32; n];
        for (rank, h) in present.into_iter().filter(|&h| h != u32::MAX).enumerate() {
            order[h as usize] = rank as u32;
        }
        order
    }
}

impl std::fmt::Debug for Hierarchy {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let faces: Vec<usize> = self.faces.iter().map(Vec::len).collect();
        f.debug_struct("Hierarchy")
            .field("vertex_counts", &self.counts)
            .field("face_counts", &faces)
            .field("detected", &self.to_input.is_some())
            .finish()
    }
}

/// Refuses hierarchies whose finest level would exceed [`MAX_FACES`].
pub(crate) fn check_size(faces: usize, levels: usize) -> Result<()> {
    let fine = (faces as u128).checked_shl(2 * levels.min(64) as u32).unwrap_or(u128::MAX);
    if levels > 32 || fine > MAX_FACES as u128 {
        return Err(WaveletError::InvalidOption {
            name: "levels",
            reason: format!("{levels} levels over {faces} faces exceed {MAX_FACES} faces"),
        });
    }
    Ok(())
}

/// One 4-to-1 split of the faces (topology only), in the order of
/// [`mesh_kernel::shapes::midpoint_subdivide`]: odd vertex `n + e` on edge `e`,
/// corner triangles of face `f` at `4f + k`, the middle one at `4f + 3`.
/// (That function also needs positions; the hierarchy only has topology.)
pub(crate) fn split_faces(topo: &Topology, faces: &[[u32; 3]], n: u32) -> Vec<[u32; 3]> {
    par::map(faces.len(), |f| {
        let [a, b, c] = faces[f];
        let [eab, ebc, eca] = topo.face_edges(f).map(|e| n + e);
        [[a, eab, eca], [b, ebc, eab], [c, eca, ebc], [eab, ebc, eca]]
    })
    .into_flattened()
}

#[cfg(test)]
mod tests {
    use super::*;
    use mesh_kernel::shapes;

    #[test]
    fn split_matches_mesh_kernel_midpoint_subdivide() {
        let m = shapes::torus(2.0, 0.5, 6, 4).unwrap();
        let (_, faces) = shapes::midpoint_subdivide(&m);
        let topo = Topology::new(m.vertex_count(), m.faces()).unwrap();
        let ours = split_faces(&topo, m.faces(), m.vertex_count() as u32);
        assert_eq!(ours, faces);
    }

    #[test]
    fn counts_follow_euler() {
        let m = shapes::icosphere(0).unwrap();
        let h = Hierarchy::from_base(m.vertex_count(), m.faces(), 3).unwrap();
        for j in 0..=3 {
            assert_eq!(h.vertex_count(j).unwrap(), 10 * 4usize.pow(j as u32) + 2);
            assert_eq!(h.faces(j).unwrap().len(), 20 * 4usize.pow(j as u32));
        }
        assert_eq!(h.faces(3).unwrap(), shapes::icosphere(3).unwrap().faces());
        assert!(h.faces(4).is_err() && h.parents(3).is_err() && h.vertex_count(9).is_err());
        assert_eq!(h.input_index(641), Some(641));
        assert_eq!(h.input_index(642), None);
        assert!(Hierarchy::from_base(3, &[[0, 1, 2]], 40).is_err());
        assert!(Hierarchy::from_base(3, &[], 1).is_err());
        assert!(Hierarchy::from_base(3, &[[0, 1, 3]], 1).is_err());
        assert!(Hierarchy::from_base(3, &[[0, 1, 1]], 1).is_err());
    }

    #[test]
    fn new_validates() {
        assert!(Hierarchy::new(vec![3], vec![vec![[0, 1, 3]]], vec![], None).is_err());
        assert!(Hierarchy::new(vec![3], vec![vec![[0, 1, 2]]], vec![], Some(vec![0, 0, 1])).is_err());
        let h = Hierarchy::new(vec![3], vec![vec![[0, 1, 2]]], vec![], Some(vec![2, 0, 1])).unwrap();
        assert_eq!(h.output_order(0).unwrap(), vec![2, 0, 1]);
        assert!(Hierarchy::new(vec![3], vec![vec![[0, 1, 1]]], vec![], None).is_err());
    }
}
