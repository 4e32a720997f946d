//! The colour bar of a field picture: a vertical gradient on the right with
//! the top, middle and bottom values beside it, the field's caption at the
//! top left, and at the bottom left the note that the colours were clipped
//! to the 2-98% percentiles, with the full range, when they were.

use mesh_kernel::glam::DVec3;

use super::font::{self, GLYPH_HEIGHT, GLYPH_WIDTH};
use super::ColorScale;

/// Pixels per font cell.
const SCALE: usize = 2;
/// Pictures smaller than this (either side) get no legend.
const MIN_SIZE: (usize, usize) = (240, 160);

/// Draws the legend into `rgb` (`width` x `height` RGB8 pixels, top row first).
pub fn draw(rgb: &mut [u8], width: usize, height: usize, scale: &ColorScale, caption: &str) {
    if width < MIN_SIZE.0 || height < MIN_SIZE.1 || rgb.len() != width * height * 3 {
        return;
    }
    let mut canvas = Canvas { rgb, width, height };
    let (bar_x, bar_w) = (width - 104, 14);
    let (top, bottom) = (height / 5, height - height / 5);
    for y in top..=bottom {
        let t = (bottom - y) as f64 / (bottom - top) as f64;
        let c = scale.color(scale.min + t * (scale.max - scale.min));
        for x in bar_x..bar_x + bar_w {
            canvas.put(x, y, c);
        }
    }
    let black = DVec3::ZERO;
    canvas.frame(bar_x - 1, top - 1, bar_x + bar_w, bottom + 1, black);
    let label_x = bar_x + bar_w + 6;
    let half = GLYPH_HEIGHT * SCALE / 2;
    canvas.text(label_x, top - half, &format_value(scale.max), black);
    canvas.text(label_x, (top + bottom) / 2 - half, &format_value(0.5 * (scale.min + scale.max)), black);
    canvas.text(label_x, bottom - half, &format_value(scale.min), black);
    canvas.text(10, 10, caption, black);
    if let (true, Some((lo, hi))) = (scale.clipped(), scale.data_range) {
        let note = format!("colours clipped to 2-98% (full range {} .. {})", format_value(lo), format_value(hi));
        canvas.text(10, height - 10 - GLYPH_HEIGHT * SCALE, &note, black);
    }
}

/// A value in at most 9 characters: fixed point between 1e-2 and 1e4,
/// scientific otherwise.
pub fn format_value(x: f64) -> String {
    let a = x.abs();
    if a == 0.0 {
        "0".into()
    } else if (1e-2..1e4).contains(&a) {
        let digits = (2 - a.log10().floor() as i32).clamp(0, 4) as usize;
        format!("{x:.digits$}")
    } else {
        format!("{x:.2e}")
    }
}

struct Canvas<'a> {
    rgb: &'a mut [u8],
    width: usize,
    height: usize,
}

impl Canvas<'_> {
    fn put(&mut self, x: usize, y: usize, c: DVec3) {
        if x < self.width && y < self.height {
            let c = (c.clamp(DVec3::ZERO, DVec3::ONE) * 255.0).round();
            let i = 3 * (y * self.width + x);
            self.rgb[i..i + 3].copy_from_slice(&[c.x as u8, c.y as u8, c.z as u8]);
        }
    }

    fn frame(&mut self, x0: usize, y0: usize, x1: usize, y1: usize, c: DVec3) {
        for x in x0..=x1 {
            self.put(x, y0, c);
            self.put(x, y1, c);
        }
        for y in y0..=y1 {
            self.put(x0, y, c);
            self.put(x1, y, c);
        }
    }

    /// Text with its top-left corner at (`x`, `y`), on a white backing so it
    /// stays legible over the mesh; cut at the picture's right edge.
    fn text(&mut self, x: usize, y: usize, text: &str, c: DVec3) {
        let w = font::text_width(text) * SCALE;
        for py in y.saturating_sub(1)..y + GLYPH_HEIGHT * SCALE + 1 {
            for px in x.saturating_sub(1)..(x + w).min(self.width) {
                self.put(px, py, DVec3::ONE);
            }
        }
        for (i, ch) in text.chars().enumerate() {
            for row in 0..GLYPH_HEIGHT {
                for col in 0..GLYPH_WIDTH {
                    if font::lit(ch, col, row) {
                        for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                            self.put(x + (i * font::ADVANCE + col) * SCALE + dx, y + row * SCALE + dy, c);
                        }
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_fit_in_nine_characters() {
        for x in [0.0, 1.0, -1.0, 0.012345, -123.456, 9999.0, 12345.0, -3.6e10, 1e-300, -2.5e-7] {
            let s = format_value(x);
            assert!(s.len() <= 9, "{x} -> {s}");
            let back: f64 = s.parse().unwrap();
            assert!((back - x).abs() <= 0.01 * x.abs(), "{x} -> {s}");
        }
    }

    #[test]
    fn legend_draws_bar_and_clipping_note() {
        let (w, h) = (400, 300);
        let mut values: Vec<f64> = (0..100).map(|i| i as f64).collect();
        values.push(1e6);
        let scale = ColorScale::fit(&values);
        assert!(scale.clipped());
        let mut rgb = vec![255u8; w * h * 3];
        draw(&mut rgb, w, h, &scale, "distance [L]");
        let px = |x: usize, y: usize| &rgb[3 * (y * w + x)..3 * (y * w + x) + 3];
        // The bar's top is the high end of the map (yellow), its bottom the low end (purple).
        let (top, bottom) = (px(w - 100, h / 5 + 2), px(w - 100, h - h / 5 - 2));
        assert!(top[0] > 200 && top[2] < 100, "{top:?}");
        assert!(bottom[2] > 60 && bottom[1] < 30, "{bottom:?}");
        // Some dark pixels of text at the top left (caption) and bottom left (note).
        let dark = |y0: usize| (y0..y0 + 10).any(|y| (10..200).any(|x| px(x, y)[0] == 0));
        assert!(dark(10) && dark(h - 20));
        // A field that fits needs no note.
        let mut plain = vec![255u8; w * h * 3];
        draw(&mut plain, w, h, &ColorScale::fit(&[1.0, 2.0]), "k");
        assert!(!(h - 20..h - 10).any(|y| (10..200).any(|x| plain[3 * (y * w + x)] == 0)));
    }
}
