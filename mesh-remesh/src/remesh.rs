//! [`remesh`]: the entry point, and the triangulation of each chart.

use glam::{DVec2, DVec3};
use mesh_delaunay::{refine_polygon_sized, PolygonDomain, RefineOptions};
use mesh_kernel::{geometry, TriMesh};
use mesh_param::{atlas, AtlasOptions, BoundaryMap, Chart, ChartLayout, ParamMethod, Spacing};

use crate::collapse::collapse_short_edges;
use crate::error::{RemeshError, Result};
use crate::flips::surface_delaunay_flips;
use crate::locate::UvGrid;
use crate::report::{quality_report, RemeshReport};
use crate::seams::{chart_loops, sample_seams, Seams};

/// The refinement's size bound is on a triangle's longest edge; Delaunay
/// refinement then leaves edges between about half and all of it. The size
/// asked for is this multiple of the edge length times the map's smallest
/// stretch, so that the edges come out spread around the edge length
/// (measured on the shapes and shared meshes of the README: a mean edge of
/// 0.82-0.92 times the edge length).
pub const SIZE_FACTOR: f64 = 1.5;

/// Options of [`remesh`].
#[derive(Debug, Clone, PartialEq)]
pub struct RemeshOptions {
    /// The target edge length, in the unit of the input (finite, > 0).
    pub edge_length: f64,
    /// The smallest angle asked of the refinement inside each chart, in
    /// degrees, in `[0, 35]`. Default `28`. Triangles along the seams keep
    /// the seam samples and may miss it.
    pub min_angle: f64,
    /// The most output vertices. Default `4_000_000`. An edge length that
    /// needs more (estimated from the area before any work: about
    /// `1.15 area / edge_length^2`) is [`RemeshError::TooManyVertices`].
    pub max_vertices: usize,
    /// Charts are split while their mean area distortion exceeds this
    /// (`mesh_param::AtlasOptions::max_area_distortion`, at least 1).
    /// Default `2`.
    pub max_area_distortion: f64,
    /// Charts of at most about this many input faces (compact farthest-point
    /// Voronoi regions, `mesh_param::AtlasOptions::max_chart_faces`).
    /// Default `Some(300)`. Without it the distortion bound alone splits
    /// charts, in halves, again and again: on the test torus that left
    /// strips (a tube's ring, cut open and mapped onto a circle: angle
    /// distortion up to 49) beside pieces of 1-4 faces, and 3-8% of the
    /// triangles under 20 degrees instead of 1-4%.
    pub max_chart_faces: Option<usize>,
    /// After the charts are stitched, flip edges toward a Delaunay mesh on
    /// the surface where the two faces fold by less than this many degrees
    /// (their normals' angle); `0` turns the flips off. Default `20`. The
    /// refinement bounds angles in the parameter plane; the map's
    /// anisotropy and the seams leave thin triangles in 3D, and flips
    /// (which move no vertex) cure most of them.
    pub max_fold_degrees: f64,
    /// Compute the Hausdorff distance to the input (default `true`; it costs
    /// about as much as the remeshing).
    pub hausdorff: bool,
}

impl Default for RemeshOptions {
    fn default() -> Self {
        Self {
            edge_length: 1.0,
            min_angle: 28.0,
            max_vertices: 4_000_000,
            max_area_distortion: 2.0,
            max_chart_faces: Some(300),
            max_fold_degrees: 20.0,
            hausdorff: true,
        }
    }
}

/// A remeshed surface and its report.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct Remeshed {
    /// The new mesh: seam samples first, then the inside vertices chart by
    /// chart; triangles oriented as the input.
    pub mesh: TriMesh,
    /// The chart of each output face.
    pub face_chart: Vec<u32>,
    /// Quality, distance and topology.
    pub report: RemeshReport,
}

/// The atlas options used: mean-value maps onto a circle, split to the
/// distortion bound.
///
/// Mean-value (Floater 2003) on a convex boundary is a bijection (Tutte's
/// and Floater's theorem), so every chart's parameter domain is a convex
/// polygon without folds: a polygon through any of its boundary points in
/// order (the seam samples) is simple and lies inside it, so every point the
/// refinement inserts has a containing triangle to lift it by. LSCM has a
/// free, possibly non-convex (even overlapping) boundary, and the samples'
/// polygon could leave it. The circle costs area distortion near the
/// boundary, which the splitting bounds.
pub fn atlas_options(options: &RemeshOptions) -> AtlasOptions {
    AtlasOptions {
        method: ParamMethod::MeanValue,
        boundary: BoundaryMap::Circle(Spacing::ChordLength),
        max_area_distortion: Some(options.max_area_distortion),
        max_chart_faces: options.max_chart_faces,
        ..Default::default()
    }
}

