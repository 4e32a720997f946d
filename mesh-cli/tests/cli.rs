//! End-to-end tests of the `mesh` binary.

mod common;

use common::{json, mesh};

use std::path::Path;

use serde_json::Value;

#[test]
fn info_on_builtin_shapes() {
    let v = json(&["info", "--json", "--shape", "torus", "--res", "8"]);
    assert_eq!(v["euler_characteristic"], 0);
    assert_eq!(v["genus"], 1);
    assert_eq!(v["vertices"], 32 * 8);
    let v = json(&["info", "--json"]);
    assert_eq!(v["genus"], 0);
    assert_eq!(v["boundary_loops"], 0);
}

#[test]
fn info_lists_attributes_with_kind_and_arity() {
    let dir = tempfile::tempdir().unwrap();
    let curvature = dir.path().join("k.ply");
    let (ok, _, err) = mesh(&["curvature", "--shape", "icosphere", "--res", "2", "--out", curvature.to_str().unwrap()]);
    assert!(ok, "{err}");
    let info = json(&["info", "--json", curvature.to_str().unwrap()]);
    let list = info["attributes"].as_array().unwrap().clone();
    let find = |name: &str| {
        let a = list.iter().find(|a| a["name"] == name).unwrap_or_else(|| panic!("{name} not in {list:?}"));
        (a["element"].as_str().unwrap().to_owned(), a["kind"].as_str().unwrap().to_owned(), a["arity"].as_u64())
    };
    assert_eq!(find("d1"), ("vertex".into(), "vector".into(), Some(3)));
    assert_eq!(find("flag"), ("vertex".into(), "label".into(), Some(1)));
    assert_eq!(find("mean"), ("vertex".into(), "scalar".into(), Some(1)));
    assert!(list.iter().all(|a| a["name"] != "d1x"), "vector components are not listed as scalars");
    let (ok, text, _) = mesh(&["info", curvature.to_str().unwrap()]);
    assert!(ok && text.contains("attribute          vertex vector d1 (3 per value)"), "{text}");
    let atlas = dir.path().join("a.ply");
    let (ok, _, err) = mesh(&["param", "--shape", "torus", "--res", "6", "--out", atlas.to_str().unwrap()]);
    assert!(ok, "{err}");
    let info = json(&["info", "--json", atlas.to_str().unwrap()]);
    let kinds: Vec<(String, String)> = info["attributes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|a| (a["name"].as_str().unwrap().to_owned(), format!("{} {}", a["element"], a["kind"])))
        .collect();
    for (name, kind) in
        [("uvs", r#""corner" "uv""#), ("chart", r#""face" "label""#), ("angle_distortion", r#""face" "scalar""#)]
    {
        assert!(kinds.contains(&(name.to_owned(), kind.to_owned())), "{name}: {kinds:?}");
    }
}

#[test]
fn info_matches_the_shared_data_readme() {
    let Some(dir) = mesh_testkit::shared_data() else { return };
    for m in mesh_testkit::data::SHARED_MESHES {
        let (file, path) = (m.name, dir.join(m.name));
        let info = json(&["info", "--json", path.to_str().unwrap()]);
        assert_eq!(info["vertices"], m.vertices, "{file}");
        assert_eq!(info["faces"], m.faces, "{file}");
        assert_eq!(info["euler_characteristic"], m.euler, "{file}");
        assert_eq!(info["genus"], m.genus, "{file}");
        assert_eq!(info["boundary_loops"], m.boundary_loops, "{file}");
        assert_eq!(info["manifold"], true, "{file}");
    }
}

#[test]
fn defects_are_counted_without_panic() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.off");
    // A fan of three triangles on edge 0-1 (non-manifold edge), a duplicate of
    // the first (in another order), two unreferenced vertices, a bow-tie at 0,
    // and a zero-area triangle.
    let off = "OFF\n10 7 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n9 9 9\n8 8 8\n-1 0 0\n-1 1 0\n2 0 0\n\
               3 0 1 2\n3 1 0 3\n3 0 1 4\n3 2 0 1\n3 0 7 8\n3 0 1 9\n3 7 0 8\n";
    std::fs::write(&path, off).unwrap();
    let info = json(&["info", "--json", path.to_str().unwrap()]);
    assert_eq!(info["manifold"], false);
    assert_eq!(info["genus"], Value::Null);
    assert_eq!(info["boundary_loops"], Value::Null);
    assert_eq!(info["non_manifold_edges"], 1);
    assert_eq!(info["duplicate_faces"], 2);
    assert_eq!(info["unreferenced_vertices"], 2);
    assert_eq!(info["degenerate_faces"], 1);
    let clean_out = dir.path().join("clean.ply");
    let summary = json(&["clean", "--json", path.to_str().unwrap(), clean_out.to_str().unwrap()]);
    assert_eq!(summary["duplicate_faces"], 2);
    assert_eq!(summary["degenerate_faces"], 1);
    assert_eq!(summary["unreferenced_vertices"], 3);
}

#[test]
fn clean_manifold_repairs_the_dirty_dragon_scan() {
    let Some(data) = mesh_testkit::shared_data() else { return };
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("clean.ply");
    let input = data.join("npm_dragon_res3.ply");
    let summary = json(&["clean", "--manifold", "--json", input.to_str().unwrap(), out.to_str().unwrap()]);
    assert_eq!(summary["manifold"], true);
    assert_eq!(summary["duplicate_faces"], 1254);
    // The shared data README: 1,564 non-manifold edges remain after dropping duplicates.
    assert_eq!(summary["fin_edges"], 1564);
    assert_eq!(summary["unorientable_components"], 0);
    let info = json(&["info", "--json", out.to_str().unwrap()]);
    assert_eq!(info["manifold"], true);
    assert_eq!((info["non_manifold_edges"].clone(), info["faces"].clone()), (0.into(), summary["faces"].clone()));
    // Without --manifold the result says it is not a manifold.
    let plain = json(&["clean", "--json", input.to_str().unwrap(), out.to_str().unwrap()]);
    assert_eq!(plain["manifold"], false);
}

#[test]
fn refuses_to_overwrite_the_input() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("m.off");
    std::fs::write(&path, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n").unwrap();
    let before = std::fs::read(&path).unwrap();
    let (ok, _, stderr) = mesh(&["convert", path.to_str().unwrap(), path.to_str().unwrap()]);
    assert!(!ok);
    assert!(stderr.contains("refusing to overwrite"), "{stderr}");
    assert_eq!(std::fs::read(&path).unwrap(), before);
}

#[test]
fn bad_input_is_an_error_not_a_panic() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.off");
    std::fs::write(&path, "OFF\n3 1 0\n0 0 0\n1 0 nan\n0 1 0\n3 0 1 7\n").unwrap();
    let (ok, _, stderr) = mesh(&["info", path.to_str().unwrap()]);
    assert!(!ok);
    assert!(stderr.starts_with("mesh: error:"), "{stderr}");
    let (ok, _, stderr) = mesh(&["info", "--shape", "teapot"]);
    assert!(!ok && stderr.contains("unknown shape"), "{stderr}");
    let (ok, _, _) = mesh(&["info", "--shape", "grid", "--res", "0"]);
    assert!(!ok);
}

#[test]
fn report_writes_viewer_files() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let v = json(&["report", "--shape", "cube", "--res", "4", "--out", out.to_str().unwrap()]);
    assert_eq!(v["sections"]["info"]["euler_characteristic"], 2);
    assert_eq!(v["sections"]["operators"]["feature_edges"], 12 * 4);
    for f in v["files"].as_array().unwrap() {
        assert!(out.join(f.as_str().unwrap()).is_file(), "{f}");
    }
    assert!(out.join("report.json").is_file());
    // A clean cube needs no warning about its input; its sharp edges have no
    // finite curvature, and the curvature section says where it flagged them;
    // on 98 vertices the heat distance is a few percent off the exact one,
    // and the geodesic section says so.
    let warnings: Vec<&str> = v["warnings"].as_array().unwrap().iter().map(|w| w.as_str().unwrap()).collect();
    assert!(
        warnings.iter().all(|w| (w.starts_with("curvature:") && w.contains("unresolved"))
            || w.starts_with("geodesic: the heat distance differs from the exact")),
        "{warnings:?}"
    );
    let g = &v["sections"]["geodesic"];
    assert_eq!(g["reference"], "exact polyhedral distance");
    assert!(g["heat_vs_reference_max_relative"].as_f64().unwrap() < 0.1, "{g}");
    let flagged = v["sections"]["curvature"]["flagged"]["by_reason"]["unresolved"].as_u64().unwrap();
    assert!(flagged > 0 && flagged < 6 * 4 * 4 + 2, "{flagged}");
}

