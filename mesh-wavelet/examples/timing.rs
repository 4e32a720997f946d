//! Rough timings of the main operations on a ~1e6-vertex semi-regular torus
//! and of one Loop step on a ~38k-vertex mesh (criterion benches give the
//! figures of the README; this is a quick look).
//!
//! Run with `cargo run --release -p mesh-wavelet --example timing`.

use std::sync::Arc;
use std::time::Instant;

use mesh_core::shapes;
use mesh_wavelet::{detect, subdivide, FilterBank, Hierarchy, Multiresolution, Scheme, WaveletKind};

fn time<T>(label: &str, f: impl FnOnce() -> T) -> T {
    let t = Instant::now();
    let r = f();
    println!("{label:40} {:9.2} ms", t.elapsed().as_secs_f64() * 1e3);
    r
}

fn main() {
    let base = shapes::torus(2.0, 0.5, 22, 11).unwrap();
    let fine = time("subdivide midpoint 6 levels", || subdivide(&base, Scheme::Midpoint, 6).unwrap());
    println!("{} vertices", fine.vertex_count());
    let h = time("hierarchy from base", || Hierarchy::from_base(base.vertex_count(), base.faces(), 6).unwrap());
    time("Connectivity::new fine", || mesh_core::Connectivity::new(fine.vertex_count(), fine.faces()).edge_count());
    let fresh = mesh_core::TriMesh::new(fine.positions().to_vec(), fine.faces().to_vec()).unwrap();
    let hd = Arc::new(time("detect (incl. connectivity)", || detect(&fresh, &Default::default()).unwrap()));
    for scheme in Scheme::ALL {
        for kind in [WaveletKind::Lazy, WaveletKind::Lifted] {
            let bank = time(&format!("bank {scheme} {kind}"), || FilterBank::new(&hd, scheme, kind).unwrap());
            let mut data: Vec<_> = (0..fine.vertex_count()).map(|h| fine.positions()[hd.input_index(h)]).collect();
            time(&format!("  analyze {scheme} {kind}"), || bank.analyze(&mut data).unwrap());
            time(&format!("  synthesize {scheme} {kind}"), || bank.synthesize(&mut data).unwrap());
        }
    }
    let hd2 = hd.clone();
    let bank = Arc::new(FilterBank::new(&hd2, Scheme::Midpoint, WaveletKind::Lifted).unwrap());
    let mr = time("Multiresolution::from_parts", || {
        Multiresolution::from_parts(hd.clone(), bank.clone(), fresh.positions()).unwrap()
    });
    time("synthesize -> TriMesh", || mr.synthesize().unwrap());
    time("compress 10%", || mr.compress(&Default::default()).unwrap());
    drop(h);

    let m = shapes::torus(2.0, 0.5, 194, 194).unwrap();
    println!("{} vertices", m.vertex_count());
    for scheme in Scheme::ALL {
        time("Connectivity::new fine", || mesh_core::Connectivity::new(fine.vertex_count(), fine.faces()).edge_count());
        let fresh = mesh_core::TriMesh::new(m.positions().to_vec(), m.faces().to_vec()).unwrap();
        time(&format!("one level {scheme}"), || subdivide(&fresh, scheme, 1).unwrap());
    }
}
