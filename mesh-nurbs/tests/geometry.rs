//! Exact differential geometry against analytic ground truth (eq. 2.19-2.24):
//! circle, sphere, torus, cylinder, cone; derivatives against finite
//! differences; knot insertion leaves surfaces unchanged.

use std::f64::consts::TAU;

use mesh_nurbs::glam::DVec3;
use mesh_nurbs::{shapes, KnotVector, NurbsSurface, SurfaceFrame};
use proptest::prelude::*;

#[test]
fn rational_circle_points_lie_on_the_circle() {
    let center = DVec3::new(0.5, -1.5, 2.0);
    let c = shapes::circle(center, 2.5).expect("circle");
    assert_eq!(c.control_points().len(), 9);
    for s in 0..=1000 {
        let u = s as f64 / 1000.0;
        let p = c.point(u).expect("point");
        assert!(((p - center).length() - 2.5).abs() < 1e-14, "u {u}");
        assert!((p.z - center.z).abs() < 1e-15);
        assert!((c.curvature(u).expect("curvature") - 0.4).abs() < 1e-12);
    }
    assert_eq!(c.point(0.0).expect("start"), c.point(1.0).expect("end"));
}

#[test]
fn sphere_has_constant_curvature() {
    for r in [0.5, 1.0, 3.0] {
        let s = shapes::sphere(DVec3::new(1.0, 2.0, 3.0), r).expect("sphere");
        for a in 0..=40 {
            for b in 1..40 {
                let (u, v) = (a as f64 / 40.0, b as f64 / 40.0);
                let f = SurfaceFrame::new(&s, u, v).expect("frame");
                assert!(f.regular);
                assert!((f.gaussian - 1.0 / (r * r)).abs() < 1e-10 / (r * r), "K {} at ({u}, {v})", f.gaussian);
                assert!((f.mean - 1.0 / r).abs() < 1e-10 / r, "H {} at ({u}, {v})", f.mean);
                assert!((f.k1 - 1.0 / r).abs() < 1e-7 / r && (f.k2 - 1.0 / r).abs() < 1e-7 / r);
                let radial = (f.point() - DVec3::new(1.0, 2.0, 3.0)) / r;
                assert!((radial.length() - 1.0).abs() < 1e-14);
                assert!((f.normal - radial).length() < 1e-12, "outward normal");
                assert!(f.d1.dot(f.normal).abs() < 1e-12 && f.d2.dot(f.d1).abs() < 1e-12);
            }
        }
    }
}

#[test]
fn sphere_poles_are_finite_and_flagged() {
    let s = shapes::sphere(DVec3::ZERO, 2.0).expect("sphere");
    for (v, z) in [(0.0, -1.0), (1.0, 1.0)] {
        for a in 0..8 {
            let f = SurfaceFrame::new(&s, a as f64 / 8.0, v).expect("frame");
            assert!(!f.regular);
            assert!((f.normal - DVec3::new(0.0, 0.0, z)).length() < 1e-12);
            assert!(
                (f.gaussian - 0.25).abs() < 1e-6 && (f.mean - 0.5).abs() < 1e-6,
                "K {} H {} at u {}",
                f.gaussian,
                f.mean,
                a
            );
            assert!([f.k1, f.k2, f.e, f.f, f.g, f.l, f.m, f.n].iter().all(|x| x.is_finite()));
        }
    }
}

/// Tube angle of a torus point about its centre circle.
fn tube_angle(p: DVec3, major: f64) -> f64 {
    let rho = (p.x * p.x + p.y * p.y).sqrt();
    p.z.atan2(rho - major)
}

#[test]
fn torus_matches_analytic_curvature() {
    let (big, small) = (3.0, 1.0);
    let t = shapes::torus(DVec3::ZERO, big, small).expect("torus");
    for a in 0..=24 {
        for b in 0..=48 {
            let (u, v) = (a as f64 / 24.0, b as f64 / 48.0);
            let f = SurfaceFrame::new(&t, u, v).expect("frame");
            assert!(f.regular);
            let theta = tube_angle(f.point(), big);
            let c = theta.cos();
            let k_expected = c / (small * (big + small * c));
            assert!((f.gaussian - k_expected).abs() < 1e-10, "K at ({u}, {v})");
            assert!((f.k1 - 1.0 / small).abs() < 1e-9, "k1 {} at ({u}, {v})", f.k1);
            assert!((f.k2 - c / (big + small * c)).abs() < 1e-9, "k2 {} at ({u}, {v})", f.k2);
            assert!((f.mean - 0.5 * (1.0 / small + c / (big + small * c))).abs() < 1e-10);
            // d1 (curvature 1/r) runs around the tube, d2 along the parallel.
            let parallel = DVec3::new(-f.point().y, f.point().x, 0.0).normalize();
            assert!(f.d2.cross(parallel).length() < 1e-7, "d2 along the parallel at ({u}, {v})");
            // Outward: away from the centre circle.
            let rho = DVec3::new(f.point().x, f.point().y, 0.0).normalize() * big;
            assert!((f.normal - (f.point() - rho) / small).length() < 1e-12);
        }
    }
}

