//! The Beckmann projected area `A = cos θ (1 + Λ)` in `f32`, without an
//! exponential: the hot path of the Beckmann BRDF (`eval`, `pdf`, the
//! weight of `sample`, and their vector kernels).
//!
//! With `a = cos θ/(α sin θ)` the exact Smith `Λ` of Beckmann (Heitz 2014,
//! "Understanding the Masking-Shadowing Function", JCGT 3(2), eq. 80) gives
//!
//! ```text
//! A = cos θ + α sin θ · aΛ(a),   aΛ(a) = e^{−a²} T(a)/(2√π),   T(a) = 1 − √π a erfcx(a).
//! ```
//!
//! Only `A` matters to the BRDF, and only to `f32` accuracy, so `aΛ` needs
//! an error below `ε (a + aΛ(a))` (relative error `ε` of `A`): relative
//! accuracy at grazing (`a → 0`, `Λ` dominates), only absolute accuracy
//! `~ε a` where `Λ` is small. Under that weight `aΛ` itself — exponential
//! included — is one rational `P(a)/Q(a)` of degree 6/6 on
//! `[0, AREA_CUT]`, fitted by `brdfs/tools/fit_beckmann_area.py` (weighted
//! Sanathanan–Koerner + Lawson against 60-digit mpmath, coefficients
//! rounded to `f32`; weighted error 2.8·10⁻⁸). Beyond `AREA_CUT = 3.5`, `Λ < 1.5·10⁻⁸` (2⁻²⁶) and
//! `A = cos θ`.
//!
//! Accuracy of `A` (unit test `area_matches_f64`, against `cos θ (1 + Λ)`
//! in `f64` from libm's `erfc` at the same `f32` inputs): ≤ 3 ulp (measured
//! 2.2), where the `f64` form it replaces reached ≤ 1.5 ulp. The evaluation
//! is generic over `f32` and the `simd` lane type, so the vector kernel runs
//! the same operations in the same order (bit-identical by construction).

/// `aΛ(a) ≈ P(a)/Q(a)` on `[0, AREA_CUT]`: the numerator (see the module
/// documentation; `fit_beckmann_area.py`).
const AREA_P: [f32; 7] = [
    0.282_036_24,
    -0.508_735,
    0.387_040_64,
    -0.158_842_33,
    0.037_055_973,
    -0.004_654_668,
    0.000_245_699_9,
];

/// The denominator of the `aΛ` rational; `P(0)/Q(0) = 1/(2√π)` to
/// 9·10⁻¹⁴ (no single `f32` holds `1/(2√π)` better than 5·10⁻⁸, a pair does).
const AREA_Q: [f32; 7] = [
    0.999_792_46,
    -0.031_333_823,
    0.316_720_4,
    0.029_378_297,
    0.034_448_37,
    0.007_166_684,
    0.002_771_403_6,
];

/// Beyond `a = 3.5`, `Λ(a) < 1.42·10⁻⁸ < 2⁻²⁶`: `A = cos θ` to within a
/// quarter of an `f32` ulp.
pub(crate) const AREA_CUT: f32 = 3.5;

/// The `f32` arithmetic of the rational, for `f32` and (feature `simd`)
/// the lane vector: the same operations in the same order in both.
pub(crate) trait F32Arith:
    Copy
    + core::ops::Add<Output = Self>
    + core::ops::Mul<Output = Self>
    + core::ops::Div<Output = Self>
{
    /// The constant in every lane.
    fn splat(c: f32) -> Self;
}

impl F32Arith for f32 {
    #[inline(always)]
    fn splat(c: f32) -> f32 {
        c
    }
}

#[cfg(feature = "simd")]
impl F32Arith for crate::simd::Vf {
    #[inline(always)]
    fn splat(c: f32) -> Self {
        crate::simd::Vf::splat(c)
    }
}

/// `aΛ(a) ≈ P(a)/Q(a)` (Horner, `f32`) for `0 ≤ a ≤ AREA_CUT`; the caller
/// handles `a > AREA_CUT` (where the rational is not fitted).
#[inline(always)]
pub(crate) fn a_lambda_rational<T: F32Arith>(a: T) -> T {
    let k = T::splat;
    let mut p = k(AREA_P[6]);
    let mut q = k(AREA_Q[6]);
    for i in (0..6).rev() {
        p = p * a + k(AREA_P[i]);
        q = q * a + k(AREA_Q[i]);
    }
    p / q
}

/// `A = cos θ (1 + Λ)` of Beckmann with roughness `alpha`, from `cos θ ≥ 0`
/// and `sin²θ` of a unit direction: `cos θ + α sin θ · P(a)/Q(a)` with
/// `a = cos θ/(α sin θ)`, `cos θ` for `a ≥ AREA_CUT` and at normal incidence
/// (`α sin θ = 0`). At grazing (`cos θ = 0`) `A = α sin θ/(2√π)`, the limit.
/// Finite and `≥ cos θ` for finite input; ≤ 3 ulp from the exact value.
#[inline(always)]
pub(crate) fn area(alpha: f32, cos_theta: f32, sin2: f32) -> f32 {
    let alpha_s = alpha * libm::sqrtf(sin2);
    let a = cos_theta / alpha_s;
    // `!(a < CUT)` also takes `alpha_s = 0` (a = +∞, or NaN for 0/0).
    if !(a < AREA_CUT) {
        return cos_theta;
    }
    cos_theta + alpha_s * a_lambda_rational(a)
}

