//! Block Krylov-Schur with full reorthogonalization (Stewart 2001, "A
//! Krylov-Schur algorithm for large eigenproblems", in its symmetric form:
//! thick-restart block Lanczos, Wu and Simon 2000; Zhou and Saad 2008).
//!
//! For a symmetric operator `B` (here the shift-invert operator) the method
//! keeps an orthonormal basis `V` (n x s), a symmetric projected matrix `H`
//! and an orthonormal residual block `Q` (n x b) with
//!
//! ```text
//! B V = V H + Q G          (G: b x s)
//! ```
//!
//! - **expand**: append `Q` to `V`, compute `W = B Q` (one multi-right-hand
//!   side solve), orthogonalize `W` against the whole basis by block
//!   classical Gram-Schmidt applied twice (matrix-matrix products), then
//!   orthonormalize it inside the block (`W = Q' R`); `H` gains the block
//!   `Q^T B Q`, `G` becomes `[0 .. 0 R]`;
//! - **Rayleigh-Ritz**: `H = S Theta S^T` (dense self-adjoint eigen); the
//!   Ritz pair `(theta_j, V s_j)` has residual norm exactly `||G s_j||`;
//! - **restart**: keep the `p` largest Ritz pairs: `V <- V S_p`,
//!   `H <- Theta_p`, `G <- G S_p`, and expand again from `Q`;
//! - **lock** (Stewart 2001, section 3): a wanted pair whose estimate
//!   `||G s_j||` is a hundredth of the tolerance gets its column of `G`
//!   set to zero at the restart. It then stays a fixed leading column of
//!   `V`, out of the later Rayleigh-Ritz problems and restart rotations
//!   (at k = 200, 24 to 167 of the 349 kept pairs on ico6 at the five
//!   restarts), still in every orthogonalization; its purified vector is
//!   set aside when it is locked.
//!
//! A block of `b` vectors sees up to `b` copies of a repeated eigenvalue, so
//! the block size is chosen above the multiplicities to expect; columns that
//! become dependent (invariant subspace found) are replaced by fresh random
//! directions, so the iteration never stalls. Every loop is bounded.

use std::time::Instant;

use faer::linalg::matmul::matmul;
use faer::reborrow::{Reborrow, ReborrowMut};
use faer::{Accum, Mat, MatMut, MatRef, Par, Side};

use super::narrow::dot;
use super::tall;
use crate::error::{Result, SpectralError};
use mesh_kernel::random::SplitMix64;

/// Pairs are locked once their residual estimate is this fraction of the
/// tolerance: dropping their coupling perturbs the Krylov relation by at
/// most that much, two orders of magnitude below what they must meet.
const LOCK: f64 = 0.01;

/// A symmetric operator applied to blocks of vectors.
pub(crate) trait BlockOperator {
    /// Dimension n.
    fn dim(&self) -> usize;
    /// `w = B q` (both n x b).
    fn apply(&self, q: MatRef<'_, f64>, w: &mut Mat<f64>) -> Result<()>;
}

/// Sizes and stopping rule of one run.
#[derive(Debug, Clone)]
pub(crate) struct Config {
    /// Pairs that must converge (the largest `theta`).
    pub want: usize,
    /// Pairs kept at each restart at least (`want` plus guard vectors).
    pub nev: usize,
    /// Block size b.
    pub block: usize,
    /// Largest basis size m (`nev + 2 b <= m`, `m + b <= n`).
    pub basis: usize,
    /// Relative tolerance on the Ritz residual estimate `||G s|| <= tol theta`.
    pub tol: f64,
    /// Bound on restarts.
    pub max_restarts: usize,
    /// Seed of the random start block.
    pub seed: u64,
}

/// What the caller's acceptance test returns for the candidate pairs.
pub(crate) struct Verdict<T> {
    /// Per pair, explicit residual divided by its target (<= 1 passes).
    pub ratios: Vec<f64>,
    /// What the caller built from the candidates (its eigenvectors, and
    /// what it computed to test them).
    pub accepted: T,
}

/// Where the time of a run went.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Timings {
    /// Operator applications (linear solves).
    pub apply: f64,
    /// Orthogonalization.
    pub orthogonalize: f64,
    /// Rayleigh-Ritz, restarts and acceptance tests.
    pub other: f64,
}

/// Result of a converged run.
pub(crate) struct Outcome<T> {
    /// What the accepted [`Verdict`] carried.
    pub accepted: T,
    /// Restarts performed.
    pub restarts: usize,
    /// Operator applications, counted in columns.
    pub columns: usize,
    /// Time split.
    pub timings: Timings,
}

/// Bases of at least this many columns keep a smaller share of their
/// unwanted Ritz pairs at a thick restart.
const WIDE_BASIS: usize = 256;

