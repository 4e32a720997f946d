//! The journal of a batch: `results.jsonl` in the output folder, one JSON
//! object per processed mesh, appended as each mesh finishes (after its
//! output file is in place), so that an interrupted run loses at most the
//! meshes in flight. A later run reads it to skip the meshes already done.
//!
//! Beside it, `started.jsonl` gets a line (the stamp and the time) as each
//! mesh starts, and each record carries the time its mesh started: a start
//! later than the mesh's last record is a run that ended while processing
//! it (killed, out of memory, interrupted). A later run counts those
//! ([`Previous::interruptions`]) to process such meshes last and one at a
//! time, and to refuse one that ended a run twice instead of letting it end
//! every run.

use std::collections::HashMap;
use std::fs::File;
use std::io::{BufRead, BufReader, Read, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::time::UNIX_EPOCH;

use serde_json::Value;

use crate::output::CliResult;

/// The journal's file name in the output folder.
pub const FILE_NAME: &str = "results.jsonl";

/// The file of starts in the output folder.
pub const STARTED_FILE: &str = "started.jsonl";

/// Lines longer than this are not a record of ours: they are skipped when
/// reading (a journal is never read whole into memory).
const MAX_LINE: u64 = 16 << 20;

/// What identifies a finished piece of work: the input file as it was (path,
/// size and modification time) and the configuration (operations and their
/// parameters). Any change means the mesh is processed again.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct Stamp {
    pub id: String,
    pub input: String,
    pub size: u64,
    pub modified_ns: u128,
    pub config: String,
}

impl Stamp {
    /// The stamp of `path` now, under `config`.
    pub fn of(id: &str, path: &Path, config: &str) -> CliResult<Self> {
        let meta = std::fs::metadata(path).map_err(|e| format!("{}: {e}", path.display()))?;
        let modified_ns =
            meta.modified().ok().and_then(|t| t.duration_since(UNIX_EPOCH).ok()).map_or(0, |d| d.as_nanos());
        Ok(Self {
            id: id.to_owned(),
            input: path.display().to_string(),
            size: meta.len(),
            modified_ns,
            config: config.to_owned(),
        })
    }

    /// The stamp's fields, as they appear in a record.
    pub fn to_json(&self) -> serde_json::Map<String, Value> {
        let mut m = serde_json::Map::new();
        m.insert("id".into(), Value::from(self.id.clone()));
        m.insert("input".into(), Value::from(self.input.clone()));
        m.insert("size".into(), Value::from(self.size));
        // As a string: a nanosecond time does not fit a JSON number exactly.
        m.insert("modified_ns".into(), Value::from(self.modified_ns.to_string()));
        m.insert("config".into(), Value::from(self.config.clone()));
        m
    }

    /// The stamp's fields and the time its mesh started: a line of
    /// [`STARTED_FILE`], and the start of a record.
    pub fn started_json(&self, started_ns: u128) -> serde_json::Map<String, Value> {
        let mut m = self.to_json();
        m.insert("started_ns".into(), Value::from(started_ns.to_string()));
        m
    }

    fn from_json(v: &Value) -> Option<Self> {
        Some(Self {
            id: v.get("id")?.as_str()?.to_owned(),
            input: v.get("input")?.as_str()?.to_owned(),
            size: v.get("size")?.as_u64()?,
            modified_ns: v.get("modified_ns")?.as_str()?.parse().ok()?,
            config: v.get("config")?.as_str()?.to_owned(),
        })
    }
}

/// What an earlier run left: the last record of every id (a later run of
/// other options rewrites the id's output file, so only the last record
/// says what the file holds), the starts of every id, and how many lines
/// could not be read.
#[derive(Debug, Default)]
pub struct Previous {
    pub last: HashMap<String, Last>,
    pub starts: HashMap<String, Vec<(Stamp, u128)>>,
    pub unreadable_lines: usize,
}

/// The last record of an id: its stamp, whether it succeeded, the output
/// file it wrote (relative to the output folder), when its mesh started,
/// and whether it is a refusal of a mesh that ended two runs ([`KILLED`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Last {
    pub stamp: Stamp,
    pub ok: bool,
    pub output: Option<String>,
    pub started_ns: u128,
    pub killed: bool,
}

