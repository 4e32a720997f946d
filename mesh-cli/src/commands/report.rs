//! `mesh report`: the main job. Runs every analysis of the workspace on one
//! mesh and writes, into one folder, a JSON report and files a viewer opens
//! directly: `mesh.ply` (normals and every per-vertex field: curvatures,
//! geodesic distance, first harmonic, heat kernel signature), PNG pictures
//! of the fields, the texture atlas as `uv.obj`, the traced geodesic and
//! the feature edges as OBJ polylines.
//!
//! A section that does not apply to the mesh (a parameterization of a mesh
//! that cleaning cannot make manifold, wavelets without subdivision connectivity)
//! records why in the report instead of failing the whole run.

use std::path::{Path, PathBuf};
use std::time::Instant;

use mesh_io::MeshView;
use mesh_kernel::glam::DVec3;
use mesh_kernel::{geometry, operators, TriMesh, VertexId};
use serde_json::{json, Map, Value};

use super::info::Info;
use super::render::Up;
use crate::choice::choice;
use crate::input::InputArgs;
use crate::output::{check_output, finite, stats, write_json, write_mesh, CliResult};
use crate::render::{render_png, RenderOptions};

/// Arguments of `mesh report`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub(crate) input: InputArgs,
    /// Output folder (created if needed).
    #[arg(long, default_value = "out")]
    out: PathBuf,
    /// Dihedral angle, in degrees, above which an edge is a feature edge.
    #[arg(long, default_value_t = 30.0)]
    feature_angle: f64,
    /// The axis pointing up in the pictures: x, y, z, or auto (the file
    /// format's convention: y for OBJ, PLY, OFF and glTF, z for STL and for
    /// built-in shapes).
    #[arg(long, default_value_t = Up::Auto, value_parser = choice::<Up>(Up::ALL.map(Up::name)))]
    up: Up,
}

/// The caption of each field's picture: what it is and its unit, with L the
/// file's unit of length (a mesh file does not say which it is).
const CAPTIONS: &[(&str, &str)] = &[
    ("gaussian", "gaussian curvature K [1/L^2]"),
    ("mean", "mean curvature H [1/L]"),
    ("k1", "principal curvature k1 [1/L]"),
    ("k2", "principal curvature k2 [1/L]"),
    ("gaussian_discrete", "angle defect / area [1/L^2]"),
    ("mean_discrete", "cotan mean curvature / area [1/L]"),
    ("gaussian_integrated", "angle defect [rad]"),
    ("mean_integrated", "integrated mean curvature [L]"),
    ("distance", "geodesic distance [L]"),
    ("harmonic1", "first non-constant harmonic [1/L]"),
    ("hks", "heat kernel signature [1/L^2]"),
];

/// What the report collects: JSON sections, timings, per-vertex fields and
/// the files written.
struct Report<'a> {
    dir: PathBuf,
    input: Option<&'a Path>,
    picture: RenderOptions,
    sections: Map<String, Value>,
    timings_ms: Map<String, Value>,
    fields: Vec<(&'static str, Vec<f64>)>,
    files: Vec<String>,
    /// What a reader of the report must know: defects of the input, work
    /// done on a part of it, values flagged as untrustworthy.
    warnings: Vec<String>,
}

impl Report<'_> {
    fn time<T>(&mut self, name: &str, f: impl FnOnce() -> T) -> T {
        let t = Instant::now();
        let out = f();
        self.timings_ms.insert(name.into(), json!(t.elapsed().as_secs_f64() * 1e3));
        out
    }

    /// The path of an output file, recorded in the report.
    fn file(&mut self, name: &str) -> CliResult<PathBuf> {
        let path = self.dir.join(name);
        check_output(&path, self.input, false)?;
        self.files.push(name.to_owned());
        Ok(path)
    }

    /// Adds a section, or its error when the analysis does not apply.
    fn section(&mut self, name: &str, result: CliResult<Value>) {
        let value = result.unwrap_or_else(|e| json!({ "applicable": false, "reason": e.to_string() }));
        self.sections.insert(name.into(), value);
    }

    /// Records a warning for the top of `report.json`.
    fn warn(&mut self, warning: impl Into<String>) {
        self.warnings.push(warning.into());
    }

    /// Keeps a per-vertex field for `mesh.ply` and renders it, with a colour
    /// bar captioned from [`CAPTIONS`].
    fn field(&mut self, mesh: &TriMesh, name: &'static str, values: Vec<f64>) -> CliResult<()> {
        let png = self.file(&format!("{name}.png"))?;
        let caption = CAPTIONS.iter().find(|(n, _)| *n == name).map_or(name, |(_, c)| c);
        let picture = RenderOptions { title: Some(caption.to_owned()), ..self.picture.clone() };
        render_png(mesh, Some(&values), &png, &picture)?;
        self.fields.push((name, values));
        Ok(())
    }
}

