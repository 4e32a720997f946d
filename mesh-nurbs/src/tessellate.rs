//! Tessellation of a NURBS surface into a watertight [`TriMesh`] with exact
//! per-vertex differential geometry.
//!
//! The surface is sampled on a tensor grid of parameters: uniform
//! ([`tessellate`]), adaptive to a chordal tolerance ([`tessellate_adaptive`])
//! or given by the caller ([`tessellate_parameters`]). Then:
//!
//! - sides that coincide (the seam of a sphere, torus or cylinder) are welded,
//!   and a side collapsed to one point (a sphere pole, a cone apex) becomes a
//!   single vertex with a fan of triangles, so no triangle is degenerate and
//!   closed surfaces are closed meshes (sphere: `chi = 2`; torus: `chi = 0`,
//!   no boundary);
//! - triangles are counter-clockwise around `s_u x s_v` (outward for the
//!   shapes of [`crate::shapes`]); each grid cell is split along its shorter
//!   diagonal;
//! - each vertex carries its parameter and the exact [`SurfaceFrame`]
//!   quantities. A welded vertex carries the parameter of its first
//!   occurrence (smallest `v`, then smallest `u`).

use glam::{DVec2, DVec3};
use mesh_kernel::TriMesh;

use crate::error::{NurbsError, Result};
use crate::frame::SurfaceFrame;
use crate::knots::KnotVector;
use crate::surface::{NurbsSurface, SpanBasis};

/// Default cap on the number of grid vertices (16.7 million, about 2.5 GB of
/// output): resolutions beyond it are refused with a typed error.
pub const DEFAULT_MAX_VERTICES: usize = 1 << 24;

/// A tessellated surface: the mesh and per-vertex exact geometry, every
/// vector indexed by vertex like `mesh.positions()`.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct Tessellation {
    /// The triangle mesh (positions `S(u, v)`).
    pub mesh: TriMesh,
    /// Parameter `(u, v)` of each vertex.
    pub uv: Vec<DVec2>,
    /// Exact unit normal `s_u x s_v / |s_u x s_v|`.
    pub normal: Vec<DVec3>,
    /// Exact Gaussian curvature (eq. 2.23).
    pub gaussian: Vec<f64>,
    /// Exact mean curvature (eq. 2.24, positive on a sphere with outward normal).
    pub mean: Vec<f64>,
    /// Largest principal curvature.
    pub k1: Vec<f64>,
    /// Smallest principal curvature.
    pub k2: Vec<f64>,
    /// Principal direction of `k1`.
    pub d1: Vec<DVec3>,
    /// Principal direction of `k2`.
    pub d2: Vec<DVec3>,
    /// `false` at degenerate points (poles, apexes), whose values are limits
    /// (see [`crate::frame`]).
    pub regular: Vec<bool>,
}

impl Tessellation {
    /// Names of the per-vertex scalar properties of [`Self::scalar_properties`],
    /// in order.
    pub const SCALAR_PROPERTIES: [&'static str; 6] = ["u", "v", "gaussian", "mean", "k1", "k2"];

    /// Per-vertex scalars by name (`u v gaussian mean k1 k2`), ready to be
    /// written as vertex properties (PLY and the like). Cost O(V), copies.
    pub fn scalar_properties(&self) -> Vec<(&'static str, Vec<f64>)> {
        let [u, v, gaussian, mean, k1, k2] = Self::SCALAR_PROPERTIES;
        vec![
            (u, self.uv.iter().map(|p| p.x).collect()),
            (v, self.uv.iter().map(|p| p.y).collect()),
            (gaussian, self.gaussian.clone()),
            (mean, self.mean.clone()),
            (k1, self.k1.clone()),
            (k2, self.k2.clone()),
        ]
    }
}

/// Options of the uniform grid tessellation [`tessellate`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GridOptions {
    /// Number of segments along `u` (>= 1; >= 3 along a closed direction).
    pub segments_u: usize,
    /// Number of segments along `v` (>= 1; >= 3 along a closed direction).
    pub segments_v: usize,
    /// Largest accepted number of grid vertices `(segments_u + 1)(segments_v + 1)`.
    pub max_vertices: usize,
}

