//! [`Image`]: an RGB picture in memory, the canvas every drawing ends on,
//! with rectangles, text in the bitmap font, copying of one picture into
//! another and PNG encoding.

use glam::{DVec2, DVec3};

use crate::error::{RenderError, Result};
use crate::font::{self, GLYPH_HEIGHT, GLYPH_WIDTH};

/// The largest side of a picture, in pixels.
pub const MAX_SIDE: usize = 8192;

/// White, the background of every picture.
pub const WHITE: DVec3 = DVec3::ONE;
/// Black, for text and lines.
pub const BLACK: DVec3 = DVec3::ZERO;

/// A pixel rectangle: `x`, `y` of the top-left corner, width and height.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Rect {
    /// Left column.
    pub x: usize,
    /// Top row.
    pub y: usize,
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
}

/// An RGB8 picture, rows top first.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Image {
    width: usize,
    height: usize,
    rgb: Vec<u8>,
}

/// Checks a picture size.
/// Calls `pixel(t, y * w + x)` for every pixel of a `w` x `h` picture
/// whose centre is within `radius` (at least sqrt(0.5)) of a sample of the
/// segment `a b`, one sample every half pixel at `a + t (b - a)`; nothing
/// when the segment is wholly outside the picture.
pub(crate) fn segment_stamps(w: usize, h: usize, a: DVec2, b: DVec2, radius: f64, mut pixel: impl FnMut(f64, usize)) {
    let (wf, hf) = (w as f64, h as f64);
    // Wholly outside the picture (also guards the step count below).
    if a.x.max(b.x) < -radius || a.y.max(b.y) < -radius || a.x.min(b.x) > wf + radius || a.y.min(b.y) > hf + radius {
        return;
    }
    let steps = ((b - a).length() / 0.5).ceil().min(1e6) as usize + 1;
    let r2 = (radius * radius).max(0.5);
    for k in 0..=steps {
        let t = k as f64 / steps as f64;
        let p = a.lerp(b, t);
        let (x0, x1) = ((p.x - radius).floor().max(0.0), (p.x + radius).ceil().min(wf - 1.0));
        let (y0, y1) = ((p.y - radius).floor().max(0.0), (p.y + radius).ceil().min(hf - 1.0));
        if x0 > x1 || y0 > y1 {
            continue;
        }
        for y in y0 as usize..=y1 as usize {
            for x in x0 as usize..=x1 as usize {
                if (DVec2::new(x as f64 + 0.5, y as f64 + 0.5) - p).length_squared() <= r2 {
                    pixel(t, y * w + x);
                }
            }
        }
    }
}

/// `ss` x `ss` box filter of a `width * ss` x `height * ss` colour buffer
/// (row-major) down to a `width` x `height` picture.
pub(crate) fn downsample(color: &[DVec3], ss: usize, width: usize, height: usize) -> Result<Image> {
    let w = width * ss;
    let mut out = Vec::with_capacity(width * height * 3);
    for y in 0..height {
        for x in 0..width {
            let mut sum = DVec3::ZERO;
            for dy in 0..ss {
                for dx in 0..ss {
                    sum += color[(y * ss + dy) * w + x * ss + dx];
                }
            }
            out.extend(to_rgb8(sum / (ss * ss) as f64));
        }
    }
    Image::from_rgb(width, height, out)
}

pub(crate) fn check_size(width: usize, height: usize) -> Result<()> {
    if width == 0 || height == 0 || width > MAX_SIDE || height > MAX_SIDE {
        return Err(RenderError::Size { width, height });
    }
    Ok(())
}

/// A colour in [0, 1] as RGB8 (clamped; NaN counts as 0).
pub fn to_rgb8(c: DVec3) -> [u8; 3] {
    let q = |x: f64| if x.is_nan() { 0 } else { (x.clamp(0.0, 1.0) * 255.0).round() as u8 };
    [q(c.x), q(c.y), q(c.z)]
}

