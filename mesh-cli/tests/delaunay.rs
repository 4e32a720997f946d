//! End-to-end tests of `mesh delaunay`.

mod common;

use common::{json, mesh};

#[test]
fn random_points_by_spade_and_by_flips_agree() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (dir.path().join("a.obj"), dir.path().join("b.ply"));
    let v = json(&["delaunay", "--random", "500", "--seed", "3", "--json", "--out", a.to_str().unwrap()]);
    assert_eq!(v["points"], 500);
    assert_eq!(v["violations"], 0);
    let w = json(&["delaunay", "--random", "500", "--seed", "3", "--flips", "--json", "--out", b.to_str().unwrap()]);
    assert!(w["flips"].as_u64().unwrap() > 0);
    assert!(w["sweep_violations"].as_u64().unwrap() > 0);
    assert_eq!(w["violations"], 0);
    assert_eq!(w["triangles"], v["triangles"]);
    // Both files read back as the same planar mesh.
    let (ia, ib) = (json(&["info", "--json", a.to_str().unwrap()]), json(&["info", "--json", b.to_str().unwrap()]));
    assert_eq!(ia["faces"], ib["faces"]);
    assert_eq!(ia["boundary_loops"], 1);
    assert_eq!(ia["euler_characteristic"], 1);
    // Without --json the flip count is printed.
    let (ok, out, err) = mesh(&["delaunay", "--random", "100", "--flips"]);
    assert!(ok, "{err}");
    assert!(out.contains("Lawson flips from the sweep triangulation"), "{out}");
}

#[test]
fn points_from_a_text_file_and_voronoi_cells() {
    let dir = tempfile::tempdir().unwrap();
    let points = dir.path().join("p.txt");
    let text: String = (0..10).flat_map(|i| (0..10).map(move |j| format!("{i} {j}\n"))).collect();
    std::fs::write(&points, format!("# a 10x10 grid, co-circular everywhere\n{text}0 0\n")).unwrap();
    let cells = dir.path().join("cells.obj");
    let v = json(&["delaunay", points.to_str().unwrap(), "--voronoi", cells.to_str().unwrap(), "--json"]);
    assert_eq!(v["points"], 101);
    assert_eq!(v["duplicates"], 1);
    assert_eq!(v["triangles"], 162);
    assert_eq!(v["voronoi_cells"], 100);
    assert_eq!(v["violations"], 0);
    let obj = std::fs::read_to_string(&cells).unwrap();
    assert_eq!(obj.lines().filter(|l| l.starts_with("l ")).count(), 100);
    // A mesh file's vertices work as points too.
    let grid = dir.path().join("g.obj");
    let (ok, _, err) = mesh(&["generate", grid.to_str().unwrap(), "--shape", "grid", "--res", "4"]);
    assert!(ok, "{err}");
    let v = json(&["delaunay", grid.to_str().unwrap(), "--json"]);
    assert_eq!(v["violations"], 0);
}

#[test]
fn a_polygon_with_a_hole_is_refined() {
    let dir = tempfile::tempdir().unwrap();
    let poly = dir.path().join("plate.txt");
    std::fs::write(&poly, "0 0\n4 0\n4 3\n0 3\n\n1 1\n1 2\n2 2\n2 1\n").unwrap();
    let out = dir.path().join("plate.obj");
    let v = json(&[
        "delaunay",
        "--polygon",
        poly.to_str().unwrap(),
        "--min-angle",
        "28",
        "--max-area",
        "0.05",
        "--json",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(v["complete"], true);
    assert!(v["min_angle_degrees"].as_f64().unwrap() >= 28.0);
    assert!(v["max_triangle_area"].as_f64().unwrap() <= 0.05);
    let info = json(&["info", "--json", out.to_str().unwrap()]);
    assert_eq!(info["boundary_loops"], 2);
    assert!((info["area"].as_f64().unwrap() - 11.0).abs() < 1e-9, "{info}");
}

#[test]
fn bad_input_is_an_error_not_a_panic() {
    let dir = tempfile::tempdir().unwrap();
    let line = dir.path().join("line.txt");
    std::fs::write(&line, "0 0\n1 1\n2 2\n").unwrap();
    let (ok, _, err) = mesh(&["delaunay", line.to_str().unwrap()]);
    assert!(!ok && err.contains("collinear"), "{err}");
    let bowtie = dir.path().join("bowtie.txt");
    std::fs::write(&bowtie, "0 0\n1 1\n1 0\n0 1\n").unwrap();
    let (ok, _, err) = mesh(&["delaunay", "--polygon", bowtie.to_str().unwrap()]);
    assert!(!ok && err.contains("crosses"), "{err}");
    let square = dir.path().join("square.txt");
    std::fs::write(&square, "0 0\n1 0\n1 1\n0 1\n").unwrap();
    let (ok, _, err) = mesh(&["delaunay", "--polygon", square.to_str().unwrap(), "--min-angle", "60"]);
    assert!(!ok && err.contains("--min-angle 60"), "{err}");
    let (ok, _, err) = mesh(&["delaunay", "--polygon", square.to_str().unwrap(), "--max-area", "0"]);
    assert!(!ok && err.contains("--max-area"), "{err}");
    let garbage = dir.path().join("garbage.txt");
    std::fs::write(&garbage, "0 0\nhello world\n").unwrap();
    let (ok, _, err) = mesh(&["delaunay", garbage.to_str().unwrap()]);
    assert!(!ok && err.contains("garbage.txt:2"), "{err}");
    let (ok, _, err) = mesh(&["delaunay"]);
    assert!(!ok && err.contains("--random"), "{err}");
    // Never the input file.
    let (ok, _, err) = mesh(&["delaunay", line.to_str().unwrap(), "--out", line.to_str().unwrap()]);
    assert!(!ok && err.contains("refusing to overwrite"), "{err}");
    let (ok, _, err) = mesh(&["delaunay", "--random", "1000000000000"]);
    assert!(!ok && err.contains("at most"), "{err}");
    let (ok, _, err) = mesh(&["delaunay", "--random", "2"]);
    assert!(!ok && err.contains("3 distinct points"), "{err}");
}
