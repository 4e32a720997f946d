//! Seams: the input edges on the boundary of some chart (the surface's
//! boundary, the borders between charts, and the cuts inside a chart),
//! split into curves between corner vertices, and sampled once in 3D so
//! that every chart along a curve gets the same points.

use std::collections::HashMap;

use glam::DVec3;
use mesh_kernel::TriMesh;
use mesh_param::Atlas;

use crate::error::{RemeshError, Result};

/// An input edge by its vertices, smaller first.
pub(crate) type EdgeKey = (u32, u32);

/// The seam graph, its curves and their samples.
#[derive(Debug, Clone)]
pub(crate) struct Seams {
    /// Output index of the input vertices that are output vertices (corners,
    /// and samples falling on a vertex).
    pub vertex_out: HashMap<u32, u32>,
    /// Samples strictly inside each seam edge: parameter from the smaller
    /// vertex to the larger, increasing, and output index.
    pub edge_samples: HashMap<EdgeKey, Vec<(f64, u32)>>,
    /// Positions of the output vertices made so far (the samples).
    pub positions: Vec<DVec3>,
    /// Number of curves.
    pub curves: usize,
}

/// One chart's boundary loop, by its chart vertices in order.
pub(crate) fn chart_loops(atlas: &Atlas) -> Result<Vec<Vec<u32>>> {
    let mut out = Vec::with_capacity(atlas.charts.len());
    for (c, chart) in atlas.charts.iter().enumerate() {
        let loops = chart
            .mesh
            .connectivity()
            .boundary_loops()
            .map_err(|e| RemeshError::ChartFailed { chart: c, reason: format!("the chart is not a manifold: {e}") })?;
        if loops.len() != 1 {
            return Err(RemeshError::ChartFailed {
                chart: c,
                reason: format!("the chart has {} boundary loops, a disk has 1", loops.len()),
            });
        }
        out.push(loops[0].vertices.iter().map(|v| v.0).collect());
    }
    Ok(out)
}

fn key(a: u32, b: u32) -> EdgeKey {
    (a.min(b), a.max(b))
}

