//! Per-element geometry: areas, normals, angles, edge lengths, dihedral
//! angles, feature edges, bounding box, area and volume.
//!
//! Every function is a short loop over faces or edges, O(F), allocation of
//! the output only. Degenerate (zero-area) faces give zero normals and zero
//! areas, never NaN. Lengths of products of coordinates (areas, normals) go
//! through [`norm`] and [`unit_vector`], so that nothing over- or underflows
//! for coordinates between 1e-150 and 1e150: the unit of length does not
//! change an answer.

use glam::{DVec2, DVec3};

use crate::error::MeshError;
use crate::ids::{EdgeId, FaceId};
use crate::mesh::TriMesh;
use crate::par;

/// Euclidean length of `v` without overflow or underflow in the squares:
/// `v.length()` when the largest component lies in `[1e-150, 1e150]`,
/// otherwise computed on `v` rescaled by a power of two (exact). 0 for the
/// zero vector; infinite or NaN only when a component is.
#[inline]
pub fn norm(v: DVec3) -> f64 {
    let m = v.abs().max_element();
    if squares_are_safe(m) {
        return v.length();
    }
    if m == 0.0 || !m.is_finite() {
        return if v.is_nan() { f64::NAN } else { m };
    }
    let unit = power_of_two_near(m);
    (v / unit).length() * unit
}

/// Whether a vector whose largest absolute component is `m` has squares
/// that neither overflow nor underflow: `m` in `(1e-150, 1e150)`.
#[inline(always)]
fn squares_are_safe(m: f64) -> bool {
    m > 1e-150 && m < 1e150
}

/// `v / |v|` computed without overflow or underflow (see [`norm`]), or zero
/// when `v` is zero or not finite.
#[inline(always)]
pub fn unit_vector(v: DVec3) -> DVec3 {
    let m = v.abs().max_element();
    if squares_are_safe(m) {
        return v.normalize_or_zero();
    }
    if m == 0.0 || !m.is_finite() {
        return DVec3::ZERO;
    }
    (v / power_of_two_near(m)).normalize_or_zero()
}

/// Every vector of `vectors` replaced by its [`unit_vector`], in parallel
/// from [`par::UPDATE_FROM`] groups of four; the same bits as one call per
/// vector. Four vectors at a time: their four square roots and divisions
/// are independent, which the processor overlaps (1.5x faster than one
/// call per vector at 655,362 vectors, 2026-12-05).
pub fn unit_vectors_in_place(vectors: &mut [DVec3]) {
    let (quads, rest) = vectors.as_chunks_mut::<4>();
    par::update(quads, |q| *q = unit_vectors(*q));
    rest.iter_mut().for_each(|v| *v = unit_vector(*v));
}

/// [`unit_vector`] of four vectors. Where all four lie in the range without
/// rescaling, `v * (1 / |v|)` is what `normalize_or_zero` computes there
/// (the length is finite and nonzero), without its checks.
#[inline(always)]
fn unit_vectors(q: [DVec3; 4]) -> [DVec3; 4] {
    if !q.iter().all(|v| squares_are_safe(v.abs().max_element())) {
        return q.map(unit_vector);
    }
    let inverse = q.map(|v| 1.0 / v.length_squared().sqrt());
    [q[0] * inverse[0], q[1] * inverse[1], q[2] * inverse[2], q[3] * inverse[3]]
}

/// The power of two `2^e` with `2^e <= x < 2^(e + 1)`, for finite `x > 0`
/// (also subnormal); dividing by it is exact.
#[inline]
pub fn power_of_two_near(x: f64) -> f64 {
    const EXPONENT: u64 = 0x7ff0_0000_0000_0000;
    if x >= f64::MIN_POSITIVE {
        f64::from_bits(x.to_bits() & EXPONENT)
    } else {
        // Subnormal: lift into the normal range first (2^600 is exact).
        let lift = 2f64.powi(600);
        f64::from_bits((x * lift).to_bits() & EXPONENT) / lift
    }
}

/// The triangle divided by a power of two near the size of its edges, and
/// that power: `([a, b, c] / unit, unit)`, the triangle itself and 1 when
/// its edges' coordinates lie in `[1e-60, 1e60]` (division by a power of two
/// is exact, so no digit changes). Angles, cotangents and normals computed
/// on the result are those of the triangle, without overflow or underflow
/// whatever the unit of length.
#[inline]
pub fn triangle_in_own_unit(tri: [DVec3; 3]) -> ([DVec3; 3], f64) {
    let [a, b, c] = tri;
    let m = (b - a).abs().max((c - a).abs()).max_element();
    if (m > 1e-60 && m < 1e60) || m == 0.0 || !m.is_finite() {
        return (tri, 1.0);
    }
    let unit = power_of_two_near(m);
    (tri.map(|p| p / unit), unit)
}

