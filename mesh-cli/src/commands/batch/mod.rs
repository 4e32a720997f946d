//! `mesh batch`: one or more operations over every mesh of a dataset, on
//! several threads, resumable.
//!
//! ```text
//! mesh batch DIR_OR_GLOB... --do info,curvature,hks --out OUT [--jobs N]
//! ```
//!
//! - Inputs: folders (their mesh files; sub-folders with `--recursive`),
//!   patterns (`'data/**/*.ply'`, quoted so the shell leaves them alone) and
//!   files; never the per-mesh files a batch wrote (`OUT/meshes`).
//! - `OUT/results.jsonl`: one JSON object per mesh, appended as each one
//!   finishes: the input's path, size and time stamp, the configuration,
//!   `status` (`ok` or `failed` with its `error`), vertex and face counts,
//!   one section of summary figures per operation and the time of each.
//! - `OUT/meshes/<id>.ply`: the mesh with every per-vertex field computed
//!   (curvatures, distance, hks0...), binary PLY, written atomically before
//!   its record.
//! - A mesh that fails is recorded with its error and the run goes on; the
//!   exit status is 1 when any mesh failed, after all were tried.
//! - Running again skips the meshes whose last record says `ok` for the
//!   same file (path, size, modification time) and configuration and whose
//!   output file is still there, so an interrupted run resumes where it
//!   stopped; `--redo` processes all.
//! - `OUT/started.jsonl` notes each mesh as it starts. A mesh that was
//!   started after its last record was being processed when a run ended
//!   (killed, out of memory, interrupted): the next run processes it after
//!   the others and alone, so that it cannot take other meshes down with it
//!   and is known for certain if it ends that run too. A mesh that ended two
//!   runs is not tried again: it gets a `failed` record with
//!   `"ended_runs": 2` and the run exits with status 1; later runs skip it
//!   (and still exit 1) until `--redo`.
//! - One run at a time per output folder: a second one exits at once with
//!   an error (an advisory lock on `OUT/batch.lock`, released however the
//!   first run ends).
//! - Progress: a bar on a terminal, one line per mesh otherwise.

mod inputs;
mod journal;
mod ops;

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use rayon::prelude::*;
use serde_json::{json, Value};

use self::inputs::Input;
use self::journal::{Journal, Stamp};
pub use self::ops::Op;
use self::ops::Params;
use crate::choice::choice;
use crate::output::{binary_ply, check_output, print_json, write_mesh, CliResult};

/// Arguments of `mesh batch`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Folders, mesh files or quoted patterns (`*`, `?`, `[a-z]`, `**` for any depth of folders).
    #[arg(value_name = "DIR_OR_GLOB", required = true)]
    inputs: Vec<PathBuf>,
    /// Operations, comma-separated.
    #[arg(long = "do", value_name = "OPS", value_delimiter = ',', default_value = "info",
          value_parser = choice::<Op>(Op::ALL.map(Op::name)))]
    ops: Vec<Op>,
    /// Output folder (created if needed): results.jsonl and meshes/.
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
    /// Meshes processed at once (default: the number of cores). Each mesh's
    /// own loops share the same threads.
    #[arg(long, value_name = "N")]
    jobs: Option<usize>,
    /// Also the mesh files of sub-folders of a folder given.
    #[arg(long)]
    recursive: bool,
    /// Eigenpairs for `eigen` and `hks`.
    #[arg(long, default_value_t = 30)]
    k: usize,
    /// Times of the heat kernel signature.
    #[arg(long, default_value_t = 8)]
    times: usize,
    /// Write only the journal, no per-mesh PLY files.
    #[arg(long)]
    no_fields: bool,
    /// Process every mesh again, even those the journal records as done.
    #[arg(long)]
    redo: bool,
    /// Print the run's summary as one JSON object.
    #[arg(long)]
    json: bool,
}

/// The folder of per-mesh files inside the output folder.
const MESHES: &str = "meshes";

/// Bounds of the options that size allocations or thread pools.
const MAX_K: usize = 10_000;
const MAX_TIMES: usize = 1_000;
const MAX_JOBS: usize = 1_024;

