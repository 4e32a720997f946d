//! A small software renderer: a mesh, optionally coloured by a per-vertex
//! scalar field, shaded and written as a PNG picture (z-buffer, Gouraud
//! shading, 2x2 supersampling, orthographic camera). A coloured picture
//! carries a colour bar with the field's name, unit and value range, and
//! says when the range was clipped to robust percentiles.

mod font;
mod legend;

use std::path::Path;

use mesh_kernel::geometry::{self, NormalWeighting};
use mesh_kernel::glam::{DVec2, DVec3};
use mesh_kernel::TriMesh;

use crate::output::CliResult;

/// Camera and picture size.
#[derive(Debug, Clone, PartialEq)]
pub struct RenderOptions {
    /// Picture width in pixels.
    pub width: u32,
    /// Picture height in pixels.
    pub height: u32,
    /// Camera azimuth around the z axis, degrees.
    pub azimuth: f64,
    /// Camera elevation above the plane orthogonal to `up`, degrees.
    pub elevation: f64,
    /// The axis that points up in the picture.
    pub up: DVec3,
    /// The caption of the colour bar (field name and unit), drawn when a
    /// field colours the mesh; `None` draws the bar with an untitled caption.
    pub title: Option<String>,
}

impl Default for RenderOptions {
    fn default() -> Self {
        Self { width: 800, height: 600, azimuth: -60.0, elevation: 30.0, up: DVec3::Z, title: None }
    }
}

/// How a scalar field maps to colours: the range shown (robust 2-98%
/// percentiles) and whether the map is diverging (blue-white-red around 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ColorScale {
    /// Lowest value shown.
    pub min: f64,
    /// Highest value shown.
    pub max: f64,
    /// Diverging map centred on zero (for signed fields).
    pub diverging: bool,
    /// Smallest and largest finite value of the field (`None` when it has none).
    pub data_range: Option<(f64, f64)>,
}

impl ColorScale {
    /// The 2-98% percentile range of the finite values; diverging when they
    /// take both signs.
    pub fn fit(values: &[f64]) -> Self {
        let mut v: Vec<f64> = values.iter().copied().filter(|x| x.is_finite()).collect();
        if v.is_empty() {
            return Self { min: 0.0, max: 1.0, diverging: false, data_range: None };
        }
        v.sort_by(f64::total_cmp);
        let pick = |q: f64| v[((v.len() - 1) as f64 * q).round() as usize];
        let (lo, hi) = (pick(0.02), pick(0.98));
        let data_range = Some((v[0], v[v.len() - 1]));
        if lo < 0.0 && hi > 0.0 {
            let m = lo.abs().max(hi);
            Self { min: -m, max: m, diverging: true, data_range }
        } else if hi > lo {
            Self { min: lo, max: hi, diverging: false, data_range }
        } else {
            Self { min: lo - 0.5, max: lo + 0.5, diverging: false, data_range }
        }
    }

    /// `true` when some finite values lie outside the colours' range (they
    /// take the end colours).
    pub fn clipped(&self) -> bool {
        self.data_range.is_some_and(|(lo, hi)| lo < self.min || hi > self.max)
    }

    /// RGB in [0, 1] of a value (grey for non-finite values).
    pub fn color(&self, x: f64) -> DVec3 {
        if !x.is_finite() {
            return DVec3::splat(0.5);
        }
        let t = ((x - self.min) / (self.max - self.min)).clamp(0.0, 1.0);
        let stops: &[DVec3] = if self.diverging {
            &[DVec3::new(0.23, 0.30, 0.75), DVec3::new(0.87, 0.87, 0.87), DVec3::new(0.71, 0.02, 0.15)]
        } else {
            // Viridis, sampled at five points.
            &[
                DVec3::new(0.267, 0.005, 0.329),
                DVec3::new(0.230, 0.322, 0.546),
                DVec3::new(0.128, 0.567, 0.551),
                DVec3::new(0.369, 0.789, 0.383),
                DVec3::new(0.993, 0.906, 0.144),
            ]
        };
        let s = t * (stops.len() - 1) as f64;
        let i = (s.floor() as usize).min(stops.len() - 2);
        stops[i].lerp(stops[i + 1], s - i as f64)
    }
}

