//! Integral curvature over neighbourhoods, shape index and curvedness.

mod common;

use std::f64::consts::PI;

use mesh_curvature::{
    curvature_tensor, curvedness, gaussian_curvature, integral_curvature, shape_index, CurvatureError, GaussianOptions,
    IntegralOptions, Neighborhood, TensorOptions,
};
use mesh_kernel::shapes;

#[test]
fn a_ball_covering_everything_integrates_the_whole_surface() {
    // Gauss-Bonnet over the whole closed surface: 4 pi for a sphere, 0 for a
    // torus; total mean curvature of the unit sphere: 4 pi (H = 1, area 4 pi).
    let sphere = shapes::icosphere(4).unwrap();
    let ic = integral_curvature(&sphere, &IntegralOptions { neighborhood: Neighborhood::Ball(3.0) }).unwrap();
    for i in 0..sphere.vertex_count() {
        assert_eq!(ic.size[i] as usize, sphere.vertex_count());
        assert!((ic.gaussian[i] - 4.0 * PI).abs() < 1e-10);
        // H = 1 integrated over the inscribed polyhedron's area.
        assert!((ic.mean[i] / ic.area[i] - 1.0).abs() < 1e-5);
        assert!((ic.area[i] - mesh_kernel::geometry::surface_area(&sphere)).abs() < 1e-10);
    }
    let torus = shapes::torus(2.0, 0.5, 48, 12).unwrap();
    let ic = integral_curvature(&torus, &IntegralOptions { neighborhood: Neighborhood::Rings(100) }).unwrap();
    assert!(ic.gaussian.iter().all(|k| k.abs() < 1e-10));
}

#[test]
fn local_averages_match_the_analytic_curvature() {
    // On the unit sphere, the average K and H over any k-ring is 1; on the
    // torus, the average over a small ring is close to the pointwise value.
    let sphere = shapes::icosphere(5).unwrap();
    for k in [1, 2, 4] {
        let ic = integral_curvature(&sphere, &IntegralOptions { neighborhood: Neighborhood::Rings(k) }).unwrap();
        let worst_k = ic.mean_gaussian().iter().map(|x| (x - 1.0).abs()).fold(0.0, f64::max);
        let worst_h = ic.mean_mean().iter().map(|x| (x - 1.0).abs()).fold(0.0, f64::max);
        assert!(worst_k < 5e-4 && worst_h < 1e-4, "{k}: {worst_k} {worst_h}");
    }
    // The 1-ring average smooths K over a region of size h: O(h^2) off.
    let worst = |nu, nv| {
        let (torus, truth) = common::torus(nu, nv);
        let ic = integral_curvature(&torus, &IntegralOptions { neighborhood: Neighborhood::Rings(1) }).unwrap();
        let avg = ic.mean_gaussian();
        (0..torus.vertex_count()).map(|i| (avg[i] - truth.k1[i] * truth.k2[i]).abs()).fold(0.0, f64::max)
    };
    let (coarse, fine) = (worst(128, 32), worst(256, 64));
    assert!(common::order(coarse, fine, 2.0) > 1.8 && fine < 1e-2, "{coarse} {fine}");
    let (torus, _) = common::torus(256, 64);
    let ic = integral_curvature(&torus, &IntegralOptions { neighborhood: Neighborhood::Rings(1) }).unwrap();
    // Larger neighbourhoods integrate more: monotone sizes and areas.
    let wide = integral_curvature(&torus, &IntegralOptions { neighborhood: Neighborhood::Rings(3) }).unwrap();
    assert!((0..torus.vertex_count()).all(|i| wide.size[i] > ic.size[i] && wide.area[i] > ic.area[i]));
}

#[test]
fn integral_gaussian_sums_angle_defects() {
    let (m, _) = common::ellipsoid(3, [1.0, 0.6, 0.4]);
    let k = gaussian_curvature(&m, &GaussianOptions::default()).unwrap();
    let ic = integral_curvature(&m, &IntegralOptions { neighborhood: Neighborhood::Rings(1) }).unwrap();
    let conn = m.connectivity();
    for v in m.vertex_ids() {
        let expected: f64 = k.integrated[v.idx()] + conn.neighbors(v).map(|w| k.integrated[w.idx()]).sum::<f64>();
        assert!((ic.gaussian[v.idx()] - expected).abs() < 1e-12);
    }
}

#[test]
fn shape_index_and_curvedness_of_known_shapes() {
    assert!((shape_index(1.0, 1.0) - 1.0).abs() < 1e-15); // cap
    assert!((shape_index(-1.0, -1.0) + 1.0).abs() < 1e-15); // cup
    assert!((shape_index(1.0, 0.0) - 0.5).abs() < 1e-15); // ridge
    assert!((shape_index(0.0, -1.0) + 0.5).abs() < 1e-15); // valley
    assert!(shape_index(1.0, -1.0).abs() < 1e-15); // symmetric saddle
    assert_eq!(shape_index(0.0, 0.0), 0.0); // plane: undefined, 0
    assert_eq!(shape_index(0.3, 2.0), shape_index(2.0, 0.3)); // order does not matter
    assert!((curvedness(3.0, 4.0) - 12.5f64.sqrt()).abs() < 1e-15);
    // Scale: shape index is invariant, curvedness scales as 1 / size.
    assert!((shape_index(2.0, 0.7) - shape_index(20.0, 7.0)).abs() < 1e-15);

    let t = curvature_tensor(&shapes::icosphere(4).unwrap(), &TensorOptions::default()).unwrap();
    assert!(t.shape_index().iter().all(|s| (s - 1.0).abs() < 1e-5));
    assert!(t.curvedness().iter().all(|c| (c - 1.0).abs() < 1e-3));
    let (cyl, truth) = common::cylinder(64, 16, 2);
    let t = curvature_tensor(&cyl, &TensorOptions::default()).unwrap();
    let si = t.shape_index();
    for i in 0..cyl.vertex_count() {
        if truth.check[i] {
            assert!((si[i] - 0.5).abs() < 1e-3, "{}", si[i]);
        }
    }
    // Torus: caps outside (both curvatures positive), saddles inside.
    let (torus, truth) = common::torus(128, 32);
    let si = curvature_tensor(&torus, &TensorOptions::default()).unwrap().shape_index();
    for i in 0..torus.vertex_count() {
        let exact = shape_index(truth.k1[i], truth.k2[i]);
        assert!((si[i] - exact).abs() < 1e-2, "{} vs {exact}", si[i]);
        assert!(si[i] > 0.0 || truth.k2[i] < 0.0);
    }
}

#[test]
fn invalid_neighbourhoods_are_errors() {
    let m = shapes::icosphere(1).unwrap();
    for nbh in [Neighborhood::Rings(0), Neighborhood::Ball(0.0), Neighborhood::Ball(f64::NAN)] {
        assert!(matches!(
            integral_curvature(&m, &IntegralOptions { neighborhood: nbh }),
            Err(CurvatureError::InvalidOption { .. })
        ));
    }
}

#[test]
fn data_meshes_are_finite() {
    for (name, m) in common::data_meshes() {
        let ic = integral_curvature(&m, &IntegralOptions { neighborhood: Neighborhood::Rings(2) }).unwrap();
        for v in [&ic.gaussian, &ic.mean, &ic.area, &ic.mean_gaussian(), &ic.mean_mean()] {
            assert!(v.iter().all(|x| x.is_finite()), "{name}");
        }
    }
}
