//! Connectivity, manifold check, boundary loops, normals, Laplacian and mass
//! matrices on meshes from 1e3 to 1e6 vertices, and on the shared meshes.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use mesh_kernel::geometry::{self, NormalWeighting};
use mesh_kernel::operators::{self, IntrinsicOptions, IntrinsicTriangulation, MassKind};
use mesh_kernel::{shapes, TriMesh};

/// Meshes from about 1e3 to 1e6 vertices: icospheres (closed) and a torus.
fn meshes() -> Vec<(String, TriMesh)> {
    let mut out: Vec<(String, TriMesh)> = (4..=7)
        .map(|level| {
            let m = shapes::icosphere(level).expect("valid level");
            (format!("icosphere{level}_{}v", m.vertex_count()), m)
        })
        .collect();
    let torus = shapes::torus(2.0, 0.5, 1024, 1000).expect("valid torus");
    out.push((format!("torus_{}v", torus.vertex_count()), torus));
    let disk = shapes::disk(100, 1).expect("valid disk");
    out.push((format!("disk_{}v", disk.vertex_count()), disk));
    out
}

fn fresh(m: &TriMesh) -> TriMesh {
    TriMesh::new(m.positions().to_vec(), m.faces().to_vec()).expect("valid copy")
}

fn bench_core(c: &mut Criterion) {
    let mut group = c.benchmark_group("core");
    group.sample_size(10).warm_up_time(Duration::from_millis(500)).measurement_time(Duration::from_secs(2));
    for (name, mesh) in meshes() {
        group.bench_with_input(BenchmarkId::new("connectivity+manifold", &name), &mesh, |b, m| {
            b.iter_batched(|| fresh(m), |m| black_box(m.connectivity().is_manifold()), criterion::BatchSize::LargeInput)
        });
        group.bench_with_input(BenchmarkId::new("boundary_loops", &name), &mesh, |b, m| {
            b.iter_batched(
                || fresh(m),
                |m| black_box(m.connectivity().boundary_loops().map(|l| l.len()).unwrap_or(0)),
                criterion::BatchSize::LargeInput,
            )
        });
        group.bench_with_input(BenchmarkId::new("normals_area", &name), &mesh, |b, m| {
            b.iter(|| black_box(geometry::vertex_normals(m, NormalWeighting::Area)))
        });
        let _ = mesh.connectivity();
        group.bench_with_input(BenchmarkId::new("cotan_laplacian", &name), &mesh, |b, m| {
            b.iter(|| black_box(operators::cotan_laplacian(m)))
        });
        group.bench_with_input(BenchmarkId::new("mass_voronoi", &name), &mesh, |b, m| {
            b.iter(|| black_box(operators::mass_matrix(m, MassKind::MixedVoronoi)))
        });
        group.bench_with_input(BenchmarkId::new("mass_galerkin", &name), &mesh, |b, m| {
            b.iter(|| black_box(operators::mass_matrix(m, MassKind::Galerkin)))
        });
        group.bench_with_input(BenchmarkId::new("intrinsic_delaunay_laplacian", &name), &mesh, |b, m| {
            b.iter(|| {
                black_box(
                    IntrinsicTriangulation::delaunay(m, &IntrinsicOptions::default()).map(|t| t.cotan_laplacian()),
                )
            })
        });
    }
    group.finish();
}

fn bench_shared(c: &mut Criterion) {
    let Some(dir) = mesh_testkit::shared_data() else { return };
    let mut group = c.benchmark_group("shared");
    group.sample_size(20).warm_up_time(Duration::from_millis(300)).measurement_time(Duration::from_secs(1));
    for file in ["cgal_fandisk.off", "cgal_holes.off", "cgal_elephant.off"] {
        let raw = mesh_testkit::read_raw(&dir.join(file)).unwrap_or_else(|e| panic!("{e}"));
        let positions = raw.positions.into_iter().map(mesh_kernel::glam::DVec3::from).collect();
        let mesh = TriMesh::new(positions, raw.faces).unwrap_or_else(|e| panic!("{file}: {e}"));
        group.bench_with_input(BenchmarkId::new("connectivity+manifold", file), &mesh, |b, m| {
            b.iter_batched(|| fresh(m), |m| black_box(m.connectivity().is_manifold()), criterion::BatchSize::LargeInput)
        });
        group.bench_with_input(BenchmarkId::new("cotan_laplacian", file), &mesh, |b, m| {
            b.iter(|| black_box(operators::cotan_laplacian(m)))
        });
    }
    group.finish();
}

criterion_group!(benches, bench_core, bench_shared);
criterion_main!(benches);
