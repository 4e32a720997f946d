//! Delaunay triangulation (spade's bulk load behind `delaunay`), Lawson's
//! flips from the sweep triangulation, and refinement of a square with a
//! hole (constant area bound and a varying size), from 1e3 to 1e6 points.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use glam::DVec2;
use mesh_delaunay::{
    delaunay, lawson_flips, refine_polygon, refine_polygon_sized, sweep_triangulation, LawsonOptions, PolygonDomain,
    RefineOptions,
};
use mesh_testkit::SplitMix64;

fn random_points(n: usize) -> Vec<DVec2> {
    let mut rng = SplitMix64::new(n as u64);
    (0..n).map(|_| DVec2::new(rng.signed(), rng.signed())).collect()
}

fn square_with_hole() -> PolygonDomain {
    let sq =
        |c: DVec2, h: f64| [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)].map(|(x, y)| c + h * DVec2::new(x, y));
    PolygonDomain { outer: sq(DVec2::ZERO, 1.0).to_vec(), holes: vec![sq(DVec2::splat(0.3), 0.2).to_vec()] }
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("delaunay");
    group.warm_up_time(Duration::from_millis(500)).measurement_time(Duration::from_secs(3)).sample_size(10);
    for n in [1_000, 10_000, 100_000, 1_000_000] {
        let p = random_points(n);
        group.throughput(Throughput::Elements(n as u64));
        group.bench_with_input(BenchmarkId::new("delaunay", n), &p, |b, p| b.iter(|| black_box(delaunay(p))));
        group.bench_with_input(BenchmarkId::new("sweep", n), &p, |b, p| b.iter(|| black_box(sweep_triangulation(p))));
        if n <= 100_000 {
            let sweep = sweep_triangulation(&p).expect("random points");
            group.bench_with_input(BenchmarkId::new("lawson_flips", n), &p, |b, p| {
                b.iter(|| black_box(lawson_flips(p, &sweep, &LawsonOptions::default())))
            });
        }
        // An area bound of (domain area) / 2n: about 1.55 n vertices.
        let domain = square_with_hole();
        let area = domain.area() / (2.0 * n as f64);
        let o = RefineOptions { max_area: Some(area), max_added_vertices: 4 * n, ..Default::default() };
        group.bench_with_input(BenchmarkId::new("refine_area", n), &domain, |b, d| {
            b.iter(|| black_box(refine_polygon(d, &o)))
        });
        // A size growing from the left to the right, the same order of vertices.
        let h = (4.0 * area).sqrt();
        let size = move |p: DVec2| h * (0.6 + 0.4 * (p.x + 1.0));
        let o = RefineOptions { max_added_vertices: 4 * n, ..Default::default() };
        group.bench_with_input(BenchmarkId::new("refine_sized", n), &domain, |b, d| {
            b.iter(|| black_box(refine_polygon_sized(d, size, &o)))
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
