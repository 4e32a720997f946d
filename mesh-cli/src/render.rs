//! Pictures: the renderer is the `mesh-render` crate; this module writes
//! its pictures as PNG files, atomically.

use std::path::Path;

use mesh_kernel::TriMesh;
pub use mesh_render::RenderOptions;

use crate::output::CliResult;

/// Renders the mesh (coloured by `scalar` when given, with a colour bar) to a PNG file.
pub fn render_png(mesh: &TriMesh, scalar: Option<&[f64]>, path: &Path, options: &RenderOptions) -> CliResult<()> {
    let image = mesh_render::render_field(mesh, scalar, options)?;
    write_png(path, &image)
}

/// Writes a picture as a PNG file, atomically (a temporary file renamed
/// over `path`, which is untouched on error).
pub fn write_png(path: &Path, image: &mesh_render::Image) -> CliResult<()> {
    mesh_io::write_atomic(path, |w| -> CliResult<()> {
        image.write_png(w)?;
        Ok(())
    })
}
