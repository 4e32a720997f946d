//! Every shared real mesh reads with the vertex and face counts of its
//! README (skipped or failed as `mesh_testkit::data` says when the data is
//! absent).

mod common;

use mesh_io::{read, write, Format, WriteOptions};

use mesh_testkit::data::SHARED_MESHES;

/// (file, vertices, faces) of every shared mesh.
fn meshes() -> impl Iterator<Item = (&'static str, usize, usize)> {
    SHARED_MESHES.iter().map(|m| (m.name, m.vertices, m.faces))
}

#[test]
fn shared_meshes_have_their_readme_counts() {
    let Some(dir) = mesh_testkit::shared_data() else { return };
    for (name, v, f) in meshes() {
        let data = read(dir.join(name)).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!((data.mesh.vertex_count(), data.mesh.face_count()), (v, f), "{name}");
        assert!(data.report.is_clean(), "{name}: {:?}", data.report);
    }
}

#[test]
fn shared_meshes_survive_every_format() {
    let Some(dir) = mesh_testkit::shared_data() else { return };
    let tmp = tempfile::tempdir().unwrap();
    for (name, v, f) in meshes() {
        let data = read(dir.join(name)).unwrap();
        for format in Format::ALL {
            let path = tmp.path().join(format!("m.{}", format.extension()));
            write(&path, &data, &WriteOptions::default()).unwrap();
            let back = read(&path).unwrap_or_else(|e| panic!("{name} as {format}: {e}"));
            assert_eq!(back.mesh.face_count(), f, "{name} as {format}");
            if format != Format::Stl {
                assert_eq!(back.mesh.vertex_count(), v, "{name} as {format}");
            }
        }
    }
}
