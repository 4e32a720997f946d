//! Constrained Delaunay triangulation of a polygon with holes and its
//! refinement (Chew 1989, Ruppert 1995, Shewchuk 2002 "Delaunay refinement
//! algorithms for triangular mesh generation"), on spade's
//! `ConstrainedDelaunayTriangulation` and its `refine`, plus a refinement to
//! a size that varies over the domain (a sizing function), which spade's
//! refinement (one maximum area for the whole domain) does not offer.

use std::collections::HashSet;
use std::panic::{catch_unwind, AssertUnwindSafe};

use glam::DVec2;
use spade::handles::{FixedDirectedEdgeHandle, FixedVertexHandle};
use spade::{
    AngleLimit, ConstrainedDelaunayTriangulation, HierarchyHintGenerator, Intersection, LineIntersectionIterator,
    Point2, RefinementParameters, Triangulation,
};

use crate::error::{DelaunayError, Result};
use crate::frame::{circumcenter, orient, point_in_polygon, polygon_area, unit_of_points};

/// With a point-location hierarchy (O(log n) per location): the size
/// refinement inserts points in no spatial order.
type Cdt = ConstrainedDelaunayTriangulation<Point2<f64>, (), (), (), HierarchyHintGenerator<f64>>;

/// A polygon with holes: an outer loop and hole loops, each a closed
/// polygon given by its vertices in order (either orientation; a last
/// vertex equal to the first is dropped). The domain is the inside of the
/// outer loop minus the inside of every hole. Loops may not cross, touch,
/// or share a vertex; holes lie inside the outer loop and outside each
/// other.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PolygonDomain {
    /// The outer loop.
    pub outer: Vec<DVec2>,
    /// The hole loops.
    pub holes: Vec<Vec<DVec2>>,
}

impl PolygonDomain {
    /// The area of the domain: the outer loop's minus the holes' (computed
    /// in a power-of-two unit near the largest coordinate, so that it does
    /// not overflow before the result does). O(n).
    pub fn area(&self) -> f64 {
        let all: Vec<DVec2> = self.outer.iter().chain(self.holes.iter().flatten()).copied().collect();
        let unit = unit_of_points(&all).unwrap_or(1.0);
        let a = |l: &[DVec2]| polygon_area(&l.iter().map(|p| *p / unit).collect::<Vec<_>>()).abs();
        (a(&self.outer) - self.holes.iter().map(|h| a(h)).sum::<f64>()) * unit * unit
    }
}

/// Options of [`refine_polygon`] and [`refine_polygon_sized`].
#[derive(Debug, Clone, PartialEq)]
pub struct RefineOptions {
    /// The smallest angle wanted, in degrees, in `[0, 40]`. Default `25`.
    /// Ruppert's algorithm guarantees up to about 20.7 degrees, spade's
    /// refinement usually reaches 30; above 30 it may not terminate before
    /// `max_added_vertices`. `0` refines for size only.
    pub min_angle: f64,
    /// The largest triangle area allowed, in the unit of the points. Default
    /// `None` (no bound).
    pub max_area: Option<f64>,
    /// The most vertices the refinement may add. Default `2_000_000`; when
    /// it is reached the refinement stops and [`RefinedMesh::complete`] is
    /// `false`.
    pub max_added_vertices: usize,
    /// Keep the polygon's edges unsplit. Default `false`: edges are split at
    /// their midpoints where the refinement needs it (Ruppert 1995), which
    /// the angle and size guarantees require; with `true` the boundary keeps
    /// its vertices (for meshes that must match a neighbour's boundary) and
    /// triangles along it may miss the angle bound. The size bound of
    /// [`refine_polygon_sized`] then exempts the triangles at the ends of a
    /// polygon edge longer than the size (no insertion can shorten them):
    /// split the boundary to the size first.
    pub keep_boundary: bool,
}

impl Default for RefineOptions {
    fn default() -> Self {
        Self { min_angle: 25.0, max_area: None, max_added_vertices: 2_000_000, keep_boundary: false }
    }
}

/// A refined triangulation of a [`PolygonDomain`].
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct RefinedMesh {
    /// The vertices: first the polygon's, unchanged and in the order of the
    /// loops (outer, then holes; a dropped closing vertex is not counted),
    /// then the added ones.
    pub points: Vec<DVec2>,
    /// Counter-clockwise triangles covering the domain, none in a hole.
    pub triangles: Vec<[u32; 3]>,
    /// How many of `points` are the polygon's.
    pub input_vertices: usize,
    /// `false` when `max_added_vertices` was reached: the angle and size
    /// bounds may not hold everywhere.
    pub complete: bool,
}

