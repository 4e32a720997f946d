//! The shared real meshes: where they are, what happens when they are not
//! there, and the counts they are known to have.
//!
//! The meshes are third-party files kept next to the repository checkout
//! (`../shared/data` from the workspace root), never inside a crate or its
//! package. The rule, one for every test, bench, example and xtask check:
//!
//! | situation | result |
//! |---|---|
//! | `MESH_SHARED_DATA` names a directory | that directory is used |
//! | otherwise `../shared/data` beside the workspace exists | it is used |
//! | neither, and `MESH_REQUIRE_SHARED_DATA=1` (continuous integration) | the test fails (a panic naming the folder and both variables) |
//! | neither, otherwise | a `SKIPPED (needs the workspace's shared data)` line on the terminal, not captured by the test harness, and the data-dependent part returns |
//!
//! A data directory that exists but lacks a file one asks for is always a
//! failure: the data is incomplete, not absent.

use std::io::Write;
use std::path::PathBuf;

/// The environment variable naming the data directory (overrides the default).
pub const DATA_VAR: &str = "MESH_SHARED_DATA";

/// The environment variable that, set to `1`, turns a missing data
/// directory into a failure instead of a skip.
pub const REQUIRE_VAR: &str = "MESH_REQUIRE_SHARED_DATA";

/// Where the data is looked for: `MESH_SHARED_DATA` when set and non-empty,
/// else `../shared/data` beside the workspace root. Nothing is checked. O(1).
pub fn data_path() -> PathBuf {
    match std::env::var_os(DATA_VAR) {
        Some(dir) if !dir.is_empty() => PathBuf::from(dir),
        _ => PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/data")),
    }
}

/// Whether `MESH_REQUIRE_SHARED_DATA=1` is set (missing data is a failure). O(1).
pub fn required() -> bool {
    std::env::var_os(REQUIRE_VAR).is_some_and(|v| v == "1")
}

/// The data directory if it exists, else the path that was looked for.
/// Neither prints nor panics: for callers that report skips themselves
/// (xtask's validation table). One `stat`.
///
/// # Errors
/// The looked-for path when it is not a directory.
pub fn locate() -> Result<PathBuf, PathBuf> {
    let dir = data_path();
    if dir.is_dir() {
        Ok(dir)
    } else {
        Err(dir)
    }
}

/// Why a data-dependent step did not run, for a report line.
pub fn absent_reason(dir: &std::path::Path) -> String {
    format!("needs the workspace's shared data: {} is absent (set {DATA_VAR} to its directory)", dir.display())
}

/// `Err` with a message when the data is absent and [`required`]; `Ok`
/// otherwise (present, or absent and allowed to be skipped). One `stat`.
///
/// # Errors
/// The message for the failure, naming the folder and both variables.
pub fn require() -> Result<(), String> {
    match locate() {
        Err(dir) if required() => Err(format!("{}; {REQUIRE_VAR}=1 makes this a failure", absent_reason(&dir))),
        _ => Ok(()),
    }
}

/// The data directory for a test, bench or example: `Some` when present;
/// when absent, panics if [`required`], else prints a `SKIPPED` line
/// (straight to the process's stderr, which the test harness does not
/// capture) and returns `None`. One `stat`.
///
/// # Panics
/// When the directory is absent and `MESH_REQUIRE_SHARED_DATA=1`.
pub fn shared_data() -> Option<PathBuf> {
    match locate() {
        Ok(dir) => Some(dir),
        Err(dir) => {
            if let Err(failure) = require() {
                panic!("{failure}");
            }
            let reason = absent_reason(&dir);
            let caller = std::thread::current().name().unwrap_or("main").to_owned();
            // A failed write to stderr leaves nothing better to do.
            let _ = writeln!(std::io::stderr(), "SKIPPED {caller}: {reason}");
            None
        }
    }
}

/// One file of the data directory: `None` (with the skip or failure of
/// [`shared_data`]) when the directory is absent. O(1).
///
/// # Panics
/// When the directory exists but the file does not (incomplete data), or as
/// [`shared_data`].
pub fn shared_file(name: &str) -> Option<PathBuf> {
    let path = shared_data()?.join(name);
    assert!(path.is_file(), "{} is missing from the shared data", path.display());
    Some(path)
}

/// Ground truth of one shared mesh, from the data's README (counted over
/// referenced vertices; chi = V - E + F).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SharedMesh {
    /// File name inside the data directory.
    pub name: &'static str,
    /// Vertex count.
    pub vertices: usize,
    /// Face count.
    pub faces: usize,
    /// Euler-Poincare characteristic.
    pub euler: i64,
    /// Genus (every listed mesh is orientable and manifold).
    pub genus: u64,
    /// Number of boundary loops.
    pub boundary_loops: usize,
}

/// The manifold shared meshes and their counts (the dirty scan
/// `npm_dragon_res3.ply` is left out: it has no genus).
pub const SHARED_MESHES: [SharedMesh; 7] = [
    mesh("cgal_nefertiti.off", 299, 562, 1, 0, 1),
    mesh("cgal_mushroom.off", 2337, 4608, 1, 0, 1),
    mesh("cgal_elephant.off", 2775, 5558, -4, 3, 0),
    mesh("cgal_fandisk.off", 6475, 12946, 2, 0, 0),
    mesh("npm_bunny.obj", 1839, 3674, 2, 0, 0),
    mesh("cgal_holes.off", 4291, 8288, -5, 0, 7),
    mesh("cgal_degtri_sliding.off", 8, 8, 1, 0, 1),
];

const fn mesh(
    name: &'static str,
    vertices: usize,
    faces: usize,
    euler: i64,
    genus: u64,
    boundary_loops: usize,
) -> SharedMesh {
    SharedMesh { name, vertices, faces, euler, genus, boundary_loops }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_is_consistent() {
        // chi = 2 - 2g - b for a connected orientable surface; the holes mesh
        // and the degenerate patch are connected too.
        for m in SHARED_MESHES {
            assert_eq!(m.euler, 2 - 2 * m.genus as i64 - m.boundary_loops as i64, "{}", m.name);
        }
    }

    #[test]
    fn the_table_matches_the_data_readme() {
        let Some(dir) = shared_data() else { return };
        let readme = std::fs::read_to_string(dir.join("README.md")).expect("the data has a README");
        for m in SHARED_MESHES {
            let row = format!(
                "| `{}` | {} | {} | {} | {} | {} |",
                m.name, m.vertices, m.faces, m.euler, m.genus, m.boundary_loops
            );
            assert!(readme.contains(&row), "{row} is not in the data README");
        }
    }
}
