//! `mesh spectral`: the smallest eigenpairs of the Laplace-Beltrami operator
//! ("Digital Shape Processing" thesis chapter, sec. 2.7) with mesh-spectral, and the tools built on them:
//!
//! - `mesh spectral [input] --k K --out OUT.ply`: eigenvectors as per-vertex
//!   double properties `phi0`, `phi1`, ...; `--json` prints the ascending
//!   `eigenvalues` (exact zeros first, one per component), the relative
//!   `residuals` (each at most `tolerance`), the Laplacian taken and why,
//!   and timings; `--component largest` keeps only the largest piece;
//! - `mesh spectral filter [input] --keep K --out OUT.obj`: manifold-harmonic
//!   filtering of the geometry (ideal low-pass by default, `--cutoff` for a
//!   Butterworth low-pass, `--band LO,HI --gain G` to exaggerate a band);
//! - `mesh spectral compress [input] --keep K [--out OUT.obj] --json`: keep
//!   the first K coefficients, with the error curve at 1, 2, 4, ... K;
//! - `mesh spectral hks [input] --k K --times T --out OUT.ply`: heat kernel
//!   signature at T times, as properties `hks0`, `hks1`, ...

use std::path::PathBuf;
use std::time::Instant;

use mesh_io::MeshView;
use mesh_kernel::TriMesh;
use mesh_spectral::{
    compress, compression_curve, filter_mesh, heat_kernel_signature, hks_times, ComponentSelection, EigenOptions,
    HarmonicsOptions, LaplacianKind, ManifoldHarmonics, MassKind, SpectralCompressionPoint, Transfer,
};
use serde::Serialize;

use crate::choice::choice;
use crate::input::InputArgs;
use crate::output::{binary_ply, check_output, finite, print_json, write_mesh, CliResult, SaveArgs};

/// Arguments of `mesh spectral`.
#[derive(Debug, clap::Args)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct Args {
    #[command(subcommand)]
    command: Option<SpectralCommand>,
    #[command(flatten)]
    eigen: EigenArgs,
}

#[derive(Debug, clap::Subcommand)]
enum SpectralCommand {
    /// Filters the geometry by a transfer function over frequencies sqrt(lambda).
    Filter(FilterArgs),
    /// Keeps the first K harmonic coefficients of the geometry; error curve.
    Compress(CompressArgs),
    /// Heat kernel signature (Sun et al. 2009) at log-spaced times.
    Hks(HksArgs),
}

/// The operator pair and solver settings shared by every subcommand.
#[derive(Debug, Clone, clap::Args)]
struct OperatorArgs {
    /// Laplacian: auto (intrinsic when the mesh has zero-area faces, else
    /// cotan), cotan (the mesh's, = -igl::cotmatrix) or intrinsic
    /// (intrinsic Delaunay, mollified, robust on bad triangles).
    #[arg(long, default_value = "auto")]
    laplacian: String,
    /// Lumped mass: voronoi (mixed Voronoi, igl VORONOI) or barycentric.
    #[arg(long, default_value = "voronoi")]
    mass: String,
    /// Relative tolerance of every returned pair:
    /// ||L x - lambda M x|| / ((|lambda| + s) ||M x||), s the spectral scale.
    #[arg(long, value_name = "TOL", default_value_t = EigenOptions::default().tolerance)]
    tolerance: f64,
}

impl OperatorArgs {
    fn options(&self) -> CliResult<HarmonicsOptions> {
        let laplacian: LaplacianKind = self.laplacian.parse()?;
        let mass: MassKind = self.mass.parse()?;
        let eigen = EigenOptions { tolerance: self.tolerance, ..EigenOptions::default() };
        Ok(HarmonicsOptions { laplacian, mass, eigen })
    }
}

