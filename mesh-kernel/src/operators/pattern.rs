//! The sparsity pattern of edge-based operators, built once in O(V + E)
//! straight from the sorted edge list, without sorting or hashing.

use sprs::{CompressedStorage, CsMat, CsMatView};

use crate::ids::VertexId;
use crate::rows::fill_rows;

/// Edges (or entries, when filling) between the one being placed and the
/// one whose memory is asked for ahead: the cotan Laplacian at 470,274
/// vertices in Loop subdivision's order took 80-82 ms instead of 89-94 on
/// one thread and 52-58 instead of 59-64 on two, and no faster nor slower
/// in Hilbert order (three alternated rounds, 2026-12-06).
const AHEAD: usize = crate::par::READ_AHEAD;

/// CSR pattern with one diagonal entry per vertex and two entries per edge,
/// columns sorted in each row. Any operator that couples only vertices sharing
/// an edge (adjacency, Laplacians, Galerkin mass) fills it from per-edge
/// values in O(V + E). Filling consumes the pattern (its arrays become the
/// matrix's, no copy); clone it first to fill several matrices.
#[derive(Debug, Clone)]
pub struct EdgePattern {
    indptr: Vec<usize>,
    indices: Vec<usize>,
    diag: Vec<usize>,
    /// The edge of each off-diagonal entry (unused on the diagonal).
    slot_edge: Vec<u32>,
}

impl EdgePattern {
    /// Pattern of `n` vertices and `edges` given as (lo, hi) pairs with
    /// lo < hi, sorted lexicographically (as [`crate::Connectivity::edges`]).
    ///
    /// # Panics
    /// If a row would not be strictly increasing (an edge given twice, a
    /// pair of equal ends, edges out of order) or a vertex is `n` or more.
    pub fn new(n: usize, edges: &[[VertexId; 2]]) -> Self {
        // Row i: lower entries (edges (j, i), j < i, in increasing j since edges
        // are sorted), then the diagonal, then upper entries (edges (i, j)).
        // `lower[i]` and `upper[i]` count them, then serve as the cursors
        // where the next ones go; the lower cursor ends on the diagonal.
        let mut lower = vec![0usize; n];
        let mut upper = vec![0usize; n];
        // The larger endpoints jump about: their counters and rows are
        // asked for ahead ([`crate::hint::prefetch`]).
        let far = |e: usize| edges.get(e + AHEAD).map(|[_, b]| b.idx());
        for (e, [a, b]) in edges.iter().enumerate() {
            if let Some(c) = far(e).and_then(|b| lower.get(b)) {
                crate::hint::prefetch(c);
            }
            upper[a.idx()] += 1;
            lower[b.idx()] += 1;
        }
        let mut indptr = Vec::with_capacity(n + 1);
        indptr.push(0);
        for i in 0..n {
            let start = indptr[i];
            indptr.push(start + lower[i] + 1 + upper[i]);
            upper[i] = start + lower[i] + 1;
            lower[i] = start;
        }
        let mut indices = vec![0usize; indptr[n]];
        let mut slot_edge = vec![u32::MAX; indptr[n]];
        for (e, [a, b]) in edges.iter().enumerate() {
            if let Some(c) = edges.get(e + 2 * AHEAD).and_then(|[_, b]| lower.get(b.idx())) {
                crate::hint::prefetch(c);
            }
            if let Some(&s) = far(e).and_then(|b| lower.get(b)) {
                crate::hint::prefetch(indices[s..].as_ptr());
                crate::hint::prefetch(slot_edge[s..].as_ptr());
            }
            let (a, b) = (a.idx(), b.idx());
            let s = upper[a];
            indices[s] = b;
            slot_edge[s] = e as u32;
            upper[a] += 1;
            let s = lower[b];
            indices[s] = a;
            slot_edge[s] = e as u32;
            lower[b] += 1;
        }
        let diag = lower;
        for (i, &d) in diag.iter().enumerate() {
            indices[d] = i;
        }
        // The check of `CsMat::new`, made here so that filling the pattern
        // (`build`) need not repeat it: beside the cotan weights on two
        // threads, this side has time to spare.
        let units = vec![(); indices.len()];
        if let Err((.., e)) = CsMatView::try_new((n, n), &indptr[..], &indices[..], &units[..]) {
            panic!("edges that make a row unsorted or name a vertex from {n} on: {e}");
        }
        Self { indptr, indices, diag, slot_edge }
    }

