//! Parameterization maps (Tutte, harmonic, mean-value, LSCM), the distortion
//! report, cutting to a disk and the boundary check, on disks from 1e3 to 1e6
//! vertices. `disk_8269v` is the size of the libigl reference mesh of the earlier measurements.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use glam::DVec2;
use mesh_kernel::{shapes, TriMesh, VertexId};
use mesh_param::{
    bijectivity, boundary, cut_to_disk, distortion, lscm, require_disk, DegeneratePolicy, FixedBoundarySolver,
    Harmonic, LscmOptions, MeanValue, Spacing, Uniform, Weights,
};

/// Unit disks of 1 + 3 r (r + 1) vertices.
fn disk(rings: usize) -> (String, TriMesh) {
    let m = shapes::disk(rings, 1).expect("valid disk");
    let _ = m.connectivity();
    (format!("disk_{}v", m.vertex_count()), m)
}

fn map<W: Weights>(mesh: &TriMesh, weights: &W, b: &[VertexId], pos: &[DVec2]) -> Vec<DVec2> {
    FixedBoundarySolver::new(mesh, weights, b, DegeneratePolicy::Uniform).and_then(|s| s.solve(pos)).expect("disk maps")
}

fn bench_maps(c: &mut Criterion) {
    let mut group = c.benchmark_group("param");
    group.warm_up_time(Duration::from_millis(500)).measurement_time(Duration::from_secs(3));
    for rings in [18, 52, 180, 577] {
        let (name, mesh) = disk(rings);
        let huge = mesh.vertex_count() > 500_000;
        group.sample_size(if mesh.vertex_count() > 50_000 { 10 } else { 30 });
        let b = require_disk(&mesh).expect("a disk").vertices.clone();
        let circle = boundary::circle(&mesh, &b, Spacing::ChordLength);
        group.bench_with_input(BenchmarkId::new("tutte", &name), &mesh, |bn, m| {
            bn.iter(|| black_box(map(m, &Uniform, &b, &circle)))
        });
        group.bench_with_input(BenchmarkId::new("harmonic", &name), &mesh, |bn, m| {
            bn.iter(|| black_box(map(m, &Harmonic, &b, &circle)))
        });
        if !huge {
            group.bench_with_input(BenchmarkId::new("mean_value", &name), &mesh, |bn, m| {
                bn.iter(|| black_box(map(m, &MeanValue, &b, &circle)))
            });
            group.bench_with_input(BenchmarkId::new("lscm", &name), &mesh, |bn, m| {
                bn.iter(|| black_box(lscm(m, &LscmOptions::default()).expect("disk maps")))
            });
        }
        let uv = map(&mesh, &Harmonic, &b, &circle);
        group.bench_with_input(BenchmarkId::new("distortion_report", &name), &mesh, |bn, m| {
            bn.iter(|| black_box(distortion(m, &uv).expect("valid map")))
        });
        let loop_uv: Vec<DVec2> = b.iter().map(|v| uv[v.idx()]).collect();
        group.bench_with_input(BenchmarkId::new("boundary_check", &name), &loop_uv, |bn, l| {
            bn.iter(|| black_box(bijectivity::boundary_is_simple(std::slice::from_ref(l))))
        });
    }
    for level in [4, 6, 8] {
        let m = shapes::icosphere(level).expect("valid level");
        let _ = m.connectivity();
        group.sample_size(10);
        group.bench_with_input(
            BenchmarkId::new("cut_to_disk", format!("icosphere_{}v", m.vertex_count())),
            &m,
            |bn, m| bn.iter(|| black_box(cut_to_disk(m).expect("cuts"))),
        );
    }
    let torus = shapes::torus(2.0, 0.5, 400, 250).expect("valid torus");
    let _ = torus.connectivity();
    group.bench_with_input(
        BenchmarkId::new("cut_to_disk", format!("torus_{}v", torus.vertex_count())),
        &torus,
        |bn, m| bn.iter(|| black_box(cut_to_disk(m).expect("cuts"))),
    );
    group.finish();
}

criterion_group!(benches, bench_maps);
criterion_main!(benches);
