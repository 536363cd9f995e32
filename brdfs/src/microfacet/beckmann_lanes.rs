//! The vector form (feature `simd`) of [`Beckmann::sample_visible`], lane
//! for lane bit-identical to the scalar code: the `f32` fast path of the
//! visible-slope inversion (`beckmann_slope::lanes`) in every lane and, only
//! when some lane has `u₀` outside its range, the tail scheme of Heitz &
//! d'Eon 2014 (§4, bounded start and two safeguarded Halley steps, see
//! `Beckmann::sample_slope_x`) for those lanes. In the tail scheme both
//! branches of the slope inversion (`x̃ ≤ 0` and `x̃ > 0`) run in every lane
//! and a select keeps the one the scalar code takes.

use super::beckmann_slope::lanes::slope_x_v;
use super::beckmann_slope::{U_HI, U_LO};
use super::beckmann_tail::TAIL_RESOLUTION;
use super::special::{FRAC_1_SQRT_PI, MAX_SLOPE, SQRT_PI};
use super::special_lanes::{
    beckmann_s_v, erfcinv_v, erfcx_v, erfinv_2p_minus_1_v, exp_neg_sq_v, ln64_v, lnf_v,
};
#[cfg(doc)]
use super::{Beckmann, MicrofacetDistribution};
use crate::simd::{Dirs, Vd, Vf, narrow, widen};

/// `clamp01` lane-wise: `u > 0 ? min(u, 1) : 0` (NaN → 0).
#[inline(always)]
pub(super) fn clamp01(u: Vf) -> Vf {
    u.simd_gt(Vf::ZERO).select(u.min(Vf::ONE), Vf::ZERO)
}

/// One bracketed step: `next` if it lies in `[lo, hi]`, else the midpoint.
#[inline(always)]
fn bracketed(next: Vf, lo: Vf, hi: Vf) -> Vf {
    (next.simd_ge(lo) & next.simd_le(hi)).select(next, Vf::splat(0.5) * (lo + hi))
}

