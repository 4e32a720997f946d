//! Subdivision masks: where the odd vertex of an edge goes and how even
//! vertices move, for each [`crate::Scheme`], as sparse rows over the
//! vertices of K^j.
//!
//! All masks are affine (weights sum to one), so every scheme commutes with
//! rigid motions and reproduces constants.

use std::f64::consts::TAU;

use crate::scheme::Scheme;
use crate::topology::{Kind, Topology};

/// Loop's (1987) even-vertex weight for an interior vertex of valence `n`:
/// `beta = (5/8 - (3/8 + cos(2 pi / n) / 4)^2) / n`. Cost O(1).
pub fn loop_beta(n: usize) -> f64 {
    const TABLE: usize = 16;
    static BETA: std::sync::OnceLock<[f64; TABLE]> = std::sync::OnceLock::new();
    if n < TABLE {
        return BETA.get_or_init(|| std::array::from_fn(beta_formula))[n];
    }
    beta_formula(n)
}

fn beta_formula(n: usize) -> f64 {
    let n = n.max(1) as f64;
    let c = 3.0 / 8.0 + 0.25 * (TAU / n).cos();
    (5.0 / 8.0 - c * c) / n
}

/// The modified-butterfly weights `s_0..s_{k-1}` of the neighbours of an
/// extraordinary interior vertex of valence `k`, in counter-clockwise order
/// starting at the other end of the edge (Zorin, Schroeder, Sweldens 1996):
/// `k = 3`: 5/12, -1/12, -1/12; `k = 4`: 3/8, 0, -1/8, 0; `k >= 5`:
/// `(1/4 + cos(2 pi j / k) + cos(4 pi j / k) / 2) / k`. The vertex itself
/// weighs 3/4. `None` for `k < 3`, where no mask exists. Cost O(k).
pub fn butterfly_vertex_weights(k: usize) -> Option<Vec<f64>> {
    match k {
        0..=2 => None,
        3 => Some(vec![5.0 / 12.0, -1.0 / 12.0, -1.0 / 12.0]),
        4 => Some(vec![3.0 / 8.0, 0.0, -1.0 / 8.0, 0.0]),
        _ => Some(
            (0..k)
                .map(|j| {
                    let t = TAU * j as f64 / k as f64;
                    (0.25 + t.cos() + 0.5 * (2.0 * t).cos()) / k as f64
                })
                .collect(),
        ),
    }
}

/// The edge of K^j between `a` and `b`, if any. `hint` is tried first (the
/// odd vertex index, which is the edge index for hierarchies built by
/// subdivision). Cost O(valence).
pub(crate) fn find_edge(topo: &Topology, a: u32, b: u32, hint: usize) -> Option<u32> {
    if topo.edges().get(hint) == Some(&[a.min(b), a.max(b)]) {
        return Some(hint as u32);
    }
    topo.find_edge(a, b)
}

/// Neighbours of `v` with the number of faces on the connecting edge (1 on
/// the boundary, 2 inside), into `out`.
pub(crate) fn ring_with_face_counts(topo: &Topology, v: u32, out: &mut Vec<(u32, u8)>) {
    out.clear();
    let out_h = topo.out(v);
    for &h in out_h {
        out.push((topo.dest(h), if topo.twin(h).is_some() { 2 } else { 1 }));
    }
    if topo.kind(v) == Kind::Boundary {
        if let Some(&h) = out_h.last() {
            out.push((topo.opposite(h), 1));
        }
    }
}

/// Scratch buffers reused across odd vertices.
#[derive(Default)]
pub(crate) struct Scratch {
    ring_a: Vec<u32>,
    ring_b: Vec<u32>,
}

