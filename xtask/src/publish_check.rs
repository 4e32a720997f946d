//! `cargo xtask publish-check`: whether the workspace can go to crates.io.
//!
//! 1. Every publishable package name is looked up with `cargo info NAME`
//!    (from a folder outside the workspace, so the registry answers): a
//!    name that is absent is free; a name that is present must carry this
//!    workspace's repository URL, else it belongs to someone else and a
//!    published dependent would resolve the wrong crate.
//! 2. `cargo publish --workspace --dry-run` packages every publishable crate
//!    and builds each one from its archive, in dependency order, against
//!    the registry and the archives before it. It needs a clean work tree
//!    (no `--allow-dirty`), as continuous integration has.
//!
//! Each archive is built as a workspace of its own, where this workspace's
//! `[profile.dev]` does not apply; the dry run is given the same settings
//! (as `CARGO_PROFILE_DEV_*` variables read from the root `Cargo.toml`), so
//! that it reuses the dependencies an earlier `cargo test` built. Our own
//! crates, which the dry run compiles again from their archives, are
//! compiled there without optimization (`--config
//! profile.dev.package.NAME.opt-level=0`): 74 s on the 2-core Xeon VM
//! after the tests, against 231 s optimized and 20+ minutes from nothing.

use std::path::Path;
use std::process::Command;

use crate::tidy::deps::{metadata, Package};
use crate::Result;

/// Arguments of `cargo xtask publish-check`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Only check the names against the registry (no packaging).
    #[arg(long)]
    names_only: bool,
    /// Package every crate without building it from its archive
    /// (`cargo publish --no-verify`): the manifests, metadata and file lists
    /// are checked in about 20 s instead of about 75 (after `cargo test`).
    #[arg(long)]
    no_verify: bool,
}

/// Runs both steps; fails at the first that fails.
///
/// # Errors
/// A name owned by another repository, a failed lookup, or a failed dry run.
pub fn run(args: &Args) -> Result<()> {
    let root = crate::tidy::workspace_root();
    let meta = metadata(&root)?;
    let ours: Vec<&Package> = meta.members.iter().filter(|p| p.publish).collect();
    let mut taken = Vec::new();
    for p in &ours {
        let owner = registry_repository(&p.name)?;
        let verdict = name_verdict(owner.as_deref(), p.repository.as_deref());
        println!("publish-check: {:16} {verdict}", p.name);
        if let Verdict::Taken(_) = verdict {
            taken.push(p.name.clone());
        }
    }
    if !taken.is_empty() {
        return Err(format!("names taken on crates.io by other projects: {}", taken.join(", ")).into());
    }
    if args.names_only {
        return Ok(());
    }
    let names: Vec<&str> = ours.iter().map(|p| p.name.as_str()).collect();
    forget_stale_archives(&names)?;
    let mut publish = cargo(&root);
    publish.args(["publish", "--workspace", "--dry-run", "--locked"]);
    if args.no_verify {
        publish.arg("--no-verify");
    }
    for (key, value) in dev_profile(&std::fs::read_to_string(root.join("Cargo.toml"))?) {
        publish.env(format!("CARGO_PROFILE_DEV_{}", key.to_uppercase().replace('-', "_")), value);
    }
    // Our own crates are compiled from their archives without optimization:
    // the dry run checks that they build, not how fast they run, and most of
    // its time went to optimizing the generic code they instantiate.
    for name in &names {
        publish.arg("--config").arg(format!("profile.dev.package.{name}.opt-level=0"));
    }
    let status = publish.status()?;
    if !status.success() {
        return Err(format!("cargo publish --workspace --dry-run failed ({status})").into());
    }
    if args.no_verify {
        println!("publish-check: every publishable crate packages (not built from its archive: --no-verify)");
    } else {
        println!("publish-check: every publishable crate packages and builds from its archive");
    }
    Ok(())
}

