//! Named attributes beyond per-vertex scalars: vectors, integer labels and
//! per-face values, written then read back per format (bit-exact in PLY),
//! reported when a format cannot hold them, and hostile input refused with
//! typed errors.

mod common;

use mesh_io::{
    read_from, write_to, AttributeElement, AttributeKind, Format, IoError, MeshData, MeshView, PlyEncoding, PlyOptions,
    ReadOptions, WriteOptions,
};
use mesh_kernel::glam::DVec3;
use mesh_kernel::TriMesh;
use proptest::prelude::*;

fn ply(encoding: PlyEncoding) -> WriteOptions {
    WriteOptions { ply: PlyOptions { encoding, ..PlyOptions::default() }, ..WriteOptions::default() }
}

const ENCODINGS: [PlyEncoding; 3] = [PlyEncoding::Ascii, PlyEncoding::BinaryLittleEndian, PlyEncoding::BinaryBigEndian];

/// Writes `view` as `format` and reads it back.
fn through<'a>(
    view: impl Into<MeshView<'a>>,
    format: Format,
    options: &WriteOptions,
) -> (MeshData, mesh_io::WriteReport) {
    let mut bytes = Vec::new();
    let report = write_to(&mut bytes, format, view, options).unwrap();
    (read_from(&bytes, format, &ReadOptions::default()).unwrap(), report)
}

fn bits(v: &[DVec3]) -> Vec<[u64; 3]> {
    v.iter().map(|d| d.to_array().map(f64::to_bits)).collect()
}

/// A tetrahedron with values that use every bit of an `f64` and labels at
/// the ends of the 32-bit ranges.
fn tetra() -> TriMesh {
    TriMesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z], vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]])
        .unwrap()
}

#[test]
fn ply_keeps_vectors_labels_and_face_values_bit_exact() {
    let mesh = tetra();
    let third = 1.0 / 3.0;
    let d1 = [DVec3::new(third, -0.0, 1e-300), DVec3::new(f64::MAX, f64::MIN_POSITIVE, 5e-324), DVec3::X, DVec3::NEG_Y];
    let segment = [i64::from(i32::MIN), -1, 0, i64::from(i32::MAX)];
    let wide = [0, 1, i64::from(u32::MAX), 7];
    let distortion = [1.0, std::f64::consts::PI, 1e200, third];
    let gradient = [DVec3::splat(third), DVec3::ONE, DVec3::new(1e-10, 2e10, -3.0), DVec3::ZERO];
    let chart = [3, 2, 1, 0];
    let view = MeshView::new(&mesh)
        .with_vector("d1", &d1)
        .with_label("segment", &segment)
        .with_label("id", &wide)
        .with_face_scalar("distortion", &distortion)
        .with_face_vector("gradient", &gradient)
        .with_face_label("chart", &chart);
    for encoding in ENCODINGS {
        let (back, report) = through(view.clone(), Format::Ply, &ply(encoding));
        assert!(report.is_clean() && back.report.is_clean(), "{encoding:?}: {report} / {}", back.report);
        assert_eq!(bits(back.vector("d1").unwrap()), bits(&d1), "{encoding:?}");
        assert_eq!(back.label("segment"), Some(&segment[..]));
        assert_eq!(back.label("id"), Some(&wide[..]));
        let face = back.face_scalar("distortion").unwrap();
        assert_eq!(face.iter().map(|x| x.to_bits()).collect::<Vec<_>>(), distortion.map(f64::to_bits));
        assert_eq!(bits(back.face_vector("gradient").unwrap()), bits(&gradient));
        assert_eq!(back.face_label("chart"), Some(&chart[..]));
        assert!(back.scalars.is_empty(), "vector components are not read as scalars: {:?}", back.scalars);
        let listed: Vec<_> = back.attributes().iter().map(|a| (a.element, a.kind(), a.arity())).collect();
        assert!(listed.contains(&(AttributeElement::Face, AttributeKind::Vector, 3)), "{listed:?}");
    }
}

