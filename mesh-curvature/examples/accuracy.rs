//! Accuracy of every estimator against analytic truth on the sphere, torus,
//! cylinder, a jittered sphere and an ellipsoid, at several resolutions.
//! Run with `cargo run --release -p mesh-curvature --example accuracy`.

use std::f64::consts::TAU;

use mesh_curvature::*;
use mesh_kernel::glam::DVec3;
use mesh_kernel::{shapes, TriMesh};

/// Per-vertex truth: k1, k2, and the k1 direction when it is defined.
struct Truth {
    k1: Vec<f64>,
    k2: Vec<f64>,
    d1: Vec<Option<DVec3>>,
    mask: Vec<bool>,
}

fn sphere(level: u32) -> (TriMesh, Truth) {
    let m = shapes::icosphere(level).unwrap();
    let n = m.vertex_count();
    (m, Truth { k1: vec![1.0; n], k2: vec![1.0; n], d1: vec![None; n], mask: vec![true; n] })
}

fn torus(nu: usize, nv: usize) -> (TriMesh, Truth) {
    let (big, r) = (2.0, 0.5);
    let m = shapes::torus(big, r, nu, nv).unwrap();
    let mut t = Truth { k1: vec![], k2: vec![], d1: vec![], mask: vec![] };
    for i in 0..nu {
        let u = TAU * i as f64 / nu as f64;
        for j in 0..nv {
            let v = TAU * j as f64 / nv as f64;
            t.k1.push(1.0 / r);
            t.k2.push(v.cos() / (big + r * v.cos()));
            t.d1.push(Some(DVec3::new(-v.sin() * u.cos(), -v.sin() * u.sin(), v.cos())));
            t.mask.push(true);
        }
    }
    (m, t)
}

fn cylinder(around: usize, along: usize, margin: usize) -> (TriMesh, Truth) {
    let m = shapes::cylinder(1.0, 2.0, around, along).unwrap();
    let mut t = Truth { k1: vec![], k2: vec![], d1: vec![], mask: vec![] };
    for i in 0..around {
        let a = TAU * i as f64 / around as f64;
        for j in 0..=along {
            t.k1.push(1.0);
            t.k2.push(0.0);
            t.d1.push(Some(DVec3::new(-a.sin(), a.cos(), 0.0)));
            t.mask.push(j >= margin && j + margin <= along);
        }
    }
    (m, t)
}

/// Icosphere with every vertex moved tangentially by up to `amount` of the
/// edge length, back on the sphere: an irregular triangulation.
fn jittered_sphere(level: u32, amount: f64) -> (TriMesh, Truth) {
    let (m, t) = sphere(level);
    let h = 1.1 / 2f64.powi(level as i32);
    let mut rng = mesh_testkit::SplitMix64::new(0x1234_5678_9abc_def0);
    let mut rnd = || rng.signed();
    let p: Vec<DVec3> =
        m.positions().iter().map(|p| (*p + amount * h * DVec3::new(rnd(), rnd(), rnd())).normalize()).collect();
    (TriMesh::new(p, m.faces().to_vec()).unwrap(), t)
}

/// Ellipsoid x^2/a^2 + y^2/b^2 + z^2/c^2 = 1 from a scaled icosphere.
fn ellipsoid(level: u32, [a, b, c]: [f64; 3]) -> (TriMesh, Truth) {
    let s = shapes::icosphere(level).unwrap();
    let p: Vec<DVec3> = s.positions().iter().map(|p| DVec3::new(a * p.x, b * p.y, c * p.z)).collect();
    let m = TriMesh::new(p.clone(), s.faces().to_vec()).unwrap();
    let mut t = Truth { k1: vec![], k2: vec![], d1: vec![], mask: vec![] };
    for q in &p {
        let g = DVec3::new(q.x / (a * a), q.y / (b * b), q.z / (c * c));
        let gl2 = g.length_squared();
        let k = 1.0 / ((a * b * c).powi(2) * gl2 * gl2);
        let h = (a * a + b * b + c * c - q.length_squared()) / (2.0 * (a * b * c).powi(2) * gl2.powf(1.5));
        let disc = (h * h - k).max(0.0).sqrt();
        t.k1.push(h + disc);
        t.k2.push(h - disc);
        t.d1.push(None);
        t.mask.push(true);
    }
    (m, t)
}

struct Errors {
    k1: f64,
    k2: f64,
    k: f64,
    h: f64,
    angle: f64,
}

