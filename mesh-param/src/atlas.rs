//! Atlases: a texture atlas of any oriented manifold mesh, whatever its
//! number of components, genus and boundary loops. Each connected component
//! (or, with [`AtlasOptions::max_chart_faces`], each region of a component
//! split by [`crate::segment`]) becomes one chart: cut into a topological disk ([`crate::cut_to_disk`],
//! tree-cotree), flattened with the chosen method, scaled to its 3D size
//! (every chart keeps its share of the surface area: parameter area
//! proportional to surface area), turned to its smallest bounding box, and
//! packed with the other charts into the unit square ([`crate::pack`]).
//! Each face gets one UV per corner (vertices along seams and on several
//! charts get several), and each chart its distortion (eq. 2.8-2.11).
//!
//! A piece the method cannot flatten (a solver failure, a square
//! boundary on a triangle, a non-finite coordinate) is flattened by Tutte's
//! map onto a circle instead, and failing that laid out face by face
//! ([`ChartLayout::FacesApart`]: each triangle on its own with its 3D edge
//! lengths); such a chart carries the reason in [`Chart::fallback`]. A
//! piece without area (all faces zero-area) is sized by its 3D extent
//! and flagged [`Chart::zero_area`]. Nothing of this makes the whole call
//! fail.

use glam::{DVec2, DVec3};
use mesh_kernel::{geometry, FaceId, SubMesh, TriMesh, VertexId};

use crate::boundary::{BoundaryMap, Spacing};
use crate::cut::cut_to_disk;
use crate::distortion::{distortion, summarize, DistortionSummary, FaceDistortion};
use crate::error::{ParamError, Result};
use crate::fixed::DegeneratePolicy;
use crate::pack::{min_area_rotation, pack_rectangles, UvRect};
use crate::param::{map_disk, ParamMethod, ParamOptions};
use crate::segment::{chart_labels, chart_pieces};
use crate::topology::Topology;

/// Options of [`atlas`].
#[derive(Debug, Clone, PartialEq)]
pub struct AtlasOptions {
    /// The method of every chart (default: mean-value).
    pub method: ParamMethod,
    /// Boundary of the fixed-boundary methods: [`BoundaryMap::Circle`]
    /// (default, chord length) or [`BoundaryMap::Square`];
    /// [`BoundaryMap::Fixed`] names vertices of one disk and is refused.
    pub boundary: BoundaryMap,
    /// Gap between charts in the unit square (half of it to the square's
    /// sides), default 1/256; made smaller when the charts are too many for it.
    pub margin: f64,
    /// Split components of more faces into regions of about this many
    /// (farthest-point Voronoi regions, [`crate::segment`]); `None`
    /// (default): one chart per component. Smaller charts distort less.
    pub max_chart_faces: Option<usize>,
    /// Split a chart in two, again and again, while its mean area distortion
    /// (area-weighted mean of max(r, 1/r), eq. 2.8-2.9) exceeds this value
    /// (at least 1); `None` (default): never.
    pub max_area_distortion: Option<f64>,
}

impl Default for AtlasOptions {
    fn default() -> Self {
        Self {
            method: ParamMethod::MeanValue,
            boundary: BoundaryMap::default(),
            margin: 1.0 / 256.0,
            max_chart_faces: None,
            max_area_distortion: None,
        }
    }
}

/// How a chart was flattened.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ChartLayout {
    /// Cut to a disk and mapped with this method.
    Method(ParamMethod),
    /// Every face laid out on its own (the last resort; the chart is then
    /// not a disk but one triangle per face).
    FacesApart,
}

impl std::fmt::Display for ChartLayout {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Method(m) => f.write_str(m.name()),
            Self::FacesApart => f.write_str("faces-apart"),
        }
    }
}

