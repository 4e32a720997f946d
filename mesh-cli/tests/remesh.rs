//! End-to-end tests of `mesh remesh`.

mod common;

use common::{json, mesh};

#[test]
fn a_torus_is_remeshed_with_its_topology() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("torus.ply");
    let o = out.to_str().unwrap();
    let v = json(&["remesh", "--shape", "torus", "--res", "16", "--edge-length", "0.1", "--json", "--out", o]);
    assert_eq!(v["edge_length_source"], "given");
    assert_eq!(v["topology_changed"], false);
    assert_eq!(v["output_topology"]["euler_characteristic"], 0);
    assert_eq!(v["output_topology"]["boundary_loops"], 0);
    assert!(v["edge_lengths"]["within_half"].as_f64().unwrap() > 0.9, "{v}");
    assert!(v["hausdorff"]["symmetric_relative"].as_f64().unwrap() < 0.01, "{v}");
    let hist: f64 = v["edge_lengths"]["histogram"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).sum();
    assert!((hist - 1.0).abs() < 1e-9);
    let info = json(&["info", "--json", o]);
    assert_eq!(info["faces"], v["faces"]);
    assert_eq!(info["euler_characteristic"], 0);
    // Text output, and the default edge length.
    let (ok, text, err) = mesh(&["remesh", "--shape", "icosphere", "--res", "3", "--out", o]);
    assert!(ok, "{err}");
    assert!(text.contains("mean edge length of the input") && text.contains("Hausdorff"), "{text}");
}

#[test]
fn a_shared_disk_keeps_its_boundary() {
    let Some(file) = mesh_testkit::shared_file("cgal_nefertiti.off") else { return };
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("n.obj");
    let v = json(&["remesh", file.to_str().unwrap(), "--json", "--out", out.to_str().unwrap()]);
    assert_eq!(v["input_topology"]["boundary_loops"], 1);
    assert_eq!(v["output_topology"]["boundary_loops"], 1);
    assert_eq!(v["topology_changed"], false);
}

#[test]
fn bad_input_is_refused_without_writing() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o.obj");
    let o = out.to_str().unwrap();
    for h in ["0", "-1", "NaN", "inf"] {
        let (ok, _, err) = mesh(&["remesh", "--shape", "icosphere", &format!("--edge-length={h}"), "--out", o]);
        assert!(!ok && err.contains("--edge-length"), "{h}: {err}");
    }
    let (ok, _, err) = mesh(&["remesh", "--shape", "icosphere", "--edge-length", "1e-6", "--out", o]);
    assert!(!ok && err.contains("--max-vertices"), "{err}");
    let (ok, _, err) = mesh(&["remesh", "--shape", "icosphere", "--min-angle", "60", "--out", o]);
    assert!(!ok && err.contains("--min-angle"), "{err}");
    assert!(!out.exists());
    // The input is never overwritten.
    let input = dir.path().join("in.obj");
    assert!(mesh(&["generate", input.to_str().unwrap(), "--shape", "icosphere", "--res", "2"]).0);
    let before = std::fs::read(&input).unwrap();
    let (ok, _, err) = mesh(&["remesh", input.to_str().unwrap(), "--out", input.to_str().unwrap()]);
    assert!(!ok && err.contains("refusing to overwrite"), "{err}");
    assert_eq!(std::fs::read(&input).unwrap(), before);
}
