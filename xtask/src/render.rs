//! `cargo xtask render`: a gallery of PNG pictures of the built-in shapes and
//! the shared meshes, made with the `mesh render` command, in `target/render`.

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::validate::shared_data;
use crate::Result;

/// Arguments of `cargo xtask render`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Output folder.
    #[arg(long, default_value = "target/render")]
    out: PathBuf,
}

/// Runs `mesh` with arguments through cargo (so it is built first).
pub(crate) fn mesh(args: &[&str]) -> Result<()> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let status = Command::new(cargo).args(["run", "--quiet", "--package", "mesh-cli", "--"]).args(args).status()?;
    if !status.success() {
        return Err(format!("mesh {} failed ({status})", args.join(" ")).into());
    }
    Ok(())
}

/// A path as UTF-8 text for a command line.
pub(crate) fn path_str(p: &Path) -> Result<&str> {
    p.to_str().ok_or_else(|| format!("{} is not valid UTF-8", p.display()).into())
}

/// Runs `cargo xtask render`.
pub fn run(args: &Args) -> Result<()> {
    std::fs::create_dir_all(&args.out)?;
    for (shape, res) in [("icosphere", "3"), ("torus", "16"), ("cylinder", "24"), ("disk", "12"), ("cube", "4")] {
        let png = args.out.join(format!("{shape}.png"));
        mesh(&["render", "--shape", shape, "--res", res, "--out", path_str(&png)?])?;
    }
    if let Some(dir) = shared_data() {
        for (file, up) in
            [("cgal_elephant.off", "y"), ("cgal_fandisk.off", "z"), ("npm_bunny.obj", "y"), ("cgal_holes.off", "z")]
        {
            let png = args.out.join(Path::new(file).with_extension("png"));
            mesh(&["render", path_str(&dir.join(file))?, "--up", up, "--out", path_str(&png)?])?;
        }
    } else {
        eprintln!("render: shared meshes skipped: {}", crate::validate::no_shared_data());
    }
    println!("render: pictures in {}", args.out.display());
    Ok(())
}