/// Twice the signed area vector of a triangle: (b - a) x (c - a).
#[inline]
pub fn double_area_vector([a, b, c]: [DVec3; 3]) -> DVec3 {
    (b - a).cross(c - a)
}

/// Area of a triangle.
#[inline]
pub fn triangle_area(tri: [DVec3; 3]) -> f64 {
    // In the triangle's own unit, so that the cross product cannot overflow
    // (an area past f64::MAX is infinite, never NaN).
    let (tri, unit) = triangle_in_own_unit(tri);
    0.5 * norm(double_area_vector(tri)) * unit * unit
}

/// Unit normal of a counter-clockwise triangle (the chapter's face normal, section 2.2.2),
/// or zero when the triangle has no area.
#[inline]
pub fn triangle_normal(tri: [DVec3; 3]) -> DVec3 {
    unit_vector(double_area_vector(triangle_in_own_unit(tri).0))
}

/// Angle between two vectors in [0, pi], robust for tiny and nearly parallel
/// vectors (atan2 of the sine and cosine parts); 0 when one is zero.
#[inline]
pub fn angle_between(u: DVec3, v: DVec3) -> f64 {
    let m = u.abs().max(v.abs()).max_element();
    if (m > 1e-60 && m < 1e60) || m == 0.0 || !m.is_finite() {
        return norm(u.cross(v)).atan2(u.dot(v));
    }
    let unit = power_of_two_near(m);
    let (u, v) = (u / unit, v / unit);
    u.cross(v).length().atan2(u.dot(v))
}

/// Interior angles of a triangle, `[k]` at corner `k`, computed so that they
/// sum to pi: `atan2(2 area, dot)` at the two ends of the longest edge (the
/// two smaller, well-conditioned angles) and pi minus both at the third
/// corner. Zero-area and zero-length-edge triangles give angles in `[0, pi]`
/// summing to pi. Works in the triangle's own unit
/// ([`triangle_in_own_unit`]), so any finite size is fine.
#[inline]
pub fn triangle_angles(tri: [DVec3; 3]) -> [f64; 3] {
    TriangleParts::new(tri).angles()
}

/// What a triangle's corner angles and corner areas share, in the
/// triangle's own unit ([`triangle_in_own_unit`]): computed once when both
/// are needed.
#[derive(Debug, Clone, Copy)]
pub(crate) struct TriangleParts {
    /// Edge `k` runs from corner `k` to corner `k + 1`.
    pub edges: [DVec3; 3],
    /// Squared edge lengths.
    pub len2: [f64; 3],
    /// Twice the area.
    pub double_area: f64,
    /// The unit the parts are measured in.
    pub unit: f64,
}

impl TriangleParts {
    #[inline]
    pub fn new(tri: [DVec3; 3]) -> Self {
        let (tri, unit) = triangle_in_own_unit(tri);
        let edges = [tri[1] - tri[0], tri[2] - tri[1], tri[0] - tri[2]];
        let double_area = norm(edges[0].cross(edges[2]));
        Self { edges, len2: edges.map(|x| x.length_squared()), double_area, unit }
    }

    /// The dot product of the two edges at corner `k` (edge `k` and the
    /// reversed edge `k + 2`). A zero is always `+0`: negating a `+0` dot
    /// would give `-0`, whose `atan2(0, -0)` is pi, and a triangle whose
    /// three points coincide would get the angles `[pi, pi, -pi]`.
    #[inline]
    pub fn corner_dot(&self, k: usize) -> f64 {
        0.0 - self.edges[k].dot(self.edges[(k + 2) % 3])
    }

    /// [`triangle_angles`].
    #[inline]
    pub fn angles(&self) -> [f64; 3] {
        let len2 = self.len2;
        // The longest edge, first of equals, without a branch: the edges
        // of a mesh come in no order the branch predictor could learn.
        let not_first = usize::from(!(len2[0] >= len2[1] && len2[0] >= len2[2]));
        let m = not_first * (1 + usize::from(len2[1] < len2[2]));
        const NEXT: [usize; 5] = [0, 1, 2, 0, 1];
        let (k0, k1, k2) = (m, NEXT[m + 1], NEXT[m + 2]);
        let dots = [0, 1, 2].map(|k| self.corner_dot(k));
        let (a0, a1) = (atan2_upper(self.double_area, dots[k0]), atan2_upper(self.double_area, dots[k1]));
        let mut out = [0.0; 3];
        out[k0] = a0;
        out[k1] = a1;
        out[k2] = std::f64::consts::PI - a0 - a1;
        out
    }
}

