//! Procedural textures sampled through UV coordinates ([`Texture`]), and
//! per-corner UVs from per-vertex ones ([`corner_uvs`]).

use glam::{DVec2, DVec3};
use mesh_kernel::TriMesh;

use crate::error::{RenderError, Result};

/// A texture on the unit square, repeated outside it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Texture {
    /// `cells` x `cells` squares alternating between two colours.
    Checker {
        /// Squares per side of the unit square.
        cells: u32,
        /// The colour of the squares whose indices sum to an even number.
        even: DVec3,
        /// The other colour.
        odd: DVec3,
    },
    /// `count` stripes along u, dashed along v every `1 / count`
    /// (the chapter's Figure 2.4 "dashed texture").
    Dashes {
        /// Stripes per unit of u.
        count: u32,
        /// Background.
        background: DVec3,
        /// Stripe colour.
        ink: DVec3,
    },
}

impl Texture {
    /// A black-and-white checker of `cells` squares per side.
    pub fn checker(cells: u32) -> Self {
        Self::Checker { cells: cells.max(1), even: DVec3::splat(0.95), odd: DVec3::new(0.15, 0.15, 0.2) }
    }

    /// The colour at `uv` (grey for non-finite coordinates).
    pub fn sample(&self, uv: DVec2) -> DVec3 {
        if !uv.is_finite() {
            return DVec3::splat(0.5);
        }
        match *self {
            Self::Checker { cells, even, odd } => {
                let n = f64::from(cells.max(1));
                let (i, j) = ((uv.x * n).floor() as i64, (uv.y * n).floor() as i64);
                if (i + j).rem_euclid(2) == 0 {
                    even
                } else {
                    odd
                }
            }
            Self::Dashes { count, background, ink } => {
                let n = f64::from(count.max(1));
                let (fu, fv) = ((uv.x * n).rem_euclid(1.0), (uv.y * n).rem_euclid(1.0));
                if fu < 0.3 && fv < 0.7 {
                    ink
                } else {
                    background
                }
            }
        }
    }
}

/// The UVs of each face's three corners, from one UV per vertex.
///
/// # Errors
/// `RenderError::Length` when `uv` does not have one entry per vertex.
pub fn corner_uvs(mesh: &TriMesh, uv: &[DVec2]) -> Result<Vec<[DVec2; 3]>> {
    if uv.len() != mesh.vertex_count() {
        return Err(RenderError::Length { what: "UVs", got: uv.len(), expected: mesh.vertex_count(), per: "vertices" });
    }
    Ok(mesh.faces().iter().map(|f| f.map(|v| uv[v as usize])).collect())
}

/// UVs scaled uniformly into the unit square (the bounding box's longer
/// side becomes 1, its corner goes to the origin); non-finite UVs stay.
pub fn normalize_uvs(uv: &mut [[DVec2; 3]]) {
    let (lo, hi) = uv
        .iter()
        .flatten()
        .filter(|q| q.is_finite())
        .fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(lo, hi), &q| (lo.min(q), hi.max(q)));
    let side = (hi - lo).max_element();
    if !(side.is_finite() && side > 0.0) {
        return;
    }
    for q in uv.iter_mut().flatten() {
        *q = (*q - lo) / side;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checker_alternates() {
        let t = Texture::checker(4);
        let a = t.sample(DVec2::new(0.1, 0.1));
        let b = t.sample(DVec2::new(0.3, 0.1));
        let c = t.sample(DVec2::new(0.3, 0.3));
        assert!(a != b && a == c);
        assert_eq!(t.sample(DVec2::new(-0.1, 0.1)), b); // repeats
        assert_eq!(t.sample(DVec2::NAN), DVec3::splat(0.5));
        let d = Texture::Dashes { count: 2, background: DVec3::ONE, ink: DVec3::ZERO };
        assert_eq!(d.sample(DVec2::new(0.05, 0.1)), DVec3::ZERO);
        assert_eq!(d.sample(DVec2::new(0.4, 0.1)), DVec3::ONE);
    }

    #[test]
    fn corner_uvs_check_length_and_normalize() {
        let m = mesh_kernel::shapes::grid(2.0, 1.0, 2, 1).unwrap();
        assert!(corner_uvs(&m, &[DVec2::ZERO]).is_err());
        let uv: Vec<DVec2> = m.positions().iter().map(|p| DVec2::new(p.x, p.y) * 3.0).collect();
        let mut c = corner_uvs(&m, &uv).unwrap();
        normalize_uvs(&mut c);
        let max = c.iter().flatten().fold(DVec2::NEG_INFINITY, |a, &b| a.max(b));
        let min = c.iter().flatten().fold(DVec2::INFINITY, |a, &b| a.min(b));
        assert!((max.x - 1.0).abs() < 1e-12 && min.x.abs() < 1e-12 && (max.y - 0.5).abs() < 1e-12);
    }
}
