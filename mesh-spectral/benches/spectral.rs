//! Timings of the eigensolver and the transforms built on it.
//!
//! - `eigenpairs_k20`: the 20 smallest pairs of `L x = lambda M x` (cotangent
//!   Laplacian, mixed Voronoi mass) on unit icospheres of 642 to 40,962
//!   vertices (levels 3 to 6) and a 99,856-vertex torus (`torus 158`, the
//!   size class of the 100,250-vertex peer figure);
//! - `harmonics_forward` / `harmonics_inverse` / `compress`: with 100
//!   harmonics of the 10,242- and 40,962-vertex spheres.
//!
//! k = 200 on 100k vertices (one run of tens of seconds) and 1e6 vertices are
//! timed once by `examples/eigs.rs` instead: criterion's 10-sample minimum
//! would take many minutes on the shared 2-core machine.
//!
//! `cargo bench -p mesh-spectral --bench spectral -- --warm-up-time 1 --measurement-time 3`

use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use mesh_kernel::operators::{self, MassKind};
use mesh_kernel::{shapes, TriMesh};
use mesh_spectral::{compress, eigenpairs, EigenOptions, HarmonicsOptions, ManifoldHarmonics};

fn group<'a>(c: &'a mut Criterion, name: &str) -> criterion::BenchmarkGroup<'a, criterion::measurement::WallTime> {
    let mut g = c.benchmark_group(name);
    g.sample_size(10).warm_up_time(Duration::from_millis(500));
    g
}

fn meshes() -> Vec<TriMesh> {
    let mut out: Vec<TriMesh> = (3..=6).map(|level| shapes::icosphere(level).expect("icosphere")).collect();
    out.push(shapes::by_name("torus", 158).expect("torus"));
    out
}

fn bench_eigenpairs(c: &mut Criterion) {
    let mut g = group(c, "eigenpairs_k20");
    for mesh in meshes() {
        let l = operators::cotan_laplacian(&mesh);
        let m = operators::lumped_mass(&mesh, MassKind::MixedVoronoi);
        g.bench_with_input(BenchmarkId::from_parameter(mesh.vertex_count()), &(l, m), |b, (l, m)| {
            b.iter(|| eigenpairs(l, m, 20, &EigenOptions::default()).expect("eigenpairs"))
        });
    }
}

fn bench_transforms(c: &mut Criterion) {
    const K: usize = 100;
    let cases: Vec<(TriMesh, ManifoldHarmonics)> = [5, 6]
        .into_iter()
        .map(|level| {
            let mesh = shapes::icosphere(level).expect("icosphere");
            let h = ManifoldHarmonics::new(&mesh, K, &HarmonicsOptions::default()).expect("harmonics");
            (mesh, h)
        })
        .collect();
    let mut g = group(c, "harmonics_forward");
    for (mesh, h) in &cases {
        let f: Vec<f64> = mesh.positions().iter().map(|p| p.x * p.y + p.z).collect();
        g.bench_with_input(BenchmarkId::from_parameter(mesh.vertex_count()), &f, |b, f| {
            b.iter(|| h.forward(f).expect("forward"))
        });
    }
    g.finish();
    let mut g = group(c, "harmonics_inverse");
    for (mesh, h) in &cases {
        let coefficients: Vec<f64> = (0..K).map(|i| 1.0 / (1.0 + i as f64)).collect();
        g.bench_with_input(BenchmarkId::from_parameter(mesh.vertex_count()), &coefficients, |b, c| {
            b.iter(|| h.inverse(c).expect("inverse"))
        });
    }
    g.finish();
    let mut g = group(c, "compress_k50");
    for (mesh, h) in &cases {
        g.bench_with_input(BenchmarkId::from_parameter(mesh.vertex_count()), mesh, |b, m| {
            b.iter(|| compress(m, h, 50).expect("compress"))
        });
    }
}

criterion_group!(benches, bench_eigenpairs, bench_transforms);
criterion_main!(benches);