/// Runs `mesh report`.
pub fn run(args: &Args) -> CliResult<()> {
    if !(args.feature_angle.is_finite() && (0.0..=180.0).contains(&args.feature_angle)) {
        return Err(format!("--feature-angle must be in [0, 180], got {}", args.feature_angle).into());
    }
    let picture = RenderOptions { up: args.up.axis(&args.input), ..RenderOptions::default() };
    std::fs::create_dir_all(&args.out).map_err(|e| format!("cannot create {}: {e}", args.out.display()))?;
    let mut report = Report {
        dir: args.out.clone(),
        input: args.input.path(),
        picture,
        sections: Map::new(),
        timings_ms: Map::new(),
        fields: Vec::new(),
        files: Vec::new(),
        warnings: Vec::new(),
    };
    let data = report.time("read", || args.input.load())?;
    let mesh = &data.mesh;
    let info = report.time("info", || Info::of(mesh));
    report.sections.insert("info".into(), serde_json::to_value(&info)?);
    input_warnings(&mut report, mesh, &info, &data.report);

    let operators = operators_section(&mut report, mesh, args.feature_angle);
    report.section("operators", operators);
    let curvature = curvature_section(&mut report, mesh);
    report.section("curvature", curvature);
    let geodesic = geodesic_section(&mut report, mesh);
    report.section("geodesic", geodesic);
    let param = param_section(&mut report, mesh);
    report.section("parameterization", param);
    let spectral = spectral_section(&mut report, mesh);
    report.section("spectral", spectral);
    let wavelet = wavelet_section(&mut report, mesh);
    report.section("wavelet", wavelet);

    let normals = geometry::vertex_normals(mesh, geometry::NormalWeighting::Area);
    let ply = report.file("mesh.ply")?;
    let mut view = MeshView::new(mesh).with_normals(&normals);
    for (name, values) in &report.fields {
        view = view.with_scalar(name, values);
    }
    write_mesh(&ply, view, &mesh_io::WriteOptions::default())?;
    let shaded = report.file("mesh.png")?;
    render_png(mesh, None, &shaded, &report.picture)?;

    let summary = json!({
        "input": args.input.describe(),
        "warnings": report.warnings,
        "sections": report.sections,
        "timings_ms": report.timings_ms,
        "fields": report.fields.iter().map(|(n, _)| *n).collect::<Vec<_>>(),
        "files": report.files,
    });
    let json_path = args.out.join("report.json");
    write_json(&json_path, &summary)?;
    println!("{}", crate::output::json_text(&summary, true)?);
    eprintln!("wrote {} and {} files in {}", json_path.display(), report.files.len(), args.out.display());
    Ok(())
}

