//! `mesh curvature`: Gaussian (eq. 2.25), mean (eq. 2.26) and principal
//! curvatures and directions (eq. 2.27-2.31) of a mesh, written as binary
//! PLY with per-vertex `double` properties, with summary statistics.

use std::f64::consts::TAU;
use std::path::PathBuf;
use std::time::Instant;

use mesh_curvature::{
    curvature_tensor, gaussian_curvature, mean_curvature, AreaKind, Degree, FitOptions, GaussianOptions, MeanOptions,
    Method, Neighborhood, StatusCounts, TensorOptions, VertexStatus,
};
use mesh_io::MeshView;
use serde::Serialize;

use crate::input::InputArgs;
use crate::output::{binary_ply, check_not_input, ensure_parent, finite, print_json, CliResult};

/// Arguments of `mesh curvature`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    input: InputArgs,
    /// Output PLY file: positions as double and per-vertex double properties
    /// gaussian mean k1 k2 d1x d1y d1z d2x d2y d2z shape_index curvedness valid.
    #[arg(long, value_name = "OUT.ply")]
    out: PathBuf,
    /// Curvature tensor estimator: fit (quartic jet over the 2-ring, the most
    /// accurate), quadric (libigl-style quadric over the 1-ring),
    /// rusinkiewicz (per-face fit, the fastest) or normal-cycle.
    #[arg(long, default_value = "fit")]
    method: String,
    /// Neighbourhood of the fit or normal cycle as a geodesic ball of this
    /// radius (model units) instead of rings.
    #[arg(long, value_name = "R", conflicts_with = "rings")]
    radius: Option<f64>,
    /// Neighbourhood of the fit or normal cycle as a k-ring (default: 2 for
    /// fit, 1 for quadric and normal-cycle).
    #[arg(long, value_name = "K")]
    rings: Option<u32>,
    /// Area dividing the integrated Gaussian and mean curvature: mixed
    /// (mixed Voronoi) or barycentric.
    #[arg(long, default_value = "mixed")]
    area: String,
    /// Print a JSON summary instead of text.
    #[arg(long)]
    json: bool,
    /// Allow writing over the input file.
    #[arg(long)]
    force: bool,
}

/// Minimum, maximum and mean of a field over the vertices with an estimate.
#[derive(Debug, Clone, Serialize)]
pub struct Stats {
    /// Smallest value (`null` without valid vertices).
    pub min: Option<f64>,
    /// Largest value.
    pub max: Option<f64>,
    /// Mean value.
    pub mean: Option<f64>,
}

impl Stats {
    fn of(values: &[f64], keep: &[bool]) -> Self {
        let kept: Vec<f64> = values.iter().zip(keep).filter(|(_, k)| **k).map(|(v, _)| *v).collect();
        if kept.is_empty() {
            return Self { min: None, max: None, mean: None };
        }
        let min = kept.iter().copied().fold(f64::INFINITY, f64::min);
        let max = kept.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let mean = kept.iter().sum::<f64>() / kept.len() as f64;
        Self { min: finite(min), max: finite(max), mean: finite(mean) }
    }
}

/// Vertex counts per status of the tensor estimate.
#[derive(Debug, Clone, Serialize)]
pub struct Counts {
    /// Interior vertices with an estimate.
    pub valid: usize,
    /// Boundary vertices (one-sided estimates).
    pub boundary: usize,
    /// Non-manifold vertices.
    pub non_manifold: usize,
    /// Vertices referenced by no face.
    pub isolated: usize,
    /// Vertices without an estimate (zero area, too few neighbours).
    pub degenerate: usize,
}

/// Everything `mesh curvature --json` prints.
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    /// The input (file or shape).
    pub input: String,
    /// The written PLY file.
    pub output: String,
    /// Number of vertices.
    pub vertices: usize,
    /// The tensor estimator.
    pub method: String,
    /// Sum of angle defects plus boundary geodesic curvature (discrete
    /// Gauss-Bonnet), and 2 pi chi, which it equals on manifold meshes.
    pub gauss_bonnet_total: f64,
    /// 2 pi times the Euler characteristic.
    pub two_pi_chi: f64,
    /// Gaussian curvature (angle defect / area) over valid vertices.
    pub gaussian: Stats,
    /// Mean curvature (cotangent formula) over valid vertices.
    pub mean: Stats,
    /// Maximum principal curvature over valid vertices.
    pub k1: Stats,
    /// Minimum principal curvature over valid vertices.
    pub k2: Stats,
    /// Status counts of the tensor estimate.
    pub status: Counts,
    /// Wall time of each computation, in milliseconds.
    pub timings_ms: Timings,
}

