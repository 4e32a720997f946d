//! Remeshing of shapes and shared meshes: the output lies on the input,
//! edges near the target, angles bounded, the topology kept, no cracks.

use glam::DVec3;
use mesh_kernel::{geometry, shapes, TriMesh};
use mesh_remesh::{remesh, RemeshError, RemeshOptions, Remeshed};

fn run(mesh: &TriMesh, h: f64) -> Remeshed {
    remesh(mesh, &RemeshOptions { edge_length: h, ..Default::default() }).unwrap()
}

/// Every edge has two faces (closed) or one (on the input's boundary only),
/// and the topology is the input's.
fn check_watertight_and_topology(input: &TriMesh, r: &Remeshed) {
    let q = &r.report;
    assert!(!q.topology_changed, "{:?} vs {:?}", q.input_topology, q.output_topology);
    assert_eq!(q.input_topology.euler_characteristic, q.output_topology.euler_characteristic);
    assert_eq!(q.input_topology.components, q.output_topology.components);
    assert_eq!(q.input_topology.boundary_loops, q.output_topology.boundary_loops);
    let conn = r.mesh.manifold_connectivity().unwrap();
    let boundary_edges =
        (0..conn.edge_count()).filter(|&e| conn.is_boundary_edge(mesh_kernel::EdgeId(e as u32))).count();
    if input.connectivity().boundary_loop_count() == Some(0) {
        assert_eq!(boundary_edges, 0, "cracks in a closed output");
    }
    assert_eq!(r.face_chart.len(), r.mesh.face_count());
    assert!(r.mesh.positions().iter().all(|p| p.is_finite()));
}

/// Quality bounds common to every test mesh.
fn check_quality(r: &Remeshed, h: f64, max_relative_hausdorff: f64) {
    let q = &r.report;
    let e = &q.edge_lengths;
    assert!(e.within_half > 0.95, "{e:?}");
    assert!((0.8..1.1).contains(&e.mean_over_target), "{e:?}");
    assert!(q.mean_min_angle_degrees > 45.0, "{}", q.mean_min_angle_degrees);
    assert!(q.below_20_degrees < 0.01, "{}", q.below_20_degrees);
    assert!(q.min_angle_degrees > 5.0, "{}", q.min_angle_degrees);
    let d = q.hausdorff.unwrap();
    assert!(d.symmetric_relative < max_relative_hausdorff, "{d:?}");
    assert!(d.symmetric <= d.diagonal && (h > 0.0));
    // Triangles against the input's normal: none on these smooth shapes.
    assert_eq!(q.normal_disagreements, 0, "{} of {}", q.normal_disagreements, q.faces);
}

#[test]
fn sphere_is_remeshed_on_the_surface() {
    let sphere = shapes::icosphere(4).unwrap(); // unit sphere, edges about 0.075
    let h = 0.15;
    let r = run(&sphere, h);
    check_watertight_and_topology(&sphere, &r);
    check_quality(&r, h, 0.01);
    // Vertices lie on the input (which lies within its own sag of the unit
    // sphere): radius 1 within the input's chord sag.
    let sag = 0.075f64.powi(2) / 2.0;
    for p in r.mesh.positions() {
        assert!((p.length() - 1.0).abs() < sag, "{}", p.length());
    }
    // The output's chords: sag of a triangle of edge about 1.5 h on a unit sphere.
    let d = r.report.hausdorff.unwrap();
    assert!(d.symmetric < (1.5 * h) * (1.5 * h) / 2.0, "{d:?}");
    // Count near the area over an equilateral triangle of side h, over 2.
    let expected = geometry::surface_area(&sphere) / (3f64.sqrt() / 4.0 * h * h) / 2.0;
    let v = r.mesh.vertex_count() as f64;
    assert!(v > 0.8 * expected && v < 2.0 * expected, "{v} vs {expected}");
    // Consistent orientation: the enclosed volume is positive, as the input's.
    assert!(geometry::enclosed_volume(&r.mesh) > 0.9 * geometry::enclosed_volume(&sphere));
}

#[test]
fn torus_is_remeshed_with_its_genus() {
    let torus = shapes::torus(2.0, 0.7, 64, 32).unwrap();
    let h = 0.15;
    let r = run(&torus, h);
    check_watertight_and_topology(&torus, &r);
    assert_eq!(r.report.output_topology.euler_characteristic, 0);
    check_quality(&r, h, 0.005);
    // Vertices on the torus (up to the input's sag).
    for p in r.mesh.positions() {
        let ring = (DVec3::new(p.x, p.y, 0.0).length() - 2.0).hypot(p.z);
        assert!((ring - 0.7).abs() < 0.01, "{ring}");
    }
}