impl Default for GridOptions {
    /// 64 x 64 segments.
    fn default() -> Self {
        Self { segments_u: 64, segments_v: 64, max_vertices: DEFAULT_MAX_VERTICES }
    }
}

/// Options of the adaptive tessellation [`tessellate_adaptive`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AdaptiveOptions {
    /// Largest distance between the mesh and the surface, in model units.
    pub chordal_tolerance: f64,
    /// Fewest segments per direction (>= 1; at least 3 are used along a
    /// closed direction).
    pub min_segments: usize,
    /// Most segments per direction; asking for more gives
    /// [`NurbsError::ToleranceUnreachable`].
    pub max_segments: usize,
    /// Largest accepted number of grid vertices.
    pub max_vertices: usize,
}

impl Default for AdaptiveOptions {
    /// Tolerance 1e-3, 4 to 4096 segments per direction.
    fn default() -> Self {
        Self { chordal_tolerance: 1e-3, min_segments: 4, max_segments: 4096, max_vertices: DEFAULT_MAX_VERTICES }
    }
}

/// Tessellates on a uniform `segments_u x segments_v` parameter grid.
/// Cost O(segments_u segments_v (p q + p^2 + q^2)), parallel with the `rayon`
/// feature.
///
/// # Errors
/// `NurbsError::InvalidOption` (`segments_u`, `segments_v`) for a segment count outside 1..2^32;
/// `NurbsError::Mesh` when the grid does not make a valid mesh.
pub fn tessellate(surface: &NurbsSurface, options: &GridOptions) -> Result<Tessellation> {
    let us = uniform(surface.domain_u(), options.segments_u, "segments_u")?;
    let vs = uniform(surface.domain_v(), options.segments_v, "segments_v")?;
    tessellate_parameters(surface, &us, &vs, options.max_vertices)
}

/// Tessellates on a tensor grid whose lines are placed by recursive bisection
/// of the knot spans until, along sampled iso-parameter lines, the surface
/// deviates from its chords by at most half the tolerance in each direction
/// (so cells deviate by about the tolerance at most). No T-junctions, so seams
/// and poles stay watertight. Cost O((segments_u + segments_v) s) evaluations
/// for the search (`s` sample lines: 4 per knot span of the other direction)
/// plus the grid.
///
/// # Errors
/// `NurbsError::InvalidOption` (`chordal_tolerance` not > 0, `min_segments`);
/// `NurbsError::ToleranceUnreachable` when the tolerance needs more than the allowed segments.
pub fn tessellate_adaptive(surface: &NurbsSurface, options: &AdaptiveOptions) -> Result<Tessellation> {
    let tol = options.chordal_tolerance;
    if !(tol.is_finite() && tol > 0.0) {
        return Err(NurbsError::InvalidOption { name: "chordal_tolerance", reason: format!("{tol} must be > 0") });
    }
    if options.min_segments == 0 || options.max_segments < options.min_segments {
        return Err(NurbsError::InvalidOption {
            name: "min_segments",
            reason: format!(
                "need 1 <= min_segments ({}) <= max_segments ({})",
                options.min_segments, options.max_segments
            ),
        });
    }
    let samples_u = sample_lines(surface.knots_u());
    let samples_v = sample_lines(surface.knots_v());
    let us = refine(surface, Direction::U, &samples_v, options)?;
    let vs = refine(surface, Direction::V, &samples_u, options)?;
    tessellate_parameters(surface, &us, &vs, options.max_vertices)
}

