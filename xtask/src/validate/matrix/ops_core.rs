//! Columns of the matrix for mesh-kernel (connectivity, geometry, operators,
//! clean, submesh) and mesh-io (a write and read round trip per format and
//! variant).

use std::f64::consts::PI;

use mesh_io::{Format, PlyEncoding, PlyOptions, ReadOptions, StlEncoding, WriteOptions};
use mesh_kernel::clean::CleanOptions;
use mesh_kernel::geometry::{self, NormalWeighting};
use mesh_kernel::operators::{self, IntrinsicOptions, IntrinsicTriangulation, MassKind};
use mesh_kernel::TriMesh;

use super::check::{xyz, Out};
use super::Op;

/// The mesh-kernel and mesh-io columns.
pub const OPS: &[Op] = &[
    ("core", "connectivity", connectivity),
    ("core", "geometry", geometry_op),
    ("core", "cotan L", cotan),
    ("core", "mass", mass),
    ("core", "intrinsic L", intrinsic),
    ("core", "clean", clean_default),
    ("core", "clean manif.", clean_manifold),
    ("core", "largest comp.", largest),
    ("io", "obj", |m| round_trip(m, Format::Obj, WriteOptions::default())),
    ("io", "off", |m| round_trip(m, Format::Off, WriteOptions::default())),
    ("io", "ply bin f64", |m| round_trip(m, Format::Ply, WriteOptions::default())),
    ("io", "ply ascii", |m| round_trip(m, Format::Ply, ply(PlyEncoding::Ascii, true))),
    ("io", "ply bin f32", |m| round_trip(m, Format::Ply, ply(PlyEncoding::BinaryBigEndian, false))),
    ("io", "stl bin", |m| round_trip(m, Format::Stl, WriteOptions::default())),
    ("io", "stl ascii", |m| round_trip(m, Format::Stl, WriteOptions { stl: StlEncoding::Ascii, ..Default::default() })),
    ("io", "gltf", |m| round_trip(m, Format::Gltf, WriteOptions::default())),
    ("io", "glb", |m| round_trip(m, Format::Glb, WriteOptions::default())),
];

fn e(err: impl std::fmt::Display) -> String {
    err.to_string()
}

fn count(x: impl TryInto<i64>) -> f64 {
    x.try_into().map_or(-1.0, |v| v as f64)
}

/// Counts from the half-edge structure; edges, referenced vertices and
/// chi = V - E + F recounted here from the face list.
fn connectivity(m: &TriMesh) -> Result<Out, String> {
    let c = m.connectivity();
    let r = c.non_manifold_report();
    let chi = c.euler_characteristic();
    let mut edges: Vec<[u32; 2]> = m
        .faces()
        .iter()
        .flat_map(|f| [0, 1, 2].map(|k| [f[k].min(f[(k + 1) % 3]), f[k].max(f[(k + 1) % 3])]))
        .collect();
    edges.sort_unstable();
    edges.dedup();
    let mut used: Vec<u32> = m.faces().iter().flatten().copied().collect();
    used.sort_unstable();
    used.dedup();
    let recount = used.len() as i64 - edges.len() as i64 + m.face_count() as i64;
    let counts = vec![
        count(c.edge_count()),
        count(chi),
        count(c.components().count),
        c.boundary_loop_count().map_or(-1.0, |n| n as f64),
        c.genus().map_or(-1.0, |g| g as f64),
        count(r.edges.len()),
        count(r.vertices.len()),
        count(r.inconsistent_edges.len()),
    ];
    Ok(Out::default()
        .counts("E, chi, components, loops, genus, defects", counts)
        .require(c.edge_count() == edges.len(), || {
            format!("{} edges, {} in the face list", c.edge_count(), edges.len())
        })
        .require(chi == recount, || format!("chi {chi}, V - E + F of the face list {recount}")))
}

