//! `mesh param`: flattens any mesh onto the unit square (section 2.4 of the
//! "Digital Shape Processing" thesis chapter) as a texture atlas: the mesh is
//! cleaned into an oriented manifold when it is not one, each connected
//! component (or region of bounded size and distortion, `--max-chart-faces`,
//! `--max-area-distortion`) is cut into a disk and flattened with Tutte,
//! mean-value, harmonic, authalic, intrinsic, LSCM or ARAP weights, the
//! charts are scaled to their surface area and packed without overlap.
//! Writes an OBJ with texture coordinates (one `vt` per vertex when no vertex
//! has two, per corner otherwise), or a PLY that adds per-face attributes
//! (the chart of each face and its distortion, eq. 2.8-2.9), and prints
//! what cleaning did, the charts and their distortion (eq. 2.8-2.11).

use mesh_kernel::MeshError;
use std::path::PathBuf;
use std::time::Instant;

use mesh_io::MeshView;
use mesh_kernel::clean::CleanOptions;
use mesh_kernel::{FaceId, TriMesh};
use mesh_param::distortion::face_distortion;
use mesh_param::{atlas, Atlas, AtlasOptions, BoundaryMap, Chart, DistortionSummary, ParamMethod, Spacing};
use serde::Serialize;

use crate::choice::choice;
use crate::input::InputArgs;
use crate::output::{check_folder, check_output, finite, print_json, write_mesh, CliResult};

/// Arguments of `mesh param`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub(crate) input: InputArgs,
    /// Output file: OBJ with one `vt` per vertex (per corner along seams),
    /// or PLY (the UVs, plus per-face int labels `chart` and
    /// `distortion_flag` (0 measured, 1 flipped, 2 collapsed in the plane,
    /// 3 zero surface area) and double `angle_distortion` (sigma1 / sigma2)
    /// and `area_scale` (sigma1 sigma2 with the atlas's UV scale divided
    /// out; 1 where a face keeps its area), both 0 where not measured).
    #[arg(long, value_name = "OUT.obj|OUT.ply")]
    out: PathBuf,
    /// tutte, mean-value, harmonic, authalic, intrinsic, lscm or arap.
    #[arg(long, default_value_t = ParamMethod::MeanValue,
          value_parser = choice::<ParamMethod>(ParamMethod::ALL.map(|m| m.name())))]
    method: ParamMethod,
    /// Weight of the conformal energy (intrinsic only).
    #[arg(long, value_name = "L", default_value_t = 0.5)]
    lambda: f64,
    /// Weight of the authalic energy (intrinsic only).
    #[arg(long, value_name = "M", default_value_t = 0.5)]
    mu: f64,
    /// Boundary of each chart for the fixed-boundary methods: circle or square.
    #[arg(long, default_value_t = BoundaryMap::default(),
          value_parser = choice::<BoundaryMap>(BoundaryMap::ALL.map(|b| b.name())))]
    boundary: BoundaryMap,
    /// Spacing of the boundary vertices on the circle: chord (3D edge
    /// lengths) or uniform.
    #[arg(long, default_value_t = Spacing::default(), value_parser = choice::<Spacing>(Spacing::ALL.map(Spacing::name)))]
    spacing: Spacing,
    /// Local/global iterations (arap only).
    #[arg(long, value_name = "N", default_value_t = 20)]
    iterations: usize,
    /// Gap between charts in the unit square.
    #[arg(long, value_name = "M", default_value_t = 1.0 / 256.0)]
    margin: f64,
    /// Split components of more faces into charts of about N faces
    /// (farthest-point regions); default: one chart per component.
    #[arg(long, value_name = "N")]
    max_chart_faces: Option<usize>,
    /// Split charts in two while their mean area distortion (area-weighted
    /// mean of max(r, 1/r)) exceeds D (at least 1); default: never.
    #[arg(long, value_name = "D")]
    max_area_distortion: Option<f64>,
    /// Repair the mesh first: auto (only when it is not an oriented
    /// manifold), always, or never (refuse such a mesh).
    #[arg(long, default_value_t = CleanMode::Auto, value_parser = choice::<CleanMode>(CleanMode::ALL.map(CleanMode::name)))]
    clean: CleanMode,
    /// Print a JSON summary instead of text.
    #[arg(long)]
    json: bool,
    /// Allow writing over the input file.
    #[arg(long)]
    force: bool,
}

