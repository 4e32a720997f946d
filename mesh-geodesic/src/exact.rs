//! Exact polyhedral geodesic distances by window propagation.
//!
//! A *window* is an interval of a mesh edge together with the position,
//! unfolded into the plane of the edge's two faces, of the point it is seen
//! from (the source or a pseudo-source vertex) and that point's distance
//! `sigma` (Mitchell, Mount and Papadimitriou 1987; the planar window
//! geometry of Surazhsky, Surazhsky, Kirsanov, Gortler and Hoppe 2005).
//! Windows are propagated across faces in order of their smallest distance;
//! a geodesic can only bend at a vertex whose total angle exceeds 2 pi
//! (saddles) or that lies on the boundary, and such vertices become
//! pseudo-sources that emit windows in every direction.
//!
//! Instead of MMP's exact trimming of overlapping windows, a window is
//! dropped when the vertex distances already found prove it useless: a
//! window on edge UV is useless if `d(U) + |U P| < sigma + |s P|` at its end
//! P farthest from U (or the same with V), because every geodesic through
//! it is then beaten by the path through U along the edge (the filter of
//! Xin and Wang 2009, "improved Chen and Han", which VTP, Qin et al. 2016,
//! builds on). Rays of a window that cross the ray by which an earlier
//! window on the same edge reached the face's apex more shortly are cut
//! (Chen and Han 1990, "one angle, one split"). All tests are
//! conservative, so the result is the exact polyhedral distance up to
//! rounding. Worst case O(V^2 log V) time;
//! bounded by [`ExactOptions::max_windows`].

use std::cmp::Ordering;
use std::collections::BinaryHeap;
use std::f64::consts::PI;

use mesh_kernel::glam::DVec2;
use mesh_kernel::{Connectivity, HalfedgeId, TriMesh, VertexId, VertexKind};

use crate::error::{GeodesicError, Result};
use crate::support::{validate_sources, HeapEntry};

/// Options of [`exact_distance`].
#[derive(Debug, Clone, PartialEq)]
pub struct ExactOptions {
    /// The work bound: at most this many windows are created; past it the
    /// call fails with [`GeodesicError::WorkLimit`] instead of running on.
    /// Each window costs about 60 bytes while queued. Default 20 million.
    pub max_windows: usize,
}

impl Default for ExactOptions {
    fn default() -> Self {
        Self { max_windows: 20_000_000 }
    }
}

/// Relative margin by which a window must be beaten before it is dropped:
/// ties (and rounding noise) keep the window.
const PRUNE_MARGIN: f64 = 1e-12;

/// Relative height below which a triangle is treated as having no area.
const DEGENERATE: f64 = 1e-12;

/// Exact geodesic distance (along the polyhedral surface) from the nearest
/// source to every vertex, by window propagation (Mitchell, Mount and
/// Papadimitriou 1987; Surazhsky et al. 2005) with the vertex-distance
/// filter of Xin and Wang 2009. `+infinity` where no source is reachable.
///
/// Needs an oriented 2-manifold ([`mesh_kernel::MeshError::NonManifold`]
/// otherwise) without zero-area triangles ([`GeodesicError::Degenerate`]).
/// Cost: about V^1.6 windows on the icospheres (measured), worst case
/// O(V^2 log V) time; at most
/// [`ExactOptions::max_windows`] windows, then [`GeodesicError::WorkLimit`].
///
/// ```
/// use mesh_kernel::{shapes, VertexId};
/// use mesh_geodesic::{exact_distance, ExactOptions};
///
/// // A flat grid: geodesics are straight lines.
/// let grid = shapes::grid(2.0, 1.0, 8, 4)?;
/// let d = exact_distance(&grid, &[VertexId(0)], &ExactOptions::default())?;
/// let p0 = grid.position(VertexId(0));
/// for (i, p) in grid.positions().iter().enumerate() {
///     assert!((d[i] - p.distance(p0)).abs() < 1e-12);
/// }
/// # Ok::<(), mesh_geodesic::GeodesicError>(())
/// ```
///
/// # Errors
/// `GeodesicError::NoSources` / `GeodesicError::SourceOutOfRange` for bad sources; `GeodesicError::Mesh`
/// (`MeshError::NonManifold`) when the mesh is not an oriented manifold, or (`MeshError::Degenerate`) for
/// degenerate geometry; `GeodesicError::WorkLimit` past `ExactOptions::max_windows` windows.
pub fn exact_distance(mesh: &TriMesh, sources: &[VertexId], options: &ExactOptions) -> Result<Vec<f64>> {
    validate_sources(mesh, sources)?;
    // Unfoldings square lengths: work in a unit where nothing overflows.
    let (mesh, unit) = mesh_kernel::units::normalized(mesh);
    let conn = mesh.manifold_connectivity()?;
    let geometry = Geometry::new(&mesh)?;
    let mut state = Propagation::new(conn, &geometry, options.max_windows);
    for &s in sources {
        state.set_source(s);
    }
    state.run()?;
    Ok(state.distance.iter().map(|d| d * unit).collect())
}

