//! Best-of-10 timing of one Loop level on a ~38k-vertex torus, against the
//! connectivity build it needs. Run with
//! `cargo run --release -p mesh-wavelet --example loop_timing`.

use std::time::Instant;

use mesh_core::shapes;
use mesh_wavelet::{subdivide, Scheme};

fn best<T>(f: impl Fn() -> T) -> f64 {
    (0..10)
        .map(|_| {
            let t = Instant::now();
            std::hint::black_box(f());
            t.elapsed().as_secs_f64() * 1e3
        })
        .fold(f64::INFINITY, f64::min)
}

fn main() {
    let m = shapes::torus(2.0, 0.5, 194, 194).unwrap();
    let fresh = || mesh_core::TriMesh::new(m.positions().to_vec(), m.faces().to_vec()).unwrap();
    println!("{} vertices", m.vertex_count());
    println!("copy mesh          {:7.2} ms", best(fresh));
    println!(
        "connectivity       {:7.2} ms",
        best(|| mesh_core::Connectivity::new(m.vertex_count(), m.faces()).edge_count())
    );
    println!("topology           {:7.2} ms", best(|| mesh_wavelet::__topology_edges(m.vertex_count(), m.faces())));
    let big = subdivide(&m, Scheme::Midpoint, 3).unwrap();
    println!("{} vertices", big.vertex_count());
    println!(
        "connectivity       {:7.2} ms",
        best(|| mesh_core::Connectivity::new(big.vertex_count(), big.faces()).edge_count())
    );
    println!("topology           {:7.2} ms", best(|| mesh_wavelet::__topology_edges(big.vertex_count(), big.faces())));
    for scheme in Scheme::ALL {
        println!("{scheme:18} {:7.2} ms", best(|| subdivide(&fresh(), scheme, 1).unwrap()));
    }
}
