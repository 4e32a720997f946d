//! Awkward input: several pieces, isolated vertices, zero-area faces,
//! non-manifold configurations, bad arguments. Never a panic or a NaN.

mod common;

use common::{clusters, data_mesh, masses, orthonormality_error, pencil, union};
use mesh_kernel::glam::DVec3;
use mesh_kernel::{operators, shapes, TriMesh};
use mesh_spectral::{eigenpairs, EigenOptions, HarmonicsOptions, LaplacianKind, ManifoldHarmonics, SpectralError};
use proptest::prelude::*;

fn finite(pairs: &mesh_spectral::Eigenpairs) -> bool {
    pairs.values.iter().chain(&pairs.residuals).all(|x| x.is_finite())
        && (0..pairs.len()).all(|j| pairs.vector(j).iter().all(|x| x.is_finite()))
}

#[test]
fn identical_pieces_repeat_every_eigenvalue() {
    let a = shapes::icosphere(3).unwrap();
    let mut b = a.clone();
    b.positions_mut().iter_mut().for_each(|p| *p += DVec3::new(5.0, 0.0, 0.0));
    let two = union(&a, &b);
    let (l, m) = pencil(&two);
    let pairs = eigenpairs(&l, &m, 8, &EigenOptions::default()).unwrap();
    // 0 twice (one constant per piece), then 2 six times.
    assert_eq!(clusters(&pairs.values, 1e-9), vec![2, 6], "{:?}", pairs.values);
    assert_eq!(pairs.stats.components, 2);
    assert!(orthonormality_error(&pairs, &masses(&two)) < 1e-10);
    assert!(pairs.residuals.iter().all(|r| *r < 1e-8));
}

#[test]
fn many_small_pieces_give_zero_once_per_piece() {
    // Twenty separate triangles: 20 zero eigenvalues, found by the dense path.
    let mut p = Vec::new();
    let mut f = Vec::new();
    for i in 0..20u32 {
        let o = DVec3::new(3.0 * i as f64, 0.0, 0.0);
        p.extend([o, o + DVec3::X, o + DVec3::Y]);
        f.push([3 * i, 3 * i + 1, 3 * i + 2]);
    }
    let mesh = TriMesh::new(p, f).unwrap();
    let (l, m) = pencil(&mesh);
    let pairs = eigenpairs(&l, &m, 25, &EigenOptions::default()).unwrap();
    assert!(pairs.values[..20].iter().all(|v| v.abs() < 1e-12), "{:?}", pairs.values);
    assert!(pairs.values[20] > 1.0);
    assert!(finite(&pairs));
}

#[test]
fn isolated_vertices_are_excluded_not_nan() {
    let sphere = shapes::icosphere(3).unwrap();
    let (l0, m0) = pencil(&sphere);
    let reference = eigenpairs(&l0, &m0, 10, &EigenOptions::default()).unwrap();
    let mut p = sphere.positions().to_vec();
    let n = p.len();
    p.extend([DVec3::splat(9.0), DVec3::splat(-9.0)]);
    let mesh = TriMesh::new(p, sphere.faces().to_vec()).unwrap();
    let (l, m) = pencil(&mesh);
    let pairs = eigenpairs(&l, &m, 10, &EigenOptions::default()).unwrap();
    assert_eq!(pairs.excluded, vec![n, n + 1]);
    assert!(finite(&pairs));
    for j in 0..10 {
        assert_eq!(&pairs.vector(j)[n..], &[0.0, 0.0]);
        assert!((pairs.values[j] - reference.values[j]).abs() < 1e-9);
    }
    // The harmonics and the transforms go through as well.
    let mh = ManifoldHarmonics::new(&mesh, 10, &HarmonicsOptions::default()).unwrap();
    let coefficients = mh.forward_points(mesh.positions()).unwrap();
    assert!(coefficients.iter().all(|c| c.is_finite()));
}

#[test]
fn zero_area_faces_are_handled() {
    // A planar patch with collinear (zero-area) triangles from CGAL's data.
    let Some(mesh) = data_mesh("cgal_degtri_sliding.off") else { return };
    for laplacian in [LaplacianKind::Cotan, LaplacianKind::IntrinsicDelaunay] {
        let options = HarmonicsOptions { laplacian, ..HarmonicsOptions::default() };
        let (l, mass) = ManifoldHarmonics::operators(&mesh, &options).unwrap();
        let available = mass.iter().filter(|m| **m > 0.0).count();
        let pairs = eigenpairs(&l, &mass, available, &EigenOptions::default()).unwrap();
        assert!(finite(&pairs), "{laplacian:?}");
        assert!(pairs.values[0].abs() < 1e-9);
        assert!(pairs.residuals.iter().all(|r| *r < 1e-8), "{laplacian:?}: {:?}", pairs.residuals);
    }
}

