//! `cargo xtask fuzz [--iterations N] [--format F] [--seed S] [--replay I]`:
//! in-process, structure-aware fuzzing of every mesh-io reader on stable
//! Rust. Valid seed files of every format and variant ([`seeds`]) are
//! mutated ([`mutate`]) and run through the reader, the mesh's validation,
//! its connectivity report and `clean` with and without manifold repair
//! ([`harness`]). A finding is a panic, an input taking more than 1 s, a
//! peak allocation above 256 MB for an input under 1 MB (counted by the
//! [`alloc::Counting`] global allocator), a NaN in a result, or a repaired
//! mesh that is not manifold. Every input is rebuilt from (format, seed,
//! iteration); findings are written to `target/fuzz-failures/` with the
//! command that replays them. A watchdog ends the run on an input that
//! takes more than [`HANG_SECONDS`] (a hang), after writing it out.
//!
//! `cargo xtask validate --only fuzz` runs a short campaign per format
//! ([`validate_group`]); RELIABILITY.md records the long ones.

pub mod alloc;
mod harness;
mod mutate;
pub mod panics;
mod rng;
mod seeds;

use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use mesh_io::Format;

use crate::validate::Validator;
use crate::Result;

/// An input running longer than this is a hang: the run stops.
pub const HANG_SECONDS: f64 = 20.0;

/// Inputs per format in `cargo xtask validate` (a few seconds each).
pub const SHORT_RUN: u64 = 5000;

/// Arguments of `cargo xtask fuzz`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Inputs per format.
    #[arg(long, default_value_t = 10_000)]
    iterations: u64,
    /// Only this format (obj, off, ply, stl, gltf, glb).
    #[arg(long)]
    format: Option<String>,
    /// Campaign seed: the same seed gives the same inputs.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Run only this iteration (with --format and --seed) and write its input.
    #[arg(long)]
    replay: Option<u64>,
}

/// Where failing inputs go.
fn failure_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../target/fuzz-failures")
}

/// One finding of a campaign.
#[derive(Debug, Clone)]
pub struct Failure {
    /// Iteration that produced it.
    pub iteration: u64,
    /// Short kind (panic, slow, memory, NaN, ...).
    pub kind: &'static str,
    /// Details.
    pub message: String,
    /// Where the input was written.
    pub file: Option<PathBuf>,
}

/// Figures of one format's campaign.
#[derive(Debug, Clone, Default)]
pub struct Stats {
    /// Inputs run.
    pub inputs: u64,
    /// Inputs the reader accepted.
    pub parsed: u64,
    /// Seed files.
    pub seeds: usize,
    /// Slowest input, seconds.
    pub max_seconds: f64,
    /// Largest peak allocation of an input, bytes.
    pub max_bytes: usize,
    /// Wall time of the campaign, seconds.
    pub wall: f64,
    /// Inputs over the time limit once but not when run again (the
    /// machine was busy).
    pub unconfirmed_slow: u64,
    /// Findings.
    pub failures: Vec<Failure>,
}

/// The input being run, for the watchdog.
#[derive(Default)]
struct Current {
    started: Option<Instant>,
    format: Option<Format>,
    seed: u64,
    iteration: u64,
    bytes: Vec<u8>,
}

/// The command that replays one input.
fn replay_command(format: Format, seed: u64, iteration: u64) -> String {
    format!("cargo xtask fuzz --format {} --seed {seed} --replay {iteration}", format.extension())
}

fn write_input(format: Format, seed: u64, iteration: u64, bytes: &[u8]) -> Option<PathBuf> {
    let dir = failure_dir();
    std::fs::create_dir_all(&dir).ok()?;
    let path = dir.join(format!("{}-seed{seed}-iter{iteration}.{}", format.extension(), format.extension()));
    std::fs::write(&path, bytes).ok()?;
    Some(path)
}

