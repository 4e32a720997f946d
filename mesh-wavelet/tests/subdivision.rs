//! Subdivision against ground truth: counts and topology, mesh-kernel's
//! midpoint split, polynomial reproduction of butterfly and Loop on regular
//! grids, Loop limit positions, affine invariance, bad input.

mod common;

use common::{base_meshes, fin_edge, real_mesh, SplitMix64};
use mesh_kernel::{glam::DVec3, shapes, MeshError, TriMesh};
use mesh_wavelet::{rules::loop_beta, subdivide, Scheme, SubdivideOptions, WaveletError};
use proptest::prelude::*;

#[test]
fn counts_topology_and_order() {
    for (name, base) in base_meshes() {
        let c0 = base.connectivity();
        for scheme in Scheme::ALL {
            let mut prev = base.clone();
            for level in 1..=3 {
                let m = subdivide(&base, &SubdivideOptions { scheme, levels: level }).unwrap();
                let (pc, c) = (prev.connectivity(), m.connectivity());
                assert_eq!(m.vertex_count(), prev.vertex_count() + pc.edge_count(), "{name} {scheme}");
                assert_eq!(m.face_count(), 4 * prev.face_count());
                assert!(c.is_manifold());
                assert_eq!(c.euler_characteristic(), c0.euler_characteristic());
                assert_eq!(c.boundary_loop_count(), c0.boundary_loop_count());
                assert_eq!(c.components().count, c0.components().count);
                // Same topology and numbering for every scheme: that of mesh-kernel's midpoint split.
                let (_, faces) = shapes::midpoint_subdivide(&prev);
                assert_eq!(m.faces(), &faces[..], "{name} {scheme} level {level}");
                if scheme.is_interpolating() {
                    assert_eq!(&m.positions()[..prev.vertex_count()], prev.positions());
                }
                prev = subdivide(&prev, &SubdivideOptions { scheme, levels: 1 }).unwrap();
                assert_eq!(prev, m, "one level at a time equals {level} levels at once");
            }
        }
    }
}

#[test]
fn midpoint_is_mesh_kernel_midpoint_split() {
    let m = shapes::cube(2).unwrap();
    let (p, f) = shapes::midpoint_subdivide(&m);
    assert_eq!(
        subdivide(&m, &SubdivideOptions { scheme: Scheme::Midpoint, levels: 1 }).unwrap(),
        TriMesh::new(p, f).unwrap()
    );
}

/// A cubic polynomial in (x, y).
fn cubic(x: f64, y: f64) -> f64 {
    0.3 + 1.1 * x - 0.7 * y + 0.5 * x * x - 0.8 * x * y + 0.25 * y * y + 0.9 * x * x * x - 0.4 * x * x * y
        + 0.6 * x * y * y
        - 0.2 * y * y * y
}

/// The regular grid with z = f(x, y) at its vertices.
fn graph(n: usize, f: impl Fn(f64, f64) -> f64) -> TriMesh {
    let g = shapes::grid(1.0, 1.0, n, n).unwrap();
    let p = g.positions().iter().map(|p| DVec3::new(p.x, p.y, f(p.x, p.y))).collect();
    TriMesh::new(p, g.faces().to_vec()).unwrap()
}

#[test]
fn butterfly_reproduces_cubics_on_regular_grids() {
    // The 8-point butterfly (w = 1/16) and the boundary 4-point rule have
    // cubic precision (Dyn, Levin, Gregory 1990): new vertices land on the
    // cubic wherever the regular masks apply.
    let n = 8;
    let m = graph(n, cubic);
    let s = subdivide(&m, &SubdivideOptions { scheme: Scheme::Butterfly, levels: 1 }).unwrap();
    let h = 1.0 / n as f64;
    let mut checked = (0, 0);
    for p in &s.positions()[m.vertex_count()..] {
        let (dx, dy) = (p.x.min(1.0 - p.x), p.y.min(1.0 - p.y));
        let interior = dx > 2.0 * h && dy > 2.0 * h;
        let boundary = (dx.abs() < 1e-12 && dy > 1.5 * h) || (dy.abs() < 1e-12 && dx > 1.5 * h);
        if interior || boundary {
            assert!((p.z - cubic(p.x, p.y)).abs() < 1e-13, "at ({}, {}): {} vs {}", p.x, p.y, p.z, cubic(p.x, p.y));
            if interior {
                checked.0 += 1
            } else {
                checked.1 += 1
            }
        }
    }
    assert!(checked.0 >= 40 && checked.1 >= 16, "{checked:?}");
}

