//! Filter banks as in-place lifting steps: analysis (A, B) and synthesis
//! (P, Q) between K^{j+1} and K^j (the chapter's eq. 2.38-2.39, figure 2.12).
//!
//! With the vertices of level j+1 split into the `n_j` even ones (those of
//! K^j) and the odd ones, one synthesis step is
//!
//! 1. update (lifted wavelet only): `even -= U w`;
//! 2. predict: `odd = Pred(even) + w` with the odd mask of the scheme;
//! 3. smooth (Loop only): `even = alpha even + Gamma odd`, Loop's even rule
//!    written over the new odd vertices.
//!
//! and analysis runs the same steps backwards with opposite signs, so
//! analysis followed by synthesis is the identity up to rounding, for any
//! weights. With zero wavelet coefficients synthesis is the subdivision
//! scheme itself, so `P` is its subdivision matrix; `Q` holds the wavelets.
//! Both directions cost O(n_{j+1}) per level and O(n_J) in all.

use std::ops::{Add, Mul, Sub};

use glam::DVec3;

use crate::error::{Result, WaveletError};
use crate::hierarchy::Hierarchy;
use crate::rules::{self, find_edge, Scratch};
use crate::scheme::{Scheme, WaveletKind};
use crate::topology::Topology;
use crate::update::{update_weights, Rings, UpdateScratch};

/// What the filter banks transform: `f64` scalar functions or `DVec3`
/// positions on the mesh.
pub trait Coefficient: Copy + Default + Add<Output = Self> + Sub<Output = Self> + Mul<f64, Output = Self> {}
impl Coefficient for f64 {}
impl Coefficient for DVec3 {}

/// A sparse matrix in compressed rows, one row per odd vertex.
#[derive(Debug, Clone, Default)]
pub(crate) struct Rows {
    offsets: Vec<u32>,
    index: Vec<u32>,
    weight: Vec<f64>,
}

impl Rows {
    fn with_capacity(rows: usize, entries: usize) -> Self {
        let mut offsets = Vec::with_capacity(rows + 1);
        offsets.push(0);
        Self { offsets, index: Vec::with_capacity(entries), weight: Vec::with_capacity(entries) }
    }

    fn push_row(&mut self, row: &[(u32, f64)]) {
        for &(i, w) in row {
            self.index.push(i);
            self.weight.push(w);
        }
        self.offsets.push(self.index.len() as u32);
    }

    #[inline]
    pub(crate) fn row(&self, r: usize) -> impl Iterator<Item = (usize, f64)> + '_ {
        let range = self.offsets[r] as usize..self.offsets[r + 1] as usize;
        self.index[range.clone()].iter().zip(&self.weight[range]).map(|(&i, &w)| (i as usize, w))
    }

    pub(crate) fn rows(&self) -> usize {
        self.offsets.len() - 1
    }
}

/// The lifting steps of one level j -> j+1.
#[derive(Debug, Clone)]
pub struct LevelFilter {
    pub(crate) coarse: usize,
    pub(crate) fine: usize,
    pub(crate) predict: Rows,
    pub(crate) update: Option<Rows>,
    pub(crate) smooth: Option<(Vec<f64>, Rows)>,
}

