//! Sparse linear solvers on faer, shared by every crate of the workspace.
//!
//! - [`Cholesky`]: a sparse Cholesky factorization of a symmetric positive
//!   definite matrix, reused across any number of right-hand sides and
//!   refactorable with the same pattern (heat method, shift-invert
//!   eigensolvers). From [`SUPERNODAL_FROM`] unknowns the factor is
//!   supernodal and solved by this module's own triangular solves, which
//!   take blocks of right-hand sides row by row ([`Cholesky::solve_rows`]).
//! - [`FillOrdering`]: how the factor orders the unknowns: faer's minimum
//!   degree for any matrix, or a geometric nested dissection of unknowns
//!   placed at a mesh's vertices (from [`DISSECTION_FROM`] unknowns).
//! - [`Lu`]: sparse LU with partial pivoting for non-symmetric systems (the
//!   asymmetric parameterization weights).
//! - [`DirichletSolver`]: fix some unknowns, factor the rest once, solve for
//!   any boundary values and right-hand sides.
//!
//! One tuning policy for every crate: the supernodal factor from
//! [`SUPERNODAL_FROM`] unknowns, the dissection (when points are given)
//! from [`DISSECTION_FROM`], threads from [`PARALLEL_FROM`].
//!
//! Matrices come in as `sprs::CsMat<f64>` (CSR or CSC); conversion to faer is
//! a copy of the raw arrays. Factorization errors (not positive definite,
//! singular) are [`MeshError::Solver`]; NaN or infinite entries are refused
//! before factoring; a right-hand side of the wrong length is
//! [`MeshError::Dimension`], never a silent no-op.

mod cholesky;
mod dirichlet;
mod dissection;
mod lu;
mod supernodal;

pub use cholesky::{Cholesky, FillOrdering};
pub use dirichlet::{DirichletSolver, Factorization};
pub use lu::Lu;

use faer::dyn_stack::MemBuffer;
use faer::sparse::{SparseColMat, SymbolicSparseColMat};
use faer::Par;
use sprs::CsMat;

use crate::error::{MeshError, Result};

/// Copies a sprs matrix into faer's compressed-column format.
///
/// # Errors
/// [`MeshError::Solver`] when a matrix entry is NaN or infinite.
pub fn to_faer(a: &CsMat<f64>) -> Result<SparseColMat<usize, f64>> {
    let csc;
    let a = if a.is_csc() {
        a
    } else {
        csc = a.to_csc();
        &csc
    };
    if let Some(bad) = a.data().iter().find(|v| !v.is_finite()) {
        return Err(MeshError::Solver(format!("matrix has a non-finite entry ({bad})")));
    }
    let (nrows, ncols) = a.shape();
    let symbolic = SymbolicSparseColMat::new_checked(
        nrows,
        ncols,
        a.indptr().to_proper().into_owned(),
        None,
        a.indices().to_vec(),
    );
    Ok(SparseColMat::new(symbolic, a.data().to_vec()))
}

fn check_square(a: &CsMat<f64>) -> Result<usize> {
    let (r, c) = a.shape();
    if r != c {
        return Err(MeshError::Dimension(format!("matrix is {r} x {c}, not square")));
    }
    Ok(r)
}

fn check_rhs(n: usize, len: usize) -> Result<()> {
    if !len.is_multiple_of(n.max(1)) || (n == 0 && len != 0) {
        return Err(MeshError::Dimension(format!("right-hand side of length {len} for {n} unknowns")));
    }
    Ok(())
}

/// Unknowns from which the Cholesky factor is supernodal: faer's automatic
/// choice keeps the simplicial one on 2D meshes up to ~50k unknowns, where
/// the supernodal one factors up to 1.7x faster (crossover measured at
/// 2.5k-3.5k unknowns on disks).
pub const SUPERNODAL_FROM: usize = 2000;

/// Unknowns from which a [`FillOrdering::Dissection`] is used; below, the
/// minimum-degree ordering made smaller factors (Loop-subdivided bunny:
/// 7k vertices 254k against 261k entries; 29k vertices 1.51 M against
/// 1.35 M, factored in the same time).
pub const DISSECTION_FROM: usize = 20_000;

/// Unknowns from which factorizations run on faer's global thread pool.
/// faer's supernodal factorization walks the supernodes in order and
/// parallelizes inside their dense blocks, which are small on surface
/// meshes: on 2-core machines two threads made an 8k-unknown factorization
/// 1.5x slower, the heat method's precomputation at 470k vertices 1.3x
/// slower (3.9-4.1 s against 3.0-3.2 s) and at 1.9M vertices no faster
/// (41-42 s either way).
pub const PARALLEL_FROM: usize = 1_000_000;

