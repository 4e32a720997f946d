//! The valid files the fuzzer mutates: small meshes built from mesh-kernel's
//! shapes, written by mesh-io's own writers in every format and variant
//! (PLY ascii / binary little / binary big endian, float and double, with
//! normals, texture coordinates, colours, a scalar, a vector, a label and
//! per-face values; STL ascii and binary;
//! glTF with a `data:` URI buffer; GLB), a few hand-written files with the
//! features the writers never produce (polygons, negative OBJ indices,
//! comments, extra PLY elements), and the shared test meshes under 20 KB.

use mesh_io::{Format, MeshView, PlyEncoding, PlyOptions, StlEncoding, WriteOptions};
use mesh_kernel::glam::{DVec2, DVec3};
use mesh_kernel::{geometry, shapes, TriMesh};

use crate::validate::shared_data;

/// One seed file.
pub struct Seed {
    /// What it is, for messages.
    pub name: String,
    /// The file's bytes.
    pub bytes: Vec<u8>,
}

/// The small shapes every format gets.
fn shapes() -> Vec<(&'static str, TriMesh)> {
    let mut out = Vec::new();
    let tetra =
        TriMesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z], vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]]);
    for (name, mesh) in [
        ("tetrahedron", tetra),
        ("icosphere(1)", shapes::icosphere(1)),
        ("grid 3x2", shapes::grid(1.0, 1.0, 3, 2)),
        ("torus 6x4", shapes::torus(2.0, 0.5, 6, 4)),
    ] {
        if let Ok(m) = mesh {
            out.push((name, m));
        }
    }
    out
}

/// Attributes of a mesh: per-vertex normals, uvs, colours, a scalar, a
/// vector and a label; per-face a scalar and a label.
struct Attributes {
    normals: Vec<DVec3>,
    uvs: Vec<DVec2>,
    colors: Vec<[f32; 4]>,
    scalar: Vec<f64>,
    label: Vec<i64>,
    face_scalar: Vec<f64>,
    face_label: Vec<i64>,
}

impl Attributes {
    fn of(mesh: &TriMesh) -> Self {
        let p = mesh.positions();
        Self {
            normals: geometry::vertex_normals(mesh, geometry::NormalWeighting::Area),
            uvs: p.iter().map(|q| DVec2::new(q.x, q.y)).collect(),
            colors: p.iter().map(|q| [0.5 + 0.25 * q.x.clamp(-1.0, 1.0) as f32, 0.5, 0.25, 1.0]).collect(),
            scalar: p.iter().map(|q| q.z * 3.0 + 0.125).collect(),
            label: (0..p.len()).map(|i| i as i64 % 5 - 2).collect(),
            face_scalar: (0..mesh.face_count()).map(|f| f as f64 * 0.5 + 1.0).collect(),
            face_label: (0..mesh.face_count()).map(|f| (f / 2) as i64).collect(),
        }
    }

    fn view<'a>(&'a self, mesh: &'a TriMesh) -> MeshView<'a> {
        MeshView::new(mesh)
            .with_normals(&self.normals)
            .with_uvs(&self.uvs)
            .with_colors(&self.colors)
            .with_scalar("quality", &self.scalar)
            .with_vector("direction", &self.normals)
            .with_label("segment", &self.label)
            .with_face_scalar("distortion", &self.face_scalar)
            .with_face_label("chart", &self.face_label)
    }
}

/// Every writer variant of a format: a name and its options.
fn variants(format: Format) -> Vec<(&'static str, WriteOptions)> {
    let base = WriteOptions { format: Some(format), ..WriteOptions::default() };
    match format {
        Format::Ply => [
            ("ascii", PlyEncoding::Ascii, true),
            ("binary little", PlyEncoding::BinaryLittleEndian, true),
            ("binary big", PlyEncoding::BinaryBigEndian, true),
            ("binary little float", PlyEncoding::BinaryLittleEndian, false),
            ("binary big float", PlyEncoding::BinaryBigEndian, false),
        ]
        .into_iter()
        .map(|(n, encoding, double)| (n, WriteOptions { ply: PlyOptions { encoding, double, ..base.ply }, ..base }))
        .collect(),
        Format::Stl => vec![
            ("ascii", WriteOptions { stl: StlEncoding::Ascii, ..base }),
            ("binary", WriteOptions { stl: StlEncoding::Binary, ..base }),
        ],
        _ => vec![("", base)],
    }
}

