//! The atlas's invariants, measured on its corner UVs: every face has finite
//! UVs in [0, 1]^2 inside its chart's box, no two chart boxes meet, every
//! face belongs to one chart, and Tutte never flips or collapses a face
//! (zero-area surface faces included). On the shared meshes and on random
//! collections of shapes of very different sizes with a zero-area piece.

mod common;

use glam::{DVec2, DVec3};
use mesh_kernel::{shapes, TriMesh};
use mesh_param::{atlas, Atlas, AtlasOptions, ParamMethod, UvRect};
use proptest::prelude::*;

/// Checks the invariants; returns the number of flipped and collapsed faces
/// (exact sign of the determinant of each face's corner UVs).
fn check(mesh: &TriMesh, a: &Atlas) -> (usize, usize) {
    assert_eq!(a.corner_uvs.len(), mesh.face_count());
    let unit = UvRect { min: DVec2::ZERO, max: DVec2::ONE };
    for (f, t) in a.corner_uvs.iter().enumerate() {
        let rect = a.charts[a.face_chart[f] as usize].rect;
        assert!(t.iter().all(|q| q.is_finite() && unit.contains(*q) && rect.contains(*q)), "face {f}: {t:?}");
    }
    for (i, c) in a.charts.iter().enumerate() {
        for d in &a.charts[i + 1..] {
            assert!(!c.rect.meets(&d.rect), "{:?} meets {:?}", c.rect, d.rect);
        }
    }
    let covered: usize = a.charts.iter().map(|c| c.faces.len()).sum();
    assert_eq!(covered, mesh.face_count());
    let det = |t: &[DVec2; 3]| (t[1] - t[0]).perp_dot(t[2] - t[0]);
    let flipped = a.corner_uvs.iter().filter(|t| det(t) < 0.0).count();
    let collapsed = a.corner_uvs.iter().filter(|t| det(t) == 0.0).count();
    (flipped, collapsed)
}

fn options(method: ParamMethod, split: bool) -> AtlasOptions {
    AtlasOptions {
        method,
        max_chart_faces: split.then_some(500),
        max_area_distortion: split.then_some(2.0),
        ..AtlasOptions::default()
    }
}

#[test]
fn shared_meshes() {
    for name in mesh_testkit::data::SHARED_MESHES.map(|m| m.name) {
        let Some(mesh) = common::read(name) else { return };
        for method in [ParamMethod::Tutte, ParamMethod::Harmonic, ParamMethod::Lscm] {
            for split in [false, true] {
                let a =
                    atlas(&mesh, &options(method, split)).unwrap_or_else(|e| panic!("{name} {}: {e}", method.name()));
                let (flipped, collapsed) = check(&mesh, &a);
                if method == ParamMethod::Tutte {
                    assert_eq!((flipped, collapsed), (0, 0), "{name} split {split}");
                    assert_eq!(a.summary.distortion.flipped_faces, 0, "{name}");
                }
                if split {
                    for c in &a.charts {
                        let d = c.distortion.area_distortion_mean;
                        assert!(d <= 2.0 + 1e-9 || c.faces.len() == 1, "{name} {}: {d}", method.name());
                    }
                }
            }
        }
    }
}

/// Shape `kind` (0 sphere, 1 torus, 2 disk, 3 cylinder, 4 zero-area strip)
/// scaled by `scale`.
fn shape(kind: u8, scale: f64) -> TriMesh {
    let mut m = match kind {
        0 => shapes::icosphere(2),
        1 => shapes::torus(2.0, 0.5, 12, 6),
        2 => shapes::disk(4, 3),
        3 => shapes::cylinder(1.0, 3.0, 10, 4),
        _ => TriMesh::new((0..4).map(|i| DVec3::new(i as f64, 0.0, 0.0)).collect(), vec![[0, 1, 2], [0, 2, 3]]),
    }
    .unwrap();
    m.positions_mut().iter_mut().for_each(|p| *p *= scale);
    m
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]
    #[test]
    fn random_collections(parts in prop::collection::vec((0u8..5, -6i32..4), 1..6), split in any::<bool>()) {
        let (mut p, mut f) = (Vec::new(), Vec::new());
        for (k, &(kind, exponent)) in parts.iter().enumerate() {
            let m = shape(kind, 10f64.powi(exponent));
            let n = p.len() as u32;
            p.extend(m.positions().iter().map(|q| *q + DVec3::new(1e4 * k as f64, 0.0, 0.0)));
            f.extend(m.faces().iter().map(|t| t.map(|v| v + n)));
        }
        let mesh = TriMesh::new(p, f).unwrap();
        for method in [ParamMethod::Tutte, ParamMethod::Harmonic, ParamMethod::Lscm] {
            let a = atlas(&mesh, &options(method, split)).unwrap();
            let (flipped, collapsed) = check(&mesh, &a);
            if method == ParamMethod::Tutte {
                prop_assert_eq!((flipped, collapsed), (0, 0));
            }
            let zero_area = parts.iter().filter(|x| x.0 == 4).count();
            prop_assert_eq!(a.summary.zero_area_charts, zero_area);
        }
    }
}
