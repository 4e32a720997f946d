//! Welding coincident vertices, exactly or within a tolerance.

use glam::DVec3;

use crate::error::{MeshError, Result};
use crate::union_find::UnionFind;

/// Merges vertices within `tolerance` of each other (transitively), keeping the
/// position of the lowest-indexed vertex of each cluster, and rewrites `faces`.
/// Returns the welded positions, faces (which may now repeat a vertex) and the
/// number of merged vertices. Vertex order is kept.
///
/// Exact welding (`tolerance == 0`) sorts positions; with a tolerance, points
/// are sorted into cells of that size and each is compared with the 27
/// neighbouring cells. Cost O(n log n). Non-finite or negative tolerances,
/// and tolerances larger than the bounding-box diagonal (which would merge
/// every vertex into one), are an error.
pub fn weld_vertices(
    positions: &[DVec3],
    faces: &[[u32; 3]],
    tolerance: f64,
) -> Result<(Vec<DVec3>, Vec<[u32; 3]>, usize)> {
    if !(tolerance >= 0.0 && tolerance.is_finite()) {
        return Err(MeshError::InvalidOption { name: "weld_tolerance", reason: format!("{tolerance} is not >= 0") });
    }
    let diagonal = crate::geometry::Aabb::of(positions).map_or(0.0, |b| b.diagonal());
    if diagonal > 0.0 && tolerance > diagonal {
        return Err(MeshError::InvalidOption {
            name: "weld_tolerance",
            reason: format!(
                "{tolerance} is larger than the bounding-box diagonal {diagonal:.6e}: every vertex would merge into one"
            ),
        });
    }
    let n = positions.len();
    let mut sets = UnionFind::new(n);
    if tolerance == 0.0 {
        // Sort (bit pattern, index) pairs computed once; -0.0 and 0.0 weld.
        let key = |p: DVec3| [p.x, p.y, p.z].map(|c| if c == 0.0 { 0u64 } else { c.to_bits() });
        let mut keyed: Vec<([u64; 3], u32)> = positions.iter().enumerate().map(|(i, &p)| (key(p), i as u32)).collect();
        keyed.sort_unstable();
        for w in keyed.windows(2) {
            if w[0].0 == w[1].0 {
                sets.union(w[0].1, w[1].1);
            }
        }
    } else {
        let cell = |p: DVec3| {
            let c = (p / tolerance).floor();
            [c.x, c.y, c.z].map(|x| x.clamp(i64::MIN as f64, i64::MAX as f64) as i64)
        };
        let mut order: Vec<([i64; 3], u32)> = (0..n).map(|i| (cell(positions[i]), i as u32)).collect();
        order.sort_unstable();
        let tol2 = tolerance * tolerance;
        for &(c, i) in &order {
            for dx in -1..=1i64 {
                for dy in -1..=1i64 {
                    for dz in -1..=1i64 {
                        let nc = [c[0].saturating_add(dx), c[1].saturating_add(dy), c[2].saturating_add(dz)];
                        let lo = order.partition_point(|(k, _)| *k < nc);
                        for &(k, j) in &order[lo..] {
                            if k != nc {
                                break;
                            }
                            if j < i && positions[i as usize].distance_squared(positions[j as usize]) <= tol2 {
                                sets.union(i, j);
                            }
                        }
                    }
                }
            }
        }
    }
    // Each cluster is named by its lowest index.
    let mut remap = vec![0u32; n];
    let mut welded = Vec::with_capacity(n);
    for i in 0..n {
        let root = sets.find(i as u32) as usize;
        if root == i {
            remap[i] = welded.len() as u32;
            welded.push(positions[i]);
        } else {
            remap[i] = remap[root];
        }
    }
    let merged = n - welded.len();
    let faces = faces.iter().map(|f| f.map(|v| remap[v as usize])).collect();
    Ok((welded, faces, merged))
}
