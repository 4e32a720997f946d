//! Filter banks and the multiresolution representation: perfect
//! reconstruction, the sparse matrices, orthogonality under eq. 2.36,
//! coefficients on the sphere against their closed form, decay, compression,
//! editing, level of detail and bad input.

mod common;

use std::sync::Arc;

use common::{bumpy_sphere, real_mesh, relative_max_distance, shuffled, smooth_torus, SplitMix64};
use mesh_kernel::{glam::DVec3, shapes, sprs::CsMat, MeshError, TriMesh};
use mesh_wavelet::{
    decay_rate, inner_product_matrix, subdivide, CompressOptions, FilterBank, Hierarchy, MultiresOptions,
    Multiresolution, Scheme, SubdivideOptions, WaveletError, WaveletKind,
};
use proptest::prelude::*;

const KINDS: [WaveletKind; 2] = [WaveletKind::Lazy, WaveletKind::Lifted];

fn options(scheme: Scheme, wavelet: WaveletKind) -> MultiresOptions {
    MultiresOptions { scheme, wavelet, ..Default::default() }
}

/// Smooth surfaces with subdivision connectivity, and a real one.
fn surfaces() -> Vec<(&'static str, TriMesh)> {
    let mut v = vec![
        ("sphere", shapes::icosphere(4).unwrap()),
        ("torus", smooth_torus(3)),
        ("bumpy sphere", bumpy_sphere(4)),
        (
            "loop disk",
            subdivide(&shapes::disk(3, 2).unwrap(), &SubdivideOptions { scheme: Scheme::Loop, levels: 3 }).unwrap(),
        ),
    ];
    if let Some(m) = real_mesh("cgal_holes.off") {
        v.push(("cgal_holes", m));
    }
    v
}

#[test]
fn analysis_then_synthesis_is_the_identity() {
    for (name, mesh) in surfaces() {
        for scheme in Scheme::ALL {
            for wavelet in KINDS {
                let mr = Multiresolution::analyze(&mesh, &options(scheme, wavelet)).unwrap();
                let back = mr.synthesize().unwrap();
                assert_eq!(back.faces(), mesh.faces());
                let err = relative_max_distance(&mesh, &back);
                assert!(err < 1e-12, "{name} {scheme} {wavelet}: {err:e}");
            }
        }
    }
    // Every level count from 1 to 5.
    let sphere = shapes::icosphere(5).unwrap();
    for levels in 1..=5 {
        for scheme in Scheme::ALL {
            for wavelet in KINDS {
                let o = MultiresOptions { scheme, wavelet, max_levels: levels };
                let mr = Multiresolution::analyze(&sphere, &o).unwrap();
                assert_eq!(mr.levels(), levels);
                assert!(relative_max_distance(&sphere, &mr.synthesize().unwrap()) < 1e-12);
            }
        }
    }
}

fn dense(m: &CsMat<f64>) -> Vec<Vec<f64>> {
    let (r, c) = m.shape();
    let mut d = vec![vec![0.0; c]; r];
    for (&v, (i, j)) in m.iter() {
        d[i][j] += v;
    }
    d
}

fn max_abs_diff_from(m: &CsMat<f64>, identity: bool) -> f64 {
    let d = dense(m);
    let mut worst: f64 = 0.0;
    for (i, row) in d.iter().enumerate() {
        for (j, &v) in row.iter().enumerate() {
            let target = if identity && i == j { 1.0 } else { 0.0 };
            worst = worst.max((v - target).abs());
        }
    }
    worst
}

