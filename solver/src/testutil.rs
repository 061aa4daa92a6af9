//! Test helpers: a tiny seeded random number generator (SplitMix64), so the
//! tests are deterministic without extra dependencies.

/// SplitMix64 generator.
pub(crate) struct Lcg {
    state: u64,
}

impl Lcg {
    /// A generator with the given seed.
    pub(crate) fn new(seed: u64) -> Lcg {
        Lcg { state: seed }
    }

    fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[lo, hi)`.
    pub(crate) fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        let unit = (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        lo + (hi - lo) * unit
    }
}
