//! Sorting the half-edge buckets: many runs of a few distinct keys each.
//!
//! A comparison sort of six keys takes branches that depend on the keys
//! and on the run's length, which a processor cannot predict when runs
//! arrive in no particular order. Where the processor has AVX2, runs of up
//! to [`RANKED`] keys are sorted by rank instead: each key is compared with
//! the whole run at once (four registers of four keys) and stored at the
//! count of keys below it, with no branch on a key.
//!
//! Measured inside `Connectivity::new` on one core of an Emerald Rapids
//! Xeon VM, 2026-12-07: the Stanford dragon's full scan (437,645
//! vertices, in the scan's order) and a bunny Loop-subdivided four times
//! (470,274 vertices) in three orders. The bucket sort, best of eight
//! builds, and the whole build and the edge numbering alone
//! ([`super::number_edges`]), medians of 21 builds alternated in one
//! process, ms:
//!
//! | vertex order | bucket sort: comparison / rank | build | edge numbering |
//! |---|---|---|---|
//! | the dragon's scan | 17.7 / 10.5 | 144.5 / 137.1 | 54.7 / 47.7 |
//! | subdivision's own | 6.4 / 10.1 | 104.4 / 103.5 | 37.0 / 42.0 |
//! | along a Hilbert curve | 20.5 / 11.5 | 130.7 / 121.5 | 61.1 / 49.2 |
//! | shuffled | 24.4 / 11.3 | 200.7 / 189.8 | 99.8 / 81.1 |
//!
//! Subdivision numbers vertices in a pattern that the comparisons learn;
//! a scan's order, a spatial one or none does not.

use crate::par;

/// The longest run sorted by rank; longer ones (vertices of valence above
/// 16 on a closed mesh) are sorted by comparison.
#[cfg_attr(not(target_arch = "x86_64"), allow(dead_code))]
pub(super) const RANKED: usize = 16;

/// Sorts each run `keys[offsets[i]..offsets[i + 1]]` of distinct keys in
/// place, runs side by side on [`par`]'s threads. Keys that repeat within
/// a run are sorted too, by comparison.
pub(super) fn sort_buckets(keys: &mut [u64], offsets: &[usize]) {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("popcnt") {
        // Blocks of runs, each sorted by one call compiled for AVX2, and
        // enough blocks for every thread.
        let runs = offsets.len().saturating_sub(1);
        let block = (runs / (2 * par::PARALLEL_FROM)).clamp(1, 64);
        let coarse: Vec<usize> = (0..runs).step_by(block).map(|i| offsets[i]).chain([keys.len()]).collect();
        par::rows(keys, &coarse, |b, part| {
            let fine = &offsets[b * block..=((b + 1) * block).min(runs)];
            // SAFETY: the processor has AVX2 and POPCNT, checked above.
            unsafe { sort_block_avx2(part, fine) }
        });
        return;
    }
    par::rows(keys, offsets, |_, run| run.sort_unstable());
}

/// [`sort_buckets`] of the runs `fine` (offsets into the whole array) of
/// `part`.
///
/// # Safety
/// The processor must have AVX2 and POPCNT.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,popcnt")]
unsafe fn sort_block_avx2(part: &mut [u64], fine: &[usize]) {
    let base = fine[0];
    for w in fine.windows(2) {
        let (start, n) = (w[0] - base, w[1] - w[0]);
        let end = (start + RANKED).min(part.len());
        let window = &mut part[start..end];
        // SAFETY: the caller's.
        if n > 1 && (n > RANKED || !unsafe { by_rank_avx2(window, n) }) {
            part[start..start + n].sort_unstable();
        }
    }
}

