//! `mesh figures` and `mesh render` end to end: files, sizes, captions, errors.

use std::path::Path;
use std::process::Command;

fn mesh(args: &[&str]) -> (bool, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_mesh"))
        .args(args)
        .env_remove("MESH_SHARED_DATA")
        .output()
        .expect("the mesh binary runs");
    (out.status.success(), String::from_utf8_lossy(&out.stderr).into())
}

/// Width and height of a PNG file, and whether it has any non-white pixel.
fn png_info(path: &Path) -> (u32, u32, bool) {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    let drawn = buf[..info.buffer_size()].iter().any(|&b| b != 255);
    (info.width, info.height, drawn)
}

#[test]
fn figures_writes_a_picture_and_a_caption_per_figure() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("figs");
    let (ok, err) = mesh(&["figures", "--out", out.to_str().unwrap(), "--only", "2.13,2.9", "--size", "100x90"]);
    assert!(ok, "{err}");
    let mut names: Vec<String> =
        std::fs::read_dir(&out).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    names.sort();
    assert_eq!(names, ["figure-2.13.png", "figure-2.13.txt", "figure-2.9.png", "figure-2.9.txt"]);
    // Three panels of 100 x 90 in a row: 6 + 3 * 106 wide.
    for id in ["2.9", "2.13"] {
        let (w, h, drawn) = png_info(&out.join(format!("figure-{id}.png")));
        assert_eq!(w, 6 + 3 * 106, "figure {id}");
        assert!(h > 90 && drawn, "figure {id}");
        let caption = std::fs::read_to_string(out.join(format!("figure-{id}.txt"))).unwrap();
        assert!(caption.starts_with(&format!("Figure {id}:")) && caption.ends_with('\n'));
        assert_eq!(caption.lines().count(), 1);
    }
}

#[test]
fn figures_refuses_bad_options_and_missing_meshes() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o");
    let out = out.to_str().unwrap();
    let (ok, err) = mesh(&["figures", "--out", out, "--only", "2.99"]);
    assert!(!ok && err.contains("no such figure") && err.contains("2.14"), "{err}");
    let (ok, err) = mesh(&["figures", "--out", out, "--size", "12x12"]);
    assert!(!ok && err.contains("--size 12x12"), "{err}");
    let (ok, err) = mesh(&["figures", "--out", out, "--data", dir.path().join("nowhere").to_str().unwrap()]);
    assert!(!ok && err.contains("does not exist"), "{err}");
    // A data folder without the nefertiti mesh: a typed error, not a stand-in.
    let (ok, err) = mesh(&["figures", "--out", out, "--only", "2.4", "--data", dir.path().to_str().unwrap()]);
    assert!(!ok && err.contains("cgal_nefertiti.off is missing"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn render_still_writes_a_picture() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("s.png");
    let (ok, err) = mesh(&[
        "render",
        "--shape",
        "icosphere",
        "--res",
        "2",
        "--width",
        "120",
        "--height",
        "90",
        "--out",
        png.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    assert_eq!(png_info(&png), (120, 90, true));
    let (ok, err) = mesh(&["render", "--shape", "icosphere", "--width", "0", "--out", png.to_str().unwrap()]);
    assert!(!ok && err.contains("out of range"), "{err}");
}