/// Constrained Delaunay triangulation of `domain` refined to the angle and
/// area bounds of `options` by spade's Delaunay refinement (Ruppert 1995,
/// Shewchuk 2002). The triangles cover the domain exactly (holes empty); the
/// smallest angle is at least `min_angle` except in triangles at an input
/// angle smaller than about 60 degrees between two polygon edges, which no
/// refinement can cure (Shewchuk 2002). O(n log n) expected in the output
/// size.
///
/// # Errors
///
/// As [`refine_polygon_sized`].
pub fn refine_polygon(domain: &PolygonDomain, options: &RefineOptions) -> Result<RefinedMesh> {
    refine(domain, None, options)
}

/// As [`refine_polygon`], and every triangle's longest edge is at most the
/// sizing function `size(p)` at its centroid `p`: a target edge length that
/// varies over the domain (for remeshing through a parameterization, whose
/// scale varies). Spade's refinement handles the angle and area bounds;
/// then triangles longer than the size have their circumcentre inserted
/// (Chew 1989, Ruppert 1995), except that a circumcentre beyond a polygon
/// edge, or inside an edge's diametral circle (encroaching it), splits that
/// edge at its midpoint instead (with `keep_boundary` the centroid is
/// inserted instead); the two steps alternate until neither adds a vertex.
/// A circumcentre is at least half the longest edge away from every vertex,
/// so vertices stay apart by about half the smallest size and the loop ends.
/// O(n log n) expected in the output size.
///
/// # Errors
///
/// [`DelaunayError::NonFinite`] / [`DelaunayError::OutOfRange`] for
/// coordinates that cannot be triangulated; [`DelaunayError::DegenerateLoop`]
/// for a loop with fewer than 3 distinct vertices, two consecutive equal
/// vertices, zero area, or a vertex shared with another loop;
/// [`DelaunayError::SelfIntersecting`] for edges that cross, overlap or
/// touch; [`DelaunayError::MisplacedHole`] for a hole outside the outer loop
/// or inside another hole; [`DelaunayError::InvalidOption`] for options out
/// of range or a size that is not finite and positive where it is asked;
/// [`DelaunayError::Backend`] if spade fails (a guard).
pub fn refine_polygon_sized(
    domain: &PolygonDomain,
    size: impl Fn(DVec2) -> f64,
    options: &RefineOptions,
) -> Result<RefinedMesh> {
    refine(domain, Some(&size), options)
}

/// The loops without a closing repeat of the first vertex.
fn loops(domain: &PolygonDomain) -> Vec<&[DVec2]> {
    std::iter::once(&domain.outer)
        .chain(&domain.holes)
        .map(|l| match l.as_slice() {
            [first, .., last] if l.len() > 1 && first == last => &l[..l.len() - 1],
            s => s,
        })
        .collect()
}

fn check_options(options: &RefineOptions) -> Result<()> {
    if !(0.0..=40.0).contains(&options.min_angle) {
        return Err(DelaunayError::InvalidOption {
            name: "min_angle",
            reason: format!("{} degrees is not in [0, 40]", options.min_angle),
        });
    }
    if let Some(a) = options.max_area {
        if !(a.is_finite() && a > 0.0) {
            return Err(DelaunayError::InvalidOption {
                name: "max_area",
                reason: format!("{a} is not finite and > 0"),
            });
        }
    }
    Ok(())
}

