//! The heat method far from the sources, against exact distances on
//! developable meshes (their exact polyhedral distance is the Euclidean
//! distance in the unrolled plane): a flat strip, a strip wound into a
//! helix, a long thin cylinder. The targets are those of the large-mesh
//! work: max |heat - exact| <= 2% and median <= 0.5% of the largest
//! distance, whatever the number of edge lengths spanned, and no plateau.

use mesh_geodesic::{HeatDistance, HeatFarField, HeatGeodesics, HeatOptions, HeatStatus};
use mesh_kernel::glam::DVec3;
use mesh_kernel::{shapes, TriMesh, VertexId};

/// Max and median of |d - truth| over the largest truth, and the fraction
/// of vertices within 1% of the field's own maximum (the plateau).
fn relative_errors(d: &[f64], truth: &[f64]) -> (f64, f64, f64) {
    let scale = truth.iter().copied().fold(0.0, f64::max);
    let mut e: Vec<f64> = d.iter().zip(truth).map(|(a, b)| (a - b).abs() / scale).collect();
    e.sort_by(f64::total_cmp);
    let top = d.iter().copied().fold(0.0, f64::max);
    let plateau = d.iter().filter(|x| **x > 0.99 * top).count() as f64 / d.len() as f64;
    (e[e.len() - 1], e[e.len() / 2], plateau)
}

fn solve(mesh: &TriMesh, far_field: HeatFarField) -> HeatDistance {
    let heat = HeatGeodesics::new(mesh, &HeatOptions { far_field, ..Default::default() }).unwrap();
    heat.solve(&[VertexId(0)]).unwrap()
}

fn check_targets(name: &str, d: &HeatDistance, truth: &[f64]) {
    assert!(d.distance.iter().all(|x| x.is_finite()), "{name}: non-finite distance");
    let (max, median, plateau) = relative_errors(&d.distance, truth);
    println!(
        "{name}: max {max:.2e} median {median:.2e} plateau {plateau:.4}; heat {} far field {} unresolved {}",
        d.count(HeatStatus::Heat),
        d.count(HeatStatus::FarField),
        d.count(HeatStatus::Unresolved)
    );
    assert!(max <= 0.02 && median <= 0.005, "{name}: max {max}, median {median}");
    // A plateau would put a large share of the vertices at the maximum; the
    // exact field has one vertex column (of ~thousands) within 1% of it.
    assert!(plateau < 0.02, "{name}: {plateau} of the vertices on a plateau");
    assert_eq!(d.count(HeatStatus::Unresolved), 0, "{name}");
}

/// The strip: 1500 x 2 unit squares, 3 rows of vertices, source at a
/// corner; the heat method used to stop at 427 with 72% of the vertices on
/// a plateau.
#[test]
fn strip_1500_is_covered_by_the_heat_flow_alone() {
    let mesh = shapes::grid(1500.0, 2.0, 1500, 2).unwrap();
    let truth: Vec<f64> = mesh.positions().iter().map(|p| p.length()).collect();
    let d = solve(&mesh, HeatFarField::None);
    check_targets("strip 1500 x 2", &d, &truth);
    // 1341 mean edge lengths are inside the heat flow's resolved range.
    assert_eq!(d.count(HeatStatus::Heat), mesh.vertex_count());
}

/// 6000 edge lengths: beyond the exponent range of the heat flow; each
/// continuation meets the targets, and without one the far vertices are
/// flagged rather than silently flat.
#[test]
fn strip_6000_is_continued_beyond_the_heat_flow() {
    let mesh = shapes::grid(6000.0, 2.0, 6000, 2).unwrap();
    let truth: Vec<f64> = mesh.positions().iter().map(|p| p.length()).collect();
    for far_field in [HeatFarField::FastMarching, HeatFarField::Restart] {
        let d = solve(&mesh, far_field);
        check_targets(&format!("strip 6000 x 2, {far_field}"), &d, &truth);
        let continued = if far_field == HeatFarField::FastMarching { HeatStatus::FarField } else { HeatStatus::Heat };
        assert!(d.count(continued) > mesh.vertex_count() / 2, "{far_field}");
    }
    let d = solve(&mesh, HeatFarField::None);
    let flagged: Vec<usize> = (0..truth.len()).filter(|&v| d.status[v] == HeatStatus::Unresolved).collect();
    assert!(flagged.len() > mesh.vertex_count() / 2);
    assert!(d.distance.iter().all(|x| x.is_finite()));
    // Everything closer than 1300 is resolved, everything flagged is far.
    assert!(flagged.iter().all(|&v| truth[v] > 1300.0), "a near vertex flagged");
    assert!((0..truth.len()).all(|v| truth[v] > 1300.0 || d.status[v] == HeatStatus::Heat));
}

