//! The tail scheme of the Beckmann visible-slope sampler (Heitz & d'Eon
//! 2014, §4.2): a bounded start and two safeguarded Halley steps, valid for
//! every `u`; `Beckmann::sample_visible` uses it where `u₀` is outside the
//! range of the fast path (`beckmann_slope`), and the vector form
//! (`beckmann_lanes`) mirrors it bit for bit.

use super::Beckmann;
use super::special::{FRAC_1_SQRT_PI, MAX_SLOPE, SQRT_PI, beckmann_s, erfcinv, erfcx, exp_neg_sq, ln64, lnf};

impl Beckmann {
    /// The CDF (unnormalised) of the visible slope `x̃` of the standard
    /// (`α = 1`) Beckmann surface seen at angle θ (Heitz & d'Eon 2014,
    /// §4.2): `C(x) = ∫_{−∞}^x (cos θ − t sin θ) e^{−t²}/√π dt
    ///            = cos θ erfc(−x)/2 + sin θ e^{−x²}/(2√π)`.
    ///
    /// [`sample_slope_x`](Self::sample_slope_x) evaluates it in the split,
    /// cancellation-free forms derived below; this direct form is kept for
    /// the tests.
    #[cfg(test)]
    pub(super) fn slope_cdf(cos_t: f32, sin_t: f32, x: f32) -> f32 {
        0.5 * cos_t * super::special::erfc(-x) + 0.5 * sin_t * FRAC_1_SQRT_PI * exp_neg_sq(x)
    }

    /// The tail scheme of the slope sampler (used for `u` outside the fast
    /// range of `beckmann_slope`; valid for every `u`):
    /// samples the slope `x̃ ∈ [−MAX_SLOPE, b]` with density ∝
    /// `(cos θ − x̃ sin θ) e^{−x̃²}` (Heitz & d'Eon 2014, §4.2 and eq. 11–12 for
    /// Beckmann), `b = min(cot θ, MAX_SLOPE)`, by solving `C(x̃) = u C(b)`
    /// with a fixed number of steps — no data-dependent loop: a bound-based
    /// start and two Halley steps (Newton with the cheap second-derivative
    /// correction; cubic convergence) in a logarithmic form, each
    /// safeguarded by bisection on a bracket.
    ///
    /// Notation: `c = cos θ`, `s = sin θ`, `H(x) = c erfcx(−x) + s/√π`, so
    /// `2C(x) = e^{−x²} H(x)` for `x ≤ 0`; `2C(0) = c + s/√π`; and
    /// `2C(b) = 2c + s S(b)/√π` with `S(a) = e^{−a²} − √π a erfc(a)` (for
    /// `b = cot θ` this is `2 cos θ (1 + Λ)`, the projected-area identity).
    /// The target `2uC(b)` decides the branch:
    ///
    /// * **`x̃ ≤ 0`** (`2uC(b) ≤ 2C(0)`): solve
    ///   `g(x) = ln(2C(x)) − ln(2uC(b)) = L₀ − x² + ln(H(x)/2C(0)) = 0`,
    ///   `L₀ = ln(2C(0)/(2uC(b)))`. `C` has a log-concave density, so `C` is
    ///   log-concave (Prékopa) and both tangent-type bounds are lower bounds
    ///   of the root: `−√L₀` (from `H ≤ 2C(0)`) and `−L₀/g'(0)` (tangent of
    ///   `ln C` at 0). The start is their maximum. No `expf` is needed:
    ///   `g' = 2(c − x s)/(√π H)` and `g'' = −(2/(√π H))(s + (c − x s)(g' + 2x))`.
    /// * **`x̃ > 0`**: solve `φ(x) = ln G(x) − ln G*` for the complement
    ///   `G(x) = 2C(b) − 2C(x) = s S(b)/√π + e^{−x²}(c erfcx(x) − s/√π)`,
    ///   `G* = 2(1 − u)C(b)` (`1 − u` is exact here since `u > 1/2`);
    ///   `φ' = −2p/G`, `φ'' = −2p'/G − φ'²` with `p = (c − x s)e^{−x²}/√π`.
    ///   Start: the minimum of (i) the Gaussian-shift estimate
    ///   `z − h`, `z = erfcinv(q)`, `q = (G* − s S(b)/√π)/c`, `h` the positive
    ///   root of `z h² + (1 − zτ) h = τ/2` (`τ = tan θ`; second-order
    ///   expansion of `Φ(x) + (τ/2)φ(x) = Φ(z)`), and (ii) for `b = cot θ` the
    ///   endpoint bound `b − sqrt(√π G* e^{x_e²}/s)`, `x_e` the lower endpoint
    ///   bound `b − sqrt(√π G* e^{b²}/s)` (from `e^{−b²} ≤ e^{−t²} ≤ e^{−x_e²}`
    ///   on `[x, b]`).
    ///
    /// Accuracy of the scheme in exact arithmetic (`brdfs/tools/
    /// beckmann_slope_sweep.py` mirrors it in `f64`; θ ∈ [0, π/2],
    /// u ∈ [10⁻³⁸, 1 − 6·10⁻⁸]): after the two Halley steps
    /// `|C(x̃)/C(b) − u| ≤ 6.3·10⁻⁹`, and relative to the tail mass
    /// `min(u, 1 − u)` ≤ 1.7·10⁻⁴ (worst in the 10⁻²⁰ tails at grazing) for
    /// `u ≤ 1 − 10⁻⁷`; 1.4·10⁻³ at `u = 1 − 6·10⁻⁸`, where the upper branch
    /// keeps its start once the target is below the `f32` resolution of `G`
    /// ([`TAIL_RESOLUTION`]; in `f32` the steps there reached 9·10⁻⁵ absolute
    /// error, test `tail_scheme_top_of_range_near_grazing`). A χ²
    /// test with 10⁶ samples resolves bin probabilities to ~10⁻³ relative, so
    /// this is invisible to it. In `f32` the result is at the rounding level
    /// of `C` (unit test `slope_inversion_reproduces_u`: ≤ 0.3 of its
    /// resolution unit; `slope_sampler_tails_and_monotonicity` checks 10⁻³
    /// relative in the lower tail down to u = 10⁻³⁰).
    pub(super) fn sample_slope_x(cos_t: f32, sin_t: f32, u: f32) -> f32 {
        let (c, s) = (cos_t, sin_t);
        let b = if s * MAX_SLOPE <= c { MAX_SLOPE } else { c / s };
        if u.is_nan() || u <= 0.0 {
            return -MAX_SLOPE;
        }
        if u >= 1.0 {
            return b;
        }
        let excess = s * FRAC_1_SQRT_PI * beckmann_s(b); // 2C(b) − 2c
        let total2 = 2.0 * c + excess; // 2C(b)
        let c0 = c + s * FRAC_1_SQRT_PI; // 2C(0)
        let target = u * total2;
        if target <= c0 {
            Self::slope_lower(c, s, u, total2, c0)
        } else {
            Self::slope_upper(c, s, u, b, total2, excess)
        }
    }

