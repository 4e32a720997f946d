//! Geodesic paths by integrating the gradient flow dC/dt = -grad U
//! (eq. 2.35) of a distance field U back to the sources.
//!
//! U is taken piecewise linear over the triangles, with its (constant)
//! gradient in each face. Following that field alone zigzags: wherever the
//! face gradients on both sides of an edge point into it, the flow is
//! trapped on the edge. The tracer therefore follows the continuous field
//! obtained by averaging the face gradients at the vertices (area-weighted)
//! and interpolating them linearly in each face, projected into the face,
//! in short explicit steps in barycentric coordinates; any step that would
//! not descend the piecewise-linear U falls back to the face's own gradient,
//! so U decreases strictly along the path. Where both neighbours still push
//! into an edge it follows the edge downhill; at a vertex it leaves through
//! the face the field points into, or along the steepest descending edge. Where nothing descends (a local
//! minimum of an approximate field away from the sources), and after a
//! bounded number of steps, it finishes along the shortest edge path of
//! [`crate::dijkstra()`], so it terminates on every input.

use mesh_kernel::glam::DVec3;
use mesh_kernel::{FaceId, HalfedgeId, TriMesh, VertexId};

use crate::dijkstra::{dijkstra, DijkstraOptions};
use crate::error::{GeodesicError, Result};
use crate::support::validate_length;

/// A point on the surface: a face and barycentric coordinates with respect
/// to its three corners (non-negative, summing to one).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfacePoint {
    /// The face holding the point.
    pub face: FaceId,
    /// Weights of the face's corners, in the order of [`TriMesh::face`].
    pub bary: [f64; 3],
}

impl SurfacePoint {
    /// A validated surface point: the face must exist and the coordinates be
    /// finite, at least -1e-9 and sum to 1 within 1e-9 (they are clamped
    /// and renormalized).
    ///
    /// # Errors
    /// `GeodesicError::InvalidSurfacePoint` when `face` is not a face of the mesh or `bary` is not a convex
    /// combination (finite, non-negative, summing to 1).
    pub fn new(mesh: &TriMesh, face: FaceId, bary: [f64; 3]) -> Result<Self> {
        let bad = |reason: String| GeodesicError::InvalidSurfacePoint { face, reason };
        if face.idx() >= mesh.face_count() {
            return Err(bad(format!("the mesh has {} faces", mesh.face_count())));
        }
        let sum: f64 = bary.iter().sum();
        if bary.iter().any(|b| !b.is_finite() || *b < -1e-9) || !((sum - 1.0).abs() <= 1e-9) {
            return Err(bad(format!("barycentric coordinates {bary:?} are not a convex combination")));
        }
        let clamped = bary.map(|b| b.max(0.0));
        let total: f64 = clamped.iter().sum();
        Ok(Self { face, bary: clamped.map(|b| b / total) })
    }

    /// The point at vertex `v`, in the first face around it; `None` for an
    /// out-of-range or isolated vertex.
    pub fn at_vertex(mesh: &TriMesh, v: VertexId) -> Option<Self> {
        if v.idx() >= mesh.vertex_count() {
            return None;
        }
        let h = *mesh.connectivity().outgoing(v).first()?;
        let mut bary = [0.0; 3];
        bary[h.corner()] = 1.0;
        Some(Self { face: h.face(), bary })
    }

    /// The 3D position: the barycentric combination of the face's corners.
    pub fn position(&self, mesh: &TriMesh) -> DVec3 {
        let t = mesh.triangle(self.face);
        self.bary[0] * t[0] + self.bary[1] * t[1] + self.bary[2] * t[2]
    }

    /// The corner this point sits on, if one coordinate is 1.
    fn corner(&self) -> Option<usize> {
        self.bary.iter().position(|b| *b >= 1.0 - SNAP)
    }
}

/// Options of [`trace_path`].
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TraceOptions {
    /// Largest number of faces and vertices the flow may visit before the
    /// path is finished along edges; 0 means 4 (V + F) + 64.
    pub max_steps: usize,
}

/// A path on the surface, from its start to a source.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct GeodesicPath {
    /// The polyline's points (start first, the source last).
    pub points: Vec<SurfacePoint>,
    /// Their 3D positions.
    pub positions: Vec<DVec3>,
    /// Length of the polyline.
    pub length: f64,
    /// The source reached.
    pub source: VertexId,
    /// How many of the segments follow the edge-path fallback (0 when the
    /// gradient flow reached the source by itself).
    pub fallback_edges: usize,
}

/// Coordinates this close to 0 or 1 snap to the edge or vertex.
const SNAP: f64 = 1e-9;

