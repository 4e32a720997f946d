//! mesh-nurbs operations, on surfaces of their own (the mesh file is not
//! used): `nurbs_point_tangents_1m` (one million points with first
//! derivatives on a rational bicubic 16 x 16 surface, one thread: the
//! issue's target is 10 million per second, so at most 100 ms),
//! `nurbs_frames_100k` (100,000 exact curvature frames on the same surface)
//! and `nurbs_tessellate_1000x1000` (the unit sphere on a 1000 x 1000 grid,
//! welded, with exact curvature per vertex; target well under a second).

use std::path::Path;

use mesh_io::MeshData;
use mesh_nurbs::glam::DVec3;
use mesh_nurbs::{shapes, tessellate, GridOptions, KnotVector, NurbsSurface, SurfaceFrame};

use super::Operation;

/// A rational bicubic surface with 16 x 16 control points (as in
/// mesh-nurbs' criterion bench).
fn bicubic() -> mesh_nurbs::error::Result<NurbsSurface> {
    let n = 16;
    let knots = KnotVector::clamped_uniform(3, n)?;
    let mut points = Vec::with_capacity(n * n);
    let mut weights = Vec::with_capacity(n * n);
    for i in 0..n {
        for j in 0..n {
            let (x, y) = (i as f64, j as f64);
            points.push(DVec3::new(x, y, (0.5 * x).sin() * (0.3 * y).cos()));
            weights.push(1.0 + 0.1 * ((i + 2 * j) % 3) as f64);
        }
    }
    NurbsSurface::new(knots.clone(), knots, points, weights)
}

/// `count` parameters spread over the unit square (a 2D Kronecker walk).
fn parameters(count: usize) -> Vec<(f64, f64)> {
    (0..count).map(|k| ((k as f64 * 0.618_033_988_7).fract(), (k as f64 * 0.754_877_666_2).fract())).collect()
}

/// The NURBS operations (none if a surface cannot be built).
pub fn operations<'a>(_path: &'a Path, _data: &'a MeshData) -> Vec<Operation<'a>> {
    let (Ok(surface), Ok(sphere)) = (bicubic(), shapes::sphere(DVec3::ZERO, 1.0)) else { return Vec::new() };
    let points = parameters(1_000_000);
    let frames = parameters(100_000);
    let s1 = surface.clone();
    let grid = GridOptions { segments_u: 1000, segments_v: 1000, ..Default::default() };
    vec![
        Operation::new("nurbs_point_tangents_1m", move || {
            let mut acc = DVec3::ZERO;
            for &(u, v) in &points {
                let [p, su, sv] = s1.point_and_tangents(u, v)?;
                acc += p + su + sv;
            }
            Ok(acc)
        }),
        Operation::new("nurbs_frames_100k", move || {
            let mut acc = 0.0;
            for &(u, v) in &frames {
                let f = SurfaceFrame::new(&surface, u, v)?;
                acc += f.mean + f.gaussian;
            }
            Ok(acc)
        }),
        Operation::new("nurbs_tessellate_1000x1000", move || Ok(tessellate(&sphere, &grid)?)),
    ]
}
