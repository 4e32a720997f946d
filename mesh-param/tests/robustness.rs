//! Bad input never panics and never yields NaN: degenerate, duplicate,
//! non-manifold, disconnected, isolated vertices, random triangle soups.

mod common;

use glam::{DVec2, DVec3};
use mesh_kernel::{shapes, TriMesh, VertexId};
use mesh_param::{
    cut_to_disk, parameterize, parameterize_cut, BoundaryMap, DegeneratePolicy, ParamError, ParamMethod, ParamOptions,
};
use proptest::prelude::*;

fn all_methods() -> Vec<ParamMethod> {
    ParamMethod::ALL.to_vec()
}

fn options(method: ParamMethod) -> ParamOptions {
    ParamOptions { method, ..Default::default() }
}

#[test]
fn zero_area_triangles_give_finite_bijective_maps() {
    let Some(m) = common::read("cgal_degtri_sliding.off") else { return };
    for method in all_methods() {
        let p = parameterize(&m, &options(method)).unwrap();
        assert!(p.uv.iter().all(|q| q.is_finite()), "{}", method.name());
        assert_eq!(p.degenerate_faces.len(), 4, "{}", method.name());
        assert_eq!(p.report.summary.degenerate_faces, 4);
        assert!(p.report.summary.angle_distortion_mean.is_finite());
        assert!(p.report.summary.bijective, "{} is not bijective", method.name());
    }
    let refuse = ParamOptions { degenerate: DegeneratePolicy::Error, ..Default::default() };
    assert!(matches!(parameterize(&m, &refuse), Err(ParamError::DegenerateFaces { count: 4, .. })));
    let refuse_lscm =
        ParamOptions { method: ParamMethod::Lscm, degenerate: DegeneratePolicy::Error, ..Default::default() };
    assert!(matches!(parameterize(&m, &refuse_lscm), Err(ParamError::DegenerateFaces { .. })));
}

#[test]
fn coincident_vertices_and_collapsed_meshes_are_finite() {
    // Duplicate vertex (distinct index, same position): zero-length edges.
    let mut m = shapes::disk(3, 1).unwrap();
    let p4 = m.positions()[4];
    m.positions_mut()[5] = p4;
    // Every vertex at one point.
    let mut point = shapes::disk(2, 1).unwrap();
    point.positions_mut().iter_mut().for_each(|p| *p = DVec3::ONE);
    for mesh in [m, point] {
        for method in all_methods() {
            match parameterize(&mesh, &options(method)) {
                Ok(p) => assert!(p.uv.iter().all(|q| q.is_finite())),
                Err(e) => assert!(!e.to_string().is_empty()),
            }
        }
        let tutte = parameterize(&mesh, &options(ParamMethod::Tutte)).unwrap();
        assert!(tutte.report.summary.bijective);
    }
}

#[test]
fn isolated_vertices_are_carried_along() {
    let d = shapes::disk(4, 2).unwrap();
    let (mut p, f) = d.into_parts();
    p.push(DVec3::new(9.0, 9.0, 9.0));
    let m = TriMesh::new(p, f).unwrap();
    for method in all_methods() {
        let r = parameterize(&m, &ParamOptions { normalize: true, ..options(method) }).unwrap();
        assert_eq!(r.uv.len(), m.vertex_count());
        assert!(r.uv.iter().all(|q| q.is_finite()));
        assert!(r.report.summary.bijective, "{}", method.name());
        // The free-boundary results stay in the unit box.
        if matches!(method, ParamMethod::Lscm | ParamMethod::Arap { .. }) {
            assert!(r.uv.iter().all(|q| q.min_element() >= -1e-12 && q.max_element() <= 1.0 + 1e-12));
        }
    }
}

