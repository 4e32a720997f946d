//! Helpers shared by the integration tests.
#![allow(dead_code)]

use mesh_kernel::{glam::DVec3, shapes, TriMesh};
use mesh_wavelet::{subdivide, Scheme, SubdivideOptions};

pub use mesh_testkit::SplitMix64;

/// Reads a shared mesh by file name, `None` when the data folder is absent
/// (see `mesh_testkit::data`).
pub fn real_mesh(name: &str) -> Option<TriMesh> {
    let path = mesh_testkit::shared_file(name)?;
    Some(mesh_io::read(&path).unwrap_or_else(|e| panic!("{name}: {e}")).mesh)
}

/// `mesh` with vertices renumbered by a random permutation, faces shuffled
/// and their corners rotated. Returns the mesh and `new_index[old]`.
pub fn shuffled(mesh: &TriMesh, seed: u64) -> (TriMesh, Vec<u32>) {
    let mut rng = SplitMix64::new(seed);
    let n = mesh.vertex_count();
    let new_index = rng.permutation(n);
    let mut positions = vec![DVec3::ZERO; n];
    for (old, &new) in new_index.iter().enumerate() {
        positions[new as usize] = mesh.positions()[old];
    }
    let order = rng.permutation(mesh.face_count());
    let faces = order
        .iter()
        .map(|&f| {
            let t = mesh.faces()[f as usize].map(|v| new_index[v as usize]);
            let r = rng.below(3);
            [t[r], t[(r + 1) % 3], t[(r + 2) % 3]]
        })
        .collect();
    (TriMesh::new(positions, faces).unwrap(), new_index)
}

/// Largest vertex distance between two meshes with the same vertex count,
/// relative to the largest coordinate magnitude of `a`.
pub fn relative_max_distance(a: &TriMesh, b: &TriMesh) -> f64 {
    assert_eq!(a.vertex_count(), b.vertex_count());
    let scale = a.positions().iter().map(|p| p.abs().max_element()).fold(1e-300, f64::max);
    a.positions().iter().zip(b.positions()).map(|(p, q)| p.distance(*q)).fold(0.0, f64::max) / scale
}

/// A torus base mesh split `levels` times, vertices projected onto the
/// exact torus R = 2, r = 0.5: smooth, with subdivision connectivity.
pub fn smooth_torus(levels: usize) -> TriMesh {
    let base = shapes::torus(2.0, 0.5, 12, 6).unwrap();
    let fine = subdivide(&base, &SubdivideOptions { scheme: Scheme::Midpoint, levels }).unwrap();
    let p = fine
        .positions()
        .iter()
        .map(|p| {
            let u = p.y.atan2(p.x);
            let c = DVec3::new(2.0 * u.cos(), 2.0 * u.sin(), 0.0);
            c + (*p - c).normalize() * 0.5
        })
        .collect();
    TriMesh::new(p, fine.faces().to_vec()).unwrap()
}

/// The icosphere with radius `1 + 0.1 sin(3x) sin(3y) sin(3z)`.
pub fn bumpy_sphere(levels: u32) -> TriMesh {
    let s = shapes::icosphere(levels).unwrap();
    let p = s
        .positions()
        .iter()
        .map(|p| *p * (1.0 + 0.1 * (3.0 * p.x).sin() * (3.0 * p.y).sin() * (3.0 * p.z).sin()))
        .collect();
    TriMesh::new(p, s.faces().to_vec()).unwrap()
}

/// Three triangles on one edge (0, 1): a non-manifold mesh.
pub fn fin_edge() -> TriMesh {
    TriMesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z, DVec3::NEG_Y], vec![[0, 1, 2], [1, 0, 3], [0, 1, 4]])
        .unwrap()
}

/// Base meshes with extraordinary vertices, boundaries and several components.
pub fn base_meshes() -> Vec<(&'static str, TriMesh)> {
    let ico = shapes::icosphere(0).unwrap();
    let tet = TriMesh::new(
        vec![
            DVec3::new(1.0, 1.0, 1.0),
            DVec3::new(1.0, -1.0, -1.0),
            DVec3::new(-1.0, 1.0, -1.0),
            DVec3::new(-1.0, -1.0, 1.0),
        ],
        vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]],
    )
    .unwrap();
    // Two components: an icosahedron and a shifted tetrahedron.
    let mut p = ico.positions().to_vec();
    let mut f = ico.faces().to_vec();
    let off = p.len() as u32;
    p.extend(tet.positions().iter().map(|q| *q + DVec3::new(5.0, 0.0, 0.0)));
    f.extend(tet.faces().iter().map(|t| t.map(|v| v + off)));
    let two = TriMesh::new(p, f).unwrap();
    vec![
        ("icosahedron", ico),
        ("tetrahedron", tet),
        ("cube", shapes::cube(1).unwrap()),
        ("torus", shapes::torus(2.0, 0.5, 5, 3).unwrap()),
        ("disk", shapes::disk(3, 5).unwrap()),
        ("cylinder", shapes::cylinder(1.0, 2.0, 5, 2).unwrap()),
        ("grid", shapes::grid(1.0, 1.0, 3, 2).unwrap()),
        ("two components", two),
    ]
}
