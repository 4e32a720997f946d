//! The report of a remeshing: counts, angles, edge lengths against the
//! target, Hausdorff distance to the input, and the topology of both.

use mesh_kernel::{geometry, FaceId, TriMesh};

use crate::hausdorff::{one_sided_hausdorff, TriangleGrid};

/// Euler characteristic, components and boundary loops of a mesh.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TopologySummary {
    /// chi = V - E + F over referenced vertices.
    pub euler_characteristic: i64,
    /// Connected components.
    pub components: usize,
    /// Boundary loops (`None` for a non-manifold mesh).
    pub boundary_loops: Option<usize>,
    /// Whether every edge has one or two faces and every vertex one fan.
    pub manifold: bool,
}

impl TopologySummary {
    /// The topology of `mesh`. O(V + F).
    pub fn of(mesh: &TriMesh) -> Self {
        let conn = mesh.connectivity();
        Self {
            euler_characteristic: conn.euler_characteristic(),
            components: conn.components().count,
            boundary_loops: conn.boundary_loop_count(),
            manifold: conn.is_manifold(),
        }
    }
}

/// Edge lengths of the output against the target `h`.
#[derive(Debug, Clone, PartialEq)]
pub struct EdgeLengthStats {
    /// Shortest edge.
    pub min: f64,
    /// Mean edge.
    pub mean: f64,
    /// Longest edge.
    pub max: f64,
    /// Mean over the target.
    pub mean_over_target: f64,
    /// Fraction of edges within `[0.5 h, 1.5 h]`.
    pub within_half: f64,
    /// Fraction of edges within `[0.75 h, 1.25 h]`.
    pub within_quarter: f64,
    /// Fractions of edges by length over target, in bins of width
    /// [`EdgeLengthStats::BIN_WIDTH`] from 0; the last bin holds every edge
    /// from 2 h up.
    pub histogram: Vec<f64>,
}

impl EdgeLengthStats {
    /// Width of a histogram bin, in units of the target.
    pub const BIN_WIDTH: f64 = 0.25;
    /// Number of histogram bins.
    pub const BINS: usize = 9;

    /// The statistics of `lengths` against `h` (all zero for no edges). O(n).
    pub fn of(lengths: &[f64], h: f64) -> Self {
        let n = lengths.len().max(1) as f64;
        let mut histogram = vec![0.0; Self::BINS];
        for &l in lengths {
            let b = ((l / h / Self::BIN_WIDTH) as usize).min(Self::BINS - 1);
            histogram[b] += 1.0 / n;
        }
        let frac = |lo: f64, hi: f64| lengths.iter().filter(|&&l| l >= lo * h && l <= hi * h).count() as f64 / n;
        let mean = lengths.iter().sum::<f64>() / n;
        Self {
            min: if lengths.is_empty() { 0.0 } else { lengths.iter().copied().fold(f64::INFINITY, f64::min) },
            mean,
            max: lengths.iter().copied().fold(0.0, f64::max),
            mean_over_target: mean / h,
            within_half: frac(0.5, 1.5),
            within_quarter: frac(0.75, 1.25),
            histogram,
        }
    }
}

/// Sampled Hausdorff distances between the input and the output.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HausdorffDistance {
    /// Largest distance from the output's samples to the input surface.
    pub output_to_input: f64,
    /// Largest distance from the input's samples to the output surface.
    pub input_to_output: f64,
    /// The larger of the two.
    pub symmetric: f64,
    /// The input's bounding-box diagonal; the distances over it are below.
    pub diagonal: f64,
    /// `output_to_input / diagonal`.
    pub output_to_input_relative: f64,
    /// `input_to_output / diagonal`.
    pub input_to_output_relative: f64,
    /// `symmetric / diagonal`.
    pub symmetric_relative: f64,
}

