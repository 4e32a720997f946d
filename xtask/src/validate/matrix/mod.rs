//! The dirty-mesh matrix (`cargo xtask validate --only matrix`): meshes
//! with every common defect ([`meshes`]), built in code, times every
//! operation of every crate that takes a mesh ([`ops_core`], [`ops_algo`]).
//! A cell passes with a result that passes the operation's own check
//! (sizes, invariants such as Gauss-Bonnet, geodesic >= chord, a repaired
//! mesh being manifold, a file read back equal) and has no NaN, or with an
//! error (the crates' typed errors); never with a panic or a hang. On the
//! control mesh every operation must succeed. On the meshes scaled by
//! 1e300 and 1e-300 the answer must be the unscaled mesh's, rescaled by the
//! power of the scale its unit carries ([`check::same_up_to_scale`]), or an
//! error where that answer lies outside the range of f64.
//!
//! Also: NaN coordinates and out-of-range indices refused by `TriMesh::new`
//! and `clean` with their typed errors, and files with negative and huge
//! counts refused by mesh-io ([`files`]). One check per row goes to the
//! validator; the whole table is printed.

mod check;
mod files;
mod meshes;
mod ops_algo;
mod ops_core;

use std::sync::{mpsc, Arc};
use std::time::{Duration, Instant};

use mesh_kernel::clean::CleanOptions;
use mesh_kernel::glam::DVec3;
use mesh_kernel::{MeshError, TriMesh};

use super::Validator;
use crate::fuzz::panics;
use check::Out;
use meshes::{Kind, Row};

/// One column: crate, operation, and the function running it.
pub type Op = (&'static str, &'static str, fn(&TriMesh) -> Result<Out, String>);

/// A cell taking longer than this is reported as a hang.
const CELL_SECONDS: u64 = 20;

/// The outcome of one cell.
#[derive(Debug, Clone)]
enum Cell {
    /// A result that passed its checks.
    Ok,
    /// A typed error, acceptable here.
    Err(String),
    /// A panic, hang, NaN, wrong answer, or an error where none is allowed.
    Fail(String),
}

/// Runs the operation on its own thread: `Err` on a panic or a hang.
fn run_cell(op: &Op, mesh: &Arc<TriMesh>) -> Result<Result<Out, String>, String> {
    let (send, receive) = mpsc::channel();
    let (f, mesh) = (op.2, mesh.clone());
    std::thread::spawn(move || {
        let _ = send.send(panics::catch(|| f(&mesh)));
    });
    match receive.recv_timeout(Duration::from_secs(CELL_SECONDS)) {
        Ok(Ok(result)) => Ok(result),
        Ok(Err(panic)) => Err(format!("panic: {panic}")),
        Err(_) => Err(format!("no answer within {CELL_SECONDS} s")),
    }
}

/// Judges one cell's outcome for its row.
fn judge(kind: Kind, outcome: Result<Result<Out, String>, String>, reference: Option<&Result<Out, String>>) -> Cell {
    let result = match outcome {
        Err(fail) => return Cell::Fail(fail),
        Ok(r) => r,
    };
    match (kind, result) {
        (Kind::Control, Err(e)) => Cell::Fail(format!("error on the control mesh: {e}")),
        (Kind::Scaled { scale, .. }, Err(e)) => match reference {
            // A typed error is a right answer past 1e200 (the rule
            // for 1e300 and 1e-300); up to there the answer is required.
            Some(Ok(u)) if check::representable(u, scale) && scale.log10().abs() < 200.0 => {
                Cell::Fail(format!("error, yet the unscaled mesh has a representable answer: {e}"))
            }
            _ => Cell::Err(e),
        },
        (_, Err(e)) => Cell::Err(e),
        (Kind::Scaled { scale, .. }, Ok(out)) if matches!(reference, Some(Ok(u)) if !check::representable(u, scale)) => {
            // The invariants were checked on the unscaled mesh; here sums of
            // overflowed values are infinite, and the value-by-value
            // comparison below is the stricter test.
            let Some(Ok(u)) = reference else { return Cell::Fail("no unscaled result".into()) };
            match check::saturated(&out, u, scale) {
                Ok(()) => Cell::Ok,
                Err(why) => Cell::Fail(format!("not the correctly rounded answer: {why}")),
            }
        }
        (kind, Ok(out)) => {
            if let Some(bad) = out.non_finite() {
                return Cell::Fail(format!("non-finite value {bad}"));
            }
            if let Some(wrong) = out.wrong {
                return Cell::Fail(format!("wrong: {wrong}"));
            }
            if let Kind::Scaled { scale, .. } = kind {
                match reference {
                    Some(Ok(u)) => {
                        if let Err(why) = check::same_up_to_scale(&out, u, scale) {
                            return Cell::Fail(format!("not the unscaled answer: {why}"));
                        }
                    }
                    Some(Err(e)) => {
                        return Cell::Fail(format!("a result, where the unscaled mesh gives an error ({e})"))
                    }
                    None => return Cell::Fail("no unscaled result to compare with".into()),
                }
            }
            Cell::Ok
        }
    }
}

