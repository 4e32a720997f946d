//! [`Figure`]: several pictures side by side (in rows of a chosen number of
//! columns), a one-line caption under each and a title above them all.

use crate::error::{RenderError, Result};
use crate::font::GLYPH_HEIGHT;
use crate::image::{Image, Rect, BLACK, WHITE};

/// Pixels per font cell of titles and captions.
const TEXT_SCALE: usize = 2;
/// Height of the title strip.
pub const TITLE_HEIGHT: usize = GLYPH_HEIGHT * TEXT_SCALE + 12;
/// Height of the caption strip under each panel.
pub const CAPTION_HEIGHT: usize = GLYPH_HEIGHT * TEXT_SCALE + 10;
/// Gap between panels.
pub const GAP: usize = 6;

/// One picture of a figure and the line under it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Panel {
    /// The picture.
    pub image: Image,
    /// Its caption (cut to the panel's width when drawn).
    pub caption: String,
}

impl Panel {
    /// A panel.
    pub fn new(image: Image, caption: impl Into<String>) -> Self {
        Self { image, caption: caption.into() }
    }
}

/// Panels in a grid under a title.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Figure {
    /// The line above the panels (cut to the figure's width when drawn).
    pub title: String,
    /// The panels, row by row.
    pub panels: Vec<Panel>,
    /// Panels per row (at least 1).
    pub columns: usize,
}

impl Figure {
    /// A figure with every panel in one row.
    pub fn row(title: impl Into<String>, panels: Vec<Panel>) -> Self {
        let columns = panels.len().max(1);
        Self { title: title.into(), panels, columns }
    }

    /// Cell size: the largest panel.
    fn cell(&self) -> (usize, usize) {
        self.panels.iter().fold((0, 0), |(w, h), p| (w.max(p.image.width()), h.max(p.image.height())))
    }

    /// The rectangle of each panel's picture in [`Figure::compose`]'s output.
    pub fn panel_rects(&self) -> Vec<Rect> {
        let (cw, ch) = self.cell();
        let cols = self.columns.max(1).min(self.panels.len().max(1));
        self.panels
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let (col, row) = (i % cols, i / cols);
                let x = GAP + col * (cw + GAP) + (cw - p.image.width()) / 2;
                let y = TITLE_HEIGHT + row * (ch + CAPTION_HEIGHT + GAP) + (ch - p.image.height()) / 2;
                Rect { x, y, width: p.image.width(), height: p.image.height() }
            })
            .collect()
    }

    /// The figure as one picture: title, then the panels with thin frames
    /// and their captions.
    ///
    /// # Errors
    /// `RenderError::InvalidOption` for a figure without panels;
    /// `RenderError::Size` when the figure would exceed the largest picture.
    pub fn compose(&self) -> Result<Image> {
        if self.panels.is_empty() {
            return Err(RenderError::InvalidOption { name: "panels", reason: "a figure needs a panel".into() });
        }
        let (cw, ch) = self.cell();
        let cols = self.columns.max(1).min(self.panels.len());
        let rows = self.panels.len().div_ceil(cols);
        let width = GAP + cols * (cw + GAP);
        let height = TITLE_HEIGHT + rows * (ch + CAPTION_HEIGHT + GAP);
        let mut out = Image::new(width, height, WHITE)?;
        out.text_centred(Rect { x: 0, y: 6, width, height: TITLE_HEIGHT }, &self.title, BLACK, TEXT_SCALE);
        let grey = glam::DVec3::splat(0.8);
        for (i, (p, r)) in self.panels.iter().zip(self.panel_rects()).enumerate() {
            out.blit(&p.image, r.x, r.y);
            let border = Rect { x: r.x - 1, y: r.y - 1, width: r.width + 2, height: r.height + 2 };
            out.frame(border, grey);
            let (col, row) = (i % cols, i / cols);
            let (cell_x, cell_y) = (GAP + col * (cw + GAP), TITLE_HEIGHT + row * (ch + CAPTION_HEIGHT + GAP));
            let caption = Rect { x: cell_x, y: cell_y + ch + 5, width: cw, height: CAPTION_HEIGHT };
            out.text_centred(caption, &p.caption, BLACK, TEXT_SCALE);
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn panels_land_in_their_rectangles() {
        let red = Image::new(40, 30, DVec3::new(1.0, 0.0, 0.0)).unwrap();
        let blue = Image::new(40, 30, DVec3::new(0.0, 0.0, 1.0)).unwrap();
        let fig = Figure {
            title: "T".into(),
            panels: vec![Panel::new(red, "A"), Panel::new(blue.clone(), "B"), Panel::new(blue, "C")],
            columns: 2,
        };
        let out = fig.compose().unwrap();
        let rects = fig.panel_rects();
        assert_eq!(out.width(), GAP + 2 * (40 + GAP));
        assert_eq!(out.height(), TITLE_HEIGHT + 2 * (30 + CAPTION_HEIGHT + GAP));
        assert_eq!(out.pixel(rects[0].x + 5, rects[0].y + 5), Some([255, 0, 0]));
        assert_eq!(out.pixel(rects[2].x + 5, rects[2].y + 5), Some([0, 0, 255]));
        assert!(rects[2].y > rects[1].y + 30);
        // Captions: dark pixels under each panel.
        for r in &rects {
            let strip = Rect { x: r.x, y: r.y + r.height + 2, width: r.width, height: CAPTION_HEIGHT - 2 };
            assert!(out.count_differing(strip, WHITE) > 0);
        }
        assert!(Figure::row("x", vec![]).compose().is_err());
    }
}
