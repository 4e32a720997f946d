//! Corner angles and corner areas of [`CORNER_BATCH`] faces at a time, bit
//! for bit those of [`corner_angles_and_masses`], for single passes over
//! the faces such as the angle defect's and the lumped mass's
//! ([`crate::par::scatter_batched`]); and the corners' cotangents, bit for
//! bit those of [`triangle_cotans`], for the Laplacian applied without
//! assembling it ([`super::cotan_laplacian_apply`]).
//!
//! One face at a time, the work is a chain of dependent latencies (edge
//! vectors, cross product, square root, two divisions and a polynomial for
//! each `atan2`, one division for the cotangents) and random reads of the
//! corner positions, which the processor cannot overlap with the next face:
//! its instructions do not fit in the reorder window. Here the positions of
//! all the faces of a batch are read first (their cache misses overlap), then
//! one loop over the lanes, free of branches, computes every face; with AVX2
//! (detected at run time) the compiler turns that loop into 4-wide vector
//! operations. The arithmetic is the scalar one, operation for operation, so
//! that the results are identical: faces outside its fast path (an edge's
//! coordinates outside `[1e-60, 1e60]`, a cross product outside
//! `[1e-150, 1e150]`, a right or obtuse angle at an end of the longest edge,
//! zero area) are recomputed by `corner_angles_and_masses` (the
//! cotangents: outside the first two, by `triangle_cotans`).

use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};

use glam::DVec3;

use super::laplacian::{triangle_cotans, DEGENERATE_TOLERANCE};
use super::mass::{corner_angles_and_masses, corner_masses, MassKind};
use crate::geometry::{rotated_atan, PI_2_LO, PI_4_LO, TAN_PI_8};
use crate::TriMesh;

/// Faces per batch.
pub const CORNER_BATCH: usize = 8;
const LANES: usize = CORNER_BATCH;

/// Each corner's `(angle, area)`, per face of a batch.
pub type CornerBatch = [[(f64, f64); 3]; CORNER_BATCH];

/// The corner angles ([`crate::geometry::triangle_angles`]) and `kind`
/// areas ([`super::corner_masses`]: barycentric thirds or the mixed Voronoi
/// areas of Meyer et al. 2003) of `mesh`'s faces `first..` (up to
/// [`CORNER_BATCH`] of them, fewer at the end) into `out`, bit for bit
/// those of [`corner_angles_and_masses`] face by face, about twice as fast:
/// the positions of the batch are read first, then one loop over the
/// faces without branches, 4-wide where the processor has AVX2. Returns
/// how many faces were done (0 from `first >= face_count`). O(1).
pub fn corner_angles_and_masses_batch(mesh: &TriMesh, first: usize, kind: MassKind, out: &mut CornerBatch) -> usize {
    batch::<true>(mesh, first, kind, out)
}

/// [`corner_angles_and_masses_batch`] without the angles (left zero): the
/// corner areas alone, bit for bit those of [`corner_masses`], for the
/// lumped mass. O(1).
pub(crate) fn corner_masses_batch(mesh: &TriMesh, first: usize, kind: MassKind, out: &mut CornerBatch) -> usize {
    batch::<false>(mesh, first, kind, out)
}

/// The corner batch of the faces `first..`, 4-wide where the processor has
/// AVX2; how many faces it holds (0 past the last face).
#[inline(always)]
fn batch<const ANGLES: bool>(mesh: &TriMesh, first: usize, kind: MassKind, out: &mut CornerBatch) -> usize {
    let Some(faces) = batch_faces(mesh, first) else { return 0 };
    let positions = mesh.positions();
    with_avx2_if_present(
        #[inline(always)]
        || batch_lanes::<ANGLES>(positions, faces, kind, out),
    );
    faces.len()
}

/// The faces of the batch that starts at `first` (up to [`CORNER_BATCH`]),
/// `None` from `first >= face_count`.
#[inline(always)]
fn batch_faces(mesh: &TriMesh, first: usize) -> Option<&[[u32; 3]]> {
    let faces = mesh.faces();
    (first < faces.len()).then(|| &faces[first..faces.len().min(first + LANES)])
}

