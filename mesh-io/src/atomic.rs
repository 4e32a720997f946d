//! Atomic file writes: readers of a path see the old file or the complete new
//! one, never a partial write.

use std::fs::{File, OpenOptions};
use std::io::{BufWriter, ErrorKind, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{SystemTime, UNIX_EPOCH};

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
    let name = path.file_name().map(|n| n.to_string_lossy()).unwrap_or_default();
    let mut tmp = TempFile::create(dir, &name).map_err(io)?;
    {
        let mut out = BufWriter::with_capacity(1 << 16, &mut tmp.file);
        write(&mut out)?;
        out.flush().map_err(io)?;
    }
    tmp.persist(path).map_err(io)
}

/// A hidden temporary file beside the target, removed on drop unless
/// persisted. Created with `create_new` (never an existing file) and the
/// permissions of any new file (0666 less the umask). Written here rather
/// than taken from the tempfile crate, which brought eight crates into
/// mesh-io's dependency tree for these few lines.
struct TempFile {
    path: Option<PathBuf>,
    file: File,
}

impl TempFile {
    fn create(dir: &Path, target: &str) -> std::io::Result<Self> {
        static COUNTER: AtomicU64 = AtomicU64::new(0);
        let nanos = SystemTime::now().duration_since(UNIX_EPOCH).map_or(0, |d| d.subsec_nanos());
        let mut last = None;
        for _ in 0..64 {
            let n = COUNTER.fetch_add(1, Ordering::Relaxed);
            let path = dir.join(format!(".{target}.{:x}-{nanos:x}-{n}.tmp", std::process::id()));
            match OpenOptions::new().write(true).create_new(true).open(&path) {
                Ok(file) => return Ok(Self { path: Some(path), file }),
                Err(e) if e.kind() == ErrorKind::AlreadyExists => last = Some(e),
                Err(e) => return Err(e),
            }
        }
        Err(last.unwrap_or_else(|| ErrorKind::AlreadyExists.into()))
    }

    /// Renames the file over `target` (atomic within one file system).
    fn persist(mut self, target: &Path) -> std::io::Result<()> {
        let path = self.path.take().ok_or(ErrorKind::NotFound)?;
        std::fs::rename(&path, target).inspect_err(|_| {
            let _ = std::fs::remove_file(&path);
        })
    }
}

impl Drop for TempFile {
    fn drop(&mut self) {
        if let Some(path) = &self.path {
            let _ = std::fs::remove_file(path);
        }
    }
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
