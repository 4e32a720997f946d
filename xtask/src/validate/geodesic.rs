//! mesh-geodesic: the accuracy targets against great circles on the
//! unit icosphere (level 5) and straight lines on the flat disk, convergence
//! under refinement, traced path lengths, metric invariants, and finite
//! distances (infinity only across components) on every shared mesh;
//! farthest-point sampling against fresh multi-source searches; exact
//! polyhedral geodesics against straight lines, cube unfoldings and MMP.

use std::f64::consts::PI;

use mesh_geodesic::{
    dijkstra, exact_distance, farthest_point_sampling, fmm_distance, heat_distance, trace_path, ExactOptions,
    FmmOptions, FmmUpdate, GeodesicError, HeatGeodesics, HeatOptions, SamplingMetric, SamplingOptions, SurfacePoint,
    TraceOptions,
};
use mesh_kernel::{shapes, TriMesh, VertexId};

use super::{convergence_order, no_shared_data, shared_data, Validator};

/// Runs the mesh-geodesic checks.
pub fn run(v: &mut Validator) {
    sphere_targets(v);
    disk_convergence(v);
    traced_paths(v);
    metric_invariants(v);
    farthest_points(v);
    exact_geodesics(v);
    shared_meshes(v);
}

type Res<T> = std::result::Result<T, String>;

/// Great-circle distance from vertex `s` on the unit sphere.
fn great_circles(m: &TriMesh, s: VertexId) -> Vec<f64> {
    let p0 = m.position(s);
    m.positions().iter().map(|p| p.dot(p0).clamp(-1.0, 1.0).acos()).collect()
}

/// Largest and mean absolute error.
fn errors(d: &[f64], truth: &[f64]) -> (f64, f64) {
    let e: Vec<f64> = d.iter().zip(truth).map(|(a, b)| (a - b).abs()).collect();
    (e.iter().copied().fold(0.0, f64::max), e.iter().sum::<f64>() / e.len().max(1) as f64)
}

fn sphere_errors(level: u32, field: impl Fn(&TriMesh) -> Res<Vec<f64>>) -> Res<(f64, f64)> {
    let m = shapes::icosphere(level).map_err(|e| e.to_string())?;
    Ok(errors(&field(&m)?, &great_circles(&m, VertexId(0))))
}

fn fmm(update: FmmUpdate) -> impl Fn(&TriMesh) -> Res<Vec<f64>> {
    move |m| fmm_distance(m, &[VertexId(0)], &FmmOptions { update, ..Default::default() }).map_err(|e| e.to_string())
}

fn heat(m: &TriMesh) -> Res<Vec<f64>> {
    heat_distance(m, &[VertexId(0)], &HeatOptions::default()).map_err(|e| e.to_string())
}

/// Icosphere level 5, source at a vertex, truth arccos(<v0, v>).
fn sphere_targets(v: &mut Validator) {
    match sphere_errors(5, fmm(FmmUpdate::CurvedFront)) {
        Ok((max, _)) => v.at_most("icosphere(5) FMM max error (target 0.005 pi; gdist exact 5e-4)", max, 0.005 * PI),
        Err(e) => v.error("icosphere(5) FMM", e),
    }
    match sphere_errors(5, fmm(FmmUpdate::PlaneWave)) {
        // The seed's plane-wave update alone stays above the target (0.0198).
        Ok((max, _)) => v.at_most("icosphere(5) FMM plane-wave (eq. 2.34) max error", max, 0.025),
        Err(e) => v.error("icosphere(5) FMM plane-wave", e),
    }
    match sphere_errors(5, heat) {
        Ok((max, mean)) => {
            v.at_most("icosphere(5) heat max error (potpourri3d 0.019)", max, 0.019);
            v.at_most("icosphere(5) heat mean error (potpourri3d 0.0089)", mean, 0.0089);
        }
        Err(e) => v.error("icosphere(5) heat", e),
    }
    let graph = |m: &TriMesh| -> Res<Vec<f64>> {
        dijkstra(m, &[VertexId(0)], &Default::default()).map(|t| t.distance).map_err(|e| e.to_string())
    };
    match sphere_errors(5, graph) {
        Ok((max, _)) => v.at_most("icosphere(5) Dijkstra max error (scipy 0.197)", max, 0.2),
        Err(e) => v.error("icosphere(5) Dijkstra", e),
    }
    for (name, field, min_order) in [
        ("FMM", Box::new(fmm(FmmUpdate::CurvedFront)) as Box<dyn Fn(&TriMesh) -> Res<Vec<f64>>>, 1.5),
        ("FMM plane-wave", Box::new(fmm(FmmUpdate::PlaneWave)), 0.5),
        ("heat", Box::new(heat), 0.4),
    ] {
        match (3..=6).map(|l| sphere_errors(l, &field).map(|e| e.0)).collect::<Res<Vec<f64>>>() {
            Ok(e) => v.at_least(
                format!("icosphere(3..6) {name} max-error order ({})", show(&e)),
                convergence_order(&e),
                min_order,
            ),
            Err(err) => v.error(format!("icosphere {name} convergence"), err),
        }
    }
}

