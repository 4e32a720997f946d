//! mesh-nurbs: exact geometry (the rational circle on its circle, the
//! sphere's and torus's Gaussian and mean curvature from the fundamental
//! forms, partition of unity and non-negativity of the basis), the
//! tessellated sphere's area under refinement, and the cross-crate check:
//! mesh-curvature's default estimator on tessellations of exact surfaces
//! (torus, sphere, cylinder, saddle) converges to the exact per-vertex
//! curvatures, with the observed order.

use std::f64::consts::PI;

use mesh_curvature::{curvature_tensor, TensorOptions};
use mesh_kernel::{VertexId, VertexKind};
use mesh_nurbs::basis::basis_values;
use mesh_nurbs::glam::DVec3;
use mesh_nurbs::{shapes, tessellate, GridOptions, KnotVector, NurbsSurface, SurfaceFrame};

use super::{convergence_order, Validator};

/// Runs the mesh-nurbs checks.
pub fn run(v: &mut Validator) {
    circle(v);
    sphere_frames(v);
    torus_frames(v);
    partition_of_unity(v);
    sphere_area(v);
    curvature_convergence(v);
}

/// `count + 1` equally spaced values over `[a, b]`.
fn samples((a, b): (f64, f64), count: usize) -> impl Iterator<Item = f64> {
    (0..=count).map(move |k| a + (b - a) * k as f64 / count as f64)
}

/// Points of rational quadratic circles lie on their circle.
fn circle(v: &mut Validator) {
    let result = (|| -> mesh_nurbs::error::Result<f64> {
        let mut worst = 0.0f64;
        for (center, r) in [(DVec3::ZERO, 1.0), (DVec3::new(0.3, -1.2, 2.0), 2.5)] {
            let c = shapes::circle(center, r)?;
            for u in samples(c.domain(), 10_000) {
                worst = worst.max((c.point(u)?.distance(center) - r).abs() / r);
            }
        }
        Ok(worst)
    })();
    match result {
        Ok(e) => v.at_most("rational circle: max ||P(u) - c| - r| / r, 2 circles x 10001 points", e, 1e-14),
        Err(e) => v.error("rational circle", e),
    }
}

/// Largest errors of K and H over a 101 x 101 parameter grid of regular
/// points, skipping parameters within `margin_v` of the v ends (poles).
fn frame_errors(
    s: &NurbsSurface,
    margin_v: f64,
    exact: impl Fn(&SurfaceFrame) -> (f64, f64),
) -> mesh_nurbs::error::Result<(f64, f64, usize)> {
    let (v0, v1) = s.domain_v();
    let (mut ek, mut eh, mut count) = (0.0f64, 0.0f64, 0);
    for u in samples(s.domain_u(), 100) {
        for w in samples((v0 + margin_v, v1 - margin_v), 100) {
            let f = SurfaceFrame::new(s, u, w)?;
            if !f.regular {
                continue;
            }
            let (k, h) = exact(&f);
            ek = ek.max((f.gaussian - k).abs());
            eh = eh.max((f.mean - h).abs());
            count += 1;
        }
    }
    Ok((ek, eh, count))
}

/// Sphere of radius 2: K = 1/4, H = 1/2 (outward normal), away from poles.
fn sphere_frames(v: &mut Validator) {
    let r = 2.0;
    match shapes::sphere(DVec3::new(1.0, -0.5, 0.25), r)
        .and_then(|s| frame_errors(&s, 0.01, |_| (1.0 / (r * r), 1.0 / r)))
    {
        Ok((ek, eh, n)) => {
            v.at_most(format!("sphere r = 2: max |K - 1/r^2| over {n} points off the poles"), ek, 1e-10);
            v.at_most(format!("sphere r = 2: max |H - 1/r| over {n} points off the poles"), eh, 1e-10);
        }
        Err(e) => v.error("sphere frames", e),
    }
}

