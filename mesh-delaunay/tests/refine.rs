//! Constrained Delaunay refinement of polygons with holes: angle, area and
//! size bounds, empty holes, the area of the domain, typed errors.

use glam::DVec2;
use mesh_delaunay::{refine_polygon, refine_polygon_sized, DelaunayError, PolygonDomain, RefineOptions, RefinedMesh};

fn square(c: DVec2, half: f64) -> Vec<DVec2> {
    [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)].map(|(x, y)| c + half * DVec2::new(x, y)).to_vec()
}

fn circle(c: DVec2, r: f64, n: usize) -> Vec<DVec2> {
    (0..n).map(|k| c + r * DVec2::from_angle(std::f64::consts::TAU * k as f64 / n as f64)).collect()
}

/// A square with a square hole and a round (clockwise) hole.
fn plate() -> PolygonDomain {
    let mut round = circle(DVec2::new(0.5, -0.4), 0.25, 24);
    round.reverse();
    PolygonDomain { outer: square(DVec2::ZERO, 1.0), holes: vec![square(DVec2::new(-0.4, 0.4), 0.3), round] }
}

fn tri_points(m: &RefinedMesh, t: [u32; 3]) -> [DVec2; 3] {
    t.map(|v| m.points[v as usize])
}

fn angles([a, b, c]: [DVec2; 3]) -> [f64; 3] {
    let ang = |p: DVec2, q: DVec2, r: DVec2| (q - p).angle_to(r - p).abs().to_degrees();
    [ang(a, b, c), ang(b, c, a), ang(c, a, b)]
}

fn area([a, b, c]: [DVec2; 3]) -> f64 {
    0.5 * (b - a).perp_dot(c - a)
}

fn inside(p: DVec2, poly: &[DVec2]) -> bool {
    let mut odd = false;
    for i in 0..poly.len() {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        if (a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x) {
            odd = !odd;
        }
    }
    odd
}

/// Counter-clockwise triangles, holes empty, the domain's area covered.
fn assert_covers(d: &PolygonDomain, m: &RefinedMesh) {
    let mut total = 0.0;
    for t in &m.triangles {
        let p = tri_points(m, *t);
        assert!(area(p) > 0.0, "{t:?} is not counter-clockwise");
        total += area(p);
        let centroid = (p[0] + p[1] + p[2]) / 3.0;
        assert!(inside(centroid, &d.outer), "a triangle outside the outer loop");
        for h in &d.holes {
            assert!(!inside(centroid, h), "a triangle in a hole: {p:?}");
        }
    }
    let want = d.area();
    assert!((total - want).abs() <= 1e-9 * want, "area {total} vs {want}");
    let input: usize = std::iter::once(&d.outer).chain(&d.holes).map(Vec::len).sum();
    assert_eq!(m.input_vertices, input);
    assert_eq!(&m.points[..input], &d.outer.iter().chain(d.holes.iter().flatten()).copied().collect::<Vec<_>>()[..]);
}

#[test]
fn angle_and_area_bounds_hold_and_holes_stay_empty() {
    let d = plate();
    for (min_angle, max_area) in [(20.0, None), (25.0, Some(0.01)), (30.0, Some(0.002)), (0.0, Some(0.05))] {
        let o = RefineOptions { min_angle, max_area, ..Default::default() };
        let m = refine_polygon(&d, &o).expect("a valid polygon");
        assert!(m.complete);
        assert_covers(&d, &m);
        // No input angle is below 90 degrees here, so the bound holds everywhere.
        let smallest = m.triangles.iter().flat_map(|t| angles(tri_points(&m, *t))).fold(180.0, f64::min);
        assert!(smallest >= min_angle - 1e-9, "min angle {smallest} < {min_angle}");
        if let Some(a) = max_area {
            let largest = m.triangles.iter().map(|t| area(tri_points(&m, *t))).fold(0.0, f64::max);
            assert!(largest <= a * (1.0 + 1e-12), "area {largest} > {a}");
        }
    }
}

