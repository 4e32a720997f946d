//! Accuracy against ground truth: reproduction of planar meshes, the
//! stereographic projection of a hemisphere (the exact conformal map), the
//! unrolled cylinder, and the identities between weight families.

mod common;

use glam::{DVec2, DVec3};
use mesh_kernel::{shapes, TriMesh, VertexId};
use mesh_param::{parameterize, parameterize_cut, BoundaryMap, ParamMethod, ParamOptions};

const FIXED_METHODS: [ParamMethod; 5] = [
    ParamMethod::Tutte,
    ParamMethod::MeanValue,
    ParamMethod::Harmonic,
    ParamMethod::Authalic,
    ParamMethod::Intrinsic { lambda: 0.5, mu: 0.5 },
];

/// The boundary vertices of a disk with their (x, y) positions.
fn own_boundary(mesh: &TriMesh, f: impl Fn(DVec3) -> DVec2) -> BoundaryMap {
    let b = &mesh.connectivity().boundary_loops().unwrap()[0].vertices;
    BoundaryMap::Fixed(b.iter().map(|&v| (v, f(mesh.position(v)))).collect())
}

fn max_error(uv: &[DVec2], mesh: &TriMesh, f: impl Fn(DVec3) -> DVec2) -> f64 {
    uv.iter().zip(mesh.positions()).map(|(q, p)| q.distance(f(*p))).fold(0.0, f64::max)
}

/// A planar, irregular disk (jittered interior, some obtuse triangles),
/// rotated and shifted out of the xy plane's origin.
fn planar_disk(rings: usize, seed: u64) -> TriMesh {
    let mut m = shapes::disk(rings, seed).unwrap();
    for p in m.positions_mut() {
        *p = DVec3::new(3.0 * p.x + 1.0, 2.0 * p.y - 0.5, 0.0);
    }
    m
}

#[test]
fn planar_disk_is_reproduced_by_linear_precision_weights() {
    let xy = |p: DVec3| DVec2::new(p.x, p.y);
    for (rings, seed) in [(3, 1), (10, 2), (30, 3)] {
        let m = planar_disk(rings, seed);
        for method in [
            ParamMethod::MeanValue,
            ParamMethod::Harmonic,
            ParamMethod::Authalic,
            ParamMethod::Intrinsic { lambda: 0.3, mu: 0.7 },
        ] {
            let options = ParamOptions { method, boundary: own_boundary(&m, xy), ..Default::default() };
            let p = parameterize(&m, &options).unwrap();
            let err = max_error(&p.uv, &m, xy);
            eprintln!("planar reproduction, {} rings, {}: {err:.1e}", rings, method.name());
            assert!(err < 1e-13, "{}: {err}", method.name());
            assert!(p.report.summary.bijective);
            assert!((p.report.summary.dirichlet_area_ratio - 1.0).abs() < 1e-12);
            assert!((p.report.summary.angle_distortion_max - 1.0).abs() < 1e-10);
        }
        // Tutte has no linear precision on an irregular mesh: it must move vertices.
        let options = ParamOptions { method: ParamMethod::Tutte, boundary: own_boundary(&m, xy), ..Default::default() };
        assert!(max_error(&parameterize(&m, &options).unwrap().uv, &m, xy) > 1e-3);
    }
}

#[test]
fn lscm_reproduces_a_planar_disk_up_to_similarity() {
    for (rings, seed) in [(3, 4), (12, 5), (30, 6)] {
        let m = planar_disk(rings, seed);
        let p = parameterize(&m, &ParamOptions { method: ParamMethod::Lscm, normalize: true, ..Default::default() })
            .unwrap();
        let xy: Vec<DVec2> = m.positions().iter().map(|p| DVec2::new(p.x, p.y)).collect();
        let r = common::similarity_residual(&xy, &p.uv);
        eprintln!("LSCM planar reproduction, {rings} rings: {r:.1e}");
        // Two pins leave nearly-conformal deformations (z + eps z^2) with
        // energies ~ h^2: the system's condition grows faster than n and so
        // does rounding (observed 1e-15, 1e-13, 3e-12 relative to the diameter
        // at 37, 469, 2791 vertices).
        assert!(r < 1e-16 * (m.vertex_count() as f64).powf(1.5), "{r}");
        // Normalized into the unit box, touching both ends of its long side.
        let (lo, hi) = p.uv.iter().fold((DVec2::MAX, DVec2::MIN), |(lo, hi), q| (lo.min(*q), hi.max(*q)));
        assert!(lo.min_element().abs() < 1e-15 && (hi.max_element() - 1.0).abs() < 1e-15);
    }
}

/// Inverse stereographic projection of the unit disk onto the upper unit
/// hemisphere: the disk's own (x, y) is then the exact conformal map.
fn hemisphere(rings: usize) -> TriMesh {
    let mut m = shapes::disk(rings, 11).unwrap();
    for p in m.positions_mut() {
        let r2 = p.x * p.x + p.y * p.y;
        *p = DVec3::new(2.0 * p.x, 2.0 * p.y, 1.0 - r2) / (1.0 + r2);
    }
    m
}

fn stereographic(p: DVec3) -> DVec2 {
    DVec2::new(p.x, p.y) / (1.0 + p.z)
}

