//! A tiny seeded generator for reproducible start blocks.

/// SplitMix64 (Steele, Lea and Flood 2014): 64-bit state, one multiply-xorshift
/// chain per draw. Deterministic for a given seed on every platform.
#[derive(Debug, Clone)]
pub(crate) struct SplitMix64(u64);

impl SplitMix64 {
    pub(crate) fn new(seed: u64) -> Self {
        Self(seed)
    }

    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [-1, 1).
    pub(crate) fn next_signed(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }

    /// Fills a slice with uniform values in [-1, 1).
    pub(crate) fn fill(&mut self, out: &mut [f64]) {
        for x in out {
            *x = self.next_signed();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn deterministic_and_in_range() {
        let (mut a, mut b) = (SplitMix64::new(7), SplitMix64::new(7));
        for _ in 0..1000 {
            let x = a.next_signed();
            assert_eq!(x, b.next_signed());
            assert!((-1.0..1.0).contains(&x));
        }
        assert_ne!(SplitMix64::new(1).next_signed(), SplitMix64::new(2).next_signed());
    }
}