#[test]
fn sparse_matrices_are_biorthogonal_and_match_the_lifting() {
    let meshes = [shapes::icosphere(0).unwrap(), shapes::disk(3, 1).unwrap()];
    for base in &meshes {
        let h = Hierarchy::from_base(base.vertex_count(), base.faces(), 2).unwrap();
        for scheme in Scheme::ALL {
            for wavelet in KINDS {
                let bank = FilterBank::new(&h, scheme, wavelet).unwrap();
                for j in 0..2 {
                    let m = bank.matrices(j).unwrap();
                    let (nc, n) = (h.vertex_count(j).unwrap(), h.vertex_count(j + 1).unwrap());
                    assert_eq!(
                        (m.p.shape(), m.q.shape(), m.a.shape(), m.b.shape()),
                        ((n, nc), (n, n - nc), (nc, n), (n - nc, n))
                    );
                    assert!(max_abs_diff_from(&(&m.a * &m.p), true) < 1e-13);
                    assert!(max_abs_diff_from(&(&m.b * &m.q), true) < 1e-13);
                    assert!(max_abs_diff_from(&(&m.a * &m.q), false) < 1e-13);
                    assert!(max_abs_diff_from(&(&m.b * &m.p), false) < 1e-13);
                    let pa_qb = &(&m.p * &m.a) + &(&m.q * &m.b);
                    assert!(max_abs_diff_from(&pa_qb, true) < 1e-13);
                    // The in-place analysis step computes [A x; B x].
                    let mut rng = SplitMix64::new(j as u64 + 17);
                    let x: Vec<f64> = (0..n).map(|_| rng.signed()).collect();
                    let mut y = x.clone();
                    bank.level(j).unwrap().analyze(&mut y).unwrap();
                    let (ax, bx) = (dense(&m.a), dense(&m.b));
                    for i in 0..nc {
                        let v: f64 = ax[i].iter().zip(&x).map(|(a, b)| a * b).sum();
                        assert!((v - y[i]).abs() < 1e-13);
                    }
                    for i in 0..n - nc {
                        let v: f64 = bx[i].iter().zip(&x).map(|(a, b)| a * b).sum();
                        assert!((v - y[nc + i]).abs() < 1e-13);
                    }
                }
                // P is the subdivision matrix of the scheme.
                let m = bank.matrices(0).unwrap();
                let p = dense(&m.p);
                let s = subdivide(base, &SubdivideOptions { scheme, levels: 1 }).unwrap();
                for (i, row) in p.iter().enumerate() {
                    let v: DVec3 = row.iter().zip(base.positions()).map(|(w, q)| *q * *w).sum();
                    assert!(v.distance(s.positions()[i]) < 1e-13, "{scheme} {wavelet} row {i}");
                }
                assert!(bank.matrices(2).is_none());
            }
        }
    }
}

/// Root mean square of the cosines between wavelets and coarse scaling
/// functions, over the pairs that overlap, under the inner product of eq. 2.36.
fn wavelet_scaling_cosines(h: &Hierarchy, bank: &FilterBank, j: usize) -> f64 {
    let g = dense(&inner_product_matrix(h.vertex_count(j + 1).unwrap(), h.faces(j + 1).unwrap(), j + 1).unwrap());
    let m = bank.matrices(j).unwrap();
    let (p, q) = (dense(&m.p), dense(&m.q));
    let n = g.len();
    let col = |a: &Vec<Vec<f64>>, c: usize| (0..n).map(|i| a[i][c]).collect::<Vec<f64>>();
    let inner =
        |u: &[f64], v: &[f64]| -> f64 { (0..n).map(|i| (0..n).map(|k| u[i] * g[i][k] * v[k]).sum::<f64>()).sum() };
    let phis: Vec<Vec<f64>> = (0..p[0].len()).map(|c| col(&p, c)).collect();
    let psis: Vec<Vec<f64>> = (0..q[0].len()).map(|c| col(&q, c)).collect();
    let (mut sum, mut count) = (0.0, 0);
    for psi in &psis {
        let npsi = inner(psi, psi).sqrt();
        for phi in &phis {
            let overlap = psi.iter().zip(phi).any(|(a, b)| *a != 0.0 && *b != 0.0);
            if overlap {
                let c = inner(psi, phi) / (npsi * inner(phi, phi).sqrt());
                sum += c * c;
                count += 1;
            }
        }
    }
    (sum / count as f64).sqrt()
}

