//! Atomic file writes: readers of a path see the old file or the complete new
//! one, never a partial write.

use std::io::{BufWriter, Write};
use std::path::Path;

use crate::error::IoError;

/// Writes a file atomically: `write` fills a temporary file created in the
/// same directory as `path`, which then replaces `path` by a rename. When
/// `write` fails, the temporary file is removed and `path` is untouched.
///
/// The writer handed to `write` is buffered. The file is not `fsync`ed: the
/// rename is atomic for other processes, not against a power cut. Any error
/// type that wraps [`IoError`] can be used.
///
/// ```
/// # fn main() -> Result<(), mesh_io::IoError> {
/// let dir = tempfile::tempdir().map_err(|e| mesh_io::IoError::io(std::path::Path::new("."), e))?;
/// let path = dir.path().join("report.txt");
/// mesh_io::write_atomic(&path, |w| w.write_all(b"done\n").map_err(|e| mesh_io::IoError::io(&path, e)))?;
/// assert_eq!(std::fs::read(&path).unwrap(), b"done\n");
/// # Ok(()) }
/// ```
///
/// # Errors
/// Whatever `write` returns, and an error converted from `IoError::Io` when the temporary file cannot be
/// created, flushed or renamed over `path` (a missing folder included); `path` is left untouched on error.
pub fn write_atomic<E: From<IoError>>(
    path: impl AsRef<Path>,
    write: impl FnOnce(&mut dyn Write) -> Result<(), E>,
) -> Result<(), E> {
    let path = path.as_ref();
    let io = |e| E::from(IoError::io(path, e));
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let prefix = format!(".{}.", path.file_name().map(|n| n.to_string_lossy()).unwrap_or_default());
    let mut tmp = temp_builder(&prefix).tempfile_in(dir).map_err(io)?;
    {
        let mut out = BufWriter::with_capacity(1 << 16, tmp.as_file_mut());
        write(&mut out)?;
        out.flush().map_err(io)?;
    }
    tmp.persist(path).map_err(|e| io(e.error))?;
    Ok(())
}

/// Temporary files are hidden, named after the target, and (on Unix) get the
/// permissions of a newly created file (0666 less the umask) instead of 0600.
fn temp_builder(prefix: &str) -> tempfile::Builder<'_, 'static> {
    let mut builder = tempfile::Builder::new();
    builder.prefix(prefix).suffix(".tmp");
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    builder
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn replaces_whole_file_or_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.txt");
        write_atomic::<IoError>(&path, |w| Ok(w.write_all(b"one")?)).unwrap();
        let failed = write_atomic::<IoError>(&path, |w| {
            w.write_all(b"partial").unwrap();
            Err(IoError::io(&path, std::io::Error::other("stop")))
        });
        assert!(failed.is_err());
        assert_eq!(std::fs::read(&path).unwrap(), b"one");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1, "temporary file left behind");
    }

    #[test]
    fn missing_directory_is_a_typed_error() {
        let e = write_atomic::<IoError>("/nonexistent-dir/x.ply", |_| Ok(())).unwrap_err();
        assert!(matches!(e, IoError::Io { .. }));
    }
}
