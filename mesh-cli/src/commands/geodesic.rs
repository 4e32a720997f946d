//! `mesh geodesic`: geodesic distance from source vertices (section 2.6
//! of the "Digital Shape Processing" thesis chapter) by the heat method,
//! Fast Marching (eq. 2.32-2.34), Dijkstra on the edges or exact polyhedral
//! geodesics (window propagation), written as binary PLY with a per-vertex double `distance` (+infinity where no source
//! is reachable), and optionally the path from a vertex back to the sources
//! along -grad U (eq. 2.35) as an OBJ polyline. For the heat method the PLY
//! also flags, per vertex, where the heat flow was below what double
//! precision resolves: `far_field` (1 where the distance was continued
//! there, by Fast Marching or restarted heat flows) and `unresolved` (1
//! where it was not: `--far-field none`); `--json` counts both.

use mesh_kernel::MeshError;
use std::path::PathBuf;
use std::time::Instant;

use mesh_geodesic::{
    dijkstra, exact_distance, trace_path, DijkstraOptions, ExactOptions, FastMarching, FmmOptions, FmmUpdate,
    HeatFarField, HeatGeodesics, HeatOptions, HeatStatus, LaplacianKind, SurfacePoint, TraceOptions,
};
use mesh_io::MeshView;
use mesh_kernel::VertexId;
use serde::Serialize;

use crate::choice::choice;
use crate::input::InputArgs;
use crate::output::{binary_ply, check_folder, check_output, finite, print_json, write_mesh, CliResult};

/// Arguments of `mesh geodesic`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub(crate) input: InputArgs,
    /// Source vertices, comma separated (e.g. 0,17,42).
    #[arg(long, value_name = "V[,V...]", value_delimiter = ',', required = true)]
    source: Vec<u32>,
    /// heat, fmm, dijkstra or exact (exact polyhedral geodesics: oriented
    /// manifolds without zero-area faces, slower; refused with a message
    /// otherwise).
    #[arg(long, default_value_t = Method::Heat, value_parser = choice::<Method>(Method::ALL.map(Method::name)))]
    method: Method,
    /// Output PLY file: positions as double, per-vertex double `distance`.
    #[arg(long, value_name = "OUT.ply")]
    out: PathBuf,
    /// Trace the path from this vertex back to the nearest source.
    #[arg(long, value_name = "V", requires = "path_out")]
    path_from: Option<u32>,
    /// Where to write the traced path (OBJ polyline).
    #[arg(long, value_name = "PATH.obj", requires = "path_from")]
    path_out: Option<PathBuf>,
    /// Heat method: time step t = m h^2 (h the mean edge length).
    #[arg(long, value_name = "M", default_value_t = 1.0)]
    time_factor: f64,
    /// Heat method: Laplacian of the intrinsic Delaunay triangulation
    /// (intrinsic, robust on bad triangles) or of the mesh (cotan).
    #[arg(long, default_value = "intrinsic")]
    laplacian: String,
    /// Heat method: what computes the distance where the heat flow is below
    /// what double precision resolves (about 1400 mean edge lengths from the
    /// sources): fmm (Fast Marching from the resolved part), restart
    /// (restarted heat flows) or none (flag the vertices `unresolved`).
    #[arg(long, default_value_t = HeatFarField::default(),
          value_parser = choice::<HeatFarField>(HeatFarField::ALL.map(HeatFarField::name)))]
    far_field: HeatFarField,
    /// Fast Marching local update: curved (default), point-source or
    /// plane-wave (eq. 2.34).
    #[arg(long, default_value_t = FmmUpdate::default(),
          value_parser = choice::<FmmUpdate>(FmmUpdate::ALL.map(FmmUpdate::name)))]
    fmm_update: FmmUpdate,
    /// Print a JSON summary instead of text.
    #[arg(long)]
    json: bool,
    /// Allow writing over the input file.
    #[arg(long)]
    force: bool,
}

