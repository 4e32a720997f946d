//! SplitMix64 (Steele, Lea and Flood 2014): a tiny deterministic generator,
//! so that every fuzz input is reproducible from (format, seed, iteration).

/// The generator state.
#[derive(Debug, Clone)]
pub struct Rng(u64);

impl Rng {
    /// A generator for one fuzz input: the state mixes the three numbers.
    pub fn for_input(format: u64, seed: u64, iteration: u64) -> Self {
        let mut r = Rng(seed ^ format.wrapping_mul(0xA24B_AED4_963E_E407));
        let s = r.next_u64() ^ iteration.wrapping_mul(0x9FB2_1C65_1E98_DF25);
        Rng(s)
    }

    /// The next 64 random bits. O(1).
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `0..n` (0 when `n` is 0).
    pub fn below(&mut self, n: usize) -> usize {
        if n == 0 {
            0
        } else {
            (self.next_u64() % n as u64) as usize
        }
    }

    /// `true` with probability `1 / n`.
    pub fn one_in(&mut self, n: usize) -> bool {
        self.below(n) == 0
    }

    /// A random element of a non-empty slice.
    pub fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reproducible_and_distinct() {
        let a: Vec<u64> = (0..4).map(|_| Rng::for_input(1, 2, 3).next_u64()).collect();
        assert!(a.windows(2).all(|w| w[0] == w[1]));
        assert_ne!(Rng::for_input(1, 2, 3).next_u64(), Rng::for_input(1, 2, 4).next_u64());
        assert_ne!(Rng::for_input(1, 2, 3).next_u64(), Rng::for_input(2, 2, 3).next_u64());
    }
}