/// Largest change of a barycentric coordinate in one step inside a face.
const MAX_STEP: f64 = 0.25;

/// A face's unit normal and the gradients of its hat functions,
/// grad(phi_k) = n x (edge opposite k) / |n|^2 with n = (b - a) x (c - a).
struct Frame {
    normal: DVec3,
    hat_gradients: [DVec3; 3],
    area2: f64,
}

impl Frame {
    /// `None` for a face of (relatively) zero area.
    fn new(mesh: &TriMesh, f: FaceId) -> Option<Self> {
        let p = mesh.triangle(f);
        let n = (p[1] - p[0]).cross(p[2] - p[0]);
        let area2 = n.length();
        let longest = (0..3).map(|k| p[k].distance_squared(p[(k + 1) % 3])).fold(0.0, f64::max);
        if !(area2 > 1e-12 * longest) {
            return None;
        }
        let hat_gradients = [0, 1, 2].map(|k| n.cross(p[(k + 2) % 3] - p[(k + 1) % 3]) / (area2 * area2));
        Some(Self { normal: n / area2, hat_gradients, area2 })
    }

    /// Gradient of the linear function with corner values `u`.
    fn gradient(&self, u: [f64; 3]) -> DVec3 {
        (0..3).map(|k| u[k] * self.hat_gradients[k]).sum()
    }

    /// Rates of change of the barycentric coordinates moving along `d`.
    fn rates(&self, d: DVec3) -> Option<[f64; 3]> {
        let rates = self.hat_gradients.map(|g| g.dot(d));
        let scale = rates.iter().fold(0.0f64, |m, r| m.max(r.abs()));
        (scale > 0.0 && scale.is_finite()).then_some(rates)
    }
}

/// Traces the gradient flow dC/dt = -grad U (eq. 2.35) of the per-vertex
/// distance `distance` (from [`crate::fmm_distance`], the heat method, ...)
/// from `from` back to the nearest of `sources`, face by face. Terminates on
/// every input: at most [`TraceOptions::max_steps`] faces and vertices are
/// visited, and where the flow finds no descent the path is finished along
/// the shortest edge path. Cost O(length of the path in faces), plus one
/// Dijkstra when the fallback is needed.
///
/// Errors: a field of the wrong length or with NaN, no or out-of-range
/// sources, an invalid start, or a start not connected to any source.
///
/// ```
/// use mesh_kernel::{shapes, VertexId};
/// use mesh_geodesic::{fmm_distance, trace_path, FmmOptions, SurfacePoint, TraceOptions};
///
/// let sphere = shapes::icosphere(4)?;
/// let d = fmm_distance(&sphere, &[VertexId(0)], &FmmOptions::default())?;
/// let start = SurfacePoint::at_vertex(&sphere, VertexId(500)).unwrap();
/// let path = trace_path(&sphere, &d, &[VertexId(0)], start, &TraceOptions::default())?;
/// assert_eq!(path.source, VertexId(0));
/// assert!((path.length - d[500]).abs() < 0.01 * d[500]);
/// # Ok::<(), mesh_geodesic::GeodesicError>(())
/// ```
///
/// # Errors
/// `GeodesicError::FieldLength` when `distance` does not have one value per vertex;
/// `GeodesicError::NoSources` / `GeodesicError::SourceOutOfRange` for bad sources;
/// `GeodesicError::InvalidOption` (`distance`) when the field holds NaN; `GeodesicError::InvalidSurfacePoint`
/// for a bad start point; `GeodesicError::Unreachable` when the start is in a component without a source.
pub fn trace_path(
    mesh: &TriMesh,
    distance: &[f64],
    sources: &[VertexId],
    from: SurfacePoint,
    options: &TraceOptions,
) -> Result<GeodesicPath> {
    validate_length("distance", mesh.vertex_count(), distance.len())?;
    crate::support::validate_sources(mesh, sources)?;
    if distance.iter().any(|d| d.is_nan()) {
        return Err(GeodesicError::InvalidOption { name: "distance", reason: "the field holds NaN".into() });
    }
    let from = SurfacePoint::new(mesh, from.face, from.bary)?;
    let corners = mesh.face(from.face);
    if corners.iter().zip(from.bary).any(|(v, b)| b > 0.0 && !distance[v.idx()].is_finite()) {
        return Err(GeodesicError::Unreachable);
    }
    let max_steps = match options.max_steps {
        0 => 4 * (mesh.vertex_count() + mesh.face_count()) + 64,
        m => m,
    };
    // Gradients divide by areas: trace in a unit where none over- or underflows.
    let (mesh, unit) = mesh_kernel::units::normalized(mesh);
    if unit == 1.0 {
        return Tracer::new(&mesh, distance, sources).run(from, max_steps);
    }
    let distance: Vec<f64> = distance.iter().map(|d| d / unit).collect();
    let mut path = Tracer::new(&mesh, &distance, sources).run(from, max_steps)?;
    path.positions.iter_mut().for_each(|p| *p *= unit);
    path.length *= unit;
    Ok(path)
}

