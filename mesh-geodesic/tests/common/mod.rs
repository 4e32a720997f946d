//! Test helpers: the real meshes of `../shared/data` (read with a minimal
//! OFF / OBJ reader, so these tests do not depend on another crate's state)
//! and ground truth on analytic shapes.
#![allow(dead_code)]

use std::path::{Path, PathBuf};

use mesh_kernel::glam::DVec3;
use mesh_kernel::{TriMesh, VertexId};

/// The shared data folder, or `None` (with a message) when it is absent.
pub fn data_dir() -> Option<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/data");
    if dir.is_dir() {
        Some(dir)
    } else {
        eprintln!("skipping: {} not found", dir.display());
        None
    }
}

/// Every mesh file of the shared data folder, by name.
pub fn data_meshes() -> Vec<(String, TriMesh)> {
    let Some(dir) = data_dir() else { return Vec::new() };
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.file_name().to_string_lossy().into_owned()))
        .filter(|n| n.ends_with(".off") || n.ends_with(".obj"))
        .collect();
    names.sort();
    names.into_iter().map(|n| (n.clone(), read_mesh(&dir.join(&n)))).collect()
}

/// Reads a triangle (or polygon, fan-triangulated) OFF or OBJ file.
pub fn read_mesh(path: &Path) -> TriMesh {
    let text = std::fs::read_to_string(path).unwrap();
    let mut positions = Vec::new();
    let mut faces = Vec::new();
    let fan = |idx: &[u32], faces: &mut Vec<[u32; 3]>| {
        for k in 1..idx.len().saturating_sub(1) {
            faces.push([idx[0], idx[k], idx[k + 1]]);
        }
    };
    if path.extension().is_some_and(|e| e == "off") {
        let mut tokens = text.lines().map(|l| l.split('#').next().unwrap_or("")).flat_map(str::split_whitespace);
        assert_eq!(tokens.next(), Some("OFF"));
        let mut num = || tokens.next().unwrap().parse::<f64>().unwrap();
        let (nv, nf, _) = (num() as usize, num() as usize, num());
        for _ in 0..nv {
            positions.push(DVec3::new(num(), num(), num()));
        }
        for _ in 0..nf {
            let k = num() as usize;
            let idx: Vec<u32> = (0..k).map(|_| num() as u32).collect();
            fan(&idx, &mut faces);
        }
    } else {
        for line in text.lines() {
            let mut it = line.split_whitespace();
            match it.next() {
                Some("v") => {
                    let c: Vec<f64> = it.take(3).map(|t| t.parse().unwrap()).collect();
                    positions.push(DVec3::new(c[0], c[1], c[2]));
                }
                Some("f") => {
                    let idx: Vec<u32> = it.map(|t| t.split('/').next().unwrap().parse::<u32>().unwrap() - 1).collect();
                    fan(&idx, &mut faces);
                }
                _ => {}
            }
        }
    }
    TriMesh::new(positions, faces).unwrap()
}

/// Two meshes side by side as one (the second's indices shifted), plus
/// `isolated` unreferenced vertices at the end.
pub fn union(a: &TriMesh, b: &TriMesh, isolated: usize) -> TriMesh {
    let mut positions = a.positions().to_vec();
    positions.extend(b.positions().iter().map(|p| *p + DVec3::new(10.0, 0.0, 0.0)));
    let shift = a.vertex_count() as u32;
    let mut faces = a.faces().to_vec();
    faces.extend(b.faces().iter().map(|f| f.map(|v| v + shift)));
    positions.extend((0..isolated).map(|i| DVec3::new(-5.0, i as f64, 0.0)));
    TriMesh::new(positions, faces).unwrap()
}

/// Great-circle distance on the unit sphere from vertex `source`.
pub fn sphere_truth(mesh: &TriMesh, source: VertexId) -> Vec<f64> {
    let p0 = mesh.position(source).normalize();
    mesh.positions().iter().map(|p| p.normalize().dot(p0).clamp(-1.0, 1.0).acos()).collect()
}

/// Largest and mean absolute difference.
pub fn errors(d: &[f64], truth: &[f64]) -> (f64, f64) {
    let (mut max, mut sum) = (0.0f64, 0.0);
    for (a, b) in d.iter().zip(truth) {
        let e = (a - b).abs();
        max = max.max(e);
        sum += e;
    }
    (max, sum / d.len() as f64)
}

/// Convergence order between two refinements of ratio 2 in mesh size.
pub fn order(coarse: f64, fine: f64) -> f64 {
    (coarse / fine).log2()
}
