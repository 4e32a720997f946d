//! Checking the matrices of `L x = lambda M x` and splitting the problem into
//! the connected components of `L`'s graph.
//!
//! The spectrum of a block-diagonal pencil is the union of the spectra of its
//! blocks, so each component is solved on its own: a mesh with `c` pieces has
//! the eigenvalue 0 exactly `c` times (one indicator function per piece) and
//! identical pieces repeat every eigenvalue; solving per component finds
//! every copy whatever the block size. Components whose total mass is zero
//! (isolated vertices, pieces made only of zero-area triangles) carry no
//! finite eigenvalue and are excluded: their vertices get zero in every
//! eigenvector. Zero-mass vertices inside a massive component stay: they are
//! constraints `(L x)_i = 0`, solved exactly by the harmonic extension.

use faer::Mat;
use sprs::CsMat;

use crate::error::{Result, SpectralError};

/// One connected component of the graph of `L`.
#[derive(Debug, Clone)]
pub(crate) struct Component {
    /// Global indices of its vertices, ascending.
    pub vertices: Vec<usize>,
    /// `L` restricted to the component (local indices, CSR).
    pub laplacian: CsMat<f64>,
    /// Lumped mass of each local vertex (non-negative).
    pub mass: Vec<f64>,
    /// Number of vertices with positive mass (= number of finite eigenvalues).
    pub massive: usize,
    /// Total mass (the area of the piece for a mesh).
    pub area: f64,
}

/// A component's pencil with its rows and columns in another order, a
/// factor's: `laplacian = P L P^T`, `mass[i]` that of row `order[i]`. The
/// Krylov vectors live in the factor's order; the acceptance tests and the
/// final Rayleigh-Ritz work there too, and the result is put back in the
/// component's order once ([`Self::to_component`]). At 470k vertices and
/// 200 vectors, turning the Ritz vectors into eigenvectors went from 3.5 s
/// of scattered stores to 0.15 s in place, and the one reordering at the
/// end takes 0.85 s.
pub(crate) struct Reordered<'a> {
    pub order: &'a [usize],
    pub laplacian: CsMat<f64>,
    pub mass: Vec<f64>,
}

impl<'a> Reordered<'a> {
    /// `c` in `order` (`order[i]` is the component row that comes i-th; a
    /// permutation of the component's rows). O(nnz log d).
    ///
    /// # Errors
    /// `SpectralError::Dimension` when `order` is not a permutation of the
    /// component's rows.
    pub fn new(c: &Component, order: &'a [usize]) -> Result<Self> {
        let n = c.vertices.len();
        let mut position = vec![usize::MAX; n];
        for (i, &row) in order.iter().enumerate() {
            match position.get_mut(row) {
                Some(p) if *p == usize::MAX => *p = i,
                _ => return Err(SpectralError::Dimension(format!("order is not a permutation of {n} rows"))),
            }
        }
        if order.len() != n {
            return Err(SpectralError::Dimension(format!("order has {} rows, the component {n}", order.len())));
        }
        let mut indptr = Vec::with_capacity(n + 1);
        let (mut indices, mut data) = (Vec::with_capacity(c.laplacian.nnz()), Vec::with_capacity(c.laplacian.nnz()));
        let mut row: Vec<(usize, f64)> = Vec::new();
        indptr.push(0);
        for &old in order {
            row.clear();
            if let Some(lane) = c.laplacian.outer_view(old) {
                row.extend(lane.iter().map(|(j, &v)| (position[j], v)));
            }
            row.sort_unstable_by_key(|e| e.0);
            indices.extend(row.iter().map(|e| e.0));
            data.extend(row.iter().map(|e| e.1));
            indptr.push(indices.len());
        }
        let laplacian = CsMat::try_new((n, n), indptr, indices, data)
            .map_err(|e| SpectralError::Dimension(format!("reordered L: {}", e.3)))?;
        let mass = order.iter().map(|&row| c.mass[row]).collect();
        Ok(Self { order, laplacian, mass })
    }

    /// `x` (rows in this order) with its rows back in the component's
    /// order, in place, by groups of 8 columns through a row-major buffer:
    /// one scattered cache line per row and group instead of one per value.
    pub fn to_component(&self, mut x: Mat<f64>) -> Mat<f64> {
        const GROUP: usize = 8;
        let (n, k) = (x.nrows(), x.ncols());
        let mut rows = vec![[0.0; GROUP]; n];
        for g in (0..k).step_by(GROUP) {
            let width = GROUP.min(k - g);
            let cols: Vec<_> = (g..g + width).map(|j| x.col(j)).collect();
            for (i, &row) in self.order.iter().enumerate() {
                for (c, col) in cols.iter().enumerate() {
                    rows[row][c] = col[i];
                }
            }
            super::quality::from_rows(&rows, x.as_mut().subcols_mut(g, width));
        }
        x
    }
}

