//! Detection of subdivision connectivity: subdivide known base meshes,
//! shuffle vertices and faces, detect, and compare with the truth; meshes
//! without it, and bad input, give typed errors.

mod common;

use common::{base_meshes, fin_edge, real_mesh, relative_max_distance, shuffled, SplitMix64};
use mesh_kernel::{glam::DVec3, shapes, MeshError, TriMesh};
use mesh_wavelet::{
    detect, subdivide, DetectOptions, Hierarchy, MultiresOptions, Multiresolution, Scheme, SubdivideOptions,
    WaveletError, WaveletKind,
};
use proptest::prelude::*;

/// Faces as sorted vertex triples, sorted, for comparing triangulations.
fn face_set(faces: impl IntoIterator<Item = [u32; 3]>) -> Vec<[u32; 3]> {
    let mut f: Vec<[u32; 3]> = faces
        .into_iter()
        .map(|mut t| {
            t.sort_unstable();
            t
        })
        .collect();
    f.sort_unstable();
    f
}

/// Splitting the detected base mesh J times gives back the input faces.
fn assert_reproduces(h: &Hierarchy, mesh: &TriMesh) {
    let j = h.levels();
    let again = Hierarchy::from_base(h.vertex_count(0).unwrap(), h.faces(0).unwrap(), j).unwrap();
    let to_input = h.to_input().unwrap();
    let rebuilt = face_set(again.faces(j).unwrap().iter().map(|f| f.map(|v| to_input[v as usize])));
    assert_eq!(rebuilt, face_set(mesh.faces().iter().copied()));
}

/// Meshes where every vertex is regular (valence 6 inside, 4 on the
/// boundary) have several valid base meshes: a 10 x 6 torus grid splits a
/// 5 x 3 one four ways (translations). Only the others are compared with the
/// original base.
const ALL_REGULAR: [&str; 2] = ["torus", "cylinder"];

#[test]
fn recovers_base_mesh_and_levels_after_shuffling() {
    for (name, base) in base_meshes() {
        for levels in 1..=3 {
            let fine = subdivide(&base, &SubdivideOptions { scheme: Scheme::Midpoint, levels }).unwrap();
            let (mesh, new_index) = shuffled(&fine, 7 + levels as u64);
            let h = detect(&mesh, &DetectOptions::default()).unwrap();
            assert_reproduces(&h, &mesh);
            let n0 = base.vertex_count();
            if ALL_REGULAR.contains(&name) {
                assert!(h.levels() >= levels, "{name}");
                continue;
            }
            assert_eq!(h.levels(), levels, "{name} at {levels} levels");
            assert_eq!((h.vertex_count(0).unwrap(), h.faces(0).unwrap().len()), (n0, base.face_count()), "{name}");
            // The base vertices are the original ones (vertices 0..n0 of the
            // subdivided mesh), and the base faces the original faces.
            let to_input = h.to_input().unwrap();
            let mut base_inputs: Vec<u32> = to_input[..n0].to_vec();
            base_inputs.sort_unstable();
            let mut expected: Vec<u32> = new_index[..n0].to_vec();
            expected.sort_unstable();
            assert_eq!(base_inputs, expected, "{name}");
            let detected = face_set(h.faces(0).unwrap().iter().map(|f| f.map(|v| to_input[v as usize])));
            let truth = face_set(base.faces().iter().map(|f| f.map(|v| new_index[v as usize])));
            assert_eq!(detected, truth, "{name}");
            // Orientation is kept: each base face appears with its own cyclic order.
            for f in h.faces(0).unwrap() {
                let t = f.map(|v| to_input[v as usize]);
                let same = base
                    .faces()
                    .iter()
                    .map(|g| g.map(|v| new_index[v as usize]))
                    .any(|g| (0..3).any(|r| [g[r], g[(r + 1) % 3], g[(r + 2) % 3]] == t));
                assert!(same, "{name}: face {t:?} flipped");
            }
        }
    }
}

