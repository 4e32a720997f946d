//! Gaussian curvature by angle defect: Gauss-Bonnet on every manifold mesh,
//! convergence to the analytic curvature, robustness.

mod common;

use std::f64::consts::{PI, TAU};

use mesh_curvature::{gaussian_curvature, GaussianOptions, MassKind, VertexStatus};
use mesh_kernel::glam::DVec3;
use mesh_kernel::{shapes, TriMesh};
use proptest::prelude::*;

fn gauss_bonnet_gap(mesh: &TriMesh) -> f64 {
    let k = gaussian_curvature(mesh, &GaussianOptions::default()).unwrap();
    let chi = mesh.connectivity().euler_characteristic() as f64;
    (k.total() - TAU * chi).abs()
}

#[test]
fn gauss_bonnet_on_every_shape() {
    let shapes = [
        shapes::icosphere(4).unwrap(),
        shapes::uv_sphere(2.0, 24, 12).unwrap(),
        shapes::torus(2.0, 0.5, 64, 16).unwrap(),
        shapes::cylinder(1.0, 2.0, 32, 8).unwrap(),
        shapes::grid(1.0, 2.0, 7, 5).unwrap(),
        shapes::disk(8, 3).unwrap(),
        shapes::cube(4).unwrap(),
    ];
    for m in &shapes {
        assert!(gauss_bonnet_gap(m) < 1e-10, "{m:?}: {}", gauss_bonnet_gap(m));
    }
}

#[test]
fn gauss_bonnet_on_every_data_mesh() {
    for (name, m) in common::data_meshes() {
        assert!(m.connectivity().is_manifold(), "{name}");
        let gap = gauss_bonnet_gap(&m);
        assert!(gap < 1e-10, "{name}: sum K + sum k_g - 2 pi chi = {gap}");
        let k = gaussian_curvature(&m, &GaussianOptions::default()).unwrap();
        assert!(k.pointwise.iter().chain(&k.integrated).chain(&k.geodesic).all(|x| x.is_finite()), "{name}");
    }
}

#[test]
fn boundary_defect_is_geodesic_curvature() {
    // A flat disk: K = 0 inside, and the boundary polygon turns by 2 pi.
    let m = shapes::disk(6, 9).unwrap();
    let k = gaussian_curvature(&m, &GaussianOptions::default()).unwrap();
    for v in 0..m.vertex_count() {
        match k.status[v] {
            VertexStatus::Valid => assert!(k.integrated[v].abs() < 1e-12 && k.geodesic[v] == 0.0),
            VertexStatus::Boundary => assert_eq!(k.integrated[v], 0.0),
            s => panic!("unexpected status {s:?}"),
        }
    }
    let turning: f64 = k.geodesic.iter().sum();
    assert!((turning - TAU).abs() < 1e-12, "{turning}");
}

#[test]
fn cone_apex_defect_is_exact() {
    // Apex of a cone over a regular n-gon of half-angle a: the angle sum is
    // n times the apex angle of each face, the defect 2 pi - sum.
    let n = 7;
    let mut p = vec![DVec3::new(0.0, 0.0, 1.0)];
    for i in 0..n {
        let t = TAU * i as f64 / n as f64;
        p.push(DVec3::new(t.cos(), t.sin(), 0.0));
    }
    p.push(DVec3::new(0.0, 0.0, -1.0));
    let mut faces = Vec::new();
    for i in 0..n as u32 {
        faces.push([0, 1 + i, 1 + (i + 1) % n as u32]);
        faces.push([n as u32 + 1, 1 + (i + 1) % n as u32, 1 + i]);
    }
    let m = TriMesh::new(p.clone(), faces).unwrap();
    let k = gaussian_curvature(&m, &GaussianOptions::default()).unwrap();
    let (a, b) = (p[1] - p[0], p[2] - p[0]);
    let apex = a.angle_between(b);
    assert!((k.integrated[0] - (TAU - n as f64 * apex)).abs() < 1e-14);
    assert!((k.total() - 4.0 * PI).abs() < 1e-12);
}

