//! How precisely the coordinates were stored: the position noise that
//! rounding them to a file's precision left.
//!
//! Files round coordinates: to single precision (binary STL, glTF, float
//! PLY), to a number of decimal places (`%.6f`) or of significant digits
//! (`%g`) in text formats. The grid a mesh's coordinates lie on says how
//! far each point may have moved: half a step of that grid. Quantities of
//! higher order in the coordinates amplify it (a curvature estimate by
//! `1 / h^2`), so a flat region of a single-precision mesh shows curvatures
//! that are only this noise; [`position_noise`] lets a caller tell the two
//! apart.
//!
//! Detection: a mesh whose every coordinate is a single-precision number is
//! taken as stored in single precision. Otherwise the coarsest decimal grid
//! every coordinate lies on is found, in places after the point (up to
//! [`MAX_PLACES`]) and in significant digits (up to
//! [`MAX_SIGNIFICANT_DIGITS`]), and the larger of the two half-steps is
//! taken (either could be the one the writer used; the larger is an upper
//! bound either way). A decimal test is exact: `x` has `k` places when
//! `round(x 10^k) / 10^k == x` (both operations are exact or correctly
//! rounded, and a parsed `k`-place decimal is the double nearest to it).
//! Coordinates on none of these grids are taken as exact (noise 0).

use glam::DVec3;

use crate::par;
use crate::TriMesh;

/// Decimal places tried after the point.
pub const MAX_PLACES: i32 = 12;
/// Significant decimal digits tried.
pub const MAX_SIGNIFICANT_DIGITS: i32 = 10;

/// How the coordinates of a mesh were rounded, as [`storage`] finds it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Storage {
    /// Every coordinate is a single-precision number.
    Single,
    /// Decimal: every coordinate has at most `places` places after the point
    /// (`None`: more than [`MAX_PLACES`]) and at most `digits` significant
    /// digits (`None`: more than [`MAX_SIGNIFICANT_DIGITS`]); at least one
    /// of the two is known.
    Decimal {
        /// Places after the point.
        places: Option<i32>,
        /// Significant digits.
        digits: Option<i32>,
    },
    /// None of these: the coordinates are taken as exact.
    Exact,
}

/// How the coordinates of `mesh` were rounded. O(V).
pub fn storage(mesh: &TriMesh) -> Storage {
    let coords = || mesh.positions().iter().flat_map(|p| p.to_array()).filter(|x| *x != 0.0);
    if coords().all(|x| f64::from(x as f32) == x) {
        return Storage::Single;
    }
    // Having k places (digits) implies having more: each coordinate is
    // first tried at the most found so far, almost always enough.
    let places = coords().try_fold(0, |most, x| (most..=MAX_PLACES).find(|&k| has_places(x, k)));
    let digits = coords().try_fold(1, |most, x| (most..=MAX_SIGNIFICANT_DIGITS).find(|&s| has_digits(x, s)));
    match (places, digits) {
        (None, None) => Storage::Exact,
        (places, digits) => Storage::Decimal { places, digits },
    }
}

/// The position noise of every vertex: the length of the largest
/// displacement the rounding of its coordinates may have caused (half a
/// step of the grid, per axis), in the mesh's unit; zeros for
/// [`Storage::Exact`]. O(V).
pub fn position_noise(mesh: &TriMesh) -> Vec<f64> {
    let storage = storage(mesh);
    let half_step = |x: f64| -> f64 {
        match storage {
            Storage::Exact => 0.0,
            Storage::Single => half_ulp_single(x),
            Storage::Decimal { places, digits } => {
                let fixed = places.map_or(0.0, |k| 0.5 * 10f64.powi(-k));
                let significant = digits.map_or(0.0, |s| 0.5 * 10f64.powi(exponent10(x) - s + 1));
                fixed.max(significant)
            }
        }
    };
    par::map(mesh.vertex_count(), |v| {
        let p = mesh.positions()[v];
        DVec3::new(half_step(p.x), half_step(p.y), half_step(p.z)).length()
    })
}

/// Half the spacing of single-precision numbers at `x`.
fn half_ulp_single(x: f64) -> f64 {
    let a = (x as f32).abs();
    if !a.is_finite() {
        return 0.0;
    }
    let next = f32::from_bits(a.to_bits() + 1);
    0.5 * f64::from(next - a)
}

