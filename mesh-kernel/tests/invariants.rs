//! Property tests on random meshes: perturbed and randomly re-triangulated
//! grids with holes, random triangle soups, subdivided shapes.

use mesh_kernel::clean::{self, CleanOptions};
use mesh_kernel::glam::DVec3;
use mesh_kernel::operators::{self, IntrinsicOptions, IntrinsicTriangulation};
use mesh_kernel::{shapes, Connectivity, FaceId, HalfedgeId, TriMesh, VertexId, VertexKind};
use proptest::prelude::*;

/// A planar grid of `nx` x `ny` cells, each split along a random diagonal,
/// vertices jittered inside their cell, some cells removed (holes).
fn random_grid() -> impl Strategy<Value = TriMesh> {
    (2usize..9, 2usize..9).prop_flat_map(|(nx, ny)| {
        let cells = nx * ny;
        (
            Just((nx, ny)),
            proptest::collection::vec(any::<bool>(), cells),
            proptest::collection::vec(0u8..10, cells),
            // At most 0.2 per coordinate: a vertex moves less than 0.29, so the
            // distance 0.71 from a corner to the opposite diagonal cannot close
            // (two vertices moving 0.3 apart could fold a triangle over, and
            // linear precision holds only for unfolded planar meshes).
            proptest::collection::vec((-0.2f64..0.2, -0.2f64..0.2), (nx + 1) * (ny + 1)),
        )
            .prop_map(|((nx, ny), diagonal, keep, jitter)| {
                let w = nx + 1;
                let positions = (0..(nx + 1) * (ny + 1))
                    .map(|i| {
                        let (x, y) = ((i % w) as f64, (i / w) as f64);
                        let (dx, dy) = jitter[i];
                        DVec3::new(x + dx, y + dy, 0.0)
                    })
                    .collect();
                let mut faces = Vec::new();
                for j in 0..ny {
                    for i in 0..nx {
                        let c = j * nx + i;
                        if keep[c] == 0 {
                            continue; // a hole
                        }
                        let (a, b, cc, d) = (
                            (j * w + i) as u32,
                            (j * w + i + 1) as u32,
                            ((j + 1) * w + i + 1) as u32,
                            ((j + 1) * w + i) as u32,
                        );
                        if diagonal[c] {
                            faces.extend([[a, b, cc], [a, cc, d]]);
                        } else {
                            faces.extend([[a, b, d], [b, cc, d]]);
                        }
                    }
                }
                TriMesh::new(positions, faces).expect("grid indices are valid")
            })
    })
}

fn check_halfedges(m: &TriMesh) {
    let c = m.connectivity();
    for h in 0..c.halfedge_count() {
        let h = HalfedgeId(h as u32);
        assert_eq!(h.next().next().next(), h);
        if let Some(t) = c.twin(h) {
            assert_eq!(c.twin(t), Some(h));
            assert_eq!(c.origin(t), c.dest(h));
            assert_eq!(c.edge(t), c.edge(h));
        }
        assert!(c.edge_halfedges(c.edge(h)).contains(&h));
        let [a, b] = c.edge_vertices(c.edge(h));
        let (o, d) = (c.origin(h), c.dest(h));
        assert!((a, b) == (o.min(d), o.max(d)));
    }
}

fn check_rings(m: &TriMesh) {
    let c = m.connectivity();
    for v in m.vertex_ids() {
        let ring: Vec<VertexId> = c.neighbors(v).collect();
        match c.vertex_kind(v) {
            VertexKind::Interior | VertexKind::Boundary => {
                // Consecutive neighbours share a face with v.
                let out = c.outgoing(v);
                for (k, h) in out.iter().enumerate() {
                    assert_eq!(c.dest(*h), ring[k]);
                    assert_eq!(c.opposite_vertex(*h), ring[(k + 1) % ring.len()]);
                }
                assert_eq!(c.valence(v), ring.len());
            }
            VertexKind::Isolated => assert!(ring.is_empty()),
            VertexKind::NonManifold => {}
        }
        // The valence counts each neighbour once, whatever the fan.
        let mut distinct = ring.clone();
        distinct.sort_unstable();
        distinct.dedup();
        assert_eq!(c.valence(v), distinct.len());
    }
}

