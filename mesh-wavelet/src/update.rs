//! Update weights of the lifted wavelet: a local least-squares
//! orthogonalisation under the inner product of eq. 2.36.
//!
//! The lifted wavelet of the odd vertex m on edge (a, b) of K^j is
//! `psi_m = phi^{j+1}_m - sum_{k in S} s_k phi^j_k` over the diamond
//! `S = {a, b, c, d}` (c, d opposite the edge; one of them on the boundary).
//! The weights minimise `sum_i <psi_m, phi^j_i>^2` over every coarse hat
//! function `phi^j_i` the wavelet can overlap (the closed 1-rings of S): the
//! normal equations `(M^T M) s = M^T g` with `M_ik = <phi^j_k, phi^j_i>` and
//! `g_i = <phi^{j+1}_m, phi^j_i>`.
//!
//! With the inner product of eq. 2.36 every base face has unit area, so a
//! face of K^j has area `4^-j` and all inner products are combinatorial. In
//! units of the area of a face of K^{j+1}:
//! `<phi^j_k, phi^j_k> = 4 F_k / 6`, `<phi^j_k, phi^j_i> = 4 F_ki / 12`
//! (F = number of faces at a vertex or an edge), and, refining
//! `phi^j_a = phi^{j+1}_a + 1/2 sum_odd phi^{j+1}_o`,
//! `g_a = g_b = 5 F_ab / 12`, `g_c = g_d = 1 / 6`, zero elsewhere.
//! These are exact for the hat functions of the midpoint scheme; for Loop
//! and butterfly the same weights are used (the hat functions then
//! approximate their smooth scaling functions).

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

use crate::rules::ring_with_face_counts;
use crate::topology::{Kind, Topology};

/// The closed 1-rings of every vertex of K^j, stored contiguously
/// (counter-clockwise, interior rings rotated on demand): one random access
/// per stencil vertex instead of one per neighbour. Cost O(F_j) to build.
pub(crate) struct Rings {
    start: Vec<u32>,
    entries: Vec<(u32, u8)>,
    faces: Vec<u32>,
    interior: Vec<bool>,
}

impl Rings {
    pub(crate) fn new(topo: &Topology) -> Self {
        let n = topo.vertex_count();
        let mut start = Vec::with_capacity(n + 1);
        let mut entries = Vec::with_capacity(2 * topo.edge_count() + n);
        let mut faces = Vec::with_capacity(n);
        let mut interior = Vec::with_capacity(n);
        let mut ring = Vec::new();
        start.push(0);
        for v in 0..n as u32 {
            ring_with_face_counts(topo, v, &mut ring);
            entries.extend_from_slice(&ring);
            start.push(entries.len() as u32);
            faces.push(topo.out(v).len() as u32);
            interior.push(topo.kind(v) == Kind::Interior);
        }
        Self { start, entries, faces, interior }
    }

    fn ring(&self, v: u32) -> &[(u32, u8)] {
        &self.entries[self.start[v as usize] as usize..self.start[v as usize + 1] as usize]
    }
}

/// Scratch space for [`update_weights`], reused across the odd vertices of
/// one level: a small open-addressing table from vertex to local slot.
///
/// The weights depend only on the combinatorics of the diamond's
/// neighbourhood, so they are memoised by a byte signature of it: the rings
/// are walked from a canonical start, and the signature records, for each
/// stencil vertex, its face count and, for each ring entry, the local slot
/// of the neighbour and the face count of the edge. Equal signatures give
/// equal least-squares systems; a semi-regular mesh has a handful of them.
pub(crate) struct UpdateScratch {
    slots: Vec<u32>,
    rows: Vec<[f64; 4]>,
    table: [(u32, u8); TABLE],
    used: Vec<u8>,
    signature: Vec<u8>,
    cache: HashMap<Vec<u8>, Option<[f64; 4]>, BuildHasherDefault<FxHasher>>,
}

const TABLE: usize = 128;

impl UpdateScratch {
    /// Empty scratch.
    pub(crate) fn new() -> Self {
        Self {
            slots: Vec::new(),
            rows: Vec::new(),
            table: [(u32::MAX, 0); TABLE],
            used: Vec::with_capacity(TABLE),
            signature: Vec::with_capacity(128),
            cache: HashMap::default(),
        }
    }

    fn begin(&mut self) {
        for &i in &self.used {
            self.table[i as usize].0 = u32::MAX;
        }
        self.used.clear();
        self.slots.clear();
        self.rows.clear();
    }

    /// The local slot of `v`, or `None` when the neighbourhood is too large
    /// for the table (then the caller falls back to no update).
    fn slot(&mut self, v: u32) -> Option<usize> {
        let mut i = hash_slot(v);
        loop {
            match self.table[i].0 {
                x if x == v => return Some(self.table[i].1 as usize),
                u32::MAX => break,
                _ => i = (i + 1) % TABLE,
            }
        }
        if self.slots.len() >= TABLE / 2 {
            return None;
        }
        self.table[i] = (v, self.slots.len() as u8);
        self.used.push(i as u8);
        self.slots.push(v);
        self.rows.push([0.0; 4]);
        Some(self.slots.len() - 1)
    }
}

fn hash_slot(v: u32) -> usize {
    (v.wrapping_mul(0x9E37_79B1) >> 25) as usize % TABLE
}

/// A small fast hasher for the signatures (FxHash's multiply-rotate).
#[derive(Default)]
struct FxHasher(u64);

impl Hasher for FxHasher {
    fn write(&mut self, bytes: &[u8]) {
        for chunk in bytes.chunks(8) {
            let mut word = [0u8; 8];
            word[..chunk.len()].copy_from_slice(chunk);
            self.0 = (self.0.rotate_left(5) ^ u64::from_le_bytes(word)).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
        }
    }