/// Runs `mesh batch`.
pub fn run(args: &Args) -> CliResult<()> {
    let start = Instant::now();
    let mut ops = args.ops.clone();
    ops.sort();
    ops.dedup();
    if !(1..=MAX_K).contains(&args.k) || !(1..=MAX_TIMES).contains(&args.times) {
        return Err(format!("--k must be in 1..={MAX_K} and --times in 1..={MAX_TIMES}").into());
    }
    let jobs = match args.jobs {
        Some(n) if !(1..=MAX_JOBS).contains(&n) => return Err(format!("--jobs must be in 1..={MAX_JOBS}").into()),
        Some(n) => n,
        None => std::thread::available_parallelism().map_or(1, |n| n.get()),
    };
    std::fs::create_dir_all(args.out.join(MESHES))
        .map_err(|e| format!("cannot create {}: {e}", args.out.join(MESHES).display()))?;
    let _lock = lock(&args.out)?;
    // Only what this command writes is left out of the inputs (the output
    // folder may be the input folder).
    let all = inputs::collect(&args.inputs, args.recursive, &args.out.join(MESHES))?;
    let config = config_string(&ops, args);
    let previous = journal::read(&args.out)?;
    let Plan { todo, alone, ended_twice, refused_before } = plan(&all, &previous, &config, args)?;
    let skipped = all.len() - todo.len() - alone.len() - ended_twice.len() - refused_before;
    let journal = Journal::open(&args.out, &previous)?;
    let progress = Progress::new(todo.len() + alone.len() + ended_twice.len());
    let pool = rayon::ThreadPoolBuilder::new().num_threads(jobs).build()?;
    let params = Params { k: args.k, times: args.times };
    let finish = |input: &Input, mut record: Value| {
        if let Err(e) = journal.append(&record) {
            // Not recorded: the next run does it again; this one fails.
            record["status"] = json!("failed");
            record["error"] = json!(format!("the record could not be written: {e}"));
        }
        progress.finished(&input.id, &record);
        record
    };
    let mut records: Vec<Value> = ended_twice
        .iter()
        .map(|(input, stamp)| finish(input, refusal(stamp, &previous, previous.interruptions(stamp))))
        .collect();
    let run_one = |(input, stamp): &(&Input, Stamp)| finish(input, process(input, stamp, &journal, &ops, params, args));
    records.extend(pool.install(|| todo.par_iter().with_max_len(1).map(run_one).collect::<Vec<_>>()));
    // One at a time, each mesh's own loops on every thread.
    records.extend(pool.install(|| alone.iter().map(run_one).collect::<Vec<_>>()));
    progress.finish();
    let ok = records.iter().filter(|r| r["status"] == "ok").count();
    let failed = records.len() - ok;
    let wall_s = start.elapsed().as_secs_f64();
    let vertices: u64 = records.iter().filter_map(|r| r["vertices"].as_u64()).sum();
    let summary = json!({
        "inputs": all.len(),
        "skipped_as_done": skipped,
        "processed": records.len(),
        "ok": ok,
        "failed": failed,
        "jobs": jobs,
        "operations": ops.iter().map(|o| o.name()).collect::<Vec<_>>(),
        "wall_s": wall_s,
        "meshes_per_s": records.len() as f64 / wall_s,
        "vertices_per_s": vertices as f64 / wall_s,
        "retried_alone": alone.len(),
        "refused_for_ending_runs": ended_twice.len() + refused_before,
        "journal": args.out.join(journal::FILE_NAME).display().to_string(),
        "unreadable_journal_lines": previous.unreadable_lines,
    });
    if args.json {
        print_json(&summary)?;
    } else {
        println!(
            "{} meshes: {ok} ok, {failed} failed, {skipped} already done{}; {wall_s:.1} s, {:.1} meshes/s, \
             {:.0} vertices/s ({} threads); records in {}",
            all.len(),
            if refused_before > 0 { format!(", {refused_before} skipped for ending two runs") } else { String::new() },
            records.len() as f64 / wall_s,
            vertices as f64 / wall_s,
            jobs,
            args.out.join(journal::FILE_NAME).display()
        );
    }
    if failed > 0 {
        return Err(format!(
            "{failed} of {} meshes failed (their records in {} have \"status\": \"failed\" and the error)",
            records.len(),
            args.out.join(journal::FILE_NAME).display()
        )
        .into());
    }
    if refused_before > 0 {
        return Err(format!(
            "{refused_before} of the meshes were not tried: each ended two runs while being processed (their records in {} \
             have \"{}\"; --redo tries them again)",
            args.out.join(journal::FILE_NAME).display(),
            journal::KILLED
        )
        .into());
    }
    Ok(())
}

