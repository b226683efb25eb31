//! The one fingerprint of bit patterns: 64-bit FNV-1a over little-endian bytes. Equal digests of
//! a run's state (positions and velocities, an optimizer's swarm) mean a bit-identical run,
//! natively and in wasm; a cache keyed by a digest (the flow field's obstacles) rebuilds when any
//! bit of its input changed. Not a cryptographic hash: nothing here defends against crafted input.

/// FNV-1a, 64 bits: feed values, then [`Fnv1a::finish`].
#[derive(Clone, Copy, Debug)]
pub struct Fnv1a(u64);

impl Fnv1a {
    /// The FNV-1a 64-bit offset basis.
    const OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
    /// The FNV-1a 64-bit prime.
    const PRIME: u64 = 0x0000_0100_0000_01b3;

    /// An empty digest.
    pub const fn new() -> Self {
        Self(Self::OFFSET)
    }

    /// Feeds `bytes` in order.
    pub fn bytes(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 ^= u64::from(b);
            self.0 = self.0.wrapping_mul(Self::PRIME);
        }
    }

    /// Feeds an `f32`'s bit pattern (so -0.0 and 0.0, and every NaN payload, differ).
    pub fn f32(&mut self, x: f32) {
        self.bytes(&x.to_bits().to_le_bytes());
    }

    /// Feeds an `f64`'s bit pattern.
    pub fn f64(&mut self, x: f64) {
        self.bytes(&x.to_bits().to_le_bytes());
    }

    /// The digest of everything fed so far.
    pub const fn finish(self) -> u64 {
        self.0
    }
}

impl Default for Fnv1a {
    fn default() -> Self {
        Self::new()
    }
}

#[cfg(test)]
mod tests {
    use super::Fnv1a;

    #[test]
    fn matches_the_published_fnv1a_vectors() {
        // FNV-1a 64 test vectors (Fowler, Noll, Vo): "" and "a" and "foobar".
        assert_eq!(Fnv1a::new().finish(), 0xcbf2_9ce4_8422_2325);
        for (text, expected) in [("a", 0xaf63_dc4c_8601_ec8c_u64), ("foobar", 0x8594_4171_f739_67e8)] {
            let mut h = Fnv1a::new();
            h.bytes(text.as_bytes());
            assert_eq!(h.finish(), expected, "{text:?}");
        }
    }

    #[test]
    fn a_float_feeds_its_little_endian_bits() {
        let mut by_value = Fnv1a::new();
        by_value.f32(-0.0);
        let mut by_bytes = Fnv1a::new();
        by_bytes.bytes(&(-0.0f32).to_bits().to_le_bytes());
        assert_eq!(by_value.finish(), by_bytes.finish());
        let mut zero = Fnv1a::new();
        zero.f32(0.0);
        assert_ne!(zero.finish(), by_value.finish(), "-0.0 and 0.0 differ");
    }
}
