//! The vector form (feature `simd`) of [`Beckmann::sample_visible`]: the
//! visible-slope sampler of Heitz & d'Eon 2014 (§4, bounded start and two
//! safeguarded Halley steps, see `Beckmann::sample_slope_x`) lane for lane,
//! bit-identical to the scalar code. Both branches of the slope inversion
//! (`x̃ ≤ 0` and `x̃ > 0`) run in every lane and a select keeps the one the
//! scalar code takes.

use super::special::{FRAC_1_SQRT_PI, MAX_SLOPE, SQRT_PI};
use super::special_lanes::{
    beckmann_s_v, erfcinv_v, erfcx_v, erfinv_2p_minus_1_v, exp_neg_sq_v, ln64_v, lnf_v,
};
#[cfg(doc)]
use super::{Beckmann, MicrofacetDistribution};
use crate::simd::{Dirs, Vf, narrow, widen};

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

/// The `x̃ ≤ 0` branch (`Beckmann::slope_lower`) lane-wise.
#[inline(always)]
fn slope_lower(c: Vf, s: Vf, u: Vf, total2: Vf, c0: Vf) -> Vf {
    let (zero, one, two) = (Vf::ZERO, Vf::ONE, Vf::splat(2.0));
    let inv_c0 = one / c0;
    let (uh, th, ih) = (widen(u), widen(total2), widen(inv_c0));
    let l0 = narrow([-ln64_v(uh[0] * th[0] * ih[0]), -ln64_v(uh[1] * th[1] * ih[1])]);
    let l0 = l0.max(zero);
    let x = -l0.sqrt();
    let tangent = -l0 * (Vf::splat(0.5 * SQRT_PI) * c0 / c);
    // `f32::max` ignores a NaN second operand, as `wide`'s `max` does.
    let x = c.simd_gt(zero).select(x.max(tangent), x);
    let mut x = x.max(Vf::splat(-MAX_SLOPE));
    let (mut lo, mut hi) = (x, zero);
    let sf = s * Vf::splat(FRAC_1_SQRT_PI);
    for _ in 0..2 {
        let h = c * erfcx_v(-x) + sf;
        let g = (l0 - x * x) + lnf_v(h * inv_c0);
        let pos = g.simd_gt(zero);
        hi = pos.select(x, hi);
        lo = pos.select(lo, x);
        let den = c - x * s;
        let gh = g * Vf::splat(SQRT_PI) * h;
        let step = two * gh * den
            / (Vf::splat(4.0) * den * den * (one + Vf::splat(0.5) * g) + gh * (s + two * x * den));
        x = bracketed(x - step, lo, hi);
    }
    x.max(Vf::splat(-MAX_SLOPE)).min(zero) + zero
}

/// The `x̃ > 0` branch (`Beckmann::slope_upper`) lane-wise.
#[inline(always)]
fn slope_upper(c: Vf, s: Vf, u: Vf, b: Vf, total2: Vf, excess: Vf) -> Vf {
    let (zero, one, two) = (Vf::ZERO, Vf::ONE, Vf::splat(2.0));
    let gs = (one - u) * total2;
    let ln_gs = lnf_v(gs);
    let q = (gs - excess) / c;
    let z = erfcinv_v(q);
    let zs = z * s;
    let shift = z - s / (((c * c + zs * zs).sqrt() + c) - zs);
    let use_q = c.simd_gt(zero) & q.simd_gt(zero) & q.simd_lt(two);
    let mut x = use_q.select(b.min(shift), b);
    let sqrt_pi = Vf::splat(SQRT_PI);
    let xe = (b - (sqrt_pi * gs / (s * exp_neg_sq_v(b))).sqrt()).max(zero);
    let end = b - (sqrt_pi * gs / (s * exp_neg_sq_v(xe))).sqrt();
    x = b.simd_lt(Vf::splat(MAX_SLOPE)).select(x.min(end), x);
    let mut x = x.max(zero);
    let (mut lo, mut hi) = (zero, b);
    let sf = s * Vf::splat(FRAC_1_SQRT_PI);
    for _ in 0..2 {
        let e = exp_neg_sq_v(x);
        let den = c - x * s;
        let g = excess + e * (c * erfcx_v(x) - sf);
        let gpos = g.simd_gt(zero);
        let phi = lnf_v(g) - ln_gs;
        let ppos = phi.simd_gt(zero);
        lo = (gpos & ppos).select(x, lo);
        hi = (gpos & !ppos).select(x, hi);
        hi = gpos.select(hi, x);
        let p4 = Vf::splat(4.0) * den * e * Vf::splat(FRAC_1_SQRT_PI);
        let pg = phi * g;
        let next = x + two * pg * den / (p4 * den * (one + Vf::splat(0.5) * phi) - pg * (s + two * x * den));
        let next = gpos.select(next, Vf::splat(f32::NAN));
        x = bracketed(next, lo, hi);
    }
    x.max(zero).min(b) + zero
}

