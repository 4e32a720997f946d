//! Shared helpers of the integration tests: the shared meshes (read without
//! mesh-io, so these tests do not depend on it) and ground-truth comparisons.
#![allow(dead_code)]

use glam::{DVec2, DVec3};
use mesh_kernel::TriMesh;

/// A shared mesh read with the test kit's minimal reader, `None` when the
/// data is absent (see `mesh_testkit::data`).
pub fn read(name: &str) -> Option<TriMesh> {
    let raw = mesh_testkit::read_raw(&mesh_testkit::shared_file(name)?).unwrap_or_else(|e| panic!("{e}"));
    Some(TriMesh::new(raw.positions.into_iter().map(DVec3::from).collect(), raw.faces).unwrap())
}

/// Largest distance between `a` and the best similarity image of `b`
/// (least-squares fit a z + c over complex numbers), relative to the
/// diameter of `a`.
pub fn similarity_residual(a: &[DVec2], b: &[DVec2]) -> f64 {
    let n = a.len() as f64;
    let (ca, cb) = (a.iter().sum::<DVec2>() / n, b.iter().sum::<DVec2>() / n);
    // a - ca = s (b - cb), s complex: s = sum conj(b') a' / sum |b'|^2.
    let (mut re, mut im, mut norm) = (0.0, 0.0, 0.0);
    for (p, q) in a.iter().zip(b) {
        let (p, q) = (*p - ca, *q - cb);
        re += q.x * p.x + q.y * p.y;
        im += q.x * p.y - q.y * p.x;
        norm += q.length_squared();
    }
    let s = DVec2::new(re / norm, im / norm);
    let diameter = a.iter().map(|p| p.distance(ca)).fold(0.0, f64::max) * 2.0;
    a.iter()
        .zip(b)
        .map(|(p, q)| {
            let q = *q - cb;
            let fitted = DVec2::new(s.x * q.x - s.y * q.y, s.x * q.y + s.y * q.x) + ca;
            p.distance(fitted)
        })
        .fold(0.0, f64::max)
        / diameter
}