#[test]
fn lifted_wavelets_are_closer_to_orthogonal_under_eq_2_36() {
    for base in [shapes::icosphere(0).unwrap(), shapes::disk(3, 1).unwrap()] {
        let h = Hierarchy::from_base(base.vertex_count(), base.faces(), 2).unwrap();
        for scheme in Scheme::ALL {
            for j in 0..2 {
                let lazy = wavelet_scaling_cosines(&h, &FilterBank::new(&h, scheme, WaveletKind::Lazy).unwrap(), j);
                let lifted = wavelet_scaling_cosines(&h, &FilterBank::new(&h, scheme, WaveletKind::Lifted).unwrap(), j);
                println!("{scheme} level {j}: rms cosine lazy {lazy:.3}, lifted {lifted:.3}");
                if scheme == Scheme::Midpoint {
                    assert!(lifted < 0.5 * lazy, "{scheme} level {j}: lazy {lazy}, lifted {lifted}");
                } else {
                    assert!(lifted < lazy, "{scheme} level {j}: lazy {lazy}, lifted {lifted}");
                }
            }
        }
    }
}

#[test]
fn lazy_linear_coefficients_on_the_sphere_are_the_sagitta() {
    // The icosphere puts each new vertex at the normalised midpoint of unit
    // vectors a, b: the lazy linear wavelet coefficient is exactly
    // (1 - cos(theta/2)) times the unit midpoint direction.
    let mesh = shapes::icosphere(5).unwrap();
    let mr = Multiresolution::analyze(&mesh, &options(Scheme::Midpoint, WaveletKind::Lazy)).unwrap();
    let h = mr.hierarchy().clone();
    let mut means = Vec::new();
    for j in 0..mr.levels() {
        let coarse = mr.level_positions(j).unwrap();
        let w = mr.coefficients(j).unwrap();
        for (i, &[a, b]) in h.parents(j).unwrap().iter().enumerate() {
            let (pa, pb) = (coarse[a as usize], coarse[b as usize]);
            let theta = pa.angle_between(pb);
            let expected = (pa + pb).normalize() * (1.0 - (theta / 2.0).cos());
            assert!(w[i].distance(expected) < 1e-14, "level {j}, coefficient {i}");
        }
        means.push(w.iter().map(|c| c.length()).sum::<f64>() / w.len() as f64);
    }
    // theta halves per level, so the sagitta shrinks by 4.
    let last = means[means.len() - 2] / means[means.len() - 1];
    assert!((last - 4.0).abs() < 0.05, "{means:?}");
    assert!(decay_rate(&mr.statistics()).unwrap() > 3.7);
}

#[test]
fn coefficients_decay_geometrically_on_smooth_surfaces() {
    for (name, mesh) in
        [("sphere", shapes::icosphere(5).unwrap()), ("torus", smooth_torus(4)), ("bumpy", bumpy_sphere(5))]
    {
        for scheme in Scheme::ALL {
            for wavelet in KINDS {
                let mr = Multiresolution::analyze(&mesh, &options(scheme, wavelet)).unwrap();
                let stats = mr.statistics();
                let rate = decay_rate(&stats).unwrap();
                let finest = stats[stats.len() - 2].mean / stats[stats.len() - 1].mean;
                println!("{name} {scheme} {wavelet}: decay rate {rate:.2}, finest ratio {finest:.2}");
                assert!(rate > 2.5 && finest > 3.0, "{name} {scheme} {wavelet}: {rate} {finest}");
            }
        }
    }
}