/// `run()`, compiled for AVX2 where the processor has it (detected at run
/// time): the lanes' loops inline into it and become 4-wide.
#[inline(always)]
fn with_avx2_if_present<R>(run: impl FnOnce() -> R) -> R {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the processor has AVX2, checked just above.
        return unsafe { in_avx2(run) };
    }
    run()
}

/// `run()` compiled for AVX2.
///
/// # Safety
/// The processor must have AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn in_avx2<R>(run: impl FnOnce() -> R) -> R {
    run()
}

/// `if c { a } else { b }`, which the compiler keeps as a select (a vector
/// blend in the lanes' loop).
#[inline(always)]
fn pick(c: bool, a: f64, b: f64) -> f64 {
    if c {
        a
    } else {
        b
    }
}

/// glam's `max` of two coordinates.
#[inline(always)]
fn max(a: f64, b: f64) -> f64 {
    if a > b {
        a
    } else {
        b
    }
}

/// [`crate::geometry`]'s `atan2_upper` for `x > 0`, `y > 0`, with the rotation
/// picked by selects instead of a table: `y.atan2(x)` within 2 ulps, by a
/// rotation of 0, pi/4 or pi/2 to `atan(u)`, `|u| <= tan(pi/8)`, and a
/// polynomial of degree 10 in `u^2` (see there for the fit).
#[inline(always)]
fn atan2_lane(y: f64, x: f64) -> f64 {
    let (above, steep) = (y > TAN_PI_8 * x, x < TAN_PI_8 * y);
    let (a, b) = (pick(steep, 0.0, 1.0), pick(above, 1.0, 0.0));
    let hi = pick(steep, FRAC_PI_2, pick(above, FRAC_PI_4, 0.0));
    let lo = pick(steep, PI_2_LO, pick(above, PI_4_LO, 0.0));
    let u = (a * y - b * x) / (a * x + b * y);
    rotated_atan(u, hi, lo)
}

/// The corner coordinates of `faces` (1 to [`CORNER_BATCH`]) by corner
/// and axis, lane by lane; a short batch repeats its last face.
#[inline(always)]
fn gather(positions: &[DVec3], faces: &[[u32; 3]]) -> [[f64; LANES]; 9] {
    let n = faces.len();
    debug_assert!((1..=LANES).contains(&n));
    let mut p = [[0.0f64; LANES]; 9];
    for i in 0..LANES {
        let face = faces[i.min(n - 1)];
        for (k, &v) in face.iter().enumerate() {
            let q = positions[v as usize];
            (p[3 * k][i], p[3 * k + 1][i], p[3 * k + 2][i]) = (q.x, q.y, q.z);
        }
    }
    p
}

/// What every kernel computes of the triangle in lane `i`, operation for
/// operation as the scalar code does.
struct LaneTriangle {
    /// Squared length of edge k, from corner k to k + 1.
    squared: [f64; 3],
    /// The dot product of the two edges leaving corner k.
    dots: [f64; 3],
    /// `|(b - a) x (c - a)|`.
    double_area: f64,
    /// The largest coordinate of `b - a` and `c - a` (`triangle_in_own_unit`'s
    /// size) and of the cross product.
    size: f64,
    cross_size: f64,
}