/// Torus R = 2, r = 0.5: K = cos t / (r (R + r cos t)), H = (1/r + cos t /
/// (R + r cos t)) / 2, with `R + r cos t` the distance to the axis.
fn torus_frames(v: &mut Validator) {
    let (big, r) = (2.0, 0.5);
    let exact = |f: &SurfaceFrame| {
        let rho = f.point().truncate().length();
        let cos_t = (rho - big) / r;
        (cos_t / (r * rho), 0.5 * (1.0 / r + cos_t / rho))
    };
    match shapes::torus(DVec3::ZERO, big, r).and_then(|s| frame_errors(&s, 0.0, exact)) {
        Ok((ek, eh, n)) => {
            v.at_most(format!("torus R = 2 r = 0.5: max |K - cos t / (r (R + r cos t))| over {n} points"), ek, 1e-10);
            v.at_most(format!("torus R = 2 r = 0.5: max |H - exact| over {n} points"), eh, 1e-10);
        }
        Err(e) => v.error("torus frames", e),
    }
}

/// The basis functions of a span sum to one and are non-negative.
fn partition_of_unity(v: &mut Validator) {
    let result = (|| -> mesh_nurbs::error::Result<(f64, f64)> {
        let knots = [
            KnotVector::clamped_uniform(3, 8)?,
            KnotVector::new(3, vec![0.0, 0.0, 0.0, 0.0, 0.1, 0.15, 0.5, 0.5, 0.9, 1.0, 1.0, 1.0, 1.0])?,
            KnotVector::new(2, vec![0.0, 0.0, 0.0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1.0, 1.0, 1.0])?,
        ];
        let (mut sum_error, mut lowest) = (0.0f64, f64::INFINITY);
        for kv in &knots {
            for u in samples(kv.domain(), 10_000) {
                let n = basis_values(kv, kv.span(u), u);
                let values = &n[..=kv.degree()];
                sum_error = sum_error.max((values.iter().sum::<f64>() - 1.0).abs());
                lowest = values.iter().fold(lowest, |a, &b| a.min(b));
            }
        }
        Ok((sum_error, lowest))
    })();
    match result {
        Ok((sum, lowest)) => {
            v.at_most("basis: max |sum_i N_i,p(u) - 1|, 3 knot vectors x 10001 points", sum, 1e-14);
            v.at_least("basis: min N_i,p(u) (non-negative)", lowest, 0.0);
        }
        Err(e) => v.error("basis partition of unity", e),
    }
}

/// The inscribed tessellation's area tends to 4 pi r^2 at order 2.
fn sphere_area(v: &mut Validator) {
    let result = (|| -> mesh_nurbs::error::Result<Vec<f64>> {
        let s = shapes::sphere(DVec3::ZERO, 1.0)?;
        [8, 16, 32, 64]
            .iter()
            .map(|&n| {
                let t = tessellate(&s, &GridOptions { segments_u: 2 * n, segments_v: n, ..Default::default() })?;
                Ok((mesh_kernel::geometry::surface_area(&t.mesh) - 4.0 * PI).abs())
            })
            .collect()
    })();
    match result {
        Ok(e) => {
            let name = format!("sphere tessellation area -> 4 pi r^2 order, 2n x n, n = 8..64 ({})", list(&e));
            v.at_least(name, convergence_order(&e), 1.8);
        }
        Err(e) => v.error("sphere tessellation area", e),
    }
}

fn list(e: &[f64]) -> String {
    e.iter().map(|x| format!("{x:.1e}")).collect::<Vec<_>>().join(" ")
}

/// Vertices compared: all regular interior ones, or those off the poles.
#[derive(Clone, Copy)]
enum Keep {
    All,
    OffPoles,
}

/// Max errors of k1, k2, H, K and max(|k1 - k1 exact|, |k2 - k2 exact|) of
/// the default estimator over the regular interior vertices with a valid
/// estimate, on a `segments_u x segments_v` grid.
fn estimator_errors(s: &NurbsSurface, segments_u: usize, segments_v: usize, keep: Keep) -> Result<[f64; 5], String> {
    let t = tessellate(s, &GridOptions { segments_u, segments_v, ..Default::default() }).map_err(|e| e.to_string())?;
    let est = curvature_tensor(&t.mesh, &TensorOptions::default()).map_err(|e| e.to_string())?;
    let conn = t.mesh.connectivity();
    let mut e = [0.0f64; 5];
    for (i, p) in t.mesh.positions().iter().enumerate() {
        let interior = conn.vertex_kind(VertexId::new(i)) == VertexKind::Interior;
        let kept = match keep {
            Keep::All => true,
            // 11.5 degree caps around the poles of the unit sphere.
            Keep::OffPoles => p.z.abs() <= 0.98,
        };
        if !(t.regular[i] && interior && est.status[i].is_valid() && kept) {
            continue;
        }
        let (k1, k2) = (est.k1[i], est.k2[i]);
        let (d1, d2) = ((k1 - t.k1[i]).abs(), (k2 - t.k2[i]).abs());
        for (q, x) in [d1, d2, (0.5 * (k1 + k2) - t.mean[i]).abs(), (k1 * k2 - t.gaussian[i]).abs(), d1.max(d2)]
            .into_iter()
            .enumerate()
        {
            e[q] = e[q].max(x);
        }
    }
    Ok(e)
}

