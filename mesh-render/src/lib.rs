//! A small software renderer for the mesh workspace: the pictures of
//! `mesh render`, `mesh report` and the chapter's figures (`mesh figures`).
//! Everything is drawn on the CPU into an [`Image`] and encoded as PNG; no
//! GPU, no window, no font files.
//!
//! | module | what it holds |
//! |---|---|
//! | [`image`](mod@image) | [`Image`]: RGB pixels, rectangles, bitmap-font text, copying, PNG encoding |
//! | [`camera`] | [`View`]: orthographic camera from azimuth, elevation and the up axis |
//! | [`scene`] | [`Scene`]: shaded surfaces ([`Paint`]: plain, per-vertex colours, textures) and 3D lines under one z-buffer, 2x2 supersampling |
//! | [`isolines`](mod@isolines) | [`isolines()`]: level sets of a per-vertex field, a segment per crossed triangle |
//! | [`texture`] | [`Texture`]: checker and dashes sampled through per-corner UVs |
//! | [`color`] | [`ColorScale`] (viridis, diverging) and [`CurvatureClasses`] (red convex, blue concave, grey saddle) |
//! | [`legend`] | colour bars (vertical, horizontal) and swatch keys |
//! | [`figure`] | [`Figure`]: panels side by side with captions and a title |
//! | [`plane`] | [`Drawing`]: points, segments and filled polygons in the plane |
//! | [`field`] | [`render_field`]: one mesh coloured by a field with its colour bar |
//!
//! ```
//! use mesh_render::{isolines, Levels, LineStyle, Paint, Scene, Shading, View};
//! use mesh_render::glam::DVec3;
//!
//! let sphere = mesh_kernel::shapes::icosphere(3)?;
//! let height: Vec<f64> = sphere.positions().iter().map(|p| p.z).collect();
//! let mut scene = Scene::new();
//! scene.surface(&sphere, Paint::Plain(DVec3::splat(0.8)), Shading::Smooth)?;
//! scene.lines(isolines(&sphere, &height, &Levels::Count(9))?, LineStyle::new(DVec3::ZERO, 1.5))?;
//! let image = scene.render(&View::default(), 320, 240, [0; 4])?;
//! let png = image.encode_png()?;
//! assert_eq!(&png[1..4], b"PNG");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! Nothing a caller passes in panics: sizes, lengths, widths and angles are
//! checked and refused with a [`RenderError`]; non-finite geometry is left
//! out of the picture.
#![deny(missing_docs)]
// `!(x > 0.0)` is the NaN-rejecting test used on purpose.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod camera;
pub mod color;
pub mod error;
pub mod field;
pub mod figure;
mod font;
pub mod image;
pub mod isolines;
pub mod legend;
pub mod plane;
pub mod scene;
pub mod texture;

pub use camera::View;
pub use color::{ColorScale, CurvatureClass, CurvatureClasses};
pub use error::RenderError;
pub use field::{render_field, RenderOptions};
pub use figure::{Figure, Panel};
pub use image::{Image, Rect};
pub use isolines::{isolines, Levels};
pub use plane::Drawing;
pub use scene::{LineStyle, Paint, Scene, Shading};
pub use texture::{corner_uvs, normalize_uvs, Texture};

pub use glam;

/// The README's example, compiled and run as a doc-test.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
