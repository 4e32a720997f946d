//! `mesh clean`: repair a mesh and say what changed.

use std::path::PathBuf;

use mesh_kernel::clean::{CleanOptions, CleanReport};
use serde::Serialize;

use crate::input::read_mesh;
use crate::output::{check_output, print_json, write_mesh, CliResult, WriteArgs};

/// Arguments of `mesh clean`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Input mesh file.
    pub(crate) input: PathBuf,
    /// Output mesh file.
    output: PathBuf,
    /// Weld vertices closer than this distance (default: identical positions
    /// only); at most the bounding box diagonal.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    weld: f64,
    /// Make the result an oriented manifold: edges with three or more faces
    /// keep their best-continuing pair and detach the others, unorientable
    /// gluing is cut, vertices with several fans are split (one copy per fan).
    #[arg(long)]
    manifold: bool,
    /// Do not flip faces to a consistent (outward) orientation.
    #[arg(long)]
    no_orient: bool,
    /// Allow the output to be the input file.
    #[arg(long)]
    force: bool,
    #[command(flatten)]
    write: WriteArgs,
    /// Print the report as JSON.
    #[arg(long)]
    json: bool,
}

/// What `mesh_kernel::clean` changed, and the size of its result.
#[derive(Debug, Clone, Serialize)]
pub(crate) struct Summary {
    welded_vertices: usize,
    collapsed_faces: usize,
    degenerate_faces: usize,
    duplicate_faces: usize,
    unreferenced_vertices: usize,
    fin_edges: usize,
    detached_faces: usize,
    cut_edges: usize,
    split_vertices: usize,
    flipped_faces: usize,
    unorientable_components: usize,
    vertices: usize,
    faces: usize,
    manifold: bool,
}

impl Summary {
    pub(crate) fn new(r: &CleanReport, mesh: &mesh_kernel::TriMesh) -> Self {
        Self {
            welded_vertices: r.welded_vertices,
            collapsed_faces: r.collapsed_faces,
            degenerate_faces: r.degenerate_faces,
            duplicate_faces: r.duplicate_faces,
            unreferenced_vertices: r.unreferenced_vertices,
            fin_edges: r.fin_edges,
            detached_faces: r.detached_faces,
            cut_edges: r.cut_edges,
            split_vertices: r.split_vertices,
            flipped_faces: r.flipped_faces,
            unorientable_components: r.unorientable_components,
            vertices: mesh.vertex_count(),
            faces: mesh.face_count(),
            manifold: mesh.connectivity().require_manifold().is_ok(),
        }
    }
}

impl Args {
    /// The library options set from flags, for [`crate::errors::translate`].
    pub fn given(&self) -> Vec<(&'static str, String)> {
        vec![("weld_tolerance", crate::errors::flag("--weld", crate::errors::number(self.weld)))]
    }
}

/// Runs `mesh clean`.
pub fn run(args: &Args) -> CliResult<()> {
    check_output(&args.output, Some(&args.input), args.force)?;
    let data = read_mesh(&args.input)?;
    let options = CleanOptions {
        weld_tolerance: Some(args.weld),
        manifold: args.manifold,
        orient: !args.no_orient,
        ..CleanOptions::default()
    };
    let (mesh, report) = data.mesh.cleaned(&options)?;
    write_mesh(&args.output, &mesh, &args.write.options(Default::default()))?;
    let summary = Summary::new(&report, &mesh);
    if args.json {
        print_json(&summary)
    } else {
        println!("cleaned {} -> {}", args.input.display(), args.output.display());
        println!("  welded vertices          {}", summary.welded_vertices);
        println!("  collapsed faces          {}", summary.collapsed_faces);
        println!("  degenerate faces         {}", summary.degenerate_faces);
        println!("  duplicate faces          {}", summary.duplicate_faces);
        println!("  unreferenced vertices    {}", summary.unreferenced_vertices);
        if args.manifold {
            println!("  fin edges (3+ faces)     {}", summary.fin_edges);
            println!("  detached faces           {}", summary.detached_faces);
            println!("  cut edges                {}", summary.cut_edges);
            println!("  split vertices           {}", summary.split_vertices);
        }
        println!("  flipped faces            {}", summary.flipped_faces);
        println!("  unorientable components  {}", summary.unorientable_components);
        let manifold = if summary.manifold { "oriented manifold" } else { "not an oriented manifold (see --manifold)" };
        println!("  result                   {} vertices, {} faces, {manifold}", summary.vertices, summary.faces);
        Ok(())
    }
}
