//! Accuracy of the default estimator on tessellations of exact NURBS
//! surfaces (mesh-nurbs): torus, sphere, cylinder and saddle at four
//! resolutions, max errors of k1, k2, H, K over the regular interior
//! vertices against the exact per-vertex values, with the observed orders.
//! Run with `cargo run --release -p mesh-curvature --example nurbs`.

use mesh_curvature::{curvature_tensor, TensorOptions};
use mesh_kernel::{VertexId, VertexKind};
use mesh_nurbs::glam::DVec3;
use mesh_nurbs::{shapes, tessellate, GridOptions, NurbsSurface};

type Keep = fn(DVec3) -> bool;

/// Max errors of k1, k2, H, K and the number of vertices compared.
fn errors(surface: &NurbsSurface, su: usize, sv: usize, keep: Keep) -> Result<([f64; 4], usize, usize), String> {
    let t = tessellate(surface, &GridOptions { segments_u: su, segments_v: sv, ..Default::default() })
        .map_err(|e| e.to_string())?;
    let est = curvature_tensor(&t.mesh, &TensorOptions::default()).map_err(|e| e.to_string())?;
    let conn = t.mesh.connectivity();
    let (mut e, mut compared) = ([0.0f64; 4], 0);
    for (i, p) in t.mesh.positions().iter().enumerate() {
        let interior = conn.vertex_kind(VertexId::new(i)) == VertexKind::Interior;
        if !(t.regular[i] && interior && est.status[i].is_valid() && keep(*p)) {
            continue;
        }
        compared += 1;
        let (k1, k2) = (est.k1[i], est.k2[i]);
        for (q, err) in
            [k1 - t.k1[i], k2 - t.k2[i], 0.5 * (k1 + k2) - t.mean[i], k1 * k2 - t.gaussian[i]].into_iter().enumerate()
        {
            e[q] = e[q].max(err.abs());
        }
    }
    Ok((e, compared, t.mesh.vertex_count()))
}

fn main() -> Result<(), String> {
    let o = DVec3::ZERO;
    let all: Keep = |_| true;
    let off_poles: Keep = |p| p.z.abs() <= 0.98;
    let nurbs = |r: mesh_nurbs::error::Result<NurbsSurface>| r.map_err(|e| e.to_string());
    let cases: Vec<(&str, NurbsSurface, usize, Keep)> = vec![
        ("torus R 2 r 0.5", nurbs(shapes::torus(o, 2.0, 0.5))?, 4, all),
        ("sphere r 1", nurbs(shapes::sphere(o, 1.0))?, 2, all),
        ("sphere, |z| <= 0.98", nurbs(shapes::sphere(o, 1.0))?, 2, off_poles),
        ("cylinder r 1 h 2", nurbs(shapes::cylinder(o, 1.0, 2.0))?, 3, all),
        ("saddle z = xy", nurbs(shapes::bilinear(o, DVec3::X, DVec3::Y, DVec3::new(1.0, 1.0, 1.0)))?, 1, all),
    ];
    let filter: Vec<String> = std::env::args().skip(1).collect();
    for (name, surface, ratio, keep) in &cases {
        if !filter.is_empty() && !filter.iter().any(|f| name.contains(f.as_str())) {
            continue;
        }
        println!("== {name}: grid {ratio}n x n, max errors (regular interior vertices)");
        println!("{:>5} {:>8} {:>8} {:>10} {:>10} {:>10} {:>10}", "n", "V", "compared", "k1", "k2", "H", "K");
        let mut rows = Vec::new();
        for n in [16, 32, 64, 128] {
            let (e, compared, v) = errors(surface, ratio * n, n, *keep)?;
            println!("{n:5} {v:8} {compared:8} {:10.2e} {:10.2e} {:10.2e} {:10.2e}", e[0], e[1], e[2], e[3]);
            rows.push(e);
        }
        let orders: Vec<String> = (0..4)
            .map(|q| {
                rows.windows(2).map(|w| format!("{:.1}", (w[0][q] / w[1][q]).log2())).collect::<Vec<_>>().join("/")
            })
            .collect();
        println!("orders k1 {}  k2 {}  H {}  K {}", orders[0], orders[1], orders[2], orders[3]);
    }
    Ok(())
}
