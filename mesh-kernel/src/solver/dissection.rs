//! Geometric nested dissection: a fill-reducing order of the unknowns of a
//! sparse symmetric matrix whose unknowns sit at points in space (a mesh's
//! vertices), after George (1973) and, for separators cut by planes, Miller,
//! Teng, Thurston and Vavasis (1998).
//!
//! Each set of unknowns is cut by a plane normal to one of its principal
//! axes, placed where it cuts fewest edges for the balance it leaves
//! (`Work::best_cut`; the median of the principal axis for small sets);
//! the unknowns of one side that touch the other side (of the side where
//! they are fewer) form the vertex separator, numbered after both sides,
//! which are split in turn down to `LEAF` unknowns. On a surface mesh a
//! plane cuts a set of `m` vertices along about `sqrt(m)` of them, so the
//! factor has `O(n log n)` entries.
//!
//! What was measured and left out (BENCHMARKS.md, "Nested dissection"):
//! cutting at the median of the principal axis alone made factors 6%
//! (icosphere) to 20% (Loop-subdivided bunny, uneven vertex density)
//! larger;
//! refining separators by Fiduccia-Mattheyses vertex moves (Ashcraft and
//! Liu 1998) shrank them by 1-3% for up to 60% more ordering time;
//! minimum degree on the smallest sets gained under 1%. Cost:
//! `O(nnz log n)`, about minimum degree's time at 5e5 unknowns.

use glam::DVec3;

use crate::reorder::hilbert_order;

/// A fill-reducing order of the unknowns of the symmetric pattern given by
/// its lower triangle (`col_ptr`, `row_idx`: compressed columns, any entry
/// above the diagonal ignored): `order[i]` is the unknown eliminated `i`-th.
/// Unknown `j` sits at `points[j]`; `points.len()` is the dimension, and
/// every row index must be below it and below `u32::MAX`. Non-finite
/// points are compared with `total_cmp` (the order stays a permutation,
/// only a worse one).
pub(crate) fn nested_dissection(col_ptr: &[usize], row_idx: &[usize], points: &[DVec3]) -> Vec<usize> {
    let n = points.len();
    // Work on the unknowns renumbered along a Hilbert curve: the sets split
    // below are then runs of nearby memory.
    let hilbert = hilbert_order(points);
    let mut renumber = vec![0u32; n];
    for (new, &old) in hilbert.iter().enumerate() {
        renumber[old as usize] = new as u32;
    }
    let graph = Graph::symmetric(col_ptr, row_idx, &renumber);
    let points: Vec<DVec3> = hilbert.iter().map(|&v| points[v as usize]).collect();
    let mut order: Vec<usize> = (0..n).collect();
    let mut work = Work::new(n);
    // Sets still to split, as (start, end) in `order`.
    let mut sets = vec![(0, n)];
    while let Some((start, end)) = sets.pop() {
        if end - start <= LEAF {
            continue;
        }
        let (left, right) = work.split(&graph, &points, &mut order[start..end]);
        sets.push((start, start + left));
        sets.push((start + left, start + left + right));
    }
    order.iter().map(|&v| hilbert[v] as usize).collect()
}

/// The adjacency (both directions, no diagonal) in compressed rows; each
/// row starts with its neighbours of higher index.
struct Graph {
    ptr: Vec<usize>,
    /// End of the higher neighbours of each row.
    later: Vec<usize>,
    idx: Vec<u32>,
}