/// Inserts the loops' vertices and edges, checking the loops.
fn build(loops: &[&[DVec2]], unit: f64) -> Result<(Cdt, Vec<DVec2>)> {
    let mut cdt = Cdt::new();
    let mut points = Vec::new();
    let mut seen = HashSet::new();
    for (l, lp) in loops.iter().enumerate() {
        let degenerate = |reason: String| Err(DelaunayError::DegenerateLoop { loop_index: l, reason });
        if lp.len() < 3 {
            return degenerate(format!("{} vertices, a loop needs 3", lp.len()));
        }
        for (i, p) in lp.iter().enumerate() {
            if !seen.insert((p.x + 0.0).to_bits() as u128 | (((p.y + 0.0).to_bits() as u128) << 64)) {
                let what = if *p == lp[(i + lp.len() - 1) % lp.len()] {
                    "two consecutive vertices are equal"
                } else {
                    "a vertex repeats (in this loop or another)"
                };
                return degenerate(format!("vertex {i} at {p}: {what}"));
            }
        }
        // Collinear vertices, in the unit of the triangulation (where nothing
        // overflows): every vertex within 1e-12 of the loop's size of the
        // line through the first vertex and the farthest from it.
        let scaled: Vec<DVec2> = lp.iter().map(|p| *p / unit).collect();
        let far = scaled.iter().copied().max_by(|a, b| (*a - scaled[0]).length().total_cmp(&(*b - scaled[0]).length()));
        let axis = far.map_or(DVec2::ZERO, |f| f - scaled[0]);
        let width = scaled.iter().map(|p| axis.perp_dot(*p - scaled[0]).abs()).fold(0.0, f64::max);
        if width <= 1e-12 * axis.length_squared() {
            return degenerate("its vertices are collinear (zero area)".into());
        }
        points.extend_from_slice(lp);
    }
    for p in &points {
        let q = *p / unit;
        cdt.insert(Point2::new(q.x, q.y)).map_err(|e| DelaunayError::Backend { reason: format!("{e:?}") })?;
    }
    if cdt.num_vertices() != points.len() {
        return Err(DelaunayError::Backend { reason: "two distinct vertices were merged".into() });
    }
    let mut first = 0;
    for (l, lp) in loops.iter().enumerate() {
        for i in 0..lp.len() {
            let (a, b) = (first + i, first + (i + 1) % lp.len());
            let before = cdt.num_constraints();
            let added = cdt.try_add_constraint(FixedVertexHandle::from_index(a), FixedVertexHandle::from_index(b));
            if added.len() != 1 || cdt.num_constraints() != before + 1 {
                return Err(DelaunayError::SelfIntersecting { loop_index: l, edge: i });
            }
        }
        first += lp.len();
    }
    for (h, hole) in loops[1..].iter().enumerate() {
        if !point_in_polygon(hole[0], loops[0]) {
            return Err(DelaunayError::MisplacedHole { hole: h, reason: "outside the outer loop".into() });
        }
        if let Some(other) = (0..loops.len() - 1).find(|&o| o != h && point_in_polygon(hole[0], loops[o + 1])) {
            return Err(DelaunayError::MisplacedHole { hole: h, reason: format!("inside hole {other}") });
        }
    }
    Ok((cdt, points))
}

fn position(cdt: &Cdt, v: FixedVertexHandle) -> DVec2 {
    let p = cdt.vertex(v).position();
    DVec2::new(p.x, p.y)
}

/// Which faces (by index) lie in the domain: an odd number of constraint
/// edges away from the outer face (a flood fill, crossing a constraint edge
/// flips the side). O(F).
fn inside_faces(cdt: &Cdt) -> Vec<bool> {
    const UNKNOWN: u8 = 2;
    let mut side = vec![UNKNOWN; cdt.num_all_faces()];
    let mut stack = Vec::new();
    for f in cdt.inner_faces() {
        for e in f.adjacent_edges() {
            if e.rev().face().is_outer() && side[f.fix().index()] == UNKNOWN {
                side[f.fix().index()] = u8::from(e.is_constraint_edge());
                stack.push(f.fix());
            }
        }
    }
    while let Some(f) = stack.pop() {
        let s = side[f.index()];
        for e in cdt.face(f).adjacent_edges() {
            if let Some(g) = e.rev().face().as_inner() {
                if side[g.fix().index()] == UNKNOWN {
                    side[g.fix().index()] = s ^ u8::from(e.is_constraint_edge());
                    stack.push(g.fix());
                }
            }
        }
    }
    side.into_iter().map(|s| s == 1).collect()
}