#[derive(Debug, clap::Args)]
struct EigenArgs {
    #[command(flatten)]
    input: InputArgs,
    #[command(flatten)]
    operator: OperatorArgs,
    /// Number of eigenpairs (the smallest).
    #[arg(long, value_name = "K", default_value_t = 20)]
    k: usize,
    /// Components: all (one zero eigenvalue per piece) or largest (the
    /// spectrum of the largest piece only; eigenvectors 0 elsewhere).
    #[arg(long, default_value_t = ComponentSelection::default(),
          value_parser = choice::<ComponentSelection>(ComponentSelection::ALL.map(ComponentSelection::name)))]
    component: ComponentSelection,
    /// Output PLY file: positions as double, per-vertex doubles phi0, phi1, ...
    #[arg(long, value_name = "OUT.ply")]
    out: Option<PathBuf>,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
    /// Allow writing over the input file.
    #[arg(long)]
    force: bool,
}

#[derive(Debug, clap::Args)]
struct FilterArgs {
    #[command(flatten)]
    input: InputArgs,
    #[command(flatten)]
    operator: OperatorArgs,
    /// Harmonics computed (the basis size); alone, the ideal low-pass
    /// keeping exactly these.
    #[arg(long, value_name = "K")]
    keep: usize,
    /// Butterworth low-pass with this cutoff frequency sqrt(lambda).
    #[arg(long, value_name = "OMEGA", conflicts_with = "band")]
    cutoff: Option<f64>,
    /// Order of the Butterworth low-pass.
    #[arg(long, value_name = "N", default_value_t = 4)]
    order: u32,
    /// Frequency band LO,HI to scale by --gain (detail beyond the basis kept).
    #[arg(long, value_name = "LO,HI", value_delimiter = ',', requires = "gain")]
    band: Option<Vec<f64>>,
    /// Gain inside --band (> 1 exaggerates).
    #[arg(long, value_name = "G")]
    gain: Option<f64>,
    /// Output mesh file (format from the extension).
    #[arg(long, value_name = "OUT.obj")]
    out: PathBuf,
    #[command(flatten)]
    save: SaveArgs,
}

#[derive(Debug, clap::Args)]
#[command(mut_arg("json", |a| a.help("Print the summary and error curve as JSON")))]
struct CompressArgs {
    #[command(flatten)]
    input: InputArgs,
    #[command(flatten)]
    operator: OperatorArgs,
    /// Coefficients kept per coordinate.
    #[arg(long, value_name = "K")]
    keep: usize,
    /// Output mesh file (the reconstruction).
    #[arg(long, value_name = "OUT.obj")]
    out: Option<PathBuf>,
    #[command(flatten)]
    save: SaveArgs,
}

#[derive(Debug, clap::Args)]
struct HksArgs {
    #[command(flatten)]
    input: InputArgs,
    #[command(flatten)]
    operator: OperatorArgs,
    /// Eigenpairs used.
    #[arg(long, value_name = "K", default_value_t = 100)]
    k: usize,
    /// Number of log-spaced times from 4 ln 10 / lambda_K to 4 ln 10 / lambda_1.
    #[arg(long, value_name = "T", default_value_t = 5)]
    times: usize,
    /// Output PLY file with per-vertex doubles hks0, hks1, ...
    #[arg(long, value_name = "OUT.ply")]
    out: PathBuf,
    /// Print a JSON summary.
    #[arg(long)]
    json: bool,
    /// Allow writing over the input file.
    #[arg(long)]
    force: bool,
}

/// Wall times in milliseconds.
#[derive(Debug, Clone, Serialize)]
pub struct Timings {
    /// Laplacian and mass assembly.
    pub assembly: f64,
    /// Sparse Cholesky of L - sigma M.
    pub factorization: f64,
    /// Krylov iteration (or dense eigendecomposition).
    pub iteration: f64,
    /// Part of `iteration` in the block solves of the shift-invert operator.
    pub solves: f64,
    /// Part of `iteration` orthogonalizing against the basis.
    pub orthogonalization: f64,
    /// Final Rayleigh-Ritz and residuals.
    pub finalize: f64,
    /// The whole eigensolver call.
    pub eigensolver: f64,
    /// Writing the output file.
    pub write: f64,
}

