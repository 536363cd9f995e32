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

use rand_core::Rng;

/// The crate's one generator, re-exported here for the noise models.
pub use crate::rng::Pcg32;

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
    // cos 2πu₂ by `sincos_turn` (turns, `f32` only; `libm::cosf` computes in `f64`).
    crate::math::sqrtf(-2.0 * libm::logf(u1)) * crate::math::sincos_turn(u2).1
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
