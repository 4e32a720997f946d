//! Project automation, one subcommand per module (the rust-analyzer layout):
//!
//! - `cargo xtask validate [--json PATH] [--scale]`: every crate against analytic ground
//!   truth and invariants; prints one table, writes a JSON report, exits
//!   non-zero on any miss.
//! - `cargo xtask bench --mesh PATH [--json OUT] [--runs N]`: times every
//!   implemented operation on one mesh, single-threaded and with default
//!   threads, under stable names shared with `../shared/peers/peer_bench.py`.
//! - `cargo xtask render [--out DIR]`: a gallery of PNG pictures made with
//!   `mesh render`.
//! - `cargo xtask publish-check`: packages every publishable crate.
//! - `cargo xtask fuzz [--iterations N] [--format F] [--seed S]`: structure-aware
//!   fuzzing of every mesh-io reader, in-process (see RELIABILITY.md).

mod bench;
mod fuzz;
mod publish_check;
mod render;
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
    /// Render a gallery of PNG pictures.
    Render(render::Args),
    /// Package every publishable crate in dependency order.
    PublishCheck(publish_check::Args),
    /// Fuzz every mesh reader with mutated files.
    Fuzz(fuzz::Args),
}

fn main() {
    let cli = Cli::parse();
    let result = match &cli.command {
        Command::Validate(args) => validate::run(args),
        Command::Bench(args) => bench::run(args),
        Command::Render(args) => render::run(args),
        Command::PublishCheck(args) => publish_check::run(args),
        Command::Fuzz(args) => fuzz::run(args),
    };
    if let Err(e) = result {
        eprintln!("xtask: {e}");
        std::process::exit(1);
    }
}

/// Any error, printed by `main`.
pub type Result<T> = std::result::Result<T, Box<dyn std::error::Error + Send + Sync>>;
