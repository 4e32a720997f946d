//! `mesh subdivide` and `mesh wavelet`: 4-to-1 subdivision (midpoint, Loop,
//! modified butterfly) and the multiresolution analysis of section 2.8
//! (eq. 2.36-2.39) of the "Digital Shape Processing" thesis chapter, with
//! mesh-wavelet: coefficient statistics, compression by keeping the largest
//! coefficients, and levels of detail.
//!
//! Outputs keep the input's vertex order wherever the vertex set is the
//! same: subdivision lists the old vertices first, a level of detail lists
//! its vertices in their input order, and the full level is the input order.

use std::path::PathBuf;
use std::time::Instant;

use mesh_kernel::TriMesh;
use mesh_wavelet::{
    decay_rate, subdivide, CompressOptions, MultiresOptions, Multiresolution, Scheme, SubdivideOptions, WaveletKind,
};
use serde::Serialize;

use crate::choice::choice;
use crate::input::InputArgs;
use crate::output::{check_output, finite, print_json, write_mesh, CliResult, SaveArgs};

/// Arguments of `mesh subdivide`.
#[derive(Debug, clap::Args)]
pub struct SubdivideArgs {
    #[command(flatten)]
    input: InputArgs,
    /// Refinement scheme: midpoint, loop or butterfly.
    #[arg(long, default_value_t = SubdivideOptions::default().scheme,
          value_parser = choice::<Scheme>(Scheme::ALL.map(Scheme::name)))]
    scheme: Scheme,
    /// Number of 4-to-1 splits.
    #[arg(long, default_value_t = SubdivideOptions::default().levels)]
    levels: usize,
    /// Output mesh file (the format comes from the extension).
    #[arg(long, value_name = "OUT.obj")]
    out: PathBuf,
    #[command(flatten)]
    save: SaveArgs,
}

/// What `mesh subdivide --json` prints.
#[derive(Debug, Clone, Serialize)]
pub struct SubdivideSummary {
    /// The input (file or shape).
    pub input: String,
    /// The written file.
    pub output: String,
    /// The scheme.
    pub scheme: String,
    /// Number of splits.
    pub levels: usize,
    /// Input vertex and face counts.
    pub input_vertices: usize,
    /// Input face count.
    pub input_faces: usize,
    /// Input vertices no face used, dropped before subdividing (the output
    /// then has subdivision connectivity, which `mesh wavelet` needs).
    pub unreferenced_vertices_dropped: usize,
    /// Output vertex count.
    pub vertices: usize,
    /// Output face count.
    pub faces: usize,
    /// Wall time of the subdivision, milliseconds.
    pub time_ms: f64,
}

/// Runs `mesh subdivide`.
pub fn run_subdivide(args: &SubdivideArgs) -> CliResult<()> {
    let scheme = args.scheme;
    check_output(&args.out, args.input.path(), args.save.force)?;
    let data = args.input.load()?;
    let (mesh, dropped) = drop_unreferenced(&data.mesh)?;
    let start = Instant::now();
    let fine = subdivide(&mesh, &SubdivideOptions { scheme, levels: args.levels })?;
    let time_ms = start.elapsed().as_secs_f64() * 1e3;
    write_mesh(&args.out, &fine, &args.save.write.options(Default::default()))?;
    let summary = SubdivideSummary {
        input: args.input.describe(),
        output: args.out.display().to_string(),
        scheme: scheme.name().into(),
        levels: args.levels,
        input_vertices: data.mesh.vertex_count(),
        input_faces: data.mesh.face_count(),
        unreferenced_vertices_dropped: dropped,
        vertices: fine.vertex_count(),
        faces: fine.face_count(),
        time_ms,
    };
    if args.save.json {
        return print_json(&summary);
    }
    if dropped > 0 {
        eprintln!("dropped {dropped} unreferenced vertices of the input (no face uses them)");
    }
    eprintln!(
        "wrote {} ({} {} level(s): {} vertices, {} faces, {:.1} ms)",
        summary.output, summary.scheme, summary.levels, summary.vertices, summary.faces, time_ms
    );
    Ok(())
}

/// The mesh without the vertices no face uses (the others renumbered in
/// order), and how many were dropped. Cost O(V + F).
fn drop_unreferenced(mesh: &TriMesh) -> CliResult<(std::borrow::Cow<'_, TriMesh>, usize)> {
    if mesh_kernel::clean::unreferenced_vertices(mesh.vertex_count(), mesh.faces()).is_empty() {
        return Ok((std::borrow::Cow::Borrowed(mesh), 0));
    }
    let only_unreferenced = mesh_kernel::clean::CleanOptions {
        weld_tolerance: None,
        drop_degenerate: false,
        drop_duplicates: false,
        drop_unreferenced: true,
        manifold: false,
        orient: false,
        ..Default::default()
    };
    let (compact, report) = mesh.cleaned(&only_unreferenced)?;
    Ok((std::borrow::Cow::Owned(compact), report.unreferenced_vertices))
}

