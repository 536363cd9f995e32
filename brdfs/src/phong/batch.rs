//! The vector kernels of [`ModifiedPhong`] (feature `simd`). `eval`:
//! `f = kd/π + ks (n+2)/(2π) cos^n α`, zero unless both directions are
//! strictly above the horizon, on the hot path of `upper_pair` (both unit
//! to within `4ε`; the other lanes are recomputed by the scalar method), with
//! `cos^n α = exp(n log1p(−δ))`, `δ = |ωi − reflect_z(ωo)|²/2`.
//!
//! Bit-identical to `eval`: the same operations in the same order, and
//! `exp`/`log1p` are the bit-exact ports [`crate::simd::expf`] /
//! [`crate::simd::log1pf`] of `libm`'s.
//!
//! The `sample` kernel ([`Sample`]) and the vector forms of the
//! sampler's steps shared with [`BlinnPhong`](crate::BlinnPhong)
//! (`choose_strategy`, the two warps, the finishing) live here too.

use super::ModifiedPhong;
use crate::simd::Vf;
use crate::simd::{
    Dirs, Kernel, LANES, SampleKernel, cold_lanes, expm1f, logf, pow_one_minus, sincos_turn, store,
};
use core::f32::consts::FRAC_1_PI;
use radiometry::glam::Vec3;
use radiometry::math::ONE_MINUS_EPSILON;
use radiometry::{Brdf, BrdfSample, Spectrum};

/// `(up, cold, cos^n α)`: the hot path of `upper_pair` (both directions
/// used as given, both strictly above the horizon; `cold` marks the
/// lanes where one is not unit to within `4ε`, which the driver
/// recomputes with the scalar method) and the lobe `(1 − δ)^n`,
/// `δ = |ωi − reflect_z(ωo)|²/2 = 1 − cos α`, as the scalar `lobe`.
#[inline(always)]
fn upper_lobe<S: Spectrum>(b: &ModifiedPhong<S>, a: Dirs, c: Dirs) -> (Vf, u32, Vf) {
    let zero = Vf::ZERO;
    let cold = cold_lanes(a, c);
    let up = a.z.simd_gt(zero) & c.z.simd_gt(zero);
    let d = Dirs {
        x: a.x - (-c.x),
        y: a.y - (-c.y),
        z: a.z - c.z,
    };
    let delta = Vf::splat(0.5) * d.length_squared();
    (up, cold, pow_one_minus(delta, b.exponent))
}

pub(super) struct Eval<'a, S: Spectrum>(pub(super) &'a ModifiedPhong<S>);

impl<S: Spectrum> Kernel for Eval<'_, S> {
    type Out = S;

    #[inline(always)]
    fn lanes(&self, wi: Dirs, wo: Dirs, out: &mut [S; LANES]) -> u32 {
        let b = self.0;
        let zero = Vf::ZERO;
        let (up, cold, lobe) = upper_lobe(b, wi, wo);
        let norm = (b.exponent + 2.0) * (0.5 * FRAC_1_PI);
        let lobe = Vf::splat(norm) * lobe;
        let diffuse = b.kd * FRAC_1_PI;
        store(out, |ch| {
            let f = Vf::splat(diffuse.channel(ch)) + Vf::splat(b.ks.channel(ch)) * lobe;
            up.select(f, zero)
        });
        cold
    }

    #[inline(always)]
    fn one(&self, wi: Vec3, wo: Vec3) -> S {
        self.0.eval(wi, wo)
    }
}

/// `pdf = pd cos θi/π + ps (n+1)/(2π) cos^n α` where both directions are
/// above the horizon, else 0.
pub(super) struct Pdf<'a, S: Spectrum>(pub(super) &'a ModifiedPhong<S>);

