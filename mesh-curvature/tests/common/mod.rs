//! Shared helpers of the integration tests: analytic surfaces with their
//! exact curvature per vertex, the shared real meshes, and error measures.
#![allow(dead_code)]

use std::f64::consts::TAU;

use mesh_curvature::CurvatureTensor;
use mesh_kernel::glam::DVec3;
use mesh_kernel::{shapes, TriMesh};

/// Exact curvature per vertex: principal curvatures, the k1 direction where
/// it is defined (not at umbilics), and which vertices to check.
pub struct Truth {
    pub k1: Vec<f64>,
    pub k2: Vec<f64>,
    pub d1: Vec<Option<DVec3>>,
    pub check: Vec<bool>,
}

/// Unit icosphere: k1 = k2 = 1 everywhere.
pub fn sphere(level: u32) -> (TriMesh, Truth) {
    let m = shapes::icosphere(level).unwrap();
    let n = m.vertex_count();
    (m, Truth { k1: vec![1.0; n], k2: vec![1.0; n], d1: vec![None; n], check: vec![true; n] })
}

/// Torus R = 2, r = 0.5 on an `nu` x `nv` grid, vertex `i nv + j` at
/// u = 2 pi i / nu, v = 2 pi j / nv (documented by mesh-kernel): k1 = 1 / r
/// around the tube, k2 = cos v / (R + r cos v) along it.
pub fn torus(nu: usize, nv: usize) -> (TriMesh, Truth) {
    let (big, r) = (2.0, 0.5);
    let m = shapes::torus(big, r, nu, nv).unwrap();
    let mut t = Truth { k1: vec![], k2: vec![], d1: vec![], check: vec![] };
    for i in 0..nu {
        let u = TAU * i as f64 / nu as f64;
        for j in 0..nv {
            let v = TAU * j as f64 / nv as f64;
            t.k1.push(1.0 / r);
            t.k2.push(v.cos() / (big + r * v.cos()));
            t.d1.push(Some(DVec3::new(-v.sin() * u.cos(), -v.sin() * u.sin(), v.cos())));
            t.check.push(true);
        }
    }
    (m, t)
}

/// Open unit cylinder of height 2: k1 = 1 around, k2 = 0 along the axis;
/// checked on the vertices at least `margin` rings from either boundary.
pub fn cylinder(around: usize, along: usize, margin: usize) -> (TriMesh, Truth) {
    let m = shapes::cylinder(1.0, 2.0, around, along).unwrap();
    let mut t = Truth { k1: vec![], k2: vec![], d1: vec![], check: vec![] };
    for i in 0..around {
        let a = TAU * i as f64 / around as f64;
        for j in 0..=along {
            t.k1.push(1.0);
            t.k2.push(0.0);
            t.d1.push(Some(DVec3::new(-a.sin(), a.cos(), 0.0)));
            t.check.push(j >= margin && j + margin <= along);
        }
    }
    (m, t)
}

/// Ellipsoid x^2/a^2 + y^2/b^2 + z^2/c^2 = 1 from a scaled icosphere: an
/// irregular, anisotropic triangulation with exact K and H (principal
/// curvatures from them).
pub fn ellipsoid(level: u32, [a, b, c]: [f64; 3]) -> (TriMesh, Truth) {
    let s = shapes::icosphere(level).unwrap();
    let p: Vec<DVec3> = s.positions().iter().map(|p| DVec3::new(a * p.x, b * p.y, c * p.z)).collect();
    let m = TriMesh::new(p.clone(), s.faces().to_vec()).unwrap();
    let mut t = Truth { k1: vec![], k2: vec![], d1: vec![], check: vec![] };
    for q in &p {
        let g = DVec3::new(q.x / (a * a), q.y / (b * b), q.z / (c * c));
        let g2 = g.length_squared();
        let k = 1.0 / ((a * b * c).powi(2) * g2 * g2);
        let h = (a * a + b * b + c * c - q.length_squared()) / (2.0 * (a * b * c).powi(2) * g2.powf(1.5));
        let disc = (h * h - k).max(0.0).sqrt();
        t.k1.push(h + disc);
        t.k2.push(h - disc);
        t.d1.push(None);
        t.check.push(true);
    }
    (m, t)
}

