//! The vector kernels of the rough diffuse plugins (feature `simd`):
//! [`Fon`](super::Fon), [`Eon`](super::Eon) and
//! [`OrenNayar`](super::OrenNayar) share them through
//! [`RoughLobe`]'s lane methods.
//!
//! * `eval`: the scalar [`eval`](super::eval) lane-wise — both directions
//!   through the hot branches of `unitize` ([`Dirs::unitize_again`]; the
//!   other lanes are handed back to the scalar method), the horizon mask, and
//!   the plugin's `eval_unit` as [`RoughLobe::unit_lanes`] /
//!   [`RoughLobe::channel_lanes`]. EON's multiple-scattering factor needs
//!   `G(μ)/π` of both cosines, with `acos` from the bit-exact port
//!   [`crate::simd::acosf`].
//! * `pdf`: the mixture density `(1 − p_u) cos θi/π + p_u/(2π)`.
//! * `sample`: the mixture sampler — `u₀ < p_u` picks the uniform
//!   hemisphere (`cos θ = u₀/p_u`), else Malley's cosine-weighted concentric
//!   map (the Phong family's vector warp) on `(u₀ − p_u)/(1 − p_u)`; then the
//!   pdf and `weight = f_r cos θi/pdf` of the normalised `ωi`.
//!
//! Bit-identical to the scalar methods: the same operations in the same
//! order (comparisons and selects for the scalar branches, `max` and
//! `clamp`), no FMA.

use super::{C1, RoughLobe};
use crate::phong::batch::{clamp01, safe_sqrt, warp};
use crate::simd::{Dirs, Kernel, LANES, SampleKernel, Vf, acosf, sincos_turn, store};
use core::f32::consts::FRAC_1_PI;
use radiometry::glam::Vec3;
use radiometry::math::ONE_MINUS_EPSILON;
use radiometry::{BrdfSample, Spectrum};

/// `f32::max(x, 0)` for non-NaN `x` that is never `−0` (every use here):
/// `x > 0 ? x : 0`.
#[inline(always)]
pub(super) fn max0(x: Vf) -> Vf {
    x.simd_gt(Vf::ZERO).select(x, Vf::ZERO)
}

/// [`g_over_pi`](super::g_over_pi) lane-wise, bit for bit: `μ` clamped to
/// `[0, 1]` as `f32::clamp` does it (NaN passes through), `sin θ = √((1 −
/// μ)(1 + μ))`, `θ = acos μ` ([`acosf`]) and the scalar expression in its
/// order.
#[inline(always)]
pub(crate) fn g_over_pi(mu: Vf) -> Vf {
    let one = Vf::ONE;
    let mu = mu.simd_lt(Vf::ZERO).select(Vf::ZERO, mu);
    let mu = mu.simd_gt(one).select(one, mu);
    let sin2 = (one - mu) * (one + mu);
    let sin = sin2.sqrt();
    let theta = acosf(mu);
    let one_sin = one + sin;
    let g = sin * (theta - sin * mu) + Vf::splat(2.0 / 3.0) * sin * (mu * (one_sin + sin2) / one_sin - one);
    g * Vf::splat(FRAC_1_PI)
}

/// [`fon_deficit`](super::fon_deficit) `max(c₁ − G(μ)/π, 0)` lane-wise
/// (bit for bit). When every lane holds the same `μ` (one `ωo` for the whole
/// batch, as an integrator's nodes have it) the scalar function is called
/// once instead.
#[inline(always)]
pub(crate) fn fon_deficit(mu: Vf) -> Vf {
    let first = mu.to_array()[0];
    if mu.simd_eq(Vf::splat(first)).all() {
        return Vf::splat(super::fon_deficit(first));
    }
    max0(Vf::splat(C1) - g_over_pi(mu))
}