impl<S: Spectrum> Kernel for Pdf<'_, S> {
    type Out = f32;

    #[inline(always)]
    fn lanes(&self, wi: Dirs, wo: Dirs, out: &mut [f32; LANES]) -> u32 {
        let b = self.0;
        let (up, cold, lobe) = upper_lobe(b, wi, wo);
        let diffuse = Vf::splat(b.p_diffuse) * wi.z * Vf::splat(FRAC_1_PI);
        let lobe = if b.p_lobe > 0.0 {
            Vf::splat(b.p_lobe * ((b.exponent + 1.0) * (0.5 * FRAC_1_PI))) * lobe
        } else {
            Vf::ZERO
        };
        *out = up.select(diffuse + lobe, Vf::ZERO).to_array();
        cold
    }

    #[inline(always)]
    fn one(&self, wi: Vec3, wo: Vec3) -> f32 {
        self.0.pdf(wi, wo)
    }
}

/// `sample` of [`ModifiedPhong`] lane for lane: the strategy choice,
/// the cosine-weighted warp or `cos θ = ξ^{1/(n+1)}` around
/// `ωr = reflect_z(ωo)` (rotated by `frame_around_upper(ωr)`), then
/// `pdf = pd cos θi/π + ps (n+1)/(2π) cos^n α` and
/// `weight = f cos θi/pdf` with one evaluation of the lobe, as the
/// scalar `sample`.
///
/// Lanes handed back to the scalar method: `ωo` not unit to within `4ε`
/// (the scalar normalises it, and `upper_pair` sees the original), and a
/// sampled `ωi` not unit to within `4ε` (the scalar's `try_normalize`,
/// or `upper_pair`'s cold path for a diffuse sample).
pub(super) struct Sample<'a, S: Spectrum>(pub(super) &'a ModifiedPhong<S>);

impl<S: Spectrum> SampleKernel for Sample<'_, S> {
    type Out = Option<BrdfSample<S>>;

    #[inline(always)]
    fn lanes(&self, wo: Dirs, u0: Vf, u1: Vf, out: &mut [Self::Out; LANES]) -> u32 {
        let b = self.0;
        let Some((diffuse, v)) = choose_strategy(u0, b.p_diffuse, b.p_lobe, b.inv_p) else {
            out.fill(None);
            return 0;
        };
        let local = warp(diffuse, v, u1, b.inv_n1);
        // Lobe lanes: `frame_around_upper(reflect_z(ωo)).to_world(local)`.
        let wi = if diffuse.all() {
            local
        } else {
            let n = Dirs {
                x: -wo.x,
                y: -wo.y,
                z: wo.z,
            };
            let a = Vf::splat(-1.0) / (Vf::ONE + n.z);
            let bb = n.x * n.y * a;
            let s = Dirs {
                x: Vf::ONE + n.x * n.x * a,
                y: bb,
                z: -n.x,
            };
            let t = Dirs {
                x: bb,
                y: Vf::ONE + n.y * n.y * a,
                z: -n.y,
            };
            let l = local;
            let world = Dirs {
                x: l.x * s.x + l.y * t.x + l.z * n.x,
                y: l.x * s.y + l.y * t.y + l.z * n.y,
                z: l.x * s.z + l.y * t.z + l.z * n.z,
            };
            Dirs {
                x: diffuse.select(l.x, world.x),
                y: diffuse.select(l.y, world.y),
                z: diffuse.select(l.z, world.z),
            }
        };
        // `unit_or_normalize(ωi)` and `upper_pair(ωi, ωo)`: hot where
        // both are unit to within 4ε, else handed back.
        let (up, cold, lobe) = upper_lobe(b, wi, wo);
        let diffuse_pdf = Vf::splat(b.p_diffuse) * wi.z * Vf::splat(FRAC_1_PI);
        let lobe_pdf = if b.p_lobe > 0.0 {
            Vf::splat(b.p_lobe * ((b.exponent + 1.0) * (0.5 * FRAC_1_PI))) * lobe
        } else {
            Vf::ZERO
        };
        let norm = (b.exponent + 2.0) * (0.5 * FRAC_1_PI);
        finish(
            b.kd,
            b.ks,
            Vf::splat(norm) * lobe,
            wi,
            diffuse_pdf + lobe_pdf,
            up,
            out,
        );
        cold
    }

    #[inline(always)]
    fn one(&self, wo: Vec3, u: [f32; 2]) -> Self::Out {
        self.0.sample(wo, u)
    }
}

