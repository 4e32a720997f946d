//! Tessellation: watertight topology of closed shapes, orientation, poles,
//! convergence of the area, adaptive chordal tolerance, per-vertex data.

use std::f64::consts::PI;

use mesh_kernel::TriMesh;
use mesh_nurbs::glam::DVec3;
use mesh_nurbs::{
    shapes, tessellate, tessellate_adaptive, AdaptiveOptions, GridOptions, NurbsSurface, SurfaceFrame, Tessellation,
};

fn grid(surface: &NurbsSurface, nu: usize, nv: usize) -> Tessellation {
    tessellate(surface, &GridOptions { segments_u: nu, segments_v: nv, ..Default::default() }).expect("tessellation")
}

fn area(mesh: &TriMesh) -> f64 {
    mesh.faces()
        .iter()
        .map(|&[a, b, c]| {
            let p = mesh.positions();
            0.5 * (p[b as usize] - p[a as usize]).cross(p[c as usize] - p[a as usize]).length()
        })
        .sum()
}

/// Six times the signed volume: positive for a closed mesh with outward,
/// counter-clockwise triangles.
fn signed_volume(mesh: &TriMesh) -> f64 {
    let p = mesh.positions();
    mesh.faces().iter().map(|&[a, b, c]| p[a as usize].dot(p[b as usize].cross(p[c as usize]))).sum::<f64>() / 6.0
}

/// No triangle of zero area.
fn no_degenerate_triangles(mesh: &TriMesh) -> bool {
    let p = mesh.positions();
    mesh.faces()
        .iter()
        .all(|&[a, b, c]| (p[b as usize] - p[a as usize]).cross(p[c as usize] - p[a as usize]).length() > 0.0)
}

#[test]
fn sphere_is_a_closed_genus_zero_surface() {
    let r = 1.5;
    let s = shapes::sphere(DVec3::ZERO, r).expect("sphere");
    for (nu, nv) in [(3, 2), (8, 4), (40, 20), (33, 17)] {
        let t = grid(&s, nu, nv);
        let c = t.mesh.manifold_connectivity().expect("manifold");
        assert_eq!(c.euler_characteristic(), 2);
        assert_eq!(c.genus(), Some(0));
        assert_eq!(c.boundary_loop_count(), Some(0));
        assert_eq!(t.mesh.vertex_count(), nu * (nv - 1) + 2);
        assert!(no_degenerate_triangles(&t.mesh));
        assert!(signed_volume(&t.mesh) > 0.0);
        // Poles: one vertex each, flagged, with the exact outward normal.
        let poles: Vec<usize> = (0..t.mesh.vertex_count()).filter(|&v| !t.regular[v]).collect();
        assert_eq!(poles.len(), 2);
        for &v in &poles {
            assert!((t.normal[v] - t.mesh.positions()[v] / r).length() < 1e-12);
            assert_eq!(c.valence(mesh_kernel::VertexId::new(v)), nu);
        }
    }
}

#[test]
fn sphere_vertex_data_is_exact() {
    let r = 2.0;
    let t = grid(&shapes::sphere(DVec3::new(1.0, 0.0, -1.0), r).expect("sphere"), 64, 32);
    for v in 0..t.mesh.vertex_count() {
        let p = t.mesh.positions()[v] - DVec3::new(1.0, 0.0, -1.0);
        assert!((p.length() - r).abs() < 1e-14);
        assert!((t.normal[v] - p / r).length() < 1e-12);
        assert!((t.gaussian[v] - 0.25).abs() < 1e-7 && (t.mean[v] - 0.5).abs() < 1e-7);
        assert!(t.k1[v] >= t.k2[v]);
        assert!(t.d1[v].dot(t.normal[v]).abs() < 1e-9 && (t.d1[v].length() - 1.0).abs() < 1e-12);
    }
    let props = t.scalar_properties();
    assert_eq!(props.iter().map(|p| p.0).collect::<Vec<_>>(), Tessellation::SCALAR_PROPERTIES);
    assert!(props
        .iter()
        .all(|(_, values)| values.len() == t.mesh.vertex_count() && values.iter().all(|x| x.is_finite())));
}

#[test]
fn sphere_area_converges() {
    let r = 1.0;
    let s = shapes::sphere(DVec3::ZERO, r).expect("sphere");
    let exact = 4.0 * PI * r * r;
    let mut previous = f64::INFINITY;
    for n in [8, 16, 32, 64, 128] {
        let error = (area(&grid(&s, 2 * n, n).mesh) - exact).abs();
        assert!(error < previous * 0.5, "n {n}: error {error} after {previous}");
        previous = error;
    }
    assert!(previous < 2e-3, "error {previous}");
}

