//! Supernodal sparse Cholesky (faer's analysis and numeric factorization)
//! with a triangular solve tuned for blocks of right-hand sides.
//!
//! faer's own solve walks the right-hand sides column by column inside each
//! supernode (column-major storage, bounds-checked element access, optional
//! thread spawning per supernode); on meshes of 1e4 to 1e6 vertices that
//! makes a block of 8 to 32 columns cost nearly as much per column as single
//! solves. Here the block is stored row-major (the `b` values of one
//! unknown are contiguous), so every non-zero of the factor is read once per
//! block and applied to `b` contiguous values: the inner loops are
//! `b`-wide fused multiply-adds that the compiler vectorizes.
//! `mesh_kernel::solver::Cholesky` is the general-purpose wrapper; this
//! private helper exists for speed only (see the crate README).

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::SparseColMat;
use faer::Side;
use mesh_kernel::MeshError;

use crate::error::Result;

/// One supernode: columns `start..start + size` of the factor, stored as a
/// dense column-major `(size + pattern.len()) x size` block at `offset`.
#[derive(Debug, Clone)]
struct Supernode {
    start: usize,
    size: usize,
    pattern: Vec<usize>,
    offset: usize,
}

/// `P A P^T = L L^T` with `L` supernodal.
#[derive(Debug)]
pub(crate) struct BlockCholesky {
    n: usize,
    /// `fwd[i]`: original index of permuted unknown i.
    fwd: Vec<usize>,
    nodes: Vec<Supernode>,
    values: Vec<f64>,
}

fn solver_error(what: &str, e: impl std::fmt::Debug) -> MeshError {
    MeshError::Solver(format!("{what}: {e:?}"))
}

