//! `expf` lane-wise, bit for bit with `libm::expf`.

use super::Vf;
use super::bits::*;

/// `libm::expf` lane-wise, **bit for bit** (a port of its algorithm, FreeBSD
/// `e_expf.c`, with the same operations in the same order; no FMA):
///
/// * `|x| ≤ 2⁻¹⁴`: `1 + x`;
/// * otherwise `k = round(x/ln 2)` (`trunc(x/ln 2 ± 1/2)`, or `±1` for
///   `|x| ≤ 1.5 ln 2`, or `0` for `|x| ≤ ln 2/2`), `r = (x − k ln2_hi) − k ln2_lo`,
///   the Remez form `c = r − r²(P1 + r² P2)`, `y = 1 + (r c/(2 − c) − lo + hi)`
///   and `scalbnf(y, k)` — a product by `2^k` with one rounding, formed here
///   as `(y · 2^{k₁}) · 2^{k₂}` with an exact first factor;
/// * `x ≥ 88.7228`: `+∞`; `x ≤ −103.972`: `0`; NaN: NaN.
///
/// The `brdfs` unit test `expf_is_libm_bit_for_bit` compares it with
/// `libm::expf` on every `f32` in `[−104, 89]` with a stride and on the
/// special values.
#[inline(always)]
pub(crate) fn expf(x: Vf) -> Vf {
    // libm's constants, by their bits.
    const LN2_HI: f32 = f32::from_bits(0x3f31_7200); // 6.9314575195e-01
    const LN2_LO: f32 = f32::from_bits(0x35bf_be8e); // 1.4286067653e-06
    const INV_LN2: f32 = f32::from_bits(0x3fb8_aa3b); // 1.4426950216e+00
    const P1: f32 = f32::from_bits(0x3e2a_aa8f); // 1.6666625440e-1
    const P2: f32 = f32::from_bits(0xbb35_5215); // -2.7667332906e-3
    let (zero, one) = (Vf::ZERO, Vf::ONE);
    let ax = x.abs();
    let neg = x.is_sign_negative();
    let above = |bits: u32| ax.simd_gt(Vf::splat(f32::from_bits(bits)));
    // k as a float: |x| > 1.5 ln2, |x| > ln2/2, else 0.
    let half = neg.select(Vf::splat(-0.5), Vf::splat(0.5));
    let k_big = (Vf::splat(INV_LN2) * x + half).trunc();
    let k_mid = neg.select(-one, one);
    let k = above(0x3f85_1592).select(k_big, above(0x3eb1_7218).select(k_mid, zero));
    // (For k = 0 these are hi = x, lo = 0, r = x, exactly as the scalar branch.)
    let hi = x - k * Vf::splat(LN2_HI);
    let lo = k * Vf::splat(LN2_LO);
    let r = hi - lo;
    let rr = r * r;
    let c = r - rr * (Vf::splat(P1) + rr * Vf::splat(P2));
    let y = one + (r * c / (Vf::splat(2.0) - c) - lo + hi);
    // k ∈ [−150, 128].
    let v = scalbnf(y, k);
    // Special cases, in the scalar order of precedence.
    let v = above(0x3900_0000).select(v, one + x);
    let v = (!neg & ax.simd_ge(Vf::splat(f32::from_bits(0x42b1_7218)))).select(Vf::splat(f32::INFINITY), v);
    let v = (neg & ax.simd_ge(Vf::splat(f32::from_bits(0x42cf_f1b5)))).select(zero, v);
    x.is_nan().select(x, v)
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::simd::{LANES, assert_lanes_match, check_values, sweep};
    use std::vec;

    /// `expf` equals `libm::expf` bit for bit: every 7th `f32` of
    /// `[−104, 89]` (both signs; about 150 million values), plus the special
    /// values and the thresholds of the scalar branches ± 1 ulp.
    #[test]
    fn expf_is_libm_bit_for_bit() {
        let mut specials = vec![
            0.0f32,
            -0.0,
            f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::MAX,
            f32::MIN,
            f32::MIN_POSITIVE,
            -f32::MIN_POSITIVE,
            1e-45,
            -1e-45,
            1.0,
            -1.0,
        ];
        crate::simd::push_near(
            &mut specials,
            &[
                0x3900_0000u32,
                0x3eb1_7218,
                0x3f85_1592,
                0x42ae_ac50,
                0x42b1_7218,
                0x42cf_f1b5,
            ],
            true,
        );
        let check = |xs: &[f32; LANES]| assert_lanes_match("expf", expf, libm::expf, xs);
        check_values(&check, &specials);
        sweep(&check, &[(0, 89.0), (0x8000_0000, 104.0)]);
    }
}
