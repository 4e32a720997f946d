//! Procedural test shapes with exactly known geometry and topology.
//!
//! Every constructor returns a manifold, consistently oriented mesh (closed
//! shapes face outward) and documents its ground truth: vertex and face
//! counts, Euler characteristic, and the analytic surface the vertices lie on.
//! Resolutions are validated and give [`MeshError::InvalidOption`] when out of
//! range (too coarse to be a surface, or beyond 32-bit indices).

use std::f64::consts::{PI, TAU};

use glam::{DVec2, DVec3};

use crate::error::{MeshError, Result};
use crate::mesh::TriMesh;
use crate::random::SplitMix64;

/// Largest vertex count a procedural shape may have (about 1.3e8).
const MAX_VERTICES: u128 = 1 << 27;

fn check_count(name: &'static str, vertices: u128) -> Result<()> {
    if vertices > MAX_VERTICES {
        return Err(MeshError::InvalidOption { name, reason: format!("{vertices} vertices is too many") });
    }
    Ok(())
}

fn check_min(name: &'static str, value: usize, min: usize) -> Result<()> {
    if value < min {
        return Err(MeshError::InvalidOption { name, reason: format!("must be at least {min}, got {value}") });
    }
    Ok(())
}

fn check_positive(name: &'static str, value: f64) -> Result<()> {
    if !(value > 0.0 && value.is_finite()) {
        return Err(MeshError::InvalidOption { name, reason: format!("must be positive and finite, got {value}") });
    }
    Ok(())
}

/// Unit icosphere: the icosahedron with each face split 4-to-1 `level` times,
/// new vertices projected onto the unit sphere.
///
/// Truth: all vertices on |x| = 1; V = 10 * 4^level + 2, F = 20 * 4^level,
/// chi = 2, genus 0. Level 5 has 10,242 vertices; level 8, 655,362.
///
/// # Errors
/// [`MeshError::InvalidOption`] for a level whose vertex count would exceed the shapes' limit.
pub fn icosphere(level: u32) -> Result<TriMesh> {
    if level > 12 {
        return Err(MeshError::InvalidOption { name: "level", reason: format!("{level} is above 12") });
    }
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let mut positions: Vec<DVec3> = [
        (-1.0, t, 0.0),
        (1.0, t, 0.0),
        (-1.0, -t, 0.0),
        (1.0, -t, 0.0),
        (0.0, -1.0, t),
        (0.0, 1.0, t),
        (0.0, -1.0, -t),
        (0.0, 1.0, -t),
        (t, 0.0, -1.0),
        (t, 0.0, 1.0),
        (-t, 0.0, -1.0),
        (-t, 0.0, 1.0),
    ]
    .iter()
    .map(|&(x, y, z)| DVec3::new(x, y, z).normalize())
    .collect();
    let mut faces: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..level {
        let mesh = TriMesh::new(positions, faces)?;
        let (p, f) = midpoint_subdivide(&mesh);
        positions = p.into_iter().map(|x| x.normalize()).collect();
        faces = f;
    }
    TriMesh::new(positions, faces)
}

/// One step of 4-to-1 midpoint splitting (the chapter's figure 2.13): returns the old
/// vertices followed by one new vertex per edge (in [`crate::Connectivity`]
/// edge order, at the edge midpoint), and four faces per face: the three
/// corner triangles of face `f` at `4 f`, `4 f + 1`, `4 f + 2` and the
/// middle one at `4 f + 3`. Cost O(V + F); the new positions and faces
/// are filled on [`crate::par`]'s threads.
pub fn midpoint_subdivide(mesh: &TriMesh) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let (edges, halfedge_edge) = crate::connectivity::number_edges(mesh);
    let n = mesh.vertex_count() as u32;
    let p = mesh.positions();
    let positions = crate::par::map(p.len() + edges.len(), |i| match i.checked_sub(p.len()) {
        None => p[i],
        Some(e) => {
            let [a, b] = edges[e];
            (p[a as usize] + p[b as usize]) * 0.5
        }
    });
    let faces = mesh.faces();
    let faces = crate::par::map(faces.len(), |f| {
        let [a, b, c] = faces[f];
        let e = &halfedge_edge[3 * f..3 * f + 3];
        let [eab, ebc, eca] = [n + e[0], n + e[1], n + e[2]];
        [[a, eab, eca], [b, ebc, eab], [c, eca, ebc], [eab, ebc, eca]]
    })
    .into_flattened();
    (positions, faces)
}

