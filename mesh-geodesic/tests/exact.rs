//! Exact polyhedral geodesics against ground truth: straight lines on flat
//! meshes, unfoldings on the cube, MMP (pygeodesic) on the icosphere, bounds
//! by the chord and by Dijkstra on every shared mesh, and the metric
//! invariants (exact symmetry) on random perturbed meshes.

mod common;

use mesh_geodesic::{dijkstra, exact_distance, fmm_distance, ExactOptions, GeodesicError};
use mesh_kernel::glam::DVec3;
use mesh_kernel::{shapes, MeshError, TriMesh, VertexId};
use proptest::prelude::*;

fn exact(mesh: &TriMesh, sources: &[VertexId]) -> Vec<f64> {
    exact_distance(mesh, sources, &ExactOptions::default()).unwrap()
}

fn max_error(d: &[f64], truth: impl Fn(DVec3) -> f64, mesh: &TriMesh) -> f64 {
    mesh.positions().iter().zip(d).map(|(p, x)| (x - truth(*p)).abs()).fold(0.0, f64::max)
}

#[test]
fn flat_meshes_give_straight_lines() {
    // A regular grid (flat interior vertices) and a jittered disk (irregular,
    // partly obtuse triangles, convex boundary): the distance is Euclidean.
    let grid = shapes::grid(2.0, 1.0, 16, 8).unwrap();
    let disk = shapes::disk(12, 3).unwrap();
    for (name, mesh) in [("grid", grid), ("disk", disk)] {
        for s in [0, mesh.vertex_count() / 2, mesh.vertex_count() - 1] {
            let p0 = mesh.position(VertexId::new(s));
            let d = exact(&mesh, &[VertexId::new(s)]);
            let err = max_error(&d, |p| p.distance(p0), &mesh);
            assert!(err < 1e-12, "{name} source {s}: {err:e}");
        }
    }
}

#[test]
fn multiple_sources_give_the_nearest() {
    let mesh = shapes::grid(1.0, 1.0, 10, 10).unwrap();
    let sources = [VertexId(0), VertexId(60), VertexId(120)];
    let d = exact(&mesh, &sources);
    let err =
        max_error(&d, |p| sources.iter().map(|s| p.distance(mesh.position(*s))).fold(f64::INFINITY, f64::min), &mesh);
    assert!(err < 1e-12, "{err:e}");
}

/// Geodesic distance on the surface of [-1, 1]^3 from the corner (-1, -1, -1)
/// by unfolding: straight on the three faces through the corner; on a far
/// face through one of the two near faces along its edges.
fn cube_corner_truth(p: DVec3) -> f64 {
    let q = (p + DVec3::ONE).to_array();
    if q.iter().any(|x| x.abs() < 1e-12) {
        return DVec3::from_array(q).length();
    }
    let mut best = f64::INFINITY;
    for i in 0..3 {
        if (q[i] - 2.0).abs() < 1e-12 {
            let (a, b) = (q[(i + 1) % 3], q[(i + 2) % 3]);
            best = best.min((2.0 + a).hypot(b)).min((2.0 + b).hypot(a));
        }
    }
    best
}

#[test]
fn cube_distances_match_unfoldings() {
    for n in [1, 3, 6] {
        let mesh = shapes::cube(n).unwrap();
        let corner = mesh.positions().iter().position(|p| (*p + DVec3::ONE).length() < 1e-12).unwrap();
        let d = exact(&mesh, &[VertexId::new(corner)]);
        let err = max_error(&d, cube_corner_truth, &mesh);
        assert!(err < 1e-12, "cube({n}): {err:e}");
    }
}

fn fixture(name: &str) -> Vec<f64> {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures").join(name);
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .filter(|l| !l.starts_with('#'))
        .map(|l| l.trim().parse().unwrap())
        .collect()
}