#[test]
fn file_round_trip_subdivide_shuffle_detect_analyze_synthesize() {
    // A mesh read back from a file has lost its hierarchy: detection finds it.
    let dir = tempfile::tempdir().unwrap();
    for (name, base) in base_meshes() {
        for scheme in Scheme::ALL {
            let fine = subdivide(&base, &SubdivideOptions { scheme, levels: 3 }).unwrap();
            let (mesh, _) = shuffled(&fine, 99);
            let path = dir.path().join(format!("{}-{scheme}.obj", name.replace(' ', "_")));
            mesh_io::write(&path, &mesh, &Default::default()).unwrap();
            let read = mesh_io::read(&path).unwrap().mesh;
            assert_eq!(read.faces(), mesh.faces());
            for wavelet in [WaveletKind::Lazy, WaveletKind::Lifted] {
                let mr = Multiresolution::analyze(&read, &MultiresOptions { scheme, wavelet, ..Default::default() })
                    .unwrap();
                assert!(mr.levels() >= 3 && (mr.levels() == 3 || ALL_REGULAR.contains(&name)), "{name}");
                let back = mr.synthesize().unwrap();
                assert_eq!(back.faces(), read.faces(), "{name}: faces in input order");
                assert!(relative_max_distance(&read, &back) < 1e-12, "{name} {scheme} {wavelet}");
            }
        }
    }
}

#[test]
fn regular_tori_reverse_as_far_as_they_can() {
    // A 24 x 12 torus grid is a 6 x 3 one split twice (all valence 6: no
    // vertex is forced to be even, so the seed face tries its four roles).
    let m = shapes::torus(2.0, 0.5, 24, 12).unwrap();
    let (m, _) = shuffled(&m, 3);
    let h = detect(&m, &DetectOptions::default()).unwrap();
    assert_reproduces(&h, &m);
    assert_eq!((h.levels(), h.vertex_count(0).unwrap()), (2, 18));
    let h1 = detect(&m, &DetectOptions { max_levels: 1 }).unwrap();
    assert_eq!((h1.levels(), h1.vertex_count(0).unwrap()), (1, 72));
}

#[test]
fn cgal_holes_and_mushroom_are_twice_split_meshes() {
    // Found by detection: the CGAL "holes" (genus 0, 7 boundary loops) and
    // "mushroom" (a disk) demo meshes are coarse meshes split 4-to-1 twice.
    for (name, n0, f0, chi, loops) in [("cgal_holes.off", 292, 518, -5, 7), ("cgal_mushroom.off", 153, 288, 1, 1)] {
        let Some(m) = real_mesh(name) else { return };
        let h = detect(&m, &DetectOptions::default()).unwrap();
        assert_eq!((h.levels(), h.vertex_count(0).unwrap(), h.faces(0).unwrap().len()), (2, n0, f0), "{name}");
        assert_reproduces(&h, &m);
        let base = TriMesh::new(vec![DVec3::ZERO; n0], h.faces(0).unwrap().to_vec()).unwrap();
        let c = base.connectivity();
        assert_eq!((c.euler_characteristic(), c.boundary_loop_count()), (chi, Some(loops)), "{name}");
    }
}