/// tan(pi/8) rounded, where [`atan2_upper`] changes its rotation.
pub(crate) const TAN_PI_8: f64 = 0.414_213_562_373_095_03;
/// `pi/4 - FRAC_PI_4` and `pi/2 - FRAC_PI_2`: the low parts of the rotations.
pub(crate) const PI_4_LO: f64 = 3.061_616_997_868_383e-17;
pub(crate) const PI_2_LO: f64 = 6.123_233_995_736_766e-17;
/// The polynomial `P` of [`atan2_upper`], lowest degree first.
pub(crate) const ATAN_P: [f64; 11] = [
    -0.333_333_333_333_333_3,
    0.199_999_999_999_955_2,
    -0.142_857_142_846_665_42,
    0.111_111_110_152_563_61,
    -0.090_909_045_781_239_03,
    0.076_921_831_908_260_87,
    -0.066_645_114_473_819_48,
    0.058_581_489_128_022_1,
    -0.050_854_497_379_402_6,
    0.039_231_658_295_587_19,
    -0.019_176_887_119_062_26,
];

/// `y.atan2(x)` for `y >= 0`, within 2 ulps of it and about twice as fast
/// (no call, no branch on the octant), for the corner angles of
/// [`TriangleParts::angles`]. For `x > 0` and `y > 0` the angle in
/// `(0, pi/2)` is reduced by a rotation of 0, pi/4 or pi/2 (chosen by
/// comparing `y` with `x tan(pi/8)` and `x` with `y tan(pi/8)`) to
/// `atan(u)` with `|u| <= tan(pi/8)`, `u = (a y - b x) / (a x + b y)` with
/// `(a, b)` one of `(1, 0)`, `(1, 1)`, `(0, 1)`, so that `u` is one
/// correctly rounded division of exact or once-rounded terms; `atan(u) = u
/// + u s P(s)`, `s = u^2`, with `P` of degree 10 fitted to
/// `(atan(sqrt s) / sqrt s - 1) / s` on `[0, tan^2(pi/8)]` at Chebyshev
/// nodes (error 7e-18 relative to `u`, below half an ulp), evaluated by
/// Estrin's scheme; the rotation is added back as `pi/4` or `pi/2` in two
/// parts. Every other input (a zero, a negative `x`, NaN) goes to
/// [`f64::atan2`].
#[inline]
pub(crate) fn atan2_upper(y: f64, x: f64) -> f64 {
    use std::f64::consts::{FRAC_PI_2, FRAC_PI_4};
    /// The rotations' `(a, b)`, and their angles as high and low parts
    /// (`pi/4 - FRAC_PI_4` and `pi/2 - FRAC_PI_2`).
    const A: [f64; 3] = [1.0, 1.0, 0.0];
    const B: [f64; 3] = [0.0, 1.0, 1.0];
    const HI: [f64; 3] = [0.0, FRAC_PI_4, FRAC_PI_2];
    const LO: [f64; 3] = [0.0, PI_4_LO, PI_2_LO];
    if !(x > 0.0 && y > 0.0) {
        return y.atan2(x);
    }
    let k = usize::from(y > TAN_PI_8 * x) + usize::from(x < TAN_PI_8 * y);
    let (a, b) = (A[k], B[k]);
    let u = (a * y - b * x) / (a * x + b * y);
    rotated_atan(u, HI[k], LO[k])
}

/// `hi + lo + atan(u)` for `|u| <= tan(pi/8)`, the last step of
/// [`atan2_upper`] (and of the corner batches' copy of its reduction):
/// `atan(u) = u + u s P(s)` by Estrin's scheme, the rotation `hi + lo`
/// added in two parts.
#[inline(always)]
pub(crate) fn rotated_atan(u: f64, hi: f64, lo: f64) -> f64 {
    const P: [f64; 11] = ATAN_P;
    let s = u * u;
    let (s2, s4) = (s * s, s * s * s * s);
    let p03 = (P[3] * s + P[2]) * s2 + (P[1] * s + P[0]);
    let p47 = (P[7] * s + P[6]) * s2 + (P[5] * s + P[4]);
    let p8a = P[10] * s2 + (P[9] * s + P[8]);
    let p = (p8a * s4 + p47) * s4 + p03;
    hi + (u + (u * s * p + lo))
}

/// The apex of a triangle laid out in the plane from its side lengths: the
/// base runs from the origin to `(base, 0)`, the apex lies at `from_start`
/// from the origin and `from_end` from `(base, 0)`, on the side `y >= 0`.
/// `x` by the law of cosines, `y = 2 area / base` with Kahan's Heron area
/// ([`crate::operators::intrinsic::heron_area`]), which stays accurate on
/// slivers where `sqrt(from_start^2 - x^2)` cancels. Lengths that violate
/// the triangle inequality give `y = 0`; a base that is not positive gives
/// the origin. O(1).
#[inline]
pub fn planar_apex(base: f64, from_start: f64, from_end: f64) -> DVec2 {
    if base.is_nan() || base <= 0.0 {
        return DVec2::ZERO;
    }
    let x = (base * base + from_start * from_start - from_end * from_end) / (2.0 * base);
    let area = crate::operators::intrinsic::heron_area(base, from_start, from_end);
    DVec2::new(x, 2.0 * area / base)
}