#[test]
fn loop_reproduces_linear_functions_away_from_corners() {
    let m = graph(6, |x, y| 0.5 + 2.0 * x - 3.0 * y);
    let s = subdivide(&m, &SubdivideOptions { scheme: Scheme::Loop, levels: 2 }).unwrap();
    let mut checked = 0;
    for p in s.positions() {
        let near_corner = (p.x.min(1.0 - p.x) < 0.3) && (p.y.min(1.0 - p.y) < 0.3);
        if !near_corner {
            assert!((p.z - (0.5 + 2.0 * p.x - 3.0 * p.y)).abs() < 1e-13);
            checked += 1;
        }
    }
    assert!(checked > 100);
}

#[test]
fn loop_converges_to_its_limit_positions() {
    // Limit of an interior vertex of valence n (eigen-analysis of the Loop
    // mask): (1 - n w) v + w sum v_i with w = 1 / (n + 3 / (8 beta));
    // boundary vertices follow the cubic B-spline: (v- + 4 v + v+) / 6.
    // The distance shrinks by the subdominant eigenvalue
    // 3/8 + cos(2 pi / n) / 4 per level.
    let ico = shapes::icosphere(0).unwrap();
    let c = ico.connectivity();
    let v0 = mesh_kernel::VertexId(0);
    let n = c.valence(v0);
    let w = 1.0 / (n as f64 + 3.0 / (8.0 * loop_beta(n)));
    let sum: DVec3 = c.neighbors(v0).map(|u| ico.position(u)).sum();
    let limit = (1.0 - n as f64 * w) * ico.position(v0) + w * sum;
    let mut errors = Vec::new();
    for level in 1..=7 {
        let s = subdivide(&ico, &SubdivideOptions { scheme: Scheme::Loop, levels: level }).unwrap();
        errors.push(s.positions()[0].distance(limit));
    }
    let lambda = 3.0 / 8.0 + 0.25 * (std::f64::consts::TAU / n as f64).cos();
    for k in 2..errors.len() {
        let rate = errors[k] / errors[k - 1];
        assert!(rate < lambda * lambda + 1e-3, "level {k}: rate {rate}, lambda^2 {}", lambda * lambda);
    }
    assert!(errors[6] < 1e-5, "{errors:?}");

    let disk = shapes::disk(2, 9).unwrap();
    let loops = disk.connectivity().boundary_loops().unwrap();
    let lp = &loops[0].vertices;
    let (a, b, cc) = (lp[lp.len() - 1], lp[0], lp[1]);
    let limit = (disk.position(a) + 4.0 * disk.position(b) + disk.position(cc)) / 6.0;
    let s = subdivide(&disk, &SubdivideOptions { scheme: Scheme::Loop, levels: 8 }).unwrap();
    assert!(s.positions()[b.idx()].distance(limit) < 1e-5);
}

#[test]
fn loop_stays_in_the_bounding_box_of_real_meshes() {
    // Loop's masks are convex combinations.
    for name in ["npm_bunny.obj", "cgal_holes.off", "cgal_elephant.off"] {
        let Some(m) = real_mesh(name) else { return };
        let bb = mesh_kernel::geometry::bounding_box(&m).unwrap();
        let s = subdivide(&m, &SubdivideOptions { scheme: Scheme::Loop, levels: 1 }).unwrap();
        let c = s.connectivity();
        assert!(c.is_manifold());
        assert_eq!(c.euler_characteristic(), m.connectivity().euler_characteristic());
        let tol = 1e-12 * bb.diagonal();
        assert!(s.positions().iter().all(|p| p.cmpge(bb.min - tol).all() && p.cmple(bb.max + tol).all()), "{name}");
        let b = subdivide(&m, &SubdivideOptions { scheme: Scheme::Butterfly, levels: 1 }).unwrap();
        assert_eq!(&b.positions()[..m.vertex_count()], m.positions());
    }
}