/// Runs block Krylov-Schur on `op` until the `want` largest pairs pass the
/// estimate and then `accept`, which gets the Ritz values, Ritz vectors `y`
/// and purified vectors `u = B y / theta`, which it owns (first from the
/// Krylov relation; if they fail, from one more application of `B`: over
/// many restarts the relation drifts by rounding and limits the accuracy of
/// the former).
pub(crate) fn solve<O: BlockOperator, T>(
    op: &O,
    cfg: &Config,
    mut accept: impl FnMut(&[f64], Mat<f64>, Mat<f64>) -> Result<Verdict<T>>,
) -> Result<Outcome<T>> {
    let n = op.dim();
    let (b, m, want) = (cfg.block, cfg.basis, cfg.want);
    if b == 0 || want == 0 || want > cfg.nev || cfg.nev + 2 * b > m || m + b > n {
        return Err(SpectralError::InvalidOption {
            name: "block_size",
            reason: format!(
                "inconsistent Krylov sizes: n = {n}, want = {want}, nev = {}, block = {b}, basis = {m}",
                cfg.nev
            ),
        });
    }
    let mut rng = SplitMix64::new(cfg.seed);
    let mut ks = KrylovSchur::new(n, m, b);
    ks.start(&mut rng);
    // To first order the estimate is the purified pair's relative residual,
    // so it is held to the tolerance itself; the explicit residuals decide,
    // and tighten it when they disagree. (A quarter of the tolerance cost
    // one more restart on every mesh measured, 16 of 216 solve columns.)
    let mut est_tol = cfg.tol;
    let mut columns = 0;
    let mut times = Timings::default();
    for restart in 0..=cfg.max_restarts {
        while ks.s + b <= m {
            ks.expand(op, &mut rng, &mut times)?;
            columns += b;
        }
        let clock = Instant::now();
        let ritz = ks.rayleigh_ritz()?;
        let estimate = |j: usize| ritz.beta[j] / ritz.theta[j].abs().max(f64::MIN_POSITIVE);
        let worst = (0..want).map(estimate).fold(0.0, f64::max);
        if worst <= est_tol {
            // Purified vectors from the Krylov relation (free); if the
            // explicit residuals reject them, from one more application of
            // B, which does not depend on the relation's rounding drift.
            // `accept` owns the Ritz vectors (their block can hold its
            // products): the second try forms them again.
            for fresh in [false, true] {
                let y = ks.ritz_vectors(&ritz, want);
                let u = if fresh {
                    let t = Instant::now();
                    let mut u = Mat::zeros(n, want);
                    op.apply(y.as_ref(), &mut u)?;
                    times.apply += t.elapsed().as_secs_f64();
                    columns += want;
                    for j in 0..want {
                        let inv = 1.0 / ritz.theta[j];
                        u.col_as_slice_mut(j).iter_mut().for_each(|x| *x *= inv);
                    }
                    u
                } else {
                    ks.purified(&ritz, y.as_ref(), want)
                };
                let verdict = accept(&ritz.theta[..want], y, u)?;
                let ratio = verdict.ratios.iter().copied().fold(0.0, f64::max);
                if ratio <= 1.0 {
                    times.other += clock.elapsed().as_secs_f64();
                    return Ok(Outcome { accepted: verdict.accepted, restarts: restart, columns, timings: times });
                }
                if fresh {
                    // The estimate was too optimistic (uneven masses): tighten it.
                    est_tol = (est_tol * (0.5 / ratio).clamp(1e-4, 0.5)).max(1e-15);
                }
            }
            let t = Instant::now();
            columns += ks.restore_locked(op, want)?;
            times.apply += t.elapsed().as_secs_f64();
        }
        if restart == cfg.max_restarts {
            let residuals: Vec<f64> = (0..want).map(estimate).collect();
            let converged = residuals.iter().filter(|&&r| r <= est_tol).count();
            return Err(SpectralError::NotConverged {
                converged,
                wanted: want,
                attempts: 1,
                restarts: restart,
                tolerance: cfg.tol,
                residuals,
            });
        }
        // Kept: the nev wanted and guard pairs and a share of the rest,
        // smaller for a wide basis, whose rotations cost more than the solve
        // columns saved. k = 200 (basis 500): keeping 2/5 took 4 restarts
        // where half took 5, for the same 1,120 solve columns (54.3 s
        // against 57.1 s at 470k vertices, 4.2 s against 4.4 s on ico6; a
        // third took 64 more columns). k = 20 (basis 56) at 470k: 2/5 took
        // 124 columns against 116 and 6.5 s against 6.2 s. Bases between
        // 56 and 500 columns were not measured; the switch is at 256.
        let rest = ks.s - cfg.nev;
        let p = (cfg.nev + if ks.s >= WIDE_BASIS { rest * 2 / 5 } else { rest / 2 }).min(ks.s - b);
        ks.restart(&ritz, p, want, LOCK * est_tol);
        times.other += clock.elapsed().as_secs_f64();
    }
    // The loop returns on its last iteration.
    Err(SpectralError::NotConverged {
        converged: 0,
        wanted: want,
        attempts: 1,
        restarts: cfg.max_restarts,
        tolerance: cfg.tol,
        residuals: Vec::new(),
    })
}