/// When to clean the input.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum CleanMode {
    /// Only when the mesh is not an oriented manifold.
    Auto,
    /// Always.
    Always,
    /// Never: such a mesh is refused.
    Never,
}

impl CleanMode {
    /// Every mode, in the order `--help` lists them.
    pub(crate) const ALL: [Self; 3] = [Self::Auto, Self::Always, Self::Never];

    /// The name on the command line.
    pub(crate) fn name(self) -> &'static str {
        match self {
            Self::Auto => "auto",
            Self::Always => "always",
            Self::Never => "never",
        }
    }
}

mesh_kernel::named_choice!(CleanMode, "clean", MeshError);

/// What was done to make the input an oriented manifold.
#[derive(Debug, Clone, Serialize)]
pub struct Cleaning {
    /// Whether `mesh_kernel::clean` ran.
    pub applied: bool,
    /// Why it ran, or why not.
    pub reason: String,
    /// What it changed, when it ran.
    pub changes: Option<super::clean::Summary>,
}

/// Distortion totals (eq. 2.8-2.11) as printed, non-finite values as null.
#[derive(Debug, Clone, Serialize)]
pub struct Distortion {
    /// Surface-area-weighted mean of sigma1 / sigma2.
    pub angle_distortion_mean: Option<f64>,
    /// Largest sigma1 / sigma2.
    pub angle_distortion_max: Option<f64>,
    /// Area-weighted mean of max(r, 1/r), r = normalized area ratio.
    pub area_distortion_mean: Option<f64>,
    /// Largest max(r, 1/r).
    pub area_distortion_max: Option<f64>,
    /// Faces whose parameter triangle is clockwise (and not collapsed).
    pub flipped_faces: usize,
    /// Faces whose parameter triangle has zero area (twice its area at most
    /// 1e-12 times its longest side squared).
    pub collapsed_faces: usize,
    /// Faces of zero surface area (weighted uniformly, left out of the means).
    pub degenerate_faces: usize,
    /// Dirichlet energy / surface area (1 iff conformal, eq. 2.11).
    pub dirichlet_area_ratio: Option<f64>,
    /// The parameter boundaries do not intersect themselves or each other.
    pub boundary_simple: bool,
    /// No flipped or collapsed face and simple boundaries.
    pub bijective: bool,
}

impl From<&DistortionSummary> for Distortion {
    fn from(s: &DistortionSummary) -> Self {
        Self {
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
        }
    }
}

/// One chart as printed.
#[derive(Debug, Clone, Serialize)]
pub struct ChartSummary {
    /// Connected component of the (cleaned) mesh.
    pub component: usize,
    /// Faces of the chart.
    pub faces: usize,
    /// Vertices of the chart (seam vertices once per side).
    pub vertices: usize,
    /// Genus of the component.
    pub genus: u64,
    /// Boundary loops of the component.
    pub boundary_loops: usize,
    /// Edges cut open to make it a disk.
    pub seam_edges: usize,
    /// The method used, or `faces-apart`.
    pub layout: String,
    /// Why the chosen method was not used, when it was not.
    pub fallback: Option<String>,
    /// The component has no surface area.
    pub zero_area: bool,
    /// Surface area of the component.
    pub surface_area: f64,
    /// The chart's box in the unit square: [min u, min v, max u, max v].
    pub rect: [f64; 4],
    /// Distortion of the chart.
    #[serde(flatten)]
    pub distortion: Distortion,
}

impl From<&Chart> for ChartSummary {
    fn from(c: &Chart) -> Self {
        Self {
            component: c.component,
            faces: c.faces.len(),
            vertices: c.vertices.len(),
            genus: c.topology.genus,
            boundary_loops: c.topology.boundary_loops,
            seam_edges: c.seam.len(),
            layout: c.layout.to_string(),
            fallback: c.fallback.clone(),
            zero_area: c.zero_area,
            surface_area: c.surface_area,
            rect: [c.rect.min.x, c.rect.min.y, c.rect.max.x, c.rect.max.y],
            distortion: Distortion::from(&c.distortion),
        }
    }
}

