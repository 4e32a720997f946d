//! `cargo xtask bench --mesh PATH`: times every implemented operation on one
//! mesh, in-process, as the median of several runs, once on one thread and
//! once with the default thread count.
//!
//! Operation names are stable and shared with `../shared/peers/peer_bench.py`
//! so that figures compare side by side (see BENCHMARKS.md):
//! `read`, `connectivity` (half-edges with edge- and vertex-manifold checks),
//! `boundary_loops` (connectivity from scratch plus loops), `normals_area`,
//! `cotan_laplacian`, `mass_voronoi`, `intrinsic_delaunay`, ... Each crate
//! adds its operations in one module registered in [`GROUPS`].

mod core;
mod curvature;
mod geodesic;
mod nurbs;
mod param;
mod spectral;
mod wavelet;

use std::path::PathBuf;
use std::time::Instant;

use mesh_io::MeshData;
use mesh_kernel::TriMesh;
use serde_json::{json, Map, Value};

use crate::Result;

/// What one run leaves: its wall time in milliseconds and what it made
/// (dropped after the clock stopped).
type Sample = (f64, Box<dyn std::any::Any + Send>);

/// An operation to time: a name and a closure run once per sample.
pub struct Operation<'a> {
    /// Stable name (see the module documentation).
    pub name: &'static str,
    /// One run, timed inside: a setup may come before the clock starts, and
    /// what the run made is dropped after it stops.
    pub run: Box<dyn FnMut() -> Result<Sample> + Send + 'a>,
    /// The least memory traffic of one run in bytes (inputs read once,
    /// outputs written once), for operations bound by memory bandwidth:
    /// the achieved GB/s is printed, to read next to the machine's
    /// `stream_copy` and `gather_copy`.
    pub bytes: Option<usize>,
}

impl<'a> Operation<'a> {
    /// An operation from a closure returning anything.
    pub fn new<T: Send + 'static>(name: &'static str, mut f: impl FnMut() -> Result<T> + Send + 'a) -> Self {
        Self::after(name, || (), move |()| f())
    }

    /// An operation on the input `setup` makes before each run, outside the
    /// timed region (a copy of the mesh without its cached connectivity,
    /// as the peers get their arrays).
    pub fn after<S: Send + 'static, T: Send + 'static>(
        name: &'static str,
        mut setup: impl FnMut() -> S + Send + 'a,
        mut f: impl FnMut(S) -> Result<T> + Send + 'a,
    ) -> Self {
        let run = move || -> Result<Sample> {
            let input = setup();
            let start = Instant::now();
            let out = f(input)?;
            Ok((start.elapsed().as_secs_f64() * 1e3, Box::new(out)))
        };
        Self { name, run: Box::new(run), bytes: None }
    }

    /// [`Operation::after`] with a fresh copy of `mesh` (no cached
    /// connectivity) as the input.
    pub fn on_fresh<T: Send + 'static>(
        name: &'static str,
        mesh: &'a TriMesh,
        f: impl FnMut(TriMesh) -> Result<T> + Send + 'a,
    ) -> Self {
        Self::after(name, move || fresh(mesh), f)
    }

    /// The same operation with its least memory traffic per run.
    pub fn moving(self, bytes: usize) -> Self {
        Self { bytes: Some(bytes), ..self }
    }
}

/// Every group of operations: a function from the mesh file and its content
/// to the operations.
type Group = for<'a> fn(&'a std::path::Path, &'a MeshData) -> Vec<Operation<'a>>;
const GROUPS: &[Group] = &[
    core::operations,
    curvature::operations,
    geodesic::operations,
    nurbs::operations,
    param::operations,
    spectral::operations,
    wavelet::operations,
];

