//! mesh-wavelet: perfect reconstruction of every filter bank, the sphere's
//! lazy coefficients against their closed form, geometric decay, compression
//! error falling with the kept fraction and lifting beating the lazy
//! wavelet, orthogonality under eq. 2.36, subdivision against polynomial
//! precision and Loop's limit positions, detection of subdivision
//! connectivity after shuffling and on the shared meshes.

use std::f64::consts::TAU;

use mesh_kernel::glam::DVec3;
use mesh_kernel::{shapes, TriMesh};
use mesh_wavelet::rules::loop_beta;
use mesh_wavelet::{
    decay_rate, detect, inner_product_matrix, subdivide, FilterBank, Hierarchy, MultiresOptions, Multiresolution,
    Scheme, SubdivideOptions, WaveletError, WaveletKind,
};

use super::{no_shared_data, shared_data, Validator};

const KINDS: [WaveletKind; 2] = [WaveletKind::Lazy, WaveletKind::Lifted];

/// Runs the mesh-wavelet checks.
pub fn run(v: &mut Validator) {
    reconstruction(v);
    sphere_sagitta(v);
    decay(v);
    compression(v);
    orthogonality(v);
    butterfly_cubic_precision(v);
    loop_limit(v);
    detection(v);
}

fn options(scheme: Scheme, wavelet: WaveletKind) -> MultiresOptions {
    MultiresOptions { scheme, wavelet, ..MultiresOptions::default() }
}

fn max_distance(a: &TriMesh, b: &TriMesh) -> f64 {
    a.positions().iter().zip(b.positions()).map(|(p, q)| p.distance(*q)).fold(0.0, f64::max)
}

fn diagonal(m: &TriMesh) -> f64 {
    mesh_kernel::geometry::bounding_box(m).map_or(1.0, |b| b.diagonal())
}

/// A torus base mesh split `levels` times, projected onto the exact torus.
fn smooth_torus(levels: usize) -> Result<TriMesh, WaveletError> {
    let fine = subdivide(&shapes::torus(2.0, 0.5, 12, 6)?, &SubdivideOptions { scheme: Scheme::Midpoint, levels })?;
    let p = fine
        .positions()
        .iter()
        .map(|p| {
            let c = DVec3::new(p.x, p.y, 0.0).normalize() * 2.0;
            c + (*p - c).normalize() * 0.5
        })
        .collect();
    Ok(TriMesh::new(p, fine.faces().to_vec())?)
}

/// The icosphere with radius 1 + 0.1 sin(3x) sin(3y) sin(3z).
fn bumpy_sphere(levels: u32) -> Result<TriMesh, WaveletError> {
    let s = shapes::icosphere(levels)?;
    let p = s
        .positions()
        .iter()
        .map(|p| *p * (1.0 + 0.1 * (3.0 * p.x).sin() * (3.0 * p.y).sin() * (3.0 * p.z).sin()))
        .collect();
    Ok(TriMesh::new(p, s.faces().to_vec())?)
}

/// Analysis then synthesis returns the input to 1e-12 relative, for every
/// scheme, wavelet and level count (the bound).
fn reconstruction(v: &mut Validator) {
    let mut cases: Vec<(String, Result<TriMesh, WaveletError>)> =
        vec![("icosphere(5)".into(), shapes::icosphere(5).map_err(Into::into)), ("torus".into(), smooth_torus(3))];
    if let Some(dir) = shared_data() {
        cases.push((
            "cgal_holes.off".into(),
            mesh_io::read(dir.join("cgal_holes.off"))
                .map(|d| d.mesh)
                .map_err(|e| WaveletError::InvalidOption { name: "file", reason: e.to_string() }),
        ));
    }
    for (name, mesh) in cases {
        let mesh = match mesh {
            Ok(m) => m,
            Err(e) => {
                v.error(format!("reconstruction {name}"), e);
                continue;
            }
        };
        let mut worst: f64 = 0.0;
        let mut failure = None;
        for levels in 1..=5 {
            for scheme in Scheme::ALL {
                for wavelet in KINDS {
                    let o = MultiresOptions { scheme, wavelet, max_levels: levels };
                    match Multiresolution::analyze(&mesh, &o).and_then(|mr| mr.synthesize()) {
                        Ok(back) => worst = worst.max(max_distance(&mesh, &back) / diagonal(&mesh)),
                        Err(e) => failure = Some(e),
                    }
                }
            }
        }
        match failure {
            Some(e) => v.error(format!("{name}: analysis + synthesis"), e),
            None => {
                v.at_most(format!("{name}: analysis + synthesis, all schemes, wavelets, levels (rel.)"), worst, 1e-12)
            }
        }
    }
}

