//! `mesh remesh`: remeshing through a parameterization (chapter section
//! 2.4, "texture mapping, remeshing"): low-distortion charts, seams sampled
//! once, constrained Delaunay refinement of each chart's parameter domain
//! sized by the map's scale, lifted back onto the input.

use std::path::PathBuf;
use std::time::Instant;

use mesh_io::MeshView;
use mesh_kernel::geometry;
use mesh_remesh::{remesh, RemeshOptions, RemeshReport, TopologySummary};
use serde::Serialize;

use crate::input::InputArgs;
use crate::output::{check_output, finite, print_json, write_mesh, CliResult, SaveArgs};

/// Arguments of `mesh remesh`.
#[derive(Debug, clap::Args)]
#[command(mut_arg("json", |a| a.help("Print the report as JSON on standard output")))]
#[command(mut_arg("force", |a| a.help("Allow the output to be the input file")))]
pub struct Args {
    #[command(flatten)]
    pub(crate) input: InputArgs,
    /// Target edge length, in the unit of the input. Default: the input's
    /// mean edge length (a remesh at about the same resolution).
    #[arg(long, value_name = "H")]
    edge_length: Option<f64>,
    /// Smallest angle asked of the refinement inside each chart, in degrees
    /// (0-35; triangles along the seams may miss it).
    #[arg(long, value_name = "A", default_value_t = 28.0)]
    min_angle: f64,
    /// The most output vertices; a smaller edge length is refused before any work.
    #[arg(long, value_name = "N", default_value_t = 4_000_000)]
    max_vertices: usize,
    /// Rounds of tangential smoothing on the input surface (each two
    /// iterations and flips); 0 turns it off.
    #[arg(long, value_name = "N", default_value_t = 3, value_parser = clap::value_parser!(u32).range(0..=100))]
    smoothing_rounds: u32,
    /// Skip the Hausdorff distance (it costs about as much as the remeshing).
    #[arg(long)]
    no_hausdorff: bool,
    /// Output mesh (.obj, .off, .ply, .stl, .gltf, .glb).
    #[arg(long, value_name = "FILE")]
    out: PathBuf,
    #[command(flatten)]
    save: SaveArgs,
}

impl Args {
    /// The library options this command line set.
    pub fn given(&self) -> Vec<(&'static str, String)> {
        use crate::errors::flag;
        let mut given = vec![
            ("min_angle", flag("--min-angle", self.min_angle)),
            ("max_vertices", flag("--max-vertices", self.max_vertices)),
            ("smoothing_rounds", flag("--smoothing-rounds", self.smoothing_rounds)),
        ];
        if let Some(h) = self.edge_length {
            given.push(("edge_length", flag("--edge-length", h)));
        }
        given
    }
}

/// Topology of one mesh in the report.
#[derive(Debug, Serialize)]
struct Topology {
    euler_characteristic: i64,
    components: usize,
    boundary_loops: Option<usize>,
    manifold: bool,
}

impl From<TopologySummary> for Topology {
    fn from(t: TopologySummary) -> Self {
        Self {
            euler_characteristic: t.euler_characteristic,
            components: t.components,
            boundary_loops: t.boundary_loops,
            manifold: t.manifold,
        }
    }
}

/// Output edge lengths against the target.
#[derive(Debug, Serialize)]
struct EdgeLengths {
    min: Option<f64>,
    mean: Option<f64>,
    max: Option<f64>,
    mean_over_target: Option<f64>,
    /// Fraction within [0.5 H, 1.5 H].
    within_half: f64,
    /// Fraction within [0.75 H, 1.25 H].
    within_quarter: f64,
    /// Bin width (in units of H) of `histogram`; the last bin is open.
    bin_width: f64,
    histogram: Vec<f64>,
}