/// The checked and split problem.
#[derive(Debug, Clone)]
pub(crate) struct Problem {
    /// Number of rows of `L`.
    pub n: usize,
    /// Components with positive total mass, ordered by smallest vertex.
    pub components: Vec<Component>,
    /// Vertices of massless components, ascending.
    pub excluded: Vec<usize>,
}

impl Problem {
    /// Number of finite eigenvalues of the whole pencil.
    pub fn available(&self) -> usize {
        self.components.iter().map(|c| c.massive).sum()
    }

    /// Keeps only the component of largest total mass (the first among
    /// equals); the vertices of the others join `excluded`.
    pub fn keep_largest(&mut self) {
        let Some(best) = (0..self.components.len())
            .max_by(|&a, &b| self.components[a].area.total_cmp(&self.components[b].area).then(b.cmp(&a)))
        else {
            return;
        };
        let kept = self.components.swap_remove(best);
        for c in self.components.drain(..) {
            self.excluded.extend_from_slice(&c.vertices);
        }
        self.excluded.sort_unstable();
        self.components.push(kept);
    }
}

fn invalid(name: &'static str, reason: String) -> SpectralError {
    SpectralError::InvalidMatrix { name, reason }
}

/// Checks `L` (square, finite, symmetric) and `M` (same size, diagonal,
/// finite, non-negative) and splits them by connected components.
/// O(nnz alpha(n)).
pub(crate) fn split(l: &CsMat<f64>, m: &CsMat<f64>) -> Result<Problem> {
    let converted;
    let l = if l.is_csr() {
        l
    } else {
        converted = l.to_csr();
        &converted
    };
    let n = check_laplacian(l)?;
    let mass = check_mass(m, n)?;
    let roots = union_find_components(l);
    // Group vertices by root, in order of first appearance (smallest vertex).
    let mut slot = vec![usize::MAX; n];
    let mut groups: Vec<Vec<usize>> = Vec::new();
    for v in 0..n {
        let r = roots[v];
        if slot[r] == usize::MAX {
            slot[r] = groups.len();
            groups.push(Vec::new());
        }
        groups[slot[r]].push(v);
    }
    let mut components = Vec::new();
    let mut excluded = Vec::new();
    let mut local = vec![usize::MAX; n];
    for vertices in groups {
        let area: f64 = vertices.iter().map(|&v| mass[v]).sum();
        if area <= 0.0 {
            excluded.extend_from_slice(&vertices);
            continue;
        }
        for (i, &v) in vertices.iter().enumerate() {
            local[v] = i;
        }
        let laplacian = restrict(l, &vertices, &local);
        let cmass: Vec<f64> = vertices.iter().map(|&v| mass[v]).collect();
        let massive = cmass.iter().filter(|&&x| x > 0.0).count();
        components.push(Component { vertices, laplacian, mass: cmass, massive, area });
    }
    excluded.sort_unstable();
    Ok(Problem { n, components, excluded })
}

/// Checks that the CSR matrix `l` is square, finite and symmetric to 1e-10
/// of its largest entry (an entry without its mirror is compared with 0).
/// One sweep down the rows, with a cursor into every row for the entries
/// left of the diagonal not yet matched: each entry (i, j) right of the
/// diagonal meets its mirror (j, i) at row j's cursor, and the cursor
/// passes over the entries of row j that have no mirror. O(nnz), where
/// looking every mirror up was O(nnz log d).
fn check_laplacian(l: &CsMat<f64>) -> Result<usize> {
    let (r, c) = l.shape();
    if r != c {
        return Err(invalid("L", format!("is {r} x {c}, not square")));
    }
    if let Some(bad) = l.data().iter().find(|v| !v.is_finite()) {
        return Err(invalid("L", format!("has a non-finite entry ({bad})")));
    }
    let scale = l.data().iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let tol = 1e-10 * scale;
    let (indptr, indices, data) = (l.indptr(), l.indices(), l.data());
    let row = |i: usize| indptr.outer_inds_sz(i);
    let asymmetric = |i: usize, j: usize, v: f64, t: f64| {
        invalid("L", format!("is not symmetric: L[{i},{j}] = {v} but L[{j},{i}] = {t}"))
    };
    // Row j's first entry left of its diagonal not yet matched.
    let mut cursor: Vec<usize> = (0..r).map(|j| row(j).start).collect();
    for i in 0..r {
        for k in row(i) {
            let (j, v) = (indices[k], data[k]);
            if j <= i {
                continue;
            }
            // Entries of row j left of column i have no mirror (their rows
            // are done): each must be within the tolerance of 0.
            let mut at = cursor[j];
            while at < row(j).end && indices[at] < i {
                if data[at].abs() > tol {
                    return Err(asymmetric(j, indices[at], data[at], 0.0));
                }
                at += 1;
            }
            let t = if at < row(j).end && indices[at] == i {
                at += 1;
                data[at - 1]
            } else {
                0.0
            };
            cursor[j] = at;
            if (v - t).abs() > tol {
                return Err(asymmetric(i, j, v, t));
            }
        }
    }
    // What is left of each row's entries left of its diagonal has no mirror.
    for j in 0..r {
        for k in cursor[j]..row(j).end {
            if indices[k] >= j {
                break;
            }
            if data[k].abs() > tol {
                return Err(asymmetric(j, indices[k], data[k], 0.0));
            }
        }
    }
    Ok(r)
}