/// One chart of an [`Atlas`]: a connected component of the input (or a
/// region of one), cut open.
///
/// The chart is a mesh of its own ([`Chart::mesh`], a topological disk for
/// [`ChartLayout::Method`]) with one UV per chart vertex; its boundary loop
/// (`chart.mesh.connectivity().boundary_loops()`) is the outline of the
/// chart's parameter domain, made of the piece's own boundary loops (those
/// of the surface and, for a region, the borders with the neighbouring
/// charts) and both sides of its seam.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct Chart {
    /// The connected component of the input it belongs to (numbered as in
    /// `mesh_kernel::Connectivity::components`).
    pub component: usize,
    /// Topology of the piece before cutting.
    pub topology: Topology,
    /// The piece cut open: face k is input face `faces[k]` with the same
    /// corner order, its vertices are copies of input vertices.
    pub mesh: TriMesh,
    /// The input face of each chart face.
    pub faces: Vec<FaceId>,
    /// The input vertex of each chart vertex (vertices on the seam appear
    /// once per side, and once per fan where the piece touches itself at a
    /// vertex).
    pub vertices: Vec<VertexId>,
    /// The input edges cut open, as pairs of input vertices.
    pub seam: Vec<[VertexId; 2]>,
    /// UV of each chart vertex, in [`Chart::rect`].
    pub uv: Vec<DVec2>,
    /// The chart's box in the unit square.
    pub rect: UvRect,
    /// How the chart was flattened.
    pub layout: ChartLayout,
    /// Why the chosen method was not used, when it was not.
    pub fallback: Option<String>,
    /// The piece has no surface area (every face zero-area); its size
    /// comes from its 3D extent.
    pub zero_area: bool,
    /// Surface area of the piece.
    pub surface_area: f64,
    /// Distortion of the chart's map (eq. 2.8-2.11; area distortion relative
    /// to the chart's own area ratio).
    pub distortion: DistortionSummary,
}

/// Totals over an [`Atlas`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct AtlasSummary {
    /// Number of charts.
    pub charts: usize,
    /// Charts not flattened with the chosen method ([`Chart::fallback`]).
    pub fallback_charts: usize,
    /// Charts laid out face by face.
    pub faces_apart_charts: usize,
    /// Charts without surface area ([`Chart::zero_area`]).
    pub zero_area_charts: usize,
    /// Distortion over every face of every chart; area distortion relative
    /// to the atlas-wide ratio of surface to parameter area, so it also
    /// measures how well the charts keep their relative sizes.
    pub distortion: DistortionSummary,
    /// Faces whose parameter triangle collapsed and whose surface triangle
    /// has zero area too (counted in `distortion.collapsed_faces`).
    pub collapsed_zero_area_faces: usize,
    /// Parameter area of all faces over the unit square's area.
    pub coverage: f64,
}

/// A texture atlas: one UV per face corner in the unit square.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct Atlas {
    /// `[f][k]`: UV of corner k of input face f, in [0, 1]^2.
    pub corner_uvs: Vec<[DVec2; 3]>,
    /// The chart of each input face (index into [`Atlas::charts`]).
    pub face_chart: Vec<u32>,
    /// The charts, in order of component (and of region inside one).
    pub charts: Vec<Chart>,
    /// UV units per unit of surface length (the same for all charts).
    pub scale: f64,
    /// The margin between charts used (see [`AtlasOptions::margin`]).
    pub margin: f64,
    /// Totals.
    pub summary: AtlasSummary,
}

impl Atlas {
    /// One UV per input vertex when no vertex has two (no seam was cut),
    /// `None` otherwise; unreferenced vertices get (0, 0). `vertex_count` is
    /// that of the input mesh. O(V + F).
    pub fn vertex_uvs(&self, vertex_count: usize) -> Option<Vec<DVec2>> {
        let mut uv = vec![None; vertex_count];
        for chart in &self.charts {
            for (v, q) in chart.vertices.iter().zip(&chart.uv) {
                if uv.get_mut(v.idx())?.replace(*q).is_some() {
                    return None;
                }
            }
        }
        Some(uv.into_iter().map(|q| q.unwrap_or(DVec2::ZERO)).collect())
    }
}