/// Per half-edge layout: half-edge `h` runs from A = (0, 0) to B = (len, 0)
/// and its face's third corner C lies at `apex`, above the axis.
struct Geometry {
    len: Vec<f64>,
    apex: Vec<DVec2>,
    /// Vertices a geodesic may bend around: total angle above 2 pi (beyond
    /// rounding) or on the boundary. Geodesics also pass straight through
    /// flat vertices; the windows on both sides of such a vertex cover that
    /// line, so flat vertices need not emit windows.
    pseudo_source: Vec<bool>,
}

impl Geometry {
    /// Lays out every face from its edge lengths; O(F).
    fn new(mesh: &TriMesh) -> Result<Self> {
        let p = mesh.positions();
        let conn = mesh.connectivity();
        let nh = 3 * mesh.face_count();
        let mut len = vec![0.0; nh];
        let mut apex = vec![DVec2::ZERO; nh];
        let mut angle = vec![0.0; mesh.vertex_count()];
        for (f, face) in mesh.faces().iter().enumerate() {
            for k in 0..3 {
                let (a, b, c) = (p[face[k] as usize], p[face[(k + 1) % 3] as usize], p[face[(k + 2) % 3] as usize]);
                let (l, ac, bc) = (a.distance(b), a.distance(c), b.distance(c));
                let DVec2 { x, y } = mesh_kernel::geometry::planar_apex(l, ac, bc);
                if !(y > DEGENERATE * l.max(ac).max(bc)) || !x.is_finite() {
                    return Err(GeodesicError::Degenerate(format!(
                        "face {f} has no area; exact geodesics need proper triangles \
                         (the heat method with the intrinsic Delaunay Laplacian handles them)"
                    )));
                }
                len[3 * f + k] = l;
                apex[3 * f + k] = DVec2::new(x, y);
                angle[face[k] as usize] += y.atan2(x);
            }
        }
        let pseudo_source = (0..mesh.vertex_count())
            .map(|v| match conn.vertex_kind(VertexId::new(v)) {
                VertexKind::Interior => angle[v] > 2.0 * PI * (1.0 + 1e-12),
                _ => true,
            })
            .collect();
        Ok(Self { len, apex, pseudo_source })
    }
}

/// A window on half-edge `h`, in the layout of [`Geometry`]: the interval
/// `[b0, b1]` of the edge, seen from `source` (below the axis) at distance
/// `sigma`; `key` is its smallest distance.
#[derive(Debug, Clone, Copy)]
struct Window {
    key: f64,
    h: u32,
    b0: f64,
    b1: f64,
    source: DVec2,
    sigma: f64,
}

impl PartialEq for Window {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}

impl Eq for Window {}

impl PartialOrd for Window {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Window {
    /// Reversed, so that `BinaryHeap` pops the nearest window first.
    fn cmp(&self, other: &Self) -> Ordering {
        other.key.total_cmp(&self.key).then_with(|| other.h.cmp(&self.h))
    }
}

/// The state of one propagation: vertex distances and the two queues.
struct Propagation<'a> {
    conn: &'a Connectivity,
    geo: &'a Geometry,
    distance: Vec<f64>,
    windows: BinaryHeap<Window>,
    vertices: BinaryHeap<HeapEntry>,
    /// Per half-edge: the shortest distance to the apex C found by a window
    /// on it, and where that window's ray to C crosses the edge.
    through_apex: Vec<(f64, f64)>,
    created: usize,
    max_windows: usize,
}