/// The state `B V = V H + Q G` with `V = v[:, ..s]`, `Q = v[:, s..s + b]`;
/// only columns `g_from..s` of `G` can be non-zero.
struct KrylovSchur {
    v: Mat<f64>,
    h: Mat<f64>,
    g: Mat<f64>,
    w: Mat<f64>,
    coef: Mat<f64>,
    /// The n x b buffer of the block QR.
    qr: Mat<f64>,
    b: usize,
    s: usize,
    g_from: usize,
    /// Leading columns of `V` that are locked Ritz vectors: `H` diagonal
    /// and `G` zero there.
    locked: usize,
    /// The purified vectors of the locked columns (n x want, allocated at
    /// the first lock).
    locked_u: Option<Mat<f64>>,
}

/// Ritz pairs of the projected matrix, largest first.
struct Ritz {
    theta: Vec<f64>,
    /// Eigenvectors of `H` (s x s), columns in the order of `theta`: the
    /// unit vector `e_j` for the locked column `j`, zero on the locked rows
    /// for the others.
    vectors: Mat<f64>,
    /// Residual norms `||G s_j||` (zero for locked pairs).
    beta: Vec<f64>,
    /// Where each pair comes from: below the locked count, that locked
    /// column; above, the active pairs in decreasing order.
    slot: Vec<usize>,
}

impl KrylovSchur {
    fn new(n: usize, m: usize, b: usize) -> Self {
        Self {
            v: Mat::zeros(n, m + b),
            h: Mat::zeros(m, m),
            g: Mat::zeros(b, m),
            w: Mat::zeros(n, b),
            coef: Mat::zeros(m + b, b),
            qr: Mat::zeros(n, b),
            b,
            s: 0,
            g_from: 0,
            locked: 0,
            locked_u: None,
        }
    }

    /// Random orthonormal start block in `Q`.
    fn start(&mut self, rng: &mut SplitMix64) {
        let (n, b) = (self.v.nrows(), self.b);
        let mut q = Mat::zeros(n, b);
        for j in 0..b {
            rng.fill_signed(q.col_as_slice_mut(j));
        }
        let mut gram = Mat::zeros(b, b);
        tall::gram(gram.as_mut(), q.as_ref(), q.as_ref());
        let norms = gram_norms(&gram);
        let (empty, rest) = self.v.as_mut().split_at_col_mut(0);
        orthonormalize_block(empty.rb(), &mut q, gram, &norms, rest.subcols_mut(0, b), rng, &mut self.qr);
    }

    /// Appends `Q` to the basis and computes the next residual block:
    /// `W = B Q`; the components the Krylov relation predicts
    /// (`V G^T + Q A` with `A = Q^T W`) are removed first (cheap: G is
    /// zero outside the last block except right after a restart), then one
    /// classical Gram-Schmidt pass against the whole basis, and a second one
    /// only for blocks that lost more than half their norm in it
    /// (Daniel, Gragg, Kaufman and Stewart 1976).
    fn expand<O: BlockOperator>(&mut self, op: &O, rng: &mut SplitMix64, times: &mut Timings) -> Result<()> {
        let (s, b, from) = (self.s, self.b, self.g_from);
        let t = s + b;
        let clock = Instant::now();
        op.apply(self.v.as_ref().subcols(s, b), &mut self.w)?;
        times.apply += clock.elapsed().as_secs_f64();
        let clock = Instant::now();
        let norms: Vec<f64> = column_norms(&self.w);
        if norms.iter().any(|x| !x.is_finite()) {
            return Err(SpectralError::Dense("the shift-invert operator produced a non-finite vector".into()));
        }
        // H gains the coupling of the old basis with Q (B is symmetric).
        for i in 0..b {
            for j in from..s {
                let x = self.g[(i, j)];
                self.h[(s + i, j)] = x;
                self.h[(j, s + i)] = x;
            }
        }
        // Local step: W -= V G^T, then A = Q^T W, W -= Q A.
        if s > from {
            let g = self.g.as_ref().submatrix(0, from, b, s - from);
            tall::mul(self.w.as_mut(), Accum::Add, self.v.as_ref().subcols(from, s - from), g.transpose(), -1.0);
        }
        let q = self.v.as_ref().subcols(s, b);
        // Every product into W also forms W's Gram matrix: its diagonal
        // gives the column norms, and the Cholesky QR starts from it.
        let mut a = Mat::zeros(b, b);
        let mut gram = Mat::zeros(b, b);
        tall::gram(a.as_mut(), q, self.w.as_ref());
        tall::mul_gram(self.w.as_mut(), Accum::Add, q, a.as_ref(), -1.0, gram.as_mut());
        // Full passes.
        let basis = self.v.as_ref().subcols(0, t);
        let mut before = gram_norms(&gram);
        for _ in 0..2 {
            let mut c = self.coef.as_mut().subrows_mut(0, t);
            tall::gram(c.rb_mut(), basis, self.w.as_ref());
            tall::mul_gram(self.w.as_mut(), Accum::Add, basis, c.rb(), -1.0, gram.as_mut());
            for i in 0..b {
                for j in 0..b {
                    a[(i, j)] += self.coef[(s + i, j)];
                }
            }
            let current = gram_norms(&gram);
            let kept = current.iter().zip(&before).all(|(a, b)| *a >= 0.5 * b);
            before = current;
            if kept {
                break;
            }
        }
        for i in 0..b {
            for j in 0..b {
                self.h[(s + i, s + j)] = 0.5 * (a[(i, j)] + a[(j, i)]);
            }
        }
        let (prev, next) = self.v.as_mut().split_at_col_mut(t);
        let r = orthonormalize_block(prev.rb(), &mut self.w, gram, &norms, next.subcols_mut(0, b), rng, &mut self.qr);
        self.g.as_mut().subcols_mut(from, s - from).fill(0.0);
        self.g.as_mut().submatrix_mut(0, s, b, b).copy_from(&r);
        self.s = t;
        self.g_from = s;
        times.orthogonalize += clock.elapsed().as_secs_f64();
        Ok(())
    }

