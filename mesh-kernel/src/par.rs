//! Data-parallel maps over index ranges, one policy for every crate: rayon
//! with the `rayon` feature for ranges of at least [`PARALLEL_FROM`] items
//! ([`UPDATE_FROM`] for the cheap in-place [`update`], [`CHEAP_FROM`] for
//! maps of a few nanoseconds per item; split into tasks of at least
//! [`MIN_TASK`] items), a plain loop otherwise. Results are identical
//! either way: each output of a map depends only on its index, and
//! [`scatter`] adds in an order fixed by the mesh, not by the thread
//! count.

use std::sync::atomic::{AtomicU32, AtomicU64, Ordering::Relaxed};
use std::sync::OnceLock;

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

/// Items from which maps of a few nanoseconds per item ([`map_columns`],
/// [`map_chunks`]) run in parallel: where a second thread saves more than
/// the 0.1-0.4 ms of waking it. At 40,962 vertices, the per-vertex pass
/// of the Gaussian curvature took 0.4 ms longer on two threads than on
/// one (2026-12-05).
pub const CHEAP_FROM: usize = 1 << 17;

/// `K` arrays of `n` values and one of `n` flags, row `i` of them being
/// `f(i) = (values, flag)`: a [`map`] whose results go to separate arrays
/// (a struct of arrays), each entry written once, with no array filled
/// beforehand; in parallel from [`CHEAP_FROM`] rows (per-vertex values
/// from sums over faces, and a status). A `()` flag costs nothing.
pub fn map_columns<T, U, const K: usize>(
    n: usize,
    f: impl Fn(usize) -> ([T; K], U) + Sync + Send,
) -> ([Vec<T>; K], Vec<U>)
where
    T: Copy + Send + Sync,
    U: Copy + Send + Sync,
{
    use std::mem::{take, MaybeUninit};
    let mut columns: [Vec<T>; K] = std::array::from_fn(|_| Vec::with_capacity(n));
    let mut flags: Vec<U> = Vec::with_capacity(n);
    type Piece<'a, X> = &'a mut [MaybeUninit<X>];
    let fill = |(first, mut pieces, flags): (usize, [Piece<T>; K], Piece<U>)| {
        for (j, flag) in flags.iter_mut().enumerate() {
            let (row, f_j) = f(first + j);
            for (piece, value) in pieces.iter_mut().zip(row) {
                piece[j].write(value);
            }
            flag.write(f_j);
        }
    };
    let mut rest: [Piece<T>; K] = columns.each_mut().map(|c| &mut c.spare_capacity_mut()[..n]);
    let mut rest_flags: Piece<U> = &mut flags.spare_capacity_mut()[..n];
    let mut chunks = Vec::with_capacity(n.div_ceil(MIN_TASK));
    for first in (0..n).step_by(MIN_TASK) {
        let len = MIN_TASK.min(n - first);
        let pieces = rest.each_mut().map(|r| {
            let (head, tail) = take(r).split_at_mut(len);
            *r = tail;
            head
        });
        let (head, tail) = take(&mut rest_flags).split_at_mut(len);
        rest_flags = tail;
        chunks.push((first, pieces, head));
    }
    #[cfg(feature = "rayon")]
    if n >= CHEAP_FROM {
        use rayon::prelude::*;
        chunks.into_par_iter().for_each(fill);
    } else {
        chunks.into_iter().for_each(fill);
    }
    #[cfg(not(feature = "rayon"))]
    chunks.into_iter().for_each(fill);
    // SAFETY: the chunks cover rows 0..n of every array, and `fill` wrote
    // each of their slots (had `f` panicked, we would not be here); `Copy`
    // values need no drop.
    unsafe {
        columns.iter_mut().for_each(|column| column.set_len(n));
        flags.set_len(n);
    }
    (columns, flags)
}

/// Items from which [`update`] runs in parallel. Its updates are cheap
/// (unit normals four at a time, about 20 ns per item), and waking a second
/// thread cost about 0.4 ms on a 2-core Intel Xeon VM: from
/// [`PARALLEL_FROM`] the area-weighted normals of a 40,962-vertex
/// icosphere took 0.87-0.90 ms on two threads against 0.47-0.51 on one
/// (0.46-0.49 from this threshold), while at 470,274 vertices two threads
/// still save 1.1-2.4 ms (2026-12-05).
pub const UPDATE_FROM: usize = 1 << 15;