fn show(e: &[f64]) -> String {
    e.iter().map(|x| format!("{x:.1e}")).collect::<Vec<_>>().join(" ")
}

/// Flat disk with jittered (irregular, partly obtuse) triangles, truth |x|:
/// error O(h), falling at every refinement.
fn disk_convergence(v: &mut Validator) {
    for (name, update) in [("FMM", FmmUpdate::CurvedFront), ("FMM plane-wave", FmmUpdate::PlaneWave)] {
        let errs: Res<Vec<f64>> = [10, 20, 40, 80]
            .iter()
            .map(|&rings| {
                let m = shapes::disk(rings, 7).map_err(|e| e.to_string())?;
                let truth: Vec<f64> = m.positions().iter().map(|p| p.length()).collect();
                Ok(errors(&fmm(update)(&m)?, &truth).0)
            })
            .collect();
        match errs {
            Ok(e) => {
                v.holds(
                    format!("disk {name} error falls at every refinement"),
                    e.windows(2).all(|w| w[1] < w[0]),
                    show(&e),
                );
                v.at_least(format!("disk(10..80) {name} max-error order ({})", show(&e)), convergence_order(&e), 0.7);
            }
            Err(err) => v.error(format!("disk {name}"), err),
        }
    }
}

/// Paths traced on the unit sphere: length within 1% of the great circle,
/// every point on the mesh surface.
fn traced_paths(v: &mut Validator) {
    let run = || -> Res<(f64, f64, usize)> {
        let m = shapes::icosphere(5).map_err(|e| e.to_string())?;
        let d = fmm(FmmUpdate::CurvedFront)(&m)?;
        let truth = great_circles(&m, VertexId(0));
        let (mut worst, mut off_surface, mut paths) = (0.0f64, 0.0f64, 0);
        for s in (1..m.vertex_count()).step_by(53).filter(|&s| truth[s] > 0.1 && truth[s] < 3.0) {
            let start = SurfacePoint::at_vertex(&m, VertexId::new(s)).ok_or("isolated vertex")?;
            let path =
                trace_path(&m, &d, &[VertexId(0)], start, &TraceOptions::default()).map_err(|e| e.to_string())?;
            worst = worst.max((path.length - truth[s]).abs() / truth[s]);
            for (p, x) in path.points.iter().zip(&path.positions) {
                let inside = p.bary.iter().all(|b| *b >= 0.0) && (p.bary.iter().sum::<f64>() - 1.0).abs() < 1e-12;
                off_surface = off_surface.max(if inside { (p.position(&m) - *x).length() } else { f64::INFINITY });
            }
            paths += 1;
        }
        Ok((worst, off_surface, paths))
    };
    match run() {
        Ok((worst, off, paths)) => {
            v.at_most(
                format!("icosphere(5) traced path length vs great circle, worst relative ({paths} paths)"),
                worst,
                0.01,
            );
            v.at_most("icosphere(5) traced path points off the mesh surface", off, 1e-12);
        }
        Err(e) => v.error("traced paths", e),
    }
}

