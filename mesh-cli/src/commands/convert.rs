//! `mesh convert`: from one format to another, attributes kept where the
//! target format can hold them.

use std::path::PathBuf;

use crate::output::{check_not_input, ensure_parent, CliResult};

/// Arguments of `mesh convert`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Input mesh file.
    input: PathBuf,
    /// Output mesh file; the format comes from its extension.
    output: PathBuf,
    /// Allow the output to be the input file.
    #[arg(long)]
    force: bool,
}

/// Runs `mesh convert`.
pub fn run(args: &Args) -> CliResult<()> {
    check_not_input(&args.output, Some(&args.input), args.force)?;
    let data = mesh_io::read(&args.input)?;
    ensure_parent(&args.output)?;
    mesh_io::write(&args.output, data.view(), &mesh_io::WriteOptions::default())?;
    eprintln!(
        "wrote {} ({} vertices, {} faces)",
        args.output.display(),
        data.mesh.vertex_count(),
        data.mesh.face_count()
    );
    Ok(())
}
