//! Data-parallel maps over index ranges, one policy for every crate: rayon
//! with the `rayon` feature for ranges of at least [`PARALLEL_FROM`] items
//! (split into tasks of at least [`MIN_TASK`] items), a plain loop
//! otherwise. Results are identical either way: each output of a map depends
//! only on its index, and [`scatter`] adds in an order fixed by the mesh, not
//! by the thread count.

/// Items from which a map runs in parallel: below it, one loop is faster
/// than handing out tasks (per-face loops of ~10 ns per item).
pub const PARALLEL_FROM: usize = 1 << 12;

/// Smallest number of items in one parallel task.
pub const MIN_TASK: usize = 1 << 11;

/// `(0..n).map(f).collect()`, in parallel from [`PARALLEL_FROM`] items.
pub fn map<T: Send>(n: usize, f: impl Fn(usize) -> T + Sync + Send) -> Vec<T> {
    #[cfg(feature = "rayon")]
    if n >= PARALLEL_FROM {
        use rayon::prelude::*;
        return (0..n).into_par_iter().with_min_len(MIN_TASK).map(f).collect();
    }
    (0..n).map(f).collect()
}

/// `items.iter_mut().for_each(f)`, in parallel from [`PARALLEL_FROM`] items.
pub fn update<T: Send>(items: &mut [T], f: impl Fn(&mut T) + Sync + Send) {
    #[cfg(feature = "rayon")]
    if items.len() >= PARALLEL_FROM {
        use rayon::prelude::*;
        items.par_iter_mut().with_min_len(MIN_TASK).for_each(f);
        return;
    }
    items.iter_mut().for_each(f);
}

/// Calls `f(i, row)` for every row `i` of a compressed-row array (`row` is
/// `data[offsets[i]..offsets[i + 1]]`), in parallel from [`PARALLEL_FROM`]
/// rows. `offsets` must start at 0, never decrease and end at
/// `data.len()`.
pub fn rows<T: Send>(data: &mut [T], offsets: &[usize], f: impl Fn(usize, &mut [T]) + Sync + Send) {
    let n = offsets.len().saturating_sub(1);
    let block = |first: usize, data: &mut [T]| {
        let base = offsets[first];
        for i in first..(first + MIN_TASK).min(n) {
            f(i, &mut data[offsets[i] - base..offsets[i + 1] - base]);
        }
    };
    #[cfg(feature = "rayon")]
    if n >= PARALLEL_FROM {
        use rayon::prelude::*;
        let mut blocks = Vec::with_capacity(n.div_ceil(MIN_TASK));
        let mut rest = data;
        for first in (0..n).step_by(MIN_TASK) {
            let len = offsets[(first + MIN_TASK).min(n)] - offsets[first];
            let (head, tail) = rest.split_at_mut(len);
            blocks.push((first, head));
            rest = tail;
        }
        blocks.into_par_iter().for_each(|(first, data)| block(first, data));
        return;
    }
    for first in (0..n).step_by(MIN_TASK) {
        let (lo, hi) = (offsets[first], offsets[(first + MIN_TASK).min(n)]);
        block(first, &mut data[lo..hi]);
    }
}

/// Faces per chunk of a [`scatter`] (the chunk count depends on the face
/// count only, so that the order of the sums does too).
pub const SCATTER_CHUNK: usize = 1 << 15;