/// Latitude-longitude sphere of radius `radius` with `segments` meridians and
/// `rings` latitude bands; single pole vertices with triangle fans.
///
/// Truth: |x| = radius; V = segments (rings - 1) + 2, F = 2 segments (rings - 1),
/// chi = 2.
///
/// # Errors
/// [`MeshError::InvalidOption`] for a radius that is not positive and finite, too few segments or
/// rings, or too many vertices.
pub fn uv_sphere(radius: f64, segments: usize, rings: usize) -> Result<TriMesh> {
    check_positive("radius", radius)?;
    check_min("segments", segments, 3)?;
    check_min("rings", rings, 2)?;
    check_count("segments * rings", segments as u128 * rings as u128)?;
    let mut positions = vec![DVec3::new(0.0, 0.0, radius)];
    for i in 1..rings {
        let theta = PI * i as f64 / rings as f64;
        for j in 0..segments {
            let phi = TAU * j as f64 / segments as f64;
            positions.push(radius * DVec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos()));
        }
    }
    positions.push(DVec3::new(0.0, 0.0, -radius));
    let s = segments as u32;
    let south = positions.len() as u32 - 1;
    let ring = |i: u32, j: u32| 1 + i * s + j % s;
    let mut faces = Vec::with_capacity(2 * segments * (rings - 1));
    for j in 0..s {
        faces.push([0, ring(0, j), ring(0, j + 1)]);
    }
    for i in 0..rings as u32 - 2 {
        for j in 0..s {
            let (a, b, c, d) = (ring(i, j), ring(i + 1, j), ring(i + 1, j + 1), ring(i, j + 1));
            faces.push([a, b, c]);
            faces.push([a, c, d]);
        }
    }
    for j in 0..s {
        let last = rings as u32 - 2;
        faces.push([south, ring(last, j + 1), ring(last, j)]);
    }
    TriMesh::new(positions, faces)
}

/// Torus with major radius `major` (centre to tube centre) and minor radius
/// `minor`, around the z axis, on a `nu` x `nv` grid (u around the axis, v
/// around the tube). Vertex `i * nv + j` sits at u = 2 pi i / nu, v = 2 pi j / nv:
/// ((R + r cos v) cos u, (R + r cos v) sin u, r sin v).
///
/// Truth: V = nu nv, F = 2 nu nv, chi = 0, genus 1. Principal curvatures
/// 1/r (around the tube) and cos v / (R + r cos v) (along it); Gaussian
/// curvature cos v / (r (R + r cos v)).
///
/// # Errors
/// [`MeshError::InvalidOption`] for radii that are not positive and finite (or a minor radius not
/// below the major), too few segments, or too many vertices.
pub fn torus(major: f64, minor: f64, nu: usize, nv: usize) -> Result<TriMesh> {
    check_positive("major", major)?;
    check_positive("minor", minor)?;
    if minor >= major {
        return Err(MeshError::InvalidOption {
            name: "minor",
            reason: format!("minor radius {minor} must be below the major radius {major}"),
        });
    }
    check_min("nu", nu, 3)?;
    check_min("nv", nv, 3)?;
    check_count("nu * nv", nu as u128 * nv as u128)?;
    let positions = (0..nu)
        .flat_map(|i| {
            let u = TAU * i as f64 / nu as f64;
            (0..nv).map(move |j| {
                let v = TAU * j as f64 / nv as f64;
                let rho = major + minor * v.cos();
                DVec3::new(rho * u.cos(), rho * u.sin(), minor * v.sin())
            })
        })
        .collect();
    let faces = periodic_grid_faces(nu, nv, true);
    TriMesh::new(positions, faces)
}

