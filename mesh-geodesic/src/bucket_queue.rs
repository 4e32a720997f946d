//! A monotone priority queue of `(distance, vertex)` entries for
//! Dijkstra's search (Dial 1969): distances fall into buckets of a fixed
//! width, an entry is appended to its bucket's list in O(1), and a vertex
//! whose distance falls is appended again to its new bucket, its old entry
//! left behind as stale (skipped when it comes up). The buckets live in a
//! ring that covers the longest edge, with a bitmap of the occupied ones.
//!
//! When the width is at most half the shortest edge, an edge always leads
//! to a later bucket: the current bucket's vertices cannot lower one
//! another, their distances are final, and they are settled in the order
//! they came (Goldberg's smart queue, 2001, rests on the same fact). The
//! width is that, unless the longest edge exceeds the shortest 2
//! [`MAX_SPAN`] times or the shortest has length zero: the width is then a
//! [`MAX_SPAN`]-th of the longest edge, the current bucket is kept as a
//! heap, and pops come out in non-decreasing distance.
//!
//! Against the indexed 4-ary heap it replaces (`crate::indexed_heap`, kept
//! for Fast Marching), one core, three alternated rounds (2026-12-06):
//! prepared queries 1.15-1.22 ms instead of 1.42-1.61 on a 40,962-vertex
//! icosphere, 27.2-28.0 instead of 32.7-34.0 at 470,274 vertices in file
//! order (a twelfth of the entries stale, about a dozen vertices per
//! bucket); one-off calls there 47.6-52.1 ms instead of 54.4-58.3.
//! Keeping the current bucket as a heap even when no edge can lead into it
//! made those queries 40-43 ms instead (47-49 with lists of bare vertices,
//! whose distances were read when their bucket came up).

use std::collections::BinaryHeap;

use crate::support::HeapEntry as Entry;

/// The ring spans the longest edge in at most this many buckets.
const MAX_SPAN: f64 = 1024.0;

/// The queue; see the module documentation.
#[derive(Debug, Clone)]
pub(crate) struct BucketQueue {
    /// One over the bucket width: bucket `b` holds the distances `d` with
    /// `floor(d * scale) == b`. Zero when the width is zero, infinite or
    /// too small to invert, all distances then sharing bucket 0 (a heap).
    scale: f64,
    /// Whether an edge may lead into the current bucket, whose entries are
    /// then a heap.
    ordered: bool,
    /// The current bucket's entries when `ordered`: a min-heap.
    now: BinaryHeap<Entry>,
    /// The current bucket's entries otherwise, taken in the order they
    /// came, `taken` of them so far.
    unordered: Vec<Entry>,
    taken: usize,
    /// The entries of bucket `b > current` in `lists[b & mask]`.
    lists: Vec<Vec<Entry>>,
    /// Bit `i` set when `lists[i]` is not empty.
    occupied: Vec<u64>,
    mask: u64,
    /// The current bucket.
    current: u64,
}

impl BucketQueue {
    /// An empty queue for a graph whose edge lengths lie in `[shortest,
    /// longest]` (`+infinity` and 0 without edges).
    pub(crate) fn new(shortest: f64, longest: f64) -> Self {
        let width = (shortest / 2.0).max(longest / MAX_SPAN);
        let scale = if width > 0.0 && (1.0 / width).is_finite() { 1.0 / width } else { 0.0 };
        // A push lands at most `ceil(longest * scale) + 1` buckets after
        // the current one (the sum and the product each round once).
        let slots = ((longest * scale).ceil() as usize + 3).next_power_of_two();
        Self {
            scale,
            ordered: scale == 0.0 || !(width <= shortest / 2.0),
            now: BinaryHeap::new(),
            unordered: Vec::new(),
            taken: 0,
            lists: vec![Vec::new(); slots],
            occupied: vec![0; slots.div_ceil(64)],
            mask: slots as u64 - 1,
            current: 0,
        }
    }

    /// The bucket of a distance (not negative, not NaN).
    #[inline]
    fn bucket(&self, distance: f64) -> u64 {
        (distance * self.scale) as u64
    }

    /// Whether every distance still to come exceeds `distance` (not NaN).
    #[inline]
    pub(crate) fn beyond(&self, distance: f64) -> bool {
        self.current > self.bucket(distance)
    }

    /// Queues `vertex` at `distance`, not below the last distance popped.
    /// O(1), or O(log) of the current bucket's size for a push into the
    /// current bucket.
    #[inline]
    pub(crate) fn push(&mut self, distance: f64, vertex: u32) {
        let b = self.bucket(distance);
        debug_assert!(b >= self.current && b - self.current <= self.mask, "a push outside the ring");
        let entry = Entry { distance, vertex };
        if b == self.current {
            if self.ordered {
                self.now.push(entry);
            } else {
                self.unordered.push(entry);
            }
        } else {
            let slot = (b & self.mask) as usize;
            self.lists[slot].push(entry);
            self.occupied[slot / 64] |= 1 << (slot % 64);
        }
    }