    /// Ritz pairs: the locked columns as they are, the active block of
    /// `H` diagonalized, merged largest first.
    fn rayleigh_ritz(&self) -> Result<Ritz> {
        let (s, c) = (self.s, self.locked);
        let na = s - c;
        let eig = self
            .h
            .as_ref()
            .submatrix(c, c, na, na)
            .self_adjoint_eigen(Side::Lower)
            .map_err(|e| SpectralError::Dense(format!("projected eigenproblem: {e:?}")))?;
        // Slot j < c: locked column j; slot c + i: the i-th largest active pair.
        let value = |slot: usize| if slot < c { self.h[(slot, slot)] } else { eig.S()[na - 1 - (slot - c)] };
        let mut slot: Vec<usize> = (0..s).collect();
        slot.sort_by(|&x, &y| value(y).total_cmp(&value(x)));
        let theta: Vec<f64> = slot.iter().map(|&x| value(x)).collect();
        let mut vectors = Mat::zeros(s, s);
        for (k, &x) in slot.iter().enumerate() {
            if x < c {
                vectors[(x, k)] = 1.0;
            } else {
                let from = eig.U().col(na - 1 - (x - c));
                vectors.as_mut().col_mut(k).subrows_mut(c, na).copy_from(from);
            }
        }
        // The locked columns of G are zero: their pairs' residual estimates too.
        let mut gs = Mat::zeros(self.b, s);
        let (g, v) = (self.g.as_ref().subcols(c, na), vectors.as_ref().subrows(c, na));
        matmul(gs.as_mut(), Accum::Replace, g, v, 1.0, Par::Seq);
        let beta = column_norms(&gs);
        Ok(Ritz { theta, vectors, beta, slot })
    }

    /// Ritz vectors `y_j = V s_j` of the first `want` pairs: the locked
    /// ones copied, the others from the active columns of `V`, formed in
    /// the first columns and moved to their places.
    fn ritz_vectors(&self, ritz: &Ritz, want: usize) -> Mat<f64> {
        let (n, s, c) = (self.v.nrows(), self.s, self.locked);
        let active: Vec<usize> = (0..want).filter(|&k| ritz.slot[k] >= c).collect();
        let sa = Mat::from_fn(s - c, active.len(), |i, q| ritz.vectors[(c + i, active[q])]);
        let mut y = Mat::zeros(n, want);
        let v = self.v.as_ref();
        tall::mul(y.as_mut().subcols_mut(0, active.len()), Accum::Replace, v.subcols(c, s - c), sa.as_ref(), 1.0);
        move_columns(&mut y, &active);
        for (k, &j) in ritz.slot[..want].iter().enumerate() {
            if j < c {
                y.as_mut().col_mut(k).copy_from(v.col(j));
            }
        }
        y
    }

