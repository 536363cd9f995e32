//! Vector forms (feature `simd`) of the special functions the Beckmann
//! sampler calls, lane for lane the scalar functions of `special.rs`
//! (bit-identical: the `f64` arithmetic is the same generic code, the bit
//! manipulation the same per lane).

use super::special::{
    ERFC_MAX_SLOPE, ERFINV_CENTRAL, ERFINV_TAIL1, ERFINV_TAIL2, MAX_SLOPE, SQRT_HALF_BITS, TAIL1_CENTRE,
    TAIL2_CENTRE, beckmann_s64, erfcx64_any, exp_neg64_v, ln64_poly, poly7, poly8, poly9,
};
use crate::simd::{Vd, Vf, narrow, widen};

/// `f` on the two `f64` halves of `x`, rounded back to `f32`.
#[inline(always)]
fn via64(x: Vf, f: impl Fn(Vd) -> Vd) -> Vf {
    let h = widen(x);
    narrow([f(h[0]), f(h[1])])
}

/// The `u64` vector of the same width as [`Vd`].
#[cfg(target_feature = "avx512f")]
type Vu64 = wide::u64x8;
#[cfg(not(target_feature = "avx512f"))]
type Vu64 = wide::u64x4;
// The two widths are chosen by separate `cfg`s: the build fails if they disagree.
const _: () = assert!(core::mem::size_of::<Vu64>() == core::mem::size_of::<Vd>());

/// `ln64` lane-wise: the split `x = 2^k m` of the scalar `ln64` in integer
/// vector operations, then the shared polynomial. With `t = bits(x) −
/// bits(√½)` (wrapping), `k = t >> 52` (arithmetic) is formed without a
/// signed shift: `k << 52 = t & 0xfff0…0`, and `k + 1024 = (t + 2⁶²) >> 52`
/// (logical; `t ≥ −2⁶²` for every positive `x`), converted exactly through
/// the bits of `2⁵² + k + 1024`. Lanes with `x ≤ 0` or NaN give
/// unspecified finite-or-NaN values (as the scalar), never a panic.
#[inline(always)]
pub(super) fn ln64_v(x: Vd) -> Vd {
    let u = |c: u64| Vu64::splat(c);
    let bits: Vu64 = wide::bytemuck::cast(x);
    let t = bits - u(SQRT_HALF_BITS);
    let m: Vd = wide::bytemuck::cast(bits - (t & u(0xfff0_0000_0000_0000)));
    let kb = (t + u(1 << 62)) >> 52_u32;
    let k: Vd = wide::bytemuck::cast(kb | u(0x4330_0000_0000_0000));
    let k = k - Vd::splat(4_503_599_627_371_520.0); // 2⁵² + 1024
    ln64_poly(k, m)
}

/// `lnf` lane-wise: `ln64` of the widened lanes, rounded to `f32`.
#[inline(always)]
pub(super) fn lnf_v(x: Vf) -> Vf {
    via64(x, ln64_v)
}

/// `exp_neg_sq` lane-wise: `e^{−x²}` in `f64` (exact square), rounded.
#[inline(always)]
pub(super) fn exp_neg_sq_v(x: Vf) -> Vf {
    via64(x, |x| exp_neg64_v(x * x))
}

/// `erfcx` lane-wise for `y ≤ ERFC_ZERO` (the rational branch; the
/// samplers pass `|x| ≤ MAX_SLOPE`): `P(y)/Q(y)` of `max(y, 0)` in `f64`.
#[inline(always)]
pub(super) fn erfcx_v(y: Vf) -> Vf {
    via64(y.max(Vf::ZERO), erfcx64_any)
}

/// `beckmann_s` lane-wise for `0 ≤ a ≤ MAX_SLOPE` (below `LAMBDA_ZERO_A`,
/// the samplers' range).
#[inline(always)]
pub(super) fn beckmann_s_v(a: Vf) -> Vf {
    via64(a.max(Vf::ZERO), beckmann_s64)
}

/// `erfcinv_upper` lane-wise: `y ≥ 0` with `erfc(y) = q` for
/// `q ∈ [0, 1]`; `MAX_SLOPE` for `q < erfc(9)` and NaN, `0` for `q ≥ 1`.
/// Every lane evaluates the central polynomial; the two tail pieces (and
/// `√w`) only when some lane of the half needs them (`w ≥ 5`, i.e.
/// `q < 0.0067`: rare for uniform `p`), and a select keeps the piece the
/// scalar branches pick.
#[inline(always)]
fn erfcinv_upper_v(q: Vf) -> Vf {
    let y = via64(q, |q| {
        let w = -ln64_v(q * (Vd::splat(2.0) - q));
        let central = (Vd::ONE - q) * poly9(&ERFINV_CENTRAL, w - Vd::splat(2.5));
        let is_central = w.simd_lt(Vd::splat(5.0));
        if is_central.all() {
            return central;
        }
        let s = w.sqrt();
        let t1 = poly7(&ERFINV_TAIL1, s - Vd::splat(TAIL1_CENTRE));
        let t2 = poly8(&ERFINV_TAIL2, s - Vd::splat(TAIL2_CENTRE));
        is_central.select(central, s.simd_lt(Vd::splat(4.0)).select(t1, t2))
    });
    // `y.max(0).min(MAX_SLOPE)` (NaN → 0), then the early returns.
    let y = y.simd_gt(Vf::ZERO).select(y.min(Vf::splat(MAX_SLOPE)), Vf::ZERO);
    let y = (q.is_nan() | q.simd_lt(Vf::splat(ERFC_MAX_SLOPE))).select(Vf::splat(MAX_SLOPE), y);
    q.simd_ge(Vf::ONE).select(Vf::ZERO, y)
}

/// `erfcinv` lane-wise for `q ∈ [0, 2]` (NaN → `MAX_SLOPE`):
/// `−erfcinv_upper(2 − q)` above 1.
#[inline(always)]
pub(super) fn erfcinv_v(q: Vf) -> Vf {
    let above = q.simd_gt(Vf::ONE);
    let y = erfcinv_upper_v(above.select(Vf::splat(2.0) - q, q));
    above.select(-y, y)
}

/// `erfinv_2p_minus_1` lane-wise for `p ∈ [0, 1]` (the caller clamps):
/// `q = 2 min(p, 1 − p)`, `erfcinv_upper(q)` with the sign of `p − 1/2`.
#[inline(always)]
pub(super) fn erfinv_2p_minus_1_v(p: Vf) -> Vf {
    let q = Vf::splat(2.0) * p.min(Vf::ONE - p);
    let y = erfcinv_upper_v(q);
    let sign = (p - Vf::splat(0.5)).is_sign_negative();
    let mag = y.abs();
    sign.select(-mag, mag)
}