    /// Whether pops come out in non-decreasing distance.
    #[cfg(test)]
    pub(crate) fn is_ordered(&self) -> bool {
        self.ordered
    }

    /// The current bucket's next entry.
    #[inline]
    fn top(&self) -> Option<Entry> {
        if self.ordered {
            self.now.peek().copied()
        } else {
            self.unordered.get(self.taken).copied()
        }
    }

    /// The vertex a pop would return next, as far as the queue knows: the
    /// current bucket's next entry, else the first entry of the next
    /// occupied bucket (a hint: entries may come in before it).
    #[inline]
    pub(crate) fn peek(&self) -> Option<u32> {
        match self.top() {
            Some(e) => Some(e.vertex),
            None => self.next_occupied().and_then(|slot| self.lists[slot].first()).map(|e| e.vertex),
        }
    }

    /// Removes the next entry whose distance is still its vertex's
    /// (`distance(v)`), skipping stale ones: one of smallest distance when
    /// the queue is ordered, else one of the current bucket. Amortized O(1)
    /// per entry, plus O(log) of the current bucket's size when ordered.
    #[inline]
    pub(crate) fn pop(&mut self, distance: impl Fn(u32) -> f64) -> Option<(f64, u32)> {
        loop {
            self.drop_stale(&distance);
            if self.top().is_some() {
                break;
            }
            if !self.advance() {
                return None;
            }
        }
        let Entry { distance: d, vertex: v } = if self.ordered { self.now.pop() } else { self.take() }?;
        // The next bucket becomes current only at the next pop, after the
        // edges of `v` have been relaxed into buckets from this one on.
        self.drop_stale(&distance);
        Some((d, v))
    }

    /// Drops the stale entries at the top of the current bucket, so that
    /// [`BucketQueue::peek`] sees the next vertex to settle.
    #[inline]
    fn drop_stale(&mut self, distance: &impl Fn(u32) -> f64) {
        while let Some(Entry { distance: d, vertex: v }) = self.top() {
            if d == distance(v) {
                return;
            }
            if self.ordered {
                self.now.pop();
            } else {
                self.taken += 1;
            }
        }
    }

    /// The next entry of an unordered current bucket.
    #[inline]
    fn take(&mut self) -> Option<Entry> {
        let e = self.unordered.get(self.taken).copied();
        self.taken += 1;
        e
    }

    /// Makes the next occupied bucket current (its list a heap when
    /// ordered); `false` when every bucket is empty. O(ring / 64) bit
    /// words, and O(list) to heapify.
    fn advance(&mut self) -> bool {
        let Some(slot) = self.next_occupied() else { return false };
        let start = ((self.current + 1) & self.mask) as usize;
        self.current += 1 + ((slot as u64).wrapping_sub(start as u64) & self.mask);
        self.occupied[slot / 64] &= !(1 << (slot % 64));
        let list = std::mem::take(&mut self.lists[slot]);
        self.lists[slot] = if self.ordered {
            std::mem::replace(&mut self.now, BinaryHeap::from(list)).into_vec()
        } else {
            self.taken = 0;
            let mut spent = std::mem::replace(&mut self.unordered, list);
            spent.clear();
            spent
        };
        true
    }

    /// The slot of the first occupied bucket after the current one.
    /// O(ring / 64).
    fn next_occupied(&self) -> Option<usize> {
        let start = ((self.current + 1) & self.mask) as usize;
        let words = self.occupied.len();
        (0..=words).find_map(|k| {
            let w = (start / 64 + k) % words;
            let bits = if k == 0 { self.occupied[w] & (!0 << (start % 64)) } else { self.occupied[w] };
            (bits != 0).then(|| w * 64 + bits.trailing_zeros() as usize)
        })
    }

    /// Makes an empty queue ready for another search on the same graph.
    pub(crate) fn restart(&mut self) {
        debug_assert!(
            self.occupied.iter().all(|&w| w == 0) && self.now.is_empty() && self.taken >= self.unordered.len()
        );
        (self.current, self.taken) = (0, 0);
        self.unordered.clear();
    }

    /// Every vertex still queued, stale entries included (for a search cut
    /// off before the queue ran dry, to unmark them).
    pub(crate) fn drain(&mut self) -> impl Iterator<Item = u32> + '_ {
        self.occupied.fill(0);
        let lists = self.lists.iter_mut().flat_map(|l| l.drain(..));
        self.now.drain().chain(self.unordered.drain(..).skip(self.taken)).chain(lists).map(|e| e.vertex)
    }
}
