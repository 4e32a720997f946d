//! The triangle mesh itself: positions, triangles and lazily cached connectivity.

use std::sync::OnceLock;

use crate::cache::{Cache, Geometry};

use glam::DVec3;

use crate::connectivity::Connectivity;
use crate::error::{MeshError, Result};
use crate::ids::{FaceId, VertexId};
use crate::par;

/// A triangle mesh: `f64` positions and counter-clockwise triangles.
///
/// Construction validates the input (indices in range, finite coordinates, no
/// triangle repeating a vertex) so that every algorithm downstream can index
/// without checks. Non-manifold, disconnected and degenerate (zero-area)
/// meshes are valid `TriMesh`es: algorithms that need more ask for it and
/// return a typed error.
///
/// Connectivity ([`TriMesh::connectivity`]) is derived from the triangles on
/// first use, in O(F), and cached; moving vertices with
/// [`TriMesh::positions_mut`] keeps it, since it depends only on the triangles.
#[derive(Clone)]
pub struct TriMesh {
    positions: Vec<DVec3>,
    faces: Vec<[u32; 3]>,
    connectivity: OnceLock<Connectivity>,
    geometry: Cache,
}

/// Whether every triangle's corners are below `n` and distinct: two
/// reductions without a branch, the largest corner and the smallest XOR
/// of two corners of a triangle (zero exactly when they are equal). The
/// unsigned minima and maxima are vector instructions from SSE4.1 on, so
/// the scan is also compiled for AVX2 and picked at run time: 3.76 million
/// faces took 13 ms on one thread with the baseline's SSE2 and 6 ms with
/// AVX2, which is then bound by memory (2026-12-06).
fn valid_triangles(faces: &[[u32; 3]], n: usize) -> bool {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the processor has AVX2, checked just above.
        return unsafe { valid_triangles_avx2(faces, n) };
    }
    valid_triangles_portable(faces, n)
}

/// [`valid_triangles_portable`] compiled for AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn valid_triangles_avx2(faces: &[[u32; 3]], n: usize) -> bool {
    valid_triangles_portable(faces, n)
}

/// [`valid_triangles`] for any processor.
#[inline(always)]
fn valid_triangles_portable(faces: &[[u32; 3]], n: usize) -> bool {
    let (largest, differ) = faces.iter().fold((0u32, u32::MAX), |(hi, lo), &[a, b, c]| {
        (hi.max(a.max(b).max(c)), lo.min((a ^ b).min(a ^ c).min(b ^ c)))
    });
    (largest as usize) < n && differ != 0
}

/// The error for the first vertex with a NaN or infinite coordinate, if
/// any: a branch-free scan in parallel, then the search that names it.
fn check_positions(positions: &[DVec3]) -> Result<()> {
    if par::all_chunks(positions, |chunk| chunk.iter().fold(true, |ok, p| ok & p.is_finite())) {
        return Ok(());
    }
    match positions.iter().position(|p| !p.is_finite()) {
        Some(v) => {
            let p = positions[v];
            Err(MeshError::NonFinitePosition { vertex: VertexId::new(v), x: p.x, y: p.y, z: p.z })
        }
        None => Ok(()),
    }
}

/// The error for the first triangle with a corner out of range or
/// repeated, if any.
fn check_triangles(faces: &[[u32; 3]], n: usize) -> Result<()> {
    for (f, tri) in faces.iter().enumerate() {
        for &v in tri {
            if v as usize >= n {
                return Err(MeshError::IndexOutOfRange { face: FaceId::new(f), vertex: v, vertex_count: n });
            }
        }
        let [a, b, c] = *tri;
        if a == b || a == c {
            return Err(MeshError::RepeatedVertex { face: FaceId::new(f), vertex: VertexId(a) });
        }
        if b == c {
            return Err(MeshError::RepeatedVertex { face: FaceId::new(f), vertex: VertexId(b) });
        }
    }
    Ok(())
}

impl TriMesh {
    /// Builds a mesh after checking that every index is in range, every
    /// coordinate finite and no triangle repeats a vertex. Cost O(V + F).
    ///
    /// # Errors
    /// [`MeshError::TooLarge`] past `u32` indices, [`MeshError::NonFinitePosition`] naming the
    /// first vertex with a NaN or infinite coordinate, [`MeshError::IndexOutOfRange`] naming the
    /// face and index, [`MeshError::RepeatedVertex`] for a triangle that names a vertex twice.
    pub fn new(positions: Vec<DVec3>, faces: Vec<[u32; 3]>) -> Result<Self> {
        if positions.len() >= u32::MAX as usize {
            return Err(MeshError::TooLarge { what: "vertex", count: positions.len() });
        }
        // Half-edges are numbered 3 f + k in a u32.
        if faces.len() >= (u32::MAX / 3) as usize {
            return Err(MeshError::TooLarge { what: "face", count: faces.len() });
        }
        // Branch-free scans in parallel first; the loops that name the
        // first offender run only when one finds it.
        check_positions(&positions)?;
        let n = positions.len();
        if !par::all_chunks(&faces, |chunk| valid_triangles(chunk, n)) {
            check_triangles(&faces, n)?;
        }
        Ok(Self { positions, faces, connectivity: OnceLock::new(), geometry: Cache::default() })
    }

