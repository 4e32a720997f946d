//! The unit of length changes no answer: every quantity of mesh-kernel on a
//! mesh and on the same mesh scaled by `s` agrees (to 1e-12 relative) after
//! dividing by `s^d`, `d` the quantity's degree in lengths, for `s` from
//! 1e-150 to 1e150 (where every such quantity is representable).

use mesh_kernel::clean::{clean, degenerate_faces, CleanOptions};
use mesh_kernel::glam::DVec3;
use mesh_kernel::operators::{self, IntrinsicOptions, IntrinsicTriangulation, MassKind};
use mesh_kernel::{geometry, shapes, TriMesh};

const SCALES: [f64; 6] = [1e-150, 3.7e-90, 2e-20, 1.5e30, 6e99, 1e150];

fn scaled(mesh: &TriMesh, s: f64) -> TriMesh {
    TriMesh::new(mesh.positions().iter().map(|p| *p * s).collect(), mesh.faces().to_vec()).unwrap()
}

/// `max |a / unit - b| <= 1e-12 max |b|`.
fn assert_same(what: &str, a: &[f64], b: &[f64], unit: f64) {
    assert_eq!(a.len(), b.len(), "{what}");
    let size = b.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        assert!((x / unit - y).abs() <= 1e-12 * size, "{what}[{i}]: {x} / {unit} vs {y}");
    }
}

/// A sphere with two zero-area faces (collinear and coincident corners) and
/// a copy of one of its vertices.
fn sphere_with_needles() -> TriMesh {
    let (mut p, mut f) = shapes::icosphere(2).unwrap().into_parts();
    let n = p.len() as u32;
    p.extend([DVec3::new(2.0, 0.0, 0.0), DVec3::new(3.0, 0.0, 0.0), DVec3::new(4.0, 1e-14, 0.0)]);
    p.extend([p[0], DVec3::new(2.0, 0.0, 0.0)]);
    f.extend([[n, n + 1, n + 2], [n + 3, f[0][1], f[0][2]], [n, n + 1, n + 4]]);
    TriMesh::new(p, f).unwrap()
}

#[test]
fn geometry_does_not_depend_on_the_unit() {
    let mesh = shapes::irregular_torus(1.0, 0.4, 20, 10, 0.2, 3).unwrap();
    let normals =
        |m: &TriMesh, w| -> Vec<f64> { geometry::vertex_normals(m, w).iter().flat_map(|n| n.to_array()).collect() };
    for s in SCALES {
        let m = scaled(&mesh, s);
        assert_same("face areas", &geometry::face_areas(&m), &geometry::face_areas(&mesh), s * s);
        assert_same("surface area", &[geometry::surface_area(&m)], &[geometry::surface_area(&mesh)], s * s);
        assert_same("edge lengths", &geometry::edge_lengths(&m), &geometry::edge_lengths(&mesh), s);
        let diagonal = |m: &TriMesh| geometry::bounding_box(m).unwrap().diagonal();
        assert_same("diagonal", &[diagonal(&m)], &[diagonal(&mesh)], s);
        let angles = |m: &TriMesh| geometry::corner_angles(m).concat();
        assert_same("angles", &angles(&m), &angles(&mesh), 1.0);
        assert_same("dihedral angles", &geometry::dihedral_angles(&m), &geometry::dihedral_angles(&mesh), 1.0);
        for w in [
            geometry::NormalWeighting::Area,
            geometry::NormalWeighting::Angle,
            geometry::NormalWeighting::Uniform,
            geometry::NormalWeighting::Max,
        ] {
            assert_same(&format!("{w:?} normals"), &normals(&m, w), &normals(&mesh, w), 1.0);
        }
        if (1e-100..1e100).contains(&s) {
            let volume = geometry::enclosed_volume;
            assert_same("volume", &[volume(&m)], &[volume(&mesh)], s * s * s);
        }
    }
}

#[test]
fn operators_do_not_depend_on_the_unit() {
    let mesh = shapes::irregular_torus(1.0, 0.4, 20, 10, 0.2, 5).unwrap();
    let intrinsic = |m: &TriMesh| {
        IntrinsicTriangulation::delaunay(m, &IntrinsicOptions::default()).unwrap().cotan_laplacian().data().to_vec()
    };
    for s in SCALES {
        let m = scaled(&mesh, s);
        let cotan = |m: &TriMesh| operators::cotan_laplacian(m).data().to_vec();
        assert_same("cotan Laplacian", &cotan(&m), &cotan(&mesh), 1.0);
        assert_same("intrinsic Delaunay Laplacian", &intrinsic(&m), &intrinsic(&mesh), 1.0);
        for kind in [MassKind::MixedVoronoi, MassKind::Barycentric] {
            let mass = |m: &TriMesh| operators::lumped_mass(m, kind);
            assert_same(&format!("{kind:?} mass"), &mass(&m), &mass(&mesh), s * s);
        }
    }
}

#[test]
fn degeneracy_and_cleaning_do_not_depend_on_the_unit() {
    let mesh = sphere_with_needles();
    let reference = degenerate_faces(&mesh, 1e-12);
    assert_eq!(reference.len(), 2);
    let cleaned = |m: &TriMesh| {
        let (c, r) = clean(m.positions().to_vec(), m.faces().to_vec(), &CleanOptions::default()).unwrap();
        (c.vertex_count(), c.face_count(), r)
    };
    let expected = cleaned(&mesh);
    for s in SCALES.into_iter().chain([1e-300, 1e300]) {
        let m = scaled(&mesh, s);
        assert_eq!(degenerate_faces(&m, 1e-12), reference, "scale {s}");
        assert_eq!(cleaned(&m), expected, "scale {s}");
    }
}

#[test]
fn a_weld_tolerance_past_the_diagonal_is_refused() {
    let (p, f) = shapes::icosphere(1).unwrap().into_parts();
    for tolerance in [3.5, 1e300] {
        let options = CleanOptions { weld_tolerance: Some(tolerance), ..Default::default() };
        let err = clean(p.clone(), f.clone(), &options).unwrap_err().to_string();
        assert!(err.contains("bounding-box diagonal"), "{err}");
    }
    let options = CleanOptions { weld_tolerance: Some(1.9), ..Default::default() };
    assert!(clean(p, f, &options).is_ok());
}
