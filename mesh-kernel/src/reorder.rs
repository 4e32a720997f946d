//! Cache-friendly vertex and face orders.
//!
//! Per-face loops read three vertices per face and per-vertex loops read a
//! ring of neighbours; both run at memory speed only when neighbouring
//! elements sit near each other in memory. A mesh whose vertices and faces
//! come in random order runs local operators 1.7-4x slower than the same
//! mesh in a local order.
//!
//! [`Reordering::spatial`] sorts vertices along a Hilbert curve through the
//! bounding box (Hilbert 1891; the transpose form of Skilling 2004), which
//! keeps vertices that are close in space close in memory whatever the
//! connectivity (non-manifold, many components); faces follow, sorted by
//! their smallest vertex in the new order. [`Reordering::apply`] builds
//! the renumbered mesh, and the maps bring results back to the input's
//! order. On a shuffled 470,274-vertex mesh it made normals about 4x
//! faster, Dijkstra 2.3x, the cotan Laplacian 1.6-2.3x and the half-edges
//! 1.3-1.6x. A mesh already in a local order gains little: Loop
//! subdivision numbers each level's new vertices edge by edge, and on its
//! output the sums over faces ran up to 15% faster after renumbering
//! (BENCHMARKS.md, "Vertex order on a shuffled mesh"). The half-edges and
//! the midpoint upsample ran 25-50% and 20-45% slower after it until
//! their buckets were sorted by rank and their fans' ends found without a
//! search; they now build as fast in either order (at 470,274 vertices on
//! one core, 2026-12-07: the half-edges in 100-107 ms against 106-120 on
//! one machine, the upsample in 74.2-75.7 ms against 75.1-75.4 on
//! another).
//!
//! Renumbering never happens behind a caller's back: a reordered mesh is a
//! new mesh with its own indices. Whether it pays depends on how often the
//! mesh is used: computing and applying the order costs about as much as
//! one pass of the cotangent Laplacian (see BENCHMARKS.md).

use glam::DVec3;

use crate::error::{MeshError, Result};
use crate::geometry::Aabb;
use crate::ids::{FaceId, VertexId};
use crate::mesh::TriMesh;

/// Bits per axis of the Hilbert grid: 3 x 21 = 63 bits of key.
const BITS: u32 = 21;

/// A renumbering of the vertices and faces of a mesh.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Reordering {
    /// Old index of each new vertex.
    vertex_order: Vec<u32>,
    /// New index of each old vertex.
    vertex_rank: Vec<u32>,
    /// Old index of each new face.
    face_order: Vec<u32>,
}

impl Reordering {
    /// Vertices along a Hilbert curve through the bounding box (on a grid of
    /// 2^21 cells per axis), faces by their smallest vertex in that order
    /// (ties keep the input order). Unreferenced vertices are ordered like
    /// the others. Cost O(V log V + F).
    pub fn spatial(mesh: &TriMesh) -> Self {
        Self::from_vertex_order(mesh, hilbert_order(mesh.positions()))
    }

    /// The reordering that puts vertices in `vertex_order` (old index of
    /// each new vertex) and faces by their smallest vertex in that order.
    ///
    /// # Errors
    /// [`MeshError::Dimension`] when `vertex_order` is not a permutation of
    /// the mesh's vertices.
    pub fn with_vertex_order(mesh: &TriMesh, vertex_order: Vec<VertexId>) -> Result<Self> {
        let n = mesh.vertex_count();
        let mut seen = vec![false; n];
        let valid = vertex_order.len() == n
            && vertex_order.iter().all(|v| v.idx() < n && !std::mem::replace(&mut seen[v.idx()], true));
        if !valid {
            return Err(MeshError::Dimension(format!(
                "the vertex order ({} entries) is not a permutation of the mesh's {n} vertices",
                vertex_order.len()
            )));
        }
        Ok(Self::from_vertex_order(mesh, vertex_order.into_iter().map(|v| v.0).collect()))
    }

    /// Ranks the vertices and sorts faces by their smallest new vertex with
    /// a counting sort; `vertex_order` is a permutation. O(V + F).
    fn from_vertex_order(mesh: &TriMesh, vertex_order: Vec<u32>) -> Self {
        let mut vertex_rank = vec![0u32; vertex_order.len()];
        for (new, &old) in vertex_order.iter().enumerate() {
            vertex_rank[old as usize] = new as u32;
        }
        let first = |f: &[u32; 3]| f.iter().map(|&v| vertex_rank[v as usize]).min().unwrap_or(0) as usize;
        let mut start = vec![0u32; vertex_order.len() + 1];
        for f in mesh.faces() {
            start[first(f) + 1] += 1;
        }
        for i in 1..start.len() {
            start[i] += start[i - 1];
        }
        let mut face_order = vec![0u32; mesh.face_count()];
        for (old, f) in mesh.faces().iter().enumerate() {
            let slot = &mut start[first(f)];
            face_order[*slot as usize] = old as u32;
            *slot += 1;
        }
        Self { vertex_order, vertex_rank, face_order }
    }

