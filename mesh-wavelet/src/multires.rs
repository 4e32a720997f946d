//! The multiresolution representation of eq. 2.39: a base mesh plus wavelet
//! coefficients per level, with reconstruction at any level, from any subset
//! of coefficients, and multiresolution editing.

use std::sync::Arc;

use glam::DVec3;
use mesh_kernel::{MeshError, TriMesh, VertexId};

use crate::detect::{detect, DetectOptions};
use crate::error::{Result, WaveletError};
use crate::filter::FilterBank;
use crate::hierarchy::Hierarchy;
use crate::scheme::{Scheme, WaveletKind};

/// Options of [`Multiresolution::analyze`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct MultiresOptions {
    /// Refinement scheme, the predictor of the filter bank. Default: midpoint
    /// (Lounsbery's piecewise-linear wavelets).
    pub scheme: Scheme,
    /// Lazy or lifted wavelets. Default: lifted.
    pub wavelet: WaveletKind,
    /// At most this many levels are detected. Default: all.
    pub max_levels: usize,
}

impl Default for MultiresOptions {
    fn default() -> Self {
        Self { scheme: Scheme::Midpoint, wavelet: WaveletKind::Lifted, max_levels: DetectOptions::default().max_levels }
    }
}

/// Magnitudes of the wavelet coefficients of one level.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct LevelStatistics {
    /// The level j of `w^j` (coefficients between K^j and K^{j+1}).
    pub level: usize,
    /// Number of coefficients (odd vertices of K^{j+1}).
    pub count: usize,
    /// Mean Euclidean norm.
    pub mean: f64,
    /// Root mean square norm.
    pub rms: f64,
    /// Largest norm.
    pub max: f64,
}

/// A mesh with subdivision connectivity as base mesh + wavelet coefficients
/// (eq. 2.39): `rho^J = sum_i v^0_i phi^0_i + sum_k sum_i w^k_i psi^k_i`.
///
/// Cloning is cheap apart from the coefficients: the hierarchy and the
/// filter bank are shared.
#[derive(Debug, Clone)]
pub struct Multiresolution {
    hierarchy: Arc<Hierarchy>,
    bank: Arc<FilterBank>,
    /// `[v^0 | w^0 | ... | w^{J-1}]` in hierarchical order.
    data: Vec<DVec3>,
}

impl Multiresolution {
    /// Detects the subdivision connectivity of `mesh` ([`detect`]), builds
    /// the filter bank and runs the analysis. Errors when the mesh is empty,
    /// non-manifold or has no subdivision connectivity
    /// ([`WaveletError::NoSubdivisionConnectivity`]). Cost O(n).
    ///
    /// # Errors
    /// The errors of `detect` (`WaveletError::InvalidOption` for `max_levels` 0, `MeshError::Empty`,
    /// `MeshError::NonManifold`, `WaveletError::NoSubdivisionConnectivity`).
    pub fn analyze(mesh: &TriMesh, options: &MultiresOptions) -> Result<Self> {
        let hierarchy = detect(mesh, &DetectOptions { max_levels: options.max_levels })?;
        let bank = FilterBank::new(&hierarchy, options.scheme, options.wavelet)?;
        Self::from_parts(Arc::new(hierarchy), Arc::new(bank), mesh.positions())
    }

    /// Analysis of `positions` (in input order, [`Hierarchy::to_input`]) on a
    /// known hierarchy with a prebuilt filter bank of that hierarchy. Cost O(n).
    ///
    /// # Errors
    /// `WaveletError::Dimension` when `positions` does not have one entry per vertex of the finest level or
    /// the bank was built for another hierarchy; `MeshError::NonFinitePosition` for a NaN or infinite
    /// position.
    pub fn from_parts(hierarchy: Arc<Hierarchy>, bank: Arc<FilterBank>, positions: &[DVec3]) -> Result<Self> {
        let n = hierarchy.count(hierarchy.levels());
        if positions.len() != n || bank.levels() != hierarchy.levels() || (bank.levels() > 0 && bank.len() != n) {
            return Err(WaveletError::Dimension(format!(
                "{} positions, a hierarchy of {n} vertices and a filter bank of {} levels",
                positions.len(),
                bank.levels()
            )));
        }
        check_finite(positions)?;
        let mut data: Vec<DVec3> = (0..n).map(|h| positions[hierarchy.input_of(h)]).collect();
        bank.analyze(&mut data)?;
        Ok(Self { hierarchy, bank, data })
    }