/// What `mesh spectral --json` prints.
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    /// The input (file or shape).
    pub input: String,
    /// The written PLY file, if any.
    pub output: Option<String>,
    /// Number of vertices.
    pub vertices: usize,
    /// all or largest.
    pub component: String,
    /// Vertices of the mesh the spectrum was computed on (the largest piece
    /// with `--component largest`); eigenvectors are 0 on the others.
    pub component_vertices: usize,
    /// The Laplacian built: cotan or intrinsic.
    pub laplacian: String,
    /// The Laplacian, the reason for it, and the mass, in words.
    pub operator: String,
    /// Zero-area faces of the mesh (the reason `auto` takes intrinsic).
    pub degenerate_faces: usize,
    /// Eigenvalues, ascending.
    pub eigenvalues: Vec<Option<f64>>,
    /// Eigenvalues that are exact zeros (one constant per component).
    pub zero_eigenvalues: usize,
    /// Relative residuals ||L x - lambda M x|| / ((|lambda| + s) ||M x||).
    pub residuals: Vec<Option<f64>>,
    /// Largest relative residual (at most `tolerance`).
    pub max_residual: Option<f64>,
    /// The tolerance met: the requested one, or the rounding level of the
    /// residual where that is larger.
    pub tolerance: f64,
    /// The tolerance asked for.
    pub requested_tolerance: f64,
    /// ||L x - lambda M x|| / ||M x|| per pair (units of lambda).
    pub absolute_residuals: Vec<Option<f64>>,
    /// null-space, dense or block-krylov-schur (largest solved piece).
    pub method: String,
    /// Shift sigma of K = L - sigma M (largest solved piece).
    pub shift: Option<f64>,
    /// Connected pieces with mass.
    pub components: usize,
    /// Pieces the spectrum was computed on.
    pub components_used: usize,
    /// Vertices where every eigenvector is 0 (no mass, or outside the piece).
    pub excluded_vertices: usize,
    /// Attempts of the largest solved piece (1 when the first converged).
    pub attempts: usize,
    /// False when copies of a repeated eigenvalue may be missing (see
    /// `mesh_spectral::EigenStats::clusters_verified`; a warning is printed).
    pub clusters_verified: bool,
    /// Linear solves (columns) of the shift-invert iteration.
    pub operator_columns: usize,
    /// Wall times in milliseconds.
    pub timings_ms: Timings,
}

/// What `mesh spectral filter --json` prints.
#[derive(Debug, Clone, Serialize)]
pub struct FilterSummary {
    /// The input (file or shape).
    pub input: String,
    /// The written file.
    pub output: String,
    /// Basis size.
    pub harmonics: usize,
    /// The transfer function.
    pub transfer: String,
    /// Largest vertex displacement relative to the bounding-box diagonal.
    pub max_displacement: Option<f64>,
    /// Wall time of basis and filter, milliseconds.
    pub time_ms: f64,
}

/// One point of the compression error curve.
#[derive(Debug, Clone, Serialize)]
pub struct CurvePoint {
    /// Coefficients kept.
    pub keep: usize,
    /// Area-weighted RMS distance / bounding-box diagonal.
    pub rms: Option<f64>,
    /// Plain per-vertex RMS distance / diagonal.
    pub vertex_rms: Option<f64>,
    /// Largest distance / diagonal.
    pub max: Option<f64>,
}

impl From<SpectralCompressionPoint> for CurvePoint {
    fn from(e: SpectralCompressionPoint) -> Self {
        Self { keep: e.keep, rms: finite(e.rms), vertex_rms: finite(e.vertex_rms), max: finite(e.max) }
    }
}

