//! `cargo xtask dataset --out DIR [--count N] [--seed S]`: a dataset of mesh
//! files for `mesh batch`, the Dask example and their throughput figures.
//!
//! The same seed gives the same files. Each file is a built-in shape or a
//! shared mesh (when the shared data is present; some Loop-subdivided once),
//! moved by a random rotation, translation and scale between 1e-3 and 1e3
//! (results must not depend on the unit of length), in a format chosen in
//! turn (OBJ, OFF, PLY, STL, GLB). One file in 50 is broken on purpose (cut
//! short) so that a batch shows how it records
//! failures. `DIR/dataset.json` lists every file with what it is and
//! whether it is broken.

use std::path::PathBuf;

use mesh_kernel::glam::{DQuat, DVec3};
use mesh_kernel::random::SplitMix64;
use mesh_kernel::{shapes, TriMesh};
use serde_json::json;

use crate::Result;

/// Arguments of `cargo xtask dataset`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Output folder (created; existing files of the same names are replaced).
    #[arg(long, default_value = "target/dataset")]
    out: PathBuf,
    /// Number of files.
    #[arg(long, default_value_t = 300)]
    count: usize,
    /// Seed of the random choices.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Largest face count of a shared mesh that is Loop-subdivided once.
    #[arg(long, default_value_t = 20_000)]
    subdivide_below: usize,
}

/// One file in this many is broken on purpose.
const BROKEN_EVERY: usize = 50;

const FORMATS: [&str; 5] = ["obj", "off", "ply", "stl", "glb"];

const SHARED: [&str; 8] = [
    "npm_bunny.obj",
    "cgal_elephant.off",
    "cgal_fandisk.off",
    "cgal_holes.off",
    "cgal_mushroom.off",
    "cgal_nefertiti.off",
    "cgal_degtri_sliding.off",
    "npm_dragon_res3.ply",
];

/// Runs `cargo xtask dataset`.
pub fn run(args: &Args) -> Result<()> {
    std::fs::create_dir_all(&args.out)?;
    let shared: Vec<(String, TriMesh)> = match mesh_testkit::data::shared_data() {
        Some(dir) => SHARED
            .iter()
            .map(|name| Ok(((*name).to_owned(), mesh_io::read(dir.join(name))?.mesh)))
            .collect::<Result<_>>()?,
        None => Vec::new(),
    };
    let mut rng = SplitMix64::new(args.seed);
    let mut listing = Vec::new();
    for i in 0..args.count {
        let broken = i % BROKEN_EVERY == BROKEN_EVERY - 1;
        // A broken file is in a format that says how much it holds (a cut
        // OBJ is a valid, smaller OBJ).
        let format = if broken { FORMATS[1 + (i / BROKEN_EVERY) % 4] } else { FORMATS[i % FORMATS.len()] };
        let name = format!("mesh{i:04}.{format}");
        let path = args.out.join(&name);
        let (what, mesh) = pick(&mut rng, &shared, args.subdivide_below)?;
        let mesh = moved(&mesh, &mut rng)?;
        mesh_io::write(&path, &mesh, &mesh_io::WriteOptions::default())?;
        if broken {
            let bytes = std::fs::read(&path)?;
            let cut = &bytes[..bytes.len() / 3];
            mesh_io::write_atomic(&path, |w| w.write_all(cut).map_err(|e| mesh_io::IoError::io(&path, e)))?;
        }
        listing.push(json!({
            "file": name,
            "source": what,
            "vertices": mesh.vertex_count(),
            "faces": mesh.face_count(),
            "broken": broken,
        }));
    }
    let manifest = args.out.join("dataset.json");
    let text = serde_json::to_string_pretty(&json!({ "seed": args.seed, "files": listing }))?;
    mesh_io::write_atomic(&manifest, |w| w.write_all(text.as_bytes()).map_err(|e| mesh_io::IoError::io(&manifest, e)))?;
    let broken = listing.iter().filter(|f| f["broken"] == true).count();
    println!(
        "{} files ({broken} broken on purpose) in {}; list in {}",
        args.count,
        args.out.display(),
        manifest.display()
    );
    Ok(())
}

/// A built-in shape at a random resolution, or a shared mesh (two times in
/// five when there are any), some of them subdivided once.
fn pick(rng: &mut SplitMix64, shared: &[(String, TriMesh)], subdivide_below: usize) -> Result<(String, TriMesh)> {
    if !shared.is_empty() && rng.below(5) < 2 {
        let (name, mesh) = &shared[rng.below(shared.len())];
        if mesh.face_count() <= subdivide_below && rng.one_in(2) {
            let options = mesh_wavelet::SubdivideOptions::default();
            return Ok((format!("{name} Loop x1"), mesh_wavelet::subdivide(mesh, &options)?));
        }
        return Ok((name.clone(), mesh.clone()));
    }
    let shape = *rng.pick(shapes::SHAPE_NAMES).ok_or("no built-in shapes")?;
    let res = match shape {
        "icosphere" => 1 + rng.below(4),
        "cube" => 2 + rng.below(8),
        _ => 6 + rng.below(27),
    };
    Ok((format!("{shape} {res}"), shapes::by_name(shape, res)?))
}

/// The mesh under a random rotation, scale in [1e-3, 1e3] and translation.
fn moved(mesh: &TriMesh, rng: &mut SplitMix64) -> Result<TriMesh> {
    let axis = DVec3::new(rng.signed(), rng.signed(), rng.signed()).try_normalize().unwrap_or(DVec3::Z);
    let rotation = DQuat::from_axis_angle(axis, std::f64::consts::PI * rng.signed());
    let scale = 10f64.powf(3.0 * rng.signed());
    let shift = DVec3::new(rng.signed(), rng.signed(), rng.signed()) * 10.0 * scale;
    let positions = mesh.positions().iter().map(|&p| rotation * p * scale + shift).collect();
    Ok(TriMesh::new(positions, mesh.faces().to_vec())?)
}
