//! What every end-to-end test of the `mesh` binary shares: running it, and
//! reading what it printed as JSON.
#![allow(dead_code)] // each test binary uses its own subset

use std::process::Command;

use serde_json::Value;

/// Runs `mesh ARGS`: (exit code, standard output, standard error); -1 when
/// a signal ended it.
pub fn mesh_code(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_mesh")).args(args).output().expect("the mesh binary runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

/// Runs `mesh ARGS`: (success, standard output, standard error).
pub fn mesh(args: &[&str]) -> (bool, String, String) {
    let (code, stdout, stderr) = mesh_code(args);
    (code == 0, stdout, stderr)
}

/// Runs `mesh ARGS`, which must succeed, and parses its standard output as JSON.
pub fn json(args: &[&str]) -> Value {
    let (ok, stdout, stderr) = mesh(args);
    assert!(ok, "mesh {args:?} failed: {stderr}");
    serde_json::from_str(&stdout).unwrap_or_else(|e| panic!("mesh {args:?} printed invalid JSON ({e}): {stdout}"))
}
