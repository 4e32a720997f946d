//! The one place where errors of the library crates are put in the terms of
//! the command line: the flag the user typed (with its value), the file,
//! the element, and what to do. Library messages stay as they are for Rust
//! users; this layer rewrites only what names a Rust item (`LaplacianKind::
//! IntrinsicDelaunay`) or an option (`boundary`, `pins`) that the user did
//! not type.
//!
//! Each command lists the library option names it sets from its flags, as
//! [`Given`] pairs; an option error on a name in the list quotes the flag,
//! an error on any other name is reported as a failure of an internal step.

use mesh_io::IoError;

use crate::output::CliError;

/// The library options a command set from its flags: `(library option
/// name, the flag and value as typed)`, e.g. `("k", "--k 0".into())`.
pub type Given<'a> = &'a [(&'static str, String)];

/// A flag and its value as the user would type it.
pub fn flag(name: &str, value: impl std::fmt::Display) -> String {
    format!("{name} {value}")
}

/// Any error a command returned, in command-line terms: errors of the
/// library crates are recognized by type, rewritten, and prefixed with the
/// input file (mesh-io errors name it already); others (already in
/// command-line terms) pass unchanged.
pub fn translate(e: CliError, given: Given<'_>, input: Option<&std::path::Path>) -> CliError {
    let on_file = |e: CliError| -> CliError {
        match input {
            Some(file) => format!("{}: {e}", file.display()).into(),
            None => e,
        }
    };
    library(e, given, on_file)
}

fn library(e: CliError, given: Given<'_>, on_file: impl Fn(CliError) -> CliError) -> CliError {
    let e = match e.downcast::<IoError>() {
        Ok(e) => return io(*e),
        Err(e) => e,
    };
    let e = match e.downcast::<mesh_kernel::MeshError>() {
        Ok(e) => return on_file(core(*e, given)),
        Err(e) => e,
    };
    let e = match e.downcast::<mesh_geodesic::GeodesicError>() {
        Ok(e) => return on_file(geodesic(*e, given)),
        Err(e) => e,
    };
    let e = match e.downcast::<mesh_param::ParamError>() {
        Ok(e) => return on_file(param(*e, given)),
        Err(e) => e,
    };
    let e = match e.downcast::<mesh_spectral::SpectralError>() {
        Ok(e) => return on_file(spectral(*e, given)),
        Err(e) => e,
    };
    let e = match e.downcast::<mesh_curvature::CurvatureError>() {
        Ok(e) => return on_file(curvature(*e, given)),
        Err(e) => e,
    };
    let e = match e.downcast::<mesh_delaunay::DelaunayError>() {
        Ok(e) => return on_file(delaunay(*e, given)),
        Err(e) => e,
    };
    let e = match e.downcast::<mesh_remesh::RemeshError>() {
        Ok(e) => return on_file(remesh(*e, given)),
        Err(e) => e,
    };
    match e.downcast::<mesh_wavelet::WaveletError>() {
        Ok(e) => on_file(wavelet(*e, given)),
        Err(e) => e,
    }
}

/// A mesh-io error in command-line terms.
pub fn io(e: IoError) -> CliError {
    match &e {
        IoError::Precision { .. } => format!("{e} (pass --allow-precision-loss to write it anyway)").into(),
        _ => e.into(),
    }
}

/// An invalid-option error of any crate: quotes the flag when the user set
/// the option, and otherwise says which internal step failed.
fn option(name: &str, reason: &str, given: Given<'_>) -> CliError {
    let Some((_, typed)) = given.iter().find(|(n, _)| *n == name) else {
        return format!("an internal step ({}) failed: {reason}", internal_step(name)).into();
    };
    // A reason that starts with the value ("1e300 is larger than ...")
    // reads on from the flag as typed, without the value printed twice.
    let value = typed.rsplit(' ').next().and_then(|v| v.parse::<f64>().ok());
    let (first, rest) = reason.split_once(' ').unwrap_or((reason, ""));
    let message = match (value, first.parse::<f64>()) {
        (Some(v), Ok(r)) if v == r || (v.is_nan() && r.is_nan()) => format!("{typed} {rest}"),
        _ => format!("{typed}: {reason}"),
    };
    match hint(name) {
        Some(hint) => format!("{message}; {hint}").into(),
        None => message.into(),
    }
}

/// What to do about a bad value of an option, when the reason alone does not say.
fn hint(name: &str) -> Option<&'static str> {
    match name {
        "weld_tolerance" => {
            Some("give a distance >= 0 and well below the bounding box diagonal (0 welds identical positions only)")
        }
        _ => None,
    }
}

/// What an option the command sets on its own is for, in plain words.
fn internal_step(name: &str) -> String {
    match name {
        "boundary" => "placing the chart boundary".into(),
        "pins" => "pinning two boundary vertices of a chart".into(),
        "constrained" => "fixing the boundary vertices".into(),
        "sizes" | "margin" => "packing the charts".into(),
        other => format!("`{other}`"),
    }
}

/// A mesh-kernel error in command-line terms.
pub fn core(e: mesh_kernel::MeshError, given: Given<'_>) -> CliError {
    use mesh_kernel::MeshError;
    match &e {
        MeshError::InvalidOption { name, reason } => option(name, reason, given),
        MeshError::Empty => "the mesh has no faces; this command needs a surface".into(),
        MeshError::Solver(detail) => {
            // The solver's detail is a Rust debug value: keep its first words.
            let detail = detail.split(" (").next().unwrap_or(detail);
            let laplacian = given.iter().find(|(n, _)| *n == "laplacian").map(|(_, typed)| typed.as_str());
            let what_to_do = match laplacian {
                Some(typed) if !typed.ends_with("intrinsic") => {
                    "zero-area or needle faces are the usual cause: pass --laplacian intrinsic, or remove them with \
                     `mesh clean IN OUT`"
                }
                _ => "zero-area or needle faces are the usual cause: remove them with `mesh clean IN OUT`",
            };
            format!("the linear solver failed ({detail}); {what_to_do}").into()
        }
        MeshError::NonManifold(_) => {
            format!("{e}; `mesh clean --manifold IN OUT` makes it one (see `mesh info` for the counts)").into()
        }
        _ => e.into(),
    }
}

/// A mesh-geodesic error in command-line terms.
pub fn geodesic(e: mesh_geodesic::GeodesicError, given: Given<'_>) -> CliError {
    use mesh_geodesic::GeodesicError;
    match e {
        GeodesicError::Mesh(e) => core(e, given),
        GeodesicError::InvalidOption { name, reason } => option(name, &reason, given),
        GeodesicError::Degenerate(text) if text.contains("LaplacianKind::IntrinsicDelaunay") => {
            let text = text.replace("; use LaplacianKind::IntrinsicDelaunay", "");
            let intrinsic = given.iter().any(|(n, typed)| *n == "laplacian" && typed.ends_with("intrinsic"));
            let what_to_do = if intrinsic {
                "even with --laplacian intrinsic; remove them first with `mesh clean IN OUT`"
            } else {
                "pass --laplacian intrinsic (the intrinsic Delaunay Laplacian handles them)"
            };
            format!("degenerate geometry: {text}; {what_to_do}").into()
        }
        e => e.into(),
    }
}

/// A mesh-param error in command-line terms.
pub fn param(e: mesh_param::ParamError, given: Given<'_>) -> CliError {
    use mesh_param::ParamError;
    match e {
        ParamError::Mesh(e) => core(e, given),
        ParamError::InvalidOption { name, reason } => option(name, &reason, given),
        ParamError::DegenerateFaces { count, first } => format!(
            "{count} zero-area faces (first: face {first}) make the cotangent weights undefined; remove them \
             with `mesh clean IN OUT`, or use --method tutte (uniform weights)"
        )
        .into(),
        ParamError::NonFinite { vertex } => format!(
            "the solve produced a non-finite coordinate at vertex {vertex}; try --method tutte or --method \
             mean-value"
        )
        .into(),
        e => e.into(),
    }
}

/// A mesh-spectral error in command-line terms.
pub fn spectral(e: mesh_spectral::SpectralError, given: Given<'_>) -> CliError {
    use mesh_spectral::SpectralError;
    match e {
        SpectralError::Mesh(e) => core(e, given),
        SpectralError::InvalidOption { name, reason } => option(name, &reason, given),
        SpectralError::TooManyPairs { requested, available } => {
            let typed = given.iter().find(|(n, _)| *n == "k").map_or("--k".into(), |(_, t)| t.clone());
            format!("{typed}: the mesh has only {available} vertices carrying mass, so at most {available} eigenpairs (asked for {requested}); give a smaller --k").into()
        }
        e => e.into(),
    }
}

/// A mesh-curvature error in command-line terms.
pub fn curvature(e: mesh_curvature::CurvatureError, given: Given<'_>) -> CliError {
    use mesh_curvature::CurvatureError;
    match e {
        CurvatureError::Mesh(e) => core(e, given),
        CurvatureError::InvalidOption { name, reason } => option(name, &reason, given),
        e => e.into(),
    }
}

/// A mesh-remesh error in command-line terms.
pub fn remesh(e: mesh_remesh::RemeshError, given: Given<'_>) -> CliError {
    use mesh_remesh::RemeshError;
    match e {
        RemeshError::Mesh(e) => core(e, given),
        RemeshError::Param(e) => param(e, given),
        RemeshError::InvalidOption { name, reason } => option(name, &reason, given),
        RemeshError::TooManyVertices { edge_length, estimated, limit } => format!(
            "--edge-length {edge_length} needs about {estimated} vertices, more than --max-vertices {limit}: \
             choose a longer edge length or raise --max-vertices"
        )
        .into(),
        other => other.into(),
    }
}

/// A mesh-delaunay error in command-line terms.
pub fn delaunay(e: mesh_delaunay::DelaunayError, given: Given<'_>) -> CliError {
    use mesh_delaunay::DelaunayError;
    match e {
        DelaunayError::Mesh(e) => core(e, given),
        DelaunayError::InvalidOption { name, reason } => option(name, &reason, given),
        DelaunayError::DegenerateLoop { loop_index, reason } => {
            format!("polygon loop {} (counting from 1, the outer loop first) is degenerate: {reason}", loop_index + 1)
                .into()
        }
        e => e.into(),
    }
}

/// A mesh-wavelet error in command-line terms.
pub fn wavelet(e: mesh_wavelet::WaveletError, given: Given<'_>) -> CliError {
    use mesh_wavelet::WaveletError;
    match e {
        WaveletError::Mesh(e) => core(e, given),
        WaveletError::InvalidOption { name, reason } => option(name, &reason, given),
        WaveletError::NoSubdivisionConnectivity { reason } => format!(
            "the mesh has no subdivision connectivity ({reason}); `mesh wavelet` analyzes meshes made by 4-to-1 \
             splits, e.g. the output of `mesh subdivide`"
        )
        .into(),
        e => e.into(),
    }
}

/// A number as a user would type it: plain for ordinary magnitudes,
/// scientific (`1e300`) otherwise.
pub fn number(x: f64) -> String {
    if x == 0.0 || !x.is_finite() || (1e-4..1e15).contains(&x.abs()) {
        x.to_string()
    } else {
        format!("{x:e}")
    }
}
