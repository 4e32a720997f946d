//! mesh-curvature: the accuracy targets for principal curvatures
//! and directions (torus 256 x 64, icosphere level 5, cylinder interior),
//! convergence orders of every estimator, Gauss-Bonnet with the boundary's
//! geodesic curvature on every shape and shared mesh, finite output on every
//! shared mesh (zero-area faces included).

use std::f64::consts::{PI, TAU};

use mesh_curvature::{
    curvature_tensor, gaussian_curvature, integral_curvature, mean_curvature, CurvatureTensor, Degree, FitOptions,
    GaussianOptions, IntegralOptions, MeanOptions, Neighborhood, TensorMethod, TensorOptions,
};
use mesh_kernel::glam::DVec3;
use mesh_kernel::{shapes, TriMesh};

use super::{convergence_order, no_shared_data, shared_data, Validator};

/// Runs the mesh-curvature checks.
pub fn run(v: &mut Validator) {
    targets(v);
    convergence(v);
    gauss_bonnet(v);
    shared_meshes(v);
    integral(v);
}

/// Exact curvature per vertex: (k1, k2, k1 direction if defined, checked).
type Truth = Vec<(f64, f64, Option<DVec3>, bool)>;

/// Torus R = 2, r = 0.5 with mesh-kernel's documented vertex parameters.
fn torus(nu: usize, nv: usize) -> mesh_kernel::Result<(TriMesh, Truth)> {
    let m = shapes::torus(2.0, 0.5, nu, nv)?;
    let truth = (0..nu * nv)
        .map(|i| {
            let (u, w) = (TAU * (i / nv) as f64 / nu as f64, TAU * (i % nv) as f64 / nv as f64);
            let d1 = DVec3::new(-w.sin() * u.cos(), -w.sin() * u.sin(), w.cos());
            (2.0, w.cos() / (2.0 + 0.5 * w.cos()), Some(d1), true)
        })
        .collect();
    Ok((m, truth))
}

/// Unit cylinder of height 2; checked off the boundary rings.
fn cylinder(around: usize, along: usize) -> mesh_kernel::Result<(TriMesh, Truth)> {
    let m = shapes::cylinder(1.0, 2.0, around, along)?;
    let truth = (0..around * (along + 1))
        .map(|i| {
            let (a, j) = (TAU * (i / (along + 1)) as f64 / around as f64, i % (along + 1));
            (1.0, 0.0, Some(DVec3::new(-a.sin(), a.cos(), 0.0)), j > 0 && j < along)
        })
        .collect();
    Ok((m, truth))
}

/// Ellipsoid (1, 0.8, 0.6) from a scaled icosphere: irregular triangles,
/// exact K and H.
fn ellipsoid(level: u32) -> mesh_kernel::Result<(TriMesh, Truth)> {
    let (a, b, c) = (1.0, 0.8, 0.6);
    let s = shapes::icosphere(level)?;
    let p: Vec<DVec3> = s.positions().iter().map(|p| DVec3::new(a * p.x, b * p.y, c * p.z)).collect();
    let truth = p
        .iter()
        .map(|q| {
            let g2 = DVec3::new(q.x / (a * a), q.y / (b * b), q.z / (c * c)).length_squared();
            let k = 1.0 / ((a * b * c) * (a * b * c) * g2 * g2);
            let h = (a * a + b * b + c * c - q.length_squared()) / (2.0 * (a * b * c) * (a * b * c) * g2.powf(1.5));
            let disc = (h * h - k).max(0.0).sqrt();
            (h + disc, h - disc, None, true)
        })
        .collect();
    Ok((TriMesh::new(p, s.faces().to_vec())?, truth))
}

