//! `libm::expm1f` lane-wise, bit for bit.

use super::{Vf, Vi, fmask, from_bits, to_bits};

/// `libm::expm1f` lane-wise, **bit for bit** (a port of its algorithm,
/// FreeBSD `s_expm1f.c`, the same operations in the same order; no FMA):
///
/// * NaN: NaN; `x ≤ −27 ln 2`: `−1`; `x > 88.7217` (`ln f32::MAX`):
///   `x · 2¹²⁷` (`+∞`); `|x| < 2⁻²⁵`: `x`;
/// * otherwise `k = round(x/ln 2)` (`±1` for `ln2/2 < |x| < 1.5 ln 2`, `0`
///   for `|x| ≤ ln2/2`, else `trunc(x/ln 2 ± 1/2)`), the reduced
///   `r = hi − lo` with `hi = x − k ln2_hi`, `lo = k ln2_lo` and its
///   rounding error `c = (hi − r) − lo`;
/// * the rational form of `expm1` on `|r| ≤ 0.347` with the Remez
///   polynomial `r₁ = 1 + h(Q1 + h Q2)`, `h = r²/2`:
///   `e = h ((r₁ − t)/(6 − r t))`, `t = 3 − r₁ r/2`;
/// * `k = 0`: `r − (r e − h)`; else `e' = (r (e − c) − c) − h` and
///   `2^k (r − e' + 1) − 1` in libm's forms for `k = −1`, `k = 1`
///   (two, split at `r = −1/4`), `k ∉ [0, 56]` (with `k = 128` as
///   `((r − e' + 1) · 2) · 2¹²⁷`), `2 ≤ k < 23` and `23 ≤ k ≤ 56`.
///
/// The unit test `expm1f_is_libm_bit_for_bit` compares it with
/// `libm::expm1f` on every 7th `f32` of `[−104, 89]` and on the special
/// values and branch thresholds.
#[inline(always)]
pub(crate) fn expm1f(x: Vf) -> Vf {
    // libm's constants, by their bits.
    const LN2_HI: f32 = f32::from_bits(0x3f31_7180); // 6.9313812256e-01
    const LN2_LO: f32 = f32::from_bits(0x3717_f7d1); // 9.0580006145e-06
    const INV_LN2: f32 = f32::from_bits(0x3fb8_aa3b); // 1.4426950216e+00
    const Q1: f32 = f32::from_bits(0xbd08_8868); // -3.3333212137e-2
    const Q2: f32 = f32::from_bits(0x3acf_3010); // 1.5807170421e-3
    let si = |v: i32| Vi::splat(v);
    let sp = |v: f32| Vf::splat(v);
    let (zero, one) = (Vf::ZERO, Vf::ONE);
    let hx = to_bits(x) & si(0x7fff_ffff);
    let neg = x.is_sign_negative();
    let above = |bits: i32| fmask(hx.simd_gt(si(bits)));
    // k as a float: |x| ≥ 1.5 ln2 (rounded quotient), > ln2/2 (±1), else 0.
    let k_big = (sp(INV_LN2) * x + neg.select(sp(-0.5), sp(0.5))).trunc();
    let k_mid = neg.select(-one, one);
    let k = above(0x3f85_1591).select(k_big, above(0x3eb1_7218).select(k_mid, zero));
    // k ln2_hi is exact; for k = ±1 these are libm's x ∓ ln2_hi and ±ln2_lo,
    // for k = 0 they leave x unchanged with c = 0.
    let hi = x - k * sp(LN2_HI);
    let lo = k * sp(LN2_LO);
    let r = hi - lo;
    let c = (hi - r) - lo;
    let hfx = sp(0.5) * r;
    let hxs = r * hfx;
    let r1 = one + hxs * (sp(Q1) + hxs * sp(Q2));
    let t = sp(3.0) - r1 * hfx;
    let e = hxs * ((r1 - t) / (sp(6.0) - r * t));
    let v_k0 = r - (r * e - hxs);
    let tiny = fmask(hx.simd_lt(si(0x3300_0000)));
    if k.simd_eq(zero).all() {
        // Every lane has |x| ≤ ln2/2 (so it is neither NaN nor out of
        // range): only libm's `k = 0` form and its tiny-argument case.
        return tiny.select(x, v_k0);
    }
    let e = r * (e - c) - c;
    let e = e - hxs;
    let v_m1 = sp(0.5) * (r - e) - sp(0.5);
    let v_p1 = r
        .simd_lt(sp(-0.25))
        .select(sp(-2.0) * (e - (r + sp(0.5))), one + sp(2.0) * (r - e));
    // 2^k and 2^−k by their bits (garbage on the lanes that do not use them).
    let ki = k.trunc_int();
    let twopk = from_bits((ki + si(0x7f)) << 23_u32);
    let uf = from_bits((si(0x7f) - ki) << 23_u32);
    let y = r - e + one;
    let at_max = k.simd_eq(sp(128.0));
    let y = at_max.select(y * sp(2.0) * sp(f32::from_bits(0x7f00_0000)), y * twopk);
    let v_far = y - one;
    let v_small = (r - e + (one - uf)) * twopk;
    let v_large = (r - (e + uf) + one) * twopk;
    let v = k.simd_lt(sp(23.0)).select(v_small, v_large);
    let v = (k.simd_lt(zero) | k.simd_gt(sp(56.0))).select(v_far, v);
    let v = k.simd_eq(one).select(v_p1, v);
    let v = k.simd_eq(-one).select(v_m1, v);
    let v = k.simd_eq(zero).select(v_k0, v);
    // Special cases, in the scalar order of precedence.
    let v = tiny.select(x, v);
    let v = (!neg & above(0x42b1_7217)).select(x * sp(f32::from_bits(0x7f00_0000)), v);
    let v = (neg & above(0x4195_b843)).select(-one, v);
    x.is_nan().select(x, v)
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::super::LANES;
    use super::*;

    /// Every 7th `f32` of `[−104, 89]` (both signs; about 150 million
    /// values), every 7919th one beyond, and the special values and branch
    /// thresholds ± 2 ulp.
    #[test]
    fn expm1f_is_libm_bit_for_bit() {
        let check = |xs: &[f32; LANES]| crate::simd::assert_lanes_match("expm1f", expm1f, libm::expm1f, xs);
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
            -f32::MIN_POSITIVE,
            1e-45,
            -1e-45,
            -0.25,
        ];
        crate::simd::push_near(
            &mut specials,
            &[
                0x3300_0000u32,
                0x3eb1_7218,
                0x3f85_1592,
                0x4195_b844,
                0x42b1_7217,
                0x0080_0000,
            ],
            true,
        );
        crate::simd::check_values(&check, &specials);
        let sweep =
            |sign: u32, end: f32, stride: u32| crate::simd::sweep_stride(&check, &[(sign, end)], stride);
        sweep(0, 89.0, crate::simd::dense_stride());
        sweep(0x8000_0000, 104.0, crate::simd::dense_stride());
        sweep(0, f32::MAX, 7919);
        sweep(0x8000_0000, f32::MAX, 7919);
    }
}
