//! The error type of this crate: every failure names the file, the line (in
//! text formats) and what was expected.

use std::fmt;
use std::path::{Path, PathBuf};

use mesh_kernel::MeshError;
use thiserror::Error;

use crate::format::Format;

/// Where in the input an error happened: file (when reading from a path),
/// format, and line (text formats only).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Location {
    /// The file, when the data came from a path.
    pub path: Option<PathBuf>,
    /// The format being read or written.
    pub format: Format,
    /// The 1-based line, in text formats.
    pub line: Option<usize>,
}

impl Location {
    /// A location in `format` data with no path and no line yet.
    pub fn new(format: Format) -> Self {
        Self { path: None, format, line: None }
    }

    /// The same location at a 1-based line.
    pub fn at_line(format: Format, line: usize) -> Self {
        Self { path: None, format, line: Some(line) }
    }
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.format)?;
        if let Some(path) = &self.path {
            write!(f, " file {}", path.display())?;
        }
        if let Some(line) = self.line {
            write!(f, " line {line}")?;
        }
        Ok(())
    }
}

/// Everything that can go wrong while reading or writing a mesh file.
///
/// Errors from per-format functions working on bytes carry no path;
/// [`crate::read`] and [`crate::write`] fill it in ([`IoError::with_path`]).
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum IoError {
    /// The operating system refused to read or write a file or stream.
    #[error("{}: {source}", path.as_deref().map_or("<stream>".into(), Path::to_string_lossy))]
    Io {
        /// The file (`None` for a stream without a name).
        path: Option<PathBuf>,
        /// The underlying error.
        source: std::io::Error,
    },
    /// The file name has no extension this crate knows.
    #[error("{}: unknown mesh format (expected .obj, .off, .ply, .stl, .gltf or .glb)", path.display())]
    UnknownFormat {
        /// The file.
        path: PathBuf,
    },
    /// The content is not of the format its name says (wrong magic bytes).
    #[error("{at}: not a {} file: expected {expected}, found {found}", at.format)]
    WrongMagic {
        /// Where.
        at: Location,
        /// What the format starts with.
        expected: &'static str,
        /// What the file starts with.
        found: String,
    },
    /// A token or header line is not what the format requires here.
    #[error("{at}: expected {expected}, found {found}")]
    Syntax {
        /// Where.
        at: Location,
        /// What the reader expected.
        expected: String,
        /// What it found (quoted excerpt).
        found: String,
    },
    /// The data ends before everything announced was read.
    #[error("{at}: the data ends early: expected {expected}")]
    Truncated {
        /// Where.
        at: Location,
        /// What was still missing.
        expected: String,
    },
    /// A header count that is negative, too large for 32-bit indices, or
    /// larger than the data could hold (checked before allocating).
    #[error("{at}: impossible {what} count {count}: {reason}")]
    Count {
        /// Where.
        at: Location,
        /// Which element is counted.
        what: String,
        /// The count as written.
        count: i128,
        /// Why it is refused.
        reason: String,
    },
    /// A face refers to a vertex (or texture coordinate) that does not exist.
    #[error("{at}: face {face} refers to {what} {index}, but there are only {count}")]
    Index {
        /// Where.
        at: Location,
        /// The face, numbered from 0 in file order.
        face: usize,
        /// `"vertex"`, `"texture coordinate"`, ...
        what: &'static str,
        /// The index as written (after resolving the format's base).
        index: i64,
        /// How many such elements exist.
        count: usize,
    },
    /// A vertex position is NaN or infinite.
    #[error("{at}: vertex {vertex} has a non-finite coordinate")]
    NonFinite {
        /// Where.
        at: Location,
        /// The vertex, numbered from 0.
        vertex: usize,
    },
    /// A valid file using a feature this crate does not read or write.
    #[error("{at}: unsupported: {what}")]
    Unsupported {
        /// Where.
        at: Location,
        /// The feature.
        what: String,
    },
    /// The positions and faces read do not make a valid [`mesh_kernel::TriMesh`].
    #[error("{at}: {source}")]
    Mesh {
        /// Where.
        at: Location,
        /// Why the mesh was refused.
        source: MeshError,
    },
    /// An attribute handed to a writer has the wrong length.
    #[error("{what} has {found} entries, expected {expected}")]
    AttributeLength {
        /// The attribute (`"normals"`, `"vertex scalar `mean`"`, ...).
        what: String,
        /// One per vertex, or per face for corner UVs and face attributes.
        expected: usize,
        /// What was given.
        found: usize,
    },
    /// A named attribute handed to a writer has an empty name or shares its
    /// name with another attribute of the same element.
    #[error("{what}: {problem}")]
    AttributeName {
        /// The attribute (`"vertex scalar `mean`"`, ...).
        what: String,
        /// What is wrong with its name.
        problem: String,
    },
    /// A glTF buffer `uri` that may not be read: not a `data:` URI or a
    /// relative path to a regular file inside the `.gltf` file's folder, or a
    /// file shorter than the buffer's `byteLength`.
    #[error("{at}: buffer uri `{uri}` refused: {reason}")]
    ExternalBuffer {
        /// Where (the `.gltf` file).
        at: Location,
        /// The URI as written.
        uri: String,
        /// Why it is refused, naming the file it resolves to when it got that far.
        reason: String,
    },
    /// A value the format stores as a 32-bit float would be lost: finite but
    /// beyond the `f32` range, or non-zero but flushed to zero (see
    /// [`crate::precision`]). [`crate::WriteOptions::allow_precision_loss`]
    /// writes it anyway.
    #[error("{at}: the {what} is {value:e}, which {problem}; write a format that stores 64-bit values (OBJ, OFF, PLY with double), rescale the mesh, or allow the loss")]
    Precision {
        /// Where (the format written).
        at: Location,
        /// The value, e.g. "position of vertex 12".
        what: String,
        /// The value in `f64`.
        value: f64,
        /// What would happen to it.
        problem: &'static str,
    },
    /// The glTF JSON is malformed or does not validate.
    #[cfg(feature = "gltf")]
    #[error("{at}: {source}")]
    Gltf {
        /// Where.
        at: Location,
        /// The gltf crate's error.
        source: gltf::Error,
    },
}

