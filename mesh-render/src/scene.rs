//! [`Scene`]: shaded surfaces (a colour, a colour per vertex, or a texture
//! through UVs) and line segments in 3D, rendered with one z-buffer:
//! Gouraud or flat shading, 2x2 supersampling, an orthographic [`View`].
//! Lines pass the same depth test as the surfaces, with a small offset
//! toward the camera so that lines lying on a surface stay visible while
//! lines behind it are hidden.

use glam::{DVec2, DVec3};
use mesh_kernel::geometry::{self, NormalWeighting};
use mesh_kernel::TriMesh;

use crate::camera::{Projection, View};
use crate::error::{RenderError, Result};
use crate::image::{check_size, downsample, segment_stamps, Image, WHITE};
use crate::texture::Texture;

/// Samples per pixel along each axis.
const SS: usize = 2;
/// Depth offset of lines toward the camera, as a fraction of the scene's
/// bounding-box diagonal.
const LINE_DEPTH_OFFSET: f64 = 0.006;

/// The default surface colour: a light blue-grey.
pub const SURFACE: DVec3 = DVec3::new(0.75, 0.78, 0.85);

/// What colours a surface before shading.
#[derive(Debug, Clone, PartialEq)]
pub enum Paint {
    /// One colour.
    Plain(DVec3),
    /// One colour per vertex, interpolated across faces.
    Vertex(Vec<DVec3>),
    /// A texture sampled at the UV interpolated across each face: one UV
    /// per face corner (so seams of a cut parameterization are allowed).
    Texture {
        /// The UVs of each face's corners.
        uv: Vec<[DVec2; 3]>,
        /// The texture.
        texture: Texture,
    },
}

/// How light varies across a face.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Shading {
    /// Interpolated from area-weighted vertex normals (Gouraud).
    #[default]
    Smooth,
    /// Constant per face, from the face normal (shows the triangles).
    Flat,
}

/// The colour and width of a set of lines.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LineStyle {
    /// Colour in [0, 1].
    pub color: DVec3,
    /// Width in output pixels (> 0).
    pub width: f64,
}

impl LineStyle {
    /// A line style.
    pub fn new(color: DVec3, width: f64) -> Self {
        Self { color, width }
    }
}

struct Surface<'a> {
    mesh: &'a TriMesh,
    paint: Paint,
    shading: Shading,
}

/// Surfaces and lines to render together.
#[derive(Default)]
pub struct Scene<'a> {
    surfaces: Vec<Surface<'a>>,
    lines: Vec<([DVec3; 2], LineStyle)>,
}

impl std::fmt::Debug for Scene<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Scene").field("surfaces", &self.surfaces.len()).field("lines", &self.lines.len()).finish()
    }
}

fn check_style(style: &LineStyle) -> Result<()> {
    if !(style.width.is_finite() && style.width > 0.0 && style.width <= 64.0) {
        return Err(RenderError::InvalidOption {
            name: "line width",
            reason: format!("{} is not in (0, 64] pixels", style.width),
        });
    }
    Ok(())
}

impl<'a> Scene<'a> {
    /// An empty scene.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds a surface.
    ///
    /// # Errors
    /// `RenderError::Length` when per-vertex colours or per-corner UVs do
    /// not match the mesh.
    pub fn surface(&mut self, mesh: &'a TriMesh, paint: Paint, shading: Shading) -> Result<&mut Self> {
        match &paint {
            Paint::Vertex(c) if c.len() != mesh.vertex_count() => {
                return Err(RenderError::Length {
                    what: "vertex colours",
                    got: c.len(),
                    expected: mesh.vertex_count(),
                    per: "vertices",
                })
            }
            Paint::Texture { uv, .. } if uv.len() != mesh.face_count() => {
                return Err(RenderError::Length {
                    what: "corner UVs",
                    got: uv.len(),
                    expected: mesh.face_count(),
                    per: "faces",
                })
            }
            _ => {}
        }
        self.surfaces.push(Surface { mesh, paint, shading });
        Ok(self)
    }

    /// Adds line segments; segments with a non-finite end are left out.
    ///
    /// # Errors
    /// `RenderError::InvalidOption` for a width outside (0, 64] pixels.
    pub fn lines(&mut self, segments: impl IntoIterator<Item = [DVec3; 2]>, style: LineStyle) -> Result<&mut Self> {
        check_style(&style)?;
        self.lines.extend(segments.into_iter().filter(|s| s[0].is_finite() && s[1].is_finite()).map(|s| (s, style)));
        Ok(self)
    }

