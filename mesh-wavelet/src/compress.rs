//! Wavelet compression: keep the largest coefficients, measure the error.

use glam::DVec3;
use mesh_kernel::geometry::bounding_box;

use crate::error::{Result, WaveletError};
use crate::multires::Multiresolution;

/// Options of [`Multiresolution::compress`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CompressOptions {
    /// Fraction of the wavelet coefficients to keep, in [0, 1] (the base
    /// mesh is always kept). Default 0.1.
    pub keep_fraction: f64,
}

impl Default for CompressOptions {
    fn default() -> Self {
        Self { keep_fraction: 0.1 }
    }
}

/// A thresholded representation and its error against the original.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct WaveletCompression {
    /// The representation with the dropped coefficients set to zero.
    pub multiresolution: Multiresolution,
    /// Number of wavelet coefficients (one 3-vector per odd vertex).
    pub total_coefficients: usize,
    /// Number kept.
    pub kept_coefficients: usize,
    /// Root mean square distance between corresponding vertices of the
    /// reconstruction and the original, divided by the bounding-box diagonal.
    pub rms_error: f64,
    /// Largest such distance, divided by the bounding-box diagonal.
    pub max_error: f64,
}

/// One point of a compression curve (see [`Multiresolution::compression_curve`]).
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct WaveletCompressionPoint {
    /// Requested fraction.
    pub keep_fraction: f64,
    /// Coefficients kept.
    pub kept_coefficients: usize,
    /// Relative RMS vertex error.
    pub rms_error: f64,
    /// Relative maximum vertex error.
    pub max_error: f64,
}

impl Multiresolution {
    /// Scores of all wavelet coefficients: `|w^j_i| 2^-j`, the magnitude
    /// scaled by the norm of a level-j hat function under eq. 2.36 (a face of
    /// K^j has area 4^-j), so the score estimates the L2 error of dropping
    /// it. Returns (score, index into [`Multiresolution::data`]).
    fn scored_coefficients(&self) -> Vec<(f64, u32)> {
        let h = self.hierarchy();
        let mut scored = Vec::with_capacity(self.data().len() - h.count(0));
        for j in 0..self.levels() {
            let scale = 0.5f64.powi(j as i32);
            for i in h.count(j)..h.count(j + 1) {
                scored.push((self.data()[i].length() * scale, i as u32));
            }
        }
        scored
    }

    /// Keeps the `round(keep_fraction * total)` coefficients of largest score (see
    /// [`CompressOptions`]) and reports the error of the reconstruction
    /// against this representation's own synthesis. Cost O(n) (selection by
    /// quickselect).
    ///
    /// # Errors
    /// `WaveletError::InvalidOption` (`keep_fraction`) when `options.keep_fraction` is not a fraction in [0, 1];
    /// `WaveletError::Mesh` if a synthesized level does not make a valid mesh (non-finite positions).
    pub fn compress(&self, options: &CompressOptions) -> Result<WaveletCompression> {
        check_fraction(options.keep_fraction)?;
        let mut scored = self.scored_coefficients();
        let total = scored.len();
        let kept = ((options.keep_fraction * total as f64).round() as usize).min(total);
        if kept < total && kept > 0 {
            scored.select_nth_unstable_by(kept - 1, by_score);
        }
        let mut data = self.data().to_vec();
        for &(_, i) in &scored[kept..] {
            data[i as usize] = DVec3::ZERO;
        }
        let reference = self.synthesize()?;
        let mut multiresolution = self.clone();
        multiresolution.replace_data(data)?;
        let approx = multiresolution.synthesize()?;
        let (rms_error, max_error) = relative_errors(reference.positions(), approx.positions(), &reference);
        Ok(WaveletCompression {
            multiresolution,
            total_coefficients: total,
            kept_coefficients: kept,
            rms_error,
            max_error,
        })
    }

    /// Errors for several kept fractions at once, sharing one sort of the
    /// coefficients. Cost O(n log n + k n) for k fractions.
    ///
    /// # Errors
    /// `WaveletError::InvalidOption` (`keep_fraction`) when a fraction is not in [0, 1]; `WaveletError::Mesh` if a
    /// synthesized level does not make a valid mesh.
    pub fn compression_curve(&self, fractions: &[f64]) -> Result<Vec<WaveletCompressionPoint>> {
        for &f in fractions {
            check_fraction(f)?;
        }
        let mut scored = self.scored_coefficients();
        scored.sort_unstable_by(by_score);
        let reference = self.synthesize()?;
        let total = scored.len();
        fractions
            .iter()
            .map(|&keep_fraction| {
                let kept = ((keep_fraction * total as f64).round() as usize).min(total);
                let mut data = self.data().to_vec();
                for &(_, i) in &scored[kept..] {
                    data[i as usize] = DVec3::ZERO;
                }
                let approx = self.synthesize_data(data)?;
                let (rms_error, max_error) = relative_errors(reference.positions(), approx.positions(), &reference);
                Ok(WaveletCompressionPoint { keep_fraction, kept_coefficients: kept, rms_error, max_error })
            })
            .collect()
    }
}

/// Larger scores first, ties by position, so that every selection of the
/// `k` best is the same set.
fn by_score(a: &(f64, u32), b: &(f64, u32)) -> std::cmp::Ordering {
    b.0.total_cmp(&a.0).then(a.1.cmp(&b.1))
}

fn check_fraction(f: f64) -> Result<()> {
    if !(0.0..=1.0).contains(&f) {
        return Err(WaveletError::InvalidOption {
            name: "keep_fraction",
            reason: format!("{f} is not a fraction in [0, 1]"),
        });
    }
    Ok(())
}

/// RMS and maximum distance between corresponding vertices, relative to the
/// bounding-box diagonal of `reference` (absolute if the diagonal is zero).
pub(crate) fn relative_errors(a: &[DVec3], b: &[DVec3], reference: &mesh_kernel::TriMesh) -> (f64, f64) {
    let diag = bounding_box(reference).map_or(0.0, |bb| bb.diagonal());
    let scale = if diag > 0.0 { 1.0 / diag } else { 1.0 };
    let n = a.len().max(1) as f64;
    let (sum2, max) =
        a.iter().zip(b).map(|(p, q)| p.distance(*q)).fold((0.0, 0.0f64), |(s, m), d| (s + d * d, m.max(d)));
    ((sum2 / n).sqrt() * scale, max * scale)
}