/// What the input's defects mean for the analyses that follow.
fn input_warnings(report: &mut Report, mesh: &TriMesh, info: &Info, read: &mesh_io::ReadReport) {
    if !read.is_clean() {
        report.warn(format!("reading the file changed it: {read}"));
    }
    if info.coincident_vertices > 0 {
        let welded =
            mesh_kernel::clean::weld_vertices(mesh.positions(), mesh.faces(), 0.0).ok().map(|(p, mut f, _)| {
                f.retain(|[a, b, c]| a != b && b != c && a != c);
                mesh_kernel::connectivity::Connectivity::new(p.len(), &f).components().count
            });
        let joined = match welded {
            Some(after) if after < info.components => {
                format!("; welding them (`mesh clean`) joins the {} components into {after}", info.components)
            }
            _ => " (`mesh clean` welds them)".to_owned(),
        };
        report.warn(format!(
            "{} vertices sit exactly on another vertex without sharing its index: the surface is cut there{joined}",
            info.coincident_vertices
        ));
    }
    if info.components > 1 {
        report.warn(format!("{} connected components: distances do not cross between them", info.components));
    }
    if !info.manifold {
        report.warn(format!(
            "not an oriented manifold ({} non-manifold edges, {} non-manifold vertices, {} inconsistent edges): \
             the parameterization runs on a repaired copy (`mesh clean --manifold`), curvature flags the \
             vertices concerned",
            info.non_manifold_edges, info.non_manifold_vertices, info.inconsistent_edges
        ));
    }
    if info.degenerate_faces > 0 {
        report.warn(format!(
            "{} zero-area faces: cotangent weights are undefined there (intrinsic Delaunay operators are used \
             where it matters)",
            info.degenerate_faces
        ));
    }
    if info.duplicate_faces > 0 {
        report.warn(format!("{} duplicate faces", info.duplicate_faces));
    }
    if info.unreferenced_vertices > 0 {
        report.warn(format!("{} vertices belong to no face (their fields are empty)", info.unreferenced_vertices));
    }
}

/// Laplacian sanity figures and feature edges (chapter section 2.2.2).
fn operators_section(report: &mut Report, mesh: &TriMesh, feature_angle: f64) -> CliResult<Value> {
    let laplacian = report.time("cotan_laplacian", || operators::cotan_laplacian(mesh));
    let negative = laplacian.iter().filter(|(v, (i, j))| i != j && **v > 0.0).count() / 2;
    let mass = report.time("mass_voronoi", || operators::lumped_mass(mesh, operators::MassKind::MixedVoronoi));
    let features = report.time("feature_edges", || geometry::feature_edges(mesh, feature_angle.to_radians()));
    let conn = mesh.connectivity();
    let lines: Vec<[DVec3; 2]> =
        features.iter().map(|&e| conn.edge_vertices(e).map(|v: VertexId| mesh.position(v))).collect();
    mesh_io::write_polylines(report.file("feature_edges.obj")?, &lines)?;
    Ok(json!({
        "ran_on": "the mesh as read",
        "laplacian_nonzeros": laplacian.nnz(),
        "negative_cotan_weights": negative,
        "total_voronoi_area": mass.iter().sum::<f64>(),
        "feature_edges": features.len(),
        "feature_angle_degrees": feature_angle,
    }))
}

