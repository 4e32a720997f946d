//! mesh-kernel: topology of every shape, Gauss-Bonnet, area convergence,
//! Laplacian invariants, linear precision, intrinsic Delaunay.

use std::f64::consts::{PI, TAU};

use mesh_kernel::operators::{self, IntrinsicOptions, IntrinsicTriangulation};
use mesh_kernel::{geometry, shapes, TriMesh, VertexKind};

use super::{convergence_order, no_shared_data, shared_data, Validator};

/// Runs the mesh-kernel checks.
pub fn run(v: &mut Validator) {
    shape_topology(v);
    shared_meshes(v);
    gauss_bonnet(v);
    sphere_area(v);
    laplacian_invariants(v);
    linear_precision(v);
    intrinsic_delaunay(v);
}

/// Shapes with documented chi, genus and boundary loop counts.
fn shape_topology(v: &mut Validator) {
    let cases: Vec<(&str, mesh_kernel::Result<TriMesh>, i64, u64, usize)> = vec![
        ("icosphere(4)", shapes::icosphere(4), 2, 0, 0),
        ("uv_sphere(32, 16)", shapes::uv_sphere(1.0, 32, 16), 2, 0, 0),
        ("torus(64, 16)", shapes::torus(2.0, 0.5, 64, 16), 0, 1, 0),
        ("cylinder(32, 8)", shapes::cylinder(1.0, 2.0, 32, 8), 0, 0, 2),
        ("grid(16, 9)", shapes::grid(1.0, 1.0, 16, 9), 1, 0, 1),
        ("disk(12)", shapes::disk(12, 1), 1, 0, 1),
        ("cube(5)", shapes::cube(5), 2, 0, 0),
    ];
    for (name, mesh, chi, genus, loops) in cases {
        match mesh {
            Ok(m) => topology(v, name, &m, chi, genus, loops),
            Err(e) => v.error(name, e),
        }
    }
}

/// Checks the Euler characteristic, genus and boundary loop count of `m`
/// (-1 stands for an undefined genus or loop count).
fn topology(v: &mut Validator, name: &str, m: &TriMesh, chi: i64, genus: u64, loops: usize) {
    let c = m.connectivity();
    v.equal(format!("{name}: euler characteristic"), c.euler_characteristic(), chi);
    v.equal(format!("{name}: genus"), c.genus().map_or(-1, |g| g as i64), genus as i64);
    v.equal(format!("{name}: boundary loops"), c.boundary_loop_count().map_or(-1, |b| b as i64), loops as i64);
}

/// The counts of the shared meshes' README (`mesh_testkit::data::SHARED_MESHES`).
fn shared_meshes(v: &mut Validator) {
    let Some(dir) = shared_data() else {
        v.skip("shared meshes", no_shared_data());
        return;
    };
    for m in mesh_testkit::data::SHARED_MESHES {
        let (file, nv, nf, chi, genus, loops) = (m.name, m.vertices, m.faces, m.euler, m.genus, m.boundary_loops);
        match mesh_io::read(dir.join(file)) {
            Ok(data) => {
                let m = &data.mesh;
                v.equal(format!("{file}: vertices"), m.vertex_count() as i64, nv as i64);
                v.equal(format!("{file}: faces"), m.face_count() as i64, nf as i64);
                topology(v, file, m, chi, genus, loops);
            }
            Err(e) => v.error(file, e),
        }
    }
}

/// Sum of angle defects plus boundary turning angles minus 2 pi chi: zero on
/// every manifold mesh, by the discrete Gauss-Bonnet theorem.
fn gauss_bonnet_residual(m: &TriMesh) -> f64 {
    let c = m.connectivity();
    let mut angle_sum = vec![0.0; m.vertex_count()];
    for (tri, angles) in m.faces().iter().zip(geometry::corner_angles(m)) {
        for k in 0..3 {
            angle_sum[tri[k] as usize] += angles[k];
        }
    }
    let total: f64 = m
        .vertex_ids()
        .map(|vid| match c.vertex_kind(vid) {
            VertexKind::Interior => TAU - angle_sum[vid.idx()],
            VertexKind::Boundary => PI - angle_sum[vid.idx()],
            _ => 0.0,
        })
        .sum();
    (total - TAU * c.euler_characteristic() as f64).abs()
}

fn gauss_bonnet(v: &mut Validator) {
    let mut meshes: Vec<(String, TriMesh)> = Vec::new();
    for (name, m) in [
        ("torus", shapes::torus(2.0, 0.5, 48, 16)),
        ("cylinder", shapes::cylinder(1.0, 2.0, 24, 6)),
        ("disk", shapes::disk(10, 3)),
        ("cube", shapes::cube(4)),
    ] {
        match m {
            Ok(m) => meshes.push((name.to_owned(), m)),
            Err(e) => v.error(name, e),
        }
    }
    if let Some(dir) = shared_data() {
        for file in ["cgal_elephant.off", "cgal_holes.off", "cgal_mushroom.off", "npm_bunny.obj"] {
            match mesh_io::read(dir.join(file)) {
                Ok(d) => meshes.push((file.to_owned(), d.mesh)),
                Err(e) => v.error(file, e),
            }
        }
    }
    for (name, m) in meshes {
        v.at_most(format!("Gauss-Bonnet |sum K + sum k_g - 2 pi chi|, {name}"), gauss_bonnet_residual(&m), 1e-10);
    }
}

