//! One module per subcommand, each with `Args` and `run`.

pub mod batch;
pub mod clean;
pub mod convert;
pub mod curvature;
pub mod delaunay;
pub mod figures;
pub mod generate;
pub mod geodesic;
pub mod info;
pub mod nurbs;
pub mod param;
pub mod remesh;
pub mod render;
pub mod report;
pub mod spectral;
pub mod wavelet;

/// Parses the arguments of one command as `mesh <name> <extra>` would (tests).
#[cfg(test)]
pub(crate) fn parse_args<A: clap::Args>(name: &str, extra: &[&str]) -> A {
    match try_parse_args(name, extra) {
        Ok(args) => args,
        Err(e) => e.exit(),
    }
}

/// [`parse_args`], returning clap's error (a name not in an enum's list, a
/// malformed number) instead of exiting (tests).
#[cfg(test)]
pub(crate) fn try_parse_args<A: clap::Args>(name: &str, extra: &[&str]) -> Result<A, clap::Error> {
    use clap::Parser;
    #[derive(Parser)]
    struct Cli<A: clap::Args> {
        #[command(flatten)]
        args: A,
    }
    Ok(Cli::<A>::try_parse_from(std::iter::once(name).chain(extra.iter().copied()))?.args)
}
