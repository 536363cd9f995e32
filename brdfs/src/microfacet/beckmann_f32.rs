//! The hot path of the Beckmann BRDF in `f32` (`eval`, `pdf`, the weight
//! of `sample`, and their vector kernels): the projected area
//! `A = cos θ (1 + Λ)` without an exponential, and `D` with one `f32`
//! exponential ([`d`]).
//!
//! # Projected area
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
//! `[0, AREA_CUT]`, fitted by `brdfs/tools/fit_beckmann_f32.py` (weighted
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
/// documentation; `fit_beckmann_f32.py`).
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
    + core::ops::Sub<Output = Self>
    + core::ops::Mul<Output = Self>
    + core::ops::Div<Output = Self>
{
    /// The constant in every lane.
    fn splat(c: f32) -> Self;
    /// `2^{−k}` where `k ∈ [0, 126]` sits in the low 8 mantissa bits of `t`
    /// (`t = k + 1.5·2²³`); other bits give unspecified finite values.
    fn pow2_neg_from_shifted(t: Self) -> Self;
}

impl F32Arith for f32 {
    #[inline(always)]
    fn splat(c: f32) -> f32 {
        c
    }

    #[inline(always)]
    fn pow2_neg_from_shifted(t: f32) -> f32 {
        f32::from_bits(127u32.wrapping_sub(t.to_bits() & 0xff) << 23)
    }
}

/// The `i32` vector of the width of [`Vf`](crate::simd::Vf).
#[cfg(all(feature = "simd", target_feature = "avx512f"))]
type Vi = wide::i32x16;
#[cfg(all(feature = "simd", not(target_feature = "avx512f")))]
type Vi = wide::i32x8;
// The two widths are chosen by separate `cfg`s: the build fails if they disagree.
#[cfg(feature = "simd")]
const _: () = assert!(core::mem::size_of::<Vi>() == core::mem::size_of::<crate::simd::Vf>());

#[cfg(feature = "simd")]
impl F32Arith for crate::simd::Vf {
    #[inline(always)]
    fn splat(c: f32) -> Self {
        crate::simd::Vf::splat(c)
    }

    #[inline(always)]
    fn pow2_neg_from_shifted(t: Self) -> Self {
        let bits: Vi = wide::bytemuck::cast(t);
        wide::bytemuck::cast((Vi::splat(127) - (bits & Vi::splat(0xff))) << 23_u32)
    }
}

// ------------------------------------------------------------------ D

/// `e^r ≈ Σ c_k r^k` on `|r| ≤ ln2/2`: the degree-6 minimax polynomial of
/// [`exp_neg64`](super::special::exp_neg64) (relative error 1.9·10⁻⁹)
/// rounded to `f32` (adds < 2·10⁻⁸).
const EXP_POLY32: [f32; 7] = {
    let c = super::special::EXP_POLY;
    [
        c[0] as f32,
        c[1] as f32,
        c[2] as f32,
        c[3] as f32,
        c[4] as f32,
        c[5] as f32,
        c[6] as f32,
    ]
};

/// `ln 2` split for Cody–Waite reduction: `LN2_HI` has 16 significant
/// bits, so `k · LN2_HI` is exact for `k < 2⁸`.
const LN2_HI: f32 = 0.693_145_75;
const LN2_LO: f32 = 1.428_606_8e-6;

/// `1.5·2²³`: adding it rounds an `f32` below 2²² to an integer in the low
/// mantissa bits.
const SHIFTER: f32 = 12_582_912.0;

/// Beyond `x = 87`, `e^{−x} < 1.7·10⁻³⁸` is flushed to 0 by the callers.
pub(crate) const EXP_NEG_MAX: f32 = 87.0;