fn refine(domain: &PolygonDomain, size: Option<&dyn Fn(DVec2) -> f64>, options: &RefineOptions) -> Result<RefinedMesh> {
    check_options(options)?;
    let loops = loops(domain);
    let all: Vec<DVec2> = loops.iter().flat_map(|l| l.iter().copied()).collect();
    crate::triangulate::check_count(all.len())?;
    let unit = unit_of_points(&all)?;
    let (mut cdt, input) = build(&loops, unit)?;
    let n_in = input.len();
    let budget = n_in.saturating_add(options.max_added_vertices);
    if budget > u32::MAX as usize {
        return Err(DelaunayError::InvalidOption {
            name: "max_added_vertices",
            reason: format!("{} with the polygon's vertices exceeds the u32 indices", options.max_added_vertices),
        });
    }
    let mut unsplittable = HashSet::new();
    let mut complete = true;
    // The size refinement first, then spade's angle and area refinement
    // (O(F) per call, so called once or twice); done when the size
    // refinement after spade's adds nothing.
    'outer: loop {
        if let Some(size) = size {
            if let Pass::OutOfVertices =
                size_refine(&mut cdt, size, unit, options.keep_boundary, budget, &mut unsplittable)?
            {
                complete = false;
                break 'outer;
            }
        }
        let remaining = budget.saturating_sub(cdt.num_vertices());
        let mut params = RefinementParameters::<f64>::new()
            .with_angle_limit(AngleLimit::from_deg(options.min_angle))
            .exclude_outer_faces(true)
            .with_max_additional_vertices(remaining);
        if let Some(a) = options.max_area {
            params = params.with_max_allowed_area(a / unit / unit);
        }
        if options.keep_boundary {
            params = params.keep_constraint_edges();
        }
        let before = cdt.num_vertices();
        let result = catch_unwind(AssertUnwindSafe(|| cdt.refine(params)))
            .map_err(|_| DelaunayError::Backend { reason: "spade's refinement panicked".into() })?;
        if !result.refinement_complete || cdt.num_vertices() >= budget {
            complete = false;
            break;
        }
        let Some(size) = size else { break };
        if cdt.num_vertices() == before {
            break;
        }
        match size_refine(&mut cdt, size, unit, options.keep_boundary, budget, &mut unsplittable)? {
            Pass::Done => break,
            Pass::Inserted => {}
            Pass::OutOfVertices => {
                complete = false;
                break;
            }
        }
    }
    Ok(collect(&cdt, input, unit, complete))
}

enum Pass {
    Done,
    Inserted,
    OutOfVertices,
}

/// A triangle by its vertices, counter-clockwise.
type Tri = [FixedVertexHandle; 3];

/// The state of the size refinement: the sizing function in the unit of
/// the triangulation, and what may not be split.
struct Sizer<'a> {
    size: &'a dyn Fn(DVec2) -> f64,
    unit: f64,
    keep_boundary: bool,
    unsplittable: &'a mut HashSet<(usize, usize)>,
    /// Endpoints of polygon edges longer than the size that may not be
    /// split: the triangle on such an edge has two edges of at least half
    /// its length whatever is inserted, so triangles at these vertices are
    /// exempt.
    frozen: HashSet<usize>,
}

impl Sizer<'_> {
    /// Whether the triangle is longer than the size at its centroid (and
    /// not exempt).
    fn too_long(&self, cdt: &Cdt, t: Tri) -> Result<bool> {
        let [a, b, c] = t.map(|v| position(cdt, v));
        let centroid = (a + b + c) / 3.0;
        let h = (self.size)(centroid * self.unit);
        if !(h.is_finite() && h > 0.0) {
            return Err(DelaunayError::InvalidOption {
                name: "size",
                reason: format!("the size at {} is {h}, not finite and > 0", centroid * self.unit),
            });
        }
        let longest = (a - b).length().max((b - c).length()).max((c - a).length()) * self.unit;
        Ok(longest > h && !t.iter().any(|v| self.frozen.contains(&v.index())))
    }

    fn freeze_if_long(&mut self, cdt: &Cdt, p: FixedVertexHandle, q: FixedVertexHandle) {
        let (a, b) = (position(cdt, p), position(cdt, q));
        if (a - b).length() * self.unit > (self.size)(0.5 * (a + b) * self.unit) {
            self.frozen.extend([p.index(), q.index()]);
        }
    }
}

fn key(p: FixedVertexHandle, q: FixedVertexHandle) -> (usize, usize) {
    (p.index().min(q.index()), p.index().max(q.index()))
}