/// The icosphere places each new vertex at the normalised midpoint of unit
/// vectors a, b: the lazy linear coefficient is (1 - cos(theta/2)) times
/// the unit midpoint direction, exactly.
fn sphere_sagitta(v: &mut Validator) {
    let run = || -> Result<f64, WaveletError> {
        let mesh = shapes::icosphere(5)?;
        let mr = Multiresolution::analyze(&mesh, &options(Scheme::Midpoint, WaveletKind::Lazy))?;
        let h = mr.hierarchy().clone();
        let mut worst: f64 = 0.0;
        for j in 0..mr.levels() {
            let coarse = mr.level_positions(j)?;
            for (w, &[a, b]) in mr.coefficients(j)?.iter().zip(h.parents(j)?) {
                let (pa, pb) = (coarse[a as usize], coarse[b as usize]);
                let expected = (pa + pb).normalize() * (1.0 - (pa.angle_between(pb) / 2.0).cos());
                worst = worst.max(w.distance(expected));
            }
        }
        Ok(worst)
    };
    match run() {
        Ok(e) => v.at_most("icosphere(5) lazy linear coefficients vs 1 - cos(theta/2)", e, 1e-14),
        Err(e) => v.error("icosphere(5) lazy linear coefficients", e),
    }
}

/// Coefficient magnitudes decay geometrically with level on smooth surfaces;
/// for the lazy linear wavelet on the sphere the ratio tends to 4 (theta
/// halves, the sagitta goes as theta^2).
fn decay(v: &mut Validator) {
    let surfaces: Vec<(&str, Result<TriMesh, WaveletError>)> = vec![
        ("icosphere(5)", shapes::icosphere(5).map_err(Into::into)),
        ("torus", smooth_torus(4)),
        ("bumpy sphere", bumpy_sphere(5)),
    ];
    for (name, mesh) in surfaces {
        let Ok(mesh) = mesh else {
            v.error(format!("decay {name}"), "mesh construction failed");
            continue;
        };
        for scheme in Scheme::ALL {
            for wavelet in KINDS {
                match Multiresolution::analyze(&mesh, &options(scheme, wavelet)) {
                    Ok(mr) => {
                        let stats = mr.statistics();
                        let rate = decay_rate(&stats).unwrap_or(f64::NAN);
                        let finest = stats[stats.len() - 2].mean / stats[stats.len() - 1].mean;
                        v.at_least(format!("{name} {scheme} {wavelet}: decay rate per level"), rate, 2.5);
                        if scheme == Scheme::Midpoint && wavelet == WaveletKind::Lazy && name == "icosphere(5)" {
                            v.at_most("icosphere(5) lazy linear: |finest ratio - 4|", (finest - 4.0).abs(), 0.05);
                        }
                    }
                    Err(e) => v.error(format!("decay {name} {scheme} {wavelet}"), e),
                }
            }
        }
    }
}

/// Compression error falls with the kept fraction; the lifted linear wavelet
/// beats the lazy one at every fraction.
fn compression(v: &mut Validator) {
    let fractions = [0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1.0];
    let surfaces: Vec<(&str, Result<TriMesh, WaveletError>)> = vec![
        ("icosphere(5)", shapes::icosphere(5).map_err(Into::into)),
        ("torus", smooth_torus(4)),
        ("bumpy sphere", bumpy_sphere(5)),
    ];
    for (name, mesh) in surfaces {
        let Ok(mesh) = mesh else { continue };
        for scheme in Scheme::ALL {
            let mut curves = Vec::new();
            for wavelet in KINDS {
                match Multiresolution::analyze(&mesh, &options(scheme, wavelet))
                    .and_then(|mr| mr.compression_curve(&fractions))
                {
                    Ok(c) => {
                        let increases = c.windows(2).filter(|w| w[1].rms_error > w[0].rms_error * (1.0 + 1e-9)).count();
                        v.equal(
                            format!("{name} {scheme} {wavelet}: rms error increases with kept fraction"),
                            increases as i64,
                            0,
                        );
                        v.at_most(format!("{name} {scheme} {wavelet}: rms error keeping all"), c[6].rms_error, 1e-14);
                        curves.push(c);
                    }
                    Err(e) => v.error(format!("compression {name} {scheme} {wavelet}"), e),
                }
            }
            if curves.len() == 2 && scheme == Scheme::Midpoint {
                let worst = curves[0][..6]
                    .iter()
                    .zip(&curves[1][..6])
                    .map(|(lazy, lifted)| lifted.rms_error / lazy.rms_error)
                    .fold(0.0, f64::max);
                v.at_most(format!("{name} midpoint: worst lifted / lazy rms error, 1% to 50% kept"), worst, 1.0);
            }
        }
    }
}