/// Symmetry and triangle inequality on a perturbed sphere, in units of the
/// mean edge length h.
fn metric_invariants(v: &mut Validator) {
    let run = || -> Res<[f64; 4]> {
        let mut m = shapes::icosphere(3).map_err(|e| e.to_string())?;
        for (i, p) in m.positions_mut().iter_mut().enumerate() {
            *p *= 1.0 + 0.15 * ((i as f64) * 12.9898).sin();
        }
        let h = mesh_kernel::geometry::mean_edge_length(&m);
        let verts: Vec<VertexId> = (0..m.vertex_count()).step_by(29).map(VertexId::new).collect();
        let heat = HeatGeodesics::new(&m, &HeatOptions::default()).map_err(|e| e.to_string())?;
        let fmm = mesh_geodesic::FastMarching::new(&m, &FmmOptions::default()).map_err(|e| e.to_string())?;
        let mut out = [0.0f64; 4];
        for (k, rows) in [
            verts.iter().map(|s| fmm.distance(&[*s])).collect::<Result<Vec<_>, _>>(),
            verts.iter().map(|s| heat.distance(&[*s])).collect::<Result<Vec<_>, _>>(),
        ]
        .into_iter()
        .enumerate()
        {
            let rows = rows.map_err(|e| e.to_string())?;
            for i in 0..verts.len() {
                for j in 0..verts.len() {
                    out[2 * k] = out[2 * k].max((rows[i][verts[j].idx()] - rows[j][verts[i].idx()]).abs() / h);
                    for l in 0..verts.len() {
                        let excess = rows[i][verts[l].idx()] - rows[i][verts[j].idx()] - rows[j][verts[l].idx()];
                        out[2 * k + 1] = out[2 * k + 1].max(excess / h);
                    }
                }
            }
        }
        Ok(out)
    };
    match run() {
        Ok([fs, ft, hs, ht]) => {
            v.at_most("perturbed sphere FMM |d(a,b) - d(b,a)| / h", fs, 1.0);
            v.at_most("perturbed sphere FMM triangle-inequality excess / h", ft, 1.0);
            v.at_most("perturbed sphere heat |d(a,b) - d(b,a)| / h", hs, 1.0);
            v.at_most("perturbed sphere heat triangle-inequality excess / h", ht, 1.0);
        }
        Err(e) => v.error("metric invariants", e),
    }
}

/// Farthest-point sampling on the edge graph against fresh searches: after
/// each sample, the covering radius is the largest distance of a fresh
/// multi-source Dijkstra from the samples so far (bit for bit), and the
/// next sample is the vertex that has it (a perturbed sphere: no ties).
fn farthest_points(v: &mut Validator) {
    let run = || -> Res<usize> {
        let mut m = shapes::icosphere(4).map_err(|e| e.to_string())?;
        for (i, p) in m.positions_mut().iter_mut().enumerate() {
            *p *= 1.0 + 0.1 * ((i as f64) * 7.31).sin();
        }
        let options = SamplingOptions { metric: SamplingMetric::Dijkstra, ..SamplingOptions::default() };
        let fps = farthest_point_sampling(&m, 80, &options).map_err(|e| e.to_string())?;
        let mut mismatches = usize::from(fps.seeds.len() != 80);
        for j in 1..=fps.seeds.len() {
            let fresh = dijkstra(&m, &fps.seeds[..j], &Default::default()).map_err(|e| e.to_string())?.distance;
            let far = (0..fresh.len()).max_by(|&a, &b| fresh[a].total_cmp(&fresh[b]).then(b.cmp(&a)));
            mismatches += usize::from(far.map(|f| fresh[f]) != Some(fps.radii[j - 1]));
            if let (Some(next), Some(f)) = (fps.seeds.get(j), far) {
                mismatches += usize::from(next.idx() != f);
            }
            if j == fps.seeds.len() {
                mismatches += fresh.iter().zip(&fps.distance).filter(|(a, b)| a != b).count();
            }
        }
        Ok(mismatches)
    };
    match run() {
        Ok(bad) => {
            v.at_most("farthest-point sampling (80, Dijkstra) against fresh searches: mismatches", bad as f64, 0.0)
        }
        Err(e) => v.error("farthest-point sampling", e),
    }
}

fn exact(m: &TriMesh, s: VertexId) -> Res<Vec<f64>> {
    exact_distance(m, &[s], &ExactOptions::default()).map_err(|e| e.to_string())
}