    /// The renumbered mesh: vertex `i` is old vertex `old_vertex(i)`, face `j`
    /// is old face `old_face(j)` with its corners renamed (same orientation,
    /// same first corner). Cost O(V + F).
    ///
    /// # Errors
    /// [`MeshError::Dimension`] when `mesh` does not have the vertex and face
    /// counts of the mesh this reordering was made for.
    pub fn apply(&self, mesh: &TriMesh) -> Result<TriMesh> {
        if mesh.vertex_count() != self.vertex_order.len() || mesh.face_count() != self.face_order.len() {
            return Err(MeshError::Dimension(format!(
                "a reordering of {} vertices and {} faces applied to a mesh of {} and {}",
                self.vertex_order.len(),
                self.face_order.len(),
                mesh.vertex_count(),
                mesh.face_count()
            )));
        }
        let p = mesh.positions();
        let positions: Vec<DVec3> = self.vertex_order.iter().map(|&v| p[v as usize]).collect();
        let faces = self.face_order.iter().map(|&f| mesh.faces()[f as usize].map(|v| self.vertex_rank[v as usize]));
        TriMesh::new(positions, faces.collect())
    }

    /// The old index of new vertex `v`.
    pub fn old_vertex(&self, v: VertexId) -> VertexId {
        VertexId(self.vertex_order[v.idx()])
    }

    /// The new index of old vertex `v`.
    pub fn new_vertex(&self, v: VertexId) -> VertexId {
        VertexId(self.vertex_rank[v.idx()])
    }

    /// The old index of new face `f`.
    pub fn old_face(&self, f: FaceId) -> FaceId {
        FaceId(self.face_order[f.idx()])
    }

    /// Per-vertex values of the reordered mesh, in the input's vertex order.
    ///
    /// # Errors
    /// [`MeshError::Dimension`] when `values` has not one entry per vertex.
    pub fn vertex_values_to_input<T: Clone>(&self, values: &[T]) -> Result<Vec<T>> {
        gather(values, &self.vertex_rank, "vertex")
    }

    /// Per-vertex values of the input mesh, in the reordered mesh's order.
    ///
    /// # Errors
    /// [`MeshError::Dimension`] when `values` has not one entry per vertex.
    pub fn vertex_values_from_input<T: Clone>(&self, values: &[T]) -> Result<Vec<T>> {
        gather(values, &self.vertex_order, "vertex")
    }

    /// Per-face values of the input mesh, in the reordered mesh's order.
    ///
    /// # Errors
    /// [`MeshError::Dimension`] when `values` has not one entry per face.
    pub fn face_values_from_input<T: Clone>(&self, values: &[T]) -> Result<Vec<T>> {
        gather(values, &self.face_order, "face")
    }

    /// Per-face values of the reordered mesh, in the input's face order.
    ///
    /// # Errors
    /// [`MeshError::Dimension`] when `values` has not one entry per face.
    pub fn face_values_to_input<T: Clone>(&self, values: &[T]) -> Result<Vec<T>> {
        let mut rank = vec![0u32; self.face_order.len()];
        for (new, &old) in self.face_order.iter().enumerate() {
            rank[old as usize] = new as u32;
        }
        gather(values, &rank, "face")
    }
}

/// `index.map(|i| values[i])`, after checking the lengths agree.
fn gather<T: Clone>(values: &[T], index: &[u32], what: &str) -> Result<Vec<T>> {
    if values.len() != index.len() {
        return Err(MeshError::Dimension(format!("{} values for {} {what}s", values.len(), index.len())));
    }
    Ok(index.iter().map(|&i| values[i as usize].clone()).collect())
}

/// The points' indices along a Hilbert curve through their bounding box
/// (ties keep the input order). Cost O(n log n).
pub(crate) fn hilbert_order(p: &[DVec3]) -> Vec<u32> {
    let Some(b) = Aabb::of(p) else { return (0..p.len() as u32).collect() };
    // The keys beside their points, so that the sort moves contiguous
    // pairs instead of reading a key array at random; eight keys at a
    // time, lane by lane.
    let mut keyed: Vec<(u64, u32)> = Vec::with_capacity(p.len());
    for (c, chunk) in p.chunks(KEY_LANES).enumerate() {
        let mut cells = [[0u32; KEY_LANES]; 3];
        for (lane, &x) in chunk.iter().enumerate() {
            let cell = grid_cell(x, &b);
            (0..3).for_each(|i| cells[i][lane] = cell[i]);
        }
        let keys = hilbert_keys(cells);
        keyed.extend((0..chunk.len()).map(|lane| (keys[lane], (c * KEY_LANES + lane) as u32)));
    }
    keyed.sort_unstable();
    keyed.into_iter().map(|(_, v)| v).collect()
}

