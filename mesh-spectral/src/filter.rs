//! Spectral filtering of geometry (Vallet and Levy 2008, section 5): the
//! coordinates are transformed, each coefficient multiplied by a transfer
//! function of its frequency `omega_i = sqrt(lambda_i)`, and transformed
//! back:
//!
//! ```text
//! p' = sum_i g(omega_i) c_i phi_i + g_beyond (p - sum_i c_i phi_i)
//! ```
//!
//! The last term is the detail that the k computed harmonics do not
//! represent (frequencies above `omega_k`): a low-pass drops it
//! (`g_beyond = 0`), a band exaggeration keeps it (`g_beyond = 1`), so
//! enhancing a band does not smooth the rest of the surface away.

use faer::{Accum, Mat};
use glam::DVec3;
use mesh_kernel::TriMesh;

use crate::eigen::tall;
use crate::error::{Result, SpectralError};
use crate::harmonics::ManifoldHarmonics;

/// A transfer function over frequencies `omega = sqrt(lambda)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Transfer {
    /// Ideal low-pass by count: the first `keep` harmonics with gain 1, the
    /// rest (and everything beyond the basis) removed.
    KeepFirst(usize),
    /// Butterworth low-pass `g = 1 / (1 + (omega / cutoff)^(2 order))`,
    /// nothing kept beyond the basis: smooth roll-off without ringing.
    LowPass {
        /// Cutoff frequency (gain 1/2).
        cutoff: f64,
        /// Steepness (1 to 8 are typical).
        order: u32,
    },
    /// Band exaggeration: gain `gain` for `low <= omega <= high`, 1
    /// elsewhere and beyond the basis.
    Band {
        /// Lower band edge.
        low: f64,
        /// Upper band edge.
        high: f64,
        /// Gain inside the band (> 1 exaggerates, < 1 attenuates).
        gain: f64,
    },
}

impl Transfer {
    /// Gain of harmonic `index` with frequency `omega`.
    pub fn gain(&self, index: usize, omega: f64) -> f64 {
        match *self {
            Transfer::KeepFirst(keep) => f64::from(u8::from(index < keep)),
            Transfer::LowPass { cutoff, order } => 1.0 / (1.0 + (omega / cutoff).powi(2 * order.min(64) as i32)),
            Transfer::Band { low, high, gain } => {
                if (low..=high).contains(&omega) {
                    gain
                } else {
                    1.0
                }
            }
        }
    }

    /// Gain applied to the detail beyond the basis.
    pub fn beyond(&self) -> f64 {
        match self {
            Transfer::KeepFirst(_) | Transfer::LowPass { .. } => 0.0,
            Transfer::Band { .. } => 1.0,
        }
    }

    fn validate(&self) -> Result<()> {
        let bad = |name, reason: String| Err(SpectralError::InvalidOption { name, reason });
        match *self {
            Transfer::KeepFirst(_) => Ok(()),
            Transfer::LowPass { cutoff, order } => {
                if !(cutoff > 0.0 && cutoff.is_finite()) {
                    return bad("cutoff", format!("{cutoff} is not positive and finite"));
                }
                if order == 0 {
                    return bad("order", "must be at least 1".into());
                }
                Ok(())
            }
            Transfer::Band { low, high, gain } => {
                if !(low.is_finite() && high.is_finite() && low <= high) {
                    return bad("band", format!("[{low}, {high}] is not a finite interval"));
                }
                if !gain.is_finite() {
                    return bad("gain", format!("{gain} is not finite"));
                }
                Ok(())
            }
        }
    }
}

/// Filters point positions (one per vertex) with `transfer`. Vertices
/// excluded by the eigensolver (no mass) keep their position. O(n k).
///
/// # Errors
/// `SpectralError::InvalidOption` for an invalid transfer function (`cutoff`, `order`, `band`, `gain`) or a
/// non-finite position (`positions`); `SpectralError::Dimension` when `positions` does not have one entry per
/// vertex of the basis.
pub fn filter(harmonics: &ManifoldHarmonics, positions: &[DVec3], transfer: &Transfer) -> Result<Vec<DVec3>> {
    transfer.validate()?;
    filter_with(harmonics, positions, |i, omega| transfer.gain(i, omega), transfer.beyond())
}

/// Filters with any gain function `gain(index, omega)` and gain `beyond`
/// for the detail outside the basis. Non-finite gains are refused.
///
/// # Errors
/// `SpectralError::InvalidOption` (`gain`) for a non-finite gain, (`positions`) for a non-finite position;
/// `SpectralError::Dimension` when `positions` does not have one entry per vertex of the basis.
pub fn filter_with(
    harmonics: &ManifoldHarmonics,
    positions: &[DVec3],
    gain: impl Fn(usize, f64) -> f64,
    beyond: f64,
) -> Result<Vec<DVec3>> {
    let omega = harmonics.frequencies();
    let gains: Vec<f64> = omega.iter().enumerate().map(|(i, &w)| gain(i, w)).collect();
    if let Some(bad) = gains.iter().chain([&beyond]).find(|g| !g.is_finite()) {
        return Err(SpectralError::InvalidOption { name: "gain", reason: format!("{bad} is not finite") });
    }
    let p = Mat::from_fn(positions.len(), 3, |i, j| positions.get(i).map_or(0.0, |p| p[j]));
    if positions.iter().any(|p| !p.is_finite()) {
        return Err(SpectralError::InvalidOption { name: "positions", reason: "non-finite coordinate".into() });
    }
    let c = harmonics.forward_columns(p.as_ref())?;
    let k = harmonics.len();
    // p' = beyond p + Phi ((g - beyond) c)
    let scaled = Mat::from_fn(k, 3, |i, j| (gains[i] - beyond) * c[(i, j)]);
    let mut out = Mat::from_fn(positions.len(), 3, |i, j| beyond * p[(i, j)]);
    tall::mul(out.as_mut(), Accum::Add, harmonics.eigenpairs().vectors(), scaled.as_ref(), 1.0);
    let mut result: Vec<DVec3> =
        (0..positions.len()).map(|v| DVec3::new(out[(v, 0)], out[(v, 1)], out[(v, 2)])).collect();
    for &v in &harmonics.eigenpairs().excluded {
        result[v] = positions[v];
    }
    Ok(result)
}

/// [`filter`] applied to a mesh's vertices; the connectivity is unchanged.
///
/// # Errors
/// The errors of [`filter`], and `SpectralError::Mesh` when the filtered positions do not make a valid mesh.
pub fn filter_mesh(mesh: &TriMesh, harmonics: &ManifoldHarmonics, transfer: &Transfer) -> Result<TriMesh> {
    let p = filter(harmonics, mesh.positions(), transfer)?;
    Ok(TriMesh::new(p, mesh.faces().to_vec())?)
}
