//! [`Drawing`]: figures in the plane (points, segments, filled polygons),
//! fitted into a picture with equal scales on both axes, y up. For planar
//! figures: triangulations and their Voronoi cells, 4-to-1 splits, UV layouts.

use glam::{DVec2, DVec3};

use crate::error::{RenderError, Result};
use crate::image::{check_size, downsample, segment_stamps, Image, WHITE};

/// Samples per pixel along each axis.
const SS: usize = 2;

#[derive(Debug, Clone)]
enum Item {
    Polygon(Vec<DVec2>, DVec3),
    Segment([DVec2; 2], DVec3, f64),
    Point(DVec2, DVec3, f64),
}

/// Points, segments and filled polygons in the plane, drawn in the order
/// polygons, segments, points (whatever order they were added in).
#[derive(Debug, Clone, Default)]
pub struct Drawing {
    items: Vec<Item>,
}

fn check_width(name: &'static str, w: f64) -> Result<()> {
    if !(w.is_finite() && w > 0.0 && w <= 64.0) {
        return Err(RenderError::InvalidOption { name, reason: format!("{w} is not in (0, 64] pixels") });
    }
    Ok(())
}

impl Drawing {
    /// An empty drawing.
    pub fn new() -> Self {
        Self::default()
    }

    /// A filled polygon (even-odd rule; fewer than three finite corners draw nothing).
    pub fn polygon(&mut self, corners: Vec<DVec2>, fill: DVec3) -> &mut Self {
        if corners.len() >= 3 && corners.iter().all(|c| c.is_finite()) {
            self.items.push(Item::Polygon(corners, fill));
        }
        self
    }

    /// A segment `width` pixels wide (left out when an end is not finite).
    ///
    /// # Errors
    /// `RenderError::InvalidOption` for a width outside (0, 64].
    pub fn segment(&mut self, a: DVec2, b: DVec2, color: DVec3, width: f64) -> Result<&mut Self> {
        check_width("line width", width)?;
        if a.is_finite() && b.is_finite() {
            self.items.push(Item::Segment([a, b], color, width));
        }
        Ok(self)
    }

    /// A round point of `diameter` pixels (left out when not finite).
    ///
    /// # Errors
    /// `RenderError::InvalidOption` for a diameter outside (0, 64].
    pub fn point(&mut self, p: DVec2, color: DVec3, diameter: f64) -> Result<&mut Self> {
        check_width("point diameter", diameter)?;
        if p.is_finite() {
            self.items.push(Item::Point(p, color, diameter));
        }
        Ok(self)
    }

    /// The edges of triangles (`[a, b, c]` indices into `points`) as
    /// segments, each edge once; indices out of range are skipped.
    ///
    /// # Errors
    /// `RenderError::InvalidOption` for a width outside (0, 64].
    pub fn triangle_edges(
        &mut self,
        points: &[DVec2],
        triangles: &[[u32; 3]],
        color: DVec3,
        width: f64,
    ) -> Result<&mut Self> {
        check_width("line width", width)?;
        let mut edges: Vec<(u32, u32)> = triangles
            .iter()
            .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
            .map(|(a, b)| (a.min(b), a.max(b)))
            .collect();
        edges.sort_unstable();
        edges.dedup();
        for (a, b) in edges {
            if let (Some(&pa), Some(&pb)) = (points.get(a as usize), points.get(b as usize)) {
                self.segment(pa, pb, color, width)?;
            }
        }
        Ok(self)
    }

    fn bounds(&self) -> (DVec2, DVec2) {
        let mut lo = DVec2::INFINITY;
        let mut hi = DVec2::NEG_INFINITY;
        let mut add = |p: DVec2| {
            lo = lo.min(p);
            hi = hi.max(p);
        };
        for item in &self.items {
            match item {
                Item::Polygon(c, _) => c.iter().for_each(|&p| add(p)),
                Item::Segment(s, _, _) => s.iter().for_each(|&p| add(p)),
                Item::Point(p, _, _) => add(*p),
            }
        }
        (lo, hi)
    }

