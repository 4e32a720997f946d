//! Heat kernel signature against the sphere's closed form.

mod common;

use mesh_kernel::shapes;
use mesh_spectral::{heat_kernel_signature, heat_trace, hks_times, HarmonicsOptions, ManifoldHarmonics};
use std::f64::consts::PI;

/// On the unit sphere HKS(x, t) = sum_l (2 l + 1) / (4 pi) exp(-l (l + 1) t)
/// at every point (addition theorem of spherical harmonics).
fn sphere_hks(t: f64, lmax: usize) -> f64 {
    (0..=lmax).map(|l| (2 * l + 1) as f64 / (4.0 * PI) * (-((l * (l + 1)) as f64) * t).exp()).sum()
}

#[test]
fn sphere_signature_matches_the_closed_form() {
    let mut previous = f64::INFINITY;
    for level in [3, 4] {
        let mesh = shapes::icosphere(level).unwrap();
        // 36 pairs: l <= 5 complete; the dropped terms are < e^{-42 t}.
        let mh = ManifoldHarmonics::new(&mesh, 36, &HarmonicsOptions::default()).unwrap();
        let times = [0.3, 0.6, 1.2];
        let hks = heat_kernel_signature(mh.eigenpairs(), &times).unwrap();
        let mut worst: f64 = 0.0;
        for (t, values) in times.iter().zip(&hks) {
            let truth = sphere_hks(*t, 60);
            for v in values {
                worst = worst.max((v - truth).abs() / truth);
            }
        }
        assert!(worst < 2e-2, "level {level}: {worst}");
        assert!(worst < previous, "level {level}: {worst} after {previous}");
        previous = worst;
        // Decreasing in time at every vertex.
        assert!(hks[0].iter().zip(&hks[1]).all(|(a, b)| a > b));
    }
}

#[test]
fn default_times_span_the_spectrum() {
    let mesh = shapes::icosphere(3).unwrap();
    let mh = ManifoldHarmonics::new(&mesh, 20, &HarmonicsOptions::default()).unwrap();
    let times = hks_times(mh.eigenpairs(), 5).unwrap();
    let values = mh.eigenvalues();
    let ln = 4.0 * 10f64.ln();
    assert!((times[0] - ln / values[19]).abs() < 1e-12 * times[0]);
    assert!((times[4] - ln / values[1]).abs() < 1e-12 * times[4]);
    assert!(times.windows(2).all(|w| w[0] < w[1]));
    assert!(hks_times(mh.eigenpairs(), 0).is_err());
    assert!(heat_kernel_signature(mh.eigenpairs(), &[-1.0]).is_err());
}

/// The heat trace is the area-weighted sum of the signature, and on the unit
/// sphere it is `sum_l (2 l + 1) exp(-l (l + 1) t)` (4 pi times the
/// signature's closed form), truncated to the 36 pairs of l <= 5.
#[test]
fn heat_trace_is_the_integral_of_the_signature() {
    let mesh = shapes::icosphere(4).unwrap();
    let mh = ManifoldHarmonics::new(&mesh, 36, &HarmonicsOptions::default()).unwrap();
    let times = [0.05, 0.3, 1.2];
    let trace = heat_trace(mh.eigenpairs(), &times).unwrap();
    let hks = heat_kernel_signature(mh.eigenpairs(), &times).unwrap();
    for ((t, z), h) in times.iter().zip(&trace).zip(&hks) {
        let integral: f64 = h.iter().zip(mh.mass()).map(|(x, m)| x * m).sum();
        assert!((integral - z).abs() < 1e-9 * z, "t = {t}: {integral} vs {z}");
        let truth: f64 = (0..=5).map(|l| (2 * l + 1) as f64 * (-((l * (l + 1)) as f64) * t).exp()).sum();
        assert!((z - truth).abs() < 1e-2 * truth, "t = {t}: {z} vs {truth}");
    }
    assert!(heat_trace(mh.eigenpairs(), &[f64::NAN]).is_err());
}