/// `Beckmann::sample_slope_x` lane-wise (`u` already clamped to `[0, 1]`).
///
/// The two branches of the scalar code (`slope_lower` for `x̃ ≤ 0`,
/// `slope_upper` for `x̃ > 0`) share their expensive calls: per lane one
/// logarithm for the start (`ln(2uC(b)/2C(0))` or `ln G*`), and per Halley
/// step one `erfcx` (of `−x` or `x`) and one logarithm (of `H/2C(0)` or
/// `G`); the cheap `f32` step formulas of both branches run in every lane
/// and a select keeps the one the scalar code takes.
#[inline(always)]
fn sample_slope_x(c: Vf, s: Vf, u: Vf) -> Vf {
    let (zero, one, two, four) = (Vf::ZERO, Vf::ONE, Vf::splat(2.0), Vf::splat(4.0));
    let (max, half) = (Vf::splat(MAX_SLOPE), Vf::splat(0.5));
    let sqrt_pi = Vf::splat(SQRT_PI);
    let b = (s * max).simd_le(c).select(max, c / s);
    let sf = s * Vf::splat(FRAC_1_SQRT_PI);
    let excess = sf * beckmann_s_v(b);
    let total2 = two * c + excess;
    let c0 = c + sf;
    let lower = (u * total2).simd_le(c0);

    // Start. Lower: L₀ = −ln(u 2C(b)/2C(0)) (the product in f64); upper:
    // ln G*, G* = (1 − u) 2C(b). One logarithm of the selected argument.
    let inv_c0 = one / c0;
    let gs = (one - u) * total2;
    let (uh, th, ih, gh) = (widen(u), widen(total2), widen(inv_c0), widen(gs));
    let lw = widen(lower.select(-one, one));
    let ln = |k: usize| {
        let arg = lw[k].simd_lt(Vd::ZERO).select(uh[k] * th[k] * ih[k], gh[k]);
        ln64_v(arg)
    };
    let ln = narrow([ln(0), ln(1)]);
    let l0 = (-ln).max(zero);
    let ln_gs = ln;
    // Lower start: max(−√L₀, −L₀/g'(0), −MAX_SLOPE).
    let xl = -l0.sqrt();
    let tangent = -l0 * (Vf::splat(0.5 * SQRT_PI) * c0 / c);
    // `f32::max` ignores a NaN second operand, as `wide`'s `max` does.
    let xl = c.simd_gt(zero).select(xl.max(tangent), xl).max(-max);
    // Upper start: min(b, z − h, endpoint bounds), then ≥ 0.
    let q = (gs - excess) / c;
    let use_q = c.simd_gt(zero) & q.simd_gt(zero) & q.simd_lt(two);
    // Lanes that do not use `z` get a harmless `q` (no tail pieces).
    let z = erfcinv_v((use_q & !lower).select(q, half));
    let zs = z * s;
    let shift = z - s / (((c * c + zs * zs).sqrt() + c) - zs);
    let xu = use_q.select(b.min(shift), b);
    let eb = exp_neg_sq_v(b);
    let xe = (b - (sqrt_pi * gs / (s * eb)).sqrt()).max(zero);
    let end = b - (sqrt_pi * gs / (s * exp_neg_sq_v(xe))).sqrt();
    let xu = b.simd_lt(max).select(xu.min(end), xu).max(zero);

    let mut x = lower.select(xl, xu);
    let mut lo = lower.select(xl, zero);
    let mut hi = lower.select(zero, b);
    for _ in 0..2 {
        let ex = erfcx_v(lower.select(-x, x));
        let e = exp_neg_sq_v(x);
        let den = c - x * s;
        // Lower: H = c erfcx(−x) + s/√π, g = L₀ − x² + ln(H/2C(0)).
        let h = c * ex + sf;
        // Upper: G = excess + e^{−x²}(c erfcx(x) − s/√π), φ = ln G − ln G*.
        let gu = excess + e * (c * ex - sf);
        let lnv = lnf_v(lower.select(h * inv_c0, gu));
        let g = (l0 - x * x) + lnv;
        let gpos = g.simd_gt(zero);
        let gh_l = g * sqrt_pi * h;
        let next_l =
            x - two * gh_l * den / (four * den * den * (one + half * g) + gh_l * (s + two * x * den));
        let upos = gu.simd_gt(zero);
        let phi = lnv - ln_gs;
        let ppos = phi.simd_gt(zero);
        let p4 = four * den * e * Vf::splat(FRAC_1_SQRT_PI);
        let pg = phi * gu;
        let next_u = x + two * pg * den / (p4 * den * (one + half * phi) - pg * (s + two * x * den));
        let next_u = upos.select(next_u, Vf::splat(f32::NAN));
        // Brackets: lower raises `hi` where g > 0; upper raises `lo` where
        // φ > 0 and lowers `hi` otherwise (also where G ≤ 0).
        let raise_lo = lower.select(!gpos, upos & ppos);
        lo = raise_lo.select(x, lo);
        hi = raise_lo.select(hi, x);
        x = bracketed(lower.select(next_l, next_u), lo, hi);
    }
    // Upper lanes whose target is below the resolution of `G` keep their
    // start (`Beckmann::slope_upper`, `TAIL_RESOLUTION`).
    let keep = !lower & b.simd_lt(max) & gs.simd_le(Vf::splat(TAIL_RESOLUTION) * (excess + sf * eb));
    let x = keep.select(xu, x);
    let x = lower.select(x.max(-max).min(zero), x.max(zero).min(b)) + zero;
    let x = u.simd_ge(one).select(b, x);
    u.simd_le(zero).select(-max, x)
}

