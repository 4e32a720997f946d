//! Timings of every algorithm on unit icospheres from 642 to 655,362
//! vertices (levels 3 to 8); level 6 (40,962 vertices) is the size class of
//! the 37,706-vertex peer figures. Sources at vertex 0.
//!
//! `cargo bench -p mesh-geodesic --bench geodesic -- --warm-up-time 1 --measurement-time 3`

use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use mesh_geodesic::{
    dijkstra, exact_distance, farthest_point_sampling, trace_path, DijkstraOptions, FastMarching, FmmOptions,
    FmmUpdate, HeatGeodesics, HeatOptions, LaplacianKind, SamplingOptions, SurfacePoint, TraceOptions,
};
use mesh_kernel::{shapes, TriMesh, VertexId};

const LEVELS: [u32; 6] = [3, 4, 5, 6, 7, 8];

fn sphere(level: u32) -> TriMesh {
    let mesh = shapes::icosphere(level).expect("icosphere");
    let _ = mesh.connectivity(); // built once and cached, like any caller's
    mesh
}

fn group<'a>(c: &'a mut Criterion, name: &str) -> criterion::BenchmarkGroup<'a, criterion::measurement::WallTime> {
    let mut g = c.benchmark_group(name);
    g.sample_size(10).warm_up_time(Duration::from_millis(500));
    g
}

fn bench_dijkstra(c: &mut Criterion) {
    let mut g = group(c, "dijkstra");
    for level in LEVELS {
        let mesh = sphere(level);
        g.bench_with_input(BenchmarkId::from_parameter(mesh.vertex_count()), &mesh, |b, m| {
            b.iter(|| dijkstra(m, &[VertexId(0)], &DijkstraOptions::default()).expect("dijkstra"))
        });
    }
}

fn bench_fmm(c: &mut Criterion) {
    let mut g = group(c, "fmm");
    for level in LEVELS {
        let mesh = sphere(level);
        let n = mesh.vertex_count();
        for update in [FmmUpdate::CurvedFront, FmmUpdate::PlaneWave] {
            let opts = FmmOptions { update, ..Default::default() };
            g.bench_with_input(BenchmarkId::new(format!("{update:?}/one-off"), n), &mesh, |b, m| {
                b.iter(|| FastMarching::new(m, &opts).and_then(|f| f.distance(&[VertexId(0)])).expect("fmm"))
            });
            let fmm = FastMarching::new(&mesh, &opts).expect("fmm");
            g.bench_with_input(BenchmarkId::new(format!("{update:?}/march"), n), &fmm, |b, f| {
                b.iter(|| f.distance(&[VertexId(0)]).expect("fmm"))
            });
        }
    }
}

fn bench_heat(c: &mut Criterion) {
    let mut g = group(c, "heat");
    for level in LEVELS {
        let mesh = sphere(level);
        let n = mesh.vertex_count();
        // At 655k vertices only the default Laplacian (a factorization takes seconds).
        let laplacians: &[LaplacianKind] = if level < 8 {
            &[LaplacianKind::IntrinsicDelaunay, LaplacianKind::Cotan]
        } else {
            &[LaplacianKind::IntrinsicDelaunay]
        };
        for &laplacian in laplacians {
            let opts = HeatOptions { laplacian, ..Default::default() };
            g.bench_with_input(BenchmarkId::new(format!("{laplacian:?}/precompute"), n), &mesh, |b, m| {
                b.iter(|| HeatGeodesics::new(m, &opts).expect("heat"))
            });
            let heat = HeatGeodesics::new(&mesh, &opts).expect("heat");
            g.bench_with_input(BenchmarkId::new(format!("{laplacian:?}/solve"), n), &heat, |b, h| {
                b.iter(|| h.distance(&[VertexId(0)]).expect("heat"))
            });
        }
    }
}

fn bench_exact(c: &mut Criterion) {
    let mut g = group(c, "exact");
    // Up to 10,242 vertices: the window count grows faster than V.
    for level in [3, 4, 5] {
        let mesh = sphere(level);
        g.bench_with_input(BenchmarkId::from_parameter(mesh.vertex_count()), &mesh, |b, m| {
            b.iter(|| exact_distance(m, &[VertexId(0)], &Default::default()).expect("exact"))
        });
    }
}

fn bench_trace(c: &mut Criterion) {
    let mut g = group(c, "trace");
    for level in [4, 5, 6, 7] {
        let mesh = sphere(level);
        let d = FastMarching::new(&mesh, &FmmOptions::default()).and_then(|f| f.distance(&[VertexId(0)])).expect("fmm");
        // Start at the vertex closest to 3 rad from the source.
        let far =
            (0..mesh.vertex_count()).min_by(|a, b| (d[*a] - 3.0).abs().total_cmp(&(d[*b] - 3.0).abs())).unwrap_or(0);
        let start = SurfacePoint::at_vertex(&mesh, VertexId::new(far)).expect("vertex");
        g.bench_with_input(BenchmarkId::from_parameter(mesh.vertex_count()), &mesh, |b, m| {
            b.iter(|| trace_path(m, &d, &[VertexId(0)], start, &TraceOptions::default()).expect("trace"))
        });
    }
}

fn bench_sampling(c: &mut Criterion) {
    let mut g = group(c, "farthest_point_sampling_100");
    for level in [4, 5, 6] {
        let mesh = sphere(level);
        g.bench_with_input(BenchmarkId::from_parameter(mesh.vertex_count()), &mesh, |b, m| {
            b.iter(|| farthest_point_sampling(m, 100, &SamplingOptions::default()).expect("fps"))
        });
    }
}

criterion_group!(benches, bench_dijkstra, bench_fmm, bench_heat, bench_exact, bench_trace, bench_sampling);
criterion_main!(benches);
