//! Every mesh of `shared/data` reads with the vertex and face counts its
//! README gives (skipped with a message when the folder is absent).

mod common;

use mesh_io::{read, write, Format, WriteOptions};

const MESHES: [(&str, usize, usize); 7] = [
    ("cgal_nefertiti.off", 299, 562),
    ("cgal_mushroom.off", 2337, 4608),
    ("cgal_elephant.off", 2775, 5558),
    ("cgal_fandisk.off", 6475, 12946),
    ("npm_bunny.obj", 1839, 3674),
    ("cgal_holes.off", 4291, 8288),
    ("cgal_degtri_sliding.off", 8, 8),
];

#[test]
fn shared_meshes_have_their_readme_counts() {
    let Some(dir) = common::shared_data() else { return };
    for (name, v, f) in MESHES {
        let data = read(dir.join(name)).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!((data.mesh.vertex_count(), data.mesh.face_count()), (v, f), "{name}");
        assert!(data.report.is_clean(), "{name}: {:?}", data.report);
    }
}

#[test]
fn shared_meshes_survive_every_format() {
    let Some(dir) = common::shared_data() else { return };
    let tmp = tempfile::tempdir().unwrap();
    for (name, v, f) in MESHES {
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