/// Ends the process when one input runs past [`HANG_SECONDS`].
fn watchdog(current: Arc<Mutex<Current>>) {
    std::thread::spawn(move || loop {
        std::thread::sleep(Duration::from_millis(500));
        // The campaign has ended (it dropped its handle).
        if Arc::strong_count(&current) == 1 {
            return;
        }
        let Ok(c) = current.lock() else { return };
        if let (Some(started), Some(format)) = (c.started, c.format) {
            if started.elapsed().as_secs_f64() > HANG_SECONDS {
                let file = write_input(format, c.seed, c.iteration, &c.bytes);
                eprintln!(
                    "\nfuzz: HANG: one input ran {HANG_SECONDS} s; input {}; replay: {}",
                    file.map_or("not written".into(), |p| p.display().to_string()),
                    replay_command(format, c.seed, c.iteration)
                );
                std::process::exit(3);
            }
        }
    });
}

/// The mutated input of one iteration, with the seed's name and the
/// mutations applied.
fn input(format: Format, all: &[seeds::Seed], seed: u64, iteration: u64) -> (Vec<u8>, String) {
    let index = Format::ALL.iter().position(|f| *f == format).unwrap_or(0) as u64;
    let mut rng = rng::for_input(index, seed, iteration);
    let base = rng::pick(&mut rng, all);
    let other = rng::pick(&mut rng, all);
    let (bytes, applied) = mutate::mutate(&mut rng, &base.bytes, &other.bytes);
    (bytes, format!("seed file `{}`, mutations: {}", base.name, applied.join(", ")))
}

/// Runs `iterations` inputs of one format; `progress` prints a line every
/// so often.
pub fn campaign(format: Format, seed: u64, iterations: u64, progress: bool) -> Result<Stats> {
    let all = seeds::seeds(format)?;
    if all.is_empty() {
        return Err(format!("no seed files for {}", format.extension()).into());
    }
    let current = Arc::new(Mutex::new(Current::default()));
    watchdog(current.clone());
    let mut stats = Stats { seeds: all.len(), ..Stats::default() };
    let start = Instant::now();
    panics::quietly(|| {
        for iteration in 0..iterations {
            // A panic here is the fuzzer's own bug: stop with its message.
            let (bytes, _) = match panics::catch(|| input(format, &all, seed, iteration)) {
                Ok(made) => made,
                Err(panic) => {
                    eprintln!("fuzz: building input {iteration} panicked: {panic}");
                    std::process::exit(4);
                }
            };
            alloc::set_context(&replay_command(format, seed, iteration));
            if let Ok(mut c) = current.lock() {
                c.bytes.clear();
                c.bytes.extend_from_slice(&bytes);
                (c.format, c.seed, c.iteration, c.started) = (Some(format), seed, iteration, Some(Instant::now()));
            }
            let mut outcome = harness::run(&bytes, format);
            if outcome.finding.as_ref().is_some_and(|f| f.0 == "slow") {
                // Wall time on a shared machine: a slow input counts only
                // when it is slow again.
                let again = harness::run(&bytes, format);
                if again.seconds <= harness::MAX_SECONDS {
                    stats.unconfirmed_slow += 1;
                    outcome = again;
                }
            }
            if let Ok(mut c) = current.lock() {
                c.started = None;
            }
            stats.inputs += 1;
            stats.parsed += u64::from(outcome.parsed);
            stats.max_seconds = stats.max_seconds.max(outcome.seconds);
            stats.max_bytes = stats.max_bytes.max(outcome.peak_bytes);
            if let Some((kind, message)) = outcome.finding {
                let file = write_input(format, seed, iteration, &bytes);
                stats.failures.push(Failure { iteration, kind, message, file });
            }
            if progress && (iteration + 1) % 100_000 == 0 {
                eprintln!(
                    "fuzz: {} {} inputs, {} findings, {:.0} s",
                    format.extension(),
                    iteration + 1,
                    stats.failures.len(),
                    start.elapsed().as_secs_f64()
                );
            }
        }
    });
    if let Ok(mut c) = current.lock() {
        c.format = None;
    }
    stats.wall = start.elapsed().as_secs_f64();
    Ok(stats)
}

/// The formats named by `--format`, or all of them.
fn formats(name: Option<&str>) -> Result<Vec<Format>> {
    match name {
        None => Ok(Format::ALL.to_vec()),
        Some(n) => Format::from_extension(n)
            .map(|f| vec![f])
            .ok_or_else(|| format!("unknown format `{n}`; known: obj, off, ply, stl, gltf, glb").into()),
    }
}