/// Builds a texture atlas of `mesh` (see the module documentation). Needs an
/// oriented manifold (non-manifold input is the wrapped
/// `mesh_kernel::MeshError::NonManifold`; `mesh_kernel::clean` repairs it).
/// Cost: per chart, that of [`crate::cut_to_disk`] and of the method
/// (one sparse factorization), plus O(F) for the distortion and the
/// packing's O(c^2) for c charts (about 20 trial packings).
///
/// ```
/// use mesh_param::{atlas, AtlasOptions, ParamMethod};
///
/// // Two components: a torus (cut to a disk) and a sphere.
/// let torus = mesh_kernel::shapes::torus(2.0, 0.5, 24, 12)?;
/// let sphere = mesh_kernel::shapes::icosphere(2)?;
/// let (mut p, mut f) = torus.into_parts();
/// let n = p.len() as u32;
/// p.extend(sphere.positions().iter().map(|q| *q + glam::DVec3::new(5.0, 0.0, 0.0)));
/// f.extend(sphere.faces().iter().map(|t| t.map(|v| v + n)));
/// let mesh = mesh_kernel::TriMesh::new(p, f)?;
///
/// let a = atlas(&mesh, &AtlasOptions { method: ParamMethod::Tutte, ..Default::default() })?;
/// assert_eq!(a.charts.len(), 2);
/// assert_eq!(a.summary.distortion.flipped_faces, 0);
/// assert!(a.corner_uvs.iter().flatten().all(|q| q.min_element() >= 0.0 && q.max_element() <= 1.0));
/// assert!(!a.charts[0].rect.meets(&a.charts[1].rect));
/// # Ok::<(), mesh_param::ParamError>(())
/// ```
///
/// # Errors
/// `ParamError::InvalidOption` for `boundary` (a fixed boundary: an atlas places boundaries itself),
/// `max_area_distortion` (not finite and >= 1), `margin`, `max_chart_faces` (0), the method's own options
/// (`lambda/mu`, `iterations`, `method`), and `sizes` when the charts cannot be packed; `ParamError::Mesh`
/// (`MeshError::NonManifold`) when the mesh is not an oriented manifold; the errors of each chart's
/// flattening (`ParamError::DegenerateFaces`, `ParamError::NonFinite`, `ParamError::Mesh` with
/// `MeshError::Solver`).
pub fn atlas(mesh: &TriMesh, options: &AtlasOptions) -> Result<Atlas> {
    if matches!(options.boundary, BoundaryMap::Fixed(_)) {
        return Err(ParamError::InvalidOption {
            name: "boundary",
            reason: "an atlas places each chart's boundary itself: use a circle or a square".into(),
        });
    }
    // The method and the margin are checked before any work.
    options.method.validate()?;
    pack_rectangles(&[], options.margin)?;
    if let Some(limit) = options.max_area_distortion.filter(|x| !(x.is_finite() && *x >= 1.0)) {
        return Err(ParamError::InvalidOption {
            name: "max_area_distortion",
            reason: format!("need a finite value >= 1, got {limit}"),
        });
    }
    // Charts are sized against each other by their areas, which over- or
    // underflow on a mesh far from unit size: they are made on the mesh in
    // its unit of length (a power of two, so the UVs are those of any
    // scale), and take their 3D parts from the input.
    let (work, unit) = mesh_kernel::units::normalized(mesh);
    let mut atlas = atlas_in_unit(&work, options)?;
    if unit != 1.0 {
        for chart in &mut atlas.charts {
            let positions = chart.vertices.iter().map(|&v| mesh.position(v)).collect();
            chart.mesh = TriMesh::new(positions, chart.mesh.faces().to_vec())?;
            chart.surface_area = geometry::surface_area(&chart.mesh);
            areas_in_input_units(&mut chart.distortion, unit);
        }
        areas_in_input_units(&mut atlas.summary.distortion, unit);
        atlas.scale /= unit;
    }
    Ok(atlas)
}

/// The areas of a summary measured on the mesh in units of `unit` (a
/// power of two), in the input's units: infinite or zero where they do not
/// fit a double. Its other measures are ratios.
fn areas_in_input_units(summary: &mut DistortionSummary, unit: f64) {
    // Times the unit twice: its square may overflow where the product does not.
    summary.surface_area = summary.surface_area * unit * unit;
    summary.dirichlet_energy = summary.dirichlet_energy * unit * unit;
}

