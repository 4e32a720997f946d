//! mesh-param: the accuracy targets. Planar disks reproduced by the
//! linear-precision weights (harmonic, mean-value, authalic, intrinsic) and
//! by LSCM up to a similarity; Tutte's and Floater's theorems (no flipped
//! face onto a convex boundary) on the shared disks and on perturbed disks;
//! the intrinsic family's endpoints; the unrolled cylinder (Dirichlet energy
//! = area); convergence of the harmonic map of a hemisphere to the
//! stereographic projection; bijective Tutte and conformal maps of every
//! shared mesh (cut to a disk when needed); finite UVs on zero-area faces.

use mesh_kernel::glam::{DVec2, DVec3};
use mesh_kernel::{shapes, TriMesh};
use mesh_param::{parameterize, parameterize_cut, BoundaryMap, ParamError, ParamMethod, ParamOptions};

use super::{convergence_order, no_shared_data, shared_data, Validator};

/// Runs the mesh-param checks.
pub fn run(v: &mut Validator) {
    planar_reproduction(v);
    convex_boundary_theorems(v);
    intrinsic_endpoints(v);
    cylinder(v);
    hemisphere(v);
    shared_meshes(v);
}

fn map(mesh: &TriMesh, method: ParamMethod, boundary: BoundaryMap) -> Result<mesh_param::Parameterization, ParamError> {
    parameterize(mesh, &ParamOptions { method, boundary, ..ParamOptions::default() })
}

/// The boundary vertices with positions given by `f`.
fn own_boundary(mesh: &TriMesh, f: impl Fn(DVec3) -> DVec2) -> BoundaryMap {
    let loops = mesh.connectivity().boundary_loops().map(|l| l.to_vec()).unwrap_or_default();
    BoundaryMap::Fixed(loops.iter().flat_map(|l| l.vertices.iter().map(|&v| (v, f(mesh.position(v))))).collect())
}

fn max_distance(a: &[DVec2], b: &[DVec2]) -> f64 {
    a.iter().zip(b).map(|(p, q)| p.distance(*q)).fold(0.0, f64::max)
}

/// Largest distance from `a` to the least-squares similarity image of `b`,
/// relative to the diameter of `a`.
fn similarity_residual(a: &[DVec2], b: &[DVec2]) -> f64 {
    let n = a.len() as f64;
    let (ca, cb) = (a.iter().sum::<DVec2>() / n, b.iter().sum::<DVec2>() / n);
    let (mut re, mut im, mut norm) = (0.0, 0.0, 0.0);
    for (p, q) in a.iter().zip(b) {
        let (p, q) = (*p - ca, *q - cb);
        re += q.dot(p);
        im += q.perp_dot(p);
        norm += q.length_squared();
    }
    let s = DVec2::new(re, im) / norm;
    let diameter = 2.0 * a.iter().map(|p| p.distance(ca)).fold(0.0, f64::max);
    let fitted: Vec<DVec2> = b.iter().map(|q| s.rotate(*q - cb) + ca).collect();
    max_distance(a, &fitted) / diameter
}

/// A planar irregular disk (unit disk, jittered interior, some obtuse faces).
fn planar_disk(rings: usize) -> mesh_kernel::Result<TriMesh> {
    shapes::disk(rings, 3)
}

fn xy(p: DVec3) -> DVec2 {
    DVec2::new(p.x, p.y)
}

fn planar_reproduction(v: &mut Validator) {
    let m = match planar_disk(30) {
        Ok(m) => m,
        Err(e) => return v.error("planar disk", e),
    };
    let truth: Vec<DVec2> = m.positions().iter().map(|p| xy(*p)).collect();
    for method in [
        ParamMethod::Harmonic,
        ParamMethod::MeanValue,
        ParamMethod::Authalic,
        ParamMethod::Intrinsic { lambda: 0.5, mu: 0.5 },
    ] {
        let name = format!("planar disk 2791v, own boundary: {} max error", method.name());
        match map(&m, method, own_boundary(&m, xy)) {
            Ok(p) => v.at_most(name, max_distance(&p.uv, &truth), 1e-13),
            Err(e) => v.error(name, e),
        }
    }
    for rings in [12, 30] {
        let name = format!("planar disk, LSCM = input up to similarity (rings {rings}), relative");
        match planar_disk(rings).map_err(ParamError::from).and_then(|m| {
            let truth: Vec<DVec2> = m.positions().iter().map(|p| xy(*p)).collect();
            map(&m, ParamMethod::Lscm, BoundaryMap::default()).map(|p| similarity_residual(&truth, &p.uv))
        }) {
            // Two pins leave a system whose condition grows faster than n.
            Ok(r) => v.at_most(name, r, 1e-16 * (1.0 + 3.0 * (rings * (rings + 1)) as f64).powf(1.5)),
            Err(e) => v.error(name, e),
        }
    }
}

