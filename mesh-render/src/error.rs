//! [`RenderError`]: what can go wrong when drawing a picture.

use thiserror::Error;

/// Every error of this crate. Nothing a caller passes in panics: sizes out
/// of range, arrays of the wrong length and non-finite inputs are errors.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum RenderError {
    /// A picture size outside `1..=MAX_SIDE` on either side.
    #[error("picture size {width}x{height} is out of range 1..{max}", max = crate::image::MAX_SIDE)]
    Size {
        /// Requested width in pixels.
        width: usize,
        /// Requested height in pixels.
        height: usize,
    },
    /// A per-vertex or per-face array whose length does not match the mesh.
    #[error("{what}: {got} values for {expected} {per}")]
    Length {
        /// What the array holds (`"scalar field"`, `"corner UVs"`).
        what: &'static str,
        /// Its length.
        got: usize,
        /// The length it must have.
        expected: usize,
        /// `"vertices"` or `"faces"`.
        per: &'static str,
    },
    /// An option out of its range (a non-finite angle, a line width <= 0).
    #[error("{name}: {reason}")]
    InvalidOption {
        /// The option.
        name: &'static str,
        /// Why it was refused.
        reason: String,
    },
    /// The PNG encoder failed (for instance, the writer failed).
    #[error("PNG encoding failed: {0}")]
    Png(#[from] png::EncodingError),
}

/// `Result` with [`RenderError`].
pub type Result<T> = std::result::Result<T, RenderError>;