/// Points whose Hilbert keys are computed together by [`hilbert_keys`].
const KEY_LANES: usize = 8;

/// The cell of `x` on the grid of 2^BITS cells per axis over `b`; a flat
/// axis maps to cell 0. Differences are taken in halves, which cannot
/// overflow for finite coordinates.
fn grid_cell(x: DVec3, b: &Aabb) -> [u32; 3] {
    let cells = f64::from(1u32 << BITS);
    let (lo, extent) = (b.min * 0.5, b.max * 0.5 - b.min * 0.5);
    let axis = |x: f64, lo: f64, e: f64| {
        let t = if e > 0.0 { (x * 0.5 - lo) / e } else { 0.0 };
        // In [0, 1] up to rounding.
        (t * cells).clamp(0.0, cells - 1.0) as u32
    };
    [axis(x.x, lo.x, extent.x), axis(x.y, lo.y, extent.y), axis(x.z, lo.z, extent.z)]
}

/// The index of each of `L` cells along the 3-D Hilbert curve of 2^BITS
/// cells per axis, from their coordinates axis by axis (`x[i][lane]`):
/// Skilling's transform of the coordinates into the "transposed" Hilbert
/// index, whose bits, interleaved from the most significant, are the index.
/// Every step runs lane by lane, so that the compiler does `L` cells at
/// once in vector registers, where one cell's steps form one chain of about
/// 300 cycles: with eight lanes, `Reordering::spatial` took 31.6 ms instead
/// of 78-85 at 470,274 vertices and 2.36 instead of 6.5 at 40,962 (one
/// thread, three alternated rounds on an Emerald Rapids Xeon, 2026-12-07),
/// with the same keys as one cell at a time on 2.4 million random cells.
fn hilbert_keys<const L: usize>(mut x: [[u32; L]; 3]) -> [u64; L] {
    // Without branches: a coordinate's bits are as good as random, and a
    // branch on each was mispredicted half the time.
    let ones = |x: u32, level: u32| 0u32.wrapping_sub((x >> level) & 1);
    // Undo the excess work of the Gray code, level by level: where bit
    // `level` of x[i] is set, invert the lower bits of x[0], else exchange
    // them with x[i]'s (for i = 0 the exchange does nothing).
    for level in (1..BITS).rev() {
        let p = (1u32 << level) - 1;
        for i in 0..3 {
            for lane in 0..L {
                let set = ones(x[i][lane], level);
                let t = (x[0][lane] ^ x[i][lane]) & p & !set;
                x[0][lane] ^= (p & set) | t;
                x[i][lane] ^= t;
            }
        }
    }
    // Gray encode.
    let mut t = [0u32; L];
    for lane in 0..L {
        x[1][lane] ^= x[0][lane];
        x[2][lane] ^= x[1][lane];
        for level in (1..BITS).rev() {
            t[lane] ^= ((1u32 << level) - 1) & ones(x[2][lane], level);
        }
    }
    std::array::from_fn(|lane| {
        let [a, b, c] = [0, 1, 2].map(|i| spread(x[i][lane] ^ t[lane]));
        (a << 2) | (b << 1) | c
    })
}

