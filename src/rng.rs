//! The crate's one random number generator, [`Pcg32`]: the Monte Carlo
//! integrators' pseudo-random points and the sensor noise models draw from
//! it, and it implements the `rand_core` interface (re-exported as
//! [`radiometry::rand_core`](crate::rand_core)), so any `rand_core::Rng` works
//! wherever the crate takes a generator.
//!
//! ```
//! use radiometry::rng::Pcg32;
//! use radiometry::rand_core::Rng;
//! let (mut a, mut b) = (Pcg32::new(7), Pcg32::new(7));
//! assert_eq!(a.next_u32(), b.next_u32()); // deterministic
//! let u = a.next_f32();
//! assert!((0.0..1.0).contains(&u));
//! ```

use core::convert::Infallible;
use rand_core::TryRng;

/// PCG32 (PCG-XSH-RR 64/32; O'Neill 2014, "PCG: A family of simple fast
/// space-efficient statistically good algorithms for random number
/// generation", HMC-CS-2014-0905, §6.3.1): 64-bit LCG state with multiplier
/// `6364136223846793005` (Knuth, TAOCP vol. 2, §3.3.4), 32-bit output by an
/// xorshift-high + random-rotate permutation. Period `2⁶⁴` per stream,
/// `2⁶³` streams. Small, seedable, `no_std`; implements
/// `rand_core::TryRng<Error = Infallible>`, hence `rand_core::Rng`.
///
/// ```
/// use radiometry::rng::Pcg32;
/// let (mut a, mut b) = (Pcg32::with_stream(7, 1), Pcg32::with_stream(7, 1));
/// assert_eq!(a.next_u32(), b.next_u32()); // deterministic
/// let mut c = Pcg32::with_stream(7, 2);
/// assert_ne!(Pcg32::with_stream(7, 1).next_u32(), c.next_u32()); // streams differ
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Pcg32 {
    state: u64,
    inc: u64,
}

impl Pcg32 {
    const MUL: u64 = 6_364_136_223_846_793_005;

    /// Seeds the generator on its default stream; equal seeds give equal
    /// sequences.
    pub fn new(seed: u64) -> Self {
        Self::with_stream(seed, 0xda3e_39cb_94b9_5bdb)
    }

    /// Seeds the generator on one of `2⁶³` independent streams (O'Neill's
    /// `pcg32_srandom_r`).
    pub fn with_stream(seed: u64, stream: u64) -> Self {
        let mut r = Self {
            state: 0,
            inc: (stream << 1) | 1,
        };
        r.next_u32();
        r.state = r.state.wrapping_add(seed);
        r.next_u32();
        r
    }

    /// The next 32 uniformly distributed bits.
    #[inline]
    pub fn next_u32(&mut self) -> u32 {
        let old = self.state;
        self.state = old.wrapping_mul(Self::MUL).wrapping_add(self.inc);
        let xorshifted = (((old >> 18) ^ old) >> 27) as u32;
        let rot = (old >> 59) as u32;
        xorshifted.rotate_right(rot)
    }

    /// A uniform `f32` in `[0, 1)`: the top 24 bits times `2⁻²⁴` (every
    /// value is exact; the largest is `1 − 2⁻²⁴`).
    #[inline]
    pub fn next_f32(&mut self) -> f32 {
        (self.next_u32() >> 8) as f32 * (1.0 / 16_777_216.0)
    }

    /// A uniform `f64` in `[0, 1)` from 53 random bits.
    #[inline]
    pub fn next_f64(&mut self) -> f64 {
        let hi = (self.next_u32() >> 5) as u64; // 27 bits
        let lo = (self.next_u32() >> 6) as u64; // 26 bits
        ((hi << 26) | lo) as f64 * (1.0 / 9_007_199_254_740_992.0)
    }
}

impl TryRng for Pcg32 {
    type Error = Infallible;
    fn try_next_u32(&mut self) -> Result<u32, Infallible> {
        Ok(Pcg32::next_u32(self))
    }
    fn try_next_u64(&mut self) -> Result<u64, Infallible> {
        let lo = Pcg32::next_u32(self) as u64;
        let hi = Pcg32::next_u32(self) as u64;
        Ok(lo | (hi << 32))
    }
    fn try_fill_bytes(&mut self, dst: &mut [u8]) -> Result<(), Infallible> {
        for chunk in dst.chunks_mut(4) {
            let b = Pcg32::next_u32(self).to_le_bytes();
            chunk.copy_from_slice(&b[..chunk.len()]);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// O'Neill's reference `pcg32-demo` output for `pcg32_srandom_r(42, 54)`
    /// (pcg-c-basic, the first six `pcg32_random_r` values).
    #[test]
    fn matches_the_reference_sequence() {
        let mut r = Pcg32::with_stream(42, 54);
        let want = [
            0xa15c_02b7,
            0x7b47_f409,
            0xba1d_3330,
            0x83d2_f293,
            0xbfa4_784b,
            0xcbed_606e,
        ];
        for w in want {
            assert_eq!(r.next_u32(), w);
        }
    }

    #[test]
    fn the_rand_core_interface_draws_the_same_stream() {
        use rand_core::Rng;
        let (mut a, mut b) = (Pcg32::new(9), Pcg32::new(9));
        assert_eq!(Rng::next_u32(&mut a), b.next_u32());
        let mut bytes = [0u8; 6];
        a.fill_bytes(&mut bytes);
        let w = b.next_u32().to_le_bytes();
        assert_eq!(bytes[..4], w);
        assert_eq!(bytes[4..], b.next_u32().to_le_bytes()[..2]);
    }
}
