//! Spectral compression of geometry (Karni and Gotsman 2000, with the
//! manifold-harmonic basis of Vallet and Levy 2008): keep the first `keep`
//! coefficients of the coordinates, reconstruct, and measure the error.
//!
//! The reconstruction from the first `keep` harmonics is the M-orthogonal
//! projection of the coordinates onto their span, so the area-weighted RMS
//! error can only decrease as `keep` grows (nested subspaces); the plain
//! per-vertex RMS and the maximum usually do too, without that guarantee.

use faer::{Accum, Mat};
use glam::DVec3;
use mesh_kernel::TriMesh;

use crate::error::{Result, SpectralError};
use crate::harmonics::ManifoldHarmonics;

/// Reconstruction error with `keep` coefficients, relative to the diagonal
/// of the mesh's bounding box.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct SpectralCompressionPoint {
    /// Coefficients kept (per coordinate).
    pub keep: usize,
    /// Area-weighted RMS distance `sqrt(sum m_v d_v^2 / sum m_v) / diagonal`.
    pub rms: f64,
    /// Plain RMS over vertices `sqrt(mean d_v^2) / diagonal`.
    pub vertex_rms: f64,
    /// Largest vertex distance `max d_v / diagonal`.
    pub max: f64,
}

/// Reconstructs `mesh` from its first `keep` harmonic coefficients and
/// reports the error. Vertices excluded by the eigensolver keep their
/// position. O(n k).
///
/// # Errors
/// `SpectralError::InvalidOption` (`keep`) when `keep` exceeds the basis size; `SpectralError::Dimension`
/// when the basis was computed for another vertex count; `SpectralError::Mesh` when the result does not make
/// a valid mesh.
pub fn compress(
    mesh: &TriMesh,
    harmonics: &ManifoldHarmonics,
    keep: usize,
) -> Result<(TriMesh, SpectralCompressionPoint)> {
    check_keep(harmonics, keep)?;
    let mut positions = Vec::new();
    let curve = curve(mesh, harmonics, &[keep], Some(&mut positions))?;
    let mesh = TriMesh::new(positions, mesh.faces().to_vec())?;
    Ok((mesh, curve[0]))
}

/// The error for each count in `keeps` (any order, each `<= k`), computed
/// incrementally from one forward transform: O(n k) in total.
///
/// # Errors
/// `SpectralError::InvalidOption` (`keep`) when a count exceeds the basis size; `SpectralError::Dimension`
/// when the basis was computed for another vertex count.
pub fn compression_curve(
    mesh: &TriMesh,
    harmonics: &ManifoldHarmonics,
    keeps: &[usize],
) -> Result<Vec<SpectralCompressionPoint>> {
    for &keep in keeps {
        check_keep(harmonics, keep)?;
    }
    curve(mesh, harmonics, keeps, None)
}

fn check_keep(harmonics: &ManifoldHarmonics, keep: usize) -> Result<()> {
    if keep > harmonics.len() {
        return Err(SpectralError::InvalidOption {
            name: "keep",
            reason: format!("{keep} coefficients asked, the basis has {}", harmonics.len()),
        });
    }
    Ok(())
}

/// Errors for `keeps` (returned in the given order); when `positions` is
/// given, fills it with the reconstruction for the largest count.
fn curve(
    mesh: &TriMesh,
    harmonics: &ManifoldHarmonics,
    keeps: &[usize],
    positions: Option<&mut Vec<DVec3>>,
) -> Result<Vec<SpectralCompressionPoint>> {
    let p = mesh.positions();
    let n = p.len();
    let pm = Mat::from_fn(n, 3, |i, j| p[i][j]);
    let c = harmonics.forward_columns(pm.as_ref())?;
    let diagonal = mesh_kernel::geometry::bounding_box(mesh).map_or(0.0, |b| b.diagonal());
    // Errors are measured on positions and masses divided by powers of two
    // near their sizes (mass times squared distance is of degree four), and
    // reported relative to the diagonal.
    let unit = mesh_kernel::units::length_unit(mesh);
    let scale = if diagonal > 0.0 { unit / diagonal } else { 1.0 };
    let mut excluded = vec![false; n];
    for &v in &harmonics.eigenpairs().excluded {
        excluded[v] = true;
    }
    let mass_unit = mesh_kernel::units::unit_of(harmonics.mass().iter().copied());
    let mass: Vec<f64> = harmonics.mass().iter().map(|m| m / mass_unit).collect();
    let total_mass: f64 = mass.iter().sum();
    let counted = excluded.iter().filter(|e| !**e).count().max(1) as f64;
    let mut order: Vec<usize> = (0..keeps.len()).collect();
    order.sort_by_key(|&i| keeps[i]);
    let mut out = vec![SpectralCompressionPoint { keep: 0, rms: 0.0, vertex_rms: 0.0, max: 0.0 }; keeps.len()];
    let mut recon = Mat::<f64>::zeros(n, 3);
    let mut done = 0;
    for &i in &order {
        let keep = keeps[i];
        if keep > done {
            let block = c.as_ref().subrows(done, keep - done);
            let phi = harmonics.eigenpairs().vectors().subcols(done, keep - done);
            crate::eigen::tall::mul(recon.as_mut(), Accum::Add, phi, block, 1.0);
            done = keep;
        }
        let (mut weighted, mut plain, mut worst) = (0.0, 0.0, 0.0f64);
        for v in (0..n).filter(|&v| !excluded[v]) {
            let d2 = (0..3).map(|j| ((p[v][j] - recon[(v, j)]) / unit).powi(2)).sum::<f64>();
            weighted += mass[v] * d2;
            plain += d2;
            worst = worst.max(d2);
        }
        let rms = if total_mass > 0.0 { (weighted / total_mass).sqrt() } else { 0.0 };
        out[i] = SpectralCompressionPoint {
            keep,
            rms: rms * scale,
            vertex_rms: (plain / counted).sqrt() * scale,
            max: worst.sqrt() * scale,
        };
    }
    if let Some(positions) = positions {
        *positions = (0..n)
            .map(|v| if excluded[v] { p[v] } else { DVec3::new(recon[(v, 0)], recon[(v, 1)], recon[(v, 2)]) })
            .collect();
    }
    Ok(out)
}
