//! Errors and notices of the `mesh` binary in the user's terms: the flag and
//! value typed, the file, what to do; nothing dropped or changed without a
//! word.

mod common;

use common::mesh;

use std::path::Path;

/// Runs a command that must fail; returns its standard error.
fn fails(args: &[&str]) -> String {
    let (ok, _, stderr) = mesh(args);
    assert!(!ok, "mesh {args:?} succeeded");
    assert!(stderr.starts_with("mesh: error") || stderr.contains("\nmesh: error"), "{stderr}");
    stderr
}

fn contains_all(text: &str, phrases: &[&str]) {
    for p in phrases {
        assert!(text.contains(p), "missing {p:?} in: {text}");
    }
    for rust in ["::", "LaplacianKind", "DegeneratePolicy", "invalid option `"] {
        assert!(!text.contains(rust), "Rust terms {rust:?} in: {text}");
    }
}

fn write(dir: &Path, name: &str, text: &str) -> String {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.to_str().unwrap().to_owned()
}

/// Three faces, two of which repeat a vertex.
const THREE_FACES: &str = "OFF\n3 3 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 0 1\n3 1 1 2\n";

#[test]
fn info_shows_what_the_reader_dropped() {
    let dir = tempfile::tempdir().unwrap();
    let file = write(dir.path(), "three.off", THREE_FACES);
    let (ok, stdout, stderr) = mesh(&["info", &file]);
    assert!(ok, "{stderr}");
    assert!(stdout.contains("read               2 faces dropped"), "{stdout}");
    assert!(stderr.contains("note") && stderr.contains("three.off") && stderr.contains("2 faces dropped"), "{stderr}");
    let (ok, stdout, _) = mesh(&["info", &file, "--json"]);
    assert!(ok);
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(v["read"]["faces_dropped"], 2);
    assert_eq!(v["read"]["polygons_triangulated"], 0);
    assert_eq!(v["read"]["vertices_welded"], 0);
    assert!(v["read"]["notes"].as_array().unwrap().is_empty());
    // Every command reading the file says so, once.
    let out = dir.path().join("c.off");
    let (ok, _, stderr) = mesh(&["convert", &file, out.to_str().unwrap()]);
    assert!(ok && stderr.matches("2 faces dropped").count() == 1, "{stderr}");
}

#[test]
fn no_command_creates_missing_folders() {
    let dir = tempfile::tempdir().unwrap();
    let file = write(dir.path(), "three.off", THREE_FACES);
    let missing = dir.path().join("no/such/folder/out.ply");
    let missing = missing.to_str().unwrap();
    for args in [
        vec!["convert", &file, missing],
        vec!["clean", &file, missing],
        vec!["generate", missing],
        vec!["curvature", "--out", missing],
    ] {
        let e = fails(&args);
        contains_all(&e, &["does not exist", "no/such/folder", "mkdir -p"]);
    }
    assert!(!dir.path().join("no").exists());
}

#[test]
fn clean_refuses_a_weld_distance_beyond_the_diagonal() {
    let dir = tempfile::tempdir().unwrap();
    let file = write(dir.path(), "three.off", THREE_FACES);
    let out = dir.path().join("c.off");
    let e = fails(&["clean", &file, out.to_str().unwrap(), "--weld", "1e300"]);
    contains_all(&e, &["--weld 1e300 is larger", "diagonal", "1.414", "three.off"]);
    let e = fails(&["clean", &file, out.to_str().unwrap(), "--weld", "-1"]);
    contains_all(&e, &["--weld -1", ">= 0", "three.off"]);
    assert!(!out.exists());
    let (ok, _, stderr) = mesh(&["clean", &file, out.to_str().unwrap(), "--weld", "0.1"]);
    assert!(ok, "{stderr}");
}

