//! mesh-param operations on a disk-like mesh (none otherwise), named as in
//! peer_bench.py where they match: `param_harmonic` (circle boundary, as
//! `igl.harmonic` after `igl.map_vertices_to_circle`) and `param_lscm` (as
//! `igl.lscm` with two pinned boundary vertices); also `param_tutte`,
//! `param_mean_value` and `param_distortion` (the distortion report).

use std::path::Path;

use mesh_io::MeshData;
use mesh_param::{
    boundary, distortion, lscm, require_disk, DegeneratePolicy, FixedBoundarySolver, Harmonic, LscmOptions, MeanValue,
    Spacing, Uniform, Weights,
};

use super::Operation;

/// The parameterization operations, or none when the mesh is not a disk.
pub fn operations<'a>(_path: &'a Path, data: &'a MeshData) -> Vec<Operation<'a>> {
    let mesh = &data.mesh;
    let Ok(lp) = require_disk(mesh) else { return Vec::new() };
    let b = lp.vertices.clone();
    let circle = boundary::circle(mesh, &b, Spacing::Uniform);
    let fixed = move |w: &dyn Weights| {
        FixedBoundarySolver::new(mesh, w, &b, DegeneratePolicy::Uniform).and_then(|s| s.solve(&circle))
    };
    let uv = fixed(&Harmonic).unwrap_or_default();
    let fixed = std::sync::Arc::new(fixed);
    let (f1, f2, f3) = (fixed.clone(), fixed.clone(), fixed);
    vec![
        Operation::new("param_harmonic", move || Ok(f1(&Harmonic)?)),
        Operation::new("param_tutte", move || Ok(f2(&Uniform)?)),
        Operation::new("param_mean_value", move || Ok(f3(&MeanValue)?)),
        Operation::new("param_lscm", move || Ok(lscm(mesh, &LscmOptions::default())?)),
        Operation::new("param_distortion", move || Ok(distortion(mesh, &uv)?)),
    ]
}
