//! Which files a batch processes: every mesh file (by extension) of a
//! folder, of a glob pattern, or a file named outright, each with an id that
//! names its outputs and its line in the journal.
//!
//! Only what the user named is read: a folder's files (its sub-folders with
//! `--recursive`, never through a symbolic link to a folder, so no cycle),
//! the paths a pattern matches, and nothing under the output folder. The
//! order is sorted, so ids and the journal do not depend on the file system.

use std::path::{Component, Path, PathBuf};

use crate::output::CliResult;

/// A mesh file to process and its id (its path from the folder or the
/// pattern's fixed prefix, `/` turned into `__` and unusual characters
/// into `_`: stable between runs; two paths that come out the same, such as
/// `a b.ply` and `a_b.ply`, are refused by [`collect`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Input {
    pub path: PathBuf,
    pub id: String,
}

/// Deepest folder level searched by `**` or `--recursive`.
const MAX_DEPTH: usize = 32;

/// Every mesh file the arguments name, sorted by id; two inputs with the
/// same id are an error (they would write the same outputs).
pub fn collect(args: &[PathBuf], recursive: bool, exclude: &Path) -> CliResult<Vec<Input>> {
    let exclude = exclude.canonicalize().ok();
    let mut out = Vec::new();
    for arg in args {
        let found = expand(arg, recursive)?;
        if found.is_empty() {
            return Err(format!("{}: no mesh file (.obj .off .ply .stl .gltf .glb) found", arg.display()).into());
        }
        out.extend(found.into_iter().filter(|input| !is_under(&input.path, exclude.as_deref())));
    }
    out.sort_by(|a, b| a.id.cmp(&b.id));
    if let Some(w) = out.windows(2).find(|w| w[0].id == w[1].id) {
        return Err(format!(
            "{} and {} would write the same outputs (id {}): give them in separate runs or folders",
            w[0].path.display(),
            w[1].path.display(),
            w[0].id
        )
        .into());
    }
    Ok(out)
}

fn is_under(path: &Path, dir: Option<&Path>) -> bool {
    match (dir, path.canonicalize()) {
        (Some(dir), Ok(p)) => p.starts_with(dir),
        _ => false,
    }
}

/// Whether a file name has a mesh format's extension.
pub fn is_mesh_file(path: &Path) -> bool {
    path.extension().and_then(|e| e.to_str()).and_then(mesh_io::Format::from_extension).is_some()
}

/// The mesh files one argument names: a file, a folder, or a pattern.
fn expand(arg: &Path, recursive: bool) -> CliResult<Vec<Input>> {
    let text = arg.to_string_lossy();
    if !text.contains(['*', '?', '[']) || arg.exists() {
        if arg.is_dir() {
            let mut out = Vec::new();
            walk(arg, Path::new(""), if recursive { MAX_DEPTH } else { 0 }, &mut |rel, path| {
                if is_mesh_file(path) {
                    out.push(Input { path: path.to_path_buf(), id: id_of(rel) });
                }
            })?;
            return Ok(out);
        }
        if arg.is_file() {
            let name = arg.file_name().map(PathBuf::from).unwrap_or_default();
            return Ok(vec![Input { path: arg.to_path_buf(), id: id_of(&name) }]);
        }
        return Err(format!("{}: no such file or folder", arg.display()).into());
    }
    // A pattern: its components up to the first with a wildcard are a folder.
    let components: Vec<Component> = arg.components().collect();
    let first = components.iter().position(|c| c.as_os_str().to_string_lossy().contains(['*', '?', '['])).unwrap_or(0);
    let base: PathBuf = components[..first].iter().collect();
    let patterns: Vec<String> =
        components[first..].iter().map(|c| c.as_os_str().to_string_lossy().into_owned()).collect();
    let base = if base.as_os_str().is_empty() { PathBuf::from(".") } else { base };
    let mut out = Vec::new();
    walk(&base, Path::new(""), MAX_DEPTH, &mut |rel, path| {
        if is_mesh_file(path) && path_matches(&patterns, rel) {
            out.push(Input { path: path.to_path_buf(), id: id_of(rel) });
        }
    })?;
    Ok(out)
}