/// An irregular torus: [`torus`] with the (u, v) grid parameters of every
/// vertex jittered by up to `jitter` of a grid step (deterministically from
/// `seed`) and each quad split along a random diagonal, so triangles are
/// needles, obtuse and of varying valence, while every vertex stays exactly
/// on the surface. Vertex `i * nv + j` sits near u = 2 pi i / nu,
/// v = 2 pi j / nv; its exact curvature follows from its position (see
/// [`torus`]: v = atan2(z, |(x, y)| - R)). `jitter` must lie in [0, 0.5).
///
/// Truth: as [`torus`] (V = nu nv, F = 2 nu nv, chi = 0, genus 1).
///
/// # Errors
/// [`MeshError::InvalidOption`] for a jitter outside `[0, 0.5)`, and those of [`torus`].
pub fn irregular_torus(major: f64, minor: f64, nu: usize, nv: usize, jitter: f64, seed: u64) -> Result<TriMesh> {
    if !(0.0..0.5).contains(&jitter) {
        return Err(MeshError::InvalidOption { name: "jitter", reason: format!("{jitter} is not in [0, 0.5)") });
    }
    let regular = torus(major, minor, nu, nv)?;
    let mut rng = SplitMix64::new(seed);
    let (du, dv) = (TAU / nu as f64, TAU / nv as f64);
    let positions = (0..nu * nv)
        .map(|k| {
            let u = (k / nv) as f64 * du + jitter * du * rng.signed();
            let v = (k % nv) as f64 * dv + jitter * dv * rng.signed();
            let rho = major + minor * v.cos();
            DVec3::new(rho * u.cos(), rho * u.sin(), minor * v.sin())
        })
        .collect();
    // Each quad [a, b, c], [a, c, d] becomes [a, b, d], [b, c, d] on a coin flip.
    let mut faces = regular.into_parts().1;
    for quad in faces.chunks_exact_mut(2) {
        if rng.next_u64() & 1 == 1 {
            let ([a, b, c], d) = (quad[0], quad[1][2]);
            quad[0] = [a, b, d];
            quad[1] = [b, c, d];
        }
    }
    TriMesh::new(positions, faces)
}

/// Triangles of an `nu` x `nv` grid with vertex `i * nv + j`, periodic in `i`
/// and, when `wrap_j`, in `j`; counter-clockwise in the (i, j) plane.
fn periodic_grid_faces(nu: usize, nv: usize, wrap_j: bool) -> Vec<[u32; 3]> {
    let (nu32, nv32) = (nu as u32, nv as u32);
    let id = |i: u32, j: u32| (i % nu32) * nv32 + (j % nv32);
    let jmax = if wrap_j { nv32 } else { nv32 - 1 };
    let mut faces = Vec::with_capacity(2 * nu * nv);
    for i in 0..nu32 {
        for j in 0..jmax {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            faces.push([a, b, c]);
            faces.push([a, c, d]);
        }
    }
    faces
}

/// Open cylinder of radius `radius` around the z axis, from z = 0 to
/// z = `height`, with `around` vertices per ring and `along` + 1 rings.
/// Vertex `i * (along + 1) + j` is at angle 2 pi i / around, height j / along.
///
/// Truth: V = around (along + 1), F = 2 around along, chi = 0, two boundary
/// loops, genus 0; principal curvatures 1/radius and 0, normals outward.
///
/// # Errors
/// [`MeshError::InvalidOption`] for a radius or height that is not positive and finite, or too few
/// segments.
pub fn cylinder(radius: f64, height: f64, around: usize, along: usize) -> Result<TriMesh> {
    check_positive("radius", radius)?;
    check_positive("height", height)?;
    check_min("around", around, 3)?;
    check_min("along", along, 1)?;
    check_count("around * along", (around as u128).saturating_mul(along as u128 + 1))?;
    let positions = (0..around)
        .flat_map(|i| {
            let a = TAU * i as f64 / around as f64;
            (0..=along).map(move |j| DVec3::new(radius * a.cos(), radius * a.sin(), height * j as f64 / along as f64))
        })
        .collect();
    let faces = periodic_grid_faces(around, along + 1, false);
    TriMesh::new(positions, faces)
}