/// Everything `mesh param --json` prints (and `mesh report`'s
/// parameterization section).
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    /// The input (file or shape).
    pub input: String,
    /// The written OBJ file.
    pub output: String,
    /// Number of vertices of the input.
    pub vertices: usize,
    /// Number of faces of the input.
    pub faces: usize,
    /// What cleaning did (the OBJ holds the cleaned mesh).
    pub cleaning: Cleaning,
    /// The method.
    pub method: String,
    /// Number of charts (one per connected component).
    pub charts: usize,
    /// Charts not flattened with the chosen method.
    pub fallback_charts: usize,
    /// Charts laid out face by face (the last resort).
    pub faces_apart_charts: usize,
    /// Charts without surface area, sized by their extent.
    pub zero_area_charts: usize,
    /// Edges cut open, over all charts.
    pub seam_edges: usize,
    /// Whether UVs are written per corner (some vertex has several).
    pub per_corner: bool,
    /// UV units per unit of surface length, the same for every chart.
    pub scale: f64,
    /// Gap between charts in the unit square.
    pub margin: f64,
    /// Parameter area over the unit square's area.
    pub coverage: f64,
    /// Distortion over all faces (area distortion relative to the
    /// atlas-wide area ratio).
    #[serde(flatten)]
    pub distortion: Distortion,
    /// Collapsed faces whose surface triangle has zero area too.
    pub collapsed_zero_area_faces: usize,
    /// Wall time of cleaning, cutting, flattening, packing and distortion, ms.
    pub time_ms: f64,
    /// Every chart, largest surface area first.
    pub chart_list: Vec<ChartSummary>,
}

/// The options from the command line.
fn options(args: &Args) -> CliResult<AtlasOptions> {
    let method = match args.method {
        ParamMethod::Intrinsic { .. } => ParamMethod::Intrinsic { lambda: args.lambda, mu: args.mu },
        ParamMethod::Arap { .. } => ParamMethod::Arap { iterations: args.iterations },
        other => other,
    };
    let boundary = match &args.boundary {
        BoundaryMap::Circle(_) => BoundaryMap::Circle(args.spacing),
        other => other.clone(),
    };
    Ok(AtlasOptions {
        method,
        boundary,
        margin: args.margin,
        max_chart_faces: args.max_chart_faces,
        max_area_distortion: args.max_area_distortion,
    })
}

/// Cleans `mesh` as `mode` says so that it becomes an oriented manifold
/// (`mesh_kernel::clean` with `manifold`: fins detached, unorientable gluing
/// cut, one vertex per fan, then duplicate, zero-area and unreferenced
/// elements dropped), and says what was done.
pub(crate) fn prepare(mesh: TriMesh, mode: CleanMode) -> CliResult<(TriMesh, Cleaning)> {
    let defect = mesh.manifold_connectivity().err().map(|e| e.to_string());
    let reason = match (mode, defect) {
        (CleanMode::Never, Some(d)) => return Err(format!("{d} (--clean never)").into()),
        (CleanMode::Never, None) => "--clean never".to_owned(),
        (CleanMode::Auto, None) => "an oriented manifold already".to_owned(),
        (CleanMode::Auto, Some(d)) => d,
        (CleanMode::Always, d) => d.unwrap_or_else(|| "--clean always".to_owned()),
    };
    if mode == CleanMode::Never || reason == "an oriented manifold already" {
        return Ok((mesh, Cleaning { applied: false, reason, changes: None }));
    }
    let (cleaned, report) = mesh.cleaned(&CleanOptions { manifold: true, ..CleanOptions::default() })?;
    let changes = super::clean::Summary::new(&report, &cleaned);
    if let Err(e) = cleaned.manifold_connectivity() {
        return Err(format!("still not an oriented manifold after cleaning: {e}").into());
    }
    Ok((cleaned, Cleaning { applied: true, reason, changes: Some(changes) }))
}

