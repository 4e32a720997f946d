//! `mesh nurbs`: tessellates an exact NURBS surface (a built-in shape or a
//! surface in the mesh-nurbs JSON format) and writes it as binary PLY with
//! the exact per-vertex differential geometry (eq. 2.21-2.24): properties
//! `u v gaussian mean k1 k2` as doubles, and exact unit normals.
//!
//! `--compare` also runs mesh-curvature's default estimator on the
//! tessellation and reports its error against the exact values: a ground
//! truth check of any mesh curvature method on any NURBS surface.

use std::path::PathBuf;
use std::time::Instant;

use mesh_io::MeshView;
use mesh_nurbs::glam::DVec3;
use mesh_nurbs::{shapes, tessellate, tessellate_adaptive, AdaptiveOptions, GridOptions, NurbsSurface, Tessellation};
use serde::Serialize;

use crate::output::{binary_ply, check_folder, check_output, finite, print_json, write_mesh, CliResult};

/// The built-in exact shapes, with the size they are built at.
pub const NURBS_SHAPES: &[&str] = &["sphere", "torus", "cylinder", "cone", "saddle"];

/// Arguments of `mesh nurbs`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Built-in exact surface: sphere (r = 1), torus (R = 2, r = 0.5),
    /// cylinder (r = 1, height 2), cone (r = 1, height 1), saddle (bilinear
    /// patch z = xy over the unit square).
    #[arg(long, default_value = "torus", conflicts_with = "surface")]
    shape: String,
    /// A surface in the mesh-nurbs JSON format instead of a built-in shape.
    #[arg(long, value_name = "FILE.json")]
    surface: Option<PathBuf>,
    /// Grid resolution: N segments along the shorter parameter direction,
    /// proportionally more along the other (by the lengths of the control
    /// polygon, at most 16 N): the sphere gets about 2N x N, the torus 4N x N.
    #[arg(long, value_name = "N", default_value_t = 32, conflicts_with = "tolerance")]
    res: usize,
    /// Adaptive tessellation: largest distance between mesh and surface.
    #[arg(long, value_name = "T")]
    tolerance: Option<f64>,
    /// Output PLY file (binary, doubles): exact normals and per-vertex
    /// properties u v gaussian mean k1 k2.
    #[arg(long, value_name = "OUT.ply")]
    out: PathBuf,
    /// Also write the surface itself in the JSON format.
    #[arg(long, value_name = "OUT.json")]
    surface_out: Option<PathBuf>,
    /// Estimate the curvature of the tessellation with mesh-curvature and
    /// report its error against the exact values.
    #[arg(long)]
    compare: bool,
    /// Print a JSON summary instead of text.
    #[arg(long)]
    json: bool,
    /// Allow writing over the input file.
    #[arg(long)]
    force: bool,
}

/// Smallest and largest value of a field.
#[derive(Debug, Serialize)]
struct Range {
    min: Option<f64>,
    max: Option<f64>,
}

impl Range {
    fn of(values: &[f64]) -> Self {
        let (lo, hi) = values.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| (a.min(x), b.max(x)));
        Self { min: finite(lo), max: finite(hi) }
    }
}

/// Largest error of mesh-curvature's estimates over the regular, valid
/// interior vertices.
#[derive(Debug, Serialize)]
struct Comparison {
    method: String,
    vertices_compared: usize,
    max_error_k1: Option<f64>,
    max_error_k2: Option<f64>,
    max_error_mean: Option<f64>,
    max_error_gaussian: Option<f64>,
}

#[derive(Debug, Serialize)]
struct Summary {
    surface: String,
    output: String,
    vertices: usize,
    faces: usize,
    euler_characteristic: i64,
    boundary_loops: usize,
    irregular_vertices: usize,
    gaussian: Range,
    mean: Range,
    k1: Range,
    k2: Range,
    comparison: Option<Comparison>,
    time_ms: f64,
}

