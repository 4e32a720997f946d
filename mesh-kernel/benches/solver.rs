//! Sparse Cholesky solves of the heat method's system `M + t L` on
//! icospheres from 2.5e3 to 6.6e5 vertices: one right-hand side, two (the u
//! and v of a parameterization) and blocks of eight (block eigensolvers),
//! through [`Cholesky`] and, for comparison, faer's own triangular solve of
//! the same factorization.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::cholesky::{factorize_symbolic_cholesky, CholeskySymbolicParams, LltRef, SymmetricOrdering};
use faer::sparse::linalg::SupernodalThreshold;
use faer::{Conj, MatMut, Par, Side, Spec};
use mesh_kernel::operators::{self, MassKind};
use mesh_kernel::shapes;
use mesh_kernel::solver::{to_faer, Cholesky};
use sprs::CsMat;

/// `M + t L` with `t` the squared mean edge length, as in the heat method.
fn heat_system(level: u32) -> CsMat<f64> {
    let m = shapes::icosphere(level).expect("valid level");
    let l = operators::cotan_laplacian(&m);
    let mass = operators::mass_matrix(&m, MassKind::MixedVoronoi);
    let h = 4.0 / 2f64.powi(level as i32);
    &mass + &l.map(|v| v * h * h)
}

/// faer's supernodal factorization and solve of `a`, for comparison.
fn faer_solver(a: &CsMat<f64>) -> impl Fn(&mut [f64]) {
    let fa = to_faer(a).expect("finite");
    let params = CholeskySymbolicParams {
        supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
        ..Default::default()
    };
    let symbolic = factorize_symbolic_cholesky(fa.symbolic(), Side::Lower, SymmetricOrdering::Amd, params).expect("ok");
    let mut values = vec![0.0; symbolic.len_val()];
    let scratch = symbolic.factorize_numeric_llt_scratch::<f64>(Par::Seq, Spec::default());
    let mut mem = MemBuffer::new(scratch);
    symbolic
        .factorize_numeric_llt(
            &mut values,
            fa.as_ref(),
            Side::Lower,
            Default::default(),
            Par::Seq,
            MemStack::new(&mut mem),
            Spec::default(),
        )
        .expect("positive definite");
    move |b: &mut [f64]| {
        let n = symbolic.nrows();
        let k = b.len() / n;
        let mut mem = MemBuffer::new(symbolic.solve_in_place_scratch::<f64>(k, Par::Seq));
        LltRef::new(&symbolic, &values).solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(b, n, k),
            Par::Seq,
            MemStack::new(&mut mem),
        );
    }
}

fn bench_solves(c: &mut Criterion) {
    let mut group = c.benchmark_group("cholesky_solve");
    group.sample_size(10).warm_up_time(Duration::from_millis(300)).measurement_time(Duration::from_secs(2));
    for level in 4..=8 {
        let a = heat_system(level);
        let n = a.rows();
        let ours = Cholesky::new(&a).expect("positive definite");
        let theirs = faer_solver(&a);
        for k in [1, 2, 8] {
            let b: Vec<f64> = (0..n * k).map(|i| ((i * 7919) % 1000) as f64 / 1000.0).collect();
            let id = format!("{n}v_{k}rhs");
            group.bench_with_input(BenchmarkId::new("mesh_kernel", &id), &b, |bench, b| {
                bench.iter(|| black_box(ours.solve(b).expect("solves")))
            });
            group.bench_with_input(BenchmarkId::new("faer", &id), &b, |bench, b| {
                bench.iter(|| {
                    let mut x = b.clone();
                    theirs(&mut x);
                    black_box(x)
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, bench_solves);
criterion_main!(benches);