/// A surface of the cross-crate check: its grid (`ratio n x n`), the
/// vertices compared and the quantities judged (indices into the errors of
/// [`estimator_errors`]).
struct Case {
    name: &'static str,
    surface: mesh_nurbs::error::Result<NurbsSurface>,
    ratio: usize,
    keep: Keep,
    quantities: &'static [usize],
}

/// mesh-curvature's default estimator against the exact curvature of the
/// tessellations at n = 16, 32, 64, 128 (the mesh size halves): every error
/// falls at every step, at an observed mean order of at least 2.5 (a
/// quartic fit: 3, one more on symmetric neighbourhoods).
fn curvature_convergence(v: &mut Validator) {
    let o = DVec3::ZERO;
    let all_four: &[usize] = &[0, 1, 2, 3];
    // Umbilics: k1 - k2 = 2 sqrt(H^2 - K) splits any error arbitrarily
    // between k1 and k2, so the sphere is judged on H, K, max(|dk1|, |dk2|).
    let umbilic: &[usize] = &[2, 3, 4];
    let cases = [
        Case {
            name: "torus R 2 r 0.5, 4n x n",
            surface: shapes::torus(o, 2.0, 0.5),
            ratio: 4,
            keep: Keep::All,
            quantities: all_four,
        },
        Case {
            name: "sphere r 1, 2n x n",
            surface: shapes::sphere(o, 1.0),
            ratio: 2,
            keep: Keep::All,
            quantities: umbilic,
        },
        Case {
            name: "sphere r 1, 2n x n, |z| <= 0.98",
            surface: shapes::sphere(o, 1.0),
            ratio: 2,
            keep: Keep::OffPoles,
            quantities: umbilic,
        },
        Case {
            name: "cylinder r 1 h 2, 3n x n",
            surface: shapes::cylinder(o, 1.0, 2.0),
            ratio: 3,
            keep: Keep::All,
            quantities: all_four,
        },
        Case {
            name: "saddle z = xy, n x n",
            surface: shapes::bilinear(o, DVec3::X, DVec3::Y, DVec3::new(1.0, 1.0, 1.0)),
            ratio: 1,
            keep: Keep::All,
            quantities: all_four,
        },
    ];
    let names = ["k1", "k2", "H", "K", "max(|dk1|, |dk2|)"];
    for Case { name, surface, ratio, keep, quantities } in cases {
        let errors = surface
            .map_err(|e| e.to_string())
            .and_then(|s| [16, 32, 64, 128].iter().map(|&n| estimator_errors(&s, ratio * n, n, keep)).collect());
        let errors: Vec<[f64; 5]> = match errors {
            Ok(e) => e,
            Err(e) => {
                v.error(format!("mesh-curvature on {name}"), e);
                continue;
            }
        };
        let mut falls = true;
        for &q in quantities {
            let e: Vec<f64> = errors.iter().map(|e| e[q]).collect();
            falls &= e.windows(2).all(|w| w[1] < w[0]);
            let check = format!("mesh-curvature on {name}: {} order ({})", names[q], list(&e));
            v.at_least(check, convergence_order(&e), 2.5);
        }
        v.holds(
            format!("mesh-curvature on {name}: every error falls at every refinement"),
            falls,
            "n = 16, 32, 64, 128",
        );
    }
    // The torus target, on the NURBS torus's 256 x 64 grid.
    let shapes_torus = shapes::torus(o, 2.0, 0.5).map_err(|e| e.to_string());
    match shapes_torus.and_then(|s| estimator_errors(&s, 256, 64, Keep::All)) {
        Ok(e) => {
            v.at_most("mesh-curvature on torus 256x64: max |k1 - exact| (issue target)", e[0], 0.01);
            v.at_most("mesh-curvature on torus 256x64: max |k2 - exact| (issue target)", e[1], 0.01);
        }
        Err(e) => v.error("mesh-curvature on torus 256x64", e),
    }
}
