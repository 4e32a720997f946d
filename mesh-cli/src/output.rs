//! Shared output helpers: the error type, safe file writing, JSON printing.

use std::path::Path;

use serde::Serialize;

/// Any error a command returns; `main` prints it and exits with status 1.
pub type CliError = Box<dyn std::error::Error + Send + Sync>;

/// Commands return any error; `main` prints it and exits with status 1.
pub type CliResult<T> = Result<T, CliError>;

/// Checks an output path before any work is done: its folder must exist
/// (no command creates folders for its outputs, except `mesh report` for
/// its own `--out` folder), and it must not be the input file unless `force`
/// is set (writes themselves are atomic: temporary file, then rename).
pub fn check_output(out: &Path, input: Option<&Path>, force: bool) -> CliResult<()> {
    check_folder(out)?;
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

/// Refuses an output path whose folder does not exist.
pub fn check_folder(out: &Path) -> CliResult<()> {
    match out.parent() {
        Some(dir) if !dir.as_os_str().is_empty() && !dir.is_dir() => Err(format!(
            "cannot write {}: the folder {} does not exist (create it first, e.g. `mkdir -p {}`)",
            out.display(),
            dir.display(),
            dir.display()
        )
        .into()),
        _ => Ok(()),
    }
}

/// The write option every command that writes a mesh file shares.
#[derive(Debug, Clone, Copy, Default, clap::Args)]
pub struct WriteArgs {
    /// Write coordinates and attributes that a 32-bit float format (STL,
    /// glTF/GLB, float PLY) cannot hold (they become infinite or zero)
    /// instead of refusing.
    #[arg(long)]
    pub allow_precision_loss: bool,
}

/// `--json`, `--force` and the [`WriteArgs`] of a command that writes a mesh
/// and prints a summary. A command whose flags say it otherwise changes the
/// help with `#[command(mut_arg(..))]`.
#[derive(Debug, clap::Args)]
pub struct SaveArgs {
    /// Print a JSON summary.
    #[arg(long)]
    pub json: bool,
    /// Allow writing over the input file.
    #[arg(long)]
    pub force: bool,
    #[command(flatten)]
    pub write: WriteArgs,
}

impl WriteArgs {
    /// `options` with this command line's choices.
    pub fn options(&self, options: mesh_io::WriteOptions) -> mesh_io::WriteOptions {
        mesh_io::WriteOptions { allow_precision_loss: self.allow_precision_loss, ..options }
    }
}

/// Writes a mesh file (the folder must exist, see [`check_output`]) and
/// prints a one-line warning on standard error when values stored as 32-bit
/// floats were rounded by more than 1e-6 of the mesh's size or lost.
pub fn write_mesh<'a>(
    path: &Path,
    data: impl Into<mesh_io::MeshView<'a>>,
    options: &mesh_io::WriteOptions,
) -> CliResult<mesh_io::WriteReport> {
    check_folder(path)?;
    let report = mesh_io::write(path, data, options).map_err(crate::errors::io)?;
    if !report.is_clean() {
        eprintln!("mesh: warning: {}: {report}", path.display());
    }
    Ok(report)
}

/// Prints a value as pretty JSON on standard output ([`json_text`]).
pub fn print_json<T: Serialize>(value: &T) -> CliResult<()> {
    println!("{}", json_text(value, true)?);
    Ok(())
}

/// Writes a value as pretty JSON to a file, atomically ([`json_text`]).
pub fn write_json<T: Serialize>(path: &Path, value: &T) -> CliResult<()> {
    check_folder(path)?;
    let text = json_text(value, true)?;
    mesh_io::write_atomic(path, |w| w.write_all(text.as_bytes()).map_err(|e| mesh_io::IoError::io(path, e)))?;
    Ok(())
}

/// The JSON text of a value, pretty or on one line, with every `-0.0`
/// written `0.0`: Rust's sum of no `f64` is `-0.0`, as are some products
/// on flat surfaces, and the sign of a zero means nothing in a report.
pub fn json_text<T: Serialize>(value: &T, pretty: bool) -> CliResult<String> {
    let mut value = serde_json::to_value(value)?;
    unsign_zeros(&mut value);
    Ok(if pretty { serde_json::to_string_pretty(&value)? } else { serde_json::to_string(&value)? })
}

fn unsign_zeros(value: &mut serde_json::Value) {
    use serde_json::Value;
    match value {
        Value::Number(n) if n.is_f64() && n.as_f64() == Some(0.0) => *value = Value::from(0.0),
        Value::Array(items) => items.iter_mut().for_each(unsign_zeros),
        Value::Object(fields) => fields.values_mut().for_each(unsign_zeros),
        _ => {}
    }
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

/// Minimum, maximum, mean and count of the finite values at the indices
/// `keep` accepts; `null` when there are none.
pub fn stats(values: &[f64], keep: impl Fn(usize) -> bool) -> serde_json::Value {
    let kept: Vec<f64> =
        values.iter().enumerate().filter(|(i, v)| keep(*i) && v.is_finite()).map(|(_, v)| *v).collect();
    if kept.is_empty() {
        return serde_json::Value::Null;
    }
    let min = kept.iter().copied().fold(f64::INFINITY, f64::min);
    let max = kept.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    serde_json::json!({ "min": min, "max": max, "mean": kept.iter().sum::<f64>() / kept.len() as f64, "count": kept.len() })
}

#[cfg(test)]
mod tests {
    use super::json_text;

    #[test]
    fn json_text_writes_no_negative_zero() {
        let value = serde_json::json!({"sum": -0.0, "stats": [-0.0, 0.0, -1.5, 2], "nested": {"k2": -0.0}});
        for pretty in [false, true] {
            let text = json_text(&value, pretty).unwrap();
            assert!(!text.contains("-0.0") && text.contains("-1.5"), "{text}");
            let back: serde_json::Value = serde_json::from_str(&text).unwrap();
            assert_eq!(back["stats"][0].as_f64().map(f64::is_sign_positive), Some(true));
            assert_eq!(back["stats"][3], 2);
        }
    }
}
