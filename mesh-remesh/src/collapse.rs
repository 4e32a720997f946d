//! Collapses of short edges onto one of their ends: the seams' corners can
//! be closer than the edge length (a short seam curve gets one short
//! segment), and the triangles on such a segment are thin in both charts.
//! A collapse keeps one end, which lies on the input, so no vertex leaves
//! the surface.

use std::collections::HashSet;

use glam::DVec3;
use mesh_kernel::geometry;

/// Collapses edges shorter than `min_length`, shortest first (one pass),
/// each onto the end that keeps the surface's boundary and raises the
/// smallest angle among the faces it changes, when: the link condition
/// holds (the ends share exactly the neighbours opposite the edge, so the
/// topology is kept), an interior edge does not join two boundary vertices,
/// no face turns by more than 30 degrees, and no new edge is longer than
/// `max_length`. Removes the collapsed vertices and faces; returns the new
/// positions, faces, which input faces were kept (the output faces are
/// those, in order) and the number of collapses. O((V + F) log F).
pub(crate) fn collapse_short_edges(
    positions: Vec<DVec3>,
    faces: Vec<[u32; 3]>,
    min_length: f64,
    max_length: f64,
) -> (Vec<DVec3>, Vec<[u32; 3]>, Vec<bool>, usize) {
    let n = positions.len();
    let mut faces = faces;
    let mut alive = vec![true; faces.len()];
    let mut vf: Vec<Vec<u32>> = vec![Vec::new(); n];
    for (f, t) in faces.iter().enumerate() {
        for &v in t {
            vf[v as usize].push(f as u32);
        }
    }
    let p = |v: u32| positions[v as usize];
    let mut edges: Vec<(f64, u32, u32)> = faces
        .iter()
        .flat_map(|t| (0..3).map(move |k| (t[k], t[(k + 1) % 3])))
        .filter(|(a, b)| a < b)
        .map(|(a, b)| (p(a).distance(p(b)), a, b))
        .filter(|e| e.0 < min_length)
        .collect();
    edges.sort_by(|x, y| x.0.total_cmp(&y.0));
    edges.dedup_by(|x, y| x.1 == y.1 && x.2 == y.2);
    let mut dead = vec![false; n];
    let mut collapses = 0;
    let neighbours = |v: u32, vf: &Vec<Vec<u32>>, faces: &Vec<[u32; 3]>| -> Vec<(u32, usize)> {
        let mut count: Vec<(u32, usize)> = Vec::new();
        for &f in &vf[v as usize] {
            for w in faces[f as usize] {
                if w != v {
                    match count.iter_mut().find(|(x, _)| *x == w) {
                        Some(c) => c.1 += 1,
                        None => count.push((w, 1)),
                    }
                }
            }
        }
        count
    };
    let min_angle = |t: [u32; 3]| geometry::triangle_angles(t.map(p)).into_iter().fold(f64::INFINITY, f64::min);
    let cos30 = 30f64.to_radians().cos();
    for &(_, a, b) in &edges {
        if dead[a as usize] || dead[b as usize] {
            continue;
        }
        let shared: Vec<u32> = vf[a as usize].iter().copied().filter(|&f| faces[f as usize].contains(&b)).collect();
        if shared.is_empty() || shared.len() > 2 {
            continue;
        }
        let (na, nb) = (neighbours(a, &vf, &faces), neighbours(b, &vf, &faces));
        let boundary = |nbrs: &[(u32, usize)]| nbrs.iter().any(|&(_, c)| c == 1);
        let (ba, bb) = (boundary(&na), boundary(&nb));
        if shared.len() == 2 && ba && bb {
            continue;
        }
        // Link condition.
        let opposite: HashSet<u32> =
            shared.iter().flat_map(|&f| faces[f as usize]).filter(|&v| v != a && v != b).collect();
        let common: HashSet<u32> = na.iter().map(|&(v, _)| v).filter(|v| nb.iter().any(|&(w, _)| w == *v)).collect();
        if common != opposite {
            continue;
        }
        // Valences after the collapse: an opposite vertex loses one
        // neighbour, the kept vertex has the union; at least 3 inside and
        // 2 on the boundary (a tetrahedron, or a lone triangle, stays).
        let least = |_v: u32, nbrs: &[(u32, usize)]| if boundary(nbrs) { 2 } else { 3 };
        let merged = na.len() + nb.len() - 2 - common.len();
        if merged < least(a, &na).max(least(b, &nb))
            || opposite.iter().any(|&c| {
                let nc = neighbours(c, &vf, &faces);
                nc.len() - 1 < least(c, &nc)
            })
        {
            continue;
        }
        let mut orders = Vec::new();
        if shared.len() == 1 || !bb {
            orders.push((b, a)); // remove b, keep a
        }
        if shared.len() == 1 || !ba {
            orders.push((a, b));
        }
        let mut best: Option<(f64, u32, u32)> = None;
        for (r, k) in orders {
            let changed: Vec<u32> = vf[r as usize].iter().copied().filter(|f| !shared.contains(f)).collect();
            let before = vf[r as usize].iter().map(|&f| min_angle(faces[f as usize])).fold(f64::INFINITY, f64::min);
            let mut after = f64::INFINITY;
            let mut ok = true;
            for &f in &changed {
                let old = faces[f as usize];
                let new = old.map(|v| if v == r { k } else { v });
                let (n0, n1) = (geometry::double_area_vector(old.map(p)), geometry::double_area_vector(new.map(p)));
                if n0.dot(n1) <= cos30 * n0.length() * n1.length() {
                    ok = false;
                    break;
                }
                if new.iter().any(|&v| v != k && p(v).distance(p(k)) > max_length) {
                    ok = false;
                    break;
                }
                after = after.min(min_angle(new));
            }
            if ok && after > before && best.is_none_or(|(x, _, _)| after > x) {
                best = Some((after, r, k));
            }
        }
        let Some((_, r, k)) = best else { continue };
        for &f in &shared {
            alive[f as usize] = false;
            for v in faces[f as usize] {
                vf[v as usize].retain(|&g| g != f);
            }
        }
        let moved = std::mem::take(&mut vf[r as usize]);
        for f in moved {
            for v in faces[f as usize].iter_mut() {
                if *v == r {
                    *v = k;
                }
            }
            vf[k as usize].push(f);
        }
        dead[r as usize] = true;
        collapses += 1;
    }
    // Compact.
    let mut index = vec![u32::MAX; n];
    let mut out_p = Vec::with_capacity(n);
    for v in 0..n {
        if !dead[v] {
            index[v] = out_p.len() as u32;
            out_p.push(positions[v]);
        }
    }
    let out_f = faces.iter().zip(&alive).filter(|(_, &a)| a).map(|(t, _)| t.map(|v| index[v as usize])).collect();
    (out_p, out_f, alive, collapses)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn collapses_a_short_edge_and_keeps_the_topology() {
        // A square fan around a centre, with one vertex very close to the centre.
        let mut p = vec![DVec3::ZERO, DVec3::new(0.02, 0.0, 0.0)];
        let ring: Vec<DVec3> =
            (0..8).map(|k| k as f64 * std::f64::consts::FRAC_PI_4).map(|t| DVec3::new(t.cos(), t.sin(), 0.0)).collect();
        p.extend(&ring);
        // Triangulate: the short edge 0-1, vertex 1 toward ring vertex 2 (angle 0).
        let mut f = Vec::new();
        for k in 0..8u32 {
            let (r0, r1) = (2 + k, 2 + (k + 1) % 8);
            if k == 0 || k == 7 {
                // Vertex 1 sits between the centre and ring vertex 2 (k = 0 side).
                continue;
            }
            f.push([0, r0, r1]);
        }
        f.push([0, 1, 3]);
        f.push([1, 2, 3]);
        f.push([0, 9, 1]);
        f.push([1, 9, 2]);
        let mesh = mesh_kernel::TriMesh::new(p.clone(), f.clone()).unwrap();
        let chi = mesh.connectivity().euler_characteristic();
        let (q, g, kept, count) = collapse_short_edges(p, f, 0.1, 2.0);
        assert_eq!(count, 1);
        assert_eq!(kept.iter().filter(|&&k| !k).count(), 2);
        assert_eq!(q.len(), 9);
        let out = mesh_kernel::TriMesh::new(q, g).unwrap();
        assert_eq!(out.connectivity().euler_characteristic(), chi);
        assert_eq!(out.connectivity().boundary_loop_count(), Some(1));
        assert!(out.connectivity().is_manifold());
    }
}