#[test]
fn writers_refuse_precision_loss_unless_asked() {
    let dir = tempfile::tempdir().unwrap();
    let huge = write(dir.path(), "huge.off", "OFF\n3 1 0\n0 0 0\n1e300 0 0\n0 1e300 0\n3 0 1 2\n");
    let stl = dir.path().join("huge.stl");
    let stl = stl.to_str().unwrap();
    let e = fails(&["convert", &huge, stl]);
    contains_all(&e, &["vertex 1", "1e300", "--allow-precision-loss", "32-bit"]);
    let (ok, _, stderr) = mesh(&["convert", &huge, stl, "--allow-precision-loss"]);
    assert!(ok && stderr.contains("warning") && stderr.contains("lost"), "{stderr}");
    // Faceless meshes cannot be STL.
    let points = write(dir.path(), "points.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n");
    let e = fails(&["convert", &points, stl]);
    contains_all(&e, &["without faces", "STL"]);
    let glb = dir.path().join("points.glb");
    let (ok, _, stderr) = mesh(&["convert", &points, glb.to_str().unwrap()]);
    assert!(ok, "{stderr}");
    let (ok, stdout, _) = mesh(&["info", glb.to_str().unwrap()]);
    assert!(ok && stdout.contains("vertices           3"), "{stdout}");
}

#[test]
fn subdivide_output_is_accepted_by_wavelet_analyze() {
    let dir = tempfile::tempdir().unwrap();
    let file = write(dir.path(), "unref.off", "OFF\n5 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n5 5 5\n3 0 1 2\n3 1 3 2\n");
    let out = dir.path().join("sub.obj");
    let out = out.to_str().unwrap();
    let (ok, stdout, stderr) = mesh(&["subdivide", &file, "--levels", "2", "--out", out, "--json"]);
    assert!(ok, "{stderr}");
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(v["unreferenced_vertices_dropped"], 1);
    let (ok, stdout, stderr) = mesh(&["wavelet", "analyze", out]);
    assert!(ok, "{stderr}");
    assert!(stdout.contains("levels             2"), "{stdout}");
}

#[test]
fn library_errors_quote_the_flags_typed() {
    let e = fails(&["wavelet", "analyze", "--max-levels", "0"]);
    contains_all(&e, &["--max-levels 0", "at least one"]);
    let e = fails(&["spectral", "--shape", "icosphere", "--res", "0", "--k", "50", "--out", "/tmp/never-written.ply"]);
    contains_all(&e, &["--k 50", "at most 12"]);
    let e = fails(&["subdivide", "--levels", "30", "--out", "/tmp/never-written.obj"]);
    contains_all(&e, &["--levels 30"]);
    let e = fails(&["spectral", "hks", "--times", "0", "--out", "/tmp/never-written.ply"]);
    contains_all(&e, &["--times 0"]);
}

#[test]
fn heat_on_zero_area_faces_says_which_flag_to_pass() {
    let dir = tempfile::tempdir().unwrap();
    // A fan around vertex 0 where one triangle has zero area and cuts vertex 4 off.
    let file =
        write(dir.path(), "sliver.off", "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n-1 0 0\n2 0 0\n3 0 1 2\n3 0 2 3\n3 0 4 1\n");
    let out = dir.path().join("d.ply");
    let out = out.to_str().unwrap();
    let (ok, _, stderr) = mesh(&["geodesic", &file, "--source", "0", "--laplacian", "cotan", "--out", out]);
    if !ok {
        contains_all(&stderr, &["--laplacian intrinsic"]);
        assert!(!stderr.contains("NonPositivePivot"), "{stderr}");
    }
    if let Some(shared) = mesh_testkit::shared_file("cgal_degtri_sliding.off") {
        let args = ["geodesic", shared.to_str().unwrap(), "--source", "0", "--laplacian", "cotan", "--out", out];
        contains_all(&fails(&args), &["pass --laplacian intrinsic"]);
    }
    let (ok, _, stderr) = mesh(&["geodesic", &file, "--source", "0", "--laplacian", "intrinsic", "--out", out]);
    if !ok {
        assert!(!stderr.contains("pass --laplacian intrinsic"), "{stderr}");
    }
}
