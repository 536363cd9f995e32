//! Random numbers for noise models: a seeded PCG32 generator implementing
//! the `rand_core` 0.10 interface, and uniform, normal and Poisson
//! samplers over any `rand_core::Rng`.
//!
//! ```
//! use radiometry::sensor::noise::{Pcg32, poisson, standard_normal, uniform};
//! let mut rng = Pcg32::new(42);
//! let u = uniform(&mut rng);
//! assert!((0.0..1.0).contains(&u));
//! assert!(standard_normal(&mut rng).is_finite());
//! let k = poisson(&mut rng, 3.5);
//! assert!(k >= 0.0 && k == k.floor());
//! ```

use core::convert::Infallible;
use rand_core::{Rng, TryRng};

/// PCG32 (PCG-XSH-RR 64/32; O'Neill 2014, "PCG: A family of simple fast
/// space-efficient statistically good algorithms for random number
/// generation", HMC-CS-2014-0905, §6.3.1). Small, seedable, `no_std`.
/// Implements `rand_core::TryRng<Error = Infallible>`, hence
/// `rand_core::Rng`.
///
/// ```
/// use radiometry::sensor::Pcg32;
/// use rand_core::Rng;
/// let (mut a, mut b) = (Pcg32::new(7), Pcg32::new(7));
/// assert_eq!(a.next_u32(), b.next_u32());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Pcg32 {
    state: u64,
    inc: u64,
}

impl Pcg32 {
    const MUL: u64 = 6_364_136_223_846_793_005;

    /// Seeds the generator (stream fixed); equal seeds give equal
    /// sequences.
    pub fn new(seed: u64) -> Self {
        Self::with_stream(seed, 0xda3e_39cb_94b9_5bdb)
    }

    /// Seeds the generator on one of 2⁶³ independent streams.
    pub fn with_stream(seed: u64, stream: u64) -> Self {
        let mut r = Self {
            state: 0,
            inc: (stream << 1) | 1,
        };
        r.step();
        r.state = r.state.wrapping_add(seed);
        r.step();
        r
    }

    #[inline]
    fn step(&mut self) {
        self.state = self.state.wrapping_mul(Self::MUL).wrapping_add(self.inc);
    }

    #[inline]
    fn output(&mut self) -> u32 {
        let old = self.state;
        self.step();
        let xorshifted = (((old >> 18) ^ old) >> 27) as u32;
        let rot = (old >> 59) as u32;
        xorshifted.rotate_right(rot)
    }
}

impl TryRng for Pcg32 {
    type Error = Infallible;
    fn try_next_u32(&mut self) -> Result<u32, Infallible> {
        Ok(self.output())
    }
    fn try_next_u64(&mut self) -> Result<u64, Infallible> {
        let lo = self.output() as u64;
        let hi = self.output() as u64;
        Ok(lo | (hi << 32))
    }
    fn try_fill_bytes(&mut self, dst: &mut [u8]) -> Result<(), Infallible> {
        for chunk in dst.chunks_mut(4) {
            let b = self.output().to_le_bytes();
            chunk.copy_from_slice(&b[..chunk.len()]);
        }
        Ok(())
    }
}

/// Uniform on `[0, 1)` with 24 random bits.
#[inline]
pub fn uniform<G: Rng + ?Sized>(rng: &mut G) -> f32 {
    (rng.next_u32() >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// Uniform on `(0, 1]` (safe for `ln`).
#[inline]
fn uniform_open0<G: Rng + ?Sized>(rng: &mut G) -> f32 {
    ((rng.next_u32() >> 8) + 1) as f32 * (1.0 / 16_777_216.0)
}

/// Standard normal deviate by the Box–Muller transform (Box & Muller
/// 1958, Ann. Math. Stat. 29: `z = √(−2 ln u₁) cos 2πu₂`), `u₁ ∈ (0, 1]`
/// so the result is always finite (|z| ≤ 5.8).
#[inline]
pub fn standard_normal<G: Rng + ?Sized>(rng: &mut G) -> f32 {
    let u1 = uniform_open0(rng);
    let u2 = uniform(rng);
    libm::sqrtf(-2.0 * libm::logf(u1)) * libm::cosf(core::f32::consts::TAU * u2)
}

/// Mean above which [`poisson`] switches from inversion to PTRS.
pub const POISSON_INVERSION_LIMIT: f32 = 10.0;

/// A Poisson deviate with mean `mu`, returned as an integer-valued `f32`.
///
/// * `mu ≤ 0`, NaN → 0; `mu` is capped at 1e12 (beyond any full well).
/// * `mu < 10`: sequential-search inversion of the CDF (Devroye 1986,
///   *Non-Uniform Random Variate Generation*, §X.3.3), exact up to f32
///   rounding of the CDF; the search is capped at 200 terms.
/// * `mu ≥ 10`: PTRS, transformed rejection with squeeze (Hörmann 1993,
///   "The transformed rejection method for generating Poisson random
///   variables", Insurance: Mathematics and Economics 12, 39–45, Table 1),
///   exact; its acceptance test compares `k ln μ − μ − ln k!` in `f64`
///   (documented: in `f32` these terms cancel catastrophically for
///   large μ).
pub fn poisson<G: Rng + ?Sized>(rng: &mut G, mu: f32) -> f32 {
    if mu.is_nan() || mu <= 0.0 {
        return 0.0;
    }
    let mu = mu.min(1e12);
    if mu < POISSON_INVERSION_LIMIT {
        let u = uniform(rng);
        let mut p = libm::expf(-mu);
        let mut cdf = p;
        let mut k = 0u32;
        while u > cdf && k < 200 {
            k += 1;
            p *= mu / k as f32;
            cdf += p;
        }
        return k as f32;
    }
    let m = mu as f64;
    let smu = libm::sqrt(m);
    let b = 0.931 + 2.53 * smu;
    let a = -0.059 + 0.02483 * b;
    let inv_alpha = 1.1239 + 1.1328 / (b - 3.4);
    let v_r = 0.9277 - 3.6224 / (b - 2.0);
    let ln_mu = libm::log(m);
    for _ in 0..1000 {
        let u = uniform(rng) as f64 - 0.5;
        let v = uniform_open0(rng) as f64;
        let us = 0.5 - libm::fabs(u);
        let k = libm::floor((2.0 * a / us + b) * u + m + 0.43);
        if us >= 0.07 && v <= v_r {
            return k as f32;
        }
        if k < 0.0 || (us < 0.013 && v > us) {
            continue;
        }
        let lhs = libm::log(v) + libm::log(inv_alpha) - libm::log(a / (us * us) + b);
        let rhs = -m + k * ln_mu - libm::lgamma(k + 1.0);
        if lhs <= rhs {
            return k as f32;
        }
    }
    // Unreachable in practice (acceptance rate > 0.9); a finite fallback.
    libm::roundf(mu)
}
