//! Negative, huge and off-by-one counts and indices as files through
//! mesh-io: every one must be refused with an `IoError`, quickly, without a
//! panic and without allocating what the count claims.

use std::time::Instant;

use mesh_io::{Format, ReadOptions, WriteOptions};
use mesh_kernel::shapes;

use crate::fuzz::{alloc, panics};
use crate::validate::Validator;

/// Largest time and peak allocation for one of these files.
const MAX_SECONDS: f64 = 1.0;
const MAX_MB: f64 = 256.0;

fn text(s: &str) -> Vec<u8> {
    s.as_bytes().to_vec()
}

/// A file written by mesh-io with its first `"key":number` set to `value`.
fn json_number(format: Format, key: &str, value: &str) -> Vec<u8> {
    let mut bytes = Vec::new();
    if let Ok(m) = shapes::icosphere(0) {
        let _ = mesh_io::write_to(&mut bytes, format, &m, &WriteOptions::default());
    }
    let pattern = format!("\"{key}\":");
    let Some(at) = bytes.windows(pattern.len()).position(|w| w == pattern.as_bytes()) else { return bytes };
    let start = at + pattern.len();
    let end = start + bytes[start..].iter().take_while(|b| b.is_ascii_digit()).count();
    let mut out = bytes[..start].to_vec();
    out.extend_from_slice(value.as_bytes());
    out.extend_from_slice(&bytes[end..]);
    if format == Format::Glb && out.len() != bytes.len() {
        // Keep the container's lengths consistent with the edited JSON.
        let delta = out.len() as i64 - bytes.len() as i64;
        for range in [8..12, 12..16] {
            let old = u32::from_le_bytes(out[range.clone()].try_into().unwrap_or([0; 4]));
            out[range].copy_from_slice(&((old as i64 + delta) as u32).to_le_bytes());
        }
    }
    out
}

/// A GLB written by mesh-io with the u32 at `offset` set to `value`.
fn glb_field(offset: usize, value: u32) -> Vec<u8> {
    let mut bytes = Vec::new();
    if let Ok(m) = shapes::icosphere(0) {
        let _ = mesh_io::write_to(&mut bytes, Format::Glb, &m, &WriteOptions::default());
    }
    if bytes.len() >= offset + 4 {
        bytes[offset..offset + 4].copy_from_slice(&value.to_le_bytes());
    }
    bytes
}

fn stl_count(count: u32) -> Vec<u8> {
    let mut bytes = vec![0u8; 80];
    bytes.extend_from_slice(&count.to_le_bytes());
    bytes.extend_from_slice(&[0u8; 50]);
    bytes
}

fn ply_binary(header_counts: &str, body: &[u8]) -> Vec<u8> {
    let mut bytes = text(&format!(
        "ply\nformat binary_little_endian 1.0\n{header_counts}property list uchar int vertex_indices\nend_header\n"
    ));
    bytes.extend_from_slice(body);
    bytes
}

const TRIANGLE: &str = "0 0 0\n1 0 0\n0 1 0\n";