/// `clamp_unit`: `x > 0 ? min(x, 1 − 2⁻²⁴) : 0` (NaN → 0).
#[inline(always)]
fn clamp_unit(x: Vf) -> Vf {
    x.simd_gt(Vf::ZERO)
        .select(x.min(Vf::splat(ONE_MINUS_EPSILON)), Vf::ZERO)
}

/// `radiometry::math::clamp01`: `x > 0 ? min(x, 1) : 0` (NaN → 0).
#[inline(always)]
pub(crate) fn clamp01(x: Vf) -> Vf {
    x.simd_gt(Vf::ZERO).select(x.min(Vf::ONE), Vf::ZERO)
}

/// `f32::clamp(x, lo, hi)` by its comparisons (`x < lo → lo`,
/// `x > hi → hi`; NaN and `−0` pass through).
#[inline(always)]
fn clamp(x: Vf, lo: f32, hi: f32) -> Vf {
    let x = x.simd_lt(Vf::splat(lo)).select(Vf::splat(lo), x);
    x.simd_gt(Vf::splat(hi)).select(Vf::splat(hi), x)
}

/// `radiometry::math::safe_sqrt` (`√max(x, 0)`) lane-wise. The sign of
/// `max(±0, 0)` is not fixed by IEEE 754 (`maxNum` may return either
/// zero), so lanes with `x = ±0` take the scalar function itself: its
/// `√(−0) = −0` or `+0`, whichever the scalar code gives.
#[inline(always)]
pub(crate) fn safe_sqrt(x: Vf) -> Vf {
    let r = x.max(Vf::ZERO).sqrt();
    if !x.simd_eq(Vf::ZERO).any() {
        return r;
    }
    let (xs, rs) = (x.to_array(), r.to_array());
    Vf::new(core::array::from_fn(|k| {
        if xs[k] == 0.0 {
            radiometry::math::safe_sqrt(xs[k])
        } else {
            rs[k]
        }
    }))
}

/// `choose_strategy(u₀, pd, ps, inv)` lane-wise: `None` (for every
/// lane) when `pd + ps ≤ 0` or either is NaN, else the mask of the
/// diffuse lanes (`u₀ < pd`, or every lane when `ps ≤ 0`, none when
/// `pd ≤ 0`) and the rescaled `clamp_unit(u₀/pd)` or
/// `clamp_unit((u₀ − pd)/ps)` (as products with `inv`).
#[inline(always)]
pub(crate) fn choose_strategy(u0: Vf, pd: f32, ps: f32, inv: [f32; 2]) -> Option<(Vf, Vf)> {
    if pd.is_nan() || ps.is_nan() || pd + ps <= 0.0 {
        return None;
    }
    let u = clamp_unit(u0);
    let all = Vf::ZERO.simd_eq(Vf::ZERO);
    let (diffuse, v) = if ps <= 0.0 {
        (all, u)
    } else if pd <= 0.0 {
        (!all, u)
    } else {
        let d = u.simd_lt(Vf::splat(pd));
        let pd = Vf::splat(pd);
        (d, d.select(u * Vf::splat(inv[0]), (u - pd) * Vf::splat(inv[1])))
    };
    Some((diffuse, clamp_unit(v)))
}

