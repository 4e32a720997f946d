//! Rules on the manifests: every declared dependency is used, and the
//! declared `rust-version` is at least every resolved dependency's.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde_json::Value;

use super::{lexer, rust_files, Problem};

/// One workspace package, as `cargo metadata` describes it.
pub struct Package {
    /// Package name.
    pub name: String,
    /// Folder of its Cargo.toml.
    pub dir: PathBuf,
    /// `false` for `publish = false`.
    pub publish: bool,
    /// Its `rust-version`, if any.
    pub rust_version: Option<String>,
    /// Its `repository`, if any.
    pub repository: Option<String>,
    /// (name in code, kind: "normal", "dev" or "build") of every dependency.
    pub dependencies: Vec<(String, String)>,
}

/// The targets whose resolved dependencies must build with the declared
/// `rust-version`: the tier-1 platforms users build on. Dependencies behind
/// other `cfg`s (e.g. faer's `cfg(loom)` test dependency, which needs Rust
/// 1.95) are never built by users and do not count.
pub const TARGETS: [&str; 3] = ["x86_64-unknown-linux-gnu", "x86_64-pc-windows-msvc", "aarch64-apple-darwin"];

/// The workspace packages and the `rust-version` of every other package
/// resolved for one of [`TARGETS`] (all features).
pub struct Metadata {
    /// Workspace members.
    pub members: Vec<Package>,
    /// (rust-version, package) of every resolved non-member that declares one.
    pub resolved: Vec<(String, String)>,
}

/// Runs `cargo metadata --format-version 1 --locked --filter-platform T`
/// in `root` for each of [`TARGETS`] and keeps what the rules need.
///
/// # Errors
/// When cargo fails or prints something that is not its metadata.
pub fn metadata(root: &Path) -> crate::Result<Metadata> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let mut all: Option<Metadata> = None;
    for target in TARGETS {
        let out = std::process::Command::new(&cargo)
            .args(["metadata", "--format-version", "1", "--locked", "--filter-platform", target])
            .current_dir(root)
            .output()?;
        if !out.status.success() {
            return Err(format!("cargo metadata failed: {}", String::from_utf8_lossy(&out.stderr)).into());
        }
        let meta = parse_metadata(&serde_json::from_slice(&out.stdout)?)?;
        match &mut all {
            None => all = Some(meta),
            Some(a) => a.resolved.extend(meta.resolved),
        }
    }
    all.ok_or_else(|| "no target".into())
}

fn parse_metadata(meta: &Value) -> crate::Result<Metadata> {
    let members: Vec<&str> =
        meta["workspace_members"].as_array().ok_or("no workspace_members")?.iter().filter_map(Value::as_str).collect();
    let (mut out, mut resolved) = (Vec::new(), Vec::new());
    for p in meta["packages"].as_array().ok_or("no packages")? {
        let name = p["name"].as_str().unwrap_or_default().to_owned();
        let rust_version = p["rust_version"].as_str().map(str::to_owned);
        if !members.contains(&p["id"].as_str().unwrap_or_default()) {
            resolved.extend(rust_version.map(|v| (v, format!("{name} {}", p["version"].as_str().unwrap_or("?")))));
            continue;
        }
        let manifest = PathBuf::from(p["manifest_path"].as_str().ok_or("no manifest_path")?);
        let dependencies = p["dependencies"]
            .as_array()
            .map(|deps| {
                deps.iter()
                    .map(|d| {
                        let name = d["rename"].as_str().or(d["name"].as_str()).unwrap_or_default();
                        (name.replace('-', "_"), d["kind"].as_str().unwrap_or("normal").to_owned())
                    })
                    .collect()
            })
            .unwrap_or_default();
        out.push(Package {
            name,
            dir: manifest.parent().ok_or("manifest without folder")?.to_path_buf(),
            publish: !p["publish"].as_array().is_some_and(Vec::is_empty),
            rust_version,
            repository: p["repository"].as_str().map(str::to_owned),
            dependencies,
        });
    }
    Ok(Metadata { members: out, resolved })
}

/// Whether `ident` is used as a crate name in `text`: `ident::`, `use ident`
/// or `extern crate ident`, not preceded by an identifier character.
pub fn mentions(text: &str, ident: &str) -> bool {
    let ident_char = |c: char| c.is_alphanumeric() || c == '_';
    text.match_indices(ident).any(|(at, _)| {
        let head = &text[..at];
        // `::name` is a crate root only when nothing names a path before it.
        let root = head.strip_suffix("::").unwrap_or(head);
        if root.ends_with(|c: char| ident_char(c) || c == ':' || c == '>') {
            return false;
        }
        let after = &text[at + ident.len()..];
        let word_end = !after.starts_with(ident_char);
        let head = head.trim_end();
        after.starts_with("::") || (word_end && (head.ends_with("use") || head.ends_with("extern crate")))
    })
}