#[test]
fn cylinder_and_cone_curvature() {
    let cyl = shapes::cylinder(DVec3::ZERO, 2.0, 5.0).expect("cylinder");
    for (u, v) in [(0.1, 0.2), (0.6, 0.9), (0.33, 0.5)] {
        let f = SurfaceFrame::new(&cyl, u, v).expect("frame");
        assert!(f.gaussian.abs() < 1e-12 && (f.mean - 0.25).abs() < 1e-12);
        assert!((f.k1 - 0.5).abs() < 1e-12 && f.k2.abs() < 1e-12);
        assert!(f.d2.cross(DVec3::Z).length() < 1e-12);
    }
    let (radius, height) = (1.0, 2.0);
    let cone = shapes::cone(DVec3::ZERO, radius, height).expect("cone");
    let slope = radius.atan2(height); // half-angle at the apex
    for (u, v) in [(0.1, 0.2), (0.6, 0.7)] {
        let f = SurfaceFrame::new(&cone, u, v).expect("frame");
        let rho = (f.point().x.powi(2) + f.point().y.powi(2)).sqrt();
        assert!(f.gaussian.abs() < 1e-12);
        // Parallel circle of radius rho: normal curvature cos(half-angle) / rho.
        assert!((f.k1 - slope.cos() / rho).abs() < 1e-10, "k1 {}", f.k1);
        assert!(f.normal.z > 0.0 && f.normal.x * f.point().x + f.normal.y * f.point().y > 0.0);
    }
    let apex = SurfaceFrame::new(&cone, 0.3, 1.0).expect("apex frame");
    assert!(!apex.regular);
    assert!(apex.normal.is_finite() && apex.mean.is_finite() && apex.gaussian.is_finite());
    assert!((apex.point() - DVec3::new(0.0, 0.0, height)).length() < 1e-15);
}

#[test]
fn revolved_profile_matches_its_curve() {
    let profile = shapes::line(DVec3::new(1.0, 0.0, 0.0), DVec3::new(2.0, 0.0, 1.0)).expect("profile");
    let s = shapes::revolve(&profile, TAU / 3.0).expect("revolve");
    for a in 0..=10 {
        let u = a as f64 / 10.0;
        let p = s.point(u, 0.5).expect("point");
        assert!(((p.x * p.x + p.y * p.y).sqrt() - 1.5).abs() < 1e-14 && (p.z - 0.5).abs() < 1e-15);
    }
    let end = s.point(1.0, 0.0).expect("end");
    assert!((end - DVec3::new((TAU / 3.0).cos(), (TAU / 3.0).sin(), 0.0)).length() < 1e-14);
}