    fn finish(&self) -> u64 {
        self.0
    }
}

/// Update weights `s_k` for the odd vertex on edge (`a`, `b`) with opposite
/// vertices `opposite` (one or two), appended to `row` as (coarse vertex,
/// weight). Falls back to no update (the lazy wavelet) if the local system
/// is singular, which only a degenerate diamond (repeated vertices) causes.
/// Cost O(valence^2) per odd vertex, O(valence) on a memoised configuration.
pub(crate) fn update_weights(
    rings: &Rings,
    a: u32,
    b: u32,
    opposite: &[u32],
    scratch: &mut UpdateScratch,
    row: &mut Vec<(u32, f64)>,
) {
    let nf = opposite.len() as f64;
    let mut stencil: [(u32, f64); 4] = [(u32::MAX, 0.0); 4];
    let mut size = 0;
    for (v, g) in
        [(a, 5.0 * nf / 12.0), (b, 5.0 * nf / 12.0)].into_iter().chain(opposite.iter().map(|&c| (c, 1.0 / 6.0)))
    {
        if size == 4 || stencil[..size].iter().any(|s| s.0 == v) {
            return; // degenerate diamond: keep the lazy wavelet
        }
        stencil[size] = (v, g);
        size += 1;
    }
    scratch.begin();
    scratch.signature.clear();
    scratch.signature.push(size as u8);
    // Column k of M: <phi^j_k, phi^j_i> for i in the closed ring of stencil
    // vertex k, walked from a canonical neighbour (b for a; a for b and c; b for d).
    for k in 0..size {
        let v = stencil[k].0;
        let faces = rings.faces[v as usize];
        let Some(s) = scratch.slot(v) else { return };
        scratch.rows[s][k] += 4.0 * faces as f64 / 6.0;
        let ring = rings.ring(v);
        let first = if rings.interior[v as usize] {
            let start = if k == 0 || k == 3 { b } else { a };
            ring.iter().position(|r| r.0 == start).unwrap_or(0)
        } else {
            0
        };
        if faces > 255 || ring.len() > 255 {
            return; // keep the lazy wavelet at absurd valences
        }
        scratch.signature.extend([faces as u8, ring.len() as u8, rings.interior[v as usize] as u8]);
        for &(w, fe) in ring[first..].iter().chain(&ring[..first]) {
            let Some(s) = scratch.slot(w) else { return };
            scratch.rows[s][k] += fe as f64 / 3.0;
            scratch.signature.extend([s as u8, fe]);
        }
    }
    let weights = match scratch.cache.get(&scratch.signature) {
        Some(&w) => w,
        None => {
            let w = solve_normal_equations(scratch, &stencil[..size]);
            scratch.cache.insert(scratch.signature.clone(), w);
            w
        }
    };
    if let Some(s) = weights {
        row.extend(stencil[..size].iter().zip(s).map(|(st, w)| (st.0, w)));
    }
}

/// The least-squares weights from the assembled rows of M.
fn solve_normal_equations(scratch: &UpdateScratch, stencil: &[(u32, f64)]) -> Option<[f64; 4]> {
    let size = stencil.len();
    let mut mtm = [[0.0; 4]; 4];
    let mut rhs = [0.0; 4];
    for (slot, r) in scratch.rows.iter().enumerate() {
        let v = scratch.slots[slot];
        let g = stencil.iter().find(|s| s.0 == v).map_or(0.0, |s| s.1);
        for k in 0..size {
            rhs[k] += r[k] * g;
            for l in 0..size {
                mtm[k][l] += r[k] * r[l];
            }
        }
    }
    solve_spd(&mut mtm, &mut rhs, size)
}

/// Solves a small symmetric positive definite system by Cholesky, `None`
/// if it is not numerically positive definite.
fn solve_spd(m: &mut [[f64; 4]; 4], rhs: &mut [f64; 4], n: usize) -> Option<[f64; 4]> {
    let scale = (0..n).map(|i| m[i][i]).fold(0.0, f64::max);
    for j in 0..n {
        let mut d = m[j][j];
        for k in 0..j {
            d -= m[j][k] * m[j][k];
        }
        if d.is_nan() || d <= 1e-12 * scale {
            return None;
        }
        let d = d.sqrt();
        m[j][j] = d;
        for i in j + 1..n {
            let mut s = m[i][j];
            for k in 0..j {
                s -= m[i][k] * m[j][k];
            }
            m[i][j] = s / d;
        }
    }
    let mut y = [0.0; 4];
    for i in 0..n {
        let mut s = rhs[i];
        for k in 0..i {
            s -= m[i][k] * y[k];
        }
        y[i] = s / m[i][i];
    }
    for i in (0..n).rev() {
        let mut s = y[i];
        for k in i + 1..n {
            s -= m[k][i] * y[k];
        }
        y[i] = s / m[i][i];
    }
    y.iter().all(|x| x.is_finite()).then_some(y)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cholesky_solves() {
        let mut m = [[4.0, 1.0, 0.0, 0.0], [1.0, 3.0, 0.0, 0.0], [0.0; 4], [0.0; 4]];
        let mut r = [1.0, 2.0, 0.0, 0.0];
        let x = solve_spd(&mut m, &mut r, 2).unwrap();
        assert!((4.0 * x[0] + x[1] - 1.0).abs() < 1e-14);
        assert!((x[0] + 3.0 * x[1] - 2.0).abs() < 1e-14);
        let mut z = [[0.0; 4]; 4];
        assert!(solve_spd(&mut z, &mut r, 2).is_none());
    }
}