#[test]
fn report_warns_about_what_the_input_lacks() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("two.off");
    // Two triangles of a square whose diagonal vertices are duplicated (the
    // square is cut along the diagonal), and a lone third triangle far away.
    let off = "OFF\n9 3 0\n0 0 0\n1 0 0\n1 1 0\n0 0 0\n1 1 0\n0 1 0\n5 5 0\n6 5 0\n5 6 0\n\
               3 0 1 2\n3 3 4 5\n3 6 7 8\n";
    std::fs::write(&path, off).unwrap();
    let out = dir.path().join("out");
    let v = json(&["report", path.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    let warnings: Vec<&str> = v["warnings"].as_array().unwrap().iter().map(|w| w.as_str().unwrap()).collect();
    assert!(warnings.iter().any(|w| w.starts_with("2 vertices sit exactly on another")), "{warnings:?}");
    assert!(warnings.iter().any(|w| w.starts_with("3 connected components")), "{warnings:?}");
    assert_eq!(v["sections"]["info"]["coincident_vertices"], 2);
}

#[test]
fn report_runs_every_analysis_on_a_torus() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let v = json(&["report", "--shape", "torus", "--res", "16", "--out", out.to_str().unwrap()]);
    let s = &v["sections"];
    // Torus R = 2, r = 0.5: k1 = 1/r = 2 everywhere; Gauss-Bonnet total 0.
    // (16 vertices around the tube: the estimate is within 2%.)
    assert!((s["curvature"]["k1"]["mean"].as_f64().unwrap() - 2.0).abs() < 0.05, "{}", s["curvature"]);
    assert!(s["curvature"]["gauss_bonnet_total"].as_f64().unwrap().abs() < 1e-10);
    // Farthest point from a vertex on the outer equator: half way round the
    // tube and half way round the axis, at most pi (R + r) + pi r.
    let far = s["geodesic"]["max_distance_heat"].as_f64().unwrap();
    assert!(far > 2.0 * std::f64::consts::PI * 0.9 && far < std::f64::consts::PI * 3.0, "{far}");
    assert_eq!(s["geodesic"]["unreachable"], 0);
    assert_eq!(s["parameterization"]["bijective"], true);
    assert!(s["wavelet"]["levels"].as_u64().unwrap() >= 1);
    // Spectrum: 0, then the first rotation mode around the axis, about
    // 1/R^2 = 0.25, twice (cos and sin); residuals at solver tolerance.
    let lambda: Vec<f64> =
        s["spectral"]["eigenvalues"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
    assert_eq!(lambda.len(), 20);
    assert!(
        lambda[0].abs() < 1e-9 && (lambda[1] - lambda[2]).abs() < 1e-8 && (0.2..0.3).contains(&lambda[1]),
        "{lambda:?}"
    );
    assert!(s["spectral"]["max_residual"].as_f64().unwrap() < 1e-8);
    for f in ["mesh.ply", "uv.obj", "geodesic_path.obj", "mean.png", "distance.png", "harmonic1.png"] {
        assert!(out.join(f).is_file(), "{f}");
    }
    let ply = mesh_io_fields(&out.join("mesh.ply"));
    for name in ["gaussian", "mean", "k1", "k2", "distance", "harmonic1", "hks"] {
        assert!(ply.contains(&name.to_owned()), "{name} missing from {ply:?}");
    }
}

/// Names of the per-vertex properties in a binary PLY header.
fn mesh_io_fields(path: &Path) -> Vec<String> {
    let bytes = std::fs::read(path).unwrap();
    let end = bytes.windows(10).position(|w| w == b"end_header").unwrap();
    String::from_utf8_lossy(&bytes[..end])
        .lines()
        .filter_map(|l| l.strip_prefix("property double ").map(str::to_owned))
        .collect()
}

#[test]
fn spectral_eigenvalues_of_a_small_icosphere() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("phi.ply");
    let v =
        json(&["spectral", "--shape", "icosphere", "--res", "3", "--k", "9", "--json", "--out", out.to_str().unwrap()]);
    let lambda: Vec<f64> = v["eigenvalues"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
    // Unit sphere: 0 | l (l + 1) = 2 three times | 6 five times, ascending
    // (642 vertices: within 2% of the continuum values).
    assert_eq!(lambda.len(), 9);
    assert!(lambda[0].abs() < 1e-9, "{lambda:?}");
    assert!(lambda[1..4].iter().all(|x| (x - 2.0).abs() < 0.02 * 2.0), "{lambda:?}");
    assert!(lambda[4..9].iter().all(|x| (x - 6.0).abs() < 0.02 * 6.0), "{lambda:?}");
    assert!(lambda.windows(2).all(|w| w[0] <= w[1]), "{lambda:?}");
    assert_eq!(v["residuals"].as_array().unwrap().len(), 9);
    assert!(v["max_residual"].as_f64().unwrap() <= 1e-8);
    assert!(v["timings_ms"]["eigensolver"].as_f64().unwrap() >= 0.0);
    let fields = mesh_io_fields(&out);
    assert!((0..9).all(|j| fields.contains(&format!("phi{j}"))), "{fields:?}");
}

#[test]
fn spectral_filter_and_compress_write_their_outputs() {
    let dir = tempfile::tempdir().unwrap();
    let smooth = dir.path().join("smooth.obj");
    let (ok, _, stderr) = mesh(&[
        "spectral",
        "filter",
        "--shape",
        "torus",
        "--res",
        "8",
        "--keep",
        "10",
        "--out",
        smooth.to_str().unwrap(),
    ]);
    assert!(ok, "{stderr}");
    assert!(std::fs::metadata(&smooth).unwrap().len() > 0);
    let restored = dir.path().join("restored.obj");
    let v = json(&[
        "spectral",
        "compress",
        "--shape",
        "torus",
        "--res",
        "8",
        "--keep",
        "32",
        "--json",
        "--out",
        restored.to_str().unwrap(),
    ]);
    assert!(restored.is_file());
    assert_eq!(v["keep"], 32);
    // The area-weighted error never increases with the number of coefficients.
    let curve: Vec<f64> = v["curve"].as_array().unwrap().iter().map(|p| p["rms"].as_f64().unwrap()).collect();
    assert!(curve.len() >= 2 && curve.windows(2).all(|w| w[1] <= w[0] * (1.0 + 1e-12)), "{curve:?}");
    let at_keep = v["error"]["rms"].as_f64().unwrap();
    assert!((at_keep - curve.last().unwrap()).abs() <= 1e-12 * at_keep, "{at_keep} vs {curve:?}");
}

#[test]
fn spectral_bad_input_is_an_error_not_a_panic() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("one.off");
    std::fs::write(&path, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n").unwrap();
    // More pairs than vertices, k = 0, keep above the basis, a NaN vertex,
    // an unknown Laplacian: each an error message, never a panic.
    let cases: [&[&str]; 5] = [
        &["spectral", path.to_str().unwrap(), "--k", "5"],
        &["spectral", "--shape", "icosphere", "--res", "1", "--k", "0"],
        &["spectral", "compress", "--shape", "icosphere", "--res", "1", "--keep", "500"],
        &["spectral", "--shape", "icosphere", "--res", "1", "--laplacian", "graph"],
        &["spectral", "--shape", "grid", "--res", "0"],
    ];
    for args in cases {
        let (ok, _, stderr) = mesh(args);
        assert!(!ok, "{args:?} succeeded");
        assert!(stderr.starts_with("mesh: error:"), "{args:?}: {stderr}");
    }
    std::fs::write(&path, "OFF\n3 1 0\n0 0 0\n1 0 nan\n0 1 0\n3 0 1 2\n").unwrap();
    let (ok, _, stderr) = mesh(&["spectral", path.to_str().unwrap()]);
    assert!(!ok && stderr.starts_with("mesh: error:"), "{stderr}");
}

#[test]
fn info_does_not_depend_on_the_unit_of_length() {
    let dir = tempfile::tempdir().unwrap();
    let base = dir.path().join("torus.off");
    let (ok, _, stderr) = mesh(&["generate", "--shape", "torus", "--res", "12", base.to_str().unwrap()]);
    assert!(ok, "{stderr}");
    let text = std::fs::read_to_string(&base).unwrap();
    let reference = json(&["info", "--json", base.to_str().unwrap()]);
    for scale in [1e-150, 1e150, 1e-300, 1e300] {
        // The same file with every coordinate multiplied by `scale`.
        let mut lines = text.lines();
        let mut out = vec![lines.next().unwrap().to_owned(), lines.next().unwrap().to_owned()];
        let n: usize = out[1].split_whitespace().next().unwrap().parse().unwrap();
        for line in lines.by_ref().take(n) {
            let xyz: Vec<String> =
                line.split_whitespace().map(|x| format!("{:e}", x.parse::<f64>().unwrap() * scale)).collect();
            out.push(xyz.join(" "));
        }
        out.extend(lines.map(str::to_owned));
        let path = dir.path().join(format!("torus-{scale:e}.off"));
        std::fs::write(&path, out.join("\n")).unwrap();
        let info = json(&["info", "--json", path.to_str().unwrap()]);
        for key in ["faces", "genus", "components", "degenerate_faces", "coincident_vertices"] {
            assert_eq!(info[key], reference[key], "{key} at {scale:e}");
        }
        let relative = |key: &str, power: i32| {
            let (a, b) = (info[key].as_f64().unwrap(), reference[key].as_f64().unwrap());
            (a / scale.powi(power) / b - 1.0).abs()
        };
        assert!(relative("mean_edge_length", 1) < 1e-9, "{scale:e}");
        let out_of_range = info["out_of_range"].as_array().unwrap();
        if (1e-200..1e200).contains(&scale) {
            assert!(relative("area", 2) < 1e-9, "{scale:e}");
            assert_eq!(out_of_range.len(), 1, "the volume {scale:e}^3 is out of range: {out_of_range:?}");
        } else {
            assert!(info["area"].is_null() && info["volume"].is_null(), "{info}");
            assert_eq!(out_of_range.len(), 2, "{out_of_range:?}");
        }
    }
}