#[test]
fn compression_error_falls_with_the_kept_fraction_and_lifting_helps() {
    let fractions = [0.0, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1.0];
    for (name, mesh) in surfaces().into_iter().filter(|s| s.0 != "loop disk") {
        for scheme in Scheme::ALL {
            let mut curves = Vec::new();
            for wavelet in KINDS {
                let mr = Multiresolution::analyze(&mesh, &options(scheme, wavelet)).unwrap();
                let curve = mr.compression_curve(&fractions).unwrap();
                for w in curve.windows(2) {
                    assert!(w[1].rms_error <= w[0].rms_error * (1.0 + 1e-9), "{name} {scheme} {wavelet}: {curve:?}");
                    assert!(w[1].kept_coefficients >= w[0].kept_coefficients);
                }
                assert!(curve[7].rms_error < 1e-14 && curve[7].max_error < 1e-14);
                assert!(curve[0].rms_error > curve[1].rms_error);
                // compress() agrees with the curve.
                let c = mr.compress(&CompressOptions { keep_fraction: 0.1 }).unwrap();
                assert_eq!(c.kept_coefficients, curve[4].kept_coefficients);
                assert!((c.rms_error - curve[4].rms_error).abs() <= 1e-12 * curve[4].rms_error.max(1e-300));
                assert!(c.max_error >= c.rms_error);
                curves.push(curve);
            }
            for (lazy, lifted) in curves[0][1..7].iter().zip(&curves[1][1..7]) {
                println!(
                    "{name} {scheme} keep {}: lazy {:.3e} lifted {:.3e}",
                    lazy.keep_fraction, lazy.rms_error, lifted.rms_error
                );
                if scheme == Scheme::Midpoint {
                    assert!(lifted.rms_error < lazy.rms_error, "{name} keep {}", lazy.keep_fraction);
                }
            }
            let mean_log_ratio: f64 = curves[0][1..7]
                .iter()
                .zip(&curves[1][1..7])
                .map(|(a, b)| (b.rms_error / a.rms_error).ln())
                .sum::<f64>()
                / 6.0;
            assert!(mean_log_ratio < 0.0, "{name} {scheme}: lifting does not help on average");
        }
    }
}

#[test]
fn a_subdivision_surface_has_no_details_in_its_own_scheme() {
    // Synthesis with zero coefficients is the scheme's subdivision, so the
    // analysis of a subdivided mesh gives back its base and zero details.
    let base = shapes::disk(3, 2).unwrap();
    let base = TriMesh::new(
        base.positions().iter().map(|p| DVec3::new(p.x, p.y, (3.0 * p.x).sin() * p.y)).collect(),
        base.faces().to_vec(),
    )
    .unwrap();
    for scheme in Scheme::ALL {
        let fine = subdivide(&base, &SubdivideOptions { scheme, levels: 3 }).unwrap();
        for wavelet in KINDS {
            let mr = Multiresolution::analyze(&fine, &options(scheme, wavelet)).unwrap();
            assert_eq!(mr.levels(), 3);
            let largest = mr.statistics().iter().map(|s| s.max).fold(0.0, f64::max);
            assert!(largest < 1e-14, "{scheme} {wavelet}: {largest:e}");
            let b = mr.level(0).unwrap();
            assert!(relative_max_distance(&base, &b) < 1e-14);
            let c = mr.compress(&CompressOptions { keep_fraction: 0.0 }).unwrap();
            assert!(c.rms_error < 1e-14);
        }
        // Other schemes do see details.
        for other in Scheme::ALL.into_iter().filter(|&o| o != scheme) {
            let mr = Multiresolution::analyze(&fine, &options(other, WaveletKind::Lazy)).unwrap();
            assert!(mr.statistics()[2].max > 1e-6, "{scheme} analysed with {other}");
        }
    }
}