#[test]
fn torus_is_a_closed_genus_one_surface() {
    let (big, small) = (3.0, 1.0);
    let s = shapes::torus(DVec3::ZERO, big, small).expect("torus");
    for (nu, nv) in [(3, 3), (24, 12), (50, 31)] {
        let t = grid(&s, nu, nv);
        let c = t.mesh.manifold_connectivity().expect("manifold");
        assert_eq!(c.euler_characteristic(), 0);
        assert_eq!(c.genus(), Some(1));
        assert_eq!(c.boundary_loop_count(), Some(0));
        assert_eq!(t.mesh.vertex_count(), nu * nv);
        assert!(t.regular.iter().all(|&r| r));
        assert!(signed_volume(&t.mesh) > 0.0);
    }
    let t = grid(&s, 96, 48);
    let volume = 2.0 * PI * PI * big * small * small;
    assert!((signed_volume(&t.mesh) - volume).abs() < 0.01 * volume);
}

#[test]
fn cylinder_and_cone_are_open_where_they_should_be() {
    let cyl = grid(&shapes::cylinder(DVec3::ZERO, 1.0, 2.0).expect("cylinder"), 16, 4);
    let c = cyl.mesh.manifold_connectivity().expect("manifold");
    assert_eq!(c.boundary_loop_count(), Some(2));
    assert_eq!(c.euler_characteristic(), 0);
    assert_eq!(cyl.mesh.vertex_count(), 16 * 5);
    let cone = grid(&shapes::cone(DVec3::ZERO, 1.0, 2.0).expect("cone"), 16, 4);
    let c = cone.mesh.manifold_connectivity().expect("manifold");
    assert_eq!(c.boundary_loop_count(), Some(1));
    assert_eq!(c.euler_characteristic(), 1);
    assert!(no_degenerate_triangles(&cone.mesh));
    let apex: Vec<usize> = (0..cone.mesh.vertex_count()).filter(|&v| !cone.regular[v]).collect();
    assert_eq!(apex.len(), 1);
    assert!(cone.gaussian.iter().chain(&cone.mean).all(|x| x.is_finite()));
    // Outward-facing: normals of the triangles agree with the exact normals.
    let p = cone.mesh.positions();
    for &[a, b, c] in cone.mesh.faces() {
        let n = (p[b as usize] - p[a as usize]).cross(p[c as usize] - p[a as usize]);
        let exact = cone.normal[a as usize] + cone.normal[b as usize] + cone.normal[c as usize];
        assert!(n.dot(exact) > 0.0);
    }
}

#[test]
fn open_patch_keeps_its_boundary() {
    let s = shapes::bilinear(DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(1.0, 1.0, 0.5)).expect("patch");
    let t = grid(&s, 5, 7);
    assert_eq!(t.mesh.vertex_count(), 6 * 8);
    assert_eq!(t.mesh.face_count(), 2 * 5 * 7);
    let c = t.mesh.manifold_connectivity().expect("manifold");
    assert_eq!(c.boundary_loop_count(), Some(1));
    // Hyperbolic paraboloid: K < 0 everywhere.
    assert!(t.gaussian.iter().all(|&k| k < 0.0));
}

#[test]
fn adaptive_tessellation_meets_the_tolerance() {
    let r = 1.0;
    let s = shapes::sphere(DVec3::ZERO, r).expect("sphere");
    let mut previous_vertices = 0;
    for tol in [1e-2, 1e-3, 1e-4] {
        let options = AdaptiveOptions { chordal_tolerance: tol, ..Default::default() };
        let t = tessellate_adaptive(&s, &options).expect("adaptive");
        assert_eq!(t.mesh.connectivity().euler_characteristic(), 2);
        assert!(t.mesh.vertex_count() > previous_vertices);
        previous_vertices = t.mesh.vertex_count();
        // Distance from triangle centroids (the deepest points of the
        // triangles, about) to the sphere.
        let p = t.mesh.positions();
        let worst = t
            .mesh
            .faces()
            .iter()
            .map(|&[a, b, c]| r - ((p[a as usize] + p[b as usize] + p[c as usize]) / 3.0).length())
            .fold(0.0, f64::max);
        assert!(worst <= tol, "tolerance {tol}: deviation {worst}");
        assert!(worst > tol / 40.0, "tolerance {tol}: over-refined, deviation {worst}");
    }
}

#[test]
fn adaptive_follows_curvature() {
    // A torus is more curved around the tube than about the axis.
    let s = shapes::torus(DVec3::ZERO, 4.0, 0.5).expect("torus");
    let t =
        tessellate_adaptive(&s, &AdaptiveOptions { chordal_tolerance: 1e-3, ..Default::default() }).expect("adaptive");
    let c = t.mesh.manifold_connectivity().expect("manifold");
    assert_eq!(c.genus(), Some(1));
    let distinct = |values: Vec<f64>| {
        let mut v = values;
        v.sort_by(f64::total_cmp);
        v.dedup();
        v.len()
    };
    let us = distinct(t.uv.iter().map(|p| p.x).collect());
    let vs = distinct(t.uv.iter().map(|p| p.y).collect());
    // Arc lengths: 2 pi 4.5 about the axis at the outer equator and 2 pi 0.5
    // around the tube, but the sag depends on the radius of curvature.
    assert!(us > 0 && vs > 0);
    let frame = SurfaceFrame::new(&s, 0.0, 0.0).expect("frame");
    assert!(frame.k1 > frame.k2);
}
