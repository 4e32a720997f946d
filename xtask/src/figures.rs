//! `cargo xtask figures`: the README's gallery, the chapter's figures made
//! by `mesh figures` into `docs/figures` with small panels, checked to stay
//! small enough to commit (each PNG under 150 kB, all under 1.5 MB).

use std::path::PathBuf;

use crate::render::{mesh, path_str};
use crate::validate::shared_data;
use crate::Result;

/// Largest size of one PNG of the gallery, bytes.
const MAX_PNG: u64 = 150_000;
/// Largest size of the whole gallery, bytes.
const MAX_TOTAL: u64 = 1_500_000;

/// Arguments of `cargo xtask figures`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Output folder.
    #[arg(long, default_value = "docs/figures")]
    out: PathBuf,
    /// Size of each panel, WxH.
    #[arg(long, default_value = "220x200")]
    size: String,
}

/// Runs `cargo xtask figures`.
pub fn run(args: &Args) -> Result<()> {
    std::fs::create_dir_all(&args.out)?;
    let out = path_str(&args.out)?;
    match shared_data() {
        Some(dir) => mesh(&["figures", "--out", out, "--size", &args.size, "--data", path_str(&dir)?])?,
        None => {
            eprintln!("figures: {}; drawing built-in stand-ins", crate::validate::no_shared_data());
            mesh(&["figures", "--out", out, "--size", &args.size])?
        }
    }
    let mut total = 0;
    let mut too_big = Vec::new();
    for entry in std::fs::read_dir(&args.out)? {
        let entry = entry?;
        if entry.path().extension().is_some_and(|e| e == "png") {
            let size = entry.metadata()?.len();
            total += size;
            if size > MAX_PNG {
                too_big.push(format!("{} ({size} bytes)", entry.path().display()));
            }
        }
    }
    if !too_big.is_empty() || total > MAX_TOTAL {
        return Err(format!(
            "the gallery is too large to commit: {total} bytes in all (at most {MAX_TOTAL}); over {MAX_PNG} bytes: {}",
            too_big.join(", ")
        )
        .into());
    }
    println!("figures: {} ({total} bytes of PNG)", args.out.display());
    Ok(())
}