impl Image {
    /// A picture filled with `background`.
    ///
    /// # Errors
    /// `RenderError::Size` when a side is 0 or larger than [`MAX_SIDE`].
    pub fn new(width: usize, height: usize, background: DVec3) -> Result<Self> {
        check_size(width, height)?;
        let px = to_rgb8(background);
        Ok(Self { width, height, rgb: px.iter().copied().cycle().take(width * height * 3).collect() })
    }

    /// A picture from RGB8 rows, top first (`rgb.len() == 3 width height`).
    ///
    /// # Errors
    /// `RenderError::Size` for a bad size, `RenderError::Length` when `rgb`
    /// does not hold three bytes per pixel.
    pub fn from_rgb(width: usize, height: usize, rgb: Vec<u8>) -> Result<Self> {
        check_size(width, height)?;
        if rgb.len() != width * height * 3 {
            return Err(RenderError::Length {
                what: "RGB bytes",
                got: rgb.len(),
                expected: width * height * 3,
                per: "pixel channels",
            });
        }
        Ok(Self { width, height, rgb })
    }

    /// Width in pixels.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> usize {
        self.height
    }

    /// The whole picture as a rectangle.
    pub fn rect(&self) -> Rect {
        Rect { x: 0, y: 0, width: self.width, height: self.height }
    }

    /// The RGB8 bytes, rows top first.
    pub fn rgb(&self) -> &[u8] {
        &self.rgb
    }

    /// The RGB8 bytes, consumed.
    pub fn into_rgb(self) -> Vec<u8> {
        self.rgb
    }

    /// The pixel at (`x`, `y`), `None` outside the picture.
    pub fn pixel(&self, x: usize, y: usize) -> Option<[u8; 3]> {
        (x < self.width && y < self.height).then(|| {
            let i = 3 * (y * self.width + x);
            [self.rgb[i], self.rgb[i + 1], self.rgb[i + 2]]
        })
    }

    /// Sets one pixel; outside the picture nothing happens.
    pub fn put(&mut self, x: usize, y: usize, c: DVec3) {
        if x < self.width && y < self.height {
            let i = 3 * (y * self.width + x);
            self.rgb[i..i + 3].copy_from_slice(&to_rgb8(c));
        }
    }

    /// Fills a rectangle (cut at the picture's edges).
    pub fn fill(&mut self, r: Rect, c: DVec3) {
        for y in r.y..(r.y + r.height).min(self.height) {
            for x in r.x..(r.x + r.width).min(self.width) {
                self.put(x, y, c);
            }
        }
    }

    /// A one-pixel frame on the inside of a rectangle.
    pub fn frame(&mut self, r: Rect, c: DVec3) {
        if r.width == 0 || r.height == 0 {
            return;
        }
        let (x1, y1) = (r.x + r.width - 1, r.y + r.height - 1);
        for x in r.x..=x1 {
            self.put(x, r.y, c);
            self.put(x, y1, c);
        }
        for y in r.y..=y1 {
            self.put(r.x, y, c);
            self.put(x1, y, c);
        }
    }

    /// Copies `other` with its top-left corner at (`x`, `y`), cut at the edges.
    pub fn blit(&mut self, other: &Image, x: usize, y: usize) {
        for row in 0..other.height.min(self.height.saturating_sub(y)) {
            let n = other.width.min(self.width.saturating_sub(x));
            let src = 3 * row * other.width;
            let dst = 3 * ((y + row) * self.width + x);
            self.rgb[dst..dst + 3 * n].copy_from_slice(&other.rgb[src..src + 3 * n]);
        }
    }

    /// Draws `text` in the bitmap font, each font cell `scale` pixels
    /// square, top-left corner at (`x`, `y`); with `backing`, on a white box
    /// so it stays legible over a picture. Cut at the right edge.
    pub fn text(&mut self, x: usize, y: usize, text: &str, c: DVec3, scale: usize, backing: bool) {
        let scale = scale.max(1);
        if backing {
            let w = font::text_width(text) * scale;
            let r =
                Rect { x: x.saturating_sub(1), y: y.saturating_sub(1), width: w + 1, height: GLYPH_HEIGHT * scale + 2 };
            self.fill(r, WHITE);
        }
        for (i, ch) in text.chars().enumerate() {
            for row in 0..GLYPH_HEIGHT {
                for col in 0..GLYPH_WIDTH {
                    if font::lit(ch, col, row) {
                        let (px, py) = (x + (i * font::ADVANCE + col) * scale, y + row * scale);
                        self.fill(Rect { x: px, y: py, width: scale, height: scale }, c);
                    }
                }
            }
        }
    }

    /// `text` cut to at most `width` pixels at `scale` (characters dropped
    /// from the end, the last replaced by `.` when any were dropped).
    pub fn fit_text(text: &str, width: usize, scale: usize) -> String {
        let max = width / (font::ADVANCE * scale.max(1));
        if text.chars().count() <= max {
            return text.to_owned();
        }
        let mut s: String = text.chars().take(max.saturating_sub(1)).collect();
        if max > 0 {
            s.push('.');
        }
        s
    }

    /// Draws `text` centred horizontally in `r` (cut to its width), its
    /// glyphs' top at `r.y`.
    pub fn text_centred(&mut self, r: Rect, text: &str, c: DVec3, scale: usize) {
        let text = Self::fit_text(text, r.width, scale);
        let w = font::text_width(&text) * scale.max(1);
        self.text(r.x + r.width.saturating_sub(w) / 2, r.y, &text, c, scale, false);
    }

    /// Number of pixels in `r` that differ from `background`.
    pub fn count_differing(&self, r: Rect, background: DVec3) -> usize {
        let bg = to_rgb8(background);
        let mut n = 0;
        for y in r.y..(r.y + r.height).min(self.height) {
            for x in r.x..(r.x + r.width).min(self.width) {
                if self.pixel(x, y) != Some(bg) {
                    n += 1;
                }
            }
        }
        n
    }

    /// The picture as a PNG file's bytes (RGB8, the encoder's best
    /// compression with adaptive filters).
    ///
    /// # Errors
    /// `RenderError::Png` when the encoder fails.
    pub fn encode_png(&self) -> Result<Vec<u8>> {
        let mut out = Vec::new();
        self.write_png(&mut out)?;
        Ok(out)
    }

    /// Writes the picture as PNG to `w`.
    ///
    /// # Errors
    /// `RenderError::Png` when the encoder or the writer fails.
    pub fn write_png<W: std::io::Write>(&self, w: W) -> Result<()> {
        let mut encoder = png::Encoder::new(w, self.width as u32, self.height as u32);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_compression(png::Compression::High);
        encoder.set_filter(png::Filter::Adaptive);
        encoder.write_header()?.write_image_data(&self.rgb)?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_are_checked_and_pixels_round_trip() {
        assert!(matches!(Image::new(0, 4, WHITE), Err(RenderError::Size { .. })));
        assert!(matches!(Image::new(4, MAX_SIDE + 1, WHITE), Err(RenderError::Size { .. })));
        assert!(matches!(Image::from_rgb(2, 2, vec![0; 11]), Err(RenderError::Length { .. })));
        let mut im = Image::new(4, 3, WHITE).unwrap();
        im.put(1, 2, DVec3::new(1.0, 0.0, f64::NAN));
        im.put(9, 9, BLACK);
        assert_eq!(im.pixel(1, 2), Some([255, 0, 0]));
        assert_eq!(im.pixel(4, 0), None);
        assert_eq!(im.count_differing(im.rect(), WHITE), 1);
        let png = im.encode_png().unwrap();
        assert_eq!(&png[1..4], b"PNG");
    }

    #[test]
    fn blit_and_text_stay_inside() {
        let mut big = Image::new(10, 10, WHITE).unwrap();
        let small = Image::new(4, 4, BLACK).unwrap();
        big.blit(&small, 8, 8);
        assert_eq!(big.count_differing(big.rect(), WHITE), 4);
        big.text(0, 0, "HELLO WORLD", BLACK, 2, true);
        assert!(big.pixel(0, 0).is_some());
        assert_eq!(Image::fit_text("abcdef", 16, 1), "abc.");
        assert_eq!(Image::fit_text("ab", 16, 1), "ab");
    }
}