/// [`atlas`] of a mesh whose areas do not over- or underflow (checked
/// options).
fn atlas_in_unit(mesh: &TriMesh, options: &AtlasOptions) -> Result<Atlas> {
    let conn = mesh.manifold_connectivity()?;
    let (labels, count) = chart_labels(mesh, options.max_chart_faces)?;
    let pieces = chart_pieces(mesh, &labels, count)?;
    let fallback_length = geometry::mean_edge_length(mesh);
    let mut flats = Vec::with_capacity(pieces.len());
    for piece in pieces {
        let component = piece.faces.first().map_or(0, |f| conn.components().face_component[f.idx()] as usize);
        flatten_bounded(piece, component, options, fallback_length, &mut flats)?;
    }
    let sizes: Vec<DVec2> = flats.iter().map(|f| f.size).collect();
    let packing = pack_rectangles(&sizes, options.margin)?;
    let mut corner_uvs = vec![[DVec2::ZERO; 3]; mesh.face_count()];
    let mut face_chart = vec![u32::MAX; mesh.face_count()];
    let mut all_faces: Vec<FaceDistortion> = Vec::with_capacity(mesh.face_count());
    let mut charts = Vec::with_capacity(flats.len());
    for (k, flat) in flats.into_iter().enumerate() {
        let rect = packing.rects[k];
        let uv = place(&flat.uv, flat.size, rect, packing.scale, packing.turned[k]);
        let report = distortion(&flat.mesh, &uv)?;
        for (j, (&f, tri)) in flat.faces.iter().zip(flat.mesh.faces()).enumerate() {
            corner_uvs[f.idx()] = tri.map(|v| uv[v as usize]);
            face_chart[f.idx()] = k as u32;
            all_faces.push(report.faces[j]);
        }
        charts.push(Chart {
            component: flat.component,
            topology: flat.topology,
            mesh: flat.mesh,
            faces: flat.faces,
            vertices: flat.vertices,
            seam: flat.seam,
            uv,
            rect,
            layout: flat.layout,
            fallback: flat.fallback,
            zero_area: flat.zero_area,
            surface_area: flat.surface_area,
            distortion: report.summary,
        });
    }
    let summary = AtlasSummary {
        charts: charts.len(),
        fallback_charts: charts.iter().filter(|c| c.fallback.is_some()).count(),
        faces_apart_charts: charts.iter().filter(|c| c.layout == ChartLayout::FacesApart).count(),
        zero_area_charts: charts.iter().filter(|c| c.zero_area).count(),
        distortion: summarize(&all_faces, charts.iter().all(|c| c.distortion.boundary_simple)),
        collapsed_zero_area_faces: all_faces.iter().filter(|d| d.collapsed && d.degenerate).count(),
        // From +0: Rust's sum of nothing is -0.
        coverage: all_faces.iter().map(|d| d.uv_signed_area.abs()).fold(0.0, |a, b| a + b),
    };
    Ok(Atlas { corner_uvs, face_chart, charts, scale: packing.scale, margin: packing.margin, summary })
}

/// The options of one chart's map: never normalized (the atlas scales),
/// zero-area faces weighted uniformly.
fn map_options(method: ParamMethod, boundary: &BoundaryMap) -> ParamOptions {
    ParamOptions { method, boundary: boundary.clone(), degenerate: DegeneratePolicy::Uniform, normalize: false }
}

/// A chart before packing: UVs in surface units, turned to their smallest
/// box, lower-left corner at the origin.
struct Flat {
    component: usize,
    topology: Topology,
    mesh: TriMesh,
    faces: Vec<FaceId>,
    vertices: Vec<VertexId>,
    seam: Vec<[VertexId; 2]>,
    uv: Vec<DVec2>,
    size: DVec2,
    layout: ChartLayout,
    fallback: Option<String>,
    zero_area: bool,
    surface_area: f64,
}

/// Flattens `piece` into `out`; while its mean area distortion exceeds
/// [`AtlasOptions::max_area_distortion`], splits it in two (two
/// farthest-point regions, [`crate::segment`]) and flattens the halves
/// instead. Cost: that of [`flatten_piece`] per level, about log2(F) levels
/// at worst.
fn flatten_bounded(
    piece: SubMesh,
    component: usize,
    options: &AtlasOptions,
    fallback_length: f64,
    out: &mut Vec<Flat>,
) -> Result<()> {
    let flat = flatten_piece(&piece, component, options, fallback_length)?;
    let too_distorted = match options.max_area_distortion {
        Some(limit) if piece.faces.len() > 1 => distortion(&flat.mesh, &flat.uv)?.summary.area_distortion_mean > limit,
        _ => false,
    };
    let halves = if too_distorted {
        let (labels, count) = chart_labels(&piece.mesh, Some(piece.faces.len().div_ceil(2)))?;
        chart_pieces(&piece.mesh, &labels, count)?
    } else {
        Vec::new()
    };
    if halves.len() < 2 {
        out.push(flat);
        return Ok(());
    }
    for half in halves {
        let half = SubMesh {
            mesh: half.mesh,
            vertices: half.vertices.iter().map(|v| piece.vertices[v.idx()]).collect(),
            faces: half.faces.iter().map(|f| piece.faces[f.idx()]).collect(),
        };
        flatten_bounded(half, component, options, fallback_length, out)?;
    }
    Ok(())
}