#[test]
fn editing_the_base_mesh_carries_the_details() {
    let mesh = bumpy_sphere(4);
    let t = DVec3::new(0.3, -1.2, 2.5);
    for scheme in Scheme::ALL {
        for wavelet in KINDS {
            let mut mr = Multiresolution::analyze(&mesh, &options(scheme, wavelet)).unwrap();
            // Translating the base translates everything (partition of unity).
            let base: Vec<DVec3> = mr.level(0).unwrap().positions().iter().map(|p| *p + t).collect();
            mr.set_base_positions(&base).unwrap();
            let moved = mr.synthesize().unwrap();
            for (p, q) in moved.positions().iter().zip(mesh.positions()) {
                assert!(p.distance(*q + t) < 1e-12);
            }
            // Moving one base vertex moves the surface by d times the base
            // scaling function: 1 at the vertex for interpolating schemes,
            // within [0, 1] for midpoint and Loop (nonnegative, partition of unity).
            let mut mr = Multiresolution::analyze(&mesh, &options(scheme, wavelet)).unwrap();
            let mut base = mr.level(0).unwrap().positions().to_vec();
            let d = DVec3::new(0.0, 0.0, 0.5);
            base[3] += d;
            mr.set_base_positions(&base).unwrap();
            let edited = mr.synthesize().unwrap();
            let phi: Vec<f64> = edited
                .positions()
                .iter()
                .zip(mesh.positions())
                .map(|(p, q)| (*p - *q).dot(d) / d.length_squared())
                .collect();
            let h = mr.hierarchy();
            let at_vertex =
                phi[h.input_index(h.output_order(0).unwrap().iter().position(|&o| o == 3).unwrap()).unwrap()];
            if scheme.is_interpolating() {
                assert!((at_vertex - 1.0).abs() < 1e-12);
            }
            if scheme != Scheme::Butterfly {
                assert!(phi.iter().all(|&x| (-1e-12..=1.0 + 1e-12).contains(&x)), "{scheme} {wavelet}");
            }
            // The hat function of the icosahedron vertex covers its 5 of 20 faces.
            let support = phi.iter().filter(|x| x.abs() > 1e-12).count();
            if scheme == Scheme::Midpoint {
                assert!(support < mesh.vertex_count() / 3, "local support: {support}");
            }
        }
    }
}

#[test]
fn reconstruction_from_subsets_and_levels_of_detail() {
    // The icosphere's numbering is the hierarchical one (mesh-kernel builds
    // it with midpoint_subdivide), so meshes compare vertex by vertex.
    let mesh = bumpy_sphere(4);
    for scheme in Scheme::ALL {
        for wavelet in KINDS {
            let mr = Multiresolution::analyze(&mesh, &options(scheme, wavelet)).unwrap();
            assert!(relative_max_distance(&mesh, &mr.reconstruct(|_, _| true).unwrap()) < 1e-12);
            for k in 0..mr.levels() {
                let partial = mr.reconstruct(|j, _| j < k).unwrap();
                let lod = mr.level(k).unwrap();
                assert_eq!(lod.vertex_count(), mr.hierarchy().vertex_count(k).unwrap());
                assert_eq!(lod.faces(), mr.hierarchy().faces(k).unwrap());
                let refined = subdivide(&lod, &SubdivideOptions { scheme, levels: mr.levels() - k }).unwrap();
                assert!(relative_max_distance(&refined, &partial) < 1e-12, "{scheme} {wavelet} k = {k}");
            }
            // Dropping the odd coefficients of one level changes only the
            // support of those wavelets.
            let mut mr2 = mr.clone();
            mr2.coefficients_mut(0).unwrap()[0] += DVec3::X;
            assert!(relative_max_distance(&mesh, &mr2.synthesize().unwrap()) > 1e-3);
        }
    }
    // A shuffled input: levels of detail keep the relative input order and
    // the lazy interpolating wavelet subsamples.
    let (shuffled_mesh, _) = shuffled(&mesh, 5);
    let mr = Multiresolution::analyze(&shuffled_mesh, &options(Scheme::Midpoint, WaveletKind::Lazy)).unwrap();
    let h = mr.hierarchy();
    for j in 0..=mr.levels() {
        let mut inputs: Vec<usize> = (0..h.vertex_count(j).unwrap()).map(|v| h.input_index(v).unwrap()).collect();
        inputs.sort_unstable();
        let lod = mr.level(j).unwrap();
        for (k, &i) in inputs.iter().enumerate() {
            assert_eq!(lod.positions()[k], shuffled_mesh.positions()[i]);
        }
    }
    assert_eq!(mr.level(mr.levels()).unwrap().faces(), shuffled_mesh.faces());
}