/// Largest errors (k1, k2, K, H, direction in degrees) over checked vertices.
fn errors(t: &CurvatureTensor, truth: &Truth) -> [f64; 5] {
    let mut e = [0.0f64; 5];
    for (i, &(k1, k2, d1, check)) in truth.iter().enumerate() {
        if !check {
            continue;
        }
        e[0] = e[0].max((t.k1[i] - k1).abs());
        e[1] = e[1].max((t.k2[i] - k2).abs());
        e[2] = e[2].max((t.k1[i] * t.k2[i] - k1 * k2).abs());
        e[3] = e[3].max((0.5 * (t.k1[i] + t.k2[i]) - 0.5 * (k1 + k2)).abs());
        if let Some(d) = d1 {
            e[4] = e[4].max(t.d1[i].dot(d).abs().min(1.0).acos().to_degrees());
        }
    }
    e
}

fn tensor(m: &TriMesh, method: TensorMethod) -> mesh_curvature::error::Result<CurvatureTensor> {
    curvature_tensor(m, &TensorOptions { method, ..Default::default() })
}

/// The targets, on the default estimator.
fn targets(v: &mut Validator) {
    match torus(256, 64).map_err(|e| e.to_string()).and_then(|(m, t)| {
        let c = tensor(&m, TensorMethod::default()).map_err(|e| e.to_string())?;
        Ok(errors(&c, &t))
    }) {
        Ok(e) => {
            v.at_most("torus 256x64 max |k1 - 1/r| (libigl 0.10)", e[0], 0.01);
            v.at_most("torus 256x64 max |k2 - cos v/(R + r cos v)| (libigl 0.027)", e[1], 0.01);
            v.at_most("torus 256x64 max principal direction error, degrees", e[4], 2.0);
        }
        Err(e) => v.error("torus 256x64 curvature tensor", e),
    }
    match shapes::icosphere(5).map_err(|e| e.to_string()).and_then(|m| {
        let n = m.vertex_count();
        let c = tensor(&m, TensorMethod::default()).map_err(|e| e.to_string())?;
        Ok(errors(&c, &vec![(1.0, 1.0, None, true); n]))
    }) {
        Ok(e) => {
            for (k, name) in ["k1", "k2", "K", "H"].iter().enumerate() {
                v.at_most(format!("icosphere(5) max |{name} - 1| (tensor)"), e[k], 1e-3);
            }
        }
        Err(e) => v.error("icosphere(5) curvature tensor", e),
    }
    match cylinder(128, 64).map_err(|e| e.to_string()).and_then(|(m, t)| {
        let c = tensor(&m, TensorMethod::default()).map_err(|e| e.to_string())?;
        Ok(errors(&c, &t))
    }) {
        Ok(e) => {
            v.at_most("cylinder 128x64 interior max |k1 - 1|", e[0], 1e-3);
            v.at_most("cylinder 128x64 interior max |k2|", e[1], 1e-3);
        }
        Err(e) => v.error("cylinder curvature tensor", e),
    }
    // Pointwise Gaussian and mean curvature against the sphere.
    match shapes::icosphere(5).map_err(|e| e.to_string()).and_then(|m| {
        let k = gaussian_curvature(&m, &GaussianOptions::default()).map_err(|e| e.to_string())?;
        let h = mean_curvature(&m, &MeanOptions::default()).map_err(|e| e.to_string())?;
        let worst = |x: &[f64]| x.iter().map(|x| (x - 1.0).abs()).fold(0.0, f64::max);
        Ok((worst(&k.pointwise), worst(&h.pointwise)))
    }) {
        Ok((k, h)) => {
            v.at_most("icosphere(5) max |angle defect / mixed area - 1| (libigl 3.6e-4)", k, 1e-3);
            v.at_most("icosphere(5) max |cotan mean curvature - 1| (libigl 2.2e-6)", h, 1e-5);
        }
        Err(e) => v.error("icosphere(5) Gaussian and mean curvature", e),
    }
}

/// Errors at three refinements (mesh size halving) and their mean order.
fn orders(v: &mut Validator, name: &str, errs: mesh_kernel::Result<Vec<f64>>, min_order: f64) {
    match errs {
        Ok(e) => v.at_least(
            format!("{name} order ({})", e.iter().map(|x| format!("{x:.1e}")).collect::<Vec<_>>().join(" ")),
            convergence_order(&e),
            min_order,
        ),
        Err(e) => v.error(name, e),
    }
}

