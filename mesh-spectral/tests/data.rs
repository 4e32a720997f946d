//! The shared real meshes (skipped with a message when absent).

mod common;

use common::{data_mesh, masses, orthonormality_error, pencil};
use mesh_spectral::{eigenpairs, EigenOptions, HarmonicsOptions, LaplacianKind, ManifoldHarmonics};

#[test]
fn real_meshes_give_accurate_orthonormal_pairs() {
    for name in ["cgal_elephant.off", "cgal_holes.off", "cgal_fandisk.off", "npm_bunny.obj", "cgal_mushroom.off"] {
        let Some(mesh) = data_mesh(name) else { continue };
        let (l, m) = pencil(&mesh);
        let pairs = eigenpairs(&l, &m, 40, &EigenOptions::default()).unwrap();
        let scale = pairs.values[39];
        assert!(pairs.values[0].abs() < 1e-9 * scale, "{name}: {}", pairs.values[0]);
        assert!(pairs.values[1] > 1e-6 * scale, "{name}: one connected piece");
        let worst = pairs.residuals.iter().copied().fold(0.0, f64::max);
        assert!(worst < 1e-8 * scale.max(1.0), "{name}: residual {worst}");
        assert!(orthonormality_error(&pairs, &masses(&mesh)) < 1e-10, "{name}");
    }
}

#[test]
fn intrinsic_delaunay_spectrum_is_close_to_the_cotangent_one() {
    // Same surface, different discretization: the smallest eigenvalues agree
    // to the discretization error.
    let Some(mesh) = data_mesh("cgal_elephant.off") else { return };
    let cotan = ManifoldHarmonics::new(&mesh, 10, &HarmonicsOptions::default()).unwrap();
    let options = HarmonicsOptions { laplacian: LaplacianKind::IntrinsicDelaunay, ..HarmonicsOptions::default() };
    let intrinsic = ManifoldHarmonics::new(&mesh, 10, &options).unwrap();
    for (a, b) in cotan.eigenvalues()[1..].iter().zip(&intrinsic.eigenvalues()[1..]) {
        assert!((a - b).abs() < 0.05 * a, "{a} vs {b}");
    }
    assert!(intrinsic.eigenpairs().residuals.iter().all(|r| *r < 1e-8));
}