/// Sampled Hausdorff distances, absolute and over the input's bounding-box diagonal.
#[derive(Debug, Serialize)]
struct Hausdorff {
    output_to_input: f64,
    input_to_output: f64,
    symmetric: f64,
    diagonal: f64,
    output_to_input_relative: f64,
    input_to_output_relative: f64,
    symmetric_relative: f64,
}

/// The JSON report.
#[derive(Debug, Serialize)]
struct Summary {
    input: String,
    output: String,
    edge_length: f64,
    /// "given" or "mean edge length of the input".
    edge_length_source: &'static str,
    input_vertices: usize,
    input_faces: usize,
    vertices: usize,
    faces: usize,
    charts: usize,
    chart_area_distortion_max: f64,
    seam_curves: usize,
    seam_vertices: usize,
    flips: usize,
    collapses: usize,
    stitch_splits: usize,
    smoothing_moves: usize,
    min_angle_degrees: Option<f64>,
    mean_min_angle_degrees: Option<f64>,
    below_20_degrees: f64,
    edge_lengths: EdgeLengths,
    hausdorff: Option<Hausdorff>,
    normal_disagreements: usize,
    input_topology: Topology,
    output_topology: Topology,
    topology_changed: bool,
    time_ms: f64,
}

fn summarize(input: String, output: String, source: &'static str, r: &RemeshReport, time_ms: f64) -> Summary {
    let e = &r.edge_lengths;
    Summary {
        input,
        output,
        edge_length: r.edge_length,
        edge_length_source: source,
        input_vertices: r.input_vertices,
        input_faces: r.input_faces,
        vertices: r.vertices,
        faces: r.faces,
        charts: r.charts,
        chart_area_distortion_max: r.chart_area_distortion_max,
        seam_curves: r.seam_curves,
        seam_vertices: r.seam_vertices,
        flips: r.flips,
        collapses: r.collapses,
        stitch_splits: r.stitch_splits,
        smoothing_moves: r.smoothing_moves,
        min_angle_degrees: finite(r.min_angle_degrees),
        mean_min_angle_degrees: finite(r.mean_min_angle_degrees),
        below_20_degrees: r.below_20_degrees,
        edge_lengths: EdgeLengths {
            min: finite(e.min),
            mean: finite(e.mean),
            max: finite(e.max),
            mean_over_target: finite(e.mean_over_target),
            within_half: e.within_half,
            within_quarter: e.within_quarter,
            bin_width: mesh_remesh::EdgeLengthStats::BIN_WIDTH,
            histogram: e.histogram.clone(),
        },
        hausdorff: r.hausdorff.map(|d| Hausdorff {
            output_to_input: d.output_to_input,
            input_to_output: d.input_to_output,
            symmetric: d.symmetric,
            diagonal: d.diagonal,
            output_to_input_relative: d.output_to_input_relative,
            input_to_output_relative: d.input_to_output_relative,
            symmetric_relative: d.symmetric_relative,
        }),
        normal_disagreements: r.normal_disagreements,
        input_topology: r.input_topology.into(),
        output_topology: r.output_topology.into(),
        topology_changed: r.topology_changed,
        time_ms,
    }
}

