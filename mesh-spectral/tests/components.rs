//! Many components, fragments of tiny area, zero-area faces, and a solve
//! that cannot converge: ground truth from unions of spheres, whose
//! spectrum is the union of `l (l + 1) / r^2` (multiplicity 2 l + 1) with one
//! zero per piece.

mod common;

use common::orthonormality_error;
use mesh_kernel::glam::DVec3;
use mesh_kernel::operators::mass::diagonal;
use mesh_kernel::{shapes, TriMesh};
use mesh_spectral::{
    eigenpairs, pencil, ComponentSelection, EigenOptions, EigenSolver, HarmonicsOptions, LaplacianKind,
    ManifoldHarmonics, MassKind, SpectralError,
};

/// Icosphere of `level` scaled by `radius` and moved by `offset`.
fn sphere(level: u32, radius: f64, offset: f64) -> TriMesh {
    let mut m = shapes::icosphere(level).unwrap();
    m.positions_mut().iter_mut().for_each(|p| *p = *p * radius + DVec3::new(offset, 0.0, 0.0));
    m
}

fn union(parts: &[TriMesh]) -> TriMesh {
    let (mut p, mut f) = (Vec::new(), Vec::new());
    for m in parts {
        let o = p.len() as u32;
        p.extend_from_slice(m.positions());
        f.extend(m.faces().iter().map(|t| t.map(|v| v + o)));
    }
    TriMesh::new(p, f).unwrap()
}

/// Two spheres (radius 2, level 4: 2,562 v; radius 1, level 3: 642 v; both
/// on the Krylov path) and a fragment of area 1e-11 (dense path), like the
/// 150 fragments of the full dragon scan.
fn spheres_and_fragment() -> TriMesh {
    union(&[sphere(4, 2.0, 0.0), sphere(3, 1.0, 10.0), sphere(1, 1e-6, 20.0)])
}

fn auto_pencil(mesh: &TriMesh) -> (sprs::CsMat<f64>, sprs::CsMat<f64>, Vec<f64>) {
    let p = pencil(mesh, LaplacianKind::Auto, MassKind::MixedVoronoi).unwrap();
    (p.laplacian, diagonal(p.mass.clone()), p.mass)
}

#[test]
fn one_exact_zero_per_component_then_the_spheres_groups() {
    let mesh = spheres_and_fragment();
    let (l, _, mass) = auto_pencil(&mesh);
    // 3 zeros | 1/2 x3 (radius 2) | 3/2 x5 (radius 2) | 2 x3 (radius 1).
    let pairs = eigenpairs(&l, &mass, 14, &EigenOptions::default()).unwrap();
    assert_eq!(&pairs.values[..3], &[0.0; 3], "{:?}", pairs.values);
    assert_eq!(pairs.stats.zero_eigenvalues, 3);
    assert_eq!(pairs.stats.components, 3);
    let truth = [0.5, 0.5, 0.5, 1.5, 1.5, 1.5, 1.5, 1.5, 2.0, 2.0, 2.0];
    for (j, (&v, &t)) in pairs.values[3..].iter().zip(&truth).enumerate() {
        // Discretization error: 6.6e-3 at level 4, 2.6e-2 at level 3.
        assert!((v - t).abs() <= 0.03 * t, "pair {}: {v} vs {t}", j + 3);
    }
    assert!(pairs.residuals.iter().all(|r| *r <= pairs.stats.tolerance), "{:?}", pairs.residuals);
    assert_eq!(pairs.stats.tolerance, EigenOptions::default().tolerance);
    assert!(orthonormality_error(&pairs, &mass) < 1e-10);
    // The zeros are the pieces' constants, largest piece first.
    let first = pairs.vector(0);
    assert!((first[0] - 1.0 / (16.0 * std::f64::consts::PI).sqrt()).abs() < 1e-3);
    assert!(first[2562..].iter().all(|x| *x == 0.0));
}

