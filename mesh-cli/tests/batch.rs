//! End-to-end tests of `mesh batch`: records, failures, resuming, patterns.

mod common;

use common::mesh_code as mesh;

use std::path::Path;

use serde_json::Value;

fn records(out: &Path) -> Vec<Value> {
    let text = std::fs::read_to_string(out.join("results.jsonl")).unwrap();
    text.lines().map(|l| serde_json::from_str(l).unwrap_or_else(|e| panic!("{e}: {l}"))).collect()
}

/// A folder with three shapes (one in a sub-folder), a file that is not a
/// mesh, and a PLY cut short.
fn dataset(dir: &Path) {
    std::fs::create_dir_all(dir.join("sub")).unwrap();
    for (shape, res, file) in [("icosphere", "2", "a.off"), ("torus", "8", "b.obj"), ("cube", "3", "sub/c.ply")] {
        let path = dir.join(file);
        let (code, _, err) = mesh(&["generate", "--shape", shape, "--res", res, path.to_str().unwrap()]);
        assert_eq!(code, 0, "{err}");
    }
    std::fs::write(dir.join("notes.txt"), "not a mesh").unwrap();
    let good = std::fs::read(dir.join("sub/c.ply")).unwrap();
    std::fs::write(dir.join("broken.ply"), &good[..good.len() / 2]).unwrap();
}