/// Arguments of `cargo xtask bench`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The mesh file to time operations on.
    #[arg(long)]
    mesh: PathBuf,
    /// Write the figures as JSON here.
    #[arg(long)]
    json: Option<PathBuf>,
    /// Runs per operation (the median is reported).
    #[arg(long, default_value_t = 7)]
    runs: usize,
    /// Only operations whose name contains one of these texts
    /// (comma-separated), e.g. `normals,cotan`.
    #[arg(long, value_delimiter = ',')]
    only: Vec<String>,
    /// Leave out operations whose name contains any of these texts
    /// (comma-separated), e.g. slow ones on a large mesh.
    #[arg(long, value_delimiter = ',')]
    skip: Vec<String>,
}

/// A copy of the mesh without its cached connectivity.
pub fn fresh(mesh: &TriMesh) -> TriMesh {
    // Positions and faces were validated when the mesh was built.
    TriMesh::new(mesh.positions().to_vec(), mesh.faces().to_vec()).expect("copy of a valid mesh")
}

/// Median wall time in milliseconds; the output of each run is dropped after
/// the clock stops. From 3 runs on, one untimed run comes first: it warms
/// the caches and builds what a group prepares lazily for its operations.
fn time(op: &mut Operation<'_>, runs: usize) -> Result<f64> {
    if runs >= 3 {
        drop((op.run)()?);
    }
    let mut samples = Vec::with_capacity(runs);
    for _ in 0..runs.max(1) {
        let (ms, out) = (op.run)()?;
        samples.push(ms);
        drop(out);
    }
    samples.sort_by(f64::total_cmp);
    Ok(samples[samples.len() / 2])
}

/// Runs `cargo xtask bench`.
pub fn run(args: &Args) -> Result<()> {
    let data = mesh_io::read(&args.mesh)?;
    let threads = rayon::current_num_threads();
    println!(
        "{} ({} vertices, {} faces), median of {} runs, ms",
        args.mesh.display(),
        data.mesh.vertex_count(),
        data.mesh.face_count(),
        args.runs
    );
    println!("{:<28} {:>12} {:>12} {:>10}", "operation", "1 thread", format!("{threads} threads"), "GB/s (1)");
    let single = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;
    let mut results = Map::new();
    for group in GROUPS {
        for mut op in group(&args.mesh, &data) {
            let skipped = args.skip.iter().any(|s| op.name.contains(s.as_str()));
            let chosen = args.only.is_empty() || args.only.iter().any(|o| op.name.contains(o.as_str()));
            if skipped || !chosen {
                continue;
            }
            mesh_kernel::faer::set_global_parallelism(mesh_kernel::faer::Par::Seq);
            let one = single.install(|| time(&mut op, args.runs));
            mesh_kernel::faer::set_global_parallelism(mesh_kernel::faer::Par::rayon(0));
            let all = time(&mut op, args.runs);
            let show = |r: &Result<f64>| match r {
                Ok(ms) => format!("{ms:12.3}"),
                Err(e) => format!("error: {e}"),
            };
            // Bytes per millisecond / 1e6 = GB/s.
            let rate = match (&one, op.bytes) {
                (Ok(ms), Some(b)) if *ms > 0.0 => Some(b as f64 / ms / 1e6),
                _ => None,
            };
            let shown = rate.map_or(String::new(), |r| format!("{r:10.2}"));
            println!("{:<28} {:>12} {:>12} {:>10}", op.name, show(&one), show(&all), shown);
            let value = |r: Result<f64>| r.map_or_else(|e| Value::String(format!("error: {e}")), |ms| json!(ms));
            results.insert(
                op.name.to_owned(),
                json!({"single_thread_ms": value(one), "default_threads_ms": value(all), "bytes": op.bytes, "single_thread_gb_per_s": rate}),
            );
        }
    }
    if let Some(path) = &args.json {
        let out = json!({
            "mesh": args.mesh.display().to_string(),
            "vertices": data.mesh.vertex_count(),
            "faces": data.mesh.face_count(),
            "runs": args.runs,
            "threads": threads,
            "ms": results,
        });
        std::fs::write(path, serde_json::to_string_pretty(&out)?)?;
    }
    Ok(())
}
