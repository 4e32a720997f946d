//! Shared test meshes.
#![allow(dead_code)]

use mesh_io::MeshData;
use mesh_kernel::glam::{DVec2, DVec3};
use mesh_kernel::TriMesh;

/// An `n x n` vertex grid over `[0, 1]^2` with a bump in z, coordinates that
/// are exact in `f32` (multiples of 1/64), and every attribute filled in
/// with values each format stores exactly (colours are multiples of 1/255).
pub fn grid(n: u32) -> MeshData {
    let mut positions = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let (x, y) = (f64::from(i) / 64.0, f64::from(j) / 64.0);
            positions.push(DVec3::new(x, y, f64::from((i * j) % 7) / 64.0));
        }
    }
    let mut faces = Vec::new();
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            let v = j * n + i;
            faces.push([v, v + 1, v + n + 1]);
            faces.push([v, v + n + 1, v + n]);
        }
    }
    let nv = positions.len();
    let mut data = MeshData::new(TriMesh::new(positions.clone(), faces).unwrap());
    data.normals = Some((0..nv).map(|i| DVec3::new(0.0, (i % 3) as f64 * 0.5, 1.0)).collect());
    data.uvs = Some(positions.iter().map(|p| DVec2::new(p.x, p.y)).collect());
    data.colors = Some((0..nv).map(|i| [(i % 256) as f32 / 255.0, 0.0, 1.0, 1.0]).collect());
    data.scalars = vec![
        ("gaussian".into(), (0..nv).map(|i| i as f64 * 0.125).collect()),
        ("mean".into(), (0..nv).map(|i| -(i as f64) / 4.0).collect()),
    ];
    data.vectors = vec![("d1".into(), (0..nv).map(|i| DVec3::new(1.0, i as f64 / 8.0, -0.5)).collect())];
    data.labels = vec![("segment".into(), (0..nv).map(|i| (i % 5) as i64).collect())];
    let nf = data.mesh.face_count();
    data.face_scalars = vec![("distortion".into(), (0..nf).map(|f| 1.0 + f as f64 / 16.0).collect())];
    data.face_vectors = vec![("gradient".into(), (0..nf).map(|f| DVec3::new(0.5, -(f as f64), 2.0)).collect())];
    data.face_labels = vec![("chart".into(), (0..nf).map(|f| (f / 3) as i64 - 1).collect())];
    data
}

/// Per-corner texture coordinates with a seam: every face's own layout.
pub fn corner_uvs(data: &MeshData) -> Vec<[DVec2; 3]> {
    (0..data.mesh.face_count())
        .map(|f| {
            let s = (f % 4) as f64 / 4.0;
            [DVec2::new(s, 0.0), DVec2::new(s + 0.25, 0.0), DVec2::new(s, 0.25)]
        })
        .collect()
}

/// A mesh whose coordinates use all 53 bits of the mantissa.
pub fn irrational(n: u32) -> MeshData {
    let mut data = grid(n);
    let p: Vec<DVec3> =
        data.mesh.positions().iter().map(|p| *p * std::f64::consts::PI + DVec3::splat(1.0 / 3.0)).collect();
    data.mesh.set_positions(p).unwrap();
    data.scalars[0].1.iter_mut().for_each(|x| *x = x.sqrt() * std::f64::consts::E);
    data
}

/// Each face as its three corner positions, in a canonical order, so that
/// meshes equal up to vertex numbering compare equal.
pub fn triangle_soup(mesh: &TriMesh) -> Vec<[[u64; 3]; 3]> {
    let mut soup: Vec<[[u64; 3]; 3]> = mesh
        .faces()
        .iter()
        .map(|f| {
            let mut t = f.map(|v| mesh.positions()[v as usize].to_array().map(f64::to_bits));
            let first = (0..3).min_by_key(|&k| t[k]).unwrap_or(0);
            t.rotate_left(first);
            t
        })
        .collect();
    soup.sort_unstable();
    soup
}