#[test]
fn zero_mass_vertices_coupled_by_the_laplacian_get_the_harmonic_extension() {
    // Vertices without mass but with stiffness (as with the mollified
    // intrinsic Laplacian next to zero-area triangles): constraint rows
    // (L x)_i = 0, on both the dense and the block Krylov path.
    let mesh = shapes::grid(1.0, 1.0, 20, 20).unwrap();
    let (l, mut mass) = ManifoldHarmonics::operators(&mesh, &HarmonicsOptions::default()).unwrap();
    // Make a few interior vertices massless by hand.
    for v in [50, 51, 200] {
        mass[v] = 0.0;
    }
    for dense_threshold in [0, 10_000] {
        let o = EigenOptions { dense_threshold, ..EigenOptions::default() };
        let pairs = eigenpairs(&l, &mass, 6, &o).unwrap();
        assert!(finite(&pairs));
        for j in 0..6 {
            let x = pairs.vector(j);
            for v in [50usize, 51, 200] {
                let lx: f64 = l.outer_view(v).unwrap().iter().map(|(c, w)| w * x[c]).sum();
                assert!(lx.abs() < 1e-8, "dense_threshold {dense_threshold}, pair {j}, vertex {v}: {lx}");
            }
        }
        assert!(pairs.residuals.iter().all(|r| *r < 1e-8), "{:?}", pairs.residuals);
    }
}

#[test]
fn non_manifold_input_is_solved() {
    // Two tetrahedra sharing one vertex (a pinched, non-manifold vertex) and
    // a fin: three triangles on one edge.
    let p = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z, -DVec3::X, -DVec3::Y, -DVec3::Z, DVec3::new(1.0, 1.0, 1.0)];
    let f = vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2], [0, 5, 4], [0, 4, 6], [4, 5, 6], [0, 6, 5], [1, 2, 7]];
    let mesh = TriMesh::new(p, f).unwrap();
    assert!(!mesh.connectivity().is_manifold());
    let (l, m) = pencil(&mesh);
    let pairs = eigenpairs(&l, &m, 8, &EigenOptions::default()).unwrap();
    assert!(finite(&pairs));
    assert!(pairs.values[0].abs() < 1e-12);
}

#[test]
fn bad_arguments_are_typed_errors() {
    let mesh = shapes::icosphere(1).unwrap();
    let (l, m) = pencil(&mesh);
    let n = mesh.vertex_count();
    assert!(matches!(eigenpairs(&l, &m, 0, &EigenOptions::default()), Err(SpectralError::InvalidOption { .. })));
    assert!(matches!(
        eigenpairs(&l, &m, n + 1, &EigenOptions::default()),
        Err(SpectralError::TooManyPairs { requested, available }) if requested == n + 1 && available == n
    ));
    let bad = EigenOptions { tolerance: f64::NAN, ..EigenOptions::default() };
    assert!(eigenpairs(&l, &m, 3, &bad).is_err());
    let bad = EigenOptions { shift: Some(f64::INFINITY), ..EigenOptions::default() };
    assert!(eigenpairs(&l, &m, 3, &bad).is_err());
    let bad = EigenOptions { block_size: Some(0), ..EigenOptions::default() };
    assert!(eigenpairs(&l, &m, 3, &bad).is_err());
    // A shift above the spectrum cannot be factored: an error, not garbage.
    let big = shapes::icosphere(3).unwrap();
    let (lb, mb) = pencil(&big);
    let above = EigenOptions { shift: Some(3.0), dense_threshold: 0, ..EigenOptions::default() };
    assert!(eigenpairs(&lb, &mb, 3, &above).is_err());
    // All pairs of a small mesh: the dense path.
    let all = eigenpairs(&l, &m, n, &EigenOptions::default()).unwrap();
    assert_eq!(all.len(), n);
    assert!(all.residuals.iter().all(|r| *r < 1e-8));
    // Matrices of the wrong shape or content.
    let nan = l.map(|v| if *v > 0.0 { f64::NAN } else { *v });
    assert!(matches!(eigenpairs(&nan, &m, 3, &EigenOptions::default()), Err(SpectralError::InvalidMatrix { .. })));
    let small = vec![1.0; n - 1];
    assert!(matches!(eigenpairs(&l, &small, 3, &EigenOptions::default()), Err(SpectralError::Dimension(_))));
    // Only zero-area faces: nothing carries mass.
    let flat = TriMesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::new(2.0, 0.0, 0.0)], vec![[0, 1, 2]]).unwrap();
    let (lf, mf) = pencil(&flat);
    assert!(matches!(
        eigenpairs(&lf, &mf, 1, &EigenOptions::default()),
        Err(SpectralError::TooManyPairs { available: 0, .. })
    ));
}

