//! The k smallest pairs over all components: the exact null vectors first
//! (one constant per component), then as many computed pairs per component
//! as can still rank among the k smallest.

use faer::Mat;

use super::component::{self, spectral_scale, Partial};
use super::problem::{Component, Problem};
use super::quality::{quality, Quality, Stiffness};
use super::{EigenOptions, EigenSolver, EigenStats, Eigenpairs};
use crate::error::{Result, SpectralError};

/// Where a returned pair comes from.
#[derive(Debug, Clone, Copy)]
enum Source {
    /// The constant of component `c`.
    Null(usize),
    /// Pair `j` of the partial result of component `c`.
    Computed(usize, usize),
}

/// The constant of a component, M-normalized: `1 / sqrt(area)` on its
/// vertices, with its quality, or `None` when it misses the tolerance (the
/// rows of `L` do not sum to zero: not a Laplacian).
fn null_pair(c: &Component, scale: f64, tolerance: f64) -> Result<Option<(Mat<f64>, Quality)>> {
    let x = Mat::from_fn(c.vertices.len(), 1, |_, _| 1.0 / c.area.sqrt());
    let p = Stiffness::new(&c.laplacian).apply(x.as_ref());
    let q = quality(&p, &c.mass, &[0.0], x.as_ref(), scale, tolerance);
    Ok((q.misses() == 0).then_some((x, q)))
}

/// Solves every component of `problem` for its share of the `k` smallest
/// pairs and merges them: ascending values, ties by component (largest area
/// first) then position, so the result is deterministic.
pub(crate) fn solve_all(problem: &Problem, k: usize, options: &EigenOptions) -> Result<Eigenpairs> {
    let comps = &problem.components;
    let mut by_area: Vec<usize> = (0..comps.len()).collect();
    by_area.sort_by(|&a, &b| comps[b].area.total_cmp(&comps[a].area).then(a.cmp(&b)));
    let mut rank = vec![0; comps.len()];
    for (r, &c) in by_area.iter().enumerate() {
        rank[c] = r;
    }
    let scales: Vec<f64> = comps.iter().map(|c| spectral_scale(c.area, k)).collect();
    let nulls =
        comps.iter().zip(&scales).map(|(c, &s)| null_pair(c, s, options.tolerance)).collect::<Result<Vec<_>>>()?;
    let deflated = nulls.iter().filter(|n| n.is_some()).count();
    // Every null vector ranks before any positive eigenvalue.
    let beyond_nulls = k - k.min(deflated);
    let mut partials: Vec<Option<Partial>> = Vec::with_capacity(comps.len());
    for (comp, null) in comps.iter().zip(&nulls) {
        let want = if null.is_some() { beyond_nulls.min(comp.massive - 1) } else { k.min(comp.massive) };
        partials.push(if want == 0 { None } else { Some(component::solve(comp, want, null.is_some(), k, options)?) });
    }
    let mut order: Vec<(f64, usize, usize, Source)> = Vec::new();
    for c in 0..comps.len() {
        if nulls[c].is_some() {
            order.push((0.0, rank[c], 0, Source::Null(c)));
        }
        if let Some(p) = &partials[c] {
            order.extend(p.values.iter().enumerate().map(|(j, &v)| (v, rank[c], j + 1, Source::Computed(c, j))));
        }
    }
    order.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));
    order.truncate(k);
    let mut vectors = Mat::zeros(problem.n, order.len());
    let mut chosen = Quality::default();
    let mut values = Vec::with_capacity(order.len());
    let mut zeros = 0;
    for (col, &(value, _, _, source)) in order.iter().enumerate() {
        let (c, x, q, j) = match source {
            Source::Null(c) => {
                zeros += 1;
                let (x, q) = nulls[c].as_ref().map(|(x, q)| (x, q)).ok_or_else(missing)?;
                (c, x, q, 0)
            }
            Source::Computed(c, j) => {
                let p = partials[c].as_ref().ok_or_else(missing)?;
                (c, &p.vectors, &p.quality, j)
            }
        };
        values.push(value);
        chosen.relative.push(q.relative[j]);
        chosen.absolute.push(q.absolute[j]);
        chosen.target.push(q.target[j]);
        let (src, dst) = (x.col_as_slice(j), vectors.col_as_slice_mut(col));
        for (li, &g) in comps[c].vertices.iter().enumerate() {
            dst[g] = src[li];
        }
    }
    if chosen.misses() > 0 {
        return Err(SpectralError::NotConverged {
            converged: order.len() - chosen.misses(),
            wanted: k,
            attempts: 1,
            restarts: 0,
            tolerance: options.tolerance,
            residuals: chosen.relative,
        });
    }
    let mut stats = combined_stats(&by_area, &partials);
    stats.components_used = comps.len();
    stats.zero_eigenvalues = zeros;
    stats.tolerance = chosen.target.iter().copied().fold(options.tolerance, f64::max);
    Ok(Eigenpairs {
        values,
        residuals: chosen.relative,
        absolute_residuals: chosen.absolute,
        excluded: Vec::new(),
        stats,
        vectors,
    })
}

fn missing() -> SpectralError {
    SpectralError::Dense("internal: a merged pair has no source".into())
}

/// Counts and times summed over the solved components; sizes, shift and
/// method of the largest solved one.
fn combined_stats(by_area: &[usize], partials: &[Option<Partial>]) -> EigenStats {
    let solved: Vec<&EigenStats> = partials.iter().flatten().map(|p| &p.stats).collect();
    let largest = by_area.iter().find_map(|&c| partials[c].as_ref().map(|p| p.stats.clone()));
    let mut stats = largest.unwrap_or_else(|| EigenStats::empty(EigenSolver::NullSpace));
    // A fold from +0: an empty `sum` of f64 is -0.
    let sum = |f: fn(&EigenStats) -> f64| solved.iter().fold(0.0, |a, s| a + f(s));
    stats.clusters_verified = solved.iter().all(|s| s.clusters_verified);
    stats.restarts = solved.iter().map(|s| s.restarts).sum();
    stats.operator_columns = solved.iter().map(|s| s.operator_columns).sum();
    stats.factor_seconds = sum(|s| s.factor_seconds);
    stats.iterate_seconds = sum(|s| s.iterate_seconds);
    stats.solve_seconds = sum(|s| s.solve_seconds);
    stats.orthogonalize_seconds = sum(|s| s.orthogonalize_seconds);
    stats.finalize_seconds = sum(|s| s.finalize_seconds);
    stats
}