#[test]
fn a_varying_size_is_followed() {
    let d = plate();
    // Edges from 0.02 at the left to 0.3 at the right.
    let size = |p: DVec2| 0.02 + 0.14 * (p.x + 1.0);
    let m = refine_polygon_sized(&d, size, &RefineOptions::default()).expect("valid");
    assert!(m.complete);
    assert_covers(&d, &m);
    let mut left = 0usize;
    for t in &m.triangles {
        let p = tri_points(&m, *t);
        let centroid = (p[0] + p[1] + p[2]) / 3.0;
        let longest = (p[0] - p[1]).length().max((p[1] - p[2]).length()).max((p[2] - p[0]).length());
        assert!(longest <= size(centroid) * (1.0 + 1e-12), "{longest} > {}", size(centroid));
        left += usize::from(centroid.x < 0.0);
        assert!(angles(p).iter().all(|&a| a >= 25.0 - 1e-9));
    }
    // Far more triangles where the size is small.
    assert!(left > 3 * (m.triangles.len() - left), "{left} of {}", m.triangles.len());
    // Keeping the boundary, split below the size beforehand: no vertex is
    // added on it and every triangle meets the size.
    let split = |l: &[DVec2], k: usize| -> Vec<DVec2> {
        (0..l.len()).flat_map(|i| (0..k).map(move |j| l[i].lerp(l[(i + 1) % l.len()], j as f64 / k as f64))).collect()
    };
    let fine = PolygonDomain { outer: split(&d.outer, 10), holes: vec![split(&d.holes[0], 3), d.holes[1].clone()] };
    let keep = RefineOptions { keep_boundary: true, ..Default::default() };
    let k = refine_polygon_sized(&fine, |_| 0.21, &keep).expect("valid");
    assert!(k.complete);
    assert_covers(&fine, &k);
    for t in &k.triangles {
        let p = tri_points(&k, *t);
        assert!((p[0] - p[1]).length().max((p[1] - p[2]).length()).max((p[2] - p[0]).length()) <= 0.21);
    }
    let on_boundary = |p: &DVec2| {
        p.x.abs() == 1.0
            || p.y.abs() == 1.0
            || (*p - DVec2::new(0.5, -0.4)).length() > 0.2499 && (*p - DVec2::new(0.5, -0.4)).length() < 0.2501
    };
    assert_eq!(k.points[k.input_vertices..].iter().filter(|p| on_boundary(p)).count(), 0);
}

#[test]
fn small_input_angles_are_the_documented_exception() {
    // A thin wedge: its 5.7-degree tip cannot be improved.
    let d = PolygonDomain { outer: vec![DVec2::ZERO, DVec2::new(1.0, 0.0), DVec2::new(1.0, 0.1)], holes: vec![] };
    let m = refine_polygon(&d, &RefineOptions { min_angle: 25.0, ..Default::default() }).expect("valid");
    assert_covers(&d, &m);
    let tip = 0.1f64.atan().to_degrees();
    for t in &m.triangles {
        let p = tri_points(&m, *t);
        let smallest = angles(p).into_iter().fold(180.0, f64::min);
        // Triangles with a vertex at the tip may keep its angle.
        if p.iter().all(|q| q.length() > 1e-12) && smallest < 25.0 - 1e-9 {
            // Away from the tip, the small angles are between the wedge's
            // edges split near the tip (Shewchuk 2002).
            assert!(smallest >= tip * 0.5 - 1e-9, "angle {smallest}");
        }
    }
}

#[test]
fn scale_does_not_change_the_mesh() {
    let d = plate();
    let base = refine_polygon(&d, &RefineOptions { max_area: Some(0.01), ..Default::default() }).expect("valid");
    // Powers of two: the scaled coordinates are the same numbers.
    for s in [2f64.powi(-330), 2f64.powi(330)] {
        let scaled = PolygonDomain {
            outer: d.outer.iter().map(|p| *p * s).collect(),
            holes: d.holes.iter().map(|h| h.iter().map(|p| *p * s).collect()).collect(),
        };
        let o = RefineOptions { max_area: Some(0.01 * s * s), ..Default::default() };
        let m = refine_polygon(&scaled, &o).expect("valid");
        assert_eq!(m.triangles, base.triangles, "scale {s}");
    }
}