/// The atlas's summary (the chart list sorted by surface area), with the
/// input and output left empty for the caller.
pub(crate) fn summarize(
    cleaning: Cleaning,
    method: &ParamMethod,
    atlas: &Atlas,
    per_corner: bool,
    time_ms: f64,
) -> Summary {
    let s = &atlas.summary;
    let mut chart_list: Vec<ChartSummary> = atlas.charts.iter().map(ChartSummary::from).collect();
    chart_list.sort_by(|a, b| b.surface_area.total_cmp(&a.surface_area).then(a.component.cmp(&b.component)));
    Summary {
        input: String::new(),
        output: String::new(),
        vertices: 0,
        faces: 0,
        cleaning,
        method: method.name().to_owned(),
        charts: s.charts,
        fallback_charts: s.fallback_charts,
        faces_apart_charts: s.faces_apart_charts,
        zero_area_charts: s.zero_area_charts,
        seam_edges: atlas.charts.iter().map(|c| c.seam.len()).sum(),
        per_corner,
        scale: atlas.scale,
        margin: atlas.margin,
        coverage: s.coverage,
        distortion: Distortion::from(&s.distortion),
        collapsed_zero_area_faces: s.collapsed_zero_area_faces,
        time_ms,
        chart_list,
    }
}

/// Does the work of `mesh param` but the printing.
fn execute(args: &Args) -> CliResult<Summary> {
    let options = options(args)?;
    let mode = args.clean;
    check_output(&args.out, args.input.path(), args.force)?;
    let data = args.input.load()?;
    let (vertices, faces) = (data.mesh.vertex_count(), data.mesh.face_count());
    let start = Instant::now();
    let (mesh, cleaning) = prepare(data.mesh, mode)?;
    let a = atlas(&mesh, &options)?;
    let time_ms = start.elapsed().as_secs_f64() * 1e3;
    let vertex_uvs = a.vertex_uvs(mesh.vertex_count());
    let mut view = match &vertex_uvs {
        Some(uv) => MeshView::new(&mesh).with_uvs(uv),
        None => MeshView::new(&mesh).with_corner_uvs(&a.corner_uvs),
    };
    let ply = mesh_io::Format::from_path(&args.out).ok() == Some(mesh_io::Format::Ply);
    let per_face = FaceFields::new(&mesh, &a);
    if ply {
        view = view
            .with_face_label("chart", &per_face.chart)
            .with_face_label("distortion_flag", &per_face.flag)
            .with_face_scalar("angle_distortion", &per_face.angle)
            .with_face_scalar("area_scale", &per_face.area);
    }
    check_folder(&args.out)?;
    let format = if ply { mesh_io::Format::Ply } else { mesh_io::Format::Obj };
    write_mesh(&args.out, view, &mesh_io::WriteOptions { format: Some(format), ..Default::default() })?;
    Ok(Summary {
        input: args.input.describe(),
        output: args.out.display().to_string(),
        vertices,
        faces,
        ..summarize(cleaning, &options.method, &a, vertex_uvs.is_none(), time_ms)
    })
}

/// Per-face values of an atlas as written to PLY.
struct FaceFields {
    /// The chart of each face (-1 for a face in none).
    chart: Vec<i64>,
    /// 0 measured, 1 flipped, 2 collapsed in the plane, 3 zero surface area.
    flag: Vec<i64>,
    /// sigma1 / sigma2 (eq. 2.8-2.9), 0 where not measured.
    angle: Vec<f64>,
    /// sigma1 sigma2 times the atlas's scale squared, 0 where not measured.
    area: Vec<f64>,
}

impl FaceFields {
    /// Per-face distortion of the atlas's corner UVs on `mesh`
    /// (`mesh_param::distortion::face_distortion` on each face). O(F).
    fn new(mesh: &TriMesh, atlas: &Atlas) -> Self {
        let n = mesh.face_count();
        let mut out = Self { chart: Vec::with_capacity(n), flag: vec![0; n], angle: vec![0.0; n], area: vec![0.0; n] };
        out.chart.extend(atlas.face_chart.iter().map(|&c| if c == u32::MAX { -1 } else { i64::from(c) }));
        let square = atlas.scale * atlas.scale;
        for (f, q) in atlas.corner_uvs.iter().enumerate() {
            let d = face_distortion(mesh.triangle(FaceId::new(f)), *q);
            out.flag[f] = match (d.degenerate, d.collapsed, d.uv_signed_area < 0.0) {
                (true, _, _) => 3,
                (false, true, _) => 2,
                (false, false, true) => 1,
                (false, false, false) => 0,
            };
            if out.flag[f] <= 1 && d.angle_distortion.is_finite() && (d.area_scale * square).is_finite() {
                (out.angle[f], out.area[f]) = (d.angle_distortion, d.area_scale * square);
            } else {
                out.flag[f] = out.flag[f].max(2);
            }
        }
        out
    }
}

