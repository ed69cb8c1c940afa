//! A seeded generator for tests that draw their cases by a rule (Knuth's MMIX linear
//! congruential step): the same seed gives the same cases on every machine.

/// The generator's state.
pub(crate) struct TestRng(u64);

impl TestRng {
    /// A generator started at `seed`.
    pub(crate) fn new(seed: u64) -> TestRng {
        TestRng(seed)
    }

    /// The next 64-bit state.
    pub(crate) fn next_u64(&mut self) -> u64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        self.0
    }

    /// A number in [0, 1) from the state's top 53 bits.
    pub(crate) fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
}