/// Visits every file under `dir` down to `depth` folder levels, with its
/// path relative to the starting folder; folder entries in sorted order.
fn walk(dir: &Path, rel: &Path, depth: usize, visit: &mut dyn FnMut(&Path, &Path)) -> CliResult<()> {
    let entries = match std::fs::read_dir(dir) {
        Ok(entries) => entries,
        // A sub-folder that cannot be listed is reported and passed over;
        // the folder the user named must be readable.
        Err(e) if !rel.as_os_str().is_empty() => {
            eprintln!("mesh: warning: {} not searched: {e}", dir.display());
            return Ok(());
        }
        Err(e) => return Err(format!("cannot list {}: {e}", dir.display()).into()),
    };
    let mut entries: Vec<_> = entries.filter_map(|e| e.ok()).collect();
    entries.sort_by_key(|e| e.file_name());
    for entry in entries {
        let path = entry.path();
        let rel = rel.join(entry.file_name());
        let Ok(kind) = entry.file_type() else { continue };
        if kind.is_dir() {
            // `file_type` does not follow links: a link to a folder is skipped.
            if depth > 0 {
                walk(&path, &rel, depth - 1, visit)?;
            }
        } else if path.is_file() {
            visit(&rel, &path);
        }
    }
    Ok(())
}

/// Whether the relative path `rel` matches the pattern components, where
/// `**` matches any number of folders.
fn path_matches(patterns: &[String], rel: &Path) -> bool {
    let names: Vec<String> = rel.components().map(|c| c.as_os_str().to_string_lossy().into_owned()).collect();
    matches_from(patterns, &names)
}

/// Whether `patterns` match `names` component by component, `**` standing
/// for any number of names: dynamic programming over (pattern, name)
/// positions, O(patterns x names) whatever the number of `**`.
fn matches_from(patterns: &[String], names: &[String]) -> bool {
    let (np, nn) = (patterns.len(), names.len());
    // ok[i][j]: patterns[i..] matches names[j..].
    let mut ok = vec![vec![false; nn + 1]; np + 1];
    ok[np][nn] = true;
    for i in (0..np).rev() {
        for j in (0..=nn).rev() {
            ok[i][j] = if patterns[i] == "**" {
                ok[i + 1][j] || (j < nn && ok[i][j + 1])
            } else {
                j < nn && glob_match(patterns[i].as_bytes(), names[j].as_bytes()) && ok[i + 1][j + 1]
            };
        }
    }
    ok[0][0]
}

/// Shell-style match of one file name: `*` any run of characters, `?` one
/// character, `[abc]` / `[a-z]` / `[!a-z]` one of a set. Linear in the name
/// times the number of `*` (backtracking to the last star only).
pub fn glob_match(pattern: &[u8], name: &[u8]) -> bool {
    let (mut p, mut n) = (0, 0);
    let mut star: Option<(usize, usize)> = None;
    while n < name.len() {
        let step = match pattern.get(p) {
            Some(b'*') => {
                star = Some((p, n));
                p += 1;
                continue;
            }
            Some(b'?') => Some(p + 1),
            Some(b'[') => class_match(&pattern[p..], name[n]).map(|len| p + len),
            Some(&c) => (c == name[n]).then_some(p + 1),
            None => None,
        };
        match (step, star) {
            (Some(next), _) => {
                p = next;
                n += 1;
            }
            (None, Some((sp, sn))) => {
                p = sp + 1;
                n = sn + 1;
                star = Some((sp, sn + 1));
            }
            (None, None) => return false,
        }
    }
    pattern[p..].iter().all(|&c| c == b'*')
}

/// Matches `c` against the class at the start of `pattern` (`[...]`):
/// `Some(length of the class)` when it matches, `None` otherwise (also for
/// a class without its closing bracket, which then matches nothing).
fn class_match(pattern: &[u8], c: u8) -> Option<usize> {
    let mut i = 1;
    let negate = matches!(pattern.get(1), Some(b'!' | b'^'));
    if negate {
        i += 1;
    }
    let mut found = false;
    let mut first = true;
    while i < pattern.len() {
        let lo = pattern[i];
        if lo == b']' && !first {
            return (found != negate).then_some(i + 1);
        }
        first = false;
        if pattern.get(i + 1) == Some(&b'-') && pattern.get(i + 2).is_some_and(|&hi| hi != b']') {
            found |= (lo..=pattern[i + 2]).contains(&c);
            i += 3;
        } else {
            found |= lo == c;
            i += 1;
        }
    }
    None
}

