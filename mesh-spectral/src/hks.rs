//! Heat kernel signature (Sun, Ovsjanikov and Guibas 2009, "A concise and
//! provably informative multi-scale signature based on heat diffusion"):
//!
//! ```text
//! HKS(x, t) = k_t(x, x) = sum_i exp(-lambda_i t) phi_i(x)^2
//! ```
//!
//! the heat that stays at `x` after time `t` from a unit source there. It is
//! isometry invariant, and small `t` probes local geometry (`HKS ~ 1 / (4 pi
//! t) + K(x) / (12 pi)` with Gaussian curvature K) while large `t` sees the
//! global shape. Truncating to the k smallest pairs is accurate for
//! `t >= 4 ln 10 / lambda_k` (the dropped terms are below 1e-4 of the first).

use crate::eigen::Eigenpairs;
use crate::error::{Result, SpectralError};

/// `HKS(x, t)` for every vertex and every time: one vector of per-vertex
/// values per entry of `times`. O(n k |times|).
///
/// # Errors
/// `SpectralError::InvalidOption` (`times`) for a time that is negative or not finite.
pub fn heat_kernel_signature(pairs: &Eigenpairs, times: &[f64]) -> Result<Vec<Vec<f64>>> {
    check_times(times)?;
    let n = pairs.vertex_count();
    Ok(times
        .iter()
        .map(|&t| {
            let mut h = vec![0.0; n];
            for (i, &lambda) in pairs.values.iter().enumerate() {
                // Eigenvalues are >= 0 up to rounding; a tiny negative one
                // must not blow up for large t.
                let w = (-lambda.max(0.0) * t).exp();
                for (hv, phi) in h.iter_mut().zip(pairs.vector(i)) {
                    *hv += w * phi * phi;
                }
            }
            h
        })
        .collect())
}

/// The heat trace `Z(t) = sum_i exp(-lambda_i t)` over the pairs, for every
/// time: the total heat left at time `t`, which is the area-weighted sum of
/// [`heat_kernel_signature`] over the vertices (the eigenvectors are
/// M-orthonormal), so `Z(t) / area` is the signature's mean. A global,
/// isometry-invariant descriptor of the shape; at the times of [`hks_times`]
/// (inversely proportional to the eigenvalues) it does not depend on the
/// unit of length. O(k |times|).
///
/// # Errors
/// `SpectralError::InvalidOption` (`times`) for a time that is negative or not finite, (`pairs`) for an
/// eigenvalue that is not finite.
pub fn heat_trace(pairs: &Eigenpairs, times: &[f64]) -> Result<Vec<f64>> {
    check_times(times)?;
    if let Some(bad) = pairs.values.iter().find(|l| !l.is_finite()) {
        return Err(SpectralError::InvalidOption { name: "pairs", reason: format!("eigenvalue {bad} is not finite") });
    }
    Ok(times.iter().map(|&t| pairs.values.iter().map(|&lambda| (-lambda.max(0.0) * t).exp()).sum()).collect())
}

fn check_times(times: &[f64]) -> Result<()> {
    match times.iter().find(|t| !(t.is_finite() && **t >= 0.0)) {
        Some(bad) => {
            Err(SpectralError::InvalidOption { name: "times", reason: format!("{bad} is not a finite time >= 0") })
        }
        None => Ok(()),
    }
}

/// `count` times sampled logarithmically over the range where the
/// truncated signature is meaningful (Sun et al. 2009, section 4):
/// `t_min = 4 ln 10 / lambda_max` to `t_max = 4 ln 10 / lambda_1`, with
/// `lambda_1` the smallest eigenvalue above the rounding level of zero.
///
/// # Errors
/// `SpectralError::InvalidOption` (`count`) for a count of 0 or eigenpairs without a positive eigenvalue.
pub fn hks_times(pairs: &Eigenpairs, count: usize) -> Result<Vec<f64>> {
    let largest = pairs.values.iter().copied().fold(0.0, f64::max);
    let threshold = 1e-8 * largest;
    let smallest = pairs.values.iter().copied().filter(|&l| l > threshold).fold(f64::INFINITY, f64::min);
    if count == 0 || !(largest > 0.0 && smallest.is_finite()) {
        return Err(SpectralError::InvalidOption {
            name: "count",
            reason: "need at least one time and one positive eigenvalue".into(),
        });
    }
    let (lo, hi) = ((4.0 * 10f64.ln() / largest).ln(), (4.0 * 10f64.ln() / smallest).ln());
    Ok((0..count)
        .map(|i| {
            let s = if count == 1 { 0.5 } else { i as f64 / (count - 1) as f64 };
            (lo + s * (hi - lo)).exp()
        })
        .collect())
}