/// Refines to the size: a full scan finds the triangles too long, a queue
/// processes them and the triangles around each new vertex (largest ratio
/// first within a scan), and a new scan catches triangles changed by
/// edge flips away from new vertices; done when a scan finds nothing.
/// O(F) per scan, a few scans.
fn size_refine(
    cdt: &mut Cdt,
    size: &dyn Fn(DVec2) -> f64,
    unit: f64,
    keep_boundary: bool,
    budget: usize,
    unsplittable: &mut HashSet<(usize, usize)>,
) -> Result<Pass> {
    let mut sizer = Sizer { size, unit, keep_boundary, unsplittable, frozen: HashSet::new() };
    let mut inserted = false;
    loop {
        let inside = inside_faces(cdt);
        sizer.frozen.clear();
        let frozen_edges: Vec<(FixedVertexHandle, FixedVertexHandle)> = cdt
            .undirected_edges()
            .filter(|e| e.is_constraint_edge())
            .map(|e| e.vertices().map(|v| v.fix()))
            .map(|[p, q]| (p, q))
            .filter(|&(p, q)| keep_boundary || sizer.unsplittable.contains(&key(p, q)))
            .collect();
        for (p, q) in frozen_edges {
            sizer.freeze_if_long(cdt, p, q);
        }
        let mut queue = std::collections::VecDeque::new();
        for f in cdt.inner_faces() {
            let t = f.vertices().map(|v| v.fix());
            if inside[f.fix().index()] && sizer.too_long(cdt, t)? {
                queue.push_back(t);
            }
        }
        if queue.is_empty() {
            return Ok(if inserted { Pass::Inserted } else { Pass::Done });
        }
        while let Some(t) = queue.pop_front() {
            if cdt.num_vertices() >= budget {
                return Ok(Pass::OutOfVertices);
            }
            let [v0, v1, v2] = t;
            let alive =
                cdt.get_edge_from_neighbors(v0, v1).and_then(|e| e.opposite_vertex()).is_some_and(|o| o.fix() == v2);
            if !alive || !sizer.too_long(cdt, t)? {
                continue;
            }
            for (v, inside_side) in refine_triangle(cdt, t, &mut sizer)? {
                inserted = true;
                // The triangles around the new vertex on the domain's side.
                let star: Vec<Tri> = cdt
                    .vertex(v)
                    .out_edges()
                    .filter_map(|e| e.face().as_inner())
                    .map(|f| f.vertices().map(|w| w.fix()))
                    .collect();
                for s in star {
                    let on_side = match inside_side {
                        None => true,
                        Some((a, b, sign)) => {
                            let [x, y, z] = s.map(|w| position(cdt, w));
                            orient(a, b, (x + y + z) / 3.0).signum() == sign
                        }
                    };
                    if on_side && sizer.too_long(cdt, s)? {
                        queue.push_back(s);
                    }
                }
            }
        }
    }
}

/// Where the domain lies around a new vertex: `None` for a vertex inside
/// the domain (its whole star is), or a polygon edge's line and the sign of
/// the domain's side for a vertex splitting that edge.
type Side = Option<(DVec2, DVec2, f64)>;

/// Refines one triangle too long for the size: its circumcentre, or the
/// midpoint of the polygon edge the circumcentre lies beyond or encroaches
/// (Ruppert 1995), or its centroid where no edge may be split. Returns the
/// vertices added.
fn refine_triangle(cdt: &mut Cdt, t: Tri, sizer: &mut Sizer<'_>) -> Result<Vec<(FixedVertexHandle, Side)>> {
    let [a, b, c] = t.map(|v| position(cdt, v));
    let centroid = (a + b + c) / 3.0;
    let Some(centre) = circumcenter(a, b, c) else { return Ok(Vec::new()) };
    let centroid_inside = orient(a, b, centroid) > 0.0 && orient(b, c, centroid) > 0.0 && orient(c, a, centroid) > 0.0;
    // The first polygon edge between the triangle and its circumcentre.
    let crossed =
        LineIntersectionIterator::new(&*cdt, Point2::new(centroid.x, centroid.y), Point2::new(centre.x, centre.y))
            .find_map(|i| match i {
                Intersection::EdgeIntersection(e) | Intersection::EdgeOverlap(e) if e.is_constraint_edge() => {
                    Some(Some(e.fix()))
                }
                // Through a vertex of the polygon: the far side is unknown.
                Intersection::VertexIntersection(v) if v.out_edges().any(|e| e.is_constraint_edge()) => Some(None),
                _ => None,
            });
    if let Some(edge) = crossed {
        return match edge {
            Some(e) if !sizer.keep_boundary => Ok(split_edge(cdt, e, centroid, sizer)?.into_iter().collect()),
            // The centroid, when rounding leaves it strictly inside.
            _ if centroid_inside => Ok(insert_point(cdt, centroid)?.map(|v| (v, None)).into_iter().collect()),
            _ => Ok(Vec::new()),
        };
    }
    let Some(v) = insert_point(cdt, centre)? else { return Ok(Vec::new()) };
    if sizer.keep_boundary {
        return Ok(vec![(v, None)]);
    }
    // Does the new vertex encroach a polygon edge of its star?
    let encroached = cdt.vertex(v).out_edges().map(|e| e.next()).find(|e| {
        e.is_constraint_edge() && {
            let [p, q] = e.positions().map(|p| DVec2::new(p.x, p.y));
            (centre - p).dot(centre - q) < 0.0
        }
    });
    let Some([p, q]) = encroached.map(|e| [e.from().fix(), e.to().fix()]) else { return Ok(vec![(v, None)]) };
    cdt.remove(v);
    let Some(e) = cdt.get_edge_from_neighbors(p, q).map(|e| e.fix()) else { return Ok(Vec::new()) };
    Ok(split_edge(cdt, e, centre, sizer)?.into_iter().collect())
}