impl Graph {
    /// The graph of the lower triangle's pattern, unknown `v` renumbered
    /// `renumber[v]`.
    fn symmetric(col_ptr: &[usize], row_idx: &[usize], renumber: &[u32]) -> Self {
        let n = renumber.len();
        let edges = || {
            (0..n).flat_map(move |j| {
                row_idx[col_ptr[j]..col_ptr[j + 1]]
                    .iter()
                    .filter(move |&&i| i > j)
                    .map(move |&i| (renumber[i] as usize, renumber[j] as usize))
            })
        };
        let mut ptr = vec![0usize; n + 1];
        for (i, j) in edges() {
            ptr[i + 1] += 1;
            ptr[j + 1] += 1;
        }
        for v in 0..n {
            ptr[v + 1] += ptr[v];
        }
        // Higher neighbours first: fill them, then the lower ones.
        let mut fill = ptr.clone();
        let mut idx = vec![0u32; ptr[n]];
        for (i, j) in edges() {
            let (low, high) = if i < j { (i, j) } else { (j, i) };
            idx[fill[low]] = high as u32;
            fill[low] += 1;
        }
        let later = fill.clone();
        for (i, j) in edges() {
            let (low, high) = if i < j { (i, j) } else { (j, i) };
            idx[fill[high]] = low as u32;
            fill[high] += 1;
        }
        Self { ptr, later, idx }
    }

    /// The neighbours of higher index (each edge once over all rows).
    fn later_neighbors(&self, v: usize) -> impl Iterator<Item = usize> + '_ {
        self.idx[self.ptr[v]..self.later[v]].iter().map(|&w| w as usize)
    }

    fn neighbors(&self, v: usize) -> impl Iterator<Item = usize> + '_ {
        self.idx[self.ptr[v]..self.ptr[v + 1]].iter().map(|&w| w as usize)
    }
}

/// Labels of the unknowns (each split draws fresh ones, so labels of other
/// sets never collide) and reused buffers.
struct Work {
    label: Vec<usize>,
    next: usize,
    /// Per unknown, its slab along each of the three axes of the cut search.
    slab: Vec<[u16; 3]>,
    /// Per axis: unknowns per slab, and the difference array of edges cut
    /// between slabs.
    counts: [Vec<usize>; 3],
    cuts: [Vec<i64>; 3],
    keyed: Vec<(f64, usize)>,
    touching: Vec<bool>,
    scratch: Vec<usize>,
}

impl Work {
    fn new(n: usize) -> Self {
        Self {
            label: vec![0; n],
            next: 1,
            slab: vec![[0; 3]; n],
            counts: Default::default(),
            cuts: Default::default(),
            keyed: Vec::new(),
            touching: Vec::new(),
            scratch: Vec::new(),
        }
    }

    /// Splits `set` in place into `[first half | second half | separator]`;
    /// returns the sizes of the two halves.
    fn split(&mut self, graph: &Graph, points: &[DVec3], set: &mut [usize]) -> (usize, usize) {
        let axes = principal_axes(set.iter().map(|&v| points[v]));
        let search = if set.len() >= SEARCH_FROM { self.best_cut(graph, points, set, &axes) } else { None };
        match search {
            // The sides are the slabs on either side of the plane.
            Some(cut) => self.finish_cut(graph, set, cut),
            None => {
                let mid = set.len() / 2;
                self.keyed.clear();
                self.keyed.extend(set.iter().map(|&v| (points[v].dot(axes[0]), v)));
                self.keyed.select_nth_unstable_by(mid, |x, y| x.0.total_cmp(&y.0));
                set.iter_mut().zip(&self.keyed).for_each(|(slot, &(_, v))| *slot = v);
                self.finish(graph, set, mid)
            }
        }
    }

