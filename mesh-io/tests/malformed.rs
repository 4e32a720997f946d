//! Malformed input gives typed errors naming the file and line; no input
//! makes a reader panic (proptest over random bytes, truncations and
//! mutations of valid files of every format and encoding).

mod common;

use std::sync::OnceLock;

use mesh_io::{
    read, read_from, write_to, Format, IoError, PlyEncoding, PlyOptions, ReadOptions, StlEncoding, WriteOptions,
};
use proptest::prelude::*;

/// Reads `bytes` as `format` from a file named `name`.
fn read_file(name: &str, bytes: &[u8]) -> mesh_io::error::Result<mesh_io::MeshData> {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(name);
    std::fs::write(&path, bytes).unwrap();
    read(&path)
}

fn from(format: Format, bytes: &[u8]) -> IoError {
    match read_from(bytes, format, &ReadOptions::default()) {
        Ok(d) => panic!("malformed {format} accepted: {:?} {:?}", d.mesh, d.report),
        Err(e) => e,
    }
}

#[test]
fn wrong_magic_names_the_file() {
    let e = read_file("mesh.ply", b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n").unwrap_err();
    assert!(matches!(e, IoError::WrongMagic { .. }), "{e}");
    let at = e.location().unwrap();
    assert!(at.path.as_ref().unwrap().ends_with("mesh.ply"));
    assert!(e.to_string().contains("mesh.ply"), "{e}");
    assert!(matches!(
        read_file("m.glb", b"{\"asset\":{\"version\":\"2.0\"}}").unwrap_err(),
        IoError::WrongMagic { .. }
    ));
    assert!(matches!(read_file("m.off", b"ply\nformat ascii 1.0\n").unwrap_err(), IoError::WrongMagic { .. }));
    assert!(matches!(read_file("m.xyz", b"").unwrap_err(), IoError::UnknownFormat { .. }));
    assert!(matches!(read("/nonexistent/m.obj").unwrap_err(), IoError::Io { .. }));
}

#[test]
fn errors_name_the_line() {
    let e = read_file("bad.obj", b"# x\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n").unwrap_err();
    assert!(e.to_string().ends_with("face 0 refers to vertex 7, but there are only 3"), "{e}");
    assert!(e.to_string().starts_with("OBJ file ") && e.to_string().contains("bad.obj line 5"), "{e}");
}

#[test]
fn bad_indices() {
    let off = b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 -1\n";
    assert!(matches!(from(Format::Off, off), IoError::Index { index: -1, .. }));
    let ply = b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n\
element face 1\nproperty list uchar uint vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n";
    assert!(matches!(from(Format::Ply, ply), IoError::Index { index: 3, .. }));
    let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n";
    assert!(matches!(from(Format::Obj, obj), IoError::Index { index: -4, .. }));
    let mut glb = valid(Format::Glb, 0).clone();
    // The last index of the index accessor (the last bytes of BIN) points past the vertices.
    let n = glb.len();
    glb[n - 4..].copy_from_slice(&1000u32.to_le_bytes());
    assert!(matches!(from(Format::Glb, &glb), IoError::Index { index: 1000, .. }));
}

#[test]
fn nan_coordinates() {
    assert!(matches!(from(Format::Off, b"OFF\n1 0 0\nnan 0 0\n"), IoError::NonFinite { vertex: 0, .. }));
    assert!(matches!(from(Format::Obj, b"v 0 0 0\nv 0 -inf 0\n"), IoError::NonFinite { vertex: 1, .. }));
    let mut stl = valid(Format::Stl, 1).clone();
    stl[84 + 12..84 + 16].copy_from_slice(&f32::NAN.to_le_bytes());
    assert!(matches!(from(Format::Stl, &stl), IoError::NonFinite { vertex: 0, .. }));
    let mut ply = valid(Format::Ply, 1).clone();
    let body = ply.windows(11).position(|w| w == b"end_header\n").unwrap() + 11;
    ply[body..body + 8].copy_from_slice(&f64::NAN.to_le_bytes());
    assert!(matches!(from(Format::Ply, &ply), IoError::NonFinite { vertex: 0, .. }));
    let mut glb = valid(Format::Glb, 0).clone();
    let json_len = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
    let bin = 20 + json_len + 8;
    glb[bin..bin + 4].copy_from_slice(&f32::INFINITY.to_le_bytes());
    assert!(matches!(from(Format::Glb, &glb), IoError::NonFinite { vertex: 0, .. }));
}

#[test]
fn negative_and_huge_counts_do_not_allocate() {
    let count = |format, bytes: &[u8]| matches!(from(format, bytes), IoError::Count { .. });
    assert!(count(Format::Off, b"OFF\n-3 1 0\n"));
    assert!(count(Format::Off, b"OFF\n3 -1 0\n0 0 0\n1 0 0\n0 1 0\n"));
    assert!(count(Format::Off, b"OFF\n4000000000 4000000000 0\n"));
    assert!(count(Format::Off, b"OFF\n100000000 0 0\n0 0 0\n"));
    for format in ["ascii", "binary_little_endian", "binary_big_endian"] {
        let ply = format!(
            "ply\nformat {format} 1.0\nelement vertex 4000000000\nproperty double x\nproperty double y\n\
             property double z\nend_header\n"
        );
        assert!(count(Format::Ply, ply.as_bytes()), "{format}");
        let ply = ply.replace("4000000000", "-2");
        assert!(count(Format::Ply, ply.as_bytes()), "{format}");
        let ply = ply.replace("-2", "300000000");
        assert!(count(Format::Ply, ply.as_bytes()), "{format}");
    }
    let mut stl = vec![0u8; 84 + 50];
    stl[80..84].copy_from_slice(&u32::MAX.to_le_bytes());
    assert!(matches!(from(Format::Stl, &stl), IoError::Truncated { .. }));
    let gltf = String::from_utf8(valid(Format::Gltf, 0).clone()).unwrap();
    let at = gltf.find("\"count\":").unwrap() + 8;
    let digits = gltf[at..].find(|c: char| !c.is_ascii_digit()).unwrap();
    let huge = format!("{}4000000000{}", &gltf[..at], &gltf[at + digits..]);
    assert!(matches!(from(Format::Gltf, huge.as_bytes()), IoError::Truncated { .. }));
}

#[test]
fn truncated_files() {
    // OBJ has no counts or terminator: a file cut at a line end is a smaller
    // valid file. A text file cut inside its last number cannot be told from
    // a shorter number, so only binary files are cut 3 bytes short.
    for (format, variant) in CASES.iter().filter(|(f, _)| *f != Format::Obj) {
        let bytes = valid(*format, *variant);
        let binary = matches!((format, variant), (Format::Ply, 1 | 2) | (Format::Stl, 1) | (Format::Glb, _));
        let last = if binary { bytes.len() - 3 } else { bytes.len() * 9 / 10 };
        for cut in [bytes.len() / 3, bytes.len() / 2, last] {
            let result = read_from(&bytes[..cut], *format, &ReadOptions::default());
            let e = result.err().unwrap_or_else(|| panic!("{format}/{variant} cut at {cut} was accepted"));
            assert!(
                matches!(
                    e,
                    IoError::Truncated { .. } | IoError::Count { .. } | IoError::Gltf { .. } | IoError::Syntax { .. }
                ),
                "{format}/{variant} cut at {cut}: {e}"
            );
        }
    }
}

#[test]
fn gltf_structure_errors() {
    let text = String::from_utf8(valid(Format::Gltf, 0).clone()).unwrap();
    let cycle = text.replacen("\"mesh\":0", "\"mesh\":0,\"children\":[0]", 1);
    assert!(read_from(cycle.as_bytes(), Format::Gltf, &ReadOptions::default()).is_err());
    let external = text.replacen("data:application/octet-stream;base64,", "missing.bin#", 1);
    assert!(matches!(from(Format::Gltf, external.as_bytes()), IoError::ExternalBuffer { .. }));
    let bad64 = text.replacen(";base64,", ";base64,*", 1);
    assert!(matches!(from(Format::Gltf, bad64.as_bytes()), IoError::Syntax { .. }));
    assert!(matches!(from(Format::Gltf, b"{\"asset\":{}}"), IoError::Gltf { .. }));
}

/// Every format and encoding: (format, variant).
const CASES: [(Format, usize); 9] = [
    (Format::Obj, 0),
    (Format::Off, 0),
    (Format::Ply, 0),
    (Format::Ply, 1),
    (Format::Ply, 2),
    (Format::Stl, 0),
    (Format::Stl, 1),
    (Format::Gltf, 0),
    (Format::Glb, 0),
];

/// A valid file: PLY variants ascii / little / big endian, STL ascii / binary.
fn valid(format: Format, variant: usize) -> &'static Vec<u8> {
    // One file per entry of CASES.
    static FILES: OnceLock<Vec<Vec<u8>>> = OnceLock::new();
    let files = FILES.get_or_init(|| {
        let mut data = common::grid(4);
        data.corner_uvs = Some(common::corner_uvs(&data));
        CASES
            .iter()
            .map(|&(format, variant)| {
                let encoding = [PlyEncoding::Ascii, PlyEncoding::BinaryLittleEndian, PlyEncoding::BinaryBigEndian];
                let stl = [StlEncoding::Ascii, StlEncoding::Binary];
                let options = WriteOptions {
                    ply: PlyOptions { encoding: encoding[variant.min(2)], double: true, ..Default::default() },
                    stl: stl[variant.min(1)],
                    ..Default::default()
                };
                let mut out = Vec::new();
                write_to(&mut out, format, &data, &options).unwrap();
                out
            })
            .collect()
    });
    &files[CASES.iter().position(|&c| c == (format, variant)).unwrap()]
}