/// What a run does with its inputs.
struct Plan<'a> {
    /// In parallel, largest files first (the long meshes start early and
    /// the short ones fill in).
    todo: Vec<(&'a Input, Stamp)>,
    /// After those, one at a time: a run ended while each was processed.
    alone: Vec<(&'a Input, Stamp)>,
    /// Not tried: two runs ended while each was processed; recorded as failed.
    ended_twice: Vec<(&'a Input, Stamp)>,
    /// Not tried and not recorded again: refused by an earlier run.
    refused_before: usize,
}

/// Sorts the inputs by what the journal says of them (everything is done
/// again under `--redo`); those done are left out.
fn plan<'a>(all: &'a [Input], previous: &journal::Previous, config: &str, args: &Args) -> CliResult<Plan<'a>> {
    let mut plan = Plan { todo: Vec::new(), alone: Vec::new(), ended_twice: Vec::new(), refused_before: 0 };
    for input in all {
        let stamp = Stamp::of(&input.id, &input.path, config)?;
        if args.redo {
            plan.todo.push((input, stamp));
        } else if previous.was_refused(&stamp) {
            plan.refused_before += 1;
        } else if !previous.is_done(&stamp, &args.out) {
            match previous.interruptions(&stamp) {
                0 => plan.todo.push((input, stamp)),
                1 => plan.alone.push((input, stamp)),
                _ => plan.ended_twice.push((input, stamp)),
            }
        }
    }
    plan.todo.sort_by(|a, b| b.1.size.cmp(&a.1.size).then_with(|| a.0.id.cmp(&b.0.id)));
    Ok(plan)
}

/// The failed record of a mesh during which `count` runs ended (after the
/// first, it was processed alone): it is not tried again.
fn refusal(stamp: &Stamp, previous: &journal::Previous, count: usize) -> Value {
    let mut record = stamp.started_json(previous.last_start(stamp).unwrap_or(0));
    record.insert("status".into(), json!("failed"));
    record.insert(
        "error".into(),
        json!(format!(
            "{count} runs ended while processing this mesh (killed, out of memory?), the later ones with no \
             other mesh in progress: not tried again until --redo"
        )),
    );
    record.insert(journal::KILLED.into(), json!(count));
    record.insert("total_ms".into(), json!(0.0));
    Value::Object(record)
}

/// The lock file in the output folder.
const LOCK: &str = "batch.lock";

/// Locks the output folder for this run (an advisory lock on `OUT/batch.lock`,
/// released when the run ends, however it ends): a second run on the same
/// folder would redo the first one's meshes and take its meshes in flight
/// for ones that ended a run. Where the file system has no locks, the run
/// goes on with a warning.
fn lock(out: &std::path::Path) -> CliResult<Option<std::fs::File>> {
    let path = out.join(LOCK);
    let file = std::fs::OpenOptions::new()
        .create(true)
        .truncate(false)
        .write(true)
        .open(&path)
        .map_err(|e| format!("cannot open {}: {e}", path.display()))?;
    match file.try_lock() {
        Ok(()) => Ok(Some(file)),
        Err(std::fs::TryLockError::WouldBlock) => Err(format!(
            "another `mesh batch` is writing to {} (it holds {}): wait for it to end, or choose another --out",
            out.display(),
            path.display()
        )
        .into()),
        Err(std::fs::TryLockError::Error(e)) => {
            eprintln!(
                "warning: {} cannot be locked ({e}); do not run two batches into this folder at once",
                path.display()
            );
            Ok(None)
        }
    }
}

/// The configuration a record was made under: operations and parameters.
fn config_string(ops: &[Op], args: &Args) -> String {
    let names: Vec<&str> = ops.iter().map(|o| o.name()).collect();
    format!("do={};k={};times={};fields={}", names.join(","), args.k, args.times, !args.no_fields)
}