/// The field that marks the record of a mesh refused because runs ended
/// while processing it.
pub const KILLED: &str = "ended_runs";

impl Previous {
    /// Whether the mesh with `stamp` is done: its last record succeeded
    /// with the same stamp, and the output file it wrote is still in `dir`.
    pub fn is_done(&self, stamp: &Stamp, dir: &Path) -> bool {
        self.last.get(&stamp.id).is_some_and(|last| {
            last.ok && last.stamp == *stamp && last.output.as_ref().is_none_or(|o| dir.join(o).is_file())
        })
    }

    /// How many runs ended while processing the mesh with `stamp` since its
    /// last record: its starts after that record's start.
    pub fn interruptions(&self, stamp: &Stamp) -> usize {
        let since = self.last.get(&stamp.id).map_or(0, |l| l.started_ns);
        self.starts.get(&stamp.id).map_or(0, |s| s.iter().filter(|(st, t)| st == stamp && *t > since).count())
    }

    /// The start time of the last of those interrupted starts, if any.
    pub fn last_start(&self, stamp: &Stamp) -> Option<u128> {
        self.starts.get(&stamp.id)?.iter().filter(|(st, _)| st == stamp).map(|(_, t)| *t).max()
    }

    /// Whether the mesh with `stamp` was refused by an earlier run for
    /// ending runs, and has not been started since.
    pub fn was_refused(&self, stamp: &Stamp) -> bool {
        self.last.get(&stamp.id).is_some_and(|l| l.killed && l.stamp == *stamp) && self.interruptions(stamp) == 0
    }
}

/// Reads the journal and the starts in `dir`, if there are any. A line cut
/// short by an interrupted run, or not of ours, is counted and skipped.
pub fn read(dir: &Path) -> CliResult<Previous> {
    let mut previous = Previous::default();
    let started = |r: &Value| r.get("started_ns").and_then(Value::as_str).and_then(|t| t.parse::<u128>().ok());
    let mut unreadable = each_record(&dir.join(FILE_NAME), |r| {
        let output = r.get("output").and_then(Value::as_str).map(str::to_owned);
        let last = Last {
            stamp: Stamp::from_json(r)?,
            ok: r.get("status")?.as_str()? == "ok",
            output,
            // Records of runs before starts were logged have none.
            started_ns: started(r).unwrap_or(0),
            killed: r.get(KILLED).is_some(),
        };
        previous.last.insert(last.stamp.id.clone(), last);
        Some(())
    })?;
    unreadable += each_record(&dir.join(STARTED_FILE), |r| {
        let stamp = Stamp::from_json(r)?;
        previous.starts.entry(stamp.id.clone()).or_default().push((stamp, started(r)?));
        Some(())
    })?;
    previous.unreadable_lines = unreadable;
    Ok(previous)
}

/// Calls `take` on every JSON line of the file at `path` (none if there is
/// no file); the number of lines that are not JSON, too long, or that
/// `take` refuses.
fn each_record(path: &Path, mut take: impl FnMut(&Value) -> Option<()>) -> CliResult<usize> {
    let file = match File::open(path) {
        Ok(f) => f,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(0),
        Err(e) => return Err(format!("cannot read {}: {e}", path.display()).into()),
    };
    let mut reader = BufReader::new(file);
    let mut unreadable = 0;
    let mut line = Vec::new();
    loop {
        line.clear();
        let n = (&mut reader)
            .take(MAX_LINE)
            .read_until(b'\n', &mut line)
            .map_err(|e| format!("{}: {e}", path.display()))?;
        if n == 0 {
            break;
        }
        if line.last() != Some(&b'\n') && n as u64 == MAX_LINE {
            // Too long: skip to the end of the line.
            unreadable += 1;
            skip_line(&mut reader).map_err(|e| format!("{}: {e}", path.display()))?;
            continue;
        }
        let text = String::from_utf8_lossy(&line);
        if text.trim().is_empty() {
            continue;
        }
        let record: Option<Value> = serde_json::from_str(text.trim()).ok();
        if record.as_ref().and_then(&mut take).is_none() {
            unreadable += 1;
        }
    }
    Ok(unreadable)
}