/// `items.iter_mut().for_each(f)`, in parallel from [`UPDATE_FROM`] items.
pub fn update<T: Send>(items: &mut [T], f: impl Fn(&mut T) + Sync + Send) {
    #[cfg(feature = "rayon")]
    if items.len() >= UPDATE_FROM {
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
    rows_with(data, offsets, || (), |_, i, row| f(i, row));
}

/// Like [`rows`], with one scratch value per task (created by `init`) and
/// a result per row: `f(&mut scratch, i, row)` for every row `i`, the
/// results in row order.
pub fn rows_with<T: Send, S, R: Send>(
    data: &mut [T],
    offsets: &[usize],
    init: impl Fn() -> S + Sync + Send,
    f: impl Fn(&mut S, usize, &mut [T]) -> R + Sync + Send,
) -> Vec<R> {
    let n = offsets.len().saturating_sub(1);
    let block = |first: usize, data: &mut [T]| {
        let (base, mut scratch) = (offsets[first], init());
        let rows = first..(first + MIN_TASK).min(n);
        rows.map(|i| f(&mut scratch, i, &mut data[offsets[i] - base..offsets[i + 1] - base])).collect::<Vec<R>>()
    };
    let mut blocks = Vec::with_capacity(n.div_ceil(MIN_TASK));
    let mut rest = data;
    for first in (0..n).step_by(MIN_TASK) {
        let len = offsets[(first + MIN_TASK).min(n)] - offsets[first];
        let (head, tail) = rest.split_at_mut(len);
        blocks.push((first, head));
        rest = tail;
    }
    #[cfg(feature = "rayon")]
    if n >= PARALLEL_FROM {
        use rayon::prelude::*;
        let done: Vec<Vec<R>> = blocks.into_par_iter().map(|(first, data)| block(first, data)).collect();
        return concat(done, n);
    }
    concat(blocks.into_iter().map(|(first, data)| block(first, data)), n)
}

/// The parts one after the other, `len` values in all (a copy per part,
/// not a step per value).
fn concat<R>(parts: impl IntoIterator<Item = Vec<R>>, len: usize) -> Vec<R> {
    let mut all = Vec::with_capacity(len);
    for mut part in parts {
        all.append(&mut part);
    }
    all
}

/// A stable counting sort of `G len` items given in records of `G` (the
/// corners of faces, say): item `G i + j` has key `keys(i)[j] < key_count`
/// and value `values(i)[j]`. Returns the start of each key's group
/// (`key_count + 1` offsets) and the values in group order, the items of
/// one key in increasing item number.
///
/// On several threads the records are counted and placed in runs side by
/// side, each run's items of a key after those of the runs before it,
/// which is the order of one run: the result does not depend on the thread
/// count. `G len` must fit in `u32`.
pub fn group_by_key<T, const G: usize>(
    key_count: usize,
    len: usize,
    keys: impl Fn(usize) -> [usize; G] + Sync + Send,
    values: impl Fn(usize) -> [T; G] + Sync + Send,
) -> (Vec<usize>, Vec<T>)
where
    T: Into<u64> + From<u64> + Clone + Send,
{
    let runs = if G * len >= PARALLEL_FROM { threads().min(MAX_RUNS) } else { 1 };
    let piece = len.div_ceil(runs).max(1);
    let records = |r: usize| r * piece..len.min((r + 1) * piece);
    let counts = map_heavy(runs, |r| {
        let mut count = vec![0u32; key_count];
        for i in records(r) {
            keys(i).into_iter().for_each(|k| count[k] += 1);
        }
        count
    });
    // Where each run's first item of each key goes.
    let mut fills = counts;
    let mut offsets = Vec::with_capacity(key_count + 1);
    let mut total = 0u32;
    for k in 0..key_count {
        offsets.push(total as usize);
        for fill in &mut fills {
            total += std::mem::replace(&mut fill[k], total);
        }
    }
    offsets.push(total as usize);
    // Each run places its items after its own cursors; every slot is
    // written once. One run writes them straight into the result.
    if runs == 1 {
        let mut grouped: Vec<T> = vec![T::from(0); G * len];
        let at = grouped.as_ptr();
        place(records(0), fills[0].clone(), &keys, &values, at, |p, x| grouped[p] = x);
        return (offsets, grouped);
    }
    let slots = atomic_slots64(G * len);
    map_heavy(runs, |r| {
        place(records(r), fills[r].clone(), &keys, &values, slots.as_ptr(), |p, x| slots[p].store(x.into(), Relaxed))
    });
    (offsets, slots.into_iter().map(|s| T::from(s.into_inner())).collect())
}

/// The items of `records` of a [`group_by_key`] to `put(position, value)`,
/// each after the cursor `fill` of its key (generic in `put`, so that it
/// inlines). The slots `slots[fill[k]]` of the keys [`READ_AHEAD`] records
/// on are asked for ahead ([`crate::hint::prefetch`]): the items land at
/// random, and the processor does not ask for the lines of stores ahead on
/// its own. Boundary loops from scratch at 470,274 vertices (two such
/// sorts) took 88.5-91.9 ms on one thread instead of 93.7-101.4, 59.1-67.8
/// on two instead of 64.1-72.6 (three alternated rounds, 2026-12-06).
#[inline(always)]
fn place<T, S, const G: usize>(
    records: std::ops::Range<usize>,
    mut fill: Vec<u32>,
    keys: &impl Fn(usize) -> [usize; G],
    values: &impl Fn(usize) -> [T; G],
    slots: *const S,
    mut put: impl FnMut(usize, T),
) {
    let end = records.end;
    for i in records {
        if i + READ_AHEAD < end {
            for k in keys(i + READ_AHEAD) {
                crate::hint::prefetch(slots.wrapping_add(fill[k] as usize));
            }
        }
        for (k, x) in keys(i).into_iter().zip(values(i)) {
            put(fill[k] as usize, x);
            fill[k] += 1;
        }
    }
}

/// Most runs of a [`group_by_key`] or of a [`scatter`]'s [`owners`]: each
/// costs an array over the keys or the vertices, and one step more to merge.
const MAX_RUNS: usize = 4;

/// The number of threads a parallel map started here runs on (1 without
/// the `rayon` feature).
fn threads() -> usize {
    #[cfg(feature = "rayon")]
    return rayon::current_num_threads();
    #[cfg(not(feature = "rayon"))]
    1
}

/// `len` slots holding `value`, for arrays that several threads fill, each
/// slot by one of them (relaxed stores: plain writes on x86); [`plain`]
/// turns them back into values once every thread is done.
pub fn atomic_slots(len: usize, value: u32) -> Vec<AtomicU32> {
    map(len, |_| AtomicU32::new(value))
}

/// The values of [`atomic_slots`] once every writer is done, collected in
/// place (same layout).
pub fn plain(slots: Vec<AtomicU32>) -> Vec<u32> {
    slots.into_iter().map(AtomicU32::into_inner).collect()
}

/// `len` zeroed 64-bit [`atomic_slots`]. Both are made by a [`map`], on
/// several threads: a [`group_by_key`]'s 2,614,242 slots took 1.4-1.5 ms
/// on two threads instead of 2.0-2.3 in one loop (2026-12-07).
fn atomic_slots64(len: usize) -> Vec<AtomicU64> {
    map(len, |_| AtomicU64::new(0))
}

/// Fewest faces per part of a [`scatter`] on several threads.
pub const SCATTER_CHUNK: usize = 1 << 16;

/// Adds per-corner values of every face into per-vertex accumulators: for
/// face `f` with corners `[a, b, c]` and `values(f) = [x, y, z]`, it calls
/// `add(&mut out[a], x)`, then `b` and `c` likewise; `out` starts as `n`
/// copies of `init`. Corners must be below `n`.
///
/// Every vertex receives its values in face order, whatever the thread
/// count, so the sums are identical on any number of threads. Several
/// threads split the faces into consecutive parts; a vertex belongs to the
/// first part that has it as a corner, which adds to it directly, while
/// later parts set their values for it aside, to be added part after part
/// at the end. The first part looks up no owner (it owns all its
/// corners), and the others look up a face's three at once, with the rare
/// face that has a corner to set aside handled out of the loop: at 470,274
/// vertices on two threads, normals took 4.94-4.97 ms instead of 5.48-5.53
/// and the Voronoi mass 9.0-9.5 instead of 10.0-10.1, where a lookup and a
/// branch per corner had made each part's loop 1.5 times slower per face
/// than one loop over all faces (three alternated rounds on an Emerald
/// Rapids Xeon, 2026-12-07). On meshes whose consecutive faces lie side by
/// side (scans, subdivided meshes, any mesh after
/// [`crate::reorder::Reordering`]) few values are set aside; where a
/// sample of the faces shows more than one corner in eight to set aside
/// (faces in random order), one loop adds everything.
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
    scatter_with(n, faces, &[] as &[u8], init, &Single(values), add)
}

