//! The rows of the dirty-mesh matrix: meshes built in code, each with a
//! known defect (or none, for the control and the shapes the scaled copies
//! are compared with).

use std::f64::consts::TAU;

use mesh_kernel::glam::DVec3;
use mesh_kernel::{shapes, TriMesh};
use mesh_wavelet::{Scheme, SubdivideOptions};

/// How a row's results are judged.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Kind {
    /// Every operation must succeed.
    Control,
    /// A result must pass the operation's check; an error is acceptable.
    Dirty,
    /// Row `base` scaled by `scale`: the same answer as that row, rescaled.
    Scaled {
        /// Name of the unscaled row (listed earlier).
        base: &'static str,
        /// The factor applied to every coordinate.
        scale: f64,
    },
}

/// One row.
pub struct Row {
    /// Short name for the table.
    pub name: &'static str,
    /// The mesh, or why it could not be built (a failed check).
    pub mesh: Result<TriMesh, String>,
    /// How results are judged.
    pub kind: Kind,
}

fn build(positions: Vec<DVec3>, faces: Vec<[u32; 3]>) -> Result<TriMesh, String> {
    TriMesh::new(positions, faces).map_err(|e| e.to_string())
}

fn scaled(mesh: &Result<TriMesh, String>, s: f64) -> Result<TriMesh, String> {
    let m = mesh.as_ref().map_err(Clone::clone)?;
    build(m.positions().iter().map(|p| *p * s).collect(), m.faces().to_vec())
}

/// The icosphere of level 2 (162 vertices) with a few faces reversed.
fn flipped() -> Result<TriMesh, String> {
    let m = shapes::icosphere(2).map_err(|e| e.to_string())?;
    let mut faces = m.faces().to_vec();
    for f in [0, 57, 200] {
        faces[f].swap(1, 2);
    }
    build(m.positions().to_vec(), faces)
}

/// The icosphere with three vertices no face uses.
fn isolated() -> Result<TriMesh, String> {
    let m = shapes::icosphere(2).map_err(|e| e.to_string())?;
    let mut p = m.positions().to_vec();
    p.extend([DVec3::splat(3.0), DVec3::new(-2.0, 0.5, 0.0), DVec3::ZERO]);
    build(p, m.faces().to_vec())
}