/// Area of every face.
pub fn face_areas(mesh: &TriMesh) -> Vec<f64> {
    par::map(mesh.face_count(), |f| triangle_area(mesh.triangle(FaceId::new(f))))
}

/// Unit normal of every face (zero for zero-area faces).
pub fn face_normals(mesh: &TriMesh) -> Vec<DVec3> {
    par::map(mesh.face_count(), |f| triangle_normal(mesh.triangle(FaceId::new(f))))
}

/// Interior angle at each corner of every face, `[f][k]` at corner `k`.
pub fn corner_angles(mesh: &TriMesh) -> Vec<[f64; 3]> {
    par::map(mesh.face_count(), |f| triangle_angles(mesh.triangle(FaceId::new(f))))
}

/// How incident face normals are averaged into a vertex normal.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum NormalWeighting {
    /// Plain average of unit face normals.
    Uniform,
    /// Weighted by face area (libigl's `PER_VERTEX_NORMALS_WEIGHTING_TYPE_AREA`).
    #[default]
    Area,
    /// Weighted by the corner angle at the vertex (Thurmer and Wuthrich 1998).
    Angle,
    /// Max 1999 ("Weights for computing vertex normals from facet normals"):
    /// each face adds `(e1 x e2) / (|e1|^2 |e2|^2)`, `e1`, `e2` its edges at
    /// the vertex. Exact when the vertex and its 1-ring lie on a sphere; the
    /// normals of Rusinkiewicz's 2004 curvature estimator. Falls back to the
    /// area weighting where the sum vanishes (zero-length edges).
    Max,
}

crate::named_choice!(NormalWeighting, "normals", MeshError);

impl NormalWeighting {
    /// Every choice, in the order of the names `uniform`, `area`, `angle`, `max`.
    pub const ALL: [Self; 4] = [Self::Uniform, Self::Area, Self::Angle, Self::Max];

    /// The name parsed and displayed.
    pub fn name(self) -> &'static str {
        match self {
            Self::Uniform => "uniform",
            Self::Area => "area",
            Self::Angle => "angle",
            Self::Max => "max",
        }
    }
}

/// Unit vertex normals: the normalized weighted sum of incident face normals.
/// Isolated vertices, and vertices whose weighted sum vanishes, get zero
/// (the Max weighting first falls back to the area weighting). The weights
/// are summed in the mesh's [`crate::units::length_unit`], so that no unit
/// of length over- or underflows them. O(F).
pub fn vertex_normals(mesh: &TriMesh, weighting: NormalWeighting) -> Vec<DVec3> {
    // Multiplying by the inverse of a power of two is as exact as dividing,
    // and faster. The inverse of a subnormal unit would overflow: such a
    // mesh is first copied into its unit (normals do not depend on scale).
    let per_unit = 1.0 / crate::units::length_unit(mesh);
    if !per_unit.is_finite() {
        return vertex_normals(&crate::units::normalized(mesh).0, weighting);
    }
    let (n, faces, p) = (mesh.vertex_count(), mesh.faces(), mesh.positions());
    let corners = |f: usize| scaled_corners(p, faces[f], per_unit);
    let mut normals = match weighting {
        // The common case on its own, with its closures inlined into the
        // loop by force: left to the compiler they were calls returning
        // through memory, 1.3-1.5x slower (2026-12-03).
        NormalWeighting::Area => par::scatter_reading(
            n,
            faces,
            p,
            DVec3::ZERO,
            #[inline(always)]
            |f| [double_area_vector(corners(f)); 3],
            #[inline(always)]
            |sum, w| *sum += w,
        ),
        NormalWeighting::Max => {
            // With the area-weighted sum beside, for where Max's sum vanishes.
            let sums = par::scatter_reading(
                n,
                faces,
                p,
                [DVec3::ZERO; 2],
                |f| {
                    let c = corners(f);
                    let area2 = double_area_vector(c);
                    normal_weights(weighting, c, area2).map(|w| [w, area2])
                },
                |sum, [w, area2]| {
                    sum[0] += w;
                    sum[1] += area2;
                },
            );
            return par::map(n, |v| match unit_vector(sums[v][0]) {
                DVec3::ZERO => unit_vector(sums[v][1]),
                unit => unit,
            });
        }
        _ => par::scatter_reading(
            n,
            faces,
            p,
            DVec3::ZERO,
            |f| {
                let c = corners(f);
                normal_weights(weighting, c, double_area_vector(c))
            },
            |sum, w| *sum += w,
        ),
    };
    unit_vectors_in_place(&mut normals);
    normals
}

/// The corners of a face times `scale`; always inlined, since a call per face
/// costs as much as the work of an area-weighted normal.
#[inline(always)]
fn scaled_corners(p: &[DVec3], [a, b, c]: [u32; 3], scale: f64) -> [DVec3; 3] {
    [p[a as usize] * scale, p[b as usize] * scale, p[c as usize] * scale]
}

