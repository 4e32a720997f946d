//! [`remesh`]: the entry point, and the triangulation of each chart.

use mesh_kernel::{geometry, TriMesh};
use mesh_param::{atlas, AtlasOptions, BoundaryMap, ParamMethod, Spacing};

use crate::chart::{chart_polygon, chart_triangles};
use crate::collapse::collapse_short_edges;
use crate::error::{RemeshError, Result};
use crate::flips::surface_delaunay_flips;
use crate::hausdorff::TriangleGrid;
use crate::report::{normal_disagreements, quality_report, RemeshReport};
use crate::seams::{chart_loops, sample_seams};
use crate::smooth::tangential_smoothing;
use crate::stitch::{check_stitching, split_third_faces};

/// The refinement's size bound is on a triangle's longest edge; Delaunay
/// refinement then leaves edges between about half and all of it. The size
/// asked for is this multiple of the edge length times the map's smallest
/// stretch, so that the edges come out spread around the edge length
/// (measured on the shapes and shared meshes of the README after the flips,
/// collapses and smoothing: a mean edge of 0.86-0.97 times the edge length;
/// 1.5 gave 0.80-0.89).
pub const SIZE_FACTOR: f64 = 1.7;

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
    /// Rounds of tangential smoothing (Botsch and Kobbelt 2004) after the flips (each: two
    /// iterations of moving every vertex toward its neighbours' centroid in
    /// its tangent plane, projected back onto the input, then flips).
    /// Default `3`; `0` turns it off; at most 100. The seams' samples are placed along
    /// input edges, and where short seam curves meet they leave triangles
    /// of a few degrees that no flip cures; the smoothing moves them.
    pub smoothing_rounds: usize,
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
            smoothing_rounds: 3,
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
    if o.smoothing_rounds > 100 {
        return Err(RemeshError::InvalidOption {
            name: "smoothing_rounds",
            reason: format!("{} is not in [0, 100]", o.smoothing_rounds),
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
    let mut triangles = Vec::with_capacity(loops.len());
    for (c, lp) in loops.iter().enumerate() {
        let polygon = chart_polygon(&atlas.charts[c], lp, &seams);
        triangles.push(chart_triangles(c, &atlas.charts[c], polygon, &mut seams, options)?);
    }
    let stitch_splits = split_third_faces(&mut triangles, &atlas.charts, &mut seams.positions)?;
    for (c, tris) in triangles.into_iter().enumerate() {
        face_chart.extend(std::iter::repeat_n(c as u32, tris.len()));
        faces.extend(tris.into_iter().map(|t| t.0));
    }
    check_stitching(&faces, &face_chart, options.edge_length)?;
    let (mut flips, mut collapses, mut moves) = (0, 0, 0);
    let mut positions = seams.positions;
    let h = options.edge_length;
    if options.max_fold_degrees > 0.0 {
        flips += surface_delaunay_flips(&positions, &mut faces, options.max_fold_degrees);
        let kept;
        (positions, faces, kept, collapses) = collapse_short_edges(positions, faces, 0.5 * h, 1.5 * h);
        face_chart = face_chart.into_iter().zip(kept).filter(|(_, k)| *k).map(|(c, _)| c).collect();
        flips += surface_delaunay_flips(&positions, &mut faces, options.max_fold_degrees);
    }
    if faces.is_empty() {
        return Err(RemeshError::ChartFailed { chart: 0, reason: "no output triangle".into() });
    }
    let grid = TriangleGrid::new(mesh).ok_or(mesh_kernel::MeshError::Empty)?;
    let mut out = TriMesh::new(positions, faces)?;
    for _ in 0..options.smoothing_rounds {
        moves += tangential_smoothing(&mut out, mesh, &grid, h, 2);
        if options.max_fold_degrees > 0.0 {
            let (positions, mut faces) = out.into_parts();
            flips += surface_delaunay_flips(&positions, &mut faces, options.max_fold_degrees);
            out = TriMesh::new(positions, faces)?;
        }
    }
    let mut report = quality_report(mesh, &out, options.edge_length, options.hausdorff);
    report.charts = atlas.charts.len();
    report.seam_curves = seams.curves;
    report.seam_vertices = seam_vertices;
    report.flips = flips;
    report.collapses = collapses;
    report.smoothing_moves = moves;
    report.stitch_splits = stitch_splits;
    report.normal_disagreements = normal_disagreements(&out, mesh, &grid);
    report.chart_area_distortion_max =
        atlas.charts.iter().map(|c| c.distortion.area_distortion_mean).fold(1.0, f64::max);
    Ok(Remeshed { mesh: out, face_chart, report })
}