#[test]
fn fewer_pairs_than_components_are_all_null_vectors() {
    let mesh = spheres_and_fragment();
    let (l, _, mass) = auto_pencil(&mesh);
    let pairs = eigenpairs(&l, &mass, 2, &EigenOptions::default()).unwrap();
    assert_eq!(pairs.values, vec![0.0, 0.0]);
    assert_eq!(pairs.stats.method, EigenSolver::NullSpace);
    assert_eq!(pairs.stats.operator_columns, 0);
}

#[test]
fn tiny_fragments_give_no_negative_eigenvalue() {
    // Thirty fragments of area 1e-11 around a sphere: their zeros used to
    // come out near -eps lambda_max (about -1e-4) and rank first.
    let mut parts = vec![sphere(3, 1.0, 0.0)];
    parts.extend((0..30).map(|i| sphere(1, 1e-6, 5.0 + i as f64)));
    let mesh = union(&parts);
    let (l, _, mass) = auto_pencil(&mesh);
    let pairs = eigenpairs(&l, &mass, 34, &EigenOptions::default()).unwrap();
    assert_eq!(&pairs.values[..31], &[0.0; 31]);
    assert!(pairs.values[31..].iter().all(|v| (v - 2.0).abs() < 0.06), "{:?}", &pairs.values[31..]);
    assert!(pairs.residuals.iter().all(|r| *r <= pairs.stats.tolerance));
}

#[test]
fn largest_component_only() {
    let mesh = spheres_and_fragment();
    // Matrix level: the component of largest mass (the radius-2 sphere).
    let (l, _, mass) = auto_pencil(&mesh);
    let o = EigenOptions { component: ComponentSelection::Largest, ..EigenOptions::default() };
    let pairs = eigenpairs(&l, &mass, 9, &o).unwrap();
    assert_eq!(pairs.values[0], 0.0);
    assert!(pairs.values[1..].iter().all(|v| *v > 0.4), "{:?}", pairs.values);
    assert_eq!((pairs.stats.zero_eigenvalues, pairs.stats.components, pairs.stats.components_used), (1, 3, 1));
    assert_eq!(pairs.excluded.len(), mesh.vertex_count() - 2562);
    // Mesh level: the largest piece is cut out, the harmonics are zero elsewhere.
    let options = HarmonicsOptions { eigen: o, ..HarmonicsOptions::default() };
    let mh = ManifoldHarmonics::new(&mesh, 9, &options).unwrap();
    assert_eq!(mh.vertex_count(), mesh.vertex_count());
    assert_eq!(mh.operator_info().unwrap().vertices, 2562);
    for (a, b) in mh.eigenvalues().iter().zip(&pairs.values) {
        assert!((a - b).abs() <= 1e-9 * (1.0 + b), "{a} vs {b}");
    }
    assert!(mh.harmonic(3)[2562..].iter().all(|x| *x == 0.0));
    let coefficients = mh.forward_points(mesh.positions()).unwrap();
    assert!(coefficients.iter().all(|c| c.is_finite()));
}

/// A closed sphere where some faces are split by a vertex on one of their
/// edges, the T-junction closed by a zero-area triangle (a, b, p): a
/// manifold mesh with zero-area faces, as scanners produce.
fn sphere_with_zero_area_faces(level: u32, every: usize) -> (TriMesh, usize) {
    let base = shapes::icosphere(level).unwrap();
    let mut p = base.positions().to_vec();
    let mut faces = Vec::new();
    let mut used = std::collections::HashSet::new();
    let mut slivers = 0;
    for (i, &[a, b, c]) in base.faces().iter().enumerate() {
        let edge = (a.min(b), a.max(b));
        if i % every == 0 && used.insert(edge) {
            let m = p.len() as u32;
            p.push(0.5 * (p[a as usize] + p[b as usize]));
            faces.extend([[a, m, c], [m, b, c], [a, b, m]]);
            slivers += 1;
        } else {
            faces.push([a, b, c]);
        }
    }
    (TriMesh::new(p, faces).unwrap(), slivers)
}