/// Random rational bicubic-by-quadratic patch.
fn random_surface() -> impl Strategy<Value = NurbsSurface> {
    (prop::collection::vec(-1.0f64..1.0, 5 * 4 * 3), prop::collection::vec(0.5f64..2.0, 5 * 4), 0.2f64..0.8).prop_map(
        |(coords, weights, knot)| {
            let ku = KnotVector::new(3, vec![0.0, 0.0, 0.0, 0.0, knot, 1.0, 1.0, 1.0, 1.0]).expect("knots");
            let kv = KnotVector::clamped_uniform(2, 4).expect("knots");
            let points = (0..20)
                .map(|k| {
                    let (i, j) = (k / 4, k % 4);
                    DVec3::new(i as f64, j as f64, 0.0) + DVec3::from_slice(&coords[3 * k..3 * k + 3]) * 0.4
                })
                .collect();
            NurbsSurface::new(ku, kv, points, weights).expect("surface")
        },
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn derivatives_agree_with_central_differences(s in random_surface(), u in 0.05f64..0.95, v in 0.05f64..0.95) {
        let h = 1e-6;
        let p = |u: f64, v: f64| s.point(u, v).expect("point");
        let d1 = |u: f64, v: f64| s.derivatives(u, v, 1).expect("derivatives");
        let d = s.derivatives(u, v, 2).expect("derivatives");
        let scale = 1.0 + d.su.length() + d.sv.length();
        prop_assert!((d.su - (p(u + h, v) - p(u - h, v)) / (2.0 * h)).length() < 1e-6 * scale);
        prop_assert!((d.sv - (p(u, v + h) - p(u, v - h)) / (2.0 * h)).length() < 1e-6 * scale);
        let scale2 = 1.0 + d.suu.length() + d.suv.length() + d.svv.length();
        let suu = (d1(u + h, v).su - d1(u - h, v).su) / (2.0 * h);
        let suv = (d1(u, v + h).su - d1(u, v - h).su) / (2.0 * h);
        let svv = (d1(u, v + h).sv - d1(u, v - h).sv) / (2.0 * h);
        prop_assert!((d.suu - suu).length() < 1e-5 * scale2);
        prop_assert!((d.suv - suv).length() < 1e-5 * scale2);
        prop_assert!((d.svv - svv).length() < 1e-5 * scale2);
    }

    #[test]
    fn knot_insertion_leaves_the_surface_unchanged(s in random_surface(), ku in 0.01f64..0.99, kv in 0.01f64..0.99, times in 1usize..=2) {
        let refined = s.insert_knot_u(ku, times).expect("insert u").insert_knot_v(kv, 1).expect("insert v");
        prop_assert_eq!(refined.count_u(), s.count_u() + times);
        prop_assert_eq!(refined.count_v(), s.count_v() + 1);
        for a in 0..=8 {
            for b in 0..=8 {
                let (u, v) = (a as f64 / 8.0, b as f64 / 8.0);
                let before = s.derivatives(u, v, 1).expect("before");
                let after = refined.derivatives(u, v, 1).expect("after");
                prop_assert!((before.point - after.point).length() < 1e-12);
                prop_assert!((before.su - after.su).length() < 1e-9 * (1.0 + before.su.length()));
            }
        }
    }

    #[test]
    fn frames_are_consistent(s in random_surface(), u in 0.0f64..=1.0, v in 0.0f64..=1.0) {
        let f = SurfaceFrame::new(&s, u, v).expect("frame");
        prop_assert!(f.k1 >= f.k2);
        let scale = 1.0 + f.k1.abs().max(f.k2.abs());
        prop_assert!((f.gaussian - f.k1 * f.k2).abs() < 1e-8 * scale * scale);
        prop_assert!((f.mean - 0.5 * (f.k1 + f.k2)).abs() < 1e-9 * scale);
        if f.regular {
            prop_assert!((f.normal.length() - 1.0).abs() < 1e-12);
            prop_assert!((f.d1.length() - 1.0).abs() < 1e-12 && f.d1.dot(f.normal).abs() < 1e-9);
            prop_assert!((f.normal_curvature(f.d1) - f.k1).abs() < 1e-9 * scale);
        }
    }
}

#[test]
fn degree_elevation_keeps_surfaces() {
    let torus = shapes::torus(DVec3::ZERO, 3.0, 1.0).expect("torus");
    let up = torus.elevate_degree_u().expect("u").elevate_degree_v().expect("v");
    assert_eq!((up.knots_u().degree(), up.knots_v().degree()), (3, 3));
    for a in 0..=12 {
        for b in 0..=12 {
            let (u, v) = (a as f64 / 12.0, b as f64 / 12.0);
            let (f, g) =
                (SurfaceFrame::new(&torus, u, v).expect("frame"), SurfaceFrame::new(&up, u, v).expect("frame"));
            assert!((f.point() - g.point()).length() < 1e-13);
            assert!((f.gaussian - g.gaussian).abs() < 1e-10 && (f.mean - g.mean).abs() < 1e-10);
        }
    }
}

#[test]
fn point_and_tangents_match_derivatives() {
    let s = shapes::torus(DVec3::ZERO, 2.0, 0.5).expect("torus");
    for (u, v) in [(0.0, 0.0), (0.3, 0.7), (1.0, 0.25)] {
        let [p, su, sv] = s.point_and_tangents(u, v).expect("tangents");
        let d = s.derivatives(u, v, 1).expect("derivatives");
        assert_eq!((p, su, sv), (d.point, d.su, d.sv));
    }
    assert!(s.point_and_tangents(f64::NAN, 0.0).is_err());
}