/// Notes the start of one mesh and processes it into its record; never
/// fails and never unwinds: an error (or a panic, which would be a bug)
/// becomes a `failed` record.
fn process(input: &Input, stamp: &Stamp, journal: &Journal, ops: &[Op], params: Params, args: &Args) -> Value {
    let start = Instant::now();
    let (started_ns, result) = match journal.start(stamp) {
        Ok(t) => (
            t,
            catch_unwind(AssertUnwindSafe(|| process_mesh(input, ops, params, args)))
                .unwrap_or_else(|panic| Err(format!("internal error: {}", panic_text(&panic)).into())),
        ),
        Err(e) => (0, Err(format!("the start could not be noted: {e}").into())),
    };
    let mut record = stamp.started_json(started_ns);
    match result {
        Ok(fields) => {
            record.insert("status".into(), json!("ok"));
            record.extend(fields);
        }
        Err(e) => {
            record.insert("status".into(), json!("failed"));
            record.insert("error".into(), json!(e.to_string()));
        }
    }
    record.insert("total_ms".into(), json!(start.elapsed().as_secs_f64() * 1e3));
    Value::Object(record)
}

fn panic_text(panic: &Box<dyn std::any::Any + Send>) -> String {
    panic
        .downcast_ref::<String>()
        .cloned()
        .or_else(|| panic.downcast_ref::<&str>().map(|s| (*s).to_owned()))
        .unwrap_or_else(|| "a panic".to_owned())
}

fn process_mesh(input: &Input, ops: &[Op], params: Params, args: &Args) -> CliResult<serde_json::Map<String, Value>> {
    let read_start = Instant::now();
    let data = mesh_io::read(&input.path).map_err(crate::errors::io)?;
    let read_ms = read_start.elapsed().as_secs_f64() * 1e3;
    let mesh = &data.mesh;
    let mut outcome = ops::run(mesh, ops, params)?;
    outcome.timings_ms.insert("read".into(), json!(read_ms));
    let mut record = serde_json::Map::new();
    record.insert("vertices".into(), json!(mesh.vertex_count()));
    record.insert("faces".into(), json!(mesh.face_count()));
    if !data.report.is_clean() {
        record.insert("read_changed".into(), json!(data.report.to_string()));
    }
    if !args.no_fields && !outcome.fields.is_empty() {
        let name = format!("{MESHES}/{}.ply", input.id);
        let path = args.out.join(&name);
        check_output(&path, Some(&input.path), false)?;
        let mut view = mesh_io::MeshView::new(mesh);
        for (field, values) in &outcome.fields {
            view = view.with_scalar(field, values);
        }
        write_mesh(&path, view, &binary_ply())?;
        record.insert("output".into(), json!(name));
    }
    record.insert("sections".into(), Value::Object(outcome.sections));
    record.insert("timings_ms".into(), Value::Object(outcome.timings_ms));
    Ok(record)
}

/// Progress on standard error: a bar on a terminal, a line per mesh
/// otherwise (logs, CI).
struct Progress {
    bar: Option<indicatif::ProgressBar>,
    done: AtomicUsize,
    total: usize,
}

impl Progress {
    fn new(total: usize) -> Self {
        use std::io::IsTerminal;
        let bar = std::io::stderr().is_terminal().then(|| {
            let bar = indicatif::ProgressBar::new(total as u64);
            if let Ok(style) = indicatif::ProgressStyle::with_template(
                "{bar:40} {pos}/{len} meshes, {elapsed} elapsed, {eta} left {msg}",
            ) {
                bar.set_style(style);
            }
            bar
        });
        Self { bar, done: AtomicUsize::new(0), total }
    }

    fn finished(&self, id: &str, record: &Value) {
        let done = self.done.fetch_add(1, Ordering::Relaxed) + 1;
        let status = match &record["error"] {
            Value::String(e) => format!("failed: {e}"),
            _ => format!("ok, {:.0} ms", record["total_ms"].as_f64().unwrap_or(0.0)),
        };
        match &self.bar {
            Some(bar) => {
                if record["status"] != "ok" {
                    bar.println(format!("{id}: {status}"));
                }
                bar.inc(1);
            }
            None => eprintln!("[{done}/{}] {id}: {status}", self.total),
        }
    }

    fn finish(&self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}
