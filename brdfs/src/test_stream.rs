//! The unit tests' own uniform stream (xorshift64, Marsaglia 2003, shifts
//! 13/7/17; the top 24 bits as an `f32` in `[0, 1)`): deterministic, no
//! dependency.

/// Uniforms in `[0, 1)` from `seed` (non-zero).
pub(crate) fn uniforms(seed: u64) -> impl FnMut() -> f32 {
    let mut s = seed;
    move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 40) as f32 / (1u64 << 24) as f32
    }
}