    /// The data of the matrix whose entry `(i, j)` for the edge `e` between
    /// `i` and `j` is `-weight(e, i < j)` and whose diagonal entry is
    /// `diagonal(i, s)`, `s` the sum of the row's weights in slot order;
    /// rows in parallel, each written whole without zeroing it first
    /// ([`fill_rows`]). Whether `i < j` comes from the slot's side of the
    /// diagonal, not from reading the column. `weight` reads `reads[e]`,
    /// whose entries are asked for [`AHEAD`] entries of the matrix ahead:
    /// the edges of a row's lower entries are far apart.
    fn fill(
        &self,
        reads: &[f64],
        weight: impl Fn(usize, bool) -> f64 + Sync + Send,
        diagonal: impl Fn(usize, f64) -> f64 + Sync + Send,
    ) -> Vec<f64> {
        fill_rows(&self.indptr, |i, row| {
            let first = self.indptr[i];
            let prefetch = |s: usize| {
                if let Some(w) = self.slot_edge.get(s + AHEAD).and_then(|&e| reads.get(e as usize)) {
                    crate::hint::prefetch(w);
                }
            };
            // Lower entries, the diagonal, upper entries: the upper weights
            // are read twice, for the diagonal's sum and for their slots.
            let (lower, upper) = (first..self.diag[i], self.diag[i] + 1..self.indptr[i + 1]);
            let mut sum = 0.0;
            for s in lower {
                prefetch(s);
                let w = weight(self.slot_edge[s] as usize, false);
                row.push(-w);
                sum += w;
            }
            for s in upper.clone() {
                prefetch(s);
                sum += weight(self.slot_edge[s] as usize, true);
            }
            row.push(diagonal(i, sum));
            for s in upper {
                row.push(-weight(self.slot_edge[s] as usize, true));
            }
        })
    }

    /// The matrix with this pattern and `data`; the pattern's arrays become
    /// the matrix's (no copy).
    fn build(self, data: Vec<f64>) -> CsMat<f64> {
        let n = self.diag.len();
        assert_eq!(data.len(), self.indices.len(), "one value per entry of the pattern");
        // SAFETY: `EdgePattern::new` checked this structure as `CsMat::new`
        // would (`sprs`' `check_compressed_structure`), and nothing changes
        // `indptr` or `indices` after it; `data` has one value per index
        // (asserted above).
        unsafe { CsMat::new_unchecked(CompressedStorage::CSR, (n, n), self.indptr, self.indices, data) }
    }

    /// Symmetric matrix with `M_ab = M_ba = weights[e]` for edge e = (a, b) and
    /// diagonal `diagonal(i, sum of weights of edges at i)`.
    pub fn symmetric(self, weights: &[f64], diagonal: impl Fn(usize, f64) -> f64 + Sync + Send) -> CsMat<f64> {
        // Negating is exact: the sum of the negated weights is the negated sum.
        let data = self.fill(weights, |e, _| -weights[e], |i, negated| diagonal(i, -negated));
        self.build(data)
    }

    /// Laplacian-like matrix from directed weights: for edge e = (a, b), row a
    /// gets `-w_ab = -lo_hi[e]`, row b gets `-w_ba = -hi_lo[e]`, and each
    /// diagonal is its row's weight sum, so rows sum to zero:
    /// `(L q)_i = sum_j w_ij (q_i - q_j)`.
    pub fn directed(self, lo_hi: &[f64], hi_lo: &[f64]) -> CsMat<f64> {
        // `row_is_lo`: the entry's row is the edge's smaller end, its column the larger.
        let data = self.fill(lo_hi, |e, row_is_lo| if row_is_lo { lo_hi[e] } else { hi_lo[e] }, |_, sum| sum);
        self.build(data)
    }

    /// Symmetric Laplacian `L_ab = -w_e`, `L_ii = sum of w_e at i`.
    pub fn laplacian(self, weights: &[f64]) -> CsMat<f64> {
        self.directed(weights, weights)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pattern_of_a_path() {
        // 0 - 1 - 2, plus 0 - 2.
        let e = [[0, 1], [0, 2], [1, 2]].map(|[a, b]| [VertexId(a), VertexId(b)]);
        let p = EdgePattern::new(3, &e);
        let l = p.directed(&[1.0, 2.0, 3.0], &[10.0, 20.0, 30.0]);
        let dense = l.to_dense();
        assert_eq!(dense.row(0).to_vec(), vec![3.0, -1.0, -2.0]);
        assert_eq!(dense.row(1).to_vec(), vec![-10.0, 13.0, -3.0]);
        assert_eq!(dense.row(2).to_vec(), vec![-20.0, -30.0, 50.0]);
    }

    /// The structure check that the matrices skip is made here: a repeated
    /// edge, edges out of order in a row, or a pair of equal ends never
    /// reach a matrix.
    #[test]
    fn edges_that_make_unsorted_rows_are_refused() {
        let cases = [[[0, 1], [0, 1]], [[1, 2], [0, 2]], [[0, 1], [2, 2]]];
        for edges in cases {
            let e = edges.map(|[a, b]| [VertexId(a), VertexId(b)]);
            let refused = std::panic::catch_unwind(|| EdgePattern::new(3, &e)).is_err();
            assert!(refused, "{edges:?}");
        }
    }
}