/// The sampler's two warps, one per lane (one `sincos_turn` for both):
/// `square_to_cosine_hemisphere([v, u₁])` on the `diffuse` lanes
/// (Shirley & Chiu's concentric map, `r = ±o`, `θ/2π = o_y/o_x / 8` or
/// `1/4 − o_x/o_y / 8`, lifted by `z = √(1 − |d|²)`), and
/// `sample_cos_power([v, u₁], 1/(n+1))` on the others
/// (`1 − cos θ = −expm1(ln ξ/(n+1))`, `ξ = 1 − v`, `φ = 2π u₁`, with
/// the bit-exact ports [`logf`], [`expm1f`] and [`sincos_turn`]); the
/// operations and clamps of the scalar functions, in their order.
#[inline(always)]
pub(crate) fn warp(diffuse: Vf, v: Vf, u1: Vf, inv_n1: f32) -> Dirs {
    let (zero, one) = (Vf::ZERO, Vf::ONE);
    let any_lobe = !diffuse.all();
    let any_diffuse = diffuse.any();
    // Concentric map: (ox, oy) ∈ [−1, 1]², radius r and angle θ.
    let ox = Vf::splat(2.0) * clamp01(v) - one;
    let oy = Vf::splat(2.0) * clamp01(u1) - one;
    let center = ox.simd_eq(zero) & oy.simd_eq(zero);
    let horiz = ox.abs().simd_gt(oy.abs());
    let (r, angle) = if any_diffuse {
        // One division: o_y/o_x where |o_x| > |o_y|, else o_x/o_y.
        let ratio = horiz.select(oy, ox) / horiz.select(ox, oy);
        // θ/2π = o_y/o_x / 8 or 1/4 − o_x/o_y / 8 (turns).
        let q = Vf::splat(0.125) * ratio;
        let turns = horiz.select(q, Vf::splat(0.25) - q);
        (horiz.select(ox, oy), center.select(zero, turns))
    } else {
        (zero, zero)
    };
    let (sn, cs) = sincos_turn(diffuse.select(angle, clamp_unit(u1)));
    // Cosine-weighted hemisphere (the centre maps to (0, 0, 1)).
    let dx = center.select(zero, r * cs);
    let dy = center.select(zero, r * sn);
    let dz = safe_sqrt(one - (dx * dx + dy * dy));
    if !any_lobe {
        return Dirs { x: dx, y: dy, z: dz };
    }
    // cos^n lobe around +Z.
    let xi = one - clamp_unit(v);
    let delta = clamp(-expm1f(logf(xi) * Vf::splat(inv_n1)), 0.0, 1.0);
    let sin_t = clamp(safe_sqrt(delta * (Vf::splat(2.0) - delta)), -1.0, 1.0);
    Dirs {
        x: diffuse.select(dx, sin_t * cs),
        y: diffuse.select(dy, sin_t * sn),
        z: diffuse.select(dz, clamp(one - delta, -1.0, 1.0)),
    }
}

/// `finish_with(ωi, pdf, f)` lane-wise, with `f = kd/π + ks · ls`
/// (`ls` the scaled lobe, `N cos^n`): `Some` where `valid` and
/// `0 < pdf < ∞` and every channel of `weight = (f/pdf) cos θi` is
/// finite, else `None`.
#[inline(always)]
pub(crate) fn finish<S: Spectrum>(
    kd: S,
    ks: S,
    ls: Vf,
    wi: Dirs,
    pdf: Vf,
    valid: Vf,
    out: &mut [Option<BrdfSample<S>>; LANES],
) {
    let diffuse = kd * FRAC_1_PI;
    let mut ok = valid & pdf.is_finite() & pdf.simd_gt(Vf::ZERO);
    let mut weight = [S::zero(); LANES];
    store(&mut weight, |ch| {
        let f = Vf::splat(diffuse.channel(ch)) + Vf::splat(ks.channel(ch)) * ls;
        let w = (f / pdf) * wi.z;
        ok &= w.is_finite();
        w
    });
    let (x, y, z, p) = (wi.x.to_array(), wi.y.to_array(), wi.z.to_array(), pdf.to_array());
    let ok = ok.to_bitmask();
    for (k, o) in out.iter_mut().enumerate() {
        *o = (ok & (1 << k) != 0).then(|| BrdfSample {
            wi: Vec3::new(x[k], y[k], z[k]),
            pdf: p[k],
            weight: weight[k],
        });
    }
}