    /// Builds a mesh from flat coordinate and index arrays (`xyz` holds three
    /// numbers per vertex, `indices` three per triangle).
    ///
    /// # Errors
    /// [`MeshError::Dimension`] when either array's length is not a multiple of 3; then those of
    /// [`TriMesh::new`].
    pub fn from_flat(xyz: &[f64], indices: &[u32]) -> Result<Self> {
        if !xyz.len().is_multiple_of(3) {
            return Err(MeshError::Dimension(format!("{} coordinates is not a multiple of 3", xyz.len())));
        }
        if !indices.len().is_multiple_of(3) {
            return Err(MeshError::Dimension(format!("{} indices is not a multiple of 3", indices.len())));
        }
        let positions = xyz.chunks_exact(3).map(|c| DVec3::new(c[0], c[1], c[2])).collect();
        let faces = indices.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
        Self::new(positions, faces)
    }

    /// Vertex positions.
    #[inline]
    pub fn positions(&self) -> &[DVec3] {
        &self.positions
    }

    /// Mutable vertex positions. The cached connectivity stays valid, since it
    /// depends only on the triangles; the cached geometry ([`TriMesh::geometry`])
    /// is dropped. Callers must keep coordinates finite.
    #[inline]
    pub fn positions_mut(&mut self) -> &mut [DVec3] {
        self.geometry = Cache::default();
        &mut self.positions
    }

    /// Replaces all positions at once (same count), keeping the connectivity.
    ///
    /// # Errors
    /// [`MeshError::Dimension`] for a different vertex count, [`MeshError::NonFinitePosition`]
    /// naming the first non-finite vertex.
    pub fn set_positions(&mut self, positions: Vec<DVec3>) -> Result<()> {
        if positions.len() != self.positions.len() {
            return Err(MeshError::Dimension(format!(
                "{} positions given for a mesh of {} vertices",
                positions.len(),
                self.positions.len()
            )));
        }
        check_positions(&positions)?;
        self.positions = positions;
        self.geometry = Cache::default();
        Ok(())
    }

    /// Triangles as vertex index triples, counter-clockwise seen from outside.
    #[inline]
    pub fn faces(&self) -> &[[u32; 3]] {
        &self.faces
    }

    /// Number of vertices (referenced or not).
    #[inline]
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Number of triangles.
    #[inline]
    pub fn face_count(&self) -> usize {
        self.faces.len()
    }

    /// Position of one vertex.
    #[inline]
    pub fn position(&self, v: VertexId) -> DVec3 {
        self.positions[v.idx()]
    }

    /// The three vertices of a face.
    #[inline]
    pub fn face(&self, f: FaceId) -> [VertexId; 3] {
        let [a, b, c] = self.faces[f.idx()];
        [VertexId(a), VertexId(b), VertexId(c)]
    }

    /// The three corner positions of a face.
    #[inline]
    pub fn triangle(&self, f: FaceId) -> [DVec3; 3] {
        let [a, b, c] = self.faces[f.idx()];
        [self.positions[a as usize], self.positions[b as usize], self.positions[c as usize]]
    }

    /// All vertex ids.
    pub fn vertex_ids(&self) -> impl ExactSizeIterator<Item = VertexId> + use<> {
        (0..self.positions.len() as u32).map(VertexId)
    }

    /// All face ids.
    pub fn face_ids(&self) -> impl ExactSizeIterator<Item = FaceId> + use<> {
        (0..self.faces.len() as u32).map(FaceId)
    }

    /// Connectivity (edges, half-edges, vertex rings, manifold report), built on
    /// first call in O(V + F) and cached.
    pub fn connectivity(&self) -> &Connectivity {
        crate::par::init_once(&self.connectivity, || Connectivity::new(self.positions.len(), &self.faces))
    }

    /// The connectivity, or [`MeshError::NonManifold`] with every defect when the
    /// mesh is not an oriented 2-manifold (with or without boundary).
    ///
    /// # Errors
    /// [`MeshError::NonManifold`] with the report (see [`crate::Connectivity::require_manifold`]).
    pub fn manifold_connectivity(&self) -> Result<&Connectivity> {
        let c = self.connectivity();
        c.require_manifold()?;
        Ok(c)
    }