fn check_options(mesh: &TriMesh, o: &RemeshOptions) -> Result<()> {
    let h = o.edge_length;
    if !(h.is_finite() && h > 0.0) {
        return Err(RemeshError::InvalidOption { name: "edge_length", reason: format!("{h} is not finite and > 0") });
    }
    if !(0.0..=35.0).contains(&o.min_angle) {
        return Err(RemeshError::InvalidOption {
            name: "min_angle",
            reason: format!("{} degrees is not in [0, 35]", o.min_angle),
        });
    }
    if !(o.max_area_distortion.is_finite() && o.max_area_distortion >= 1.0) {
        return Err(RemeshError::InvalidOption {
            name: "max_area_distortion",
            reason: format!("{} is not finite and >= 1", o.max_area_distortion),
        });
    }
    if !(0.0..=90.0).contains(&o.max_fold_degrees) {
        return Err(RemeshError::InvalidOption {
            name: "max_fold_degrees",
            reason: format!("{} degrees is not in [0, 90]", o.max_fold_degrees),
        });
    }
    if o.max_vertices < 3 || o.max_vertices > u32::MAX as usize / 2 {
        return Err(RemeshError::InvalidOption {
            name: "max_vertices",
            reason: format!("{} is not in [3, {}]", o.max_vertices, u32::MAX / 2),
        });
    }
    let estimated = 1.155 * geometry::surface_area(mesh) / (h * h);
    if estimated.is_nan() || estimated > o.max_vertices as f64 {
        let estimated = if estimated.is_finite() { estimated.min(1e18) as usize } else { usize::MAX };
        return Err(RemeshError::TooManyVertices { edge_length: h, estimated, limit: o.max_vertices });
    }
    Ok(())
}