fn check_mass(m: &CsMat<f64>, n: usize) -> Result<Vec<f64>> {
    if m.shape() != (n, n) {
        return Err(SpectralError::Dimension(format!("M is {} x {}, L is {n} x {n}", m.rows(), m.cols())));
    }
    let mut mass = vec![0.0; n];
    for (&v, (i, j)) in m.iter() {
        if !v.is_finite() {
            return Err(invalid("M", format!("has a non-finite entry ({v})")));
        }
        if i != j {
            if v != 0.0 {
                return Err(invalid("M", format!("must be diagonal (lumped), but M[{i},{j}] = {v}")));
            }
            continue;
        }
        mass[i] += v;
    }
    if let Some(i) = mass.iter().position(|&x| x < 0.0) {
        return Err(invalid("M", format!("has a negative mass M[{i},{i}] = {}", mass[i])));
    }
    Ok(mass)
}

/// Root of each vertex's component in the graph of the non-zero
/// off-diagonal entries (union-find with path halving). O(nnz alpha(n)).
fn union_find_components(l: &CsMat<f64>) -> Vec<usize> {
    let n = l.rows();
    let mut parent: Vec<usize> = (0..n).collect();
    fn find(parent: &mut [usize], mut x: usize) -> usize {
        while parent[x] != x {
            parent[x] = parent[parent[x]];
            x = parent[x];
        }
        x
    }
    for (i, row) in l.outer_iterator().enumerate() {
        for (j, &v) in row.iter() {
            if j != i && v != 0.0 {
                let (a, b) = (find(&mut parent, i), find(&mut parent, j));
                if a != b {
                    // Smaller index becomes the root: deterministic.
                    let (lo, hi) = if a < b { (a, b) } else { (b, a) };
                    parent[hi] = lo;
                }
            }
        }
    }
    (0..n).map(|v| find(&mut parent, v)).collect()
}

/// Rows and columns `vertices` of the CSR matrix `l`, renumbered by `local`.
fn restrict(l: &CsMat<f64>, vertices: &[usize], local: &[usize]) -> CsMat<f64> {
    let mut indptr = Vec::with_capacity(vertices.len() + 1);
    let mut indices = Vec::new();
    let mut data = Vec::new();
    indptr.push(0);
    for &v in vertices {
        if let Some(row) = l.outer_view(v) {
            for (j, &x) in row.iter() {
                // Every neighbour through a non-zero lies in the component;
                // explicit zeros to other components are dropped.
                if x != 0.0 || j == v {
                    let lj = local[j];
                    if lj < vertices.len() && vertices[lj] == j {
                        indices.push(lj);
                        data.push(x);
                    }
                }
            }
        }
        indptr.push(indices.len());
    }
    CsMat::new((vertices.len(), vertices.len()), indptr, indices, data)
}

/// The graph Laplacian of `edges` on `n` vertices (unit weights), for tests.
#[cfg(test)]
pub(crate) fn graph_laplacian(n: usize, edges: &[(usize, usize)]) -> CsMat<f64> {
    let mut t = sprs::TriMat::new((n, n));
    for &(a, b) in edges {
        t.add_triplet(a, b, -1.0);
        t.add_triplet(b, a, -1.0);
        t.add_triplet(a, a, 1.0);
        t.add_triplet(b, b, 1.0);
    }
    t.to_csr()
}

#[cfg(test)]
mod tests {
    use super::*;
    use sprs::TriMat;