#[test]
fn wrong_topology_says_what_it_found() {
    let err = |m: &TriMesh| parameterize(m, &ParamOptions::default()).unwrap_err().to_string();
    assert!(err(&shapes::torus(2.0, 0.5, 12, 6).unwrap()).contains("closed surface of genus 1"));
    let p = (0..5).map(|i| DVec3::new(i as f64, (i * i) as f64, 0.0)).collect();
    let bowtie = TriMesh::new(p, vec![[0, 1, 2], [0, 3, 4]]).unwrap();
    assert!(matches!(parameterize(&bowtie, &ParamOptions::default()), Err(ParamError::Mesh(_))));
    assert!(matches!(cut_to_disk(&bowtie), Err(ParamError::Mesh(_))));
    let empty = TriMesh::new(vec![], vec![]).unwrap();
    assert!(err(&empty).contains("without faces"));
    let two = {
        let (mut p, mut f) = shapes::disk(2, 1).unwrap().into_parts();
        let n = p.len() as u32;
        p.extend(p.clone().iter().map(|q| *q + DVec3::X * 5.0));
        f.extend(f.clone().iter().map(|t| t.map(|v| v + n)));
        TriMesh::new(p, f).unwrap()
    };
    assert!(err(&two).contains("2 connected components"));
    assert!(parameterize_cut(&two, &ParamOptions::default()).unwrap_err().to_string().contains("separately"));
}

#[test]
fn invalid_options_are_errors() {
    let m = shapes::disk(3, 1).unwrap();
    let bad = |method, boundary| parameterize(&m, &ParamOptions { method, boundary, ..Default::default() }).is_err();
    let circle = BoundaryMap::default();
    assert!(bad(ParamMethod::Intrinsic { lambda: -1.0, mu: 1.0 }, circle.clone()));
    assert!(bad(ParamMethod::Intrinsic { lambda: 0.0, mu: 0.0 }, circle.clone()));
    assert!(bad(ParamMethod::Intrinsic { lambda: f64::NAN, mu: 1.0 }, circle.clone()));
    assert!(bad(ParamMethod::Arap { iterations: 1_000_000 }, circle));
    // A fixed boundary missing a vertex, with a NaN, or out of range.
    let b = m.connectivity().boundary_loops().unwrap()[0].vertices.clone();
    let partial: Vec<(VertexId, DVec2)> = b.iter().skip(1).map(|&v| (v, DVec2::ZERO)).collect();
    assert!(bad(ParamMethod::Harmonic, BoundaryMap::Fixed(partial)));
    let mut nan: Vec<(VertexId, DVec2)> = b.iter().map(|&v| (v, DVec2::ONE * v.0 as f64)).collect();
    nan[0].1.x = f64::NAN;
    assert!(bad(ParamMethod::Harmonic, BoundaryMap::Fixed(nan)));
    let mut out: Vec<(VertexId, DVec2)> = b.iter().map(|&v| (v, DVec2::ONE * v.0 as f64)).collect();
    out.push((VertexId(1000), DVec2::ZERO));
    assert!(bad(ParamMethod::Harmonic, BoundaryMap::Fixed(out)));
    // LSCM takes exactly two pins.
    let three = BoundaryMap::Fixed(b.iter().take(3).map(|&v| (v, DVec2::ONE * v.0 as f64)).collect());
    assert!(bad(ParamMethod::Lscm, three));
    let tri = TriMesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y], vec![[0, 1, 2]]).unwrap();
    let square = ParamOptions { boundary: BoundaryMap::Square, ..Default::default() };
    assert!(parameterize(&tri, &square).is_err());
    // A single triangle is a disk: every method maps it.
    for method in all_methods() {
        assert!(parameterize(&tri, &options(method)).unwrap().report.summary.bijective);
    }
}

/// Random triangles over a few vertices: any soup at all.
fn soup() -> impl Strategy<Value = TriMesh> {
    (3usize..10)
        .prop_flat_map(|n| {
            let p = prop::collection::vec((-2i8..3, -2i8..3, -1i8..2), n);
            let f = prop::collection::vec((0..n as u32, 0..n as u32, 0..n as u32), 1..14);
            (p, f)
        })
        .prop_map(|(p, f)| {
            let p = p.into_iter().map(|(x, y, z)| DVec3::new(x as f64, y as f64, z as f64 * 0.5)).collect();
            let f = f.into_iter().filter(|(a, b, c)| a != b && b != c && a != c).map(|(a, b, c)| [a, b, c]).collect();
            TriMesh::new(p, f).unwrap()
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]
    #[test]
    fn triangle_soups_never_panic_or_nan(mesh in soup(), m in 0usize..7) {
        let method = ParamMethod::ALL[m];
        let direct = parameterize(&mesh, &options(method)).map(|p| p.uv);
        let cut = parameterize_cut(&mesh, &options(method)).map(|p| p.param.uv);
        for uv in [direct, cut].into_iter().flatten() {
            prop_assert!(uv.iter().all(|q| q.is_finite()));
        }
    }
}
