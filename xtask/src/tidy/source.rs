//! Rules on the sources: `unsafe` only where allowed, `# Errors` on public
//! fallible functions, no comment or document tied to one machine.

use super::Problem;
use std::path::Path;

/// Files allowed to hold `unsafe`, with the exact count of the keyword in
/// their code and why. A file not listed must have none; a listed file must
/// have exactly its count (so the list stays true when code moves).
pub const UNSAFE_ALLOWED: &[(&str, usize, &str)] = &[
    ("mesh-kernel/src/operators/corner_batch.rs", 2, "AVX2 build of the corner batches, behind runtime detection"),
    ("mesh-kernel/src/solver/supernodal.rs", 4, "AVX2 and AVX-512 block triangular solves, behind runtime detection"),
    (
        "mesh-kernel/src/connectivity/bucket_sort.rs",
        7,
        "AVX2 sort of the half-edge buckets by rank, behind runtime detection, and its test",
    ),
    ("mesh-kernel/src/mesh.rs", 2, "AVX2 build of the faces' validity scan, behind runtime detection"),
    ("mesh-spectral/src/eigen/narrow.rs", 4, "AVX2 builds of the narrow tall products, behind runtime detection"),
    ("mesh-spectral/src/eigen/tile.rs", 3, "the AVX-512 kernel of the basis update, behind runtime detection"),
    ("mesh-kernel/src/solver/cholesky.rs", 1, "its test of the AVX2 and AVX-512 solves against the portable one"),
    (
        "mesh-kernel/src/par.rs",
        3,
        "scatter's parts adding into one array, each vertex by one part; map_columns' arrays filled chunk by chunk before their lengths are set",
    ),
    (
        "mesh-kernel/src/rows.rs",
        3,
        "RowFill's and fill_rows' slots, reserved unwritten and handed over once each was written through a cursor",
    ),
    (
        "mesh-kernel/src/operators/pattern.rs",
        1,
        "the edge pattern's matrix built unchecked, its structure checked when the pattern was made",
    ),
    ("mesh-kernel/src/hint.rs", 1, "the cache prefetch hint (never faults)"),
    ("mesh-kernel/src/alloc.rs", 20, "the block-keeping global allocator: mmap, munmap, mremap, mallopt, sysconf and its tests"),
    ("xtask/src/fuzz/alloc.rs", 5, "the fuzzer's counting global allocator"),
    ("mesh-curvature/examples/timing.rs", 1, "clock_gettime for per-thread CPU time"),
];

/// Counts the word `unsafe` in code (not comments or strings).
pub fn unsafe_count(code: &str) -> usize {
    code.match_indices("unsafe")
        .filter(|(at, w)| {
            let before = code[..*at].chars().next_back();
            let after = code[at + w.len()..].chars().next();
            let ident = |c: Option<char>| c.is_some_and(|c| c.is_alphanumeric() || c == '_');
            !ident(before) && !ident(after)
        })
        .count()
}

/// The `unsafe` rule for one file (`relative` to the workspace root).
pub fn check_unsafe(relative: &str, path: &Path, code: &str) -> Option<Problem> {
    let found = unsafe_count(code);
    let allowed = UNSAFE_ALLOWED.iter().find(|(f, ..)| *f == relative).map_or(0, |(_, n, _)| *n);
    (found != allowed).then(|| {
        Problem::new(
            path,
            0,
            format!("{found} `unsafe` where the allow-list (xtask/src/tidy/source.rs) says {allowed}"),
        )
    })
}

/// Whether a signature (from `pub fn` to its body or `;`) returns a `Result`
/// (`Result<..>`, `io::Result<..>`, a crate's `Result` alias).
pub fn returns_result(signature: &str) -> bool {
    let Some((_, ret)) = signature.rsplit_once("->") else { return false };
    let ty = ret.trim_start();
    let last_segment = ty.split('<').next().unwrap_or("").rsplit("::").next().unwrap_or("");
    last_segment.trim() == "Result"
}