/// The distance a `mesh geodesic` run computes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Method {
    /// The heat method.
    Heat,
    /// Fast Marching.
    Fmm,
    /// Dijkstra on the edges.
    Dijkstra,
    /// Exact polyhedral geodesics.
    Exact,
}

impl Method {
    /// Every method, in the order `--help` lists them.
    const ALL: [Self; 4] = [Self::Heat, Self::Fmm, Self::Dijkstra, Self::Exact];

    /// The name on the command line.
    fn name(self) -> &'static str {
        match self {
            Self::Heat => "heat",
            Self::Fmm => "fmm",
            Self::Dijkstra => "dijkstra",
            Self::Exact => "exact",
        }
    }
}

mesh_kernel::named_choice!(Method, "method", MeshError);

/// Everything `mesh geodesic --json` prints.
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    /// The input (file or shape).
    pub input: String,
    /// The written PLY file.
    pub output: String,
    /// Number of vertices.
    pub vertices: usize,
    /// The method.
    pub method: String,
    /// The sources.
    pub sources: Vec<u32>,
    /// Largest finite distance (`null` when only sources are reached).
    pub max_distance: Option<f64>,
    /// Vertices reached (finite distance).
    pub reached: usize,
    /// Vertices no source reaches (+infinity).
    pub unreachable: usize,
    /// The heat method's far field, for `--method heat`.
    pub heat: Option<HeatSummary>,
    /// The traced path, if asked for.
    pub path: Option<PathSummary>,
    /// Wall times in milliseconds.
    pub timings_ms: Timings,
}

/// Where the heat flow was not resolved (beyond about 1400 mean edge
/// lengths from the sources, or negative).
#[derive(Debug, Clone, Serialize)]
pub struct HeatSummary {
    /// The continuation chosen with `--far-field`.
    pub far_field: String,
    /// Vertices whose distance was continued (PLY field `far_field` = 1).
    pub far_field_vertices: usize,
    /// Vertices whose distance is not trustworthy (PLY field
    /// `unresolved` = 1): only with `--far-field none`, or past the
    /// restart limit.
    pub unresolved_vertices: usize,
}

/// The traced path.
#[derive(Debug, Clone, Serialize)]
pub struct PathSummary {
    /// Start vertex.
    pub from: u32,
    /// Source reached.
    pub to: u32,
    /// Length of the polyline.
    pub length: f64,
    /// Distance at the start according to the field.
    pub field_distance: Option<f64>,
    /// Number of points.
    pub points: usize,
    /// Segments that had to follow edges (no descent).
    pub fallback_edges: usize,
    /// The written OBJ file.
    pub output: String,
}

/// Wall times in milliseconds.
#[derive(Debug, Clone, Serialize)]
pub struct Timings {
    /// Preprocessing (factorization, stencils); 0 for Dijkstra and exact.
    pub precompute: f64,
    /// The distance query itself.
    pub solve: f64,
    /// Path tracing.
    pub trace: Option<f64>,
}

fn ms(start: Instant) -> f64 {
    start.elapsed().as_secs_f64() * 1e3
}

/// A distance field, the heat method's per-vertex status, and the
/// (precompute, solve) times in milliseconds.
struct Field {
    distance: Vec<f64>,
    status: Option<Vec<HeatStatus>>,
    precompute: f64,
    solve: f64,
}

impl Field {
    fn plain(distance: Vec<f64>, precompute: f64, solve: f64) -> Self {
        Self { distance, status: None, precompute, solve }
    }
}