/// Face areas, corner angles (summing to pi on non-degenerate faces),
/// unit or zero vertex normals, the bounding box.
fn geometry_op(m: &TriMesh) -> Result<Out, String> {
    let areas = geometry::face_areas(m);
    let angles = geometry::corner_angles(m);
    let normals = geometry::vertex_normals(m, NormalWeighting::Area);
    let diagonal = geometry::bounding_box(m).map_or(0.0, |b| b.diagonal());
    let bad_sum =
        angles.iter().zip(&areas).position(|(a, area)| *area > 0.0 && (a.iter().sum::<f64>() - PI).abs() > 1e-9);
    let bad_normal = normals.iter().position(|n| n.length() != 0.0 && (n.length() - 1.0).abs() > 1e-9);
    Ok(Out::default()
        .field("face areas", 2, areas)
        .field("corner angles", 0, angles.iter().flatten().copied().collect())
        .field("vertex normals", 0, xyz(&normals))
        .field("surface area", 2, vec![geometry::surface_area(m)])
        .field("bounding box diagonal", 1, vec![diagonal])
        .require(bad_sum.is_none(), || format!("the angles of face {bad_sum:?} do not sum to pi"))
        .require(bad_normal.is_none(), || format!("vertex normal {bad_normal:?} is neither unit nor zero")))
}

/// Largest |entry|, asymmetry and row sum of a Laplacian, relative.
fn laplacian_defect(l: &mesh_kernel::sprs::CsMat<f64>) -> Option<String> {
    let max = l.data().iter().fold(0.0f64, |a, x| a.max(x.abs()));
    let t = l.transpose_view().to_csr();
    let asym = (l - &t).data().iter().fold(0.0f64, |a, x| a.max(x.abs()));
    let row = l.outer_iterator().map(|r| r.iter().map(|(_, x)| x).sum::<f64>().abs()).fold(0.0, f64::max);
    (asym > 1e-12 * max || row > 1e-12 * max)
        .then(|| format!("asymmetry {asym:e}, row sum {row:e}, largest entry {max:e}"))
}

fn cotan(m: &TriMesh) -> Result<Out, String> {
    let l = operators::cotan_laplacian(m);
    let defect = laplacian_defect(&l);
    Ok(Out::default().field("L entries", 0, l.data().to_vec()).require(defect.is_none(), || defect.unwrap_or_default()))
}

/// Mixed Voronoi masses sum to the surface area.
fn mass(m: &TriMesh) -> Result<Out, String> {
    let masses = operators::lumped_mass(m, MassKind::MixedVoronoi);
    let (sum, area) = (masses.iter().sum::<f64>(), geometry::surface_area(m));
    Ok(Out::default()
        .field("masses", 2, masses)
        .require((sum - area).abs() <= 1e-9 * area, || format!("masses sum to {sum:e}, area {area:e}")))
}

fn intrinsic(m: &TriMesh) -> Result<Out, String> {
    let t = IntrinsicTriangulation::delaunay(m, &IntrinsicOptions::default()).map_err(e)?;
    let l = t.cotan_laplacian();
    let weights = t.interior_edge_weights();
    let max = weights.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    let min = weights.iter().copied().fold(0.0, f64::min);
    let defect = laplacian_defect(&l);
    Ok(Out::default()
        .field("L entries", 0, l.data().to_vec())
        .counts("flips", vec![t.flip_count() as f64])
        .require(min >= -1e-9 * max, || format!("negative intrinsic Delaunay weight {min:e}"))
        .require(defect.is_none(), || defect.unwrap_or_default()))
}

fn clean_with(m: &TriMesh, options: &CleanOptions) -> Result<(TriMesh, Out), String> {
    let (c, report) = m.cleaned(options).map_err(e)?;
    let out = Out::default()
        .field("positions", 1, xyz(c.positions()))
        .counts("faces, report", [vec![c.face_count() as f64], report.counts().map(|n| n as f64).to_vec()].concat());
    Ok((c, out))
}

/// Default cleaning: nothing degenerate, duplicated or unreferenced is left.
fn clean_default(m: &TriMesh) -> Result<Out, String> {
    let (c, out) = clean_with(m, &CleanOptions::default())?;
    let degenerate = mesh_kernel::clean::degenerate_faces(&c, CleanOptions::default().degenerate_tolerance).len();
    let duplicates = mesh_kernel::clean::duplicate_faces(c.faces()).len();
    let unused = mesh_kernel::clean::unreferenced_vertices(c.vertex_count(), c.faces()).len();
    Ok(out.require(degenerate + duplicates + unused == 0, || {
        format!("left {degenerate} degenerate, {duplicates} duplicate faces, {unused} unreferenced vertices")
    }))
}

