//! `mesh report`: the main job. Runs every analysis of the workspace on one
//! mesh and writes, into one folder, a JSON report and files a viewer opens
//! directly (PLY with per-vertex fields, OBJ polylines).

use std::path::{Path, PathBuf};
use std::time::Instant;

use mesh_core::{geometry, operators, VertexId};
use mesh_io::MeshView;
use serde_json::{json, Map, Value};

use super::info::Info;
use crate::input::InputArgs;
use crate::output::{check_not_input, write_json, CliResult};
use crate::render::{render_png, RenderOptions};

/// Arguments of `mesh report`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    input: InputArgs,
    /// Output folder (created if needed).
    #[arg(long, default_value = "out")]
    out: PathBuf,
    /// Dihedral angle, in degrees, above which an edge is a feature edge.
    #[arg(long, default_value_t = 30.0)]
    feature_angle: f64,
    /// The axis pointing up in the pictures: x, y or z.
    #[arg(long, default_value = "z")]
    up: String,
}

/// Collects sections, timings and written files.
struct Report {
    dir: PathBuf,
    sections: Map<String, Value>,
    timings_ms: Map<String, Value>,
    files: Vec<String>,
}

impl Report {
    fn time<T>(&mut self, name: &str, f: impl FnOnce() -> T) -> T {
        let t = Instant::now();
        let out = f();
        self.timings_ms.insert(name.into(), json!(t.elapsed().as_secs_f64() * 1e3));
        out
    }

    fn file(&mut self, name: &str) -> PathBuf {
        self.files.push(name.to_owned());
        self.dir.join(name)
    }
}

/// Runs `mesh report`.
pub fn run(args: &Args) -> CliResult<()> {
    if !(args.feature_angle.is_finite() && (0.0..=180.0).contains(&args.feature_angle)) {
        return Err(format!("--feature-angle must be in [0, 180], got {}", args.feature_angle).into());
    }
    std::fs::create_dir_all(&args.out).map_err(|e| format!("cannot create {}: {e}", args.out.display()))?;
    let mut report = Report { dir: args.out.clone(), sections: Map::new(), timings_ms: Map::new(), files: Vec::new() };
    let data = report.time("read", || args.input.load())?;
    let mesh = &data.mesh;
    let info = report.time("info", || Info::of(mesh));
    report.sections.insert("info".into(), serde_json::to_value(&info)?);

    let normals = report.time("vertex_normals", || geometry::vertex_normals(mesh, geometry::NormalWeighting::Area));
    let mass = report.time("mass_voronoi", || operators::lumped_mass(mesh, operators::MassKind::MixedVoronoi));
    let laplacian = report.time("cotan_laplacian", || operators::cotan_laplacian(mesh));
    let negative = laplacian.iter().filter(|(v, (i, j))| i != j && **v > 0.0).count() / 2;
    let features = report.time("feature_edges", || geometry::feature_edges(mesh, args.feature_angle.to_radians()));
    report.sections.insert(
        "operators".into(),
        json!({
            "laplacian_nonzeros": laplacian.nnz(),
            "negative_cotan_weights": negative,
            "feature_edges": features.len(),
            "feature_angle_degrees": args.feature_angle,
        }),
    );

    let ply = report.file("mesh.ply");
    check_not_input(&ply, args.input.path(), false)?;
    let view = MeshView::new(mesh).with_normals(&normals).with_scalar("voronoi_area", &mass);
    mesh_io::write(&ply, view, &mesh_io::WriteOptions::default())?;
    write_feature_edges(&report.file("feature_edges.obj"), mesh, &features)?;
    let picture = RenderOptions { up: super::render::axis(&args.up)?, ..RenderOptions::default() };
    render_png(mesh, None, &report.file("mesh.png"), &picture)?;

    let summary = json!({
        "input": args.input.describe(),
        "sections": report.sections,
        "timings_ms": report.timings_ms,
        "files": report.files,
    });
    let json_path = args.out.join("report.json");
    write_json(&json_path, &summary)?;
    println!("{}", serde_json::to_string_pretty(&summary)?);
    eprintln!("wrote {} and {} files in {}", json_path.display(), report.files.len(), args.out.display());
    Ok(())
}

fn write_feature_edges(path: &Path, mesh: &mesh_core::TriMesh, edges: &[mesh_core::EdgeId]) -> CliResult<()> {
    let conn = mesh.connectivity();
    let lines: Vec<[mesh_core::glam::DVec3; 2]> =
        edges.iter().map(|&e| conn.edge_vertices(e).map(|v: VertexId| mesh.position(v))).collect();
    mesh_io::write_polylines(path, &lines)?;
    Ok(())
}