    /// The plane that cuts fewest edges for its balance: along each axis the
    /// set is cut into equal slabs, and each slab boundary leaving at least
    /// a share [`SMALLEST_SHARE`] on both sides is scored by its cut edges over
    /// `4 f (1 - f)` (`f`: the share on one side). Returns the cut, the
    /// slabs left in `self.slab` and the set's unknowns labelled with
    /// [`Cut::tag`]; `None` when the points do not spread.
    fn best_cut(&mut self, graph: &Graph, points: &[DVec3], set: &[usize], axes: &[DVec3; 3]) -> Option<Cut> {
        let m = set.len();
        let bins = (m / 4).clamp(2, SLABS);
        let tag = self.next;
        self.next += 1;
        let (mut low, mut high) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for &v in set {
            self.label[v] = tag;
            for a in 0..3 {
                let k = points[v].dot(axes[a]);
                low[a] = low[a].min(k);
                high[a] = high[a].max(k);
            }
        }
        let scale: [f64; 3] = std::array::from_fn(|a| {
            let extent = high[a] - low[a];
            if extent > 0.0 && extent.is_finite() {
                bins as f64 / extent
            } else {
                0.0
            }
        });
        for a in 0..3 {
            self.counts[a].clear();
            self.counts[a].resize(bins, 0);
            self.cuts[a].clear();
            self.cuts[a].resize(bins + 1, 0);
        }
        for &v in set {
            for a in 0..3 {
                let b = (((points[v].dot(axes[a]) - low[a]) * scale[a]) as usize).min(bins - 1);
                self.slab[v][a] = b as u16;
                self.counts[a][b] += 1;
            }
        }
        // The most slabs an edge spans, per axis.
        let mut span = [0u16; 3];
        for &u in set {
            let su = self.slab[u];
            for w in graph.later_neighbors(u) {
                if self.label[w] != tag {
                    continue;
                }
                let sw = self.slab[w];
                for a in 0..3 {
                    // An edge inside one slab adds and removes at one place.
                    let (first, last) = if su[a] <= sw[a] { (su[a], sw[a]) } else { (sw[a], su[a]) };
                    self.cuts[a][first as usize + 1] += 1;
                    self.cuts[a][last as usize + 1] -= 1;
                    span[a] = span[a].max(last - first);
                }
            }
        }
        // The best (score, axis, first slab above) so far.
        let mut best: Option<(f64, usize, usize)> = None;
        for a in (0..3).filter(|&a| scale[a] > 0.0) {
            let (mut cut, mut below) = (0i64, 0usize);
            for j in 1..bins {
                cut += self.cuts[a][j];
                below += self.counts[a][j - 1];
                let f = below as f64 / m as f64;
                if (SMALLEST_SHARE..=1.0 - SMALLEST_SHARE).contains(&f) {
                    let score = cut as f64 / (4.0 * f * (1.0 - f));
                    if best.is_none_or(|b| score < b.0) {
                        best = Some((score, a, j));
                    }
                }
            }
        }
        // `j < bins <= SLABS` fits the slabs' type.
        best.map(|(_, axis, j)| Cut { axis, boundary: j as u16, span: span[axis], tag })
    }

    /// Splits `set` by a searched cut: the first side is the slabs below
    /// the boundary, the second the slabs above, and the separator the
    /// unknowns of the side with fewer of them that have a neighbour on the
    /// other side. Only unknowns within [`Cut::span`] slabs of the
    /// boundary can have one, so only their neighbours are read. Lays
    /// `set` out as `[first side | second side | separator]`; returns the
    /// sizes of the two sides.
    fn finish_cut(&mut self, graph: &Graph, set: &mut [usize], cut: Cut) -> (usize, usize) {
        let Cut { axis, boundary, span, tag } = cut;
        let near = boundary.saturating_sub(span)..boundary.saturating_add(span);
        let mut counts = [0usize; 2];
        let mut touching = [0usize; 2];
        self.touching.clear();
        for &v in set.iter() {
            let slab = self.slab[v][axis];
            let below = slab < boundary;
            counts[usize::from(!below)] += 1;
            let touches = near.contains(&slab)
                && graph.neighbors(v).any(|w| self.label[w] == tag && (self.slab[w][axis] < boundary) != below);
            touching[usize::from(!below)] += usize::from(touches);
            self.touching.push(touches);
        }
        // The separator is taken from the side with fewer touching unknowns.
        let from = usize::from(touching[1] < touching[0]);
        let mut sizes = counts;
        sizes[from] -= touching[from];
        let mut at = [0, sizes[0], sizes[0] + sizes[1]];
        self.scratch.clear();
        self.scratch.resize(set.len(), 0);
        for (&v, &touches) in set.iter().zip(&self.touching) {
            let side = usize::from(self.slab[v][axis] >= boundary);
            let part = if touches && side == from { 2 } else { side };
            self.scratch[at[part]] = v;
            at[part] += 1;
        }
        set.copy_from_slice(&self.scratch);
        (sizes[0], sizes[1])
    }