/// Exact polyhedral distances: Euclidean on flat meshes, unfoldings on the
/// cube, MMP (pygeodesic, committed fixtures) on icosphere(3) with the
/// chord and Fast Marching as bounds, on icosphere(6) and on the shared
/// meshes, and the great-circle error on icosphere(5) next to gdist's.
fn exact_geodesics(v: &mut Validator) {
    let flat = || -> Res<f64> {
        let mut worst = 0.0f64;
        for m in [shapes::grid(2.0, 1.0, 32, 16), shapes::disk(20, 5)] {
            let m = m.map_err(|e| e.to_string())?;
            for s in [0, m.vertex_count() / 3] {
                let p0 = m.position(VertexId::new(s));
                let truth: Vec<f64> = m.positions().iter().map(|p| p.distance(p0)).collect();
                worst = worst.max(errors(&exact(&m, VertexId::new(s))?, &truth).0);
            }
        }
        Ok(worst)
    };
    match flat() {
        Ok(e) => v.at_most("exact: grid and jittered disk vs Euclidean distance, max error", e, 1e-12),
        Err(e) => v.error("exact on flat meshes", e),
    }
    let cube = || -> Res<f64> {
        let m = shapes::cube(8).map_err(|e| e.to_string())?;
        let corner = m.positions().iter().position(|p| (*p + 1.0).length() < 1e-12).ok_or("no corner vertex")?;
        // From (-1,-1,-1): straight on the faces through the corner, else
        // through one of the two near faces next to the far face.
        let truth: Vec<f64> = m
            .positions()
            .iter()
            .map(|p| {
                let q = (*p + 1.0).to_array();
                if q.iter().any(|x| x.abs() < 1e-12) {
                    return (*p + 1.0).length();
                }
                (0..3)
                    .filter(|&i| (q[i] - 2.0).abs() < 1e-12)
                    .map(|i| {
                        let (a, b) = (q[(i + 1) % 3], q[(i + 2) % 3]);
                        (2.0 + a).hypot(b).min((2.0 + b).hypot(a))
                    })
                    .fold(f64::INFINITY, f64::min)
            })
            .collect();
        Ok(errors(&exact(&m, VertexId::new(corner))?, &truth).0)
    };
    match cube() {
        Ok(e) => v.at_most("exact: cube(8) from a corner vs unfolding, max error", e, 1e-12),
        Err(e) => v.error("exact on the cube", e),
    }
    let mmp = || -> Res<(f64, f64, f64)> {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../mesh-geodesic/tests/fixtures/icosphere3_exact_v0.txt");
        let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        let truth: Vec<f64> = text
            .lines()
            .filter(|l| !l.starts_with('#'))
            .map(|l| l.trim().parse::<f64>().map_err(|e| e.to_string()))
            .collect::<Res<_>>()?;
        let m = shapes::icosphere(3).map_err(|e| e.to_string())?;
        let d = exact(&m, VertexId(0))?;
        let f = fmm(FmmUpdate::CurvedFront)(&m)?;
        if truth.len() != d.len() {
            return Err(format!("fixture has {} values for {} vertices", truth.len(), d.len()));
        }
        let p0 = m.position(VertexId(0));
        let below_chord = m.positions().iter().zip(&d).map(|(p, x)| p.distance(p0) - x).fold(0.0, f64::max);
        let above_fmm = d.iter().zip(&f).map(|(x, y)| x - y).fold(0.0, f64::max);
        Ok((errors(&d, &truth).0, below_chord, above_fmm))
    };
    match mmp() {
        Ok((e, chord, above)) => {
            v.at_most("exact: icosphere(3) vs MMP (pygeodesic fixture), max difference", e, 1e-9);
            v.at_most("exact: icosphere(3) amount below the Euclidean chord", chord, 1e-12);
            v.at_most("exact: icosphere(3) amount above Fast Marching", above, 1e-12);
        }
        Err(e) => v.error("exact vs MMP", e),
    }
    exact_vs_mmp_fixtures(v);
    match sphere_errors(5, |m| exact(m, VertexId(0))) {
        // The polyhedron's own geodesics differ from great circles by this much.
        Ok((max, _)) => v.at_most("icosphere(5) exact polyhedral max error vs great circle (gdist 5e-4)", max, 6e-4),
        Err(e) => v.error("icosphere(5) exact", e),
    }
}

/// A fixture of `mesh-geodesic/scripts/exact_fixtures.py`: the largest
/// distance and (vertex, distance) pairs.
fn mmp_fixture(name: &str) -> Res<(f64, Vec<(usize, f64)>)> {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../mesh-geodesic/tests/fixtures")
        .join(format!("{name}_exact_v0.txt"));
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut max = None;
    let mut pairs = Vec::new();
    for line in text.lines() {
        if let Some(m) = line.strip_prefix("# max ") {
            max = Some(m.trim().parse::<f64>().map_err(|e| e.to_string())?);
        } else if !line.starts_with('#') {
            let mut it = line.split_whitespace();
            let (Some(i), Some(d)) = (it.next(), it.next()) else { return Err(format!("bad line `{line}`")) };
            pairs.push((i.parse::<usize>().map_err(|e| e.to_string())?, d.parse::<f64>().map_err(|e| e.to_string())?));
        }
    }
    Ok((max.ok_or("no `# max` line")?, pairs))
}