fn built_in(name: &str) -> CliResult<NurbsSurface> {
    let o = DVec3::ZERO;
    Ok(match name {
        "sphere" => shapes::sphere(o, 1.0)?,
        "torus" => shapes::torus(o, 2.0, 0.5)?,
        "cylinder" => shapes::cylinder(o, 1.0, 2.0)?,
        "cone" => shapes::cone(o, 1.0, 1.0)?,
        "saddle" => shapes::bilinear(o, DVec3::X, DVec3::Y, DVec3::new(1.0, 1.0, 1.0))?,
        other => return Err(format!("unknown NURBS shape `{other}`; known: {}", NURBS_SHAPES.join(", ")).into()),
    })
}

fn load_surface(args: &Args) -> CliResult<(NurbsSurface, String)> {
    match &args.surface {
        Some(path) => {
            let file = std::fs::File::open(path).map_err(|e| format!("cannot open {}: {e}", path.display()))?;
            let surface = mesh_nurbs::json::read_json(std::io::BufReader::new(file))
                .map_err(|e| format!("{}: {e}", path.display()))?;
            Ok((surface, path.display().to_string()))
        }
        None => Ok((built_in(&args.shape)?, format!("nurbs:{}", args.shape))),
    }
}

/// Longest control polygon row along u and along v.
fn control_polygon_lengths(surface: &NurbsSurface) -> (f64, f64) {
    let (nu, nv, p) = (surface.count_u(), surface.count_v(), surface.control_points());
    let at = |i: usize, j: usize| p[i * nv + j];
    let along_u = (0..nv).map(|j| (1..nu).map(|i| at(i, j).distance(at(i - 1, j))).sum::<f64>()).fold(0.0, f64::max);
    let along_v = (0..nu).map(|i| (1..nv).map(|j| at(i, j).distance(at(i, j - 1))).sum::<f64>()).fold(0.0, f64::max);
    (along_u, along_v)
}

/// Segments (u, v) for `--res N`: N along the shorter direction.
fn grid_segments(surface: &NurbsSurface, n: usize) -> (usize, usize) {
    let (lu, lv) = control_polygon_lengths(surface);
    let ratio =
        |long: f64, short: f64| if short > 0.0 && long.is_finite() { (long / short).clamp(1.0, 16.0) } else { 1.0 };
    let scaled = |r: f64| (n as f64 * r).round() as usize;
    if lu >= lv {
        (scaled(ratio(lu, lv)), n)
    } else {
        (n, scaled(ratio(lv, lu)))
    }
}

fn tessellation(args: &Args, surface: &NurbsSurface) -> CliResult<Tessellation> {
    if let Some(tolerance) = args.tolerance {
        let options = AdaptiveOptions { chordal_tolerance: tolerance, ..AdaptiveOptions::default() };
        return Ok(tessellate_adaptive(surface, &options)?);
    }
    let (segments_u, segments_v) = grid_segments(surface, args.res);
    Ok(tessellate(surface, &GridOptions { segments_u, segments_v, ..GridOptions::default() })?)
}

/// mesh-curvature's default tensor estimator against the exact curvatures.
fn compare(t: &Tessellation) -> CliResult<Comparison> {
    use mesh_curvature::{curvature_tensor, TensorOptions};
    let options = TensorOptions::default();
    let estimate = curvature_tensor(&t.mesh, &options)?;
    let conn = t.mesh.connectivity();
    let keep: Vec<usize> = (0..t.mesh.vertex_count())
        .filter(|&i| {
            let v = mesh_kernel::VertexId::new(i);
            t.regular[i] && conn.vertex_kind(v) == mesh_kernel::VertexKind::Interior && estimate.status[i].is_valid()
        })
        .collect();
    let max_error = |f: &dyn Fn(usize) -> f64| finite(keep.iter().map(|&i| f(i).abs()).fold(f64::NAN, f64::max));
    Ok(Comparison {
        method: format!("{:?}", options.method),
        vertices_compared: keep.len(),
        max_error_k1: max_error(&|i| estimate.k1[i] - t.k1[i]),
        max_error_k2: max_error(&|i| estimate.k2[i] - t.k2[i]),
        max_error_mean: max_error(&|i| 0.5 * (estimate.k1[i] + estimate.k2[i]) - t.mean[i]),
        max_error_gaussian: max_error(&|i| estimate.k1[i] * estimate.k2[i] - t.gaussian[i]),
    })
}