/// Adds per-corner values of every face into per-vertex accumulators: for
/// face `f` with corners `[a, b, c]` and `values(f) = [x, y, z]`, it calls
/// `add(&mut out[a], x)`, then `b` and `c` likewise; `out` starts as `n`
/// copies of `init`. Corners must be below `n`.
///
/// Two cores split the work without changing the result: the faces form
/// chunks of [`SCATTER_CHUNK`] faces, each the sole writer of a range of
/// vertices, which it adds to in face order. A value for a vertex outside
/// the range is set aside, and what was set aside is added afterwards,
/// chunk after chunk. The vertex ranges start at the first corner of each
/// chunk's first face where those increase, so on meshes whose faces follow
/// their vertices (after [`crate::reorder::Reordering`]) little is set aside.
/// On meshes where a sample of the faces shows more than one corner in
/// eight outside its range, one loop adds everything in face order.
/// Either way the order depends on the mesh only.
pub fn scatter<A, V, I>(
    n: usize,
    faces: &[[I; 3]],
    init: A,
    values: impl Fn(usize) -> [V; 3] + Sync + Send,
    add: impl Fn(&mut A, V) + Sync + Send,
) -> Vec<A>
where
    A: Clone + Send + Sync,
    V: Copy + Send,
    I: Copy + Sync,
    u32: From<I>,
{
    scatter_with(n, faces, init, &Single(values), add)
}

/// [`scatter`] with the values of `B` consecutive faces at a time:
/// `values(first)` gives those of faces `first..first + B` (entries past
/// the last face are ignored), for kernels that are faster on a batch
/// ([`crate::operators::corner_angles_and_masses_batch`]). Batches start at
/// the first face of each chunk and every `B` faces after it; the sums are
/// added in the same order as [`scatter`]'s.
pub fn scatter_batched<A, V, I, const B: usize>(
    n: usize,
    faces: &[[I; 3]],
    init: A,
    values: impl Fn(usize) -> [[V; 3]; B] + Sync + Send,
    add: impl Fn(&mut A, V) + Sync + Send,
) -> Vec<A>
where
    A: Clone + Send + Sync,
    V: Copy + Send,
    I: Copy + Sync,
    u32: From<I>,
{
    scatter_with(n, faces, init, &Batched(values), add)
}

/// The values of the faces of a batch: a trait rather than a closure, so
/// that the one-face case inlines into the loop (a call per face, with its
/// result returned through memory, cost a third of an area-weighted normal).
trait FaceValues<V, const B: usize>: Sync + Send {
    fn of(&self, first: usize) -> [[V; 3]; B];
}

/// One face at a time ([`scatter`]).
struct Single<F>(F);

impl<V, F: Fn(usize) -> [V; 3] + Sync + Send> FaceValues<V, 1> for Single<F> {
    #[inline(always)]
    fn of(&self, first: usize) -> [[V; 3]; 1] {
        [(self.0)(first)]
    }
}

/// `B` faces at a time ([`scatter_batched`]).
struct Batched<F>(F);

impl<V, F: Fn(usize) -> [[V; 3]; B] + Sync + Send, const B: usize> FaceValues<V, B> for Batched<F> {
    #[inline(always)]
    fn of(&self, first: usize) -> [[V; 3]; B] {
        (self.0)(first)
    }
}

/// [`scatter_batched`] over any [`FaceValues`].
fn scatter_with<A, V, I, const B: usize>(
    n: usize,
    faces: &[[I; 3]],
    init: A,
    values: &impl FaceValues<V, B>,
    add: impl Fn(&mut A, V) + Sync + Send,
) -> Vec<A>
where
    A: Clone + Send + Sync,
    V: Copy + Send,
    I: Copy + Sync,
    u32: From<I>,
{
    let mut out = vec![init; n];
    let chunks = faces.len().div_ceil(SCATTER_CHUNK);
    let bounds = if chunks > 1 { vertex_ranges(n, faces, chunks) } else { Vec::new() };
    if chunks <= 1 || !mostly_owned(faces, &bounds) {
        each_corner::<V, I, B>(faces, values, 0, faces.len(), &mut |v, x| add(&mut out[v as usize], x));
        return out;
    }
    let mut owned = Vec::with_capacity(chunks);
    let mut rest = out.as_mut_slice();
    for c in 0..chunks {
        let (head, tail) = rest.split_at_mut(bounds[c + 1] - bounds[c]);
        owned.push((c, head));
        rest = tail;
    }
    let chunk = |(c, range): (usize, &mut [A])| {
        let (lo, first) = (bounds[c], c * SCATTER_CHUNK);
        let mut aside = Vec::with_capacity(SCATTER_CHUNK / 2);
        each_corner::<V, I, B>(faces, values, first, faces.len().min(first + SCATTER_CHUNK), &mut |v, x| match range
            .get_mut((v as usize).wrapping_sub(lo))
        {
            Some(slot) => add(slot, x),
            None => aside.push((v, x)),
        });
        aside
    };
    #[cfg(feature = "rayon")]
    let aside: Vec<Vec<(u32, V)>> = {
        use rayon::prelude::*;
        owned.into_par_iter().with_max_len(1).map(chunk).collect()
    };
    #[cfg(not(feature = "rayon"))]
    let aside: Vec<Vec<(u32, V)>> = owned.into_iter().map(chunk).collect();
    for (v, x) in aside.into_iter().flatten() {
        add(&mut out[v as usize], x);
    }
    out
}