/// Tessellates on the tensor grid `us x vs` (each strictly increasing, finite,
/// at least two values, clamped into the domain), refusing grids of more than
/// `max_vertices` vertices. Cost as [`tessellate`].
///
/// # Errors
/// `NurbsError::InvalidOption` (`u`, `v`) for fewer than two parameter values or values that do not increase
/// strictly, (`segments`) when the grid gives no triangle; `NurbsError::NonFiniteParameter`;
/// `NurbsError::Mesh` when the grid does not make a valid mesh.
pub fn tessellate_parameters(
    surface: &NurbsSurface,
    us: &[f64],
    vs: &[f64],
    max_vertices: usize,
) -> Result<Tessellation> {
    check_parameters("u", us)?;
    check_parameters("v", vs)?;
    let count = us.len().checked_mul(vs.len()).filter(|&n| n <= max_vertices && n < u32::MAX as usize);
    if count.is_none() {
        return Err(NurbsError::InvalidOption {
            name: "max_vertices",
            reason: format!("a {} x {} grid exceeds {max_vertices} vertices", us.len(), vs.len()),
        });
    }
    let bu: Vec<SpanBasis<3>> = us.iter().map(|&u| SpanBasis::new(surface.knots_u(), u)).collect();
    let bv: Vec<SpanBasis<3>> = vs.iter().map(|&v| SpanBasis::new(surface.knots_v(), v)).collect();
    let grid = Grid::new(surface, &bu, &bv)?;
    let (ids, reps) = grid.vertices();
    let mut out = Attributes::new(reps.len());
    let uv = |i: usize, j: usize| DVec2::new(surface.knots_u().clamp(us[i]), surface.knots_v().clamp(vs[j]));
    fill(&mut out, &reps, |(i, j)| {
        SurfaceFrame::from_derivatives(surface, uv(i, j), surface.derivatives_with(&bu[i], &bv[j]))
    });
    let faces = grid.faces(&ids, &out.positions);
    if faces.is_empty() {
        return Err(NurbsError::InvalidOption { name: "segments", reason: "the grid gives no triangle".into() });
    }
    let mesh = TriMesh::new(out.positions, faces)?;
    let Attributes { uv, normal, gaussian, mean, k1, k2, d1, d2, regular, .. } = out;
    Ok(Tessellation { mesh, uv, normal, gaussian, mean, k1, k2, d1, d2, regular })
}

/// `segments + 1` equally spaced parameters over `domain`.
fn uniform((a, b): (f64, f64), segments: usize, name: &'static str) -> Result<Vec<f64>> {
    if segments == 0 || segments >= u32::MAX as usize {
        return Err(NurbsError::InvalidOption { name, reason: format!("{segments} is outside 1..{}", u32::MAX) });
    }
    let mut out: Vec<f64> = (0..segments).map(|k| a + (b - a) * (k as f64 / segments as f64)).collect();
    out.push(b);
    Ok(out)
}

fn check_parameters(name: &'static str, values: &[f64]) -> Result<()> {
    if values.len() < 2 {
        return Err(NurbsError::InvalidOption { name, reason: "need at least two parameter values".into() });
    }
    if let Some(&value) = values.iter().find(|t| !t.is_finite()) {
        return Err(NurbsError::NonFiniteParameter { name, value });
    }
    if values.windows(2).any(|w| w[0] >= w[1]) {
        return Err(NurbsError::InvalidOption { name, reason: "parameter values must increase strictly".into() });
    }
    Ok(())
}

/// Which side of the grid: `u = min`, `u = max`, `v = min`, `v = max`.
const U0: usize = 0;
const U1: usize = 1;
const V0: usize = 2;
const V1: usize = 3;

/// Grid topology: welded sides and collapsed sides (poles).
struct Grid {
    nu: usize,
    nv: usize,
    closed_u: bool,
    closed_v: bool,
    pole: [bool; 4],
}

impl Grid {
    /// Detects seams and poles by comparing the boundary samples to within
    /// 1e-9 of the control box diagonal.
    fn new(surface: &NurbsSurface, bu: &[SpanBasis<3>], bv: &[SpanBasis<3>]) -> Result<Self> {
        let (nu, nv) = (bu.len() - 1, bv.len() - 1);
        let tol = 1e-9 * surface.control_box_diagonal().max(f64::MIN_POSITIVE);
        let at = |i: usize, j: usize| surface.derivatives_with(&bu[i], &bv[j]).point;
        let same = |a: DVec3, b: DVec3| (a - b).length() <= tol;
        let closed_u = (0..=nv).all(|j| same(at(0, j), at(nu, j)));
        let closed_v = (0..=nu).all(|i| same(at(i, 0), at(i, nv)));
        let pole = [
            (0..=nv).all(|j| same(at(0, j), at(0, 0))),
            (0..=nv).all(|j| same(at(nu, j), at(nu, 0))),
            (0..=nu).all(|i| same(at(i, 0), at(0, 0))),
            (0..=nu).all(|i| same(at(i, nv), at(0, nv))),
        ];
        let grid = Self { nu, nv, closed_u, closed_v, pole };
        grid.check_resolution("segments_u", nu, closed_u, pole[U0] && pole[U1])?;
        grid.check_resolution("segments_v", nv, closed_v, pole[V0] && pole[V1])?;
        Ok(grid)
    }

