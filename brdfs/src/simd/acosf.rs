//! `libm::acosf` lane-wise, bit for bit.

use super::bits::clear_low;
use super::{Vf, Vi, fmask, to_bits};

// libm's constants of `acosf` (FreeBSD `e_acosf.c`), by their bits.
const PIO2_HI: f32 = f32::from_bits(0x3fc9_0fda); // 1.5707962513e+00
const PIO2_LO: f32 = f32::from_bits(0x33a2_2168); // 7.5497894159e-08
const P_S0: f32 = f32::from_bits(0x3e2a_aa75); // 1.6666586697e-01
const P_S1: f32 = f32::from_bits(0xbd2f_13ba); // -4.2743422091e-02
const P_S2: f32 = f32::from_bits(0xbc0d_d36b); // -8.6563630030e-03
const Q_S1: f32 = f32::from_bits(0xbf34_e5ae); // -7.0662963390e-01
/// `2⁻¹²⁰`: added to the results `π/2` and `π` only to raise "inexact" in C;
/// it does not change the rounded `f32` (kept for the same operations).
const X1P_120: f32 = f32::from_bits(0x0380_0000);

/// The rational `R(z) = z (pS0 + z (pS1 + z pS2))/(1 + z qS1)` of
/// `acosf`, `(acos x − π/2 + x)/x³`-like in `z = x²` or `z = (1 − |x|)/2`.
#[inline(always)]
fn r(z: Vf) -> Vf {
    let p = z * (Vf::splat(P_S0) + z * (Vf::splat(P_S1) + z * Vf::splat(P_S2)));
    let q = Vf::ONE + z * Vf::splat(Q_S1);
    p / q
}

/// `libm::acosf` lane-wise, **bit for bit** (a port of its algorithm,
/// FreeBSD `e_acosf.c` as musl and `libm` have it, the same operations in
/// the same order; no FMA). With `R` the rational above:
///
/// * `|x| > 1` or NaN: NaN (libm: `0/(x − x)`); `x = 1`: `+0`; `x = −1`:
///   `2·pio2_hi + 2⁻¹²⁰`;
/// * `|x| ≤ 2⁻²⁶` (bits `≤ 0x32800000`): `pio2_hi + 2⁻¹²⁰`;
/// * `|x| < 1/2`: `pio2_hi − (x − (pio2_lo − x R(x²)))`;
/// * `x ≤ −1/2`: `z = (1 + x)/2`, `s = √z`,
///   `2 (pio2_hi − (s + (R(z) s − pio2_lo)))`;
/// * `x ≥ 1/2`: `z = (1 − x)/2`, `s = √z`, `df = s` with the low 12 bits
///   cleared, `c = (z − df²)/(s + df)`, `2 (df + (R(z) s + c))`.
///
/// Every branch is computed for every lane and the lane's branch selected
/// (one `R`, one square root: the `|x| < 1/2` lanes evaluate `R(x²)`, the
/// others `R((1 − |x|)/2)`; `1 + x = 1 − |x|` exactly for `x < 0`).
///
/// The unit test `acosf_is_libm_bit_for_bit` compares it with `libm::acosf`
/// on every 7th `f32` of `[−1, 1]` (with `RADIOMETRY_FULL_SWEEP=1`), on
/// values beyond `±1` and on the special values and branch thresholds.
#[inline(always)]
pub(crate) fn acosf(x: Vf) -> Vf {
    let si = |v: i32| Vi::splat(v);
    let half = Vf::splat(0.5);
    let two = Vf::splat(2.0);
    let hx = to_bits(x);
    let ix = hx & si(0x7fff_ffff);
    let negative = fmask(hx.simd_lt(si(0)));
    let small = fmask(ix.simd_lt(si(0x3f00_0000)));
    // (1 − |x|)/2: `(1 + x)·0.5` for x < 0 and `(1 − x)·0.5` for x > 0.
    let z_big = (Vf::ONE - x.abs()) * half;
    let z = small.select(x * x, z_big);
    let rz = r(z);
    // |x| < 1/2.
    let v_small = Vf::splat(PIO2_HI) - (x - (Vf::splat(PIO2_LO) - x * rz));
    // |x| ≥ 1/2.
    let s = z_big.sqrt();
    let v_neg = two * (Vf::splat(PIO2_HI) - (s + (rz * s - Vf::splat(PIO2_LO))));
    let df = clear_low(s, 0xffff_f000);
    let c = (z_big - df * df) / (s + df);
    let v_pos = two * (df + (rz * s + c));
    let v = small.select(v_small, negative.select(v_neg, v_pos));
    // The special cases, in the scalar order of precedence.
    let tiny = fmask(ix.simd_le(si(0x3280_0000)));
    let v = tiny.select(Vf::splat(PIO2_HI) + Vf::splat(X1P_120), v);
    let one = fmask(ix.simd_eq(si(0x3f80_0000)));
    let v_one = negative.select(two * Vf::splat(PIO2_HI) + Vf::splat(X1P_120), Vf::ZERO);
    let v = one.select(v_one, v);
    let out_of_range = fmask(ix.simd_gt(si(0x3f80_0000)));
    // libm's `0/(x − x)`: a NaN (its payload is not part of the contract).
    out_of_range.select(Vf::splat(f32::NAN), v)
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::super::LANES;
    use super::*;

    /// The constants are libm's decimal literals, rounded to `f32`.
    #[test]
    fn constants_are_libm_literals() {
        let parse = |t: &str| t.parse::<f32>().unwrap();
        assert_eq!(PIO2_HI, parse("1.5707962513e+00"));
        assert_eq!(PIO2_LO, parse("7.5497894159e-08"));
        assert_eq!(P_S0, parse("1.6666586697e-01"));
        assert_eq!(P_S1, parse("-4.2743422091e-02"));
        assert_eq!(P_S2, parse("-8.6563630030e-03"));
        assert_eq!(Q_S1, parse("-7.0662963390e-01"));
    }

    /// Every 7th `f32` of `[−1, 1]` (about 304 million values with
    /// `RADIOMETRY_FULL_SWEEP=1`, every 61st otherwise; both signs, the
    /// subnormals included), every 7919th beyond `±1` up to `±∞`, and the
    /// special values and branch thresholds ± 2 ulp.
    #[test]
    fn acosf_is_libm_bit_for_bit() {
        let check = |xs: &[f32; LANES]| crate::simd::assert_lanes_match("acosf", acosf, libm::acosf, xs);
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
            1.0,
            -1.0,
            0.5,
            -0.5,
        ];
        crate::simd::push_near(
            &mut specials,
            &[0x3f80_0000u32, 0x3f00_0000, 0x3280_0000, 0x0080_0000, 0x7f80_0000],
            true,
        );
        crate::simd::check_values(&check, &specials);
        let stride = crate::simd::dense_stride();
        crate::simd::sweep_stride(&check, &[(0, 1.0), (0x8000_0000, 1.0)], stride);
        // Beyond ±1 (NaN), both signs, every 7919th bit pattern up to ∞.
        let beyond: std::vec::Vec<f32> = (0x3f80_0001u32..=0x7f80_0000)
            .step_by(7919)
            .flat_map(|b| [f32::from_bits(b), -f32::from_bits(b)])
            .collect();
        crate::simd::check_values(&check, &beyond);
    }
}