impl BlockCholesky {
    /// Analyses (AMD ordering) and factors the symmetric positive definite
    /// `a` (its lower triangle is read). Fails if `a` is not positive definite.
    ///
    /// # Errors
    /// `SpectralError::Mesh` (`MeshError::Solver`) when the symbolic analysis fails, memory runs out, or the
    /// matrix is not positive definite.
    pub fn new(a: &SparseColMat<usize, f64>) -> Result<Self> {
        let n = a.nrows();
        let params = CholeskySymbolicParams {
            supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
            ..Default::default()
        };
        let symbolic = factorize_symbolic_cholesky(a.symbolic(), Side::Lower, SymmetricOrdering::Amd, params)
            .map_err(|e| solver_error("symbolic Cholesky failed", e))?;
        let mut values = vec![0.0; symbolic.len_val()];
        let par = faer::get_global_parallelism();
        let mut buf = MemBuffer::try_new(symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default()))
            .map_err(|e| solver_error("out of memory", e))?;
        symbolic
            .factorize_numeric_llt(
                &mut values,
                a.as_ref(),
                Side::Lower,
                Default::default(),
                par,
                MemStack::new(&mut buf),
                Default::default(),
            )
            .map_err(|e| solver_error("Cholesky factorization failed, the matrix is not positive definite", e))?;
        let nodes = supernodes(&symbolic)?;
        let fwd = match symbolic.perm() {
            Some(p) => p.arrays().0.to_vec(),
            None => (0..n).collect(),
        };
        Ok(Self { n, fwd, nodes, values })
    }

    /// Number of stored values of the factor.
    pub fn nnz(&self) -> usize {
        self.values.len()
    }

    /// Original index of permuted unknown `i` (the row order expected by
    /// [`Self::solve_lanes`]).
    pub fn permutation(&self) -> &[usize] {
        &self.fwd
    }

    /// Solves `A X = B` in place for [`LANES`] right-hand sides stored
    /// row-major in permuted order: `x[i][j]` is unknown `permutation()[i]`
    /// of right-hand side j. `x.len()` must be n (otherwise nothing is done).
    pub fn solve_lanes(&self, x: &mut [Lane]) {
        if x.len() != self.n {
            return;
        }
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU supports AVX2, checked just above.
            unsafe { self.solve_avx2(x) };
            return;
        }
        self.solve_portable(x);
    }

    /// [`Self::solve_portable`] compiled for AVX2: the lane loops become
    /// 256-bit vector instructions (the crate is built for baseline x86-64,
    /// SSE2 only). Same operations in the same order: identical results.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn solve_avx2(&self, x: &mut [Lane]) {
        self.solve_portable(x);
    }

    #[inline(always)]
    fn solve_portable(&self, x: &mut [Lane]) {
        for node in &self.nodes {
            self.forward(node, x);
        }
        for node in self.nodes.iter().rev() {
            self.backward(node, x);
        }
    }

    /// Forward substitution through one supernode, by chunks of up to
    /// [`CHUNK`] columns (right-looking): inside the chunk `x_c /= L_cc` and
    /// `x_r -= L_rc x_c` column by column, then every row below the chunk
    /// (rest of the supernode, then its pattern of later unknowns) receives
    /// `x_r -= sum_c L_rc x_c` in one visit: each row is loaded and stored
    /// once per chunk instead of once per column.
    #[inline(always)]
    fn forward(&self, node: &Supernode, x: &mut [Lane]) {
        let mut c0 = 0;
        while c0 < node.size {
            match node.size - c0 {
                1 => self.forward_chunk::<1>(node, c0, x),
                2 => self.forward_chunk::<2>(node, c0, x),
                3 => self.forward_chunk::<3>(node, c0, x),
                _ => self.forward_chunk::<CHUNK>(node, c0, x),
            }
            c0 += CHUNK.min(node.size - c0);
        }
    }

    #[inline(always)]
    fn forward_chunk<const Q: usize>(&self, node: &Supernode, c0: usize, x: &mut [Lane]) {
        let (size, rows) = (node.size, node.size + node.pattern.len());
        let val = &self.values[node.offset..node.offset + rows * size];
        let cols: [&[f64]; Q] = std::array::from_fn(|i| &val[(c0 + i) * rows..(c0 + i + 1) * rows]);
        let (head, tail) = x.split_at_mut(node.start + size);
        let xt = &mut head[node.start..];
        let below = node.start + size;
        for i in 0..Q {
            let xc = scaled(&xt[c0 + i], 1.0 / cols[i][c0 + i]);
            xt[c0 + i] = xc;
            for j in i + 1..Q {
                sub_scaled(&mut xt[c0 + j], cols[i][c0 + j], &xc);
            }
        }
        let xs: [Lane; Q] = std::array::from_fn(|i| xt[c0 + i]);
        for r in c0 + Q..size {
            sub_combination(&mut xt[r], std::array::from_fn(|i| cols[i][r]), &xs);
        }
        for (p, &row) in node.pattern.iter().enumerate() {
            sub_combination(&mut tail[row - below], std::array::from_fn(|i| cols[i][size + p]), &xs);
        }
    }

    /// Backward substitution `L^T x = y` through one supernode, by the same
    /// chunks in reverse: `x_c = (y_c - sum_{r > c} L_rc x_r) / L_cc`, where
    /// the rows below the chunk are visited once for all its columns.
    #[inline(always)]
    fn backward(&self, node: &Supernode, x: &mut [Lane]) {
        let last = node.size.saturating_sub(1) / CHUNK * CHUNK;
        let mut c0 = last;
        loop {
            match node.size - c0 {
                1 => self.backward_chunk::<1>(node, c0, x),
                2 => self.backward_chunk::<2>(node, c0, x),
                3 => self.backward_chunk::<3>(node, c0, x),
                _ => self.backward_chunk::<CHUNK>(node, c0, x),
            }
            if c0 == 0 {
                break;
            }
            c0 -= CHUNK;
        }
    }

    #[inline(always)]
    fn backward_chunk<const Q: usize>(&self, node: &Supernode, c0: usize, x: &mut [Lane]) {
        let (size, rows) = (node.size, node.size + node.pattern.len());
        let val = &self.values[node.offset..node.offset + rows * size];
        let cols: [&[f64]; Q] = std::array::from_fn(|i| &val[(c0 + i) * rows..(c0 + i + 1) * rows]);
        let (head, tail) = x.split_at_mut(node.start + size);
        let xt = &mut head[node.start..];
        let below = node.start + size;
        let mut acc = [[0.0; LANES]; Q];
        for r in c0 + Q..size {
            add_products(&mut acc, std::array::from_fn(|i| cols[i][r]), &xt[r]);
        }
        for (p, &row) in node.pattern.iter().enumerate() {
            add_products(&mut acc, std::array::from_fn(|i| cols[i][size + p]), &tail[row - below]);
        }
        for i in (0..Q).rev() {
            let mut v = xt[c0 + i];
            for k in 0..LANES {
                v[k] -= acc[i][k];
            }
            for j in i + 1..Q {
                let (l, xj) = (cols[i][c0 + j], xt[c0 + j]);
                for k in 0..LANES {
                    v[k] -= l * xj[k];
                }
            }
            xt[c0 + i] = scaled(&v, 1.0 / cols[i][c0 + i]);
        }
    }
}