/// Exact distances from vertex 0 against MMP (pygeodesic fixtures, about
/// 600 vertices per mesh) on the valid shared meshes (closed, genus 3,
/// boundaries, creases; saddle vertices act as pseudo-sources) and on
/// icosphere(6) (40,962 vertices): max difference relative to the largest
/// distance, limit 1e-9.
fn exact_vs_mmp_fixtures(v: &mut Validator) {
    let mut cases: Vec<(&str, Option<&str>)> = vec![("icosphere6", None)];
    let dir = shared_data();
    if dir.is_some() {
        for file in [
            "cgal_elephant.off",
            "cgal_fandisk.off",
            "cgal_holes.off",
            "cgal_mushroom.off",
            "cgal_nefertiti.off",
            "npm_bunny.obj",
        ] {
            cases.push((file.split('.').next().unwrap_or(file), Some(file)));
        }
    } else {
        v.skip("exact vs MMP fixtures on the shared meshes", no_shared_data());
    }
    for (name, file) in cases {
        let run = || -> Res<(f64, usize)> {
            let (max, pairs) = mmp_fixture(name)?;
            let m = match (file, &dir) {
                (Some(f), Some(d)) => mesh_io::read(d.join(f)).map_err(|e| e.to_string())?.mesh,
                _ => shapes::icosphere(6).map_err(|e| e.to_string())?,
            };
            let d = exact(&m, VertexId(0))?;
            let mut worst = 0.0f64;
            let mut wrong_finiteness = 0;
            for (i, truth) in pairs {
                let ours = *d.get(i).ok_or(format!("fixture vertex {i} out of range"))?;
                if ours.is_finite() != truth.is_finite() {
                    wrong_finiteness += 1;
                } else if truth.is_finite() {
                    worst = worst.max((ours - truth).abs() / max);
                }
            }
            Ok((worst, wrong_finiteness))
        };
        match run() {
            Ok((worst, wrong)) => {
                v.at_most(
                    format!("exact vs MMP (pygeodesic fixture) on {name}: max difference / max distance"),
                    worst,
                    1e-9,
                );
                v.equal(format!("exact vs MMP on {name}: vertices with a different finiteness"), wrong as i64, 0);
            }
            Err(e) => v.error(format!("exact vs MMP on {name}"), e),
        }
    }
}

/// Finite distances within the source's component, infinite outside, on
/// every shared mesh and method; heat with the intrinsic Laplacian on
/// zero-area triangles (libigl returns NaN there).
fn shared_meshes(v: &mut Validator) {
    let Some(dir) = shared_data() else {
        v.skip("geodesics on shared meshes", no_shared_data());
        return;
    };
    let mut files: Vec<_> =
        std::fs::read_dir(&dir).map(|r| r.filter_map(|e| e.ok()).map(|e| e.path()).collect()).unwrap_or_default();
    files.retain(|p| p.extension().is_some_and(|e| e == "off" || e == "obj"));
    files.sort();
    for path in files {
        let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        let m = match mesh_io::read(&path) {
            Ok(d) => d.mesh,
            Err(e) => {
                v.error(format!("read {name}"), e);
                continue;
            }
        };
        let comp = m.connectivity().components().vertex_component.clone();
        let s = VertexId(0);
        let exact_field = match exact_distance(&m, &[s], &ExactOptions::default()) {
            Err(GeodesicError::Degenerate(why)) => {
                v.holds(format!("{name} exact: zero-area faces refused with a clear error"), true, why);
                None
            }
            other => Some(("exact", other.map_err(|e| e.to_string()))),
        };
        let fields: [(&str, Res<Vec<f64>>); 3] = [
            ("heat", heat(&m)),
            ("fmm", fmm(FmmUpdate::CurvedFront)(&m)),
            ("dijkstra", dijkstra(&m, &[s], &Default::default()).map(|t| t.distance).map_err(|e| e.to_string())),
        ];
        for (method, field) in fields.into_iter().chain(exact_field) {
            match field {
                Ok(d) => {
                    let wrong = d
                        .iter()
                        .enumerate()
                        .filter(|(i, x)| x.is_nan() || x.is_finite() != (comp[*i] == comp[s.idx()]))
                        .count();
                    v.equal(format!("{name} {method}: vertices with a wrong finiteness"), wrong as i64, 0);
                }
                Err(e) => v.error(format!("{name} {method}"), e),
            }
        }
    }
}