fn summary(format: Format, s: &Stats) -> String {
    format!(
        "{}: {} inputs from {} seeds ({} parsed), {} findings, max {:.1} ms, max {:.1} MB, {:.1} s{}",
        format.extension(),
        s.inputs,
        s.seeds,
        s.parsed,
        s.failures.len(),
        s.max_seconds * 1e3,
        s.max_bytes as f64 / (1 << 20) as f64,
        s.wall,
        if s.unconfirmed_slow > 0 {
            format!(", {} slow once but not again", s.unconfirmed_slow)
        } else {
            String::new()
        }
    )
}

/// Runs `cargo xtask fuzz`.
pub fn run(args: &Args) -> Result<()> {
    let formats = formats(args.format.as_deref())?;
    if let Some(iteration) = args.replay {
        return replay(&formats, args.seed, iteration);
    }
    let mut findings = 0;
    for format in formats {
        let stats = campaign(format, args.seed, args.iterations, true)?;
        println!("{}", summary(format, &stats));
        for f in &stats.failures {
            println!(
                "  {} at iteration {}: {}\n    input: {}\n    replay: {}",
                f.kind,
                f.iteration,
                f.message,
                f.file.as_ref().map_or("not written".into(), |p| p.display().to_string()),
                replay_command(format, args.seed, f.iteration)
            );
        }
        findings += stats.failures.len();
    }
    if findings > 0 {
        return Err(format!("{findings} fuzz findings").into());
    }
    Ok(())
}

/// Rebuilds one input, writes it, and runs it with panics shown.
fn replay(formats: &[Format], seed: u64, iteration: u64) -> Result<()> {
    let [format] = formats else { return Err("--replay needs --format".into()) };
    let all = seeds::seeds(*format)?;
    let (bytes, how) = input(*format, &all, seed, iteration);
    let file = write_input(*format, seed, iteration, &bytes).ok_or("cannot write the input")?;
    println!("input ({} bytes, {how}) written to {}", bytes.len(), file.display());
    let outcome = harness::run(&bytes, *format);
    println!(
        "parsed: {}, {:.3} ms, peak {:.2} MB, finding: {:?}",
        outcome.parsed,
        outcome.seconds * 1e3,
        outcome.peak_bytes as f64 / (1 << 20) as f64,
        outcome.finding
    );
    Ok(())
}

/// Kinds of finding, as the short run reports them.
const KINDS: &[(&str, &[&str])] = &[
    ("panics", &["panic"]),
    ("inputs over 1 s", &["slow"]),
    ("inputs over 256 MB", &["memory"]),
    ("NaN or infinity in a mesh", &["NaN"]),
    ("NaN or infinity in an attribute (normal, uv, colour)", &["non-finite attribute"]),
    ("invalid meshes or non-manifold repairs", &["invalid mesh", "not manifold"]),
];

/// The short run of `cargo xtask validate`: [`SHORT_RUN`] inputs per format
/// (seed 0); no finding of any kind, every input under 1 s and 256 MB.
pub fn validate_group(v: &mut Validator) {
    for format in Format::ALL {
        let name = format.extension();
        let s = match campaign(format, 0, SHORT_RUN, false) {
            Ok(s) => s,
            Err(e) => {
                v.error(format!("{name}: seed files"), e);
                continue;
            }
        };
        for (what, kinds) in KINDS {
            let found: Vec<&Failure> = s.failures.iter().filter(|f| kinds.contains(&f.kind)).collect();
            let note = match found.first() {
                None => String::new(),
                Some(f) => format!(
                    "first at iteration {}: {} ({})",
                    f.iteration,
                    f.message,
                    replay_command(format, 0, f.iteration)
                ),
            };
            v.holds(format!("{name}: {what}: {} of {} inputs", found.len(), s.inputs), found.is_empty(), note);
        }
        v.at_most(format!("{name}: slowest input, s"), s.max_seconds, harness::MAX_SECONDS);
        v.at_most(
            format!("{name}: largest peak allocation of an input, MB"),
            s.max_bytes as f64 / (1 << 20) as f64,
            (harness::MAX_BYTES >> 20) as f64,
        );
        v.holds(format!("{name}: campaign"), true, summary(format, &s));
    }
}