fn errors(t: &CurvatureTensor, truth: &Truth) -> Errors {
    let mut e = Errors { k1: 0.0, k2: 0.0, k: 0.0, h: 0.0, angle: 0.0 };
    for i in 0..t.len() {
        if !truth.mask[i] {
            continue;
        }
        e.k1 = e.k1.max((t.k1[i] - truth.k1[i]).abs());
        e.k2 = e.k2.max((t.k2[i] - truth.k2[i]).abs());
        e.k = e.k.max((t.k1[i] * t.k2[i] - truth.k1[i] * truth.k2[i]).abs());
        e.h = e.h.max((0.5 * (t.k1[i] + t.k2[i]) - 0.5 * (truth.k1[i] + truth.k2[i])).abs());
        if let Some(d) = truth.d1[i] {
            let c = t.d1[i].dot(d).abs().min(1.0);
            e.angle = e.angle.max(c.acos().to_degrees());
        }
    }
    e
}

fn methods() -> Vec<(&'static str, TensorOptions)> {
    let fit = |rings, degree, use_normals, refine_normal| {
        TensorMethod::Fit(FitOptions { neighborhood: Neighborhood::Rings(rings), degree, use_normals, refine_normal })
    };
    let with = |method| TensorOptions { method, normals: NormalWeighting::Max };
    vec![
        ("quartic fit, 2-ring (default)", TensorOptions::default()),
        ("cubic fit, 2-ring", with(fit(2, Degree::Cubic, false, true))),
        ("cubic + normals, 1-ring (G&I 2004)", with(fit(1, Degree::Cubic, true, false))),
        ("quadric fit, 1-ring (libigl-like)", with(fit(1, Degree::Quadric, false, false))),
        ("Rusinkiewicz, Max normals", with(TensorMethod::Rusinkiewicz)),
        (
            "Rusinkiewicz, area normals",
            TensorOptions { method: TensorMethod::Rusinkiewicz, normals: NormalWeighting::Area },
        ),
        ("normal cycle, 1-ring", with(TensorMethod::NormalCycle(Neighborhood::Rings(1)))),
        ("normal cycle, 2-ring", with(TensorMethod::NormalCycle(Neighborhood::Rings(2)))),
    ]
}

fn main() {
    let cases: Vec<(String, (TriMesh, Truth))> = vec![
        ("icosphere 4".into(), sphere(4)),
        ("icosphere 5".into(), sphere(5)),
        ("torus 128x32".into(), torus(128, 32)),
        ("torus 256x64".into(), torus(256, 64)),
        ("torus 512x128".into(), torus(512, 128)),
        ("cylinder 64x32".into(), cylinder(64, 32, 1)),
        ("cylinder 128x64".into(), cylinder(128, 64, 1)),
        ("jitter sphere 4".into(), jittered_sphere(4, 0.2)),
        ("jitter sphere 5".into(), jittered_sphere(5, 0.2)),
        ("jitter sphere 6".into(), jittered_sphere(6, 0.2)),
        ("ellipsoid 4".into(), ellipsoid(4, [1.0, 0.8, 0.6])),
        ("ellipsoid 5".into(), ellipsoid(5, [1.0, 0.8, 0.6])),
        ("ellipsoid 6".into(), ellipsoid(6, [1.0, 0.8, 0.6])),
    ];
    let filter: Vec<String> = std::env::args().skip(1).collect();
    for (name, (mesh, truth)) in &cases {
        if !filter.is_empty() && !filter.iter().any(|f| name.contains(f.as_str())) {
            continue;
        }
        println!("== {name} ({} vertices): max errors", mesh.vertex_count());
        println!("{:36} {:>10} {:>10} {:>10} {:>10} {:>8} {:>8}", "method", "k1", "k2", "K", "H", "deg", "ms");
        for (label, opts) in methods() {
            let t0 = std::time::Instant::now();
            let t = curvature_tensor(mesh, &opts).unwrap();
            let ms = t0.elapsed().as_secs_f64() * 1e3;
            let e = errors(&t, truth);
            println!("{label:22} {:10.2e} {:10.2e} {:10.2e} {:10.2e} {:8.3} {:8.1}", e.k1, e.k2, e.k, e.h, e.angle, ms);
        }
        let h = mean_curvature(mesh, &Default::default()).unwrap();
        let k = gaussian_curvature(mesh, &Default::default()).unwrap();
        let (mut eh, mut ek) = (0.0f64, 0.0f64);
        for i in 0..mesh.vertex_count() {
            if truth.mask[i] && h.status[i].is_valid() {
                eh = eh.max((h.pointwise[i] - 0.5 * (truth.k1[i] + truth.k2[i])).abs());
                ek = ek.max((k.pointwise[i] - truth.k1[i] * truth.k2[i]).abs());
            }
        }
        println!("{:36} {:>10} {:>10} {ek:10.2e} {eh:10.2e}", "angle defect / cotan formula", "", "");
    }
}
