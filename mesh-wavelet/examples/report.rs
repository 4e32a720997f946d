//! Prints the accuracy figures of the README: reconstruction error, coefficient
//! decay and compression curves on smooth semi-regular surfaces.
//!
//! Run with `cargo run --release -p mesh-wavelet --example report`.

use std::sync::Arc;

#[path = "../tests/common/mod.rs"]
mod common;

use common::{bumpy_sphere, smooth_torus};
use mesh_kernel::{shapes, TriMesh};
use mesh_wavelet::{decay_rate, FilterBank, Multiresolution, Scheme, WaveletKind};

/// The icosahedron split `levels` times with new vertices on the unit sphere.
fn sphere(levels: u32) -> TriMesh {
    shapes::icosphere(levels).unwrap()
}

fn main() {
    let mut shapes: Vec<(&str, TriMesh)> =
        vec![("sphere", sphere(5)), ("torus", smooth_torus(4)), ("bumpy", bumpy_sphere(5))];
    if let Some(holes) = mesh_testkit::shared_file("cgal_holes.off") {
        let data = mesh_io::read(&holes).unwrap_or_else(|e| panic!("{}: {e}", holes.display()));
        shapes.push(("cgal_holes.off", data.mesh));
    }
    for (name, mesh) in &shapes {
        let h = Arc::new(mesh_wavelet::detect(mesh, &Default::default()).unwrap());
        println!(
            "\n## {name}: {} vertices, {} levels, base {} vertices",
            mesh.vertex_count(),
            h.levels(),
            h.vertex_count(0).unwrap()
        );
        for scheme in Scheme::ALL {
            for kind in [WaveletKind::Lazy, WaveletKind::Lifted] {
                let bank = Arc::new(FilterBank::new(&h, scheme, kind).unwrap());
                let mr = Multiresolution::from_parts(h.clone(), bank, mesh.positions()).unwrap();
                let back = mr.synthesize().unwrap();
                let scale = mesh.positions().iter().map(|p| p.length()).fold(0.0, f64::max);
                let err =
                    back.positions().iter().zip(mesh.positions()).map(|(a, b)| a.distance(*b)).fold(0.0, f64::max)
                        / scale;
                let stats = mr.statistics();
                let means: Vec<String> = stats.iter().map(|s| format!("{:.2e}", s.mean)).collect();
                let curve = mr.compression_curve(&[0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1.0]).unwrap();
                let rms: Vec<String> = curve.iter().map(|c| format!("{:.2e}", c.rms_error)).collect();
                println!(
                    "{scheme:9} {kind:6} recon {err:.1e} decay {:.2} means [{}]\n                 rms@[1,2,5,10,20,50,100]% [{}]",
                    decay_rate(&stats).unwrap_or(f64::NAN),
                    means.join(" "),
                    rms.join(" ")
                );
            }
        }
    }
}