/// Runs `mesh param`.
pub fn run(args: &Args) -> CliResult<()> {
    let summary = execute(args)?;
    if args.json {
        return print_json(&summary);
    }
    print_text(&summary);
    Ok(())
}

/// Mean area distortion above which the text summary suggests smaller charts.
const DISTORTION_HINT: f64 = 10.0;

/// How many charts the text summary lists.
const LISTED_CHARTS: usize = 10;

fn print_text(s: &Summary) {
    let show = |x: Option<f64>| x.map_or("n/a".to_owned(), |v| format!("{v:.4}"));
    println!("mesh: {} ({} vertices, {} faces)", s.input, s.vertices, s.faces);
    // The first clause of the reason: the full defect list is in --json.
    let reason = s.cleaning.reason.split(':').next().unwrap_or_default();
    match &s.cleaning.changes {
        Some(changes) => {
            let value = serde_json::to_value(changes).unwrap_or_default();
            let fields = value.as_object();
            let count = |k: &str| fields.and_then(|m| m.get(k)).and_then(|v| v.as_u64()).unwrap_or(0);
            let counts: Vec<String> = fields
                .into_iter()
                .flatten()
                .filter(|(k, v)| !["vertices", "faces"].contains(&k.as_str()) && v.as_u64().is_some_and(|n| n > 0))
                .map(|(k, v)| format!("{k} {v}"))
                .collect();
            println!("  cleaning           {} ({reason})", counts.join(", "));
            println!("  cleaned mesh       {} vertices, {} faces", count("vertices"), count("faces"));
        }
        None => println!("  cleaning           none ({reason})"),
    }
    println!("  method             {}", s.method);
    println!(
        "  charts             {} ({} fallback, {} faces apart, {} zero-area), {} seam edges, UVs per {}",
        s.charts,
        s.fallback_charts,
        s.faces_apart_charts,
        s.zero_area_charts,
        s.seam_edges,
        if s.per_corner { "corner" } else { "vertex" }
    );
    println!(
        "  packing            scale {:.4e} per unit length, margin {:.4}, coverage {:.3}",
        s.scale, s.margin, s.coverage
    );
    let d = &s.distortion;
    println!("  angle distortion   mean {}, max {}", show(d.angle_distortion_mean), show(d.angle_distortion_max));
    println!("  area distortion    mean {}, max {}", show(d.area_distortion_mean), show(d.area_distortion_max));
    println!("  dirichlet / area   {}", show(d.dirichlet_area_ratio));
    println!(
        "  faces              {} flipped, {} collapsed ({} of zero surface area), {} degenerate",
        d.flipped_faces, d.collapsed_faces, s.collapsed_zero_area_faces, d.degenerate_faces
    );
    println!("  bijective          {} (boundaries simple: {})", d.bijective, d.boundary_simple);
    if d.area_distortion_mean.is_none_or(|x| x > DISTORTION_HINT) {
        println!("  hint               smaller charts distort less: --max-chart-faces 5000 --max-area-distortion 2");
    }
    println!("  largest charts     component, faces, genus, loops, seam, layout, angle mean, area mean, flipped");
    for c in s.chart_list.iter().take(LISTED_CHARTS) {
        let d = &c.distortion;
        println!(
            "    {:>6} {:>8} {:>4} {:>4} {:>6}  {:<10} {:>8} {:>8} {:>6}{}",
            c.component,
            c.faces,
            c.genus,
            c.boundary_loops,
            c.seam_edges,
            c.layout,
            show(d.angle_distortion_mean),
            show(d.area_distortion_mean),
            d.flipped_faces,
            c.fallback.as_ref().map_or(String::new(), |r| format!("  (fallback: {r})"))
        );
    }
    if s.chart_list.len() > LISTED_CHARTS {
        println!("    ... {} more (--json lists every chart)", s.chart_list.len() - LISTED_CHARTS);
    }
    println!("  time (ms)          {:.2}", s.time_ms);
    println!("  wrote              {}", s.output);
}