/// The distance field of the chosen method.
fn distance(args: &Args, mesh: &mesh_kernel::TriMesh, sources: &[VertexId]) -> CliResult<Field> {
    match args.method {
        Method::Heat => {
            let laplacian = match args.laplacian.as_str() {
                "intrinsic" => LaplacianKind::IntrinsicDelaunay,
                "cotan" => LaplacianKind::Cotan,
                other => return Err(format!("unknown --laplacian `{other}`; known: intrinsic, cotan").into()),
            };
            let far_field = args.far_field;
            let opts = HeatOptions { time_factor: args.time_factor, laplacian, far_field, ..Default::default() };
            let start = Instant::now();
            let heat = HeatGeodesics::new(mesh, &opts)?;
            let precompute = ms(start);
            let start = Instant::now();
            let d = heat.solve(sources)?;
            Ok(Field { distance: d.distance, status: Some(d.status), precompute, solve: ms(start) })
        }
        Method::Fmm => {
            let update = args.fmm_update;
            let start = Instant::now();
            let fmm = FastMarching::new(mesh, &FmmOptions { update, ..Default::default() })?;
            let pre = ms(start);
            let start = Instant::now();
            let d = fmm.distance(sources)?;
            Ok(Field::plain(d, pre, ms(start)))
        }
        Method::Dijkstra => {
            let start = Instant::now();
            let d = dijkstra(mesh, sources, &DijkstraOptions::default())?.distance;
            Ok(Field::plain(d, 0.0, ms(start)))
        }
        Method::Exact => {
            let start = Instant::now();
            let d = exact_distance(mesh, sources, &ExactOptions::default())?;
            Ok(Field::plain(d, 0.0, ms(start)))
        }
    }
}

/// Runs `mesh geodesic`.
pub fn run(args: &Args) -> CliResult<()> {
    check_output(&args.out, args.input.path(), args.force)?;
    if let Some(p) = &args.path_out {
        check_output(p, args.input.path(), args.force)?;
    }
    let data = args.input.load()?;
    let mesh = &data.mesh;
    let n = mesh.vertex_count();
    let sources: Vec<VertexId> = args.source.iter().map(|&s| VertexId(s)).collect();
    if let Some(&bad) = args.source.iter().find(|&&s| s as usize >= n) {
        return Err(format!("--source {bad} is not a vertex (the mesh has {n})").into());
    }
    let field = distance(args, mesh, &sources)?;
    let d = &field.distance;

    check_folder(&args.out)?;
    let mut view = MeshView::new(mesh).with_scalar("distance", d);
    let flag =
        |which: HeatStatus| -> Vec<i64> { field.status.iter().flatten().map(|s| i64::from(*s == which)).collect() };
    let (far_field, unresolved) = (flag(HeatStatus::FarField), flag(HeatStatus::Unresolved));
    if field.status.is_some() {
        view = view.with_label("far_field", &far_field).with_label("unresolved", &unresolved);
    }
    write_mesh(&args.out, view, &binary_ply())?;
    let heat = field.status.as_ref().map(|_| HeatSummary {
        far_field: args.far_field.to_string(),
        far_field_vertices: far_field.iter().filter(|x| **x > 0).count(),
        unresolved_vertices: unresolved.iter().filter(|x| **x > 0).count(),
    });

    let (path, trace_ms) = match (args.path_from, &args.path_out) {
        (Some(from), Some(out)) => {
            let start_point = SurfacePoint::at_vertex(mesh, VertexId(from))
                .ok_or_else(|| format!("--path-from {from} is not a vertex of any face"))?;
            let start = Instant::now();
            let path = trace_path(mesh, d, &sources, start_point, &TraceOptions::default())?;
            let t = ms(start);
            check_folder(out)?;
            mesh_io::write_polylines(out, &[&path.positions])?;
            let summary = PathSummary {
                from,
                to: path.source.0,
                length: path.length,
                field_distance: finite(d[from as usize]),
                points: path.points.len(),
                fallback_edges: path.fallback_edges,
                output: out.display().to_string(),
            };
            (Some(summary), Some(t))
        }
        _ => (None, None),
    };

    let reached = d.iter().filter(|x| x.is_finite()).count();
    let max = d.iter().copied().filter(|x| x.is_finite()).fold(0.0f64, f64::max);
    let summary = Summary {
        input: args.input.describe(),
        output: args.out.display().to_string(),
        vertices: n,
        method: args.method.to_string(),
        sources: args.source.clone(),
        max_distance: (reached > 0).then_some(max),
        reached,
        unreachable: n - reached,
        heat,
        path,
        timings_ms: Timings { precompute: field.precompute, solve: field.solve, trace: trace_ms },
    };
    if args.json {
        return print_json(&summary);
    }
    print_text(&summary);
    Ok(())
}