/// `Beckmann::sample_slope_x` lane-wise (`u` already clamped to `[0, 1]`).
#[inline(always)]
fn sample_slope_x(c: Vf, s: Vf, u: Vf) -> Vf {
    let max = Vf::splat(MAX_SLOPE);
    let b = (s * max).simd_le(c).select(max, c / s);
    let excess = s * Vf::splat(FRAC_1_SQRT_PI) * beckmann_s_v(b);
    let total2 = Vf::splat(2.0) * c + excess;
    let c0 = c + s * Vf::splat(FRAC_1_SQRT_PI);
    let target = u * total2;
    let x = target.simd_le(c0).select(
        slope_lower(c, s, u, total2, c0),
        slope_upper(c, s, u, b, total2, excess),
    );
    let x = u.simd_ge(Vf::ONE).select(b, x);
    u.simd_le(Vf::ZERO).select(-max, x)
}

/// [`Beckmann`]'s [`sample_visible`](MicrofacetDistribution::sample_visible)
/// lane-wise for unit `ωo`: `(m, cold)`, `cold` the lanes whose scalar
/// normalisations leave the hot branches (handed back).
#[inline(always)]
pub(super) fn sample_visible(alpha: f32, wo: Dirs, u0: Vf, u1: Vf) -> (Dirs, Vf) {
    let a = Vf::splat(alpha);
    let stretched = Dirs {
        x: a * wo.x,
        y: a * wo.y,
        z: wo.z.abs(),
    };
    let (v, cold_v) = stretched.unitize();
    let sin_t = (v.x * v.x + v.y * v.y).sqrt().min(Vf::ONE);
    let cos_t = v.z;
    let pos = sin_t.simd_gt(Vf::ZERO);
    let cos_p = pos.select(v.x / sin_t, Vf::ONE);
    let sin_p = pos.select(v.y / sin_t, Vf::ZERO);
    let sx = sample_slope_x(cos_t, sin_t, clamp01(u0));
    let sy = erfinv_2p_minus_1_v(clamp01(u1));
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
    use super::super::special::{erfcinv, erfinv_2p_minus_1, ln64};
    use super::*;
    use crate::simd::LANES;

    /// The vector special functions against their scalar forms, bit for
    /// bit, on a dense grid of their sampler ranges.
    #[test]
    fn special_lanes_are_scalar_bit_for_bit() {
        let mut xs = std::vec::Vec::new();
        let mut t = 1e-38f32;
        while t < 2.0 {
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
            let ln = ln64_v(widen(v)[0]).to_array();
            let inv = erfcinv_v(v).to_array();
            let p = clamp01(v);
            let ei = erfinv_2p_minus_1_v(p).to_array();
            let pa = p.to_array();
            for k in 0..LANES {
                if k < LANES / 2 && a[k] > 0.0 {
                    assert_eq!(ln[k].to_bits(), ln64(a[k] as f64).to_bits(), "ln64({})", a[k]);
                }
                assert_eq!(inv[k].to_bits(), erfcinv(a[k]).to_bits(), "erfcinv({})", a[k]);
                assert_eq!(
                    ei[k].to_bits(),
                    erfinv_2p_minus_1(pa[k]).to_bits(),
                    "erfinv({})",
                    pa[k]
                );
            }
        }
    }
}