fn convex_boundary_theorems(v: &mut Validator) {
    // Perturbed disks: jittered, bent by a height field, and folded over.
    let mut failures = [0i64; 2];
    let mut count = 0;
    for seed in 0..40u64 {
        let rings = 2 + (seed as usize * 7) % 14;
        let Ok(mut m) = shapes::disk(rings, seed) else { continue };
        let (height, waves) = (0.2 + (seed % 5) as f64 * 0.4, 1.0 + (seed % 7) as f64);
        for p in m.positions_mut() {
            p.z = height * (waves * p.x).sin() * (waves * p.y + seed as f64).cos();
            if seed % 4 == 3 && p.x > 0.0 {
                *p = DVec3::new(-p.x, p.y, p.z + 0.3 * p.x);
            }
        }
        count += 1;
        for (k, method) in [ParamMethod::Tutte, ParamMethod::MeanValue].into_iter().enumerate() {
            let ok = map(&m, method, BoundaryMap::default()).is_ok_and(|p| p.report.summary.bijective);
            failures[k] += i64::from(!ok);
        }
    }
    v.equal(format!("Tutte onto a circle: non-bijective maps of {count} perturbed disks"), failures[0], 0);
    v.equal(format!("mean-value onto a circle: non-bijective maps of {count} perturbed disks"), failures[1], 0);
}

fn intrinsic_endpoints(v: &mut Validator) {
    let Ok(mut m) = shapes::disk(16, 5) else { return v.skip("intrinsic endpoints", "no disk") };
    for p in m.positions_mut() {
        p.z = 0.4 * (2.0 * p.x).sin() * p.y;
    }
    let pairs = [
        (
            "intrinsic mu = 0 vs harmonic, max difference",
            ParamMethod::Intrinsic { lambda: 1.0, mu: 0.0 },
            ParamMethod::Harmonic,
        ),
        (
            "intrinsic lambda = 0 vs authalic, max difference",
            ParamMethod::Intrinsic { lambda: 0.0, mu: 1.0 },
            ParamMethod::Authalic,
        ),
    ];
    for (name, a, b) in pairs {
        match map(&m, a, BoundaryMap::default()).and_then(|p| Ok((p, map(&m, b, BoundaryMap::default())?))) {
            Ok((p, q)) => v.at_most(name, max_distance(&p.uv, &q.uv), 1e-13),
            Err(e) => v.error(name, e),
        }
    }
}

fn cylinder(v: &mut Validator) {
    let name = "cylinder 48x10 cut open, LSCM: |Dirichlet energy / area - 1|";
    match shapes::cylinder(1.0, 2.0, 48, 10)
        .map_err(ParamError::from)
        .and_then(|m| parameterize_cut(&m, &ParamOptions { method: ParamMethod::Lscm, ..ParamOptions::default() }))
    {
        Ok(p) => {
            v.at_most(name, (p.param.report.summary.dirichlet_area_ratio - 1.0).abs(), 1e-10);
            v.holds("cylinder 48x10 cut open, LSCM bijective", p.param.report.summary.bijective, "");
        }
        Err(e) => v.error(name, e),
    }
}

fn hemisphere(v: &mut Validator) {
    // Inverse stereographic projection of the unit disk: the disk's own
    // coordinates are the exact conformal (hence harmonic) map.
    let stereographic = |p: DVec3| DVec2::new(p.x, p.y) / (1.0 + p.z);
    let mut errors = Vec::new();
    for rings in [4, 8, 16, 32] {
        let Ok(mut m) = shapes::disk(rings, 11) else { return v.skip("hemisphere", "no disk") };
        for p in m.positions_mut() {
            let r2 = p.x * p.x + p.y * p.y;
            *p = DVec3::new(2.0 * p.x, 2.0 * p.y, 1.0 - r2) / (1.0 + r2);
        }
        let truth: Vec<DVec2> = m.positions().iter().map(|p| stereographic(*p)).collect();
        match map(&m, ParamMethod::Harmonic, own_boundary(&m, stereographic)) {
            Ok(p) => errors.push(max_distance(&p.uv, &truth)),
            Err(e) => return v.error("hemisphere harmonic map", e),
        }
    }
    v.at_most("hemisphere harmonic map vs stereographic, max error at h = 1/32", errors[3], 1e-3);
    v.at_least("hemisphere harmonic map vs stereographic, convergence order", convergence_order(&errors), 1.5);
}

fn shared_meshes(v: &mut Validator) {
    let Some(dir) = shared_data() else { return v.skip("shared meshes", no_shared_data()) };
    let files = [
        "cgal_nefertiti.off",
        "cgal_mushroom.off",
        "cgal_degtri_sliding.off",
        "cgal_elephant.off",
        "cgal_fandisk.off",
        "npm_bunny.obj",
        "cgal_holes.off",
    ];
    for file in files {
        let mesh = match mesh_io::read(dir.join(file)) {
            Ok(d) => d.mesh,
            Err(e) => {
                v.error(format!("{file}: read"), e);
                continue;
            }
        };
        let disk = mesh_param::Topology::of(&mesh).is_ok_and(|t| t.is_disk());
        for method in [ParamMethod::Tutte, ParamMethod::Harmonic, ParamMethod::Lscm] {
            let name = format!("{file}: {} map bijective", method.name());
            match parameterize_cut(&mesh, &ParamOptions { method, ..ParamOptions::default() }) {
                Ok(p) => {
                    let s = p.param.report.summary;
                    let note = format!(
                        "{} seam edges, {} flipped, angle distortion {:.3}",
                        p.cut.seam.len(),
                        s.flipped_faces,
                        s.angle_distortion_mean
                    );
                    let finite = p.param.uv.iter().all(|q| q.is_finite());
                    if method == ParamMethod::Lscm && !disk {
                        // A free boundary of a cut mesh may overlap itself:
                        // reported, not required.
                        v.skip(name, format!("cut mesh, free boundary: bijective = {}; {note}", s.bijective));
                    } else {
                        v.holds(name, s.bijective && finite, note);
                    }
                }
                Err(e) => v.error(name, e),
            }
        }
    }
}