/// Files written by hand, with what the writers never produce.
fn handwritten(format: Format) -> Vec<(&'static str, &'static str)> {
    match format {
        Format::Obj => vec![(
            "quads, negative indices, v/vt/vn",
            "# cube corner\no thing\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nvt 0 0\nvt 1 0\nvt 1 1\n\
             vn 0 0 1\ng side\nusemtl red\nf 1/1/1 2/2/1 3/3/1 4/1/1\nf -1 -2 -5\nf 1//1 5//1 2//1\ns off\n\
             l 1 2\n",
        )],
        Format::Off => vec![
            ("quads and a pentagon", "OFF\n# comment\n6 3 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n2 0 0\n2 1 0\n4 0 1 2 3\n3 1 4 5\n5 0 1 4 5 2\n"),
            ("COFF with colours", "COFF\n4 2 5\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n1 1 0 0 0 255 255\n0 1 0 9 9 9 255\n3 0 1 2\n3 0 2 3\n"),
        ],
        Format::Ply => vec![(
            "ascii, uchar/int lists, extra element",
            "ply\nformat ascii 1.0\ncomment hand written\nelement vertex 4\nproperty float x\nproperty float y\n\
             property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nelement face 2\n\
             property list uchar int vertex_indices\nelement edge 1\nproperty int vertex1\nproperty int vertex2\n\
             end_header\n0 0 0 255 0 0\n1 0 0 0 255 0\n1 1 0 0 0 255\n0 1 0 1 2 3\n4 0 1 2 3\n3 0 2 3\n0 1\n",
        ), (
            "ascii, a NAME_x vector, a label, face properties around the list",
            "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n\
             property float d_x\nproperty float d_y\nproperty float d_z\nproperty short segment\nelement face 2\n\
             property uchar flags\nproperty list uchar int vertex_indices\nproperty float quality\nend_header\n\
             0 0 0 1 0 0 -1\n1 0 0 0 1 0 2\n1 1 0 0 0 1 3\n0 1 0 1 1 1 4\n7 4 0 1 2 3 0.5\n1 3 0 2 3 0.25\n",
        )],
        Format::Stl => vec![(
            "ascii with a name",
            "solid named part\nfacet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  vertex 0 1 0\n \
             endloop\nendfacet\nfacet normal 0 0 1\nouter loop\nvertex 1 0 0\nvertex 1 1 0\nvertex 0 1 0\nendloop\n\
             endfacet\nendsolid named part\n",
        )],
        Format::Gltf | Format::Glb => vec![],
    }
}

/// Every seed of a format. The writers' own errors are returned: a seed that
/// cannot be written is a finding in itself.
pub fn seeds(format: Format) -> Result<Vec<Seed>, String> {
    let mut out = Vec::new();
    for (shape, mesh) in shapes() {
        let attributes = Attributes::of(&mesh);
        for (variant, options) in variants(format) {
            for (with, view) in [("", MeshView::new(&mesh)), (" + attributes", attributes.view(&mesh))] {
                let mut bytes = Vec::new();
                mesh_io::write_to(&mut bytes, format, view, &options)
                    .map_err(|e| format!("writing seed {shape} {variant}{with}: {e}"))?;
                out.push(Seed { name: format!("{shape} {variant}{with}"), bytes });
            }
        }
    }
    for (name, text) in handwritten(format) {
        out.push(Seed { name: name.to_owned(), bytes: text.as_bytes().to_vec() });
    }
    if let Some(dir) = shared_data() {
        let mut files: Vec<_> =
            std::fs::read_dir(&dir).map(|r| r.filter_map(|e| e.ok()).map(|e| e.path()).collect()).unwrap_or_default();
        files.sort();
        for path in files {
            let small = std::fs::metadata(&path).is_ok_and(|m| m.len() <= 20_000);
            if small && Format::from_path(&path).is_ok_and(|f| f == format) {
                if let Ok(bytes) = std::fs::read(&path) {
                    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
                    out.push(Seed { name, bytes });
                }
            }
        }
    }
    Ok(out)
}