/// Icosphere whose vertices are moved tangentially by up to `amount` of the
/// edge length and put back on the unit sphere (deterministic).
pub fn jittered_sphere(level: u32, amount: f64, seed: u64) -> (TriMesh, Truth) {
    let (m, t) = sphere(level);
    let h = 1.1 / 2f64.powi(level as i32);
    let mut rng = mesh_testkit::SplitMix64::new(seed);
    let mut rnd = || rng.signed();
    let p = m.positions().iter().map(|p| (*p + amount * h * DVec3::new(rnd(), rnd(), rnd())).normalize()).collect();
    (TriMesh::new(p, m.faces().to_vec()).unwrap(), t)
}

/// Largest errors of a tensor against the truth, over the checked vertices.
#[derive(Debug, Clone, Copy, Default)]
pub struct Errors {
    pub k1: f64,
    pub k2: f64,
    pub gaussian: f64,
    pub mean: f64,
    /// Largest angle between d1 and the true direction, in degrees.
    pub degrees: f64,
}

pub fn errors(t: &CurvatureTensor, truth: &Truth) -> Errors {
    let mut e = Errors::default();
    for i in 0..t.len() {
        if !truth.check[i] {
            continue;
        }
        e.k1 = e.k1.max((t.k1[i] - truth.k1[i]).abs());
        e.k2 = e.k2.max((t.k2[i] - truth.k2[i]).abs());
        e.gaussian = e.gaussian.max((t.k1[i] * t.k2[i] - truth.k1[i] * truth.k2[i]).abs());
        e.mean = e.mean.max((0.5 * (t.k1[i] + t.k2[i]) - 0.5 * (truth.k1[i] + truth.k2[i])).abs());
        if let Some(d) = truth.d1[i] {
            e.degrees = e.degrees.max(t.d1[i].dot(d).abs().min(1.0).acos().to_degrees());
        }
    }
    e
}

/// A triangle soup from proptest's draws: points, faces as index triples
/// (taken modulo the point count, repeated corners dropped), optionally
/// snapped to a coarse lattice, which makes coincident and collinear points.
pub fn soup(points: &[(f64, f64, f64)], faces: &[(usize, usize, usize)], snap: bool) -> TriMesh {
    let n = points.len();
    let p: Vec<DVec3> = points
        .iter()
        .map(|&(x, y, z)| {
            let q = DVec3::new(x, y, z);
            if snap {
                (q * 2.0).round() / 2.0
            } else {
                q
            }
        })
        .collect();
    let f: Vec<[u32; 3]> = faces
        .iter()
        .map(|&(a, b, c)| [a % n, b % n, c % n].map(|x| x as u32))
        .filter(|[a, b, c]| a != b && b != c && a != c)
        .collect();
    TriMesh::new(p, f).unwrap()
}

/// Observed convergence order between two errors at mesh sizes h and h / ratio.
pub fn order(coarse: f64, fine: f64, ratio: f64) -> f64 {
    (coarse / fine).ln() / ratio.ln()
}

/// Every shared mesh by file name, read with the test kit's minimal reader
/// (so the tests do not depend on another crate); empty when the data is
/// absent (see `mesh_testkit::data`).
pub fn data_meshes() -> Vec<(String, TriMesh)> {
    let tri =
        |raw: mesh_testkit::RawMesh| TriMesh::new(raw.positions.into_iter().map(DVec3::from).collect(), raw.faces);
    mesh_testkit::shared_meshes().into_iter().map(|(name, raw)| (name.to_string(), tri(raw).unwrap())).collect()
}