/// Runs `mesh nurbs`.
pub fn run(args: &Args) -> CliResult<()> {
    if let Some(t) = args.tolerance {
        if !(t.is_finite() && t > 0.0) {
            return Err(format!("--tolerance must be a positive number, got {t}").into());
        }
    }
    check_output(&args.out, args.surface.as_deref(), args.force)?;
    if let Some(json) = &args.surface_out {
        check_output(json, args.surface.as_deref(), args.force)?;
    }
    let (surface, name) = load_surface(args)?;
    let start = Instant::now();
    let t = tessellation(args, &surface)?;
    let time_ms = start.elapsed().as_secs_f64() * 1e3;

    // (u, v) as the PLY's texture coordinates, named `u v`; the exact
    // curvatures as double properties.
    let mut view = MeshView::new(&t.mesh).with_normals(&t.normal).with_uvs(&t.uv);
    for (property, values) in [("gaussian", &t.gaussian), ("mean", &t.mean), ("k1", &t.k1), ("k2", &t.k2)] {
        view = view.with_scalar(property, values);
    }
    check_folder(&args.out)?;
    let mut write = binary_ply();
    write.ply.uv_names = mesh_io::PlyUvNames::Uv;
    write_mesh(&args.out, view, &write)?;
    if let Some(path) = &args.surface_out {
        check_folder(path)?;
        let text = mesh_nurbs::json::to_json_string(&surface)?;
        mesh_io::write_atomic(path, |w| w.write_all(text.as_bytes()).map_err(|e| mesh_io::IoError::io(path, e)))?;
    }

    let conn = t.mesh.connectivity();
    let summary = Summary {
        surface: name,
        output: args.out.display().to_string(),
        vertices: t.mesh.vertex_count(),
        faces: t.mesh.face_count(),
        euler_characteristic: conn.euler_characteristic(),
        boundary_loops: conn.boundary_loops()?.len(),
        irregular_vertices: t.regular.iter().filter(|r| !**r).count(),
        gaussian: Range::of(&t.gaussian),
        mean: Range::of(&t.mean),
        k1: Range::of(&t.k1),
        k2: Range::of(&t.k2),
        comparison: if args.compare { Some(compare(&t)?) } else { None },
        time_ms,
    };
    if args.json {
        return print_json(&summary);
    }
    let show = |r: &Range| format!("[{:.6}, {:.6}]", r.min.unwrap_or(f64::NAN), r.max.unwrap_or(f64::NAN));
    println!(
        "surface: {} -> {} ({} vertices, {} faces, chi {})",
        summary.surface, summary.output, summary.vertices, summary.faces, summary.euler_characteristic
    );
    println!(
        "  exact K {}  H {}  k1 {}  k2 {}",
        show(&summary.gaussian),
        show(&summary.mean),
        show(&summary.k1),
        show(&summary.k2)
    );
    if let Some(c) = &summary.comparison {
        let e = |x: Option<f64>| x.map_or("n/a".to_owned(), |v| format!("{v:.2e}"));
        println!(
            "  mesh-curvature ({}) on {} vertices: max error k1 {}  k2 {}  H {}  K {}",
            c.method,
            c.vertices_compared,
            e(c.max_error_k1),
            e(c.max_error_k2),
            e(c.max_error_mean),
            e(c.max_error_gaussian)
        );
    }
    eprintln!("tessellated in {time_ms:.1} ms");
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(extra: &[&str]) -> Args {
        crate::commands::parse_args("nurbs", extra)
    }

    #[test]
    fn torus_is_written_with_exact_curvature_and_parameters() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("t.ply");
        run(&args(&["--shape", "torus", "--res", "12", "--out", out.to_str().unwrap(), "--json"])).unwrap();
        let data = mesh_io::read(&out).unwrap();
        assert_eq!(data.mesh.connectivity().genus(), Some(1));
        let uv = data.uvs.as_ref().expect("u v written as texture coordinates");
        let (k1, k2, h, k) = (
            data.scalar("k1").unwrap(),
            data.scalar("k2").unwrap(),
            data.scalar("mean").unwrap(),
            data.scalar("gaussian").unwrap(),
        );
        for (i, p) in data.mesh.positions().iter().enumerate() {
            // R = 2, r = 0.5: k1 = 1/r; k2 = cos(theta) / (R + r cos(theta)),
            // with R + r cos(theta) the distance to the axis.
            let rho = p.truncate().length();
            let cos_theta = (rho - 2.0) / 0.5;
            assert!((k1[i] - 2.0).abs() < 1e-9, "k1 {}", k1[i]);
            assert!((k2[i] - cos_theta / rho).abs() < 1e-9, "k2 {} at {p}", k2[i]);
            assert!((h[i] - 0.5 * (k1[i] + k2[i])).abs() < 1e-12 && (k[i] - k1[i] * k2[i]).abs() < 1e-12);
            assert!((0.0..=1.0).contains(&uv[i].x) && (0.0..=1.0).contains(&uv[i].y));
        }
    }

    #[test]
    fn surface_json_round_trips_and_bad_input_is_an_error() {
        let dir = tempfile::tempdir().unwrap();
        let json = dir.path().join("s.json");
        let (a, b) = (dir.path().join("a.ply"), dir.path().join("b.ply"));
        let (json, a, b) = (json.to_str().unwrap(), a.to_str().unwrap(), b.to_str().unwrap());
        run(&args(&["--shape", "sphere", "--res", "8", "--out", a, "--surface-out", json])).unwrap();
        run(&args(&["--surface", json, "--res", "8", "--out", b])).unwrap();
        let (ma, mb) = (mesh_io::read(a).unwrap(), mesh_io::read(b).unwrap());
        assert_eq!(ma.mesh.vertex_count(), mb.mesh.vertex_count());
        for bad in [
            &["--shape", "klein", "--out", a][..],
            &["--shape", "torus", "--res", "0", "--out", a],
            &["--shape", "torus", "--tolerance", "0", "--out", a],
            &["--shape", "torus", "--res", "100000000", "--out", a],
            &["--surface", a, "--out", b],
            &["--surface", json, "--out", json],
        ] {
            assert!(run(&args(bad)).is_err(), "{bad:?}");
        }
    }

    #[test]
    fn resolution_follows_the_control_polygon() {
        let segments = |name| grid_segments(&built_in(name).unwrap(), 10);
        // Around the axis against the profile: 2 pi r / pi r for the
        // sphere, 2 pi R / 2 pi r = 4 for the torus (control polygons are
        // longer than the curves, not in proportion).
        let (sphere, torus) = (segments("sphere"), segments("torus"));
        assert!(sphere.1 == 10 && (15..=25).contains(&sphere.0), "{sphere:?}");
        assert!(torus.1 == 10 && (35..=55).contains(&torus.0), "{torus:?}");
        assert_eq!(segments("saddle"), (10, 10));
    }

    #[test]
    fn comparison_with_mesh_curvature_is_reported() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("c.ply");
        let a = args(&["--shape", "cylinder", "--res", "24", "--out", out.to_str().unwrap(), "--compare"]);
        let surface = built_in("cylinder").unwrap();
        let t = tessellation(&a, &surface).unwrap();
        let c = compare(&t).unwrap();
        assert!(c.vertices_compared > 0);
        // Cylinder r = 1: k1 = 1, k2 = 0 exactly; the estimate is close
        // (largest next to the open ends, where the 2-ring is cut).
        assert!(c.max_error_k1.unwrap() < 0.05 && c.max_error_k2.unwrap() < 0.05, "{c:?}");
    }
}