#[test]
fn meshes_without_subdivision_connectivity_say_so() {
    for name in ["npm_bunny.obj", "cgal_elephant.off", "cgal_fandisk.off", "cgal_nefertiti.off"] {
        let Some(m) = real_mesh(name) else { return };
        match detect(&m, &DetectOptions::default()) {
            Err(WaveletError::NoSubdivisionConnectivity { reason }) => assert!(!reason.is_empty()),
            other => panic!("{name}: {other:?}"),
        }
        let e = Multiresolution::analyze(&m, &MultiresOptions::default()).unwrap_err();
        assert!(e.to_string().contains("no subdivision connectivity"), "{e}");
    }
    // A uv sphere has poles of high valence and no 4-to-1 structure.
    let uv = shapes::uv_sphere(1.0, 16, 8).unwrap();
    assert!(matches!(detect(&uv, &Default::default()), Err(WaveletError::NoSubdivisionConnectivity { .. })));
    // One flipped diagonal breaks it.
    let fine =
        subdivide(&shapes::icosphere(0).unwrap(), &SubdivideOptions { scheme: Scheme::Midpoint, levels: 2 }).unwrap();
    let mut faces = fine.faces().to_vec();
    let c = fine.connectivity();
    let e = (0..c.edge_count())
        .map(mesh_kernel::EdgeId::new)
        .find(|&e| {
            !c.is_boundary_edge(e) && c.valence(c.edge_vertices(e)[0]) == 6 && c.valence(c.edge_vertices(e)[1]) == 6
        })
        .unwrap();
    let [h0, h1] = [c.edge_halfedges(e)[0], c.edge_halfedges(e)[1]];
    let (a, b) = (c.origin(h0).0, c.dest(h0).0);
    let (x, y) = (c.opposite_vertex(h0).0, c.opposite_vertex(h1).0);
    faces[h0.face().idx()] = [x, a, y];
    faces[h1.face().idx()] = [y, b, x];
    let flipped = TriMesh::new(fine.positions().to_vec(), faces).unwrap();
    assert!(flipped.connectivity().is_manifold());
    match detect(&flipped, &Default::default()) {
        Err(WaveletError::NoSubdivisionConnectivity { .. }) => {}
        Ok(h) => panic!("a flipped mesh reversed {} levels", h.levels()),
        Err(e) => panic!("{e}"),
    }
}

#[test]
fn bad_input_is_a_typed_error() {
    let nonmanifold = fin_edge();
    assert!(matches!(detect(&nonmanifold, &Default::default()), Err(WaveletError::Mesh(MeshError::NonManifold(_)))));
    let empty = TriMesh::new(vec![], vec![]).unwrap();
    assert!(matches!(detect(&empty, &Default::default()), Err(WaveletError::Mesh(MeshError::Empty))));
    // An isolated vertex has no place in the hierarchy.
    let fine =
        subdivide(&shapes::icosphere(0).unwrap(), &SubdivideOptions { scheme: Scheme::Midpoint, levels: 1 }).unwrap();
    let mut p = fine.positions().to_vec();
    p.push(DVec3::ONE);
    let with_isolated = TriMesh::new(p, fine.faces().to_vec()).unwrap();
    match detect(&with_isolated, &Default::default()) {
        Err(WaveletError::NoSubdivisionConnectivity { reason }) => assert!(reason.contains("no face"), "{reason}"),
        other => panic!("{other:?}"),
    }
    assert!(detect(&fine, &DetectOptions { max_levels: 0 }).is_err());
    // Degenerate (zero-area) faces do not matter to a combinatorial test.
    if let Some(deg) = real_mesh("cgal_degtri_sliding.off") {
        let fine = subdivide(&deg, &SubdivideOptions { scheme: Scheme::Midpoint, levels: 2 }).unwrap();
        let h = detect(&fine, &Default::default()).unwrap();
        assert!(h.levels() >= 2);
        let mr = Multiresolution::analyze(&fine, &MultiresOptions::default()).unwrap();
        assert!(relative_max_distance(&fine, &mr.synthesize().unwrap()) < 1e-12);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    /// Random grids (boundary, corners of valence 2 and 3), random levels,
    /// random numbering: detection finds at least the levels made, and the
    /// multiresolution round trip is exact.
    #[test]
    fn random_grids_round_trip(nx in 1usize..5, ny in 1usize..5, levels in 1usize..4, seed in any::<u64>()) {
        let mut rng = SplitMix64::new(seed);
        let g = shapes::grid(1.0, 1.0, nx, ny).unwrap();
        let p = g.positions().iter().map(|p| *p + DVec3::new(0.0, 0.0, 0.1 * rng.signed())).collect();
        let base = TriMesh::new(p, g.faces().to_vec()).unwrap();
        let fine = subdivide(&base, &SubdivideOptions { scheme: Scheme::Loop, levels }).unwrap();
        let (mesh, _) = shuffled(&fine, seed);
        let h = detect(&mesh, &Default::default()).unwrap();
        assert_reproduces(&h, &mesh);
        prop_assert!(h.levels() >= levels);
        let mr = Multiresolution::analyze(&mesh, &MultiresOptions::default()).unwrap();
        prop_assert!(relative_max_distance(&mesh, &mr.synthesize().unwrap()) < 1e-12);
    }
}