impl LevelFilter {
    /// Builds the steps of one level from the topology of K^j and the parent
    /// edges of the odd vertices. Cost O(n_{j+1}).
    pub(crate) fn new(topo: &Topology, parents: &[[u32; 2]], scheme: Scheme, kind: WaveletKind) -> Result<Self> {
        let coarse = topo.vertex_count();
        let odd = parents.len();
        let mut predict = Rows::with_capacity(odd, 4 * odd);
        let mut update = (kind == WaveletKind::Lifted).then(|| Rows::with_capacity(odd, 4 * odd));
        let loop_even: Vec<(f64, f64, f64)> = match scheme {
            Scheme::Loop => (0..coarse as u32).map(|v| rules::loop_even_lifting(topo, v)).collect(),
            _ => Vec::new(),
        };
        let mut smooth = (scheme == Scheme::Loop)
            .then(|| (loop_even.iter().map(|t| t.0).collect::<Vec<_>>(), Rows::with_capacity(odd, 2 * odd)));
        let mut scratch = Scratch::default();
        let rings = (kind == WaveletKind::Lifted).then(|| Rings::new(topo));
        let mut update_scratch = UpdateScratch::new();
        let mut row = Vec::with_capacity(16);
        let mut opposite = Vec::with_capacity(2);
        for (i, &[a, b]) in parents.iter().enumerate() {
            let e = find_edge(topo, a, b, i).ok_or_else(|| {
                WaveletError::Dimension(format!("odd vertex {} splits ({a}, {b}), which is not an edge", coarse + i))
            })?;
            topo.edge_opposites(e, &mut opposite);
            row.clear();
            rules::odd_mask(topo, scheme, a, b, &opposite, &mut scratch, &mut row);
            predict.push_row(&row);
            if let (Some(u), Some(rings)) = (&mut update, &rings) {
                row.clear();
                update_weights(rings, a, b, &opposite, &mut update_scratch, &mut row);
                u.push_row(&row);
            }
            if let Some((_, g)) = &mut smooth {
                let boundary = opposite.len() == 1;
                row.clear();
                for v in [a, b] {
                    let (_, inner, outer) = loop_even[v as usize];
                    let w = if boundary { outer } else { inner };
                    if w != 0.0 {
                        row.push((v, w));
                    }
                }
                g.push_row(&row);
            }
        }
        Ok(Self { coarse, fine: coarse + odd, predict, update, smooth })
    }

    /// Number of vertices of K^j.
    pub fn coarse_count(&self) -> usize {
        self.coarse
    }

    /// Number of vertices of K^{j+1}.
    pub fn fine_count(&self) -> usize {
        self.fine
    }

    fn split<'a, T>(&self, data: &'a mut [T]) -> Result<(&'a mut [T], &'a mut [T])> {
        if data.len() < self.fine {
            return Err(WaveletError::Dimension(format!(
                "{} values for a level of {} vertices",
                data.len(),
                self.fine
            )));
        }
        Ok(data[..self.fine].split_at_mut(self.coarse))
    }

    /// One analysis step in place on `data[..n_{j+1}]`: afterwards
    /// `data[..n_j]` holds the coarse approximation `A v^{j+1}` and
    /// `data[n_j..n_{j+1}]` the wavelet coefficients `B v^{j+1}`.
    /// Cost O(n_{j+1}).
    ///
    /// # Errors
    /// `WaveletError::Dimension` when `data` has fewer values than this level has fine vertices.
    pub fn analyze<T: Coefficient>(&self, data: &mut [T]) -> Result<()> {
        let (even, odd) = self.split(data)?;
        if let Some((alpha, gamma)) = &self.smooth {
            for (i, &o) in odd.iter().enumerate() {
                for (k, w) in gamma.row(i) {
                    even[k] = even[k] - o * w;
                }
            }
            for (e, &a) in even.iter_mut().zip(alpha) {
                *e = *e * (1.0 / a);
            }
        }
        for (i, o) in odd.iter_mut().enumerate() {
            let mut p = T::default();
            for (k, w) in self.predict.row(i) {
                p = p + even[k] * w;
            }
            *o = *o - p;
        }
        if let Some(u) = &self.update {
            for (i, &o) in odd.iter().enumerate() {
                for (k, w) in u.row(i) {
                    even[k] = even[k] + o * w;
                }
            }
        }
        Ok(())
    }

    /// One synthesis step in place, the exact inverse of
    /// [`LevelFilter::analyze`]: `v^{j+1} = P v^j + Q w^j`. Cost O(n_{j+1}).
    ///
    /// # Errors
    /// `WaveletError::Dimension` when `data` has fewer values than this level has fine vertices.
    pub fn synthesize<T: Coefficient>(&self, data: &mut [T]) -> Result<()> {
        let (even, odd) = self.split(data)?;
        if let Some(u) = &self.update {
            for (i, &o) in odd.iter().enumerate() {
                for (k, w) in u.row(i) {
                    even[k] = even[k] - o * w;
                }
            }
        }
        for (i, o) in odd.iter_mut().enumerate() {
            let mut p = T::default();
            for (k, w) in self.predict.row(i) {
                p = p + even[k] * w;
            }
            *o = *o + p;
        }
        if let Some((alpha, gamma)) = &self.smooth {
            for (e, &a) in even.iter_mut().zip(alpha) {
                *e = *e * a;
            }
            for (i, &o) in odd.iter().enumerate() {
                for (k, w) in gamma.row(i) {
                    even[k] = even[k] + o * w;
                }
            }
        }
        Ok(())
    }
}

