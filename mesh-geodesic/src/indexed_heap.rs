//! An indexed 4-ary min-heap of `(distance, vertex)` entries with
//! decrease-key, for Fast Marching's label-setting search:
//! every vertex is in the heap at most once, so no stale entries are
//! popped, and the heap stays as small as the front.
//!
//! Each vertex's position in the heap is kept by the caller, in a slice
//! indexed by vertex: `NOT_QUEUED` while the vertex is not in the heap
//! (before it enters and after it leaves), else its index in the heap's
//! entries; once a heap is [`IndexedHeap::clear`]ed, every position is
//! `NOT_QUEUED` again, ready for the next search. A node's four
//! children are consecutive; a pop compares them as two pairs and then the
//! two smaller keys, so that each level waits for two comparisons, not
//! three in a row: prepared Dijkstra queries at 470,274 vertices took
//! 11% less time than with a scan of the four (FMM 3%). The keys are the
//! distances' bits, compared as integers (queries 3-5% faster than with
//! floating-point comparisons).
//! Equal distances come out in an order fixed by the sequence of pushes
//! and pops (the same on every run and machine), not by vertex number:
//! a version that broke ties by vertex, with the whole entry compared in
//! the child loop, made the searches 1.5-2x slower.
//!
//! A pop moves the hole down to a leaf along the smallest children and
//! lets the heap's last entry rise from there (the bottom-up variant of
//! Floyd 1964, analysed by Wegener 1993):
//! the last entry mostly belongs near the bottom, so this saves a
//! comparison per level. Prepared Dijkstra queries: 4% faster on a
//! 40,962-vertex icosphere, 1-2% at 470,274 vertices (one core).
//!
//! Dijkstra's search used it until 2026-12-06, when a ring of buckets
//! ([`crate::bucket_queue`]) made its queries 10-25% faster. Measured
//! against the radix heap on the distances' bits (Ahuja, Mehlhorn, Orlin
//! and Tarjan 1990) it had replaced, single-source Dijkstra on one core:
//! 0.7x the time at 470,274 vertices in breadth-first order (the radix heap
//! moved each entry 6 times between its buckets there) and 0.75x on a
//! 40,962-vertex icosphere.

/// Position of a vertex that is not in the heap.
pub(crate) const NOT_QUEUED: u32 = u32::MAX;

/// The heap's key of a distance (not negative, not NaN): its bits, which
/// order such numbers as their values do (`+0.0` for `-0.0`), and which
/// integer comparisons order faster than floating-point ones.
#[inline]
fn key(distance: f64) -> u64 {
    (distance + 0.0).to_bits()
}

/// Children per node.
const ARITY: usize = 4;

/// An indexed 4-ary min-heap; see the module documentation.
#[derive(Debug, Default)]
pub(crate) struct IndexedHeap {
    /// `(key, vertex)`, the key a distance's bits ([`key`]).
    entries: Vec<(u64, u32)>,
}

impl IndexedHeap {
    /// An empty heap.
    pub(crate) fn new() -> Self {
        Self::default()
    }

    /// Puts `vertex` in the heap at `distance`, or lowers its distance if it
    /// is already there. `distance` must not be NaN nor larger than the
    /// vertex's distance in the heap: both searches only push a vertex at a
    /// distance below its current one (debug-checked; a version that
    /// allowed a raise, with a sift down beside the sift up, was 5-20%
    /// slower on a 41k-vertex icosphere).
    /// O(log of the heap's size).
    #[inline]
    pub(crate) fn push_or_decrease(&mut self, distance: f64, vertex: u32, positions: &mut [u32]) {
        debug_assert!(distance >= 0.0, "a negative or NaN distance");
        let distance = key(distance);
        let at = match positions[vertex as usize] {
            NOT_QUEUED => {
                self.entries.push((distance, vertex));
                self.entries.len() - 1
            }
            p => {
                debug_assert!(distance <= self.entries[p as usize].0, "decrease-key that increases");
                p as usize
            }
        };
        self.sift_up(at, (distance, vertex), positions);
    }

    /// Whether the heap holds no vertex.
    pub(crate) fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// Removes an entry of smallest distance. O(log of the heap's size).
    #[inline]
    pub(crate) fn pop(&mut self, positions: &mut [u32]) -> Option<(f64, u32)> {
        let top = *self.entries.first()?;
        positions[top.1 as usize] = NOT_QUEUED;
        let last = self.entries.pop()?;
        if !self.entries.is_empty() {
            self.sift_down(0, last, positions);
        }
        Some((f64::from_bits(top.0), top.1))
    }

    /// Empties the heap, its vertices' positions back to `NOT_QUEUED`.
    /// O(size).
    pub(crate) fn clear(&mut self, positions: &mut [u32]) {
        for &(_, v) in &self.entries {
            positions[v as usize] = NOT_QUEUED;
        }
        self.entries.clear();
    }

    /// Moves the hole at `at` towards the root until `entry` fits there.
    #[inline]
    fn sift_up(&mut self, mut at: usize, entry: (u64, u32), positions: &mut [u32]) {
        while at > 0 {
            let parent = (at - 1) / ARITY;
            let above = self.entries[parent];
            if above.0 <= entry.0 {
                break;
            }
            self.entries[at] = above;
            positions[above.1 as usize] = at as u32;
            at = parent;
        }
        self.entries[at] = entry;
        positions[entry.1 as usize] = at as u32;
    }