/// Dependencies that no source of their kind names: normal ones in the
/// library and binary sources (code only, `src/`), dev ones anywhere in the
/// package (doc-tests and READMEs included), build ones in `build.rs`.
pub fn unused(packages: &[Package]) -> Vec<Problem> {
    let mut problems = Vec::new();
    for p in packages {
        let files = rust_files(&p.dir);
        let read = |f: &Path| std::fs::read_to_string(f).unwrap_or_default();
        let src: String =
            files.iter().filter(|f| f.starts_with(p.dir.join("src"))).map(|f| lexer::lex(&read(f)).code).collect();
        let mut all: String = files.iter().map(|f| read(f)).collect();
        all.push_str(&read(&p.dir.join("README.md")));
        let build = read(&p.dir.join("build.rs"));
        for (name, kind) in &p.dependencies {
            let text = match kind.as_str() {
                "dev" => &all,
                "build" => &build,
                _ => &src,
            };
            if !mentions(text, name) {
                let manifest = p.dir.join("Cargo.toml");
                problems.push(Problem::new(&manifest, 0, format!("{kind} dependency `{name}` is not used")));
            }
        }
    }
    problems
}

/// `(major, minor, patch)` of a version like `1.88` or `1.88.0`.
pub fn version(v: &str) -> (u64, u64, u64) {
    let mut parts = v.split('.').map(|x| x.parse::<u64>().unwrap_or(0));
    (parts.next().unwrap_or(0), parts.next().unwrap_or(0), parts.next().unwrap_or(0))
}

/// Every member's `rust-version` must be present and at least the largest
/// `rust-version` among resolved dependencies. Returns the problems and that
/// largest version with the packages that declare it.
pub fn rust_version(meta: &Metadata, root: &Path) -> (Vec<Problem>, String) {
    let mut by_version: BTreeMap<(u64, u64, u64), Vec<&str>> = BTreeMap::new();
    for (v, p) in &meta.resolved {
        by_version.entry(version(v)).or_default().push(p);
    }
    let Some(((a, b, c), needed_by)) = by_version.last_key_value() else { return (Vec::new(), "none".into()) };
    let needed = format!("{a}.{b}.{c} ({})", needed_by.join(", "));
    let manifest = root.join("Cargo.toml");
    let problems = meta
        .members
        .iter()
        .filter_map(|p| match &p.rust_version {
            None => Some(format!("{} declares no rust-version (dependencies need {needed})", p.name)),
            Some(v) if version(v) < (*a, *b, *c) => {
                Some(format!("{}: rust-version {v} is below what dependencies need: {needed}", p.name))
            }
            Some(_) => None,
        })
        .map(|m| Problem::new(&manifest, 0, m))
        .collect();
    (problems, needed)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crate_names_are_found_as_paths_only() {
        assert!(mentions("use glam::DVec3;", "glam"));
        assert!(mentions("let x = ::rayon::join(a, b);", "rayon"));
        assert!(mentions("use thiserror;\n", "thiserror"));
        assert!(mentions("extern crate serde;", "serde"));
        assert!(!mentions("let glam_like = 1; serde_json::to_string(x)", "serde"));
        assert!(!mentions("mesh_kernel::glam::DVec3", "glam"));
        assert!(!mentions("<T as Trait>::glam::f()", "glam"));
        assert!(!mentions("// uses rayon", "rayon"));
    }

    #[test]
    fn versions_compare_numerically() {
        assert!(version("1.88") > version("1.9"));
        assert_eq!(version("1.85.1"), (1, 85, 1));
        let meta = Metadata {
            members: vec![Package {
                name: "a".into(),
                dir: PathBuf::new(),
                publish: true,
                rust_version: Some("1.85".into()),
                repository: None,
                dependencies: Vec::new(),
            }],
            resolved: vec![("1.88".into(), "sprs 0.11.3".into()), ("1.70".into(), "glam".into())],
        };
        let (problems, needed) = rust_version(&meta, Path::new("."));
        assert_eq!(problems.len(), 1);
        assert!(needed.starts_with("1.88.0 (sprs"), "{needed}");
    }
}
