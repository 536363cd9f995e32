//! `libm::logf` lane-wise, bit for bit.

use super::{Vf, Vi, fmask, from_bits, int_to_float, to_bits};

// libm's constants of `logf`/`log1pf`, by their bits.
pub(super) const LN2_HI: f32 = f32::from_bits(0x3f31_7180); // 6.9313812256e-01
pub(super) const LN2_LO: f32 = f32::from_bits(0x3717_f7d1); // 9.0580006145e-06
const LG1: f32 = f32::from_bits(0x3f2a_aaaa); // 0.66666662693
const LG2: f32 = f32::from_bits(0x3ecc_ce13); // 0.40000972152
const LG3: f32 = f32::from_bits(0x3e91_e9ee); // 0.28498786688
const LG4: f32 = f32::from_bits(0x3e78_9e26); // 0.24279078841

/// The reduced-argument core shared by [`logf`] and
/// [`log1pf`](super::log1pf::log1pf): for `f = m − 1`, `s = f/(2 + f)` and the
/// Remez polynomial `R = s²(Lg1 + s⁴Lg3) + s⁴(Lg2 + s⁴Lg4)`, returns
/// `(s (f²/2 + R), f²/2)` in libm's operation order (each caller adds its
/// own `k ln2` and correction terms around them).
#[inline(always)]
pub(super) fn log_kernel(f: Vf) -> (Vf, Vf) {
    let s = f / (Vf::splat(2.0) + f);
    let z = s * s;
    let w = z * z;
    let t1 = w * (Vf::splat(LG2) + w * Vf::splat(LG4));
    let t2 = z * (Vf::splat(LG1) + w * Vf::splat(LG3));
    let r = t2 + t1;
    let hfsq = Vf::splat(0.5) * f * f;
    (s * (hfsq + r), hfsq)
}

/// `libm::logf` lane-wise, **bit for bit** (a port of its algorithm,
/// FreeBSD `e_logf.c`, the same operations in the same order; no FMA):
///
/// * `x = ±0`: `−∞`; `x < 0` (and NaN with the sign bit): NaN; `+∞`, NaN:
///   `x`; `x = 1`: `+0`;
/// * subnormal `x` is prescaled by `2²⁵` (exact), with `k = −25`;
/// * `x = 2^k (1 + f)` with `1 + f ∈ [√2/2, √2)`, split by integer operations
///   on the bits (`ix + (0x3f800000 − 0x3f3504f3)` carries into the exponent
///   exactly when the mantissa is at least that of `√2/2`);
/// * `s = f/(2 + f)`, the Remez polynomial `R(s²) = s²(Lg1 + s⁴Lg3) +
///   s⁴(Lg2 + s⁴Lg4)` (`|(log(1+s) − log(1−s))/s − Lg(s)| < 2⁻³⁴·²⁴`) and
///   `log x = (((s (f²/2 + R) + k ln2_lo) − f²/2) + f) + k ln2_hi`.
///
/// The unit test `logf_is_libm_bit_for_bit` compares it with `libm::logf`
/// on every 7th `f32` of `[0, f32::MAX]`, on negative values and on the
/// special values.
#[inline(always)]
pub(crate) fn logf(x: Vf) -> Vf {
    let si = |v: i32| Vi::splat(v);
    let zero = Vf::ZERO;
    let one = Vf::ONE;
    // Subnormal (and zero, negative: overridden below) lanes: scale by 2²⁵.
    let ix0 = to_bits(x);
    let sub = ix0.simd_lt(si(0x0080_0000));
    let xs = fmask(sub).select(x * Vf::splat(f32::from_bits(0x4c00_0000)), x);
    let ix = to_bits(xs) + si(0x3f80_0000 - 0x3f35_04f3);
    let k = ((ix >> 23_u32) - si(0x7f)) + sub.select(si(-25), si(0));
    let m = from_bits((ix & si(0x007f_ffff)) + si(0x3f35_04f3));
    let f = m - one;
    let (sr, hfsq) = log_kernel(f);
    let dk = int_to_float(k);
    let v = sr + dk * Vf::splat(LN2_LO) - hfsq + f + dk * Vf::splat(LN2_HI);
    // Special cases, in the scalar order of precedence.
    let v = x.simd_eq(one).select(zero, v);
    let v = fmask(ix0.simd_ge(si(0x7f80_0000))).select(x, v);
    let v = fmask(ix0.simd_lt(si(0))).select(Vf::splat(f32::NAN), v);
    x.simd_eq(zero).select(Vf::splat(f32::NEG_INFINITY), v)
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::super::LANES;
    use super::*;

    /// Every 7th `f32` of `[0, f32::MAX]` (about 305 million values, with the
    /// subnormals), every 7919th negative one, and the special values and
    /// the reduction thresholds ± 2 ulp.
    #[test]
    fn logf_is_libm_bit_for_bit() {
        let check = |xs: &[f32; LANES]| crate::simd::assert_lanes_match("logf", logf, libm::logf, xs);
        let mut specials = std::vec![
            0.0f32,
            -0.0,
            f32::NAN,
            -f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::MAX,
            f32::MIN,
            f32::MIN_POSITIVE,
            1e-45,
            -1e-45,
            -1.0,
            2.0,
            0.5,
        ];
        crate::simd::push_near(
            &mut specials,
            &[0x3f80_0000u32, 0x3f35_04f3, 0x3fb5_04f3, 0x0080_0000, 0x7f80_0000],
            false,
        );
        crate::simd::check_values(&check, &specials);
        // [0, f32::MAX] by 7, then the negatives from −0 to −∞ by 7919.
        crate::simd::sweep_stride(&check, &[(0, f32::MAX)], crate::simd::dense_stride());
        crate::simd::sweep_stride(&check, &[(0x8000_0000, f32::INFINITY)], 7919);
    }
}