/// `(s > 0, s/t)` lane-wise, with [`s_term`](super::s_term) `s = xi xo + yi
/// yo` and [`t_term`](super::t_term) `t = max(cos θi, cos θo, f32::MIN_POSITIVE)`
/// (as `f32::max` for the lanes whose cosines are both positive, the only
/// ones whose value is used).
#[inline(always)]
pub(crate) fn s_over_t(wi: Dirs, wo: Dirs) -> (Vf, Vf, Vf) {
    let s = wi.x * wo.x + wi.y * wo.y;
    let t = wi.z.simd_gt(wo.z).select(wi.z, wo.z);
    let min = Vf::splat(f32::MIN_POSITIVE);
    let t = t.simd_gt(min).select(t, min);
    (s.simd_gt(Vf::ZERO), s, s / t)
}

/// `p_u = 0.5 k max(1 − cos θo, 0)³` lane-wise (the scalar `p_uniform`).
#[inline(always)]
fn p_uniform(k: f32, mu_o: Vf) -> Vf {
    let c = max0(Vf::ONE - mu_o);
    Vf::splat(0.5 * k) * (c * c * c)
}

/// The mixture density of unit directions, `(1 − p_u)(cos θi/π) + p_u/(2π)`.
#[inline(always)]
fn mixture_pdf(p_u: Vf, mu_i: Vf) -> Vf {
    (Vf::ONE - p_u) * (mu_i * Vf::splat(FRAC_1_PI)) + p_u * Vf::splat(0.5 * FRAC_1_PI)
}

/// `eval`: `f_r` of the normalised pair where both cosines are positive,
/// else 0.
pub(crate) struct Eval<'a, L>(pub(crate) &'a L);

impl<L: RoughLobe> Kernel for Eval<'_, L> {
    type Out = L::S;

    #[inline(always)]
    fn lanes(&self, wi: Dirs, wo: Dirs, out: &mut [L::S; LANES]) -> u32 {
        let l = self.0;
        let (wi, cold_i) = wi.unitize_again();
        let (wo, cold_o) = wo.unitize_again();
        let up = wi.z.simd_gt(Vf::ZERO) & wo.z.simd_gt(Vf::ZERO);
        let t = l.unit_lanes(wi, wo);
        store(out, |c| up.select(l.channel_lanes(c, &t), Vf::ZERO));
        (cold_i | cold_o).to_bitmask()
    }

    #[inline(always)]
    fn one(&self, wi: Vec3, wo: Vec3) -> L::S {
        super::eval(self.0, wi, wo)
    }
}

/// `pdf`: the mixture density of the normalised pair where both cosines
/// are positive, else 0.
pub(crate) struct Pdf<'a, L>(pub(crate) &'a L);

impl<L: RoughLobe> Kernel for Pdf<'_, L> {
    type Out = f32;

    #[inline(always)]
    fn lanes(&self, wi: Dirs, wo: Dirs, out: &mut [f32; LANES]) -> u32 {
        let (wi, cold_i) = wi.unitize_again();
        let (wo, cold_o) = wo.unitize_again();
        let up = wi.z.simd_gt(Vf::ZERO) & wo.z.simd_gt(Vf::ZERO);
        let pdf = mixture_pdf(p_uniform(self.0.uniform_weight(), wo.z), wi.z);
        *out = up.select(pdf, Vf::ZERO).to_array();
        (cold_i | cold_o).to_bitmask()
    }

    #[inline(always)]
    fn one(&self, wi: Vec3, wo: Vec3) -> f32 {
        super::pdf(self.0, wi, wo)
    }
}

/// `f32::min(x, 1 − 2⁻²⁴)` (NaN → `1 − 2⁻²⁴`).
#[inline(always)]
fn min_one_minus_eps(x: Vf) -> Vf {
    let m = Vf::splat(ONE_MINUS_EPSILON);
    x.simd_lt(m).select(x, m)
}

/// `sample`: the cosine/uniform mixture, `Some { ωi, pdf, f_r cos θi/pdf }`
/// where `ωo` is above the horizon, the sampled `ωi` too and `pdf > 0`.
pub(crate) struct Sample<'a, L>(pub(crate) &'a L);

