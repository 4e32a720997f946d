//! `clean` with `manifold: true` turns any soup into an oriented manifold:
//! fins, bow-ties, Moebius strips, random soups; geometry never moves.

use mesh_kernel::clean::{clean, CleanOptions, CleanReport};
use mesh_kernel::glam::DVec3;
use mesh_kernel::{shapes, TriMesh};
use proptest::prelude::*;

fn repair(positions: Vec<DVec3>, faces: Vec<[u32; 3]>) -> (TriMesh, CleanReport) {
    let options = CleanOptions { manifold: true, ..CleanOptions::default() };
    let (mesh, report) = clean(positions, faces, &options).unwrap();
    mesh.connectivity().require_manifold().unwrap();
    (mesh, report)
}

/// The unit square in z = 0 as two triangles, plus extra points.
fn square_and(extra: &[DVec3]) -> Vec<DVec3> {
    let mut p = vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
    p.extend_from_slice(extra);
    p
}

#[test]
fn a_fin_is_detached_and_the_sheet_kept() {
    // The fin stands up from the diagonal 0-2 of the square.
    let p = square_and(&[DVec3::new(0.5, 0.5, 1.0)]);
    let (m, r) = repair(p, vec![[0, 1, 2], [0, 2, 3], [0, 2, 4]]);
    assert_eq!((r.fin_edges, r.detached_faces), (1, 1));
    assert_eq!(m.face_count(), 3);
    // The sheet stays glued: one edge with two faces, the fin has its own edge.
    let c = m.connectivity();
    let interior = (0..c.edge_count()).filter(|&e| !c.is_boundary_edge(mesh_kernel::EdgeId::new(e))).count();
    assert_eq!(interior, 1);
    assert_eq!(c.components().count, 2);
    assert_eq!(r.split_vertices, 2);
}

#[test]
fn a_book_keeps_its_flattest_pair() {
    // Four pages on the spine 0-1; pages 2 and 4 continue each other (a flat
    // sheet through the spine), pages 3 and 5 are steep.
    let p = vec![
        DVec3::ZERO,
        DVec3::X,
        DVec3::new(0.5, 1.0, 0.0),
        DVec3::new(0.5, 0.3, 1.0),
        DVec3::new(0.5, -1.0, 0.0),
        DVec3::new(0.5, -0.3, 1.0),
    ];
    let (m, r) = repair(p, vec![[0, 1, 2], [0, 1, 3], [1, 0, 4], [1, 0, 5]]);
    assert_eq!((r.fin_edges, r.detached_faces), (1, 2));
    // The flat pair (faces 0 and 2) shares the spine in the result.
    let f = m.faces();
    let shared = f[0].iter().filter(|v| f[2].contains(v)).count();
    assert_eq!(shared, 2, "{f:?}");
    assert_eq!(m.connectivity().components().count, 3);
}

#[test]
fn a_bowtie_vertex_is_split() {
    let p = vec![DVec3::ZERO, DVec3::X, DVec3::Y, -DVec3::X, -DVec3::Y];
    let (m, r) = repair(p, vec![[0, 1, 2], [0, 3, 4]]);
    assert_eq!(r.split_vertices, 1);
    assert_eq!(m.vertex_count(), 6);
    assert_eq!(m.position(mesh_kernel::VertexId(5)), DVec3::ZERO);
}

#[test]
fn a_moebius_strip_is_cut_and_oriented() {
    let n = 9;
    let mut p = Vec::new();
    for i in 0..n {
        let t = i as f64 / n as f64 * std::f64::consts::TAU;
        for s in [-1.0, 1.0] {
            let w = 0.3 * s;
            let c = (t / 2.0).cos() * w;
            p.push(DVec3::new((2.0 + c) * t.cos(), (2.0 + c) * t.sin(), (t / 2.0).sin() * w));
        }
    }
    let mut faces = Vec::new();
    for i in 0..n as u32 {
        let (a, b) = (2 * i, 2 * i + 1);
        let (c, d) = if i + 1 == n as u32 { (1, 0) } else { (2 * i + 2, 2 * i + 3) };
        faces.push([a, c, b]);
        faces.push([b, c, d]);
    }
    let (without, r0) = clean(p.clone(), faces.clone(), &CleanOptions::default()).unwrap();
    assert_eq!((r0.unorientable_components, r0.flipped_faces), (1, 0));
    assert!(without.connectivity().require_manifold().is_err());
    let (m, r) = repair(p, faces);
    assert!(r.cut_edges >= 1);
    assert_eq!(r.unorientable_components, 0);
    assert_eq!(m.face_count(), 2 * n);
}

#[test]
fn clean_meshes_pass_unchanged() {
    for mesh in [shapes::icosphere(3).unwrap(), shapes::torus(2.0, 0.5, 24, 8).unwrap(), shapes::disk(6, 1).unwrap()] {
        let (m, r) = repair(mesh.positions().to_vec(), mesh.faces().to_vec());
        assert!(r.is_unchanged(), "{r:?}");
        assert_eq!(m.faces(), mesh.faces());
    }
}

#[test]
fn unorientable_components_counts_components_not_patches() {
    // One sphere with a fin on every edge of one face: many patches, one
    // component, nothing unorientable.
    let sphere = shapes::icosphere(2).unwrap();
    let (mut p, mut f) = sphere.into_parts();
    let [a, b, c] = f[0];
    for (x, y) in [(a, b), (b, c), (c, a)] {
        p.push((p[x as usize] + p[y as usize]) * 0.7);
        f.push([x, y, (p.len() - 1) as u32]);
    }
    let (_, r) = clean(p.clone(), f.clone(), &CleanOptions::default()).unwrap();
    assert_eq!(r.unorientable_components, 0);
    let (m, r) = repair(p, f);
    assert_eq!(r.fin_edges, 3);
    assert_eq!(r.detached_faces, 3);
    assert_eq!(m.connectivity().genus(), Some(0));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    /// Random soups over few vertices (fins, bow-ties, inconsistent and
    /// unorientable gluing everywhere): the result is an oriented manifold
    /// with the same faces at the same places.
    #[test]
    fn any_soup_becomes_an_oriented_manifold(
        n in 4usize..12,
        raw in proptest::collection::vec((0u32..12, 0u32..12, 0u32..12), 1..60),
        seed in 0u64..1000,
    ) {
        let mut rng = mesh_testkit::SplitMix64::new(seed);
        let mut next = || rng.unit();
        let positions: Vec<DVec3> = (0..n).map(|_| DVec3::new(next(), next(), next())).collect();
        let faces: Vec<[u32; 3]> = raw
            .into_iter()
            .map(|(a, b, c)| [a % n as u32, b % n as u32, c % n as u32])
            .filter(|[a, b, c]| a != b && b != c && a != c)
            .collect();
        let options = CleanOptions {
            manifold: true,
            drop_degenerate: false,
            drop_duplicates: false,
            drop_unreferenced: false,
            weld_tolerance: None,
            ..CleanOptions::default()
        };
        let (m, r) = clean(positions.clone(), faces.clone(), &options).unwrap();
        prop_assert!(m.connectivity().require_manifold().is_ok(), "{}", m.connectivity().non_manifold_report());
        prop_assert_eq!(m.face_count(), faces.len());
        prop_assert_eq!(m.vertex_count(), n + r.split_vertices);
        for (out, inp) in m.faces().iter().zip(&faces) {
            let a = out.map(|v| m.positions()[v as usize]);
            let b = inp.map(|v| positions[v as usize]);
            prop_assert!(a == b || a == [b[0], b[2], b[1]]);
        }
    }
}
