//! The filter banks as sparse matrices (sprs) for inspection, and the
//! inner product of eq. 2.36 as a Gram matrix.
//!
//! For level j -> j+1 with `v^{j+1}` in hierarchical order:
//! `v^{j+1} = P v^j + Q w^j` (synthesis) and `v^j = A v^{j+1}`,
//! `w^j = B v^{j+1}` (analysis), with `[A; B] = [P Q]^{-1}`. The columns of
//! `P` are the coarse scaling functions and those of `Q` the wavelets,
//! written in the fine scaling functions.

use mesh_kernel::sprs::{CsMat, TriMat};

use crate::error::{Result, WaveletError};
use crate::filter::{FilterBank, LevelFilter};

/// The four matrices of one level of a filter bank (the chapter's figure 2.12).
#[derive(Debug, Clone)]
pub struct FilterMatrices {
    /// Synthesis, coarse part: `n_{j+1} x n_j`, the subdivision matrix.
    pub p: CsMat<f64>,
    /// Synthesis, wavelet part: `n_{j+1} x (n_{j+1} - n_j)`.
    pub q: CsMat<f64>,
    /// Analysis, coarse part: `n_j x n_{j+1}`.
    pub a: CsMat<f64>,
    /// Analysis, wavelet part: `(n_{j+1} - n_j) x n_{j+1}`.
    pub b: CsMat<f64>,
}

impl FilterBank {
    /// The matrices P, Q, A, B of level `j -> j + 1` (`j < J`), as products of
    /// the sparse lifting steps. Cost O(n_{j+1}) (a few nonzeros per row).
    pub fn matrices(&self, j: usize) -> Option<FilterMatrices> {
        self.level(j).map(level_matrices)
    }
}

fn level_matrices(l: &LevelFilter) -> FilterMatrices {
    let (nc, n) = (l.coarse, l.fine);
    // Synthesis steps as n x n matrices acting on [even; odd].
    let update_step = |sign: f64| {
        let mut t = identity_triplets(n);
        if let Some(u) = &l.update {
            for i in 0..u.rows() {
                for (k, w) in u.row(i) {
                    t.add_triplet(k, nc + i, sign * w);
                }
            }
        }
        t.to_csr()
    };
    let predict_step = |sign: f64| {
        let mut t = identity_triplets(n);
        for i in 0..l.predict.rows() {
            for (k, w) in l.predict.row(i) {
                t.add_triplet(nc + i, k, sign * w);
            }
        }
        t.to_csr()
    };
    let smooth_step = |inverse: bool| {
        let mut t = TriMat::new((n, n));
        match &l.smooth {
            Some((alpha, gamma)) => {
                for (k, &a) in alpha.iter().enumerate() {
                    t.add_triplet(k, k, if inverse { 1.0 / a } else { a });
                }
                for i in nc..n {
                    t.add_triplet(i, i, 1.0);
                }
                for i in 0..gamma.rows() {
                    for (k, w) in gamma.row(i) {
                        t.add_triplet(k, nc + i, if inverse { -w / alpha[k] } else { w });
                    }
                }
            }
            None => t = identity_triplets(n),
        }
        t.to_csr()
    };
    let synthesis: CsMat<f64> = &smooth_step(false) * &(&predict_step(1.0) * &update_step(-1.0));
    let analysis: CsMat<f64> = &update_step(1.0) * &(&predict_step(-1.0) * &smooth_step(true));
    let (p, q) = split_columns(&synthesis, nc);
    let (a, b) = split_rows(&analysis, nc);
    FilterMatrices { p, q, a, b }
}

fn identity_triplets(n: usize) -> TriMat<f64> {
    let mut t = TriMat::with_capacity((n, n), n);
    for i in 0..n {
        t.add_triplet(i, i, 1.0);
    }
    t
}

fn split_columns(m: &CsMat<f64>, at: usize) -> (CsMat<f64>, CsMat<f64>) {
    let (rows, cols) = m.shape();
    let mut left = TriMat::new((rows, at));
    let mut right = TriMat::new((rows, cols - at));
    for (&v, (i, j)) in m.iter() {
        if j < at {
            left.add_triplet(i, j, v);
        } else {
            right.add_triplet(i, j - at, v);
        }
    }
    (left.to_csr(), right.to_csr())
}

fn split_rows(m: &CsMat<f64>, at: usize) -> (CsMat<f64>, CsMat<f64>) {
    let (rows, cols) = m.shape();
    let mut top = TriMat::new((at, cols));
    let mut bottom = TriMat::new((rows - at, cols));
    for (&v, (i, j)) in m.iter() {
        if i < at {
            top.add_triplet(i, j, v);
        } else {
            bottom.add_triplet(i - at, j, v);
        }
    }
    (top.to_csr(), bottom.to_csr())
}

/// The inner product of eq. 2.36 between the hat functions of K^j: the
/// Gram matrix `G_ik = <phi^j_i, phi^j_k>` where every face of the base mesh
/// has unit area, so each of the `faces` of level `level` has area `4^-level`
/// (`A/6` on the diagonal per incident face, `A/12` per face off it).
/// Errors when a face refers to a vertex beyond `vertex_count`. Cost O(F).
///
/// # Errors
/// `WaveletError::Dimension` when a face refers to a vertex beyond `vertex_count`.
pub fn inner_product_matrix(vertex_count: usize, faces: &[[u32; 3]], level: usize) -> Result<CsMat<f64>> {
    if let Some(v) = faces.iter().flatten().find(|&&v| v as usize >= vertex_count) {
        return Err(WaveletError::Dimension(format!("a face refers to vertex {v} of {vertex_count}")));
    }
    let area = 0.25f64.powi(level.min(1000) as i32);
    let mut t = TriMat::with_capacity((vertex_count, vertex_count), 9 * faces.len());
    for f in faces {
        for (r, &i) in f.iter().enumerate() {
            for (c, &k) in f.iter().enumerate() {
                let w = if r == c { area / 6.0 } else { area / 12.0 };
                t.add_triplet(i as usize, k as usize, w);
            }
        }
    }
    Ok(t.to_csr())
}
