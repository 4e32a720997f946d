//! Accuracy of every estimator against analytic truth on the sphere, torus,
//! cylinder, a jittered sphere and an ellipsoid, at several resolutions.
//! Run with `cargo run --release -p mesh-curvature --example accuracy`.

#[path = "../tests/common/mod.rs"]
mod common;

use common::{cylinder, ellipsoid, errors, jittered_sphere, sphere, torus, Truth};
use mesh_curvature::*;
use mesh_kernel::TriMesh;

/// Seed of the jittered spheres.
const SEED: u64 = 0x1234_5678_9abc_def0;

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
        ("jitter sphere 4".into(), jittered_sphere(4, 0.2, SEED)),
        ("jitter sphere 5".into(), jittered_sphere(5, 0.2, SEED)),
        ("jitter sphere 6".into(), jittered_sphere(6, 0.2, SEED)),
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
            println!(
                "{label:22} {:10.2e} {:10.2e} {:10.2e} {:10.2e} {:8.3} {:8.1}",
                e.k1, e.k2, e.gaussian, e.mean, e.degrees, ms
            );
        }
        let h = mean_curvature(mesh, &Default::default()).unwrap();
        let k = gaussian_curvature(mesh, &Default::default()).unwrap();
        let (mut eh, mut ek) = (0.0f64, 0.0f64);
        for i in 0..mesh.vertex_count() {
            if truth.check[i] && h.status[i].is_valid() {
                eh = eh.max((h.pointwise[i] - 0.5 * (truth.k1[i] + truth.k2[i])).abs());
                ek = ek.max((k.pointwise[i] - truth.k1[i] * truth.k2[i]).abs());
            }
        }
        println!("{:36} {:>10} {:>10} {ek:10.2e} {eh:10.2e}", "angle defect / cotan formula", "", "");
    }
}