#[test]
fn a_folder_is_processed_failures_recorded_and_a_rerun_resumes() {
    let dir = tempfile::tempdir().unwrap();
    let data = dir.path().join("data");
    dataset(&data);
    // The output folder inside the input folder: never read as input.
    let out = data.join("out");
    let args = |extra: &[&str]| {
        let mut a = vec!["batch", data.to_str().unwrap(), "--recursive", "--do", "info,curvature,hks", "--k", "8"];
        a.extend_from_slice(&["--out", out.to_str().unwrap(), "--jobs", "2", "--json"]);
        a.extend_from_slice(extra);
        a.into_iter().map(str::to_owned).collect::<Vec<_>>()
    };
    let run = |extra: &[&str]| {
        let a = args(extra);
        mesh(&a.iter().map(String::as_str).collect::<Vec<_>>())
    };
    let (code, stdout, stderr) = run(&[]);
    assert_eq!(code, 1, "one mesh fails, so the run does: {stderr}");
    assert!(stderr.contains("1 of 4 meshes failed"), "{stderr}");
    let summary: Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(
        (summary["inputs"].as_u64(), summary["ok"].as_u64(), summary["failed"].as_u64()),
        (Some(4), Some(3), Some(1))
    );
    let first = records(&out);
    assert_eq!(first.len(), 4);
    let by_id = |id: &str| first.iter().find(|r| r["id"] == id).unwrap_or_else(|| panic!("{id}: {first:?}")).clone();
    let broken = by_id("broken.ply");
    assert_eq!(broken["status"], "failed");
    assert!(broken["error"].as_str().unwrap().contains("broken.ply"), "the error names the file: {broken}");
    let sphere = by_id("a.off");
    assert_eq!(sphere["status"], "ok");
    assert_eq!(sphere["vertices"], 162);
    assert_eq!(sphere["sections"]["info"]["genus"], 0);
    assert_eq!(sphere["sections"]["hks"]["times"].as_array().unwrap().len(), 8);
    assert!(sphere["timings_ms"]["curvature"].as_f64().unwrap() >= 0.0);
    // The per-mesh file holds the fields.
    let ply = out.join(sphere["output"].as_str().unwrap());
    let (code, info, err) = mesh(&["info", "--json", ply.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let info: Value = serde_json::from_str(&info).unwrap();
    let names: Vec<&str> = info["attributes"].as_array().unwrap().iter().filter_map(|a| a["name"].as_str()).collect();
    for field in ["gaussian", "mean", "k1", "k2", "hks0", "hks7"] {
        assert!(names.contains(&field), "{field} not in {names:?}");
    }
    assert_eq!(by_id("sub__c.ply")["status"], "ok");

    // Again: only the failed mesh is tried.
    let (code, stdout, _) = run(&[]);
    assert_eq!(code, 1);
    let summary: Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!((summary["skipped_as_done"].as_u64(), summary["processed"].as_u64()), (Some(3), Some(1)));
    // A changed input is done again, and a different configuration redoes all.
    let (code, _, err) =
        mesh(&["generate", "--shape", "icosphere", "--res", "3", data.join("a.off").to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    std::fs::remove_file(data.join("broken.ply")).unwrap();
    let (code, stdout, stderr) = run(&[]);
    assert_eq!(code, 0, "{stderr}");
    let summary: Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!((summary["skipped_as_done"].as_u64(), summary["processed"].as_u64()), (Some(2), Some(1)));
    let last = records(&out).pop().unwrap();
    assert_eq!((last["id"].as_str(), last["vertices"].as_u64()), (Some("a.off"), Some(642)));
    let (code, stdout, _) = run(&["--times", "4"]);
    assert_eq!(code, 0);
    let summary: Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(summary["processed"].as_u64(), Some(3));
}

#[test]
fn patterns_select_files_and_bad_arguments_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let data = dir.path().join("data");
    dataset(&data);
    let out = dir.path().join("out");
    let pattern = data.join("**").join("*.o*");
    let (code, stdout, stderr) =
        mesh(&["batch", pattern.to_str().unwrap(), "--out", out.to_str().unwrap(), "--no-fields", "--json"]);
    assert_eq!(code, 0, "{stderr}");
    let summary: Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(summary["inputs"].as_u64(), Some(2), "a.off and b.obj");
    assert!(records(&out).iter().all(|r| r["output"].is_null()), "--no-fields writes no mesh file");
    for (extra, expect) in [
        (vec!["--do", "colour"], "invalid value 'colour'"),
        (vec!["--jobs", "0"], "--jobs must be in 1..=1024"),
        (vec!["--times", "1000000000"], "--times in 1..=1000"),
        (vec!["--k", "0"], "--k must be in 1..=10000"),
    ] {
        let mut args = vec!["batch", data.to_str().unwrap(), "--out", out.to_str().unwrap()];
        args.extend(extra);
        let (code, _, stderr) = mesh(&args);
        assert_ne!(code, 0);
        assert!(stderr.contains(expect), "{args:?}: {stderr}");
    }
    let missing = data.join("*.xyz");
    let (code, _, stderr) = mesh(&["batch", missing.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert!(code != 0 && stderr.contains("no mesh file"), "{stderr}");
}

/// The resume state follows the files: a deleted output is made again, a
/// run with other options and then the first options again redoes the
/// meshes (the output file holds the last run's fields), and the output
/// folder may be the input folder.
#[test]
fn resuming_checks_the_outputs_and_the_last_options() {
    let dir = tempfile::tempdir().unwrap();
    let data = dir.path().join("data");
    dataset(&data);
    std::fs::remove_file(data.join("broken.ply")).unwrap();
    let d = data.to_str().unwrap();
    let run = |ops: &str| {
        let (code, stdout, stderr) = mesh(&["batch", d, "--do", ops, "--k", "6", "--times", "2", "--out", d, "--json"]);
        assert_eq!(code, 0, "{stderr}");
        let v: Value = serde_json::from_str(&stdout).unwrap();
        (v["inputs"].as_u64().unwrap(), v["processed"].as_u64().unwrap())
    };
    assert_eq!(run("curvature"), (2, 2), "the output folder is the input folder: a.off and b.obj");
    assert_eq!(run("curvature"), (2, 0));
    std::fs::remove_file(data.join("meshes/a.off.ply")).unwrap();
    assert_eq!(run("curvature"), (2, 1), "a deleted output is made again");
    assert_eq!(run("hks"), (2, 2));
    assert_eq!(run("curvature"), (2, 2), "the files hold hks fields now: curvature is redone");
    let (code, info, _) = mesh(&["info", "--json", data.join("meshes/a.off.ply").to_str().unwrap()]);
    assert_eq!(code, 0);
    assert!(info.contains("\"k1\"") && !info.contains("\"hks0\""), "{info}");
}

/// A run that ends while a mesh is processed (killed, out of memory) leaves
/// its start noted without a record: the next run does that mesh last and
/// alone; a mesh that ended two runs is refused, recorded and skipped until
/// `--redo`.
#[test]
fn a_mesh_that_ends_runs_is_retried_alone_then_refused() {
    let dir = tempfile::tempdir().unwrap();
    let data = dir.path().join("data");
    dataset(&data);
    std::fs::remove_file(data.join("broken.ply")).unwrap();
    let out = dir.path().join("out");
    let run = |extra: &[&str]| {
        let mut args = vec!["batch", data.to_str().unwrap(), "--recursive", "--out", out.to_str().unwrap()];
        args.extend_from_slice(&["--jobs", "2", "--json"]);
        args.extend_from_slice(extra);
        let (code, stdout, stderr) = mesh(&args);
        (code, serde_json::from_str::<Value>(&stdout).unwrap_or(Value::Null), stderr)
    };
    // What a run killed while processing a.off leaves: its start, no record.
    let forget = |id: &str| {
        let path = out.join("results.jsonl");
        let kept: Vec<String> = std::fs::read_to_string(&path)
            .unwrap()
            .lines()
            .filter(|l| serde_json::from_str::<Value>(l).unwrap()["id"] != id)
            .map(|l| format!("{l}\n"))
            .collect();
        std::fs::write(&path, kept.concat()).unwrap();
    };
    let (code, summary, stderr) = run(&[]);
    assert_eq!((code, summary["ok"].as_u64()), (0, Some(3)), "{stderr}");
    forget("a.off");
    let (code, summary, stderr) = run(&[]);
    assert_eq!(code, 0, "{stderr}");
    assert_eq!((summary["processed"].as_u64(), summary["retried_alone"].as_u64()), (Some(1), Some(1)));
    let last = records(&out).pop().unwrap();
    assert_eq!((last["id"].as_str(), last["status"].as_str()), (Some("a.off"), Some("ok")));

    // Killed while alone too: refused, with a record saying why.
    forget("a.off");
    let (code, summary, stderr) = run(&[]);
    assert_eq!(code, 1, "{stderr}");
    assert_eq!((summary["failed"].as_u64(), summary["refused_for_ending_runs"].as_u64()), (Some(1), Some(1)));
    let last = records(&out).pop().unwrap();
    assert_eq!(
        (last["id"].as_str(), last["status"].as_str(), last["ended_runs"].as_u64()),
        (Some("a.off"), Some("failed"), Some(2))
    );
    assert!(last["error"].as_str().unwrap().contains("--redo"), "{last}");
    // Skipped from then on, and the run still says so in its status.
    let (code, summary, stderr) = run(&[]);
    assert_eq!((code, summary["processed"].as_u64(), summary["skipped_as_done"].as_u64()), (1, Some(0), Some(2)));
    assert_eq!(summary["refused_for_ending_runs"].as_u64(), Some(1));
    assert!(stderr.contains("ended two runs"), "{stderr}");
    // Other inputs or options are other work: a.off is done under them.
    let (code, summary, stderr) = run(&["--no-fields"]);
    assert_eq!((code, summary["processed"].as_u64()), (0, Some(3)), "{stderr}");
    // --redo tries it again.
    let (code, summary, stderr) = run(&["--redo"]);
    assert_eq!((code, summary["ok"].as_u64()), (0, Some(3)), "{stderr}");
    let (code, summary, _) = run(&[]);
    assert_eq!((code, summary["processed"].as_u64()), (0, Some(0)));
}

/// Two runs into one output folder at once: the second one is refused.
#[test]
fn a_second_run_into_the_same_folder_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let data = dir.path().join("data");
    dataset(&data);
    let out = dir.path().join("out");
    std::fs::create_dir_all(&out).unwrap();
    let held = std::fs::File::create(out.join("batch.lock")).unwrap();
    held.lock().unwrap();
    let args = ["batch", data.to_str().unwrap(), "--out", out.to_str().unwrap()];
    let (code, _, stderr) = mesh(&args);
    assert_ne!(code, 0);
    assert!(stderr.contains("another `mesh batch` is writing to"), "{stderr}");
    assert!(!out.join("results.jsonl").exists(), "the refused run wrote nothing");
    held.unlock().unwrap();
    let (code, _, stderr) = mesh(&args);
    assert_eq!(code, 1, "only broken.ply fails: {stderr}");
}
