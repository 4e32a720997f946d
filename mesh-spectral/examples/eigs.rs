//! Times one eigensolve with its phase breakdown, and optionally writes the
//! mesh so that peers (`../shared/peers/peer_bench.py`) run on the same
//! input. Used for the runs too long for criterion (k = 200 on 100k
//! vertices, 1e6 vertices):
//!
//! ```text
//! cargo run --release -p mesh-spectral --example eigs -- torus 158 200 [OUT.off]
//! cargo run --release -p mesh-spectral --example eigs -- FILE.off 20
//! ```
//!
//! `EIGS_ORDERING=dissection` orders the factor by the vertices' positions.
//! `EIGS_BLOCK`, `EIGS_BASIS`, `EIGS_GUARD`, `EIGS_SHIFT` override the
//! corresponding [`EigenOptions`] fields (for tuning); `EIGS_LAPLACIAN`
//! (auto, cotan, intrinsic) and `EIGS_COMPONENT` (all, largest) choose the
//! pencil; `EIGS_DUMP=PREFIX` writes it as `PREFIX_L.mtx` (Matrix Market)
//! and `PREFIX_M.txt` (the mass diagonal) so that scipy solves the
//! identical problem.
//!
//! Shapes are those of `mesh_kernel::shapes::by_name` (`icosphere 6` is
//! 40,962 vertices, `torus 158` 99,856, `grid 316` 100,489).

use std::io::Write;
use std::process::ExitCode;
use std::time::Instant;

use mesh_kernel::{shapes, TriMesh};
use mesh_spectral::{eigenpairs, pencil, ComponentSelection, EigenOptions, FillOrdering, LaplacianKind, MassKind};

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (mesh, rest): (TriMesh, &[String]) = match args.as_slice() {
        [file, rest @ ..] if file.contains('.') => (mesh_io::read(file)?.mesh, rest),
        [shape, res, rest @ ..] => (shapes::by_name(shape, res.parse()?)?, rest),
        _ => return Err("usage: eigs (FILE | SHAPE RES) K [OUT.off]".into()),
    };
    let k: usize = rest.first().map_or(Ok(20), |s| s.parse())?;
    if let Some(out) = rest.get(1) {
        mesh_io::write(out, &mesh, &mesh_io::WriteOptions::default())?;
        writeln!(std::io::stdout(), "wrote {out}")?;
    }
    let text = |name: &str, default: &str| std::env::var(name).unwrap_or_else(|_| default.to_owned());
    let laplacian: LaplacianKind = text("EIGS_LAPLACIAN", "auto").parse()?;
    let component: ComponentSelection = text("EIGS_COMPONENT", "all").parse()?;
    let mesh = match component {
        ComponentSelection::Largest => mesh.largest_component()?.mesh,
        ComponentSelection::All => mesh,
    };
    let t = Instant::now();
    let p = pencil(&mesh, laplacian, MassKind::MixedVoronoi)?;
    let l = p.laplacian;
    let assemble = t.elapsed().as_secs_f64();
    writeln!(std::io::stdout(), "operator: {}", p.info.describe())?;
    if let Ok(prefix) = std::env::var("EIGS_DUMP") {
        dump(&prefix, &l, &p.mass)?;
    }
    let env = |name: &str| std::env::var(name).ok().and_then(|v| v.parse::<f64>().ok());
    let options = EigenOptions {
        block_size: env("EIGS_BLOCK").map(|v| v as usize),
        basis_size: env("EIGS_BASIS").map(|v| v as usize),
        guard: env("EIGS_GUARD").map(|v| v as usize),
        shift: env("EIGS_SHIFT"),
        ordering: (text("EIGS_ORDERING", "auto") == "dissection").then(|| FillOrdering::of_points(mesh.positions())),
        ..EigenOptions::default()
    };
    let pairs = eigenpairs(&l, &p.mass, k, &options)?;
    let s = &pairs.stats;
    let worst = pairs.residuals.iter().copied().fold(0.0, f64::max);
    let worst_abs = pairs.absolute_residuals.iter().copied().fold(0.0, f64::max);
    let mut stdout = std::io::stdout().lock();
    writeln!(
        stdout,
        "n {} k {k}: assemble {assemble:.3} s, eigenpairs {:.3} s (factor {:.3}, iterate {:.3} = solve {:.3} + orthogonalize {:.3} + rest, finalize {:.3})",
        mesh.vertex_count(),
        s.total_seconds,
        s.factor_seconds,
        s.iterate_seconds,
        s.solve_seconds,
        s.orthogonalize_seconds,
        s.finalize_seconds
    )?;
    writeln!(
        stdout,
        "  block {} basis {} restarts {} solves {} factor nnz {} shift {:?}; worst relative residual {worst:.2e} (tolerance met {:.1e}), absolute {worst_abs:.2e}; lambda_1..3 {:?}, lambda_k {:.6}",
        s.block_size,
        s.basis_size,
        s.restarts,
        s.operator_columns,
        s.factor_nonzeros,
        s.shift,
        s.tolerance,
        &pairs.values[1.min(k - 1)..4.min(k)],
        pairs.values[k - 1]
    )?;
    let values: Vec<String> = pairs.values.iter().map(|v| format!("{v:.12e}")).collect();
    writeln!(stdout, "  values {}", values.join(" "))?;
    Ok(())
}

/// `L` as a Matrix Market coordinate file (1-based, general) and the mass
/// diagonal one value per line.
fn dump(prefix: &str, l: &sprs::CsMat<f64>, mass: &[f64]) -> Result<(), Box<dyn std::error::Error>> {
    let mut out = std::io::BufWriter::new(std::fs::File::create(format!("{prefix}_L.mtx"))?);
    writeln!(out, "%%MatrixMarket matrix coordinate real general")?;
    writeln!(out, "{} {} {}", l.rows(), l.cols(), l.nnz())?;
    for (v, (i, j)) in l.iter() {
        writeln!(out, "{} {} {v:.17e}", i + 1, j + 1)?;
    }
    let mut out = std::io::BufWriter::new(std::fs::File::create(format!("{prefix}_M.txt"))?);
    for m in mass {
        writeln!(out, "{m:.17e}")?;
    }
    Ok(())
}
