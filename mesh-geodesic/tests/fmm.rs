//! Fast Marching against analytic ground truth: great circles on the unit
//! sphere, Euclidean distance on flat disks and grids; convergence under
//! refinement, obtuse splitting, weights, components, degenerate input.

mod common;

use std::f64::consts::PI;

use mesh_geodesic::{fmm_distance, FastMarching, FmmOptions, FmmUpdate, GeodesicError};
use mesh_kernel::{shapes, VertexId};

fn opts(update: FmmUpdate) -> FmmOptions {
    FmmOptions { update, ..Default::default() }
}

fn sphere_errors(level: u32, options: &FmmOptions) -> (f64, f64) {
    let mesh = shapes::icosphere(level).unwrap();
    let d = fmm_distance(&mesh, &[VertexId(0)], options).unwrap();
    common::errors(&d, &common::sphere_truth(&mesh, VertexId(0)))
}

fn disk_errors(rings: usize, options: &FmmOptions) -> (f64, f64) {
    let mesh = shapes::disk(rings, 7).unwrap();
    let d = fmm_distance(&mesh, &[VertexId(0)], options).unwrap();
    let truth: Vec<f64> = mesh.positions().iter().map(|p| p.length()).collect();
    common::errors(&d, &truth)
}

#[test]
fn sphere_level_5_meets_the_target() {
    // Target 0.005 pi; exact polyhedral geodesics (gdist) reach 5e-4 here.
    let (max, mean) = sphere_errors(5, &FmmOptions::default());
    println!("icosphere 5, curved front: max {max:.2e} mean {mean:.2e}");
    assert!(max <= 0.005 * PI);
    assert!(max < 5e-4, "{max}");
}

#[test]
fn sphere_errors_fall_under_refinement() {
    for (update, min_order) in
        [(FmmUpdate::CurvedFront, 1.5), (FmmUpdate::PointSource, 0.75), (FmmUpdate::PlaneWave, 0.5)]
    {
        let errors: Vec<f64> = (3..=6).map(|l| sphere_errors(l, &opts(update)).0).collect();
        for w in errors.windows(2) {
            let order = common::order(w[0], w[1]);
            println!("{update:?}: {:.2e} -> {:.2e}, order {order:.2}", w[0], w[1]);
            assert!(order > min_order, "{update:?}: {errors:?}");
        }
    }
}

#[test]
fn flat_disk_error_is_first_order() {
    // Irregular (jittered, partly obtuse) triangles; truth |x|.
    for update in [FmmUpdate::CurvedFront, FmmUpdate::PointSource, FmmUpdate::PlaneWave] {
        let errors: Vec<f64> = [10, 20, 40, 80].iter().map(|&r| disk_errors(r, &opts(update)).0).collect();
        for w in errors.windows(2) {
            let order = common::order(w[0], w[1]);
            println!("{update:?} disk: {:.2e} -> {:.2e}, order {order:.2}", w[0], w[1]);
            assert!(order > 0.7, "{update:?}: {errors:?}");
        }
    }
    // The circular fronts are exact up to the obtuse splits' approximations.
    assert!(disk_errors(40, &FmmOptions::default()).0 < 1e-4);
}

#[test]
fn splitting_obtuse_corners_restores_accuracy() {
    // A sheared grid: every cell has two corners of 95 degrees.
    let mut mesh = shapes::grid(1.0, 1.0, 24, 24).unwrap();
    mesh.positions_mut().iter_mut().for_each(|p| p.x += 0.09 * p.y);
    let source = VertexId(25 * 12 + 12);
    let p0 = mesh.position(source);
    let truth: Vec<f64> = mesh.positions().iter().map(|p| p.distance(p0)).collect();
    for update in [FmmUpdate::PlaneWave, FmmUpdate::CurvedFront] {
        let split = FastMarching::new(&mesh, &opts(update)).unwrap();
        assert_eq!(split.stats().split_corners, split.stats().obtuse_corners);
        assert!(split.stats().obtuse_corners > 1000);
        let no_split = FmmOptions { split_obtuse: false, ..opts(update) };
        let with = common::errors(&split.distance(&[source]).unwrap(), &truth).0;
        let without = common::errors(&fmm_distance(&mesh, &[source], &no_split).unwrap(), &truth).0;
        println!("{update:?}: split {with:.2e}, unsplit {without:.2e}");
        assert!(with < without || with < 1e-12, "{update:?}: {with} vs {without}");
    }
}

