//! Where a command's mesh comes from: a file, or a built-in shape.

use std::path::{Path, PathBuf};

use mesh_io::MeshData;
use mesh_kernel::shapes;

use crate::output::CliResult;

/// The input of every command: a mesh file, or a built-in shape (the
/// default, so that a fresh checkout can run any command at once).
#[derive(Debug, Clone, clap::Args)]
pub struct InputArgs {
    /// Mesh file (.obj, .off, .ply, .stl, .gltf, .glb). Without it, --shape is used.
    #[arg(value_name = "FILE", conflicts_with = "shape")]
    pub file: Option<PathBuf>,
    /// Built-in shape: icosphere, uv-sphere, torus, cylinder, grid, disk, cube.
    #[arg(long, value_name = "NAME")]
    pub shape: Option<String>,
    /// Resolution of the built-in shape (icosphere: subdivision level; others:
    /// segments per unit direction). Default: 4 for the icosphere, 32 otherwise.
    #[arg(long, value_name = "N")]
    pub res: Option<usize>,
}

/// Reads a mesh file; every command reads through here, so that each one
/// prints (on standard error) a one-line notice when the reader changed
/// something: faces dropped, polygons triangulated, vertices welded, parts
/// of the file not read.
pub fn read_mesh(path: &Path) -> CliResult<MeshData> {
    let data = mesh_io::read(path).map_err(crate::errors::io)?;
    if !data.report.is_clean() {
        eprintln!("mesh: note: reading {} changed the mesh: {}", path.display(), data.report);
    }
    Ok(data)
}

/// The default shape when neither a file nor a shape is given.
pub const DEFAULT_SHAPE: &str = "icosphere";

impl InputArgs {
    /// Reads the file or builds the shape.
    pub fn load(&self) -> CliResult<MeshData> {
        match &self.file {
            Some(path) => read_mesh(path),
            None => {
                let name = self.shape.as_deref().unwrap_or(DEFAULT_SHAPE);
                let default_res = if name == "icosphere" { 4 } else { 32 };
                Ok(MeshData::new(shapes::by_name(name, self.res.unwrap_or(default_res))?))
            }
        }
    }

    /// A short name for reports: the file path or `shape:NAME:N`.
    pub fn describe(&self) -> String {
        match &self.file {
            Some(p) => p.display().to_string(),
            None => {
                let name = self.shape.as_deref().unwrap_or(DEFAULT_SHAPE);
                let default_res = if name == "icosphere" { 4 } else { 32 };
                format!("shape:{name}:{}", self.res.unwrap_or(default_res))
            }
        }
    }

    /// The input file, if any.
    pub fn path(&self) -> Option<&Path> {
        self.file.as_deref()
    }
}