/// Observed orders against the expected ones (fits of degree d: d - 1, one
/// more on symmetric neighbourhoods; per-face and normal-cycle: 2 on a
/// regular grid; angle defect and cotangent formula: 2).
fn convergence(v: &mut Validator) {
    let tori = [(64, 16), (128, 32), (256, 64)];
    let torus_k = |method: TensorMethod, which: usize| -> mesh_kernel::Result<Vec<f64>> {
        tori.iter()
            .map(|&(nu, nv)| {
                let (m, t) = torus(nu, nv)?;
                let c = tensor(&m, method).map_err(|e| mesh_kernel::MeshError::Degenerate(e.to_string()))?;
                Ok(errors(&c, &t)[which])
            })
            .collect()
    };
    orders(v, "torus k1, quartic fit (default, expected >= 3)", torus_k(TensorMethod::default(), 0), 2.8);
    orders(v, "torus k2, quartic fit (default, expected >= 3)", torus_k(TensorMethod::default(), 1), 2.8);
    orders(v, "torus k1, Rusinkiewicz (expected 2)", torus_k(TensorMethod::Rusinkiewicz, 0), 1.8);
    orders(v, "torus k2, Rusinkiewicz (expected 2)", torus_k(TensorMethod::Rusinkiewicz, 1), 1.8);
    let nc = TensorMethod::NormalCycle(Neighborhood::Rings(1));
    orders(v, "torus k1, normal cycle 1-ring (expected 2)", torus_k(nc, 0), 1.8);
    orders(v, "torus k2, normal cycle 1-ring (expected 2)", torus_k(nc, 1), 1.8);
    let quadric = TensorMethod::Fit(FitOptions {
        neighborhood: Neighborhood::Rings(1),
        degree: Degree::Quadric,
        use_normals: false,
        refine_normal: false,
    });
    orders(v, "torus k1, quadric fit 1-ring (expected 2 on a regular grid)", torus_k(quadric, 0), 1.8);
    let ellipsoid_k = |which: usize| -> mesh_kernel::Result<Vec<f64>> {
        (3..=5)
            .map(|level| {
                let (m, t) = ellipsoid(level)?;
                let c = tensor(&m, TensorMethod::default())
                    .map_err(|e| mesh_kernel::MeshError::Degenerate(e.to_string()))?;
                Ok(errors(&c, &t)[which])
            })
            .collect()
    };
    orders(v, "ellipsoid (irregular) k1, quartic fit (expected 3)", ellipsoid_k(0), 2.7);
    orders(v, "ellipsoid (irregular) k2, quartic fit (expected 3)", ellipsoid_k(1), 2.7);
    let pointwise = |gaussian: bool| -> mesh_kernel::Result<Vec<f64>> {
        tori.iter()
            .map(|&(nu, nv)| {
                let (m, t) = torus(nu, nv)?;
                let err = |x: &[f64], f: &dyn Fn(f64, f64) -> f64| {
                    x.iter().zip(&t).map(|(x, (k1, k2, _, _))| (x - f(*k1, *k2)).abs()).fold(0.0, f64::max)
                };
                let to_mesh = |e: mesh_curvature::CurvatureError| mesh_kernel::MeshError::Degenerate(e.to_string());
                Ok(if gaussian {
                    err(&gaussian_curvature(&m, &GaussianOptions::default()).map_err(to_mesh)?.pointwise, &|a, b| a * b)
                } else {
                    err(&mean_curvature(&m, &MeanOptions::default()).map_err(to_mesh)?.pointwise, &|a, b| 0.5 * (a + b))
                })
            })
            .collect()
    };
    orders(v, "torus K, angle defect (expected 2)", pointwise(true), 1.8);
    orders(v, "torus H, cotangent formula (expected 2)", pointwise(false), 1.8);
}

