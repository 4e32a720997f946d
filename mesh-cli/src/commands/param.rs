//! `mesh param`: flattens a mesh onto the plane (seed section 2.4) with
//! Tutte, mean-value, harmonic, authalic, intrinsic, LSCM or ARAP weights,
//! writes an OBJ with texture coordinates (one `vt` per vertex for a disk,
//! per corner when the mesh had to be cut into a disk first) and prints the
//! distortion summary (eq. 2.8-2.11).

use std::path::PathBuf;
use std::time::Instant;

use mesh_io::MeshView;
use mesh_param::{parameterize_cut, BoundaryMap, DistortionSummary, Method, Options, Spacing};
use serde::Serialize;

use crate::input::InputArgs;
use crate::output::{check_not_input, ensure_parent, finite, print_json, CliResult};

/// Arguments of `mesh param`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    input: InputArgs,
    /// Output OBJ file with one `vt` per vertex (per corner along a seam).
    #[arg(long, value_name = "OUT.obj")]
    out: PathBuf,
    /// tutte, mean-value, harmonic, authalic, intrinsic, lscm or arap.
    #[arg(long, default_value = "mean-value")]
    method: String,
    /// Weight of the conformal energy (intrinsic only).
    #[arg(long, value_name = "L", default_value_t = 0.5)]
    lambda: f64,
    /// Weight of the authalic energy (intrinsic only).
    #[arg(long, value_name = "M", default_value_t = 0.5)]
    mu: f64,
    /// Boundary of the fixed-boundary methods: circle or square.
    #[arg(long, default_value = "circle")]
    boundary: String,
    /// Spacing of the boundary vertices on the circle: chord (3D edge
    /// lengths) or uniform.
    #[arg(long, default_value = "chord")]
    spacing: String,
    /// Local/global iterations (arap only).
    #[arg(long, value_name = "N", default_value_t = 20)]
    iterations: usize,
    /// Print a JSON summary instead of text.
    #[arg(long)]
    json: bool,
    /// Allow writing over the input file.
    #[arg(long)]
    force: bool,
}

/// Everything `mesh param --json` prints.
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    /// The input (file or shape).
    pub input: String,
    /// The written OBJ file.
    pub output: String,
    /// Number of vertices and faces of the input.
    pub vertices: usize,
    /// Number of faces.
    pub faces: usize,
    /// The method.
    pub method: String,
    /// Edges cut open to make the mesh a disk (0 for a disk).
    pub seam_edges: usize,
    /// Whether UVs are written per corner (the mesh was cut).
    pub per_corner: bool,
    /// Surface-area-weighted mean and the maximum of sigma1 / sigma2.
    pub angle_distortion_mean: Option<f64>,
    /// Largest sigma1 / sigma2.
    pub angle_distortion_max: Option<f64>,
    /// Area-weighted mean of max(r, 1/r), r = normalized area ratio.
    pub area_distortion_mean: Option<f64>,
    /// Largest max(r, 1/r).
    pub area_distortion_max: Option<f64>,
    /// Faces whose parameter triangle is clockwise.
    pub flipped_faces: usize,
    /// Faces whose parameter triangle has zero area.
    pub collapsed_faces: usize,
    /// Faces of zero surface area (weighted uniformly).
    pub degenerate_faces: usize,
    /// Dirichlet energy / surface area (1 iff conformal, eq. 2.11).
    pub dirichlet_area_ratio: Option<f64>,
    /// The parameter boundary does not intersect itself.
    pub boundary_simple: bool,
    /// No flipped or collapsed face and a simple boundary.
    pub bijective: bool,
    /// Wall time of cutting plus parameterization plus distortion, ms.
    pub time_ms: f64,
}

/// The options from the command line.
fn options(args: &Args) -> CliResult<Options> {
    let method = match args.method.as_str() {
        "intrinsic" => Method::Intrinsic { lambda: args.lambda, mu: args.mu },
        "arap" => Method::Arap { iterations: args.iterations },
        name => Method::from_name(name)
            .ok_or_else(|| format!("unknown --method `{name}`; known: {}", Method::NAMES.join(", ")))?,
    };
    let spacing = match args.spacing.as_str() {
        "chord" => Spacing::ChordLength,
        "uniform" => Spacing::Uniform,
        other => return Err(format!("unknown --spacing `{other}`; known: chord, uniform").into()),
    };
    let boundary = match args.boundary.as_str() {
        "circle" => BoundaryMap::Circle(spacing),
        "square" => BoundaryMap::Square,
        other => return Err(format!("unknown --boundary `{other}`; known: circle, square").into()),
    };
    Ok(Options { method, boundary, ..Options::default() })
}