impl Args {
    /// The library options set from flags, for [`crate::errors::translate`].
    /// The boundary counts as given only when it is not the default circle
    /// (which no mesh makes fail by the user's choice).
    pub fn given(&self) -> Vec<(&'static str, String)> {
        use crate::errors::{flag, number};
        let mut given = vec![
            ("method", flag("--method", self.method)),
            ("margin", flag("--margin", number(self.margin))),
            ("iterations", flag("--iterations", self.iterations)),
            ("lambda/mu", format!("--lambda {} --mu {}", number(self.lambda), number(self.mu))),
        ];
        if !matches!(self.boundary, BoundaryMap::Circle(_)) {
            given.push(("boundary", flag("--boundary", &self.boundary)));
        }
        if let Some(n) = self.max_chart_faces {
            given.push(("max_chart_faces", flag("--max-chart-faces", n)));
        }
        if let Some(d) = self.max_area_distortion {
            given.push(("max_area_distortion", flag("--max-area-distortion", number(d))));
        }
        given
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use mesh_kernel::glam::DVec2;

    fn args(extra: &[&str]) -> Args {
        crate::commands::parse_args("param", extra)
    }

    /// The UVs of every face corner of a written OBJ.
    fn corners(data: &mesh_io::MeshData) -> Vec<[DVec2; 3]> {
        match (&data.uvs, &data.corner_uvs) {
            (_, Some(c)) => c.clone(),
            (Some(u), None) => data.mesh.faces().iter().map(|t| t.map(|v| u[v as usize])).collect(),
            _ => Vec::new(),
        }
    }

    #[test]
    fn disk_gets_one_uv_per_vertex() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("d.obj");
        for method in ParamMethod::ALL.map(|m| m.name()) {
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
            assert!(uvs.iter().all(|q| q.is_finite() && q.min_element() >= 0.0 && q.max_element() <= 1.0));
        }
        let square = ["--shape", "grid", "--res", "4", "--boundary", "square", "--method", "harmonic", "--margin", "0"];
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
    fn ply_output_has_per_face_charts_and_distortion() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("a.ply");
        let v = ["--shape", "torus", "--res", "8", "--method", "tutte", "--max-chart-faces", "40"];
        let mut v = v.to_vec();
        v.extend(["--json", "--out", out.to_str().unwrap()]);
        let summary = execute(&args(&v)).unwrap();
        let data = mesh_io::read(&out).unwrap();
        let nf = data.mesh.face_count();
        let chart = data.face_label("chart").unwrap();
        assert_eq!(chart.len(), nf);
        let charts: std::collections::BTreeSet<i64> = chart.iter().copied().collect();
        assert_eq!(charts.len(), summary.charts, "every chart has faces, no face is in none");
        assert!(charts.iter().all(|&c| c >= 0));
        let (flag, angle, area) = (
            data.face_label("distortion_flag").unwrap(),
            data.face_scalar("angle_distortion").unwrap(),
            data.face_scalar("area_scale").unwrap(),
        );
        // Tutte maps are bijective: nothing flipped or collapsed on a torus of
        // equal-area-ish faces, and every angle distortion is at least 1.
        assert!(flag.iter().all(|&f| f == 0), "{flag:?}");
        assert!(angle.iter().all(|&x| x >= 1.0 - 1e-12 && x.is_finite()));
        assert!(area.iter().all(|&x| x > 0.0 && x.is_finite()));
        // The area-weighted mean of the per-face angle distortion is the summary's.
        let areas = mesh_kernel::geometry::face_areas(&data.mesh);
        let mean = angle.iter().zip(&areas).map(|(a, w)| a * w).sum::<f64>() / areas.iter().sum::<f64>();
        let expected = summary.distortion.angle_distortion_mean.unwrap();
        assert!((mean - expected).abs() < 1e-9 * expected, "{mean} vs {expected}");
        // The same atlas as OBJ carries no per-face values and says nothing about them.
        let obj = dir.path().join("a.obj");
        v.truncate(v.len() - 1);
        v.push(obj.to_str().unwrap());
        execute(&args(&v)).unwrap();
        assert!(mesh_io::read(&obj).unwrap().face_labels.is_empty());
    }

