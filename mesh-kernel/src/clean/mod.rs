//! Repairing triangle soups: weld coincident vertices, drop collapsed,
//! degenerate and duplicate faces and unreferenced vertices, make the mesh an
//! oriented manifold (resolving fins, unorientable gluing and non-manifold
//! vertices) and orient faces consistently, with a report of every change.
//!
//! STL files store loose triangles, so readers weld with [`weld_vertices`]
//! before building a [`TriMesh`]; [`clean`] does the whole repair.

mod manifold;
mod orient;
mod weld;

pub use orient::orient_faces;
pub use weld::weld_vertices;

use glam::DVec3;

use crate::error::{MeshError, Result};
use crate::ids::{FaceId, VertexId};
use crate::mesh::TriMesh;

/// What [`clean`] should do. Every step is on by default except welding with
/// a tolerance (exact welding is on).
#[derive(Debug, Clone, PartialEq)]
pub struct CleanOptions {
    /// Merge vertices closer than this distance (`Some(0.0)`: identical
    /// positions only; `None`: no welding). Merging is transitive.
    pub weld_tolerance: Option<f64>,
    /// Drop faces whose area is zero up to [`Self::degenerate_tolerance`].
    pub drop_degenerate: bool,
    /// A face is degenerate when `2 * area <= degenerate_tolerance * longest_edge^2`
    /// (scale-invariant; collinear and coincident corners).
    pub degenerate_tolerance: f64,
    /// Drop faces with the same three vertices as an earlier face, in any order.
    pub drop_duplicates: bool,
    /// Drop vertices that no face references (renumbering the rest in order).
    pub drop_unreferenced: bool,
    /// Make the mesh an oriented 2-manifold by cutting (default off): each
    /// edge with three or more faces keeps its best-continuing pair of faces
    /// and detaches the others, gluing that cannot be oriented is cut open,
    /// and every vertex with several fans of faces is split into one vertex
    /// per fan. Runs after welding and the removal of collapsed, degenerate
    /// and duplicate faces (a duplicate face makes every edge of its original
    /// a fin). Cost O(F) per pass, one pass on almost every mesh.
    pub manifold: bool,
    /// Flip faces so that neighbours agree, and closed components face outward.
    pub orient: bool,
}

impl Default for CleanOptions {
    fn default() -> Self {
        Self {
            weld_tolerance: Some(0.0),
            drop_degenerate: true,
            degenerate_tolerance: 1e-12,
            drop_duplicates: true,
            drop_unreferenced: true,
            manifold: false,
            orient: true,
        }
    }
}

/// What [`clean`] changed.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct CleanReport {
    /// Vertices merged into another by welding.
    pub welded_vertices: usize,
    /// Faces dropped because welding made two of their corners the same vertex.
    pub collapsed_faces: usize,
    /// Zero-area faces dropped.
    pub degenerate_faces: usize,
    /// Duplicate faces dropped.
    pub duplicate_faces: usize,
    /// Unreferenced vertices dropped.
    pub unreferenced_vertices: usize,
    /// Edges shared by three or more faces, resolved by [`CleanOptions::manifold`].
    pub fin_edges: usize,
    /// Faces detached from a fin edge (the edge kept a better pair), or
    /// given vertices of their own when a cut could not be made otherwise.
    pub detached_faces: usize,
    /// Edges cut open so that every component can be oriented.
    pub cut_edges: usize,
    /// Vertex copies added so that every vertex has a single fan of faces.
    pub split_vertices: usize,
    /// Faces whose orientation was reversed.
    pub flipped_faces: usize,
    /// Connected components holding a patch of faces that admits no
    /// consistent orientation (Moebius-like), left as they were. Always 0
    /// with [`CleanOptions::manifold`], which cuts such patches open.
    pub unorientable_components: usize,
}