/// Remeshes `mesh` to edges of about [`RemeshOptions::edge_length`]
/// through a parameterization:
///
/// 1. an atlas of low-distortion charts ([`atlas_options`]);
/// 2. the seams (chart boundaries) split into curves between corners and
///    sampled once in 3D, by arc length, into segments near the edge length;
/// 3. each chart's parameter domain, the polygon through its seam samples,
///    refined by constrained Delaunay refinement (boundary kept) to a size
///    of the edge length times the local parameter scale
///    (`sqrt(uv area / surface area)`, interpolated from the chart's
///    vertices) and the angle bound;
/// 4. the new points lifted by barycentric interpolation in their
///    containing parameter triangle; seam samples are one output vertex
///    for every chart, so the output has no cracks where the input had
///    none;
/// 5. triangles oriented as the input (checked against the input face
///    normal at each centroid, [`RemeshReport::normal_disagreements`]).
///
/// The report has the quality, the Hausdorff distance and the topology of
/// both meshes. Cost: the atlas (a sparse factorization per chart and
/// level of splitting), O(n log n) refinement in the output size, and the
/// Hausdorff sampling (a grid per mesh).
///
/// # Errors
///
/// [`RemeshError::InvalidOption`] for options out of range;
/// [`RemeshError::TooManyVertices`] when the edge length needs more than
/// `max_vertices` vertices (checked before any work, and again as the
/// charts are filled); [`RemeshError::Mesh`] for a non-manifold or empty
/// input; [`RemeshError::Param`] when the atlas fails;
/// [`RemeshError::Delaunay`] when a chart's polygon cannot be triangulated;
/// [`RemeshError::ChartFailed`] for a chart that is not a disk, a
/// refinement that does not finish, a point without a containing parameter
/// triangle, or a collapsed output triangle.
pub fn remesh(mesh: &TriMesh, options: &RemeshOptions) -> Result<Remeshed> {
    check_options(mesh, options)?;
    if mesh.face_count() == 0 {
        return Err(mesh_kernel::MeshError::Empty.into());
    }
    mesh.manifold_connectivity()?;
    let atlas = atlas(mesh, &atlas_options(options))?;
    let loops = chart_loops(&atlas)?;
    let mut seams = sample_seams(mesh, &atlas, &loops, options.edge_length, options.max_vertices)?;
    let seam_vertices = seams.positions.len();
    let mut faces: Vec<[u32; 3]> = Vec::new();
    let mut face_chart = Vec::new();
    let mut disagreements = 0;
    for (c, lp) in loops.iter().enumerate() {
        let chart = &atlas.charts[c];
        let done = chart_triangles(c, chart, lp, &mut seams, options, mesh)?;
        disagreements += done.1;
        face_chart.extend(std::iter::repeat_n(c as u32, done.0.len()));
        faces.extend(done.0);
    }
    check_stitching(&faces, &face_chart, options.edge_length)?;
    let (mut flips, mut collapses) = (0, 0);
    let mut positions = seams.positions;
    if options.max_fold_degrees > 0.0 {
        let h = options.edge_length;
        flips += surface_delaunay_flips(&positions, &mut faces, options.max_fold_degrees);
        let kept;
        (positions, faces, kept, collapses) = collapse_short_edges(positions, faces, 0.5 * h, 1.5 * h);
        face_chart = face_chart.into_iter().zip(kept).filter(|(_, k)| *k).map(|(c, _)| c).collect();
        flips += surface_delaunay_flips(&positions, &mut faces, options.max_fold_degrees);
    }
    if faces.is_empty() {
        return Err(RemeshError::ChartFailed { chart: 0, reason: "no output triangle".into() });
    }
    let out = TriMesh::new(positions, faces)?;
    let mut report = quality_report(mesh, &out, options.edge_length, options.hausdorff);
    report.charts = atlas.charts.len();
    report.seam_curves = seams.curves;
    report.seam_vertices = seam_vertices;
    report.flips = flips;
    report.collapses = collapses;
    report.normal_disagreements = disagreements;
    report.chart_area_distortion_max =
        atlas.charts.iter().map(|c| c.distortion.area_distortion_mean).fold(1.0, f64::max);
    Ok(Remeshed { mesh: out, face_chart, report })
}

/// Which output vertex each chart boundary point is, and its UV: the loop
/// through the seam samples.
fn chart_polygon(chart: &Chart, lp: &[u32], seams: &Seams) -> (Vec<DVec2>, Vec<u32>) {
    let (mut uv, mut ids) = (Vec::new(), Vec::new());
    for i in 0..lp.len() {
        let (ci, cj) = (lp[i] as usize, lp[(i + 1) % lp.len()] as usize);
        let (a, b) = (chart.vertices[ci].0, chart.vertices[cj].0);
        let (ua, ub) = (chart.uv[ci], chart.uv[cj]);
        if let Some(&id) = seams.vertex_out.get(&a) {
            uv.push(ua);
            ids.push(id);
        }
        if let Some(samples) = seams.edge_samples.get(&(a.min(b), a.max(b))) {
            if a < b {
                for &(t, id) in samples {
                    uv.push(ua.lerp(ub, t));
                    ids.push(id);
                }
            } else {
                for &(t, id) in samples.iter().rev() {
                    uv.push(ub.lerp(ua, t));
                    ids.push(id);
                }
            }
        }
    }
    (uv, ids)
}