/// Arguments of `mesh wavelet`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(subcommand)]
    command: WaveletCommand,
}

#[derive(Debug, clap::Subcommand)]
enum WaveletCommand {
    /// Detects subdivision connectivity and prints the base mesh and
    /// per-level coefficient statistics.
    Analyze(AnalyzeArgs),
    /// Keeps the largest coefficients (scaled per level) and writes the
    /// reconstruction, with its error relative to the bounding-box diagonal.
    Compress(CompressArgs),
    /// Writes the level-of-detail mesh K^j.
    Lod(LodArgs),
}

/// The filter bank of every `mesh wavelet` command.
#[derive(Debug, Clone, clap::Args)]
struct BankArgs {
    /// Refinement scheme of the filter bank: midpoint (Lounsbery's
    /// piecewise-linear wavelets), loop or butterfly.
    #[arg(long, default_value_t = MultiresOptions::default().scheme,
          value_parser = choice::<Scheme>(Scheme::ALL.map(Scheme::name)))]
    scheme: Scheme,
    /// Wavelet: lazy, or lifted (closer to orthogonal under eq. 2.36).
    #[arg(long, default_value_t = MultiresOptions::default().wavelet,
          value_parser = choice::<WaveletKind>(WaveletKind::ALL.map(WaveletKind::name)))]
    wavelet: WaveletKind,
    /// Detect at most this many levels.
    #[arg(long, value_name = "N")]
    max_levels: Option<usize>,
}

impl BankArgs {
    fn options(&self) -> MultiresOptions {
        let defaults = MultiresOptions::default();
        MultiresOptions {
            scheme: self.scheme,
            wavelet: self.wavelet,
            max_levels: self.max_levels.unwrap_or(defaults.max_levels),
        }
    }
}