    /// The one-sweep check of symmetry says what looking up every mirror
    /// says, on random patterns with entries missing their mirror (small
    /// ones, within the tolerance, and large ones, above and below the
    /// diagonal) and mirrors that differ.
    #[test]
    fn symmetry_check_agrees_with_looking_up_every_mirror() {
        let mut rng = mesh_kernel::random::SplitMix64::new(5);
        let (mut accepted, mut refused) = (0, 0);
        for case in 0..400 {
            let n = 2 + rng.below(30);
            let mut t = TriMat::new((n, n));
            let mut seen = std::collections::HashSet::new();
            for _ in 0..rng.below(4 * n) {
                let (i, j) = (rng.below(n), rng.below(n));
                if !seen.insert((i.min(j), i.max(j))) {
                    continue;
                }
                let v = rng.signed();
                t.add_triplet(i, i, 1.0);
                match rng.below(8) {
                    // Unmatched, within the tolerance, or not.
                    0 => t.add_triplet(i, j, 1e-13),
                    1 if case % 3 == 0 => t.add_triplet(i, j, v),
                    2 if case % 5 == 0 => {
                        t.add_triplet(i, j, v);
                        t.add_triplet(j, i, v + 1e-3);
                    }
                    _ => {
                        t.add_triplet(i, j, v);
                        if i != j {
                            t.add_triplet(j, i, v);
                        }
                    }
                }
            }
            let l: CsMat<f64> = t.to_csr();
            let scale = l.data().iter().fold(0.0f64, |a, v| a.max(v.abs()));
            let mirrored = l.iter().all(|(v, (i, j))| (v - l.get(j, i).copied().unwrap_or(0.0)).abs() <= 1e-10 * scale);
            assert_eq!(check_laplacian(&l).is_ok(), mirrored, "case {case}: {l:?}");
            if mirrored {
                accepted += 1;
            } else {
                refused += 1;
            }
        }
        assert!(accepted > 100 && refused > 100, "{accepted} accepted, {refused} refused");
    }

    fn path(n: usize, edges: &[(usize, usize)]) -> CsMat<f64> {
        graph_laplacian(n, edges)
    }

    #[test]
    fn reordering_permutes_the_pencil_and_puts_vectors_back() {
        let l = graph_laplacian(5, &[(0, 1), (1, 2), (2, 3), (3, 4), (0, 4), (1, 3)]);
        let mass = vec![1.0, 2.0, 3.0, 4.0, 5.0];
        let c = Component { vertices: (0..5).collect(), laplacian: l.clone(), mass, massive: 5, area: 15.0 };
        let order = [3, 0, 4, 1, 2];
        let r = Reordered::new(&c, &order).unwrap();
        for i in 0..5 {
            for j in 0..5 {
                assert_eq!(r.laplacian.get(i, j), l.get(order[i], order[j]), "({i}, {j})");
            }
            assert_eq!(r.mass[i], c.mass[order[i]]);
        }
        // 11 columns: a full group of 8 and a partial one.
        let x = Mat::from_fn(5, 11, |i, j| (order[i] * 100 + j) as f64);
        assert!(r.to_component(x) == Mat::from_fn(5, 11, |i, j| (i * 100 + j) as f64));
        assert!(Reordered::new(&c, &[0, 0, 1, 2, 3]).is_err());
        assert!(Reordered::new(&c, &[0, 1, 2]).is_err());
        assert!(Reordered::new(&c, &[0, 1, 2, 3, 9]).is_err());
    }

    #[test]
    fn components_and_exclusion() {
        let l = path(6, &[(0, 2), (2, 4), (1, 3)]);
        let m = mesh_kernel::operators::mass::diagonal(vec![1.0, 0.0, 1.0, 0.0, 1.0, 0.0]);
        let p = split(&l, &m).unwrap();
        assert_eq!(p.components.len(), 1);
        assert_eq!(p.components[0].vertices, vec![0, 2, 4]);
        assert_eq!(p.excluded, vec![1, 3, 5]);
        assert_eq!(p.available(), 3);
    }

    #[test]
    fn largest_by_mass_and_shifted_rows() {
        let l = path(5, &[(0, 1), (2, 3), (3, 4)]);
        let m = mesh_kernel::operators::mass::diagonal(vec![5.0, 5.0, 1.0, 1.0, 1.0]);
        let mut p = split(&l, &m).unwrap();
        p.keep_largest();
        assert_eq!(p.components.len(), 1);
        assert_eq!(p.components[0].vertices, vec![0, 1]);
        assert_eq!(p.excluded, vec![2, 3, 4]);
    }

    #[test]
    fn rejects_bad_matrices() {
        let l = path(3, &[(0, 1)]);
        let good = mesh_kernel::operators::mass::diagonal(vec![1.0; 3]);
        assert!(split(&l, &mesh_kernel::operators::mass::diagonal(vec![1.0; 2])).is_err());
        assert!(split(&l, &mesh_kernel::operators::mass::diagonal(vec![1.0, -1.0, 1.0])).is_err());
        assert!(split(&l, &mesh_kernel::operators::mass::diagonal(vec![1.0, f64::NAN, 1.0])).is_err());
        let mut t = TriMat::new((3, 3));
        t.add_triplet(0, 1, 1.0);
        assert!(split(&t.to_csr(), &good).is_err(), "non-symmetric L");
        assert!(split(&l, &l).is_err(), "non-diagonal M");
        let mut t = TriMat::new((3, 2));
        t.add_triplet(0, 1, 1.0);
        assert!(split(&t.to_csr(), &good).is_err(), "non-square L");
    }
}