fn print_text(s: &Summary) {
    println!("mesh: {} ({} vertices)", s.input, s.vertices);
    println!("  method             {} from {:?}", s.method, s.sources);
    match s.max_distance {
        Some(m) => println!("  max distance       {m:.6}"),
        None => println!("  max distance       n/a"),
    }
    println!("  reached            {} vertices, {} unreachable (+inf)", s.reached, s.unreachable);
    if let Some(h) = &s.heat {
        println!(
            "  heat far field     {}: {} vertices continued, {} unresolved",
            h.far_field, h.far_field_vertices, h.unresolved_vertices
        );
    }
    if let Some(p) = &s.path {
        println!(
            "  path               v{} -> v{}: length {:.6} (field {}), {} points, {} edge fallback segments",
            p.from,
            p.to,
            p.length,
            p.field_distance.map_or("n/a".to_owned(), |d| format!("{d:.6}")),
            p.points,
            p.fallback_edges
        );
        println!("  wrote              {}", p.output);
    }
    let t = &s.timings_ms;
    print!("  time (ms)          precompute {:.2}, solve {:.2}", t.precompute, t.solve);
    match t.trace {
        Some(tr) => println!(", trace {tr:.2}"),
        None => println!(),
    }
    println!("  wrote              {}", s.output);
}

impl Args {
    /// The library options set from flags, for [`crate::errors::translate`].
    pub fn given(&self) -> Vec<(&'static str, String)> {
        use crate::errors::{flag, number};
        vec![
            ("laplacian", flag("--laplacian", &self.laplacian)),
            ("time_factor", flag("--time-factor", number(self.time_factor))),
            ("far_field", flag("--far-field", self.far_field)),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(extra: &[&str]) -> Args {
        crate::commands::parse_args("geodesic", extra)
    }

    #[test]
    fn every_method_on_the_sphere() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("d.ply");
        let path = dir.path().join("p.obj");
        let (out, path) = (out.to_str().unwrap(), path.to_str().unwrap());
        for method in ["heat", "fmm", "dijkstra", "exact"] {
            let a = args(&[
                "--shape",
                "icosphere",
                "--res",
                "3",
                "--source",
                "0",
                "--method",
                method,
                "--out",
                out,
                "--path-from",
                "300",
                "--path-out",
                path,
                "--json",
            ]);
            run(&a).unwrap_or_else(|e| panic!("{method}: {e}"));
            let data = mesh_io::read(out).unwrap();
            let d = data.scalar("distance").unwrap();
            let p0 = data.mesh.positions()[0];
            for (p, x) in data.mesh.positions().iter().zip(d) {
                let truth = p.dot(p0).clamp(-1.0, 1.0).acos();
                let tolerance = if method == "dijkstra" { 0.25 } else { 0.06 };
                assert!((x - truth).abs() < tolerance, "{method}: {x} vs {truth}");
            }
            let text = std::fs::read_to_string(path).unwrap();
            assert!(text.lines().any(|l| l.starts_with("l ")), "{method}: no polyline");
        }
    }

    #[test]
    fn several_sources_and_unreachable_vertices() {
        let dir = tempfile::tempdir().unwrap();
        let input = dir.path().join("two.off");
        // Two separate triangles: the second is unreachable.
        std::fs::write(&input, "OFF\n6 2 0\n0 0 0\n1 0 0\n0 1 0\n5 0 0\n6 0 0\n5 1 0\n3 0 1 2\n3 3 4 5\n").unwrap();
        let out = dir.path().join("d.ply");
        for method in ["heat", "fmm", "dijkstra", "exact"] {
            let a =
                args(&[input.to_str().unwrap(), "--source", "0,1", "--method", method, "--out", out.to_str().unwrap()]);
            run(&a).unwrap();
            let d = mesh_io::read(&out).unwrap().scalar("distance").unwrap().to_vec();
            assert_eq!((d[0], d[1]), (0.0, 0.0));
            assert!(d[2].is_finite() && d[3..].iter().all(|x| *x == f64::INFINITY), "{method}: {d:?}");
        }
    }

    #[test]
    fn bad_arguments_are_errors() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("d.ply");
        let out = out.to_str().unwrap();
        for unknown in
            [&["--method", "magic"][..], &["--method", "fmm", "--fmm-update", "nope"], &["--far-field", "nope"]]
        {
            let mut v = vec!["--shape", "icosphere", "--source", "0", "--out", out];
            v.extend_from_slice(unknown);
            let message = crate::commands::try_parse_args::<Args>("geodesic", &v).expect_err("refused").to_string();
            assert!(message.contains(unknown[unknown.len() - 1]) && message.contains("possible values"), "{message}");
        }
        for bad in [
            &["--source", "99999"][..],
            &["--source", "0", "--laplacian", "nope"],
            &["--source", "0", "--time-factor=-1"],
        ] {
            let mut v = vec!["--shape", "icosphere", "--res", "1", "--out", out];
            v.extend_from_slice(bad);
            assert!(run(&args(&v)).is_err(), "{bad:?}");
        }
    }