    /// Moves the hole at `at` down to a leaf along the smallest children,
    /// without comparing them with `entry`, then lets `entry` rise from
    /// there ([`IndexedHeap::sift_up`]): Floyd's bottom-up variant, for an
    /// `entry` taken from the heap's end, which mostly belongs near the
    /// bottom.
    #[inline]
    fn sift_down(&mut self, mut at: usize, entry: (u64, u32), positions: &mut [u32]) {
        let n = self.entries.len();
        loop {
            let first = ARITY * at + 1;
            if first >= n {
                break;
            }
            // The first smallest child, comparing keys only: keeping the
            // whole entry, or reloading the key by index, chained each
            // comparison to the previous one and made the search 1.5-2x
            // slower.
            let child = if let Some(four) = self.entries.get(first..first + ARITY) {
                let (k0, k1, k2, k3) = (four[0].0, four[1].0, four[2].0, four[3].0);
                let (left, kl) = if k1 < k0 { (1, k1) } else { (0, k0) };
                let (right, kr) = if k3 < k2 { (3, k3) } else { (2, k2) };
                first + if kr < kl { right } else { left }
            } else {
                let (mut child, mut smallest) = (first, self.entries[first].0);
                for c in first + 1..n {
                    if self.entries[c].0 < smallest {
                        (child, smallest) = (c, self.entries[c].0);
                    }
                }
                child
            };
            let below = self.entries[child];
            self.entries[at] = below;
            positions[below.1 as usize] = at as u32;
            at = child;
        }
        self.sift_up(at, entry, positions);
    }
}

#[cfg(test)]
mod tests {
    use super::{key, IndexedHeap, NOT_QUEUED};

    /// Random pushes, decreases and pops against a plain list of the
    /// current keys: every pop returns a smallest key and the positions
    /// always point at the right entries.
    #[test]
    fn pops_the_smallest_after_random_pushes_and_decreases() {
        let mut rng = mesh_kernel::random::SplitMix64::new(11);
        let n = 300;
        let mut positions = vec![NOT_QUEUED; n];
        let mut popped = vec![false; n];
        let mut current: Vec<Option<f64>> = vec![None; n];
        let mut heap = IndexedHeap::new();
        let mut floor = 0.0f64;
        let mut pops = 0;
        for step in 0..5000 {
            let v = (rng.unit() * n as f64) as usize % n;
            if step % 3 == 2 {
                let Some((d, u)) = heap.pop(&mut positions) else { continue };
                let smallest = current.iter().flatten().copied().fold(f64::INFINITY, f64::min);
                assert_eq!(d, smallest);
                assert_eq!(current[u as usize], Some(d));
                assert_eq!(positions[u as usize], NOT_QUEUED);
                popped[u as usize] = true;
                assert!(d >= floor);
                floor = d;
                current[u as usize] = None;
                pops += 1;
            } else if !popped[v] {
                let d = floor + rng.unit() * 10.0;
                if current[v].is_none_or(|c| d < c) {
                    heap.push_or_decrease(d, v as u32, &mut positions);
                    current[v] = Some(d);
                }
            }
            for (i, &(k, u)) in heap.entries.iter().enumerate() {
                assert_eq!(positions[u as usize], i as u32);
                assert_eq!(current[u as usize], Some(f64::from_bits(k)));
            }
        }
        assert!(pops > n / 2, "{pops} pops");
        for _ in 0..10 {
            heap.pop(&mut positions);
        }
        heap.clear(&mut positions);
        assert!(heap.pop(&mut positions).is_none());
        assert!(positions.iter().all(|&p| p == NOT_QUEUED));
    }

    /// Keys order distances as their values: zero of either sign first
    /// (popped as `+0.0`), infinity last, subnormals and the largest
    /// finite number between.
    #[test]
    fn keys_order_zero_subnormals_and_infinity() {
        let values = [f64::INFINITY, f64::MAX, 1.0, f64::MIN_POSITIVE, 5e-324, -0.0];
        let (mut positions, mut heap) = (vec![NOT_QUEUED; values.len()], IndexedHeap::new());
        for (v, &d) in values.iter().enumerate() {
            heap.push_or_decrease(d, v as u32, &mut positions);
        }
        let popped: Vec<(u64, u32)> =
            (0..6).filter_map(|_| heap.pop(&mut positions)).map(|(d, v)| (d.to_bits(), v)).collect();
        let expected: Vec<(u64, u32)> = (0..6u32).rev().map(|v| ((values[v as usize] + 0.0).to_bits(), v)).collect();
        assert_eq!(popped, expected);
        assert_eq!(popped[0].0, 0.0f64.to_bits());
    }

    /// Every vertex lowered to the root in turn, one lowered between
    /// others, then a clear of a full heap.
    #[test]
    fn decrease_and_clear() {
        let n = 64;
        let (mut positions, mut heap) = (vec![NOT_QUEUED; n], IndexedHeap::new());
        for v in 0..n as u32 {
            heap.push_or_decrease(1e3 + f64::from(v), v, &mut positions);
        }
        for v in (0..n as u32).rev() {
            heap.push_or_decrease(0.5 * f64::from(v), v, &mut positions);
            assert_eq!(heap.entries[0], (key(0.5 * f64::from(v)), v));
        }
        heap.push_or_decrease(7.2, 20, &mut positions); // 10.0 lowered
        for (i, &(_, u)) in heap.entries.iter().enumerate() {
            assert_eq!(positions[u as usize], i as u32);
        }
        let popped: Vec<(f64, u32)> = (0..17).filter_map(|_| heap.pop(&mut positions)).collect();
        let mut expected: Vec<(f64, u32)> = (0..15).map(|v| (0.5 * f64::from(v), v)).collect();
        expected.extend([(7.2, 20), (7.5, 15)]);
        assert_eq!(popped, expected);
        assert_eq!(heap.entries.len(), n - 17);
        heap.clear(&mut positions);
        assert!(heap.pop(&mut positions).is_none());
        assert!(positions.iter().all(|&p| p == NOT_QUEUED));
    }
}