#[test]
fn edge_length_follows_the_target() {
    let sphere = shapes::icosphere(4).unwrap();
    let coarse = run(&sphere, 0.3);
    let fine = run(&sphere, 0.1);
    let ratio = fine.mesh.vertex_count() as f64 / coarse.mesh.vertex_count() as f64;
    assert!((6.0..12.0).contains(&ratio), "{ratio}");
    for r in [&coarse, &fine] {
        check_watertight_and_topology(&sphere, r);
    }
}

#[test]
fn bad_edge_lengths_are_typed_errors() {
    let sphere = shapes::icosphere(2).unwrap();
    for h in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let e = remesh(&sphere, &RemeshOptions { edge_length: h, ..Default::default() }).unwrap_err();
        assert!(matches!(e, RemeshError::InvalidOption { name: "edge_length", .. }), "{h}: {e}");
    }
    let tiny = RemeshOptions { edge_length: 1e-5, ..Default::default() };
    assert!(matches!(remesh(&sphere, &tiny).unwrap_err(), RemeshError::TooManyVertices { .. }));
    let bounded = RemeshOptions { edge_length: 0.05, max_vertices: 1000, ..Default::default() };
    assert!(matches!(remesh(&sphere, &bounded).unwrap_err(), RemeshError::TooManyVertices { .. }));
    for bad in [
        RemeshOptions { min_angle: 50.0, ..Default::default() },
        RemeshOptions { max_area_distortion: 0.5, ..Default::default() },
        RemeshOptions { max_fold_degrees: f64::NAN, ..Default::default() },
        RemeshOptions { max_vertices: 0, ..Default::default() },
    ] {
        assert!(matches!(remesh(&sphere, &bad).unwrap_err(), RemeshError::InvalidOption { .. }));
    }
    let empty = TriMesh::new(vec![], vec![]).unwrap();
    assert!(remesh(&empty, &RemeshOptions::default()).is_err());
}

#[test]
fn open_surfaces_keep_their_boundary() {
    // A saddle disk: one boundary loop, kept (on the input's boundary).
    let mut disk = shapes::disk(12, 3).unwrap();
    for p in disk.positions_mut() {
        p.z = 0.3 * (p.x * p.x - p.y * p.y);
    }
    let h = 0.1;
    let r = run(&disk, h);
    check_watertight_and_topology(&disk, &r);
    check_quality(&r, h, 0.01);
}

/// The shared meshes (skipped with a message when the data is absent).
fn shared(name: &str) -> Option<TriMesh> {
    let path = mesh_testkit::shared_file(name)?;
    let raw = mesh_testkit::read_raw(&path).unwrap();
    Some(TriMesh::new(raw.positions.iter().map(|p| DVec3::from_array(*p)).collect(), raw.faces).unwrap())
}

#[test]
fn shared_meshes_are_remeshed() {
    for (name, max_hausdorff) in
        [("cgal_nefertiti.off", 0.03), ("cgal_mushroom.off", 0.015), ("cgal_elephant.off", 0.015)]
    {
        let Some(mesh) = shared(name) else { return };
        let h = geometry::mean_edge_length(&mesh);
        let r = run(&mesh, h);
        check_watertight_and_topology(&mesh, &r);
        let q = &r.report;
        assert!(q.edge_lengths.within_half > 0.95, "{name}: {:?}", q.edge_lengths);
        assert!(q.mean_min_angle_degrees > 45.0 && q.below_20_degrees < 0.01, "{name}: {q:?}");
        assert!(q.min_angle_degrees > 10.0, "{name}: {q:?}");
        assert!(q.normal_disagreements * 1000 <= q.faces, "{name}: {q:?}");
        assert!(q.hausdorff.unwrap().symmetric_relative < max_hausdorff, "{name}: {:?}", q.hausdorff);
    }
}