/// Inserts a point; `None` when a vertex is already there.
fn insert_point(cdt: &mut Cdt, p: DVec2) -> Result<Option<FixedVertexHandle>> {
    let before = cdt.num_vertices();
    let v = cdt.insert(Point2::new(p.x, p.y)).map_err(|e| DelaunayError::Backend { reason: format!("{e:?}") })?;
    Ok((cdt.num_vertices() > before).then_some(v))
}

/// Splits the constraint edge at its midpoint (Ruppert 1995): unmark it,
/// insert the midpoint, constrain both halves. The midpoint is rarely
/// exactly on the line, so this bends the edge by rounding only; when the
/// halves cannot be constrained (another vertex within rounding of the
/// edge) the split is undone and the edge is never split again. Returns the
/// added vertex and the domain's side (that of `inside`, a point of the
/// domain near the edge).
fn split_edge(
    cdt: &mut Cdt,
    edge: FixedDirectedEdgeHandle,
    inside: DVec2,
    sizer: &mut Sizer<'_>,
) -> Result<Option<(FixedVertexHandle, Side)>> {
    let e = cdt.directed_edge(edge);
    let (a, b) = (e.from().fix(), e.to().fix());
    if sizer.unsplittable.contains(&key(a, b)) {
        return Ok(None);
    }
    let (pa, pb) = (position(cdt, a), position(cdt, b));
    let side = orient(pa, pb, inside).signum();
    cdt.remove_constraint_edge(edge.as_undirected());
    if let Some(m) = insert_point(cdt, 0.5 * (pa + pb))? {
        if cdt.can_add_constraint(a, m) && cdt.can_add_constraint(m, b) {
            let first = cdt.try_add_constraint(a, m);
            let second = cdt.try_add_constraint(m, b);
            if !first.is_empty() && !second.is_empty() {
                return Ok(Some((m, Some((pa, pb, side)))));
            }
        }
        cdt.remove(m);
    }
    sizer.unsplittable.insert(key(a, b));
    sizer.freeze_if_long(cdt, a, b);
    if cdt.try_add_constraint(a, b).is_empty() {
        return Err(DelaunayError::Backend {
            reason: "a polygon edge could not be restored after a failed split".into(),
        });
    }
    Ok(None)
}

/// The triangles inside the domain, with the polygon's vertices first and
/// only the added vertices that a triangle uses.
fn collect(cdt: &Cdt, input: Vec<DVec2>, unit: f64, complete: bool) -> RefinedMesh {
    let inside = inside_faces(cdt);
    let n_in = input.len();
    let mut index = vec![u32::MAX; cdt.num_vertices()];
    let mut points = input;
    for (i, slot) in index.iter_mut().enumerate().take(n_in) {
        *slot = i as u32;
    }
    let mut triangles = Vec::new();
    for f in cdt.inner_faces() {
        if !inside[f.fix().index()] {
            continue;
        }
        let t = f.vertices().map(|v| {
            let i = v.fix().index();
            if index[i] == u32::MAX {
                index[i] = points.len() as u32;
                points.push(position(cdt, v.fix()) * unit);
            }
            index[i]
        });
        triangles.push(t);
    }
    RefinedMesh { points, triangles, input_vertices: n_in, complete }
}