/// Runs `mesh param`.
pub fn run(args: &Args) -> CliResult<()> {
    let options = options(args)?;
    check_not_input(&args.out, args.input.path(), args.force)?;
    let data = args.input.load()?;
    let mesh = &data.mesh;
    let start = Instant::now();
    let p = parameterize_cut(mesh, &options)?;
    let time_ms = start.elapsed().as_secs_f64() * 1e3;
    let per_corner = !p.cut.seam.is_empty();
    let corner_uvs = p.corner_uvs();
    let view = if per_corner {
        MeshView::new(mesh).with_corner_uvs(&corner_uvs)
    } else {
        MeshView::new(mesh).with_uvs(&p.param.uv)
    };
    ensure_parent(&args.out)?;
    let write = mesh_io::WriteOptions { format: Some(mesh_io::Format::Obj), ..Default::default() };
    mesh_io::write(&args.out, view, &write)?;

    let s: &DistortionSummary = &p.param.report.summary;
    let summary = Summary {
        input: args.input.describe(),
        output: args.out.display().to_string(),
        vertices: mesh.vertex_count(),
        faces: mesh.face_count(),
        method: options.method.name().to_owned(),
        seam_edges: p.cut.seam.len(),
        per_corner,
        angle_distortion_mean: finite(s.angle_distortion_mean),
        angle_distortion_max: finite(s.angle_distortion_max),
        area_distortion_mean: finite(s.area_distortion_mean),
        area_distortion_max: finite(s.area_distortion_max),
        flipped_faces: s.flipped_faces,
        collapsed_faces: s.collapsed_faces,
        degenerate_faces: s.degenerate_faces,
        dirichlet_area_ratio: finite(s.dirichlet_area_ratio),
        boundary_simple: s.boundary_simple,
        bijective: s.bijective,
        time_ms,
    };
    if args.json {
        return print_json(&summary);
    }
    print_text(&summary);
    Ok(())
}

fn print_text(s: &Summary) {
    let show = |x: Option<f64>| x.map_or("n/a".to_owned(), |v| format!("{v:.4}"));
    println!("mesh: {} ({} vertices, {} faces)", s.input, s.vertices, s.faces);
    println!("  method             {}", s.method);
    if s.per_corner {
        println!("  cut                {} seam edges, UVs per corner", s.seam_edges);
    }
    println!("  angle distortion   mean {}, max {}", show(s.angle_distortion_mean), show(s.angle_distortion_max));
    println!("  area distortion    mean {}, max {}", show(s.area_distortion_mean), show(s.area_distortion_max));
    println!("  dirichlet / area   {}", show(s.dirichlet_area_ratio));
    println!(
        "  faces              {} flipped, {} collapsed, {} degenerate",
        s.flipped_faces, s.collapsed_faces, s.degenerate_faces
    );
    println!("  bijective          {} (boundary simple: {})", s.bijective, s.boundary_simple);
    println!("  time (ms)          {:.2}", s.time_ms);
    println!("  wrote              {}", s.output);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(extra: &[&str]) -> Args {
        crate::commands::parse_args("param", extra)
    }

    #[test]
    fn disk_gets_one_uv_per_vertex() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("d.obj");
        for method in Method::NAMES {
            run(&args(&[
                "--shape",
                "disk",
                "--res",
                "6",
                "--method",
                method,
                "--out",
                out.to_str().unwrap(),
                "--json",
            ]))
            .unwrap_or_else(|e| panic!("{method}: {e}"));
            let data = mesh_io::read(&out).unwrap();
            let uvs = data.uvs.as_ref().unwrap_or_else(|| panic!("{method}: no per-vertex UVs"));
            assert_eq!(uvs.len(), data.mesh.vertex_count());
            assert!(uvs.iter().all(|q| q.is_finite() && q.min_element() >= -1e-9 && q.max_element() <= 1.0 + 1e-9));
        }
        let square = ["--shape", "grid", "--res", "4", "--boundary", "square", "--method", "harmonic"];
        let mut v = square.to_vec();
        v.extend(["--out", out.to_str().unwrap()]);
        run(&args(&v)).unwrap();
        // The unit grid onto the unit square is the identity.
        let data = mesh_io::read(&out).unwrap();
        for (p, q) in data.mesh.positions().iter().zip(data.uvs.unwrap()) {
            assert!((p.x - q.x).abs() < 1e-12 && (p.y - q.y).abs() < 1e-12);
        }
    }

    #[test]
    fn closed_mesh_is_cut_and_written_per_corner() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("s.obj");
        run(&args(&["--shape", "torus", "--res", "8", "--method", "tutte", "--out", out.to_str().unwrap()])).unwrap();
        let data = mesh_io::read(&out).unwrap();
        let corners = data.corner_uvs.as_ref().expect("per-corner UVs along the seam");
        assert_eq!(corners.len(), data.mesh.face_count());
    }

    #[test]
    fn bad_options_are_errors() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("x.obj");
        let out = out.to_str().unwrap();
        for bad in [
            &["--method", "magic"][..],
            &["--boundary", "hexagon"],
            &["--spacing", "random"],
            &["--method", "intrinsic", "--lambda=-1"],
            &["--method", "arap", "--iterations", "100000"],
        ] {
            let mut v = vec!["--shape", "disk", "--res", "3", "--out", out];
            v.extend_from_slice(bad);
            assert!(run(&args(&v)).is_err(), "{bad:?}");
        }
    }

    #[test]
    fn shared_meshes_map_bijectively() {
        let Some(dir) = crate::commands::shared_data() else { return };
        let tmp = tempfile::tempdir().unwrap();
        for file in ["cgal_degtri_sliding.off", "cgal_nefertiti.off", "cgal_holes.off"] {
            let out = tmp.path().join(format!("{file}.obj"));
            let input = dir.join(file);
            run(&args(&[input.to_str().unwrap(), "--method", "tutte", "--out", out.to_str().unwrap(), "--json"]))
                .unwrap();
            let data = mesh_io::read(&out).unwrap();
            let finite = match (&data.uvs, &data.corner_uvs) {
                (_, Some(c)) => c.iter().flatten().all(|q| q.is_finite()),
                (Some(u), None) => u.iter().all(|q| q.is_finite()),
                _ => false,
            };
            assert!(finite, "{file}");
        }
    }
}