/// What each corner of a face (given in the mesh's unit, with its doubled
/// area vector) adds to its vertex's normal.
#[inline]
fn normal_weights(weighting: NormalWeighting, corners: [DVec3; 3], area2: DVec3) -> [DVec3; 3] {
    match weighting {
        NormalWeighting::Area => [area2; 3],
        NormalWeighting::Uniform => [unit_vector(area2); 3],
        NormalWeighting::Angle => triangle_angles(corners).map(|angle| angle * unit_vector(area2)),
        NormalWeighting::Max => {
            let [a, b, c] = corners;
            let len2 = [(b - a).length_squared(), (c - b).length_squared(), (a - c).length_squared()];
            // Corner k lies between edge k (to the next corner) and edge k + 2.
            [0, 1, 2].map(|k| {
                let w = len2[k] * len2[(k + 2) % 3];
                if w > 0.0 {
                    area2 / w
                } else {
                    DVec3::ZERO
                }
            })
        }
    }
}

/// Length of every edge, indexed by [`EdgeId`].
pub fn edge_lengths(mesh: &TriMesh) -> Vec<f64> {
    let p = mesh.positions();
    mesh.connectivity().edges().iter().map(|[a, b]| norm(p[b.idx()] - p[a.idx()])).collect()
}

/// Mean edge length (0 for a mesh without edges).
pub fn mean_edge_length(mesh: &TriMesh) -> f64 {
    let lengths = edge_lengths(mesh);
    if lengths.is_empty() {
        0.0
    } else {
        lengths.iter().sum::<f64>() / lengths.len() as f64
    }
}

/// Signed dihedral angle of every edge: the angle between the normals of its
/// two faces, in [-pi, pi], positive where the surface is convex (the edge
/// folds away from the normals), zero for flat, boundary and non-manifold
/// edges and across zero-area faces. From the cached face normals
/// ([`TriMesh::geometry`]), on [`par`]'s threads: in `mesh report` at
/// 470,274 vertices, 116 ms with the face normals' computation, where
/// computing both faces' normals for every edge on one thread took 310
/// (two cores, 2026-12-06).
pub fn dihedral_angles(mesh: &TriMesh) -> Vec<f64> {
    let conn = mesh.connectivity();
    let p = mesh.positions();
    let normals = mesh.geometry().face_normals();
    par::map(conn.edge_count(), |e| {
        let hs = conn.edge_halfedges(EdgeId::new(e));
        let [h0, h1] = match hs {
            [h0, h1] => [*h0, *h1],
            _ => return 0.0,
        };
        let (n0, n1) = (normals[h0.face().idx()], normals[h1.face().idx()]);
        if n0 == DVec3::ZERO || n1 == DVec3::ZERO {
            return 0.0;
        }
        let angle = angle_between(n0, n1);
        // Convex when the far corner of the second face lies below the first.
        let far = p[conn.opposite_vertex(h1).idx()] - p[conn.origin(h0).idx()];
        if far.dot(n0) > 0.0 {
            -angle
        } else {
            angle
        }
    })
}

/// Feature edges (chapter section 2.2.2): non-boundary edges whose face normals differ
/// by more than `threshold` radians, convex or concave.
pub fn feature_edges(mesh: &TriMesh, threshold: f64) -> Vec<EdgeId> {
    dihedral_angles(mesh)
        .into_iter()
        .enumerate()
        .filter(|(_, a)| a.abs() > threshold)
        .map(|(e, _)| EdgeId::new(e))
        .collect()
}

/// An axis-aligned bounding box.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb {
    /// Smallest coordinates.
    pub min: DVec3,
    /// Largest coordinates.
    pub max: DVec3,
}

impl Aabb {
    /// The smallest box holding `points` (NaN coordinates skipped), `None`
    /// for no point. In chunks of 32,768 points, on several threads from
    /// [`par::CHEAP_FROM`] points: at 470,274 points, read from memory, one
    /// thread took 1.0-1.2 ms (2026-12-05), and at 40,962 points a second
    /// thread cost 0.1-0.15 ms more than it saved.
    pub fn of(points: &[DVec3]) -> Option<Self> {
        let boxes = par::map_chunks(points, 1 << 15, Self::of_chunk);
        boxes.into_iter().flatten().reduce(|a, b| Self { min: a.min.min(b.min), max: a.max.max(b.max) })
    }