/// Wall times in milliseconds.
#[derive(Debug, Clone, Serialize)]
pub struct Timings {
    /// Angle defect.
    pub gaussian: f64,
    /// Cotangent mean curvature.
    pub mean: f64,
    /// Curvature tensor.
    pub tensor: f64,
}

/// The tensor options from the command line.
fn tensor_options(args: &Args) -> CliResult<TensorOptions> {
    let nbh = |default_rings: u32| -> CliResult<Neighborhood> {
        Ok(match (args.radius, args.rings) {
            (Some(r), _) => Neighborhood::Ball(r).validate()?,
            (None, Some(k)) => Neighborhood::Rings(k).validate()?,
            (None, None) => Neighborhood::Rings(default_rings),
        })
    };
    let method = match args.method.as_str() {
        "fit" => Method::Fit(FitOptions { neighborhood: nbh(2)?, ..FitOptions::default() }),
        "quadric" => Method::Fit(FitOptions {
            neighborhood: nbh(1)?,
            degree: Degree::Quadric,
            use_normals: false,
            refine_normal: false,
        }),
        "rusinkiewicz" => {
            if args.radius.is_some() || args.rings.is_some() {
                return Err("--radius and --rings do not apply to rusinkiewicz (1-ring faces)".into());
            }
            Method::Rusinkiewicz
        }
        "normal-cycle" => Method::NormalCycle(nbh(1)?),
        other => {
            return Err(format!("unknown --method `{other}`; known: fit, quadric, rusinkiewicz, normal-cycle").into())
        }
    };
    Ok(TensorOptions { method, ..TensorOptions::default() })
}

fn timed<T>(f: impl FnOnce() -> T) -> (T, f64) {
    let t = Instant::now();
    let out = f();
    (out, t.elapsed().as_secs_f64() * 1e3)
}

/// Runs `mesh curvature`.
pub fn run(args: &Args) -> CliResult<()> {
    let options = tensor_options(args)?;
    let area = match args.area.as_str() {
        "mixed" => AreaKind::MixedVoronoi,
        "barycentric" => AreaKind::Barycentric,
        other => return Err(format!("unknown --area `{other}`; known: mixed, barycentric").into()),
    };
    check_not_input(&args.out, args.input.path(), args.force)?;
    let data = args.input.load()?;
    let mesh = &data.mesh;
    let (k, t_gaussian) = timed(|| gaussian_curvature(mesh, &GaussianOptions { area }));
    let (h, t_mean) = timed(|| mean_curvature(mesh, &MeanOptions { area, ..MeanOptions::default() }));
    let (t, t_tensor) = timed(|| curvature_tensor(mesh, &options));
    let (k, h, t) = (k?, h?, t?);

    let split = |v: &[mesh_core::glam::DVec3]| -> [Vec<f64>; 3] {
        [v.iter().map(|d| d.x).collect(), v.iter().map(|d| d.y).collect(), v.iter().map(|d| d.z).collect()]
    };
    let [d1x, d1y, d1z] = split(&t.d1);
    let [d2x, d2y, d2z] = split(&t.d2);
    let shape_index = t.shape_index();
    let curvedness = t.curvedness();
    let valid: Vec<f64> = t.status.iter().map(|s| if s.is_valid() { 1.0 } else { 0.0 }).collect();
    let view = MeshView::new(mesh)
        .with_scalar("gaussian", &k.pointwise)
        .with_scalar("mean", &h.pointwise)
        .with_scalar("k1", &t.k1)
        .with_scalar("k2", &t.k2)
        .with_scalar("d1x", &d1x)
        .with_scalar("d1y", &d1y)
        .with_scalar("d1z", &d1z)
        .with_scalar("d2x", &d2x)
        .with_scalar("d2y", &d2y)
        .with_scalar("d2z", &d2z)
        .with_scalar("shape_index", &shape_index)
        .with_scalar("curvedness", &curvedness)
        .with_scalar("valid", &valid);
    ensure_parent(&args.out)?;
    let write = binary_ply();
    mesh_io::write(&args.out, view, &write)?;

    let keep_k: Vec<bool> = k.status.iter().map(|s| *s == VertexStatus::Valid).collect();
    let keep_h: Vec<bool> = h.status.iter().map(|s| *s == VertexStatus::Valid).collect();
    let keep_t: Vec<bool> = t.status.iter().map(|s| *s == VertexStatus::Valid).collect();
    let counts = StatusCounts::of(&t.status);
    let summary = Summary {
        input: args.input.describe(),
        output: args.out.display().to_string(),
        vertices: mesh.vertex_count(),
        method: format!("{:?}", options.method),
        gauss_bonnet_total: k.total(),
        two_pi_chi: TAU * mesh.connectivity().euler_characteristic() as f64,
        gaussian: Stats::of(&k.pointwise, &keep_k),
        mean: Stats::of(&h.pointwise, &keep_h),
        k1: Stats::of(&t.k1, &keep_t),
        k2: Stats::of(&t.k2, &keep_t),
        status: Counts {
            valid: counts.valid,
            boundary: counts.boundary,
            non_manifold: counts.non_manifold,
            isolated: counts.isolated,
            degenerate: counts.degenerate,
        },
        timings_ms: Timings { gaussian: t_gaussian, mean: t_mean, tensor: t_tensor },
    };
    if args.json {
        return print_json(&summary);
    }
    print_text(&summary);
    Ok(())
}