impl From<std::io::Error> for IoError {
    /// An I/O error on a stream; [`IoError::with_path`] names the file.
    fn from(source: std::io::Error) -> Self {
        Self::Io { path: None, source }
    }
}

/// Shorthand for results in this crate.
pub type Result<T, E = IoError> = std::result::Result<T, E>;

/// The location field of an [`IoError`] (by reference or by mutable
/// reference, as `$error` is), or `None` for the variants without one.
macro_rules! location_of {
    ($error:expr) => {
        match $error {
            IoError::WrongMagic { at, .. }
            | IoError::Syntax { at, .. }
            | IoError::Truncated { at, .. }
            | IoError::Count { at, .. }
            | IoError::Index { at, .. }
            | IoError::NonFinite { at, .. }
            | IoError::Unsupported { at, .. }
            | IoError::Mesh { at, .. }
            | IoError::ExternalBuffer { at, .. }
            | IoError::Precision { at, .. } => Some(at),
            #[cfg(feature = "gltf")]
            IoError::Gltf { at, .. } => Some(at),
            IoError::Io { .. }
            | IoError::UnknownFormat { .. }
            | IoError::AttributeLength { .. }
            | IoError::AttributeName { .. } => None,
        }
    };
}

impl IoError {
    /// Sets the file of the error's location (errors from byte-level readers
    /// know no path).
    pub fn with_path(mut self, file: &Path) -> Self {
        if let Some(at) = self.location_mut() {
            at.path = Some(file.to_path_buf());
        } else if let Self::Io { path: path @ None, .. } = &mut self {
            *path = Some(file.to_path_buf());
        }
        self
    }

    /// Sets the line of the error's location, when it has none yet.
    pub(crate) fn or_line(mut self, line: Option<usize>) -> Self {
        if let Some(at @ Location { line: None, .. }) = self.location_mut() {
            at.line = line;
        }
        self
    }

    /// The location of the error in the input, if it has one.
    pub fn location(&self) -> Option<&Location> {
        location_of!(self)
    }

    fn location_mut(&mut self) -> Option<&mut Location> {
        location_of!(self)
    }

    /// An I/O error on `path`.
    pub fn io(path: &Path, source: std::io::Error) -> Self {
        Self::Io { path: Some(path.to_path_buf()), source }
    }

    pub(crate) fn syntax(at: Location, expected: impl Into<String>, found: &[u8]) -> Self {
        Self::Syntax { at, expected: expected.into(), found: excerpt(found) }
    }

    pub(crate) fn truncated(at: Location, expected: impl Into<String>) -> Self {
        Self::Truncated { at, expected: expected.into() }
    }

    pub(crate) fn count(at: Location, what: impl Into<String>, count: i128, reason: impl Into<String>) -> Self {
        Self::Count { at, what: what.into(), count, reason: reason.into() }
    }

    pub(crate) fn unsupported(at: Location, what: impl Into<String>) -> Self {
        Self::Unsupported { at, what: what.into() }
    }
}

/// A short, printable, quoted excerpt of input bytes for error messages.
pub(crate) fn excerpt(bytes: &[u8]) -> String {
    const MAX: usize = 24;
    if bytes.is_empty() {
        return "nothing".to_owned();
    }
    let shown = &bytes[..bytes.len().min(MAX)];
    let text: String = shown.iter().flat_map(|&b| std::ascii::escape_default(b)).map(char::from).collect();
    let more = if bytes.len() > MAX { "..." } else { "" };
    format!("`{text}{more}`")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_name_file_line_and_expectation() {
        let e = IoError::syntax(Location::at_line(Format::Off, 3), "a vertex count", b"abc")
            .with_path(Path::new("a/b.off"));
        assert_eq!(e.to_string(), "OFF file a/b.off line 3: expected a vertex count, found `abc`");
        assert_eq!(e.location().and_then(|l| l.line), Some(3));
    }

    #[test]
    fn excerpts_are_short_and_escaped() {
        assert_eq!(excerpt(b""), "nothing");
        assert_eq!(excerpt(b"a\x00"), "`a\\x00`");
        assert!(excerpt(&[b'x'; 100]).ends_with("...`"));
    }
}