    /// Purified vectors `u_j = y_j + Q G s_j / theta_j = B y_j / theta_j`
    /// from the Krylov relation, in the block of the locked pairs' purified
    /// vectors (their columns moved to their places; at 1e5-1e6 vertices a
    /// fresh n x k block costs more in page zeroing than the product), which
    /// it takes: [`Self::restore_locked`] forms it again if the iteration
    /// goes on.
    fn purified(&mut self, ritz: &Ritz, y: MatRef<'_, f64>, want: usize) -> Mat<f64> {
        let (n, s, b, c) = (self.v.nrows(), self.s, self.b, self.locked);
        let mut gs = Mat::zeros(b, want);
        let sw = ritz.vectors.as_ref().subcols(0, want);
        matmul(gs.as_mut(), Accum::Replace, self.g.as_ref().subcols(0, s), sw, 1.0, Par::Seq);
        for j in 0..want {
            let inv = 1.0 / ritz.theta[j];
            gs.col_as_slice_mut(j).iter_mut().for_each(|x| *x *= inv);
        }
        let mut u = match self.locked_u.take() {
            Some(mut kept) => {
                let mut target = vec![usize::MAX; c];
                for (k, &j) in ritz.slot[..want].iter().enumerate() {
                    if j < c {
                        target[j] = k;
                    }
                }
                move_columns(&mut kept, &target);
                kept
            }
            None => Mat::zeros(n, want),
        };
        for (k, &j) in ritz.slot[..want].iter().enumerate() {
            if j >= c {
                u.as_mut().col_mut(k).copy_from(y.col(k));
            }
        }
        // G s = 0 for the locked pairs: their columns stay as they are.
        tall::mul(u.as_mut(), Accum::Add, self.v.as_ref().subcols(s, b), gs.as_ref(), 1.0);
        u
    }

    /// Forms the locked pairs' purified vectors `B v_j / theta_j` again
    /// when [`Self::purified`] took them; returns the operator columns
    /// applied.
    fn restore_locked<O: BlockOperator>(&mut self, op: &O, want: usize) -> Result<usize> {
        let (n, c) = (self.v.nrows(), self.locked);
        if c == 0 || self.locked_u.is_some() {
            return Ok(0);
        }
        let mut bv = Mat::zeros(n, c);
        op.apply(self.v.as_ref().subcols(0, c), &mut bv)?;
        let mut u = Mat::zeros(n, want);
        for j in 0..c {
            let inv = 1.0 / self.h[(j, j)];
            u.col_as_slice_mut(j).iter_mut().zip(bv.col_as_slice(j)).for_each(|(d, &x)| *d = x * inv);
        }
        self.locked_u = Some(u);
        Ok(c)
    }

    /// Thick restart keeping `p` Ritz pairs: the locked ones where they
    /// are, and the largest active ones, of which those among the first
    /// `want` whose residual estimate is at most `lock_tol` times their
    /// value are locked in turn (Stewart 2001's deflation): their columns of
    /// `G` are dropped, so that they leave the next Rayleigh-Ritz problems
    /// and restart rotations, and their purified vectors are kept aside.
    fn restart(&mut self, ritz: &Ritz, p: usize, want: usize, lock_tol: f64) {
        let (n, s, b, c) = (self.v.nrows(), self.s, self.b, self.locked);
        let locks = |k: usize| k < want && ritz.beta[k] <= lock_tol * ritz.theta[k].abs();
        // The rotated pairs, largest first: those to lock, then the others.
        let (mut rotated, mut others) = (Vec::new(), Vec::new());
        for k in (0..s).filter(|&k| ritz.slot[k] >= c).take(p - c) {
            if locks(k) && c + rotated.len() < want {
                rotated.push(k);
            } else {
                others.push(k);
            }
        }
        let newly = rotated.len();
        rotated.extend(others);
        let sp = Mat::from_fn(s - c, p - c, |i, q| ritz.vectors[(c + i, rotated[q])]);
        tall::rotate_in_place(self.v.as_mut().subcols_mut(c, s - c), sp.as_ref());
        // Move Q right after the kept vectors (p + b <= s: no overlap).
        let (mut left, right) = self.v.as_mut().split_at_col_mut(s);
        left.rb_mut().subcols_mut(p, b).copy_from(right.rb().subcols(0, b));
        let mut gs = Mat::zeros(b, p - c);
        matmul(gs.as_mut(), Accum::Replace, self.g.as_ref().subcols(c, s - c), sp.as_ref(), 1.0, Par::Seq);
        if newly > 0 {
            // u = y + Q G s / theta, as `purified` would give them now.
            let u = self.locked_u.get_or_insert_with(|| Mat::zeros(n, want));
            let mut dst = u.as_mut().subcols_mut(c, newly);
            dst.copy_from(self.v.as_ref().subcols(c, newly));
            let scaled = Mat::from_fn(b, newly, |i, q| gs[(i, q)] / ritz.theta[rotated[q]]);
            tall::mul(dst, Accum::Add, self.v.as_ref().subcols(p, b), scaled.as_ref(), 1.0);
        }
        let locked_theta: Vec<f64> = (0..c).map(|j| self.h[(j, j)]).collect();
        self.h.fill(0.0);
        for (j, &t) in locked_theta.iter().chain(rotated.iter().map(|&k| &ritz.theta[k])).enumerate() {
            self.h[(j, j)] = t;
        }
        let (from, active) = (c + newly, p - c - newly);
        self.g.fill(0.0);
        self.g.as_mut().subcols_mut(from, active).copy_from(gs.as_ref().subcols(newly, active));
        self.s = p;
        self.locked = from;
        self.g_from = from;
    }
}