/// Flattens one piece: the chosen method, else Tutte onto a circle, else
/// faces apart; then scales it to its surface size and turns it to its
/// smallest box. O(size of the piece) plus the method's factorization.
fn flatten_piece(sub: &SubMesh, component: usize, options: &AtlasOptions, fallback_length: f64) -> Result<Flat> {
    let topology = Topology::of(&sub.mesh)?;
    let tutte = (ParamMethod::Tutte, BoundaryMap::Circle(Spacing::ChordLength));
    let mut attempts = vec![(options.method, options.boundary.clone())];
    if attempts[0] != tutte {
        attempts.push(tutte);
    }
    let mut reasons = Vec::new();
    let mut disk = None;
    for (method, boundary) in attempts {
        match disk_map(&sub.mesh, &map_options(method, &boundary)) {
            Ok(found) => {
                disk = Some((found, method));
                break;
            }
            Err(e) => reasons.push(format!("{}: {e}", method.name())),
        }
    }
    let fallback = (!reasons.is_empty()).then(|| reasons.join("; "));
    let (chart_mesh, vertices, seam, uv, layout) = match disk {
        Some(((cut, uv), method)) => {
            let conn = sub.mesh.connectivity();
            let seam = cut.seam.iter().map(|&e| conn.edge_vertices(e).map(|v| sub.vertices[v.idx()])).collect();
            let vertices = cut.vertex_origin.iter().map(|v| sub.vertices[v.idx()]).collect();
            (cut.mesh, vertices, seam, uv, ChartLayout::Method(method))
        }
        None => {
            let (m, origin, uv) = faces_apart(&sub.mesh, fallback_length)?;
            let vertices = origin.iter().map(|v| sub.vertices[v.idx()]).collect();
            (m, vertices, Vec::new(), uv, ChartLayout::FacesApart)
        }
    };
    let surface_area: f64 = geometry::face_areas(&chart_mesh).iter().sum();
    let (factor, zero_area) = surface_factor(&chart_mesh, &uv, surface_area, fallback_length);
    let (uv, size) = upright(&uv, factor);
    Ok(Flat {
        component,
        topology,
        mesh: chart_mesh,
        faces: sub.faces.clone(),
        vertices,
        seam,
        uv,
        size,
        layout,
        fallback,
        zero_area,
        surface_area,
    })
}

/// Cuts a piece to a disk and maps it; a non-finite coordinate is an
/// error.
fn disk_map(piece: &TriMesh, options: &ParamOptions) -> Result<(crate::cut::CutMesh, Vec<DVec2>)> {
    let cut = cut_to_disk(piece)?;
    let (uv, _) = map_disk(&cut.mesh, options)?;
    if let Some(vertex) = uv.iter().position(|q| !q.is_finite()) {
        return Err(ParamError::NonFinite { vertex });
    }
    Ok((cut, uv))
}

/// Scale from the map's units to surface units: sqrt(surface area /
/// parameter area), so that the chart keeps its share of the area; for a
/// piece without area (or a map without area), the ratio of the
/// bounding-box diagonals, with `fallback_length` for a piece collapsed to a
/// point. Returns the factor and whether the piece has no area. O(F).
fn surface_factor(mesh: &TriMesh, uv: &[DVec2], surface_area: f64, fallback_length: f64) -> (f64, bool) {
    let uv_area: f64 = mesh
        .faces()
        .iter()
        .map(|t| 0.5 * (uv[t[1] as usize] - uv[t[0] as usize]).perp_dot(uv[t[2] as usize] - uv[t[0] as usize]).abs())
        .sum();
    let zero_area = surface_area <= 0.0 || surface_area.is_nan();
    if !zero_area && uv_area > 0.0 {
        return ((surface_area / uv_area).sqrt(), false);
    }
    let diagonal3 = |p: &[DVec3]| {
        let first = p.first().copied().unwrap_or(DVec3::ZERO);
        let (lo, hi) = p.iter().fold((first, first), |(lo, hi), q| (lo.min(*q), hi.max(*q)));
        lo.distance(hi)
    };
    let length = Some(diagonal3(mesh.positions())).filter(|&l| l > 0.0).unwrap_or(fallback_length);
    let uv_diagonal = UvRect::around(uv).map_or(0.0, |r| r.size().length());
    let factor = if uv_diagonal > 0.0 && length > 0.0 { length / uv_diagonal } else { 1.0 };
    (factor, zero_area)
}

