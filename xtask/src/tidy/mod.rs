//! `cargo xtask tidy`: the repository's rules, checked from its manifests
//! and sources, also run as a test (`cargo test -p xtask`), in the manner of
//! rust-analyzer's tidy tests. The rules:
//!
//! - every dependency a crate's Cargo.toml declares is used in its sources
//!   (normal ones by the library or binaries, dev ones anywhere);
//! - every member's `rust-version` is at least the largest `rust-version`
//!   of any package resolved for the tier-1 targets ([`deps::TARGETS`], all
//!   features);
//! - no `unsafe` outside [`source::UNSAFE_ALLOWED`] (by file, exact count);
//! - every `pub fn` returning a `Result` in a published crate's `src/`
//!   documents `# Errors`;
//! - no comment (Rust or TOML) and no Markdown document names one machine:
//!   measurements name the hardware ("2-core x86-64 VM"), never
//!   `this machine`; no paths of one computer's file system
//!   ([`source::MACHINE_PHRASES`]; text in backticks is a quotation).

pub mod deps;
mod lexer;
mod source;

use std::fmt;
use std::path::{Path, PathBuf};

use crate::Result;

/// Arguments of `cargo xtask tidy` (none).
#[derive(Debug, clap::Args)]
pub struct Args {}

/// One broken rule, at a file and line (0: the whole file).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Problem {
    /// The file.
    pub path: PathBuf,
    /// 1-based line, or 0.
    pub line: usize,
    /// What is wrong.
    pub message: String,
}

impl Problem {
    fn new(path: &Path, line: usize, message: String) -> Self {
        Problem { path: path.to_path_buf(), line, message }
    }
}

impl fmt::Display for Problem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}: {}", self.path.display(), self.line, self.message)
    }
}

/// The workspace root (the folder above xtask).
pub fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().map_or_else(|| PathBuf::from("."), Path::to_path_buf)
}

/// Runs every rule; prints the problems and fails if there are any.
///
/// # Errors
/// When `cargo metadata` fails, or a rule is broken.
pub fn run(_: &Args) -> Result<()> {
    let (problems, needed) = check(&workspace_root())?;
    for p in &problems {
        eprintln!("{p}");
    }
    if problems.is_empty() {
        println!("tidy: every rule holds (largest dependency rust-version: {needed})");
        Ok(())
    } else {
        Err(format!("tidy: {} problems", problems.len()).into())
    }
}

/// Every rule on the workspace at `root`, and the largest `rust-version`
/// the dependencies declare.
///
/// # Errors
/// When `cargo metadata` fails.
pub fn check(root: &Path) -> Result<(Vec<Problem>, String)> {
    let meta = deps::metadata(root)?;
    let mut problems = deps::unused(&meta.members);
    let (versions, needed) = deps::rust_version(&meta, root);
    problems.extend(versions);
    for package in &meta.members {
        problems.extend(check_sources(root, package));
    }
    problems.extend(check_documents(root, &meta.members));
    Ok((problems, needed))
}

/// The source rules on every Rust file and the manifest of one package.
fn check_sources(root: &Path, package: &deps::Package) -> Vec<Problem> {
    let mut problems = Vec::new();
    for path in rust_files(&package.dir) {
        let Ok(text) = std::fs::read_to_string(&path) else { continue };
        let lexed = lexer::lex(&text);
        let relative = path.strip_prefix(root).unwrap_or(&path).to_string_lossy().replace('\\', "/");
        problems.extend(source::check_unsafe(&relative, &path, &lexed.code));
        if package.publish && path.starts_with(package.dir.join("src")) {
            problems.extend(source::missing_errors_sections(&path, &text, &lexed.code));
        }
        for (line, comment) in &lexed.comments {
            for (k, l) in comment.lines().enumerate() {
                problems.extend(machine(&path, line + k, l));
            }
        }
    }
    let manifest = package.dir.join("Cargo.toml");
    let toml = std::fs::read_to_string(&manifest).unwrap_or_default();
    for (i, line) in toml.lines().enumerate() {
        if let Some((_, comment)) = line.split_once('#') {
            problems.extend(machine(&manifest, i + 1, comment));
        }
    }
    problems
}

/// The machine-naming rule on the Markdown files at the root and in each
/// package, and the root manifest's comments.
fn check_documents(root: &Path, packages: &[deps::Package]) -> Vec<Problem> {
    let mut files: Vec<PathBuf> = markdown(root);
    for p in packages {
        files.extend(markdown(&p.dir));
    }
    files.push(root.join("Cargo.toml"));
    let mut problems = Vec::new();
    for path in files {
        let text = std::fs::read_to_string(&path).unwrap_or_default();
        let toml = path.extension().is_some_and(|e| e == "toml");
        for (i, line) in text.lines().enumerate() {
            let checked = if toml { line.split_once('#').map_or("", |(_, c)| c) } else { line };
            problems.extend(machine(&path, i + 1, checked));
        }
    }
    problems
}

fn machine(path: &Path, line: usize, text: &str) -> Option<Problem> {
    source::names_a_machine(text).map(|p| {
        let rule = "name the hardware (cores, processor) instead";
        Problem::new(path, line, format!("names one machine (`{p}`): {rule}"))
    })
}

/// The `.md` files directly in `dir`.
fn markdown(dir: &Path) -> Vec<PathBuf> {
    let Ok(entries) = std::fs::read_dir(dir) else { return Vec::new() };
    let mut files: Vec<PathBuf> =
        entries.filter_map(|e| e.ok().map(|e| e.path())).filter(|p| p.extension().is_some_and(|e| e == "md")).collect();
    files.sort();
    files
}

/// Every `.rs` file below `dir`, skipping `target` and hidden folders, sorted.
pub fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(&d) else { continue };
        for entry in entries.flatten() {
            let path = entry.path();
            let name = entry.file_name().to_string_lossy().into_owned();
            if path.is_dir() {
                if name != "target" && !name.starts_with('.') {
                    stack.push(path);
                }
            } else if name.ends_with(".rs") {
                out.push(path);
            }
        }
    }
    out.sort();
    out
}

#[cfg(test)]
mod tests {
    /// The rules as a test: `cargo test -p xtask` fails where tidy does.
    #[test]
    fn tidy() {
        let (problems, _) = super::check(&super::workspace_root()).expect("cargo metadata runs");
        let list: Vec<String> = problems.iter().map(ToString::to_string).collect();
        assert!(list.is_empty(), "{} tidy problems:\n{}", list.len(), list.join("\n"));
    }
}
