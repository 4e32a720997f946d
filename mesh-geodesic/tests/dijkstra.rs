//! Dijkstra on the edge graph against an independent Bellman-Ford, plus
//! paths, labels, components and error cases.

mod common;

use mesh_geodesic::{dijkstra, DijkstraOptions, GeodesicError};
use mesh_kernel::{shapes, TriMesh, VertexId};

/// Bellman-Ford over the edge list: the reference shortest edge paths.
fn bellman_ford(mesh: &TriMesh, sources: &[VertexId]) -> Vec<f64> {
    let p = mesh.positions();
    let mut d = vec![f64::INFINITY; mesh.vertex_count()];
    for s in sources {
        d[s.idx()] = 0.0;
    }
    let edges = mesh.connectivity().edges();
    loop {
        let mut changed = false;
        for [a, b] in edges {
            let w = p[a.idx()].distance(p[b.idx()]);
            for (x, y) in [(a, b), (b, a)] {
                if d[x.idx()] + w < d[y.idx()] {
                    d[y.idx()] = d[x.idx()] + w;
                    changed = true;
                }
            }
        }
        if !changed {
            return d;
        }
    }
}

#[test]
fn matches_bellman_ford_on_irregular_meshes() {
    for mesh in [shapes::disk(8, 3).unwrap(), shapes::torus(2.0, 0.7, 20, 9).unwrap(), shapes::icosphere(2).unwrap()] {
        let sources = [VertexId(0), VertexId(17)];
        let tree = dijkstra(&mesh, &sources, &DijkstraOptions::default()).unwrap();
        let reference = bellman_ford(&mesh, &sources);
        for (a, b) in tree.distance.iter().zip(&reference) {
            assert!((a - b).abs() < 1e-12, "{a} vs {b}");
        }
    }
}

#[test]
fn paths_follow_edges_and_add_up() {
    let mesh = shapes::torus(2.0, 0.5, 24, 10).unwrap();
    let conn = mesh.connectivity();
    let tree = dijkstra(&mesh, &[VertexId(3), VertexId(100)], &DijkstraOptions::default()).unwrap();
    for v in mesh.vertex_ids() {
        let path = tree.edge_path(v).unwrap();
        let source = path[0];
        assert!(source == VertexId(3) || source == VertexId(100));
        assert_eq!(tree.source_index[v.idx()], if source == VertexId(3) { 0 } else { 1 });
        let mut length = 0.0;
        for w in path.windows(2) {
            assert!(conn.neighbors(w[0]).any(|n| n == w[1]), "{:?} is not an edge", w);
            length += mesh.position(w[0]).distance(mesh.position(w[1]));
        }
        assert!((length - tree.distance[v.idx()]).abs() < 1e-12);
    }
}

#[test]
fn upper_bound_of_sphere_geodesics() {
    // Edge paths are longer than the chord; their excess over the great
    // circle is the edge-graph bias (scipy's Dijkstra on level 5: 0.197).
    let mesh = shapes::icosphere(5).unwrap();
    let tree = dijkstra(&mesh, &[VertexId(0)], &DijkstraOptions::default()).unwrap();
    let truth = common::sphere_truth(&mesh, VertexId(0));
    let p0 = mesh.position(VertexId(0));
    let mut worst: f64 = 0.0;
    for ((d, t), p) in tree.distance.iter().zip(&truth).zip(mesh.positions()) {
        assert!(*d >= p.distance(p0) - 1e-12);
        worst = worst.max(d - t);
    }
    assert!(worst > 0.1 && worst < 0.2, "{worst}");
}

#[test]
fn unreachable_is_infinite_and_cutoff_applies() {
    let mesh = common::union(&shapes::icosphere(1).unwrap(), &shapes::disk(2, 1).unwrap(), 2);
    let n = mesh.vertex_count();
    let tree = dijkstra(&mesh, &[VertexId(0)], &DijkstraOptions::default()).unwrap();
    assert!(tree.distance[..42].iter().all(|d| d.is_finite()));
    assert!(tree.distance[42..].iter().all(|d| d.is_infinite()));
    assert_eq!(tree.edge_path(VertexId(50)), None);
    assert_eq!(tree.source_index[n - 1], u32::MAX);
    // A source on an isolated vertex reaches only itself.
    let tree = dijkstra(&mesh, &[VertexId(n as u32 - 1)], &DijkstraOptions::default()).unwrap();
    assert_eq!(tree.distance.iter().filter(|d| d.is_finite()).count(), 1);
    // Cut-off.
    let tree = dijkstra(&mesh, &[VertexId(0)], &DijkstraOptions { max_distance: 1.0 }).unwrap();
    assert!(tree.distance.iter().all(|d| d.is_infinite() || *d <= 1.0));
    assert!(tree.distance.iter().any(|d| d.is_infinite()));
}

#[test]
fn bad_input_is_an_error() {
    let mesh = shapes::icosphere(1).unwrap();
    let opts = DijkstraOptions::default();
    assert_eq!(dijkstra(&mesh, &[], &opts), Err(GeodesicError::NoSources));
    assert!(matches!(dijkstra(&mesh, &[VertexId(42)], &opts), Err(GeodesicError::SourceOutOfRange { .. })));
    let nan = DijkstraOptions { max_distance: f64::NAN };
    assert!(matches!(dijkstra(&mesh, &[VertexId(0)], &nan), Err(GeodesicError::InvalidOption { .. })));
}

#[test]
fn every_data_mesh_gives_finite_distances_within_components() {
    for (name, mesh) in common::data_meshes() {
        let tree = dijkstra(&mesh, &[VertexId(0)], &DijkstraOptions::default()).unwrap();
        let comp = &mesh.connectivity().components().vertex_component;
        for (v, d) in tree.distance.iter().enumerate() {
            assert_eq!(d.is_finite(), comp[v] == comp[0], "{name} vertex {v}");
        }
    }
}
