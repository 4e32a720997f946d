//! A seeded generator: reproducible jitter in [`shapes`](crate::shapes),
//! random start blocks of iterative eigensolvers, test inputs.
//!
//! (This file is also the test kit's generator, included by path, so that
//! the two are one.)

/// SplitMix64 (Steele, Lea and Flood 2014, "Fast splittable pseudorandom
/// number generators"): a 64-bit state advanced by a Weyl constant and mixed
/// by two multiply-xorshift rounds. The same seed gives the same stream on
/// every platform. Each draw is O(1). Not for cryptography.
#[derive(Debug, Clone)]
pub struct SplitMix64(u64);

impl SplitMix64 {
    /// A generator whose first draw mixes `seed`. O(1).
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }

    /// The next 64 random bits. O(1).
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[0, 1)` on a grid of 2^-53 (the top 53 bits). O(1).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in `[-1, 1)` on a grid of 2^-52. O(1).
    pub fn signed(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }

    /// Fills `out` with uniform values in `[-1, 1)`. O(out).
    pub fn fill_signed(&mut self, out: &mut [f64]) {
        for x in out {
            *x = self.signed();
        }
    }

    /// Uniform in `0..n` by a modulo (bias below n / 2^64); 0 when `n` is 0. O(1).
    pub fn below(&mut self, n: usize) -> usize {
        if n == 0 {
            0
        } else {
            (self.next_u64() % n as u64) as usize
        }
    }

    /// `true` with probability `1 / n` (always when `n` is 0 or 1). O(1).
    pub fn one_in(&mut self, n: usize) -> bool {
        self.below(n) == 0
    }

    /// A random element of a slice, `None` when it is empty. O(1).
    pub fn pick<'a, T>(&mut self, items: &'a [T]) -> Option<&'a T> {
        items.get(self.below(items.len()))
    }

    /// A uniform random permutation of `0..n` (Fisher-Yates, Durstenfeld
    /// 1964). O(n).
    pub fn permutation(&mut self, n: usize) -> Vec<u32> {
        let mut p: Vec<u32> = (0..n as u32).collect();
        for i in (1..n).rev() {
            p.swap(i, self.below(i + 1));
        }
        p
    }
}

#[cfg(test)]
mod tests {
    use super::SplitMix64;

    #[test]
    fn the_published_first_outputs() {
        // Seed 1234567: the reference values of Rosetta Code's task
        // "Pseudo-random numbers/Splitmix64" (Vigna's splitmix64.c).
        let mut r = SplitMix64::new(1234567);
        assert_eq!(r.next_u64(), 6457827717110365317);
        assert_eq!(r.next_u64(), 3203168211198807973);
        assert_eq!(r.next_u64(), 9817491932198370423);
    }

    #[test]
    fn ranges_and_reproducibility() {
        let (mut a, mut b) = (SplitMix64::new(7), SplitMix64::new(7));
        for _ in 0..1000 {
            let (x, y) = (a.signed(), a.unit());
            assert_eq!(x, b.signed());
            assert_eq!(y, b.unit());
            assert!((-1.0..1.0).contains(&x) && (0.0..1.0).contains(&y));
            assert!(a.below(5) < 5 && b.below(5) < 5);
        }
        assert_ne!(SplitMix64::new(1).next_u64(), SplitMix64::new(2).next_u64());
        assert_eq!(SplitMix64::new(3).below(0), 0);
        assert_eq!(SplitMix64::new(3).pick(&[5u8]), Some(&5));
        assert_eq!(SplitMix64::new(3).pick::<u8>(&[]), None);
    }

    #[test]
    fn permutations_are_permutations() {
        let mut p = SplitMix64::new(11).permutation(100);
        assert_ne!(p, (0..100).collect::<Vec<u32>>());
        p.sort_unstable();
        assert_eq!(p, (0..100).collect::<Vec<u32>>());
    }
}
