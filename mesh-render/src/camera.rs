//! [`View`]: an orthographic camera given by azimuth, elevation and the
//! axis that points up, and the projection that fits a set of points into
//! a picture.

use glam::{DVec2, DVec3};

use crate::error::{RenderError, Result};

/// Where the camera looks from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct View {
    /// Azimuth around `up`, degrees. 0 looks at the model's front: +z for a
    /// y-up model, -y for a z-up one (the conventions of modelling tools),
    /// +z for an x-up one.
    pub azimuth: f64,
    /// Elevation above the plane orthogonal to `up`, degrees.
    pub elevation: f64,
    /// The axis that points up in the picture.
    pub up: DVec3,
}

impl Default for View {
    fn default() -> Self {
        Self { azimuth: -60.0, elevation: 30.0, up: DVec3::Z }
    }
}

/// The camera's orthonormal frame: screen right, screen up, and the
/// direction toward the camera (depth grows toward the viewer).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    /// Screen right.
    pub right: DVec3,
    /// Screen up.
    pub up: DVec3,
    /// Toward the camera.
    pub toward: DVec3,
}

impl View {
    /// A view from the given angles with `up` as the vertical axis.
    pub fn new(azimuth: f64, elevation: f64, up: DVec3) -> Self {
        Self { azimuth, elevation, up }
    }

    /// The camera frame.
    ///
    /// # Errors
    /// `RenderError::InvalidOption` for non-finite angles or axis.
    pub fn frame(&self) -> Result<Frame> {
        if !(self.azimuth.is_finite() && self.elevation.is_finite() && self.up.is_finite()) {
            return Err(RenderError::InvalidOption {
                name: "view",
                reason: format!("angles and up axis must be finite (got {self:?})"),
            });
        }
        let (az, el) = (self.azimuth.to_radians(), self.elevation.to_radians());
        let z = self.up.try_normalize().unwrap_or(DVec3::Z);
        let front = if z.z.abs() > 0.9 { -DVec3::Y } else { DVec3::Z };
        let e1 = (front - front.dot(z) * z).try_normalize().unwrap_or_else(|| z.any_orthonormal_vector());
        let e2 = z.cross(e1);
        let toward = el.cos() * (az.cos() * e1 + az.sin() * e2) + el.sin() * z;
        let right = z.cross(toward).try_normalize().unwrap_or(e1);
        let up = toward.cross(right);
        Ok(Frame { right, up, toward })
    }
}

/// Fits points into a pixel area: screen position (pixels, y down) and depth.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Projection {
    frame: Frame,
    mid: DVec2,
    scale: f64,
    centre: DVec2,
}

impl Projection {
    /// The projection that fits `points` (non-finite ones ignored) into
    /// `area` (x, y, width, height in pixels) filling `fill` of it.
    pub(crate) fn fit(frame: Frame, points: impl Iterator<Item = DVec3>, area: [f64; 4], fill: f64) -> Self {
        let (lo, hi) = points.filter(|p| p.is_finite()).fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(lo, hi), p| {
            let q = DVec2::new(p.dot(frame.right), p.dot(frame.up));
            (lo.min(q), hi.max(q))
        });
        let (lo, hi) = if lo.x <= hi.x { (lo, hi) } else { (DVec2::ZERO, DVec2::ZERO) };
        let extent = (hi - lo).max(DVec2::splat(1e-300));
        let scale = fill * (area[2] / extent.x).min(area[3] / extent.y);
        let scale = if scale.is_finite() && scale > 0.0 { scale } else { 1.0 };
        Self {
            frame,
            mid: 0.5 * (lo + hi),
            scale,
            centre: DVec2::new(area[0] + area[2] / 2.0, area[1] + area[3] / 2.0),
        }
    }

    /// Screen position (pixels, y down) and depth (larger is nearer).
    pub(crate) fn project(&self, p: DVec3) -> (DVec2, f64) {
        let q = DVec2::new(p.dot(self.frame.right), p.dot(self.frame.up)) - self.mid;
        (DVec2::new(self.centre.x + self.scale * q.x, self.centre.y - self.scale * q.y), p.dot(self.frame.toward))
    }

    pub(crate) fn frame(&self) -> &Frame {
        &self.frame
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_is_orthonormal_and_refuses_nan() {
        let f = View::default().frame().unwrap();
        assert!((f.right.dot(f.up)).abs() < 1e-12 && (f.up.dot(f.toward)).abs() < 1e-12);
        assert!((f.right.cross(f.up) - f.toward).length() < 1e-12);
        assert!(View::new(f64::NAN, 0.0, DVec3::Z).frame().is_err());
    }

    #[test]
    fn projection_centres_the_points() {
        let f = View::new(0.0, 90.0, DVec3::Z).frame().unwrap();
        let pts = [DVec3::new(-1.0, -1.0, 0.0), DVec3::new(1.0, 1.0, 0.0)];
        let p = Projection::fit(f, pts.into_iter(), [0.0, 0.0, 100.0, 100.0], 1.0);
        let (c, _) = p.project(DVec3::ZERO);
        assert!((c - DVec2::splat(50.0)).length() < 1e-9);
    }
}