/// Runs `mesh remesh`. A changed topology is written and reported, then
/// returned as an error (exit status 1).
pub fn run(args: &Args) -> CliResult<()> {
    check_output(&args.out, args.input.path(), args.save.force)?;
    let data = args.input.load()?;
    let mesh = data.mesh;
    let (h, source) = match args.edge_length {
        Some(h) => (h, "given"),
        None => (geometry::mean_edge_length(&mesh), "mean edge length of the input"),
    };
    let options = RemeshOptions {
        edge_length: h,
        min_angle: args.min_angle,
        max_vertices: args.max_vertices,
        smoothing_rounds: args.smoothing_rounds as usize,
        hausdorff: !args.no_hausdorff,
        ..Default::default()
    };
    let start = Instant::now();
    let r = remesh(&mesh, &options)?;
    let time_ms = start.elapsed().as_secs_f64() * 1e3;
    write_mesh(&args.out, MeshView::new(&r.mesh), &args.save.write.options(Default::default()))?;
    let s = summarize(args.input.describe(), args.out.display().to_string(), source, &r.report, time_ms);
    if args.save.json {
        print_json(&s)?;
    } else {
        print_text(&s);
    }
    if s.normal_disagreements > 0 {
        eprintln!(
            "mesh: warning: {} of {} output faces point away from the normal of the nearest input face (a fold of \
             the output, a sharp fold of the input, or a thin part)",
            s.normal_disagreements, s.faces
        );
    }
    if s.topology_changed {
        return Err(format!(
            "the output's topology differs from the input's (chi {} -> {}, components {} -> {}, boundary loops \
             {:?} -> {:?}); the mesh was written to {} for inspection",
            s.input_topology.euler_characteristic,
            s.output_topology.euler_characteristic,
            s.input_topology.components,
            s.output_topology.components,
            s.input_topology.boundary_loops,
            s.output_topology.boundary_loops,
            s.output
        )
        .into());
    }
    Ok(())
}

fn print_text(s: &Summary) {
    println!("mesh: {} ({} vertices, {} faces)", s.input, s.input_vertices, s.input_faces);
    println!("edge length: {} ({})", s.edge_length, s.edge_length_source);
    println!(
        "output: {} ({} vertices, {} faces, {} charts, {:.0} ms)",
        s.output, s.vertices, s.faces, s.charts, s.time_ms
    );
    let angle = |a: Option<f64>| a.map_or("-".into(), |a| format!("{a:.1}"));
    println!(
        "smallest angle: {} degrees, mean smallest angle {} degrees, {:.1}% of triangles under 20 degrees",
        angle(s.min_angle_degrees),
        angle(s.mean_min_angle_degrees),
        100.0 * s.below_20_degrees
    );
    println!(
        "edges: mean {:.3} H, {:.1}% within [0.5 H, 1.5 H], {:.1}% within [0.75 H, 1.25 H]",
        s.edge_lengths.mean_over_target.unwrap_or(f64::NAN),
        100.0 * s.edge_lengths.within_half,
        100.0 * s.edge_lengths.within_quarter
    );
    if let Some(d) = &s.hausdorff {
        println!(
            "Hausdorff distance / bounding-box diagonal: {:.2e} (output to input {:.2e}, input to output {:.2e})",
            d.symmetric_relative, d.output_to_input_relative, d.input_to_output_relative
        );
    }
    let t = |t: &Topology| {
        format!("chi {}, {} components, {:?} boundary loops", t.euler_characteristic, t.components, t.boundary_loops)
    };
    println!("topology: input {}; output {}", t(&s.input_topology), t(&s.output_topology));
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::commands::parse_args;

    #[test]
    fn remeshes_a_shape_and_refuses_bad_lengths() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("out.obj");
        let o = out.to_str().unwrap();
        let a: Args = parse_args("remesh", &["--shape", "icosphere", "--res", "3", "--edge-length", "0.2", "--out", o]);
        run(&a).unwrap();
        let back = mesh_io::read(&out).unwrap().mesh;
        assert!(back.face_count() > 100);
        assert_eq!(back.connectivity().euler_characteristic(), 2);
        for bad in ["0", "-1", "NaN"] {
            let flag = format!("--edge-length={bad}");
            let a: Args = parse_args("remesh", &["--shape", "icosphere", &flag, "--out", o]);
            let e = crate::errors::translate(run(&a).unwrap_err(), &a.given(), None).to_string();
            assert!(e.contains("--edge-length"), "{e}");
        }
        let a: Args = parse_args("remesh", &["--shape", "icosphere", "--edge-length", "1e-6", "--out", o]);
        let e = crate::errors::translate(run(&a).unwrap_err(), &a.given(), None).to_string();
        assert!(e.contains("--max-vertices"), "{e}");
    }
}