/// [`scatter`] for `values` that read `reads[v]` (positions, usually) at
/// each corner `v` of their face: the corners' entries of `reads` and
/// their accumulators are asked for [`READ_AHEAD`] faces before their
/// turn ([`crate::hint::prefetch`]). On meshes whose faces do not follow
/// their vertices those reads are cache misses, which the processor could
/// not overlap: at 470,274 vertices in Loop subdivision's order, on one
/// thread, the Voronoi mass took 40.8-42.2 ms instead of 67.2-70.0, the
/// Gaussian curvature ([`scatter_batched`]) 38.0-39.1 instead of
/// 56.1-56.8, normals 14.6-16.6 instead of 18.2-18.6 (three alternated
/// rounds, 2026-12-06). Asking for the accumulators alone made normals
/// slower (18 to 22-23 ms).
pub fn scatter_reading<A, V, I, R>(
    n: usize,
    faces: &[[I; 3]],
    reads: &[R],
    init: A,
    values: impl Fn(usize) -> [V; 3] + Sync + Send,
    add: impl Fn(&mut A, V) + Sync + Send,
) -> Vec<A>
where
    A: Clone + Send + Sync,
    V: Copy + Send,
    I: Copy + Sync,
    R: Sync,
    u32: From<I>,
{
    scatter_with(n, faces, reads, init, &Single(values), add)
}

