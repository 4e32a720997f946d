//! Triangular solves with a supernodal Cholesky factor, for blocks of `W`
//! right-hand sides stored row by row.
//!
//! faer's own solve walks the right-hand sides column by column inside each
//! supernode (column-major storage, bounds-checked element access); on
//! meshes of 1e4 to 1e6 vertices that makes a block of 8 columns cost nearly
//! as much per column as single solves. Here the block is stored row-major
//! (the `W` values of one unknown are contiguous), so every non-zero of the
//! factor is read once per block and applied to `W` contiguous values: the
//! inner loops are `W`-wide multiply-adds that the compiler vectorizes.
//! Each supernode is walked by chunks of [`chunk`] columns, so that a row
//! below the chunk is loaded and stored once per chunk instead of once per
//! column.

use faer::sparse::linalg::cholesky::{SymbolicCholesky, SymbolicCholeskyRaw};

/// Columns of a supernode handled together by the triangular solves, for
/// one right-hand side and for blocks: with one, 8 columns per visit of the
/// rows below took 10% less time than 4 (heat solve, 40k vertices); with
/// blocks of 8, the 4 x 8 accumulators stay in registers and 8 columns took
/// 15% more.
const fn chunk(w: usize) -> usize {
    if w == 1 {
        8
    } else {
        4
    }
}

/// Right-hand sides per row at which [`Supernodes::solve`] costs least per
/// right-hand side on this CPU: 32 with AVX-512, 16 otherwise. Measured on
/// 1,120 columns at 117k unknowns (Intel Xeon): AVX-512 1.8 s in blocks of
/// 32, 2.3 s of 16, 3.2 s of 8; AVX2 2.5 s of 16, 2.7 s of 32 (its 16
/// registers spill), 3.2 s of 8.
pub(super) fn widest_block() -> usize {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx512f") {
        return 32;
    }
    16
}

/// One supernode: columns `start..start + size` of the factor, stored by
/// faer as a dense column-major `(size + pattern.len()) x size` block at
/// `offset` in the factor's values.
#[derive(Debug, Clone)]
struct Supernode {
    start: usize,
    size: usize,
    pattern: Vec<usize>,
    offset: usize,
}

/// The supernodal structure of a factor `P A P^T = L L^T`: which depends on
/// the symbolic analysis only, so it survives numeric refactorizations.
#[derive(Debug, Clone)]
pub(super) struct Supernodes {
    nodes: Vec<Supernode>,
}

impl Supernodes {
    /// The supernodes of a symbolic factor; `None` when faer chose the
    /// simplicial form.
    pub fn of(symbolic: &SymbolicCholesky<usize>) -> Option<Self> {
        let SymbolicCholeskyRaw::Supernodal(s) = symbolic.raw() else {
            return None;
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
        Some(Self { nodes })
    }

    /// The diagonal of the factor, column after column (of `D` for an
    /// `L D L^T` factorization with this structure).
    pub fn diagonal<'a>(&'a self, values: &'a [f64]) -> impl Iterator<Item = f64> + 'a {
        self.nodes.iter().flat_map(move |node| {
            let rows = node.size + node.pattern.len();
            (0..node.size).map(move |j| values[node.offset + j * rows + j])
        })
    }

    /// Solves `L L^T X = B` in place for `x` in the factor's (permuted)
    /// order, `W` right-hand sides per row. `values` are the factor's values
    /// and `x.len()` its dimension (checked by the caller).
    pub fn solve<const W: usize>(&self, values: &[f64], x: &mut [[f64; W]]) {
        // Narrower rows stay with AVX2: the heat method's single solves ran
        // 3-5% slower in AVX-512 code at 470k unknowns.
        #[cfg(target_arch = "x86_64")]
        if W >= 8 && std::arch::is_x86_feature_detected!("avx512f") {
            // SAFETY: the CPU supports AVX-512F, checked just above.
            unsafe { self.solve_avx512(values, x) };
            return;
        }
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU supports AVX2, checked just above.
            unsafe { self.solve_avx2(values, x) };
            return;
        }
        self.solve_portable(values, x);
    }