/// Columns of a supernode handled together by the triangular solves.
const CHUNK: usize = 4;

/// `y -= sum_i l_i x_i`.
#[inline(always)]
fn sub_combination<const Q: usize>(y: &mut Lane, l: [f64; Q], xs: &[Lane; Q]) {
    for k in 0..LANES {
        let mut s = 0.0;
        for i in 0..Q {
            s += l[i] * xs[i][k];
        }
        y[k] -= s;
    }
}

/// `acc_i += l_i x` for each i.
#[inline(always)]
fn add_products<const Q: usize>(acc: &mut [Lane; Q], l: [f64; Q], x: &Lane) {
    for i in 0..Q {
        for k in 0..LANES {
            acc[i][k] += l[i] * x[k];
        }
    }
}

/// Right-hand sides solved together by [`BlockCholesky::solve_lanes`]: one
/// 512-bit vector of doubles.
pub(crate) const LANES: usize = 8;

/// The values of one unknown for [`LANES`] right-hand sides.
pub(crate) type Lane = [f64; LANES];

#[inline(always)]
fn scaled(x: &Lane, a: f64) -> Lane {
    let mut y = *x;
    for v in &mut y {
        *v *= a;
    }
    y
}

/// `y -= a x`.
#[inline(always)]
fn sub_scaled(y: &mut Lane, a: f64, x: &Lane) {
    for k in 0..LANES {
        y[k] -= a * x[k];
    }
}

fn supernodes(symbolic: &SymbolicCholesky<usize>) -> Result<Vec<Supernode>> {
    let SymbolicCholeskyRaw::Supernodal(s) = symbolic.raw() else {
        return Err(MeshError::Solver("expected a supernodal Cholesky factor".into()).into());
    };
    let (begin, end) = (s.supernode_begin(), s.supernode_end());
    let ptr_val = s.col_ptr_for_val();
    let nodes = (0..s.n_supernodes())
        .map(|i| Supernode {
            start: begin[i],
            size: end[i] - begin[i],
            pattern: s.supernode(i).pattern().to_vec(),
            offset: ptr_val[i],
        })
        .collect();
    Ok(nodes)
}

#[cfg(test)]
mod tests {
    use super::*;
    use sprs::TriMat;

    #[test]
    fn solves_a_grid_laplacian_with_a_block_of_right_hand_sides() {
        let m = mesh_kernel::shapes::grid(1.0, 1.0, 20, 17).unwrap();
        let l = mesh_kernel::operators::cotan_laplacian(&m);
        let n = l.rows();
        let mut t = TriMat::new((n, n));
        for (&v, (i, j)) in l.iter() {
            t.add_triplet(i, j, v);
        }
        for i in 0..n {
            t.add_triplet(i, i, 0.01);
        }
        let a: sprs::CsMat<f64> = t.to_csr();
        let chol = BlockCholesky::new(&mesh_kernel::solver::to_faer(&a).unwrap()).unwrap();
        let truth: Vec<Lane> = (0..n).map(|i| std::array::from_fn(|j| ((i * 37 + j * 5) % 11) as f64 - 5.0)).collect();
        // rhs = A truth, in permuted order.
        let mut rhs = vec![[0.0; LANES]; n];
        for (i, row) in a.outer_iterator().enumerate() {
            for (j, &v) in row.iter() {
                for k in 0..LANES {
                    rhs[i][k] += v * truth[j][k];
                }
            }
        }
        let mut x: Vec<Lane> = chol.permutation().iter().map(|&orig| rhs[orig]).collect();
        chol.solve_lanes(&mut x);
        for (pi, &orig) in chol.permutation().iter().enumerate() {
            for k in 0..LANES {
                assert!((x[pi][k] - truth[orig][k]).abs() < 1e-9, "{pi} {k}: {} vs {}", x[pi][k], truth[orig][k]);
            }
        }
    }
}