/// Triangulates one chart: its output triangles (new vertices appended to
/// `seams.positions`) and how many disagree with the input's normal.
fn chart_triangles(
    c: usize,
    chart: &Chart,
    lp: &[u32],
    seams: &mut Seams,
    options: &RemeshOptions,
    input: &TriMesh,
) -> Result<(Vec<[u32; 3]>, usize)> {
    let fail = |reason: String| RemeshError::ChartFailed { chart: c, reason };
    if chart.layout == ChartLayout::FacesApart {
        return Err(fail("the chart could not be flattened (laid out face by face)".into()));
    }
    if chart.distortion.flipped_faces > 0 || !chart.distortion.boundary_simple {
        return Err(fail(format!(
            "its map folds ({} flipped faces, simple boundary: {})",
            chart.distortion.flipped_faces, chart.distortion.boundary_simple
        )));
    }
    let cm = &chart.mesh;
    let tris: Vec<[DVec2; 3]> = cm.faces().iter().map(|t| t.map(|v| chart.uv[v as usize])).collect();
    let signed: f64 = tris.iter().map(|t| (t[1] - t[0]).perp_dot(t[2] - t[0])).sum();
    let grid = UvGrid::new(&tris);
    // Parameter scale per chart vertex: the smallest singular value of the
    // map (UV length per surface length in the most shortened direction)
    // of its faces, weighted by area, so that no 3D edge exceeds the size
    // in any direction.
    let n = cm.vertex_count();
    let (mut uv_area, mut area, mut sigma) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    for (t, f) in tris.iter().zip(cm.faces()) {
        let a_uv = 0.5 * (t[1] - t[0]).perp_dot(t[2] - t[0]).abs();
        let p = f.map(|v| cm.positions()[v as usize]);
        let a3 = geometry::triangle_area(p);
        let s = smallest_singular_value(p, *t);
        for &v in f {
            uv_area[v as usize] += a_uv;
            area[v as usize] += a3;
            if s.is_finite() {
                sigma[v as usize] += a3 * s;
            }
        }
    }
    let total = (uv_area.iter().sum::<f64>() / area.iter().sum::<f64>()).sqrt();
    let chart_scale = if total.is_finite() && total > 0.0 { total } else { 1.0 };
    let scale: Vec<f64> = (0..n)
        .map(|v| {
            let s = sigma[v] / area[v];
            if s.is_finite() && s > 0.0 {
                s
            } else {
                chart_scale
            }
        })
        .collect();
    let tol = 1e-9;
    let h = options.edge_length * SIZE_FACTOR;
    let (outer, ids) = chart_polygon(chart, lp, seams);
    let floor = SizeFloor::new(&outer);
    let size = |x: DVec2| {
        let s = match grid.locate(&tris, x, tol) {
            Some((t, b)) => h * cm.faces()[t].iter().zip(b).map(|(&v, w)| w * scale[v as usize]).sum::<f64>(),
            None => h * chart_scale,
        };
        s.max(floor.at(x))
    };
    let budget = options.max_vertices.saturating_sub(seams.positions.len());
    let refine =
        RefineOptions { min_angle: options.min_angle, max_area: None, max_added_vertices: budget, keep_boundary: true };
    let domain = PolygonDomain { outer, holes: Vec::new() };
    let r =
        refine_polygon_sized(&domain, size, &refine).map_err(|source| RemeshError::Delaunay { chart: c, source })?;
    if !r.complete {
        return Err(RemeshError::TooManyVertices {
            edge_length: options.edge_length,
            estimated: seams.positions.len() + r.points.len(),
            limit: options.max_vertices,
        });
    }
    if r.input_vertices != ids.len() {
        return Err(fail("the refinement changed the boundary".into()));
    }
    // Lift the new points.
    let lift = |x: DVec2| -> Option<(usize, DVec3)> {
        let (t, b) = grid.locate(&tris, x, tol)?;
        let p = cm.faces()[t].iter().zip(b).map(|(&v, w)| w * cm.positions()[v as usize]).sum();
        Some((t, p))
    };
    let mut index = ids;
    for &x in &r.points[r.input_vertices..] {
        let (_, p) =
            lift(x).ok_or_else(|| fail(format!("the parameter point {x} lies in no triangle of the chart")))?;
        index.push(seams.positions.len() as u32);
        seams.positions.push(p);
    }
    let mut out = Vec::with_capacity(r.triangles.len());
    let mut disagree = 0;
    for t in &r.triangles {
        let mut tri = t.map(|v| index[v as usize]);
        if signed < 0.0 {
            tri.swap(1, 2);
        }
        if tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] {
            return Err(fail("an output triangle joins two copies of one seam point (a cut's tip)".into()));
        }
        let centroid = (r.points[t[0] as usize] + r.points[t[1] as usize] + r.points[t[2] as usize]) / 3.0;
        let (ct, _) = lift(centroid).ok_or_else(|| fail(format!("the centroid {centroid} lies in no triangle")))?;
        let face = chart.faces[ct];
        let n_in = geometry::triangle_normal(input.triangle(face));
        let p = tri.map(|v| seams.positions[v as usize]);
        if geometry::double_area_vector(p).dot(n_in) < 0.0 {
            disagree += 1;
        }
        out.push(tri);
    }
    Ok((out, disagree))
}