    /// [`Self::solve_portable`] compiled for AVX2: the lane loops become
    /// 256-bit vector instructions (the crate is built for baseline x86-64,
    /// SSE2 only). Same operations in the same order: identical results.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    pub(super) unsafe fn solve_avx2<const W: usize>(&self, values: &[f64], x: &mut [[f64; W]]) {
        self.solve_portable(values, x);
    }

    /// [`Self::solve_portable`] compiled for AVX-512: a row of 8 right-hand
    /// sides is one register, and the 4 columns of a chunk of a block of 32
    /// (16 registers) stay in the 32 registers ([`widest_block`]).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx512f")]
    pub(super) unsafe fn solve_avx512<const W: usize>(&self, values: &[f64], x: &mut [[f64; W]]) {
        self.solve_portable(values, x);
    }

    #[inline(always)]
    pub(super) fn solve_portable<const W: usize>(&self, values: &[f64], x: &mut [[f64; W]]) {
        for node in &self.nodes {
            // A supernode whose unknowns are still all zero solves to zero
            // and changes nothing below it: with a sparse right-hand side
            // (a heat source), only the supernodes on the elimination-tree
            // paths from its non-zeros to the root do any work.
            if x[node.start..node.start + node.size].iter().flatten().any(|v| *v != 0.0) {
                forward(node, values, x);
            }
        }
        for node in self.nodes.iter().rev() {
            backward(node, values, x);
        }
    }
}

/// Calls `$kernel::<q, W>` for the chunk width `q = $width` (1 to 7, or
/// `$C`), with the width as a constant so that the chunk's loops unroll.
macro_rules! by_width {
    ($kernel:ident, $width:expr, $C:ident, $W:ident, ($($arg:expr),*)) => {
        match $width {
            1 => $kernel::<1, $W>($($arg),*),
            2 => $kernel::<2, $W>($($arg),*),
            3 => $kernel::<3, $W>($($arg),*),
            4 => $kernel::<4, $W>($($arg),*),
            5 => $kernel::<5, $W>($($arg),*),
            6 => $kernel::<6, $W>($($arg),*),
            7 => $kernel::<7, $W>($($arg),*),
            _ => $kernel::<$C, $W>($($arg),*),
        }
    };
}

/// Calls `$walk::<c, W>` with the chunk width `c = chunk(W)` as a constant.
macro_rules! by_chunk {
    ($walk:ident, $W:ident, ($($arg:expr),*)) => {
        if chunk($W) == 8 {
            $walk::<8, $W>($($arg),*)
        } else {
            $walk::<4, $W>($($arg),*)
        }
    };
}

/// Forward substitution `L y = b` through one supernode, chunk by chunk
/// (right-looking): inside the chunk `x_c /= L_cc` and `x_r -= L_rc x_c`
/// column by column, then every row below the chunk (rest of the supernode,
/// then its pattern of later unknowns) receives `x_r -= sum_c L_rc x_c` in
/// one visit.
#[inline(always)]
fn forward<const W: usize>(node: &Supernode, values: &[f64], x: &mut [[f64; W]]) {
    by_chunk!(forward_by, W, (node, values, x));
}

/// [`forward`] by chunks of `C` columns (`C` at most 8).
#[inline(always)]
fn forward_by<const C: usize, const W: usize>(node: &Supernode, values: &[f64], x: &mut [[f64; W]]) {
    let mut c0 = 0;
    while c0 < node.size {
        by_width!(forward_chunk, (node.size - c0).min(C), C, W, (node, values, c0, x));
        c0 += C.min(node.size - c0);
    }
}

