//! `mesh`: every algorithm of the workspace on a mesh file or a built-in shape.
//!
//! Each subcommand lives in its own module under `commands/` with an `Args`
//! struct (clap) and a `run` function; this file only lists them.

mod choice;
mod commands;
mod errors;
mod input;
mod output;
mod render;

use clap::{Parser, Subcommand};

/// Freed large arrays kept for the next stage instead of faulted in again
/// (see `mesh_kernel::alloc`).
#[global_allocator]
static ALLOCATOR: mesh_kernel::alloc::BlockCache = mesh_kernel::alloc::BlockCache;

/// Digital shape processing on triangle meshes.
#[derive(Debug, Parser)]
#[command(name = "mesh", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

/// One variant per subcommand, each with its module in `commands/`.
#[derive(Debug, Subcommand)]
enum Command {
    /// Counts, topology, manifoldness and defects of a mesh.
    Info(commands::info::Args),
    /// Converts between formats (OBJ, OFF, PLY, STL, glTF).
    Convert(commands::convert::Args),
    /// Repairs a mesh: weld, drop degenerate/duplicate faces and unreferenced vertices, orient.
    Clean(commands::clean::Args),
    /// Writes a built-in shape to a mesh file.
    Generate(commands::generate::Args),
    /// Renders a mesh, optionally coloured by a per-vertex field, to a PNG picture.
    Render(commands::render::Args),
    /// Runs every analysis on a mesh and writes a JSON report and viewer-ready files.
    Report(commands::report::Args),
    /// Draws the chapter's figures (2.4-2.14) with the workspace's algorithms, as PNGs with caption files.
    Figures(commands::figures::Args),
    /// Gaussian, mean and principal curvatures and directions, to a PLY file.
    Curvature(commands::curvature::Args),
    /// Flattens a mesh onto the plane (Tutte, mean-value, harmonic, authalic, intrinsic, LSCM, ARAP), to an OBJ with UVs.
    Param(commands::param::Args),
    /// Geodesic distance from source vertices (heat, fmm, dijkstra, exact), to a PLY file; optional path to an OBJ polyline.
    Geodesic(commands::geodesic::Args),
    /// Tessellates an exact NURBS surface, with its exact curvatures, to a PLY file.
    Nurbs(commands::nurbs::Args),
    /// Smallest Laplacian eigenpairs to a PLY file; spectral filter, compress and heat kernel signature.
    Spectral(commands::spectral::Args),
    /// 4-to-1 subdivision: midpoint, Loop or modified butterfly.
    Subdivide(commands::wavelet::SubdivideArgs),
    /// Wavelet multiresolution analysis: statistics, compression, levels of detail.
    Wavelet(commands::wavelet::Args),
    /// Operations over every mesh of a folder or pattern, in parallel and resumable, to JSON lines.
    Batch(commands::batch::Args),
    /// Planar Delaunay triangulation of points (or by Lawson flips), Voronoi cells, constrained refinement of a polygon.
    Delaunay(commands::delaunay::Args),
    /// Remeshes a surface to a target edge length through a parameterization, with a quality and Hausdorff report.
    Remesh(commands::remesh::Args),
}

impl Command {
    /// The mesh file the command read, if any (errors name it).
    fn input_file(&self) -> Option<&std::path::Path> {
        match self {
            Command::Info(a) => a.input.path(),
            Command::Convert(a) => Some(&a.input),
            Command::Clean(a) => Some(&a.input),
            Command::Render(a) => a.input.path(),
            Command::Report(a) => a.input.path(),
            Command::Curvature(a) => a.input.path(),
            Command::Param(a) => a.input.path(),
            Command::Geodesic(a) => a.input.path(),
            Command::Spectral(a) => a.input_file(),
            Command::Subdivide(a) => a.input_file(),
            Command::Wavelet(a) => a.input_file(),
            Command::Delaunay(a) => a.input_file(),
            Command::Remesh(a) => a.input.path(),
            Command::Generate(_) | Command::Nurbs(_) | Command::Batch(_) | Command::Figures(_) => None,
        }
    }

    /// The library options this command line set, with the flags as typed
    /// (see [`errors::Given`]).
    fn given(&self) -> Vec<(&'static str, String)> {
        match self {
            Command::Geodesic(args) => args.given(),
            Command::Clean(args) => args.given(),
            Command::Param(args) => args.given(),
            Command::Spectral(args) => args.given(),
            Command::Subdivide(args) => args.given(),
            Command::Wavelet(args) => args.given(),
            Command::Curvature(args) => args.given(),
            Command::Delaunay(args) => args.given(),
            Command::Remesh(args) => args.given(),
            _ => Vec::new(),
        }
    }
}

/// Exits quietly when standard output is closed early (`mesh info | head`):
/// `println!` panics on a broken pipe, which here is not an error.
fn exit_quietly_on_broken_pipe() {
    let default_hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let message = info
            .payload()
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| info.payload().downcast_ref::<&str>().copied())
            .unwrap_or("");
        if message.contains("Broken pipe") {
            std::process::exit(0);
        }
        default_hook(info);
    }));
}

fn main() {
    exit_quietly_on_broken_pipe();
    let cli = Cli::parse();
    let result = match &cli.command {
        Command::Info(args) => commands::info::run(args),
        Command::Convert(args) => commands::convert::run(args),
        Command::Clean(args) => commands::clean::run(args),
        Command::Generate(args) => commands::generate::run(args),
        Command::Render(args) => commands::render::run(args),
        Command::Report(args) => commands::report::run(args),
        Command::Figures(args) => commands::figures::run(args),
        Command::Curvature(args) => commands::curvature::run(args),
        Command::Param(args) => commands::param::run(args),
        Command::Geodesic(args) => commands::geodesic::run(args),
        Command::Nurbs(args) => commands::nurbs::run(args),
        Command::Spectral(args) => commands::spectral::run(args),
        Command::Subdivide(args) => commands::wavelet::run_subdivide(args),
        Command::Wavelet(args) => commands::wavelet::run(args),
        Command::Batch(args) => commands::batch::run(args),
        Command::Delaunay(args) => commands::delaunay::run(args),
        Command::Remesh(args) => commands::remesh::run(args),
    };
    if let Err(e) = result {
        let e = errors::translate(e, &cli.command.given(), cli.command.input_file());
        eprintln!("mesh: error: {e}");
        std::process::exit(1);
    }
}
