//! The journal of a batch: `results.jsonl` in the output folder, one JSON
//! object per processed mesh, appended as each mesh finishes (after its
//! output file is in place), so that an interrupted run loses at most the
//! meshes in flight. A later run reads it to skip the meshes already done.

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
/// says what the file holds), and how many lines could not be read.
#[derive(Debug, Default)]
pub struct Previous {
    pub last: HashMap<String, Last>,
    pub unreadable_lines: usize,
}

/// The last record of an id: its stamp, whether it succeeded, and the
/// output file it wrote (relative to the output folder).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Last {
    pub stamp: Stamp,
    pub ok: bool,
    pub output: Option<String>,
}

impl Previous {
    /// Whether the mesh with `stamp` is done: its last record succeeded
    /// with the same stamp, and the output file it wrote is still in `dir`.
    pub fn is_done(&self, stamp: &Stamp, dir: &Path) -> bool {
        self.last.get(&stamp.id).is_some_and(|last| {
            last.ok && last.stamp == *stamp && last.output.as_ref().is_none_or(|o| dir.join(o).is_file())
        })
    }
}

/// Reads the journal in `dir`, if there is one. A line cut short by an
/// interrupted run, or not of ours, is counted and skipped.
pub fn read(dir: &Path) -> CliResult<Previous> {
    let path = dir.join(FILE_NAME);
    let file = match File::open(&path) {
        Ok(f) => f,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Previous::default()),
        Err(e) => return Err(format!("cannot read {}: {e}", path.display()).into()),
    };
    let mut reader = BufReader::new(file);
    let mut previous = Previous::default();
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
            previous.unreadable_lines += 1;
            skip_line(&mut reader).map_err(|e| format!("{}: {e}", path.display()))?;
            continue;
        }
        let text = String::from_utf8_lossy(&line);
        if text.trim().is_empty() {
            continue;
        }
        let record: Option<Value> = serde_json::from_str(text.trim()).ok();
        let last = record.as_ref().and_then(|r| {
            let output = r.get("output").and_then(Value::as_str).map(str::to_owned);
            Some(Last { stamp: Stamp::from_json(r)?, ok: r.get("status")?.as_str()? == "ok", output })
        });
        match last {
            Some(last) => {
                previous.last.insert(last.stamp.id.clone(), last);
            }
            None => previous.unreadable_lines += 1,
        }
    }
    Ok(previous)
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

/// The journal open for appending: one record per call, written with one
/// `write_all` under a lock and flushed, so records never interleave.
pub struct Journal {
    path: PathBuf,
    file: Mutex<File>,
}

impl Journal {
    /// Opens (creates) the journal in `dir` for appending. A journal whose
    /// last line was cut short by an interrupted run gets a line break first,
    /// so that the next record starts on a line of its own.
    pub fn open(dir: &Path) -> CliResult<Self> {
        let path = dir.join(FILE_NAME);
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
        Ok(Self { path, file: Mutex::new(file) })
    }

    /// Appends one record as a line.
    pub fn append(&self, record: &Value) -> CliResult<()> {
        let mut line = serde_json::to_string(record)?;
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
            let j = Journal::open(dir.path()).unwrap();
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
        Journal::open(dir.path()).unwrap().append(&record(&other, "ok")).unwrap();
        let prev = read(dir.path()).unwrap();
        assert!(prev.is_done(&other, dir.path()) && prev.is_done(&ok, dir.path()));
        assert_eq!(prev.unreadable_lines, 1);
        // Only the last record of an id counts: a later failure undoes it.
        Journal::open(dir.path()).unwrap().append(&record(&ok, "failed")).unwrap();
        assert!(!read(dir.path()).unwrap().is_done(&ok, dir.path()));
        // A changed input or configuration is not the same stamp.
        std::fs::write(&input, b"ply changed").unwrap();
        assert_ne!(Stamp::of("a.ply", &input, "info").unwrap(), ok);
        assert_ne!(Stamp { config: "info,hks".into(), ..ok.clone() }, ok);
    }
}