#[test]
fn convex_polyhedron_matches_mmp_and_is_bounded() {
    // tests/fixtures/icosphere3_exact_v0.txt: pygeodesic (Kirsanov's MMP)
    // on the same mesh written by `mesh generate --shape icosphere --res 3`.
    let mesh = shapes::icosphere(3).unwrap();
    let truth = fixture("icosphere3_exact_v0.txt");
    assert_eq!(truth.len(), mesh.vertex_count());
    let d = exact(&mesh, &[VertexId(0)]);
    let fmm = fmm_distance(&mesh, &[VertexId(0)], &Default::default()).unwrap();
    let p0 = mesh.position(VertexId(0));
    for (i, p) in mesh.positions().iter().enumerate() {
        assert!((d[i] - truth[i]).abs() < 1e-9, "vertex {i}: {} vs MMP {}", d[i], truth[i]);
        assert!(d[i] >= p.distance(p0) - 1e-12, "vertex {i}: below the chord");
        assert!(d[i] <= fmm[i] + 1e-12, "vertex {i}: {} above FMM {}", d[i], fmm[i]);
    }
}

#[test]
fn every_data_mesh_lies_between_chord_and_edge_paths() {
    for (name, mesh) in common::data_meshes() {
        let s = VertexId(0);
        match exact_distance(&mesh, &[s], &ExactOptions::default()) {
            Ok(d) => {
                let graph = dijkstra(&mesh, &[s], &Default::default()).unwrap().distance;
                let p0 = mesh.position(s);
                for (i, p) in mesh.positions().iter().enumerate() {
                    assert_eq!(d[i].is_finite(), graph[i].is_finite(), "{name} vertex {i}");
                    if graph[i].is_finite() {
                        assert!(d[i] <= graph[i] * (1.0 + 1e-12), "{name} vertex {i}: above Dijkstra");
                        assert!(d[i] >= p.distance(p0) * (1.0 - 1e-12), "{name} vertex {i}: below the chord");
                    }
                }
            }
            // Zero-area triangles: a clear error, never a wrong value.
            Err(e) => {
                assert!(name == "cgal_degtri_sliding.off" && matches!(e, GeodesicError::Degenerate(_)), "{name}: {e}")
            }
        }
    }
}

#[test]
fn other_components_are_infinite_and_isolated_vertices_too() {
    let a = shapes::icosphere(1).unwrap();
    let b = shapes::grid(1.0, 1.0, 3, 3).unwrap();
    let mesh = common::union(&a, &b, 1); // one isolated vertex at the end
    let d = exact(&mesh, &[VertexId(0)]);
    let na = a.vertex_count();
    assert!(d[..na].iter().all(|x| x.is_finite()));
    assert!(d[na..].iter().all(|x| *x == f64::INFINITY));
    // Sources on both components.
    let d = exact(&mesh, &[VertexId(0), VertexId::new(na)]);
    let n = mesh.vertex_count();
    assert!(d[..n - 1].iter().all(|x| x.is_finite()) && d[n - 1] == f64::INFINITY);
}

#[test]
fn bad_input_is_an_error() {
    let mesh = shapes::icosphere(1).unwrap();
    let opts = ExactOptions::default();
    assert!(matches!(exact_distance(&mesh, &[], &opts), Err(GeodesicError::NoSources)));
    assert!(matches!(exact_distance(&mesh, &[VertexId(1000)], &opts), Err(GeodesicError::SourceOutOfRange { .. })));
    // Three triangles on one edge.
    let p =
        vec![DVec3::ZERO, DVec3::X, DVec3::new(0.5, 1.0, 0.0), DVec3::new(0.5, -1.0, 0.0), DVec3::new(0.5, 0.0, 1.0)];
    let fan = TriMesh::new(p, vec![[0, 1, 2], [1, 0, 3], [0, 1, 4]]).unwrap();
    let err = exact_distance(&fan, &[VertexId(0)], &opts).unwrap_err();
    assert!(matches!(err, GeodesicError::Mesh(MeshError::NonManifold(_))), "{err}");
    // A zero-area triangle.
    let p = vec![DVec3::ZERO, DVec3::X, DVec3::new(2.0, 0.0, 0.0), DVec3::Y];
    let flat = TriMesh::new(p, vec![[0, 1, 3], [1, 2, 3], [0, 2, 1]]).unwrap();
    let err = exact_distance(&flat, &[VertexId(0)], &opts).unwrap_err();
    assert!(matches!(err, GeodesicError::Degenerate(_) | GeodesicError::Mesh(_)), "{err}");
    // The work bound.
    let err =
        exact_distance(&shapes::icosphere(3).unwrap(), &[VertexId(0)], &ExactOptions { max_windows: 100 }).unwrap_err();
    assert!(matches!(err, GeodesicError::WorkLimit { limit: 100, .. }), "{err}");
}

