//! `mesh convert`: from one format to another, attributes kept where the
//! target format can hold them.

use std::path::PathBuf;

use crate::input::read_mesh;
use crate::output::{check_output, write_mesh, CliResult, WriteArgs};

/// Arguments of `mesh convert`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Input mesh file.
    pub(crate) input: PathBuf,
    /// Output mesh file; the format comes from its extension.
    output: PathBuf,
    /// Allow the output to be the input file.
    #[arg(long)]
    force: bool,
    #[command(flatten)]
    write: WriteArgs,
}

/// Runs `mesh convert`.
pub fn run(args: &Args) -> CliResult<()> {
    check_output(&args.output, Some(&args.input), args.force)?;
    let data = read_mesh(&args.input)?;
    write_mesh(&args.output, data.view(), &args.write.options(Default::default()))?;
    eprintln!(
        "wrote {} ({} vertices, {} faces)",
        args.output.display(),
        data.mesh.vertex_count(),
        data.mesh.face_count()
    );
    Ok(())
}