/// Planar rectangle [0, width] x [0, height] in the z = 0 plane, split into
/// `nx` x `ny` squares of two triangles each (normal +z).
/// Vertex `j * (nx + 1) + i` is at (width i / nx, height j / ny).
///
/// Truth: V = (nx + 1)(ny + 1), F = 2 nx ny, chi = 1, one boundary loop.
///
/// # Errors
/// [`MeshError::InvalidOption`] for a size that is not positive and finite, or fewer than one cell
/// along a side.
pub fn grid(width: f64, height: f64, nx: usize, ny: usize) -> Result<TriMesh> {
    check_positive("width", width)?;
    check_positive("height", height)?;
    check_min("nx", nx, 1)?;
    check_min("ny", ny, 1)?;
    check_count("nx * ny", (nx as u128 + 1).saturating_mul(ny as u128 + 1))?;
    let positions = (0..=ny)
        .flat_map(|j| {
            (0..=nx).map(move |i| DVec3::new(width * i as f64 / nx as f64, height * j as f64 / ny as f64, 0.0))
        })
        .collect();
    let w = nx as u32 + 1;
    let mut faces = Vec::with_capacity(2 * nx * ny);
    for j in 0..ny as u32 {
        for i in 0..nx as u32 {
            let (a, b, c, d) = (j * w + i, j * w + i + 1, (j + 1) * w + i + 1, (j + 1) * w + i);
            faces.push([a, b, c]);
            faces.push([a, c, d]);
        }
    }
    TriMesh::new(positions, faces)
}

/// Unstructured flat unit disk in the z = 0 plane: `rings` concentric rings
/// of 6 k vertices (k = 1..rings) around a centre vertex, interior vertices
/// jittered deterministically (from `seed`) by up to 30% of the ring spacing,
/// so triangles are irregular and some obtuse. Boundary vertices lie exactly
/// on the unit circle.
///
/// Truth: V = 1 + 3 rings (rings + 1), F = 6 rings^2, chi = 1, one boundary
/// loop, area -> pi and boundary length -> 2 pi under refinement; normal +z.
///
/// # Errors
/// [`MeshError::InvalidOption`] for `rings = 0` or too many vertices.
pub fn disk(rings: usize, seed: u64) -> Result<TriMesh> {
    check_min("rings", rings, 1)?;
    check_count("rings^2", (3 * rings as u128).saturating_mul(rings as u128 + 1))?;
    let h = 1.0 / rings as f64;
    let mut rng = SplitMix64::new(seed);
    let mut positions = vec![DVec3::ZERO];
    let mut ring_start = vec![0usize, 1];
    for k in 1..=rings {
        let count = 6 * k;
        for i in 0..count {
            let a = TAU * i as f64 / count as f64;
            let mut p = DVec2::new(a.cos(), a.sin()) * (k as f64 * h);
            if k < rings {
                p += DVec2::new(rng.signed(), rng.signed()) * (0.3 * h);
            }
            positions.push(p.extend(0.0));
        }
        ring_start.push(positions.len());
    }
    // Stitch ring k-1 (6(k-1) vertices, or the centre) to ring k (6k vertices):
    // walk both rings by angle, always advancing the one whose next vertex
    // comes first.
    let mut faces = Vec::with_capacity(6 * rings * rings);
    for k in 1..=rings {
        let inner: Vec<u32> = (ring_start[k - 1]..ring_start[k]).map(|v| v as u32).collect();
        let outer: Vec<u32> = (ring_start[k]..ring_start[k + 1]).map(|v| v as u32).collect();
        let (ni, no) = (inner.len(), outer.len());
        let (mut i, mut o) = (0usize, 0usize);
        let centre = ni == 1;
        while o < no || (!centre && i < ni) {
            let ai = (i + 1) as f64 / ni as f64;
            let ao = (o + 1) as f64 / no as f64;
            if o < no && (centre || i == ni || ao <= ai) {
                faces.push([inner[i % ni], outer[o], outer[(o + 1) % no]]);
                o += 1;
            } else {
                faces.push([inner[i % ni], outer[o % no], inner[(i + 1) % ni]]);
                i += 1;
            }
        }
    }
    TriMesh::new(positions, faces)
}

