//! Temporary: 100 Loop steps on a 37k-vertex torus for profiling.
fn main() {
    let m = mesh_core::shapes::torus(2.0, 0.5, 194, 194).unwrap();
    let t = std::time::Instant::now();
    for _ in 0..100 {
        let f = mesh_core::TriMesh::new(m.positions().to_vec(), m.faces().to_vec()).unwrap();
        std::hint::black_box(mesh_wavelet::subdivide(&f, mesh_wavelet::Scheme::Loop, 1).unwrap());
    }
    println!("{:.2} ms per step", t.elapsed().as_secs_f64() * 10.0);
}
