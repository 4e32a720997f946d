//! `mesh generate`: writes a built-in shape to a file.

use std::path::PathBuf;

use crate::input::InputArgs;
use crate::output::{check_output, write_mesh, CliResult, WriteArgs};

/// Arguments of `mesh generate`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Output mesh file; the format comes from its extension.
    output: PathBuf,
    /// Built-in shape: icosphere, uv-sphere, torus, cylinder, grid, disk, cube.
    #[arg(long, default_value = crate::input::DEFAULT_SHAPE)]
    shape: String,
    /// Resolution (icosphere: level; others: segments).
    #[arg(long)]
    res: Option<usize>,
    #[command(flatten)]
    write: WriteArgs,
}

/// Runs `mesh generate`.
pub fn run(args: &Args) -> CliResult<()> {
    check_output(&args.output, None, false)?;
    let input = InputArgs { file: None, shape: Some(args.shape.clone()), res: args.res };
    let data = input.load()?;
    write_mesh(&args.output, &data.mesh, &args.write.options(Default::default()))?;
    eprintln!(
        "wrote {} ({}: {} vertices, {} faces)",
        args.output.display(),
        input.describe(),
        data.mesh.vertex_count(),
        data.mesh.face_count()
    );
    Ok(())
}