/// Axis-aligned cube [-1, 1]^3 with each face split into `n` x `n` squares of
/// two triangles, welded along the edges.
///
/// Truth: V = 6 n^2 + 2, F = 12 n^2, chi = 2, area 24, volume 8; twelve
/// feature edges chains of dihedral angle pi/2.
///
/// # Errors
/// [`MeshError::InvalidOption`] for `n = 0` or too many vertices.
pub fn cube(n: usize) -> Result<TriMesh> {
    check_min("n", n, 1)?;
    check_count("n^2", (6 * n as u128).saturating_mul(n as u128))?;
    let mut positions = Vec::new();
    let mut faces = Vec::new();
    // For each face: outward normal axis and two tangent axes with t1 x t2 = normal.
    let sides = [
        (DVec3::X, DVec3::Y, DVec3::Z),
        (-DVec3::X, DVec3::Z, DVec3::Y),
        (DVec3::Y, DVec3::Z, DVec3::X),
        (-DVec3::Y, DVec3::X, DVec3::Z),
        (DVec3::Z, DVec3::X, DVec3::Y),
        (-DVec3::Z, DVec3::Y, DVec3::X),
    ];
    for (normal, t1, t2) in sides {
        let base = positions.len() as u32;
        let w = n as u32 + 1;
        for j in 0..=n {
            for i in 0..=n {
                let s = -1.0 + 2.0 * i as f64 / n as f64;
                let t = -1.0 + 2.0 * j as f64 / n as f64;
                positions.push(normal + s * t1 + t * t2);
            }
        }
        for j in 0..n as u32 {
            for i in 0..n as u32 {
                let (a, b, c, d) = (j * w + i, j * w + i + 1, (j + 1) * w + i + 1, (j + 1) * w + i);
                faces.push([base + a, base + b, base + c]);
                faces.push([base + a, base + c, base + d]);
            }
        }
    }
    let (positions, faces, _) = crate::clean::weld_vertices(&positions, &faces, 0.0)?;
    TriMesh::new(positions, faces)
}

/// The names accepted by [`by_name`], for command-line help.
pub const SHAPE_NAMES: &[&str] = &["icosphere", "uv-sphere", "torus", "cylinder", "grid", "disk", "cube"];