/// `e^{−x}` in `f32` for `0 ≤ x ≤ EXP_NEG_MAX` (Cody & Waite 1980,
/// *Software Manual for the Elementary Functions*, ch. 6: `x = k ln2 + r`,
/// `|r| ≤ ln2/2`, `e^{−x} = 2^{−k} e^{−r}`), division-free: `k` rounded
/// with the `1.5·2²³` shifter, `r` by the two-part `ln 2`, `e^{−r}` by
/// [`EXP_POLY32`] (Estrin), `2^{−k}` from its bits. The callers select 0
/// outside the range (there the value is unspecified, never a panic).
/// ≤ 2 ulp (measured 1.51; unit test `exp_neg_f32_matches_libm`).
#[inline(always)]
pub(crate) fn exp_neg<T: F32Arith>(x: T) -> T {
    let k = T::splat;
    let t = x * k(core::f32::consts::LOG2_E) + k(SHIFTER);
    let kf = t - k(SHIFTER);
    let r = (x - kf * k(LN2_HI)) - kf * k(LN2_LO);
    // e^{−r} = Σ c_k (−r)^k = c₀ − r q(r): `q` by Estrin's scheme (a
    // shorter dependency chain than Horner), then one final step, so the
    // leading term is rounded once.
    let c = &EXP_POLY32;
    let r2 = r * r;
    let r4 = r2 * r2;
    let q = ((k(c[1]) - k(c[2]) * r) + r2 * (k(c[3]) - k(c[4]) * r)) + r4 * (k(c[5]) - k(c[6]) * r);
    (k(c[0]) - r * q) * T::pow2_neg_from_shifted(t)
}

/// `D(m) = exp(−tan²θm/α²) / (π α² cos⁴θm)` (Walter et al. 2007, eq. 25)
/// in `f32` from the squares `hz2 = h_z²`, `hxy2 = h_x² + h_y²` of any
/// nonzero vector `h` along `m` (the arithmetic shared by the scalar and the
/// vector form; homogeneous of degree 0): with `τ = tan²θm = h_xy²/h_z²`,
/// `u = 1/cos²θm = 1 + τ`, `x = τ · (1/α²)`,
/// `D = ((e^{−x} · (1/(πα²))) u) u`, with `e^{−x}` of [`exp_neg`] and `0`
/// for `x > EXP_NEG_MAX` or NaN (where `D < 1.7·10⁻³⁸/(πα² cos⁴θm)`).
/// `inv_a2 = 1/α²` and `k = 1/(πα²)` come from [`d_consts`]. The caller
/// maps NaN (`0·∞` at `h_z² = 0`) to 0 and `+∞` to `f32::MAX`.
#[inline(always)]
fn d_parts<T: F32Arith>(inv_a2: T, k: T, hz2: T, hxy2: T) -> (T, T) {
    let tan2 = hxy2 / hz2;
    let u = T::splat(1.0) + tan2;
    let x = tan2 * inv_a2;
    ((exp_neg(x) * k * u) * u, x)
}

/// `(1/α², 1/(π α²))` rounded to `f32` once each (from `f64`).
#[inline(always)]
pub(crate) fn d_consts(alpha: f32) -> (f32, f32) {
    let a2 = alpha as f64 * alpha as f64;
    ((1.0 / a2) as f32, (core::f64::consts::FRAC_1_PI / a2) as f32)
}

/// Beckmann `D` from the squares `h_z²`, `h_x² + h_y²` of a vector along
/// the normal (unit or not; see [`d_parts`]) in `f32`, given [`d_consts`]
/// of `α`; finite and `≥ 0` (0 at `h_z² = 0`). Relative error
/// ≤ `4 + 3x` ulp at `x = tan²θm/α²` (the rounding of `x` is amplified
/// by `e^{−x}`; unit test `d_matches_f64`).
#[inline(always)]
pub(crate) fn d((inv_a2, k): (f32, f32), hz2: f32, hxy2: f32) -> f32 {
    let (v, x) = d_parts(inv_a2, k, hz2, hxy2);
    if x > EXP_NEG_MAX || x.is_nan() {
        return 0.0;
    }
    super::finite_nonneg(v)
}

