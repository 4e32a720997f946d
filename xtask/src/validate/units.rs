//! The unit of length does not change an answer: every operation on a mesh
//! and on the same mesh scaled by `1e-150` and `1e150` gives the same result
//! (to `1e-9` relative) once rescaled by the power of the scale its quantity
//! carries (distances `s`, areas `s^2`, curvature `1 / s`, Gaussian
//! curvature and eigenvalues `1 / s^2`, counts and angles `1`); and the
//! same at `1e-300` and `1e300` for the values that stay in the range of
//! `f64` there (degree -1, 0 or 1). Volumes (`s^3`, outside the range of
//! `f64` at these scales) are left out.
//!
//! Nor does the place: every operation, and the enclosed volume, gives the
//! same result on a mesh moved 10^6 sizes from the origin as on the same
//! positions moved back.

use mesh_curvature::{
    curvature_tensor, gaussian_curvature, mean_curvature, pointwise_curvature, PointwiseOptions, TensorOptions,
};
use mesh_geodesic::{
    dijkstra, exact_distance, fmm_distance, DijkstraOptions, ExactOptions, FmmOptions, HeatGeodesics, HeatOptions,
    LaplacianKind,
};
use mesh_kernel::clean::{clean, CleanOptions};
use mesh_kernel::glam::{DVec2, DVec3};
use mesh_kernel::{geometry, shapes, TriMesh, VertexId};
use mesh_param::{parameterize, ParamMethod, ParamOptions};
use mesh_spectral::{HarmonicsOptions, ManifoldHarmonics};

use super::Validator;

/// The scales every operation is run at, besides 1; at the last two only
/// the operations whose values are of degree -1, 0 or 1 in lengths (the
/// others leave the range of `f64`).
const SCALES: [f64; 4] = [1e-150, 1e150, 1e-300, 1e300];

/// The largest relative difference allowed.
const LIMIT: f64 = 1e-9;