impl<'a> Propagation<'a> {
    fn new(conn: &'a Connectivity, geo: &'a Geometry, max_windows: usize) -> Self {
        Self {
            conn,
            geo,
            distance: vec![f64::INFINITY; conn.vertex_count()],
            windows: BinaryHeap::new(),
            vertices: BinaryHeap::new(),
            through_apex: vec![(f64::INFINITY, 0.0); geo.len.len()],
            created: 0,
            max_windows,
        }
    }

    fn set_source(&mut self, s: VertexId) {
        if self.distance[s.idx()] > 0.0 {
            self.distance[s.idx()] = 0.0;
            self.vertices.push(HeapEntry { distance: 0.0, vertex: s.0 });
        }
    }

    /// Pops windows and pseudo-source vertices nearest first until both
    /// queues are empty or the work bound is hit.
    fn run(&mut self) -> Result<()> {
        loop {
            let next_window = self.windows.peek().map_or(f64::INFINITY, |w| w.key);
            let next_vertex = self.vertices.peek().map_or(f64::INFINITY, |e| e.distance);
            if next_window.is_infinite() && next_vertex.is_infinite() {
                return Ok(());
            }
            if next_vertex <= next_window {
                if let Some(e) = self.vertices.pop() {
                    self.emit_from_vertex(VertexId(e.vertex), e.distance)?;
                }
            } else if let Some(w) = self.windows.pop() {
                if !self.useless(&w) {
                    self.propagate(&w)?;
                }
            }
        }
    }

    /// Lowers the distance of `v` to `d` if smaller; a pseudo-source whose
    /// distance drops is queued to emit windows.
    fn offer(&mut self, v: VertexId, d: f64) {
        if d < self.distance[v.idx()] {
            self.distance[v.idx()] = d;
            if self.geo.pseudo_source[v.idx()] {
                self.vertices.push(HeapEntry { distance: d, vertex: v.0 });
            }
        }
    }

    /// A source or pseudo-source `v` at distance `d` sends one window across
    /// the far edge of each of its faces (sources always; pseudo-sources
    /// only when `d` is still their distance).
    fn emit_from_vertex(&mut self, v: VertexId, d: f64) -> Result<()> {
        if d > self.distance[v.idx()] {
            return Ok(()); // stale
        }
        for &h in self.conn.outgoing(v) {
            // The far edge P -> Q of the face, with v at its apex; seen from
            // the other side (frame Q -> P), v lies below at (len - x, -y).
            let e = h.next();
            let (len, apex) = (self.geo.len[e.idx()], self.geo.apex[e.idx()]);
            self.emit(e, DVec2::new(len - apex.x, -apex.y), d, 0.0, len)?;
        }
        Ok(())
    }

    /// Creates the window `[t0, t1]` with `source`, `sigma` on the twin of
    /// `e` (in the twin's frame: from `dest(e)` at 0 to `origin(e)` at
    /// `len`). Its ends give upper bounds to the edge's vertices; it is
    /// queued if the edge is interior, it is not empty and not useless.
    fn emit(&mut self, e: HalfedgeId, source: DVec2, sigma: f64, t0: f64, t1: f64) -> Result<()> {
        let len = self.geo.len[e.idx()];
        let (t0, t1) = (t0.clamp(0.0, len), t1.clamp(0.0, len));
        let (q0, q1) = (DVec2::new(t0, 0.0), DVec2::new(t1, 0.0));
        let (d0, d1) = (sigma + source.distance(q0), sigma + source.distance(q1));
        self.offer(self.conn.dest(e), d0 + t0);
        self.offer(self.conn.origin(e), d1 + (len - t1));
        let Some(twin) = self.conn.twin(e) else { return Ok(()) };
        if !(t1 > t0) || !(source.y < 0.0) {
            return Ok(()); // empty, or grazing along the edge
        }
        let nearest = if source.x < t0 {
            d0
        } else if source.x > t1 {
            d1
        } else {
            sigma - source.y
        };
        let w = Window { key: nearest, h: twin.0, b0: t0, b1: t1, source, sigma };
        if self.useless(&w) {
            return Ok(());
        }
        self.created += 1;
        if self.created > self.max_windows {
            return Err(GeodesicError::WorkLimit { what: "exact geodesic windows", limit: self.max_windows });
        }
        self.windows.push(w);
        Ok(())
    }