fn case() -> impl Strategy<Value = (Format, usize)> {
    (0..CASES.len()).prop_map(|i| CASES[i])
}

proptest! {
    // 512 cases each by default; PROPTEST_CASES=100000 for a longer hunt.
    #![proptest_config(ProptestConfig {
        cases: std::env::var("PROPTEST_CASES").ok().and_then(|c| c.parse().ok()).unwrap_or(512),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    #[test]
    fn random_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..600), format in 0..6usize) {
        let _ = read_from(&bytes, Format::ALL[format], &ReadOptions::default());
    }

    #[test]
    fn random_bytes_after_a_valid_start_never_panic(
        (format, variant) in case(),
        keep in 0.0..1.0f64,
        tail in proptest::collection::vec(any::<u8>(), 0..300),
    ) {
        let bytes = valid(format, variant);
        let mut input = bytes[..(keep * bytes.len() as f64) as usize].to_vec();
        input.extend_from_slice(&tail);
        let _ = read_from(&input, format, &ReadOptions::default());
    }

    #[test]
    fn truncations_never_panic((format, variant) in case(), keep in 0.0..1.0f64) {
        let bytes = valid(format, variant);
        let _ = read_from(&bytes[..(keep * bytes.len() as f64) as usize], format, &ReadOptions::default());
    }

    #[test]
    fn mutations_never_panic(
        (format, variant) in case(),
        edits in proptest::collection::vec((0.0..1.0f64, any::<u8>()), 1..8),
    ) {
        let mut bytes = valid(format, variant).clone();
        for (at, value) in edits {
            let i = ((at * bytes.len() as f64) as usize).min(bytes.len() - 1);
            bytes[i] = value;
        }
        let _ = read_from(&bytes, format, &ReadOptions::default());
    }

    #[test]
    fn digit_mutations_of_text_never_panic(
        (format, variant) in case(),
        edits in proptest::collection::vec((0.0..1.0f64, prop::sample::select(b"0123456789-.e \n/#".to_vec())), 1..6),
    ) {
        let mut bytes = valid(format, variant).clone();
        for (at, value) in edits {
            let i = ((at * bytes.len() as f64) as usize).min(bytes.len() - 1);
            bytes[i] = value;
        }
        let _ = read_from(&bytes, format, &ReadOptions::default());
    }
}