#[test]
fn the_vertex_bound_stops_the_refinement() {
    let o = RefineOptions { max_area: Some(1e-6), max_added_vertices: 500, ..Default::default() };
    let m = refine_polygon(&plate(), &o).expect("valid");
    assert!(!m.complete);
    assert!(m.points.len() <= m.input_vertices + 500);
    let m = refine_polygon_sized(&plate(), |_| 1e-4, &RefineOptions { max_added_vertices: 300, ..Default::default() })
        .expect("valid");
    assert!(!m.complete);
}

#[test]
fn invalid_polygons_are_typed_errors() {
    let o = RefineOptions::default();
    let poly = |outer: Vec<DVec2>, holes: Vec<Vec<DVec2>>| PolygonDomain { outer, holes };
    let bowtie = vec![DVec2::ZERO, DVec2::new(1.0, 1.0), DVec2::new(1.0, 0.0), DVec2::new(0.0, 1.0)];
    assert!(matches!(
        refine_polygon(&poly(bowtie, vec![]), &o),
        Err(DelaunayError::SelfIntersecting { loop_index: 0, .. })
    ));
    let line = vec![DVec2::ZERO, DVec2::X, DVec2::new(2.0, 0.0)];
    assert!(matches!(
        refine_polygon(&poly(line, vec![]), &o),
        Err(DelaunayError::DegenerateLoop { loop_index: 0, .. })
    ));
    let two = vec![DVec2::ZERO, DVec2::X];
    assert!(matches!(refine_polygon(&poly(two, vec![]), &o), Err(DelaunayError::DegenerateLoop { .. })));
    let repeated = vec![DVec2::ZERO, DVec2::X, DVec2::X, DVec2::Y];
    assert!(matches!(refine_polygon(&poly(repeated, vec![]), &o), Err(DelaunayError::DegenerateLoop { .. })));
    let outer = square(DVec2::ZERO, 1.0);
    let crossing = square(DVec2::new(0.9, 0.0), 0.3);
    assert!(matches!(
        refine_polygon(&poly(outer.clone(), vec![crossing]), &o),
        Err(DelaunayError::SelfIntersecting { .. })
    ));
    let outside = square(DVec2::new(3.0, 0.0), 0.3);
    assert!(matches!(
        refine_polygon(&poly(outer.clone(), vec![outside]), &o),
        Err(DelaunayError::MisplacedHole { hole: 0, .. })
    ));
    let nested = vec![square(DVec2::ZERO, 0.5), square(DVec2::ZERO, 0.2)];
    assert!(matches!(
        refine_polygon(&poly(outer.clone(), nested), &o),
        Err(DelaunayError::MisplacedHole { hole: 1, .. })
    ));
    // A hole vertex on an outer edge touches it.
    let touching = vec![DVec2::new(1.0, 0.0), DVec2::new(0.5, 0.2), DVec2::new(0.5, -0.2)];
    assert!(matches!(
        refine_polygon(&poly(outer.clone(), vec![touching]), &o),
        Err(DelaunayError::SelfIntersecting { .. })
    ));
    let nan = vec![DVec2::ZERO, DVec2::X, DVec2::new(f64::NAN, 1.0)];
    assert!(matches!(refine_polygon(&poly(nan, vec![]), &o), Err(DelaunayError::NonFinite { index: 2 })));
    for bad in [
        RefineOptions { min_angle: 50.0, ..Default::default() },
        RefineOptions { min_angle: f64::NAN, ..Default::default() },
        RefineOptions { max_area: Some(0.0), ..Default::default() },
    ] {
        assert!(matches!(refine_polygon(&poly(outer.clone(), vec![]), &bad), Err(DelaunayError::InvalidOption { .. })));
    }
    let sized = refine_polygon_sized(&poly(outer.clone(), vec![]), |p| if p.x > 0.0 { f64::NAN } else { 0.5 }, &o);
    assert!(matches!(sized, Err(DelaunayError::InvalidOption { name: "size", .. })));
    // A closing vertex equal to the first is dropped, not refused.
    let mut closed = outer.clone();
    closed.push(outer[0]);
    let m = refine_polygon(&poly(closed, vec![]), &o).expect("a closed loop");
    assert_eq!(m.input_vertices, 4);
}
