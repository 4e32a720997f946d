//! Dijkstra on the edge graph against an independent Bellman-Ford, plus
//! paths, labels, components and error cases.

mod common;

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use mesh_geodesic::{dijkstra, DijkstraGraph, DijkstraOptions, GeodesicError, ShortestPaths};
use mesh_kernel::glam::DVec3;
use mesh_kernel::random::SplitMix64;
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

/// The length of edge uw as the search must add it: the overflow-safe norm,
/// which equals the plain length at ordinary scales.
fn edge_length(mesh: &TriMesh, u: VertexId, w: VertexId) -> f64 {
    mesh_kernel::geometry::norm(mesh.position(w) - mesh.position(u))
}

/// `mesh` with its first face turned over (an inconsistently oriented
/// closed surface).
fn flip_first_face(mesh: &TriMesh) -> TriMesh {
    let mut faces = mesh.faces().to_vec();
    faces[0].swap(1, 2);
    TriMesh::new(mesh.positions().to_vec(), faces).unwrap()
}

/// A textbook Dijkstra (binary heap of ordered bit patterns, neighbours from
/// the face list) with a cut-off: the reference distances.
fn reference(mesh: &TriMesh, sources: &[VertexId], max_distance: f64) -> Vec<f64> {
    let mut adjacent = vec![Vec::new(); mesh.vertex_count()];
    for f in mesh.faces() {
        for k in 0..3 {
            let (a, b) = (VertexId(f[k]), VertexId(f[(k + 1) % 3]));
            adjacent[a.idx()].push(b);
            adjacent[b.idx()].push(a);
        }
    }
    let mut d = vec![f64::INFINITY; mesh.vertex_count()];
    let mut heap = BinaryHeap::new();
    for s in sources {
        d[s.idx()] = 0.0;
        heap.push(Reverse((0u64, s.0)));
    }
    while let Some(Reverse((bits, v))) = heap.pop() {
        let dv = f64::from_bits(bits);
        if dv > d[v as usize] {
            continue;
        }
        for &w in &adjacent[v as usize] {
            let nd = dv + edge_length(mesh, VertexId(v), w);
            if nd < d[w.idx()] {
                d[w.idx()] = nd;
                heap.push(Reverse((nd.to_bits(), w.0)));
            }
        }
    }
    d.iter().map(|&x| if x > max_distance { f64::INFINITY } else { x }).collect()
}

/// A random triangle soup: faces on random vertex triples (non-manifold
/// edges and vertices, duplicate faces, unreferenced vertices), with some
/// vertices on top of each other (zero-length edges).
fn random_soup(rng: &mut SplitMix64, vertices: usize, faces: usize) -> TriMesh {
    let mut positions: Vec<DVec3> =
        (0..vertices).map(|_| DVec3::new(rng.signed(), rng.signed(), rng.signed())).collect();
    for _ in 0..vertices / 10 {
        let (a, b) = (rng.below(vertices), rng.below(vertices));
        positions[a] = positions[b];
    }
    let mut tris = Vec::new();
    while tris.len() < faces {
        let t = [rng.below(vertices), rng.below(vertices), rng.below(vertices)].map(|v| v as u32);
        if t[0] != t[1] && t[1] != t[2] && t[0] != t[2] {
            tris.push(t);
            if rng.one_in(20) {
                tris.push(t); // a duplicate face
            }
        }
    }
    TriMesh::new(positions, tris).unwrap()
}

/// The tree is a shortest-path tree of these distances: every reached
/// non-source vertex hangs off a neighbour whose distance plus the edge is
/// its own, bit for bit, and shares its label; sources carry their label.
fn assert_tree(mesh: &TriMesh, sources: &[VertexId], tree: &ShortestPaths) {
    for v in mesh.vertex_ids() {
        let (d, p, label) = (tree.distance[v.idx()], tree.predecessor[v.idx()], tree.source_index[v.idx()]);
        if !d.is_finite() {
            assert!(!p.is_valid() && label == u32::MAX, "{v:?}");
        } else if !p.is_valid() {
            assert_eq!(d, 0.0);
            assert_eq!(sources.iter().position(|s| *s == v), Some(label as usize), "{v:?}");
        } else {
            let shares_a_face = |f: &[u32; 3]| f.contains(&v.0) && f.contains(&p.0);
            assert!(mesh.faces().iter().any(shares_a_face), "{p:?} is not a neighbour of {v:?}");
            assert_eq!(d, tree.distance[p.idx()] + edge_length(mesh, p, v), "{v:?}");
            assert_eq!(label, tree.source_index[p.idx()], "{v:?}");
        }
    }
}

