//! glTF external buffers: only relative paths to regular files inside the
//! `.gltf` file's folder, read up to `byteLength` bytes and checked against
//! the file's size first. Devices, pipes, absolute paths, `..` escapes and
//! symbolic links out of the folder are refused before anything is read.

use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::Duration;

use mesh_io::{read, read_from, Format, IoError, ReadOptions};

/// One triangle: 3 float positions (36 bytes), buffer `uri` of `byte_length`,
/// view of `view_length` bytes.
fn gltf_json(uri: &str, byte_length: usize, view_length: usize) -> String {
    format!(
        r#"{{"asset":{{"version":"2.0"}},
"buffers":[{{"uri":"{uri}","byteLength":{byte_length}}}],
"bufferViews":[{{"buffer":0,"byteLength":{view_length}}}],
"accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}}}}]}}]}}"#
    )
}

fn triangle_bytes() -> Vec<u8> {
    [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0].iter().flat_map(|x| x.to_le_bytes()).collect()
}

/// A folder `mesh/` inside a temporary folder, with `tri.bin` (36 bytes)
/// inside and `outside.bin` next to the folder.
struct Scene {
    _root: tempfile::TempDir,
    dir: PathBuf,
    outside: PathBuf,
}

fn scene() -> Scene {
    let root = tempfile::tempdir().unwrap();
    let dir = root.path().join("mesh");
    std::fs::create_dir(&dir).unwrap();
    std::fs::create_dir(dir.join("sub")).unwrap();
    std::fs::write(dir.join("tri.bin"), triangle_bytes()).unwrap();
    let outside = root.path().join("outside.bin");
    std::fs::write(&outside, triangle_bytes()).unwrap();
    Scene { _root: root, dir, outside }
}

/// Reads `json` as `dir/m.gltf` on another thread; fails the test instead of
/// hanging when the reader blocks.
fn read_gltf(dir: &Path, json: String) -> mesh_io::error::Result<mesh_io::MeshData> {
    let path = dir.join("m.gltf");
    std::fs::write(&path, json).unwrap();
    let (send, receive) = mpsc::channel();
    std::thread::spawn(move || {
        let _ = send.send(read(&path));
    });
    receive.recv_timeout(Duration::from_secs(20)).expect("the reader blocked or read a device")
}

/// The error for `uri`, which must be an [`IoError::ExternalBuffer`] naming
/// the glTF file and the URI.
fn refused(dir: &Path, uri: &str, byte_length: usize) -> String {
    match read_gltf(dir, gltf_json(uri, byte_length, 36)) {
        Ok(_) => panic!("buffer uri {uri} accepted"),
        Err(e @ IoError::ExternalBuffer { .. }) => {
            let text = e.to_string();
            assert!(text.contains("m.gltf") && text.contains(uri), "{text}");
            text
        }
        Err(e) => panic!("buffer uri {uri}: wrong error {e:?}"),
    }
}

#[test]
fn a_relative_file_inside_the_folder_is_read() {
    let s = scene();
    for uri in ["tri.bin", "./tri.bin", "sub/./../tri.bin"] {
        if uri.contains("..") {
            // Even a `..` that stays inside is refused: the check is on the URI.
            refused(&s.dir, uri, 36);
            continue;
        }
        let data = read_gltf(&s.dir, gltf_json(uri, 36, 36)).unwrap();
        assert_eq!(data.mesh.face_count(), 1, "{uri}");
    }
    std::fs::write(s.dir.join("my mesh.bin"), triangle_bytes()).unwrap();
    assert_eq!(read_gltf(&s.dir, gltf_json("my%20mesh.bin", 36, 36)).unwrap().mesh.face_count(), 1);
    // A longer file is read up to byteLength only.
    let mut long = triangle_bytes();
    long.extend([7u8; 100]);
    std::fs::write(s.dir.join("long.bin"), long).unwrap();
    assert_eq!(read_gltf(&s.dir, gltf_json("long.bin", 36, 36)).unwrap().mesh.vertex_count(), 3);
}

#[test]
fn devices_are_refused_without_being_read() {
    let s = scene();
    for uri in ["/dev/zero", "/dev/null", "/dev/stdin", "/dev/urandom"] {
        let e = refused(&s.dir, uri, 36);
        assert!(e.contains("absolute"), "{e}");
    }
    for uri in ["%2Fdev%2Fzero", "%2fdev/zero", "file:///dev/zero", "file:tri.bin", "http://example.com/tri.bin"] {
        refused(&s.dir, uri, 36);
    }
}

#[test]
fn escapes_out_of_the_folder_are_refused() {
    let s = scene();
    let name = s.outside.file_name().unwrap().to_str().unwrap().to_owned();
    for uri in [format!("../{name}"), format!("%2e%2e/{name}"), format!("%2E%2E%2F{name}"), format!("sub/../../{name}")]
    {
        let e = refused(&s.dir, &uri, 36);
        assert!(e.contains(".."), "{e}");
    }
    let absolute = s.outside.to_str().unwrap().to_owned();
    refused(&s.dir, &absolute, 36);
}