/// What `mesh spectral compress --json` prints.
#[derive(Debug, Clone, Serialize)]
pub struct CompressSummary {
    /// The input (file or shape).
    pub input: String,
    /// The written reconstruction, if any.
    pub output: Option<String>,
    /// Number of vertices.
    pub vertices: usize,
    /// Coefficients kept.
    pub keep: usize,
    /// Error at `keep`.
    pub error: CurvePoint,
    /// Error at 1, 2, 4, ..., keep coefficients.
    pub curve: Vec<CurvePoint>,
    /// Wall time of basis and curve, milliseconds.
    pub time_ms: f64,
}

/// What `mesh spectral hks --json` prints.
#[derive(Debug, Clone, Serialize)]
pub struct HksSummary {
    /// The input (file or shape).
    pub input: String,
    /// The written file.
    pub output: String,
    /// The times, one property `hks<i>` each.
    pub times: Vec<f64>,
    /// Per time, the smallest and largest value over vertices.
    pub ranges: Vec<[Option<f64>; 2]>,
    /// Wall time, milliseconds.
    pub time_ms: f64,
}

fn ms(start: Instant) -> f64 {
    start.elapsed().as_secs_f64() * 1e3
}

/// Writes per-vertex fields named `prefix0`, `prefix1`, ... to a binary PLY.
fn write_fields(path: &std::path::Path, mesh: &TriMesh, prefix: &str, fields: &[&[f64]]) -> CliResult<()> {
    let names: Vec<String> = (0..fields.len()).map(|i| format!("{prefix}{i}")).collect();
    let mut view = MeshView::new(mesh);
    for (name, values) in names.iter().zip(fields) {
        view = view.with_scalar(name, values);
    }
    write_mesh(path, view, &binary_ply())?;
    Ok(())
}

/// Runs `mesh spectral` and its subcommands.
pub fn run(args: &Args) -> CliResult<()> {
    match &args.command {
        None => run_eigen(&args.eigen),
        Some(SpectralCommand::Filter(a)) => run_filter(a),
        Some(SpectralCommand::Compress(a)) => run_compress(a),
        Some(SpectralCommand::Hks(a)) => run_hks(a),
    }
}

fn run_eigen(args: &EigenArgs) -> CliResult<()> {
    if let Some(out) = &args.out {
        check_output(out, args.input.path(), args.force)?;
    }
    let data = args.input.load()?;
    let mesh = &data.mesh;
    let mut options = args.operator.options()?;
    options.eigen.component = args.component;
    let mh = harmonics(mesh, args.k, &options)?;
    let pairs = mh.eigenpairs();
    let info = mh.operator_info().ok_or("no operator information")?;
    let start = Instant::now();
    if let Some(out) = &args.out {
        let fields: Vec<&[f64]> = (0..pairs.len()).map(|j| pairs.vector(j)).collect();
        write_fields(out, mesh, "phi", &fields)?;
    }
    let write = ms(start);
    let st = &pairs.stats;
    let summary = Summary {
        input: args.input.describe(),
        output: args.out.as_ref().map(|p| p.display().to_string()),
        vertices: mesh.vertex_count(),
        component: options.eigen.component.to_string(),
        component_vertices: info.vertices,
        laplacian: info.laplacian.to_string(),
        operator: info.describe(),
        degenerate_faces: info.degenerate_faces,
        eigenvalues: pairs.values.iter().map(|&v| finite(v)).collect(),
        zero_eigenvalues: st.zero_eigenvalues,
        residuals: pairs.residuals.iter().map(|&v| finite(v)).collect(),
        max_residual: finite(pairs.residuals.iter().copied().fold(0.0, f64::max)),
        tolerance: st.tolerance,
        requested_tolerance: options.eigen.tolerance,
        absolute_residuals: pairs.absolute_residuals.iter().map(|&v| finite(v)).collect(),
        method: st.method.to_string(),
        shift: st.shift,
        // With --component largest the solver sees one piece: count the mesh's.
        components: match options.eigen.component {
            ComponentSelection::Largest => mesh.connectivity().components().count.max(st.components),
            ComponentSelection::All => st.components,
        },
        components_used: st.components_used,
        excluded_vertices: pairs.excluded.len(),
        attempts: st.attempts,
        clusters_verified: st.clusters_verified,
        operator_columns: st.operator_columns,
        timings_ms: Timings {
            assembly: info.assembly_seconds * 1e3,
            factorization: st.factor_seconds * 1e3,
            iteration: st.iterate_seconds * 1e3,
            solves: st.solve_seconds * 1e3,
            orthogonalization: st.orthogonalize_seconds * 1e3,
            finalize: st.finalize_seconds * 1e3,
            eigensolver: st.total_seconds * 1e3,
            write,
        },
    };
    if args.json {
        return print_json(&summary);
    }
    print_text(&summary, pairs);
    if let Some(out) = &summary.output {
        eprintln!("wrote {out}");
    }
    Ok(())
}

