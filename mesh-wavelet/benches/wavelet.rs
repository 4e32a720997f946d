//! Criterion benchmarks of mesh-wavelet: one level of subdivision (against
//! libigl's `loop` and `upsample` on the same ~38k-vertex mesh), the
//! in-place analysis and synthesis filter banks from 1e3 to 1e6 vertices,
//! and their setup (detection of subdivision connectivity, filter bank).

use std::hint::black_box;
use std::sync::Arc;

use criterion::{criterion_group, criterion_main, BatchSize, BenchmarkId, Criterion, Throughput};
use mesh_kernel::{glam::DVec3, shapes, TriMesh};
use mesh_wavelet::{detect, subdivide, FilterBank, Multiresolution, Scheme, SubdivideOptions, WaveletKind};

/// A copy without cached connectivity.
fn fresh(m: &TriMesh) -> TriMesh {
    TriMesh::new(m.positions().to_vec(), m.faces().to_vec()).expect("valid mesh")
}

/// Semi-regular meshes from 642 to 991,232 vertices: icosphere levels 3 to 7
/// and a 22 x 11 torus split 6 times.
fn semi_regular() -> Vec<(String, TriMesh)> {
    let mut v: Vec<(String, TriMesh)> =
        (3..=7).map(|l| (format!("icosphere{l}"), shapes::icosphere(l).expect("icosphere"))).collect();
    let torus = shapes::torus(2.0, 0.5, 22, 11).expect("torus");
    v.push((
        "torus-1e6".into(),
        subdivide(&torus, &SubdivideOptions { scheme: Scheme::Midpoint, levels: 6 }).expect("subdivide"),
    ));
    v
}

fn sample_size_for(n: usize) -> usize {
    if n > 500_000 {
        10
    } else if n > 100_000 {
        20
    } else {
        50
    }
}

fn subdivision(c: &mut Criterion) {
    let mut group = c.benchmark_group("subdivide 1 level");
    // The libigl comparison mesh: a 194 x 194 torus (37,636 vertices).
    let mut meshes = vec![("torus-37k".to_string(), shapes::torus(2.0, 0.5, 194, 194).expect("torus"))];
    meshes.extend((3..=6).map(|l| (format!("icosphere{l}"), shapes::icosphere(l).expect("icosphere"))));
    for (name, mesh) in &meshes {
        group.sample_size(sample_size_for(4 * mesh.vertex_count()));
        group.throughput(Throughput::Elements(mesh.vertex_count() as u64));
        for scheme in Scheme::ALL {
            group.bench_with_input(BenchmarkId::new(scheme.name(), name), mesh, |b, m| {
                b.iter_batched(
                    || fresh(m),
                    |m| black_box(subdivide(&m, &SubdivideOptions { scheme, levels: 1 }).expect("subdivide")),
                    BatchSize::LargeInput,
                )
            });
        }
    }
    group.finish();
}

fn transforms(c: &mut Criterion) {
    let mut group = c.benchmark_group("filter bank");
    for (name, mesh) in semi_regular() {
        let h = detect(&mesh, &Default::default()).expect("semi-regular");
        let n = mesh.vertex_count();
        group.sample_size(sample_size_for(n));
        group.throughput(Throughput::Elements(n as u64));
        let data: Vec<DVec3> = (0..n).map(|v| mesh.positions()[h.input_index(v).expect("valid")]).collect();
        for (scheme, kind) in [
            (Scheme::Midpoint, WaveletKind::Lazy),
            (Scheme::Midpoint, WaveletKind::Lifted),
            (Scheme::Loop, WaveletKind::Lifted),
            (Scheme::Butterfly, WaveletKind::Lifted),
        ] {
            let bank = FilterBank::new(&h, scheme, kind).expect("bank");
            let label = format!("{scheme}-{kind}");
            group.bench_with_input(BenchmarkId::new(format!("analysis+synthesis {label}"), &name), &data, |b, d| {
                b.iter_batched_ref(
                    || d.clone(),
                    |x| {
                        bank.analyze(x).expect("analyze");
                        bank.synthesize(x).expect("synthesize");
                    },
                    BatchSize::LargeInput,
                )
            });
        }
    }
    group.finish();
}

fn setup(c: &mut Criterion) {
    let mut group = c.benchmark_group("setup");
    for (name, mesh) in semi_regular().into_iter().filter(|(n, _)| n != "icosphere3" && n != "icosphere4") {
        let n = mesh.vertex_count();
        group.sample_size(10);
        group.throughput(Throughput::Elements(n as u64));
        group.bench_with_input(BenchmarkId::new("detect", &name), &mesh, |b, m| {
            b.iter(|| black_box(detect(m, &Default::default()).expect("detect")))
        });
        let h = Arc::new(detect(&mesh, &Default::default()).expect("detect"));
        for kind in [WaveletKind::Lazy, WaveletKind::Lifted] {
            group.bench_with_input(BenchmarkId::new(format!("filter bank midpoint-{kind}"), &name), &h, |b, h| {
                b.iter(|| black_box(FilterBank::new(h, Scheme::Midpoint, kind).expect("bank")))
            });
        }
        let bank = Arc::new(FilterBank::new(&h, Scheme::Midpoint, WaveletKind::Lifted).expect("bank"));
        group.bench_with_input(BenchmarkId::new("Multiresolution::analyze (all)", &name), &mesh, |b, m| {
            b.iter(|| black_box(Multiresolution::analyze(m, &Default::default()).expect("analyze")))
        });
        let mr = Multiresolution::from_parts(h.clone(), bank, mesh.positions()).expect("analyze");
        group.bench_with_input(BenchmarkId::new("compress 10%", &name), &mr, |b, mr| {
            b.iter(|| black_box(mr.compress(&Default::default()).expect("compress")))
        });
    }
    group.finish();
}

criterion_group!(benches, subdivision, transforms, setup);
criterion_main!(benches);
