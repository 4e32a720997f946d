//! mesh-kernel and mesh-io operations.

use std::path::Path;

use mesh_io::MeshData;
use mesh_kernel::geometry::{self, NormalWeighting};
use mesh_kernel::operators::{self, IntrinsicOptions, IntrinsicTriangulation, MassKind};
use mesh_kernel::{Reordering, TriMesh};

use super::Operation;

/// Elements of each of the two arrays of [`stream_copy`]: 2 x 256 MB, far
/// beyond any cache.
const STREAM_LEN: usize = 1 << 25;

/// The machine's memory bandwidth as STREAM's "copy" measures it (McCalpin
/// 1995): one array copied into another, 16 bytes moved per element,
/// split between the threads of the pool.
fn stream_copy() -> Operation<'static> {
    use rayon::prelude::*;
    let src: Vec<f64> = (0..STREAM_LEN).map(|i| i as f64).collect();
    let mut dst = vec![1.0; STREAM_LEN];
    Operation::new("stream_copy", move || {
        let chunk = STREAM_LEN.div_ceil(rayon::current_num_threads());
        dst.par_chunks_mut(chunk).zip(src.par_chunks(chunk)).for_each(|(d, s)| d.copy_from_slice(s));
        Ok(dst[STREAM_LEN / 2])
    })
    .moving(16 * STREAM_LEN)
}

/// Elements of [`gather_copy`]: 2^22, 96 MiB of records copied.
const GATHER_LEN: usize = 1 << 22;

/// What memory gives a gather in random order from an array of `n`
/// positions (as many as the mesh has vertices): `dst[i] = src[index[i]]`
/// for [`GATHER_LEN`] random indices below `n`, 52 bytes of records and
/// indices moved per element, split between the threads of the pool. Next
/// to `stream_copy` (every line used in full and foreseen by the
/// processor), it bounds operations that read the positions of vertices
/// scattered in memory: each 24-byte record costs a line fetched on demand,
/// from the cache level that holds `n` positions.
fn gather_copy(n: usize) -> Operation<'static> {
    use rayon::prelude::*;
    let src: Vec<[f64; 3]> = (0..n).map(|i| [i as f64, 0.5, -1.0]).collect();
    let mut rng = mesh_kernel::random::SplitMix64::new(15);
    let index: Vec<u32> = (0..GATHER_LEN).map(|_| rng.below(n) as u32).collect();
    let mut dst = vec![[0.0; 3]; GATHER_LEN];
    Operation::new("gather_copy", move || {
        let chunk = GATHER_LEN.div_ceil(rayon::current_num_threads());
        dst.par_chunks_mut(chunk).zip(index.par_chunks(chunk)).for_each(|(d, ix)| {
            d.iter_mut().zip(ix).for_each(|(d, &i)| *d = src[i as usize]);
        });
        Ok(dst[GATHER_LEN / 2][0])
    })
    .moving(52 * GATHER_LEN)
}

/// Multiply-adds of [`multiply_add`], split between the threads of the pool.
const MULTIPLY_ADDS: usize = 1 << 28;

/// Independent chains `x = x m + a` that [`multiply_add`] runs side by
/// side: 12 SSE2 registers (the x86-64 baseline), enough to hide the
/// latency of a multiply and an add on the processors measured.
const CHAINS: usize = 24;

/// The machine's arithmetic throughput with no memory traffic: each thread
/// of the pool runs its share of [`MULTIPLY_ADDS`] in registers (one
/// [`rayon::broadcast`] call). Next to `stream_copy`, it says what a
/// second thread can add at the time of the run to work bound by
/// arithmetic: on a VM whose vCPUs share a physical core's floating-point
/// units with each other or with other guests, much less than 2x, and
/// varying from run to run.
fn multiply_add() -> Operation<'static> {
    Operation::new("multiply_add", || {
        let rounds = MULTIPLY_ADDS / CHAINS / rayon::current_num_threads();
        Ok(rayon::broadcast(|_| chains(rounds)).iter().sum::<f64>())
    })
}

/// [`CHAINS`] chains of `rounds` multiply-adds each; their sum.
fn chains(rounds: usize) -> f64 {
    let (m, a) = (std::hint::black_box(0.999_999), std::hint::black_box(1e-9));
    let mut x = [[1.0f64; 4]; CHAINS / 4];
    for _ in 0..rounds {
        for quad in &mut x {
            for v in quad {
                *v = *v * m + a;
            }
        }
    }
    x.iter().flatten().sum()
}

/// The least traffic of a per-face operation writing `per_vertex` bytes per
/// vertex: faces (12 bytes) and positions (24 bytes) read once.
pub fn face_pass_bytes(mesh: &TriMesh, per_vertex: usize) -> usize {
    12 * mesh.face_count() + (24 + per_vertex) * mesh.vertex_count()
}

/// The core operations, named as in peer_bench.py where they match.
pub fn operations<'a>(path: &'a Path, data: &'a MeshData) -> Vec<Operation<'a>> {
    let mesh = &data.mesh;
    let (n, e) = (mesh.vertex_count(), mesh.connectivity().edge_count());
    // A CSR matrix with a diagonal and two entries per edge: 8-byte row
    // pointers, column indices and values.
    let csr = 8 * (n + 1) + 16 * (n + 2 * e);
    // Half-edge structure from scratch: faces read; per half-edge its twin
    // (4 bytes) and edge (4 bytes), per vertex one outgoing half-edge (4 bytes).
    let halfedges = 12 * mesh.face_count() + 24 * mesh.face_count() + 4 * n;
    vec![
        stream_copy(),
        gather_copy(n.max(1)),
        multiply_add(),
        Operation::new("read", move || Ok(mesh_io::read(path)?)),
        Operation::on_fresh("connectivity", mesh, |m| {
            let _ = m.connectivity().is_manifold();
            Ok(m)
        }),
        Operation::on_fresh("boundary_loops", mesh, |m| {
            let n = m.connectivity().boundary_loops()?.len();
            Ok((m, n))
        })
        .moving(halfedges),
        Operation::new("normals_area", move || Ok(geometry::vertex_normals(mesh, NormalWeighting::Area)))
            .moving(face_pass_bytes(mesh, 24)),
        Operation::new("cotan_laplacian", move || Ok(operators::cotan_laplacian(mesh)))
            .moving(face_pass_bytes(mesh, 0) + csr),
        Operation::new("mass_voronoi", move || Ok(operators::mass_matrix(mesh, MassKind::MixedVoronoi))),
        Operation::new("reorder_spatial", move || Ok(Reordering::spatial(mesh).apply(mesh)?)),
        Operation::new("intrinsic_delaunay", move || {
            Ok(IntrinsicTriangulation::delaunay(mesh, &IntrinsicOptions::default())?.cotan_laplacian())
        }),
    ]
}