/// Pointwise Gaussian and mean curvature from the curvature tensor (eq.
/// 2.19-2.20, 2.27-2.31), the discrete values (eq. 2.25, 2.26) and their
/// integrals, with the vertices flagged where a value is not an estimate
/// (their values are 0).
fn curvature_section(report: &mut Report, mesh: &TriMesh) -> CliResult<Value> {
    use mesh_curvature::{flag_code, pointwise_curvature, FlagCounts, PointwiseOptions};
    let options = PointwiseOptions::default();
    let c = report.time("curvature", || pointwise_curvature(mesh, &options))?;
    let flagged = |counts: FlagCounts| {
        let by_reason: Map<String, Value> = counts.nonzero().map(|(f, n)| (f.name().to_owned(), json!(n))).collect();
        json!({ "total": counts.total(), "by_reason": by_reason })
    };
    let (tensor_flags, discrete_flags) = (c.flag_counts(), c.discrete_flag_counts());
    let two_pi_chi = std::f64::consts::TAU * mesh.connectivity().euler_characteristic() as f64;
    let section = json!({
        "gaussian_and_mean": "k1 k2 and (k1 + k2) / 2 from the curvature tensor (quartic fit over the 2-ring)",
        "discrete": "angle defect and cotangent formula divided by the mixed Voronoi area (not pointwise estimates on irregular meshes)",
        "ran_on": "the mesh as read: vertices on fins or duplicate faces are flagged non-manifold, not measured \
                   (`mesh clean --manifold` first measures them)",
        "statistics_over": "unflagged vertices",
        "gauss_bonnet_total": c.gauss_bonnet_total(),
        "two_pi_chi": two_pi_chi,
        "gaussian": stats(&c.gaussian, |i| c.flag[i].is_none()),
        "mean": stats(&c.mean, |i| c.flag[i].is_none()),
        "k1": stats(&c.tensor.k1, |i| c.flag[i].is_none()),
        "k2": stats(&c.tensor.k2, |i| c.flag[i].is_none()),
        "gaussian_discrete": stats(&c.gaussian_discrete, |i| c.flag_discrete[i].is_none()),
        "mean_discrete": stats(&c.mean_discrete, |i| c.flag_discrete[i].is_none()),
        "resolution_limit": options.resolution,
        "flagged": flagged(tensor_flags),
        "flagged_discrete": flagged(discrete_flags),
        "valid_vertices": c.tensor.status.iter().filter(|s| s.is_valid()).count(),
    });
    let codes = |flags: &[Option<mesh_curvature::CurvatureFlag>]| -> Vec<f64> {
        flags.iter().map(|f| f64::from(flag_code(*f))).collect()
    };
    let reasons = |counts: FlagCounts| -> String {
        counts.nonzero().map(|(f, n)| format!("{n} {f}")).collect::<Vec<_>>().join(", ")
    };
    if tensor_flags.total() > 0 {
        report.warn(format!(
            "curvature: {} vertices flagged ({}): their gaussian, mean, k1 and k2 are 0, not estimates \
             (`curvature_flag` in mesh.ply)",
            tensor_flags.total(),
            reasons(tensor_flags)
        ));
    }
    // Fields without a picture: the integrated values and the flags.
    report.fields.push(("gaussian_integrated", c.gaussian_integrated));
    report.fields.push(("mean_integrated", c.mean_integrated));
    report.fields.push(("curvature_flag", codes(&c.flag)));
    report.fields.push(("curvature_flag_discrete", codes(&c.flag_discrete)));
    report.field(mesh, "gaussian", c.gaussian)?;
    report.field(mesh, "mean", c.mean)?;
    report.field(mesh, "k1", c.tensor.k1)?;
    report.field(mesh, "k2", c.tensor.k2)?;
    report.field(mesh, "gaussian_discrete", c.gaussian_discrete)?;
    report.field(mesh, "mean_discrete", c.mean_discrete)?;
    Ok(section)
}

