//! The pairs of one connected component: dense for small pieces, block
//! Krylov-Schur shift-invert otherwise, with the constant null vector
//! deflated, every returned pair checked on its explicit residual, and
//! retries (more restarts, a larger block, another shift) before
//! [`SpectralError::NotConverged`].

use std::f64::consts::PI;
use std::time::Instant;

use faer::{Mat, MatRef};

use super::krylov::{self, BlockOperator, Config, Verdict};
use super::problem::{Component, Reordered};
use super::quality::{final_rayleigh_ritz, quality, rayleigh_quotients, Quality, Stiffness};
use super::shift_invert::ShiftInvert;
use super::{dense, EigenOptions, EigenSolver, EigenStats};
use crate::error::{Result, SpectralError};
use mesh_kernel::solver::FillOrdering;

/// The pairs of one component, before merging: values ascending, vectors
/// over the component's vertices, their quality.
pub(crate) struct Partial {
    pub values: Vec<f64>,
    pub vectors: Mat<f64>,
    pub quality: Quality,
    pub stats: EigenStats,
}

/// Vertex count up to which the dense path is still taken when the Krylov
/// basis would not fit (k close to n).
const DENSE_LIMIT: usize = 4000;

/// Weyl's law for a piece of area `area`: `lambda_j ~ 4 pi j / area`; the
/// scale `max(lambda_est(want) / 20, lambda_est(1) / 2)` of the `want`
/// smallest pairs, which residuals are measured against and the default
/// shift is placed at (negated).
pub(crate) fn spectral_scale(area: f64, want: usize) -> f64 {
    let weyl = 4.0 * PI / area;
    (weyl * want as f64 / 20.0).max(weyl / 2.0)
}

/// The `want` smallest pairs of `c` (beyond the constant when `deflate`),
/// measured against the scale of `scale_pairs` pairs.
pub(crate) fn solve(
    c: &Component,
    want: usize,
    deflate: bool,
    scale_pairs: usize,
    options: &EigenOptions,
) -> Result<Partial> {
    let scale = spectral_scale(c.area, scale_pairs);
    let dim = c.massive - usize::from(deflate);
    match KrylovSizes::new(want, dim, options) {
        Some(sizes) if c.vertices.len() > options.dense_threshold => {
            krylov_component(c, want, deflate, scale, sizes, options)
        }
        _ if c.massive <= DENSE_LIMIT.max(options.dense_threshold) => dense_component(c, want, deflate, scale, options),
        _ => Err(SpectralError::InvalidOption {
            name: "k",
            reason: format!("{want} pairs of a {}-vertex piece: use k below {}", c.massive, c.massive / 3),
        }),
    }
}

fn dense_component(c: &Component, want: usize, deflate: bool, scale: f64, options: &EigenOptions) -> Result<Partial> {
    let t = Instant::now();
    let (values, vectors) = dense::smallest(c, want, deflate)?;
    let mut stats = EigenStats::empty(EigenSolver::Dense);
    stats.attempts = 1;
    stats.iterate_seconds = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let p = Stiffness::new(&c.laplacian).apply(vectors.as_ref());
    let quality = quality(&p, &c.mass, &values, vectors.as_ref(), scale, options.tolerance);
    stats.finalize_seconds = t.elapsed().as_secs_f64();
    Ok(Partial { values, vectors, quality, stats })
}

/// The block of a Krylov run for up to 32 wanted pairs (with the guard).
const NARROW_BLOCK: usize = 4;

/// The step by which larger blocks grow: 8 per 64 pairs, up to 32 (blocks
/// of 48 and 64 for k = 200 took more solve columns and time, BENCHMARKS.md,
/// 2026-12-04).
const BLOCK_STEP: usize = 8;

/// Guard, block and basis sizes of a Krylov run.
#[derive(Debug, Clone, Copy)]
struct KrylovSizes {
    nev: usize,
    block: usize,
    basis: usize,
}

impl KrylovSizes {
    /// `None` when the basis would not fit in the dimension `dim`.
    fn new(want: usize, dim: usize, o: &EigenOptions) -> Option<Self> {
        let nev = want + o.guard.unwrap_or((want / 10).max(4));
        let block = o.block_size.unwrap_or(if nev <= 32 {
            NARROW_BLOCK
        } else {
            (BLOCK_STEP * nev.div_ceil(64)).clamp(BLOCK_STEP, 4 * BLOCK_STEP)
        });
        Self::with_block(want, dim, o, block)
    }

