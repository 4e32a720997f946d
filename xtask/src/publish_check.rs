//! `cargo xtask publish-check`: packages every publishable crate of the
//! workspace with `cargo package`, which resolves unpublished path
//! dependencies through a local overlay of the packaged crates, in
//! dependency order.

use std::process::Command;

use crate::Result;

/// Arguments of `cargo xtask publish-check`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Also build each packaged crate from its archive (slow).
    #[arg(long)]
    verify: bool,
}

/// Runs `cargo package --workspace`, leaving out xtask (`publish = false`,
/// which `cargo package` does not skip by itself).
pub fn run(args: &Args) -> Result<()> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let mut cmd = Command::new(cargo);
    cmd.args(["package", "--workspace", "--exclude", "xtask", "--allow-dirty"]);
    if !args.verify {
        cmd.arg("--no-verify");
    }
    let status = cmd.status()?;
    if !status.success() {
        return Err(format!("cargo package failed ({status})").into());
    }
    println!("publish-check: every publishable crate packages");
    Ok(())
}