/// Faces between the one being added and the one whose corners a
/// [`scatter_reading`] asks for: 64, about one pointer chase to memory of
/// work ahead (16 and 32 did as well, 2026-12-06).
pub const READ_AHEAD: usize = 64;

/// [`scatter_reading`] with the values of `B` consecutive faces at a time:
/// `values(first)` gives those of faces `first..first + B` (entries past
/// the last face are ignored), for kernels that are faster on a batch
/// ([`crate::operators::corner_angles_and_masses_batch`]). Batches start at
/// the first face of each chunk and every `B` faces after it; the sums are
/// added in the same order as [`scatter`]'s.
pub fn scatter_batched<A, V, I, R, const B: usize>(
    n: usize,
    faces: &[[I; 3]],
    reads: &[R],
    init: A,
    values: impl Fn(usize) -> [[V; 3]; B] + Sync + Send,
    add: impl Fn(&mut A, V) + Sync + Send,
) -> Vec<A>
where
    A: Clone + Send + Sync,
    V: Copy + Send,
    I: Copy + Sync,
    R: Sync,
    u32: From<I>,
{
    scatter_with(n, faces, reads, init, &Batched(values), add)
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

/// [`scatter_batched`] over any [`FaceValues`] (no prefetch where `reads`
/// is empty).
fn scatter_with<A, V, I, R, const B: usize>(
    n: usize,
    faces: &[[I; 3]],
    reads: &[R],
    init: A,
    values: &impl FaceValues<V, B>,
    add: impl Fn(&mut A, V) + Sync + Send,
) -> Vec<A>
where
    A: Clone + Send + Sync,
    V: Copy + Send,
    I: Copy + Sync,
    R: Sync,
    u32: From<I>,
{
    // How many parts: see `part_count` (one loop on one thread).
    let threads = threads();
    let parts = part_count(threads).min(MAX_PARTS).min(faces.len() / SCATTER_CHUNK);
    let mut out = if parts >= 2 { map(n, |_| init.clone()) } else { vec![init; n] };
    // Part boundaries at whole batches, so that batches do not depend on them.
    let step = B.max(1);
    let bounds: Vec<usize> =
        (0..=parts).map(|k| (k * faces.len() / parts.max(1)).next_multiple_of(step).min(faces.len())).collect();
    let owner = if parts >= 2 { owners(n, faces, &bounds) } else { Vec::new() };
    if parts < 2 || !mostly_owned(faces, &bounds, &owner) {
        let ahead = Ahead { faces, reads, slots: out.as_ptr() };
        each_face::<V, I, B>(faces, values, &ahead, 0, faces.len(), &mut |tri, x| {
            for k in 0..3 {
                add(&mut out[tri[k]], x[k]);
            }
        });
        return out;
    }
    let slots = DisjointSlots(out.as_mut_ptr());
    let part = |k: usize| {
        // Copies in registers, not behind the references that writes to
        // the accumulators might alias.
        let (base, add) = (slots.start(), &add);
        let ahead = Ahead { faces, reads, slots: base.cast_const() };
        // Called only with `v < n`: checked in the first part, where it
        // indexed `owner` in the others.
        let add_mine = move |v: usize, x: V| {
            // SAFETY: in bounds (above), and vertex `v` is written by one
            // part only: the first with `v` as a corner (the others have
            // it in another owner); `out` outlives the parts, which end
            // here.
            add(unsafe { &mut *base.add(v) }, x)
        };
        let mut aside = Vec::new();
        if k == 0 {
            // The first part owns every vertex it has as a corner: no owner
            // to look up.
            each_face::<V, I, B>(faces, values, &ahead, bounds[0], bounds[1], &mut |tri, x| {
                for k in 0..3 {
                    assert!(tri[k] < n, "corner {} of a scatter over {n} vertices", tri[k]);
                    add_mine(tri[k], x[k]);
                }
            });
            return aside;
        }
        let (owner, mine) = (&owner[..n], owner_entry(k, parts));
        each_face::<V, I, B>(faces, values, &ahead, bounds[k], bounds[k + 1], &mut |tri, x| {
            let owned = tri.map(|v| owner[v] == mine);
            if owned == [true; 3] {
                (0..3).for_each(|k| add_mine(tri[k], x[k]))
            } else {
                add_or_set_aside(&add_mine, &mut aside, tri, owned, x);
            }
        });
        aside
    };
    let aside: Vec<Vec<(u32, V)>> = map_heavy(parts, part);
    for (v, x) in aside.into_iter().flatten() {
        add(&mut out[v as usize], x);
    }
    out
}

/// The corners of a face of a [`scatter`]'s part: those the part owns to
/// `add_mine`, the others kept for after the parts. Out of line, as few
/// faces have corners in other parts, so that the loop around it keeps its
/// registers.
#[cold]
#[inline(never)]
fn add_or_set_aside<V: Copy>(
    add_mine: &impl Fn(usize, V),
    aside: &mut Vec<(u32, V)>,
    tri: [usize; 3],
    owned: [bool; 3],
    x: [V; 3],
) {
    for k in 0..3 {
        if owned[k] {
            add_mine(tri[k], x[k]);
        } else {
            aside.push((tri[k] as u32, x[k]));
        }
    }
}

/// Parts of a [`scatter`] on `threads` threads. Called from outside the
/// pool, when every thread is free, one per thread, which sets aside the
/// fewest corners: at 470,274 vertices in file order on two threads,
/// normals took 7.3-8.0 ms instead of 7.4-9.6 with four per thread, the
/// Gaussian curvature 16.3-17.5 instead of 16.9-18.3, the Voronoi mass
/// 18.6-19.4 instead of 19.6-20.7 (six alternated rounds, 2026-12-06).
/// Called from a task of the pool (the cotan Laplacian's weights, beside
/// its pattern on the other side of a `join`), the task's siblings keep
/// other threads busy: on two threads, the only other one, so one loop,
/// which skips an [`owners`] pass that no thread would share (the cotan
/// Laplacian took 28.0-29.5 ms instead of 30.9-33.5 with eight parts, three
/// alternated rounds, 2026-12-06); on more, four per thread, so that
/// threads busy elsewhere leave theirs to the others.
fn part_count(threads: usize) -> usize {
    #[cfg(feature = "rayon")]
    if rayon::current_thread_index().is_none() {
        return threads;
    }
    if threads <= 2 {
        1
    } else {
        4 * threads
    }
}

/// Most parts of a [`scatter`] (at most 255, for [`owners`]' bytes): each
/// sets aside the corners it shares with the parts before it.
const MAX_PARTS: usize = 16;

/// The accumulators of a [`scatter`], written by several parts at once,
/// each vertex by one part.
struct DisjointSlots<A>(*mut A);

// SAFETY: the parts write distinct elements (see `scatter_with`), and `A`
// may move between threads.
unsafe impl<A: Send> Sync for DisjointSlots<A> {}

impl<A> DisjointSlots<A> {
    /// The first accumulator (a method, so that closures take the whole
    /// `Sync` struct rather than its pointer field).
    fn start(&self) -> *mut A {
        self.0
    }
}

/// The part of a [`scatter`] that owns each vertex: the first part (faces
/// `bounds[k]..bounds[k + 1]`) with the vertex as a corner, [`NO_PART`]
/// where none but the last has it. The faces of every part but the last
/// are split into a run per thread (up to [`MAX_RUNS`]); each run scans
/// its faces backwards, storing each face's part at its corners, so that
/// the first face's part is the one left; plain byte stores, which do not
/// wait for each other as setting bits in a word did (2026-12-05: 0.5-0.9
/// ms against 1.6-2.8 ms at 940,544 faces on two threads). The runs'
/// arrays are merged run by run, each vertex keeping the first run's part.
/// Runs by faces rather than by parts share the work among the threads
/// whatever the part count: with two parts, one run per thread instead of
/// one run in all.
fn owners<I: Copy + Sync>(n: usize, faces: &[[I; 3]], bounds: &[usize]) -> Vec<u8>
where
    u32: From<I>,
{
    let parts = bounds.len() - 1;
    let scanned = bounds[parts - 1];
    let runs = threads().min(MAX_RUNS).clamp(1, scanned.div_ceil(SCATTER_CHUNK).max(1));
    let mut arrays = map_heavy(runs, |r| {
        let (first, end) = (r * scanned / runs, (r + 1) * scanned / runs);
        let mut owner = vec![NO_PART; n];
        for k in (0..parts - 1).rev() {
            let (lo, hi) = (bounds[k].max(first), bounds[k + 1].min(end));
            for tri in faces[lo..hi.max(lo)].iter().rev() {
                for &v in tri {
                    owner[u32::from(v) as usize] = k as u8;
                }
            }
        }
        owner
    });
    let mut owner = arrays.remove(0);
    for later in arrays {
        owner.iter_mut().zip(later).for_each(|(o, l)| *o = if *o == NO_PART { l } else { *o });
    }
    owner
}

/// An [`owners`] entry for a vertex that no part but perhaps the last has.
const NO_PART: u8 = u8::MAX;

/// The [`owners`] entry of the vertices that part `k` of `parts` owns.
#[inline(always)]
fn owner_entry(k: usize, parts: usize) -> u8 {
    if k + 1 == parts {
        NO_PART
    } else {
        k as u8
    }
}

/// What a [`scatter_reading`] asks for ahead: `reads` and the
/// accumulators from `slots` at the corners of `faces`.
struct Ahead<'a, I, R, A> {
    faces: &'a [[I; 3]],
    reads: &'a [R],
    slots: *const A,
}

