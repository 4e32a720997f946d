//! File formats: from a file name's extension, or guessed from content.

use std::fmt;
use std::path::Path;

use crate::error::{IoError, Result};

/// A mesh file format. The format of a file comes from its extension
/// ([`Format::from_path`]); each reader then checks the content (magic bytes,
/// binary or ascii) and gives [`IoError::WrongMagic`] when they disagree.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Format {
    /// Wavefront OBJ (`.obj`), text.
    Obj,
    /// Geomview Object File Format (`.off`), text.
    Off,
    /// Stanford Polygon File Format (`.ply`), ascii or binary.
    Ply,
    /// Stereolithography (`.stl`), ascii or binary.
    Stl,
    /// glTF 2.0 JSON (`.gltf`), buffers embedded or in files beside it.
    Gltf,
    /// Binary glTF 2.0 (`.glb`).
    Glb,
}

impl Format {
    /// Every format, in the order of the README's table.
    pub const ALL: [Format; 6] = [Format::Obj, Format::Off, Format::Ply, Format::Stl, Format::Gltf, Format::Glb];

    /// The format for a file extension (case-insensitive, without the dot).
    pub fn from_extension(ext: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|f| f.extension().eq_ignore_ascii_case(ext))
    }

    /// The format named by a path's extension, or [`IoError::UnknownFormat`].
    ///
    /// # Errors
    /// `IoError::UnknownFormat` when the extension is missing or not one of .obj, .off, .ply, .stl, .gltf,
    /// .glb.
    pub fn from_path(path: &Path) -> Result<Self> {
        path.extension()
            .and_then(|e| e.to_str())
            .and_then(Self::from_extension)
            .ok_or_else(|| IoError::UnknownFormat { path: path.to_path_buf() })
    }

    /// The usual extension, lower case, without the dot.
    pub fn extension(self) -> &'static str {
        match self {
            Format::Obj => "obj",
            Format::Off => "off",
            Format::Ply => "ply",
            Format::Stl => "stl",
            Format::Gltf => "gltf",
            Format::Glb => "glb",
        }
    }

    /// The axis that points up by the format's convention: +Y for glTF (its
    /// specification says so) and for OBJ, PLY and OFF (the practice of
    /// modelling tools and of scan repositories such as Stanford's), +Z for
    /// STL (3D printing). A file cannot say otherwise, so this is a default
    /// for viewers, never a fact about the data.
    pub fn conventional_up(self) -> mesh_kernel::glam::DVec3 {
        use mesh_kernel::glam::DVec3;
        match self {
            Format::Stl => DVec3::Z,
            Format::Obj | Format::Off | Format::Ply | Format::Gltf | Format::Glb => DVec3::Y,
        }
    }

    /// Guesses the format from the first bytes of the content (`None` when
    /// nothing matches). OBJ has no magic: text starting with `v`, `f`, `o`,
    /// `g`, `mtllib` or a `#` comment is taken for OBJ.
    pub fn sniff(bytes: &[u8]) -> Option<Self> {
        let text = bytes.trim_ascii_start();
        let first_word = text.split(|b| b.is_ascii_whitespace()).next().unwrap_or_default();
        if bytes.starts_with(b"ply") {
            Some(Format::Ply)
        } else if bytes.starts_with(b"glTF") {
            Some(Format::Glb)
        } else if first_word.ends_with(b"OFF") {
            Some(Format::Off)
        } else if first_word.eq_ignore_ascii_case(b"solid") || crate::stl::is_binary(bytes) {
            Some(Format::Stl)
        } else if text.starts_with(b"{") {
            Some(Format::Gltf)
        } else if [&b"v"[..], b"vn", b"vt", b"f", b"o", b"g", b"mtllib", b"#"].contains(&first_word)
            || first_word.starts_with(b"#")
        {
            Some(Format::Obj)
        } else {
            None
        }
    }
}

impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Format::Obj => "OBJ",
            Format::Off => "OFF",
            Format::Ply => "PLY",
            Format::Stl => "STL",
            Format::Gltf => "glTF",
            Format::Glb => "GLB",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extensions_are_case_insensitive() {
        assert_eq!(Format::from_path(Path::new("a/B.PlY")).ok(), Some(Format::Ply));
        assert_eq!(Format::from_extension("GLB"), Some(Format::Glb));
        assert!(matches!(Format::from_path(Path::new("mesh.txt")), Err(IoError::UnknownFormat { .. })));
        assert!(Format::from_path(Path::new("mesh")).is_err());
    }

    #[test]
    fn sniffs_content() {
        assert_eq!(Format::sniff(b"ply\nformat ascii 1.0\n"), Some(Format::Ply));
        assert_eq!(Format::sniff(b"\n COFF\n"), Some(Format::Off));
        assert_eq!(Format::sniff(b"solid x\n"), Some(Format::Stl));
        assert_eq!(Format::sniff(b"glTF\x02\0\0\0"), Some(Format::Glb));
        assert_eq!(Format::sniff(b" {\"asset\":{}}"), Some(Format::Gltf));
        assert_eq!(Format::sniff(b"# made by hand\nv 0 0 0\n"), Some(Format::Obj));
        assert_eq!(Format::sniff(b"\x00\x01"), None);
    }
}