#[test]
fn ply_header_names_types_and_order() {
    let mesh = tetra();
    let (d1, label, face) = ([DVec3::X; 4], [-2i64, 0, 1, 2], [0.5; 4]);
    let wide = [0, 1, 1 << 31, 2];
    let view = MeshView::new(&mesh)
        .with_vector("d1", &d1)
        .with_label("segment", &label)
        .with_label("big", &wide)
        .with_face_scalar("distortion", &face);
    let mut bytes = Vec::new();
    write_to(&mut bytes, Format::Ply, view, &ply(PlyEncoding::Ascii)).unwrap();
    let text = String::from_utf8(bytes).unwrap();
    let header = &text[..text.find("end_header").unwrap()];
    for line in [
        "property double d1x\nproperty double d1y\nproperty double d1z\nproperty int segment\nproperty uint big\n",
        "element face 4\nproperty list uchar int vertex_indices\nproperty double distortion\n",
    ] {
        assert!(header.contains(line), "{header}");
    }
    assert!(text.contains("\n0.0 0.0 0.0 1.0 0.0 0.0 -2 0\n"), "negative labels in ascii: {text}");
    assert!(text.contains(" 1 2147483648\n") && text.contains("\n3 0 2 1 0.5\n"), "{text}");
}

#[test]
fn ply_reads_hand_written_vectors_labels_and_polygon_values() {
    let text = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n\
property float d2_x\nproperty float d2_y\nproperty float d2_z\nproperty int segment\nproperty float px\n\
property uchar py\nproperty float pz\nelement face 2\nproperty uchar flags\nproperty list uchar int vertex_indices\n\
property float quality\nproperty list uchar float extra\nend_header\n\
0 0 0 1 0 0 4 9 8 7\n1 0 0 0 1 0 5 9 8 7\n1 1 0 0 0 1 -6 9 8 7\n0 1 0 1 1 1 7 9 8 7\n\
3 4 0 1 2 3 0.5 1 2\n1 3 0 2 3 0.25 0\n";
    let d = read_from(text.as_bytes(), Format::Ply, &ReadOptions::default()).unwrap();
    assert_eq!(d.mesh.face_count(), 3, "a quad and a triangle");
    assert_eq!(d.vector("d2").unwrap()[2], DVec3::Z, "`d2_x d2_y d2_z` is the vector `d2`");
    assert_eq!(d.label("segment"), Some(&[4, 5, -6, 7][..]));
    assert!(d.vector("p").is_none(), "a triple with an integer member is not a vector");
    assert_eq!((d.scalar("px").map(<[f64]>::len), d.label("py").map(<[i64]>::len)), (Some(4), Some(4)));
    assert_eq!(d.face_label("flags"), Some(&[3, 3, 1][..]), "each triangle of the quad gets its value");
    assert_eq!(d.face_scalar("quality"), Some(&[0.5, 0.5, 0.25][..]));
    assert!(d.report.notes.iter().any(|n| n.contains("`extra` ignored")), "{:?}", d.report.notes);
}

#[test]
fn ply_labels_must_be_integers_and_nan_values_are_announced() {
    let head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\n\
property int segment\nproperty double k\nelement face 1\nproperty list uchar int vertex_indices\nproperty short chart\n\
end_header\n";
    let body = |segment: &str, k: &str, chart: &str| {
        format!("{head}0 0 0 {segment} 1\n1 0 0 1 {k}\n0 1 0 2 3\n3 0 1 2 {chart}\n")
    };
    let ok = read_from(body("0", "2", "5").as_bytes(), Format::Ply, &ReadOptions::default()).unwrap();
    assert!(ok.report.is_clean() && ok.face_label("chart") == Some(&[5][..]));
    for (segment, chart, line) in [("2.5", "5", 13), ("nan", "5", 13), ("1e300", "5", 13), ("0", "inf", 16)] {
        let e = read_from(body(segment, "2", chart).as_bytes(), Format::Ply, &ReadOptions::default()).unwrap_err();
        assert!(matches!(e, IoError::Syntax { .. }) && e.to_string().contains("an integer value"), "{e}");
        assert_eq!(e.location().and_then(|l| l.line), Some(line), "{e}");
    }
    let nan = read_from(body("0", "nan", "5").as_bytes(), Format::Ply, &ReadOptions::default()).unwrap();
    assert!(nan.scalar("k").unwrap()[1].is_nan(), "the file's own value is kept");
    let note = nan.report.notes.join("; ");
    assert!(note.contains("vertex scalar `k`: 1 values are not finite (first of vertex 1)"), "{note}");
}