/// The odd-vertex mask of `scheme` for the edge (`a`, `b`) with the vertices
/// `opposite` to it (one on the boundary), appended to `row` as (vertex, weight).
pub(crate) fn odd_mask(
    topo: &Topology,
    scheme: Scheme,
    a: u32,
    b: u32,
    opposite: &[u32],
    scratch: &mut Scratch,
    row: &mut Vec<(u32, f64)>,
) {
    let boundary_edge = opposite.len() == 1;
    match scheme {
        Scheme::Midpoint => midpoint(a, b, row),
        Scheme::Loop => {
            if boundary_edge {
                midpoint(a, b, row);
            } else {
                row.extend([(a, 3.0 / 8.0), (b, 3.0 / 8.0)]);
                row.extend(opposite.iter().map(|&c| (c, 1.0 / 8.0)));
            }
        }
        Scheme::Butterfly => butterfly(topo, a, b, opposite, boundary_edge, scratch, row),
    }
}

fn midpoint(a: u32, b: u32, row: &mut Vec<(u32, f64)>) {
    row.extend([(a, 0.5), (b, 0.5)]);
}

fn is_interior(topo: &Topology, v: u32) -> bool {
    topo.kind(v) == Kind::Interior
}

/// Modified butterfly (Zorin, Schroeder, Sweldens 1996).
fn butterfly(
    topo: &Topology,
    a: u32,
    b: u32,
    opposite: &[u32],
    boundary_edge: bool,
    scratch: &mut Scratch,
    row: &mut Vec<(u32, f64)>,
) {
    if boundary_edge {
        // The 4-point rule along the boundary curve.
        let (pa, pb) = (boundary_neighbor_other_than(topo, a, b), boundary_neighbor_other_than(topo, b, a));
        match (pa, pb) {
            (Some(pa), Some(pb)) => {
                row.extend([(a, 9.0 / 16.0), (b, 9.0 / 16.0), (pa, -1.0 / 16.0), (pb, -1.0 / 16.0)]);
            }
            _ => midpoint(a, b, row),
        }
        return;
    }
    let Scratch { ring_a, ring_b } = scratch;
    let ok_a = is_interior(topo, a) && rotated_ring(topo, a, b, ring_a);
    let ok_b = is_interior(topo, b) && rotated_ring(topo, b, a, ring_b);
    let (ka, kb) = (ring_a.len(), ring_b.len());
    match (ok_a, ok_b) {
        (true, true) if ka == 6 && kb == 6 => {
            // The regular 8-point butterfly.
            row.extend([(a, 0.5), (b, 0.5), (ring_a[1], 0.125), (ring_a[5], 0.125)]);
            row.extend([ring_a[2], ring_a[4], ring_b[2], ring_b[4]].map(|w| (w, -1.0 / 16.0)));
        }
        (true, true) if ka == 6 => vertex_mask(b, ring_b, 1.0, row),
        (true, true) if kb == 6 => vertex_mask(a, ring_a, 1.0, row),
        (true, true) => {
            vertex_mask(a, ring_a, 0.5, row);
            vertex_mask(b, ring_b, 0.5, row);
        }
        (true, false) => vertex_mask(a, ring_a, 1.0, row),
        (false, true) => vertex_mask(b, ring_b, 1.0, row),
        (false, false) => {
            // Interior edge between two boundary vertices: the 4-point
            // diamond mask, a simplification of Zorin et al.'s boundary cases.
            row.extend([(a, 3.0 / 8.0), (b, 3.0 / 8.0)]);
            row.extend(opposite.iter().map(|&c| (c, 1.0 / 8.0)));
        }
    }
}

/// The extraordinary-vertex mask of `v` (ring starting at the other end),
/// scaled by `scale`; the midpoint rule where no mask exists (valence < 3).
fn vertex_mask(v: u32, ring: &[u32], scale: f64, row: &mut Vec<(u32, f64)>) {
    match butterfly_vertex_weights(ring.len()) {
        Some(s) => {
            row.push((v, 0.75 * scale));
            row.extend(ring.iter().zip(s).map(|(&w, s)| (w, s * scale)));
        }
        None => {
            row.push((v, 0.5 * scale));
            if let Some(&w) = ring.first() {
                row.push((w, 0.5 * scale));
            }
        }
    }
}