    /// The filter: every point of `w` is reached more shortly along the edge
    /// from one of its end vertices.
    fn useless(&self, w: &Window) -> bool {
        let h = HalfedgeId(w.h);
        let len = self.geo.len[h.idx()];
        let at = |b: f64| w.sigma + w.source.distance(DVec2::new(b, 0.0));
        let (far_from_a, far_from_b) = (at(w.b1), at(w.b0));
        let da = self.distance[self.conn.origin(h).idx()];
        let db = self.distance[self.conn.dest(h).idx()];
        da + w.b1 < far_from_a * (1.0 - PRUNE_MARGIN) || db + (len - w.b0) < far_from_b * (1.0 - PRUNE_MARGIN)
    }

    /// Carries `w` across its face A B C: the rays from the source through
    /// the window's ends leave through A C, C B or both (split at C, which
    /// then gets its distance). If an earlier window on the same edge
    /// reached C more shortly, along the segment from `(x*, 0)` to C, the
    /// rays of `w` that cross that segment are dropped ("one angle, one
    /// split", Chen and Han 1990): where they cross, the other path is no
    /// longer, so theirs cannot be shortest beyond.
    fn propagate(&mut self, w: &Window) -> Result<()> {
        let h = HalfedgeId(w.h);
        let (len, c, s) = (self.geo.len[h.idx()], self.geo.apex[h.idx()], w.source);
        let (a, b) = (DVec2::ZERO, DVec2::new(len, 0.0));
        let (p0, p1) = (DVec2::new(w.b0, 0.0), DVec2::new(w.b1, 0.0));
        // Where the ray from the source through C crosses the edge line, and
        // the (possibly virtual) distance to C along it.
        let xc = s.x + (c.x - s.x) * (-s.y) / (c.y - s.y);
        let to_c = w.sigma + s.distance(c);
        let (best, best_x) = self.through_apex[h.idx()];
        let cut = (best < to_c * (1.0 - PRUNE_MARGIN)).then_some(best_x);
        if xc > w.b0 && xc < w.b1 {
            self.offer(self.conn.opposite_vertex(h), to_c);
            if to_c < best {
                self.through_apex[h.idx()] = (to_c, xc);
            }
        }
        let (ac, cb) = (h.prev(), h.next()); // half-edges C -> A and B -> C
        if xc > w.b0 {
            // Rays left of C, through [b0, min(xc, b1)]; beaten right of x*.
            let (end, end_point) = if xc < w.b1 { (xc, c) } else { (w.b1, p1) };
            match cut {
                Some(x) if x < end => {
                    if x > w.b0 {
                        self.cross(ac, [a, c], w, p0, DVec2::new(x, 0.0))?;
                    }
                }
                _ => self.cross(ac, [a, c], w, p0, end_point)?,
            }
        }
        if xc < w.b1 {
            // Rays right of C, through [max(xc, b0), b1]; beaten left of x*.
            let (start, start_point) = if xc > w.b0 { (xc, c) } else { (w.b0, p0) };
            match cut {
                Some(x) if x > start => {
                    if x < w.b1 {
                        self.cross(cb, [c, b], w, DVec2::new(x, 0.0), p1)?;
                    }
                }
                _ => self.cross(cb, [c, b], w, start_point, p1)?,
            }
        }
        Ok(())
    }

    /// Emits the part of the cone of rays from the source through `q0` and
    /// `q1` that crosses the face's edge `e` (`ends` = its twin's start and
    /// end, in the face's frame).
    fn cross(&mut self, e: HalfedgeId, ends: [DVec2; 2], w: &Window, q0: DVec2, q1: DVec2) -> Result<()> {
        let len = self.geo.len[e.idx()];
        let u = (ends[1] - ends[0]) / len;
        let n = DVec2::new(-u.y, u.x);
        let local = |p: DVec2| DVec2::new((p - ends[0]).dot(u), (p - ends[0]).dot(n));
        let s = local(w.source);
        let hit = |q: DVec2| {
            let q = local(q);
            if q.y.abs() < 1e-300 || q.y - s.y <= 0.0 {
                q.x // on the edge line already (the apex), or parallel
            } else {
                s.x + (q.x - s.x) * (-s.y) / (q.y - s.y)
            }
        };
        let (x0, x1) = (hit(q0), hit(q1));
        self.emit(e, DVec2::new(s.x, s.y.min(0.0)), w.sigma, x0.min(x1), x0.max(x1))
    }
}