#[test]
fn ply_refuses_names_it_cannot_write() {
    let mesh = tetra();
    let (v, x, l) = ([DVec3::X; 4], [0.0; 4], [0i64; 4]);
    let refused = [
        MeshView::new(&mesh).with_vector("n", &v),
        MeshView::new(&mesh).with_vector("d1", &v).with_scalar("d1y", &x),
        MeshView::new(&mesh).with_scalar("two words", &x),
        MeshView::new(&mesh).with_face_scalar("vertex_indices", &x),
        MeshView::new(&mesh).with_scalar("red", &x),
    ];
    for view in refused {
        let e = write_to(Vec::new(), Format::Ply, view, &WriteOptions::default()).unwrap_err();
        assert!(matches!(e, IoError::Unsupported { .. }), "{e}");
    }
    let huge = [0, -1, 1 << 32, 0];
    let e = write_to(Vec::new(), Format::Ply, MeshView::new(&mesh).with_label("id", &huge), &WriteOptions::default())
        .unwrap_err();
    assert!(e.to_string().contains("beyond the 32-bit integers"), "{e}");
    let short = [0i64; 3];
    let e =
        write_to(Vec::new(), Format::Ply, MeshView::new(&mesh).with_face_label("c", &short), &WriteOptions::default())
            .unwrap_err();
    assert!(matches!(e, IoError::AttributeLength { expected: 4, found: 3, .. }), "{e}");
    let e = write_to(
        Vec::new(),
        Format::Glb,
        MeshView::new(&mesh).with_label("k", &l).with_scalar("k", &x),
        &WriteOptions::default(),
    )
    .unwrap_err();
    assert!(matches!(e, IoError::AttributeName { .. }), "{e}");
}

#[test]
fn gltf_keeps_vertex_vectors_and_labels_and_reports_face_values() {
    let mesh = tetra();
    let d1 = [DVec3::X, DVec3::new(0.5, 0.25, -2.0), DVec3::Z, DVec3::NEG_Y];
    let (small, signed, wide) = ([0i64, 1, 65535, 3], [-32768i64, 0, 32767, -1], [-1i64, 70000, 1 << 24, 0]);
    let (face, chart) = ([1.0; 4], [0i64; 4]);
    let view = MeshView::new(&mesh)
        .with_vector("d1", &d1)
        .with_label("component", &small)
        .with_label("signed", &signed)
        .with_label("wide", &wide)
        .with_face_scalar("distortion", &face)
        .with_face_label("chart", &chart);
    for format in [Format::Glb, Format::Gltf] {
        let (back, report) = through(view.clone(), format, &WriteOptions::default());
        assert_eq!(back.vector("d1"), Some(&d1[..]), "{format}: values exact in f32");
        assert_eq!(back.label("component"), Some(&small[..]), "{format}: unsigned shorts");
        assert_eq!(back.label("signed"), Some(&signed[..]), "{format}: signed shorts");
        let wide_back: Vec<i64> = back.scalar("wide").unwrap().iter().map(|&x| x as i64).collect();
        assert_eq!(wide_back, wide, "{format}: wider labels as exact floats");
        assert_eq!(report.dropped, ["face scalar `distortion`", "face label `chart`"], "{format}");
        assert!(!report.is_clean() && report.to_string().contains("face label `chart`"), "{report}");
        assert!(back.report.is_clean(), "{}", back.report);
    }
    let beyond = [0, (1 << 24) + 1, 0, 0];
    let e = write_to(Vec::new(), Format::Glb, MeshView::new(&mesh).with_label("id", &beyond), &WriteOptions::default())
        .unwrap_err();
    assert!(matches!(e, IoError::Precision { .. }) && e.to_string().contains("label `id` of vertex 1"), "{e}");
    let allowed = WriteOptions { allow_precision_loss: true, ..WriteOptions::default() };
    let r = write_to(Vec::new(), Format::Glb, MeshView::new(&mesh).with_label("id", &beyond), &allowed).unwrap();
    assert_eq!(r.values_lost, 1);
}