/// Renders the mesh (coloured by `scalar` when given) to a PNG file.
pub fn render_png(mesh: &TriMesh, scalar: Option<&[f64]>, path: &Path, options: &RenderOptions) -> CliResult<()> {
    if options.width == 0 || options.height == 0 || options.width > 8192 || options.height > 8192 {
        return Err(format!("picture size {}x{} is out of range 1..8192", options.width, options.height).into());
    }
    if let Some(s) = scalar {
        if s.len() != mesh.vertex_count() {
            return Err(format!("{} scalar values for {} vertices", s.len(), mesh.vertex_count()).into());
        }
    }
    let mut rgb = rasterize(mesh, scalar, options);
    if let Some(values) = scalar {
        let caption = options.title.as_deref().unwrap_or("field");
        legend::draw(&mut rgb, options.width as usize, options.height as usize, &ColorScale::fit(values), caption);
    }
    let file = std::fs::File::create(path).map_err(|e| format!("cannot create {}: {e}", path.display()))?;
    let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), options.width, options.height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.write_header()?.write_image_data(&rgb)?;
    Ok(())
}

/// The picture as RGB8 rows, top row first.
pub fn rasterize(mesh: &TriMesh, scalar: Option<&[f64]>, options: &RenderOptions) -> Vec<u8> {
    const SS: usize = 2;
    let (w, h) = (options.width as usize * SS, options.height as usize * SS);
    let background = DVec3::splat(1.0);
    let mut color = vec![background; w * h];
    let mut depth = vec![f64::NEG_INFINITY; w * h];

    let (az, el) = (options.azimuth.to_radians(), options.elevation.to_radians());
    // A frame (e1, e2, up) with the azimuth measured in the e1-e2 plane.
    // Azimuth 0 looks at the model's front: +z for a y-up model, -y for a
    // z-up one (the conventions of modelling tools), +z for an x-up one.
    let z = options.up.try_normalize().unwrap_or(DVec3::Z);
    let front = if z.z.abs() > 0.9 { -DVec3::Y } else { DVec3::Z };
    let e1 = (front - front.dot(z) * z).try_normalize().unwrap_or_else(|| z.any_orthonormal_vector());
    let e2 = z.cross(e1);
    let toward_camera = el.cos() * (az.cos() * e1 + az.sin() * e2) + el.sin() * z;
    let right = z.cross(toward_camera).try_normalize().unwrap_or(e1);
    let up = toward_camera.cross(right);
    // Fit the projected extent of the mesh into the picture, leaving room
    // for the colour bar and the captions when a field is shown.
    let (lo, hi) = mesh.positions().iter().fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(lo, hi), p| {
        let q = DVec2::new(p.dot(right), p.dot(up));
        (lo.min(q), hi.max(q))
    });
    let (lo, hi) = if lo.x <= hi.x { (lo, hi) } else { (DVec2::ZERO, DVec2::ZERO) };
    let margin = if scalar.is_some() && options.width >= 240 && options.height >= 160 {
        [0.0, 110.0, 26.0, 26.0].map(|m| m * SS as f64) // left, right, top, bottom
    } else {
        [0.0; 4]
    };
    let area = DVec2::new(w as f64 - margin[0] - margin[1], h as f64 - margin[2] - margin[3]);
    let extent = (hi - lo).max(DVec2::splat(1e-300));
    let scale = 0.92 * (area.x / extent.x).min(area.y / extent.y);
    let mid = 0.5 * (lo + hi);
    let centre = DVec2::new(margin[0] + area.x / 2.0, margin[2] + area.y / 2.0);
    let project = |p: DVec3| {
        let q = DVec2::new(p.dot(right), p.dot(up)) - mid;
        (DVec2::new(centre.x + scale * q.x, centre.y - scale * q.y), p.dot(toward_camera))
    };
    let normals = geometry::vertex_normals(mesh, NormalWeighting::Area);
    let scale_colors = scalar.map(ColorScale::fit);
    let base = |v: usize| match (scalar, &scale_colors) {
        (Some(s), Some(cs)) => cs.color(s[v]),
        _ => DVec3::new(0.75, 0.78, 0.85),
    };
    let light = (toward_camera + 0.5 * up + 0.3 * right).normalize();
    let shade = |v: usize| base(v) * (0.3 + 0.7 * normals[v].dot(light).abs());
    let projected: Vec<(DVec2, f64)> = mesh.positions().iter().map(|&p| project(p)).collect();
    let shaded: Vec<DVec3> = (0..mesh.vertex_count()).map(shade).collect();

    for tri in mesh.faces() {
        let [a, b, c] = tri.map(|v| v as usize);
        let (pa, pb, pc) = (projected[a], projected[b], projected[c]);
        let area = (pb.0 - pa.0).perp_dot(pc.0 - pa.0);
        if area.abs() < 1e-12 {
            continue;
        }
        let min = pa.0.min(pb.0).min(pc.0).max(DVec2::ZERO);
        let max = pa.0.max(pb.0).max(pc.0).min(DVec2::new(w as f64 - 1.0, h as f64 - 1.0));
        if min.x > max.x || min.y > max.y {
            continue;
        }
        for y in min.y.floor() as usize..=max.y.ceil() as usize {
            for x in min.x.floor() as usize..=max.x.ceil() as usize {
                if x >= w || y >= h {
                    continue;
                }
                let q = DVec2::new(x as f64 + 0.5, y as f64 + 0.5);
                let l0 = (pb.0 - q).perp_dot(pc.0 - q) / area;
                let l1 = (pc.0 - q).perp_dot(pa.0 - q) / area;
                let l2 = 1.0 - l0 - l1;
                if l0 < 0.0 || l1 < 0.0 || l2 < 0.0 {
                    continue;
                }
                let z = l0 * pa.1 + l1 * pb.1 + l2 * pc.1;
                let i = y * w + x;
                if z > depth[i] {
                    depth[i] = z;
                    color[i] = l0 * shaded[a] + l1 * shaded[b] + l2 * shaded[c];
                }
            }
        }
    }
    // 2x2 box filter down to the output size.
    let (ow, oh) = (options.width as usize, options.height as usize);
    let mut out = Vec::with_capacity(ow * oh * 3);
    for y in 0..oh {
        for x in 0..ow {
            let mut sum = DVec3::ZERO;
            for dy in 0..SS {
                for dx in 0..SS {
                    sum += color[(y * SS + dy) * w + x * SS + dx];
                }
            }
            let c = (sum / (SS * SS) as f64).clamp(DVec3::ZERO, DVec3::ONE) * 255.0;
            out.extend([c.x.round() as u8, c.y.round() as u8, c.z.round() as u8]);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sphere_covers_the_middle_and_not_the_corner() {
        let m = mesh_kernel::shapes::icosphere(3).unwrap();
        let opts = RenderOptions { width: 64, height: 64, ..Default::default() };
        let rgb = rasterize(&m, None, &opts);
        let px = |x: usize, y: usize| &rgb[(y * 64 + x) * 3..(y * 64 + x) * 3 + 3];
        assert_eq!(px(0, 0), &[255, 255, 255]);
        assert_ne!(px(32, 32), &[255, 255, 255]);
    }

    #[test]
    fn diverging_scale_is_symmetric() {
        let s = ColorScale::fit(&[-1.0, 0.5, 2.0, f64::NAN]);
        assert!(s.diverging && s.min == -s.max);
        let white = s.color(0.0);
        assert!(white.x > 0.8 && white.y > 0.8 && white.z > 0.8);
    }
}