/// NaN coordinates and out-of-range indices are refused by `TriMesh::new`
/// and `clean` with their typed errors.
fn construction(v: &mut Validator) {
    let p = vec![DVec3::ZERO, DVec3::X, DVec3::new(0.0, f64::NAN, 0.0)];
    let nan = TriMesh::new(p.clone(), vec![[0, 1, 2]]);
    v.holds(
        "NaN coordinate: TriMesh::new refuses with NonFinitePosition (vertex 2)",
        matches!(nan, Err(MeshError::NonFinitePosition { vertex, .. }) if vertex.idx() == 2),
        format!("{:?}", nan.err()),
    );
    let cleaned = mesh_kernel::clean::clean(p, vec![[0, 1, 2]], &CleanOptions::default());
    v.holds(
        "NaN coordinate: clean refuses with NonFinitePosition",
        matches!(cleaned, Err(MeshError::NonFinitePosition { .. })),
        format!("{:?}", cleaned.err()),
    );
    let p = vec![DVec3::ZERO, DVec3::X, DVec3::Y];
    let out = TriMesh::new(p.clone(), vec![[0, 1, 2], [0, 2, 3]]);
    v.holds(
        "index out of range: TriMesh::new refuses with IndexOutOfRange (face 1, vertex 3)",
        matches!(out, Err(MeshError::IndexOutOfRange { face, vertex: 3, vertex_count: 3 }) if face.idx() == 1),
        format!("{:?}", out.err()),
    );
    let cleaned = mesh_kernel::clean::clean(p, vec![[0, 1, u32::MAX]], &CleanOptions::default());
    v.holds(
        "index out of range: clean refuses with IndexOutOfRange",
        matches!(cleaned, Err(MeshError::IndexOutOfRange { .. })),
        format!("{:?}", cleaned.err()),
    );
}

/// Shortens an error message for the row's note.
fn short(s: &str) -> String {
    let s = s.replace('\n', " ");
    if s.chars().count() > 90 {
        format!("{}...", s.chars().take(90).collect::<String>())
    } else {
        s
    }
}

fn print_table(rows: &[Row], ops: &[&Op], cells: &[Vec<Cell>]) {
    let widths: Vec<usize> = rows.iter().map(|r| r.name.len().max(4)).collect();
    print!("\n{:<24}", "matrix: operation");
    for (r, w) in rows.iter().zip(&widths) {
        print!(" {:>w$}", r.name);
    }
    println!();
    for (j, op) in ops.iter().enumerate() {
        print!("{:<24}", format!("{} {}", op.0, op.1));
        for (i, w) in widths.iter().enumerate() {
            let mark = cells.get(i).and_then(|c| c.get(j)).map_or("-", |c| match c {
                Cell::Ok => "ok",
                Cell::Err(_) => "err",
                Cell::Fail(_) => "FAIL",
            });
            print!(" {mark:>w$}");
        }
        println!();
    }
    println!();
}

/// Runs the matrix.
pub fn run(v: &mut Validator) {
    construction(v);
    files::run(v);
    let rows = meshes::rows();
    let ops: Vec<&Op> = ops_core::OPS.iter().chain(ops_algo::OPS).collect();
    let mut results: Vec<Vec<Result<Out, String>>> = Vec::new();
    let mut cells: Vec<Vec<Cell>> = Vec::new();
    let start = Instant::now();
    panics::quietly(|| {
        for row in &rows {
            let Ok(mesh) = &row.mesh else {
                results.push(Vec::new());
                cells.push(Vec::new());
                continue;
            };
            let mesh = Arc::new(mesh.clone());
            let base = match row.kind {
                Kind::Scaled { base, .. } => rows.iter().position(|r| r.name == base),
                _ => None,
            };
            let (mut row_results, mut row_cells) = (Vec::new(), Vec::new());
            for (j, op) in ops.iter().enumerate() {
                let outcome = run_cell(op, &mesh);
                let reference = base.and_then(|b| results.get(b)).and_then(|r: &Vec<_>| r.get(j));
                row_cells.push(judge(row.kind, outcome.clone(), reference));
                row_results.push(outcome.unwrap_or_else(Err));
            }
            results.push(row_results);
            cells.push(row_cells);
        }
    });
    let seconds = start.elapsed().as_secs_f64();
    print_table(&rows, &ops, &cells);
    for (row, row_cells) in rows.iter().zip(&cells) {
        if let Err(e) = &row.mesh {
            v.error(format!("row {}: mesh built", row.name), e);
            continue;
        }
        let count = |f: fn(&Cell) -> bool| row_cells.iter().filter(|c| f(c)).count();
        let (ok, err, fail) = (
            count(|c| matches!(c, Cell::Ok)),
            count(|c| matches!(c, Cell::Err(_))),
            count(|c| matches!(c, Cell::Fail(_))),
        );
        let mut notes: Vec<String> = Vec::new();
        for (op, cell) in ops.iter().zip(row_cells) {
            if let Cell::Fail(why) = cell {
                notes.push(format!("FAIL {} {}: {}", op.0, op.1, short(why)));
            }
        }
        for (op, cell) in ops.iter().zip(row_cells) {
            if let Cell::Err(why) = cell {
                notes.push(format!("err {} {}: {}", op.0, op.1, short(why)));
            }
        }
        v.holds(format!("row {}: {ok} ok, {err} typed errors, {fail} failed", row.name), fail == 0, notes.join("; "));
    }
    let total: usize = cells.iter().map(Vec::len).sum();
    v.holds(
        format!("{} meshes x {} operations = {total} cells in {seconds:.1} s", rows.len(), ops.len()),
        total == rows.len() * ops.len(),
        String::new(),
    );
}