    /// Takes the first `mid` unknowns of `set` as the first side and the
    /// rest as the second, takes the separator, and lays `set` out as
    /// `[first side | second side | separator]`; returns the sizes of the
    /// two sides.
    fn finish(&mut self, graph: &Graph, set: &mut [usize], mid: usize) -> (usize, usize) {
        let (a, b, s) = (self.next, self.next + 1, self.next + 2);
        self.next += 3;
        for (i, &v) in set.iter().enumerate() {
            self.label[v] = if i < mid { a } else { b };
        }
        // The separator: the vertices of the side with fewer of them that
        // touch the other side.
        let (first, second) = set.split_at(mid);
        self.touching.clear();
        self.touching.extend(first.iter().map(|&v| graph.neighbors(v).any(|w| self.label[w] == b)));
        self.touching.extend(second.iter().map(|&v| graph.neighbors(v).any(|w| self.label[w] == a)));
        let touch_first = self.touching[..mid].iter().filter(|&&t| t).count();
        let touch_second = self.touching[mid..].iter().filter(|&&t| t).count();
        let (side, sizes) = if touch_first <= touch_second {
            (0..mid, [mid - touch_first, set.len() - mid])
        } else {
            (mid..set.len(), [mid, set.len() - mid - touch_second])
        };
        for i in side {
            if self.touching[i] {
                self.label[set[i]] = s;
            }
        }
        // One pass places each unknown at the next place of its part.
        let mut at = [0, sizes[0], sizes[0] + sizes[1]];
        self.scratch.clear();
        self.scratch.resize(set.len(), 0);
        for &v in set.iter() {
            let part = self.label[v] - a;
            self.scratch[at[part]] = v;
            at[part] += 1;
        }
        set.copy_from_slice(&self.scratch);
        (sizes[0], sizes[1])
    }
}

/// A plane found by [`Work::best_cut`].
#[derive(Clone, Copy)]
struct Cut {
    /// Index of the axis in the set's principal axes.
    axis: usize,
    /// The first slab above the plane.
    boundary: u16,
    /// The most slabs any edge inside the set spans along the axis.
    span: u16,
    /// The label of the set's unknowns.
    tag: usize,
}