#[test]
fn zero_area_faces_take_the_intrinsic_laplacian_and_stay_psd() {
    let (mesh, slivers) = sphere_with_zero_area_faces(3, 7);
    assert!(mesh.connectivity().is_manifold());
    let p = pencil(&mesh, LaplacianKind::Auto, MassKind::MixedVoronoi).unwrap();
    assert_eq!(p.info.laplacian, LaplacianKind::IntrinsicDelaunay);
    assert_eq!(p.info.degenerate_faces, slivers);
    // Positive semi-definite: every eigenvalue of the whole pencil >= 0
    // (dense path, all pairs), the zero exact.
    let available = p.mass.iter().filter(|x| **x > 0.0).count();
    let all = eigenpairs(
        &p.laplacian,
        &p.mass,
        available,
        &EigenOptions { dense_threshold: 10_000, ..EigenOptions::default() },
    )
    .unwrap();
    assert_eq!(all.values[0], 0.0);
    assert!(all.values[1] > 1.5, "{:?}", &all.values[..4]);
    // The Krylov path: the unit sphere's 0 | 2 x3 | 6 x5, residuals within tolerance.
    let pairs = eigenpairs(&p.laplacian, &p.mass, 9, &EigenOptions::default()).unwrap();
    assert_eq!(pairs.stats.method, EigenSolver::BlockKrylovSchur);
    assert!(pairs.values[1..4].iter().all(|v| (v - 2.0).abs() < 0.06), "{:?}", pairs.values);
    assert!(pairs.values[4..9].iter().all(|v| (v - 6.0).abs() < 0.3), "{:?}", pairs.values);
    assert!(pairs.residuals.iter().all(|r| *r <= pairs.stats.tolerance));
    // And through the harmonics, which report the choice.
    let mh = ManifoldHarmonics::new(&mesh, 4, &HarmonicsOptions::default()).unwrap();
    let info = mh.operator_info().unwrap();
    assert!(info.describe().contains("intrinsic Delaunay"), "{}", info.describe());
}

#[test]
fn a_solve_without_enough_iterations_is_not_converged() {
    let mesh = shapes::icosphere(4).unwrap();
    let (l, _, mass) = auto_pencil(&mesh);
    let o = EigenOptions {
        block_size: Some(8),
        basis_size: Some(32),
        max_restarts: 0,
        tolerance: 1e-12,
        dense_threshold: 0,
        ..EigenOptions::default()
    };
    match eigenpairs(&l, &mass, 20, &o) {
        Err(SpectralError::NotConverged { wanted, residuals, attempts, converged, .. }) => {
            assert_eq!((wanted, attempts), (19, 3));
            assert_eq!(residuals.len(), 19);
            assert!(converged < wanted && residuals.iter().any(|r| *r > 1e-12), "{residuals:?}");
        }
        other => panic!("expected NotConverged, got {other:?}"),
    }
    let message = eigenpairs(&l, &mass, 20, &o).unwrap_err().to_string();
    assert!(message.contains("relative residuals"), "{message}");
}

#[test]
fn a_matrix_whose_rows_do_not_sum_to_zero_has_no_null_vector() {
    // L + M: every eigenvalue moves up by one, nothing is deflated.
    let mesh = shapes::icosphere(3).unwrap();
    let (l, m, mass) = auto_pencil(&mesh);
    let shifted = &l + &m;
    let pairs = eigenpairs(&shifted, &mass, 4, &EigenOptions::default()).unwrap();
    assert_eq!(pairs.stats.zero_eigenvalues, 0);
    assert!((pairs.values[0] - 1.0).abs() < 1e-9, "{:?}", pairs.values);
    assert!(pairs.values[1..].iter().all(|v| (v - 3.0).abs() < 0.1), "{:?}", pairs.values);
}