/// faer's global parallelism for large systems, one thread for small ones.
fn parallelism(n: usize) -> Par {
    if n >= PARALLEL_FROM {
        faer::get_global_parallelism()
    } else {
        Par::Seq
    }
}

fn memory<T>(req: std::result::Result<MemBuffer, T>) -> Result<MemBuffer> {
    req.map_err(|_| MeshError::Solver("out of memory for the sparse factorization".into()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;
    use sprs::TriMat;

    /// 1D Laplacian of a path with n vertices plus `shift` on the diagonal.
    fn path(n: usize, shift: f64) -> CsMat<f64> {
        let mut t = TriMat::new((n, n));
        for i in 0..n {
            t.add_triplet(i, i, shift);
            if i + 1 < n {
                t.add_triplet(i, i, 1.0);
                t.add_triplet(i + 1, i + 1, 1.0);
                t.add_triplet(i, i + 1, -1.0);
                t.add_triplet(i + 1, i, -1.0);
            }
        }
        t.to_csr()
    }

    fn residual(a: &CsMat<f64>, x: &[f64], b: &[f64]) -> f64 {
        a.outer_iterator()
            .enumerate()
            .map(|(i, row)| (row.iter().map(|(j, v)| v * x[j]).sum::<f64>() - b[i]).abs())
            .fold(0.0, f64::max)
    }

    #[test]
    fn cholesky_solves_and_refactors() {
        let a = path(50, 0.1);
        let mut c = Cholesky::new(&a).unwrap();
        let b: Vec<f64> = (0..50).map(|i| (i as f64).sin()).collect();
        let x = c.solve(&b).unwrap();
        assert!(residual(&a, &x, &b) < 1e-12);
        let a2 = path(50, 2.0);
        c.refactor(&a2).unwrap();
        assert!(c.refactor(&path(49, 2.0)).is_err());
        let mut other = TriMat::new((50, 50));
        (0..50).for_each(|i| other.add_triplet(i, i, 1.0));
        assert!(c.refactor(&other.to_csr()).is_err());
        let x = c.solve(&b).unwrap();
        assert!(residual(&a2, &x, &b) < 1e-12);
        // Two right-hand sides at once.
        let mut bb = b.clone();
        bb.extend(b.iter().map(|v| 2.0 * v));
        let xx = c.solve(&bb).unwrap();
        assert!((xx[50 + 7] - 2.0 * xx[7]).abs() < 1e-12);
        assert!(c.solve(&b[..10]).is_err());
    }

    /// A grid Laplacian plus a small multiple of the identity: symmetric
    /// positive definite with `rows * cols` unknowns.
    pub(super) fn grid(rows: usize, cols: usize) -> CsMat<f64> {
        let m = crate::shapes::grid(1.0, 1.0, rows, cols).unwrap();
        let l = crate::operators::cotan_laplacian(&m);
        let n = l.rows();
        let mut t = TriMat::new((n, n));
        for (&v, (i, j)) in l.iter() {
            t.add_triplet(i, j, v);
        }
        for i in 0..n {
            t.add_triplet(i, i, 0.01);
        }
        t.to_csr()
    }

    /// Solves `A X = A T` for 1, 2, 3, 5, 8 and 11 right-hand sides in every
    /// form (stacked columns, rows in the original order, rows in the
    /// factor's order), on a supernodal (n >= 2000) and a simplicial factor.
    #[test]
    fn cholesky_solves_blocks_of_right_hand_sides_in_every_form() {
        for (rows, cols) in [(60, 50), (12, 9)] {
            let a = grid(rows, cols);
            let n = a.rows();
            let c = Cholesky::new(&a).unwrap();
            let truth = |i: usize, j: usize| ((i * 37 + j * 5) % 11) as f64 - 5.0;
            let times = |j: usize| -> Vec<f64> {
                a.outer_iterator().map(|row| row.iter().map(|(i, v)| v * truth(i, j)).sum()).collect()
            };
            for k in [1, 2, 3, 5, 8, 11] {
                let b: Vec<f64> = (0..k).flat_map(times).collect();
                let x = c.solve(&b).unwrap();
                for (idx, xi) in x.iter().enumerate() {
                    assert!((xi - truth(idx % n, idx / n)).abs() < 1e-9, "n {n} k {k} entry {idx}");
                }
            }
            let columns: Vec<Vec<f64>> = (0..8).map(times).collect();
            let b: Vec<[f64; 8]> = (0..n).map(|i| std::array::from_fn(|j| columns[j][i])).collect();
            let mut rows_x = b.clone();
            c.solve_rows(&mut rows_x).unwrap();
            let mut ordered: Vec<[f64; 8]> = c.order().iter().map(|&i| b[i]).collect();
            c.solve_ordered_rows(&mut ordered).unwrap();
            for i in 0..n {
                for j in 0..8 {
                    assert!((rows_x[i][j] - truth(i, j)).abs() < 1e-9);
                }
            }
            for (pi, &i) in c.order().iter().enumerate() {
                assert_eq!(ordered[pi], rows_x[i]);
            }
            assert!(matches!(c.solve_rows(&mut rows_x[1..]), Err(MeshError::Dimension(_))));
            assert!(matches!(c.solve_ordered_rows(&mut vec![[0.0; 2]; n + 1]), Err(MeshError::Dimension(_))));
        }
    }

    /// Right-hand sides with one or two non-zeros (heat sources), where the
    /// forward solve skips the supernodes off their elimination-tree paths:
    /// the solution must still satisfy `A x = b` everywhere, on a
    /// supernodal factor, with the non-zeros anywhere in the order.
    #[test]
    fn cholesky_solves_sparse_right_hand_sides() {
        let a = grid(60, 50);
        let n = a.rows();
        let c = Cholesky::new(&a).unwrap();
        for nonzeros in [vec![0], vec![n - 1], vec![n / 2], vec![17, n - 40]] {
            let mut b = vec![0.0; n];
            for &i in &nonzeros {
                b[i] = 1.0;
            }
            let x = c.solve(&b).unwrap();
            assert!(residual(&a, &x, &b) < 1e-10, "{nonzeros:?}");
            // The inverse of this M-matrix is positive: a zero where it
            // should not be would show a supernode wrongly skipped.
            assert!(x.iter().all(|v| *v > 0.0), "{nonzeros:?}");
        }
    }

    #[test]
    fn dissection_solves_like_minimum_degree_with_a_smaller_factor() {
        // A triangulated 200 x 130 grid (each square split by a diagonal)
        // with a shifted graph Laplacian, its vertices in a scrambled order
        // (the ordering must not rely on the input's).
        let (w, h) = (200, 130);
        let n = w * h;
        let scramble = |v: usize| (v * 7919) % n;
        let mut t = TriMat::new((n, n));
        let mut points = vec![DVec3::ZERO; n];
        for y in 0..h {
            for x in 0..w {
                let v = scramble(y * w + x);
                points[v] = DVec3::new(x as f64, y as f64, 0.1 * ((x * y) % 3) as f64);
                t.add_triplet(v, v, 0.01);
                for (nx, ny) in [(x + 1, y), (x, y + 1), (x + 1, y + 1)] {
                    if nx < w && ny < h {
                        let u = scramble(ny * w + nx);
                        t.add_triplet(v, v, 1.0);
                        t.add_triplet(u, u, 1.0);
                        t.add_triplet(v, u, -1.0);
                        t.add_triplet(u, v, -1.0);
                    }
                }
            }
        }
        let a: CsMat<f64> = t.to_csc();
        let b: Vec<f64> = (0..n).map(|i| ((i * 31) % 17) as f64 - 8.0).collect();
        let amd = Cholesky::new(&a).unwrap();
        let nd = Cholesky::with_ordering(&a, &FillOrdering::of_points(&points)).unwrap();
        let (x_amd, x_nd) = (amd.solve(&b).unwrap(), nd.solve(&b).unwrap());
        assert!(residual(&a, &x_nd, &b) < 1e-9);
        assert!(x_amd.iter().zip(&x_nd).all(|(p, q)| (p - q).abs() < 1e-9));
        assert!(
            nd.factor_nonzeros() < amd.factor_nonzeros(),
            "dissection {} entries, minimum degree {}",
            nd.factor_nonzeros(),
            amd.factor_nonzeros()
        );
        let mut order = nd.order().to_vec();
        order.sort_unstable();
        assert_eq!(order, (0..n).collect::<Vec<_>>());
        // One point per unknown, or a dimension error.
        let wrong = FillOrdering::of_points(&points[1..]);
        assert!(matches!(Cholesky::with_ordering(&a, &wrong), Err(MeshError::Dimension(_))));
        // Restricted to a subset of rows, or minimum degree past the points.
        assert_eq!(
            FillOrdering::of_points(&points).restrict(&[3, 1]),
            FillOrdering::of_points(&[points[3], points[1]])
        );
        assert_eq!(FillOrdering::of_points(&points).restrict(&[n]), FillOrdering::MinimumDegree);
    }

    #[test]
    fn negative_eigenvalues_are_counted_by_inertia() {
        // The path's eigenvalues are 2 - 2 cos(k pi / n): a shift between the
        // j-th and the next leaves exactly j + 1 below it, on a simplicial
        // (n = 50) and a supernodal (n = 3000) factor.
        for n in [50, 3000] {
            let c = Cholesky::new(&path(n, 0.5)).unwrap();
            let value = |k: usize| 2.0 - 2.0 * (k as f64 * std::f64::consts::PI / n as f64).cos();
            for j in [0, 6, 19] {
                let mu = 0.5 * (value(j) + value(j + 1));
                assert_eq!(c.negative_eigenvalues(&path(n, -mu)).unwrap(), Some(j + 1), "n {n}, j {j}");
            }
            assert_eq!(c.negative_eigenvalues(&path(n, 0.1)).unwrap(), Some(0));
            assert!(c.negative_eigenvalues(&path(n + 1, 0.1)).is_err());
        }
        // A shift on an eigenvalue (the constant's 0): a zero pivot, no count.
        let c = Cholesky::new(&path(50, 0.5)).unwrap();
        assert_eq!(c.negative_eigenvalues(&path(50, 0.0)).unwrap(), None);
    }

    #[test]
    fn cholesky_refuses_indefinite_and_nan() {
        assert!(matches!(Cholesky::new(&path(10, 0.0)), Err(MeshError::Solver(_))));
        let mut t = TriMat::new((2, 2));
        t.add_triplet(0, 0, f64::NAN);
        t.add_triplet(1, 1, 1.0);
        assert!(Cholesky::new(&t.to_csr()).is_err());
        assert!(Cholesky::new(&CsMat::zero((2, 3))).is_err());
    }

    #[test]
    fn lu_solves_nonsymmetric() {
        let mut t = TriMat::new((3, 3));
        for (i, j, v) in [(0, 0, 4.0), (0, 1, 1.0), (1, 0, 2.0), (1, 1, 5.0), (1, 2, 1.0), (2, 1, 3.0), (2, 2, 6.0)] {
            t.add_triplet(i, j, v);
        }
        let a: CsMat<f64> = t.to_csr();
        let b = [1.0, 2.0, 3.0];
        let x = Lu::new(&a).unwrap().solve(&b).unwrap();
        assert!(residual(&a, &x, &b) < 1e-14);
        // Symmetric indefinite: Cholesky fails, CholeskyOrLu falls back.
        let mut t = TriMat::new((2, 2));
        for (i, j, v) in [(0, 0, 1.0), (0, 1, 2.0), (1, 0, 2.0), (1, 1, 1.0)] {
            t.add_triplet(i, j, v);
        }
        let s = DirichletSolver::new(&t.to_csr(), &[], Factorization::CholeskyOrLu).unwrap();
        assert_eq!(s.factorization(), Factorization::Lu);
        let x = s.solve(&[], Some(&[3.0, 3.0])).unwrap();
        assert!((x[0] - 1.0).abs() < 1e-14 && (x[1] - 1.0).abs() < 1e-14);
        let mut s = TriMat::new((2, 2));
        s.add_triplet(0, 0, 1.0);
        s.add_triplet(0, 1, 1.0);
        s.add_triplet(1, 0, 1.0);
        s.add_triplet(1, 1, 1.0);
        assert!(Lu::new(&s.to_csr()).is_err());
    }

    #[test]
    fn dirichlet_interpolates_linearly_on_a_path() {
        // Harmonic on a path with ends fixed at 0 and 1: linear.
        let a = path(11, 0.0);
        for fact in [Factorization::Cholesky, Factorization::Lu] {
            let s = DirichletSolver::new(&a, &[10, 0], fact).unwrap();
            assert_eq!(s.fixed(), &[0, 10]);
            let x = s.solve(&[0.0, 1.0], None).unwrap();
            for (i, xi) in x.iter().enumerate() {
                assert!((xi - i as f64 / 10.0).abs() < 1e-13);
            }
            // Two systems at once: the second reversed.
            let both = s.solve_many(&[&[0.0, 1.0], &[1.0, 0.0]], None).unwrap();
            assert_eq!(both[0], x);
            assert!((both[1][3] - 0.7).abs() < 1e-13);
        }
        assert!(DirichletSolver::new(&a, &[11], Factorization::Cholesky).is_err());
    }
}