#[test]
fn angles_beat_a_plain_upsample_at_the_same_vertex_count() {
    // A torus of long thin quads (split in two): midpoint subdivision keeps
    // their shape at 4x the vertices; remeshing to the same count makes
    // them round.
    let coarse = shapes::torus(2.0, 0.7, 64, 10).unwrap();
    let (p, f) = shapes::midpoint_subdivide(&coarse);
    let up = TriMesh::new(p, f).unwrap();
    let target = up.vertex_count() as f64;
    // Area over the count gives the edge length (V = 1.155 A / h^2).
    let h = (1.155 * geometry::surface_area(&coarse) / target).sqrt();
    let r = run(&coarse, h);
    let count = r.mesh.vertex_count() as f64 / target;
    assert!((0.7..1.4).contains(&count), "{count}");
    let up_report = mesh_remesh::report::quality_report(&coarse, &up, h, true);
    // The upsample lies on the coarse input exactly; the remesh nearly.
    assert!(up_report.hausdorff.unwrap().symmetric_relative < 1e-9);
    assert!(r.report.hausdorff.unwrap().symmetric_relative < 0.01);
    assert!(
        r.report.mean_min_angle_degrees > up_report.mean_min_angle_degrees + 10.0,
        "{} vs {}",
        r.report.mean_min_angle_degrees,
        up_report.mean_min_angle_degrees
    );
    assert!(r.report.below_20_degrees < up_report.below_20_degrees);
}

#[test]
fn an_open_cylinder_keeps_two_boundary_loops() {
    // A tube: charts whose circle maps shorten the seam direction; an ear
    // on both sides of a seam once made an edge with four faces here.
    let tube = shapes::by_name("cylinder", 32).unwrap();
    for h in [0.05, 0.1, 0.2] {
        let r = run(&tube, h);
        check_watertight_and_topology(&tube, &r);
        assert_eq!(r.report.output_topology.boundary_loops, Some(2));
    }
}

#[test]
fn a_long_edge_length_keeps_the_topology_or_is_refused() {
    // Edges as long as the shape: few samples per seam. Either a valid
    // sphere (at least a tetrahedron) or a typed error, never a pillow.
    let sphere = shapes::icosphere(2).unwrap();
    let mut refused = 0;
    for h in [1.0, 1.5, 3.0, 10.0] {
        match remesh(&sphere, &RemeshOptions { edge_length: h, ..Default::default() }) {
            Ok(r) => {
                check_watertight_and_topology(&sphere, &r);
                assert!(r.mesh.vertex_count() >= 4, "{h}: {} vertices", r.mesh.vertex_count());
            }
            Err(RemeshError::ChartFailed { reason, .. }) => {
                assert!(reason.contains("edge length"), "{reason}");
                refused += 1;
            }
            Err(e) => panic!("{h}: {e}"),
        }
    }
    assert!(refused < 4);
}

#[test]
fn the_dirty_dragon_scan_is_remeshed_after_cleaning() {
    // 733 components after cleaning, one-face components, charts that touch
    // themselves at a vertex (a polygon through one output vertex twice),
    // fins and folds. Once a typed error; now remeshed with its topology.
    let Some(path) = mesh_testkit::shared_file("npm_dragon_res3.ply") else { return };
    let (positions, faces) = mesh_io::read(&path).unwrap().mesh.into_parts();
    let options = mesh_kernel::clean::CleanOptions { manifold: true, ..Default::default() };
    let (mesh, _) = mesh_kernel::clean::clean(positions, faces, &options).unwrap();
    let h = geometry::mean_edge_length(&mesh);
    let r = run(&mesh, h);
    check_watertight_and_topology(&mesh, &r);
    let q = &r.report;
    assert!(q.input_topology.components > 700, "{:?}", q.input_topology);
    assert!(q.edge_lengths.within_half > 0.95, "{:?}", q.edge_lengths);
    assert!(q.mean_min_angle_degrees > 45.0 && q.below_20_degrees < 0.02, "{q:?}");
    assert!(q.hausdorff.unwrap().symmetric_relative < 0.01, "{:?}", q.hausdorff);
    // The scan folds on itself: faces against the nearest input face's
    // normal are reported (they sit where the input's normals within two
    // edge lengths span more than 90 degrees), and stay rare.
    assert!(q.normal_disagreements * 100 <= q.faces, "{} of {}", q.normal_disagreements, q.faces);
}

#[test]
fn charts_reaching_around_a_corner_are_split_instead_of_refused() {
    // At four times the mean edge length, charts of the elephant join two
    // seam points that a seam segment (or another chart) already joins: an
    // output edge with a third face, once a typed error on the full Stanford
    // dragon. The edges inside the charts are split at their midpoints.
    let Some(mesh) = shared("cgal_elephant.off") else { return };
    let h = 4.0 * geometry::mean_edge_length(&mesh);
    let r = run(&mesh, h);
    check_watertight_and_topology(&mesh, &r);
    assert!(r.report.stitch_splits > 0, "{:?}", r.report);
    // 311 vertices for an elephant: its trunk and legs are coarse.
    assert!(r.report.hausdorff.unwrap().symmetric_relative < 0.06, "{:?}", r.report.hausdorff);
}
