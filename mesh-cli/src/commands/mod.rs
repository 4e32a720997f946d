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