/// The flow's state between steps.
#[derive(Debug, Clone, Copy)]
enum At {
    /// Inside a face, or on its boundary about to enter it (`true` when it
    /// has just crossed that edge).
    Face(SurfacePoint, bool),
    /// At a vertex.
    Vertex(VertexId),
    /// Done, at this source.
    Source(VertexId),
    /// No descent from this vertex: finish along edges.
    Stuck(VertexId),
}

struct Tracer<'a> {
    mesh: &'a TriMesh,
    u: &'a [f64],
    /// Area-weighted mean of the face gradients around each vertex.
    vertex_gradient: Vec<DVec3>,
    is_source: Vec<bool>,
    sources: &'a [VertexId],
    path: GeodesicPath,
}

impl<'a> Tracer<'a> {
    fn new(mesh: &'a TriMesh, u: &'a [f64], sources: &'a [VertexId]) -> Self {
        let mut is_source = vec![false; mesh.vertex_count()];
        for s in sources {
            is_source[s.idx()] = true;
        }
        let path = GeodesicPath {
            points: Vec::new(),
            positions: Vec::new(),
            length: 0.0,
            source: VertexId::INVALID,
            fallback_edges: 0,
        };
        let mut vertex_gradient = vec![DVec3::ZERO; mesh.vertex_count()];
        let mut weight = vec![0.0; mesh.vertex_count()];
        for f in mesh.face_ids() {
            let Some(frame) = Frame::new(mesh, f) else { continue };
            let corners = mesh.face(f);
            if corners.iter().any(|v| !u[v.idx()].is_finite()) {
                continue;
            }
            let g = frame.gradient(corners.map(|v| u[v.idx()]));
            for v in corners {
                vertex_gradient[v.idx()] += frame.area2 * g;
                weight[v.idx()] += frame.area2;
            }
        }
        for (g, w) in vertex_gradient.iter_mut().zip(&weight) {
            if *w > 0.0 {
                *g /= *w;
            }
        }
        Self { mesh, u, vertex_gradient, is_source, sources, path }
    }

    fn run(mut self, from: SurfacePoint, max_steps: usize) -> Result<GeodesicPath> {
        self.push(from);
        let mut at = match from.corner() {
            Some(k) => Self::vertex_state(&self, self.mesh.face(from.face)[k]),
            None => At::Face(from, false),
        };
        for _ in 0..max_steps {
            at = match at {
                At::Face(p, crossed) => self.face_step(p, crossed),
                At::Vertex(v) => self.vertex_step(v),
                At::Source(s) => {
                    self.path.source = s;
                    return Ok(self.path);
                }
                At::Stuck(v) => return self.finish_along_edges(v),
            };
        }
        // Out of steps: finish from the lowest corner of where we are.
        let v = match at {
            At::Face(p, _) => self.lowest_corner(p.face),
            At::Vertex(v) | At::Stuck(v) => v,
            At::Source(s) => {
                self.path.source = s;
                return Ok(self.path);
            }
        };
        self.move_to_vertex(v);
        self.finish_along_edges(v)
    }

    fn vertex_state(&self, v: VertexId) -> At {
        if self.is_source[v.idx()] {
            At::Source(v)
        } else {
            At::Vertex(v)
        }
    }

    fn push(&mut self, p: SurfacePoint) {
        let x = p.position(self.mesh);
        if let Some(last) = self.path.positions.last() {
            self.path.length += last.distance(x);
        }
        self.path.points.push(p);
        self.path.positions.push(x);
    }

    fn move_to_vertex(&mut self, v: VertexId) {
        if let Some(p) = SurfacePoint::at_vertex(self.mesh, v) {
            if self.path.positions.last() != Some(&p.position(self.mesh)) {
                self.push(p);
            }
        }
    }

    /// Rates of change of the barycentric coordinates of face `f` along
    /// -grad U (the face's own gradient); `None` on zero-area faces or where
    /// U is flat.
    fn descent_rates(&self, f: FaceId) -> Option<[f64; 3]> {
        let frame = Frame::new(self.mesh, f)?;
        let g = frame.gradient(self.mesh.face(f).map(|v| self.u[v.idx()]));
        frame.rates(-g)
    }