/// Every bad file: a name, its format and its bytes.
fn files() -> Vec<(&'static str, Format, Vec<u8>)> {
    let vertex = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
    let floats: Vec<u8> = [0f32, 0., 0., 1., 0., 0., 0., 1., 0.].iter().flat_map(|x| x.to_le_bytes()).collect();
    vec![
        ("OFF, vertex count -3", Format::Off, text(&format!("OFF\n-3 1 0\n{TRIANGLE}3 0 1 2\n"))),
        ("OFF, vertex count 2^32 - 1", Format::Off, text(&format!("OFF\n4294967295 1 0\n{TRIANGLE}3 0 1 2\n"))),
        ("OFF, face count 1e11", Format::Off, text(&format!("OFF\n3 99999999999 0\n{TRIANGLE}3 0 1 2\n"))),
        ("OFF, vertex count one too many", Format::Off, text(&format!("OFF\n4 1 0\n{TRIANGLE}3 0 1 2\n"))),
        ("OFF, face with 2^32 - 1 corners", Format::Off, text(&format!("OFF\n3 1 0\n{TRIANGLE}4294967295 0 1 2\n"))),
        ("OFF, index -1", Format::Off, text(&format!("OFF\n3 1 0\n{TRIANGLE}3 0 -1 2\n"))),
        ("OFF, index 3 of 3 vertices", Format::Off, text(&format!("OFF\n3 1 0\n{TRIANGLE}3 0 1 3\n"))),
        ("OBJ, index 1e11", Format::Obj, text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999\n")),
        ("OBJ, index -9 of 3 vertices", Format::Obj, text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -9\n")),
        ("OBJ, index 0", Format::Obj, text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n")),
        ("OBJ, index 4 of 3 vertices", Format::Obj, text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n")),
        (
            "PLY ascii, vertex count -1",
            Format::Ply,
            text(&format!(
                "ply\nformat ascii 1.0\nelement vertex -1\nproperty float x\nproperty float y\nproperty float z\n\
                 element face 1\nproperty list uchar int vertex_indices\nend_header\n{TRIANGLE}3 0 1 2\n"
            )),
        ),
        (
            "PLY binary, vertex count 2^32 - 1",
            Format::Ply,
            ply_binary(
                "element vertex 4294967295\nproperty float x\nproperty float y\nproperty float z\nelement face 1\n",
                &floats,
            ),
        ),
        (
            "PLY binary, face count 2^31",
            Format::Ply,
            ply_binary(&format!("{vertex}element face 2147483648\n"), &[floats.clone(), vec![3, 0, 0, 0, 0]].concat()),
        ),
        (
            "PLY binary, a face of 255 corners in a short body",
            Format::Ply,
            ply_binary(&format!("{vertex}element face 1\n"), &[floats.clone(), vec![255, 0, 0, 0, 0]].concat()),
        ),
        (
            "PLY binary, index 2^31",
            Format::Ply,
            ply_binary(
                &format!("{vertex}element face 1\n"),
                &[
                    floats,
                    vec![3],
                    0u32.to_le_bytes().to_vec(),
                    1u32.to_le_bytes().to_vec(),
                    (1u32 << 31).to_le_bytes().to_vec(),
                ]
                .concat(),
            ),
        ),
        ("STL binary, 2^32 - 1 triangles claimed, 1 present", Format::Stl, stl_count(u32::MAX)),
        ("glTF, accessor count 2^32 - 1", Format::Gltf, json_number(Format::Gltf, "count", "4294967295")),
        ("glTF, accessor count -1", Format::Gltf, json_number(Format::Gltf, "count", "-1")),
        ("glTF, byteLength 2^32 - 1", Format::Gltf, json_number(Format::Gltf, "byteLength", "4294967295")),
        ("glTF, byteLength 1", Format::Gltf, json_number(Format::Gltf, "byteLength", "1")),
        ("GLB, accessor count 2^32 - 1", Format::Glb, json_number(Format::Glb, "count", "4294967295")),
        ("GLB, total length 2^32 - 1", Format::Glb, glb_field(8, u32::MAX)),
        ("GLB, JSON chunk length 2^32 - 1", Format::Glb, glb_field(12, u32::MAX)),
    ]
}

/// Each bad file refused with a typed error, fast, without a panic or a
/// large allocation.
pub fn run(v: &mut Validator) {
    for (name, format, bytes) in files() {
        alloc::reset_peak();
        let base = alloc::current();
        let start = Instant::now();
        let result = alloc::limited(|| {
            panics::quietly(|| panics::catch(|| mesh_io::read_from(&bytes, format, &ReadOptions::default())))
        });
        let seconds = start.elapsed().as_secs_f64();
        let mb = alloc::peak().saturating_sub(base) as f64 / (1 << 20) as f64;
        let (ok, note) = match result {
            Err(panic) => (false, format!("panic: {panic}")),
            Ok(Ok(d)) => (
                false,
                format!("accepted: {} vertices, {} faces ({})", d.mesh.vertex_count(), d.mesh.face_count(), d.report),
            ),
            Ok(Err(e)) => (seconds <= MAX_SECONDS && mb <= MAX_MB, format!("{e}; {:.1} ms, {mb:.2} MB", seconds * 1e3)),
        };
        v.holds(format!("file: {name}: refused with an IoError"), ok, note);
    }
}