    fn with_block(want: usize, dim: usize, o: &EigenOptions, block: usize) -> Option<Self> {
        let nev = want + o.guard.unwrap_or((want / 10).max(4));
        let basis = o.basis_size.unwrap_or(2 * nev + 2 * block).max(nev + 2 * block);
        (basis + block <= dim).then_some(Self { nev, block, basis })
    }

    /// The sizes of the next attempt: a block step more in the block (when
    /// the block size is automatic), the basis grown to match.
    fn grown(self, want: usize, dim: usize, o: &EigenOptions, at_least: usize) -> Self {
        if o.block_size.is_some() {
            return self;
        }
        let step = if self.block < BLOCK_STEP { NARROW_BLOCK } else { BLOCK_STEP };
        let block = (self.block + step).max(at_least.next_multiple_of(NARROW_BLOCK));
        Self::with_block(want, dim, o, block).unwrap_or(self)
    }
}

/// `P B P` with `P = I - y0 y0^T`: the shift-invert operator on the
/// complement of its exact eigenvector `y0` (the constant, scaled). Only the
/// output is projected: `y0` is an eigenvector of `B` (`K 1 = -sigma M 1`),
/// so the part of a block along `y0` comes out along `y0` and the projection
/// of the output removes it (`P B = P B P`), and rounding cannot bring the
/// constant back into the basis.
struct Deflated<'a> {
    op: &'a ShiftInvert,
    y0: Option<Vec<f64>>,
}

impl BlockOperator for Deflated<'_> {
    fn dim(&self) -> usize {
        self.op.dim()
    }
    fn apply(&self, q: MatRef<'_, f64>, w: &mut Mat<f64>) -> Result<()> {
        self.op.apply(q, w, self.y0.as_deref())
    }
}

/// Factors `L - sigma M` for the first sigma that works: `preferred`
/// (the user's shift, if any, is never changed), then ten times further
/// from the spectrum, up to 8 times.
fn factor(c: &Component, preferred: f64, fixed: bool, ordering: Option<&FillOrdering>) -> Result<ShiftInvert> {
    let ordering = ordering.map_or(FillOrdering::MinimumDegree, |o| o.restrict(&c.vertices));
    if fixed {
        return ShiftInvert::new(c, preferred, &ordering);
    }
    let mut shift = preferred;
    let mut last = None;
    for _ in 0..8 {
        match ShiftInvert::new(c, shift, &ordering) {
            Ok(op) => return Ok(op),
            Err(e) => last = Some(e),
        }
        shift *= 10.0;
    }
    Err(last.unwrap_or_else(|| SpectralError::Dense("no shift could be factored".into())))
}

/// Most attempts per component. Attempt 2 grows the block and doubles the
/// restarts; attempt 3 also moves the shift four times further from the
/// spectrum (a better conditioned `K`, for pencils where the solves limit
/// the accuracy). A converged cluster as large as the block (a block of b
/// vectors sees at most b copies of an eigenvalue) whose inertia count
/// differs also triggers a larger block; when the block cannot grow, or
/// the count still differs after the last attempt, the last converged
/// pairs are returned with [`EigenStats::clusters_verified`] false.
const MAX_ATTEMPTS: usize = 3;

