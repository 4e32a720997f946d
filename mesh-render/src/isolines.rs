//! Isolines of a per-vertex scalar field, by marching over triangles: the
//! field is linear on each triangle, so a level crosses a triangle in one
//! straight segment between two of its edges.

use glam::DVec3;
use mesh_kernel::TriMesh;

use crate::error::{RenderError, Result};

/// Which levels to draw.
#[derive(Debug, Clone, PartialEq)]
pub enum Levels {
    /// `n` levels evenly spaced strictly inside the field's finite range:
    /// `min + k (max - min) / (n + 1)` for `k = 1..=n`.
    Count(usize),
    /// These levels (non-finite ones ignored).
    Given(Vec<f64>),
    /// Every multiple of `step` inside the field's finite range (for
    /// distances: wavefronts at equal spacing from 0). Refused when it would
    /// give more than 10,000 levels.
    Step(f64),
}

impl Levels {
    /// The level values for a field.
    ///
    /// # Errors
    /// `RenderError::InvalidOption` for a step that is not finite and
    /// positive or that gives more than 10,000 levels, or more than 10,000
    /// counted levels.
    pub fn values(&self, field: &[f64]) -> Result<Vec<f64>> {
        let (lo, hi) = field
            .iter()
            .filter(|x| x.is_finite())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &x| (lo.min(x), hi.max(x)));
        let too_many =
            |n: f64| RenderError::InvalidOption { name: "levels", reason: format!("{n} levels is more than 10000") };
        match self {
            Self::Count(n) => {
                if *n > 10_000 {
                    return Err(too_many(*n as f64));
                }
                if lo >= hi {
                    return Ok(Vec::new());
                }
                Ok((1..=*n).map(|k| lo + (hi - lo) * k as f64 / (*n + 1) as f64).collect())
            }
            Self::Given(v) => Ok(v.iter().copied().filter(|x| x.is_finite()).collect()),
            Self::Step(step) => {
                if !(step.is_finite() && *step > 0.0) {
                    return Err(RenderError::InvalidOption {
                        name: "levels",
                        reason: format!("step {step} is not finite and positive"),
                    });
                }
                if lo > hi {
                    return Ok(Vec::new());
                }
                let (k0, k1) = ((lo / step).floor(), (hi / step).ceil());
                if !(k1 - k0 <= 10_000.0) {
                    return Err(too_many(k1 - k0));
                }
                Ok((k0 as i64..=k1 as i64).map(|k| k as f64 * step).filter(|&l| l > lo && l < hi).collect())
            }
        }
    }
}

/// The isoline segments of `field` (one value per vertex) at `levels`. A
/// vertex counts as above a level when its value is at least the level, so
/// each triangle a level crosses gives exactly one segment; triangles with
/// a non-finite value give none. O(F x levels).
///
/// # Errors
/// `RenderError::Length` when `field` does not have one value per vertex;
/// the errors of [`Levels::values`].
pub fn isolines(mesh: &TriMesh, field: &[f64], levels: &Levels) -> Result<Vec<[DVec3; 2]>> {
    if field.len() != mesh.vertex_count() {
        return Err(RenderError::Length {
            what: "scalar field",
            got: field.len(),
            expected: mesh.vertex_count(),
            per: "vertices",
        });
    }
    let levels = levels.values(field)?;
    let p = mesh.positions();
    let mut out = Vec::new();
    for tri in mesh.faces() {
        let v = tri.map(|v| v as usize);
        let f = v.map(|i| field[i]);
        if !f.iter().all(|x| x.is_finite()) {
            continue;
        }
        let (lo, hi) = (f[0].min(f[1]).min(f[2]), f[0].max(f[1]).max(f[2]));
        for &l in &levels {
            if l <= lo || l > hi {
                continue;
            }
            let mut ends = [DVec3::ZERO; 2];
            let mut n = 0;
            for e in 0..3 {
                let (i, j) = (e, (e + 1) % 3);
                if (f[i] >= l) != (f[j] >= l) {
                    let t = (l - f[i]) / (f[j] - f[i]);
                    if n < 2 {
                        ends[n] = p[v[i]].lerp(p[v[j]], t);
                    }
                    n += 1;
                }
            }
            if n == 2 {
                out.push(ends);
            }
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_are_evenly_spaced_inside_the_range() {
        let f = [0.0, 1.0, f64::NAN, 4.0];
        assert_eq!(Levels::Count(3).values(&f).unwrap(), vec![1.0, 2.0, 3.0]);
        assert_eq!(Levels::Step(1.5).values(&f).unwrap(), vec![1.5, 3.0]);
        assert_eq!(Levels::Given(vec![f64::NAN, 2.0]).values(&f).unwrap(), vec![2.0]);
        assert!(Levels::Step(0.0).values(&f).is_err());
        assert!(Levels::Step(1e-9).values(&f).is_err());
        assert!(Levels::Count(3).values(&[1.0, 1.0]).unwrap().is_empty());
    }

    #[test]
    fn isolines_of_a_linear_field_on_a_plane_are_straight_and_evenly_spaced() {
        // f = 2x + y on the unit square: level l is the line 2x + y = l.
        let m = mesh_kernel::shapes::grid(1.0, 1.0, 9, 7).unwrap();
        let f: Vec<f64> = m.positions().iter().map(|p| 2.0 * p.x + p.y).collect();
        let levels = Levels::Count(5);
        let values = levels.values(&f).unwrap();
        let segs = isolines(&m, &f, &levels).unwrap();
        assert!(!segs.is_empty());
        let mut per_level = vec![0.0; values.len()];
        for s in &segs {
            // Each end lies on a level line (straight: on the same line).
            let l0 = 2.0 * s[0].x + s[0].y;
            let l1 = 2.0 * s[1].x + s[1].y;
            assert!((l0 - l1).abs() < 1e-12, "{l0} {l1}");
            let k = values.iter().position(|v| (v - l0).abs() < 1e-9).expect("a segment off every level");
            per_level[k] += s[0].distance(s[1]);
            assert_eq!(s[0].z, 0.0);
        }
        // Evenly spaced: consecutive levels are (max - min) / 6 apart,
        // i.e. 3 / 6 / sqrt(5) apart as lines in the plane.
        let spacing: Vec<f64> = values.windows(2).map(|w| (w[1] - w[0]) / 5f64.sqrt()).collect();
        assert!(spacing.iter().all(|s| (s - 0.5 / 5f64.sqrt()).abs() < 1e-12), "{spacing:?}");
        // Each level's total length is the length of its line inside the square.
        for (k, &l) in values.iter().enumerate() {
            let (xa, xb) = (((l - 1.0) / 2.0).max(0.0), (l / 2.0).min(1.0));
            let expected = (xb - xa) * 5f64.sqrt();
            assert!((per_level[k] - expected).abs() < 1e-9, "level {l}: {} vs {expected}", per_level[k]);
        }
    }

    #[test]
    fn wrong_length_and_non_finite_values() {
        let m = mesh_kernel::shapes::grid(1.0, 1.0, 2, 2).unwrap();
        assert!(isolines(&m, &[0.0], &Levels::Count(1)).is_err());
        let mut f: Vec<f64> = m.positions().iter().map(|p| p.x).collect();
        f[4] = f64::INFINITY; // the centre: every triangle touches it
        let segs = isolines(&m, &f, &Levels::Given(vec![0.25])).unwrap();
        assert!(segs.iter().all(|s| s[0].is_finite() && s[1].is_finite()));
    }
}
