//! Ground truth on the flat unit disk: Neumann eigenvalues (j'_{m,k})^2.

mod common;

use common::{masses, orthonormality_error, pencil};
use mesh_kernel::shapes;
use mesh_spectral::{eigenpairs, EigenOptions};
use mesh_testkit::analytic::DISK_NEUMANN_EIGENVALUES as NEUMANN;

#[test]
fn neumann_disk_eigenvalues_converge_under_refinement() {
    let mut errors = Vec::new();
    for rings in [8, 16, 32] {
        let mesh = shapes::disk(rings, 3).unwrap();
        let (l, m) = pencil(&mesh);
        let pairs = eigenpairs(&l, &m, 8, &EigenOptions::default()).unwrap();
        assert!(pairs.values[0].abs() < 1e-9);
        let error = (1..8).map(|j| (pairs.values[j] - NEUMANN[j]).abs() / NEUMANN[j]).fold(0.0, f64::max);
        assert!(pairs.residuals.iter().all(|r| *r <= 1e-8), "{:?}", pairs.residuals);
        assert!(orthonormality_error(&pairs, &masses(&mesh)) <= 1e-10);
        errors.push(error);
    }
    let orders: Vec<f64> = errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect();
    eprintln!("disk relative errors {errors:?}, observed orders {orders:?}");
    assert!(errors[2] < 1e-2, "{errors:?}");
    assert!(orders.iter().all(|&o| o > 1.5), "{errors:?} {orders:?}");
}
