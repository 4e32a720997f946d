//! Columns of the matrix for the algorithm crates: mesh-curvature (every
//! estimator), mesh-geodesic (Dijkstra, Fast Marching, heat, exact, path
//! tracing), mesh-param (every method, the cut-open map and the atlas),
//! mesh-spectral (eigenpairs, filter, compression, heat kernel signature)
//! and mesh-wavelet (Loop and butterfly subdivision, analysis then
//! synthesis). mesh-nurbs takes no mesh as input and has no column.

use std::f64::consts::TAU;

use mesh_curvature::{
    curvature_tensor, gaussian_curvature, integral_curvature, mean_curvature, pointwise_curvature, IntegralOptions,
    Neighborhood, TensorMethod as Estimator, TensorOptions,
};
use mesh_geodesic::{
    dijkstra, exact_distance, fmm_distance, heat_distance, trace_path, ExactOptions, FmmOptions, HeatOptions,
    SurfacePoint, TraceOptions,
};
use mesh_kernel::{TriMesh, VertexId};
use mesh_param::{atlas, parameterize, parameterize_cut, AtlasOptions, ParamMethod, ParamOptions};
use mesh_spectral::{
    compress, filter, heat_kernel_signature, hks_times, HarmonicsOptions, ManifoldHarmonics, Transfer,
};
use mesh_wavelet::{subdivide, Multiresolution, Scheme, SubdivideOptions};

use super::check::{distance as chord_length, uv, xyz, Out};
use super::Op;

/// The algorithm crates' columns.
pub const OPS: &[Op] = &[
    ("curvature", "gaussian", gaussian),
    ("curvature", "mean", mean),
    ("curvature", "tensor fit", |m| tensor(m, Estimator::default())),
    ("curvature", "rusinkiewicz", |m| tensor(m, Estimator::Rusinkiewicz)),
    ("curvature", "normal cycle", |m| tensor(m, Estimator::NormalCycle(Neighborhood::Rings(2)))),
    ("curvature", "integral", integral),
    ("curvature", "pointwise", pointwise),
    ("geodesic", "dijkstra", |m| distance(m, true, |m, s| dijkstra(m, s, &Default::default()).map(|t| t.distance))),
    ("geodesic", "fmm", |m| distance(m, false, |m, s| fmm_distance(m, s, &FmmOptions::default()))),
    ("geodesic", "heat", |m| distance(m, false, |m, s| heat_distance(m, s, &HeatOptions::default()))),
    ("geodesic", "exact", exact),
    ("geodesic", "trace", trace),
    ("param", "tutte", |m| param(m, ParamMethod::Tutte)),
    ("param", "mean-value", |m| param(m, ParamMethod::MeanValue)),
    ("param", "harmonic", |m| param(m, ParamMethod::Harmonic)),
    ("param", "authalic", |m| param(m, ParamMethod::Authalic)),
    ("param", "intrinsic", |m| param(m, ParamMethod::Intrinsic { lambda: 0.5, mu: 0.5 })),
    ("param", "lscm", |m| param(m, ParamMethod::Lscm)),
    ("param", "arap", |m| param(m, ParamMethod::Arap { iterations: 5 })),
    ("param", "cut + tutte", cut),
    ("param", "atlas", atlas_op),
    ("spectral", "eigenpairs", eigen),
    ("spectral", "filter", filter_op),
    ("spectral", "compress", compress_op),
    ("spectral", "hks", hks),
    ("wavelet", "loop", |m| subdivision(m, Scheme::Loop)),
    ("wavelet", "butterfly", |m| subdivision(m, Scheme::Butterfly)),
    ("wavelet", "analyze+synth", wavelet),
];

fn e(err: impl std::fmt::Display) -> String {
    err.to_string()
}

/// Angle defects plus boundary turning: 2 pi chi on manifold meshes.
fn gaussian(m: &TriMesh) -> Result<Out, String> {
    let k = gaussian_curvature(m, &Default::default()).map_err(e)?;
    let c = m.connectivity();
    let chi = c.euler_characteristic() as f64;
    let total = k.total();
    Ok(Out::default()
        .field("pointwise", -2, k.pointwise)
        .field("integrated", 0, k.integrated)
        .require(!c.is_manifold() || (total - TAU * chi).abs() <= 1e-9, || {
            format!("total {total} vs 2 pi chi {}", TAU * chi)
        }))
}

fn mean(m: &TriMesh) -> Result<Out, String> {
    let h = mean_curvature(m, &Default::default()).map_err(e)?;
    Ok(Out::default().field("pointwise", -1, h.pointwise).field("integrated", 1, h.integrated))
}

/// Principal curvatures with k1 >= k2.
fn tensor(m: &TriMesh, method: Estimator) -> Result<Out, String> {
    let t = curvature_tensor(m, &TensorOptions { method, ..Default::default() }).map_err(e)?;
    let bad = (0..t.k1.len()).find(|&i| t.k1[i] < t.k2[i]);
    Ok(Out::default()
        .field("k1", -1, t.k1.clone())
        .field("k2", -1, t.k2.clone())
        .require(t.k1.len() == m.vertex_count(), || "one value per vertex".into())
        .require(bad.is_none(), || format!("k1 < k2 at vertex {bad:?}")))
}

