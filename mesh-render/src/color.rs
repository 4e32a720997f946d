//! Colour maps: [`ColorScale`] for scalar fields (viridis, or a diverging
//! blue-white-red map centred on zero for signed fields) and
//! [`CurvatureClasses`], the map of the chapter's Figure 2.9: red where the
//! surface is convex, blue where it is concave, grey at saddles.

use glam::DVec3;

/// The diverging map's three stops: blue, light grey, red.
const DIVERGING: [DVec3; 3] =
    [DVec3::new(0.23, 0.30, 0.75), DVec3::new(0.87, 0.87, 0.87), DVec3::new(0.71, 0.02, 0.15)];

/// Viridis, sampled at five points.
const VIRIDIS: [DVec3; 5] = [
    DVec3::new(0.267, 0.005, 0.329),
    DVec3::new(0.230, 0.322, 0.546),
    DVec3::new(0.128, 0.567, 0.551),
    DVec3::new(0.369, 0.789, 0.383),
    DVec3::new(0.993, 0.906, 0.144),
];

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
    /// take both signs. O(n log n).
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

    /// The full range of the finite values (no clipping), sequential.
    pub fn full(values: &[f64]) -> Self {
        let (lo, hi) = values
            .iter()
            .filter(|x| x.is_finite())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &x| (lo.min(x), hi.max(x)));
        if lo > hi {
            return Self { min: 0.0, max: 1.0, diverging: false, data_range: None };
        }
        let (min, max) = if hi > lo { (lo, hi) } else { (lo - 0.5, lo + 0.5) };
        Self { min, max, diverging: false, data_range: Some((lo, hi)) }
    }

    /// A diverging scale symmetric about zero, `[-m, m]` with `m` the
    /// 98th percentile of `|values|` (robust to a few spikes).
    pub fn symmetric(values: &[f64]) -> Self {
        let mut a: Vec<f64> = values.iter().filter(|x| x.is_finite()).map(|x| x.abs()).collect();
        let full = Self::full(values);
        if a.is_empty() {
            return Self { diverging: true, min: -1.0, max: 1.0, ..full };
        }
        a.sort_by(f64::total_cmp);
        let m = a[((a.len() - 1) as f64 * 0.98).round() as usize];
        let m = if m > 0.0 { m } else { 1.0 };
        Self { min: -m, max: m, diverging: true, data_range: full.data_range }
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
        let stops: &[DVec3] = if self.diverging { &DIVERGING } else { &VIRIDIS };
        let s = t * (stops.len() - 1) as f64;
        let i = (s.floor() as usize).min(stops.len() - 2);
        stops[i].lerp(stops[i + 1], s - i as f64)
    }

    /// The colour of every value.
    pub fn colors(&self, values: &[f64]) -> Vec<DVec3> {
        values.iter().map(|&x| self.color(x)).collect()
    }
}

/// The class of a surface point by the signs of its mean curvature `H` and
/// Gaussian curvature `K` (the chapter's Figure 2.9).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CurvatureClass {
    /// `K > 0`, `H > 0`: bends away from the normal in every direction (a cap).
    Convex,
    /// `K > 0`, `H < 0`: bends toward the normal in every direction (a cup).
    Concave,
    /// `K < 0`: a saddle.
    Saddle,
    /// `|K|` below the threshold: flat or curved in one direction only.
    Flat,
}

/// The colours of Figure 2.9: red convex, blue concave, grey saddle, with
/// the strength of the red and blue growing with `|H|`; flat (parabolic)
/// points light grey.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurvatureClasses {
    /// `|K|` at or below this is [`CurvatureClass::Flat`].
    pub k_threshold: f64,
    /// `|H|` at which red and blue are at full strength.
    pub h_scale: f64,
}

impl CurvatureClasses {
    /// Full red (convex).
    pub const RED: DVec3 = DVec3::new(0.80, 0.08, 0.08);
    /// Full blue (concave).
    pub const BLUE: DVec3 = DVec3::new(0.10, 0.25, 0.85);
    /// Grey (saddle).
    pub const GREY: DVec3 = DVec3::new(0.50, 0.50, 0.50);
    /// Light grey (flat, and the weak end of red and blue).
    pub const LIGHT: DVec3 = DVec3::new(0.90, 0.90, 0.88);

