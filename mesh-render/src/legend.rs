//! Colour bars and keys: the vertical bar of a full-size field picture
//! (top, middle and bottom values beside it, the field's caption at the
//! top left and, when the colours were clipped to the 2-98% percentiles, a
//! note with the full range at the bottom left), the horizontal bar of a
//! figure panel, and a row of swatches for a map of classes.

use glam::DVec3;

use crate::color::ColorScale;
use crate::font::{self, GLYPH_HEIGHT};
use crate::image::{Image, Rect, BLACK};

/// Pixels per font cell of the full-size legend.
const SCALE: usize = 2;
/// Pictures smaller than this (either side) get no vertical legend.
pub const MIN_SIZE: (usize, usize) = (240, 160);
/// Margins (left, right, top, bottom) a picture with a vertical legend
/// keeps free of the mesh, in pixels.
pub const VERTICAL_MARGINS: [usize; 4] = [0, 110, 26, 26];
/// Height in pixels of a panel's horizontal bar with its labels.
pub const BAR_HEIGHT: usize = 26;

/// Draws the vertical legend into `image`; nothing on pictures smaller than [`MIN_SIZE`].
pub fn vertical(image: &mut Image, scale: &ColorScale, caption: &str) {
    let (width, height) = (image.width(), image.height());
    if width < MIN_SIZE.0 || height < MIN_SIZE.1 {
        return;
    }
    let (bar_x, bar_w) = (width - 104, 14);
    let (top, bottom) = (height / 5, height - height / 5);
    for y in top..=bottom {
        let t = (bottom - y) as f64 / (bottom - top) as f64;
        let c = scale.color(scale.min + t * (scale.max - scale.min));
        image.fill(Rect { x: bar_x, y, width: bar_w, height: 1 }, c);
    }
    image.frame(Rect { x: bar_x - 1, y: top - 1, width: bar_w + 2, height: bottom - top + 3 }, BLACK);
    let label_x = bar_x + bar_w + 6;
    let half = GLYPH_HEIGHT * SCALE / 2;
    image.text(label_x, top - half, &format_value(scale.max), BLACK, SCALE, true);
    image.text(label_x, (top + bottom) / 2 - half, &format_value(0.5 * (scale.min + scale.max)), BLACK, SCALE, true);
    image.text(label_x, bottom - half, &format_value(scale.min), BLACK, SCALE, true);
    image.text(10, 10, caption, BLACK, SCALE, true);
    if let (true, Some((lo, hi))) = (scale.clipped(), scale.data_range) {
        let note = format!("colours clipped to 2-98% (full range {} .. {})", format_value(lo), format_value(hi));
        image.text(10, height - 10 - GLYPH_HEIGHT * SCALE, &note, BLACK, SCALE, true);
    }
}

/// A horizontal bar across the bottom [`BAR_HEIGHT`] pixels of `image`:
/// the lowest value left of it, the highest right of it (labels left out
/// on pictures narrower than 120 pixels).
pub fn horizontal(image: &mut Image, scale: &ColorScale) {
    let (width, height) = (image.width(), image.height());
    if height < BAR_HEIGHT + 4 || width < 40 {
        return;
    }
    let labels = width >= 120;
    let label_w = if labels { 9 * font::ADVANCE } else { 4 };
    let (x0, x1) = (label_w + 4, width.saturating_sub(label_w + 4));
    if x1 <= x0 + 4 {
        return;
    }
    let (y0, h) = (height - BAR_HEIGHT + 8, 10);
    for x in x0..x1 {
        let t = (x - x0) as f64 / (x1 - x0 - 1).max(1) as f64;
        image.fill(Rect { x, y: y0, width: 1, height: h }, scale.color(scale.min + t * (scale.max - scale.min)));
    }
    image.frame(Rect { x: x0 - 1, y: y0 - 1, width: x1 - x0 + 2, height: h + 2 }, BLACK);
    if labels {
        let lo = format_value(scale.min);
        let hi = format_value(scale.max);
        let ty = y0 + (h - GLYPH_HEIGHT) / 2;
        image.text(x0 - 3 - font::text_width(&lo), ty, &lo, BLACK, 1, false);
        image.text(x1 + 3, ty, &hi, BLACK, 1, false);
    }
}

/// A row of coloured squares with their names across the bottom
/// [`BAR_HEIGHT`] pixels of `image`, centred (cut at the right edge).
pub fn swatches(image: &mut Image, items: &[(DVec3, String)]) {
    let (width, height) = (image.width(), image.height());
    if height < BAR_HEIGHT + 4 {
        return;
    }
    let item_w = |label: &str| 10 + 3 + font::text_width(label) + 8;
    let total: usize = items.iter().map(|(_, l)| item_w(l)).sum();
    let mut x = width.saturating_sub(total) / 2;
    let y = height - BAR_HEIGHT + 8;
    for (c, label) in items {
        image.fill(Rect { x, y, width: 10, height: 10 }, *c);
        image.frame(Rect { x, y, width: 10, height: 10 }, BLACK);
        image.text(x + 13, y + 3, label, BLACK, 1, false);
        x += item_w(label);
    }
}

/// A value in at most 9 characters: fixed point between 1e-2 and 1e4,
/// scientific otherwise.
pub fn format_value(x: f64) -> String {
    let a = x.abs();
    if a == 0.0 {
        "0".into()
    } else if !x.is_finite() {
        format!("{x}")
    } else if (1e-2..1e4).contains(&a) {
        let digits = (2 - a.log10().floor() as i32).clamp(0, 4) as usize;
        format!("{x:.digits$}")
    } else {
        format!("{x:.2e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image::WHITE;

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
        let mut im = Image::new(w, h, WHITE).unwrap();
        vertical(&mut im, &scale, "distance [L]");
        let px = |im: &Image, x: usize, y: usize| im.pixel(x, y).unwrap();
        // The bar's top is the high end of the map (yellow), its bottom the low end (purple).
        let (top, bottom) = (px(&im, w - 100, h / 5 + 2), px(&im, w - 100, h - h / 5 - 2));
        assert!(top[0] > 200 && top[2] < 100, "{top:?}");
        assert!(bottom[2] > 60 && bottom[1] < 30, "{bottom:?}");
        // Some dark pixels of text at the top left (caption) and bottom left (note).
        let dark = |im: &Image, y0: usize| (y0..y0 + 10).any(|y| (10..200).any(|x| px(im, x, y)[0] == 0));
        assert!(dark(&im, 10) && dark(&im, h - 20));
        // A field that fits needs no note.
        let mut plain = Image::new(w, h, WHITE).unwrap();
        vertical(&mut plain, &ColorScale::fit(&[1.0, 2.0]), "k");
        assert!(!dark(&plain, h - 20));
    }

    #[test]
    fn horizontal_bar_runs_low_to_high() {
        let mut im = Image::new(200, 100, WHITE).unwrap();
        let scale = ColorScale::symmetric(&[-1.0, 1.0]);
        horizontal(&mut im, &scale);
        let y = 100 - BAR_HEIGHT + 12;
        let (left, right) = (im.pixel(9 * 4 + 6, y).unwrap(), im.pixel(200 - 9 * 4 - 7, y).unwrap());
        assert!(left[2] > left[0], "{left:?}"); // blue end
        assert!(right[0] > right[2], "{right:?}"); // red end
        let mut sw = Image::new(200, 100, WHITE).unwrap();
        swatches(&mut sw, &crate::color::CurvatureClasses::swatches());
        assert!(sw.count_differing(Rect { x: 0, y: 100 - BAR_HEIGHT, width: 200, height: BAR_HEIGHT }, WHITE) > 100);
    }
}