fn skip_line(reader: &mut impl BufRead) -> std::io::Result<()> {
    loop {
        let buf = reader.fill_buf()?;
        if buf.is_empty() {
            return Ok(());
        }
        if let Some(i) = buf.iter().position(|&b| b == b'\n') {
            reader.consume(i + 1);
            return Ok(());
        }
        let len = buf.len();
        reader.consume(len);
    }
}

/// The journal and the starts open for appending.
pub struct Journal {
    records: Lines,
    starts: Lines,
}

impl Journal {
    /// Opens (creates) the journal and the starts in `dir` for appending;
    /// starts will be noted later than `previous`'s.
    pub fn open(dir: &Path, previous: &Previous) -> CliResult<Self> {
        let mut starts = Lines::open(dir.join(STARTED_FILE))?;
        let latest = previous.starts.values().flatten().map(|(_, t)| *t);
        let latest = latest.chain(previous.last.values().map(|l| l.started_ns)).max().unwrap_or(0);
        starts.last_time = Mutex::new(latest);
        Ok(Self { records: Lines::open(dir.join(FILE_NAME))?, starts })
    }

    /// Appends one record.
    pub fn append(&self, record: &Value) -> CliResult<()> {
        self.records.append(record)
    }

    /// Notes that the mesh with `stamp` starts now; the time to put in its record.
    pub fn start(&self, stamp: &Stamp) -> CliResult<u128> {
        // Strictly after every earlier start of this process or of an
        // earlier one, even on a clock that stands still or steps back.
        let now = std::time::SystemTime::now().duration_since(UNIX_EPOCH).map_or(0, |d| d.as_nanos());
        let t = {
            let mut last = self.starts.last_time.lock().map_err(|_| "the journal lock is poisoned")?;
            *last = now.max(*last + 1);
            *last
        };
        self.starts.append(&Value::Object(stamp.started_json(t)))?;
        Ok(t)
    }
}

/// A file of JSON lines open for appending: one line per call, written with
/// one `write_all` under a lock and flushed, so lines never interleave.
struct Lines {
    path: PathBuf,
    file: Mutex<File>,
    last_time: Mutex<u128>,
}

impl Lines {
    /// Opens (creates) the file for appending. A file whose last line was
    /// cut short by an interrupted run gets a line break first, so that the
    /// next line starts on a line of its own.
    fn open(path: PathBuf) -> CliResult<Self> {
        let mut file = std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .read(true)
            .open(&path)
            .map_err(|e| format!("cannot open {}: {e}", path.display()))?;
        let len = file.metadata().map(|m| m.len()).unwrap_or(0);
        if len > 0 {
            use std::io::{Seek, SeekFrom};
            let mut last = [0u8];
            file.seek(SeekFrom::Start(len - 1))
                .and_then(|_| file.read_exact(&mut last))
                .map_err(|e| format!("{}: {e}", path.display()))?;
            if last[0] != b'\n' {
                file.write_all(b"\n").map_err(|e| format!("{}: {e}", path.display()))?;
            }
        }
        Ok(Self { path, file: Mutex::new(file), last_time: Mutex::new(0) })
    }