    /// The `x̃ ≤ 0` branch of [`sample_slope_x`](Self::sample_slope_x).
    ///
    /// The Halley step `n/(1 − n g''/(2g'))`, `n = g/g'`, is written over a
    /// common denominator so that it costs one division:
    /// `Δ = 2 g√π H (c − xs) / (4(c − xs)²(1 + g/2) + g√π H (s + 2x(c − xs)))`.
    #[inline]
    fn slope_lower(c: f32, s: f32, u: f32, total2: f32, c0: f32) -> f32 {
        let inv_c0 = 1.0 / c0;
        // L₀ = ln(2C(0)/(u 2C(b))) ≥ 0; the product in f64 cannot leave the
        // normal range even for subnormal u.
        let l0 = (-ln64(u as f64 * total2 as f64 * inv_c0 as f64) as f32).max(0.0);
        let mut x = -radiometry::math::sqrtf(l0);
        if c > 0.0 {
            // −L₀/g'(0), g'(0) = 2c/(√π 2C(0)); NaN (0·∞) is ignored by max.
            x = x.max(-l0 * (0.5 * SQRT_PI * c0 / c));
        }
        x = x.max(-MAX_SLOPE);
        let (mut lo, mut hi) = (x, 0.0f32);
        for _ in 0..2 {
            let h = c * erfcx(-x) + s * FRAC_1_SQRT_PI;
            let g = l0 - x * x + lnf(h * inv_c0);
            if g > 0.0 {
                hi = x;
            } else {
                lo = x;
            }
            let den = c - x * s;
            let gh = g * SQRT_PI * h;
            let next = x - 2.0 * gh * den / (4.0 * den * den * (1.0 + 0.5 * g) + gh * (s + 2.0 * x * den));
            x = if next >= lo && next <= hi {
                next
            } else {
                0.5 * (lo + hi)
            };
        }
        // max/min rather than clamp: panic-free and NaN-absorbing; `+ 0`
        // makes a zero `+0` (`min(−0, 0)` may return either zero), so the
        // vector kernel can match the sign bit.
        #[allow(clippy::manual_clamp)]
        let x = x.max(-MAX_SLOPE).min(0.0);
        x + 0.0
    }