/// Sets of at most this many unknowns are not split further (their order
/// changes the factor by under 1%, splitting them was 30% of the time).
const LEAF: usize = 8;
/// Sets from this size search their cut ([`Work::best_cut`]); smaller ones
/// are cut at the median of the principal axis.
const SEARCH_FROM: usize = 64;
/// Most slabs per axis in the cut search.
const SLABS: usize = 1024;
/// Smallest share of a set on either side of a searched cut.
const SMALLEST_SHARE: f64 = 0.35;
/// Unit direction of largest spread of the points (the dominant eigenvector
/// of their covariance, by cyclic Jacobi rotations); `x` when they
/// coincide.
/// The three principal directions, by decreasing spread.
fn principal_axes(points: impl Iterator<Item = DVec3>) -> [DVec3; 3] {
    // Moments about the first point (no cancellation for sets far from the
    // origin).
    let mut points = points.peekable();
    let origin = points.peek().copied().unwrap_or(DVec3::ZERO);
    let (mut count, mut sum) = (0.0f64, DVec3::ZERO);
    let mut c = [[0.0f64; 3]; 3];
    for p in points {
        let d = p - origin;
        count += 1.0;
        sum += d;
        let d = d.to_array();
        for i in 0..3 {
            for j in 0..3 {
                c[i][j] += d[i] * d[j];
            }
        }
    }
    let mean = (sum / count.max(1.0)).to_array();
    for i in 0..3 {
        for j in 0..3 {
            c[i][j] -= count * mean[i] * mean[j];
        }
    }
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let scale = c[0][0].abs() + c[1][1].abs() + c[2][2].abs();
    for _sweep in 0..12 {
        if c[0][1].abs() + c[0][2].abs() + c[1][2].abs() <= 1e-12 * scale {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if c[p][q].abs() <= 1e-300 {
                continue;
            }
            let theta = (c[q][q] - c[p][p]) / (2.0 * c[p][q]);
            let t = theta.signum() / (theta.abs() + theta.hypot(1.0));
            let cos = 1.0 / t.hypot(1.0);
            let sin = t * cos;
            for row in c.iter_mut() {
                let (x, y) = (row[p], row[q]);
                row[p] = cos * x - sin * y;
                row[q] = sin * x + cos * y;
            }
            for k in 0..3 {
                let (x, y) = (c[p][k], c[q][k]);
                c[p][k] = cos * x - sin * y;
                c[q][k] = sin * x + cos * y;
            }
            for row in v.iter_mut() {
                let (x, y) = (row[p], row[q]);
                row[p] = cos * x - sin * y;
                row[q] = sin * x + cos * y;
            }
        }
    }
    let mut k = [0, 1, 2];
    k.sort_by(|&i, &j| c[j][j].total_cmp(&c[i][i]));
    let axes = k.map(|k| DVec3::new(v[0][k], v[1][k], v[2][k]));
    if axes.iter().all(|a| a.is_finite() && a.length_squared() > 0.5) {
        axes
    } else {
        [DVec3::X, DVec3::Y, DVec3::Z]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The lower triangle of a `w x h` grid graph's 5-point pattern.
    fn grid(w: usize, h: usize) -> (Vec<usize>, Vec<usize>, Vec<DVec3>) {
        let id = |x: usize, y: usize| y * w + x;
        let (mut ptr, mut idx, mut points) = (vec![0], vec![], vec![]);
        for y in 0..h {
            for x in 0..w {
                idx.push(id(x, y));
                if x + 1 < w {
                    idx.push(id(x + 1, y));
                }
                if y + 1 < h {
                    idx.push(id(x, y + 1));
                }
                ptr.push(idx.len());
                points.push(DVec3::new(x as f64, y as f64, 0.0));
            }
        }
        (ptr, idx, points)
    }

    #[test]
    fn order_is_a_permutation_and_separators_come_last() {
        let (ptr, idx, points) = grid(32, 17);
        let order = nested_dissection(&ptr, &idx, &points);
        let mut seen = order.clone();
        seen.sort_unstable();
        assert_eq!(seen, (0..32 * 17).collect::<Vec<_>>());
        // The top separator of a 32 x 17 grid is one column of 17 vertices.
        let last: Vec<usize> = order[order.len() - 17..].iter().map(|&v| v % 32).collect();
        assert!(last.iter().all(|&x| x == last[0]), "top separator is a column: {last:?}");
    }

    #[test]
    fn degenerate_points_still_give_a_permutation() {
        let (ptr, idx, _) = grid(9, 9);
        for points in [vec![DVec3::ONE; 81], vec![DVec3::new(f64::NAN, 0.0, 1.0); 81]] {
            let mut order = nested_dissection(&ptr, &idx, &points);
            order.sort_unstable();
            assert_eq!(order, (0..81).collect::<Vec<_>>());
        }
    }

    #[test]
    fn principal_axis_of_a_tilted_segment() {
        let d = DVec3::new(1.0, 2.0, -2.0) / 3.0;
        let axis = principal_axes((0..50).map(|i| d * i as f64 + DVec3::new(0.0, 0.01 * (i % 3) as f64, 0.0)))[0];
        assert!(axis.dot(d).abs() > 0.999, "{axis}");
    }
}