/// The counter-clockwise ring of interior vertex `v` starting at `start`;
/// `false` if `start` is not in it.
fn rotated_ring(topo: &Topology, v: u32, start: u32, ring: &mut Vec<u32>) -> bool {
    topo.ring_into(v, ring);
    match ring.iter().position(|&w| w == start) {
        Some(p) => {
            ring.rotate_left(p);
            true
        }
        None => false,
    }
}

/// The boundary neighbour of boundary vertex `v` other than `not`.
fn boundary_neighbor_other_than(topo: &Topology, v: u32, not: u32) -> Option<u32> {
    let out = topo.out(v);
    let first = topo.dest(*out.first()?);
    let last = topo.opposite(*out.last()?);
    if first == not {
        Some(last)
    } else if last == not {
        Some(first)
    } else {
        None
    }
}

/// Loop's even rule applied directly to positions `p` of K^j: interior
/// `(1 - n beta) v + beta sum v_k`, boundary `3/4 v + 1/8 (v_prev + v_next)`,
/// isolated vertices unchanged. Cost O(valence).
pub(crate) fn loop_even(topo: &Topology, p: &[glam::DVec3], v: u32) -> glam::DVec3 {
    let out = topo.out(v);
    let pv = p[v as usize];
    match topo.kind(v) {
        Kind::Interior => {
            let beta = loop_beta(out.len());
            let sum: glam::DVec3 = out.iter().map(|&h| p[topo.dest(h) as usize]).sum();
            pv * (1.0 - out.len() as f64 * beta) + sum * beta
        }
        Kind::Boundary => match (out.first(), out.last()) {
            (Some(&first), Some(&last)) => {
                pv * 0.75 + (p[topo.dest(first) as usize] + p[topo.opposite(last) as usize]) * 0.125
            }
            _ => pv,
        },
        Kind::Isolated => pv,
    }
}

/// Loop's even rule written as a lifting step over the new odd vertices
/// (so that it can be inverted exactly):
/// `v' = alpha v + sum_k gamma_k e_k`. For an interior vertex of valence n,
/// `gamma = 8 beta / 5` on each of its n odd neighbours and
/// `alpha = 1 - 8 n beta / 5` (`> 0` for every n), since the odd vertices
/// sum to `3n/8 v + 5/8 sum v_k`; for a boundary vertex `gamma = 1/4` on its
/// two boundary odd neighbours and `alpha = 1/2`. Returns alpha and the
/// weight an interior (`false`) or boundary (`true`) odd neighbour gets.
pub(crate) fn loop_even_lifting(topo: &Topology, v: u32) -> (f64, f64, f64) {
    match topo.kind(v) {
        Kind::Interior => {
            let n = topo.valence(v);
            let beta = loop_beta(n);
            (1.0 - 1.6 * n as f64 * beta, 1.6 * beta, 1.6 * beta)
        }
        Kind::Boundary => (0.5, 0.0, 0.25),
        _ => (1.0, 0.0, 0.0),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn butterfly_vertex_weights_are_affine() {
        for k in 3..20 {
            let s = butterfly_vertex_weights(k).unwrap();
            assert!((0.75 + s.iter().sum::<f64>() - 1.0).abs() < 1e-14, "k = {k}");
        }
        assert!(butterfly_vertex_weights(2).is_none());
    }

    #[test]
    fn loop_beta_known_values() {
        assert!((loop_beta(3) - 3.0 / 16.0).abs() < 1e-15);
        assert!((loop_beta(6) - 1.0 / 16.0).abs() < 1e-15);
        for n in 3..30 {
            let alpha = 1.0 - 1.6 * n as f64 * loop_beta(n);
            assert!(alpha >= 0.099, "n = {n}: alpha = {alpha}");
        }
    }
}