/// Builds the seam graph of `atlas` over `mesh`, splits it into curves and
/// samples each curve into segments of length near `h` (at least one per
/// curve, more where a chart's loop would have fewer than 3 points).
/// `max_samples` bounds the samples. O(seam edges + samples).
pub(crate) fn sample_seams(
    mesh: &TriMesh,
    atlas: &Atlas,
    loops: &[Vec<u32>],
    h: f64,
    max_samples: usize,
) -> Result<Seams> {
    let p = mesh.positions();
    // Seam edges and the charts along each.
    let mut edges: HashMap<EdgeKey, usize> = HashMap::new();
    let mut sides: Vec<Vec<u32>> = Vec::new();
    let mut list: Vec<EdgeKey> = Vec::new();
    for (c, lp) in loops.iter().enumerate() {
        let verts = &atlas.charts[c].vertices;
        for i in 0..lp.len() {
            let (a, b) = (verts[lp[i] as usize].0, verts[lp[(i + 1) % lp.len()] as usize].0);
            let k = key(a, b);
            let e = *edges.entry(k).or_insert_with(|| {
                list.push(k);
                sides.push(Vec::new());
                list.len() - 1
            });
            sides[e].push(c as u32);
        }
    }
    for s in &mut sides {
        s.sort_unstable();
    }
    let mut incident: HashMap<u32, Vec<usize>> = HashMap::new();
    for (e, &(a, b)) in list.iter().enumerate() {
        incident.entry(a).or_default().push(e);
        incident.entry(b).or_default().push(e);
    }
    let mut corner: HashMap<u32, bool> =
        incident.iter().map(|(&v, es)| (v, es.len() != 2 || sides[es[0]] != sides[es[1]])).collect();
    // Curves: from each corner along each unvisited edge to the next corner;
    // then the cycles left, from their smallest vertex.
    let mut visited = vec![false; list.len()];
    let mut curves: Vec<Vec<u32>> = Vec::new();
    let trace = |start: u32, e0: usize, visited: &mut Vec<bool>, corner: &HashMap<u32, bool>| {
        let mut curve = vec![start];
        let (mut v, mut e) = (start, e0);
        loop {
            visited[e] = true;
            let (a, b) = list[e];
            v = if a == v { b } else { a };
            curve.push(v);
            if corner[&v] {
                return curve;
            }
            match incident[&v].iter().find(|&&f| !visited[f]) {
                Some(&f) => e = f,
                None => return curve,
            }
        }
    };
    let mut starts: Vec<u32> = corner.iter().filter(|(_, &c)| c).map(|(&v, _)| v).collect();
    starts.sort_unstable();
    for &v in &starts {
        for &e in &incident[&v] {
            if !visited[e] {
                curves.push(trace(v, e, &mut visited, &corner));
            }
        }
    }
    for e in 0..list.len() {
        if !visited[e] {
            let v = list[e].0;
            corner.insert(v, true);
            curves.push(trace(v, e, &mut visited, &corner));
        }
    }
    // Segments per curve: near the length over h, at least 1.
    let lengths: Vec<Vec<f64>> =
        curves.iter().map(|c| c.windows(2).map(|w| p[w[0] as usize].distance(p[w[1] as usize])).collect()).collect();
    let mut segments: Vec<usize> = Vec::with_capacity(curves.len());
    let mut total = 0usize;
    for l in &lengths {
        let n = (l.iter().sum::<f64>() / h).round();
        let n = if n.is_finite() && n >= 1.0 { n.min(1e15) as usize } else { 1 };
        total = total.saturating_add(n);
        if total > max_samples {
            return Err(RemeshError::TooManyVertices { edge_length: h, estimated: total, limit: max_samples });
        }
        segments.push(n);
    }
    // The curve and position of each seam edge, to count a loop's points.
    let mut edge_curve = vec![(0usize, 0usize); list.len()];
    for (c, curve) in curves.iter().enumerate() {
        for (i, w) in curve.windows(2).enumerate() {
            edge_curve[edges[&key(w[0], w[1])]] = (c, i);
        }
    }
    // A closed curve needs 3 segments (with 2, both would join the same two
    // points); two one-segment curves between the same corners would be one
    // output edge with four faces, so all but one get 2 segments.
    let mut single: HashMap<EdgeKey, usize> = HashMap::new();
    for (c, curve) in curves.iter().enumerate() {
        let (a, b) = (curve[0], curve[curve.len() - 1]);
        if a == b {
            segments[c] = segments[c].max(3);
        } else if segments[c] == 1 && single.insert(key(a, b), c).is_some() {
            segments[c] = 2;
        }
    }
    loop {
        let mut bumped = false;
        for (c, lp) in loops.iter().enumerate() {
            let verts = &atlas.charts[c].vertices;
            let mut count = 0;
            let mut on_loop = Vec::new();
            for i in 0..lp.len() {
                let (a, b) = (verts[lp[i] as usize].0, verts[lp[(i + 1) % lp.len()] as usize].0);
                let (k, pos) = edge_curve[edges[&key(a, b)]];
                let forward = curves[k][pos] == a;
                let last = curves[k].len() - 2;
                if (forward && pos == 0) || (!forward && pos == last) {
                    count += segments[k];
                    on_loop.push(k);
                }
            }
            if count < 3 {
                for k in on_loop {
                    segments[k] += 1;
                }
                bumped = true;
            } else if on_loop.len() == 2 {
                // Two corners: a curve of one segment is the straight chord
                // between them in the chart's plane, on which the other
                // curve's samples lie when that curve is one input edge (a
                // polygon of zero area). Two segments each keep a sample off
                // the chord (found on a one-face chart of a scan).
                for k in on_loop {
                    if segments[k] < 2 {
                        segments[k] = 2;
                        bumped = true;
                    }
                }
            }
        }
        if !bumped {
            break;
        }
    }
    // Samples by arc length.
    let mut seams =
        Seams { vertex_out: HashMap::new(), edge_samples: HashMap::new(), positions: Vec::new(), curves: 0 };
    seams.curves = curves.len();
    let vertex = |v: u32, seams: &mut Seams| {
        let next = seams.positions.len() as u32;
        let id = *seams.vertex_out.entry(v).or_insert(next);
        if id == next {
            seams.positions.push(p[v as usize]);
        }
    };
    for (c, curve) in curves.iter().enumerate() {
        vertex(curve[0], &mut seams);
        vertex(curve[curve.len() - 1], &mut seams);
        let n = segments[c];
        let cum: Vec<f64> = std::iter::once(0.0)
            .chain(lengths[c].iter().scan(0.0, |s, l| {
                *s += l;
                Some(*s)
            }))
            .collect();
        let total = cum[cum.len() - 1];
        let mut j = 0;
        for k in 1..n {
            let s = total * k as f64 / n as f64;
            while j + 1 < lengths[c].len() && cum[j + 1] <= s {
                j += 1;
            }
            let l = lengths[c][j];
            let t = if l > 0.0 { ((s - cum[j]) / l).clamp(0.0, 1.0) } else { k as f64 / n as f64 };
            let (a, b) = (curve[j], curve[j + 1]);
            if l > 0.0 && t <= 1e-9 {
                vertex(a, &mut seams);
            } else if l > 0.0 && t >= 1.0 - 1e-9 {
                vertex(b, &mut seams);
            } else {
                let id = seams.positions.len() as u32;
                seams.positions.push(p[a as usize].lerp(p[b as usize], t));
                let canonical = if a < b { t } else { 1.0 - t };
                seams.edge_samples.entry(key(a, b)).or_default().push((canonical, id));
            }
        }
    }
    for s in seams.edge_samples.values_mut() {
        s.sort_by(|x, y| x.0.total_cmp(&y.0));
    }
    Ok(seams)
}