impl CleanReport {
    /// Every count of the report, in the order of the fields.
    pub fn counts(&self) -> [usize; 11] {
        [
            self.welded_vertices,
            self.collapsed_faces,
            self.degenerate_faces,
            self.duplicate_faces,
            self.unreferenced_vertices,
            self.fin_edges,
            self.detached_faces,
            self.cut_edges,
            self.split_vertices,
            self.flipped_faces,
            self.unorientable_components,
        ]
    }

    /// `true` when nothing changed.
    pub fn is_unchanged(&self) -> bool {
        *self == Self { unorientable_components: self.unorientable_components, ..Self::default() }
    }
}

/// `true` when twice the triangle's area is at most `tolerance` times its
/// longest edge squared (collinear or coincident corners). The test is
/// scale-free: it runs on the triangle rescaled by a power of two so that its
/// longest edge is about 1, so the unit of length never decides it.
pub fn is_degenerate_triangle([a, b, c]: [DVec3; 3], tolerance: f64) -> bool {
    let (ab, ac, bc) = (b - a, c - a, c - b);
    let longest = ab.abs().max(ac.abs()).max(bc.abs()).max_element();
    if longest == 0.0 || !longest.is_finite() {
        return longest == 0.0;
    }
    let unit = crate::geometry::power_of_two_near(longest);
    let (ab, ac, bc) = (ab / unit, ac / unit, bc / unit);
    let longest2 = ab.length_squared().max(bc.length_squared()).max(ac.length_squared());
    ab.cross(ac).length() <= tolerance * longest2
}

/// Faces of zero area (see [`CleanOptions::degenerate_tolerance`]).
pub fn degenerate_faces(mesh: &TriMesh, tolerance: f64) -> Vec<FaceId> {
    mesh.face_ids().filter(|&f| is_degenerate_triangle(mesh.triangle(f), tolerance)).collect()
}

/// Faces that repeat the vertex set of an earlier face (in any order or
/// orientation). Sort-based, O(F log F).
pub fn duplicate_faces(faces: &[[u32; 3]]) -> Vec<FaceId> {
    let mut keyed: Vec<([u32; 3], u32)> = faces
        .iter()
        .enumerate()
        .map(|(i, f)| {
            let mut k = *f;
            k.sort_unstable();
            (k, i as u32)
        })
        .collect();
    keyed.sort_unstable();
    let mut dups: Vec<FaceId> = keyed.windows(2).filter(|w| w[0].0 == w[1].0).map(|w| FaceId(w[1].1)).collect();
    dups.sort_unstable();
    dups
}

/// Vertices that no face references.
pub fn unreferenced_vertices(vertex_count: usize, faces: &[[u32; 3]]) -> Vec<VertexId> {
    let mut used = vec![false; vertex_count];
    for f in faces {
        for &v in f {
            used[v as usize] = true;
        }
    }
    (0..vertex_count).filter(|&v| !used[v]).map(VertexId::new).collect()
}