#[test]
fn gltf_attributes_of_other_shapes_are_skipped_with_a_note() {
    let mesh = tetra();
    let d1 = [DVec3::X; 4];
    let mut text = Vec::new();
    write_to(&mut text, Format::Gltf, MeshView::new(&mesh).with_vector("d1", &d1), &WriteOptions::default()).unwrap();
    let text = String::from_utf8(text).unwrap();
    // Accessor 0 is POSITION, accessor 1 the vector: make it a VEC2.
    let second = text.match_indices(r#""type":"VEC3""#).nth(1).unwrap().0;
    let edited = format!("{}\"type\":\"VEC2\"{}", &text[..second], &text[second + 13..]);
    let d = read_from(edited.as_bytes(), Format::Gltf, &ReadOptions::default()).unwrap();
    assert_eq!(d.mesh, mesh);
    assert!(d.vectors.is_empty());
    assert!(d.report.notes.iter().any(|n| n.contains("`_d1` skipped")), "{:?}", d.report.notes);
}

#[test]
fn obj_off_and_stl_report_what_they_leave_out() {
    let d = common::grid(4);
    // The grid has 7 named attributes (2 vertex scalars, a vector, a label, 3 face ones).
    for (format, count, expected) in [
        (Format::Obj, 7, vec!["vertex scalar `gaussian`", "vertex vector `d1`", "face label `chart`"]),
        (Format::Off, 7, vec!["vertex label `segment`", "face scalar `distortion`"]),
        (Format::Stl, 10, vec!["normals", "texture coordinates", "colours", "face vector `gradient`"]),
    ] {
        let report = write_to(Vec::new(), format, &d, &WriteOptions::default()).unwrap();
        assert_eq!(report.dropped.len(), count, "{format}: {:?}", report.dropped);
        for what in expected {
            assert!(report.dropped.iter().any(|x| x == what), "{format}: {what} not in {:?}", report.dropped);
        }
        assert!(!report.is_clean());
    }
    let plain = write_to(Vec::new(), Format::Obj, &d.mesh, &WriteOptions::default()).unwrap();
    assert!(plain.dropped.is_empty() && plain.is_clean());
}

#[test]
fn hostile_face_counts_and_lists_are_refused_before_allocating() {
    let head = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
property float z\nelement face 4000000000\nproperty list uchar int vertex_indices\nproperty double quality\nend_header\n";
    let mut bytes = head.as_bytes().to_vec();
    bytes.extend_from_slice(&[0u8; 36]);
    let e = read_from(&bytes, Format::Ply, &ReadOptions::default()).unwrap_err();
    assert!(matches!(e, IoError::Count { .. }), "{e}");
    let list = head.replace("4000000000", "1").replace("list uchar int", "list uint int");
    let mut bytes = list.into_bytes();
    bytes.extend_from_slice(&[0u8; 36]);
    bytes.extend_from_slice(&u32::MAX.to_le_bytes());
    bytes.extend_from_slice(&[0u8; 16]);
    let e = read_from(&bytes, Format::Ply, &ReadOptions::default()).unwrap_err();
    assert!(matches!(e, IoError::Truncated { .. }), "a 4-billion-long list in 16 bytes: {e}");
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, failure_persistence: None, ..ProptestConfig::default() })]

    /// Any finite `f64` and any 32-bit label come back bit for bit, in every PLY encoding.
    #[test]
    fn ply_round_trip_is_bit_exact(
        seed in proptest::collection::vec((any::<u64>(), any::<i32>(), any::<u32>()), 4),
        encoding in 0..3usize,
    ) {
        let mesh = tetra();
        let finite = |b: u64| { let x = f64::from_bits(b); if x.is_finite() { x } else { b as f64 } };
        let scalar: Vec<f64> = seed.iter().map(|s| finite(s.0)).collect();
        let vector: Vec<DVec3> = seed.iter().map(|s| DVec3::new(finite(s.0.rotate_left(7)), finite(!s.0), -finite(s.0))).collect();
        let signed: Vec<i64> = seed.iter().map(|s| i64::from(s.1)).collect();
        let unsigned: Vec<i64> = seed.iter().map(|s| i64::from(s.2)).collect();
        let view = MeshView::new(&mesh)
            .with_scalar("k", &scalar)
            .with_face_vector("g", &vector)
            .with_label("sign", &signed)
            .with_face_label("u", &unsigned);
        let (back, _) = through(view, Format::Ply, &ply(ENCODINGS[encoding]));
        prop_assert_eq!(back.scalar("k").unwrap().iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
            scalar.iter().map(|x| x.to_bits()).collect::<Vec<_>>());
        prop_assert_eq!(bits(back.face_vector("g").unwrap()), bits(&vector));
        prop_assert_eq!(back.label("sign"), Some(&signed[..]));
        prop_assert_eq!(back.face_label("u"), Some(&unsigned[..]));
    }
}
