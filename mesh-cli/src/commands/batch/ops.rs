//! The operations a batch runs on each mesh (`--do`): each adds a section of
//! summary figures to the mesh's record and, where it computes per-vertex
//! values, fields for the mesh's output file.

use std::time::Instant;

use mesh_kernel::{MeshError, TriMesh};
use serde_json::{json, Map, Value};

use crate::output::{stats, CliResult};

/// One operation of `mesh batch --do`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Op {
    /// Counts, topology and defects (what `mesh info` prints).
    Info,
    /// Gaussian, mean and principal curvatures (quartic fit), with their
    /// statistics, a histogram of the shape index and the position noise of
    /// the stored coordinates it allowed for.
    Curvature,
    /// Heat-method geodesic distance from the first vertex of the largest
    /// component.
    Geodesic,
    /// The `k` smallest Laplace-Beltrami eigenvalues.
    Eigen,
    /// Heat kernel signature at log-spaced times, with the heat trace
    /// (its area-weighted sum, a global descriptor) at those times.
    Hks,
}

impl Op {
    /// Every choice, in the order `--help` lists them (and sections appear).
    pub const ALL: [Self; 5] = [Self::Info, Self::Curvature, Self::Geodesic, Self::Eigen, Self::Hks];

    /// The name on the command line and of the record's section.
    pub fn name(self) -> &'static str {
        match self {
            Self::Info => "info",
            Self::Curvature => "curvature",
            Self::Geodesic => "geodesic",
            Self::Eigen => "eigen",
            Self::Hks => "hks",
        }
    }
}

mesh_kernel::named_choice!(Op, "do", MeshError);

/// Parameters shared by the operations.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Params {
    /// Eigenpairs computed for `eigen` and `hks`.
    pub k: usize,
    /// Times of the heat kernel signature.
    pub times: usize,
}

/// Bins of the shape-index histogram over [-1, 1].
pub const SHAPE_INDEX_BINS: usize = 16;

/// What the operations produced on one mesh.
#[derive(Debug, Default)]
pub struct Outcome {
    /// One section per operation, named as the operation.
    pub sections: Map<String, Value>,
    /// Milliseconds per operation.
    pub timings_ms: Map<String, Value>,
    /// Per-vertex fields for the output file.
    pub fields: Vec<(String, Vec<f64>)>,
}

impl Outcome {
    fn time<T>(&mut self, name: &str, f: impl FnOnce() -> T) -> T {
        let start = Instant::now();
        let out = f();
        self.timings_ms.insert(name.to_owned(), json!(start.elapsed().as_secs_f64() * 1e3));
        out
    }
}

/// Runs `ops` (sorted, without repeats) on `mesh`. The first failing
/// operation fails the mesh: a record with a section missing would read as
/// if the operation had not been asked for.
pub fn run(mesh: &TriMesh, ops: &[Op], params: Params) -> CliResult<Outcome> {
    let mut out = Outcome::default();
    let mut harmonics = None;
    for &op in ops {
        let section = match op {
            Op::Info => serde_json::to_value(out.time("info", || mesh_kernel::summary::MeshSummary::of(mesh)))?,
            Op::Curvature => curvature(mesh, &mut out)?,
            Op::Geodesic => geodesic(mesh, &mut out)?,
            Op::Eigen | Op::Hks => {
                if harmonics.is_none() {
                    let k = params.k.min(mesh.vertex_count());
                    let options = mesh_spectral::HarmonicsOptions::default();
                    harmonics =
                        Some(out.time("eigenpairs", || mesh_spectral::ManifoldHarmonics::new(mesh, k, &options))?);
                }
                let Some(mh) = harmonics.as_ref() else { continue };
                let mut section = if op == Op::Eigen {
                    json!({ "k": mh.len(), "values": mh.eigenvalues() })
                } else {
                    hks(mh, params.times, &mut out)?
                };
                // Copies of a repeated eigenvalue may be missing.
                if let (Some(caveat), Some(fields)) = (mh.eigenpairs().stats.caveat(), section.as_object_mut()) {
                    fields.insert("warning".to_owned(), json!(caveat));
                }
                section
            }
        };
        out.sections.insert(op.name().to_owned(), section);
    }
    Ok(out)
}

fn curvature(mesh: &TriMesh, out: &mut Outcome) -> CliResult<Value> {
    use mesh_curvature::{flag_code, pointwise_curvature, PointwiseOptions};
    let c = out.time("curvature", || pointwise_curvature(mesh, &PointwiseOptions::default()))?;
    let valid = |i: usize| c.flag[i].is_none();
    let section = json!({
        "gaussian": stats(&c.gaussian, valid),
        "mean": stats(&c.mean, valid),
        "k1": stats(&c.tensor.k1, valid),
        "k2": stats(&c.tensor.k2, valid),
        "flagged": c.flag_counts().total(),
        "gauss_bonnet_total": c.gauss_bonnet_total(),
        "shape_index_histogram": c.shape_index_histogram(SHAPE_INDEX_BINS),
        "position_noise": c.position_noise,
    });
    out.fields.push(("curvature_flag".into(), c.flag.iter().map(|f| f64::from(flag_code(*f))).collect()));
    out.fields.push(("gaussian".into(), c.gaussian));
    out.fields.push(("mean".into(), c.mean));
    out.fields.push(("k1".into(), c.tensor.k1));
    out.fields.push(("k2".into(), c.tensor.k2));
    Ok(section)
}