    /// Rates along the interpolated vertex field at `p`, projected into the
    /// face; the face's own -grad U where that would not descend.
    fn flow_rates(&self, p: &SurfacePoint) -> Option<[f64; 3]> {
        let frame = Frame::new(self.mesh, p.face)?;
        let corners = self.mesh.face(p.face);
        let own = -frame.gradient(corners.map(|v| self.u[v.idx()]));
        let smooth: DVec3 = -(0..3).map(|k| p.bary[k] * self.vertex_gradient[corners[k].idx()]).sum::<DVec3>();
        let smooth = smooth - smooth.dot(frame.normal) * frame.normal;
        let direction = if smooth.dot(own) > 0.0 { smooth } else { own };
        frame.rates(direction)
    }

    /// One straight segment inside face `p.face` along -grad U, or the
    /// decision to follow an edge or stop at a corner.
    fn face_step(&mut self, p: SurfacePoint, crossed: bool) -> At {
        let corners = self.mesh.face(p.face);
        // A source corner: the straight segment to it is the geodesic.
        if let Some(k) = (0..3).find(|&k| self.is_source[corners[k].idx()]) {
            self.move_to_vertex(corners[k]);
            return At::Source(corners[k]);
        }
        let Some(rates) = self.flow_rates(&p) else {
            let v = self.lowest_corner(p.face);
            self.move_to_vertex(v);
            return self.vertex_state(v);
        };
        // The flow must enter the face: no coordinate that is already 0 may
        // decrease. Otherwise it goes on across that edge, or, right after
        // crossing it, both sides push into the edge: a valley.
        let leaving =
            (0..3).filter(|&k| p.bary[k] <= SNAP && rates[k] < 0.0).min_by(|a, b| rates[*a].total_cmp(&rates[*b]));
        if let Some(k) = leaving {
            return if crossed { self.down_the_edge(p.face, k) } else { self.cross_edge(p, k) };
        }
        let (exit, tau) = (0..3)
            .filter(|&k| rates[k] < 0.0)
            .map(|k| (k, p.bary[k] / -rates[k]))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap_or((0, 0.0));
        // Short steps: the field turns inside the face.
        let largest_rate = rates.iter().fold(0.0f64, |m, r| m.max(r.abs()));
        let cap = MAX_STEP / largest_rate;
        let (tau, reaches_edge) = if tau <= cap { (tau, true) } else { (cap, false) };
        let mut bary = [0, 1, 2].map(|k| (p.bary[k] + tau * rates[k]).max(0.0));
        if reaches_edge {
            bary[exit] = 0.0;
        }
        let total: f64 = bary.iter().sum();
        if !(total > 0.0) {
            let v = self.lowest_corner(p.face);
            self.move_to_vertex(v);
            return self.vertex_state(v);
        }
        let bary = bary.map(|b| b / total);
        let q = SurfacePoint { face: p.face, bary };
        if let Some(k) = q.corner() {
            self.move_to_vertex(corners[k]);
            return self.vertex_state(corners[k]);
        }
        self.push(q);
        if reaches_edge {
            self.cross_edge(q, exit)
        } else {
            At::Face(q, false)
        }
    }

    /// From a point on the edge opposite corner `k` of its face, into the
    /// neighbouring face (or along the edge on the boundary).
    fn cross_edge(&mut self, q: SurfacePoint, k: usize) -> At {
        let h = HalfedgeId::of_corner(q.face, (k + 1) % 3);
        let conn = self.mesh.connectivity();
        let Some(t) = conn.twin(h) else {
            return self.down_the_edge(q.face, k);
        };
        let (a, b) = (conn.origin(h), conn.dest(h));
        let (wa, wb) = (q.bary[(k + 1) % 3], q.bary[(k + 2) % 3]);
        let next = t.face();
        let mut bary = [0.0; 3];
        for (j, v) in self.mesh.face(next).iter().enumerate() {
            if *v == a {
                bary[j] = wa;
            } else if *v == b {
                bary[j] = wb;
            }
        }
        At::Face(SurfacePoint { face: next, bary }, true)
    }

    /// Moves to the lower end of the edge opposite corner `k` of face `f`
    /// (U is linear along it).
    fn down_the_edge(&mut self, f: FaceId, k: usize) -> At {
        let corners = self.mesh.face(f);
        let (a, b) = (corners[(k + 1) % 3], corners[(k + 2) % 3]);
        let v = if self.u[a.idx()] <= self.u[b.idx()] { a } else { b };
        self.move_to_vertex(v);
        self.vertex_state(v)
    }