/// An operation: its name, the power of the scale its values carry, and the
/// values (or an error message).
type Operation = (&'static str, i32, fn(&TriMesh) -> Result<Vec<f64>, String>);

/// A mesh, how to build it, and what to run on it.
type TestMesh = (&'static str, fn() -> mesh_kernel::Result<TriMesh>, &'static [Operation]);

/// Operations whose results are made of quantities of degree 2 (the
/// eigenvectors are normalized by the vertex areas): not representable at
/// `1e-300` and `1e300`, where they must fail with an error instead.
const OF_AREAS: &[&str] = &["first 6 eigenvectors (sign fixed)"];

/// Runs the unit-of-length checks.
pub fn run(v: &mut Validator) {
    let meshes: [TestMesh; 3] =
        [("irregular torus", torus, CLOSED), ("dirty sphere", dirty_sphere, DIRTY), ("curved disk", curved_disk, DISK)];
    placement(v, &meshes);
    placement(v, &[("irregular torus", torus, VOLUME)]);
    for (name, make, operations) in meshes {
        let mesh = match make() {
            Ok(m) => m,
            Err(e) => return v.error(format!("{name}: build"), e),
        };
        for (op, power, f) in operations {
            let reference = match f(&mesh) {
                Ok(r) => r,
                Err(e) => {
                    v.error(format!("{name}, {op}: unit scale"), e);
                    continue;
                }
            };
            for s in SCALES.into_iter().filter(|s| power.abs() <= 1 || (1e-200..1e200).contains(s)) {
                let label = format!("{name}, {op}: x{s:e} vs x1, max relative difference");
                let result = scaled(&mesh, s).map_err(|e| e.to_string()).and_then(|m| f(&m));
                if OF_AREAS.contains(op) && !(1e-200..1e200).contains(&s) {
                    let refused = result.as_ref().is_err_and(|e| e.contains("outside the range"));
                    v.holds(format!("{name}, {op}: x{s:e} refused"), refused, format!("{:?}", result.err()));
                    continue;
                }
                match result {
                    Ok(values) => v.at_most(label, relative_difference(&values, &reference, s.powi(*power)), LIMIT),
                    Err(e) => v.error(label, e),
                }
            }
        }
    }
}

/// Runs every operation on a mesh moved [`FAR`] sizes from the origin and
/// on the same rounded positions moved back (exactly: each coordinate lies
/// within a factor 2 of the offset's), which must agree to [`LIMIT`]: an
/// answer may not depend on where the mesh sits (a scan in survey
/// coordinates).
fn placement(v: &mut Validator, meshes: &[TestMesh]) {
    for &(name, make, operations) in meshes {
        let Ok(mesh) = make() else { continue };
        let offset = DVec3::new(FAR, -FAR, 0.5 * FAR);
        let far: Vec<DVec3> = mesh.positions().iter().map(|&p| p + offset).collect();
        let near: Vec<DVec3> = far.iter().map(|&p| p - offset).collect();
        let [far, near] = [far, near].map(|p| TriMesh::new(p, mesh.faces().to_vec()));
        let (Ok(far), Ok(near)) = (far, near) else {
            return v.error(format!("{name}: moved"), "TriMesh::new refused a moved mesh");
        };
        for (op, _, f) in operations {
            let label = format!("{name}, {op}: moved {FAR:e} vs moved back, max relative difference");
            match (f(&far), f(&near)) {
                (Ok(a), Ok(b)) => v.at_most(label, relative_difference(&a, &b, 1.0), LIMIT),
                (Err(e), _) | (_, Err(e)) => v.error(label, e),
            }
        }
    }
}

/// How far [`placement`] moves a mesh, in units of its size (about 1).
const FAR: f64 = 1e6;

/// `mesh` with every coordinate multiplied by `s`.
fn scaled(mesh: &TriMesh, s: f64) -> mesh_kernel::Result<TriMesh> {
    TriMesh::new(mesh.positions().iter().map(|p| *p * s).collect(), mesh.faces().to_vec())
}

/// `max |a / unit - b| / max |b|` (or the absolute difference when `b` is
/// all zero); infinite when the lengths differ or a value is not finite.
fn relative_difference(a: &[f64], b: &[f64], unit: f64) -> f64 {
    if a.len() != b.len() || a.iter().any(|x| !x.is_finite()) {
        return f64::INFINITY;
    }
    let size = b.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let worst = a.iter().zip(b).fold(0.0_f64, |m, (x, y)| m.max((x / unit - y).abs()));
    if size > 0.0 {
        worst / size
    } else {
        worst
    }
}

fn torus() -> mesh_kernel::Result<TriMesh> {
    shapes::irregular_torus(1.0, 0.4, 24, 12, 0.2, 7)
}

/// A unit icosphere with a duplicate face, a zero-area face, a pair of
/// coincident vertices and an unreferenced vertex.
fn dirty_sphere() -> mesh_kernel::Result<TriMesh> {
    let sphere = shapes::icosphere(2)?;
    let (mut p, mut f) = sphere.into_parts();
    let n = p.len() as u32;
    f.push(f[0]);
    p.extend([DVec3::new(2.0, 0.0, 0.0), DVec3::new(3.0, 0.0, 0.0), DVec3::new(4.0, 0.0, 0.0)]);
    f.push([n, n + 1, n + 2]);
    p.push(p[5]);
    f.push([n + 3, f[3][1], f[3][2]]);
    p.push(DVec3::new(0.0, 5.0, 0.0));
    TriMesh::new(p, f)
}

/// A paraboloid cap over an irregular disk: a curved mesh with one boundary.
fn curved_disk() -> mesh_kernel::Result<TriMesh> {
    let disk = shapes::disk(8, 3)?;
    let (p, f) = disk.into_parts();
    TriMesh::new(p.into_iter().map(|q| DVec3::new(q.x, q.y, 0.4 * (q.x * q.x + q.y * q.y))).collect(), f)
}

const CLOSED: &[Operation] = &[
    ("surface area", 2, |m| Ok(vec![geometry::surface_area(m)])),
    ("face areas", 2, |m| Ok(geometry::face_areas(m))),
    ("mean edge length", 1, |m| Ok(vec![geometry::mean_edge_length(m)])),
    ("vertex normals", 0, |m| {
        Ok(geometry::vertex_normals(m, geometry::NormalWeighting::Area).iter().flat_map(|n| n.to_array()).collect())
    }),
    ("cotan Laplacian", 0, |m| Ok(mesh_kernel::operators::cotan_laplacian(m).data().to_vec())),
    ("Gaussian curvature (angle defect)", -2, |m| {
        gaussian_curvature(m, &Default::default()).map(|k| k.pointwise).map_err(|e| e.to_string())
    }),
    ("mean curvature (cotangent)", -1, |m| {
        mean_curvature(m, &Default::default()).map(|h| h.pointwise).map_err(|e| e.to_string())
    }),
    ("principal curvatures (jet fit)", -1, |m| {
        curvature_tensor(m, &TensorOptions::default()).map(|t| [t.k1, t.k2].concat()).map_err(|e| e.to_string())
    }),
    ("pointwise Gaussian curvature", -2, |m| {
        pointwise_curvature(m, &PointwiseOptions::default()).map(|c| c.gaussian).map_err(|e| e.to_string())
    }),
    ("pointwise curvature flags", 0, |m| {
        let c = pointwise_curvature(m, &PointwiseOptions::default()).map_err(|e| e.to_string())?;
        Ok(c.flag.iter().map(|f| f.map_or(0.0, |f| 1.0 + f as u8 as f64)).collect())
    }),
    ("heat distance", 1, |m| {
        HeatGeodesics::new(m, &HeatOptions::default())
            .and_then(|h| h.distance(&[VertexId::new(0)]))
            .map_err(|e| e.to_string())
    }),
    ("heat distance (intrinsic Delaunay)", 1, |m| {
        let options = HeatOptions { laplacian: LaplacianKind::IntrinsicDelaunay, ..Default::default() };
        HeatGeodesics::new(m, &options).and_then(|h| h.distance(&[VertexId::new(0)])).map_err(|e| e.to_string())
    }),
    ("fast marching distance", 1, |m| {
        fmm_distance(m, &[VertexId::new(0)], &FmmOptions::default()).map_err(|e| e.to_string())
    }),
    ("Dijkstra distance", 1, |m| {
        dijkstra(m, &[VertexId::new(0)], &DijkstraOptions::default()).map(|d| d.distance).map_err(|e| e.to_string())
    }),
    ("exact distance", 1, |m| {
        exact_distance(m, &[VertexId::new(0)], &ExactOptions::default()).map_err(|e| e.to_string())
    }),
    ("20 smallest eigenvalues", -2, |m| {
        ManifoldHarmonics::new(m, 20, &HarmonicsOptions::default())
            .map(|h| h.eigenvalues().to_vec())
            .map_err(|e| e.to_string())
    }),
    ("first 6 eigenvectors (sign fixed)", -1, |m| {
        let h = ManifoldHarmonics::new(m, 6, &HarmonicsOptions::default()).map_err(|e| e.to_string())?;
        let pairs = h.eigenpairs();
        Ok((0..pairs.len())
            .flat_map(|j| {
                let x = pairs.vector(j);
                let big = x.iter().copied().fold(0.0_f64, |b, v| if v.abs() > b.abs() { v } else { b });
                x.iter().map(move |v| v * big.signum()).collect::<Vec<_>>()
            })
            .collect())
    }),
];

/// Checked for its placement only (a volume leaves the range of `f64` at
/// the scales).
const VOLUME: &[Operation] = &[("enclosed volume", 3, |m| Ok(vec![geometry::enclosed_volume(m)]))];

const DIRTY: &[Operation] = &[
    ("clean (default options)", 0, |m| {
        clean(m.positions().to_vec(), m.faces().to_vec(), &CleanOptions::default())
            .map(|(c, r)| counts(&c, &r))
            .map_err(|e| e.to_string())
    }),
    ("clean (manifold repair)", 0, |m| {
        clean(m.positions().to_vec(), m.faces().to_vec(), &CleanOptions { manifold: true, ..Default::default() })
            .map(|(c, r)| counts(&c, &r))
            .map_err(|e| e.to_string())
    }),
    ("degenerate faces", 0, |m| {
        Ok(mesh_kernel::clean::degenerate_faces(m, 1e-12).iter().map(|f| f.idx() as f64).collect())
    }),
    ("manifold report", 0, |m| {
        let c = m.connectivity();
        Ok(vec![
            c.euler_characteristic() as f64,
            c.components().count as f64,
            c.non_manifold_report().edges.len() as f64,
            c.non_manifold_report().vertices.len() as f64,
        ])
    }),
];

/// Counts that describe a cleaning: vertices and faces left, and the report.
fn counts(mesh: &TriMesh, r: &mesh_kernel::clean::CleanReport) -> Vec<f64> {
    [mesh.vertex_count(), mesh.face_count()].into_iter().chain(r.counts()).map(|x| x as f64).collect()
}

/// Parameterizations, as `u v` of every vertex divided by the map's size
/// (most methods fix the boundary on a unit circle; free-boundary ones carry
/// the mesh's unit, and the size takes it out).
fn uv(m: &TriMesh, method: ParamMethod) -> Result<Vec<f64>, String> {
    let p = parameterize(m, &ParamOptions { method, ..Default::default() }).map_err(|e| e.to_string())?;
    // The largest coordinate (a length would over- or underflow at 1e+-300).
    let size = p.uv.iter().fold(0.0_f64, |s, q| s.max(q.abs().max_element()));
    Ok(p.uv.iter().flat_map(|q: &DVec2| [q.x / size, q.y / size]).collect())
}

const DISK: &[Operation] = &[
    ("Tutte", 0, |m| uv(m, ParamMethod::Tutte)),
    ("mean value", 0, |m| uv(m, ParamMethod::MeanValue)),
    ("harmonic", 0, |m| uv(m, ParamMethod::Harmonic)),
    ("authalic", 0, |m| uv(m, ParamMethod::Authalic)),
    ("LSCM", 0, |m| uv(m, ParamMethod::Lscm)),
    ("ARAP", 0, |m| uv(m, ParamMethod::Arap { iterations: 10 })),
    ("distortion of the harmonic map (angle and area, means and maxima)", 0, |m| {
        let p = parameterize(m, &ParamOptions { method: ParamMethod::Harmonic, ..Default::default() })
            .map_err(|e| e.to_string())?;
        let s = &p.report.summary;
        Ok(vec![s.angle_distortion_mean, s.angle_distortion_max, s.area_distortion_mean, s.area_distortion_max])
    }),
    ("Gaussian curvature with boundary", -2, |m| {
        gaussian_curvature(m, &Default::default()).map(|k| k.pointwise).map_err(|e| e.to_string())
    }),
];