/// A built-in shape by name at a resolution `n` (meaning per shape: the
/// icosphere level, or the number of segments / rings / cells), with the
/// canonical sizes used in the documentation: unit sphere, torus R = 2,
/// r = 0.5, unit cylinder of height 2, unit square grid, unit disk, cube
/// [-1, 1]^3.
///
/// # Errors
/// [`MeshError::InvalidOption`] for an unknown name, and those of the shape's own function.
pub fn by_name(name: &str, n: usize) -> Result<TriMesh> {
    match name {
        "icosphere" => icosphere(u32::try_from(n).unwrap_or(u32::MAX)),
        "uv-sphere" => uv_sphere(1.0, 2 * n, n),
        "torus" => torus(2.0, 0.5, 4 * n, n),
        "cylinder" => cylinder(1.0, 2.0, n, n),
        "grid" => grid(1.0, 1.0, n, n),
        "disk" => disk(n, 1),
        "cube" => cube(n),
        _ => Err(MeshError::InvalidOption {
            name: "shape",
            reason: format!("unknown shape `{name}`; known: {}", SHAPE_NAMES.join(", ")),
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(mesh: &TriMesh, v: usize, f: usize, chi: i64, loops: usize, genus: u64) {
        let c = mesh.connectivity();
        assert!(c.is_manifold(), "{}", c.non_manifold_report());
        assert_eq!((mesh.vertex_count(), mesh.face_count()), (v, f));
        assert_eq!(c.euler_characteristic(), chi);
        assert_eq!(c.boundary_loop_count(), Some(loops));
        assert_eq!(c.genus(), Some(genus));
        assert_eq!(c.components().count, 1);
    }

    fn signed_volume(mesh: &TriMesh) -> f64 {
        mesh.face_ids()
            .map(|f| {
                let [a, b, c] = mesh.triangle(f);
                a.dot(b.cross(c)) / 6.0
            })
            .sum()
    }

    #[test]
    fn icosphere_counts() {
        for level in 0..4 {
            let m = icosphere(level).unwrap();
            let k = 4usize.pow(level);
            check(&m, 10 * k + 2, 20 * k, 2, 0, 0);
            assert!(m.positions().iter().all(|p| (p.length() - 1.0).abs() < 1e-14));
            assert!(signed_volume(&m) > 0.0);
        }
    }

    #[test]
    fn uv_sphere_counts() {
        let m = uv_sphere(2.0, 12, 6).unwrap();
        check(&m, 12 * 5 + 2, 2 * 12 * 5, 2, 0, 0);
        assert!(signed_volume(&m) > 0.0);
    }

    #[test]
    fn irregular_torus_stays_on_the_surface() {
        let m = irregular_torus(2.0, 0.5, 64, 16, 0.4, 7).unwrap();
        check(&m, 1024, 2048, 0, 0, 1);
        assert!(signed_volume(&m) > 0.0);
        let flipped = m.faces().iter().zip(torus(2.0, 0.5, 64, 16).unwrap().faces()).filter(|(a, b)| a != b).count();
        assert!(flipped > 500 && flipped < 1548, "{flipped} faces on the other diagonal");
        for p in m.positions() {
            let rho = (p.x * p.x + p.y * p.y).sqrt();
            assert!(((rho - 2.0).hypot(p.z) - 0.5).abs() < 1e-12);
        }
        let areas = crate::geometry::face_areas(&m);
        assert!(areas.iter().all(|a| *a > 0.0));
        assert!(irregular_torus(2.0, 0.5, 8, 8, 0.5, 0).is_err());
    }

    #[test]
    fn torus_counts() {
        let m = torus(2.0, 0.5, 16, 8).unwrap();
        check(&m, 128, 256, 0, 0, 1);
        assert!(signed_volume(&m) > 0.0);
        assert!(torus(1.0, 2.0, 8, 8).is_err());
    }

    #[test]
    fn cylinder_counts() {
        let m = cylinder(1.0, 2.0, 16, 4).unwrap();
        check(&m, 16 * 5, 2 * 16 * 4, 0, 2, 0);
        // Outward: the first face's normal points away from the axis.
        let [a, b, c] = m.triangle(crate::FaceId(0));
        let n = (b - a).cross(c - a);
        let centre = (a + b + c) / 3.0;
        assert!(n.dot(DVec3::new(centre.x, centre.y, 0.0)) > 0.0);
    }

    #[test]
    fn grid_and_disk_counts() {
        check(&grid(1.0, 1.0, 4, 3).unwrap(), 20, 24, 1, 1, 0);
        for rings in [1, 2, 5, 9] {
            let m = disk(rings, 7).unwrap();
            check(&m, 1 + 3 * rings * (rings + 1), 6 * rings * rings, 1, 1, 0);
            for f in m.face_ids() {
                let [a, b, c] = m.triangle(f);
                assert!((b - a).cross(c - a).z > 0.0, "face {f} of disk({rings}) is flipped");
            }
        }
    }

    #[test]
    fn cube_counts() {
        let m = cube(3).unwrap();
        check(&m, 6 * 9 + 2, 12 * 9, 2, 0, 0);
        assert!((signed_volume(&m) - 8.0).abs() < 1e-12);
    }

    #[test]
    fn bad_resolutions_are_errors() {
        assert!(icosphere(40).is_err());
        assert!(uv_sphere(1.0, 2, 2).is_err());
        assert!(uv_sphere(f64::NAN, 8, 8).is_err());
        assert!(grid(1.0, 1.0, 0, 3).is_err());
        assert!(grid(1.0, 1.0, usize::MAX, usize::MAX).is_err());
        assert!(by_name("teapot", 3).is_err());
    }
}