/// A strip of 3000 x 2 unit-ish parallelograms wound into a helix of
/// radius 20 (pitch pi): every quad is planar and consecutive quads hinge
/// on vertical edges, so the surface unrolls isometrically onto a planar
/// parallelogram strip and the exact distance is the Euclidean one there.
#[test]
fn helical_strip_in_3d_against_its_unrolling() {
    let (columns, radius, step, rise) = (3000usize, 20.0f64, 0.05f64, 0.5f64);
    let chord = 2.0 * radius * (0.5 * step).sin();
    let mut positions = Vec::new();
    let mut unrolled = Vec::new();
    for j in 0..3 {
        for i in 0..=columns {
            let a = step * i as f64;
            positions.push(DVec3::new(radius * a.cos(), radius * a.sin(), rise * a + j as f64));
            unrolled.push((chord * i as f64, rise * a + j as f64));
        }
    }
    let faces = shapes::grid(1.0, 1.0, columns, 2).unwrap().faces().to_vec();
    let mesh = TriMesh::new(positions, faces).unwrap();
    let (x0, y0) = unrolled[0];
    let truth: Vec<f64> = unrolled.iter().map(|(x, y)| (x - x0).hypot(y - y0)).collect();
    for far_field in [HeatFarField::FastMarching, HeatFarField::Restart] {
        check_targets(&format!("helical strip, {far_field}"), &solve(&mesh, far_field), &truth);
    }
}

/// A cylinder of radius 1 and length 2070 (12 vertices around, 4000 rings):
/// a prism whose exact distance is that of its unrolled rectangle, the
/// shorter way around.
#[test]
fn long_thin_cylinder_against_its_unrolling() {
    let (around, along) = (12usize, 4000usize);
    let chord = 2.0 * (std::f64::consts::PI / around as f64).sin();
    let height = chord * along as f64;
    let mesh = shapes::cylinder(1.0, height, around, along).unwrap();
    let truth: Vec<f64> = (0..mesh.vertex_count())
        .map(|v| {
            let (i, j) = (v / (along + 1), v % (along + 1));
            let s = chord * i.min(around - i) as f64;
            s.hypot(height * j as f64 / along as f64)
        })
        .collect();
    for far_field in [HeatFarField::FastMarching, HeatFarField::Restart] {
        check_targets(&format!("cylinder 12 x 4000, {far_field}"), &solve(&mesh, far_field), &truth);
    }
}

#[test]
fn far_field_names_round_trip() {
    for f in HeatFarField::ALL {
        assert_eq!(f.to_string().parse::<HeatFarField>().unwrap(), f);
    }
    assert!("nope".parse::<HeatFarField>().is_err());
}

/// Two 3000 x 2 strips (separate components) and an isolated vertex: the
/// far field stays on the components that hold a source.
#[test]
fn far_field_stays_on_the_source_components() {
    let strip = shapes::grid(3000.0, 2.0, 3000, 2).unwrap();
    let n = strip.vertex_count();
    let mut positions = strip.positions().to_vec();
    positions.extend(strip.positions().iter().map(|p| *p + DVec3::new(0.0, 10.0, 0.0)));
    positions.push(DVec3::new(-5.0, 0.0, 0.0));
    let mut faces = strip.faces().to_vec();
    faces.extend(strip.faces().iter().map(|f| f.map(|v| v + n as u32)));
    let mesh = TriMesh::new(positions, faces).unwrap();
    let truth: Vec<f64> = strip.positions().iter().map(|p| p.length()).collect();
    for far_field in HeatFarField::ALL {
        let heat = HeatGeodesics::new(&mesh, &HeatOptions { far_field, ..Default::default() }).unwrap();
        let one = heat.solve(&[VertexId(0)]).unwrap();
        assert!(one.distance[n..].iter().all(|x| *x == f64::INFINITY), "{far_field}");
        assert!(one.status[n..].iter().all(|s| *s == HeatStatus::Unreached), "{far_field}");
        assert_eq!(one.count(HeatStatus::Unreached), n + 1, "{far_field}");
        let both = heat.solve(&[VertexId(0), VertexId(n as u32)]).unwrap();
        assert!(both.distance[2 * n].is_infinite());
        if far_field != HeatFarField::None {
            for part in [&one.distance[..n], &both.distance[..n], &both.distance[n..2 * n]] {
                let (max, median, _) = relative_errors(part, &truth);
                assert!(max <= 0.02 && median <= 0.005, "{far_field}: {max} {median}");
            }
        }
    }
}