/// Gauss-Bonnet through the crate's API: angle defects plus boundary
/// geodesic curvature equal 2 pi chi on every manifold mesh.
fn gauss_bonnet(v: &mut Validator) {
    let mut meshes: Vec<(String, TriMesh)> = Vec::new();
    for (name, m) in [
        ("icosphere(4)", shapes::icosphere(4)),
        ("torus", shapes::torus(2.0, 0.5, 48, 16)),
        ("cylinder", shapes::cylinder(1.0, 2.0, 24, 6)),
        ("disk", shapes::disk(10, 3)),
        ("grid", shapes::grid(1.0, 1.0, 9, 7)),
        ("cube", shapes::cube(4)),
    ] {
        match m {
            Ok(m) => meshes.push((name.to_owned(), m)),
            Err(e) => v.error(name, e),
        }
    }
    meshes.extend(read_shared(v));
    for (name, m) in meshes {
        match gaussian_curvature(&m, &GaussianOptions::default()) {
            Ok(k) => {
                let chi = m.connectivity().euler_characteristic() as f64;
                v.at_most(
                    format!("curvature Gauss-Bonnet |sum K + sum k_g - 2 pi chi|, {name}"),
                    (k.total() - TAU * chi).abs(),
                    1e-10,
                );
            }
            Err(e) => v.error(format!("Gauss-Bonnet {name}"), e),
        }
    }
}

fn read_shared(v: &mut Validator) -> Vec<(String, TriMesh)> {
    let Some(dir) = shared_data() else {
        v.skip("curvature on shared meshes", no_shared_data());
        return Vec::new();
    };
    let mut out = Vec::new();
    for file in [
        "cgal_nefertiti.off",
        "cgal_mushroom.off",
        "cgal_elephant.off",
        "cgal_fandisk.off",
        "npm_bunny.obj",
        "cgal_holes.off",
        "cgal_degtri_sliding.off",
    ] {
        match mesh_io::read(dir.join(file)) {
            Ok(d) => out.push((file.to_owned(), d.mesh)),
            Err(e) => v.error(file, e),
        }
    }
    out
}

/// Every estimator gives finite values on every shared mesh.
fn shared_meshes(v: &mut Validator) {
    let methods = [
        ("fit", TensorMethod::default()),
        ("rusinkiewicz", TensorMethod::Rusinkiewicz),
        ("normal cycle", TensorMethod::NormalCycle(Neighborhood::Rings(2))),
    ];
    for (name, m) in read_shared(v) {
        let mut finite = true;
        let mut note = String::new();
        match (gaussian_curvature(&m, &GaussianOptions::default()), mean_curvature(&m, &MeanOptions::default())) {
            (Ok(k), Ok(h)) => finite &= k.pointwise.iter().chain(&h.pointwise).all(|x| x.is_finite()),
            (Err(e), _) | (_, Err(e)) => return v.error(format!("curvature of {name}"), e),
        }
        for (label, method) in methods {
            match tensor(&m, method) {
                Ok(t) => {
                    finite &= t.k1.iter().chain(&t.k2).all(|x| x.is_finite())
                        && t.d1.iter().chain(&t.d2).all(|d| d.is_finite());
                    let degenerate =
                        t.status.iter().filter(|s| **s == mesh_curvature::VertexStatus::Degenerate).count();
                    note.push_str(&format!("{label}: {degenerate} degenerate; "));
                }
                Err(e) => return v.error(format!("{label} on {name}"), e),
            }
        }
        v.holds(format!("curvature finite everywhere, {name}"), finite, note.trim_end_matches("; "));
    }
}

/// Integral curvature over the whole sphere: 4 pi.
fn integral(v: &mut Validator) {
    match shapes::icosphere(4).map_err(|e| e.to_string()).and_then(|m| {
        integral_curvature(&m, &IntegralOptions { neighborhood: Neighborhood::Ball(3.0) }).map_err(|e| e.to_string())
    }) {
        Ok(ic) => v.at_most(
            "integral Gaussian curvature over the whole icosphere(4) - 4 pi",
            (ic.gaussian[0] - 4.0 * PI).abs(),
            1e-10,
        ),
        Err(e) => v.error("integral curvature", e),
    }
}
