//! Shared helpers of the integration tests: a minimal OFF / OBJ reader for
//! the meshes in ../shared/data (tests must not depend on mesh-io) and
//! ground-truth comparisons.
#![allow(dead_code)]

use std::path::PathBuf;

use glam::{DVec2, DVec3};
use mesh_kernel::TriMesh;

/// The shared data folder, or `None` (with a message) when absent.
pub fn data_dir() -> Option<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../shared/data");
    if dir.is_dir() {
        Some(dir)
    } else {
        eprintln!("skipping: {} not found", dir.display());
        None
    }
}

/// Reads a triangle OFF or OBJ file (blank lines and repeated spaces allowed).
pub fn read(name: &str) -> Option<TriMesh> {
    let text = std::fs::read_to_string(data_dir()?.join(name)).ok()?;
    let mut positions = Vec::new();
    let mut faces = Vec::new();
    if name.ends_with(".off") {
        let mut tokens = text.lines().filter(|l| !l.starts_with('#')).flat_map(|l| l.split_whitespace());
        assert_eq!(tokens.next(), Some("OFF"));
        let mut num = || tokens.next().and_then(|t| t.parse::<f64>().ok()).unwrap();
        let (nv, nf, _) = (num() as usize, num() as usize, num());
        for _ in 0..nv {
            positions.push(DVec3::new(num(), num(), num()));
        }
        for _ in 0..nf {
            assert_eq!(num() as usize, 3);
            faces.push([num() as u32, num() as u32, num() as u32]);
        }
    } else {
        for line in text.lines() {
            let mut t = line.split_whitespace();
            match t.next() {
                Some("v") => {
                    let c: Vec<f64> = t.take(3).map(|x| x.parse().unwrap()).collect();
                    positions.push(DVec3::new(c[0], c[1], c[2]));
                }
                Some("f") => {
                    let c: Vec<u32> = t.map(|x| x.split('/').next().unwrap().parse::<u32>().unwrap() - 1).collect();
                    faces.push([c[0], c[1], c[2]]);
                }
                _ => {}
            }
        }
    }
    Some(TriMesh::new(positions, faces).unwrap())
}

/// Every mesh of the data folder with its file name.
pub const DATA: &[&str] = &[
    "cgal_nefertiti.off",
    "cgal_mushroom.off",
    "cgal_elephant.off",
    "cgal_fandisk.off",
    "npm_bunny.obj",
    "cgal_holes.off",
    "cgal_degtri_sliding.off",
];

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
