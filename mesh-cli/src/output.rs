//! Shared output helpers: the error type, safe file writing, JSON printing.

use std::path::Path;

use serde::Serialize;

/// Commands return any error; `main` prints it and exits with status 1.
pub type CliResult<T> = Result<T, Box<dyn std::error::Error + Send + Sync>>;

/// Refuses to write over the input file unless `force` is set (writes
/// themselves are atomic: temporary file, then rename).
pub fn check_not_input(out: &Path, input: Option<&Path>, force: bool) -> CliResult<()> {
    if force {
        return Ok(());
    }
    if let Some(input) = input {
        let same = match (out.canonicalize(), input.canonicalize()) {
            (Ok(a), Ok(b)) => a == b,
            _ => out == input,
        };
        if same {
            return Err(
                format!("refusing to overwrite the input file {} (pass --force to allow it)", out.display()).into()
            );
        }
    }
    Ok(())
}

/// Creates the parent directory of `path` if needed.
pub fn ensure_parent(path: &Path) -> CliResult<()> {
    if let Some(dir) = path.parent() {
        if !dir.as_os_str().is_empty() {
            std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
        }
    }
    Ok(())
}

/// Prints a value as pretty JSON on standard output.
pub fn print_json<T: Serialize>(value: &T) -> CliResult<()> {
    println!("{}", serde_json::to_string_pretty(value)?);
    Ok(())
}

/// Writes a value as pretty JSON to a file, atomically.
pub fn write_json<T: Serialize>(path: &Path, value: &T) -> CliResult<()> {
    ensure_parent(path)?;
    let text = serde_json::to_string_pretty(value)?;
    mesh_io::write_atomic(path, |w| w.write_all(text.as_bytes()).map_err(|e| mesh_io::IoError::io(path, e)))?;
    Ok(())
}

/// Write options of every per-vertex field file: binary little-endian PLY
/// with positions and properties as `double`.
pub fn binary_ply() -> mesh_io::WriteOptions {
    mesh_io::WriteOptions {
        format: Some(mesh_io::Format::Ply),
        ply: mesh_io::PlyOptions { encoding: mesh_io::PlyEncoding::BinaryLittleEndian, ..Default::default() },
        ..Default::default()
    }
}

/// Replaces non-finite numbers by `None` so that JSON stays valid.
pub fn finite(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}