/// Scales by `factor`, turns to the smallest bounding box
/// ([`min_area_rotation`]) and moves its lower-left corner to the origin.
/// Returns the points and the box size. O(n log n).
fn upright(uv: &[DVec2], factor: f64) -> (Vec<DVec2>, DVec2) {
    let rot = DVec2::from_angle(min_area_rotation(uv)) * factor;
    let mut out: Vec<DVec2> = uv.iter().map(|q| rot.rotate(*q)).collect();
    let Some(rect) = UvRect::around(&out) else { return (out, DVec2::ZERO) };
    out.iter_mut().for_each(|q| *q -= rect.min);
    (out, rect.size())
}

/// Moves an upright chart of box `size` into its packed `rect`: scaled by
/// `scale`, turned by +90 degrees when `turned` (a rotation: orientations
/// are kept), clamped into the rectangle against rounding. O(n).
fn place(uv: &[DVec2], size: DVec2, rect: UvRect, scale: f64, turned: bool) -> Vec<DVec2> {
    uv.iter()
        .map(|q| {
            let local = if turned { DVec2::new(size.y - q.y, q.x) } else { *q };
            (rect.min + scale * local).clamp(rect.min, rect.max)
        })
        .collect()
}

/// Every face on its own: a triangle with the face's 3D edge lengths (a
/// right isosceles triangle of its mean edge length, or of
/// `fallback_length`, when it has no area), placed in its cell of a square
/// grid. Returns the chart mesh (three vertices per face), the origin of each
/// of its vertices and their UVs. O(F).
fn faces_apart(mesh: &TriMesh, fallback_length: f64) -> Result<(TriMesh, Vec<VertexId>, Vec<DVec2>)> {
    let triangles: Vec<[DVec2; 3]> =
        mesh.faces().iter().map(|t| flat_triangle(t.map(|v| mesh.positions()[v as usize]), fallback_length)).collect();
    let cell = triangles
        .iter()
        .filter_map(|t| UvRect::around(t))
        .map(|r| r.size().max_element())
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    let columns = (triangles.len() as f64).sqrt().ceil().max(1.0) as usize;
    let mut uv = Vec::with_capacity(3 * triangles.len());
    for (f, t) in triangles.iter().enumerate() {
        let corner = 1.25 * cell * DVec2::new((f % columns) as f64, (f / columns) as f64);
        let lo = UvRect::around(t).map_or(DVec2::ZERO, |r| r.min);
        uv.extend(t.iter().map(|q| corner + (*q - lo)));
    }
    let positions: Vec<DVec3> = mesh.faces().iter().flat_map(|t| t.map(|v| mesh.positions()[v as usize])).collect();
    let faces: Vec<[u32; 3]> = (0..mesh.face_count() as u32).map(|f| [3 * f, 3 * f + 1, 3 * f + 2]).collect();
    let origin = mesh.faces().iter().flat_map(|t| t.map(VertexId)).collect();
    Ok((TriMesh::new(positions, faces)?, origin, uv))
}

/// A counter-clockwise plane triangle with the side lengths of `p` (law of
/// cosines), or a right isosceles one of the mean side length (or
/// `fallback_length`) when `p` has no area. O(1).
fn flat_triangle(p: [DVec3; 3], fallback_length: f64) -> [DVec2; 3] {
    let (a, b) = (p[1] - p[0], p[2] - p[0]);
    let la = a.length();
    let cross = mesh_kernel::geometry::norm(a.cross(b));
    if mesh_kernel::clean::is_degenerate_triangle(p, crate::weights::DEGENERATE_TOLERANCE) || la == 0.0 {
        let mean = (la + b.length() + (p[2] - p[1]).length()) / 3.0;
        let l = if mean > 0.0 { mean } else { fallback_length.max(f64::MIN_POSITIVE) };
        return [DVec2::ZERO, DVec2::new(l, 0.0), DVec2::new(0.0, l)];
    }
    [DVec2::ZERO, DVec2::new(la, 0.0), DVec2::new(a.dot(b) / la, cross / la)]
}

#[cfg(test)]
mod tests {
    use super::*;
    use mesh_kernel::shapes;

    /// Places copies of `parts` side by side along x as one mesh.
    fn side_by_side(parts: &[TriMesh]) -> TriMesh {
        let (mut p, mut f) = (Vec::new(), Vec::new());
        for (k, m) in parts.iter().enumerate() {
            let n = p.len() as u32;
            p.extend(m.positions().iter().map(|q| *q + DVec3::new(10.0 * k as f64, 0.0, 0.0)));
            f.extend(m.faces().iter().map(|t| t.map(|v| v + n)));
        }
        TriMesh::new(p, f).unwrap()
    }