#[inline(always)]
fn forward_chunk<const Q: usize, const W: usize>(node: &Supernode, values: &[f64], c0: usize, x: &mut [[f64; W]]) {
    let (size, rows) = (node.size, node.size + node.pattern.len());
    let val = &values[node.offset..node.offset + rows * size];
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
    let xs: [[f64; W]; Q] = std::array::from_fn(|i| xt[c0 + i]);
    for r in c0 + Q..size {
        sub_combination(&mut xt[r], std::array::from_fn(|i| cols[i][r]), &xs);
    }
    for (p, &row) in node.pattern.iter().enumerate() {
        sub_combination(&mut tail[row - below], std::array::from_fn(|i| cols[i][size + p]), &xs);
    }
}

/// Backward substitution `L^T x = y` through one supernode, by the same
/// chunks in reverse: `x_c = (y_c - sum_{r > c} L_rc x_r) / L_cc`, where the
/// rows below the chunk are visited once for all its columns.
#[inline(always)]
fn backward<const W: usize>(node: &Supernode, values: &[f64], x: &mut [[f64; W]]) {
    by_chunk!(backward_by, W, (node, values, x));
}

/// [`backward`] by chunks of `C` columns (`C` at most 8).
#[inline(always)]
fn backward_by<const C: usize, const W: usize>(node: &Supernode, values: &[f64], x: &mut [[f64; W]]) {
    let mut c0 = node.size.saturating_sub(1) / C * C;
    loop {
        by_width!(backward_chunk, (node.size - c0).min(C), C, W, (node, values, c0, x));
        if c0 == 0 {
            break;
        }
        c0 -= C;
    }
}

#[inline(always)]
fn backward_chunk<const Q: usize, const W: usize>(node: &Supernode, values: &[f64], c0: usize, x: &mut [[f64; W]]) {
    let (size, rows) = (node.size, node.size + node.pattern.len());
    let val = &values[node.offset..node.offset + rows * size];
    let cols: [&[f64]; Q] = std::array::from_fn(|i| &val[(c0 + i) * rows..(c0 + i + 1) * rows]);
    let (head, tail) = x.split_at_mut(node.start + size);
    let xt = &mut head[node.start..];
    let below = node.start + size;
    let mut acc = [[0.0; W]; Q];
    for r in c0 + Q..size {
        add_products(&mut acc, std::array::from_fn(|i| cols[i][r]), &xt[r]);
    }
    for (p, &row) in node.pattern.iter().enumerate() {
        add_products(&mut acc, std::array::from_fn(|i| cols[i][size + p]), &tail[row - below]);
    }
    for i in (0..Q).rev() {
        let mut v = xt[c0 + i];
        for k in 0..W {
            v[k] -= acc[i][k];
        }
        for j in i + 1..Q {
            let (l, xj) = (cols[i][c0 + j], xt[c0 + j]);
            for k in 0..W {
                v[k] -= l * xj[k];
            }
        }
        xt[c0 + i] = scaled(&v, 1.0 / cols[i][c0 + i]);
    }
}

/// `y -= sum_i l_i x_i`.
#[inline(always)]
fn sub_combination<const Q: usize, const W: usize>(y: &mut [f64; W], l: [f64; Q], xs: &[[f64; W]; Q]) {
    for k in 0..W {
        let mut s = 0.0;
        for i in 0..Q {
            s += l[i] * xs[i][k];
        }
        y[k] -= s;
    }
}

/// `acc_i += l_i x` for each i.
#[inline(always)]
fn add_products<const Q: usize, const W: usize>(acc: &mut [[f64; W]; Q], l: [f64; Q], x: &[f64; W]) {
    for i in 0..Q {
        for k in 0..W {
            acc[i][k] += l[i] * x[k];
        }
    }
}

#[inline(always)]
fn scaled<const W: usize>(x: &[f64; W], a: f64) -> [f64; W] {
    let mut y = *x;
    for v in &mut y {
        *v *= a;
    }
    y
}

/// `y -= a x`.
#[inline(always)]
fn sub_scaled<const W: usize>(y: &mut [f64; W], a: f64, x: &[f64; W]) {
    for k in 0..W {
        y[k] -= a * x[k];
    }
}
