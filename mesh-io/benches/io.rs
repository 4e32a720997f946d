//! Read and write throughput of every format and encoding, in bytes of file
//! per second, on generated grids of ~1e5 and ~1e6 vertices (files in a
//! temporary directory, so reads include `fs::read` from the page cache and
//! writes the atomic rename), on the shared mesh `cgal_fandisk.off` when present,
//! and `tobj` on the same OBJ as a baseline.
//!
//! `cargo bench -p mesh-io --bench io -- --warm-up-time 1 --measurement-time 3`

use std::path::{Path, PathBuf};
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use mesh_io::{Format, MeshData, PlyEncoding, PlyOptions, StlEncoding, WriteOptions};
use mesh_kernel::glam::DVec3;
use mesh_kernel::TriMesh;

/// An `n x n` grid on a wavy surface; coordinates need all 17 digits.
fn grid(n: u32) -> MeshData {
    let f = |i: u32| f64::from(i) / f64::from(n) * std::f64::consts::PI;
    let positions = (0..n * n)
        .map(|k| {
            let (x, y) = (f(k % n), f(k / n));
            DVec3::new(x, y, 0.25 * x.sin() * y.cos())
        })
        .collect();
    let mut faces = Vec::with_capacity(2 * (n as usize - 1).pow(2));
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            let v = j * n + i;
            faces.push([v, v + 1, v + n + 1]);
            faces.push([v, v + n + 1, v + n]);
        }
    }
    MeshData::new(TriMesh::new(positions, faces).expect("valid grid"))
}

/// Every format and encoding, with a label.
fn cases() -> Vec<(&'static str, Format, WriteOptions)> {
    let ply = |encoding| WriteOptions {
        ply: PlyOptions { encoding, double: true, ..Default::default() },
        ..Default::default()
    };
    let stl = |stl| WriteOptions { stl, ..Default::default() };
    vec![
        ("obj", Format::Obj, WriteOptions::default()),
        ("off", Format::Off, WriteOptions::default()),
        ("ply-ascii", Format::Ply, ply(PlyEncoding::Ascii)),
        ("ply-binary", Format::Ply, ply(PlyEncoding::BinaryLittleEndian)),
        ("stl-ascii", Format::Stl, stl(StlEncoding::Ascii)),
        ("stl-binary", Format::Stl, stl(StlEncoding::Binary)),
        ("gltf", Format::Gltf, WriteOptions::default()),
        ("glb", Format::Glb, WriteOptions::default()),
    ]
}

fn file_size(path: &Path) -> u64 {
    std::fs::metadata(path).map(|m| m.len()).unwrap_or(0)
}

fn sized(c: &mut Criterion, label: &str, n: u32) {
    let data = grid(n);
    let dir = tempfile::tempdir().expect("temporary directory");
    let files: Vec<(&str, PathBuf, WriteOptions)> = cases()
        .into_iter()
        .map(|(name, format, options)| {
            let path = dir.path().join(format!("{name}.{}", format.extension()));
            mesh_io::write(&path, &data, &options).expect("write");
            (name, path, options)
        })
        .collect();

    let mut read = c.benchmark_group(format!("read/{label}"));
    for (name, path, _) in &files {
        read.throughput(Throughput::Bytes(file_size(path)));
        read.bench_function(BenchmarkId::from_parameter(name), |b| b.iter(|| mesh_io::read(path).expect("read")));
    }
    let obj = &files[0].1;
    read.throughput(Throughput::Bytes(file_size(obj)));
    read.bench_function(BenchmarkId::from_parameter("obj-tobj"), |b| {
        b.iter(|| tobj::load_obj(obj, &tobj::LoadOptions { triangulate: true, ..Default::default() }).expect("tobj"))
    });
    read.finish();

    let mut write = c.benchmark_group(format!("write/{label}"));
    for (name, path, options) in &files {
        write.throughput(Throughput::Bytes(file_size(path)));
        let out = dir.path().join(format!("out-{}", path.file_name().and_then(|f| f.to_str()).unwrap_or("x")));
        write.bench_function(BenchmarkId::from_parameter(name), |b| {
            b.iter(|| mesh_io::write(&out, &data, options).expect("write"))
        });
    }
    write.finish();
}

fn small(c: &mut Criterion) {
    sized(c, "1e5", 316);
}

fn large(c: &mut Criterion) {
    sized(c, "1e6", 1000);
}

fn fandisk(c: &mut Criterion) {
    let Some(path) = mesh_testkit::shared_file("cgal_fandisk.off") else { return };
    let mut group = c.benchmark_group("read/fandisk");
    group.throughput(Throughput::Bytes(file_size(&path)));
    group.bench_function("off", |b| b.iter(|| mesh_io::read(&path).expect("read")));
    group.finish();
}

fn config() -> Criterion {
    Criterion::default().sample_size(10).warm_up_time(Duration::from_secs(1)).measurement_time(Duration::from_secs(3))
}

criterion_group! { name = benches; config = config(); targets = fandisk, small, large }
criterion_main!(benches);