/// The harmonics of `mesh`, with a warning on stderr when the solver could
/// not rule out missing copies of a repeated eigenvalue.
fn harmonics(mesh: &TriMesh, k: usize, options: &HarmonicsOptions) -> CliResult<ManifoldHarmonics> {
    let mh = ManifoldHarmonics::new(mesh, k, options)?;
    if let Some(caveat) = mh.eigenpairs().stats.caveat() {
        eprintln!("warning: {caveat}");
    }
    Ok(mh)
}

fn print_text(s: &Summary, pairs: &mesh_spectral::Eigenpairs) {
    println!("{} eigenpairs of {} ({} vertices), {}:", pairs.len(), s.input, s.vertices, s.method);
    println!("operator: {}", s.operator);
    if s.component == "largest" {
        println!("component: the largest, {} of {} vertices", s.component_vertices, s.vertices);
    }
    println!(
        "{} zero eigenvalue(s) (one constant per component; {} component(s) used of {})",
        s.zero_eigenvalues, s.components_used, s.components
    );
    for (j, (v, r)) in pairs.values.iter().zip(&pairs.residuals).enumerate() {
        println!("{j:>5} {v:>22.15e}  relative residual {r:.1e}");
    }
    if s.tolerance > s.requested_tolerance {
        println!(
            "every residual <= {:.1e} (the rounding level of this operator; {:.1e} was asked)",
            s.tolerance, s.requested_tolerance
        );
    } else {
        println!("every residual <= tolerance {:.1e}", s.tolerance);
    }
    println!(
        "eigensolver {:.1} ms (factorization {:.1} ms, {} attempt(s)); assembly {:.1} ms",
        s.timings_ms.eigensolver, s.timings_ms.factorization, s.attempts, s.timings_ms.assembly
    );
}

fn transfer(args: &FilterArgs) -> CliResult<Transfer> {
    Ok(match (&args.band, args.cutoff) {
        (Some(band), _) => {
            let gain = args.gain.ok_or("--band needs --gain")?;
            let &[low, high] = band.as_slice() else {
                return Err(format!("--band takes two frequencies LO,HI, got {band:?}").into());
            };
            Transfer::Band { low, high, gain }
        }
        (None, Some(cutoff)) => Transfer::LowPass { cutoff, order: args.order },
        (None, None) => Transfer::KeepFirst(args.keep),
    })
}

fn run_filter(args: &FilterArgs) -> CliResult<()> {
    check_output(&args.out, args.input.path(), args.save.force)?;
    let data = args.input.load()?;
    let mesh = &data.mesh;
    let transfer = transfer(args)?;
    let start = Instant::now();
    let mh = harmonics(mesh, args.keep, &args.operator.options()?)?;
    let filtered = filter_mesh(mesh, &mh, &transfer)?;
    let time_ms = ms(start);
    write_mesh(&args.out, &filtered, &args.save.write.options(Default::default()))?;
    let diagonal = mesh_kernel::geometry::bounding_box(mesh).map_or(1.0, |b| b.diagonal());
    let moved = mesh.positions().iter().zip(filtered.positions()).map(|(a, b)| a.distance(*b)).fold(0.0, f64::max);
    let summary = FilterSummary {
        input: args.input.describe(),
        output: args.out.display().to_string(),
        harmonics: mh.len(),
        transfer: format!("{transfer:?}"),
        max_displacement: finite(moved / diagonal),
        time_ms,
    };
    if args.save.json {
        return print_json(&summary);
    }
    eprintln!("wrote {} ({}, {} harmonics, {:.1} ms)", summary.output, summary.transfer, summary.harmonics, time_ms);
    Ok(())
}