/// [`Beckmann`]'s [`sample_visible`](MicrofacetDistribution::sample_visible)
/// lane-wise for unit `ωo`: `(m, cold)`, `cold` the lanes whose scalar
/// normalisations leave the hot branches (handed back). `x̃` by the fast
/// path (`beckmann_slope`) in every lane; only when some lane has
/// `u₀ ∉ [U_LO, U_HI]` the tail scheme runs as well, for those lanes.
#[inline(always)]
pub(super) fn sample_visible(alpha: f32, wo: Dirs, u0: Vf, u1: Vf) -> (Dirs, Vf) {
    let a = Vf::splat(alpha);
    let (u0, u1) = (clamp01(u0), clamp01(u1));
    let rxy = wo.xy_length_squared().sqrt();
    let pos = rxy.simd_gt(Vf::ZERO);
    let inv = Vf::ONE / rxy;
    let cos_p = pos.select(wo.x * inv, Vf::ONE);
    let sin_p = pos.select(wo.y * inv, Vf::ZERO);
    let c = wo.z.abs();
    let fast = u0.simd_ge(Vf::splat(U_LO)) & u0.simd_le(Vf::splat(U_HI));
    let mut sx = slope_x_v(c, a * rxy, u0);
    let mut cold_v = Vf::ZERO;
    if !fast.all() {
        // `Beckmann::slope_x_tail`: the stretched direction, normalised.
        let stretched = Dirs {
            x: a * wo.x,
            y: a * wo.y,
            z: c,
        };
        let (v, cold) = stretched.unitize();
        let sin_t = (v.x * v.x + v.y * v.y).sqrt().min(Vf::ONE);
        sx = fast.select(sx, sample_slope_x(v.z, sin_t, u0));
        cold_v = !fast & cold;
    }
    let sy = erfinv_2p_minus_1_v(u1);
    let tx = cos_p * sx - sin_p * sy;
    let ty = sin_p * sx + cos_p * sy;
    let na = Vf::splat(-alpha);
    let (m, cold_m) = Dirs {
        x: na * tx,
        y: na * ty,
        z: Vf::ONE,
    }
    .unitize();
    (m, cold_v | cold_m)
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::super::special::{erfcinv, erfinv_2p_minus_1, exp_neg_sq, ln64};
    use super::*;
    use crate::simd::LANES;

    /// The vector special functions against their scalar forms, bit for
    /// bit, on a dense grid of their sampler ranges.
    #[test]
    fn special_lanes_are_scalar_bit_for_bit() {
        let mut xs = std::vec::Vec::new();
        let mut t = 1e-45f32;
        while t < 1e12 {
            xs.push(t);
            t = (t * 1.0003).max(t.next_up());
        }
        xs.extend([
            0.0,
            -0.0,
            1.0,
            2.0,
            0.5,
            1.0f32.next_down(),
            1.0f32.next_up(),
            f32::NAN,
        ]);
        for chunk in xs.chunks(LANES) {
            let mut a = [0.25f32; LANES];
            a[..chunk.len()].copy_from_slice(chunk);
            let v = Vf::new(a);
            let ln = [ln64_v(widen(v)[0]).to_array(), ln64_v(widen(v)[1]).to_array()].concat();
            let inv = erfcinv_v(v).to_array();
            let e = exp_neg_sq_v(v).to_array();
            let p = clamp01(v);
            let ei = erfinv_2p_minus_1_v(p).to_array();
            let pa = p.to_array();
            for k in 0..LANES {
                if a[k] > 0.0 {
                    assert_eq!(ln[k].to_bits(), ln64(a[k] as f64).to_bits(), "ln64({})", a[k]);
                }
                assert_eq!(inv[k].to_bits(), erfcinv(a[k]).to_bits(), "erfcinv({})", a[k]);
                assert_eq!(e[k].to_bits(), exp_neg_sq(a[k]).to_bits(), "exp_neg_sq({})", a[k]);
                assert_eq!(
                    ei[k].to_bits(),
                    erfinv_2p_minus_1(pa[k]).to_bits(),
                    "erfinv({})",
                    pa[k]
                );
            }
        }
    }

    /// `sample_visible` lane-wise against the scalar, bit for bit, where the
    /// two slope paths meet and at the top of the `u` range near grazing
    /// (the tail scheme's kept start, `TAIL_RESOLUTION`).
    #[test]
    fn sample_visible_lanes_at_switch_points_and_top_of_range() {
        use super::super::{Beckmann, MicrofacetDistribution};
        use radiometry::glam::Vec3;
        let mut us = std::vec::Vec::new();
        for v in [U_LO, U_HI, 1.0 - 2f32.powi(-12), 1.0] {
            let mut w = v;
            for _ in 0..40 {
                w = w.next_down();
            }
            for _ in 0..80 {
                if w <= 1.0 {
                    us.push(w);
                }
                w = w.next_up();
            }
        }
        let mut compared = 0;
        for &alpha in &[0.05f32, 0.3, 1.0] {
            let d = Beckmann::new(alpha).unwrap();
            for &theta in &[0.3f64, 1.2, 1.55, 1.565, 1.57, 1.5706] {
                let wo = Vec3::new(libm::sin(theta) as f32, 0.0, libm::cos(theta) as f32);
                for chunk in us.chunks(LANES) {
                    let mut u0 = [0.5f32; LANES];
                    u0[..chunk.len()].copy_from_slice(chunk);
                    let dirs = Dirs {
                        x: Vf::splat(wo.x),
                        y: Vf::splat(wo.y),
                        z: Vf::splat(wo.z),
                    };
                    let (m, cold) = sample_visible(alpha, dirs, Vf::new(u0), Vf::splat(0.3));
                    let (mx, my, mz, cold) =
                        (m.x.to_array(), m.y.to_array(), m.z.to_array(), cold.to_array());
                    for k in 0..LANES {
                        if cold[k] != 0.0 {
                            continue;
                        }
                        let r = d.sample_visible(wo, [u0[k], 0.3]);
                        compared += 1;
                        assert_eq!(
                            [mx[k].to_bits(), my[k].to_bits(), mz[k].to_bits()],
                            [r.x.to_bits(), r.y.to_bits(), r.z.to_bits()],
                            "α={alpha} θ={theta} u={}",
                            u0[k]
                        );
                    }
                }
            }
        }
        assert!(compared > 4000, "{compared}");
    }
}