/// A Moebius strip: 24 steps around, 2 across, glued with a half twist.
fn moebius() -> Result<TriMesh, String> {
    let (n, w) = (24usize, 2usize);
    let mut p = Vec::new();
    for i in 0..n {
        let u = TAU * i as f64 / n as f64;
        for j in 0..=w {
            let v = -0.4 + 0.8 * j as f64 / w as f64;
            let r = 1.0 + v * (u / 2.0).cos();
            p.push(DVec3::new(r * u.cos(), r * u.sin(), v * (u / 2.0).sin()));
        }
    }
    let at = |i: usize, j: usize| -> u32 {
        // Past the last step the strip comes back flipped across.
        if i == n {
            (w - j) as u32
        } else {
            (i * (w + 1) + j) as u32
        }
    };
    let mut faces = Vec::new();
    for i in 0..n {
        for j in 0..w {
            faces.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            faces.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    build(p, faces)
}

/// A 4 x 4 grid whose right half uses copies of the seam's vertices
/// (coincident, unwelded), and with three faces listed twice.
fn duplicates() -> Result<TriMesh, String> {
    let g = shapes::grid(1.0, 1.0, 4, 4).map_err(|e| e.to_string())?;
    let mut p = g.positions().to_vec();
    let seam: Vec<usize> = (0..p.len()).filter(|&i| (p[i].x - 0.5).abs() < 1e-12).collect();
    let mut copy = vec![u32::MAX; p.len()];
    for &i in &seam {
        copy[i] = p.len() as u32;
        p.push(p[i]);
    }
    let mut faces: Vec<[u32; 3]> = g
        .faces()
        .iter()
        .map(|f| {
            let right = f.iter().map(|&v| p[v as usize].x).sum::<f64>() / 3.0 > 0.5;
            f.map(|v| if right && copy[v as usize] != u32::MAX { copy[v as usize] } else { v })
        })
        .collect();
    faces.extend_from_within(..3);
    build(p, faces)
}

/// The control: a wavy disk with subdivision connectivity (a 2 x 2 grid
/// split twice by the midpoint rule, 81 vertices), on which every
/// operation is defined.
fn control() -> Result<TriMesh, String> {
    let base = shapes::grid(1.0, 1.0, 2, 2).map_err(|e| e.to_string())?;
    let mut m = mesh_wavelet::subdivide(&base, &SubdivideOptions { scheme: Scheme::Midpoint, levels: 2 })
        .map_err(|e| e.to_string())?;
    for q in m.positions_mut() {
        q.z = 0.1 * (3.0 * q.x).sin() * (2.0 * q.y).cos();
    }
    Ok(m)
}

/// Row `base` scaled by `scale`.
fn scale_row(name: &'static str, mesh: &Result<TriMesh, String>, base: &'static str, scale: f64) -> Row {
    Row { name, mesh: scaled(mesh, scale), kind: Kind::Scaled { base, scale } }
}

/// Every row, unscaled shapes before their scaled copies: 1e150 and
/// 1e-150 (the target range, where every answer of the unscaled
/// mesh has a representable rescaled value), then 1e300 and 1e-300.
pub fn rows() -> Vec<Row> {
    let v = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
    let icosphere = shapes::icosphere(2).map_err(|e| e.to_string());
    let torus = shapes::torus(2.0, 0.5, 16, 8).map_err(|e| e.to_string());
    let dirty = |name, mesh| Row { name, mesh, kind: Kind::Dirty };
    vec![
        Row { name: "control", mesh: control(), kind: Kind::Control },
        dirty("empty", build(vec![], vec![])),
        dirty("triangle", build(vec![v(0., 0., 0.), v(1., 0., 0.), v(0., 1., 0.)], vec![[0, 1, 2]])),
        dirty(
            "disjoint",
            build(
                (0..3)
                    .flat_map(|k| [v(2. * k as f64, 0., 0.), v(2. * k as f64 + 1., 0., 0.), v(2. * k as f64, 1., 0.3)])
                    .collect(),
                vec![[0, 1, 2], [3, 4, 5], [6, 7, 8]],
            ),
        ),
        dirty(
            "bow-tie",
            build(
                vec![v(0., 0., 0.), v(1., 0., 0.), v(1., 1., 0.), v(-1., 0., 0.), v(-1., -1., 0.)],
                vec![[0, 1, 2], [0, 3, 4]],
            ),
        ),
        dirty(
            "fin",
            build(
                vec![v(0., 0., 0.), v(1., 0., 0.), v(0.5, 1., 0.), v(0.5, -1., 0.), v(0.5, 0., 1.)],
                vec![[0, 1, 2], [1, 0, 3], [0, 1, 4]],
            ),
        ),
        dirty(
            "degenerate",
            build((0..5).map(|i| v(i as f64, 2. * i as f64, 0.)).collect(), vec![[0, 1, 2], [1, 2, 3], [2, 3, 4]]),
        ),
        dirty("duplicates", duplicates()),
        dirty("moebius", moebius()),
        dirty("flipped", flipped()),
        dirty("isolated", isolated()),
        dirty("icosphere", icosphere.clone()),
        dirty("torus", torus.clone()),
        scale_row("ico*1e150", &icosphere, "icosphere", 1e150),
        scale_row("ico*1e-150", &icosphere, "icosphere", 1e-150),
        scale_row("torus*1e150", &torus, "torus", 1e150),
        scale_row("torus*1e-150", &torus, "torus", 1e-150),
        scale_row("ico*1e300", &icosphere, "icosphere", 1e300),
        scale_row("ico*1e-300", &icosphere, "icosphere", 1e-300),
        scale_row("torus*1e300", &torus, "torus", 1e300),
        scale_row("torus*1e-300", &torus, "torus", 1e-300),
    ]
}