    /// The `x̃ > 0` branch of [`sample_slope_x`](Self::sample_slope_x)
    /// (keeping its start where the target is below the resolution of `G`,
    /// [`TAIL_RESOLUTION`]); the
    /// Halley step over a common denominator (one division):
    /// `Δ = −2φG(c − xs) / (4p(c − xs)(1 + φ/2) − φG(s + 2x(c − xs)))`.
    #[inline]
    fn slope_upper(c: f32, s: f32, u: f32, b: f32, total2: f32, excess: f32) -> f32 {
        let gs = (1.0 - u) * total2;
        let ln_gs = lnf(gs);
        let mut x = b;
        if c > 0.0 {
            let q = (gs - excess) / c;
            if q > 0.0 && q < 2.0 {
                let z = erfcinv(q);
                let zs = z * s;
                x = x.min(z - s / (radiometry::math::sqrtf(c * c + zs * zs) + c - zs));
            }
        }
        let mut keep_start = false;
        if b < MAX_SLOPE {
            // b = cot θ, s > 0: endpoint bounds.
            let eb = exp_neg_sq(b);
            let xe = (b - radiometry::math::sqrtf(SQRT_PI * gs / (s * eb))).max(0.0);
            x = x.min(b - radiometry::math::sqrtf(SQRT_PI * gs / (s * exp_neg_sq(xe))));
            // Near b, `G = E + e^{−x²}(c erfcx(x) − s/√π)` cancels terms of
            // size ~`E + e^{−b²}s/√π`: a target below a few ε of that is
            // beyond the resolution of `G` (a step on a `G` of unresolved
            // sign would fall back to bisection far from the root), and the
            // endpoint bound, exact to leading order in b − x there, is kept.
            keep_start = gs <= TAIL_RESOLUTION * (excess + s * FRAC_1_SQRT_PI * eb);
        }
        x = x.max(0.0);
        if keep_start {
            return x.min(b) + 0.0;
        }
        let (mut lo, mut hi) = (0.0f32, b);
        for _ in 0..2 {
            let e = exp_neg_sq(x);
            let den = c - x * s;
            let g = excess + e * (c * erfcx(x) - s * FRAC_1_SQRT_PI);
            let next = if g > 0.0 {
                let phi = lnf(g) - ln_gs;
                if phi > 0.0 {
                    lo = x;
                } else {
                    hi = x;
                }
                let p4 = 4.0 * den * e * FRAC_1_SQRT_PI; // 4p
                let pg = phi * g;
                x + 2.0 * pg * den / (p4 * den * (1.0 + 0.5 * phi) - pg * (s + 2.0 * x * den))
            } else {
                // x at (or rounded onto) the end point: step back.
                hi = x;
                f32::NAN
            };
            x = if next >= lo && next <= hi {
                next
            } else {
                0.5 * (lo + hi)
            };
        }
        // `+ 0`: a zero is `+0` (as in `slope_lower`).
        x.max(0.0).min(b) + 0.0
    }
}

