//! The unit of length: an answer must not depend on it.
//!
//! Quantities of degree one or two in the coordinates (lengths, areas,
//! curvatures, cotangent weights) are computed scale-free in
//! [`crate::geometry`]. Algorithms whose intermediates reach degree four or
//! more (metric determinants, fits, factorizations of mass-weighted
//! matrices) run on the mesh divided by a power of two near its size,
//! [`normalized`], and scale their results back by the power of the unit
//! their quantity carries (distances `unit`, curvatures `1 / unit`,
//! eigenvalues `1 / unit^2`). Division by a power of two is exact, so
//! normalizing changes no digit; it only moves the mesh away from the ends
//! of the range of `f64`. Meshes whose size already lies in
//! `[2^-100, 2^100]` (about 1e-30 to 1e30) are used as they are.

use std::borrow::Cow;

use crate::geometry::power_of_two_near;
use crate::mesh::TriMesh;

/// Sizes in `[2^-SAFE, 2^SAFE]` are used as they are by [`normalized`].
const SAFE: i32 = 100;

/// A power of two near the half-extent of the mesh's bounding box (its
/// largest side divided by two): `unit <= half-extent < 2 unit`. 1 for a
/// mesh without vertices or with all vertices at one point. O(V) the
/// first time, O(1) after: the box is kept with the mesh
/// ([`crate::cache::Geometry::bounding_box`]).
pub fn length_unit(mesh: &TriMesh) -> f64 {
    let Some(b) = mesh.geometry().bounding_box() else { return 1.0 };
    // Halves first: max - min may overflow, max / 2 - min / 2 cannot.
    let half_extent = (b.max * 0.5 - b.min * 0.5).max_element();
    if half_extent > 0.0 {
        power_of_two_near(half_extent)
    } else {
        1.0
    }
}

/// A power of two near the largest magnitude among the finite `values`
/// (`unit <= largest < 2 unit`), by which they can be divided exactly; 1
/// when none is finite and non-zero. For quantities that are not lengths
/// (masses, matrix entries) that must be brought to a safe range. O(n).
pub fn unit_of(values: impl IntoIterator<Item = f64>) -> f64 {
    let largest = values.into_iter().filter(|x| x.is_finite()).fold(0.0_f64, |m, x| m.max(x.abs()));
    if largest > 0.0 {
        power_of_two_near(largest)
    } else {
        1.0
    }
}

/// The mesh in a unit where nothing over- or underflows, and that unit: the
/// mesh itself and 1 when its [`length_unit`] lies in `[2^-100, 2^100]`,
/// otherwise a copy with every position divided by the unit (exact; the
/// cached connectivity is kept). A quantity of degree `d` in lengths
/// computed on the returned mesh is multiplied by `unit^d` to answer for
/// the input. O(V) for the unit, O(V + F) for a copy.
pub fn normalized(mesh: &TriMesh) -> (Cow<'_, TriMesh>, f64) {
    let unit = length_unit(mesh);
    let safe = 2f64.powi(-SAFE)..=2f64.powi(SAFE);
    if safe.contains(&unit) {
        return (Cow::Borrowed(mesh), 1.0);
    }
    let mut copy = mesh.clone();
    for p in copy.positions_mut() {
        *p /= unit;
    }
    (Cow::Owned(copy), unit)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes;

    #[test]
    fn unit_is_a_power_of_two_near_the_half_extent() {
        let cube = shapes::cube(2).unwrap(); // [-1, 1]^3
        assert_eq!(length_unit(&cube), 1.0);
        let sphere = shapes::icosphere(1).unwrap();
        let h = sphere.positions().iter().map(|p| p.x).fold(0.0, f64::max);
        for s in [1e-300, 3e-150, 0.7, 5e150, 1e300] {
            let m = TriMesh::new(sphere.positions().iter().map(|p| *p * s).collect(), sphere.faces().to_vec()).unwrap();
            let unit = length_unit(&m);
            assert_eq!(unit.log2().fract(), 0.0, "{unit}");
            assert!(unit <= h * s && h * s < 2.0 * unit, "{s}: {unit}");
            let (n, u) = normalized(&m);
            let size = length_unit(&n);
            if (1e-30..1e30).contains(&s) {
                assert!(matches!(n, Cow::Borrowed(_)) && u == 1.0);
            } else {
                assert_eq!((size, u), (length_unit(&sphere), unit));
                assert!(n.positions().iter().zip(m.positions()).all(|(a, b)| *a * u == *b));
            }
        }
    }

    #[test]
    fn unit_of_values_ignores_what_is_not_finite() {
        assert_eq!(unit_of([3.0, -1e-300, f64::NAN]), 2.0);
        assert_eq!(unit_of([-5e300, f64::INFINITY]), power_of_two_near(5e300));
        assert_eq!(unit_of([0.0, f64::NAN]), 1.0);
        assert_eq!(unit_of(std::iter::empty()), 1.0);
    }

    #[test]
    fn meshes_without_extent_have_unit_one() {
        let point = TriMesh::new(vec![glam::DVec3::splat(1e300)], vec![]).unwrap();
        assert_eq!(length_unit(&point), 1.0);
        let empty = TriMesh::new(vec![], vec![]).unwrap();
        assert!(matches!(normalized(&empty), (Cow::Borrowed(_), 1.0)));
    }
}