#[test]
fn pointwise_curvature_converges_on_the_torus() {
    // Regular grid: the angle defect over the mixed area converges at O(h^2).
    let mut prev = None;
    for (nu, nv) in [(64, 16), (128, 32), (256, 64)] {
        let (m, truth) = common::torus(nu, nv);
        let k = gaussian_curvature(&m, &GaussianOptions::default()).unwrap();
        let err = (0..m.vertex_count()).map(|i| (k.pointwise[i] - truth.k1[i] * truth.k2[i]).abs()).fold(0.0, f64::max);
        if let Some(p) = prev {
            let order = common::order(p, err, 2.0);
            assert!(order > 1.8, "order {order} ({p} -> {err})");
        }
        prev = Some(err);
    }
    assert!(prev.unwrap() < 1e-3, "{prev:?}");
}

#[test]
fn sphere_curvature_with_both_areas() {
    // The mixed Voronoi area is the one the angle defect integrates over;
    // barycentric areas are off by the triangles' irregularity (15% on the
    // icosphere's non-uniform triangles) but sum to the same total.
    let m = shapes::icosphere(5).unwrap();
    let worst = |area| {
        let k = gaussian_curvature(&m, &GaussianOptions { area }).unwrap();
        assert!(k.status.iter().all(|s| s.is_valid()));
        let total_area: f64 = k.area.iter().sum();
        assert!((total_area - mesh_kernel::geometry::surface_area(&m)).abs() < 1e-12);
        k.pointwise.iter().map(|x| (x - 1.0).abs()).fold(0.0, f64::max)
    };
    let (mixed, barycentric) = (worst(MassKind::MixedVoronoi), worst(MassKind::Barycentric));
    assert!(mixed < 5e-4, "{mixed}");
    assert!(barycentric < 0.2 && barycentric > 10.0 * mixed, "{barycentric}");
}

#[test]
fn degenerate_and_nonmanifold_input_stays_finite() {
    // Zero-area faces (collinear and coincident points), a bow-tie vertex,
    // an edge with three faces, an isolated vertex.
    let p = vec![
        DVec3::ZERO,
        DVec3::X,
        DVec3::new(2.0, 0.0, 0.0),
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(0.0, -1.0, 0.3),
        DVec3::new(5.0, 5.0, 5.0),
    ];
    let faces = vec![[0, 1, 2], [0, 2, 3], [2, 4, 3], [0, 1, 5], [1, 0, 3], [3, 5, 0]];
    let m = TriMesh::new(p, faces).unwrap();
    let k = gaussian_curvature(&m, &GaussianOptions::default()).unwrap();
    assert!(k.integrated.iter().chain(&k.pointwise).chain(&k.geodesic).all(|x| x.is_finite()));
    assert_eq!(k.status[6], VertexStatus::Isolated);
    assert_eq!(k.pointwise[6], 0.0);
    assert!(k.status.contains(&VertexStatus::NonManifold));
}

#[test]
fn empty_mesh() {
    let m = TriMesh::new(vec![], vec![]).unwrap();
    let k = gaussian_curvature(&m, &GaussianOptions::default()).unwrap();
    assert!(k.integrated.is_empty() && k.total() == 0.0);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Gauss-Bonnet holds to rounding whatever the geometry, including
    /// folded, self-intersecting and nearly degenerate embeddings.
    #[test]
    fn gauss_bonnet_survives_any_embedding(
        seed in 0u64..1000,
        amount in 0.0f64..3.0,
        shape in 0usize..4,
    ) {
        let base = match shape {
            0 => shapes::icosphere(2).unwrap(),
            1 => shapes::torus(2.0, 0.5, 12, 6).unwrap(),
            2 => shapes::cylinder(1.0, 1.0, 10, 4).unwrap(),
            _ => shapes::disk(4, seed).unwrap(),
        };
        let mut state = seed.wrapping_add(1);
        let mut rnd = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let p = base.positions().iter().map(|p| *p + amount * DVec3::new(rnd(), rnd(), rnd())).collect();
        let m = TriMesh::new(p, base.faces().to_vec()).unwrap();
        let gap = gauss_bonnet_gap(&m);
        prop_assert!(gap < 1e-10, "gap {}", gap);
    }

    /// Collapsing vertices onto each other (zero-length edges, zero-area
    /// faces) keeps every value finite and Gauss-Bonnet exact.
    #[test]
    fn collapsed_vertices(seed in 0u64..1000, collapse in 1usize..20) {
        let base = shapes::icosphere(1).unwrap();
        let mut p = base.positions().to_vec();
        let n = p.len();
        for k in 0..collapse {
            let (a, b) = ((seed as usize + 7 * k) % n, (seed as usize * 3 + 11 * k + 1) % n);
            p[a] = p[b];
        }
        let m = TriMesh::new(p, base.faces().to_vec()).unwrap();
        let k = gaussian_curvature(&m, &GaussianOptions::default()).unwrap();
        prop_assert!(k.integrated.iter().chain(&k.pointwise).all(|x| x.is_finite()));
        prop_assert!((k.total() - 4.0 * PI).abs() < 1e-10);
    }
}