/// Public functions returning a `Result` without a `# Errors` section in
/// their doc comment. `code` is the lexed text (comments blanked), `text`
/// the original; both have the same lines.
pub fn missing_errors_sections(path: &Path, text: &str, code: &str) -> Vec<Problem> {
    let lines: Vec<&str> = text.lines().collect();
    let code_lines: Vec<&str> = code.lines().collect();
    let mut problems = Vec::new();
    for (i, line) in code_lines.iter().enumerate() {
        let t = line.trim_start();
        let public = ["pub fn ", "pub const fn ", "pub async fn ", "pub unsafe fn "].iter().any(|p| t.starts_with(p));
        if !public {
            continue;
        }
        let signature: String = code_lines[i..].iter().take(12).copied().collect::<Vec<_>>().join(" ");
        let signature = signature.split(['{', ';']).next().unwrap_or("");
        let signature = signature.split(" where ").next().unwrap_or(signature);
        if returns_result(signature) && !doc_has_errors(&lines, i) {
            let name = t.split("fn ").nth(1).and_then(|s| s.split(['(', '<']).next()).unwrap_or("?");
            problems.push(Problem::new(path, i + 1, format!("pub fn {name} returns a Result without `# Errors` docs")));
        }
    }
    problems
}

/// Whether the doc comment above line `i` (skipping attributes) has `# Errors`.
fn doc_has_errors(lines: &[&str], i: usize) -> bool {
    let mut k = i;
    while k > 0 {
        k -= 1;
        let t = lines[k].trim();
        if t.starts_with("///") {
            if t.trim_start_matches('/').trim() == "# Errors" {
                return true;
            }
        } else if t.ends_with(']') && !t.starts_with("#[") {
            // The last line of a multi-line attribute: go to its first.
            while k > 0 && !lines[k].trim().starts_with("#[") {
                k -= 1;
            }
        } else if !t.starts_with("#[") {
            return false;
        }
    }
    false
}

/// Phrases that tie a figure or remark to one machine. The rule: say which
/// hardware (cores, processor) a measurement ran on, never `this machine`;
/// no paths of one computer's file system.
pub const MACHINE_PHRASES: &[&str] = &[
    "this machine",
    "this box",
    "this computer",
    "this laptop",
    "this host",
    "this vm",
    "this server",
    "my machine",
    "my laptop",
    "our machine",
    "/home/",
    "/users/",
    "/work/",
];

/// The machine-naming rule on one comment or document line. Inline code
/// spans (between backticks) are quotations, not claims, and are skipped.
pub fn names_a_machine(line: &str) -> Option<&'static str> {
    let prose: String = line.split('`').step_by(2).collect::<Vec<_>>().join(" ");
    let lower = prose.to_lowercase();
    MACHINE_PHRASES.iter().copied().find(|p| lower.contains(p))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unsafe_is_counted_as_a_word() {
        assert_eq!(unsafe_count("unsafe { f() } unsafe_code not_unsafe unsafe fn g()"), 2);
    }

    #[test]
    fn result_returns_are_recognised() {
        assert!(returns_result("pub fn f(x: u8) -> Result<u8, E> "));
        assert!(returns_result("pub fn f() -> std::io::Result<()>"));
        assert!(returns_result("pub fn f() -> crate::Result<Vec<u8>>"));
        assert!(!returns_result("pub fn f(r: Result<u8, E>) -> u8"));
        assert!(!returns_result("pub fn f() -> Option<Result<u8, E>>"));
        assert!(!returns_result("pub fn f()"));
    }

    #[test]
    fn errors_sections_are_required() {
        let text = "/// Does f.\n///\n/// # Errors\n/// Never.\n#[inline]\npub fn f() -> Result<(), E> {}\n\
                    /// Does g.\npub fn g(\n    a: u8,\n) -> Result<u8, E> {}\npub fn h() -> u8 {}\n";
        let problems = missing_errors_sections(Path::new("x.rs"), text, text);
        assert_eq!(problems.len(), 1, "{problems:?}");
        assert_eq!(problems[0].line, 8);
    }

    #[test]
    fn machine_phrases_are_found() {
        assert_eq!(names_a_machine("// 0.1 s on This Machine"), Some("this machine"));
        assert_eq!(names_a_machine("measured on a 2-core Xeon VM"), None);
        assert_eq!(names_a_machine("the same machine as the peers"), None);
        assert_eq!(names_a_machine("never say `this machine`"), None);
    }
}