/// Faces `lo..hi` of a [`scatter_batched`], batch by batch, each corner's
/// value to `sink(vertex, value)`; generic in the sink so that it inlines.
#[inline(always)]
fn each_corner<V: Copy, I: Copy, const B: usize>(
    faces: &[[I; 3]],
    values: &impl FaceValues<V, B>,
    lo: usize,
    hi: usize,
    sink: &mut impl FnMut(u32, V),
) where
    u32: From<I>,
{
    for first in (lo..hi).step_by(B.max(1)) {
        let x = values.of(first);
        for (tri, x) in faces[first..hi.min(first + B)].iter().zip(x) {
            for k in 0..3 {
                sink(u32::from(tri[k]), x[k]);
            }
        }
    }
}

/// Whether, judged from every 61st face, at most one corner in eight falls
/// outside its chunk's vertex range: otherwise setting corners aside costs
/// more than a second thread gains (meshes whose faces do not follow their
/// vertices), and [`scatter`] runs one loop in face order.
fn mostly_owned<I: Copy>(faces: &[[I; 3]], bounds: &[usize]) -> bool
where
    u32: From<I>,
{
    let (mut seen, mut outside) = (0usize, 0usize);
    for f in (0..faces.len()).step_by(61) {
        let c = f / SCATTER_CHUNK;
        for &v in &faces[f] {
            seen += 1;
            outside += usize::from(!(bounds[c]..bounds[c + 1]).contains(&(u32::from(v) as usize)));
        }
    }
    8 * outside <= seen
}

/// Start of each chunk's vertex range (and `n` at the end): the first
/// corners of the chunks' first faces where they increase, equal ranges
/// otherwise.
fn vertex_ranges<I: Copy>(n: usize, faces: &[[I; 3]], chunks: usize) -> Vec<usize>
where
    u32: From<I>,
{
    let mut bounds: Vec<usize> = (0..chunks).map(|c| u32::from(faces[c * SCATTER_CHUNK][0]) as usize).collect();
    bounds[0] = 0;
    bounds.push(n);
    if !bounds.windows(2).all(|w| w[0] < w[1]) {
        bounds = (0..=chunks).map(|c| c * n / chunks).collect();
    }
    bounds
}

/// Like [`map`] for items that each cost a millisecond or more (a march, a
/// solve): in parallel from two items, one item per task.
pub fn map_heavy<T: Send>(n: usize, f: impl Fn(usize) -> T + Sync + Send) -> Vec<T> {
    #[cfg(feature = "rayon")]
    if n >= 2 {
        use rayon::prelude::*;
        return (0..n).into_par_iter().with_max_len(1).map(f).collect();
    }
    (0..n).map(f).collect()
}

/// Like [`map`], with one scratch value per task (created by `init`) for
/// buffers reused across items; tasks are 8 times smaller, for items that
/// each cost microseconds (per-vertex fits).
pub fn map_with<T: Send, S>(
    n: usize,
    init: impl Fn() -> S + Sync + Send,
    f: impl Fn(&mut S, usize) -> T + Sync + Send,
) -> Vec<T> {
    #[cfg(feature = "rayon")]
    if n >= PARALLEL_FROM / 8 {
        use rayon::prelude::*;
        return (0..n).into_par_iter().with_min_len(MIN_TASK / 8).map_init(init, f).collect();
    }
    let mut scratch = init();
    (0..n).map(|i| f(&mut scratch, i)).collect()
}