/// The decimal exponent of `x`: `floor(log10 |x|)`, and 0 for 0.
fn exponent10(x: f64) -> i32 {
    if x == 0.0 || !x.is_finite() {
        return 0;
    }
    let e = x.abs().log10().floor() as i32;
    // log10 may round across a power of ten.
    if 10f64.powi(e) > x.abs() {
        e - 1
    } else if 10f64.powi(e + 1) <= x.abs() {
        e + 1
    } else {
        e
    }
}

/// Whether `x` has at most `k` decimal places (`k` may be negative: a
/// multiple of `10^-k`).
fn has_places(x: f64, k: i32) -> bool {
    if k >= 0 {
        let scale = 10f64.powi(k);
        let scaled = (x * scale).round();
        scaled.abs() < 2f64.powi(53) && scaled / scale == x
    } else {
        let step = 10f64.powi(-k);
        (x / step).round() * step == x
    }
}

/// Whether `x` has at most `s` significant decimal digits.
fn has_digits(x: f64, s: i32) -> bool {
    has_places(x, s - 1 - exponent10(x))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes;

    fn decimal_places(x: f64) -> Option<i32> {
        (0..=MAX_PLACES).find(|&k| has_places(x, k))
    }

    fn significant_digits(x: f64) -> Option<i32> {
        (1..=MAX_SIGNIFICANT_DIGITS).find(|&s| has_digits(x, s))
    }

    fn moved(mesh: &TriMesh, round: impl Fn(f64) -> f64) -> TriMesh {
        let p = mesh.positions().iter().map(|p| (*p * 3.7 + DVec3::new(12.5, -0.3, 7.0)).to_array().map(&round).into());
        TriMesh::new(p.collect(), mesh.faces().to_vec()).unwrap()
    }

    #[test]
    fn finds_how_the_coordinates_were_rounded() {
        let m = shapes::torus(1.0, 0.3, 24, 12).unwrap();
        assert_eq!(storage(&moved(&m, |x| x)), Storage::Exact);
        let single = moved(&m, |x| f64::from(x as f32));
        assert_eq!(storage(&single), Storage::Single);
        // Text: "%.6f" and "%.7g", written and parsed back as a reader would.
        let fixed = moved(&m, |x| format!("{x:.6}").parse().unwrap());
        assert!(matches!(storage(&fixed), Storage::Decimal { places: Some(k), .. } if k <= 6), "{:?}", storage(&fixed));
        let sig = moved(&m, |x| format!("{x:.6e}").parse().unwrap());
        assert!(matches!(storage(&sig), Storage::Decimal { digits: Some(s), .. } if s <= 7), "{:?}", storage(&sig));
        // Integers and a few places: found exactly.
        assert_eq!(decimal_places(1250.0), Some(0));
        assert_eq!(decimal_places(-0.125), Some(3));
        assert_eq!(significant_digits(1250.0), Some(3));
        assert_eq!(significant_digits(0.000_406), Some(3));
        assert_eq!(exponent10(999.999_999_999), 2);
        assert_eq!(exponent10(1000.0), 3);
    }

    #[test]
    fn the_noise_bounds_the_rounding_and_is_zero_for_exact_coordinates() {
        let m = shapes::icosphere(2).unwrap();
        let exact = moved(&m, |x| x);
        assert!(position_noise(&exact).iter().all(|d| *d == 0.0));
        for (round, most) in [
            (Box::new(|x: f64| f64::from(x as f32)) as Box<dyn Fn(f64) -> f64>, 2e-6),
            (Box::new(|x: f64| format!("{x:.6}").parse().unwrap()), 1e-6),
            (Box::new(|x: f64| format!("{x:.5e}").parse().unwrap()), 2e-4),
        ] {
            let rounded = moved(&m, &round);
            let noise = position_noise(&rounded);
            for ((p, q), d) in exact.positions().iter().zip(rounded.positions()).zip(&noise) {
                let moved_by = (*p - *q).length();
                assert!(moved_by <= *d * (1.0 + 1e-12), "moved {moved_by}, noise {d}");
                assert!(*d > 0.0 && *d < most, "noise {d}");
            }
        }
    }
}
