//! Manifold harmonic transform, spectral filtering and compression.

mod common;

use common::{data_mesh, masses};
use mesh_kernel::glam::DVec3;
use mesh_kernel::shapes;
use mesh_spectral::{
    compress, compression_curve, filter, filter_with, HarmonicsOptions, ManifoldHarmonics, SpectralError, Transfer,
};

fn options() -> HarmonicsOptions {
    HarmonicsOptions::default()
}

#[test]
fn full_basis_transform_is_invertible_and_isometric() {
    let mesh = shapes::icosphere(2).unwrap();
    let n = mesh.vertex_count();
    let mh = ManifoldHarmonics::new(&mesh, n, &options()).unwrap();
    let f: Vec<f64> = mesh.positions().iter().map(|p| (3.0 * p.x).sin() + p.y * p.z).collect();
    let c = mh.forward(&f).unwrap();
    let back = mh.inverse(&c).unwrap();
    let worst = f.iter().zip(&back).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
    assert!(worst < 1e-10, "{worst}");
    // Parseval: sum c_i^2 = f^T M f.
    let energy: f64 = f.iter().zip(mh.mass()).map(|(x, m)| x * x * m).sum();
    let coefficient_energy: f64 = c.iter().map(|x| x * x).sum();
    assert!((energy - coefficient_energy).abs() < 1e-10 * energy);
}

#[test]
fn truncated_transform_is_the_m_orthogonal_projection() {
    let mesh = shapes::icosphere(3).unwrap();
    let mh = ManifoldHarmonics::new(&mesh, 16, &options()).unwrap();
    let f: Vec<f64> = mesh.positions().iter().map(|p| p.x * p.x * p.y + p.z).collect();
    let projected = mh.inverse(&mh.forward(&f).unwrap()).unwrap();
    // Idempotent, and the residual is M-orthogonal to every harmonic.
    let again = mh.inverse(&mh.forward(&projected).unwrap()).unwrap();
    assert!(projected.iter().zip(&again).all(|(a, b)| (a - b).abs() < 1e-10));
    let residual: Vec<f64> = f.iter().zip(&projected).map(|(a, b)| a - b).collect();
    assert!(mh.forward(&residual).unwrap().iter().all(|c| c.abs() < 1e-10));
    // x^2 y + z is a polynomial of degree 3: it lies in l <= 3 on the sphere
    // (16 harmonics), up to the discretization.
    let err: f64 = residual.iter().zip(mh.mass()).map(|(r, m)| r * r * m).sum::<f64>().sqrt();
    assert!(err < 1e-2, "{err}");
    // Partial synthesis from fewer coefficients.
    assert_eq!(mh.inverse(&[1.0]).unwrap().len(), mesh.vertex_count());
    assert!(matches!(mh.inverse(&[0.0; 17]), Err(SpectralError::Dimension(_))));
    assert!(mh.forward(&[1.0; 3]).is_err());
    assert!(mh.forward(&vec![f64::NAN; mesh.vertex_count()]).is_err());
}

#[test]
fn keeping_one_coefficient_collapses_to_the_centroid() {
    let mesh = shapes::torus(2.0, 0.5, 32, 12).unwrap();
    let mh = ManifoldHarmonics::new(&mesh, 8, &options()).unwrap();
    let mass = masses(&mesh);
    let area: f64 = mass.iter().sum();
    let centroid = mesh.positions().iter().zip(&mass).map(|(p, m)| *p * *m).sum::<DVec3>() / area;
    let filtered = filter(&mh, mesh.positions(), &Transfer::KeepFirst(1)).unwrap();
    assert!(filtered.iter().all(|p| p.distance(centroid) < 1e-10));
}