/// RMS cosine between wavelets and coarse hat functions under eq. 2.36:
/// lifting at least halves it (midpoint, exact inner products).
fn orthogonality(v: &mut Validator) {
    let run = |kind: WaveletKind| -> Result<f64, WaveletError> {
        let base = shapes::icosphere(0)?;
        let h = Hierarchy::from_base(base.vertex_count(), base.faces(), 2)?;
        let bank = FilterBank::new(&h, Scheme::Midpoint, kind)?;
        let m = bank.matrices(1).ok_or_else(|| WaveletError::Dimension("level".into()))?;
        let g = inner_product_matrix(h.vertex_count(2)?, h.faces(2)?, 2)?;
        let gp = &g * &m.p;
        let gq = &g * &m.q;
        let cross = &m.q.transpose_view().to_csr() * &gp;
        let pp = &m.p.transpose_view().to_csr() * &gp;
        let qq = &m.q.transpose_view().to_csr() * &gq;
        let (mut sum, mut count) = (0.0, 0usize);
        for (&c, (i, k)) in cross.iter() {
            let norm = (qq.get(i, i).copied().unwrap_or(0.0) * pp.get(k, k).copied().unwrap_or(0.0)).sqrt();
            sum += (c / norm).powi(2);
            count += 1;
        }
        Ok((sum / count.max(1) as f64).sqrt())
    };
    match (run(WaveletKind::Lazy), run(WaveletKind::Lifted)) {
        (Ok(lazy), Ok(lifted)) => v.at_most("eq. 2.36: rms cosine(psi, phi) lifted / lazy", lifted / lazy, 0.5),
        (Err(e), _) | (_, Err(e)) => v.error("eq. 2.36 orthogonality", e),
    }
}

fn cubic(x: f64, y: f64) -> f64 {
    0.3 + 1.1 * x - 0.7 * y + 0.5 * x * x - 0.8 * x * y + 0.25 * y * y + 0.9 * x * x * x - 0.4 * x * x * y
        + 0.6 * x * y * y
        - 0.2 * y * y * y
}

/// The butterfly (w = 1/16) and the boundary 4-point rule reproduce cubics.
fn butterfly_cubic_precision(v: &mut Validator) {
    let run = || -> Result<f64, WaveletError> {
        let n = 8;
        let g = shapes::grid(1.0, 1.0, n, n)?;
        let p = g.positions().iter().map(|p| DVec3::new(p.x, p.y, cubic(p.x, p.y))).collect();
        let m = TriMesh::new(p, g.faces().to_vec())?;
        let s = subdivide(&m, &SubdivideOptions { scheme: Scheme::Butterfly, levels: 1 })?;
        let h = 1.0 / n as f64;
        let mut worst: f64 = 0.0;
        for p in &s.positions()[m.vertex_count()..] {
            let (dx, dy) = (p.x.min(1.0 - p.x), p.y.min(1.0 - p.y));
            let interior = dx > 2.0 * h && dy > 2.0 * h;
            let boundary = (dx.abs() < 1e-12 && dy > 1.5 * h) || (dy.abs() < 1e-12 && dx > 1.5 * h);
            if interior || boundary {
                worst = worst.max((p.z - cubic(p.x, p.y)).abs());
            }
        }
        Ok(worst)
    };
    match run() {
        Ok(e) => v.at_most("butterfly: new vertices on a cubic graph (regular + boundary masks)", e, 1e-12),
        Err(e) => v.error("butterfly cubic precision", e),
    }
}