/// Heat-method distance from the first vertex (Crane et al. 2013), Fast
/// Marching for comparison (eq. 2.32-2.34), and the geodesic traced back from
/// the farthest vertex (eq. 2.35).
fn geodesic_section(report: &mut Report, mesh: &TriMesh) -> CliResult<Value> {
    use mesh_geodesic::{
        exact_distance, fmm_distance, trace_path, ExactOptions, FmmOptions, HeatGeodesics, HeatStatus, SurfacePoint,
        TraceOptions,
    };
    let components = mesh.connectivity().components();
    let source = largest_component_source(mesh)?;
    let heat = report.time("heat_precompute", || HeatGeodesics::new(mesh, &Default::default()))?;
    let solved = report.time("heat_solve", || heat.solve(&[source]))?;
    let far_field = solved.count(HeatStatus::FarField);
    let unresolved = solved.count(HeatStatus::Unresolved);
    let d = solved.distance;
    let fmm = report.time("fmm", || fmm_distance(mesh, &[source], &FmmOptions::default()))?;
    let far = (0..d.len()).filter(|&i| d[i].is_finite()).max_by(|&a, &b| d[a].total_cmp(&d[b]));
    let path = match far.and_then(|v| SurfacePoint::at_vertex(mesh, VertexId::new(v))) {
        Some(start) => {
            let p = report.time("trace_path", || trace_path(mesh, &d, &[source], start, &TraceOptions::default()))?;
            mesh_io::write_polylines(report.file("geodesic_path.obj")?, &[&p.positions])?;
            json!({ "from": far, "length": p.length, "points": p.points.len(), "fallback_edges": p.fallback_edges })
        }
        None => Value::Null,
    };
    let reached = d.iter().filter(|x| x.is_finite()).count();
    let max = |v: &[f64]| finite(v.iter().copied().filter(|x| x.is_finite()).fold(f64::NAN, f64::max));
    // Exact polyhedral distances are the reference where they are cheap.
    let exact = (mesh.vertex_count() <= EXACT_REFERENCE_VERTICES)
        .then(|| {
            let options = ExactOptions { max_windows: EXACT_REFERENCE_WINDOWS };
            report.time("exact", || exact_distance(mesh, &[source], &options)).ok()
        })
        .flatten();
    let (reference_name, reference) = match &exact {
        Some(e) => ("exact polyhedral distance", e),
        None => ("Fast Marching", &fmm),
    };
    let agreement = relative_difference(&d, reference);
    if let Some((max_rel, median_rel)) = agreement {
        if max_rel > HEAT_MAX_ERROR || median_rel > HEAT_MEDIAN_ERROR {
            report.warn(format!(
                "geodesic: the heat distance differs from the {reference_name} by up to {:.2}% (median {:.2}%) of \
                 the largest distance",
                100.0 * max_rel,
                100.0 * median_rel
            ));
        }
    }
    if unresolved > 0 {
        report.warn(format!("geodesic: {unresolved} vertices unresolved by the heat flow (`unresolved` in mesh.ply)"));
    }
    let section = json!({
        "ran_on": format!(
            "the source's component, the largest ({reached} of {} vertices; the distance is infinite on the \
             other {} components and on unreferenced vertices)",
            mesh.vertex_count(),
            components.count - 1
        ),
        "source": source.0,
        "method": "heat",
        "laplacian": "intrinsic Delaunay (mollified)",
        "max_distance_heat": max(&d),
        "max_distance_fmm": max(&fmm),
        "reference": reference_name,
        "heat_vs_reference_max_relative": agreement.map(|a| a.0),
        "heat_vs_reference_median_relative": agreement.map(|a| a.1),
        "fmm_vs_exact_max_relative": exact.as_ref().and_then(|e| relative_difference(&fmm, e)).map(|a| a.0),
        "heat_far_field": heat.far_field().name(),
        "far_field_vertices": far_field,
        "unresolved_vertices": unresolved,
        "reached": reached,
        "unreachable": d.len() - reached,
        "path": path,
    });
    report.field(mesh, "distance", d)?;
    Ok(section)
}

/// The accuracy the heat method is held to (largest and median error
/// relative to the largest distance); a miss is a warning.
/// The source of the geodesic distances of a report or a batch: the first
/// vertex of the largest connected component.
pub(crate) fn largest_component_source(mesh: &TriMesh) -> CliResult<VertexId> {
    let components = mesh.connectivity().components();
    let largest = components.largest().ok_or("the mesh has no faces")?;
    let first = components.vertex_component.iter().position(|&c| c as usize == largest);
    Ok(VertexId::new(first.ok_or("the mesh has no faces")?))
}

const HEAT_MAX_ERROR: f64 = 0.02;
/// See [`HEAT_MAX_ERROR`].
const HEAT_MEDIAN_ERROR: f64 = 0.005;
/// Meshes up to this size get exact polyhedral distances as the reference.
const EXACT_REFERENCE_VERTICES: usize = 20_000;
/// The work bound of that exact computation (Fast Marching is the reference
/// when it is reached).
const EXACT_REFERENCE_WINDOWS: usize = 4_000_000;

/// Largest and median |field - reference| over the vertices both reach,
/// relative to the largest reference distance; `None` when nothing is reached.
fn relative_difference(field: &[f64], reference: &[f64]) -> Option<(f64, f64)> {
    let scale = reference.iter().copied().filter(|x| x.is_finite()).fold(0.0, f64::max);
    let mut diff: Vec<f64> = field
        .iter()
        .zip(reference)
        .filter(|(h, f)| h.is_finite() && f.is_finite())
        .map(|(h, f)| (h - f).abs() / scale)
        .collect();
    if diff.is_empty() || scale <= 0.0 {
        return None;
    }
    diff.sort_by(f64::total_cmp);
    Some((diff[diff.len() - 1], diff[diff.len() / 2]))
}