    #[test]
    fn faces_apart_keeps_lengths_and_orientation() {
        let m = shapes::icosphere(1).unwrap();
        let (chart, origin, uv) = faces_apart(&m, 1.0).unwrap();
        assert_eq!(chart.face_count(), m.face_count());
        for (f, t) in chart.faces().iter().enumerate() {
            let q = t.map(|v| uv[v as usize]);
            assert!((q[1] - q[0]).perp_dot(q[2] - q[0]) > 0.0);
            let p = m.triangle(FaceId::new(f));
            assert!(((q[1] - q[0]).length() - (p[1] - p[0]).length()).abs() < 1e-12);
            assert!(((q[2] - q[1]).length() - (p[2] - p[1]).length()).abs() < 1e-12);
            assert_eq!(t.map(|v| origin[v as usize].0), m.faces()[f]);
        }
        let d = distortion(&chart, &uv).unwrap().summary;
        assert!(d.bijective && (d.angle_distortion_max - 1.0).abs() < 1e-9);
    }

    /// 2^1000 and 2^-1000 times the mesh: the same charts and UVs, the
    /// input's own positions in the charts, the scale divided by the
    /// factor (the areas of such meshes over- and underflow).
    #[test]
    fn the_atlas_does_not_depend_on_the_unit_of_length() {
        let mesh = side_by_side(&[shapes::torus(2.0, 0.5, 24, 12).unwrap(), shapes::icosphere(2).unwrap()]);
        let plain = atlas(&mesh, &AtlasOptions::default()).unwrap();
        for factor in [2f64.powi(1000), 2f64.powi(-1000), 2f64.powi(200), 2f64.powi(-200)] {
            let p: Vec<DVec3> = mesh.positions().iter().map(|q| *q * factor).collect();
            let scaled = TriMesh::new(p, mesh.faces().to_vec()).unwrap();
            let a = atlas(&scaled, &AtlasOptions::default()).unwrap();
            assert_eq!(a.charts.len(), plain.charts.len());
            assert_eq!(a.face_chart, plain.face_chart);
            for (q, r) in a.corner_uvs.iter().flatten().zip(plain.corner_uvs.iter().flatten()) {
                assert!((*q - *r).length() < 1e-12, "{q} vs {r} at {factor:e}");
            }
            assert!((a.scale * factor / plain.scale - 1.0).abs() < 1e-12);
            for c in &a.charts {
                let expected: Vec<DVec3> = c.vertices.iter().map(|&v| scaled.position(v)).collect();
                assert_eq!(c.mesh.positions(), expected.as_slice());
                assert!(c.surface_area.is_finite() || factor > 1.0);
                assert!(c.surface_area > 0.0 || factor < 1.0);
            }
            // Where the areas fit a double, they are the input's.
            let squared = factor * factor;
            if squared.is_normal() {
                let pairs = a.charts.iter().zip(&plain.charts).map(|(c, d)| (&c.distortion, &d.distortion));
                for (d, e) in pairs.chain([(&a.summary.distortion, &plain.summary.distortion)]) {
                    assert!((d.surface_area / (e.surface_area * squared) - 1.0).abs() < 1e-12);
                    assert!((d.dirichlet_energy / (e.dirichlet_energy * squared) - 1.0).abs() < 1e-12);
                    assert_eq!(d.area_distortion_max, e.area_distortion_max);
                }
            }
        }
    }

    #[test]
    fn charts_keep_their_share_of_the_area() {
        // A unit square and one of side 3: parameter areas 1 : 9.
        let small = shapes::grid(1.0, 1.0, 4, 4).unwrap();
        let big = shapes::grid(3.0, 3.0, 4, 4).unwrap();
        let mesh = side_by_side(&[small, big]);
        for method in [ParamMethod::Tutte, ParamMethod::Harmonic, ParamMethod::Lscm] {
            let a = atlas(&mesh, &AtlasOptions { method, ..Default::default() }).unwrap();
            let areas: Vec<f64> = a.charts.iter().map(|c| c.distortion.uv_area).collect();
            assert!((areas[1] / areas[0] - 9.0).abs() < 1e-9, "{}: {areas:?}", method.name());
            // Each chart's parameter area is scale^2 times its surface area.
            let s2 = a.scale * a.scale;
            assert!((areas[0] - s2).abs() < 1e-9 * s2, "{}", method.name());
        }
    }