    /// The derived quantities of this mesh (areas, angles, normals, masses,
    /// Laplacians, gradient, divergence), each computed on first use and
    /// kept until the vertices move: see [`crate::cache`].
    pub fn geometry(&self) -> Geometry<'_> {
        Geometry::new(self, &self.geometry)
    }

    /// Frees the stored derived quantities (a cotangent Laplacian of a
    /// million vertices holds about 110 MB); they are computed again when
    /// asked for.
    pub fn forget_geometry(&mut self) {
        self.geometry = Cache::default();
    }

    /// Gives back positions and triangles.
    pub fn into_parts(self) -> (Vec<DVec3>, Vec<[u32; 3]>) {
        (self.positions, self.faces)
    }
}

impl std::fmt::Debug for TriMesh {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("TriMesh").field("vertices", &self.positions.len()).field("faces", &self.faces.len()).finish()
    }
}

impl PartialEq for TriMesh {
    /// Two meshes are equal when positions and triangles are (the cache is ignored).
    fn eq(&self, other: &Self) -> bool {
        self.positions == other.positions && self.faces == other.faces
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri() -> Vec<DVec3> {
        vec![DVec3::ZERO, DVec3::X, DVec3::Y]
    }

    /// The scan picked at run time agrees with the portable one and with
    /// the loop that names the first bad face, on faces with one corner out
    /// of range or one repeated corner planted anywhere.
    #[test]
    fn the_faces_scan_finds_every_planted_error() {
        let mut rng = crate::random::SplitMix64::new(5);
        let n = 1000;
        let mut faces: Vec<[u32; 3]> = (0..3000)
            .map(|_| {
                let a = rng.below(n - 2) as u32;
                [a, a + 1, a + 2]
            })
            .collect();
        assert!(valid_triangles(&faces, n) && valid_triangles_portable(&faces, n));
        for trial in 0..200 {
            let (f, k) = (rng.below(faces.len()), rng.below(3));
            let kept = faces[f];
            faces[f][k] = if trial % 2 == 0 { n as u32 + (trial as u32) } else { faces[f][(k + 1) % 3] };
            let expected = check_triangles(&faces, n).is_ok();
            assert!(!expected);
            assert_eq!(valid_triangles(&faces, n), expected);
            assert_eq!(valid_triangles_portable(&faces, n), expected);
            faces[f] = kept;
        }
    }

    #[test]
    fn validates_indices() {
        let e = TriMesh::new(tri(), vec![[0, 1, 3]]).unwrap_err();
        assert_eq!(e, MeshError::IndexOutOfRange { face: FaceId(0), vertex: 3, vertex_count: 3 });
    }

    #[test]
    fn validates_repeats_and_nan() {
        assert!(matches!(TriMesh::new(tri(), vec![[0, 1, 1]]), Err(MeshError::RepeatedVertex { .. })));
        let mut p = tri();
        p[2].z = f64::NAN;
        assert!(matches!(
            TriMesh::new(p, vec![[0, 1, 2]]),
            Err(MeshError::NonFinitePosition { vertex: VertexId(2), .. })
        ));
    }

    #[test]
    fn large_meshes_name_the_first_offender() {
        // Past the parallel scans' threshold and chunk: the error names the
        // first bad element, whichever chunk a thread checks first.
        let grid = crate::shapes::grid(1.0, 1.0, 200, 200).unwrap();
        let (p, f) = (grid.positions().to_vec(), grid.faces().to_vec());
        let n = p.len() as u32;
        let with = |edits: &[(usize, [u32; 3])]| {
            let mut faces = f.clone();
            for &(i, tri) in edits {
                faces[i] = tri;
            }
            TriMesh::new(p.clone(), faces)
        };
        assert!(with(&[]).is_ok());
        let e = with(&[(70_000, [0, 1, 1]), (30_000, [5, n, 6]), (50_000, [2, 2, 3])]).unwrap_err();
        assert_eq!(e, MeshError::IndexOutOfRange { face: FaceId(30_000), vertex: n, vertex_count: n as usize });
        let e = with(&[(79_999, [0, 1, n + 7]), (40_000, [9, 8, 9])]).unwrap_err();
        assert_eq!(e, MeshError::RepeatedVertex { face: FaceId(40_000), vertex: VertexId(9) });
        let e = with(&[(17, [4, 3, 3])]).unwrap_err();
        assert_eq!(e, MeshError::RepeatedVertex { face: FaceId(17), vertex: VertexId(3) });
        let mut q = p.clone();
        q[39_000].y = f64::INFINITY;
        q[25_000].x = f64::NAN;
        assert!(matches!(
            TriMesh::new(q, f.clone()),
            Err(MeshError::NonFinitePosition { vertex: VertexId(25_000), .. })
        ));
    }

    #[test]
    fn flat_constructor() {
        let m = TriMesh::from_flat(&[0., 0., 0., 1., 0., 0., 0., 1., 0.], &[0, 1, 2]).unwrap();
        assert_eq!(m.face_count(), 1);
        assert!(TriMesh::from_flat(&[0., 0.], &[]).is_err());
    }
}