#[derive(Debug, clap::Args)]
struct AnalyzeArgs {
    #[command(flatten)]
    input: InputArgs,
    #[command(flatten)]
    bank: BankArgs,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

#[derive(Debug, clap::Args)]
struct CompressArgs {
    #[command(flatten)]
    input: InputArgs,
    #[command(flatten)]
    bank: BankArgs,
    /// Fraction of the wavelet coefficients to keep, in [0, 1].
    #[arg(long, value_name = "FRACTION")]
    keep_fraction: f64,
    /// Output mesh file.
    #[arg(long, value_name = "OUT.obj")]
    out: PathBuf,
    #[command(flatten)]
    save: SaveArgs,
}

#[derive(Debug, clap::Args)]
struct LodArgs {
    #[command(flatten)]
    input: InputArgs,
    #[command(flatten)]
    bank: BankArgs,
    /// The level j (0 = base mesh, J = the input).
    #[arg(long, value_name = "J")]
    level: usize,
    /// Output mesh file.
    #[arg(long, value_name = "OUT.obj")]
    out: PathBuf,
    #[command(flatten)]
    save: SaveArgs,
}

/// Coefficient magnitudes of one level.
#[derive(Debug, Clone, Serialize)]
pub struct LevelSummary {
    /// Level j: coefficients between K^j and K^{j+1}.
    pub level: usize,
    /// Number of coefficients.
    pub coefficients: usize,
    /// Mean norm.
    pub mean: f64,
    /// Root mean square norm.
    pub rms: f64,
    /// Largest norm.
    pub max: f64,
}

/// What `mesh wavelet analyze --json` prints.
#[derive(Debug, Clone, Serialize)]
pub struct AnalyzeSummary {
    /// The input (file or shape).
    pub input: String,
    /// Input vertex count.
    pub vertices: usize,
    /// Input face count.
    pub faces: usize,
    /// Scheme of the filter bank.
    pub scheme: String,
    /// Lazy or lifted.
    pub wavelet: String,
    /// Number of levels J above the base mesh.
    pub levels: usize,
    /// Vertices of the base mesh K^0.
    pub base_vertices: usize,
    /// Faces of the base mesh K^0.
    pub base_faces: usize,
    /// Statistics per level, coarsest first.
    pub per_level: Vec<LevelSummary>,
    /// Geometric decay rate r of the mean magnitude (mean ~ r^-j).
    pub decay_rate: Option<f64>,
    /// Largest vertex distance after analysis and synthesis, relative to the
    /// bounding-box diagonal.
    pub reconstruction_error: Option<f64>,
    /// Wall time of detection, filter bank and analysis, milliseconds.
    pub time_ms: f64,
}

/// What `mesh wavelet compress --json` prints.
#[derive(Debug, Clone, Serialize)]
pub struct CompressSummary {
    /// The input (file or shape).
    pub input: String,
    /// The written file.
    pub output: String,
    /// Requested fraction.
    pub keep_fraction: f64,
    /// Wavelet coefficients kept.
    pub kept_coefficients: usize,
    /// All wavelet coefficients.
    pub total_coefficients: usize,
    /// RMS vertex distance to the input, relative to the bounding-box diagonal.
    pub rms_error: Option<f64>,
    /// Largest vertex distance to the input, relative to the bounding-box diagonal.
    pub max_error: Option<f64>,
    /// Number of levels.
    pub levels: usize,
}

/// What `mesh wavelet lod --json` prints.
#[derive(Debug, Clone, Serialize)]
pub struct LodSummary {
    /// The input (file or shape).
    pub input: String,
    /// The written file.
    pub output: String,
    /// The level written.
    pub level: usize,
    /// Number of levels of the input.
    pub levels: usize,
    /// Vertices written.
    pub vertices: usize,
    /// Faces written.
    pub faces: usize,
}

/// Runs `mesh wavelet`.
pub fn run(args: &Args) -> CliResult<()> {
    match &args.command {
        WaveletCommand::Analyze(a) => {
            let s = analyze(a)?;
            if a.json {
                return print_json(&s);
            }
            print_analysis(&s);
            Ok(())
        }
        WaveletCommand::Compress(a) => {
            let s = compress(a)?;
            if a.save.json {
                return print_json(&s);
            }
            eprintln!(
                "wrote {} (kept {} of {} coefficients: rms error {:.3e}, max error {:.3e} of the diagonal)",
                s.output,
                s.kept_coefficients,
                s.total_coefficients,
                s.rms_error.unwrap_or(f64::NAN),
                s.max_error.unwrap_or(f64::NAN)
            );
            Ok(())
        }
        WaveletCommand::Lod(a) => {
            let s = lod(a)?;
            if a.save.json {
                return print_json(&s);
            }
            eprintln!(
                "wrote {} (level {} of {}: {} vertices, {} faces)",
                s.output, s.level, s.levels, s.vertices, s.faces
            );
            Ok(())
        }
    }
}

fn analyze(args: &AnalyzeArgs) -> CliResult<AnalyzeSummary> {
    let options = args.bank.options();
    let data = args.input.load()?;
    let mesh = &data.mesh;
    let start = Instant::now();
    let mr = Multiresolution::analyze(mesh, &options)?;
    let time_ms = start.elapsed().as_secs_f64() * 1e3;
    let stats = mr.statistics();
    let back = mr.synthesize()?;
    let base = mr.level(0)?;
    Ok(AnalyzeSummary {
        input: args.input.describe(),
        vertices: mesh.vertex_count(),
        faces: mesh.face_count(),
        scheme: options.scheme.name().into(),
        wavelet: options.wavelet.name().into(),
        levels: mr.levels(),
        base_vertices: base.vertex_count(),
        base_faces: base.face_count(),
        per_level: stats
            .iter()
            .map(|s| LevelSummary { level: s.level, coefficients: s.count, mean: s.mean, rms: s.rms, max: s.max })
            .collect(),
        decay_rate: decay_rate(&stats).and_then(finite),
        reconstruction_error: finite(max_distance(mesh, &back) / diagonal(mesh)),
        time_ms,
    })
}

fn compress(args: &CompressArgs) -> CliResult<CompressSummary> {
    let options = args.bank.options();
    check_output(&args.out, args.input.path(), args.save.force)?;
    let data = args.input.load()?;
    let mr = Multiresolution::analyze(&data.mesh, &options)?;
    let c = mr.compress(&CompressOptions { keep_fraction: args.keep_fraction })?;
    let out = c.multiresolution.synthesize()?;
    write_mesh(&args.out, &out, &args.save.write.options(Default::default()))?;
    Ok(CompressSummary {
        input: args.input.describe(),
        output: args.out.display().to_string(),
        keep_fraction: args.keep_fraction,
        kept_coefficients: c.kept_coefficients,
        total_coefficients: c.total_coefficients,
        rms_error: finite(c.rms_error),
        max_error: finite(c.max_error),
        levels: mr.levels(),
    })
}

fn lod(args: &LodArgs) -> CliResult<LodSummary> {
    let options = args.bank.options();
    check_output(&args.out, args.input.path(), args.save.force)?;
    let data = args.input.load()?;
    let mr = Multiresolution::analyze(&data.mesh, &options)?;
    let mesh = mr.level(args.level)?;
    write_mesh(&args.out, &mesh, &args.save.write.options(Default::default()))?;
    Ok(LodSummary {
        input: args.input.describe(),
        output: args.out.display().to_string(),
        level: args.level,
        levels: mr.levels(),
        vertices: mesh.vertex_count(),
        faces: mesh.face_count(),
    })
}

fn max_distance(a: &TriMesh, b: &TriMesh) -> f64 {
    a.positions().iter().zip(b.positions()).map(|(p, q)| p.distance(*q)).fold(0.0, f64::max)
}

fn diagonal(mesh: &TriMesh) -> f64 {
    mesh_kernel::geometry::bounding_box(mesh).map_or(1.0, |b| if b.diagonal() > 0.0 { b.diagonal() } else { 1.0 })
}

fn print_analysis(s: &AnalyzeSummary) {
    println!("mesh: {} ({} vertices, {} faces)", s.input, s.vertices, s.faces);
    println!("  filter bank        {} {}", s.scheme, s.wavelet);
    println!(
        "  levels             {} above a base mesh of {} vertices, {} faces",
        s.levels, s.base_vertices, s.base_faces
    );
    println!("  {:<8} {:>12} {:>12} {:>12} {:>12}", "level", "count", "mean", "rms", "max");
    for l in &s.per_level {
        println!("  {:<8} {:>12} {:>12.4e} {:>12.4e} {:>12.4e}", l.level, l.coefficients, l.mean, l.rms, l.max);
    }
    if let Some(r) = s.decay_rate {
        println!("  decay rate         {r:.3} per level");
    }
    if let Some(e) = s.reconstruction_error {
        println!("  reconstruction     {e:.2e} of the diagonal");
    }
    println!("  time               {:.1} ms", s.time_ms);
}

impl SubdivideArgs {
    /// The input file, if any.
    pub fn input_file(&self) -> Option<&std::path::Path> {
        self.input.path()
    }

