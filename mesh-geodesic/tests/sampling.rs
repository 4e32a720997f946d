//! Farthest-point sampling and geodesic Voronoi regions: consistency with
//! fresh multi-source distances, covering radii, components, errors.

mod common;

use mesh_geodesic::{
    dijkstra, farthest_point_sampling, fmm_distance, geodesic_voronoi, FmmOptions, GeodesicError, SamplingMetric,
    SamplingOptions,
};
use mesh_kernel::glam::DVec3;
use mesh_kernel::{shapes, TriMesh, VertexId};

fn metric(metric: SamplingMetric) -> SamplingOptions {
    SamplingOptions { metric, ..Default::default() }
}

#[test]
fn voronoi_regions_hold_the_nearest_seed() {
    let mesh = shapes::torus(2.0, 0.6, 48, 16).unwrap();
    let seeds = [VertexId(0), VertexId(250), VertexId(600)];
    let h = mesh_kernel::geometry::mean_edge_length(&mesh);
    let single: Vec<Vec<f64>> =
        seeds.iter().map(|s| fmm_distance(&mesh, &[*s], &FmmOptions::default()).unwrap()).collect();
    let cells = geodesic_voronoi(&mesh, &seeds, &SamplingOptions::default()).unwrap();
    for v in 0..mesh.vertex_count() {
        let own = single[cells.region[v] as usize][v];
        let nearest = single.iter().map(|d| d[v]).fold(f64::INFINITY, f64::min);
        assert!(own <= nearest + 0.25 * h, "{v}: {own} vs {nearest}");
    }
    // With graph distances the labels are exact.
    let cells = geodesic_voronoi(&mesh, &seeds, &metric(SamplingMetric::Dijkstra)).unwrap();
    let single: Vec<Vec<f64>> =
        seeds.iter().map(|s| dijkstra(&mesh, &[*s], &Default::default()).unwrap().distance).collect();
    for v in 0..mesh.vertex_count() {
        let nearest = single.iter().map(|d| d[v]).fold(f64::INFINITY, f64::min);
        assert_eq!(single[cells.region[v] as usize][v], nearest);
        assert_eq!(cells.distance[v], nearest);
    }
}

#[test]
fn incremental_sampling_matches_a_fresh_computation() {
    let mesh = shapes::disk(12, 4).unwrap();
    let fps = farthest_point_sampling(&mesh, 15, &metric(SamplingMetric::Dijkstra)).unwrap();
    let fresh = dijkstra(&mesh, &fps.seeds, &Default::default()).unwrap();
    assert_eq!(fps.distance, fresh.distance);
    // Each vertex's region is a seed at its distance (labels set by the
    // incremental searches).
    let single: Vec<Vec<f64>> =
        fps.seeds.iter().map(|s| dijkstra(&mesh, &[*s], &Default::default()).unwrap().distance).collect();
    for v in 0..mesh.vertex_count() {
        assert_eq!(single[fps.region[v] as usize][v], fps.distance[v], "vertex {v}");
    }
    // Each sample was the farthest point: its distance to the earlier ones
    // is the previous covering radius.
    for i in 1..fps.seeds.len() {
        let earlier = dijkstra(&mesh, &fps.seeds[..i], &Default::default()).unwrap();
        assert_eq!(earlier.distance[fps.seeds[i].idx()], fps.radii[i - 1]);
        assert_eq!(fps.radii[i - 1], earlier.distance.iter().cloned().fold(0.0, f64::max));
    }
    // Fast marching: the returned field is the multi-source march of the
    // samples; the radii of the (pruned) incremental fronts are close to it.
    let fps = farthest_point_sampling(&mesh, 15, &SamplingOptions::default()).unwrap();
    let fresh = fmm_distance(&mesh, &fps.seeds, &FmmOptions::default()).unwrap();
    assert_eq!(fps.distance, fresh);
    let h = mesh_kernel::geometry::mean_edge_length(&mesh);
    let last = fresh.iter().cloned().fold(0.0, f64::max);
    assert!((fps.radii[14] - last).abs() < 0.5 * h, "{} vs {last}", fps.radii[14]);
}

#[test]
fn sphere_samples_spread_evenly() {
    let mesh = shapes::icosphere(4).unwrap();
    let fps = farthest_point_sampling(&mesh, 12, &SamplingOptions::default()).unwrap();
    assert_eq!(fps.seeds[0], VertexId(0));
    let mut sorted = fps.seeds.clone();
    sorted.sort();
    sorted.dedup();
    assert_eq!(sorted.len(), 12);
    assert!(fps.radii.windows(2).all(|w| w[1] <= w[0] + 1e-12));
    // Twelve points cover the unit sphere at best within 0.6524 rad (the
    // icosahedron); farthest-point sampling is within a factor 2.
    let radius = *fps.radii.last().unwrap();
    assert!(radius > 0.6524 - 1e-3 && radius < 2.0 * 0.6524, "{radius}");
    // The first antipodal pick.
    let truth = common::sphere_truth(&mesh, VertexId(0));
    assert!((truth[fps.seeds[1].idx()] - std::f64::consts::PI).abs() < 0.05);
}

#[test]
fn components_and_isolated_vertices() {
    let mesh = common::union(&shapes::icosphere(1).unwrap(), &shapes::disk(2, 1).unwrap(), 2);
    let n = mesh.vertex_count();
    let fps = farthest_point_sampling(&mesh, 3, &SamplingOptions::default()).unwrap();
    assert!(fps.seeds.iter().any(|s| s.idx() < 42) && fps.seeds.iter().any(|s| s.idx() >= 42 && s.idx() < n - 2));
    assert!(fps.seeds.iter().all(|s| s.idx() < n - 2), "isolated vertices are never samples");
    assert!(fps.distance[..n - 2].iter().all(|d| d.is_finite()));
    assert_eq!(fps.radii[0], f64::INFINITY);
    // One sample on the edge graph (a search that keeps no labels): region
    // 0 exactly where the sample's component is reached.
    let one = farthest_point_sampling(&mesh, 1, &metric(SamplingMetric::Dijkstra)).unwrap();
    let tree = dijkstra(&mesh, &one.seeds, &Default::default()).unwrap();
    assert_eq!(one.distance, tree.distance);
    for v in 0..n {
        assert_eq!(one.region[v], if one.distance[v].is_finite() { 0 } else { u32::MAX }, "vertex {v}");
    }
    assert!(one.region.contains(&u32::MAX) && one.region.contains(&0));
    // Asking for more samples than vertices: all of them, radius 0.
    let small = shapes::icosphere(0).unwrap();
    let fps = farthest_point_sampling(&small, 100, &metric(SamplingMetric::Dijkstra)).unwrap();
    assert_eq!(fps.seeds.len(), 12);
    assert_eq!(*fps.radii.last().unwrap(), 0.0);
}

#[test]
fn bad_input_is_an_error() {
    let mesh = shapes::icosphere(1).unwrap();
    let opts = SamplingOptions::default();
    assert!(matches!(farthest_point_sampling(&mesh, 0, &opts), Err(GeodesicError::InvalidOption { .. })));
    let far = SamplingOptions { start: Some(VertexId(999)), ..Default::default() };
    assert!(matches!(farthest_point_sampling(&mesh, 3, &far), Err(GeodesicError::SourceOutOfRange { .. })));
    assert_eq!(geodesic_voronoi(&mesh, &[], &opts), Err(GeodesicError::NoSources));
    let empty = TriMesh::new(vec![DVec3::ZERO], vec![]).unwrap();
    assert!(farthest_point_sampling(&empty, 3, &opts).is_err());
}