fn print_text(s: &Summary) {
    let show = |x: Option<f64>| x.map_or("n/a".to_owned(), |v| format!("{v:.6}"));
    println!("mesh: {} ({} vertices)", s.input, s.vertices);
    println!("  method             {}", s.method);
    println!("  gauss-bonnet       sum K + sum k_g = {:.12}, 2 pi chi = {:.12}", s.gauss_bonnet_total, s.two_pi_chi);
    println!("  {:<18} {:>14} {:>14} {:>14}", "field (valid)", "min", "max", "mean");
    for (name, st) in [("gaussian", &s.gaussian), ("mean", &s.mean), ("k1", &s.k1), ("k2", &s.k2)] {
        println!("  {name:<18} {:>14} {:>14} {:>14}", show(st.min), show(st.max), show(st.mean));
    }
    let c = &s.status;
    println!(
        "  vertices           {} valid, {} boundary, {} non-manifold, {} isolated, {} degenerate",
        c.valid, c.boundary, c.non_manifold, c.isolated, c.degenerate
    );
    let tm = &s.timings_ms;
    println!("  time (ms)          gaussian {:.2}, mean {:.2}, tensor {:.2}", tm.gaussian, tm.mean, tm.tensor);
    println!("  wrote              {}", s.output);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(extra: &[&str]) -> Args {
        crate::commands::parse_args("curvature", extra)
    }

    #[test]
    fn writes_every_property_of_a_torus() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("t.ply");
        let a = args(&["--shape", "torus", "--res", "16", "--out", out.to_str().unwrap(), "--json"]);
        run(&a).unwrap();
        let data = mesh_io::read(&out).unwrap();
        assert_eq!(data.mesh.vertex_count(), 64 * 16);
        for name in ["gaussian", "mean", "k1", "k2", "d1x", "d1y", "d1z", "d2x", "d2y", "d2z"] {
            let v = data.scalar(name).unwrap_or_else(|| panic!("missing {name}"));
            assert!(v.iter().all(|x| x.is_finite()), "{name}");
        }
        // Torus R = 2, r = 0.5: k1 = 2 everywhere.
        assert!(data.scalar("k1").unwrap().iter().all(|k| (k - 2.0).abs() < 0.05));
        // Positions survive as doubles.
        assert_eq!(data.mesh.positions(), mesh_core::shapes::by_name("torus", 16).unwrap().positions());
    }

    #[test]
    fn every_method_and_bad_options() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("s.ply");
        let out = out.to_str().unwrap();
        for m in [
            &["--method", "fit"][..],
            &["--method", "quadric", "--rings", "2"],
            &["--method", "rusinkiewicz"],
            &["--method", "normal-cycle", "--radius", "0.2"],
            &["--method", "fit", "--area", "barycentric"],
        ] {
            let mut v = vec!["--shape", "icosphere", "--res", "2", "--out", out];
            v.extend_from_slice(m);
            run(&args(&v)).unwrap_or_else(|e| panic!("{m:?}: {e}"));
        }
        for bad in [
            &["--method", "magic"][..],
            &["--method", "fit", "--rings", "0"],
            &["--method", "normal-cycle", "--radius=-1"],
            &["--method", "rusinkiewicz", "--rings", "2"],
            &["--area", "nope"],
        ] {
            let mut v = vec!["--shape", "icosphere", "--res", "1", "--out", out];
            v.extend_from_slice(bad);
            assert!(run(&args(&v)).is_err(), "{bad:?}");
        }
    }

    #[test]
    fn shared_meshes_give_finite_fields() {
        let Some(dir) = crate::commands::shared_data() else { return };
        let tmp = tempfile::tempdir().unwrap();
        for file in ["cgal_degtri_sliding.off", "cgal_holes.off", "npm_bunny.obj"] {
            let out = tmp.path().join(format!("{file}.ply"));
            let input = dir.join(file);
            run(&args(&[input.to_str().unwrap(), "--out", out.to_str().unwrap(), "--json"])).unwrap();
            let data = mesh_io::read(&out).unwrap();
            for name in ["gaussian", "mean", "k1", "k2", "d1x", "d2z"] {
                assert!(data.scalar(name).unwrap().iter().all(|x| x.is_finite()), "{file} {name}");
            }
        }
    }
}