fn integral(m: &TriMesh) -> Result<Out, String> {
    let c = integral_curvature(m, &IntegralOptions { neighborhood: Neighborhood::Rings(1) }).map_err(e)?;
    Ok(Out::default().field("gaussian", 0, c.gaussian).field("mean", 1, c.mean).field("area", 2, c.area))
}

fn pointwise(m: &TriMesh) -> Result<Out, String> {
    let c = pointwise_curvature(m, &Default::default()).map_err(e)?;
    Ok(Out::default().field("gaussian", -2, c.gaussian).field("mean", -1, c.mean))
}

/// The source's component: distance 0 at the source, finite on its
/// component, +infinity elsewhere; with `chord`, never shorter than the
/// straight line (true of edge paths and exact geodesics, not of the
/// approximations of Fast Marching and the heat method).
fn distance_checks(m: &TriMesh, d: Vec<f64>, name: &'static str, chord: bool) -> Out {
    let comp = &m.connectivity().components().vertex_component;
    let p0 = m.position(VertexId(0));
    let bad = (0..d.len()).find(|&i| {
        let reachable = comp[i] == comp[0] && (i == 0 || m.connectivity().valence(VertexId::new(i)) > 0);
        d[i].is_nan() || d[i] < 0.0 || d[i].is_finite() != reachable
    });
    let below = (0..d.len())
        .filter(|&i| chord && d[i].is_finite())
        .find(|&i| d[i] < chord_length(m.position(VertexId::new(i)), p0) * (1.0 - 1e-9));
    Out::default()
        .distances(name, d.clone())
        .require(d.len() == m.vertex_count(), || "one distance per vertex".into())
        .require(d.first() == Some(&0.0), || format!("distance at the source {:?}", d.first()))
        .require(bad.is_none(), || format!("vertex {bad:?}: finite off the source's component or infinite on it"))
        .require(below.is_none(), || format!("vertex {below:?}: shorter than the straight line"))
}

fn distance(
    m: &TriMesh,
    chord: bool,
    f: impl Fn(&TriMesh, &[VertexId]) -> mesh_geodesic::error::Result<Vec<f64>>,
) -> Result<Out, String> {
    let d = f(m, &[VertexId(0)]).map_err(e)?;
    Ok(distance_checks(m, d, "distance", chord))
}

/// Exact distances: also never longer than the edge-graph distance.
fn exact(m: &TriMesh) -> Result<Out, String> {
    let d = exact_distance(m, &[VertexId(0)], &ExactOptions::default()).map_err(e)?;
    let graph = dijkstra(m, &[VertexId(0)], &Default::default()).map_err(e)?.distance;
    let above = (0..d.len()).find(|&i| d[i].is_finite() && d[i] > graph[i] * (1.0 + 1e-12));
    Ok(distance_checks(m, d, "distance", true)
        .require(above.is_none(), || format!("vertex {above:?}: longer than the graph distance")))
}

/// A path back to the source from the first vertex past a third of the
/// numbering that the source reaches (a fixed choice, so that a scaled
/// mesh traces the same path): no shorter than the straight line.
fn trace(m: &TriMesh) -> Result<Out, String> {
    let d = fmm_distance(m, &[VertexId(0)], &FmmOptions::default()).map_err(e)?;
    let c = m.connectivity();
    let from = (m.vertex_count() / 3..m.vertex_count())
        .find(|&i| d[i].is_finite() && c.valence(VertexId::new(i)) > 0)
        .unwrap_or(0);
    let start = SurfacePoint::at_vertex(m, VertexId::new(from)).ok_or("the start vertex has no face")?;
    let path = trace_path(m, &d, &[VertexId(0)], start, &TraceOptions::default()).map_err(e)?;
    let chord = chord_length(m.position(VertexId::new(from)), m.position(VertexId(0)));
    Ok(Out::default()
        .field("length", 1, vec![path.length])
        .field("points", 1, xyz(&path.positions))
        .require(path.length >= chord * (1.0 - 1e-9), || format!("length {:e} below the chord {chord:e}", path.length)))
}

/// A map into the unit square (normalized); Tutte's and Floater's maps onto
/// a convex boundary are bijective by theorem.
fn param(m: &TriMesh, method: ParamMethod) -> Result<Out, String> {
    let p = parameterize(m, &ParamOptions { method, ..ParamOptions::default() }).map_err(e)?;
    let theorem = matches!(method, ParamMethod::Tutte | ParamMethod::MeanValue);
    Ok(Out::default()
        .field("uv", 0, uv(&p.uv))
        .require(p.uv.len() == m.vertex_count(), || "one uv per vertex".into())
        .require(!theorem || p.report.summary.bijective, || {
            format!("{} map onto a circle not bijective", method.name())
        }))
}