    /// Renders the drawing into a `width` x `height` picture on white, the
    /// drawing's bounding box filling 90% of it. O(pixels x items) at worst.
    ///
    /// # Errors
    /// `RenderError::Size` for a bad picture size.
    pub fn render(&self, width: usize, height: usize) -> Result<Image> {
        check_size(width, height)?;
        let (w, h) = (width * SS, height * SS);
        let (lo, hi) = self.bounds();
        let (lo, hi) = if lo.x <= hi.x { (lo, hi) } else { (DVec2::ZERO, DVec2::ONE) };
        let extent = (hi - lo).max(DVec2::splat(1e-300));
        let scale = 0.9 * (w as f64 / extent.x).min(h as f64 / extent.y);
        let scale = if scale.is_finite() && scale > 0.0 { scale } else { 1.0 };
        let mid = 0.5 * (lo + hi);
        let to_px =
            |p: DVec2| DVec2::new(w as f64 / 2.0 + scale * (p.x - mid.x), h as f64 / 2.0 - scale * (p.y - mid.y));
        let mut color = vec![WHITE; w * h];
        let mut pass = |which: u8| {
            for item in &self.items {
                match (which, item) {
                    (0, Item::Polygon(corners, fill)) => {
                        let px: Vec<DVec2> = corners.iter().map(|&p| to_px(p)).collect();
                        fill_polygon(&mut color, w, h, &px, *fill);
                    }
                    (1, Item::Segment([a, b], c, width)) => {
                        stamp_segment(&mut color, w, h, to_px(*a), to_px(*b), 0.5 * width * SS as f64, *c)
                    }
                    (2, Item::Point(p, c, d)) => {
                        let q = to_px(*p);
                        stamp_segment(&mut color, w, h, q, q, 0.5 * d * SS as f64, *c)
                    }
                    _ => {}
                }
            }
        };
        (0..3).for_each(&mut pass);
        downsample(&color, SS, width, height)
    }
}

fn fill_polygon(color: &mut [DVec3], w: usize, h: usize, px: &[DVec2], fill: DVec3) {
    let lo = px.iter().fold(DVec2::INFINITY, |a, &b| a.min(b)).max(DVec2::ZERO);
    let hi = px.iter().fold(DVec2::NEG_INFINITY, |a, &b| a.max(b)).min(DVec2::new(w as f64 - 1.0, h as f64 - 1.0));
    if !(lo.x <= hi.x && lo.y <= hi.y) {
        return;
    }
    for y in lo.y.floor() as usize..=hi.y.ceil() as usize {
        let qy = y as f64 + 0.5;
        // Crossings of the row with the polygon's edges (even-odd rule).
        let mut xs: Vec<f64> = Vec::new();
        for (i, &a) in px.iter().enumerate() {
            let b = px[(i + 1) % px.len()];
            if (a.y <= qy) != (b.y <= qy) {
                xs.push(a.x + (qy - a.y) / (b.y - a.y) * (b.x - a.x));
            }
        }
        xs.sort_by(f64::total_cmp);
        for pair in xs.chunks_exact(2) {
            let x0 = (pair[0] - 0.5).ceil().max(0.0) as usize;
            let x1 = (pair[1] - 0.5).floor().min(w as f64 - 1.0);
            if x1 < 0.0 || y >= h {
                continue;
            }
            for x in x0..=(x1 as usize) {
                color[y * w + x] = fill;
            }
        }
    }
}

fn stamp_segment(color: &mut [DVec3], w: usize, h: usize, a: DVec2, b: DVec2, radius: f64, c: DVec3) {
    segment_stamps(w, h, a, b, radius, |_, i| color[i] = c);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image::{Rect, BLACK};

    #[test]
    fn polygon_segment_and_point_land_where_expected() {
        let mut d = Drawing::new();
        let red = DVec3::new(1.0, 0.0, 0.0);
        d.polygon(vec![DVec2::ZERO, DVec2::new(1.0, 0.0), DVec2::new(1.0, 1.0), DVec2::new(0.0, 1.0)], red);
        d.segment(DVec2::new(0.0, 0.5), DVec2::new(1.0, 0.5), BLACK, 2.0).unwrap();
        d.point(DVec2::new(0.25, 0.25), DVec3::new(0.0, 0.0, 1.0), 6.0).unwrap();
        let im = d.render(100, 100).unwrap();
        assert_eq!(im.pixel(2, 2), Some([255, 255, 255])); // outside the 90% box
        assert_eq!(im.pixel(75, 25), Some([255, 0, 0])); // top right quadrant, filled
        assert_eq!(im.pixel(75, 50).map(|p| p[0] < 40), Some(true)); // the segment across the middle (y up)
        let blue = im.pixel(28, 72).unwrap(); // the point at (0.25, 0.25), lower left
        assert!(blue[2] > 200 && blue[0] < 60, "{blue:?}");
        assert!(d.segment(DVec2::ZERO, DVec2::ONE, BLACK, f64::NAN).is_err());
        assert_eq!(
            Drawing::new().render(5, 5).unwrap().count_differing(Rect { x: 0, y: 0, width: 5, height: 5 }, WHITE),
            0
        );
    }

    #[test]
    fn triangle_edges_are_drawn_once() {
        let pts = [DVec2::ZERO, DVec2::X, DVec2::Y, DVec2::ONE];
        let mut d = Drawing::new();
        d.triangle_edges(&pts, &[[0, 1, 2], [1, 3, 2], [0, 9, 1]], BLACK, 1.0).unwrap();
        assert_eq!(d.items.len(), 5);
    }
}