/// Loop converges to the limit position (1 - n w) v + w sum v_i,
/// w = 1 / (n + 3 / (8 beta)), at the rate of the subdominant eigenvalue.
fn loop_limit(v: &mut Validator) {
    let run = || -> Result<(f64, f64), WaveletError> {
        let ico = shapes::icosphere(0)?;
        let c = ico.connectivity();
        let v0 = mesh_kernel::VertexId(0);
        let n = c.valence(v0);
        let w = 1.0 / (n as f64 + 3.0 / (8.0 * loop_beta(n)));
        let sum: DVec3 = c.neighbors(v0).map(|u| ico.position(u)).sum();
        let limit = (1.0 - n as f64 * w) * ico.position(v0) + w * sum;
        let errors: Vec<f64> = (5..=7)
            .map(|l| {
                subdivide(&ico, &SubdivideOptions { scheme: Scheme::Loop, levels: l })
                    .map(|s| s.positions()[0].distance(limit))
            })
            .collect::<Result<_, _>>()?;
        Ok((errors[2], (errors[2] / errors[1]).max(errors[1] / errors[0])))
    };
    match run() {
        Ok((e, rate)) => {
            v.at_most("Loop: distance to the limit position after 7 levels", e, 1e-5);
            let lambda = 3.0 / 8.0 + 0.25 * (TAU / 5.0).cos();
            v.at_most("Loop: per-level contraction / lambda^2 (valence 5)", rate / (lambda * lambda), 1.0 + 1e-3);
        }
        Err(e) => v.error("Loop limit", e),
    }
}

/// Subdivide, shuffle, detect: the levels and the base mesh come back; the
/// shared meshes without subdivision connectivity say so.
fn detection(v: &mut Validator) {
    // (cube(2) would not do: it is cube(1) split once, and detection finds that.)
    for (name, base) in
        [("icosahedron", shapes::icosphere(0)), ("cube(1)", shapes::cube(1)), ("disk(3)", shapes::disk(3, 1))]
    {
        let run = || -> Result<(usize, usize, usize, f64), WaveletError> {
            let base = base.clone()?;
            let fine = subdivide(&base, &SubdivideOptions { scheme: Scheme::Loop, levels: 3 })?;
            // Reverse the vertex order: the hierarchy is lost.
            let n = fine.vertex_count() as u32;
            let p: Vec<DVec3> = fine.positions().iter().rev().copied().collect();
            let f: Vec<[u32; 3]> = fine.faces().iter().map(|t| t.map(|x| n - 1 - x)).collect();
            let shuffled = TriMesh::new(p, f)?;
            let h = detect(&shuffled, &Default::default())?;
            let mr = Multiresolution::analyze(&shuffled, &options(Scheme::Loop, WaveletKind::Lifted))?;
            let err = max_distance(&shuffled, &mr.synthesize()?) / diagonal(&shuffled);
            Ok((h.levels(), h.vertex_count(0)?, h.faces(0)?.len(), err))
        };
        match (run(), base) {
            (Ok((levels, nv, nf, err)), Ok(b)) => {
                v.equal(format!("detect {name} split 3 times, shuffled: levels"), levels as i64, 3);
                v.equal(format!("detect {name}: base vertices"), nv as i64, b.vertex_count() as i64);
                v.equal(format!("detect {name}: base faces"), nf as i64, b.face_count() as i64);
                v.at_most(format!("detect {name}: Loop analysis + synthesis (rel.)"), err, 1e-12);
            }
            (Err(e), _) => v.error(format!("detect {name}"), e),
            (_, Err(e)) => v.error(format!("detect {name}"), e),
        }
    }
    let Some(dir) = shared_data() else {
        v.skip("detect shared meshes", no_shared_data());
        return;
    };
    let table = [
        ("npm_bunny.obj", None),
        ("cgal_elephant.off", None),
        ("cgal_fandisk.off", None),
        ("cgal_nefertiti.off", None),
        ("cgal_holes.off", Some((2, 292))),
        ("cgal_mushroom.off", Some((2, 153))),
    ];
    for (file, expected) in table {
        let mesh = match mesh_io::read(dir.join(file)) {
            Ok(d) => d.mesh,
            Err(e) => {
                v.error(format!("detect {file}"), e);
                continue;
            }
        };
        match (detect(&mesh, &Default::default()), expected) {
            (Err(WaveletError::NoSubdivisionConnectivity { .. }), None) => {
                v.holds(format!("detect {file}: no subdivision connectivity"), true, "typed error")
            }
            (Ok(h), Some((levels, n0))) => {
                v.equal(format!("detect {file}: levels"), h.levels() as i64, levels);
                v.equal(format!("detect {file}: base vertices"), h.vertex_count(0).unwrap_or(0) as i64, n0);
            }
            (other, _) => v.holds(format!("detect {file}"), false, format!("{other:?}")),
        }
    }
}