    /// At a vertex: leave through the face whose descent points into it
    /// (the steepest if several), else along the steepest descending edge.
    fn vertex_step(&mut self, v: VertexId) -> At {
        let conn = self.mesh.connectivity();
        // The face the interpolated field points into.
        for &h in conn.outgoing(v) {
            let (f, c) = (h.face(), h.corner());
            let mut bary = [0.0; 3];
            bary[c] = 1.0;
            let p = SurfacePoint { face: f, bary };
            let Some(rates) = self.flow_rates(&p) else { continue };
            if rates[c] < 0.0 && rates[(c + 1) % 3] >= 0.0 && rates[(c + 2) % 3] >= 0.0 {
                return At::Face(p, false);
            }
        }
        // Else the face whose own gradient points into it (the steepest).
        let mut best: Option<(f64, SurfacePoint)> = None;
        for &h in conn.outgoing(v) {
            let (f, c) = (h.face(), h.corner());
            let Some(rates) = self.descent_rates(f) else { continue };
            let (r1, r2) = (rates[(c + 1) % 3], rates[(c + 2) % 3]);
            if rates[c] < 0.0 && r1 >= 0.0 && r2 >= 0.0 {
                // Speed of descent, comparable across faces: |grad U|.
                let steepness = self.face_slope(f);
                if best.is_none_or(|(s, _)| steepness > s) {
                    let mut bary = [0.0; 3];
                    bary[c] = 1.0;
                    best = Some((steepness, SurfacePoint { face: f, bary }));
                }
            }
        }
        if let Some((_, p)) = best {
            return At::Face(p, false);
        }
        // Steepest lower neighbour along an edge.
        let pv = self.mesh.position(v);
        let mut down: Option<(f64, VertexId)> = None;
        crate::support::for_each_neighbor(conn, v, |w| {
            let drop = self.u[v.idx()] - self.u[w.idx()];
            let len = pv.distance(self.mesh.position(w));
            if drop > 0.0 && len > 0.0 && down.is_none_or(|(s, _)| drop / len > s) {
                down = Some((drop / len, w));
            }
        });
        match down {
            Some((_, w)) => {
                self.move_to_vertex(w);
                self.vertex_state(w)
            }
            None => At::Stuck(v),
        }
    }

    /// |grad U| in face `f`.
    fn face_slope(&self, f: FaceId) -> f64 {
        Frame::new(self.mesh, f)
            .map_or(0.0, |frame| frame.gradient(self.mesh.face(f).map(|v| self.u[v.idx()])).length())
    }

    fn lowest_corner(&self, f: FaceId) -> VertexId {
        let corners = self.mesh.face(f);
        *corners.iter().min_by(|a, b| self.u[a.idx()].total_cmp(&self.u[b.idx()])).unwrap_or(&corners[0])
    }

    /// Finishes the path from `v` along the shortest edge path to the
    /// nearest source.
    fn finish_along_edges(mut self, v: VertexId) -> Result<GeodesicPath> {
        let tree = dijkstra(self.mesh, self.sources, &DijkstraOptions::default())?;
        let mut edge_path = tree.edge_path(v).ok_or(GeodesicError::Unreachable)?;
        edge_path.reverse();
        for &w in &edge_path[1..] {
            self.move_to_vertex(w);
            self.path.fallback_edges += 1;
        }
        self.path.source = *edge_path.last().unwrap_or(&v);
        Ok(self.path)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn surface_points_are_validated() {
        let mesh = mesh_kernel::shapes::icosphere(0).unwrap();
        assert!(SurfacePoint::new(&mesh, FaceId(0), [0.2, 0.3, 0.5]).is_ok());
        assert!(SurfacePoint::new(&mesh, FaceId(20), [0.2, 0.3, 0.5]).is_err());
        assert!(SurfacePoint::new(&mesh, FaceId(0), [0.2, 0.3, 0.6]).is_err());
        assert!(SurfacePoint::new(&mesh, FaceId(0), [-0.2, 0.7, 0.5]).is_err());
        assert!(SurfacePoint::new(&mesh, FaceId(0), [f64::NAN, 0.5, 0.5]).is_err());
        let p = SurfacePoint::at_vertex(&mesh, VertexId(3)).unwrap();
        assert_eq!(p.position(&mesh), mesh.position(VertexId(3)));
        assert_eq!(SurfacePoint::at_vertex(&mesh, VertexId(12)), None);
    }
}