/// Manifold repair: the result is an oriented manifold.
fn clean_manifold(m: &TriMesh) -> Result<Out, String> {
    let (c, out) = clean_with(m, &CleanOptions { manifold: true, ..CleanOptions::default() })?;
    let manifold = c.manifold_connectivity().map(|_| ()).map_err(e);
    Ok(out.require(manifold.is_ok(), || format!("the repaired mesh is not manifold: {}", manifold.unwrap_err())))
}

/// The largest component: a connected piece with the most faces.
fn largest(m: &TriMesh) -> Result<Out, String> {
    let s = m.largest_component().map_err(e)?;
    let counts = m.connectivity().components();
    let most = (0..counts.count).map(|k| counts.face_component.iter().filter(|c| **c as usize == k).count()).max();
    Ok(Out::default()
        .field("positions", 1, xyz(s.mesh.positions()))
        .counts("faces", vec![s.mesh.face_count() as f64])
        .require(s.mesh.connectivity().components().count == 1, || "more than one component".into())
        .require(Some(s.mesh.face_count()) == most, || {
            format!("{} faces, the largest has {most:?}", s.mesh.face_count())
        }))
}

fn ply(encoding: PlyEncoding, double: bool) -> WriteOptions {
    WriteOptions { ply: PlyOptions { encoding, double, ..PlyOptions::default() }, ..WriteOptions::default() }
}

/// Writes and reads back. 64-bit formats must return the mesh exactly;
/// 32-bit ones (STL, glTF, float PLY) every face's corners to f32
/// precision, with STL's welding allowed to renumber vertices. A file the
/// writer produced that its reader refuses, or that comes back different
/// without a word in the read report, is a wrong answer.
fn round_trip(m: &TriMesh, format: Format, options: WriteOptions) -> Result<Out, String> {
    let mut bytes = Vec::new();
    mesh_io::write_to(&mut bytes, format, m, &WriteOptions { format: Some(format), ..options }).map_err(e)?;
    let back = match mesh_io::read_from(&bytes, format, &ReadOptions::default()) {
        Ok(d) => d,
        Err(err) => return Ok(Out::default().require(false, || format!("the written file cannot be read back: {err}"))),
    };
    let single = matches!(format, Format::Gltf | Format::Glb)
        || (format == Format::Stl && options.stl == StlEncoding::Binary)
        || (format == Format::Ply && !options.ply.double);
    let tolerance = if single { 2f64.powi(-23) } else { 0.0 };
    let close = |a: f64, b: f64| (a - b).abs() <= tolerance * a.abs().max(b.abs());
    let same_point = |p: mesh_kernel::glam::DVec3, q: mesh_kernel::glam::DVec3| (0..3).all(|k| close(p[k], q[k]));
    let b = &back.mesh;
    let problem = if b.face_count() != m.face_count() {
        Some(format!("{} faces back of {} (read report: {})", b.face_count(), m.face_count(), back.report))
    } else if format != Format::Stl && b.vertex_count() != m.vertex_count() {
        Some(format!("{} vertices back of {} (read report: {})", b.vertex_count(), m.vertex_count(), back.report))
    } else if format != Format::Stl && b.faces() != m.faces() {
        Some("faces renumbered".to_owned())
    } else {
        m.face_ids()
            .find(|&f| !m.triangle(f).iter().zip(b.triangle(f)).all(|(p, q)| same_point(*p, q)))
            .map(|f| format!("face {f:?} comes back as {:?}, was {:?}", b.triangle(f), m.triangle(f)))
    };
    let corners: Vec<f64> = b.face_ids().flat_map(|f| b.triangle(f)).flat_map(|p| p.to_array()).collect();
    let out = Out::default().counts("faces", vec![b.face_count() as f64]);
    let out = if single { out.single("corners", 1, corners) } else { out.field("corners", 1, corners) };
    Ok(out.require(problem.is_none(), || problem.unwrap_or_default()))
}