    #[test]
    fn a_long_strip_has_no_plateau_and_says_where_it_continued() {
        // 6000 x 2 unit squares, source at a corner: beyond about 1400 mean
        // edge lengths the heat flow is not resolved.
        let dir = tempfile::tempdir().unwrap();
        let input = dir.path().join("strip.ply");
        let strip = mesh_kernel::shapes::grid(6000.0, 2.0, 6000, 2).unwrap();
        mesh_io::write(&input, MeshView::new(&strip), &binary_ply()).unwrap();
        let out = dir.path().join("d.ply");
        for far_field in ["fmm", "restart", "none"] {
            let (input, out) = (input.to_str().unwrap(), out.to_str().unwrap());
            run(&args(&[input, "--source", "0", "--far-field", far_field, "--out", out])).unwrap();
            let data = mesh_io::read(out).unwrap();
            let count = |name: &str| data.label(name).unwrap().iter().filter(|x| **x == 1).count();
            let d = data.scalar("distance").unwrap();
            let worst = d.iter().zip(strip.positions()).map(|(x, p)| (x - p.length()).abs()).fold(0.0, f64::max);
            match far_field {
                "fmm" => assert!(count("far_field") > 9000 && count("unresolved") == 0 && worst < 1.0, "{worst}"),
                "restart" => assert!(count("far_field") == 0 && count("unresolved") == 0 && worst < 1.0, "{worst}"),
                _ => assert!(count("far_field") == 0 && count("unresolved") > 9000 && worst > 1000.0),
            }
        }
    }

    #[test]
    fn shared_meshes_give_finite_distances() {
        let Some(dir) = mesh_testkit::shared_data() else { return };
        let tmp = tempfile::tempdir().unwrap();
        for file in ["cgal_degtri_sliding.off", "cgal_holes.off", "npm_bunny.obj"] {
            let out = tmp.path().join(format!("{file}.ply"));
            let input = dir.join(file);
            for method in ["heat", "fmm"] {
                let a = args(&[
                    input.to_str().unwrap(),
                    "--source",
                    "0",
                    "--method",
                    method,
                    "--out",
                    out.to_str().unwrap(),
                ]);
                run(&a).unwrap_or_else(|e| panic!("{file} {method}: {e}"));
                let d = mesh_io::read(&out).unwrap().scalar("distance").unwrap().to_vec();
                assert!(d.iter().all(|x| x.is_finite()), "{file} {method}");
            }
        }
    }
}
