//! A monotone radix heap keyed by non-negative `f64` distances (Ahuja,
//! Mehlhorn, Orlin and Tarjan 1990, "Faster algorithms for the shortest path
//! problem"), for label-setting searches whose popped keys never decrease.
//!
//! The bit pattern of a non-negative `f64` (including `+0.0` and `+infinity`)
//! orders like its value, so the keys are the `u64` bits. Bucket `i` holds the
//! keys whose highest bit differing from the last popped key is bit `i - 1`
//! (bucket 0: keys equal to it). A pop empties bucket 0 first; otherwise it
//! takes the lowest non-empty bucket, makes its minimum the last key and
//! redistributes the bucket into lower ones. Every entry moves at most 64
//! times (in practice two or three), so push is O(1) and pop amortised
//! O(64); no comparisons between entries except the scan for a minimum.

/// The number of buckets: one per possible highest differing bit, plus the
/// bucket of keys equal to the last popped key.
const BUCKETS: usize = 65;

/// A min-heap of `(distance, vertex)` entries for monotone searches: every
/// pushed distance must be at least the last popped one (checked in debug
/// builds). Duplicates are allowed (lazy deletion is the caller's).
#[derive(Debug)]
pub(crate) struct RadixHeap {
    /// Bits of the last popped key (0 before the first pop).
    last: u64,
    /// Bit `i` set when bucket `i` is non-empty.
    occupied: u128,
    buckets: [Vec<(u64, u32)>; BUCKETS],
}

impl RadixHeap {
    /// An empty heap.
    pub(crate) fn new() -> Self {
        Self { last: 0, occupied: 0, buckets: std::array::from_fn(|_| Vec::new()) }
    }

    /// The bucket of `key` relative to the last popped key.
    #[inline]
    fn bucket(&self, key: u64) -> usize {
        (64 - (key ^ self.last).leading_zeros()) as usize
    }

    /// Adds `vertex` at `distance`, a non-negative number (or `+infinity`)
    /// not smaller than the last popped distance. O(1).
    #[inline]
    pub(crate) fn push(&mut self, distance: f64, vertex: u32) {
        let key = distance.to_bits();
        debug_assert!(distance >= 0.0 && key >= self.last, "radix heap keys must not decrease");
        let b = self.bucket(key);
        self.buckets[b].push((key, vertex));
        self.occupied |= 1 << b;
    }

    /// Removes an entry of smallest distance. Amortised O(1) plus the
    /// redistribution of the bucket it comes from.
    #[inline]
    pub(crate) fn pop(&mut self) -> Option<(f64, u32)> {
        if self.occupied & 1 == 0 {
            self.refill()?;
        }
        let (key, vertex) = self.buckets[0].pop()?;
        if self.buckets[0].is_empty() {
            self.occupied &= !1;
        }
        Some((f64::from_bits(key), vertex))
    }

    /// Moves the lowest non-empty bucket's entries down, its minimum into
    /// bucket 0. `None` when the heap is empty.
    fn refill(&mut self) -> Option<()> {
        if self.occupied == 0 {
            return None;
        }
        let i = self.occupied.trailing_zeros() as usize;
        let mut entries = std::mem::take(&mut self.buckets[i]);
        self.occupied &= !(1 << i);
        self.last = entries.iter().map(|e| e.0).min().unwrap_or(self.last);
        for &(key, vertex) in &entries {
            let b = self.bucket(key);
            self.buckets[b].push((key, vertex));
            self.occupied |= 1 << b;
        }
        // Keep the allocation for the next time bucket `i` fills.
        entries.clear();
        self.buckets[i] = entries;
        Some(())
    }
}

#[cfg(test)]
mod tests {
    use super::RadixHeap;

    #[test]
    fn pops_in_order_with_interleaved_monotone_pushes() {
        let mut rng = mesh_kernel::random::SplitMix64::new(7);
        let mut heap = RadixHeap::new();
        let mut reference = Vec::new();
        for v in 0..50u32 {
            let d = rng.unit() * 10.0;
            heap.push(d, v);
            reference.push(d);
        }
        heap.push(0.0, 99);
        heap.push(f64::INFINITY, 98);
        reference.extend([0.0, f64::INFINITY]);
        let mut popped = Vec::new();
        while let Some((d, v)) = heap.pop() {
            popped.push(d);
            // Monotone pushes between pops, as Dijkstra does.
            if v < 20 {
                let e = d + rng.unit();
                heap.push(e, 1000 + v);
                reference.push(e);
            }
        }
        reference.sort_by(f64::total_cmp);
        assert_eq!(popped, reference);
    }
}