/// Moves column `j` of `u` to column `target[j]` for every `j` below
/// `target.len()` (`usize::MAX`: dropped), in place: each chain of moves
/// from its free end, a cycle through one spare column.
fn move_columns(u: &mut Mat<f64>, target: &[usize]) {
    let c = target.len();
    let mut moved = vec![false; c];
    let mut spare = vec![0.0; u.nrows()];
    for first in 0..c {
        if moved[first] {
            continue;
        }
        // The sources whose places must be free before `first` moves.
        let mut chain = vec![first];
        let mut next = target[first];
        while next < c && !moved[next] && next != first {
            chain.push(next);
            next = target[next];
        }
        let cycle = next == first;
        if cycle {
            spare.copy_from_slice(u.col_as_slice(first));
        }
        for &src in chain.iter().rev() {
            moved[src] = true;
            let dst = target[src];
            if dst == usize::MAX || dst == src {
                continue;
            }
            if cycle && src == first {
                u.col_as_slice_mut(dst).copy_from_slice(&spare);
            } else if src < dst {
                let (left, mut right) = u.as_mut().split_at_col_mut(dst);
                right.rb_mut().col_mut(0).copy_from(left.rb().col(src));
            } else {
                let (mut left, right) = u.as_mut().split_at_col_mut(src);
                left.rb_mut().col_mut(dst).copy_from(right.rb().col(0));
            }
        }
    }
}

/// Orthonormalizes the columns of `q` (already orthogonal to `prev` to
/// working accuracy), returning the upper-triangular `R` with
/// `q = out R`. `norms` are the column norms before any
/// orthogonalization, `gram` the Gram matrix `q^T q`; the orthonormal
/// block goes to `out`, through the n x b buffer `work`. Matrix-matrix
/// Cholesky QR applied twice (Fukaya et al. 2014), the first time on the
/// column-normalized block, when it is well conditioned; otherwise modified
/// Gram-Schmidt twice (on `q`), where a column that kept less than 1e-13 of
/// its norm is numerically dependent (an invariant subspace was found) and
/// is replaced by a random direction orthogonal to everything (its
/// diagonal of `R` is zero).
fn orthonormalize_block(
    prev: MatRef<'_, f64>,
    q: &mut Mat<f64>,
    gram: Mat<f64>,
    norms: &[f64],
    mut out: MatMut<'_, f64>,
    rng: &mut SplitMix64,
    work: &mut Mat<f64>,
) -> Mat<f64> {
    if let Some(r) = cholesky_qr2(q, gram, norms, out.rb_mut(), work) {
        return r;
    }
    let r = gram_schmidt(prev, q, norms, rng);
    out.copy_from(&*q);
    r
}

/// Cholesky QR, twice, from the Gram matrix `gram = q^T q`, into `out`
/// through the buffer `work`; `None` (and `out` untouched) when a column
/// is nearly dependent (lost more than all but 1e-10 of its norm `norms`)
/// or the Gram matrix is too ill-conditioned for it. The first pass
/// scales the Gram matrix rather than the block: `q D^-1` has the Gram
/// matrix `D^-1 gram D^-1`, and `q D^-1 L^-T` is one product.
fn cholesky_qr2(
    q: &Mat<f64>,
    gram: Mat<f64>,
    norms: &[f64],
    mut out: MatMut<'_, f64>,
    work: &mut Mat<f64>,
) -> Option<Mat<f64>> {
    let b = q.ncols();
    let scale = gram_norms(&gram);
    if scale.iter().zip(norms).any(|(&c, &n)| !(c > 1e-10 * n && c > 0.0)) {
        return None;
    }
    let mut gram = Mat::from_fn(b, b, |i, j| gram[(i, j)] / (scale[i] * scale[j]));
    let mut r = Mat::from_fn(b, b, |i, j| if i == j { scale[j] } else { 0.0 });
    for pass in 0..2 {
        let llt = gram.llt(Side::Lower).ok()?;
        let l = llt.L();
        let (dmin, dmax) = (0..b).map(|i| l[(i, i)]).fold((f64::INFINITY, 0.0f64), |(a, z), d| (a.min(d), z.max(d)));
        if dmin.is_nan() || dmin <= 1e-5 * dmax {
            return None;
        }
        let mut linv = Mat::zeros(b, b);
        faer::linalg::triangular_inverse::invert_lower_triangular(linv.as_mut(), l, Par::Seq);
        r = l.transpose() * &r;
        // work = q D^-1 L^-T, then out = work L^-T.
        if pass == 0 {
            let factor = Mat::from_fn(b, b, |i, j| linv[(j, i)] / scale[i]);
            tall::mul_gram(work.as_mut(), Accum::Replace, q.as_ref(), factor.as_ref(), 1.0, gram.as_mut());
        } else {
            tall::mul(out.rb_mut(), Accum::Replace, work.as_ref(), linv.transpose(), 1.0);
        }
    }
    Some(r)
}