/// The filter banks of every level of a [`Hierarchy`] for one scheme and
/// wavelet kind. Build once (O(n_J)), then transform any number of
/// functions or geometries on that hierarchy in O(n_J) each.
#[derive(Debug, Clone)]
pub struct FilterBank {
    scheme: Scheme,
    kind: WaveletKind,
    levels: Vec<LevelFilter>,
}

impl FilterBank {
    /// Builds the lifting steps of all levels. Every K^j below the finest
    /// must be an oriented manifold ([`mesh_kernel::MeshError::NonManifold`]
    /// otherwise). Cost O(n_J).
    ///
    /// # Errors
    /// `WaveletError::LevelOutOfRange` or `WaveletError::Mesh` (`MeshError::NonManifold`) only for a
    /// hierarchy that was not built by this crate's constructors; none for a valid hierarchy.
    pub fn new(hierarchy: &Hierarchy, scheme: Scheme, kind: WaveletKind) -> Result<Self> {
        let levels = (0..hierarchy.levels())
            .map(|j| LevelFilter::new(hierarchy.topology(j)?, hierarchy.parents(j)?, scheme, kind))
            .collect::<Result<Vec<_>>>()?;
        Ok(Self { scheme, kind, levels })
    }

    /// The refinement scheme (the predictor).
    pub fn scheme(&self) -> Scheme {
        self.scheme
    }

    /// The wavelet construction.
    pub fn kind(&self) -> WaveletKind {
        self.kind
    }

    /// The finest level J.
    pub fn levels(&self) -> usize {
        self.levels.len()
    }

    /// The lifting steps of level j -> j+1 (`None` for `j >= J`).
    pub fn level(&self, j: usize) -> Option<&LevelFilter> {
        self.levels.get(j)
    }

    /// Number of vertices of K^J, the length of the data this bank transforms.
    pub fn len(&self) -> usize {
        self.levels.last().map_or(0, |l| l.fine)
    }

    /// `true` for a bank without levels.
    pub fn is_empty(&self) -> bool {
        self.levels.is_empty()
    }

    fn check_len<T>(&self, data: &[T], level: usize) -> Result<usize> {
        let n =
            if level == 0 { self.levels.first().map_or(data.len(), |l| l.coarse) } else { self.levels[level - 1].fine };
        if data.len() < n {
            return Err(WaveletError::Dimension(format!("{} values for level {level} with {n} vertices", data.len())));
        }
        Ok(n)
    }

    /// Full analysis in place (finest to coarsest): the values of K^J in
    /// hierarchical order become `[v^0 | w^0 | w^1 | ... | w^{J-1}]`, the
    /// base mesh followed by the wavelet coefficients of eq. 2.39. Cost O(n_J).
    ///
    /// # Errors
    /// `WaveletError::Dimension` when `data` has fewer values than the finest level has vertices.
    pub fn analyze<T: Coefficient>(&self, data: &mut [T]) -> Result<()> {
        self.check_len(data, self.levels())?;
        for l in self.levels.iter().rev() {
            l.analyze(data)?;
        }
        Ok(())
    }

    /// Synthesis in place from `[v^0 | w^0 | ... ]` up to level `level`
    /// (`data[..n_level]` then holds `v^level`, the level-of-detail mesh of
    /// that level). Cost O(n_level).
    ///
    /// # Errors
    /// `WaveletError::LevelOutOfRange` when `level > levels()`;
    /// `WaveletError::Dimension` when `data` does not have one value per vertex
    /// of level `level` at least.
    pub fn synthesize_to<T: Coefficient>(&self, data: &mut [T], level: usize) -> Result<()> {
        if level > self.levels() {
            return Err(WaveletError::LevelOutOfRange { level, levels: self.levels() });
        }
        self.check_len(data, level)?;
        for l in &self.levels[..level] {
            l.synthesize(data)?;
        }
        Ok(())
    }

    /// Full synthesis in place, the inverse of [`FilterBank::analyze`].
    ///
    /// # Errors
    /// `WaveletError::Dimension` when `data` has fewer values than the finest level has vertices.
    pub fn synthesize<T: Coefficient>(&self, data: &mut [T]) -> Result<()> {
        self.synthesize_to(data, self.levels())
    }
}