#[test]
fn harmonic_map_converges_to_the_stereographic_projection() {
    // Conformal maps are harmonic: with the boundary fixed where the
    // stereographic projection puts it, the harmonic map converges to it.
    // LSCM's free boundary has no unique continuous limit (any conformal map
    // of the hemisphere is a minimizer), so it is measured by its angle
    // distortion instead, which must tend to 1.
    let mut previous: Option<(f64, f64)> = None;
    for rings in [4, 8, 16, 32] {
        let m = hemisphere(rings);
        let h = 1.0 / rings as f64;
        let options = ParamOptions {
            method: ParamMethod::Harmonic,
            boundary: own_boundary(&m, stereographic),
            ..Default::default()
        };
        let harmonic = parameterize(&m, &options).unwrap();
        let e_h = max_error(&harmonic.uv, &m, stereographic);
        let lscm = parameterize(&m, &ParamOptions { method: ParamMethod::Lscm, ..Default::default() }).unwrap();
        let e_l = lscm.report.summary.angle_distortion_mean - 1.0;
        eprintln!("hemisphere h = {h:.4}: harmonic max error {e_h:.2e}, LSCM mean angle distortion - 1 = {e_l:.2e}");
        if let Some((ph, pl)) = previous {
            let (oh, ol) = ((ph / e_h).log2(), (pl / e_l).log2());
            eprintln!("  observed orders: harmonic {oh:.2}, LSCM {ol:.2}");
            // Positions converge at order 2, piecewise-linear Jacobians at order 1.
            assert!(oh > 1.5 && ol > 0.8, "orders {oh} {ol}");
        }
        assert!(e_h < 0.5 * h * h, "{e_h}");
        assert!(harmonic.report.summary.bijective && lscm.report.summary.bijective);
        previous = Some((e_h, e_l));
    }
}

#[test]
fn intrinsic_endpoints_are_conformal_and_authalic() {
    let mut m = shapes::disk(12, 8).unwrap();
    for p in m.positions_mut() {
        p.z = 0.4 * (2.0 * p.x).sin() * p.y;
    }
    let run = |method| parameterize(&m, &ParamOptions { method, ..Default::default() }).unwrap().uv;
    let (harmonic, authalic) = (run(ParamMethod::Harmonic), run(ParamMethod::Authalic));
    let conformal_end = run(ParamMethod::Intrinsic { lambda: 2.0, mu: 0.0 });
    let authalic_end = run(ParamMethod::Intrinsic { lambda: 0.0, mu: 3.0 });
    let diff = |a: &[DVec2], b: &[DVec2]| a.iter().zip(b).map(|(p, q)| p.distance(*q)).fold(0.0, f64::max);
    assert!(diff(&harmonic, &conformal_end) < 1e-14);
    assert!(diff(&authalic, &authalic_end) < 1e-14);
    // And the two ends really differ on a curved surface.
    assert!(diff(&harmonic, &authalic) > 1e-3);
    let mid = run(ParamMethod::Intrinsic { lambda: 0.5, mu: 0.5 });
    assert!(diff(&mid, &harmonic) > 1e-4 && diff(&mid, &authalic) > 1e-4);
}

#[test]
fn developable_cylinder_strip_is_unrolled_isometrically() {
    // A cylinder cut open along a seam is developable: its conformal map is
    // an isometry (up to scale), Dirichlet energy = area.
    for (around, along) in [(12, 3), (48, 10)] {
        let m = shapes::cylinder(1.0, 2.0, around, along).unwrap();
        for method in [ParamMethod::Lscm, ParamMethod::Arap { iterations: 30 }] {
            let p = parameterize_cut(&m, &ParamOptions { method, ..Default::default() }).unwrap();
            assert!(!p.cut.seam.is_empty());
            let s = p.param.report.summary;
            eprintln!(
                "cylinder {around}x{along} {}: E_D/A - 1 = {:.1e}, angle max - 1 = {:.1e}, area max - 1 = {:.1e}",
                method.name(),
                s.dirichlet_area_ratio - 1.0,
                s.angle_distortion_max - 1.0,
                s.area_distortion_max - 1.0
            );
            assert!(s.bijective);
            // LSCM is exact; ARAP converges linearly towards the isometry.
            let tol = if method == ParamMethod::Lscm { 1e-10 } else { 1e-2 };
            assert!((s.dirichlet_area_ratio - 1.0).abs() < tol * tol, "{}", s.dirichlet_area_ratio);
            assert!(s.angle_distortion_max - 1.0 < tol && s.area_distortion_max - 1.0 < tol);
        }
        // The harmonic map onto a circle is not conformal here.
        let h = parameterize_cut(&m, &ParamOptions { method: ParamMethod::Harmonic, ..Default::default() }).unwrap();
        assert!(h.param.report.summary.dirichlet_area_ratio > 1.01);
    }
}

#[test]
fn square_boundary_keeps_corners() {
    let m = shapes::grid(1.0, 1.0, 8, 8).unwrap();
    let corners = [0u32, 8, 80, 72].map(VertexId);
    for method in FIXED_METHODS {
        let p =
            parameterize(&m, &ParamOptions { method, boundary: BoundaryMap::Square, ..Default::default() }).unwrap();
        // The square's corners are at a quarter of the boundary length each:
        // the grid's own corners.
        for (c, v) in corners.iter().enumerate() {
            let expected = [DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y][c];
            assert!(p.uv[v.idx()].distance(expected) < 1e-14, "{}", method.name());
        }
        if method != ParamMethod::Tutte {
            // The grid is the unit square: reproduced exactly.
            let err = max_error(&p.uv, &m, |p| DVec2::new(p.x, p.y));
            assert!(err < 1e-13, "{}: {err}", method.name());
        }
    }
}