impl<L: RoughLobe> SampleKernel for Sample<'_, L> {
    type Out = Option<BrdfSample<L::S>>;

    #[inline(always)]
    fn lanes(&self, wo: Dirs, u0: Vf, u1: Vf, out: &mut [Self::Out; LANES]) -> u32 {
        let l = self.0;
        let zero = Vf::ZERO;
        let (wo, cold_o) = wo.unitize_again();
        let p_u = p_uniform(l.uniform_weight(), wo.z);
        let uniform = u0.simd_lt(p_u);
        // The cosine-weighted warp on every lane (one `sincos_turn`), the
        // uniform hemisphere where some lane picked it (a second one).
        let v = min_one_minus_eps((u0 - p_u) / (Vf::ONE - p_u));
        let all = zero.simd_eq(zero);
        let mut wi = warp(all, v, u1, 1.0);
        if uniform.any() {
            let z = clamp01(min_one_minus_eps(u0 / p_u));
            let r = safe_sqrt(Vf::ONE - z * z);
            let (sn, cs) = sincos_turn(clamp01(u1));
            wi = Dirs {
                x: uniform.select(r * cs, wi.x),
                y: uniform.select(r * sn, wi.y),
                z: uniform.select(z, wi.z),
            };
        }
        let (wn, cold_i) = wi.unitize_again();
        let pdf = mixture_pdf(p_u, wn.z);
        // `pdf > 0` is false for NaN.
        let ok = wo.z.simd_gt(zero) & wn.z.simd_gt(zero) & pdf.simd_gt(zero);
        let t = l.unit_lanes(wn, wo);
        let scale = wn.z / pdf;
        let mut weight = [L::S::zero(); LANES];
        store(&mut weight, |c| l.channel_lanes(c, &t) * scale);
        let (x, y, z, p) = (wi.x.to_array(), wi.y.to_array(), wi.z.to_array(), pdf.to_array());
        let ok = ok.to_bitmask();
        for (k, o) in out.iter_mut().enumerate() {
            *o = (ok & (1 << k) != 0).then(|| BrdfSample {
                wi: Vec3::new(x[k], y[k], z[k]),
                pdf: p[k],
                weight: weight[k],
            });
        }
        // A cold `ωi` matters only where `ωo` was usable; the scalar method
        // redoes both.
        (cold_o | cold_i).to_bitmask()
    }

    #[inline(always)]
    fn one(&self, wo: Vec3, u: [f32; 2]) -> Self::Out {
        super::sample(self.0, wo, u)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simd::{assert_lanes_match, check_values, dense_stride, sweep_stride};

    /// `G(μ)/π` and `max(c₁ − G(μ)/π, 0)` lane for lane equal to the scalar
    /// functions on every 7th `f32` of `[0, 1]` (with
    /// `RADIOMETRY_FULL_SWEEP=1`; every 61st otherwise), on negative
    /// cosines and values above 1 (clamped), NaN and infinities.
    #[test]
    fn g_over_pi_and_deficit_are_scalar_bit_for_bit() {
        let check = |xs: &[f32; LANES]| {
            assert_lanes_match("g_over_pi", g_over_pi, super::super::g_over_pi, xs);
            // Distinct lanes: the vector path of `fon_deficit`.
            assert_lanes_match("fon_deficit", fon_deficit, super::super::fon_deficit, xs);
        };
        sweep_stride(&check, &[(0, 1.0)], dense_stride());
        let specials = [
            -0.0f32,
            -1e-45,
            -0.5,
            -1.0,
            -f32::MAX,
            1.0 + f32::EPSILON,
            2.0,
            f32::MAX,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            0.5,
            1e-30,
        ];
        check_values(&check, &specials);
        // Equal lanes: the scalar shortcut.
        for x in [0.0f32, 0.3, 0.99, 1.0] {
            check(&[x; LANES]);
        }
    }
}