fn check_laplacian(m: &TriMesh) {
    let l = operators::cotan_laplacian(m);
    let t = l.transpose_view().to_csr();
    for (i, row) in l.outer_iterator().enumerate() {
        let sum: f64 = row.iter().map(|(_, v)| v).sum();
        let scale: f64 = row.iter().map(|(_, v)| v.abs()).sum::<f64>().max(1.0);
        assert!(sum.abs() <= 1e-12 * scale, "row {i} sums to {sum}");
        for (j, v) in row.iter() {
            assert!(v.is_finite());
            assert_eq!(t.get(i, j), Some(v));
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn grids_are_planar_genus_zero(m in random_grid()) {
        check_halfedges(&m);
        check_rings(&m);
        check_laplacian(&m);
        let c = m.connectivity();
        let chi = c.euler_characteristic();
        prop_assert_eq!(chi, c.referenced_vertex_count() as i64 - c.edge_count() as i64 + m.face_count() as i64);
        if c.is_manifold() {
            // Planar: every component has genus 0, so chi = 2c - b.
            prop_assert_eq!(c.genus(), Some(0));
            let b = c.boundary_loops().unwrap().len() as i64;
            prop_assert_eq!(chi, 2 * c.components().count as i64 - b);
        } else {
            prop_assert!(!c.non_manifold_report().vertices.is_empty());
        }
    }

    #[test]
    fn linear_functions_are_harmonic_on_planar_grids(m in random_grid()) {
        let l = operators::cotan_laplacian(&m);
        let c = m.connectivity();
        let x: Vec<f64> = m.positions().iter().map(|p| 3.0 * p.x - p.y).collect();
        for (i, row) in l.outer_iterator().enumerate() {
            if c.vertex_kind(VertexId::new(i)) != VertexKind::Interior {
                continue;
            }
            let lx: f64 = row.iter().map(|(j, w)| w * x[j]).sum();
            prop_assert!(lx.abs() < 1e-9, "vertex {} {}", i, lx);
        }
    }

    #[test]
    fn intrinsic_delaunay_weights_are_nonnegative(m in random_grid()) {
        let t = IntrinsicTriangulation::delaunay(&m, &IntrinsicOptions::default()).unwrap();
        prop_assert!(t.interior_edge_weights().iter().all(|w| *w >= -1e-10));
        let l = t.cotan_laplacian();
        for row in l.outer_iterator() {
            prop_assert!(row.iter().map(|(_, v)| v).sum::<f64>().abs() < 1e-9);
        }
    }

    #[test]
    fn random_soups_clean_without_panic(
        raw in proptest::collection::vec((0u32..12, 0u32..12, 0u32..12), 0..40),
        coords in proptest::collection::vec(-2i8..3, 36),
    ) {
        // Integer-ish coordinates make duplicates, collinear and coincident points likely.
        let positions: Vec<DVec3> = coords.chunks(3).map(|c| DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64)).collect();
        let faces: Vec<[u32; 3]> = raw.into_iter().map(|(a, b, c)| [a, b, c]).collect();
        let (m, _) = clean::clean(positions, faces, &CleanOptions::default()).unwrap();
        check_halfedges(&m);
        check_laplacian(&m);
        // Cleaning again changes nothing.
        let (m2, again) = m.cleaned(&CleanOptions::default()).unwrap();
        prop_assert!(again.is_unchanged(), "{:?}", again);
        prop_assert_eq!(m2.face_count(), m.face_count());
    }
}

/// A vertex's kind from its definition, by brute force over all faces:
/// isolated without faces; non-manifold at an edge of 3+ faces or when its
/// faces split into several fans (faces joined across edges at the vertex
/// that have exactly two faces); boundary at an edge of one face.
fn brute_force_kind(faces: &[[u32; 3]], v: u32) -> VertexKind {
    let around: Vec<usize> = (0..faces.len()).filter(|&f| faces[f].contains(&v)).collect();
    if around.is_empty() {
        return VertexKind::Isolated;
    }
    let faces_on = |w: u32| around.iter().filter(|&&f| faces[f].contains(&w)).count();
    let others: Vec<u32> = around.iter().flat_map(|&f| faces[f]).filter(|&w| w != v).collect();
    let mut fan: Vec<usize> = (0..around.len()).collect();
    let root = |fan: &Vec<usize>, mut i: usize| {
        while fan[i] != i {
            i = fan[i];
        }
        i
    };
    for i in 0..around.len() {
        for j in 0..i {
            let shared = faces[around[i]].iter().any(|&w| w != v && faces[around[j]].contains(&w) && faces_on(w) == 2);
            if shared {
                let (a, b) = (root(&fan, i), root(&fan, j));
                fan[a] = b;
            }
        }
    }
    let fans = (0..around.len()).filter(|&i| root(&fan, i) == i).count();
    if fans > 1 || others.iter().any(|&w| faces_on(w) > 2) {
        VertexKind::NonManifold
    } else if others.iter().any(|&w| faces_on(w) == 1) {
        VertexKind::Boundary
    } else {
        VertexKind::Interior
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// The lean edge numbering (midpoint subdivision's) is the half-edge
    /// structure's, on soups that are mostly not manifold.
    #[test]
    fn edge_numbering_matches_connectivity(
        raw in proptest::collection::vec((0u32..9, 0u32..9, 0u32..9), 0..30),
    ) {
        let faces: Vec<[u32; 3]> =
            raw.into_iter().map(|(a, b, c)| [a, b, c]).filter(|[a, b, c]| a != b && b != c && a != c).collect();
        let c = Connectivity::new(9, &faces);
        let m = TriMesh::new(vec![DVec3::ZERO; 9], faces.clone()).unwrap();
        let (edges, halfedge_edge) = mesh_kernel::connectivity::number_edges(&m);
        let theirs: Vec<[u32; 2]> = c.edges().iter().map(|e| [e[0].0, e[1].0]).collect();
        prop_assert_eq!(edges, theirs);
        for f in 0..faces.len() {
            let ours = [halfedge_edge[3 * f], halfedge_edge[3 * f + 1], halfedge_edge[3 * f + 2]];
            prop_assert_eq!(ours, c.face_edges(FaceId::new(f)).map(|e| e.0));
        }
    }

    #[test]
    fn vertex_kinds_match_their_definition(
        raw in proptest::collection::vec((0u32..9, 0u32..9, 0u32..9), 0..30),
    ) {
        let faces: Vec<[u32; 3]> =
            raw.into_iter().map(|(a, b, c)| [a, b, c]).filter(|[a, b, c]| a != b && b != c && a != c).collect();
        let m = TriMesh::new(vec![DVec3::ZERO; 9], faces.clone()).unwrap();
        for v in 0..9 {
            prop_assert_eq!(m.connectivity().vertex_kind(VertexId(v)), brute_force_kind(&faces, v), "vertex {}", v);
            // The valence is the number of distinct other corners of v's faces.
            let mut ring: Vec<u32> = faces.iter().filter(|f| f.contains(&v)).flatten().copied().filter(|&w| w != v).collect();
            ring.sort_unstable();
            ring.dedup();
            prop_assert_eq!(m.connectivity().valence(VertexId(v)), ring.len(), "vertex {}", v);
        }
        check_halfedges(&m);
        // Rings are ordered where the orientation is consistent.
        if m.connectivity().non_manifold_report().inconsistent_edges.is_empty() {
            check_rings(&m);
        }
    }
}

#[test]
fn subdivision_keeps_euler_characteristic() {
    for m in [shapes::torus(2.0, 0.5, 12, 6).unwrap(), shapes::disk(3, 2).unwrap(), shapes::cube(2).unwrap()] {
        let (p, f) = shapes::midpoint_subdivide(&m);
        let s = TriMesh::new(p, f).unwrap();
        check_halfedges(&s);
        check_rings(&s);
        assert_eq!(s.connectivity().euler_characteristic(), m.connectivity().euler_characteristic());
        assert_eq!(s.connectivity().genus(), m.connectivity().genus());
        assert_eq!(s.face_count(), 4 * m.face_count());
    }
}

#[test]
fn stl_style_soup_welds_back() {
    let m = shapes::torus(2.0, 0.5, 16, 8).unwrap();
    let soup: Vec<DVec3> = m.faces().iter().flat_map(|f| f.map(|v| m.positions()[v as usize])).collect();
    let faces: Vec<[u32; 3]> = (0..m.face_count() as u32).map(|f| [3 * f, 3 * f + 1, 3 * f + 2]).collect();
    let (w, r) = clean::clean(soup, faces, &CleanOptions::default()).unwrap();
    assert_eq!(w.vertex_count(), m.vertex_count());
    assert_eq!(r.welded_vertices, 3 * m.face_count() - m.vertex_count());
    assert_eq!(w.connectivity().genus(), Some(1));
    assert_eq!(r.flipped_faces, 0);
}
