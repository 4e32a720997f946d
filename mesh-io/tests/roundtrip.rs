//! Write then read gives back the same mesh and attributes, for every format.

mod common;

use common::{corner_uvs, grid, irrational, triangle_soup};
use mesh_io::{read, write, Format, MeshData, MeshView, PlyEncoding, PlyOptions, StlEncoding, WriteOptions};

fn round_trip(data: &MeshData, name: &str, options: &WriteOptions) -> MeshData {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(name);
    write(&path, data, options).unwrap();
    let back = read(&path).unwrap();
    let r = &back.report;
    assert!(r.faces_dropped == 0 && r.polygons_triangulated == 0 && r.notes.is_empty(), "{name}: {r:?}");
    back
}

#[test]
fn obj_keeps_positions_normals_uvs_colors() {
    let d = irrational(6);
    let back = round_trip(&d, "a.obj", &WriteOptions::default());
    assert_eq!(back.mesh, d.mesh, "shortest round-trip floats are exact");
    assert_eq!(back.normals, d.normals);
    assert_eq!(back.uvs, d.uvs);
    assert_eq!(back.colors, d.colors);
    assert!(back.scalars.is_empty());
}

#[test]
fn obj_keeps_corner_uvs() {
    let mut d = grid(5);
    d.uvs = None;
    d.corner_uvs = Some(corner_uvs(&d));
    let back = round_trip(&d, "seams.OBJ", &WriteOptions::default());
    assert_eq!(back.mesh, d.mesh);
    assert_eq!(back.corner_uvs, d.corner_uvs);
    assert_eq!(back.uvs, None);
}

#[test]
fn off_keeps_positions_normals_colors_uvs() {
    let d = irrational(6);
    let back = round_trip(&d, "a.off", &WriteOptions::default());
    assert_eq!(back.mesh, d.mesh);
    assert_eq!(back.normals, d.normals);
    assert_eq!(back.uvs, d.uvs);
    let colors = back.colors.unwrap();
    for (a, b) in colors.iter().zip(d.colors.as_ref().unwrap()) {
        for k in 0..4 {
            assert!((a[k] - b[k]).abs() < 1e-6, "{a:?} {b:?}");
        }
    }
}

#[test]
fn ply_every_encoding_keeps_everything_bit_exact() {
    let d = irrational(6);
    for encoding in [PlyEncoding::Ascii, PlyEncoding::BinaryLittleEndian, PlyEncoding::BinaryBigEndian] {
        let options =
            WriteOptions { ply: PlyOptions { encoding, double: true, ..Default::default() }, ..Default::default() };
        let back = round_trip(&d, "a.ply", &options);
        let bits = |m: &MeshData| m.mesh.positions().iter().map(|p| p.to_array().map(f64::to_bits)).collect::<Vec<_>>();
        assert_eq!(bits(&back), bits(&d), "{encoding:?}");
        assert_eq!(back.mesh.faces(), d.mesh.faces());
        assert_eq!(back.normals, d.normals);
        assert_eq!(back.uvs, d.uvs);
        assert_eq!(back.scalars, d.scalars);
        assert_eq!(back.vectors, d.vectors);
        assert_eq!(back.labels, d.labels);
        assert_eq!(back.face_scalars, d.face_scalars);
        assert_eq!(back.face_vectors, d.face_vectors);
        assert_eq!(back.face_labels, d.face_labels);
        let colors = back.colors.unwrap();
        assert!(colors.iter().zip(d.colors.as_ref().unwrap()).all(|(a, b)| (a[0] - b[0]).abs() < 1e-6));
    }
}

#[test]
fn ply_float_positions_and_corner_uvs() {
    let mut d = grid(5);
    d.uvs = None;
    d.corner_uvs = Some(corner_uvs(&d));
    let options = WriteOptions { ply: PlyOptions { double: false, ..Default::default() }, ..Default::default() };
    let back = round_trip(&d, "a.ply", &options);
    assert_eq!(back.mesh, d.mesh, "grid coordinates are exact in f32");
    assert_eq!(back.corner_uvs, d.corner_uvs);
}