#[test]
fn multiple_sources_give_the_nearest() {
    let mesh = shapes::icosphere(4).unwrap();
    let fmm = FastMarching::new(&mesh, &FmmOptions::default()).unwrap();
    let (a, b) = (VertexId(0), VertexId(7));
    let (da, db) = (fmm.distance(&[a]).unwrap(), fmm.distance(&[b]).unwrap());
    let (both, labels) = fmm.distance_and_labels(&[a, b]).unwrap();
    let h = mesh_kernel::geometry::mean_edge_length(&mesh);
    for v in 0..mesh.vertex_count() {
        let nearest = da[v].min(db[v]);
        // Where the fronts collide the triangle updates mix both (the usual
        // smearing of the shock): a little below the smaller distance.
        assert!(both[v] <= nearest + 1e-3 * h && both[v] > nearest - 0.25 * h, "{v}: {} vs {nearest}", both[v]);
        // Labels agree with the nearer source away from the bisector.
        if (da[v] - db[v]).abs() > h {
            assert_eq!(labels[v], if da[v] < db[v] { 0 } else { 1 });
        }
    }
}

#[test]
fn weights_scale_the_distance() {
    let mesh = shapes::disk(6, 2).unwrap();
    let base = fmm_distance(&mesh, &[VertexId(0)], &FmmOptions::default()).unwrap();
    // Exactly for the plane wave; up to rounding-driven choices between
    // equally good stencils for the curved front.
    for (update, tolerance) in [(FmmUpdate::PlaneWave, 1e-12), (FmmUpdate::CurvedFront, 1e-3)] {
        let weights = Some(vec![2.5; mesh.vertex_count()]);
        let d = fmm_distance(&mesh, &[VertexId(0)], &FmmOptions { weights, ..opts(update) }).unwrap();
        let plain = fmm_distance(&mesh, &[VertexId(0)], &opts(update)).unwrap();
        for (w, p) in d.iter().zip(&plain) {
            assert!((w - 2.5 * p).abs() <= tolerance * w, "{update:?}: {w} vs {}", 2.5 * p);
        }
    }
    // A slow half (P = 3 for x > 0) makes those vertices farther.
    let weights: Vec<f64> = mesh.positions().iter().map(|p| if p.x > 0.0 { 3.0 } else { 1.0 }).collect();
    let opts = FmmOptions { weights: Some(weights), ..opts(FmmUpdate::PlaneWave) };
    let d = fmm_distance(&mesh, &[VertexId(0)], &opts).unwrap();
    for (v, p) in mesh.positions().iter().enumerate() {
        if p.x > 0.2 {
            assert!(d[v] > 2.0 * base[v], "{v}");
        }
    }
}

#[test]
fn other_components_are_infinite_never_zero() {
    let mesh = common::union(&shapes::icosphere(2).unwrap(), &shapes::disk(3, 1).unwrap(), 3);
    let n = mesh.vertex_count();
    let d = fmm_distance(&mesh, &[VertexId(0)], &FmmOptions::default()).unwrap();
    assert!(d[..162].iter().all(|d| d.is_finite()));
    assert!(d[162..].iter().all(|d| *d == f64::INFINITY));
    // A source on an isolated vertex reaches nothing else.
    let d = fmm_distance(&mesh, &[VertexId(n as u32 - 1)], &FmmOptions::default()).unwrap();
    assert_eq!(d[n - 1], 0.0);
    assert!(d[..n - 1].iter().all(|d| d.is_infinite()));
    // Sources in both components.
    let d = fmm_distance(&mesh, &[VertexId(0), VertexId(170)], &FmmOptions::default()).unwrap();
    assert!(d[..n - 3].iter().all(|d| d.is_finite()));
}