/// Repairs a triangle soup according to `options` and builds the mesh.
/// Indices must be in range and coordinates finite (otherwise the same errors
/// as [`TriMesh::new`]); faces that repeat a vertex, before or after welding,
/// are dropped and counted as collapsed.
///
/// # Errors
/// [`MeshError::IndexOutOfRange`] and [`MeshError::NonFinitePosition`] for input [`TriMesh::new`]
/// would refuse (repeated corners are dropped instead), [`MeshError::InvalidOption`] for a weld
/// tolerance that is negative, not finite or larger than the bounding-box diagonal.
pub fn clean(positions: Vec<DVec3>, faces: Vec<[u32; 3]>, options: &CleanOptions) -> Result<(TriMesh, CleanReport)> {
    let mut report = CleanReport::default();
    // Validate indices and coordinates first, allowing repeated vertices.
    for (f, tri) in faces.iter().enumerate() {
        if let Some(&vertex) = tri.iter().find(|&&v| v as usize >= positions.len()) {
            return Err(MeshError::IndexOutOfRange { face: FaceId::new(f), vertex, vertex_count: positions.len() });
        }
    }
    if let Some(v) = positions.iter().position(|p| !p.is_finite()) {
        let p = positions[v];
        return Err(MeshError::NonFinitePosition { vertex: VertexId::new(v), x: p.x, y: p.y, z: p.z });
    }
    let (positions, mut faces) = match options.weld_tolerance {
        Some(tol) => {
            let (p, f, merged) = weld_vertices(&positions, &faces, tol)?;
            report.welded_vertices = merged;
            (p, f)
        }
        None => (positions, faces),
    };
    let before = faces.len();
    faces.retain(|[a, b, c]| a != b && b != c && a != c);
    report.collapsed_faces = before - faces.len();

    if options.drop_degenerate {
        let before = faces.len();
        let tol = options.degenerate_tolerance;
        faces.retain(|f| !is_degenerate_triangle(f.map(|v| positions[v as usize]), tol));
        report.degenerate_faces = before - faces.len();
    }
    if options.drop_duplicates {
        let dups = duplicate_faces(&faces);
        report.duplicate_faces = dups.len();
        let mut keep = vec![true; faces.len()];
        for f in dups {
            keep[f.idx()] = false;
        }
        let mut k = keep.iter();
        faces.retain(|_| *k.next().unwrap_or(&true));
    }
    // Faces keep their index through the manifold repair; track their flips.
    let mut flipped = vec![false; faces.len()];
    let (positions, faces) = if options.manifold {
        let (p, f, repair) = manifold::make_manifold(positions, faces)?;
        report.fin_edges = repair.fin_edges;
        report.detached_faces = repair.detached_faces;
        report.cut_edges = repair.cut_edges;
        report.split_vertices = repair.split_vertices;
        flipped = repair.flipped;
        (p, f)
    } else {
        (positions, faces)
    };
    let (positions, faces) = if options.drop_unreferenced {
        let unused = unreferenced_vertices(positions.len(), &faces);
        report.unreferenced_vertices = unused.len();
        compact_vertices(positions, faces)
    } else {
        (positions, faces)
    };
    let mut mesh = TriMesh::new(positions, faces)?;
    if options.orient {
        let (flip, unorientable) = orient_faces(&mesh);
        report.unorientable_components = unorientable;
        if flip.iter().any(|&f| f) {
            let (p, mut f) = mesh.into_parts();
            for ((tri, &flip), flipped) in f.iter_mut().zip(&flip).zip(&mut flipped) {
                if flip {
                    tri.swap(1, 2);
                    *flipped = !*flipped;
                }
            }
            mesh = TriMesh::new(p, f)?;
        }
    }
    report.flipped_faces = flipped.iter().filter(|&&f| f).count();
    Ok((mesh, report))
}

/// Removes unreferenced vertices, keeping the order of the others.
fn compact_vertices(positions: Vec<DVec3>, mut faces: Vec<[u32; 3]>) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let mut remap = vec![u32::MAX; positions.len()];
    for f in &faces {
        for &v in f {
            remap[v as usize] = 0;
        }
    }
    let mut kept = Vec::with_capacity(positions.len());
    for (i, p) in positions.into_iter().enumerate() {
        if remap[i] == 0 {
            remap[i] = kept.len() as u32;
            kept.push(p);
        }
    }
    for f in &mut faces {
        *f = f.map(|v| remap[v as usize]);
    }
    (kept, faces)
}