#[test]
fn equals_a_reference_dijkstra_on_soups_shapes_and_components() {
    let mut rng = SplitMix64::new(15);
    let mut meshes = vec![
        shapes::icosphere(3).unwrap(),
        flip_first_face(&shapes::icosphere(2).unwrap()),
        shapes::disk(10, 4).unwrap(),
        common::union(&shapes::torus(2.0, 0.7, 16, 7).unwrap(), &shapes::disk(3, 2).unwrap(), 3),
    ];
    for size in [20, 200, 2000] {
        meshes.push(random_soup(&mut rng, size, size * 2));
        // Sparse soups fall apart into many components and isolated vertices.
        meshes.push(random_soup(&mut rng, size, size / 3 + 1));
    }
    for mesh in &meshes {
        let n = mesh.vertex_count();
        let graph = DijkstraGraph::new(mesh);
        for trial in 0..4 {
            let count = 1 + rng.below(4);
            let mut sources: Vec<VertexId> = (0..count).map(|_| VertexId::new(rng.below(n))).collect();
            if trial == 3 {
                sources.push(sources[0]); // a duplicate source
            }
            let full = reference(mesh, &sources, f64::INFINITY);
            let reached: Vec<f64> = full.iter().copied().filter(|d| d.is_finite()).collect();
            let max_distance = if trial % 2 == 1 { reached[reached.len() / 2] } else { f64::INFINITY };
            let opts = DijkstraOptions { max_distance };
            let expected = reference(mesh, &sources, max_distance);
            for tree in [dijkstra(mesh, &sources, &opts).unwrap(), graph.shortest_paths(&sources, &opts).unwrap()] {
                let bits = |d: &[f64]| d.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(&tree.distance), bits(&expected), "{n} vertices, sources {sources:?}");
                assert_tree(mesh, &sources, &tree);
            }
        }
    }
}

#[test]
fn extreme_units_keep_distances_in_proportion() {
    // At 1e-200 squared lengths underflow: the robust norm must carry them.
    let mesh = shapes::icosphere(2).unwrap();
    let tiny = TriMesh::new(mesh.positions().iter().map(|p| *p * 1e-200).collect(), mesh.faces().to_vec()).unwrap();
    let sources = [VertexId(0), VertexId(9)];
    let opts = DijkstraOptions::default();
    let unit = dijkstra(&mesh, &sources, &opts).unwrap();
    let expected = reference(&tiny, &sources, f64::INFINITY);
    for tree in
        [dijkstra(&tiny, &sources, &opts).unwrap(), DijkstraGraph::new(&tiny).shortest_paths(&sources, &opts).unwrap()]
    {
        assert_eq!(tree.distance, expected);
        for (a, b) in tree.distance.iter().zip(&unit.distance) {
            assert!((a * 1e200 - b).abs() <= 1e-12 * b.max(1.0), "{a} vs {b}");
        }
    }
}

#[test]
fn prepared_graph_rejects_what_dijkstra_rejects() {
    let mesh = shapes::icosphere(1).unwrap();
    let graph = DijkstraGraph::new(&mesh);
    assert_eq!(graph.vertex_count(), 42);
    let opts = DijkstraOptions::default();
    assert_eq!(graph.shortest_paths(&[], &opts), Err(GeodesicError::NoSources));
    assert!(matches!(graph.shortest_paths(&[VertexId(42)], &opts), Err(GeodesicError::SourceOutOfRange { .. })));
    let negative = DijkstraOptions { max_distance: -1.0 };
    assert!(matches!(graph.shortest_paths(&[VertexId(0)], &negative), Err(GeodesicError::InvalidOption { .. })));
}
