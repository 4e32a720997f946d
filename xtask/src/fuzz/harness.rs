//! One fuzz input through the whole pipeline: `mesh_io::read_from`, then on
//! success the mesh's validation again, its connectivity and manifold
//! report, `clean` with default options and with manifold repair. Findings:
//! a panic, a reader that hands back an invalid mesh or NaN attributes,
//! a repair that leaves a non-manifold mesh, more than
//! [`MAX_SECONDS`] or [`MAX_BYTES`] for an input under 1 MB.

use std::time::Instant;

use mesh_io::{Format, MeshData, ReadOptions};
use mesh_kernel::clean::CleanOptions;
use mesh_kernel::TriMesh;

use super::{alloc, panics};

/// Longest time one input may take.
pub const MAX_SECONDS: f64 = 1.0;
/// Largest peak allocation for an input under [`SMALL_INPUT`] bytes.
pub const MAX_BYTES: usize = 256 << 20;
/// Inputs below this size must stay under [`MAX_BYTES`].
pub const SMALL_INPUT: usize = 1 << 20;

/// What happened to one input.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// The reader accepted it.
    pub parsed: bool,
    /// Wall time, seconds.
    pub seconds: f64,
    /// Peak bytes allocated above what was allocated before.
    pub peak_bytes: usize,
    /// What went wrong, if anything: a short kind and the details.
    pub finding: Option<(&'static str, String)>,
}

/// Runs one input (call inside [`panics::quietly`]).
pub fn run(bytes: &[u8], format: Format) -> Outcome {
    alloc::reset_peak();
    let base = alloc::current();
    let start = Instant::now();
    let result = alloc::limited(|| panics::catch(|| pipeline(bytes, format)));
    let seconds = start.elapsed().as_secs_f64();
    let peak_bytes = alloc::peak().saturating_sub(base);
    let (parsed, mut finding) = match result {
        Ok(Ok(parsed)) => (parsed, None),
        Ok(Err(finding)) => (true, Some(finding)),
        Err(message) => (false, Some(("panic", message))),
    };
    if finding.is_none() && seconds > MAX_SECONDS {
        finding = Some(("slow", format!("{seconds:.2} s (limit {MAX_SECONDS} s)")));
    }
    if finding.is_none() && bytes.len() < SMALL_INPUT && peak_bytes > MAX_BYTES {
        let mb = peak_bytes as f64 / (1 << 20) as f64;
        finding = Some(("memory", format!("{mb:.0} MB peak for a {} byte input (limit 256 MB)", bytes.len())));
    }
    Outcome { parsed, seconds, peak_bytes, finding }
}

type Finding = (&'static str, String);

/// `Ok(parsed)` or a finding.
fn pipeline(bytes: &[u8], format: Format) -> Result<bool, Finding> {
    let Ok(data) = mesh_io::read_from(bytes, format, &ReadOptions::default()) else {
        return Ok(false);
    };
    attributes_finite(&data)?;
    let mesh = TriMesh::new(data.mesh.positions().to_vec(), data.mesh.faces().to_vec())
        .map_err(|e| ("invalid mesh", format!("the reader returned a mesh TriMesh::new refuses: {e}")))?;
    let c = mesh.connectivity();
    let _ = (c.euler_characteristic(), c.components().count, c.boundary_loops().map(<[_]>::len), c.genus());
    let _ = c.non_manifold_report().to_string();
    if let Ok((cleaned, _)) = mesh.cleaned(&CleanOptions::default()) {
        finite(&cleaned, "clean")?;
    }
    let repair = CleanOptions { manifold: true, ..CleanOptions::default() };
    if let Ok((cleaned, report)) = mesh.cleaned(&repair) {
        finite(&cleaned, "clean --manifold")?;
        if let Err(e) = cleaned.manifold_connectivity() {
            return Err(("not manifold", format!("clean with manifold repair left {e} (report {report:?})")));
        }
    }
    Ok(true)
}

fn finite(mesh: &TriMesh, what: &str) -> Result<(), Finding> {
    match mesh.positions().iter().position(|p| !p.is_finite()) {
        Some(v) => Err(("NaN", format!("{what}: vertex {v} is {:?}", mesh.positions()[v]))),
        None => Ok(()),
    }
}

/// Normals, texture coordinates and colours are finite (scalars are the
/// file's own data, where NaN may mean "no value").
fn attributes_finite(data: &MeshData) -> Result<(), Finding> {
    let bad = |what: &str, i: usize| Err(("non-finite attribute", format!("{what} {i} is not finite")));
    if let Some(i) = data.normals.as_ref().and_then(|n| n.iter().position(|x| !x.is_finite())) {
        return bad("normal", i);
    }
    if let Some(i) = data.uvs.as_ref().and_then(|n| n.iter().position(|x| !x.is_finite())) {
        return bad("uv", i);
    }
    if let Some(i) = data.corner_uvs.as_ref().and_then(|n| n.iter().position(|x| x.iter().any(|q| !q.is_finite()))) {
        return bad("corner uv of face", i);
    }
    if let Some(i) = data.colors.as_ref().and_then(|n| n.iter().position(|x| x.iter().any(|q| !q.is_finite()))) {
        return bad("colour", i);
    }
    Ok(())
}