/// Runs both closures, in parallel with the `rayon` feature.
pub fn join<A: Send, B: Send>(a: impl FnOnce() -> A + Send, b: impl FnOnce() -> B + Send) -> (A, B) {
    #[cfg(feature = "rayon")]
    return rayon::join(a, b);
    #[cfg(not(feature = "rayon"))]
    (a(), b())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::random::SplitMix64;

    /// A strip of `2 m` faces over `m + 2` vertices, faces in vertex order.
    fn strip(m: usize) -> Vec<[u32; 3]> {
        (0..m as u32).flat_map(|i| [[i, i + 1, i + 2], [i + 2, i + 1, i]]).collect()
    }

    /// `faces` with `swaps` random pairs exchanged (a full shuffle from
    /// `faces.len()` swaps on).
    fn shuffled(mut faces: Vec<[u32; 3]>, seed: u64, swaps: usize) -> Vec<[u32; 3]> {
        let mut rng = SplitMix64::new(seed);
        for i in (1..faces.len()).rev().take(swaps) {
            faces.swap(i, rng.below(i + 1));
        }
        faces
    }

    #[test]
    fn scatter_adds_every_corner_once_in_any_face_order() {
        let m = 3 * SCATTER_CHUNK;
        for faces in [strip(100), strip(m), shuffled(strip(m), 7, 500), shuffled(strip(m), 7, 2 * m)] {
            let n = faces.len() / 2 + 2;
            // Integer sums are exact: the corner counts and index sums.
            let out = scatter(
                n,
                &faces,
                (0u64, 0u64),
                |f| [(1, f as u64); 3],
                |a, (c, s)| {
                    a.0 += c;
                    a.1 += s;
                },
            );
            let mut expect = vec![(0u64, 0u64); n];
            for (f, tri) in faces.iter().enumerate() {
                for &v in tri {
                    expect[v as usize].0 += 1;
                    expect[v as usize].1 += f as u64;
                }
            }
            assert_eq!(out, expect);
        }
    }

    #[cfg(feature = "rayon")]
    #[test]
    fn scatter_sums_do_not_depend_on_the_thread_count() {
        let m = 5 * SCATTER_CHUNK;
        // In order, a few faces out of place (some corners set aside), shuffled.
        for (i, faces) in [strip(m), shuffled(strip(m), 3, 2000), shuffled(strip(m), 3, 2 * m)].into_iter().enumerate()
        {
            let bounds = vertex_ranges(m + 2, &faces, (2 * m).div_ceil(SCATTER_CHUNK));
            assert_eq!(mostly_owned(&faces, &bounds), i < 2, "case {i}");
            let n = faces.len() / 2 + 2;
            let run = |threads: usize| {
                let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
                pool.install(|| {
                    scatter(n, &faces, 0.0f64, |f| [1.0 / (f as f64 + 1.0), 0.1, (f as f64).sqrt()], |a, x| *a += x)
                })
            };
            let one = run(1);
            for threads in [2, 3, 8] {
                assert!(one.iter().zip(run(threads)).all(|(a, b)| a.to_bits() == b.to_bits()), "{threads} threads");
            }
        }
    }

    #[test]
    fn rows_see_their_own_entries() {
        for n in [10, 3 * PARALLEL_FROM + 5] {
            // Rows of 0 to 6 entries.
            let offsets: Vec<usize> = (0..=n).scan(0, |end, i| Some(std::mem::replace(end, *end + i % 7))).collect();
            let mut data = vec![usize::MAX; offsets[n]];
            rows(&mut data, &offsets, |i, row| {
                assert_eq!(row.len(), offsets[i + 1] - offsets[i]);
                row.iter_mut().for_each(|x| *x = i);
            });
            for i in 0..n {
                assert!(data[offsets[i]..offsets[i + 1]].iter().all(|x| *x == i), "row {i}");
            }
        }
    }
}