fn run_compress(args: &CompressArgs) -> CliResult<()> {
    if let Some(out) = &args.out {
        check_output(out, args.input.path(), args.save.force)?;
    }
    let data = args.input.load()?;
    let mesh = &data.mesh;
    let start = Instant::now();
    let mh = harmonics(mesh, args.keep, &args.operator.options()?)?;
    let mut keeps: Vec<usize> =
        std::iter::successors(Some(1usize), |k| k.checked_mul(2)).take_while(|&k| k < args.keep).collect();
    keeps.push(args.keep);
    let curve = compression_curve(mesh, &mh, &keeps)?;
    let (restored, error) = compress(mesh, &mh, args.keep)?;
    let time_ms = ms(start);
    if let Some(out) = &args.out {
        write_mesh(out, &restored, &args.save.write.options(Default::default()))?;
    }
    let summary = CompressSummary {
        input: args.input.describe(),
        output: args.out.as_ref().map(|p| p.display().to_string()),
        vertices: mesh.vertex_count(),
        keep: args.keep,
        error: error.into(),
        curve: curve.into_iter().map(Into::into).collect(),
        time_ms,
    };
    if args.save.json {
        return print_json(&summary);
    }
    println!("{:>8} {:>12} {:>12} {:>12}", "keep", "rms", "vertex rms", "max");
    for p in &summary.curve {
        let f = |x: Option<f64>| x.map_or("-".into(), |v| format!("{v:.3e}"));
        println!("{:>8} {:>12} {:>12} {:>12}", p.keep, f(p.rms), f(p.vertex_rms), f(p.max));
    }
    if let Some(out) = &summary.output {
        eprintln!("wrote {out}");
    }
    Ok(())
}

fn run_hks(args: &HksArgs) -> CliResult<()> {
    check_output(&args.out, args.input.path(), args.force)?;
    let data = args.input.load()?;
    let mesh = &data.mesh;
    let start = Instant::now();
    let k = args.k.min(mesh.vertex_count());
    let mh = harmonics(mesh, k, &args.operator.options()?)?;
    let times = hks_times(mh.eigenpairs(), args.times)?;
    let hks = heat_kernel_signature(mh.eigenpairs(), &times)?;
    let time_ms = ms(start);
    let fields: Vec<&[f64]> = hks.iter().map(Vec::as_slice).collect();
    write_fields(&args.out, mesh, "hks", &fields)?;
    let range = |h: &Vec<f64>| {
        let (lo, hi) = h.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| (a.min(x), b.max(x)));
        [finite(lo), finite(hi)]
    };
    let summary = HksSummary {
        input: args.input.describe(),
        output: args.out.display().to_string(),
        ranges: hks.iter().map(range).collect(),
        times,
        time_ms,
    };
    if args.json {
        return print_json(&summary);
    }
    eprintln!("wrote {} ({} times, {} pairs, {:.1} ms)", summary.output, summary.times.len(), k, time_ms);
    Ok(())
}

impl Args {
    /// The input file, if any.
    pub fn input_file(&self) -> Option<&std::path::Path> {
        match &self.command {
            None => self.eigen.input.path(),
            Some(SpectralCommand::Filter(a)) => a.input.path(),
            Some(SpectralCommand::Compress(a)) => a.input.path(),
            Some(SpectralCommand::Hks(a)) => a.input.path(),
        }
    }