    #[test]
    fn bad_options_are_errors() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("x.obj");
        let out = out.to_str().unwrap();
        for unknown in [
            &["--method", "magic"][..],
            &["--boundary", "hexagon"],
            &["--spacing", "random"],
            &["--clean", "sometimes"],
        ] {
            let mut v = vec!["--shape", "disk", "--out", out];
            v.extend_from_slice(unknown);
            let message = crate::commands::try_parse_args::<Args>("param", &v).expect_err("refused").to_string();
            assert!(message.contains(unknown[1]) && message.contains("possible values"), "{message}");
        }
        for bad in [
            &["--method", "intrinsic", "--lambda=-1"][..],
            &["--method", "arap", "--iterations", "100000"],
            &["--margin", "0.6"],
            &["--max-area-distortion", "0.9"],
            &["--max-chart-faces", "0"],
        ] {
            let mut v = vec!["--shape", "disk", "--res", "3", "--out", out];
            v.extend_from_slice(bad);
            assert!(run(&args(&v)).is_err(), "{bad:?}");
        }
    }

    /// The invariants of an atlas written to `out`: every face has finite
    /// UVs in [0, 1]^2, charts (faces grouped by `face_chart`) have disjoint
    /// boxes, and no face is flipped when `tutte`.
    fn check_atlas_file(out: &std::path::Path, summary: &Summary, tutte: bool) {
        let data = mesh_io::read(out).unwrap();
        let uv = corners(&data);
        assert_eq!(uv.len(), data.mesh.face_count());
        assert!(uv.iter().flatten().all(|q| q.is_finite() && q.min_element() >= 0.0 && q.max_element() <= 1.0));
        let rects: Vec<[f64; 4]> = summary.chart_list.iter().map(|c| c.rect).collect();
        for (i, a) in rects.iter().enumerate() {
            for b in &rects[i + 1..] {
                assert!(a[2] < b[0] || b[2] < a[0] || a[3] < b[1] || b[3] < a[1], "{a:?} meets {b:?}");
            }
        }
        if tutte {
            let flipped = uv.iter().filter(|q| (q[1] - q[0]).perp_dot(q[2] - q[0]) < 0.0).count();
            assert_eq!(flipped, 0);
            assert_eq!(summary.distortion.flipped_faces, 0);
        }
    }

    #[test]
    fn shared_meshes_get_atlases() {
        let Some(dir) = mesh_testkit::shared_data() else { return };
        let tmp = tempfile::tempdir().unwrap();
        let mut files: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|x| x != "md"))
            .collect();
        files.sort();
        for input in files {
            for method in ["tutte", "harmonic", "lscm"] {
                let out = tmp.path().join("out.obj");
                let a = args(&[input.to_str().unwrap(), "--method", method, "--out", out.to_str().unwrap()]);
                let s = execute(&a).unwrap_or_else(|e| panic!("{} {method}: {e}", input.display()));
                check_atlas_file(&out, &s, method == "tutte");
            }
        }
    }

    #[test]
    fn several_components_are_packed_apart() {
        let dir = tempfile::tempdir().unwrap();
        let input = dir.path().join("two.obj");
        let torus = mesh_kernel::shapes::torus(2.0, 0.5, 16, 8).unwrap();
        let sphere = mesh_kernel::shapes::icosphere(2).unwrap();
        let (mut p, mut f) = torus.into_parts();
        let n = p.len() as u32;
        p.extend(sphere.positions().iter().map(|q| *q + mesh_kernel::glam::DVec3::X * 5.0));
        f.extend(sphere.faces().iter().map(|t| t.map(|v| v + n)));
        mesh_io::write(&input, &TriMesh::new(p, f).unwrap(), &Default::default()).unwrap();
        let out = dir.path().join("two_uv.obj");
        for method in ["tutte", "harmonic", "lscm"] {
            run(&args(&[input.to_str().unwrap(), "--method", method, "--out", out.to_str().unwrap()])).unwrap();
            let data = mesh_io::read(&out).unwrap();
            let uv = corners(&data);
            assert!(uv.iter().flatten().all(|q| q.is_finite() && q.min_element() >= 0.0 && q.max_element() <= 1.0));
        }
    }
}