/// The low [`BITS`] bits of `v` moved to every third bit (bit `i` to bit
/// `3 i`), so that three coordinates interleave by shifts and ors.
fn spread(v: u32) -> u64 {
    let mut x = u64::from(v) & ((1 << BITS) - 1);
    x = (x | x << 32) & 0x001f_0000_0000_ffff;
    x = (x | x << 16) & 0x001f_0000_ff00_00ff;
    x = (x | x << 8) & 0x100f_00f0_0f00_f00f;
    x = (x | x << 4) & 0x10c3_0c30_c30c_30c3;
    (x | x << 2) & 0x1249_2492_4924_9249
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes;

    /// The Hilbert index at a smaller resolution: the key of a cell whose
    /// coordinates are multiples of 2^(BITS - b), shifted down.
    fn coarse_key(c: [u32; 3], b: u32) -> u64 {
        let [x, y, z] = c.map(|x| [x << (BITS - b)]);
        hilbert_keys([x, y, z])[0] >> (3 * (BITS - b))
    }

    #[test]
    fn hilbert_curve_visits_every_cell_once_moving_one_step_at_a_time() {
        for b in 1..=4u32 {
            let n = 1u32 << b;
            let mut by_key = vec![None; (n * n * n) as usize];
            for x in 0..n {
                for y in 0..n {
                    for z in 0..n {
                        let k = coarse_key([x, y, z], b) as usize;
                        assert!(by_key[k].is_none(), "two cells share key {k}");
                        by_key[k] = Some([x, y, z]);
                    }
                }
            }
            let cells: Vec<[u32; 3]> = by_key.into_iter().map(|c| c.unwrap()).collect();
            for w in cells.windows(2) {
                let step: u32 = (0..3).map(|i| w[0][i].abs_diff(w[1][i])).sum();
                assert_eq!(step, 1, "{:?} -> {:?} at {b} bits", w[0], w[1]);
            }
            assert_eq!(cells[0], [0, 0, 0]);
        }
    }

    #[test]
    fn reordered_mesh_is_the_same_surface() {
        let mesh = shapes::icosphere(3).unwrap();
        let r = Reordering::spatial(&mesh);
        let out = r.apply(&mesh).unwrap();
        assert_eq!((out.vertex_count(), out.face_count()), (mesh.vertex_count(), mesh.face_count()));
        for f in out.face_ids() {
            let old = mesh.triangle(r.old_face(f));
            assert_eq!(out.triangle(f), old);
        }
        for v in out.vertex_ids() {
            assert_eq!(r.new_vertex(r.old_vertex(v)), v);
        }
        let back = r.vertex_values_to_input(out.positions()).unwrap();
        assert_eq!(back, mesh.positions());
        let forth = r.vertex_values_from_input(mesh.positions()).unwrap();
        assert_eq!(forth, out.positions());
        let areas = r.face_values_to_input(&crate::geometry::face_areas(&out)).unwrap();
        assert_eq!(areas, crate::geometry::face_areas(&mesh));
        let forth = r.face_values_from_input(&crate::geometry::face_areas(&mesh)).unwrap();
        assert_eq!(forth, crate::geometry::face_areas(&out));
        // Faces are sorted by their smallest vertex in the new order.
        let first: Vec<u32> = out.faces().iter().map(|f| *f.iter().min().unwrap()).collect();
        assert!(first.windows(2).all(|w| w[0] <= w[1]));
    }

    #[test]
    fn spatial_order_shortens_edges_in_memory() {
        // Icosphere levels append midpoints: far apart in memory.
        let mesh = shapes::icosphere(5).unwrap();
        let spread = |m: &TriMesh| -> f64 {
            let c = m.connectivity();
            let total: u64 = c.edges().iter().map(|e| u64::from(e[0].0.abs_diff(e[1].0))).sum();
            total as f64 / c.edges().len() as f64
        };
        let out = Reordering::spatial(&mesh).apply(&mesh).unwrap();
        assert!(spread(&out) < 0.25 * spread(&mesh), "{} vs {}", spread(&out), spread(&mesh));
    }

    #[test]
    fn explicit_orders_are_checked() {
        let mesh = shapes::icosphere(1).unwrap();
        let n = mesh.vertex_count();
        let reversed: Vec<VertexId> = (0..n).rev().map(VertexId::new).collect();
        let r = Reordering::with_vertex_order(&mesh, reversed).unwrap();
        assert_eq!(r.new_vertex(VertexId(0)), VertexId::new(n - 1));
        let repeated = vec![VertexId(0); n];
        assert!(matches!(Reordering::with_vertex_order(&mesh, repeated), Err(MeshError::Dimension(_))));
        let short = vec![VertexId(0)];
        assert!(matches!(Reordering::with_vertex_order(&mesh, short), Err(MeshError::Dimension(_))));
        let other = shapes::icosphere(2).unwrap();
        assert!(matches!(r.apply(&other), Err(MeshError::Dimension(_))));
        assert!(r.vertex_values_to_input(&[1.0]).is_err());
    }

    #[test]
    fn empty_and_flat_meshes() {
        let empty = TriMesh::new(Vec::new(), Vec::new()).unwrap();
        assert_eq!(Reordering::spatial(&empty).apply(&empty).unwrap().vertex_count(), 0);
        let grid = shapes::grid(1.0, 1.0, 4, 4).unwrap(); // flat in z
        let out = Reordering::spatial(&grid).apply(&grid).unwrap();
        assert!((crate::geometry::surface_area(&out) - 1.0).abs() < 1e-12);
        // Coordinates near the largest finite number still get distinct cells.
        let huge =
            TriMesh::new(vec![DVec3::splat(-f64::MAX), DVec3::ZERO, DVec3::splat(f64::MAX)], vec![[0, 1, 2]]).unwrap();
        let r = Reordering::spatial(&huge);
        let cells: Vec<_> = (0..3).map(|v| r.new_vertex(VertexId(v))).collect();
        assert_eq!(cells, [VertexId(0), VertexId(1), VertexId(2)]);
    }
}