fn krylov_component(
    c: &Component,
    want: usize,
    deflate: bool,
    scale: f64,
    sizes: KrylovSizes,
    options: &EigenOptions,
) -> Result<Partial> {
    let dim = c.massive - usize::from(deflate);
    let mut stats = EigenStats::empty(EigenSolver::BlockKrylovSchur);
    let (mut sizes, mut restarts) = (sizes, options.max_restarts);
    let mut shift = options.shift.unwrap_or(-scale);
    let mut op: Option<ShiftInvert> = None;
    // A passing result whose block may have hidden copies of a cluster, and
    // the quality of the last failed attempt.
    let mut passed: Option<Partial> = None;
    let mut failed = Quality::default();
    for attempt in 1..=MAX_ATTEMPTS {
        if op.as_ref().is_none_or(|o| o.shift() != shift) {
            let t = Instant::now();
            let factored = factor(c, shift, options.shift.is_some(), options.ordering.as_ref())?;
            stats.factor_seconds += t.elapsed().as_secs_f64();
            shift = factored.shift();
            op = Some(factored);
        }
        let Some(si) = op.as_ref() else { break };
        stats.shift = Some(si.shift());
        stats.factor_nonzeros = si.factor_nonzeros();
        stats.attempts = attempt;
        let y0 = deflate.then(|| null_vector(si, c));
        let deflated = Deflated { op: si, y0 };
        let ordered = Reordered::new(c, si.order())?;
        let run = Run { ordered: &ordered, op: &deflated, scale, want, sizes, restarts, options };
        match run.go(&mut stats) {
            Ok(partial) if partial.quality.misses() == 0 => {
                let cluster = largest_cluster(&partial.values, scale);
                if cluster < sizes.block || every_pair_found(si, c, &partial.values, deflate, scale, &mut stats)? {
                    return Ok(Partial { stats, ..partial });
                }
                // Copies may be missing: again with a larger block, or
                // flagged when the block cannot grow (the same run again
                // would give the same pairs).
                let larger = sizes.grown(want, dim, options, cluster + 2);
                if larger.block == sizes.block {
                    stats.clusters_verified = false;
                    return Ok(Partial { stats, ..partial });
                }
                sizes = larger;
                passed = Some(partial);
                continue;
            }
            Ok(partial) => failed = partial.quality,
            Err(SpectralError::NotConverged { residuals, .. }) => {
                let target = vec![options.tolerance; residuals.len()];
                failed = Quality { relative: residuals, target, absolute: Vec::new() };
            }
            Err(e) => return Err(e),
        }
        sizes = sizes.grown(want, dim, options, 0);
        restarts = restarts.saturating_mul(2);
        if attempt + 1 == MAX_ATTEMPTS && options.shift.is_none() {
            shift *= 4.0;
        }
    }
    match passed {
        Some(partial) => {
            stats.clusters_verified = false;
            Ok(Partial { stats, ..partial })
        }
        None => Err(not_converged(&failed, want, &stats, options.tolerance)),
    }
}

fn not_converged(q: &Quality, want: usize, stats: &EigenStats, tolerance: f64) -> SpectralError {
    SpectralError::NotConverged {
        converged: q.relative.len() - q.misses(),
        wanted: want,
        attempts: stats.attempts,
        restarts: stats.restarts,
        tolerance: q.target.iter().copied().fold(tolerance, f64::max),
        residuals: q.relative.clone(),
    }
}

/// Whether `values` (ascending; with the constant's 0 when `deflate`) hold
/// every copy of every eigenvalue of the component below their last
/// cluster: the number of eigenvalues below `mu`, just under that cluster,
/// counted by inertia. A block of b vectors can miss copies of an eigenvalue
/// repeated more than b times; this count finds them without solving again.
/// Copies of the last cluster beyond the k asked for need not be found:
/// they would not change the k smallest values. `false` when the count
/// differs or cannot be trusted. Its time goes to the finalize phase.
fn every_pair_found(
    si: &ShiftInvert,
    c: &Component,
    values: &[f64],
    deflate: bool,
    scale: f64,
    stats: &mut EigenStats,
) -> Result<bool> {
    let mut first = values.len().saturating_sub(1);
    while first > 0 && same_value(values[first - 1], values[first], scale) {
        first -= 1;
    }
    let Some(&bottom) = values.get(first) else { return Ok(true) };
    let mu = bottom - 1e-6 * (bottom.abs() + scale);
    let found = values.iter().filter(|v| **v < mu).count() + usize::from(deflate && mu > 0.0);
    let t = Instant::now();
    let below = si.eigenvalues_below(c, mu)?;
    stats.finalize_seconds += t.elapsed().as_secs_f64();
    Ok(below == Some(found))
}

/// `M^1/2 1 / sqrt(area)` in the coordinates of `op`: the unit eigenvector
/// of `B` for the eigenvalue 0 of the pencil.
fn null_vector(op: &ShiftInvert, c: &Component) -> Vec<f64> {
    let inv = 1.0 / c.area.sqrt();
    op.rows().iter().map(|&row| c.mass[row].sqrt() * inv).collect()
}

/// One block Krylov-Schur run and its final Rayleigh-Ritz.
struct Run<'a> {
    /// The component in the factor's order, the order of every vector
    /// until the result.
    ordered: &'a Reordered<'a>,
    op: &'a Deflated<'a>,
    scale: f64,
    want: usize,
    sizes: KrylovSizes,
    restarts: usize,
    options: &'a EigenOptions,
}

