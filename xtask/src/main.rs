//! Project automation, one subcommand per module (the rust-analyzer layout):
//!
//! - `cargo xtask validate [--json PATH] [--scale]`: every crate against analytic ground
//!   truth and invariants; prints one table, writes a JSON report, exits
//!   non-zero on any miss.
//! - `cargo xtask bench --mesh PATH [--json OUT] [--runs N]`: times every
//!   implemented operation on one mesh, single-threaded and with default
//!   threads, under stable names shared with `../shared/peers/peer_bench.py`.
//! - `cargo xtask dataset [--out DIR] [--count N] [--seed S]`: mesh files
//!   for `mesh batch` and the Dask example (shapes and shared meshes, moved and
//!   scaled, in every format, one in 50 broken on purpose).
//! - `cargo xtask render [--out DIR]`: a gallery of PNG pictures made with
//!   `mesh render`.
//! - `cargo xtask figures [--out DIR] [--size WxH]`: the chapter's figures made by
//!   `mesh figures` into `docs/figures`, the README's gallery (size-checked).
//! - `cargo xtask publish-check [--names-only]`: every package name free on crates.io
//!   or ours, then `cargo publish --workspace --dry-run`.
//! - `cargo xtask fuzz [--iterations N] [--format F] [--seed S]`: structure-aware
//!   fuzzing of every mesh-io reader, in-process (see RELIABILITY.md).
//! - `cargo xtask tidy`: the repository's rules (used dependencies, true
//!   `rust-version`, `unsafe` allow-list, `# Errors` docs, no machine names);
//!   also a test of this crate.

mod bench;
mod dataset;
mod figures;
mod fuzz;
mod publish_check;
mod render;
mod tidy;
mod validate;

use clap::{Parser, Subcommand};

/// Counts allocations so the fuzzer can bound each input's peak.
#[global_allocator]
static ALLOCATOR: fuzz::alloc::Counting = fuzz::alloc::Counting;

#[derive(Debug, Parser)]
#[command(name = "cargo xtask")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Validate every crate against ground truth and invariants.
    Validate(validate::Args),
    /// Time every operation on a mesh.
    Bench(bench::Args),
    /// Write a dataset of mesh files for `mesh batch` and the Dask example.
    Dataset(dataset::Args),
    /// Render a gallery of PNG pictures.
    Render(render::Args),
    /// Draw the chapter's figures into docs/figures (the README's gallery).
    Figures(figures::Args),
    /// Check names on crates.io and dry-run `cargo publish --workspace`.
    PublishCheck(publish_check::Args),
    /// Fuzz every mesh reader with mutated files.
    Fuzz(fuzz::Args),
    /// Check the repository's rules (dependencies, rust-version, unsafe, docs).
    Tidy(tidy::Args),
}

fn main() {
    let cli = Cli::parse();
    // The commands that use the shared meshes skip them when absent, unless
    // MESH_REQUIRE_SHARED_DATA=1 (continuous integration) makes that a failure.
    let uses_data = matches!(
        cli.command,
        Command::Validate(_) | Command::Render(_) | Command::Figures(_) | Command::Fuzz(_) | Command::Dataset(_)
    );
    let required = if uses_data { mesh_testkit::data::require().map_err(Into::into) } else { Ok(()) };
    let result = required.and_then(|()| match &cli.command {
        Command::Validate(args) => validate::run(args),
        Command::Bench(args) => bench::run(args),
        Command::Dataset(args) => dataset::run(args),
        Command::Render(args) => render::run(args),
        Command::Figures(args) => figures::run(args),
        Command::PublishCheck(args) => publish_check::run(args),
        Command::Fuzz(args) => fuzz::run(args),
        Command::Tidy(args) => tidy::run(args),
    });
    if let Err(e) = result {
        eprintln!("xtask: {e}");
        std::process::exit(1);
    }
}

/// Any error, printed by `main`.
pub type Result<T> = std::result::Result<T, Box<dyn std::error::Error + Send + Sync>>;
