//! Dijkstra on the real scans against a plain one: mesh-geodesic's
//! `dijkstra` (graph built in the call) and a `DijkstraGraph` query, from a
//! vertex of the largest component (by faces), against a binary-heap Dijkstra over
//! neighbour lists read straight from the faces (no connectivity, no edge
//! graph of ours), on the full dragon scan (151 components, zero-area
//! faces), the dirty dragon scan (non-manifold edges, duplicate faces) and
//! the bunny Loop-subdivided four times. Both settle vertices in the order
//! of their distances and round each sum once, so the distances must agree
//! to the bit, unreached vertices included; and every reached vertex but
//! the source must be its predecessor's distance plus the edge between
//! them, rounded once.

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use mesh_geodesic::{dijkstra, DijkstraGraph, DijkstraOptions, ShortestPaths};
use mesh_kernel::{TriMesh, VertexId};

use super::{ScaleMeshes, Validator};

/// Runs the Dijkstra checks.
pub fn run(v: &mut Validator, meshes: &ScaleMeshes) {
    for (name, mesh) in [
        ("dragon_vrip.ply", meshes.dragon_full()),
        ("npm_dragon_res3.ply", meshes.dragon_res3()),
        ("npm_bunny.obj Loop x4", meshes.bunny_loop4()),
    ] {
        let m = match mesh {
            Ok(m) => m,
            Err(e) => {
                v.skip(format!("{name} Dijkstra against a plain one"), e.to_owned());
                continue;
            }
        };
        let source = largest_component_vertex(m);
        let rings = face_rings(m);
        let reference = plain_dijkstra(m, &rings, source);
        let options = DijkstraOptions::default();
        for (kind, paths) in [
            ("one-off", dijkstra(m, &[source], &options)),
            ("prepared graph", DijkstraGraph::new(m).shortest_paths(&[source], &options)),
        ] {
            match paths {
                Ok(paths) => {
                    let differ =
                        paths.distance.iter().zip(&reference).filter(|(a, b)| a.to_bits() != b.to_bits()).count();
                    let reached = reference.iter().filter(|d| d.is_finite()).count();
                    v.equal(
                        format!("{name} Dijkstra {kind} from vertex {} ({reached} reached): distances not equal to a plain Dijkstra's bits", source.0),
                        differ as i64,
                        0,
                    );
                    v.equal(
                        format!("{name} Dijkstra {kind}: tree edges that do not add up"),
                        broken_tree_edges(m, &rings, &paths, source) as i64,
                        0,
                    );
                }
                Err(e) => v.error(format!("{name} Dijkstra {kind}"), e),
            }
        }
    }
}

/// The first vertex of the component with the most faces
/// ([`mesh_kernel::Components::largest`]); vertex 0 on a mesh without faces.
fn largest_component_vertex(m: &TriMesh) -> VertexId {
    let components = m.connectivity().components();
    let largest = components.largest().map_or(u32::MAX, |c| c as u32);
    VertexId::new(components.vertex_component.iter().position(|&c| c == largest).unwrap_or(0))
}

/// The other corners of each vertex's faces (some listed more than once).
fn face_rings(m: &TriMesh) -> Vec<Vec<u32>> {
    let mut rings: Vec<Vec<u32>> = vec![Vec::new(); m.vertex_count()];
    for face in m.faces() {
        for k in 0..3 {
            rings[face[k] as usize].extend([face[(k + 1) % 3], face[(k + 2) % 3]]);
        }
    }
    rings
}

/// Single-source Dijkstra with a binary heap and lazy deletion over
/// `rings`.
fn plain_dijkstra(m: &TriMesh, rings: &[Vec<u32>], source: VertexId) -> Vec<f64> {
    let p = m.positions();
    let mut distance = vec![f64::INFINITY; m.vertex_count()];
    distance[source.idx()] = 0.0;
    let mut heap = BinaryHeap::from([Reverse((0f64.to_bits(), source.0))]);
    while let Some(Reverse((bits, u))) = heap.pop() {
        let d = f64::from_bits(bits);
        if d > distance[u as usize] {
            continue;
        }
        for &w in &rings[u as usize] {
            let nd = d + (p[w as usize] - p[u as usize]).length();
            if nd < distance[w as usize] {
                distance[w as usize] = nd;
                // Non-negative distances order like their bit patterns.
                heap.push(Reverse((nd.to_bits(), w)));
            }
        }
    }
    distance
}

/// Reached vertices other than the source whose distance is not their
/// predecessor's plus the edge between them, or whose predecessor is not a
/// neighbour in `rings`; plus unreached vertices with a predecessor.
fn broken_tree_edges(m: &TriMesh, rings: &[Vec<u32>], paths: &ShortestPaths, source: VertexId) -> usize {
    let p = m.positions();
    (0..m.vertex_count())
        .filter(|&v| {
            let (d, u) = (paths.distance[v], paths.predecessor[v]);
            if v == source.idx() || !d.is_finite() {
                return u.is_valid();
            }
            !u.is_valid()
                || !rings[v].contains(&u.0)
                || (paths.distance[u.idx()] + (p[v] - p[u.idx()]).length()).to_bits() != d.to_bits()
        })
        .count()
}