/// An icosphere or a torus with every vertex moved radially by up to
/// `amplitude` (saddles and convex vertices mixed).
fn random_mesh(torus: bool, seed: u64, amplitude: f64) -> TriMesh {
    let mut mesh = if torus { shapes::torus(1.0, 0.4, 16, 8).unwrap() } else { shapes::icosphere(2).unwrap() };
    let mut rng = mesh_testkit::SplitMix64::new(seed);
    for p in mesh.positions_mut() {
        *p *= 1.0 + amplitude * rng.signed();
    }
    mesh
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// Exact distances are a metric: symmetric and with the triangle
    /// inequality up to rounding, on non-convex meshes with saddles.
    #[test]
    fn exact_distance_is_a_metric(torus in any::<bool>(), seed in any::<u64>(), amp in 0.0f64..0.3,
                                  picks in prop::array::uniform3(any::<prop::sample::Index>())) {
        let mesh = random_mesh(torus, seed, amp);
        let v = picks.map(|i| VertexId::new(i.index(mesh.vertex_count())));
        let rows = v.map(|s| exact(&mesh, &[s]));
        for i in 0..3 {
            for j in 0..3 {
                let (dij, dji) = (rows[i][v[j].idx()], rows[j][v[i].idx()]);
                prop_assert!((dij - dji).abs() <= 1e-9 * (1.0 + dij), "d({i},{j}) {dij} vs {dji}");
                for k in 0..3 {
                    let excess = rows[i][v[k].idx()] - dij - rows[j][v[k].idx()];
                    prop_assert!(excess <= 1e-9, "triangle {i} {j} {k}: {excess}");
                }
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Random triangle soups (non-manifold, degenerate, duplicate and
    /// isolated vertices): a typed error or distances without NaN, 0 at the
    /// sources, never below the Euclidean distance; nothing panics or hangs.
    #[test]
    fn random_soups_never_crash(
        points in prop::collection::vec(prop::array::uniform3(-2i8..3), 3..14),
        faces in prop::collection::vec(prop::array::uniform3(0usize..14), 1..20),
        source in 0usize..14,
    ) {
        let n = points.len();
        let p: Vec<DVec3> = points.iter().map(|c| DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64 * 0.5)).collect();
        let f: Vec<[u32; 3]> = faces.iter().map(|t| t.map(|v| (v % n) as u32)).collect();
        let Ok(mesh) = TriMesh::new(p, f) else { return Ok(()) };
        let s = VertexId::new(source % n);
        match exact_distance(&mesh, &[s], &ExactOptions { max_windows: 100_000 }) {
            Ok(d) => {
                prop_assert_eq!(d[s.idx()], 0.0);
                let p0 = mesh.position(s);
                for (i, x) in d.iter().enumerate() {
                    prop_assert!(!x.is_nan() && *x >= mesh.position(VertexId::new(i)).distance(p0) * (1.0 - 1e-12));
                }
            }
            Err(e) => prop_assert!(
                matches!(e, GeodesicError::Mesh(_) | GeodesicError::Degenerate(_) | GeodesicError::WorkLimit { .. }),
                "{e}"
            ),
        }
    }
}