impl LaneTriangle {
    #[inline(always)]
    fn new(p: &[[f64; LANES]; 9], i: usize) -> Self {
        let (ax, ay, az) = (p[0][i], p[1][i], p[2][i]);
        let (bx, by, bz) = (p[3][i], p[4][i], p[5][i]);
        let (cx, cy, cz) = (p[6][i], p[7][i], p[8][i]);
        // Edge k from corner k to k + 1, as in TriangleParts.
        let (e0x, e0y, e0z) = (bx - ax, by - ay, bz - az);
        let (e1x, e1y, e1z) = (cx - bx, cy - by, cz - bz);
        let (e2x, e2y, e2z) = (ax - cx, ay - cy, az - cz);
        // triangle_in_own_unit's size: max |b - a|, |c - a|.
        let (fx, fy, fz) = ((cx - ax).abs(), (cy - ay).abs(), (cz - az).abs());
        let size = max(max(e0x.abs(), fx), max(max(e0y.abs(), fy), max(e0z.abs(), fz)));
        let l0 = (e0x * e0x) + (e0y * e0y) + (e0z * e0z);
        let l1 = (e1x * e1x) + (e1y * e1y) + (e1z * e1z);
        let l2 = (e2x * e2x) + (e2y * e2y) + (e2z * e2z);
        // e0 x e2 and its length (norm's fast path).
        let (nx, ny, nz) = (e0y * e2z - e2y * e0z, e0z * e2x - e2z * e0x, e0x * e2y - e2x * e0y);
        let cross_size = max(nx.abs(), max(ny.abs(), nz.abs()));
        let double_area = ((nx * nx) + (ny * ny) + (nz * nz)).sqrt();
        let d0 = -((e0x * e2x) + (e0y * e2y) + (e0z * e2z));
        let d1 = -((e1x * e0x) + (e1y * e0y) + (e1z * e0z));
        let d2 = -((e2x * e1x) + (e2y * e1y) + (e2z * e1z));
        Self { squared: [l0, l1, l2], dots: [d0, d1, d2], double_area, size, cross_size }
    }

    /// Whether the scalar code takes the same path: no rescaling by
    /// `triangle_in_own_unit` (coordinate differences in `[1e-60,
    /// 1e60]`), and [`crate::geometry::norm`]'s plain square root (a cross
    /// product in `[1e-150, 1e150]`).
    #[inline(always)]
    fn squares_are_safe(&self) -> bool {
        self.size > 1e-60 && self.size < 1e60 && self.cross_size > 1e-150 && self.cross_size < 1e150
    }
}

/// The cotangents of the corners of `mesh`'s faces `first..` (up to
/// [`CORNER_BATCH`] of them) into `out`, `[f][k]` at corner `k` of the
/// batch's face `f`: bit for bit [`triangle_cotans`] face by face (zeros
/// on a degenerate face), computed as the corner batches are. Returns how
/// many faces were done (0 from `first >= face_count`). O(1).
pub(crate) fn cotans_batch(mesh: &TriMesh, first: usize, out: &mut [[f64; 3]; CORNER_BATCH]) -> usize {
    let Some(faces) = batch_faces(mesh, first) else { return 0 };
    let positions = mesh.positions();
    with_avx2_if_present(
        #[inline(always)]
        || cotan_lanes(positions, faces, out),
    );
    faces.len()
}

/// [`cotans_batch`] on `faces` (1 to [`CORNER_BATCH`]), without the
/// dispatch. Faces off the fast path (see [`LaneTriangle`]) are
/// recomputed by [`triangle_cotans`].
#[inline(always)]
fn cotan_lanes(positions: &[DVec3], faces: &[[u32; 3]], out: &mut [[f64; 3]; CORNER_BATCH]) {
    let p = gather(positions, faces);
    let mut cot = [[0.0f64; LANES]; 3];
    let mut fast = [false; LANES];
    for i in 0..LANES {
        let t = LaneTriangle::new(&p, i);
        let ([l0, l1, l2], [d0, d1, d2], double_area) = (t.squared, t.dots, t.double_area);
        // triangle_cotans' test, on |b - a|^2, |c - a|^2 and |c - b|^2.
        let proper = double_area > DEGENERATE_TOLERANCE * max(max(l0, l2), l1);
        cot[0][i] = pick(proper, d0 / double_area, 0.0);
        cot[1][i] = pick(proper, d1 / double_area, 0.0);
        cot[2][i] = pick(proper, d2 / double_area, 0.0);
        fast[i] = t.squares_are_safe();
    }
    for (i, face) in faces.iter().enumerate() {
        out[i] = if fast[i] {
            [cot[0][i], cot[1][i], cot[2][i]]
        } else {
            triangle_cotans(face.map(|v| positions[v as usize]))
        };
    }
}