    /// Thresholds from the fields: flat below 2% of the 95th percentile of
    /// `|K|`, full colour at the 90th percentile of `|H|`. Non-finite values
    /// are left out. O(n log n).
    pub fn fit(mean: &[f64], gaussian: &[f64]) -> Self {
        let quantile = |v: &[f64], q: f64| {
            let mut a: Vec<f64> = v.iter().filter(|x| x.is_finite()).map(|x| x.abs()).collect();
            a.sort_by(f64::total_cmp);
            a.get(((a.len().max(1) - 1) as f64 * q).round() as usize).copied().unwrap_or(0.0)
        };
        let k = quantile(gaussian, 0.95);
        let h = quantile(mean, 0.9);
        Self { k_threshold: 0.02 * k, h_scale: if h > 0.0 { h } else { 1.0 } }
    }

    /// The class of a point with mean curvature `h` and Gaussian curvature `k`.
    pub fn class(&self, h: f64, k: f64) -> CurvatureClass {
        if !(h.is_finite() && k.is_finite()) || k.abs() <= self.k_threshold {
            CurvatureClass::Flat
        } else if k < 0.0 {
            CurvatureClass::Saddle
        } else if h > 0.0 {
            CurvatureClass::Convex
        } else {
            CurvatureClass::Concave
        }
    }

    /// The colour of a point: red or blue (stronger with `|h|`), grey, or light grey.
    pub fn color(&self, h: f64, k: f64) -> DVec3 {
        let t = (h.abs() / self.h_scale).clamp(0.0, 1.0).sqrt();
        match self.class(h, k) {
            CurvatureClass::Convex => Self::LIGHT.lerp(Self::RED, 0.35 + 0.65 * t),
            CurvatureClass::Concave => Self::LIGHT.lerp(Self::BLUE, 0.35 + 0.65 * t),
            CurvatureClass::Saddle => Self::GREY,
            CurvatureClass::Flat => Self::LIGHT,
        }
    }

    /// The colour of every vertex (`mean` and `gaussian` of equal length;
    /// extra values of the longer one are ignored).
    pub fn colors(&self, mean: &[f64], gaussian: &[f64]) -> Vec<DVec3> {
        mean.iter().zip(gaussian).map(|(&h, &k)| self.color(h, k)).collect()
    }

    /// The legend: each class's colour and name.
    pub fn swatches() -> Vec<(DVec3, String)> {
        vec![
            (Self::RED, "convex".into()),
            (Self::BLUE, "concave".into()),
            (Self::GREY, "saddle".into()),
            (Self::LIGHT, "flat".into()),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn diverging_scale_is_symmetric() {
        let s = ColorScale::fit(&[-1.0, 0.5, 2.0, f64::NAN]);
        assert!(s.diverging && s.min == -s.max);
        let white = s.color(0.0);
        assert!(white.x > 0.8 && white.y > 0.8 && white.z > 0.8);
        let sym = ColorScale::symmetric(&[0.1, 0.2, -3.0]);
        assert!(sym.diverging && sym.max == 3.0 && sym.min == -3.0);
        assert!(sym.color(3.0).x > 0.6 && sym.color(-3.0).z > 0.6);
    }

    #[test]
    fn full_scale_keeps_the_range() {
        let s = ColorScale::full(&[2.0, 5.0, f64::INFINITY]);
        assert_eq!((s.min, s.max, s.clipped()), (2.0, 5.0, false));
        let flat = ColorScale::full(&[1.0, 1.0]);
        assert!(flat.max > flat.min);
    }

    #[test]
    fn curvature_classes_follow_the_signs() {
        let m = CurvatureClasses { k_threshold: 0.01, h_scale: 1.0 };
        assert_eq!(m.class(1.0, 1.0), CurvatureClass::Convex);
        assert_eq!(m.class(-1.0, 1.0), CurvatureClass::Concave);
        assert_eq!(m.class(0.0, -1.0), CurvatureClass::Saddle);
        assert_eq!(m.class(0.5, 0.0), CurvatureClass::Flat);
        assert_eq!(m.class(f64::NAN, 1.0), CurvatureClass::Flat);
        let red = m.color(1.0, 1.0);
        assert!(red.x > 0.7 && red.y < 0.2 && red.z < 0.2, "{red}");
        let blue = m.color(-1.0, 1.0);
        assert!(blue.z > 0.7 && blue.x < 0.2, "{blue}");
        let grey = m.color(0.3, -1.0);
        assert!((grey.x - grey.z).abs() < 1e-12 && (grey.x - grey.y).abs() < 1e-12);
        let fit = CurvatureClasses::fit(&[1.0, -2.0, f64::NAN], &[1.0, 4.0, -1.0]);
        assert!(fit.k_threshold > 0.0 && fit.h_scale > 0.0);
    }
}
