//! Vector forms (feature `simd`) of the special functions the Beckmann
//! sampler calls, lane for lane the scalar functions of `special.rs`
//! (bit-identical: the `f64` arithmetic is the same generic code, the bit
//! manipulation the same per lane).

use super::special::{
    ERFC_MAX_SLOPE, ERFINV_CENTRAL, ERFINV_TAIL1, ERFINV_TAIL2, MAX_SLOPE, TAIL1_CENTRE, TAIL2_CENTRE,
    beckmann_s64, erfcx64_any, exp_neg64_v, ln64_poly, ln64_split, poly7, poly8, poly9,
};
use crate::simd::{Vd, Vf, narrow, widen};

/// Lanes per [`Vd`].
const HALF: usize = core::mem::size_of::<Vd>() / core::mem::size_of::<f64>();

/// `f` on the two `f64` halves of `x`, rounded back to `f32`.
#[inline(always)]
fn via64(x: Vf, f: impl Fn(Vd) -> Vd) -> Vf {
    let h = widen(x);
    narrow([f(h[0]), f(h[1])])
}

/// `ln64` lane-wise (same split of the bits per lane, same polynomial).
#[inline(always)]
pub(super) fn ln64_v(x: Vd) -> Vd {
    let xs = x.to_array();
    let parts: [(f64, f64); HALF] = core::array::from_fn(|i| ln64_split(xs[i]));
    let k = Vd::new(core::array::from_fn(|i| parts[i].0));
    let m = Vd::new(core::array::from_fn(|i| parts[i].1));
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
/// Every lane evaluates the three polynomial pieces of the scalar code and
/// keeps the one the scalar branches pick.
#[inline(always)]
fn erfcinv_upper_v(q: Vf) -> Vf {
    let y = via64(q, |q| {
        let w = -ln64_v(q * (Vd::splat(2.0) - q));
        let central = (Vd::ONE - q) * poly9(&ERFINV_CENTRAL, w - Vd::splat(2.5));
        let s = w.sqrt();
        let t1 = poly7(&ERFINV_TAIL1, s - Vd::splat(TAIL1_CENTRE));
        let t2 = poly8(&ERFINV_TAIL2, s - Vd::splat(TAIL2_CENTRE));
        w.simd_lt(Vd::splat(5.0))
            .select(central, s.simd_lt(Vd::splat(4.0)).select(t1, t2))
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
