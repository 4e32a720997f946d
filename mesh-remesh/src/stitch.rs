//! Stitching the charts: no output edge may get more than two faces.

use std::collections::{HashMap, HashSet};

use glam::{DVec2, DVec3};
use mesh_param::Chart;

use crate::chart::{ChartTriangle, Lifter};
use crate::error::{RemeshError, Result};

/// A triangle of a chart and the corner its edge starts at.
type Side = (usize, usize);

/// Splits, at its midpoint in the parameter plane, edges inside a chart
/// whose output edge would otherwise have more than two faces, over all
/// charts at once (`triangles[c]` is chart `c`'s):
/// - a chart that reaches around a corner where two others meet can join
///   two seam points that a seam segment already joins (found on the full
///   Stanford dragon);
/// - two charts can both join the same two seam points inside;
/// - a point can see both copies of a pinched vertex.
///
/// The midpoint is lifted onto the input through its chart; its four edges
/// are new, so each split takes both of that edge's faces away for good.
/// Returns the splits done. O(F) per round with hash maps, a round per
/// level of nesting (one or two in practice).
///
/// # Errors
/// [`RemeshError::ChartFailed`] when an edge keeps more than two faces and
/// none of them is inside a chart, or a midpoint lies in no triangle.
pub(crate) fn split_third_faces(
    triangles: &mut [Vec<ChartTriangle>],
    charts: &[Chart],
    positions: &mut Vec<DVec3>,
) -> Result<usize> {
    let key = |a: u32, b: u32| (a.min(b), a.max(b));
    let mut lifters: HashMap<usize, Lifter<'_>> = HashMap::new();
    let mut splits = 0;
    let total: usize = triangles.iter().map(Vec::len).sum();
    for _ in 0..=total {
        let mut faces: HashMap<(u32, u32), usize> = HashMap::new();
        for (t, _) in triangles.iter().flatten() {
            for k in 0..3 {
                *faces.entry(key(t[k], t[(k + 1) % 3])).or_default() += 1;
            }
        }
        let mut excess: HashMap<(u32, u32), usize> =
            faces.into_iter().filter(|&(_, n)| n > 2).map(|(e, n)| (e, n - 2)).collect();
        if excess.is_empty() {
            return Ok(splits);
        }
        // The edges inside a chart that carry an excess: two triangles of the
        // chart along the same parameter segment.
        // (chart, (face, corner) on one side, (face, corner) on the other).
        let mut chosen: Vec<(usize, Side, Side)> = Vec::new();
        for (c, tris) in triangles.iter().enumerate() {
            let mut inside: HashMap<[u64; 4], (usize, usize)> = HashMap::new();
            let mut used = HashSet::new();
            for (f, (t, uv)) in tris.iter().enumerate() {
                for k in 0..3 {
                    let e = key(t[k], t[(k + 1) % 3]);
                    if excess.get(&e).is_none_or(|&n| n == 0) {
                        continue;
                    }
                    let (p, q) = (uv[k], uv[(k + 1) % 3]);
                    let (p, q) = if (p.x, p.y) < (q.x, q.y) { (p, q) } else { (q, p) };
                    let bits = [p.x, p.y, q.x, q.y].map(f64::to_bits);
                    match inside.remove(&bits) {
                        Some((g, l)) if used.insert(f) && used.insert(g) => {
                            if let Some(n) = excess.get_mut(&e) {
                                *n = n.saturating_sub(2);
                            }
                            chosen.push((c, (g, l), (f, k)));
                        }
                        Some(_) => {}
                        None => {
                            inside.insert(bits, (f, k));
                        }
                    }
                }
            }
        }
        if chosen.is_empty() {
            let (e, n) = excess.iter().next().map_or(((0, 0), 0), |(e, n)| (*e, *n));
            let chart = triangles.iter().position(|t| t.iter().any(|(t, _)| t.contains(&e.0) && t.contains(&e.1)));
            return Err(RemeshError::ChartFailed {
                chart: chart.unwrap_or(0),
                reason: format!(
                    "the output edge {e:?} gets {} faces after stitching and none of them lies inside a chart",
                    n + 2
                ),
            });
        }
        for (c, (f, k), (g, l)) in chosen {
            let lifter = lifters.entry(c).or_insert_with(|| Lifter::new(&charts[c]));
            let tris = &mut triangles[c];
            let ((t, uv), (u, ug)) = (tris[f], tris[g]);
            let m: DVec2 = 0.5 * (uv[k] + uv[(k + 1) % 3]);
            let p = lifter.lift(m).ok_or_else(|| RemeshError::ChartFailed {
                chart: c,
                reason: format!("the parameter point {m} lies in no triangle of the chart"),
            })?;
            let id = positions.len() as u32;
            positions.push(p);
            // (a, b, c) -> (a, m, c), (m, b, c), and the same on the other side.
            for (f, k, t, uv) in [(f, k, t, uv), (g, l, u, ug)] {
                let (a, b, c) = (k, (k + 1) % 3, (k + 2) % 3);
                tris[f] = ([t[a], id, t[c]], [uv[a], m, uv[c]]);
                tris.push(([id, t[b], t[c]], [m, uv[b], uv[c]]));
            }
            splits += 1;
        }
    }
    Err(RemeshError::ChartFailed { chart: 0, reason: "splitting edges with a third face did not finish".into() })
}

/// Refuses a stitched mesh in which an edge has more than two faces or two
/// faces have the same vertices: the charts on both sides of a seam made
/// the same triangle (seams with too few samples for their charts, from an
/// edge length near the size of the surface, or a map that shortens the
/// seam direction a lot). O(F) with a hash map.
pub(crate) fn check_stitching(faces: &[[u32; 3]], face_chart: &[u32], h: f64) -> Result<()> {
    let mut edges: std::collections::HashMap<(u32, u32), u8> = std::collections::HashMap::new();
    let mut sets = std::collections::HashSet::new();
    for (f, t) in faces.iter().enumerate() {
        let mut sorted = *t;
        sorted.sort_unstable();
        let fail = |what: &str| RemeshError::ChartFailed {
            chart: face_chart[f] as usize,
            reason: format!(
                "{what} after stitching: the charts on both sides of a seam made the same triangles \
                 (the edge length {h} may be too long for this surface)"
            ),
        };
        if !sets.insert(sorted) {
            return Err(fail("two faces with the same vertices"));
        }
        for k in 0..3 {
            let (a, b) = (t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3]));
            let c = edges.entry((a, b)).or_insert(0);
            *c += 1;
            if *c > 2 {
                return Err(fail("an edge with more than two faces"));
            }
        }
    }
    Ok(())
}