#[test]
fn unit_gain_is_the_identity_and_band_gains_scale_coefficients() {
    let mesh = shapes::icosphere(3).unwrap();
    let mh = ManifoldHarmonics::new(&mesh, 25, &options()).unwrap();
    let p = mesh.positions();
    let same = filter(&mh, p, &Transfer::Band { low: 0.0, high: 100.0, gain: 1.0 }).unwrap();
    assert!(same.iter().zip(p).all(|(a, b)| a.distance(*b) < 1e-12));
    // Exaggerate the band l = 2 (omega = sqrt 6): those coefficients triple,
    // the others are unchanged.
    let band = Transfer::Band { low: 2.0, high: 3.0, gain: 3.0 };
    let out = filter(&mh, p, &band).unwrap();
    let (before, after) = (mh.forward_points(p).unwrap(), mh.forward_points(&out).unwrap());
    for (i, w) in mh.frequencies().iter().enumerate() {
        let g = if (2.0..=3.0).contains(w) { 3.0 } else { 1.0 };
        assert!(after[i].distance(before[i] * g) < 1e-10, "{i}: {} vs {}", after[i], before[i] * g);
    }
    assert!(filter(&mh, p, &Transfer::LowPass { cutoff: -1.0, order: 2 }).is_err());
    assert!(filter_with(&mh, p, |_, _| f64::NAN, 0.0).is_err());
    assert!(filter(&mh, &p[1..], &Transfer::KeepFirst(3)).is_err());
}

#[test]
fn low_pass_removes_noise_from_a_sphere() {
    let mut mesh = shapes::icosphere(4).unwrap();
    // Deterministic radial noise of 2% amplitude.
    let mut rng = mesh_testkit::SplitMix64::new(12345);
    for p in mesh.positions_mut() {
        let r = 1.0 + 0.02 * (rng.unit() - 0.5);
        *p *= r;
    }
    let mh = ManifoldHarmonics::new(&mesh, 49, &options()).unwrap();
    let rms = |q: &[DVec3]| (q.iter().map(|p| (p.length() - 1.0).powi(2)).sum::<f64>() / q.len() as f64).sqrt();
    let noisy = rms(mesh.positions());
    let smooth = filter(&mh, mesh.positions(), &Transfer::LowPass { cutoff: 5.0, order: 4 }).unwrap();
    assert!(rms(&smooth) < noisy / 3.0, "{} -> {}", noisy, rms(&smooth));
}

#[test]
fn compression_error_decreases_with_the_number_of_coefficients() {
    let meshes = [Some(shapes::torus(2.0, 0.5, 48, 16).unwrap()), data_mesh("npm_bunny.obj")];
    for mesh in meshes.into_iter().flatten() {
        let k = 120.min(mesh.vertex_count());
        let mh = ManifoldHarmonics::new(&mesh, k, &options()).unwrap();
        let keeps: Vec<usize> = vec![1, 2, 4, 8, 16, 32, 64, 120];
        let curve = compression_curve(&mesh, &mh, &keeps).unwrap();
        for w in curve.windows(2) {
            assert!(w[1].rms <= w[0].rms * (1.0 + 1e-12), "{:?}", curve);
        }
        assert!(curve[7].rms < 0.2 * curve[0].rms, "{curve:?}");
        // The curve point equals the single compression.
        let (_, at16) = compress(&mesh, &mh, 16).unwrap();
        assert!((at16.rms - curve[4].rms).abs() < 1e-12 && (at16.max - curve[4].max).abs() < 1e-12);
        assert!(compress(&mesh, &mh, k + 1).is_err());
    }
}

#[test]
fn compression_with_every_coefficient_is_lossless() {
    let mesh = shapes::cube(3).unwrap();
    let n = mesh.vertex_count();
    let mh = ManifoldHarmonics::new(&mesh, n, &options()).unwrap();
    let (restored, error) = compress(&mesh, &mh, n).unwrap();
    assert!(error.max < 1e-12, "{error:?}");
    assert!(restored.positions().iter().zip(mesh.positions()).all(|(a, b)| a.distance(*b) < 1e-12));
}