    fn check_resolution(&self, name: &'static str, segments: usize, closed: bool, two_poles: bool) -> Result<()> {
        if closed && segments < 3 {
            return Err(NurbsError::InvalidOption {
                name,
                reason: format!("{segments} < 3 around a closed direction"),
            });
        }
        if two_poles && segments < 2 {
            return Err(NurbsError::InvalidOption { name, reason: "need 2 segments between two poles".into() });
        }
        Ok(())
    }

    /// The node a grid node is merged into (a fixpoint of the weld and pole
    /// rules; never later in row-major order).
    fn canonical(&self, mut i: usize, mut j: usize) -> (usize, usize) {
        loop {
            let before = (i, j);
            if self.closed_u && i == self.nu {
                i = 0;
            }
            if self.closed_v && j == self.nv {
                j = 0;
            }
            if (self.pole[V0] && j == 0) || (self.pole[V1] && j == self.nv) {
                i = 0;
            }
            if (self.pole[U0] && i == 0) || (self.pole[U1] && i == self.nu) {
                j = 0;
            }
            if (i, j) == before {
                return (i, j);
            }
        }
    }

    fn node(&self, i: usize, j: usize) -> usize {
        j * (self.nu + 1) + i
    }

    /// Vertex id of every node (row-major, `v` outer) and the node of every vertex.
    fn vertices(&self) -> (Vec<u32>, Vec<(usize, usize)>) {
        let mut ids = vec![0u32; (self.nu + 1) * (self.nv + 1)];
        let mut reps = Vec::new();
        for j in 0..=self.nv {
            for i in 0..=self.nu {
                let (ci, cj) = self.canonical(i, j);
                ids[self.node(i, j)] = if (ci, cj) == (i, j) {
                    reps.push((i, j));
                    (reps.len() - 1) as u32
                } else {
                    ids[self.node(ci, cj)]
                };
            }
        }
        (ids, reps)
    }

    /// Two counter-clockwise triangles per cell split along the shorter
    /// diagonal, dropping those that repeat a vertex (next to poles: fans).
    fn faces(&self, ids: &[u32], positions: &[DVec3]) -> Vec<[u32; 3]> {
        let mut faces = Vec::with_capacity(2 * self.nu * self.nv);
        for j in 0..self.nv {
            for i in 0..self.nu {
                let a = ids[self.node(i, j)];
                let b = ids[self.node(i + 1, j)];
                let c = ids[self.node(i + 1, j + 1)];
                let d = ids[self.node(i, j + 1)];
                let p = |k: u32| positions[k as usize];
                let tris = if p(a).distance_squared(p(c)) <= p(b).distance_squared(p(d)) {
                    [[a, b, c], [a, c, d]]
                } else {
                    [[a, b, d], [b, c, d]]
                };
                faces.extend(tris.into_iter().filter(|[x, y, z]| x != y && y != z && x != z));
            }
        }
        faces
    }
}

/// Per-vertex output arrays.
struct Attributes {
    positions: Vec<DVec3>,
    uv: Vec<DVec2>,
    normal: Vec<DVec3>,
    gaussian: Vec<f64>,
    mean: Vec<f64>,
    k1: Vec<f64>,
    k2: Vec<f64>,
    d1: Vec<DVec3>,
    d2: Vec<DVec3>,
    regular: Vec<bool>,
}

/// Mutable views of a range of [`Attributes`], so that ranges fill in parallel.
struct Slots<'a> {
    positions: &'a mut [DVec3],
    uv: &'a mut [DVec2],
    normal: &'a mut [DVec3],
    gaussian: &'a mut [f64],
    mean: &'a mut [f64],
    k1: &'a mut [f64],
    k2: &'a mut [f64],
    d1: &'a mut [DVec3],
    d2: &'a mut [DVec3],
    regular: &'a mut [bool],
}

