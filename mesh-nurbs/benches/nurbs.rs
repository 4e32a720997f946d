//! Criterion benchmarks of mesh-nurbs: basis functions, bicubic surface points
//! with first derivatives, curvature frames and tessellation.

use criterion::{criterion_group, criterion_main, BatchSize, Criterion, Throughput};
use mesh_nurbs::basis::basis_derivatives;
use mesh_nurbs::glam::DVec3;
use mesh_nurbs::{shapes, tessellate, GridOptions, KnotVector, NurbsSurface, SurfaceFrame};
use std::hint::black_box;

/// A rational bicubic surface with 16 x 16 control points.
fn bicubic() -> NurbsSurface {
    let n = 16;
    let knots = KnotVector::clamped_uniform(3, n).expect("valid knots");
    let mut points = Vec::with_capacity(n * n);
    let mut weights = Vec::with_capacity(n * n);
    for i in 0..n {
        for j in 0..n {
            let (x, y) = (i as f64, j as f64);
            points.push(DVec3::new(x, y, (0.5 * x).sin() * (0.3 * y).cos()));
            weights.push(1.0 + 0.1 * ((i + 2 * j) % 3) as f64);
        }
    }
    NurbsSurface::new(knots.clone(), knots, points, weights).expect("valid surface")
}

/// `count` parameters spread over the unit square (a 2D Halton-like walk).
fn parameters(count: usize) -> Vec<(f64, f64)> {
    (0..count).map(|k| ((k as f64 * 0.618_033_988_7).fract(), (k as f64 * 0.754_877_666_2).fract())).collect()
}

fn basis(c: &mut Criterion) {
    let kv = KnotVector::clamped_uniform(3, 64).expect("valid knots");
    let us: Vec<f64> = parameters(1000).into_iter().map(|p| p.0).collect();
    let mut group = c.benchmark_group("basis");
    group.throughput(Throughput::Elements(us.len() as u64));
    group.bench_function("cubic values+first derivatives x1000", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for &u in &us {
                let span = kv.span(u);
                let d = basis_derivatives::<2>(&kv, span, u);
                acc += d[1][0];
            }
            black_box(acc)
        })
    });
    group.finish();
}

fn surface(c: &mut Criterion) {
    let s = bicubic();
    let uv = parameters(1000);
    let mut group = c.benchmark_group("bicubic surface");
    group.throughput(Throughput::Elements(uv.len() as u64));
    group.bench_function("point+first derivatives (point_and_tangents) x1000", |b| {
        b.iter(|| {
            let mut acc = DVec3::ZERO;
            for &(u, v) in &uv {
                if let Ok([p, su, sv]) = s.point_and_tangents(u, v) {
                    acc += p + su + sv;
                }
            }
            black_box(acc)
        })
    });
    group.bench_function("point+first derivatives (derivatives(u, v, 1)) x1000", |b| {
        b.iter(|| {
            let mut acc = DVec3::ZERO;
            for &(u, v) in &uv {
                if let Ok(d) = s.derivatives(u, v, 1) {
                    acc += d.point + d.su + d.sv;
                }
            }
            black_box(acc)
        })
    });
    group.bench_function("SurfaceFrame (curvatures) x1000", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for &(u, v) in &uv {
                if let Ok(f) = SurfaceFrame::new(&s, u, v) {
                    acc += f.mean + f.gaussian;
                }
            }
            black_box(acc)
        })
    });
    group.finish();
}

fn tessellation(c: &mut Criterion) {
    let sphere = shapes::sphere(DVec3::ZERO, 1.0).expect("valid sphere");
    let mut group = c.benchmark_group("tessellate sphere");
    group.sample_size(10);
    for n in [100, 1000] {
        let options = GridOptions { segments_u: n, segments_v: n, ..Default::default() };
        group.throughput(Throughput::Elements(((n + 1) * (n + 1)) as u64));
        group.bench_function(format!("{n}x{n}"), |b| {
            b.iter_batched(|| (), |_| black_box(tessellate(&sphere, &options)), BatchSize::PerIteration)
        });
    }
    group.finish();
}

criterion_group!(benches, basis, surface, tessellation);
criterion_main!(benches);
