//! Exact curvature of NURBS shapes and their tessellation.
//!
//! `cargo run --release -p mesh-nurbs --example nurbs_shapes`

use mesh_nurbs::glam::DVec3;
use mesh_nurbs::{json, shapes, tessellate, tessellate_adaptive, AdaptiveOptions, GridOptions, SurfaceFrame};

fn main() -> Result<(), mesh_nurbs::NurbsError> {
    // A torus with R = 3, r = 1: exact curvature at a point.
    let torus = shapes::torus(DVec3::ZERO, 3.0, 1.0)?;
    let f = SurfaceFrame::new(&torus, 0.1, 0.25)?;
    println!(
        "torus at (0.1, 0.25): point {:.4}, K {:.6}, H {:.6}, k1 {:.6}, k2 {:.6}",
        f.point(),
        f.gaussian,
        f.mean,
        f.k1,
        f.k2
    );

    // Uniform tessellation: watertight, per-vertex exact curvature.
    let t = tessellate(&torus, &GridOptions { segments_u: 96, segments_v: 48, ..Default::default() })?;
    let c = t.mesh.connectivity();
    println!(
        "torus mesh: {} vertices, {} faces, chi {}, genus {:?}",
        t.mesh.vertex_count(),
        t.mesh.face_count(),
        c.euler_characteristic(),
        c.genus()
    );
    for (name, values) in t.scalar_properties() {
        let (lo, hi) = values.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| (a.min(x), b.max(x)));
        println!("  {name:>8}: [{lo:.6}, {hi:.6}]");
    }

    // Adaptive tessellation of a sphere to a chordal tolerance.
    let sphere = shapes::sphere(DVec3::ZERO, 1.0)?;
    for tol in [1e-2, 1e-3, 1e-4] {
        let t = tessellate_adaptive(&sphere, &AdaptiveOptions { chordal_tolerance: tol, ..Default::default() })?;
        println!("sphere, tolerance {tol:e}: {} vertices, {} faces", t.mesh.vertex_count(), t.mesh.face_count());
    }

    // The JSON format.
    let patch = shapes::bilinear(DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(1.0, 1.0, 1.0))?;
    println!("{}", json::to_json_string(&patch)?);
    Ok(())
}