/// `16ε`: where the upper-tail target `2(1 − u)C(b)` of the tail scheme is
/// below `TAIL_RESOLUTION · (E + e^{−b²} s/√π)` (the size of the terms `G`
/// cancels near `b = cot θ`), the scheme keeps its start (see
/// `Beckmann::slope_upper`).
pub(super) const TAIL_RESOLUTION: f32 = 16.0 * f32::EPSILON;

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::microfacet::clamp01;

    /// f64 reference of the slope CDF written from its integral definition
    /// `C(x) = ∫_{−∞}^x (cos θ − t sin θ) e^{−t²}/√π dt` (closed form in f64).
    fn cdf64(c: f64, s: f64, x: f64) -> f64 {
        0.5 * c * libm::erfc(-x) + 0.5 * s * libm::exp(-x * x) / core::f64::consts::PI.sqrt()
    }

    /// The inverted CDF reproduces `u`: `|C(x(u))/C(b) − u|` is measured in
    /// units of the resolution the `f32` slope allows (`C'(x)·ulp(x)`, plus
    /// the `f32` rounding of `C` itself).
    #[test]
    fn slope_inversion_reproduces_u() {
        let mut worst = 0.0f64;
        for k in 0..=12 {
            let theta = (k as f64 / 12.0) * core::f64::consts::FRAC_PI_2;
            let (s, c) = (libm::sin(theta) as f32, libm::cos(theta) as f32);
            let (s64, c64) = (s as f64, c as f64);
            let b = if s * MAX_SLOPE <= c {
                MAX_SLOPE as f64
            } else {
                (c / s) as f64
            };
            let total = cdf64(c64, s64, b);
            for i in 0..=2000 {
                let u = match i {
                    0 => 0.0f32,
                    2000 => radiometry::math::ONE_MINUS_EPSILON,
                    _ => i as f32 / 2000.0,
                };
                let x = Beckmann::sample_slope_x(c, s, u);
                assert!(x.is_finite() && x >= -MAX_SLOPE && x as f64 <= b + 1e-6);
                let got = cdf64(c64, s64, x as f64) / total;
                let dens = (c64 - x as f64 * s64).max(0.0) * libm::exp(-(x as f64).powi(2))
                    / core::f64::consts::PI.sqrt()
                    / total;
                let unit =
                    dens * (x.abs().max(1e-3) as f64) * f32::EPSILON as f64 * 4.0 + 4.0 * f32::EPSILON as f64;
                let err = (got - u as f64).abs() / unit;
                worst = worst.max(err);
                assert!(err < 4.0, "θ={theta} u={u}: x={x}, C/C(b)={got} ({err} units)");
            }
        }
        extern crate std;
        std::println!("Beckmann slope inversion: worst |C(x)/C(b) − u| = {worst:.1} resolution units");
    }

    /// The sampler's split CDF forms agree with the direct `f32` CDF
    /// (`slope_cdf`, built on the fast `erfc`) and the f64 reference.
    #[test]
    fn slope_cdf_matches_f64() {
        for k in 0..=24 {
            let theta = (k as f64 / 24.0) * core::f64::consts::FRAC_PI_2;
            let (s, c) = (libm::sin(theta) as f32, libm::cos(theta) as f32);
            for i in 0..=400 {
                let x = -9.0 + 18.0 * i as f32 / 400.0;
                let r = cdf64(c as f64, s as f64, x as f64);
                let v = Beckmann::slope_cdf(c, s, x) as f64;
                assert!(
                    (v - r).abs() <= 8.0 * f32::EPSILON as f64 * r.max(1e-30) + 1e-38,
                    "θ={theta} x={x}: {v} vs {r}"
                );
            }
        }
    }

    /// Deep tails and extreme angles of the slope sampler: finite, in range,
    /// monotone in `u`, and `C(x)/C(b)` reproduces `u` *relatively* in the
    /// lower tail (down to u = 10⁻³⁰) to 10⁻³.
    #[test]
    fn slope_sampler_tails_and_monotonicity() {
        for &theta in &[
            0.0f64,
            1e-6,
            0.3,
            0.9,
            1.3,
            1.5,
            core::f64::consts::FRAC_PI_2 - 1e-6,
            core::f64::consts::FRAC_PI_2,
        ] {
            let (s, c) = (libm::sin(theta) as f32, libm::cos(theta) as f32);
            let (s64, c64) = (s as f64, c as f64);
            let b = if s * MAX_SLOPE <= c {
                MAX_SLOPE as f64
            } else {
                (c / s) as f64
            };
            let total = cdf64(c64, s64, b);
            for &u in &[1e-30f32, 1e-20, 1e-10, 1e-6] {
                let x = Beckmann::sample_slope_x(c, s, u);
                if x > -MAX_SLOPE {
                    let got = cdf64(c64, s64, x as f64) / total;
                    assert!((got / u as f64 - 1.0).abs() < 1e-3, "θ={theta} u={u}: {got}");
                }
            }
            let mut prev = -MAX_SLOPE;
            for i in 0..=20_000 {
                let u = i as f32 / 20_000.0;
                let x = Beckmann::sample_slope_x(c, s, u);
                assert!(
                    x.is_finite() && x >= -MAX_SLOPE && x as f64 <= b + 1e-6,
                    "θ={theta} u={u}: {x}"
                );
                assert!(
                    x >= prev - 2e-6 * (1.0 + x.abs()),
                    "θ={theta} u={u}: {x} < {prev}"
                );
                prev = x;
            }
            for u in [0.0, -1.0, f32::NAN, 1.0, f32::INFINITY, 1e-45] {
                let x = Beckmann::sample_slope_x(c, s, clamp01(u));
                assert!(x.is_finite() && x >= -MAX_SLOPE && x as f64 <= b + 1e-6);
            }
        }
    }
}
