//! One namespace for the whole workspace: `use mesh_a::*; use mesh_b::*;`
//! for every pair of crates compiles, and the names the crates have in
//! common mean one thing (the convention of `mesh_kernel::conventions`).
//!
//! Two checks. This file glob-imports every crate root and uses the names
//! a user reaches for first (options, methods, outputs, errors, the kernel's
//! `Result`): a name that two crates export as different items is ambiguous
//! and the file stops compiling. And [`no_two_crates_export_one_name`] reads
//! the `pub use` lines of every `lib.rs`, so that a name added later
//! collides here even before anything uses it.

use std::collections::BTreeMap;
use std::path::Path;

use mesh_curvature::*;
use mesh_delaunay::*;
use mesh_geodesic::*;
use mesh_io::*;
use mesh_kernel::*;
use mesh_nurbs::*;
use mesh_param::*;
use mesh_spectral::*;
use mesh_wavelet::*;

/// The kernel's `Result` is the only one at a root: the crates keep theirs
/// in their `error` modules.
fn kernel_result() -> Result<usize> {
    Ok(mesh_kernel::shapes::icosphere(0)?.vertex_count())
}

#[test]
fn glob_imports_of_every_crate_resolve_the_common_names() {
    assert_eq!(kernel_result(), Ok(12));
    // Options: one struct per algorithm, named after it.
    let _options = (
        EigenOptions::default(),
        HarmonicsOptions::default(),
        ParamOptions::default(),
        LscmOptions::default(),
        ArapOptions::default(),
        AtlasOptions::default(),
        MultiresOptions::default(),
        SubdivideOptions::default(),
        CompressOptions::default(),
        DetectOptions::default(),
        TensorOptions::default(),
        IntegralOptions::default(),
        GaussianOptions::default(),
        MeanOptions::default(),
        PointwiseOptions::default(),
        FmmOptions::default(),
        HeatOptions::default(),
        DijkstraOptions::default(),
        ExactOptions::default(),
        TraceOptions::default(),
        SamplingOptions::default(),
        GridOptions::default(),
        ReadOptions::default(),
        WriteOptions::default(),
        LawsonOptions::default(),
        VoronoiOptions::default(),
        RefineOptions::default(),
    );
    // Selectable enums: one list of names each, parsed back by `FromStr`.
    let names: Vec<String> = [
        TensorMethod::ALL.map(|m| m.to_string()).to_vec(),
        Degree::ALL.map(|m| m.to_string()).to_vec(),
        DegeneratePolicy::ALL.map(|m| m.to_string()).to_vec(),
        ParamMethod::ALL.map(|m| m.to_string()).to_vec(),
        Spacing::ALL.map(|m| m.to_string()).to_vec(),
        BoundaryMap::ALL.map(|m| m.to_string()).to_vec(),
        FmmUpdate::ALL.map(|m| m.to_string()).to_vec(),
        HeatFarField::ALL.map(|m| m.to_string()).to_vec(),
        HeatBoundary::ALL.map(|m| m.to_string()).to_vec(),
        SamplingMetric::ALL.map(|m| m.to_string()).to_vec(),
        ComponentSelection::ALL.map(|m| m.to_string()).to_vec(),
        Scheme::ALL.map(|m| m.to_string()).to_vec(),
        WaveletKind::ALL.map(|m| m.to_string()).to_vec(),
    ]
    .concat();
    assert!(names.iter().all(|n| !n.is_empty() && n.chars().all(|c| c.is_ascii_lowercase() || c == '-')), "{names:?}");
    assert!(TensorMethod::ALL.iter().all(|m| m.to_string().parse::<TensorMethod>().map(|p| p.name()) == Ok(m.name())));
    assert!(ParamMethod::ALL.iter().all(|m| m.to_string().parse::<ParamMethod>() == Ok(*m)));
    assert!(Degree::ALL.iter().all(|m| m.to_string().parse::<Degree>() == Ok(*m)));
    assert!(DegeneratePolicy::ALL.iter().all(|m| m.to_string().parse::<DegeneratePolicy>() == Ok(*m)));
    assert!(Spacing::ALL.iter().all(|m| m.to_string().parse::<Spacing>() == Ok(*m)));
    assert!(BoundaryMap::ALL.iter().all(|m| m.to_string().parse::<BoundaryMap>().as_ref() == Ok(m)));
    assert!(FmmUpdate::ALL.iter().all(|m| m.to_string().parse::<FmmUpdate>() == Ok(*m)));
    assert!(HeatFarField::ALL.iter().all(|m| m.to_string().parse::<HeatFarField>() == Ok(*m)));
    assert!(HeatBoundary::ALL.iter().all(|m| m.to_string().parse::<HeatBoundary>() == Ok(*m)));
    assert!(SamplingMetric::ALL.iter().all(|m| m.to_string().parse::<SamplingMetric>() == Ok(*m)));
    assert!(ComponentSelection::ALL.iter().all(|m| m.to_string().parse::<ComponentSelection>() == Ok(*m)));
    assert!(Scheme::ALL.iter().all(|m| m.to_string().parse::<Scheme>() == Ok(*m)));
    assert!(WaveletKind::ALL.iter().all(|m| m.to_string().parse::<WaveletKind>() == Ok(*m)));
    // Output labels and errors, one type each.
    let _outputs: (EigenSolver, Option<SpectralCompressionPoint>, Option<WaveletCompressionPoint>) =
        (EigenSolver::Dense, None, None);
    let _compressed: Option<WaveletCompression> = None;
    let _errors: [Option<Box<dyn std::error::Error>>; 9] = [
        None::<MeshError>.map(|e| e.into()),
        None::<IoError>.map(|e| e.into()),
        None::<NurbsError>.map(|e| e.into()),
        None::<ParamError>.map(|e| e.into()),
        None::<CurvatureError>.map(|e| e.into()),
        None::<GeodesicError>.map(|e| e.into()),
        None::<SpectralError>.map(|e| e.into()),
        None::<WaveletError>.map(|e| e.into()),
        None::<DelaunayError>.map(|e| e.into()),
    ];
}