impl Attributes {
    fn new(n: usize) -> Self {
        Self {
            positions: vec![DVec3::ZERO; n],
            uv: vec![DVec2::ZERO; n],
            normal: vec![DVec3::ZERO; n],
            gaussian: vec![0.0; n],
            mean: vec![0.0; n],
            k1: vec![0.0; n],
            k2: vec![0.0; n],
            d1: vec![DVec3::ZERO; n],
            d2: vec![DVec3::ZERO; n],
            regular: vec![false; n],
        }
    }

    fn slots(&mut self) -> Slots<'_> {
        Slots {
            positions: &mut self.positions,
            uv: &mut self.uv,
            normal: &mut self.normal,
            gaussian: &mut self.gaussian,
            mean: &mut self.mean,
            k1: &mut self.k1,
            k2: &mut self.k2,
            d1: &mut self.d1,
            d2: &mut self.d2,
            regular: &mut self.regular,
        }
    }
}

impl<'a> Slots<'a> {
    fn len(&self) -> usize {
        self.positions.len()
    }

    fn split_at(self, k: usize) -> (Slots<'a>, Slots<'a>) {
        let (positions, positions2) = self.positions.split_at_mut(k);
        let (uv, uv2) = self.uv.split_at_mut(k);
        let (normal, normal2) = self.normal.split_at_mut(k);
        let (gaussian, gaussian2) = self.gaussian.split_at_mut(k);
        let (mean, mean2) = self.mean.split_at_mut(k);
        let (k1, k12) = self.k1.split_at_mut(k);
        let (k2, k22) = self.k2.split_at_mut(k);
        let (d1, d12) = self.d1.split_at_mut(k);
        let (d2, d22) = self.d2.split_at_mut(k);
        let (regular, regular2) = self.regular.split_at_mut(k);
        (
            Slots { positions, uv, normal, gaussian, mean, k1, k2, d1, d2, regular },
            Slots {
                positions: positions2,
                uv: uv2,
                normal: normal2,
                gaussian: gaussian2,
                mean: mean2,
                k1: k12,
                k2: k22,
                d1: d12,
                d2: d22,
                regular: regular2,
            },
        )
    }

    fn write(&mut self, k: usize, f: &SurfaceFrame) {
        self.positions[k] = f.point();
        self.uv[k] = f.uv;
        self.normal[k] = f.normal;
        self.gaussian[k] = f.gaussian;
        self.mean[k] = f.mean;
        self.k1[k] = f.k1;
        self.k2[k] = f.k2;
        self.d1[k] = f.d1;
        self.d2[k] = f.d2;
        self.regular[k] = f.regular;
    }
}

/// Evaluates `frame` for every vertex node into `out`, in parallel chunks with
/// the `rayon` feature.
fn fill(out: &mut Attributes, reps: &[(usize, usize)], frame: impl Fn((usize, usize)) -> SurfaceFrame + Sync) {
    const CHUNK: usize = 4096;
    let mut chunks = Vec::new();
    let mut rest = out.slots();
    let mut start = 0;
    while rest.len() > CHUNK {
        let (head, tail) = rest.split_at(CHUNK);
        chunks.push((start, head));
        start += CHUNK;
        rest = tail;
    }
    chunks.push((start, rest));
    let work = |(start, mut slots): (usize, Slots<'_>)| {
        for k in 0..slots.len() {
            slots.write(k, &frame(reps[start + k]));
        }
    };
    #[cfg(feature = "rayon")]
    {
        use rayon::prelude::*;
        chunks.into_par_iter().for_each(work);
    }
    #[cfg(not(feature = "rayon"))]
    chunks.into_iter().for_each(work);
}

/// Parameter direction of a grid line family.
#[derive(Clone, Copy)]
enum Direction {
    U,
    V,
}

/// Sample lines of the other direction for the chordal search: each knot
/// span cut in four.
fn sample_lines(kv: &KnotVector) -> Vec<f64> {
    let bp = kv.breakpoints();
    let mut out = vec![bp[0]];
    for w in bp.windows(2) {
        out.extend((1..=4).map(|k| w[0] + (w[1] - w[0]) * (k as f64 / 4.0)));
    }
    out
}