    /// The library options set from flags, for [`crate::errors::translate`].
    pub fn given(&self) -> Vec<(&'static str, String)> {
        use crate::errors::{flag, number};
        let operator = |o: &OperatorArgs| ("tolerance", flag("--tolerance", number(o.tolerance)));
        match &self.command {
            None => vec![
                ("k", flag("--k", self.eigen.k)),
                ("component", flag("--component", self.eigen.component)),
                operator(&self.eigen.operator),
            ],
            Some(SpectralCommand::Filter(a)) => {
                let mut given = vec![("k", flag("--keep", a.keep)), operator(&a.operator)];
                if let Some(g) = a.gain {
                    given.push(("gain", flag("--gain", number(g))));
                }
                given
            }
            Some(SpectralCommand::Compress(a)) => {
                vec![("k", flag("--keep", a.keep)), ("keep", flag("--keep", a.keep)), operator(&a.operator)]
            }
            Some(SpectralCommand::Hks(a)) => vec![
                ("k", flag("--k", a.k)),
                ("count", flag("--times", a.times)),
                ("times", flag("--times", a.times)),
                operator(&a.operator),
            ],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(args: &[&str]) -> Args {
        crate::commands::parse_args("spectral", args)
    }

    #[test]
    fn eigenvectors_are_written_as_ply_properties() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("phi.ply");
        let a = parse(&["--shape", "icosphere", "--res", "2", "--k", "6", "--out", out.to_str().unwrap()]);
        assert!(a.command.is_none());
        run(&a).unwrap();
        let data = mesh_io::read(&out).unwrap();
        assert_eq!(data.scalars.len(), 6);
        assert_eq!(data.scalars[5].0, "phi5");
        // phi0 is constant on a closed piece.
        let phi0 = &data.scalars[0].1;
        assert!(phi0.iter().all(|x| (x - phi0[0]).abs() < 1e-9));
    }

    #[test]
    fn subcommands_parse_and_run() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("f.obj");
        let o = out.to_str().unwrap();
        for args in [
            vec!["filter", "--shape", "torus", "--res", "8", "--keep", "10", "--out", o],
            vec!["filter", "--shape", "torus", "--res", "8", "--keep", "20", "--cutoff", "2", "--out", o],
            vec![
                "filter", "--shape", "torus", "--res", "8", "--keep", "20", "--band", "1,3", "--gain", "2", "--out", o,
            ],
            vec!["compress", "--shape", "torus", "--res", "8", "--keep", "16", "--out", o],
        ] {
            let a = parse(&args);
            assert!(a.command.is_some(), "{args:?}");
            run(&a).unwrap_or_else(|e| panic!("{args:?}: {e}"));
            assert_eq!(mesh_io::read(&out).unwrap().mesh.vertex_count(), 32 * 8);
        }
        let ply = dir.path().join("h.ply");
        run(&parse(&["hks", "--shape", "icosphere", "--res", "2", "--k", "30", "--out", ply.to_str().unwrap()]))
            .unwrap();
        assert_eq!(mesh_io::read(&ply).unwrap().scalars.len(), 5);
    }

    #[test]
    fn bad_arguments_are_errors() {
        assert!(run(&parse(&["--shape", "icosphere", "--res", "1", "--k", "500"])).is_err());
        assert!(run(&parse(&["--shape", "icosphere", "--res", "1", "--laplacian", "nope"])).is_err());
        assert!(run(&parse(&["--shape", "icosphere", "--res", "1", "--k", "0"])).is_err());
        let some =
            crate::commands::try_parse_args::<Args>("spectral", &["--shape", "icosphere", "--component", "some"]);
        let message = some.expect_err("an unknown component is refused").to_string();
        assert!(message.contains("some") && message.contains("largest"), "{message}");
    }

    #[test]
    fn largest_component_and_names_parse() {
        let a = parse(&["--shape", "icosphere", "--res", "2", "--k", "4", "--component", "largest", "--json"]);
        assert_eq!(a.eigen.component, mesh_spectral::ComponentSelection::Largest);
        run(&a).unwrap();
        assert!(run(&parse(&["--shape", "icosphere", "--res", "1", "--k", "4", "--laplacian", "intrinsic"])).is_ok());
    }
}