    /// The library options set from flags, for [`crate::errors::translate`].
    pub fn given(&self) -> Vec<(&'static str, String)> {
        use crate::errors::flag;
        vec![("levels", flag("--levels", self.levels)), ("scheme", flag("--scheme", self.scheme))]
    }
}

impl Args {
    /// The input file, if any.
    pub fn input_file(&self) -> Option<&std::path::Path> {
        match &self.command {
            WaveletCommand::Analyze(a) => a.input.path(),
            WaveletCommand::Compress(a) => a.input.path(),
            WaveletCommand::Lod(a) => a.input.path(),
        }
    }

    /// The library options set from flags, for [`crate::errors::translate`].
    pub fn given(&self) -> Vec<(&'static str, String)> {
        use crate::errors::flag;
        let (bank, mut given) = match &self.command {
            WaveletCommand::Analyze(a) => (&a.bank, Vec::new()),
            WaveletCommand::Compress(a) => (&a.bank, vec![("keep_fraction", flag("--keep-fraction", a.keep_fraction))]),
            WaveletCommand::Lod(a) => (&a.bank, vec![("level", flag("--level", a.level))]),
        };
        given.push(("scheme", flag("--scheme", bank.scheme)));
        given.push(("wavelet", flag("--wavelet", bank.wavelet)));
        if let Some(n) = bank.max_levels {
            given.push(("max_levels", flag("--max-levels", n)));
        }
        given
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::commands::{parse_args, try_parse_args};

    fn shuffled_subdivided_icosahedron(dir: &std::path::Path) -> (PathBuf, TriMesh) {
        // Subdivide, write, reverse the vertex order: the file has lost its hierarchy.
        let path = dir.join("ico.obj");
        let out = path.to_str().unwrap();
        let a: SubdivideArgs = parse_args(
            "subdivide",
            &["--shape", "icosphere", "--res", "0", "--scheme", "loop", "--levels", "3", "--out", out],
        );
        run_subdivide(&a).unwrap();
        let m = mesh_io::read(&path).unwrap().mesh;
        let n = m.vertex_count() as u32;
        let p: Vec<_> = m.positions().iter().rev().copied().collect();
        let f: Vec<[u32; 3]> = m.faces().iter().map(|t| t.map(|v| n - 1 - v)).collect();
        let m = TriMesh::new(p, f).unwrap();
        mesh_io::write(&path, &m, &Default::default()).unwrap();
        (path, m)
    }

    #[test]
    fn subdivide_keeps_the_input_order() {
        let dir = tempfile::tempdir().unwrap();
        for scheme in ["midpoint", "loop", "butterfly"] {
            let out = dir.path().join(format!("{scheme}.obj"));
            let a: SubdivideArgs = parse_args(
                "subdivide",
                &[
                    "--shape",
                    "torus",
                    "--res",
                    "4",
                    "--scheme",
                    scheme,
                    "--levels",
                    "2",
                    "--out",
                    out.to_str().unwrap(),
                ],
            );
            run_subdivide(&a).unwrap();
            let m = mesh_io::read(&out).unwrap().mesh;
            let input = mesh_kernel::shapes::by_name("torus", 4).unwrap();
            assert_eq!(m.face_count(), 16 * input.face_count());
            if scheme != "loop" {
                assert_eq!(&m.positions()[..input.vertex_count()], input.positions());
            }
        }
        let cubic = try_parse_args::<SubdivideArgs>("subdivide", &["--scheme", "cubic", "--out", "x.obj"]);
        let message = cubic.expect_err("an unknown scheme is refused").to_string();
        assert!(message.contains("cubic") && message.contains("butterfly"), "{message}");
    }

    #[test]
    fn analyze_a_file_that_lost_its_hierarchy() {
        let dir = tempfile::tempdir().unwrap();
        let (path, _) = shuffled_subdivided_icosahedron(dir.path());
        let a: Args = parse_args("wavelet", &["analyze", path.to_str().unwrap(), "--json", "--scheme", "loop"]);
        let WaveletCommand::Analyze(a) = a.command else { unreachable!() };
        let s = analyze(&a).unwrap();
        assert_eq!((s.levels, s.base_vertices, s.base_faces), (3, 12, 20));
        assert_eq!(s.per_level.len(), 3);
        // A Loop surface analysed with Loop wavelets has no details.
        assert!(s.per_level.iter().all(|l| l.max < 1e-12), "{:?}", s.per_level);
        assert!(s.reconstruction_error.unwrap() < 1e-12);
        let json = serde_json::to_value(&s).unwrap();
        for key in ["levels", "base_vertices", "base_faces", "per_level"] {
            assert!(json.get(key).is_some(), "{key}");
        }
    }

    #[test]
    fn compress_and_lod_keep_the_vertex_order() {
        let dir = tempfile::tempdir().unwrap();
        let (path, input) = shuffled_subdivided_icosahedron(dir.path());
        let file = path.to_str().unwrap();
        let mut last = f64::INFINITY;
        for keep in ["0", "0.05", "0.3", "1"] {
            let out = dir.path().join(format!("c{keep}.obj"));
            let a: Args = parse_args(
                "wavelet",
                &["compress", file, "--keep-fraction", keep, "--out", out.to_str().unwrap(), "--json"],
            );
            let WaveletCommand::Compress(a) = a.command else { unreachable!() };
            let s = compress(&a).unwrap();
            let rms = s.rms_error.unwrap();
            assert!(rms <= last);
            last = rms;
            let m = mesh_io::read(&out).unwrap().mesh;
            assert_eq!(m.faces(), input.faces());
            let err = max_distance(&m, &input) / diagonal(&input);
            assert!((err - s.max_error.unwrap()).abs() < 1e-9);
        }
        assert!(last < 1e-12);
        let out = dir.path().join("lod.obj");
        let a: Args =
            parse_args("wavelet", &["lod", file, "--level", "3", "--out", out.to_str().unwrap(), "--wavelet", "lazy"]);
        let WaveletCommand::Lod(a) = a.command else { unreachable!() };
        let s = lod(&a).unwrap();
        assert_eq!(s.vertices, input.vertex_count());
        let m = mesh_io::read(&out).unwrap().mesh;
        assert_eq!(m.faces(), input.faces());
        assert!(max_distance(&m, &input) < 1e-12);
        let a: Args = parse_args("wavelet", &["lod", file, "--level", "4", "--out", out.to_str().unwrap()]);
        let WaveletCommand::Lod(a) = a.command else { unreachable!() };
        assert!(lod(&a).is_err());
    }

    #[test]
    fn meshes_without_subdivision_connectivity_fail_cleanly() {
        let a: Args = parse_args("wavelet", &["analyze", "--shape", "uv-sphere", "--res", "8"]);
        let e = run(&a).unwrap_err();
        assert!(e.to_string().contains("subdivision connectivity"), "{e}");
        let haar = try_parse_args::<Args>("wavelet", &["analyze", "--wavelet", "haar"]);
        let message = haar.expect_err("an unknown wavelet is refused").to_string();
        assert!(message.contains("haar") && message.contains("lifted"), "{message}");
    }
}