/// The id of a relative path: its components joined by `__`, with any
/// character outside `[A-Za-z0-9._-]` replaced by `_`.
fn id_of(rel: &Path) -> String {
    let parts: Vec<String> = rel
        .components()
        .filter_map(|c| match c {
            Component::Normal(s) => Some(
                s.to_string_lossy()
                    .chars()
                    .map(|ch| if ch.is_ascii_alphanumeric() || matches!(ch, '.' | '_' | '-') { ch } else { '_' })
                    .collect(),
            ),
            _ => None,
        })
        .collect();
    parts.join("__")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn glob_matches_like_a_shell() {
        let m = |p: &str, n: &str| glob_match(p.as_bytes(), n.as_bytes());
        assert!(m("*.ply", "bunny.ply"));
        assert!(!m("*.ply", "bunny.obj"));
        assert!(m("b?nny*", "bunny2.off"));
        assert!(m("*a*b*c", "xxaxxbxxc"));
        assert!(!m("*a*b*c", "xxaxxcxxb"));
        assert!(m("[bc]unny.[op]*", "cunny.off"));
        assert!(m("[a-c]x", "bx") && !m("[a-c]x", "dx") && m("[!a-c]x", "dx"));
        assert!(!m("[ab", "a"), "an unclosed class matches nothing");
        assert!(m("", "") && !m("", "a") && m("*", ""));
        // Many stars on a long name stay fast (backtracking to the last star only).
        let name = "a".repeat(10_000);
        assert!(!m("*a*a*a*a*a*a*b", &name));
    }

    #[test]
    fn double_star_matches_any_depth() {
        let p = |s: &str| s.split('/').map(str::to_owned).collect::<Vec<_>>();
        let n = |s: &str| s.split('/').map(str::to_owned).collect::<Vec<_>>();
        assert!(matches_from(&p("**/*.ply"), &n("a.ply")));
        assert!(matches_from(&p("**/*.ply"), &n("x/y/a.ply")));
        assert!(!matches_from(&p("*/*.ply"), &n("a.ply")));
        assert!(matches_from(&p("x/**/a.ply"), &n("x/a.ply")));
        // Many `**` against a deep path: no exponential search.
        let deep = vec!["d"; 40].join("/") + "/a.ply";
        let many = vec!["**"; 30].join("/") + "/*.off";
        assert!(!matches_from(&p(&many), &n(&deep)));
        assert!(matches_from(&p(&(vec!["**"; 30].join("/") + "/*.ply")), &n(&deep)));
    }

    #[test]
    fn ids_are_flat_and_safe() {
        assert_eq!(id_of(Path::new("a/b c/d.ply")), "a__b_c__d.ply");
        assert_eq!(id_of(Path::new("../x.obj")), "x.obj");
    }

    #[test]
    fn folders_patterns_and_the_output_folder() {
        let dir = tempfile::tempdir().unwrap();
        let root = dir.path();
        std::fs::create_dir_all(root.join("sub/deeper")).unwrap();
        std::fs::create_dir_all(root.join("out")).unwrap();
        for f in ["a.ply", "b.obj", "notes.txt", "sub/c.off", "sub/deeper/d.stl", "out/e.ply"] {
            std::fs::write(root.join(f), b"").unwrap();
        }
        let ids = |v: Vec<Input>| v.into_iter().map(|i| i.id).collect::<Vec<_>>();
        let out = root.join("out");
        assert_eq!(ids(collect(&[root.to_path_buf()], false, &out).unwrap()), ["a.ply", "b.obj"]);
        assert_eq!(
            ids(collect(&[root.to_path_buf()], true, &out).unwrap()),
            ["a.ply", "b.obj", "sub__c.off", "sub__deeper__d.stl"],
            "recursive, without the output folder"
        );
        let pattern = root.join("**").join("*.o*");
        assert_eq!(ids(collect(&[pattern], false, &out).unwrap()), ["b.obj", "sub__c.off"]);
        assert!(collect(&[root.join("*.xyz")], false, &out).is_err(), "a pattern that matches nothing");
        assert!(collect(&[root.join("missing")], false, &out).is_err());
        // The same file twice: same id, refused.
        assert!(collect(&[root.join("a.ply"), root.join("*.ply")], false, &out).is_err());
    }
}