    /// Adds a polyline through `points` (one segment per consecutive pair).
    ///
    /// # Errors
    /// `RenderError::InvalidOption` for a width outside (0, 64] pixels.
    pub fn polyline(&mut self, points: &[DVec3], style: LineStyle) -> Result<&mut Self> {
        self.lines(points.windows(2).map(|w| [w[0], w[1]]), style)
    }

    /// Adds a field of short segments: through each `points[i]`, along
    /// `directions[i]` (normalized here), `half_length` to each side; for
    /// sign-free fields such as principal directions. Zero or non-finite
    /// directions are left out.
    ///
    /// # Errors
    /// `RenderError::Length` when the two arrays differ in length;
    /// `RenderError::InvalidOption` for a bad width or a `half_length` that
    /// is not finite and positive.
    pub fn line_field(
        &mut self,
        points: &[DVec3],
        directions: &[DVec3],
        half_length: f64,
        style: LineStyle,
    ) -> Result<&mut Self> {
        if points.len() != directions.len() {
            return Err(RenderError::Length {
                what: "directions",
                got: directions.len(),
                expected: points.len(),
                per: "points",
            });
        }
        if !(half_length.is_finite() && half_length > 0.0) {
            return Err(RenderError::InvalidOption {
                name: "half_length",
                reason: format!("{half_length} is not finite and positive"),
            });
        }
        let segments = points.iter().zip(directions).filter_map(|(&p, &d)| {
            let d = d.try_normalize()? * half_length;
            Some([p - d, p + d])
        });
        self.lines(segments, style)
    }

    /// Every point of the scene (vertices and line ends), for fitting the view.
    fn points(&self) -> impl Iterator<Item = DVec3> + '_ {
        let surfaces = self.surfaces.iter().flat_map(|s| s.mesh.positions().iter().copied());
        surfaces.chain(self.lines.iter().flat_map(|(s, _)| s.iter().copied()))
    }

    /// Renders the scene into a `width` x `height` picture on white, the
    /// scene filling 92% of the picture less `margins` (left, right, top,
    /// bottom pixels kept free for legends). O(pixels + faces + line length).
    ///
    /// # Errors
    /// `RenderError::Size` for a bad picture size or margins that leave no
    /// room; `RenderError::InvalidOption` for a non-finite view.
    pub fn render(&self, view: &View, width: usize, height: usize, margins: [usize; 4]) -> Result<Image> {
        check_size(width, height)?;
        let frame = view.frame()?;
        let (aw, ah) = (width.saturating_sub(margins[0] + margins[1]), height.saturating_sub(margins[2] + margins[3]));
        if aw == 0 || ah == 0 {
            return Err(RenderError::Size { width: aw, height: ah });
        }
        let (w, h) = (width * SS, height * SS);
        let area = [margins[0] as f64, margins[2] as f64, aw as f64, ah as f64].map(|x| x * SS as f64);
        let projection = Projection::fit(frame, self.points(), area, 0.92);
        let mut buffer = Buffer { w, h, color: vec![WHITE; w * h], depth: vec![f64::NEG_INFINITY; w * h] };
        let light = (frame.toward + 0.5 * frame.up + 0.3 * frame.right).normalize();
        for s in &self.surfaces {
            draw_surface(&mut buffer, s, &projection, light);
        }
        let (lo, hi) = self
            .points()
            .filter(|p| p.is_finite())
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| (lo.min(p), hi.max(p)));
        let diagonal = if lo.x <= hi.x { (hi - lo).length() } else { 0.0 };
        let offset = LINE_DEPTH_OFFSET * diagonal;
        for (segment, style) in &self.lines {
            draw_segment(&mut buffer, &projection, *segment, style, offset);
        }
        buffer.downsample(width, height)
    }
}

/// The supersampled colour and depth buffers.
struct Buffer {
    w: usize,
    h: usize,
    color: Vec<DVec3>,
    depth: Vec<f64>,
}

impl Buffer {
    /// SS x SS box filter down to the output size.
    fn downsample(&self, width: usize, height: usize) -> Result<Image> {
        downsample(&self.color, SS, width, height)
    }
}