/// A grid with jittered interior vertices and a random fold in z.
fn jittered_grid(nx: usize, ny: usize, seed: u64) -> TriMesh {
    let mut mesh = shapes::grid(1.0, 1.0, nx, ny).unwrap();
    let mut rng = mesh_testkit::SplitMix64::new(seed);
    let mut next = || rng.unit() - 0.5;
    let h = 1.0 / nx.max(ny) as f64;
    for p in mesh.positions_mut() {
        let boundary = p.x <= 0.0 || p.y <= 0.0 || p.x >= 1.0 || p.y >= 1.0;
        if !boundary {
            p.x += 0.4 * h * next();
            p.y += 0.4 * h * next();
        }
        p.z = 0.3 * (3.0 * p.x).sin() * p.y;
    }
    mesh
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(10))]

    /// Dense and block Krylov agree, residuals are small, vectors
    /// M-orthonormal, values ascending, on random open surfaces.
    #[test]
    fn krylov_matches_dense_on_random_surfaces(nx in 14usize..22, ny in 14usize..22, k in 1usize..14, seed in 0u64..1000) {
        let mesh = jittered_grid(nx, ny, seed);
        let (l, m) = pencil(&mesh);
        let dense = eigenpairs(&l, &m, k, &EigenOptions { dense_threshold: 10_000, ..EigenOptions::default() }).unwrap();
        let krylov = eigenpairs(&l, &m, k, &EigenOptions { dense_threshold: 0, ..EigenOptions::default() }).unwrap();
        let mass = masses(&mesh);
        for pairs in [&dense, &krylov] {
            prop_assert!(pairs.values.windows(2).all(|w| w[0] <= w[1]));
            prop_assert!(pairs.residuals.iter().all(|r| *r < 1e-8), "{:?}", pairs.residuals);
            prop_assert!(orthonormality_error(pairs, &mass) < 1e-10);
        }
        for (a, b) in dense.values.iter().zip(&krylov.values) {
            prop_assert!((a - b).abs() <= 1e-9 * (1.0 + a.abs()), "{} vs {}", a, b);
        }
    }
}

/// The unit of length changes no answer: on a mesh scaled by `s` the
/// eigenvalues are those of the unscaled mesh divided by `s^2`, and every
/// pair passes the same relative tolerance, on the dense path (296 vertices)
/// and the Krylov path (642), for scales that are powers of two (exact) and
/// that are not (rounded positions).
#[test]
fn eigenpairs_do_not_depend_on_the_unit_of_length() {
    for mesh in [shapes::cube(7).unwrap(), shapes::icosphere(3).unwrap()] {
        let solve = |s: f64| {
            let positions = mesh.positions().iter().map(|&p| p * s).collect();
            let scaled = TriMesh::new(positions, mesh.faces().to_vec()).unwrap();
            let l = operators::cotan_laplacian(&scaled);
            let m = operators::lumped_mass(&scaled, operators::MassKind::MixedVoronoi);
            eigenpairs(&l, &m, 30, &EigenOptions::default())
        };
        let reference = solve(1.0).unwrap();
        for s in [1024.0, 1.0 / 1024.0, 1e3, 1e-3, 1e6, 1e-6] {
            let pairs = solve(s).unwrap_or_else(|e| panic!("{} vertices, scale {s}: {e}", mesh.vertex_count()));
            for (j, (a, b)) in pairs.values.iter().zip(&reference.values).enumerate().skip(1) {
                let rel = (a * s * s - b).abs() / b;
                assert!(rel < 1e-9, "{} vertices, scale {s}, pair {j}: {} vs {b}", mesh.vertex_count(), a * s * s);
            }
        }
    }
}