#[test]
fn folders_and_missing_files_are_refused() {
    let s = scene();
    let e = refused(&s.dir, "sub", 36);
    assert!(e.contains("not a regular file"), "{e}");
    refused(&s.dir, "missing.bin", 36);
    refused(&s.dir, "", 36);
}

#[cfg(unix)]
#[test]
fn symbolic_links_out_of_the_folder_and_to_devices_are_refused() {
    use std::os::unix::fs::symlink;
    let s = scene();
    symlink(&s.outside, s.dir.join("out.bin")).unwrap();
    symlink("/dev/zero", s.dir.join("zero.bin")).unwrap();
    symlink("/dev/null", s.dir.join("null.bin")).unwrap();
    symlink(s.dir.join("tri.bin"), s.dir.join("inside.bin")).unwrap();
    for uri in ["out.bin", "zero.bin", "null.bin"] {
        let e = refused(&s.dir, uri, 36);
        assert!(e.contains("outside the folder"), "{e}");
    }
    assert_eq!(read_gltf(&s.dir, gltf_json("inside.bin", 36, 36)).unwrap().mesh.face_count(), 1);
}

#[cfg(unix)]
#[test]
fn pipes_are_refused_without_blocking() {
    let s = scene();
    let fifo = s.dir.join("pipe.bin");
    match std::process::Command::new("mkfifo").arg(&fifo).status() {
        Ok(status) if status.success() => {}
        other => {
            eprintln!("SKIPPED pipes_are_refused_without_blocking: mkfifo unavailable ({other:?})");
            return;
        }
    }
    let e = refused(&s.dir, "pipe.bin", 36);
    assert!(e.contains("not a regular file"), "{e}");
}

#[test]
fn byte_lengths_are_checked_against_the_file_and_the_views() {
    let s = scene();
    let e = refused(&s.dir, "tri.bin", 360);
    assert!(e.contains("36 bytes") && e.contains("360"), "{e}");
    // A buffer shorter than its view.
    let e = read_gltf(&s.dir, gltf_json("tri.bin", 24, 36)).unwrap_err();
    assert!(!matches!(e, IoError::ExternalBuffer { .. }) && e.to_string().contains("m.gltf"), "{e}");
    // A view shorter than its accessor.
    let e = read_gltf(&s.dir, gltf_json("tri.bin", 36, 24)).unwrap_err();
    assert!(matches!(e, IoError::Truncated { .. }), "{e}");
}

#[test]
fn data_uris_shorter_than_their_byte_length_are_refused() {
    // 36 bytes of base64 (48 characters), announced as 48 bytes.
    let b64 = "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA";
    let ok = gltf_json(&format!("data:application/octet-stream;base64,{b64}"), 36, 36);
    assert_eq!(read_from(ok.as_bytes(), Format::Gltf, &ReadOptions::default()).unwrap().mesh.face_count(), 1);
    let short = gltf_json(&format!("data:application/octet-stream;base64,{b64}"), 48, 36);
    let e = read_from(short.as_bytes(), Format::Gltf, &ReadOptions::default()).unwrap_err();
    assert!(matches!(e, IoError::Truncated { .. }) && e.to_string().contains("48"), "{e}");
}

#[test]
fn external_buffers_are_refused_when_reading_from_memory() {
    let e = read_from(gltf_json("tri.bin", 36, 36).as_bytes(), Format::Gltf, &ReadOptions::default()).unwrap_err();
    assert!(matches!(e, IoError::ExternalBuffer { .. }) && e.to_string().contains("memory"), "{e}");
}

#[test]
fn glb_chunk_lengths_beyond_the_file_are_refused() {
    let json = br#"{"asset":{"version":"2.0"}}  "#; // 28 bytes, a multiple of 4
    let mut glb = Vec::new();
    glb.extend(b"glTF");
    glb.extend(2u32.to_le_bytes());
    glb.extend((12 + 8 + json.len() as u32).to_le_bytes());
    glb.extend((json.len() as u32).to_le_bytes());
    glb.extend(0x4E4F_534Au32.to_le_bytes());
    glb.extend(json);
    assert!(read_from(&glb, Format::Glb, &ReadOptions::default()).is_ok());
    // Header length larger than the file.
    let mut long = glb.clone();
    long[8..12].copy_from_slice(&u32::MAX.to_le_bytes());
    let e = read_from(&long, Format::Glb, &ReadOptions::default()).unwrap_err();
    assert!(matches!(e, IoError::Truncated { .. }), "{e}");
    // Chunk length larger than the file.
    let mut chunk = glb.clone();
    chunk[12..16].copy_from_slice(&(u32::MAX - 7).to_le_bytes());
    let e = read_from(&chunk, Format::Glb, &ReadOptions::default()).unwrap_err();
    assert!(matches!(e, IoError::Truncated { .. }), "{e}");
}