    /// [`Aabb::of`] on one thread, four points at a time into four boxes,
    /// so that no comparison waits for the one before, and with plain
    /// comparisons rather than `f64::min`, whose NaN checks doubled the
    /// work: one box with `min` took 0.6 ms at 470,274 points, four with
    /// comparisons 0.4 ms (in cache). A NaN coordinate is never smaller or
    /// larger than the box's, so it is skipped.
    fn of_chunk(points: &[DVec3]) -> Option<Self> {
        if points.is_empty() {
            return None;
        }
        let (quads, rest) = points.as_chunks::<4>();
        let (mut lo, mut hi) = ([DVec3::INFINITY; 4], [DVec3::NEG_INFINITY; 4]);
        for quad in quads {
            for k in 0..4 {
                lo[k] = DVec3::select(quad[k].cmplt(lo[k]), quad[k], lo[k]);
                hi[k] = DVec3::select(quad[k].cmpgt(hi[k]), quad[k], hi[k]);
            }
        }
        for &p in rest {
            lo[0] = DVec3::select(p.cmplt(lo[0]), p, lo[0]);
            hi[0] = DVec3::select(p.cmpgt(hi[0]), p, hi[0]);
        }
        Some(Self { min: lo[0].min(lo[1]).min(lo[2].min(lo[3])), max: hi[0].max(hi[1]).max(hi[2].max(hi[3])) })
    }

    /// Length of the diagonal (finite for any finite box: the extent is
    /// taken in halves, which cannot overflow).
    pub fn diagonal(&self) -> f64 {
        norm(self.max * 0.5 - self.min * 0.5) * 2.0
    }

    /// Centre of the box.
    pub fn center(&self) -> DVec3 {
        0.5 * (self.min + self.max)
    }
}

/// Bounding box of all vertices (referenced or not), `None` without vertices.
pub fn bounding_box(mesh: &TriMesh) -> Option<Aabb> {
    Aabb::of(mesh.positions())
}

/// Total surface area. Summed in the mesh's [`crate::units::length_unit`],
/// so that it is right whenever it lies in the range of `f64` (infinite
/// past `f64::MAX`, zero below the smallest subnormal).
pub fn surface_area(mesh: &TriMesh) -> f64 {
    let unit = crate::units::length_unit(mesh);
    let p = mesh.positions();
    // A fold from +0: `sum` starts at -0, which a mesh without faces would show.
    let sum = mesh.faces().iter().map(|t| triangle_area(t.map(|v| p[v as usize] / unit))).fold(0.0, |s, a| s + a);
    sum * unit * unit
}

/// Signed volume enclosed by the mesh: the sum over the faces of the
/// signed volumes of the cones from the bounding box's centre
/// ([`cone_volume6`], divergence theorem), in the mesh's
/// [`crate::units::length_unit`] like [`surface_area`]. Exact for closed
/// outward-oriented meshes, wherever they lie; for open meshes it depends
/// on the apex (the bounding box's centre).
pub fn enclosed_volume(mesh: &TriMesh) -> f64 {
    let Some(b) = mesh.geometry().bounding_box() else { return 0.0 };
    let (centre, unit) = (b.min * 0.5 + b.max * 0.5, crate::units::length_unit(mesh));
    let p = mesh.positions();
    let sum = mesh.faces().iter().map(|t| cone_volume6(t.map(|v| p[v as usize]), centre, unit)).fold(0.0, |s, x| s + x);
    sum / 6.0 * unit * unit * unit
}