/// What [`crate::remesh()`] reports.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct RemeshReport {
    /// The target edge length.
    pub edge_length: f64,
    /// Input vertex count.
    pub input_vertices: usize,
    /// Input face count.
    pub input_faces: usize,
    /// Output vertex count.
    pub vertices: usize,
    /// Output face count.
    pub faces: usize,
    /// Charts of the atlas.
    pub charts: usize,
    /// The largest mean area distortion of a chart (eq. 2.8-2.9).
    pub chart_area_distortion_max: f64,
    /// Seam curves (between corners) sampled.
    pub seam_curves: usize,
    /// Edge flips done after stitching ([`crate::RemeshOptions::max_fold_degrees`]).
    pub flips: usize,
    /// Short edges collapsed after stitching.
    pub collapses: usize,
    /// Output vertices on the seams (the first ones of the output).
    pub seam_vertices: usize,
    /// Smallest angle of the output, in degrees.
    pub min_angle_degrees: f64,
    /// Mean of the smallest angle of each output triangle, in degrees.
    pub mean_min_angle_degrees: f64,
    /// Fraction of output triangles whose smallest angle is under 20
    /// degrees.
    pub below_20_degrees: f64,
    /// Output edge lengths against the target.
    pub edge_lengths: EdgeLengthStats,
    /// Hausdorff distances (`None` when not asked for).
    pub hausdorff: Option<HausdorffDistance>,
    /// Edges inside charts split at their midpoint so that no output edge
    /// has more than two faces (charts reaching around a corner where
    /// others meet).
    pub stitch_splits: usize,
    /// Vertex moves kept by the tangential smoothing
    /// ([`crate::RemeshOptions::smoothing_rounds`]).
    pub smoothing_moves: usize,
    /// Output triangles of the final mesh whose normal points away from the
    /// normal of the input face nearest to their centroid: folds of the
    /// output, or triangles across a sharp fold of the input (or near a
    /// thin part, where the nearest face may be on the other side).
    pub normal_disagreements: usize,
    /// Topology of the input.
    pub input_topology: TopologySummary,
    /// Topology of the output.
    pub output_topology: TopologySummary,
    /// Whether chi, components or boundary loops differ (never expected:
    /// a flag, not a silent change).
    pub topology_changed: bool,
}

/// The quality part of the report of `output` against `input`; the
/// atlas fields are left zero for the caller. O(V + F), plus the
/// Hausdorff sampling when `hausdorff`.
pub fn quality_report(input: &TriMesh, output: &TriMesh, h: f64, hausdorff: bool) -> RemeshReport {
    let smallest: Vec<f64> = output
        .face_ids()
        .map(|f| geometry::triangle_angles(output.triangle(f)).into_iter().fold(f64::INFINITY, f64::min).to_degrees())
        .collect();
    let nf = smallest.len().max(1) as f64;
    let input_topology = TopologySummary::of(input);
    let output_topology = TopologySummary::of(output);
    let topology_changed = input_topology.euler_characteristic != output_topology.euler_characteristic
        || input_topology.components != output_topology.components
        || input_topology.boundary_loops != output_topology.boundary_loops;
    let hausdorff = if hausdorff { hausdorff_distance(input, output) } else { None };
    RemeshReport {
        edge_length: h,
        input_vertices: input.vertex_count(),
        input_faces: input.face_count(),
        vertices: output.vertex_count(),
        faces: output.face_count(),
        charts: 0,
        chart_area_distortion_max: 0.0,
        seam_curves: 0,
        seam_vertices: 0,
        flips: 0,
        collapses: 0,
        min_angle_degrees: smallest.iter().copied().fold(f64::INFINITY, f64::min).min(180.0),
        mean_min_angle_degrees: smallest.iter().sum::<f64>() / nf,
        below_20_degrees: smallest.iter().filter(|&&a| a < 20.0).count() as f64 / nf,
        edge_lengths: EdgeLengthStats::of(&geometry::edge_lengths(output), h),
        hausdorff,
        stitch_splits: 0,
        smoothing_moves: 0,
        normal_disagreements: 0,
        input_topology,
        output_topology,
        topology_changed,
    }
}

/// The sampled Hausdorff distances between two surfaces, relative to the
/// bounding-box diagonal of `a` (`None` when either has no faces or
/// non-finite positions).
pub fn hausdorff_distance(a: &TriMesh, b: &TriMesh) -> Option<HausdorffDistance> {
    let output_to_input = one_sided_hausdorff(b, a)?;
    let input_to_output = one_sided_hausdorff(a, b)?;
    let diagonal = geometry::bounding_box(a)?.diagonal();
    let symmetric = output_to_input.max(input_to_output);
    let rel = |d: f64| if diagonal > 0.0 { d / diagonal } else { 0.0 };
    Some(HausdorffDistance {
        output_to_input,
        input_to_output,
        symmetric,
        diagonal,
        output_to_input_relative: rel(output_to_input),
        input_to_output_relative: rel(input_to_output),
        symmetric_relative: rel(symmetric),
    })
}

/// The output triangles whose normal points away from the normal of the
/// input face nearest to their centroid ([`RemeshReport::normal_disagreements`]);
/// `grid` is over `input`'s faces. O(F x a grid query).
pub(crate) fn normal_disagreements(output: &TriMesh, input: &TriMesh, grid: &TriangleGrid) -> usize {
    let count = |f: usize| {
        let t = output.triangle(FaceId::new(f));
        let Some((_, g)) = grid.closest((t[0] + t[1] + t[2]) / 3.0) else { return 0 };
        let n = geometry::triangle_normal(input.triangle(FaceId::new(g)));
        usize::from(geometry::double_area_vector(t).dot(n) < 0.0)
    };
    mesh_kernel::par::map(output.face_count(), count).into_iter().sum()
}