/// Modified Gram-Schmidt twice with random replacement of dependent columns.
fn gram_schmidt(prev: MatRef<'_, f64>, q: &mut Mat<f64>, norms: &[f64], rng: &mut SplitMix64) -> Mat<f64> {
    let (n, b) = (q.nrows(), q.ncols());
    let mut r = Mat::zeros(b, b);
    let mut col = vec![0.0; n];
    for i in 0..b {
        col.copy_from_slice(q.col_as_slice(i));
        for _ in 0..2 {
            against_previous(q, i, &mut col, Some(&mut r));
        }
        let mut norm = norm2(&col);
        if norm > 1e-13 * norms[i] && norm > 0.0 {
            r[(i, i)] = norm;
        } else {
            rng.fill_signed(&mut col);
            for _ in 0..2 {
                against_basis(prev, &mut col);
                against_previous(q, i, &mut col, None);
            }
            norm = norm2(&col);
        }
        let inv = if norm > 0.0 { 1.0 / norm } else { 0.0 };
        for (dst, &x) in q.col_as_slice_mut(i).iter_mut().zip(&col) {
            *dst = x * inv;
        }
    }
    r
}

/// Removes from `col` its components along columns `0..i` of `q`
/// (recording them in `r[.., i]` when given).
fn against_previous(q: &Mat<f64>, i: usize, col: &mut [f64], mut r: Option<&mut Mat<f64>>) {
    for j in 0..i {
        let qj = q.col_as_slice(j);
        let d = dot(qj, col);
        if let Some(r) = r.as_deref_mut() {
            r[(j, i)] += d;
        }
        for (x, &y) in col.iter_mut().zip(qj) {
            *x -= d * y;
        }
    }
}

/// `col -= P P^T col` for the orthonormal columns of `prev`.
fn against_basis(prev: MatRef<'_, f64>, col: &mut [f64]) {
    if prev.ncols() == 0 {
        return;
    }
    let n = col.len();
    let mut c = Mat::zeros(prev.ncols(), 1);
    tall::gram(c.as_mut(), prev, MatRef::from_column_major_slice(col, n, 1));
    tall::mul(MatMut::from_column_major_slice_mut(col, n, 1), Accum::Add, prev, c.as_ref(), -1.0);
}

/// The column norms of a block from its Gram matrix (square roots of the
/// diagonal).
fn gram_norms(gram: &Mat<f64>) -> Vec<f64> {
    (0..gram.ncols()).map(|j| gram[(j, j)].max(0.0).sqrt()).collect()
}

/// Euclidean norms of the columns (a plain dot product: faer's overflow-safe
/// `norm_l2` is several times slower and the values here are O(1)).
fn column_norms(m: &Mat<f64>) -> Vec<f64> {
    (0..m.ncols()).map(|j| norm2(m.col_as_slice(j))).collect()
}