/// [`corner_angles_and_masses_batch`] on `faces` (1 to [`CORNER_BATCH`],
/// corners into `positions`), without the dispatch; with `ANGLES` false,
/// the angles are left out (zeros), and with them their two `atan2`.
#[inline(always)]
fn batch_lanes<const ANGLES: bool>(positions: &[DVec3], faces: &[[u32; 3]], kind: MassKind, out: &mut CornerBatch) {
    let n = faces.len();
    let p = gather(positions, faces);
    let voronoi = kind == MassKind::MixedVoronoi;
    let mut angle = [[0.0f64; LANES]; 3];
    let mut area = [[0.0f64; LANES]; 3];
    let mut fast = [false; LANES];
    for i in 0..LANES {
        let t = LaneTriangle::new(&p, i);
        let ([l0, l1, l2], [d0, d1, d2], double_area) = (t.squared, t.dots, t.double_area);
        // The ends of the longest edge m (first of equals) are corners m
        // and m + 1; the third angle is pi minus theirs.
        let first = l0 >= l1 && l0 >= l2;
        let second = !first && l1 >= l2;
        let x0 = pick(first, d0, pick(second, d1, d2));
        let x1 = pick(first, d1, pick(second, d2, d0));
        if ANGLES {
            let (a0, a1) = (atan2_lane(double_area, x0), atan2_lane(double_area, x1));
            let a2 = PI - a0 - a1;
            angle[0][i] = pick(first, a0, pick(second, a2, a1));
            angle[1][i] = pick(first, a1, pick(second, a0, a2));
            angle[2][i] = pick(first, a2, pick(second, a1, a0));
        }
        // Areas: mixed Voronoi (the Voronoi shares unless a corner is
        // obtuse, then half the area there and a quarter at the others) or
        // a third of the area.
        let half = 0.5 * double_area;
        let inv = 1.0 / (2.0 * half);
        let (cot0, cot1, cot2) = (d0 * inv, d1 * inv, d2 * inv);
        let v0 = (l0 * cot2 + l2 * cot1) / 8.0;
        let v1 = (l1 * cot0 + l0 * cot2) / 8.0;
        let v2 = (l2 * cot1 + l1 * cot0) / 8.0;
        let (quarter, obtuse_share) = (half / 4.0, half / 2.0);
        let o0 = d0 < 0.0;
        let o1 = d1 < 0.0 && !o0;
        let o2 = d2 < 0.0 && !o0 && !o1;
        let obtuse = o0 || o1 || o2;
        let third = half / 3.0;
        let s0 = pick(obtuse, pick(o0, obtuse_share, quarter), v0);
        let s1 = pick(obtuse, pick(o1, obtuse_share, quarter), v1);
        let s2 = pick(obtuse, pick(o2, obtuse_share, quarter), v2);
        // (corner_masses maps a zero share to +0.) Written out corner by
        // corner: a loop over the corners here keeps the compiler from
        // vectorizing the loop over the lanes.
        area[0][i] = pick(voronoi, pick(s0 == 0.0, 0.0, s0), third);
        area[1][i] = pick(voronoi, pick(s1 == 0.0, 0.0, s1), third);
        area[2][i] = pick(voronoi, pick(s2 == 0.0, 0.0, s2), third);
        fast[i] = t.squares_are_safe() && x0 > 0.0 && x1 > 0.0;
    }
    for i in 0..n {
        out[i] = if fast[i] {
            [0, 1, 2].map(|k| (angle[k][i], area[k][i]))
        } else {
            let tri = faces[i].map(|v| positions[v as usize]);
            let (angles, areas) =
                if ANGLES { corner_angles_and_masses(tri, kind) } else { ([0.0; 3], corner_masses(tri, kind)) };
            [0, 1, 2].map(|k| (angles[k], areas[k]))
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::random::SplitMix64;

    /// Random triangles: well shaped, obtuse, slivers, right angles, zero
    /// area, repeated points, tiny and huge, so that both the fast path and
    /// every fallback run.
    fn triangles(seed: u64, count: usize) -> Vec<[DVec3; 3]> {
        let mut rng = SplitMix64::new(seed);
        let mut out = Vec::with_capacity(count);
        let v = |rng: &mut SplitMix64| DVec3::new(rng.signed(), rng.signed(), rng.signed());
        while out.len() < count {
            let (a, b) = (v(&mut rng), v(&mut rng));
            let c = match rng.below(6) {
                0 => a + (b - a) * rng.unit() + v(&mut rng) * 1e-9, // sliver
                1 => a + (b - a) * rng.unit(),                      // collinear
                2 => a,                                             // repeated point
                3 => {
                    // A right angle at a.
                    let e = b - a;
                    a + e.any_orthonormal_vector() * rng.unit()
                }
                _ => v(&mut rng),
            };
            let scale = match rng.below(8) {
                0 => 1e-70,
                1 => 1e70,
                2 => 1e-140,
                _ => 1.0 + rng.unit(),
            };
            out.push([a * scale, b * scale, c * scale]);
        }
        out
    }

    /// `run` against the scalar corners, with the angles or (`angles`
    /// false) with zeros in their place.
    fn check(angles: bool, run: impl Fn(&[DVec3], &[[u32; 3]], MassKind, &mut CornerBatch)) {
        for kind in MassKind::ALL {
            for seed in 0..4 {
                let tris = triangles(seed, 3001);
                let positions: Vec<DVec3> = tris.iter().flatten().copied().collect();
                let faces: Vec<[u32; 3]> = (0..tris.len() as u32).map(|f| [3 * f, 3 * f + 1, 3 * f + 2]).collect();
                let mut out: CornerBatch = [[(0.0, 0.0); 3]; LANES];
                for (b, chunk) in faces.chunks(LANES).enumerate() {
                    run(&positions, chunk, kind, &mut out);
                    for (i, face) in chunk.iter().enumerate() {
                        let tri = face.map(|v| positions[v as usize]);
                        let (expected, areas) = corner_angles_and_masses(tri, kind);
                        assert_eq!(areas, corner_masses(tri, kind));
                        let expected = if angles { expected } else { [0.0; 3] };
                        for k in 0..3 {
                            assert_eq!(
                                (out[i][k].0.to_bits(), out[i][k].1.to_bits()),
                                (expected[k].to_bits(), areas[k].to_bits()),
                                "{kind} face {} corner {k}: {:?}",
                                b * LANES + i,
                                tris[b * LANES + i]
                            );
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn batches_equal_the_scalar_corners_bit_for_bit() {
        check(true, batch_lanes::<true>);
        check(false, batch_lanes::<false>);
    }

    /// The dispatched batches (4-wide where the processor has AVX2).
    #[test]
    fn the_dispatched_batches_too() {
        check(true, |p, f, k, o| {
            with_avx2_if_present(
                #[inline(always)]
                || batch_lanes::<true>(p, f, k, o),
            )
        });
        check(false, |p, f, k, o| {
            with_avx2_if_present(
                #[inline(always)]
                || batch_lanes::<false>(p, f, k, o),
            )
        });
    }

    /// The cotangent batches, plain and dispatched, against
    /// `triangle_cotans` face by face, to the bit.
    #[test]
    fn cotangent_batches_equal_the_scalar_cotangents_bit_for_bit() {
        for (seed, dispatched) in (10..14).zip([false, true].into_iter().cycle()) {
            let run = |p: &[DVec3], f: &[[u32; 3]], o: &mut [[f64; 3]; LANES]| {
                if dispatched {
                    with_avx2_if_present(
                        #[inline(always)]
                        || cotan_lanes(p, f, o),
                    )
                } else {
                    cotan_lanes(p, f, o)
                }
            };
            let tris = triangles(seed, 3001);
            let positions: Vec<DVec3> = tris.iter().flatten().copied().collect();
            let faces: Vec<[u32; 3]> = (0..tris.len() as u32).map(|f| [3 * f, 3 * f + 1, 3 * f + 2]).collect();
            let mut out = [[0.0; 3]; LANES];
            let mut degenerate = 0;
            for (b, chunk) in faces.chunks(LANES).enumerate() {
                run(&positions, chunk, &mut out);
                for (i, face) in chunk.iter().enumerate() {
                    let expected = triangle_cotans(face.map(|v| positions[v as usize]));
                    degenerate += usize::from(expected == [0.0; 3]);
                    assert_eq!(out[i].map(f64::to_bits), expected.map(f64::to_bits), "face {}", b * LANES + i);
                }
            }
            assert!(degenerate > 100, "{degenerate} degenerate faces");
        }
    }
}