/// Adaptive parameter values along `dir`: knot spans cut uniformly to reach
/// `min_segments`, then bisected while the chordal deviation exceeds half the
/// tolerance.
fn refine(surface: &NurbsSurface, dir: Direction, others: &[f64], options: &AdaptiveOptions) -> Result<Vec<f64>> {
    let (kv, name) = match dir {
        Direction::U => (surface.knots_u(), "u"),
        Direction::V => (surface.knots_v(), "v"),
    };
    let bp = kv.breakpoints();
    let per_span = options.min_segments.div_ceil(bp.len() - 1).max(1);
    let at = |t: f64, s: f64| match dir {
        Direction::U => surface.derivatives_at::<1>(t, s).point,
        Direction::V => surface.derivatives_at::<1>(s, t).point,
    };
    let deviation = |a: f64, b: f64| {
        let mut worst: f64 = 0.0;
        for &s in others {
            let (pa, pb) = (at(a, s), at(b, s));
            for f in [0.25, 0.5, 0.75] {
                worst = worst.max((at(a + (b - a) * f, s) - pa.lerp(pb, f)).length());
            }
        }
        worst
    };
    let half = 0.5 * options.chordal_tolerance;
    let too_many = || NurbsError::ToleranceUnreachable {
        tolerance: options.chordal_tolerance,
        max_segments: options.max_segments,
        direction: name,
    };
    let mut out = vec![bp[0]];
    // Work list of intervals still to examine, in decreasing order so that
    // `pop` yields them left to right.
    let mut todo: Vec<(f64, f64)> = Vec::new();
    for w in bp.windows(2).rev() {
        for k in (0..per_span).rev() {
            let a = w[0] + (w[1] - w[0]) * (k as f64 / per_span as f64);
            let b = if k + 1 == per_span { w[1] } else { w[0] + (w[1] - w[0]) * ((k + 1) as f64 / per_span as f64) };
            todo.push((a, b));
        }
    }
    while let Some((a, b)) = todo.pop() {
        let mid = 0.5 * (a + b);
        if deviation(a, b) > half && mid > a && mid < b {
            todo.push((mid, b));
            todo.push((a, mid));
        } else {
            out.push(b);
        }
        if out.len() + todo.len() > options.max_segments + 1 {
            return Err(too_many());
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes;

    #[test]
    fn guards_resolutions() {
        let s = shapes::sphere(DVec3::ZERO, 1.0).unwrap();
        let bad =
            |u: usize, v: usize| tessellate(&s, &GridOptions { segments_u: u, segments_v: v, ..Default::default() });
        assert!(matches!(bad(0, 8), Err(NurbsError::InvalidOption { .. })));
        assert!(matches!(bad(8, 0), Err(NurbsError::InvalidOption { .. })));
        assert!(matches!(bad(2, 8), Err(NurbsError::InvalidOption { .. })));
        assert!(matches!(bad(8, 1), Err(NurbsError::InvalidOption { .. })));
        assert!(matches!(bad(usize::MAX, usize::MAX), Err(NurbsError::InvalidOption { .. })));
        assert!(matches!(bad(1 << 20, 1 << 20), Err(NurbsError::InvalidOption { .. })));
        assert!(bad(3, 2).is_ok());
        let adaptive =
            |t: f64| tessellate_adaptive(&s, &AdaptiveOptions { chordal_tolerance: t, ..Default::default() });
        assert!(matches!(adaptive(0.0), Err(NurbsError::InvalidOption { .. })));
        assert!(matches!(adaptive(f64::NAN), Err(NurbsError::InvalidOption { .. })));
        assert!(matches!(adaptive(1e-300), Err(NurbsError::ToleranceUnreachable { .. })));
        assert!(tessellate_parameters(&s, &[0.0, 0.5, 0.5, 1.0], &[0.0, 1.0], 100).is_err());
        assert!(tessellate_parameters(&s, &[0.0], &[0.0, 1.0], 100).is_err());
    }

    #[test]
    fn octahedron_like_minimal_sphere() {
        let s = shapes::sphere(DVec3::ZERO, 1.0).unwrap();
        let t = tessellate(&s, &GridOptions { segments_u: 4, segments_v: 2, ..Default::default() }).unwrap();
        assert_eq!(t.mesh.vertex_count(), 6);
        assert_eq!(t.mesh.face_count(), 8);
        assert_eq!(t.mesh.connectivity().euler_characteristic(), 2);
    }
}
