//! One module per subcommand, each with `Args` and `run`.

pub mod clean;
pub mod convert;
pub mod curvature;
pub mod generate;
pub mod geodesic;
pub mod info;
pub mod nurbs;
pub mod param;
pub mod render;
pub mod report;
pub mod spectral;
pub mod wavelet;

/// Parses the arguments of one command as `mesh <name> <extra>` would (tests).
#[cfg(test)]
pub(crate) fn parse_args<A: clap::Args>(name: &str, extra: &[&str]) -> A {
    use clap::Parser;
    #[derive(Parser)]
    struct Cli<A: clap::Args> {
        #[command(flatten)]
        args: A,
    }
    Cli::<A>::parse_from(std::iter::once(name).chain(extra.iter().copied())).args
}

/// `../shared/data` (real test meshes), or `None` with a message when it
/// is absent (tests).
#[cfg(test)]
pub(crate) fn shared_data() -> Option<std::path::PathBuf> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/data");
    if !dir.is_dir() {
        eprintln!("skipping: {} is absent", dir.display());
        return None;
    }
    Some(dir)
}
