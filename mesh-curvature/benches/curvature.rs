//! Criterion benchmarks of every curvature quantity on icospheres from 642
//! to 655,362 vertices, and on the 274 x 137 torus (37,538 vertices) that
//! stands in for the 37,706-vertex libigl reference mesh.
//!
//! `cargo bench -p mesh-curvature -- --warm-up-time 1 --measurement-time 3`

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use mesh_curvature::{
    curvature_tensor, gaussian_curvature, integral_curvature, mean_curvature, GaussianOptions, IntegralOptions,
    MeanOptions, Neighborhood, TensorMethod, TensorOptions,
};
use mesh_kernel::{shapes, TriMesh};

fn meshes() -> Vec<(String, TriMesh)> {
    let mut out: Vec<(String, TriMesh)> = (3..=8)
        .map(|level| {
            let m = shapes::icosphere(level).unwrap();
            (format!("icosphere{level}_{}v", m.vertex_count()), m)
        })
        .collect();
    out.insert(3, ("torus274x137_37538v".into(), shapes::torus(2.0, 0.5, 274, 137).unwrap()));
    for (_, m) in &out {
        // Connectivity is cached in the mesh: built once, like libigl's
        // callers build their adjacency once.
        let _ = m.connectivity();
    }
    out
}

fn bench(c: &mut Criterion) {
    let meshes = meshes();
    let tensor_methods = [
        ("tensor_default_quartic_fit", TensorMethod::default()),
        ("tensor_rusinkiewicz", TensorMethod::Rusinkiewicz),
        ("tensor_normal_cycle_1ring", TensorMethod::NormalCycle(Neighborhood::Rings(1))),
    ];
    let mut group = c.benchmark_group("curvature");
    for (name, mesh) in &meshes {
        if mesh.vertex_count() > 100_000 {
            group.sample_size(10);
        } else {
            group.sample_size(20);
        }
        group.bench_with_input(BenchmarkId::new("gaussian", name), mesh, |b, m| {
            b.iter(|| gaussian_curvature(m, &GaussianOptions::default()).unwrap())
        });
        group.bench_with_input(BenchmarkId::new("mean", name), mesh, |b, m| {
            b.iter(|| mean_curvature(m, &MeanOptions::default()).unwrap())
        });
        for (label, method) in tensor_methods {
            let options = TensorOptions { method, ..Default::default() };
            group.bench_with_input(BenchmarkId::new(label, name), mesh, |b, m| {
                b.iter(|| curvature_tensor(m, &options).unwrap())
            });
        }
        group.bench_with_input(BenchmarkId::new("integral_2ring", name), mesh, |b, m| {
            b.iter(|| integral_curvature(m, &IntegralOptions { neighborhood: Neighborhood::Rings(2) }).unwrap())
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