    /// The finest level J.
    pub fn levels(&self) -> usize {
        self.hierarchy.levels()
    }

    /// The hierarchy K^0..K^J.
    pub fn hierarchy(&self) -> &Arc<Hierarchy> {
        &self.hierarchy
    }

    /// The filter bank.
    pub fn bank(&self) -> &Arc<FilterBank> {
        &self.bank
    }

    /// The base positions `v^0` (hierarchical order, that of [`Multiresolution::level`]`(0)`
    /// up to [`Hierarchy::output_order`]).
    pub fn base_positions(&self) -> &[DVec3] {
        &self.data[..self.hierarchy.count(0)]
    }

    /// Multiresolution editing: replaces the base positions (in the vertex
    /// order of `level(0)`), keeping every wavelet coefficient, so the details
    /// follow the new coarse shape on synthesis. Cost O(n_0).
    ///
    /// # Errors
    /// `WaveletError::Dimension` when `positions` does not have one entry per base vertex;
    /// `MeshError::NonFinitePosition` for a NaN or infinite position.
    pub fn set_base_positions(&mut self, positions: &[DVec3]) -> Result<()> {
        let n0 = self.hierarchy.count(0);
        if positions.len() != n0 {
            return Err(WaveletError::Dimension(format!(
                "{} positions for a base mesh of {n0} vertices",
                positions.len()
            )));
        }
        check_finite(positions)?;
        let order = self.hierarchy.order_of(0);
        for (h, &o) in order.iter().enumerate() {
            self.data[h] = positions[o as usize];
        }
        Ok(())
    }

    /// The wavelet coefficients `w^j` (one per odd vertex of K^{j+1}, in
    /// hierarchical order), for `j < J`.
    ///
    /// # Errors
    /// `WaveletError::LevelOutOfRange` when `level` is 0 or greater than `levels()`.
    pub fn coefficients(&self, level: usize) -> Result<&[DVec3]> {
        let r = self.coefficient_range(level)?;
        Ok(&self.data[r])
    }

    /// Mutable wavelet coefficients of level `j < J` (to edit or threshold).
    ///
    /// # Errors
    /// `WaveletError::LevelOutOfRange` when `level` is 0 or greater than `levels()`.
    pub fn coefficients_mut(&mut self, level: usize) -> Result<&mut [DVec3]> {
        let r = self.coefficient_range(level)?;
        Ok(&mut self.data[r])
    }

    /// The whole representation `[v^0 | w^0 | ... | w^{J-1}]`.
    pub fn data(&self) -> &[DVec3] {
        &self.data
    }

    pub(crate) fn replace_data(&mut self, data: Vec<DVec3>) -> Result<()> {
        if data.len() != self.data.len() {
            return Err(WaveletError::Dimension(format!("{} values for {}", data.len(), self.data.len())));
        }
        self.data = data;
        Ok(())
    }

    fn coefficient_range(&self, level: usize) -> Result<std::ops::Range<usize>> {
        if level >= self.levels() {
            return Err(WaveletError::LevelOutOfRange { level, levels: self.levels() });
        }
        Ok(self.hierarchy.count(level)..self.hierarchy.count(level + 1))
    }

    /// Positions of K^j (hierarchical order): synthesis up to level j, the
    /// coarse approximation `v^j` of the analysis. Cost O(n_j).
    ///
    /// # Errors
    /// `WaveletError::LevelOutOfRange` when `level > levels()`.
    pub fn level_positions(&self, level: usize) -> Result<Vec<DVec3>> {
        if level > self.levels() {
            return Err(WaveletError::LevelOutOfRange { level, levels: self.levels() });
        }
        let mut data = self.data[..self.hierarchy.count(level)].to_vec();
        self.bank.synthesize_to(&mut data, level)?;
        Ok(data)
    }

    /// The level-of-detail mesh K^j with positions `v^j`. Its vertices keep
    /// their relative input order ([`Hierarchy::output_order`]); at level J
    /// this is the input mesh itself: same vertex order, same faces. Cost O(n_j).
    ///
    /// # Errors
    /// `WaveletError::LevelOutOfRange` when `level > levels()`; `WaveletError::Mesh` when edited coefficients
    /// made a position non-finite.
    pub fn level(&self, level: usize) -> Result<TriMesh> {
        let positions = self.level_positions(level)?;
        Ok(self.mesh_from(level, &positions)?)
    }