/// Sorts the first `n` keys of `window` (at most [`RANKED`]) by rank, or
/// leaves them as they were and returns `false` when two are equal. The
/// keys after them, up to 16 in all, are read when there are 16 (one load
/// per four keys, not a masked one) and never written.
///
/// # Safety
/// The processor must have AVX2 and POPCNT.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,popcnt")]
#[inline]
unsafe fn by_rank_avx2(window: &mut [u64], n: usize) -> bool {
    use std::arch::x86_64::*;
    debug_assert!(n <= RANKED && n <= window.len());
    let whole = window.len() == RANKED;
    // AVX2 compares signed lanes: flipping the top bit keeps the order of
    // unsigned keys. Lanes past the run hold the largest key, so no key of
    // the run counts them.
    let flip = _mm256_set1_epi64x(i64::MIN);
    let past = _mm256_set1_epi64x(i64::MAX);
    let len = _mm256_set1_epi64x(n as i64);
    let mut keys = [0u64; RANKED];
    let lanes: [__m256i; 4] = std::array::from_fn(|r| {
        let at = 4 * r as i64;
        let inside = _mm256_cmpgt_epi64(len, _mm256_setr_epi64x(at, at + 1, at + 2, at + 3));
        // SAFETY: a whole window has 16 keys to read; otherwise only the
        // lanes inside the run are read (the others are masked out, and a
        // masked lane never faults). `keys` has room for every lane.
        unsafe {
            let at = window.as_ptr().wrapping_add(4 * r);
            let x = if whole {
                _mm256_loadu_si256(at.cast::<__m256i>())
            } else {
                _mm256_maskload_epi64(at.cast::<i64>(), inside)
            };
            _mm256_storeu_si256(keys.as_mut_ptr().add(4 * r).cast::<__m256i>(), x);
            _mm256_blendv_epi8(past, _mm256_xor_si256(x, flip), inside)
        }
    });
    let mut ranks = 0u32;
    for &key in &keys[..n] {
        let this = _mm256_set1_epi64x((key ^ (1 << 63)) as i64);
        // The four comparisons packed into one byte mask, two bits a key.
        let [a, b, c, d] = lanes.map(|l| _mm256_cmpgt_epi64(this, l));
        let packed = _mm256_packs_epi16(_mm256_packs_epi32(a, b), _mm256_packs_epi32(c, d));
        let below = (_mm256_movemask_epi8(packed) as u32).count_ones() / 2;
        window[below as usize] = key;
        ranks |= 1 << below;
    }
    // Distinct keys have distinct ranks 0..n.
    if ranks != (1 << n) - 1 {
        window[..n].copy_from_slice(&keys[..n]);
        return false;
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::random::SplitMix64;

    /// Runs of every length from 0 to 20, then `more` runs of random
    /// lengths up to 18, with keys across the whole range of u64 (top bit
    /// set or not) and repeats.
    fn runs(rng: &mut SplitMix64, repeats: bool, more: usize) -> (Vec<u64>, Vec<usize>) {
        let (mut keys, mut offsets) = (Vec::new(), vec![0]);
        let lengths: Vec<usize> = (0..=20).chain((0..more).map(|_| rng.below(19))).collect();
        for len in lengths {
            for _ in 0..len {
                let k = match rng.next_u64() % 4 {
                    0 => rng.next_u64() % 8,
                    1 => u64::MAX - rng.next_u64() % 8,
                    _ => rng.next_u64(),
                };
                keys.push(if repeats && rng.one_in(3) { keys.last().copied().unwrap_or(k) } else { k });
            }
            offsets.push(keys.len());
        }
        (keys, offsets)
    }

    #[test]
    fn sorts_every_run_as_a_comparison_sort_does() {
        let mut rng = SplitMix64::new(11);
        // Few runs: a block per run; many: blocks of 64 runs, most runs
        // read with the 16 keys from their start.
        for (repeats, more) in [(false, 200), (true, 200), (false, 40_000), (true, 40_000)] {
            let (mut keys, offsets) = runs(&mut rng, repeats, more);
            let mut expect = keys.clone();
            for w in offsets.windows(2) {
                expect[w[0]..w[1]].sort_unstable();
            }
            sort_buckets(&mut keys, &offsets);
            assert_eq!(keys, expect, "repeats {repeats}, {more} runs");
        }
    }

    #[cfg(target_arch = "x86_64")]
    #[test]
    fn ranks_sort_distinct_keys_and_refuse_repeats() {
        if !std::arch::is_x86_feature_detected!("avx2") || !std::arch::is_x86_feature_detected!("popcnt") {
            return;
        }
        let mut rng = SplitMix64::new(5);
        for n in 0..=RANKED {
            let keys: Vec<u64> = (0..n).map(|_| rng.next_u64()).collect();
            let mut expect = keys.clone();
            expect.sort_unstable();
            let distinct = expect.windows(2).all(|w| w[0] != w[1]);
            assert!(distinct);
            // The run alone (its lanes past the end masked), and the run at
            // the start of a window of 16 whose other keys must not move.
            let after: Vec<u64> = (n..RANKED).map(|_| rng.next_u64()).collect();
            for whole in [false, true] {
                let mut window = keys.clone();
                if whole {
                    window.extend(&after);
                }
                // SAFETY: the processor has AVX2 and POPCNT, checked above.
                assert!(unsafe { by_rank_avx2(&mut window, n) });
                assert_eq!(window[..n], expect[..], "n {n} whole {whole}");
                assert_eq!(&window[n..], if whole { &after[..] } else { &[][..] }, "n {n}: keys past the run moved");
                if n >= 2 {
                    window[n / 2] = window[0];
                    let before = window.clone();
                    // SAFETY: as above.
                    assert!(!unsafe { by_rank_avx2(&mut window, n) });
                    assert_eq!(window, before, "n {n} whole {whole}: left as it was");
                }
            }
        }
    }
}