    #[test]
    fn zero_area_components_and_failing_methods_fall_back() {
        // A planar disk, a triangle (no square boundary: 3 boundary vertices)
        // and a component whose faces all have zero area.
        let disk = shapes::disk(4, 1).unwrap();
        let tri = TriMesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y], vec![[0, 1, 2]]).unwrap();
        let line = TriMesh::new(
            vec![DVec3::ZERO, DVec3::X, DVec3::new(2.0, 0.0, 0.0), DVec3::new(3.0, 0.0, 0.0)],
            vec![[0, 1, 2], [0, 2, 3]],
        )
        .unwrap();
        let mesh = side_by_side(&[disk, tri, line]);
        let options =
            AtlasOptions { method: ParamMethod::Harmonic, boundary: BoundaryMap::Square, ..Default::default() };
        let a = atlas(&mesh, &options).unwrap();
        assert_eq!(a.summary.charts, 3);
        assert_eq!(a.charts[0].layout, ChartLayout::Method(ParamMethod::Harmonic));
        assert!(a.charts[1].fallback.as_deref().is_some_and(|r| r.contains("square")), "{:?}", a.charts[1].fallback);
        assert_eq!(a.charts[1].layout, ChartLayout::Method(ParamMethod::Tutte));
        assert!(a.charts[2].zero_area && a.summary.zero_area_charts == 1);
        assert!(a.charts[2].rect.size().min_element() > 0.0);
        assert_eq!(a.summary.distortion.degenerate_faces, 2);
        assert!(a
            .corner_uvs
            .iter()
            .flatten()
            .all(|q| q.is_finite() && q.cmpge(DVec2::ZERO).all() && q.cmple(DVec2::ONE).all()));
    }

    #[test]
    fn split_charts_distort_less() {
        // A sphere cut into one disk crowds half of it near the centre;
        // regions of at most 320 faces are nearly flat caps.
        let sphere = shapes::icosphere(4).unwrap();
        let one = atlas(&sphere, &AtlasOptions { method: ParamMethod::Tutte, ..Default::default() }).unwrap();
        let options = AtlasOptions { method: ParamMethod::Tutte, max_chart_faces: Some(320), ..Default::default() };
        let split = atlas(&sphere, &options).unwrap();
        assert_eq!((one.charts.len(), split.charts.len()), (1, 5120 / 320));
        let (a, b) = (one.summary.distortion, split.summary.distortion);
        assert!(b.flipped_faces == 0 && b.collapsed_faces == 0 && b.bijective);
        assert!(b.area_distortion_mean < a.area_distortion_mean, "{b:?} vs {a:?}");
        assert!(b.angle_distortion_mean < a.angle_distortion_mean, "{b:?} vs {a:?}");
        for (i, c) in split.charts.iter().enumerate() {
            assert!(c.faces.len() <= 3 * 320, "{}", c.faces.len());
            assert!(split.charts[i + 1..].iter().all(|d| !c.rect.meets(&d.rect)));
        }
    }

    #[test]
    fn charts_are_split_until_distortion_is_bounded() {
        let sphere = shapes::icosphere(4).unwrap();
        let options = AtlasOptions { max_area_distortion: Some(1.5), ..Default::default() };
        let a = atlas(&sphere, &options).unwrap();
        assert!(a.charts.len() > 1);
        for c in &a.charts {
            assert!(c.distortion.area_distortion_mean <= 1.5 || c.faces.len() == 1, "{:?}", c.distortion);
        }
        assert_eq!(a.charts.iter().map(|c| c.faces.len()).sum::<usize>(), sphere.face_count());
        let bad = AtlasOptions { max_area_distortion: Some(0.5), ..Default::default() };
        assert!(atlas(&sphere, &bad).is_err());
    }

    #[test]
    fn bad_options_are_refused() {
        let m = shapes::disk(2, 1).unwrap();
        let fixed = AtlasOptions { boundary: BoundaryMap::Fixed(vec![]), ..Default::default() };
        assert!(atlas(&m, &fixed).is_err());
        assert!(atlas(&m, &AtlasOptions { margin: f64::NAN, ..Default::default() }).is_err());
        let bad = AtlasOptions { method: ParamMethod::Intrinsic { lambda: -1.0, mu: 0.0 }, ..Default::default() };
        assert!(atlas(&m, &bad).is_err());
        let empty = TriMesh::new(vec![], vec![]).unwrap();
        assert_eq!(atlas(&empty, &AtlasOptions::default()).unwrap().charts.len(), 0);
    }
}