impl<I: Copy, R, A> Ahead<'_, I, R, A>
where
    u32: From<I>,
{
    /// Asks for the data of the corners of faces `first..first + count`
    /// (those that exist), if there are `reads`.
    #[inline(always)]
    fn prefetch(&self, first: usize, count: usize) {
        if self.reads.is_empty() {
            return;
        }
        for tri in self.faces.iter().skip(first).take(count) {
            for &v in tri {
                let v = u32::from(v) as usize;
                if let Some(r) = self.reads.get(v) {
                    crate::hint::prefetch(r);
                }
                crate::hint::prefetch(self.slots.wrapping_add(v));
            }
        }
    }
}

/// Faces `lo..hi` of a [`scatter_batched`], batch by batch, each face's
/// corners and values to `sink(corners, values)`, asking for the corners
/// [`READ_AHEAD`] faces on as it goes; generic in the sink so that it
/// inlines.
#[inline(always)]
fn each_face<V: Copy, I: Copy, const B: usize>(
    faces: &[[I; 3]],
    values: &impl FaceValues<V, B>,
    ahead: &Ahead<'_, I, impl Sized, impl Sized>,
    lo: usize,
    hi: usize,
    sink: &mut impl FnMut([usize; 3], [V; 3]),
) where
    u32: From<I>,
{
    for first in (lo..hi).step_by(B.max(1)) {
        ahead.prefetch(first + READ_AHEAD, B.max(1));
        let x = values.of(first);
        for (tri, x) in faces[first..hi.min(first + B)].iter().zip(x) {
            sink(tri.map(|v| u32::from(v) as usize), x);
        }
    }
}