/// The cut-open map is judged by its invariants, not its UVs: on the
/// matrix's symmetric meshes (icosphere, torus) several seams are equally
/// short, and which one wins depends on the rounding of the coordinates,
/// hence on the unit.
fn cut(m: &TriMesh) -> Result<Out, String> {
    let p = parameterize_cut(m, &ParamOptions { method: ParamMethod::Tutte, ..ParamOptions::default() }).map_err(e)?;
    Ok(Out::default()
        .counts("faces", vec![p.param.report.summary.faces as f64])
        .require(p.param.report.summary.bijective, || "not bijective".into()))
}

/// Corner UVs inside the unit square; judged by invariants, not the UVs
/// themselves (the seams of symmetric meshes are ties, see [`cut`]).
fn atlas_op(m: &TriMesh) -> Result<Out, String> {
    let a = atlas(m, &AtlasOptions::default()).map_err(e)?;
    let flat: Vec<f64> = a.corner_uvs.iter().flat_map(|t| uv(t)).collect();
    let outside = flat.iter().position(|x| !(0.0..=1.0).contains(x));
    Ok(Out::default()
        .counts("corner uv count", vec![flat.len() as f64])
        .require(a.corner_uvs.len() == m.face_count(), || "one triangle of uvs per face".into())
        .require(outside.is_none(), || format!("corner uv {outside:?} outside the unit square")))
}

fn harmonics(m: &TriMesh) -> Result<ManifoldHarmonics, String> {
    ManifoldHarmonics::new(m, 8, &HarmonicsOptions::default()).map_err(e)
}

/// Eight eigenvalues, ascending, none negative, zero first.
fn eigen(m: &TriMesh) -> Result<Out, String> {
    let h = harmonics(m)?;
    let values = h.eigenvalues().to_vec();
    let top = values.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    Ok(Out::default()
        .field("eigenvalues", -2, values.clone())
        .require(values.first() == Some(&0.0), || format!("first eigenvalue {:?}", values.first()))
        .require(values.windows(2).all(|w| w[0] <= w[1]), || "not ascending".into())
        .require(values.iter().all(|x| *x >= -1e-9 * top), || "negative eigenvalue".into()))
}

fn filter_op(m: &TriMesh) -> Result<Out, String> {
    let h = harmonics(m)?;
    let p = filter(&h, m.positions(), &Transfer::KeepFirst(4)).map_err(e)?;
    Ok(Out::default()
        .field("positions", 1, xyz(&p))
        .require(p.len() == m.vertex_count(), || "one point per vertex".into()))
}

fn compress_op(m: &TriMesh) -> Result<Out, String> {
    let h = harmonics(m)?;
    let (c, error) = compress(m, &h, 4).map_err(e)?;
    // The error is relative to the bounding-box diagonal: compared beside
    // the diagonal itself (1), to the tolerance of that length.
    Ok(Out::default().field("positions", 1, xyz(c.positions())).field(
        "rms error and the diagonal",
        0,
        vec![error.rms, 1.0],
    ))
}

/// The signature on whole eigenspaces: from 10 pairs (fewer on tiny
/// meshes), as many as end on a gap (a cut through a repeated eigenvalue
/// would make the signature depend on the basis the solver picked within
/// it).
fn hks(m: &TriMesh) -> Result<Out, String> {
    let probe = ManifoldHarmonics::new(m, m.vertex_count().min(10), &HarmonicsOptions::default()).map_err(e)?;
    let values = probe.eigenvalues();
    let top = values.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    let k = (2..values.len()).rev().find(|&k| values[k] - values[k - 1] > 1e-6 * top).unwrap_or(values.len());
    let h = ManifoldHarmonics::new(m, k, &HarmonicsOptions::default()).map_err(e)?;
    let times = hks_times(h.eigenpairs(), 4).map_err(e)?;
    let s = heat_kernel_signature(h.eigenpairs(), &times).map_err(e)?;
    Ok(Out::default().field("times", 2, times).field("signature", -2, s.into_iter().flatten().collect()))
}

/// One level: four faces per face.
fn subdivision(m: &TriMesh, scheme: Scheme) -> Result<Out, String> {
    let s = subdivide(m, &SubdivideOptions { scheme, levels: 1 }).map_err(e)?;
    Ok(Out::default()
        .field("positions", 1, xyz(s.positions()))
        .require(s.face_count() == 4 * m.face_count(), || format!("{} faces from {}", s.face_count(), m.face_count())))
}

/// Analysis then synthesis gives the input back (every coordinate within
/// 1e-12 of the mesh's size).
fn wavelet(m: &TriMesh) -> Result<Out, String> {
    let mr = Multiresolution::analyze(m, &Default::default()).map_err(e)?;
    let back = mr.synthesize().map_err(e)?;
    let size = mesh_kernel::geometry::bounding_box(m).map_or(0.0, |b| b.diagonal());
    let worst =
        m.positions().iter().zip(back.positions()).map(|(a, b)| (*a - *b).abs().max_element()).fold(0.0, f64::max);
    Ok(Out::default()
        .field("coefficients", 1, xyz(mr.data()))
        .require(back.vertex_count() == m.vertex_count(), || "vertex count changed".into())
        .require(worst <= 1e-12 * size, || format!("synthesis is {worst:e} off the input (size {size:e})")))
}
