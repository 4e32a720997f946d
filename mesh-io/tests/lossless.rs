//! Nothing lost without a word when writing: values a 32-bit format cannot
//! hold are refused (or counted when allowed), rounding is reported, and a
//! mesh without faces keeps its vertices in every format that can hold them.

mod common;

use mesh_io::{read, write, IoError, PlyOptions, StlEncoding, WriteOptions};
use mesh_kernel::glam::DVec3;
use mesh_kernel::TriMesh;

/// A 5 x 5 grid of 25 vertices and 32 faces, scaled by `s`.
fn scaled_grid(s: f64) -> TriMesh {
    let g = common::grid(5).mesh;
    TriMesh::new(g.positions().iter().map(|p| *p * s).collect(), g.faces().to_vec()).unwrap()
}

/// Formats and options that store positions as `f32`.
fn narrow_formats() -> Vec<(&'static str, WriteOptions)> {
    let float_ply =
        WriteOptions { ply: PlyOptions { double: false, ..PlyOptions::default() }, ..WriteOptions::default() };
    vec![
        ("a.stl", WriteOptions::default()),
        ("a.glb", WriteOptions::default()),
        ("a.gltf", WriteOptions::default()),
        ("a.ply", float_ply),
    ]
}

#[test]
fn values_beyond_f32_are_refused_naming_the_vertex() {
    let dir = tempfile::tempdir().unwrap();
    for scale in [1e300, 1e-300, 1e-320] {
        let mesh = scaled_grid(scale);
        for (name, options) in narrow_formats() {
            let path = dir.path().join(name);
            let _ = std::fs::remove_file(&path);
            let e = write(&path, &mesh, &options).unwrap_err();
            let text = e.to_string();
            assert!(matches!(e, IoError::Precision { .. }), "{name} {scale}: {e:?}");
            assert!(text.contains("position of vertex 1") && text.contains(name), "{text}");
            assert!(!path.exists(), "nothing written on error");
            let allowed = WriteOptions { allow_precision_loss: true, ..options };
            let report = write(&path, &mesh, &allowed).unwrap();
            assert!(report.values_lost > 0 && !report.is_clean(), "{name} {scale}: {report:?}");
        }
        // Formats with 64-bit values keep the mesh exactly.
        for name in ["a.obj", "a.off", "b.ply"] {
            let path = dir.path().join(name);
            let report = write(&path, &mesh, &WriteOptions::default()).unwrap();
            assert!(report.is_clean(), "{name}");
            assert_eq!(read(&path).unwrap().mesh, mesh, "{name} {scale}");
        }
        let ascii = WriteOptions { stl: StlEncoding::Ascii, ..WriteOptions::default() };
        let path = dir.path().join("ascii.stl");
        assert!(write(&path, &mesh, &ascii).unwrap().is_clean());
        assert_eq!(read(&path).unwrap().mesh.vertex_count(), 25, "ascii STL keeps full precision");
    }
}

#[test]
fn rounding_beyond_a_millionth_is_reported() {
    let dir = tempfile::tempdir().unwrap();
    let exact = scaled_grid(1.0);
    // A millimetre-sized mesh a kilometre from the origin: f32 cannot resolve it.
    let far =
        TriMesh::new(exact.positions().iter().map(|p| *p * 1e-3 + DVec3::splat(1e3)).collect(), exact.faces().to_vec())
            .unwrap();
    for (name, options) in narrow_formats() {
        let path = dir.path().join(name);
        assert!(write(&path, &exact, &options).unwrap().is_clean(), "{name}: multiples of 1/64 are exact");
        let report = write(&path, &far, &options).unwrap();
        assert!(report.max_relative_rounding > 1e-6 && report.values_lost == 0, "{name}: {report:?}");
        assert!(report.to_string().contains("32-bit"), "{report}");
    }
}

#[test]
fn meshes_without_faces_keep_their_vertices() {
    let dir = tempfile::tempdir().unwrap();
    let points = TriMesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::new(0.5, 0.25, 2.0)], vec![]).unwrap();
    let ascii_ply = WriteOptions {
        ply: PlyOptions { encoding: mesh_io::PlyEncoding::Ascii, ..PlyOptions::default() },
        ..WriteOptions::default()
    };
    for (name, options) in [
        ("p.obj", WriteOptions::default()),
        ("p.off", WriteOptions::default()),
        ("p.ply", WriteOptions::default()),
        ("q.ply", ascii_ply),
        ("p.glb", WriteOptions::default()),
        ("p.gltf", WriteOptions::default()),
    ] {
        let path = dir.path().join(name);
        write(&path, &points, &options).unwrap();
        let back = read(&path).unwrap();
        assert_eq!(back.mesh, points, "{name}");
        assert!(back.report.is_clean(), "{name}: {:?}", back.report);
    }
    for encoding in [StlEncoding::Binary, StlEncoding::Ascii] {
        let path = dir.path().join("p.stl");
        let e = write(&path, &points, &WriteOptions { stl: encoding, ..WriteOptions::default() }).unwrap_err();
        assert!(matches!(e, IoError::Unsupported { .. }) && e.to_string().contains("without faces"), "{e}");
    }
    // An empty mesh is fine everywhere.
    let empty = TriMesh::new(vec![], vec![]).unwrap();
    for name in ["e.stl", "e.glb", "e.obj"] {
        write(dir.path().join(name), &empty, &WriteOptions::default()).unwrap();
    }
}

#[test]
fn non_finite_attributes_are_dropped_with_a_note() {
    let text = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 inf 1\nvn 0 0 1\nvn 0 0 1\nf 1//1 2//2 3//3\n";
    let data = mesh_io::read_from(text, mesh_io::Format::Obj, &Default::default()).unwrap();
    assert!(data.normals.is_none());
    assert!(!data.report.is_clean());
    assert!(data.report.notes.iter().any(|n| n.contains("normals dropped")), "{:?}", data.report.notes);
    assert_eq!(data.mesh.face_count(), 1);
}