impl Run<'_> {
    /// Adds its counts and timings to `stats`.
    fn go(&self, stats: &mut EigenStats) -> Result<Partial> {
        let t = Instant::now();
        let (tol, scale, mass) = (self.options.tolerance, self.scale, &self.ordered.mass);
        let st = Stiffness::new(&self.ordered.laplacian);
        let cfg = Config {
            want: self.want,
            nev: self.sizes.nev.min(self.sizes.basis - 2 * self.sizes.block),
            block: self.sizes.block,
            basis: self.sizes.basis,
            tol,
            max_restarts: self.restarts,
            seed: self.options.seed,
        };
        let si = self.op.op;
        let outcome = krylov::solve(self.op, &cfg, |theta, y, u| {
            let x = si.vectors(y.as_ref(), u, theta)?;
            let p = st.apply_into(x.as_ref(), y);
            let values = rayleigh_quotients(&p.lx, mass, x.as_ref());
            let q = quality(&p, mass, &values, x.as_ref(), scale, tol);
            Ok(Verdict { ratios: q.ratios(), accepted: (x, p) })
        });
        stats.iterate_seconds += t.elapsed().as_secs_f64();
        stats.block_size = cfg.block;
        stats.basis_size = cfg.basis;
        let outcome = match outcome {
            Ok(o) => o,
            Err(e) => {
                if let SpectralError::NotConverged { restarts, .. } = &e {
                    stats.restarts += restarts;
                }
                return Err(e);
            }
        };
        stats.restarts += outcome.restarts;
        stats.operator_columns += outcome.columns;
        stats.solve_seconds += outcome.timings.apply;
        stats.orthogonalize_seconds += outcome.timings.orthogonalize;
        let t = Instant::now();
        let (x, products) = outcome.accepted;
        let (values, vectors, products) = final_rayleigh_ritz(mass, x, products)?;
        let quality = quality(&products, mass, &values, vectors.as_ref(), scale, tol);
        let vectors = self.ordered.to_component(vectors);
        stats.finalize_seconds += t.elapsed().as_secs_f64();
        Ok(Partial { values, vectors, quality, stats: stats.clone() })
    }
}

/// Relative distance under which two values count as copies of one
/// eigenvalue (see [`same_value`]).
const CLUSTER: f64 = 1e-8;

/// Whether `a` and `b` count as copies of one eigenvalue:
/// `|a - b| <= CLUSTER (|b| + scale)`.
fn same_value(a: f64, b: f64, scale: f64) -> bool {
    (b - a).abs() <= CLUSTER * (b.abs() + scale)
}

/// Size of the largest run of ascending values that are [`same_value`]
/// as their neighbour.
fn largest_cluster(values: &[f64], scale: f64) -> usize {
    let mut best = usize::from(!values.is_empty());
    let mut run = 1;
    for w in values.windows(2) {
        if same_value(w[0], w[1], scale) {
            run += 1;
            best = best.max(run);
        } else {
            run = 1;
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::super::problem::{graph_laplacian, split};
    use super::*;
    use mesh_kernel::operators::mass::diagonal;

    #[test]
    fn the_inertia_count_notices_missing_copies() {
        // A path of 60 with 8 leaves on its first vertex: the differences of
        // two leaves are 7 copies of the eigenvalue 1, amid the path's modes.
        let edges: Vec<(usize, usize)> = (0..59).map(|i| (i, i + 1)).chain((60..68).map(|leaf| (0, leaf))).collect();
        let l = graph_laplacian(68, &edges);
        let problem = split(&l, &diagonal(vec![1.0; 68])).unwrap();
        let c = &problem.components[0];
        let (values, _) = dense::smallest(c, 30, true).unwrap();
        let copies: Vec<usize> = (0..values.len()).filter(|&j| (values[j] - 1.0).abs() < 1e-9).collect();
        assert_eq!(copies.len(), 7, "{values:?}");
        assert!(*copies.last().unwrap() < values.len() - 1);
        let si = ShiftInvert::new(c, -0.1, &FillOrdering::MinimumDegree).unwrap();
        let mut stats = EigenStats::empty(EigenSolver::BlockKrylovSchur);
        assert!(every_pair_found(&si, c, &values, true, 1.0, &mut stats).unwrap());
        // Two copies missing, the next values moving up in their place.
        let mut missing = values.clone();
        missing.drain(copies[0]..copies[0] + 2);
        assert!(!every_pair_found(&si, c, &missing, true, 1.0, &mut stats).unwrap());
        // Missing copies of the last cluster change nothing among the k smallest.
        let last = &values[..=copies[3]];
        assert!(every_pair_found(&si, c, last, true, 1.0, &mut stats).unwrap());
    }
}
