//! Edge flips toward a Delaunay mesh on the surface: an edge whose two
//! opposite angles sum to more than pi is flipped when its two faces are
//! nearly coplanar, which raises the smallest angle (Lawson 1977, on the
//! surface) without moving a vertex off the input.

use std::collections::HashMap;

use glam::DVec3;

use crate::smooth::smallest_angle;

/// A triangle whose smallest angle is under this (radians, 10 degrees) is a
/// sliver for the fold test of [`surface_delaunay_flips`].
const SLIVER: f64 = 10.0 * std::f64::consts::PI / 180.0;

/// Flips edges of the oriented manifold triangles `faces` (in place) while
/// their opposite angles sum to more than pi, the two faces' normals are
/// within `max_fold_degrees` of each other (unless one is a sliver, whose
/// normal is unreliable), the two new faces' normals are too, and the flip leaves both new
/// faces facing the same side as the old ones and creates no edge that is
/// already there (so connectivity, topology and orientation are kept).
/// At most 20 flips per face. Returns the flips done. O(flips + F) with
/// hash maps.
pub(crate) fn surface_delaunay_flips(positions: &[DVec3], faces: &mut [[u32; 3]], max_fold_degrees: f64) -> usize {
    let max_flips = 20 * faces.len();
    // Directed edge (a, b) -> face with a -> b in it.
    let mut owner: HashMap<(u32, u32), u32> = HashMap::with_capacity(3 * faces.len());
    for (f, t) in faces.iter().enumerate() {
        for k in 0..3 {
            owner.insert((t[k], t[(k + 1) % 3]), f as u32);
        }
    }
    let mut stack: Vec<(u32, u32)> =
        faces.iter().flat_map(|t| (0..3).map(move |k| (t[k], t[(k + 1) % 3]))).filter(|(a, b)| a < b).collect();
    let cos_fold = max_fold_degrees.to_radians().cos();
    let p = |v: u32| positions[v as usize];
    let angle = |at: u32, u: u32, v: u32| (p(u) - p(at)).angle_between(p(v) - p(at));
    let mut flips = 0;
    while let Some((a, b)) = stack.pop() {
        if flips >= max_flips {
            break;
        }
        let (Some(&f), Some(&g)) = (owner.get(&(a, b)), owner.get(&(b, a))) else { continue };
        let opposite = |t: [u32; 3], x: u32, y: u32| t.into_iter().find(|&v| v != x && v != y);
        let (Some(c), Some(d)) = (opposite(faces[f as usize], a, b), opposite(faces[g as usize], a, b)) else {
            continue;
        };
        if c == d || owner.contains_key(&(c, d)) || owner.contains_key(&(d, c)) {
            continue;
        }
        // f = (a, b, c), g = (b, a, d).
        let sum = angle(c, a, b) + angle(d, b, a);
        if sum.is_nan() || sum <= std::f64::consts::PI + 1e-9 {
            continue;
        }
        let normal = |x: u32, y: u32, z: u32| (p(y) - p(x)).cross(p(z) - p(x));
        let (nf, ng) = (normal(a, b, c), normal(b, a, d));
        let (lf, lg) = (nf.length(), ng.length());
        // A sliver's normal says little about the surface (a cap can point
        // either way): the fold is judged on the new faces alone, against
        // the pair's area-weighted normal.
        let sliver = [[a, b, c], [b, a, d]].into_iter().any(|t| smallest_angle(t.map(p)) < SLIVER);
        let both = lf > 0.0 && lg > 0.0;
        if lf + lg <= 0.0 || lf.is_nan() || lg.is_nan() || (!sliver && (!both || nf.dot(ng) < cos_fold * lf * lg)) {
            continue;
        }
        // New faces (c, a, d) and (d, b, c).
        let mean = if sliver { nf + ng } else { nf / lf + ng / lg };
        let (n1, n2) = (normal(c, a, d), normal(d, b, c));
        if !(n1.dot(mean) > 0.0 && n2.dot(mean) > 0.0) {
            continue;
        }
        // The new faces must also be no worse a fold than allowed.
        if n1.dot(n2) < cos_fold * n1.length() * n2.length() {
            continue;
        }
        for e in [(a, b), (b, c), (c, a), (b, a), (a, d), (d, b)] {
            owner.remove(&e);
        }
        faces[f as usize] = [c, a, d];
        faces[g as usize] = [d, b, c];
        for (t, id) in [([c, a, d], f), ([d, b, c], g)] {
            for k in 0..3 {
                owner.insert((t[k], t[(k + 1) % 3]), id);
            }
        }
        flips += 1;
        for (x, y) in [(a, c), (c, b), (b, d), (d, a)] {
            stack.push((x.min(y), x.max(y)));
        }
    }
    flips
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flips_a_bad_diagonal_of_a_flat_quad_and_not_a_folded_one() {
        // A flat rhombus split along its long diagonal.
        let p = vec![
            DVec3::new(-2.0, 0.0, 0.0),
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(0.0, -1.0, 0.0),
        ];
        let mut f = vec![[0, 1, 2], [1, 0, 3]];
        assert_eq!(surface_delaunay_flips(&p, &mut f, 20.0), 1);
        assert_eq!(f, vec![[2, 0, 3], [3, 1, 2]]);
        // Flipping again changes nothing (already Delaunay).
        assert_eq!(surface_delaunay_flips(&p, &mut f, 20.0), 0);
        // Folded by 90 degrees along the diagonal: kept.
        let q = vec![
            DVec3::new(-2.0, 0.0, 0.0),
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(0.0, 0.0, -1.0),
        ];
        let mut g = vec![[0, 1, 2], [1, 0, 3]];
        assert_eq!(surface_delaunay_flips(&q, &mut g, 20.0), 0);
    }
}