#[test]
fn every_algorithm_crate_re_exports_the_kernel() {
    let ico = mesh_kernel::shapes::icosphere(1).expect("icosphere");
    let same = |m: &mesh_kernel::TriMesh| m == &ico;
    assert!(same(&mesh_io::mesh_kernel::shapes::icosphere(1).expect("io")));
    assert!(same(&mesh_nurbs::mesh_kernel::shapes::icosphere(1).expect("nurbs")));
    assert!(same(&mesh_param::mesh_kernel::shapes::icosphere(1).expect("param")));
    assert!(same(&mesh_curvature::mesh_kernel::shapes::icosphere(1).expect("curvature")));
    assert!(same(&mesh_geodesic::mesh_kernel::shapes::icosphere(1).expect("geodesic")));
    assert!(same(&mesh_spectral::mesh_kernel::shapes::icosphere(1).expect("spectral")));
    assert!(same(&mesh_wavelet::mesh_kernel::shapes::icosphere(1).expect("wavelet")));
    assert!(same(&mesh_delaunay::mesh_kernel::shapes::icosphere(1).expect("delaunay")));
}

/// The crates whose roots share one namespace.
const CRATES: [&str; 9] = [
    "mesh-kernel",
    "mesh-io",
    "mesh-nurbs",
    "mesh-param",
    "mesh-curvature",
    "mesh-geodesic",
    "mesh-spectral",
    "mesh-wavelet",
    "mesh-delaunay",
];

/// Re-exports of one item under one name by several crates: the kernel and
/// the dependencies it hands out (items re-exported from `mesh_kernel::..`
/// are the kernel's too).
const SHARED: [&str; 4] = ["mesh_kernel", "glam", "sprs", "faer"];

/// The names a `lib.rs` re-exports at its root (`pub use a::b::{c, d};`,
/// `pub use a::b;`), `as` renames included, except the kernel's own items
/// handed on (`pub use mesh_kernel::operators::MassKind;`: one item whatever
/// the crate); modules are not counted (they are written with their crate's
/// path, `mesh_nurbs::shapes`).
fn root_names(lib: &str) -> Vec<String> {
    let mut names = Vec::new();
    let mut rest = lib;
    while let Some(start) = rest.find("\npub use ") {
        let after = &rest[start + "\npub use ".len()..];
        let end = after.find(';').unwrap_or(after.len());
        let item = &after[..end];
        rest = &after[end..];
        if item.starts_with("mesh_kernel::") {
            continue;
        }
        let list = match (item.find('{'), item.rfind('}')) {
            (Some(open), Some(close)) => &item[open + 1..close],
            _ => item.rsplit("::").next().unwrap_or(item),
        };
        for name in list.split(',').map(str::trim).filter(|n| !n.is_empty() && *n != "self") {
            let name = name.rsplit(" as ").next().unwrap_or(name).rsplit("::").next().unwrap_or(name);
            names.push(name.trim().to_owned());
        }
    }
    names
}

#[test]
fn no_two_crates_export_one_name() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut owners: BTreeMap<String, Vec<&str>> = BTreeMap::new();
    for krate in CRATES {
        let lib = std::fs::read_to_string(root.join(krate).join("src/lib.rs")).expect("every crate has a lib.rs");
        let names = root_names(&lib);
        assert!(names.len() >= 5, "{krate}: only {names:?} found, the parser is out of date");
        for name in names.into_iter().filter(|n| !SHARED.contains(&n.as_str())) {
            owners.entry(name).or_default().push(krate);
        }
    }
    let clashes: Vec<_> = owners.iter().filter(|(_, crates)| crates.len() > 1).collect();
    assert!(clashes.is_empty(), "names exported at more than one crate root: {clashes:?}");
    for generic in ["Options", "Method", "Stats", "Compression"] {
        assert!(!owners.contains_key(generic), "`{generic}` at a root: give it its crate's domain as a prefix");
    }
    let results: Vec<&str> = owners.get("Result").map_or(Vec::new(), |c| c.clone());
    assert_eq!(results, ["mesh-kernel"], "only the kernel exports `Result` at its root");
}