fn norm2(a: &[f64]) -> f64 {
    dot(a, a).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Diagonal operator with given eigenvalues (repeated ones included).
    struct Diagonal(Vec<f64>);

    impl BlockOperator for Diagonal {
        fn dim(&self) -> usize {
            self.0.len()
        }
        fn apply(&self, q: MatRef<'_, f64>, w: &mut Mat<f64>) -> Result<()> {
            for j in 0..q.ncols() {
                for i in 0..q.nrows() {
                    w[(i, j)] = self.0[i] * q[(i, j)];
                }
            }
            Ok(())
        }
    }

    fn run(values: Vec<f64>, want: usize, block: usize) -> Outcome<Mat<f64>> {
        let n = values.len();
        let op = Diagonal(values);
        let nev = want + 2;
        let basis = (nev + 3 * block).min(n - block);
        let cfg = Config { want, nev, block, basis, tol: 1e-12, max_restarts: 500, seed: 3 };
        solve(&op, &cfg, |theta, _, u| {
            Ok(Verdict { ratios: vec![0.0], accepted: Mat::from_fn(1, theta.len(), |_, j| theta[j] + 0.0 * u[(0, j)]) })
        })
        .unwrap()
    }

    #[test]
    fn finds_every_copy_of_a_repeated_eigenvalue() {
        // 1 / (1 + i) with a fivefold top value: the block of 6 sees all copies.
        let mut values: Vec<f64> = (0..400).map(|i| 1.0 / (2.0 + i as f64)).collect();
        for v in values.iter_mut().skip(100).take(5) {
            *v = 1.5;
        }
        let out = run(values, 8, 6);
        for (j, t) in out.accepted.row(0).iter().enumerate() {
            let expect = if j < 5 { 1.5 } else { 1.0 / (2.0 + (j - 5) as f64) };
            assert!((t - expect).abs() < 1e-12, "{j}: {t} vs {expect}");
        }
    }

    #[test]
    fn locked_pairs_stay_eigenpairs_with_their_purified_vectors() {
        let values: Vec<f64> = (0..300).map(|i| 1.0 / (1.0 + i as f64)).collect();
        let op = Diagonal(values.clone());
        let (n, want, b, m) = (300, 12, 4, 30);
        let mut rng = SplitMix64::new(5);
        let mut ks = KrylovSchur::new(n, m, b);
        ks.start(&mut rng);
        let mut times = Timings::default();
        for _ in 0..12 {
            while ks.s + b <= m {
                ks.expand(&op, &mut rng, &mut times).unwrap();
            }
            let ritz = ks.rayleigh_ritz().unwrap();
            ks.restart(&ritz, 20, want, 1e-12);
        }
        let locked = ks.locked;
        assert!(locked > 0 && locked <= want, "{locked} locked");
        let kept = ks.locked_u.as_ref().unwrap();
        for j in 0..locked {
            let theta = ks.h[(j, j)];
            let (v, u) = (ks.v.col(j), kept.col(j));
            // B v = theta v to the locking tolerance, u = B v / theta.
            let residual = (0..n).map(|i| (values[i] * v[i] - theta * v[i]).abs()).fold(0.0, f64::max);
            let purified = (0..n).map(|i| (values[i] * v[i] / theta - u[i]).abs()).fold(0.0, f64::max);
            assert!(residual < 1e-11 * theta && purified < 1e-11, "{j}: {residual:e} {purified:e}");
            assert!((theta - values[j]).abs() < 1e-13, "{j}: {theta} against {}", values[j]);
        }
        // The Ritz values and estimates see the locked pairs as converged.
        let ritz = ks.rayleigh_ritz().unwrap();
        for k in 0..want {
            assert!((ritz.theta[k] - values[k]).abs() < 1e-10, "{k}: {}", ritz.theta[k]);
        }
    }

    #[test]
    fn columns_move_along_chains_and_cycles() {
        let start = Mat::from_fn(3, 7, |i, j| (10 * j + i) as f64);
        let drop = usize::MAX;
        for target in [vec![2, 3, 0, drop], vec![1, 2, 3, 5], vec![0, 4, 1, 6], vec![3, 2, 1, 0], vec![drop, 0]] {
            let mut u = start.clone();
            move_columns(&mut u, &target);
            for (j, &t) in target.iter().enumerate().filter(|(_, &t)| t != drop) {
                assert!(u.col(t).iter().eq(start.col(j).iter()), "{target:?}: {j} to {t}");
            }
        }
    }

    #[test]
    fn a_rejected_acceptance_forms_the_locked_vectors_again() {
        let values: Vec<f64> = (0..300).map(|i| 1.0 / (1.0 + i as f64)).collect();
        let op = Diagonal(values.clone());
        let cfg = Config { want: 12, nev: 14, block: 4, basis: 30, tol: 1e-10, max_restarts: 200, seed: 5 };
        let mut calls = 0;
        let out = solve(&op, &cfg, |theta, y, u| {
            calls += 1;
            // u = B y / theta, column by column, to the tolerance.
            let worst = (0..theta.len())
                .map(|j| (0..300).map(|i| (values[i] * y[(i, j)] / theta[j] - u[(i, j)]).abs()).fold(0.0, f64::max))
                .fold(0.0, f64::max);
            Ok(Verdict { ratios: vec![if calls <= 2 { 2.0 } else { 0.0 }], accepted: (theta.to_vec(), worst) })
        })
        .unwrap();
        let (theta, worst) = out.accepted;
        assert!(calls == 3 && worst < 1e-9, "{calls} calls, worst {worst:e}");
        for (j, t) in theta.iter().enumerate() {
            assert!((t - values[j]).abs() < 1e-12, "{j}: {t}");
        }
    }

    #[test]
    fn invariant_start_does_not_stall() {
        // Rank-deficient operator: only 3 non-zero eigenvalues.
        let mut values = vec![0.0; 60];
        values[10] = 3.0;
        values[20] = 2.0;
        values[30] = 1.0;
        let out = run(values, 3, 4);
        let theta = out.accepted.row(0);
        assert!((theta[0] - 3.0).abs() < 1e-12 && (theta[2] - 1.0).abs() < 1e-12, "{theta:?}");
    }
}