/// Whether, judged from every 509th face, at most one corner in eight
/// would be set aside: otherwise setting corners aside costs more than
/// more threads gain (faces in random order), and [`scatter`] runs one
/// loop. At least 128 faces of every part of [`SCATTER_CHUNK`] or more
/// tell the 1-2% of corners set aside on a mesh in order from the half on
/// a shuffled one; every 61st face took 0.2-0.4 ms at 940,544 faces, each
/// a cache miss, every 509th 0.05-0.1 ms (2026-12-06).
fn mostly_owned<I: Copy>(faces: &[[I; 3]], bounds: &[usize], owner: &[u8]) -> bool
where
    u32: From<I>,
{
    let (mut corners, mut aside) = (0usize, 0usize);
    let parts = bounds.len() - 1;
    for k in 0..parts {
        let mine = owner_entry(k, parts);
        for tri in faces[bounds[k]..bounds[k + 1]].iter().step_by(509) {
            corners += 3;
            aside += tri.iter().filter(|&&v| owner[u32::from(v) as usize] != mine).count();
        }
    }
    8 * aside <= corners
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

/// Items per chunk of [`all_chunks`].
const CHECK_CHUNK: usize = 1 << 14;

/// Whether `test` holds for every chunk of `items` (consecutive runs of up
/// to 16,384 items), in parallel from [`PARALLEL_FROM`] items; it may stop
/// at the first chunk that fails. For branch-free validity scans.
pub fn all_chunks<T: Sync>(items: &[T], test: impl Fn(&[T]) -> bool + Sync + Send) -> bool {
    #[cfg(feature = "rayon")]
    if items.len() >= PARALLEL_FROM {
        use rayon::prelude::*;
        return items.par_chunks(CHECK_CHUNK).all(test);
    }
    items.chunks(CHECK_CHUNK).all(test)
}

/// `f` of every `chunk` consecutive items (the last chunk may be shorter),
/// in chunk order, in parallel from [`CHEAP_FROM`] items: for cheap
/// reductions (a bounding box, about 1 ns a point) whose parts are then
/// combined in an order that does not depend on the thread count.
pub fn map_chunks<T: Sync, R: Send>(items: &[T], chunk: usize, f: impl Fn(&[T]) -> R + Sync + Send) -> Vec<R> {
    #[cfg(feature = "rayon")]
    if items.len() >= CHEAP_FROM {
        use rayon::prelude::*;
        return items.par_chunks(chunk).map(f).collect();
    }
    items.chunks(chunk).map(f).collect()
}

/// Runs both closures, in parallel with the `rayon` feature.
pub fn join<A: Send, B: Send>(a: impl FnOnce() -> A + Send, b: impl FnOnce() -> B + Send) -> (A, B) {
    #[cfg(feature = "rayon")]
    return rayon::join(a, b);
    #[cfg(not(feature = "rayon"))]
    (a(), b())
}

/// The value of `cell`, made by `make` on the first request: what
/// `cell.get_or_init(make)` gives, without running `make` inside the cell's
/// initialization. Every cached quantity of a mesh goes through it.
///
/// `OnceLock::get_or_init` holds the cell while `make` runs; a thread that
/// asks for the cell then waits. When `make` runs parallel maps, the
/// initializing thread, waiting for a task another thread took, runs other
/// pending tasks (rayon's work stealing): if one of them asks for the same
/// cell, that thread waits for itself, for ever. A shared mesh asked for
/// its normals or connectivity from inside a parallel loop did so: 16
/// rayon threads over 256 tasks, each asking an icosphere(7) for its
/// connectivity or normals after a parallel sum of its own, hung within
/// 120 repetitions (2026-12-07, `std::sync::OnceLock`'s futex wait in
/// every thread). Here `make` runs outside the cell: requests that meet
/// an empty cell each make the value (the first stored is kept, and every
/// caller gets it), so concurrent first requests may repeat the work; none
/// waits for another's `make`.
pub fn init_once<T>(cell: &OnceLock<T>, make: impl FnOnce() -> T) -> &T {
    if let Some(value) = cell.get() {
        return value;
    }
    let value = make();
    cell.get_or_init(|| value)
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

    #[test]
    fn map_columns_writes_row_i_of_every_column() {
        // Empty, one partial chunk, and several threads' chunks.
        for n in [0, 5, MIN_TASK + 3, CHEAP_FROM + 7] {
            let ([a, b], c) = map_columns(n, |i| ([i as u64, 2 * i as u64 + 1], (i % 7) as u8));
            let expect = |g: fn(usize) -> u64| (0..n).map(g).collect::<Vec<_>>();
            assert_eq!(a, expect(|i| i as u64), "{n}");
            assert_eq!(b, expect(|i| 2 * i as u64 + 1), "{n}");
            assert_eq!(c, (0..n).map(|i| (i % 7) as u8).collect::<Vec<_>>(), "{n}");
        }
    }

    #[cfg(feature = "rayon")]
    #[test]
    fn owners_are_the_first_parts_with_the_vertex_on_any_thread_count() {
        // Runs of the scan (one per thread, up to four) begin inside parts.
        let m = 3 * SCATTER_CHUNK;
        let faces = shuffled(strip(m), 5, 30_000);
        let n = m + 10;
        let bounds = [0, 70_000, 150_000, 220_000, 310_000, 2 * m];
        let mut expect = vec![NO_PART; n];
        for k in (0..bounds.len() - 2).rev() {
            for tri in &faces[bounds[k]..bounds[k + 1]] {
                tri.iter().for_each(|&v| expect[v as usize] = expect[v as usize].min(k as u8));
            }
        }
        for threads in [1, 2, 3, 8] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            assert_eq!(pool.install(|| owners(n, &faces, &bounds)), expect, "{threads} threads");
        }
    }

    #[cfg(feature = "rayon")]
    #[test]
    fn scatter_sums_do_not_depend_on_the_thread_count() {
        let m = 5 * SCATTER_CHUNK;
        // In order, a few faces out of place (some corners set aside), shuffled.
        for (i, faces) in [strip(m), shuffled(strip(m), 3, 2000), shuffled(strip(m), 3, 2 * m)].into_iter().enumerate()
        {
            let bounds = [0, m, 2 * m];
            assert_eq!(mostly_owned(&faces, &bounds, &owners(m + 2, &faces, &bounds)), i < 2, "case {i}");
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
            // From outside any pool (one part per thread of the global pool).
            let outside =
                scatter(n, &faces, 0.0f64, |f| [1.0 / (f as f64 + 1.0), 0.1, (f as f64).sqrt()], |a, x| *a += x);
            assert!(one.iter().zip(outside).all(|(a, b)| a.to_bits() == b.to_bits()), "outside the pool");
        }
    }

    /// Asking for memory ahead changes no sum: [`scatter_reading`] (with a
    /// read array over every vertex, and one over half of them) and
    /// [`scatter_batched`] give [`scatter`]'s sums bit for bit, on one
    /// thread and on three, faces in order and shuffled.
    #[cfg(feature = "rayon")]
    #[test]
    fn reading_ahead_changes_no_sum() {
        let m = 3 * SCATTER_CHUNK;
        for faces in [strip(m), shuffled(strip(m), 5, 2 * m)] {
            let n = faces.len() / 2 + 2;
            let value = |f: usize| [1.0 / (f as f64 + 1.0), 0.1, (f as f64).sqrt()];
            let reads: Vec<f64> = (0..n).map(|v| v as f64).collect();
            for threads in [1, 3] {
                let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
                let bits = |x: Vec<f64>| x.into_iter().map(f64::to_bits).collect::<Vec<_>>();
                pool.install(|| {
                    let plain = bits(scatter(n, &faces, 0.0f64, value, |a, x| *a += x));
                    for r in [&reads[..], &reads[..n / 2]] {
                        assert_eq!(bits(scatter_reading(n, &faces, r, 0.0f64, value, |a, x| *a += x)), plain);
                    }
                    let batched = scatter_batched(
                        n,
                        &faces,
                        &reads,
                        0.0f64,
                        |first| std::array::from_fn::<_, 4, _>(|j| value(first + j)),
                        |a, x| *a += x,
                    );
                    assert_eq!(bits(batched), plain, "{threads} threads");
                });
            }
        }
    }

    /// A corner past the end is refused by a panic, as an index would be,
    /// on one thread and on several (where parts write through pointers).
    #[cfg(feature = "rayon")]
    #[test]
    fn scatter_panics_on_a_corner_past_the_end() {
        let m = 3 * SCATTER_CHUNK;
        let faces = strip(m);
        for threads in [1, 2, 3] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            let run = || pool.install(|| scatter(m + 1, &faces, 0.0, |_| [1.0; 3], |a, x| *a += x));
            assert!(std::panic::catch_unwind(std::panic::AssertUnwindSafe(run)).is_err(), "{threads} threads");
        }
    }

    /// A stable sort by key, the plain way, on 1, 2, 3 and 8 threads
    /// (one run, and two to four runs side by side), with keys in any
    /// order and keys without items.
    #[test]
    fn group_by_key_is_a_stable_counting_sort() {
        let mut rng = SplitMix64::new(5);
        for (records, key_count) in [(10, 4), (3 * PARALLEL_FROM + 7, 50), (3 * PARALLEL_FROM, 20_000)] {
            let keys: Vec<[usize; 3]> =
                (0..records).map(|_| [rng.below(key_count), rng.below(key_count), rng.below(key_count)]).collect();
            let mut expect: Vec<(usize, u64)> =
                (0..3 * records).map(|item| (keys[item / 3][item % 3], item as u64)).collect();
            expect.sort_by_key(|&(k, _)| k);
            let run = || group_by_key(key_count, records, |i| keys[i], |i| [0, 1, 2].map(|j| (3 * i + j) as u64));
            #[cfg(feature = "rayon")]
            let results: Vec<_> = [1, 2, 3, 8]
                .map(|threads| rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap().install(run))
                .into();
            #[cfg(not(feature = "rayon"))]
            let results = vec![run()];
            for (offsets, values) in results {
                assert_eq!(values, expect.iter().map(|&(_, item)| item).collect::<Vec<_>>());
                for k in 0..key_count {
                    let group = &expect[offsets[k]..offsets[k + 1]];
                    assert!(group.iter().all(|&(key, _)| key == k), "key {k}");
                }
                assert_eq!(offsets[key_count], 3 * records);
            }
        }
    }

    #[test]
    fn rows_with_keeps_one_scratch_per_task_and_the_row_order() {
        let n = 3 * PARALLEL_FROM + 5;
        let offsets: Vec<usize> = (0..=n).map(|i| 2 * i).collect();
        let mut data = vec![0usize; 2 * n];
        let out = rows_with(&mut data, &offsets, Vec::new, |seen: &mut Vec<usize>, i, row| {
            seen.push(i);
            row.fill(i);
            // Rows of one task come in order, from the task's first.
            seen.windows(2).all(|w| w[1] == w[0] + 1) && seen[0].is_multiple_of(MIN_TASK)
        });
        assert_eq!(out.len(), n);
        assert!(out.iter().all(|&ok| ok));
        assert!(data.iter().enumerate().all(|(s, &i)| i == s / 2));
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

    /// A request for a cell from inside the making of its own value (what
    /// a thread does when, waiting inside `make` for a parallel task, it
    /// runs a pending task that asks for the same quantity) gets a value
    /// instead of waiting for itself, and both requests return the value
    /// stored first. `OnceLock::get_or_init` waits for ever here, which
    /// the timeout turns into a failure.
    #[test]
    fn a_cell_asked_for_while_its_value_is_made_does_not_wait_for_itself() {
        let (sent, received) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let cell = OnceLock::new();
            let outer = *init_once(&cell, || *init_once(&cell, || 1) + 1);
            sent.send((outer, cell.get().copied())).ok();
        });
        let got = received.recv_timeout(std::time::Duration::from_secs(20));
        assert_eq!(got, Ok((1, Some(1))));
    }
}