/// A lower bound of the size near the polygon's edges: each edge's length
/// (plus 1%) within that length of its midpoint, on a grid of at most
/// 64 x 64 cells. With the boundary kept, an edge longer than the size
/// would exempt every triangle at its ends from the size bound (the
/// refinement cannot shorten it); the seam samples are placed in 3D, and
/// the map's anisotropy can make a segment longer in the plane than the
/// isotropic size there. The floor lets the triangles along the seam be as
/// long as the seam's segments, and no longer.
struct SizeFloor {
    min: DVec2,
    cell: f64,
    n: [usize; 2],
    floor: Vec<f64>,
}

impl SizeFloor {
    fn new(polygon: &[DVec2]) -> Self {
        let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
        for p in polygon {
            lo = lo.min(*p);
            hi = hi.max(*p);
        }
        let extent = (hi - lo).max_element();
        if !(extent.is_finite() && extent > 0.0) {
            return Self { min: DVec2::ZERO, cell: 1.0, n: [1, 1], floor: vec![0.0] };
        }
        let cell = extent / 64.0;
        let n = [((hi.x - lo.x) / cell) as usize + 1, ((hi.y - lo.y) / cell) as usize + 1].map(|k| k.min(65));
        let mut floor = Self { min: lo, cell, n, floor: vec![0.0; n[0] * n[1]] };
        for i in 0..polygon.len() {
            let (a, b) = (polygon[i], polygon[(i + 1) % polygon.len()]);
            let (mid, u) = (0.5 * (a + b), a.distance(b));
            let (x0, y0) = floor.cell_of(mid - DVec2::splat(u));
            let (x1, y1) = floor.cell_of(mid + DVec2::splat(u));
            for y in y0..=y1 {
                for x in x0..=x1 {
                    let f = &mut floor.floor[y * n[0] + x];
                    *f = f.max(1.01 * u);
                }
            }
        }
        floor
    }

    fn cell_of(&self, p: DVec2) -> (usize, usize) {
        let q = (p - self.min) / self.cell;
        let c = |v: f64, n: usize| if v.is_nan() { 0 } else { (v.max(0.0) as usize).min(n - 1) };
        (c(q.x, self.n[0]), c(q.y, self.n[1]))
    }

    fn at(&self, p: DVec2) -> f64 {
        let (x, y) = self.cell_of(p);
        self.floor[y * self.n[0] + x]
    }
}

/// The smallest singular value of the linear map from the surface triangle
/// `p` (in its own plane) to the parameter triangle `q`; NaN for a
/// degenerate triangle. O(1).
fn smallest_singular_value(p: [DVec3; 3], q: [DVec2; 3]) -> f64 {
    let (e1, e2) = (p[1] - p[0], p[2] - p[0]);
    let l = e1.length();
    let normal = e1.cross(e2);
    let (x, y) = (e1 / l, normal.cross(e1).normalize());
    // Plane coordinates: (l, 0) and (e2.x, e2.y).
    let (bx, by) = (e2.dot(x), e2.dot(y));
    let det = l * by;
    let (u1, u2) = (q[1] - q[0], q[2] - q[0]);
    // J = [u1 u2] [[l, bx], [0, by]]^-1.
    let inv = [[1.0 / l, -bx / det], [0.0, 1.0 / det]];
    let (a, b) = (u1.x * inv[0][0] + u2.x * inv[1][0], u1.x * inv[0][1] + u2.x * inv[1][1]);
    let (c, d) = (u1.y * inv[0][0] + u2.y * inv[1][0], u1.y * inv[0][1] + u2.y * inv[1][1]);
    let e = a * a + b * b + c * c + d * d;
    let dd = a * d - b * c;
    ((e - (e * e - 4.0 * dd * dd).max(0.0).sqrt()) / 2.0).max(0.0).sqrt()
}

/// Refuses a stitched mesh in which an edge has more than two faces or two
/// faces have the same vertices: the charts on both sides of a seam made
/// the same triangle (seams with too few samples for their charts, from an
/// edge length near the size of the surface, or a map that shortens the
/// seam direction a lot). O(F) with a hash map.
fn check_stitching(faces: &[[u32; 3]], face_chart: &[u32], h: f64) -> Result<()> {
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