/// The report's atlas: charts of at most about this many faces, split
/// further while their mean area distortion exceeds [`REPORT_AREA_DISTORTION`].
/// A whole scanned component in one chart is crowded around its seams (the
/// full Stanford dragon's main component in one mean-value chart: mean area
/// distortion about 1e6; in charts bounded this way: 1.4).
const REPORT_CHART_FACES: usize = 5000;

/// See [`REPORT_CHART_FACES`].
const REPORT_AREA_DISTORTION: f64 = 2.0;

/// The report lists the charts of largest surface area only.
const REPORT_LISTED_CHARTS: usize = 20;

/// Mean-value texture atlas (Floater 2003: positive weights, so each chart
/// maps one-to-one onto its circle; `mesh param`'s pipeline): the mesh
/// cleaned into an oriented manifold when it is not one, each component
/// split into charts ([`REPORT_CHART_FACES`]), each cut to a disk, flattened
/// onto a circle, scaled to its area and packed into the unit square; the
/// distortion of the whole and of each chart (eq. 2.8-2.11). `uv.obj` holds
/// the (cleaned) mesh with one UV per face corner.
fn param_section(report: &mut Report, mesh: &TriMesh) -> CliResult<Value> {
    use super::param::{prepare, summarize, CleanMode};
    use mesh_param::{atlas, AtlasOptions, ParamMethod};
    let options = AtlasOptions {
        method: ParamMethod::MeanValue,
        max_chart_faces: Some(REPORT_CHART_FACES),
        max_area_distortion: Some(REPORT_AREA_DISTORTION),
        ..AtlasOptions::default()
    };
    let start = Instant::now();
    let (cleaned, cleaning) = report.time("param_clean", || prepare(mesh.clone(), CleanMode::Auto))?;
    let a = report.time("param_mean_value", || atlas(&cleaned, &options))?;
    let time_ms = start.elapsed().as_secs_f64() * 1e3;
    let uv_obj = report.file("uv.obj")?;
    let view = MeshView::new(&cleaned).with_corner_uvs(&a.corner_uvs);
    write_mesh(&uv_obj, view, &mesh_io::WriteOptions::default())?;
    let mut summary = super::param::Summary {
        output: "uv.obj".to_owned(),
        vertices: mesh.vertex_count(),
        faces: mesh.face_count(),
        ..summarize(cleaning, &options.method, &a, true, time_ms)
    };
    let listed = summary.chart_list.len().min(REPORT_LISTED_CHARTS);
    let note = format!("the {listed} largest of {} charts; `mesh param --json` lists all", summary.chart_list.len());
    summary.chart_list.truncate(REPORT_LISTED_CHARTS);
    let ran_on = if summary.cleaning.applied {
        "a copy cleaned into an oriented manifold (see `cleaning`); uv.obj holds that copy"
    } else {
        "the mesh as read"
    };
    let mut section = serde_json::to_value(&summary)?;
    if let Some(map) = section.as_object_mut() {
        map.remove("input");
        map.insert("ran_on".into(), json!(ran_on));
        map.insert("boundary".into(), json!("circle, chord length"));
        map.insert("max_chart_faces".into(), json!(REPORT_CHART_FACES));
        map.insert("max_area_distortion".into(), json!(REPORT_AREA_DISTORTION));
        map.insert("chart_list_note".into(), json!(note));
    }
    Ok(section)
}

