//! `mesh clean`: repair a mesh and say what changed.

use std::path::PathBuf;

use mesh_core::clean::{CleanOptions, CleanReport};
use serde::Serialize;

use crate::output::{check_not_input, ensure_parent, print_json, CliResult};

/// Arguments of `mesh clean`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Input mesh file.
    input: PathBuf,
    /// Output mesh file.
    output: PathBuf,
    /// Weld vertices closer than this distance (default: identical positions only).
    #[arg(long, default_value_t = 0.0)]
    weld: f64,
    /// Do not flip faces to a consistent (outward) orientation.
    #[arg(long)]
    no_orient: bool,
    /// Allow the output to be the input file.
    #[arg(long)]
    force: bool,
    /// Print the report as JSON.
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct Summary {
    welded_vertices: usize,
    collapsed_faces: usize,
    degenerate_faces: usize,
    duplicate_faces: usize,
    unreferenced_vertices: usize,
    flipped_faces: usize,
    unorientable_components: usize,
    vertices: usize,
    faces: usize,
}

impl Summary {
    fn new(r: &CleanReport, vertices: usize, faces: usize) -> Self {
        Self {
            welded_vertices: r.welded_vertices,
            collapsed_faces: r.collapsed_faces,
            degenerate_faces: r.degenerate_faces,
            duplicate_faces: r.duplicate_faces,
            unreferenced_vertices: r.unreferenced_vertices,
            flipped_faces: r.flipped_faces,
            unorientable_components: r.unorientable_components,
            vertices,
            faces,
        }
    }
}

/// Runs `mesh clean`.
pub fn run(args: &Args) -> CliResult<()> {
    check_not_input(&args.output, Some(&args.input), args.force)?;
    let data = mesh_io::read(&args.input)?;
    let options = CleanOptions { weld_tolerance: Some(args.weld), orient: !args.no_orient, ..CleanOptions::default() };
    let (mesh, report) = data.mesh.cleaned(&options)?;
    ensure_parent(&args.output)?;
    mesh_io::write(&args.output, &mesh, &mesh_io::WriteOptions::default())?;
    let summary = Summary::new(&report, mesh.vertex_count(), mesh.face_count());
    if args.json {
        print_json(&summary)
    } else {
        println!("cleaned {} -> {}", args.input.display(), args.output.display());
        println!("  welded vertices          {}", summary.welded_vertices);
        println!("  collapsed faces          {}", summary.collapsed_faces);
        println!("  degenerate faces         {}", summary.degenerate_faces);
        println!("  duplicate faces          {}", summary.duplicate_faces);
        println!("  unreferenced vertices    {}", summary.unreferenced_vertices);
        println!("  flipped faces            {}", summary.flipped_faces);
        println!("  unorientable components  {}", summary.unorientable_components);
        println!("  result                   {} vertices, {} faces", summary.vertices, summary.faces);
        Ok(())
    }
}