fn sphere_area(v: &mut Validator) {
    let mut errors = Vec::new();
    for level in 2..=6 {
        match shapes::icosphere(level) {
            Ok(m) => errors.push((geometry::surface_area(&m) - 4.0 * PI).abs()),
            Err(e) => return v.error("icosphere area", e),
        }
    }
    v.at_most("icosphere(6) |area - 4 pi|", errors[errors.len() - 1], 2e-3);
    v.holds(
        "icosphere area error falls at every refinement",
        errors.windows(2).all(|w| w[1] < w[0]),
        errors.iter().map(|e| format!("{e:.2e}")).collect::<Vec<_>>().join(" "),
    );
    v.at_least("icosphere area convergence order (h halves per level)", convergence_order(&errors), 1.9);
}

fn laplacian_invariants(v: &mut Validator) {
    for (name, m) in
        [("torus", shapes::torus(2.0, 0.5, 64, 16)), ("disk", shapes::disk(16, 5)), ("cube", shapes::cube(6))]
    {
        let m = match m {
            Ok(m) => m,
            Err(e) => return v.error(name, e),
        };
        let l = operators::cotan_laplacian(&m);
        let t = l.transpose_view().to_csr();
        let asym = (&l - &t).data().iter().fold(0.0f64, |a, x| a.max(x.abs()));
        let row_sum = l.outer_iterator().map(|r| r.iter().map(|(_, x)| x).sum::<f64>().abs()).fold(0.0, f64::max);
        v.at_most(format!("cotan Laplacian max |L - L^T|, {name}"), asym, 1e-12);
        v.at_most(format!("cotan Laplacian max |row sum|, {name}"), row_sum, 1e-12);
    }
}

fn linear_precision(v: &mut Validator) {
    let m = match shapes::disk(20, 9) {
        Ok(m) => m,
        Err(e) => return v.error("disk", e),
    };
    let l = operators::cotan_laplacian(&m);
    let c = m.connectivity();
    let x: Vec<f64> = m.positions().iter().map(|p| 0.7 * p.x - 1.3 * p.y + 0.2).collect();
    let worst = l
        .outer_iterator()
        .enumerate()
        .filter(|(i, _)| !c.is_boundary_vertex(mesh_kernel::VertexId::new(*i)))
        .map(|(_, row)| row.iter().map(|(j, w)| w * x[j]).sum::<f64>().abs())
        .fold(0.0, f64::max);
    v.at_most("cotan Laplacian of a linear function on a planar disk (interior)", worst, 1e-12);
}

fn intrinsic_delaunay(v: &mut Validator) {
    // Already Delaunay: no flips, same weights as the cotangent Laplacian.
    match shapes::icosphere(3).and_then(|m| {
        let opts = IntrinsicOptions { mollify: 0.0, ..Default::default() };
        Ok((IntrinsicTriangulation::delaunay(&m, &opts)?, m))
    }) {
        Ok((t, m)) => {
            v.equal("intrinsic Delaunay flips on an icosphere (already Delaunay)", t.flip_count() as i64, 0);
            let diff = &t.cotan_laplacian() - &operators::cotan_laplacian(&m);
            v.at_most(
                "intrinsic vs cotan Laplacian on a Delaunay mesh",
                diff.data().iter().fold(0.0, |a, x| a.max(x.abs())),
                1e-12,
            );
        }
        Err(e) => v.error("intrinsic Delaunay on an icosphere", e),
    }
    // A squashed, bumpy disk has obtuse triangles and negative cotan weights.
    let Ok(mut m) = shapes::disk(16, 2) else { return v.error("disk", "construction failed") };
    for p in m.positions_mut() {
        p.y *= 0.1;
        p.z = 0.05 * (4.0 * p.x).sin();
    }
    let negative = operators::cotan_weights(&m).iter().filter(|w| **w < 0.0).count();
    v.at_least("negative cotan weights on a squashed disk (before flips)", negative as f64, 1.0);
    match IntrinsicTriangulation::delaunay(&m, &IntrinsicOptions::default()) {
        Ok(t) => {
            let min = t.interior_edge_weights().into_iter().fold(f64::INFINITY, f64::min);
            v.at_least("min interior intrinsic Delaunay weight, squashed disk", min, -1e-12);
        }
        Err(e) => v.error("intrinsic Delaunay on a squashed disk", e),
    }
    if let Some(dir) = shared_data() {
        match mesh_io::read(dir.join("cgal_degtri_sliding.off")).map_err(|e| e.to_string()).and_then(|d| {
            IntrinsicTriangulation::delaunay(&d.mesh, &IntrinsicOptions::default()).map_err(|e| e.to_string())
        }) {
            Ok(t) => v.holds(
                "intrinsic Laplacian finite on zero-area triangles (cgal_degtri_sliding)",
                t.cotan_laplacian().data().iter().all(|x| x.is_finite()),
                format!("{} flips", t.flip_count()),
            ),
            Err(e) => v.error("cgal_degtri_sliding", e),
        }
    }
}