    /// Full synthesis: the mesh at level J (the input, up to rounding, until
    /// coefficients or base are edited). Cost O(n).
    ///
    /// # Errors
    /// `WaveletError::Mesh` when edited coefficients made a position non-finite.
    pub fn synthesize(&self) -> Result<TriMesh> {
        self.level(self.levels())
    }

    /// Synthesis from a subset of coefficients: `keep(j, i)` decides whether
    /// coefficient `i` of level `j` takes part (the others count as zero).
    /// Keeping none gives the scheme's subdivision of the base mesh. Cost O(n).
    ///
    /// # Errors
    /// `WaveletError::Mesh` when edited coefficients made a position non-finite.
    pub fn reconstruct(&self, mut keep: impl FnMut(usize, usize) -> bool) -> Result<TriMesh> {
        let mut data = self.data.clone();
        for j in 0..self.levels() {
            let r = self.coefficient_range(j)?;
            for (i, w) in data[r].iter_mut().enumerate() {
                if !keep(j, i) {
                    *w = DVec3::ZERO;
                }
            }
        }
        self.bank.synthesize(&mut data)?;
        Ok(self.mesh_from(self.levels(), &data)?)
    }

    /// Synthesis of an arbitrary representation `[v^0 | w^0 | ...]` (same
    /// layout as [`Multiresolution::data`]) into a mesh. Cost O(n).
    pub(crate) fn synthesize_data(&self, mut data: Vec<DVec3>) -> Result<TriMesh> {
        self.bank.synthesize(&mut data)?;
        Ok(self.mesh_from(self.levels(), &data)?)
    }

    /// Per-level magnitudes of the coefficients. Cost O(n).
    pub fn statistics(&self) -> Vec<LevelStatistics> {
        (0..self.levels())
            .map(|j| {
                let w = &self.data[self.hierarchy.count(j)..self.hierarchy.count(j + 1)];
                let count = w.len();
                let (sum, sum2, max) = w
                    .iter()
                    .map(|c| c.length())
                    .fold((0.0, 0.0, 0.0f64), |(s, s2, m), x| (s + x, s2 + x * x, m.max(x)));
                let n = count.max(1) as f64;
                LevelStatistics { level: j, count, mean: sum / n, rms: (sum2 / n).sqrt(), max }
            })
            .collect()
    }

    /// Mesh of level j from positions in hierarchical order.
    fn mesh_from(&self, level: usize, positions: &[DVec3]) -> std::result::Result<TriMesh, MeshError> {
        let order = self.hierarchy.order_of(level);
        let mut out = vec![DVec3::ZERO; positions.len()];
        for (h, &o) in order.iter().enumerate() {
            out[o as usize] = positions[h];
        }
        let faces = self.hierarchy.faces_of(level).iter().map(|f| f.map(|v| order[v as usize])).collect();
        TriMesh::new(out, faces)
    }
}

/// Geometric decay rate of the coefficient magnitudes with level: `r` such
/// that the mean magnitude behaves like `C r^-j`, from a least-squares fit of
/// `log mean` against j over the levels with nonzero coefficients. `None`
/// with fewer than two such levels.
pub fn decay_rate(stats: &[LevelStatistics]) -> Option<f64> {
    let pts: Vec<(f64, f64)> = stats.iter().filter(|s| s.mean > 0.0).map(|s| (s.level as f64, s.mean.ln())).collect();
    if pts.len() < 2 {
        return None;
    }
    let n = pts.len() as f64;
    let (mx, my) = (pts.iter().map(|p| p.0).sum::<f64>() / n, pts.iter().map(|p| p.1).sum::<f64>() / n);
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    Some((-sxy / sxx).exp())
}

fn check_finite(positions: &[DVec3]) -> Result<()> {
    if let Some(v) = positions.iter().position(|p| !p.is_finite()) {
        let p = positions[v];
        return Err(MeshError::NonFinitePosition { vertex: VertexId::new(v), x: p.x, y: p.y, z: p.z }.into());
    }
    Ok(())
}