fn geodesic(mesh: &TriMesh, out: &mut Outcome) -> CliResult<Value> {
    use mesh_geodesic::{HeatGeodesics, HeatStatus};
    let source = super::super::report::largest_component_source(mesh)?;
    let heat = out.time("heat_precompute", || HeatGeodesics::new(mesh, &Default::default()))?;
    let solved = out.time("heat_solve", || heat.solve(&[source]))?;
    let d = &solved.distance;
    let reached: Vec<f64> = d.iter().copied().filter(|x| x.is_finite()).collect();
    let section = json!({
        "source": source.0,
        "max": reached.iter().copied().reduce(f64::max),
        "mean": (!reached.is_empty()).then(|| reached.iter().sum::<f64>() / reached.len() as f64),
        "reached": reached.len(),
        "unresolved": solved.count(HeatStatus::Unresolved),
    });
    out.fields.push(("distance".into(), solved.distance));
    Ok(section)
}

fn hks(mh: &mesh_spectral::ManifoldHarmonics, count: usize, out: &mut Outcome) -> CliResult<Value> {
    use mesh_spectral::{heat_kernel_signature, heat_trace, hks_times};
    let times = hks_times(mh.eigenpairs(), count)?;
    let hks = out.time("hks", || heat_kernel_signature(mh.eigenpairs(), &times))?;
    let section = json!({ "k": mh.len(), "times": times, "heat_trace": heat_trace(mh.eigenpairs(), &times)? });
    for (i, h) in hks.into_iter().enumerate() {
        out.fields.push((format!("hks{i}"), h));
    }
    Ok(section)
}

#[cfg(test)]
mod tests {
    use super::*;
    use mesh_kernel::shapes;

    #[test]
    fn every_operation_on_a_sphere() {
        let mesh = shapes::icosphere(3).unwrap();
        let out = run(&mesh, &Op::ALL, Params { k: 9, times: 4 }).unwrap();
        let names: Vec<&str> = out.sections.keys().map(String::as_str).collect();
        assert_eq!(names.len(), Op::ALL.len());
        // The unit sphere: K = 1, eigenvalues l (l + 1), all caps, geodesic max pi.
        let s = &out.sections;
        assert!((s["curvature"]["gaussian"]["mean"].as_f64().unwrap() - 1.0).abs() < 0.02);
        assert!(s["curvature"]["shape_index_histogram"][SHAPE_INDEX_BINS - 1].as_f64().unwrap() > 0.99);
        let values = s["eigen"]["values"].as_array().unwrap();
        assert_eq!(values.len(), 9);
        assert!((values[1].as_f64().unwrap() - 2.0).abs() < 0.02);
        let max = s["geodesic"]["max"].as_f64().unwrap();
        // The heat method on 642 vertices: within 2% of pi (1.6% here).
        assert!((max - std::f64::consts::PI).abs() < 0.02 * std::f64::consts::PI, "{max}");
        assert_eq!(s["hks"]["times"].as_array().unwrap().len(), 4);
        // The heat trace: 1 for the constant plus a positive term per pair,
        // decreasing in time.
        let trace: Vec<f64> = s["hks"]["heat_trace"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
        assert!(trace.windows(2).all(|w| w[0] > w[1]) && trace[3] > 1.0 && trace[0] < 9.0, "{trace:?}");
        let fields: Vec<&str> = out.fields.iter().map(|(n, _)| n.as_str()).collect();
        assert!(fields.contains(&"distance") && fields.contains(&"k1") && fields.contains(&"hks3"));
        assert!(out.fields.iter().all(|(_, v)| v.len() == mesh.vertex_count()));
    }

    /// The unit of length changes no figure beyond its own power of the
    /// scale: a torus in metres and in millimetres (with a rotation) gives
    /// eigenvalues times s^2, curvatures times s, distances divided by s, and
    /// the same shape-index histogram.
    #[test]
    fn figures_do_not_depend_on_the_unit_of_length() {
        let mesh = shapes::irregular_torus(2.0, 0.5, 48, 12, 0.2, 3).unwrap();
        let params = Params { k: 12, times: 4 };
        let ops = [Op::Curvature, Op::Geodesic, Op::Eigen];
        let a = run(&mesh, &ops, params).unwrap();
        for s in [1e-3, 1e3] {
            let rotation = mesh_kernel::glam::DQuat::from_rotation_y(0.3);
            let positions = mesh.positions().iter().map(|&p| rotation * p * s).collect();
            let b = run(&TriMesh::new(positions, mesh.faces().to_vec()).unwrap(), &ops, params).unwrap();
            let (x, y) = (&a.sections, &b.sections);
            let close = |u: f64, v: f64, what: &str| {
                assert!((u - v).abs() <= 1e-6 * u.abs().max(1e-12), "{what}, scale {s}: {u} vs {v}")
            };
            for j in 1..12 {
                close(
                    x["eigen"]["values"][j].as_f64().unwrap(),
                    y["eigen"]["values"][j].as_f64().unwrap() * s * s,
                    "eigenvalue",
                );
            }
            close(
                x["curvature"]["mean"]["mean"].as_f64().unwrap(),
                y["curvature"]["mean"]["mean"].as_f64().unwrap() * s,
                "mean curvature",
            );
            close(x["geodesic"]["max"].as_f64().unwrap(), y["geodesic"]["max"].as_f64().unwrap() / s, "distance");
            assert_eq!(x["curvature"]["flagged"], y["curvature"]["flagged"]);
            for j in 0..SHAPE_INDEX_BINS {
                let (u, v) = (
                    x["curvature"]["shape_index_histogram"][j].as_f64().unwrap(),
                    y["curvature"]["shape_index_histogram"][j].as_f64().unwrap(),
                );
                assert!((u - v).abs() < 1e-6, "shape index bin {j}, scale {s}: {u} vs {v}");
            }
        }
    }
}
