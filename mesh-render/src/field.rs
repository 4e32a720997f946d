//! One mesh, optionally coloured by a per-vertex scalar field, with the
//! vertical colour bar: the picture of `mesh render` and `mesh report`.

use glam::DVec3;
use mesh_kernel::TriMesh;

use crate::camera::View;
use crate::color::ColorScale;
use crate::error::{RenderError, Result};
use crate::image::Image;
use crate::legend;
use crate::scene::{Paint, Scene, Shading, SURFACE};

/// Camera and picture size of [`render_field`].
#[derive(Debug, Clone, PartialEq)]
pub struct RenderOptions {
    /// Picture width in pixels.
    pub width: u32,
    /// Picture height in pixels.
    pub height: u32,
    /// Camera azimuth around the up axis, degrees.
    pub azimuth: f64,
    /// Camera elevation above the plane orthogonal to `up`, degrees.
    pub elevation: f64,
    /// The axis that points up in the picture.
    pub up: DVec3,
    /// The caption of the colour bar (field name and unit), drawn when a
    /// field colours the mesh; `None` draws the bar with the caption `field`.
    pub title: Option<String>,
}

impl Default for RenderOptions {
    fn default() -> Self {
        Self { width: 800, height: 600, azimuth: -60.0, elevation: 30.0, up: DVec3::Z, title: None }
    }
}

impl RenderOptions {
    /// The camera of these options.
    pub fn view(&self) -> View {
        View::new(self.azimuth, self.elevation, self.up)
    }
}

/// The mesh, shaded, coloured by `scalar` (one value per vertex, 2-98%
/// percentile range, diverging for signed fields) when given, with a
/// colour bar on pictures of at least 240 x 160 pixels.
///
/// # Errors
/// `RenderError::Size` for a side outside 1..8192; `RenderError::Length`
/// when `scalar` does not have one value per vertex;
/// `RenderError::InvalidOption` for non-finite camera angles.
pub fn render_field(mesh: &TriMesh, scalar: Option<&[f64]>, options: &RenderOptions) -> Result<Image> {
    let (w, h) = (options.width as usize, options.height as usize);
    crate::image::check_size(w, h)?;
    let scale = match scalar {
        Some(s) if s.len() != mesh.vertex_count() => {
            return Err(RenderError::Length {
                what: "scalar field",
                got: s.len(),
                expected: mesh.vertex_count(),
                per: "vertices",
            })
        }
        Some(s) => Some((s, ColorScale::fit(s))),
        None => None,
    };
    let paint = match &scale {
        Some((s, scale)) => Paint::Vertex(scale.colors(s)),
        None => Paint::Plain(SURFACE),
    };
    let with_legend = scale.is_some() && w >= legend::MIN_SIZE.0 && h >= legend::MIN_SIZE.1;
    let margins = if with_legend { legend::VERTICAL_MARGINS } else { [0; 4] };
    let mut scene = Scene::new();
    scene.surface(mesh, paint, Shading::Smooth)?;
    let mut image = scene.render(&options.view(), w, h, margins)?;
    if let Some((_, scale)) = &scale {
        legend::vertical(&mut image, scale, options.title.as_deref().unwrap_or("field"));
    }
    Ok(image)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_field_gets_a_bar_and_a_wrong_length_is_refused() {
        let m = mesh_kernel::shapes::icosphere(2).unwrap();
        let z: Vec<f64> = m.positions().iter().map(|p| p.z).collect();
        let opts = RenderOptions { width: 300, height: 200, ..Default::default() };
        let im = render_field(&m, Some(&z), &opts).unwrap();
        // The bar's top is the red end of the diverging map.
        let top = im.pixel(300 - 100, 200 / 5 + 2).unwrap();
        assert!(top[0] > 150 && top[2] < 100, "{top:?}");
        assert!(render_field(&m, Some(&z[1..]), &opts).is_err());
        assert!(render_field(&m, None, &RenderOptions { width: 0, ..opts }).is_err());
    }
}