#[test]
fn cutoff_leaves_the_far_side_unreached() {
    let mesh = shapes::icosphere(3).unwrap();
    let opts = FmmOptions { max_distance: 1.0, ..Default::default() };
    let d = fmm_distance(&mesh, &[VertexId(0)], &opts).unwrap();
    let truth = common::sphere_truth(&mesh, VertexId(0));
    for (d, t) in d.iter().zip(&truth) {
        if *t < 0.9 {
            assert!(d.is_finite());
        }
        if *t > 1.1 {
            assert!(d.is_infinite());
        }
    }
}

#[test]
fn bad_input_is_an_error() {
    let mesh = shapes::icosphere(1).unwrap();
    let run = |sources: &[VertexId], o: FmmOptions| fmm_distance(&mesh, sources, &o);
    assert_eq!(run(&[], FmmOptions::default()), Err(GeodesicError::NoSources));
    assert!(matches!(run(&[VertexId(99)], FmmOptions::default()), Err(GeodesicError::SourceOutOfRange { .. })));
    let short = FmmOptions { weights: Some(vec![1.0; 3]), ..Default::default() };
    assert!(matches!(run(&[VertexId(0)], short), Err(GeodesicError::FieldLength { .. })));
    let negative = FmmOptions { weights: Some(vec![-1.0; 42]), ..Default::default() };
    assert!(matches!(run(&[VertexId(0)], negative), Err(GeodesicError::InvalidOption { .. })));
    let nan = FmmOptions { max_distance: f64::NAN, ..Default::default() };
    assert!(matches!(run(&[VertexId(0)], nan), Err(GeodesicError::InvalidOption { .. })));
}

#[test]
fn every_data_mesh_gives_finite_distances_within_components() {
    for (name, mesh) in common::data_meshes() {
        let comp = &mesh.connectivity().components().vertex_component;
        let h = mesh_kernel::geometry::mean_edge_length(&mesh);
        for update in [FmmUpdate::PlaneWave, FmmUpdate::CurvedFront] {
            let d = fmm_distance(&mesh, &[VertexId(0)], &opts(update)).unwrap();
            let dj = mesh_geodesic::dijkstra(&mesh, &[VertexId(0)], &Default::default()).unwrap().distance;
            for (v, x) in d.iter().enumerate() {
                assert_eq!(x.is_finite(), comp[v] == comp[0], "{name} {update:?} vertex {v}");
                // Never above the edge-graph distance; bounded below by the
                // straight line up to the method's error (the curved front's
                // smoothed curvature undershoots it by < 0.1 h on bumpy meshes).
                let chord = mesh.positions()[v].distance(mesh.positions()[0]);
                if x.is_finite() {
                    assert!(*x <= dj[v] + 1e-9, "{name} {update:?} {v}: {x} above {}", dj[v]);
                    assert!(*x >= chord - 0.1 * h, "{name} {update:?} {v}: {x} below {chord}");
                }
            }
        }
    }
}

#[test]
fn distances_are_the_single_source_fields_in_source_order() {
    let mesh = shapes::icosphere(4).unwrap();
    let fmm = FastMarching::new(&mesh, &FmmOptions::default()).unwrap();
    let sources = [VertexId(5), VertexId(0), VertexId(2000), VertexId(5)];
    let fields = fmm.distances(&sources).unwrap();
    assert_eq!(fields.len(), sources.len());
    for (field, &s) in fields.iter().zip(&sources) {
        let alone = fmm.distance(&[s]).unwrap();
        assert!(field.iter().zip(&alone).all(|(a, b)| a.to_bits() == b.to_bits()));
        assert_eq!(field[s.idx()], 0.0);
    }
    assert!(matches!(fmm.distances(&[]), Err(GeodesicError::NoSources)));
    assert!(matches!(fmm.distances(&[VertexId(5), VertexId(1 << 30)]), Err(GeodesicError::SourceOutOfRange { .. })));
}
