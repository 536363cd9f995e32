//! `log1pf` lane-wise, bit for bit with `libm::log1pf`.

use super::Vf;
use super::bits::*;
use super::logf::{LN2_HI, LN2_LO, log_kernel};

/// `libm::log1pf` lane-wise, **bit for bit** (a port of its algorithm,
/// FreeBSD `s_log1pf.c`, same operations in the same order; no FMA):
///
/// * `|x| < 2⁻²⁴`: `x`; `x = −1`: `−∞`; `x < −1`, NaN: NaN; `+∞`: `+∞`;
/// * `−0.2929 ≤ x < 0.4142` (`√2/2 ≤ 1 + x < √2`): `k = 0`, `f = x`, `c = 0`;
/// * otherwise `u = 1 + x` is split as `2^k (1 + f)` with `1 + f ∈ [√2/2, √2)`
///   by integer operations on its bits, and `c` is the rounding error of
///   `1 + x` divided by `u` (0 for `k ≥ 25`);
/// * `s = f/(2 + f)`, the Remez polynomial `R(s²)` (`LG1…LG4`, shared with `logf`: `log_kernel`) and
///   `log1p = s (f²/2 + R) + (k ln2_lo + c) − f²/2 + f + k ln2_hi`.
///
/// The `brdfs` unit test `log1pf_is_libm_bit_for_bit` compares it with
/// `libm::log1pf` on every 7th `f32` of `[−1, 2¹²⁸)` and on the special
/// values.
#[inline(always)]
pub(crate) fn log1pf(x: Vf) -> Vf {
    let (zero, one) = (Vf::ZERO, Vf::ONE);
    // √2/2 ≤ 1 + x < √2: no reduction.
    let k0 =
        x.simd_lt(Vf::splat(f32::from_bits(0x3ed4_13d0))) & x.simd_ge(Vf::splat(f32::from_bits(0xbe95_f619)));
    // u = 1 + x = 2^k (1 + f) by the bits of u (u > 0 on every kept lane).
    let u = one + x;
    let iu: Vi = wide::bytemuck::cast::<Vf, Vi>(u) + Vi::splat(0x3f80_0000 - 0x3f35_04f3);
    let k_int = (iu >> 23_u32) - Vi::splat(0x7f);
    let k = int_to_float(k_int);
    let c = k.simd_ge(Vf::splat(2.0)).select(one - (u - x), x - (u - one)) / u;
    let c = k.simd_lt(Vf::splat(25.0)).select(c, zero);
    let m: Vf = wide::bytemuck::cast((iu & Vi::splat(0x007f_ffff)) + Vi::splat(0x3f35_04f3));
    let f = k0.select(x, m - one);
    let c = k0.select(zero, c);
    let dk = k0.select(zero, k);
    let (sr, hfsq) = log_kernel(f);
    let v = sr + (dk * Vf::splat(LN2_LO) + c) - hfsq + f + dk * Vf::splat(LN2_HI);
    // Special cases, in the scalar order of precedence.
    let v = x
        .abs()
        .simd_lt(Vf::splat(f32::from_bits(0x3380_0000)))
        .select(x, v);
    let v = x.simd_eq(Vf::splat(f32::INFINITY)).select(x, v);
    let v = x.simd_eq(-one).select(Vf::splat(f32::NEG_INFINITY), v);
    (x.simd_lt(-one) | x.is_nan()).select(Vf::splat(f32::NAN), v)
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::simd::{LANES, assert_lanes_match, check_values, sweep};
    use std::vec;

    /// `log1pf` equals `libm::log1pf` bit for bit: every 7th `f32` of
    /// `[−1, f32::MAX]` (about 300 million values), the special values and
    /// the branch thresholds ± 2 ulp.
    #[test]
    fn log1pf_is_libm_bit_for_bit() {
        let mut specials = vec![
            0.0f32,
            -0.0,
            f32::NAN,
            -f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::MAX,
            f32::MIN,
            -1.0,
            -1.0 - f32::EPSILON,
            -1.0 + f32::EPSILON / 2.0,
            -2.0,
            1e-45,
            -1e-45,
            f32::MIN_POSITIVE,
            -f32::MIN_POSITIVE,
        ];
        crate::simd::push_near(
            &mut specials,
            &[
                0x3380_0000u32,
                0x3ed4_13d0,
                0xbe95_f619,
                0x3f80_0000,
                0x4b80_0000,
                0x4c00_0000,
            ],
            true,
        );
        let check = |xs: &[f32; LANES]| assert_lanes_match("log1pf", log1pf, libm::log1pf, xs);
        check_values(&check, &specials);
        sweep(&check, &[(0, f32::MAX), (0x8000_0000, 1.0)]);
    }
}
