//! The README's results: remeshes of the shared meshes at their mean edge
//! length (a table), and the comparison with a midpoint upsample at the same
//! vertex count (a table and, with `--figure FILE`, a PNG).
//!
//! `cargo run --release -p mesh-remesh --example results [-- [--figure mesh-remesh/docs/upsample.png] [FILE...]]`
//!
//! Files given (any format mesh-io reads, e.g. a large scan) are cleaned
//! into an oriented manifold and added to the table, as is the shared dirty
//! scan `npm_dragon_res3.ply`.

use std::time::Instant;

use glam::DVec3;

use mesh_kernel::{geometry, shapes, TriMesh};
use mesh_remesh::report::quality_report;
use mesh_remesh::{remesh, RemeshOptions, RemeshReport};

fn row(name: &str, r: &RemeshReport, ms: f64) {
    let d = r.hausdorff.map_or(f64::NAN, |d| d.symmetric_relative);
    println!(
        "| {name} | {} / {} | {} / {} | {} | {:.1} | {:.1} | {:.1}% | {:.2} | {:.1}% | {:.1e} | {} | {:.0} |",
        r.input_vertices,
        r.input_faces,
        r.vertices,
        r.faces,
        r.charts,
        r.min_angle_degrees,
        r.mean_min_angle_degrees,
        100.0 * r.below_20_degrees,
        r.edge_lengths.mean_over_target,
        100.0 * r.edge_lengths.within_half,
        d,
        if r.topology_changed { "changed" } else { "same" },
        ms
    );
}

fn main() {
    let figure = std::env::args().skip_while(|a| a != "--figure").nth(1);
    println!("| mesh | input V / F | output V / F | charts | min angle | mean min angle | < 20 deg | mean edge / H | edges in [0.5H, 1.5H] | Hausdorff / diagonal | topology | ms |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|");
    let shapes_list = [
        ("icosphere(4), H = 0.1", shapes::icosphere(4).unwrap(), 0.1),
        ("torus(2, 0.7, 64, 32), H = 0.1", shapes::torus(2.0, 0.7, 64, 32).unwrap(), 0.1),
    ];
    for (name, mesh, h) in shapes_list {
        let t = Instant::now();
        let r = remesh(&mesh, &RemeshOptions { edge_length: h, ..Default::default() }).unwrap();
        row(name, &r.report, t.elapsed().as_secs_f64() * 1e3);
    }
    let names = [
        "cgal_nefertiti.off",
        "cgal_mushroom.off",
        "cgal_elephant.off",
        "npm_bunny.obj",
        "cgal_holes.off",
        "cgal_fandisk.off",
        "npm_dragon_res3.ply",
    ];
    let mut files: Vec<(String, std::path::PathBuf)> =
        names.iter().filter_map(|name| Some((name.to_string(), mesh_testkit::shared_file(name)?))).collect();
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut i = 0;
    while i < args.len() {
        if args[i] == "--figure" {
            i += 2;
            continue;
        }
        let path = std::path::PathBuf::from(&args[i]);
        files.push((path.file_name().map_or(args[i].clone(), |n| n.to_string_lossy().into_owned()), path));
        i += 1;
    }
    for (name, path) in files {
        let (positions, faces) = mesh_io::read(&path).unwrap().mesh.into_parts();
        let clean = mesh_kernel::clean::CleanOptions { manifold: true, ..Default::default() };
        let (mesh, _) = mesh_kernel::clean::clean(positions, faces, &clean).unwrap();
        let h = geometry::mean_edge_length(&mesh);
        let t = Instant::now();
        match remesh(&mesh, &RemeshOptions { edge_length: h, ..Default::default() }) {
            Ok(r) => row(&format!("{name}, H = mean edge"), &r.report, t.elapsed().as_secs_f64() * 1e3),
            Err(e) => println!("| {name} | error: {e} |"),
        }
    }
    // A torus of long thin triangles: midpoint upsample vs remesh, same count.
    let coarse = shapes::torus(2.0, 0.7, 64, 10).unwrap();
    let (p, f) = shapes::midpoint_subdivide(&coarse);
    let up = TriMesh::new(p, f).unwrap();
    // The edge length for the upsample's vertex count: from the area, then
    // corrected once by the count obtained.
    let target = up.vertex_count() as f64;
    let mut h = (1.155 * geometry::surface_area(&coarse) / target).sqrt();
    let first = remesh(&coarse, &RemeshOptions { edge_length: h, ..Default::default() }).unwrap();
    h *= (first.mesh.vertex_count() as f64 / target).sqrt();
    let r = remesh(&coarse, &RemeshOptions { edge_length: h, ..Default::default() }).unwrap();
    let u = quality_report(&coarse, &up, h, true);
    println!();
    println!("| torus(2, 0.7, 64, 10) to ~{} vertices | V | min angle | mean min angle | < 20 deg | < 30 deg | edges in [0.5H, 1.5H] |", up.vertex_count());
    println!("|---|---|---|---|---|---|---|");
    for (name, m, q) in [("midpoint upsample", &up, &u), ("remesh", &r.mesh, &r.report)] {
        let below30 = m
            .face_ids()
            .filter(|&f| geometry::triangle_angles(m.triangle(f)).into_iter().fold(9.0, f64::min).to_degrees() < 30.0)
            .count() as f64
            / m.face_count() as f64;
        println!(
            "| {name} | {} | {:.1} | {:.1} | {:.1}% | {:.1}% | {:.1}% |",
            q.vertices,
            q.min_angle_degrees,
            q.mean_min_angle_degrees,
            100.0 * q.below_20_degrees,
            100.0 * below30,
            100.0 * q.edge_lengths.within_half
        );
    }
    if let Some(path) = figure {
        use mesh_render::{Figure, LineStyle, Paint, Panel, Scene, Shading, View};
        let panel = |m: &TriMesh, caption: String| {
            let edges: Vec<[DVec3; 2]> =
                m.connectivity().edges().iter().map(|[a, b]| [m.position(*a), m.position(*b)]).collect();
            let mut scene = Scene::new();
            scene.surface(m, Paint::Plain(mesh_render::scene::SURFACE), Shading::Flat).unwrap();
            scene.lines(edges, LineStyle::new(DVec3::new(0.1, 0.1, 0.2), 1.0)).unwrap();
            let view = View { azimuth: -60.0, elevation: 55.0, up: DVec3::Z };
            Panel::new(scene.render(&view, 400, 300, [0, 0, 0, 0]).unwrap(), caption)
        };
        let figure = Figure::row(
            "A torus of thin triangles, 4x the vertices: midpoint upsample (left) and remesh (right)",
            vec![
                panel(&up, format!("upsample: mean min angle {:.1} deg", u.mean_min_angle_degrees)),
                panel(&r.mesh, format!("remesh: mean min angle {:.1} deg", r.report.mean_min_angle_degrees)),
            ],
        );
        let image = figure.compose().unwrap();
        image.write_png(std::fs::File::create(&path).unwrap()).unwrap();
        println!("\nwrote {path}");
    }
}