fn draw_surface(buffer: &mut Buffer, s: &Surface<'_>, projection: &Projection, light: DVec3) {
    let mesh = s.mesh;
    let lit = |n: DVec3| 0.3 + 0.7 * n.dot(light).abs();
    let vertex_light: Vec<f64> = match s.shading {
        Shading::Smooth => geometry::vertex_normals(mesh, NormalWeighting::Area).iter().map(|&n| lit(n)).collect(),
        Shading::Flat => Vec::new(),
    };
    let projected: Vec<(DVec2, f64)> = mesh.positions().iter().map(|&p| projection.project(p)).collect();
    let (w, h) = (buffer.w, buffer.h);
    for (f, tri) in mesh.faces().iter().enumerate() {
        let [a, b, c] = tri.map(|v| v as usize);
        let (pa, pb, pc) = (projected[a], projected[b], projected[c]);
        let area = (pb.0 - pa.0).perp_dot(pc.0 - pa.0);
        if !(area.abs() >= 1e-12) {
            continue;
        }
        let light_at: [f64; 3] = match s.shading {
            Shading::Smooth => [vertex_light[a], vertex_light[b], vertex_light[c]],
            Shading::Flat => {
                let p = mesh.positions();
                let n = (p[b] - p[a]).cross(p[c] - p[a]).try_normalize().unwrap_or(projection.frame().toward);
                [lit(n); 3]
            }
        };
        let min = pa.0.min(pb.0).min(pc.0).max(DVec2::ZERO);
        let max = pa.0.max(pb.0).max(pc.0).min(DVec2::new(w as f64 - 1.0, h as f64 - 1.0));
        if !(min.x <= max.x && min.y <= max.y) {
            continue;
        }
        for y in min.y.floor() as usize..=(max.y.ceil() as usize).min(h - 1) {
            for x in min.x.floor() as usize..=(max.x.ceil() as usize).min(w - 1) {
                let q = DVec2::new(x as f64 + 0.5, y as f64 + 0.5);
                let l0 = (pb.0 - q).perp_dot(pc.0 - q) / area;
                let l1 = (pc.0 - q).perp_dot(pa.0 - q) / area;
                let l2 = 1.0 - l0 - l1;
                if l0 < 0.0 || l1 < 0.0 || l2 < 0.0 {
                    continue;
                }
                let z = l0 * pa.1 + l1 * pb.1 + l2 * pc.1;
                let i = y * w + x;
                if z > buffer.depth[i] {
                    buffer.depth[i] = z;
                    let base = match &s.paint {
                        Paint::Plain(c) => *c,
                        Paint::Vertex(col) => l0 * col[a] + l1 * col[b] + l2 * col[c],
                        Paint::Texture { uv, texture } => {
                            let [ua, ub, uc] = uv[f];
                            texture.sample(l0 * ua + l1 * ub + l2 * uc)
                        }
                    };
                    buffer.color[i] = base * (l0 * light_at[0] + l1 * light_at[1] + l2 * light_at[2]);
                }
            }
        }
    }
}