/// [`d`] lane-wise, bit for bit.
#[cfg(feature = "simd")]
#[inline(always)]
pub(crate) fn d_v((inv_a2, k): (f32, f32), hz2: crate::simd::Vf, hxy2: crate::simd::Vf) -> crate::simd::Vf {
    use crate::simd::Vf;
    let (v, x) = d_parts(Vf::splat(inv_a2), Vf::splat(k), hz2, hxy2);
    x.simd_le(Vf::splat(EXP_NEG_MAX))
        .select(crate::simd::finite_nonneg(v), Vf::ZERO)
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
    let alpha_s = alpha * radiometry::math::sqrtf(sin2);
    let a = cos_theta / alpha_s;
    // Also `alpha_s = 0` (a = +∞, or NaN for 0/0).
    if a >= AREA_CUT || a.is_nan() {
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
        assert!(
            (g / (0.3 / (2.0 * core::f64::consts::PI.sqrt())) - 1.0).abs() < 2e-7,
            "{g}"
        );
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

    /// `exp_neg` against libm's `f64` `exp` over `[0, EXP_NEG_MAX]`: ≤ 2 ulp.
    #[test]
    fn exp_neg_f32_matches_libm() {
        let mut worst = 0.0f64;
        for i in 0..=2_000_000 {
            let x = i as f32 * (EXP_NEG_MAX / 2_000_000.0);
            let r = libm::exp(-(x as f64));
            let e = ulps(exp_neg(x), r);
            worst = worst.max(e);
            assert!(e <= 2.0, "e^-{x}: {} vs {r} ({e:.2} ulp)", exp_neg(x));
        }
        assert_eq!(exp_neg(0.0f32), 1.0);
        std::println!("exp_neg (f32): worst {worst:.2} ulp");
    }

    /// `D` against Walter et al. eq. 25 in `f64` at the same `f32` squares
    /// `h_z² = cos²θ`, `h_xy² = sin²θ` (of a direction `h` unit to rounding,
    /// the reference taking `cos²θm = h_z²/(h_z² + h_xy²)`): relative error ≤ `4 + 3x` ulp, `x = tan²θm/α²`
    /// (the argument of the exponential is formed in `f32`, and `e^{−x}`
    /// amplifies its relative rounding by `x`); 0 exactly where `x > 87`;
    /// finite and `≥ 0` everywhere, `0` at `cos²θm = 0`.
    #[test]
    fn d_matches_f64() {
        let mut worst = 0.0f64;
        let mut worst_small_x = 0.0f64;
        for &alpha in &[1e-4f32, 1e-3, 0.01, 0.1, 0.3, 0.77, 1.0] {
            for i in 0..=20_000 {
                let theta = i as f64 / 20_000.0 * core::f64::consts::FRAC_PI_2;
                let (c, s) = (libm::cos(theta) as f32, libm::sin(theta) as f32);
                let (c2, s2) = (c * c, s * s);
                let v = d(d_consts(alpha), c2, s2);
                assert!(v.is_finite() && v >= 0.0, "α={alpha} θ={theta}: {v}");
                let a2 = alpha as f64 * alpha as f64;
                // The squares of a vector that is unit only to rounding:
                // `cos²θm = c2/(c2 + s2)` exactly.
                let x = s2 as f64 / (c2 as f64 * a2);
                let u = (c2 as f64 + s2 as f64) / c2 as f64;
                let r = libm::exp(-x) * u * u / (core::f64::consts::PI * a2);
                if x > EXP_NEG_MAX as f64 * (1.0 + 1e-6) {
                    assert_eq!(v, 0.0);
                    continue;
                }
                if r.is_nan() || r < f32::MIN_POSITIVE as f64 || x > EXP_NEG_MAX as f64 * (1.0 - 1e-6) {
                    continue;
                }
                let e = ulps(v, r);
                let bound = 4.0 + 3.0 * x;
                worst = worst.max(e / bound);
                if x <= 1.0 {
                    worst_small_x = worst_small_x.max(e);
                }
                assert!(
                    e <= bound,
                    "α={alpha} θ={theta} x={x}: D = {v} vs {r} ({e:.2} ulp)"
                );
            }
        }
        assert_eq!(d(d_consts(0.3), 0.0, 1.0), 0.0);
        assert_eq!(d(d_consts(0.3), 0.0, 0.0), 0.0);
        assert_eq!(d(d_consts(1e-4), 1e-30, 1.0), 0.0);
        let peak = d(d_consts(1e-4), 1.0, 0.0) as f64;
        assert!((peak * core::f64::consts::PI * 1e-8 - 1.0).abs() < 1e-6, "{peak}");
        std::println!("D (f32): worst {worst:.2} of the bound 4 + 3x ulp; {worst_small_x:.2} ulp for x ≤ 1");
    }

    /// The whole Beckmann BRDF (height-correlated Smith, `F = 1`) against
    /// Walter et al. 2007 eq. 20 written separately in `f64` — the half
    /// vector, `D` (eq. 25) and the exact `Λ` (erf form, libm's `f64` `erfc`)
    /// from the same `f32` directions (normalised in `f64`): relative error ≤ `12 + 6x` ulp of the
    /// `f64` value, `x = tan²θh/α²` (the `f32` half vector and `D`'s
    /// exponent; see `d_matches_f64`).
    #[test]
    fn eval_matches_f64() {
        use crate::microfacet::{Beckmann, HeightCorrelated, Microfacet, NoFresnel};
        use radiometry::Brdf;
        use radiometry::glam::Vec3;
        let dir = |t: f64, p: f64| {
            Vec3::new(
                (libm::sin(t) * libm::cos(p)) as f32,
                (libm::sin(t) * libm::sin(p)) as f32,
                libm::cos(t) as f32,
            )
        };
        let lam = |alpha: f64, w: [f64; 3]| {
            let s = (w[0] * w[0] + w[1] * w[1]).sqrt();
            if s == 0.0 {
                return 0.0;
            }
            lambda64(w[2] / (alpha * s))
        };
        let mut worst = 0.0f64;
        for &alpha in &[1e-3f32, 0.05, 0.3, 0.77, 1.0] {
            let b = Microfacet::<_, HeightCorrelated, _>::new(Beckmann::new(alpha).unwrap(), NoFresnel);
            let a = alpha as f64;
            for i in 1..60 {
                for j in 1..60 {
                    let wi = dir(i as f64 / 60.0 * 1.55, 0.3);
                    let wo = dir(j as f64 / 60.0 * 1.55, 0.3 + j as f64 * 0.17);
                    let v = b.eval(wi, wo);
                    let (i64_, o64) = (wi.to_array().map(f64::from), wo.to_array().map(f64::from));
                    // The directions the `f32` vectors point along
                    // (normalised in `f64`): what `eval` evaluates — its half
                    // vector is corrected for the input lengths
                    // (`Half::of`).
                    let unit = |w: [f64; 3]| {
                        let l = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
                        [w[0] / l, w[1] / l, w[2] / l]
                    };
                    let (wi64, wo64) = (unit(i64_), unit(o64));
                    let h = [wi64[0] + wo64[0], wi64[1] + wo64[1], wi64[2] + wo64[2]];
                    let x = (h[0] * h[0] + h[1] * h[1]) / (h[2] * h[2] * a * a);
                    let c2 = h[2] * h[2] / (h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
                    let d = libm::exp(-x) / (core::f64::consts::PI * a * a * c2 * c2);
                    let g2 = 1.0 / (1.0 + lam(a, wi64) + lam(a, wo64));
                    let r = d * g2 / (4.0 * wi64[2] * wo64[2]);
                    if r < 1e-30 {
                        assert!((v as f64) < 1e-29, "α={alpha} {wi} {wo}: {v} vs {r}");
                        continue;
                    }
                    let e = ulps(v, r);
                    worst = worst.max(e / (12.0 + 6.0 * x));
                    assert!(
                        e <= 12.0 + 6.0 * x,
                        "α={alpha} {wi} {wo} x={x}: {v} vs {r} ({e:.1} ulp)"
                    );
                }
            }
        }
        std::println!("Beckmann eval vs f64: worst {worst:.2} of the bound 12 + 6x ulp");
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
                // The same pairs as (cos²θm, sin²θm) of D.
                let c2 = c.map(|c| c * c);
                let dv = d_v(d_consts(alpha), Vf::new(c2), Vf::new(s)).to_array();
                for k in 0..LANES {
                    assert_eq!(
                        v[k].to_bits(),
                        area(alpha, c[k], s[k]).to_bits(),
                        "{} {}",
                        c[k],
                        s[k]
                    );
                    assert_eq!(
                        dv[k].to_bits(),
                        d(d_consts(alpha), c2[k], s[k]).to_bits(),
                        "D {} {}",
                        c2[k],
                        s[k]
                    );
                }
            }
        }
    }
}