    /// Appends one value as a line.
    fn append(&self, record: &Value) -> CliResult<()> {
        let mut line = crate::output::json_text(record, false)?;
        line.push('\n');
        let mut file = self.file.lock().map_err(|_| "the journal lock is poisoned")?;
        file.write_all(line.as_bytes())
            .and_then(|()| file.flush())
            .map_err(|e| format!("{}: {e}", self.path.display()))?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    fn record(stamp: &Stamp, status: &str) -> Value {
        let mut m = stamp.to_json();
        m.insert("status".into(), json!(status));
        Value::Object(m)
    }

    #[test]
    fn records_survive_a_cut_line_and_only_successes_count() {
        let dir = tempfile::tempdir().unwrap();
        let input = dir.path().join("a.ply");
        std::fs::write(&input, b"ply").unwrap();
        let ok = Stamp::of("a.ply", &input, "info").unwrap();
        let failed = Stamp { id: "b.ply".into(), ..ok.clone() };
        {
            let j = Journal::open(dir.path(), &Previous::default()).unwrap();
            j.append(&record(&ok, "ok")).unwrap();
            j.append(&record(&failed, "failed")).unwrap();
        }
        // An interrupted run: half a record, no line break.
        let mut f = std::fs::OpenOptions::new().append(true).open(dir.path().join(FILE_NAME)).unwrap();
        f.write_all(br#"{"id":"c.ply","inp"#).unwrap();
        drop(f);
        let prev = read(dir.path()).unwrap();
        assert!(prev.is_done(&ok, dir.path()));
        assert!(!prev.is_done(&failed, dir.path()));
        assert_eq!(prev.unreadable_lines, 1);
        // Appending after the cut line starts a new line.
        let other = Stamp { id: "d.ply".into(), ..ok.clone() };
        Journal::open(dir.path(), &Previous::default()).unwrap().append(&record(&other, "ok")).unwrap();
        let prev = read(dir.path()).unwrap();
        assert!(prev.is_done(&other, dir.path()) && prev.is_done(&ok, dir.path()));
        assert_eq!(prev.unreadable_lines, 1);
        // Only the last record of an id counts: a later failure undoes it.
        Journal::open(dir.path(), &Previous::default()).unwrap().append(&record(&ok, "failed")).unwrap();
        assert!(!read(dir.path()).unwrap().is_done(&ok, dir.path()));
        // A changed input or configuration is not the same stamp.
        std::fs::write(&input, b"ply changed").unwrap();
        assert_ne!(Stamp::of("a.ply", &input, "info").unwrap(), ok);
        assert_ne!(Stamp { config: "info,hks".into(), ..ok.clone() }, ok);
    }

    #[test]
    fn starts_after_the_last_record_count_as_interruptions() {
        let dir = tempfile::tempdir().unwrap();
        let input = dir.path().join("a.ply");
        std::fs::write(&input, b"ply").unwrap();
        let a = Stamp::of("a.ply", &input, "info").unwrap();
        let other_config = Stamp { config: "hks".into(), ..a.clone() };
        let j = Journal::open(dir.path(), &Previous::default()).unwrap();
        // Started and finished: no interruption.
        let t = j.start(&a).unwrap();
        let mut done = a.started_json(t);
        done.insert("status".into(), serde_json::json!("ok"));
        j.append(&Value::Object(done)).unwrap();
        assert_eq!(read(dir.path()).unwrap().interruptions(&a), 0);
        // Started twice more without a record, once under other options.
        j.start(&a).unwrap();
        j.start(&other_config).unwrap();
        let prev = read(dir.path()).unwrap();
        assert_eq!((prev.interruptions(&a), prev.interruptions(&other_config)), (1, 1));
        // A journal opened later notes its starts after every earlier one,
        // whatever the clock says.
        let later = Journal::open(dir.path(), &prev).unwrap();
        let t2 = later.start(&a).unwrap();
        assert!(prev.starts["a.ply"].iter().all(|(_, t)| *t < t2));
        let prev = read(dir.path()).unwrap();
        assert_eq!(prev.interruptions(&a), 2);
        assert_eq!(prev.last_start(&a), Some(t2));
        // The refusal record (started at the last start) ends the count.
        let mut refused = a.started_json(t2);
        refused.insert("status".into(), serde_json::json!("failed"));
        refused.insert(KILLED.into(), serde_json::json!(2));
        later.append(&Value::Object(refused)).unwrap();
        let prev = read(dir.path()).unwrap();
        assert_eq!(prev.interruptions(&a), 0);
        assert!(prev.was_refused(&a) && !prev.is_done(&a, dir.path()));
        // A start after the refusal (a --redo) is pending again.
        Journal::open(dir.path(), &prev).unwrap().start(&a).unwrap();
        assert!(!read(dir.path()).unwrap().was_refused(&a));
    }
}