/// A segment as round stamps every half sample along it, each sample kept
/// where it is not behind the surface (depth + `offset` >= the z-buffer).
fn draw_segment(buffer: &mut Buffer, projection: &Projection, s: [DVec3; 2], style: &LineStyle, offset: f64) {
    let (a, za) = projection.project(s[0]);
    let (b, zb) = projection.project(s[1]);
    let radius = 0.5 * style.width * SS as f64;
    let Buffer { w, h, color, depth } = buffer;
    segment_stamps(*w, *h, a, b, radius, |t, i| {
        if za + t * (zb - za) + offset >= depth[i] {
            color[i] = style.color;
        }
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image::Rect;

    fn front() -> View {
        // Looking down -z onto the xy plane... with z up the camera looks
        // along the horizontal; use x up and elevation 0 so +z faces us.
        View::new(0.0, 0.0, DVec3::Y)
    }

    #[test]
    fn sphere_covers_the_middle_and_not_the_corner() {
        let m = mesh_kernel::shapes::icosphere(3).unwrap();
        let mut scene = Scene::new();
        scene.surface(&m, Paint::Plain(SURFACE), Shading::Smooth).unwrap();
        let im = scene.render(&View::default(), 64, 64, [0; 4]).unwrap();
        assert_eq!(im.pixel(0, 0), Some([255, 255, 255]));
        assert_ne!(im.pixel(32, 32), Some([255, 255, 255]));
    }

    #[test]
    fn lines_behind_a_sphere_are_hidden_and_in_front_drawn() {
        let m = mesh_kernel::shapes::icosphere(3).unwrap();
        let view = front();
        let toward = view.frame().unwrap().toward;
        assert!((toward - DVec3::Z).length() < 1e-12, "{toward}");
        let red = LineStyle::new(DVec3::new(1.0, 0.0, 0.0), 3.0);
        // A segment across the sphere's middle behind it (z = -1.2), and a
        // second scene with the same segment in front of it (z = +1.2).
        let render = |z: f64| {
            let mut scene = Scene::new();
            scene.surface(&m, Paint::Plain(SURFACE), Shading::Smooth).unwrap();
            scene.lines([[DVec3::new(-0.5, 0.0, z), DVec3::new(0.5, 0.0, z)]], red).unwrap();
            scene.render(&view, 100, 100, [0; 4]).unwrap()
        };
        let reddish = |im: &Image| {
            let mut n = 0;
            for y in 40..60 {
                for x in 30..70 {
                    let p = im.pixel(x, y).unwrap();
                    if p[0] > 200 && p[1] < 60 && p[2] < 60 {
                        n += 1;
                    }
                }
            }
            n
        };
        assert_eq!(reddish(&render(-1.2)), 0, "a segment behind the sphere was drawn");
        assert!(reddish(&render(1.2)) > 40, "a segment in front of the sphere was not drawn");
    }

    #[test]
    fn lines_lying_on_a_surface_are_visible() {
        let m = mesh_kernel::shapes::grid(1.0, 1.0, 4, 4).unwrap();
        let mut scene = Scene::new();
        scene.surface(&m, Paint::Plain(SURFACE), Shading::Flat).unwrap();
        scene
            .lines([[DVec3::new(0.1, 0.5, 0.0), DVec3::new(0.9, 0.5, 0.0)]], LineStyle::new(DVec3::ZERO, 2.0))
            .unwrap();
        let im = scene.render(&View::new(0.0, 90.0, DVec3::Z), 80, 80, [0; 4]).unwrap();
        let dark = (10..70).filter(|&x| (30..50).any(|y| im.pixel(x, y).unwrap()[0] < 40)).count();
        assert!(dark > 50, "{dark}");
    }

    #[test]
    fn texture_is_sampled_through_uvs() {
        let m = mesh_kernel::shapes::grid(1.0, 1.0, 2, 2).unwrap();
        let uv: Vec<DVec2> = m.positions().iter().map(|p| DVec2::new(p.x, p.y)).collect();
        let uv = crate::texture::corner_uvs(&m, &uv).unwrap();
        let mut scene = Scene::new();
        scene.surface(&m, Paint::Texture { uv, texture: Texture::checker(2) }, Shading::Flat).unwrap();
        let im = scene.render(&View::new(0.0, 90.0, DVec3::Z), 100, 100, [0; 4]).unwrap();
        // Four quadrants alternate between light and dark.
        let lum = |x: usize, y: usize| im.pixel(x, y).unwrap()[0];
        let (a, b, c, d) = (lum(30, 30), lum(70, 30), lum(30, 70), lum(70, 70));
        assert!(a.abs_diff(b) > 100 && b.abs_diff(d) > 100 && a.abs_diff(d) < 10 && b.abs_diff(c) < 10);
    }

    #[test]
    fn a_convex_sphere_renders_red_in_the_curvature_classes() {
        // Outward normals: H = 1, K = 1 everywhere, convex.
        let m = mesh_kernel::shapes::icosphere(3).unwrap();
        let (h, k) = (vec![1.0; m.vertex_count()], vec![1.0; m.vertex_count()]);
        let classes = crate::color::CurvatureClasses::fit(&h, &k);
        let mut scene = Scene::new();
        scene.surface(&m, Paint::Vertex(classes.colors(&h, &k)), Shading::Smooth).unwrap();
        let im = scene.render(&View::default(), 64, 64, [0; 4]).unwrap();
        let c = im.pixel(32, 32).unwrap();
        assert!(c[0] > 120 && c[1] < 40 && c[2] < 40, "{c:?}");
    }

    #[test]
    fn bad_inputs_are_errors() {
        let m = mesh_kernel::shapes::icosphere(1).unwrap();
        let mut scene = Scene::new();
        assert!(scene.surface(&m, Paint::Vertex(vec![DVec3::ONE; 3]), Shading::Smooth).is_err());
        assert!(scene.lines([], LineStyle::new(DVec3::ZERO, 0.0)).is_err());
        assert!(scene.line_field(&[DVec3::ZERO], &[], 1.0, LineStyle::new(DVec3::ZERO, 1.0)).is_err());
        assert!(scene.line_field(&[DVec3::ZERO], &[DVec3::X], f64::NAN, LineStyle::new(DVec3::ZERO, 1.0)).is_err());
        assert!(scene.render(&View::default(), 0, 10, [0; 4]).is_err());
        assert!(scene.render(&View::default(), 10, 10, [5, 5, 0, 0]).is_err());
        // An empty scene is a white picture.
        let im = Scene::new().render(&View::default(), 8, 8, [0; 4]).unwrap();
        assert_eq!(im.count_differing(Rect { x: 0, y: 0, width: 8, height: 8 }, WHITE), 0);
    }
}