/// Deletes the sources cargo extracted from this workspace's archives in
/// earlier dry runs. The dry run serves the archives from a local registry
/// whose extraction folder (`$CARGO_HOME/registry/src/-HASH/NAME-VERSION`)
/// depends only on the workspace's path, and cargo does not extract an
/// archive again over a folder that exists: without this, a second dry run
/// of the same version builds the dependents against the first run's
/// sources. Only folders of local registries (named `-HASH`) and of this
/// workspace's package names are touched.
///
/// # Errors
/// A folder that exists but cannot be read or removed.
fn forget_stale_archives(names: &[&str]) -> Result<()> {
    let home = std::env::var_os("CARGO_HOME")
        .map(std::path::PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|h| Path::new(&h).join(".cargo")));
    let Some(sources) = home.map(|h| h.join("registry").join("src")) else { return Ok(()) };
    let Ok(registries) = std::fs::read_dir(&sources) else { return Ok(()) };
    for registry in registries {
        let registry = registry?.path();
        let local = registry.file_name().and_then(|n| n.to_str()).is_some_and(|n| n.starts_with('-'));
        if !local || !registry.is_dir() {
            continue;
        }
        for entry in std::fs::read_dir(&registry)? {
            let path = entry?.path();
            let Some(folder) = path.file_name().and_then(|n| n.to_str()) else { continue };
            let ours = names.iter().any(|name| {
                folder
                    .strip_prefix(name)
                    .and_then(|rest| rest.strip_prefix('-'))
                    .is_some_and(|v| v.starts_with(|c: char| c.is_ascii_digit()))
            });
            if ours {
                std::fs::remove_dir_all(&path)?;
            }
        }
    }
    Ok(())
}

/// The `key = value` settings of the `[profile.dev]` table of a manifest,
/// values without their quotes (the scalars a profile holds). O(text).
fn dev_profile(manifest: &str) -> Vec<(String, String)> {
    let mut inside = false;
    let mut out = Vec::new();
    for line in manifest.lines().map(str::trim) {
        if line.starts_with('[') {
            inside = line == "[profile.dev]";
        } else if let (true, Some((key, value))) = (inside, line.split_once('=')) {
            if !key.trim().starts_with('#') {
                out.push((key.trim().to_owned(), value.trim().trim_matches('"').to_owned()));
            }
        }
    }
    out
}

fn cargo(dir: &Path) -> Command {
    let mut cmd = Command::new(std::env::var("CARGO").unwrap_or_else(|_| "cargo".into()));
    cmd.current_dir(dir);
    cmd
}

/// The repository URL crates.io gives for `name`, `None` when no crate has
/// that name. Runs outside the workspace, where `cargo info` asks the registry.
fn registry_repository(name: &str) -> Result<Option<String>> {
    let out = cargo(&std::env::temp_dir()).args(["info", name, "--registry", "crates-io"]).output()?;
    let (stdout, stderr) = (String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    if out.status.success() && !stdout.trim().is_empty() {
        let repo = stdout.lines().find_map(|l| l.strip_prefix("repository:")).map(|r| r.trim().to_owned());
        return Ok(Some(repo.unwrap_or_default()));
    }
    if stderr.contains("could not find") {
        return Ok(None);
    }
    Err(format!("cargo info {name} failed: {}", stderr.trim()).into())
}

/// What a registry lookup means for one of our names.
#[derive(Debug, PartialEq, Eq)]
enum Verdict {
    /// No crate has the name.
    Free,
    /// A crate has it, published from our repository.
    Ours,
    /// A crate has it, from another repository (given).
    Taken(String),
}

impl std::fmt::Display for Verdict {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Verdict::Free => write!(f, "free on crates.io"),
            Verdict::Ours => write!(f, "on crates.io, from this repository"),
            Verdict::Taken(repo) => {
                write!(f, "TAKEN on crates.io by {}", if repo.is_empty() { "(no repository)" } else { repo })
            }
        }
    }
}

/// Compares the registry's repository (if the name exists) with ours,
/// ignoring a trailing `/` or `.git`.
fn name_verdict(registry: Option<&str>, ours: Option<&str>) -> Verdict {
    let norm = |u: &str| u.trim().trim_end_matches('/').trim_end_matches(".git").to_ascii_lowercase();
    match (registry, ours) {
        (None, _) => Verdict::Free,
        (Some(theirs), Some(ours)) if !theirs.is_empty() && norm(theirs) == norm(ours) => Verdict::Ours,
        (Some(theirs), _) => Verdict::Taken(theirs.to_owned()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_judged_by_repository() {
        let ours = Some("https://github.com/mesh-workspace/mesh");
        assert_eq!(name_verdict(None, ours), Verdict::Free);
        assert_eq!(name_verdict(Some("https://github.com/mesh-workspace/mesh.git"), ours), Verdict::Ours);
        let other = "https://github.com/mellowmarshall/mars-protocol";
        assert_eq!(name_verdict(Some(other), ours), Verdict::Taken(other.into()));
        assert_eq!(name_verdict(Some(""), ours), Verdict::Taken(String::new()));
    }
}