#[test]
fn every_vertex_of_a_large_mesh_gets_its_own_values() {
    // Past several chunks of the per-vertex pass: a closed sphere, a flat
    // grid with a boundary, a zero-area face and an isolated vertex, each
    // vertex checked against its kind, the lumped mass and the geometry.
    let sphere = shapes::icosphere(6).unwrap();
    let grid = shapes::grid(1.0, 1.0, 199, 199).unwrap();
    let mut positions = sphere.positions().to_vec();
    let mut faces = sphere.faces().to_vec();
    let offset = positions.len() as u32;
    positions.extend(grid.positions().iter().map(|p| *p + DVec3::new(5.0, 0.0, 0.0)));
    faces.extend(grid.faces().iter().map(|f| f.map(|v| v + offset)));
    let flat = positions.len() as u32;
    positions.extend([DVec3::new(9.0, 0.0, 0.0); 3]);
    faces.push([flat, flat + 1, flat + 2]);
    positions.push(DVec3::new(-9.0, 0.0, 0.0));
    let m = TriMesh::new(positions, faces).unwrap();
    assert!(m.vertex_count() > 80_000);
    let k = gaussian_curvature(&m, &GaussianOptions::default()).unwrap();
    let mass = m.geometry().lumped_mass(MassKind::default());
    let kinds = m.connectivity().vertex_kinds();
    let (mut interior, mut boundary, mut turning) = (0, 0, 0.0);
    for v in 0..m.vertex_count() {
        assert!((k.area[v] - mass[v]).abs() <= 1e-12 * mass[v].max(1e-300), "vertex {v}");
        let on_grid = v >= offset as usize && v < flat as usize;
        match k.status[v] {
            VertexStatus::Valid => {
                interior += 1;
                assert_eq!(kinds[v], mesh_kernel::VertexKind::Interior);
                assert!(k.area[v] > 0.0 && k.pointwise[v] == k.integrated[v] / k.area[v]);
                // 4 pi over the sphere's vertices, 0 on the flat grid.
                assert!(if on_grid { k.integrated[v].abs() < 1e-12 } else { k.integrated[v] > 0.0 }, "vertex {v}");
            }
            VertexStatus::Boundary => {
                assert!(k.integrated[v] == 0.0 && k.pointwise[v] == 0.0 && k.geodesic[v].is_finite(), "vertex {v}");
                if on_grid {
                    boundary += 1;
                    turning += k.geodesic[v];
                } else {
                    // The zero-area face's corners: a boundary of their own.
                    assert!(v >= flat as usize && k.area[v] == 0.0, "vertex {v}");
                }
            }
            VertexStatus::Isolated => assert_eq!(v, m.vertex_count() - 1),
            s => panic!("vertex {v}: {s:?}"),
        }
    }
    assert_eq!(interior, sphere.vertex_count() + 198 * 198);
    assert_eq!(boundary, 4 * 199);
    assert!((turning - TAU).abs() < 1e-10, "{turning}");
}
