//! Helpers of the Phong family shared with [`BlinnPhong`](crate::BlinnPhong):
//! parameter checks, the one-sample strategy choice of the two-lobe
//! mixture, the `cos^n` lobe sampler and the input handling of `eval`/`pdf`.

use crate::error::{BrdfError, check_range};
use crate::microfacet::is_unit;
use radiometry::frame::{Frame, try_normalize};
use radiometry::glam::Vec3;
use radiometry::math::{ONE_MINUS_EPSILON, safe_sqrt};
use radiometry::{BrdfSample, Spectrum};

/// Validates `kd`, `ks ∈ [0, 1]` per channel and `kd + ks ≤ 1 + 2⁻²³`.
pub(crate) fn check_kd_ks<S: Spectrum>(kd: S, ks: S) -> Result<(), BrdfError> {
    for i in 0..S::CHANNELS {
        check_range("kd", kd.channel(i), 0.0, 1.0)?;
        check_range("ks", ks.channel(i), 0.0, 1.0)?;
    }
    for i in 0..S::CHANNELS {
        if kd.channel(i) + ks.channel(i) > 1.0 + f32::EPSILON {
            return Err(BrdfError::Constraint {
                what: "kd + ks must not exceed 1 in any channel (energy conservation)",
            });
        }
    }
    Ok(())
}

/// `(kd̄/(kd̄+ks̄), ks̄/(kd̄+ks̄))`, or `(0, 0)` when both averages are 0.
pub(crate) fn strategy_probabilities<S: Spectrum>(kd: S, ks: S) -> (f32, f32) {
    let (a, b) = (kd.average(), ks.average());
    let total = a + b;
    if total > 0.0 {
        let pd = a / total;
        (pd, 1.0 - pd)
    } else {
        (0.0, 0.0)
    }
}

/// `[1/pd, 1/ps]` for [`choose_strategy`], at most `f32::MAX` (so that the
/// rescaled `u₀` is never NaN; it is clamped anyway); a component is `0`
/// where its probability is not positive (it is then never used).
pub(crate) fn strategy_reciprocals(pd: f32, ps: f32) -> [f32; 2] {
    let inv = |p: f32| if p > 0.0 { (1.0 / p).min(f32::MAX) } else { 0.0 };
    [inv(pd), inv(ps)]
}

/// Picks a strategy from `u₀` and rescales it to `[0, 1 − 2⁻²⁴]`:
/// `Some((true, u₀/pd))` for the diffuse strategy (`u₀ < pd`),
/// `Some((false, (u₀ − pd)/ps))` for the lobe, `None` when both
/// probabilities are zero. NaN maps to 0. `inv` is
/// [`strategy_reciprocals`]`(pd, ps)`: the rescaling multiplies by it
/// (the result may differ from the quotient by an ulp, which only moves
/// the sample by as much; the clamp keeps it in range).
#[inline]
pub(crate) fn choose_strategy(u0: f32, pd: f32, ps: f32, inv: [f32; 2]) -> Option<(bool, f32)> {
    if pd.is_nan() || ps.is_nan() || pd + ps <= 0.0 {
        return None;
    }
    let u0 = clamp_unit(u0);
    let (diffuse, v) = if ps <= 0.0 {
        (true, u0)
    } else if pd <= 0.0 {
        (false, u0)
    } else if u0 < pd {
        (true, u0 * inv[0])
    } else {
        (false, (u0 - pd) * inv[1])
    };
    Some((diffuse, clamp_unit(v)))
}

/// Clamps to `[0, ONE_MINUS_EPSILON]`, NaN → 0.
#[inline]
fn clamp_unit(x: f32) -> f32 {
    if x > 0.0 { x.min(ONE_MINUS_EPSILON) } else { 0.0 }
}

/// `(1 − δ)^n` for `δ = 1 − cos`, computed as `exp(n · log1p(−δ))`;
/// `0` when `δ ≥ 1` (cosine ≤ 0) or NaN, `1` when `δ ≤ 0`.
#[inline]
pub(crate) fn pow_one_minus(delta: f32, n: f32) -> f32 {
    if delta.is_nan() || delta >= 1.0 {
        0.0
    } else if delta <= 0.0 {
        1.0
    } else {
        libm::expf(n * libm::log1pf(-delta))
    }
}