#[test]
fn degenerate_and_isolated_input() {
    if let Some(m) = real_mesh("cgal_degtri_sliding.off") {
        for scheme in Scheme::ALL {
            let s = subdivide(&m, &SubdivideOptions { scheme, levels: 3 }).unwrap();
            assert!(s.positions().iter().all(|p| p.is_finite()));
        }
    }
    // An isolated vertex stays where it is.
    let mut p = shapes::icosphere(0).unwrap().positions().to_vec();
    p.push(DVec3::new(7.0, 8.0, 9.0));
    let m = TriMesh::new(p, shapes::icosphere(0).unwrap().faces().to_vec()).unwrap();
    for scheme in Scheme::ALL {
        let s = subdivide(&m, &SubdivideOptions { scheme, levels: 2 }).unwrap();
        assert_eq!(s.positions()[12], DVec3::new(7.0, 8.0, 9.0));
    }
}

#[test]
fn bad_input_is_a_typed_error() {
    let nonmanifold = fin_edge();
    for scheme in [Scheme::Loop, Scheme::Butterfly] {
        match subdivide(&nonmanifold, &SubdivideOptions { scheme, levels: 1 }) {
            Err(WaveletError::Mesh(MeshError::NonManifold(report))) => assert_eq!(report.edges.len(), 1),
            other => panic!("{other:?}"),
        }
    }
    // The midpoint split is defined on any mesh.
    assert_eq!(
        subdivide(&nonmanifold, &SubdivideOptions { scheme: Scheme::Midpoint, levels: 1 }).unwrap().face_count(),
        12
    );
    let empty = TriMesh::new(vec![DVec3::ZERO], vec![]).unwrap();
    assert!(matches!(
        subdivide(&empty, &SubdivideOptions { scheme: Scheme::Loop, levels: 1 }),
        Err(WaveletError::Mesh(MeshError::Empty))
    ));
    let tri = TriMesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y], vec![[0, 1, 2]]).unwrap();
    assert!(matches!(
        subdivide(&tri, &SubdivideOptions { scheme: Scheme::Loop, levels: 20 }),
        Err(WaveletError::InvalidOption { .. })
    ));
    assert!(matches!(
        subdivide(&tri, &SubdivideOptions { scheme: Scheme::Loop, levels: usize::MAX }),
        Err(WaveletError::InvalidOption { .. })
    ));
    assert_eq!(subdivide(&tri, &SubdivideOptions { scheme: Scheme::Butterfly, levels: 0 }).unwrap(), tri);
    for scheme in Scheme::ALL {
        assert_eq!(subdivide(&tri, &SubdivideOptions { scheme, levels: 2 }).unwrap().face_count(), 16);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// Every mask is affine: subdividing moved points equals moving the
    /// subdivided points.
    #[test]
    fn subdivision_commutes_with_affine_maps(seed in any::<u64>(), which in 0usize..8) {
        let (_, base) = base_meshes().swap_remove(which);
        let mut rng = SplitMix64::new(seed);
        let cols: Vec<DVec3> = (0..4).map(|_| DVec3::new(rng.signed(), rng.signed(), rng.signed())).collect();
        let map = |p: DVec3| cols[0] * p.x + cols[1] * p.y + cols[2] * p.z + cols[3];
        let moved = TriMesh::new(base.positions().iter().map(|&p| map(p)).collect(), base.faces().to_vec()).unwrap();
        for scheme in Scheme::ALL {
            let a = subdivide(&moved, &SubdivideOptions { scheme, levels: 2 }).unwrap();
            let b = subdivide(&base, &SubdivideOptions { scheme, levels: 2 }).unwrap();
            for (p, q) in a.positions().iter().zip(b.positions()) {
                prop_assert!(p.distance(map(*q)) < 1e-12);
            }
        }
    }
}