/// [`area`] lane-wise, bit for bit.
#[cfg(feature = "simd")]
#[inline(always)]
pub(crate) fn area_v(alpha: f32, cos_theta: crate::simd::Vf, sin2: crate::simd::Vf) -> crate::simd::Vf {
    use crate::simd::Vf;
    let alpha_s = Vf::splat(alpha) * sin2.sqrt();
    let a = cos_theta / alpha_s;
    let inside = a.simd_lt(Vf::splat(AREA_CUT));
    // Outside lanes (a ≥ CUT, +∞, NaN) evaluate a harmless `a = 0`.
    let r = a_lambda_rational(inside.select(a, Vf::ZERO));
    inside.select(cos_theta + alpha_s * r, cos_theta)
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    /// `Λ(a)` in `f64` from libm's `f64` `erfc` (the erf form of Heitz 2014,
    /// eq. 80), independent of the fit; its cancellation costs ≤ 2a² `f64`
    /// ulps, far below `f32` resolution for `a ≤ 10`.
    fn lambda64(a: f64) -> f64 {
        0.5 * (libm::exp(-a * a) / (a * core::f64::consts::PI.sqrt()) - libm::erfc(a))
    }

    /// `A = cos θ(1 + Λ)` in `f64` at the given `f32` inputs.
    fn area64(alpha: f32, c: f32, s2: f32) -> f64 {
        let (c, s) = (c as f64, (s2 as f64).sqrt());
        if s == 0.0 {
            return c;
        }
        if c == 0.0 {
            return alpha as f64 * s / (2.0 * core::f64::consts::PI.sqrt());
        }
        let a = c / (alpha as f64 * s);
        c * (1.0 + lambda64(a))
    }

    fn ulps(v: f32, r: f64) -> f64 {
        let e = libm::floor(libm::log2(r.abs().max(f32::MIN_POSITIVE as f64)));
        (v as f64 - r).abs() / libm::exp2(e - 23.0)
    }

    /// `A` against the `f64` reference on a dense grid of θ (uniform and
    /// geometric towards both ends) for roughnesses over the whole range:
    /// ≤ 3 ulp. Also `1 + Λ = A/cos θ` to the same relative accuracy (it is
    /// the same quantity) and `A ≥ cos θ`.
    #[test]
    fn area_matches_f64() {
        let mut worst = 0.0f64;
        let mut thetas: std::vec::Vec<f64> = (0..=40_000)
            .map(|i| i as f64 / 40_000.0 * core::f64::consts::FRAC_PI_2)
            .collect();
        let mut t = 1e-12f64;
        while t < 0.5 {
            thetas.push(t);
            thetas.push(core::f64::consts::FRAC_PI_2 - t);
            t *= 1.05;
        }
        for &alpha in &[1e-4f32, 1e-3, 0.01, 0.05, 0.1, 0.3, 0.5, 0.77, 1.0] {
            for &theta in &thetas {
                let (c, s) = (libm::cos(theta) as f32, libm::sin(theta) as f32);
                let s2 = s * s;
                let v = area(alpha, c, s2);
                let r = area64(alpha, c, s2);
                assert!(v.is_finite() && v >= c, "α={alpha} θ={theta}: {v}");
                let e = ulps(v, r);
                worst = worst.max(e);
                assert!(e <= 3.0, "α={alpha} θ={theta}: A = {v} vs {r} ({e:.2} ulp)");
            }
        }
        // Edges: normal incidence, grazing (the limit α/(2√π)).
        assert_eq!(area(0.3, 1.0, 0.0), 1.0);
        let g = area(0.3, 0.0, 1.0) as f64;
        assert!((g / (0.3 / (2.0 * core::f64::consts::PI.sqrt())) - 1.0).abs() < 2e-7, "{g}");
        std::println!("Beckmann A = cos θ(1 + Λ) in f32: worst {worst:.2} ulp");
    }

    /// The dropped tail: at the cut-off `Λ < 2⁻²⁶`, and the rational there
    /// agrees with the exact `aΛ` to well below `ε a`.
    #[test]
    fn cut_off_is_below_resolution() {
        let l = lambda64(AREA_CUT as f64);
        assert!(l < libm::exp2(-26.0), "Λ(cut) = {l}");
        let r = a_lambda_rational(AREA_CUT) as f64;
        let exact = AREA_CUT as f64 * l;
        assert!((r - exact).abs() < 1e-7 * AREA_CUT as f64, "{r} vs {exact}");
    }

    /// The vector form is the scalar one bit for bit.
    #[cfg(feature = "simd")]
    #[test]
    fn area_lanes_are_scalar_bit_for_bit() {
        use crate::simd::{LANES, Vf};
        let mut cs = std::vec::Vec::new();
        for i in 0..=20_000 {
            let theta = i as f64 / 20_000.0 * core::f64::consts::FRAC_PI_2;
            cs.push((libm::cos(theta) as f32, (libm::sin(theta) as f32).powi(2)));
        }
        cs.extend([(1.0, 0.0), (0.0, 1.0), (1e-30, 1.0), (1.0, 1e-45)]);
        for &alpha in &[1e-4f32, 0.3, 1.0] {
            for chunk in cs.chunks(LANES) {
                let mut c = [1.0f32; LANES];
                let mut s = [0.0f32; LANES];
                for (k, &(ck, sk)) in chunk.iter().enumerate() {
                    c[k] = ck;
                    s[k] = sk;
                }
                let v = area_v(alpha, Vf::new(c), Vf::new(s)).to_array();
                for k in 0..LANES {
                    assert_eq!(v[k].to_bits(), area(alpha, c[k], s[k]).to_bits(), "{} {}", c[k], s[k]);
                }
            }
        }
    }
}