/// Direction around `+Z` with density `(n+1)/(2π) cos^n θ`:
/// `cos θ = ξ^{1/(n+1)}`, `ξ = 1 − u₀`, `φ = 2π u₁`. `1 − cos θ` is formed
/// as `−expm1(ln ξ/(n+1))` so that it keeps its relative precision for huge
/// `n`. `u` is expected in `[0, 1 − 2⁻²⁴]` (clamped otherwise); `inv_n1`
/// is `1/(n + 1)` (precomputed: a multiplication instead of a division).
#[inline]
pub(crate) fn sample_cos_power(u: [f32; 2], inv_n1: f32) -> Vec3 {
    let xi = 1.0 - clamp_unit(u[0]); // in [2⁻²⁴, 1]
    let delta = (-libm::expm1f(libm::logf(xi) * inv_n1)).clamp(0.0, 1.0);
    let sin_t = safe_sqrt(delta * (2.0 - delta));
    let (sp, cp) = radiometry::math::sincos_turn(clamp_unit(u[1]));
    // The clamps of `spherical_direction_sc`.
    let (s, c) = (sin_t.clamp(-1.0, 1.0), (1.0 - delta).clamp(-1.0, 1.0));
    Vec3::new(s * cp, s * sp, c)
}

/// `(ωi, ωo)` as unit vectors with both strictly above the horizon, or
/// `None` (the input handling of `eval` and `pdf` of the Phong family).
///
/// Hot path: when both are already unit to rounding
/// ([`is_unit`]: `|‖w‖² − 1| ≤ 4ε`, so `|‖w‖ − 1| ≤ 2ε`, the accuracy a
/// normalised vector has anyway) they are used as given — no square root
/// or division. Otherwise (`#[cold]`) both are normalised by
/// [`try_normalize`]; a zero or non-finite vector gives `None`. The
/// vector kernels (feature `simd`) take the hot path lane-wise and hand the
/// other lanes to the scalar method.
#[inline]
pub(crate) fn upper_pair(wi: Vec3, wo: Vec3) -> Option<(Vec3, Vec3)> {
    let (wi, wo) = if is_unit(wi) && is_unit(wo) {
        (wi, wo)
    } else {
        normalize_pair_cold(wi, wo)?
    };
    (wi.z > 0.0 && wo.z > 0.0).then_some((wi, wo))
}

#[cold]
#[inline(never)]
fn normalize_pair_cold(wi: Vec3, wo: Vec3) -> Option<(Vec3, Vec3)> {
    Some((try_normalize(wi)?, try_normalize(wo)?))
}

/// Completes a sample from `wi`, its density `pdf` (computed by the
/// caller with exactly the arithmetic of `Brdf::pdf(wi, wo)`) and
/// `f = Brdf::eval(wi, wo)` (likewise): `weight = (f/pdf)·cos θi`, and
/// `None` for a non-positive or non-finite pdf or a non-finite weight
/// (possible only when the pdf underflows).
#[inline]
pub(crate) fn finish_with<S: Spectrum>(wi: Vec3, pdf: f32, f: S) -> Option<BrdfSample<S>> {
    if !pdf.is_finite() || pdf <= 0.0 {
        return None;
    }
    let weight = (f / pdf) * wi.z;
    weight.is_finite().then_some(BrdfSample { wi, pdf, weight })
}

/// `w` itself when it is already unit to rounding (`||w|² − 1| ≤ 4ε`, so
/// `||w| − 1| ≤ 2ε`: the accuracy a sampler's rotated or reflected unit
/// vector has anyway), else [`try_normalize`] (the `#[cold]` path: zero,
/// non-finite or clearly non-unit input).
#[inline]
pub(crate) fn unit_or_normalize(w: Vec3) -> Option<Vec3> {
    let l2 = w.length_squared();
    if (l2 - 1.0).abs() <= 4.0 * f32::EPSILON {
        Some(w)
    } else {
        normalize_cold(w)
    }
}

#[cold]
#[inline(never)]
fn normalize_cold(w: Vec3) -> Option<Vec3> {
    try_normalize(w)
}

/// The orthonormal basis around the unit `n` with `n.z > 0`: the
/// `sign = +1` branch of [`Frame::from_normal`] (Duff et al. 2017,
/// *Building an Orthonormal Basis, Revisited*, JCGT 6(1)), without its
/// renormalisation of an already-unit `n` and with `1 + n.z ∈ (1, 2]`, so
/// the one division is always well-conditioned.
#[inline]
pub(crate) fn frame_around_upper(n: Vec3) -> Frame {
    let a = -1.0 / (1.0 + n.z);
    let b = n.x * n.y * a;
    Frame {
        s: Vec3::new(1.0 + n.x * n.x * a, b, -n.x),
        t: Vec3::new(b, 1.0 + n.y * n.y * a, -n.y),
        n,
    }
}