impl TriMesh {
    /// A repaired copy of this mesh and what changed (see [`clean`]).
    ///
    /// # Errors
    /// Those of [`clean`].
    pub fn cleaned(&self, options: &CleanOptions) -> Result<(TriMesh, CleanReport)> {
        clean(self.positions().to_vec(), self.faces().to_vec(), options)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn welds_loose_triangles() {
        // Two loose triangles of a square, as STL stores them.
        let p =
            vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::ZERO, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
        let (w, f, merged) = weld_vertices(&p, &[[0, 1, 2], [3, 4, 5]], 0.0).unwrap();
        assert_eq!(merged, 2);
        assert_eq!(w.len(), 4);
        assert_eq!(f, vec![[0, 1, 2], [0, 2, 3]]);
    }

    #[test]
    fn welds_with_tolerance_transitively() {
        let p = vec![DVec3::ZERO, DVec3::new(0.6e-3, 0.0, 0.0), DVec3::new(1.2e-3, 0.0, 0.0), DVec3::X];
        let (w, _, merged) = weld_vertices(&p, &[], 1e-3).unwrap();
        assert_eq!(merged, 2);
        assert_eq!(w, vec![DVec3::ZERO, DVec3::X]);
        assert!(weld_vertices(&p, &[], -1.0).is_err());
        assert!(weld_vertices(&p, &[], f64::NAN).is_err());
    }

    #[test]
    fn negative_zero_welds_with_zero() {
        let p = vec![DVec3::ZERO, DVec3::new(-0.0, 0.0, 0.0)];
        assert_eq!(weld_vertices(&p, &[], 0.0).unwrap().2, 1);
    }

    #[test]
    fn clean_reports_every_change() {
        let p = vec![
            DVec3::ZERO,
            DVec3::X,
            DVec3::Y,
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(2.0, 0.0, 0.0), // collinear with 0 and 1
            DVec3::splat(9.0),         // unreferenced
            DVec3::X,                  // duplicate of 1
        ];
        let faces = vec![[0, 1, 2], [1, 3, 2], [2, 1, 0], [0, 1, 4], [6, 3, 2], [0, 6, 1]];
        let (m, r) = clean(p, faces, &CleanOptions::default()).unwrap();
        assert_eq!(r.welded_vertices, 1);
        assert_eq!(r.collapsed_faces, 1);
        assert_eq!(r.degenerate_faces, 1);
        assert_eq!(r.duplicate_faces, 2);
        assert_eq!(r.unreferenced_vertices, 2);
        assert_eq!(m.face_count(), 2);
        assert_eq!(m.vertex_count(), 4);
        assert!(m.connectivity().is_manifold());
    }

    #[test]
    fn orients_a_tetrahedron_outward() {
        let p = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
        // Consistent but inward, and one face flipped.
        let faces = vec![[0, 1, 2], [0, 3, 1], [1, 3, 2], [0, 3, 2]];
        let (m, r) = clean(p, faces, &CleanOptions::default()).unwrap();
        assert!(m.connectivity().is_manifold());
        assert_eq!(r.flipped_faces, 3);
        let vol: f64 = m
            .face_ids()
            .map(|f| {
                let [a, b, c] = m.triangle(f);
                a.dot(b.cross(c))
            })
            .sum();
        assert!(vol > 0.0);
    }

    /// An inside-out sphere is turned outward wherever it lies and in any
    /// unit: 10^6 and 10^9 radii from the origin (where the volume about
    /// the origin cancelled to the wrong sign at 10^6), and scaled by
    /// 1e-150 and 1e150 (where its cubes underflowed and overflowed).
    #[test]
    fn orients_an_inside_out_sphere_outward_wherever_it_lies() {
        let sphere = crate::shapes::icosphere(2).unwrap();
        let inward: Vec<[u32; 3]> = sphere.faces().iter().map(|&[a, b, c]| [a, c, b]).collect();
        for (offset, scale) in [(1e6, 1.0), (1e9, 1.0), (0.0, 1e-150), (0.0, 1e150), (3.0, 1e150)] {
            let far = DVec3::new(offset, -offset, 0.5 * offset);
            let p: Vec<DVec3> = sphere.positions().iter().map(|&q| (q + far) * scale).collect();
            let (m, r) = clean(p, inward.clone(), &CleanOptions::default()).unwrap();
            assert_eq!(r.flipped_faces, inward.len(), "offset {offset:e}, scale {scale:e}");
            assert_eq!(m.faces(), sphere.faces(), "offset {offset:e}, scale {scale:e}");
        }
    }

    #[test]
    fn clean_rejects_bad_indices() {
        let e = clean(vec![DVec3::ZERO], vec![[0, 1, 2]], &CleanOptions::default()).unwrap_err();
        assert!(matches!(e, MeshError::IndexOutOfRange { .. }));
    }
}