/// Six times the signed volume of the cone from `apex` over a triangle,
/// in units of `unit^3` (a power of two, by which coordinates divide
/// exactly): `(a - o) . ((b - o) x (c - o)) / unit^3`. Summed over a
/// closed surface with an apex near it, the volume keeps its accuracy
/// wherever the surface lies; about the coordinates' origin, the terms
/// grow with the distance to it and cancel (a sphere 10^6 radii away: a
/// relative error of about 10^-4). O(1).
#[inline]
pub fn cone_volume6(tri: [DVec3; 3], apex: DVec3, unit: f64) -> f64 {
    let [a, b, c] = tri.map(|p| (p - apex) / unit);
    a.dot(b.cross(c))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes;
    use std::f64::consts::{FRAC_PI_2, PI};

    #[test]
    fn upper_atan2_is_within_two_ulps_of_the_library_one() {
        let ulp = |x: f64| f64::from_bits(x.abs().to_bits() + 1) - x.abs();
        let mut rng = crate::random::SplitMix64::new(5);
        let mut worst = 0.0f64;
        let mut check = |y: f64, x: f64| {
            let (ours, std) = (atan2_upper(y, x), y.atan2(x));
            worst = worst.max((ours - std).abs() / ulp(std));
        };
        for _ in 0..200_000 {
            // Uniform angles in the first quadrant at radii over 60 decades.
            let (t, r) = (rng.unit() * FRAC_PI_2, 10f64.powf(60.0 * rng.signed()));
            check(r * t.sin(), r * t.cos());
        }
        // Near the ends and the reduction's break points.
        for i in 0..20_000 {
            let d = (i as f64 + 0.5) * 1e-7;
            for t in [d, FRAC_PI_2 - d, PI / 8.0 + d - 1e-3, PI / 8.0 * 3.0 + d - 1e-3] {
                check(t.sin(), t.cos());
            }
        }
        assert!(worst <= 2.0, "{worst} ulps");
        // The rest is the library's, bit for bit.
        for (y, x) in [(0.0, 0.0), (0.0, -0.0), (0.0, 1.0), (1.0, 0.0), (1.0, -2.0), (0.0, -1.0), (f64::NAN, 1.0)] {
            assert_eq!(atan2_upper(y, x).to_bits(), y.atan2(x).to_bits(), "({y}, {x})");
        }
    }

    #[test]
    fn unit_vectors_in_place_gives_the_bits_of_unit_vector() {
        // Plain vectors, and every fourth one from the cases that take the
        // rescaling or zero paths, so that quads of each kind occur.
        let extreme = [
            DVec3::ZERO,
            DVec3::new(1e-200, -3e-201, 0.0),
            DVec3::new(2e200, 1e199, -5e200),
            DVec3::new(f64::INFINITY, 1.0, 0.0),
            DVec3::new(f64::NAN, 0.0, 1.0),
            DVec3::new(f64::MIN_POSITIVE / 8.0, 0.0, 0.0),
        ];
        let mut rng = crate::random::SplitMix64::new(11);
        // One loop, and past the threshold of several threads.
        for len in [10_003, 4 * par::UPDATE_FROM + 3] {
            let mut vectors: Vec<DVec3> = (0..len)
                .map(|i| {
                    if i % 4 == 3 && i < 200 {
                        extreme[i % extreme.len()]
                    } else {
                        DVec3::new(rng.signed(), rng.signed(), rng.signed()) * 10f64.powf(40.0 * rng.signed())
                    }
                })
                .collect();
            let expected: Vec<DVec3> = vectors.iter().map(|&v| unit_vector(v)).collect();
            unit_vectors_in_place(&mut vectors);
            let bits = |v: &DVec3| v.to_array().map(f64::to_bits);
            for (i, (ours, theirs)) in vectors.iter().zip(&expected).enumerate() {
                assert_eq!(bits(ours), bits(theirs), "vector {i} of {len}");
            }
        }
    }

    #[test]
    fn a_mesh_without_faces_has_positive_zero_area_and_volume() {
        let m = TriMesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y], Vec::new()).unwrap();
        assert_eq!(surface_area(&m).to_bits(), 0.0f64.to_bits());
        assert_eq!(enclosed_volume(&m).to_bits(), 0.0f64.to_bits());
    }

    #[test]
    fn bounding_boxes_are_the_extremes_of_every_coordinate() {
        let mut rng = crate::random::SplitMix64::new(5);
        // One chunk, several, and past the four of several threads.
        for len in [1, 3, 7, 40_001, 4 * 32_768 + 5] {
            let mut points: Vec<DVec3> =
                (0..len).map(|_| DVec3::new(rng.signed(), rng.signed(), rng.signed())).collect();
            let fold = |pick: fn(f64, f64) -> f64| {
                DVec3::from_array([0, 1, 2].map(|k| points.iter().map(|p| p[k]).fold(points[0][k], pick)))
            };
            let expect = Aabb { min: fold(f64::min), max: fold(f64::max) };
            assert_eq!(Aabb::of(&points), Some(expect), "{len} points");
            // A NaN coordinate, even in the first point, is skipped.
            if len > 1 {
                points[0].y = f64::NAN;
                let b = Aabb::of(&points).unwrap();
                let y = points[1..].iter().map(|p| p.y);
                assert_eq!(
                    [b.min.y, b.max.y],
                    [y.clone().fold(f64::INFINITY, f64::min), y.fold(-f64::INFINITY, f64::max)]
                );
            }
        }
        assert_eq!(Aabb::of(&[]), None);
    }

    /// A sphere 10^6 or 10^9 radii from the origin has the volume of the
    /// same (rounded) positions moved back, which the subtraction recovers
    /// exactly (about the origin, the terms cancelled: the volume was 71
    /// times too large at 10^6).
    #[test]
    fn volume_does_not_depend_on_where_the_mesh_lies() {
        let sphere = shapes::icosphere(3).unwrap();
        for offset in [1e6, 1e9] {
            let far = DVec3::new(offset, -offset, 0.5 * offset);
            let moved: Vec<DVec3> = sphere.positions().iter().map(|&p| p + far).collect();
            let back: Vec<DVec3> = moved.iter().map(|&p| p - far).collect();
            let [moved, back] =
                [moved, back].map(|p| enclosed_volume(&TriMesh::new(p, sphere.faces().to_vec()).unwrap()));
            assert!((moved - back).abs() < 1e-12 * back && back > 4.0, "offset {offset:e}: {moved} against {back}");
        }
    }

    #[test]
    fn cube_geometry() {
        let m = shapes::cube(2).unwrap();
        assert!((surface_area(&m) - 24.0).abs() < 1e-12);
        assert!((enclosed_volume(&m) - 8.0).abs() < 1e-12);
        let dihedral = dihedral_angles(&m);
        let sharp: Vec<_> = dihedral.iter().filter(|a| a.abs() > 0.1).collect();
        // 12 cube edges of 2 mesh edges each, all convex right angles.
        assert_eq!(sharp.len(), 24);
        assert!(sharp.iter().all(|a| (**a - FRAC_PI_2).abs() < 1e-12));
        assert_eq!(feature_edges(&m, 0.5).len(), 24);
        let bb = bounding_box(&m).unwrap();
        assert!((bb.diagonal() - 12f64.sqrt()).abs() < 1e-14);
    }

    #[test]
    fn sphere_normals_point_outward() {
        let m = shapes::icosphere(3).unwrap();
        for w in [NormalWeighting::Uniform, NormalWeighting::Area, NormalWeighting::Angle, NormalWeighting::Max] {
            let n = vertex_normals(&m, w);
            for (p, n) in m.positions().iter().zip(&n) {
                assert!((n.length() - 1.0).abs() < 1e-12);
                assert!(n.dot(*p) > 0.999);
            }
        }
    }

    /// Normals do not depend on the unit of length: the same sphere scaled
    /// into subnormal coordinates (whose unit has no finite inverse: the
    /// mesh is first copied into its unit) and near `f64::MAX / 8` gives
    /// the same normals to rounding.
    #[test]
    fn normals_do_not_depend_on_the_scale() {
        let m = shapes::icosphere(2).unwrap();
        for w in NormalWeighting::ALL {
            let reference = vertex_normals(&m, w);
            for scale in [1e-310, 1e300] {
                let scaled =
                    TriMesh::new(m.positions().iter().map(|p| *p * scale).collect(), m.faces().to_vec()).unwrap();
                for (a, b) in vertex_normals(&scaled, w).iter().zip(&reference) {
                    assert!((*a - *b).length() < 1e-9, "{w:?} at scale {scale}: {a} vs {b}");
                }
            }
        }
    }

    #[test]
    fn max_normals_are_exact_on_a_sphere() {
        let m = shapes::uv_sphere(2.0, 24, 12).unwrap();
        for (n, p) in vertex_normals(&m, NormalWeighting::Max).iter().zip(m.positions()) {
            assert!((*n - *p / 2.0).length() < 1e-12);
        }
    }

    #[test]
    fn angles_sum_to_pi() {
        let m = shapes::disk(4, 3).unwrap();
        for a in corner_angles(&m) {
            assert!((a.iter().sum::<f64>() - PI).abs() < 1e-12);
        }
    }

    #[test]
    fn angles_of_degenerate_triangles_lie_in_zero_pi_and_sum_to_pi() {
        // Points that coincide (all three, two of them, with either sign of
        // zero in their coordinates) or lie on a line, at several scales.
        let q = [DVec3::new(1.0, -2.0, 3.0), DVec3::new(-1.5, 0.5, -0.25), DVec3::new(0.0, -0.0, 0.0)];
        let mut cases = vec![[q[0]; 3], [q[1]; 3], [q[2]; 3], [-q[0]; 3]];
        for (a, b) in [(q[0], q[1]), (q[1], q[0]), (q[0], q[2]), (-q[1], q[0])] {
            cases.extend([[a, a, b], [a, b, a], [b, a, a], [a, b, 2.0 * b - a], [a, 0.5 * (a + b), b]]);
        }
        for scale in [1.0, 1e-200, 1e200, -3.0] {
            for tri in &cases {
                let angles = triangle_angles(tri.map(|p| p * scale));
                assert!(angles.iter().all(|a| (0.0..=PI).contains(a)), "{tri:?} x {scale}: {angles:?}");
                assert!((angles.iter().sum::<f64>() - PI).abs() < 1e-15, "{tri:?} x {scale}: {angles:?}");
            }
        }
    }

    #[test]
    fn concave_edges_are_negative() {
        // Two triangles folded upward along the x axis: a valley seen from +z.
        let p = vec![DVec3::ZERO, DVec3::X, DVec3::new(0.5, 1.0, 1.0), DVec3::new(0.5, -1.0, 1.0)];
        let m = TriMesh::new(p, vec![[0, 1, 2], [1, 0, 3]]).unwrap();
        let d = dihedral_angles(&m);
        let inner = m.connectivity().edges().iter().position(|e| e[0].0 == 0 && e[1].0 == 1).unwrap();
        assert!(d[inner] < 0.0);
    }

    #[test]
    fn degenerate_faces_give_zero_not_nan() {
        let p = vec![DVec3::ZERO, DVec3::X, DVec3::new(2.0, 0.0, 0.0)];
        let m = TriMesh::new(p, vec![[0, 1, 2]]).unwrap();
        assert_eq!(face_normals(&m)[0], DVec3::ZERO);
        assert!(vertex_normals(&m, NormalWeighting::Angle).iter().all(|n| *n == DVec3::ZERO));
        assert!(corner_angles(&m)[0].iter().all(|a| a.is_finite()));
    }
}
