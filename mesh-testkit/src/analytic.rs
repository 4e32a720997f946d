//! Analytic ground truth that the tests and `cargo xtask validate` both
//! compare against.

/// The 8 smallest Neumann eigenvalues of the unit disk, `(j'_{m,k})^2` with
/// multiplicity 2 for m > 0 (zeros of J_m' from scipy.special.jnp_zeros):
/// 0 | 3.3900 (m = 1) x2 | 9.3284 (m = 2) x2 | 14.6820 (m = 0) | 17.6500 (m = 3) x2.
pub const DISK_NEUMANN_EIGENVALUES: [f64; 8] = [
    0.0,
    3.389957716672,
    3.389957716672,
    9.328363213746,
    9.328363213746,
    14.681970642124,
    17.649988519750,
    17.649988519750,
];