#[test]
fn bad_input_is_a_typed_error() {
    let mesh = shapes::icosphere(2).unwrap();
    let mut mr = Multiresolution::analyze(&mesh, &MultiresOptions::default()).unwrap();
    assert!(matches!(mr.coefficients(2), Err(WaveletError::LevelOutOfRange { level: 2, levels: 2 })));
    assert!(mr.level(3).is_err());
    assert!(mr.level_positions(7).is_err());
    assert!(matches!(mr.set_base_positions(&[DVec3::ZERO]), Err(WaveletError::Dimension(_))));
    let mut nan = mr.level(0).unwrap().positions().to_vec();
    nan[0].x = f64::NAN;
    assert!(matches!(mr.set_base_positions(&nan), Err(WaveletError::Mesh(MeshError::NonFinitePosition { .. }))));
    for keep_fraction in [-0.1, 1.5, f64::NAN] {
        assert!(matches!(mr.compress(&CompressOptions { keep_fraction }), Err(WaveletError::InvalidOption { .. })));
        assert!(mr.compression_curve(&[keep_fraction]).is_err());
    }
    mr.coefficients_mut(1).unwrap()[0] = DVec3::splat(f64::INFINITY);
    assert!(mr.synthesize().is_err());
    assert!(mr.compress(&CompressOptions::default()).is_err());
    // A hierarchy and a bank that do not fit the positions.
    let h = Arc::new(Hierarchy::from_base(12, shapes::icosphere(0).unwrap().faces(), 1).unwrap());
    let bank = Arc::new(FilterBank::new(&h, Scheme::Loop, WaveletKind::Lifted).unwrap());
    assert!(Multiresolution::from_parts(h.clone(), bank.clone(), mesh.positions()).is_err());
    let mut short = vec![0.0; 5];
    assert!(bank.analyze(&mut short).is_err());
    assert!(bank.synthesize_to(&mut short, 9).is_err());
    // Non-manifold or empty input.
    let nonmanifold = TriMesh::new(
        vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z, DVec3::NEG_Y],
        vec![[0, 1, 2], [1, 0, 3], [0, 1, 4]],
    )
    .unwrap();
    assert!(matches!(
        Multiresolution::analyze(&nonmanifold, &MultiresOptions::default()),
        Err(WaveletError::Mesh(MeshError::NonManifold(_)))
    ));
    let empty = TriMesh::new(vec![], vec![]).unwrap();
    assert!(Multiresolution::analyze(&empty, &MultiresOptions::default()).is_err());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// Random geometry on a fixed hierarchy: analysis then synthesis and
    /// synthesis then analysis are identities, for scalars and points.
    #[test]
    fn transforms_are_inverse(seed in any::<u64>(), scheme_i in 0usize..3, lifted in any::<bool>()) {
        let scheme = Scheme::ALL[scheme_i];
        let wavelet = if lifted { WaveletKind::Lifted } else { WaveletKind::Lazy };
        let base = shapes::disk(2, 3).unwrap();
        let h = Hierarchy::from_base(base.vertex_count(), base.faces(), 3).unwrap();
        let bank = FilterBank::new(&h, scheme, wavelet).unwrap();
        let mut rng = SplitMix64::new(seed);
        let n = bank.len();
        let x: Vec<DVec3> = (0..n).map(|_| DVec3::new(rng.signed(), rng.signed(), rng.signed()) * 10.0).collect();
        let mut y = x.clone();
        bank.analyze(&mut y).unwrap();
        bank.synthesize(&mut y).unwrap();
        let scale = x.iter().map(|p| p.length()).fold(0.0, f64::max);
        prop_assert!(x.iter().zip(&y).all(|(a, b)| a.distance(*b) <= 1e-12 * scale));
        let mut z = x.clone();
        bank.synthesize(&mut z).unwrap();
        bank.analyze(&mut z).unwrap();
        prop_assert!(x.iter().zip(&z).all(|(a, b)| a.distance(*b) <= 1e-12 * scale));
        let s: Vec<f64> = (0..n).map(|_| rng.signed()).collect();
        let mut t = s.clone();
        bank.analyze(&mut t).unwrap();
        bank.synthesize(&mut t).unwrap();
        prop_assert!(s.iter().zip(&t).all(|(a, b)| (a - b).abs() <= 1e-12));
    }
}