#[test]
fn ply_curvature_fields_as_the_cli_writes_them() {
    let d = irrational(4);
    let k1: Vec<f64> = (0..d.mesh.vertex_count()).map(|i| (i as f64).ln_1p()).collect();
    let view = MeshView::new(&d.mesh).with_scalar("k1", &k1).with_scalar("distance", &d.scalars[0].1);
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("curv.ply");
    write(&path, view, &WriteOptions::default()).unwrap();
    let header = std::fs::read(&path).unwrap();
    let header = String::from_utf8_lossy(&header[..300]);
    assert!(header.contains("format binary_little_endian 1.0\n"));
    assert!(header.contains("property double x\n") && header.contains("property double k1\n"));
    let back = read(&path).unwrap();
    assert_eq!(back.scalar("k1"), Some(&k1[..]));
    assert_eq!(back.mesh, d.mesh);
}

#[test]
fn stl_both_encodings_give_the_same_triangles() {
    let d = grid(6);
    for stl in [StlEncoding::Ascii, StlEncoding::Binary] {
        let back = round_trip(&d, "a.stl", &WriteOptions { stl, ..Default::default() });
        assert_eq!(back.mesh.vertex_count(), d.mesh.vertex_count(), "{stl:?}: welded back");
        assert_eq!(triangle_soup(&back.mesh), triangle_soup(&d.mesh), "{stl:?}");
    }
    let exact = irrational(4);
    let back = round_trip(&exact, "b.stl", &WriteOptions { stl: StlEncoding::Ascii, ..Default::default() });
    assert_eq!(triangle_soup(&back.mesh), triangle_soup(&exact.mesh), "ascii STL keeps f64");
}

#[test]
fn gltf_and_glb_keep_attributes() {
    let d = grid(6);
    for name in ["a.glb", "a.gltf"] {
        let back = round_trip(&d, name, &WriteOptions::default());
        assert_eq!(back.mesh, d.mesh, "{name}");
        assert_eq!(back.uvs, d.uvs);
        assert_eq!(back.colors, d.colors);
        assert_eq!(back.scalars, d.scalars);
        assert_eq!(back.vectors, d.vectors);
        assert_eq!(back.labels, d.labels);
        assert!(back.face_scalars.is_empty() && back.face_labels.is_empty(), "glTF has no per-face attributes");
        let normals = back.normals.unwrap();
        for (a, b) in normals.iter().zip(d.normals.as_ref().unwrap()) {
            assert!((*a - b.normalize()).length() < 1e-6, "normals come back unit length");
        }
    }
}

#[test]
fn gltf_with_external_buffer_next_to_it() {
    let d = grid(4);
    let mut text = Vec::new();
    mesh_io::gltf::write_gltf(&mut text, &d.view()).unwrap();
    let text = String::from_utf8(text).unwrap();
    let start = text.find("data:application/octet-stream;base64,").unwrap();
    let end = start + text[start..].find('"').unwrap();
    let dir = tempfile::tempdir().unwrap();
    let glb_bin = {
        let mut glb = Vec::new();
        mesh_io::gltf::write_glb(&mut glb, &d.view()).unwrap();
        let json_len = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
        glb[20 + json_len + 8..].to_vec()
    };
    std::fs::write(dir.path().join("my mesh.bin"), &glb_bin).unwrap();
    let external = format!("{}my%20mesh.bin{}", &text[..start], &text[end..]);
    std::fs::write(dir.path().join("ext.gltf"), external).unwrap();
    let back = read(dir.path().join("ext.gltf")).unwrap();
    assert_eq!(back.mesh, d.mesh);
}

#[test]
fn empty_and_faceless_meshes() {
    let empty = MeshData::new(mesh_kernel::TriMesh::new(vec![], vec![]).unwrap());
    for format in Format::ALL {
        let back = round_trip(&empty, &format!("e.{}", format.extension()), &WriteOptions::default());
        assert_eq!(back.mesh.vertex_count(), 0, "{format}");
    }
}

#[test]
fn write_to_any_writer_and_polylines() {
    let d = grid(3);
    let mut out = Vec::new();
    mesh_io::write_to(&mut out, Format::Off, &d.mesh, &WriteOptions::default()).unwrap();
    assert!(out.starts_with(b"OFF\n9 8 0\n"));
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("paths.obj");
    mesh_io::write_polylines(&path, &[d.mesh.positions()[..4].to_vec()]).unwrap();
    let back = read(&path).unwrap();
    assert_eq!(back.mesh.vertex_count(), 4);
    assert_eq!(back.report.notes, vec!["polyline (`l`) elements ignored".to_string()]);
}