/// The 20 smallest eigenpairs of the largest connected component (Laplacian
/// chosen automatically: intrinsic Delaunay when the mesh has zero-area
/// faces, cotangent otherwise; mixed Voronoi mass; the chapter's sec. 2.7), the
/// compression curve of the geometry in the manifold harmonic basis (Vallet
/// and Levy 2008), the first non-constant harmonic and the heat kernel
/// signature at a middle time (Sun et al. 2009) as fields (zero outside the
/// largest component).
fn spectral_section(report: &mut Report, mesh: &TriMesh) -> CliResult<Value> {
    use mesh_spectral::{
        compression_curve, heat_kernel_signature, hks_times, ComponentSelection, HarmonicsOptions, ManifoldHarmonics,
    };
    const PAIRS: usize = 20;
    let components = mesh.connectivity().components();
    let largest = components.largest().ok_or("the mesh has no faces")?;
    let piece_vertices = components.vertex_component.iter().filter(|&&c| c as usize == largest).count();
    let k = PAIRS.min(piece_vertices);
    let mut options = HarmonicsOptions::default();
    options.eigen.component = ComponentSelection::Largest;
    let mh = report.time("spectral_eigenpairs", || ManifoldHarmonics::new(mesh, k, &options))?;
    let pairs = mh.eigenpairs();
    let keeps: Vec<usize> = [1, 2, 5, 10, 20].into_iter().filter(|&j| j <= mh.len()).collect();
    let curve = report.time("spectral_compression", || compression_curve(mesh, &mh, &keeps))?;
    // Too few pairs for a time range: no signature, the rest still holds.
    let hks_time = hks_times(pairs, 3).ok().and_then(|t| t.get(1).copied());
    let hks = hks_time.and_then(|t| heat_kernel_signature(pairs, &[t]).ok()).and_then(|h| h.into_iter().next());
    let info = mh.operator_info();
    let st = &pairs.stats;
    let section = json!({
        "operator": info.map(|i| i.describe()),
        "laplacian": info.map(|i| i.laplacian.to_string()),
        "degenerate_faces": info.map(|i| i.degenerate_faces),
        "ran_on": format!(
            "the largest of {} components ({} of {} vertices; the fields are 0 elsewhere)",
            components.count, piece_vertices, mesh.vertex_count()
        ),
        "eigenvalues": pairs.values.iter().map(|&x| finite(x)).collect::<Vec<_>>(),
        "zero_eigenvalues": st.zero_eigenvalues,
        "max_residual": finite(pairs.residuals.iter().copied().fold(0.0, f64::max)),
        "tolerance": st.tolerance,
        "clusters_verified": st.clusters_verified,
        "compression": curve.iter().map(|c| json!({
            "keep": c.keep, "rms_error": finite(c.rms), "max_error": finite(c.max),
        })).collect::<Vec<_>>(),
        "hks_time": hks_time.and_then(finite),
    });
    if let Some(caveat) = st.caveat() {
        report.warn(format!("spectral: {caveat}"));
    }
    if components.count > 1 {
        report.warn(format!(
            "spectral: computed on the largest of {} components ({} of {} vertices); harmonic1 and hks are 0 on \
             the others",
            components.count,
            piece_vertices,
            mesh.vertex_count()
        ));
    }
    if mh.len() > 1 {
        report.field(mesh, "harmonic1", mh.harmonic(1).to_vec())?;
    }
    if let Some(h) = hks {
        report.field(mesh, "hks", h)?;
    }
    Ok(section)
}

/// Lounsbery wavelet analysis (eq. 2.36-2.39) when the mesh has subdivision
/// connectivity, with the coefficient decay and a compression curve.
fn wavelet_section(report: &mut Report, mesh: &TriMesh) -> CliResult<Value> {
    use mesh_wavelet::{decay_rate, Multiresolution};
    let m = report.time("wavelet_analyze", || Multiresolution::analyze(mesh, &Default::default()))?;
    let stats = m.statistics();
    let curve = m.compression_curve(&[0.01, 0.05, 0.2, 0.5])?;
    Ok(json!({
        "levels": m.levels(),
        "base_vertices": m.base_positions().len(),
        "base_faces": m.hierarchy().faces(0)?.len(),
        "coefficient_mean_norm_per_level": stats.iter().map(|s| s.mean).collect::<Vec<_>>(),
        "decay_rate": decay_rate(&stats),
        "compression": curve.iter().map(|c| json!({
            "keep_fraction": c.keep_fraction, "kept_coefficients": c.kept_coefficients,
            "rms_error": c.rms_error, "max_error": c.max_error,
        })).collect::<Vec<_>>(),
    }))
}
