//! Two GGX lobes with the height-correlated `G2` at one pair of unit
//! directions, side by side in the lanes of one `Vec4`: a material with two
//! roughnesses at one hit (OpenPBR's coat, and its specular roughness shared
//! by the metal and the dielectric specular lobe) takes each root and each
//! division once for both lobes.
//!
//! Per lobe of roughness `α` (lane `k`), the same IEEE operations in the same
//! order as [`Microfacet`](super::Microfacet)'s scalar path, so every lane
//! is bit for bit that lobe's `eval`/`pdf` term:
//!
//! ```text
//! A(ω)  = cos θ (1 + Λ) = ½ (cos θ + √(cos²θ + α² sin²θ))  (Λ: Heitz 2014, eq. 86)
//! D     = (α² |h|⁴) / (π (α² h_z² + h_x² + h_y²)²)        (Walter et al. 2007, eq. 33)
//! 1/V   = 4 ((cos θo Ai + cos θi Ao) − cos θi cos θo)      (Heitz 2014, eq. 99)
//! s     = D V,   pdf = D/(4 A(ωo))
//! ```
//!
//! with the half vector `h` and `cos θd = |ωi + ωo|/2` computed once, and
//! the unpolarised dielectric Fresnel factor of two indices at that
//! `cos θd` ([`dielectric_pair`]).

use super::fresnel::clamp_cos;
use super::{Half, finite_nonneg};
use crate::vec4::sqrt4;
use core::f32::consts::PI;
use radiometry::glam::{Vec3, Vec4, Vec4Swizzles};

/// The terms of two GGX lobes at one pair ([`ggx_pair`]): lane 0 and lane 1
/// for the roughnesses `[α₀, α₁]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct GgxPairTerms {
    /// `s = D V` of each lobe, its value before the Fresnel factor (`f_r =
    /// F(cos θd) s`, and exactly 0 where the lobe's `eval` returns 0).
    pub(crate) s: [f32; 2],
    /// `D/(4 A(ωo))` of each lobe: its `pdf`.
    pub(crate) pdf: [f32; 2],
    /// `cos θd = min(|ωi + ωo|/2, 1)`, the Fresnel factor's argument.
    pub(crate) cos_d: f32,
}

/// The terms of the GGX lobes of roughness `alpha[0]` and `alpha[1]`
/// (height-correlated `G2`) at the unit directions `wi`, `wo` (the caller
/// has checked both unit to within `4ε`, the scalar hot path's test): each
/// lane bit for bit the lobe's own computation. Where the half vector is
/// undefined (a direction at or below the horizon, `ωi ≈ −ωo`) every term is
/// 0, as the lobes' `eval` and `pdf` are.
#[inline(always)]
pub(crate) fn ggx_pair(alpha: [f32; 2], wi: Vec3, wo: Vec3) -> GgxPairTerms {
    let Some(h) = Half::of(wi, wo) else {
        return GgxPairTerms {
            s: [0.0; 2],
            pdf: [0.0; 2],
            cos_d: 0.0,
        };
    };
    let (ci, co) = (wi.z, wo.z);
    // α² in lanes [α₀, α₁, α₀, α₁] (each `α · α`, as the scalar code forms it).
    let a = Vec4::new(alpha[0], alpha[1], alpha[0], alpha[1]);
    let a2 = a * a;
    // The projected areas [Ai₀, Ai₁, Ao₀, Ao₁] with one vector root.
    let cos = Vec4::new(ci, ci, co, co);
    let (si, so) = (wi.x * wi.x + wi.y * wi.y, wo.x * wo.x + wo.y * wo.y);
    let sin2 = Vec4::new(si, si, so, so);
    let area = Vec4::splat(0.5) * (cos + sqrt4(cos * cos + a2 * sin2));
    // D's numerator and denominator in every lane (`d_ratio`).
    let l = h.hz2 + h.hxy2;
    let t = a2 * h.hz2 + Vec4::splat(h.hxy2);
    let dn = (a2 * l) * l;
    let dd = (Vec4::splat(PI) * t) * t;
    // 1/V in lanes 0 and 1: (cos θo Ai + cos θi Ao) − cos θi cos θo, times 4.
    let inv_v =
        Vec4::splat(4.0) * ((Vec4::splat(co) * area + Vec4::splat(ci) * area.zwxy()) - Vec4::splat(ci * co));
    // The quotients [pdf₀, pdf₁, s₀, s₁] = dn/(dd · [4Ao₀, 4Ao₁, 1/V₀, 1/V₁]) in one
    // vector division (`d_quotient`).
    let four_ao = Vec4::splat(4.0) * area;
    let den = Vec4::new(four_ao.z, four_ao.w, inv_v.x, inv_v.y);
    let q = dd * den;
    let r = if q.cmpge(Vec4::splat(f32::MIN_POSITIVE)).all() {
        let r = dn / q;
        Vec4::select(r.cmpgt(Vec4::ZERO), r.min(Vec4::splat(f32::MAX)), Vec4::ZERO)
    } else {
        quotients_cold(dn, dd, den, q)
    };
    GgxPairTerms {
        s: [r.z, r.w],
        pdf: [r.x, r.y],
        cos_d: h.cos_theta_d(),
    }
}

/// [`ggx_pair`]'s quotients lane by lane where a product `dd · den` is not a
/// normal `f32`: each such lane as two divisions (`d_quotient`'s cold path).
#[cold]
#[inline(never)]
fn quotients_cold(dn: Vec4, dd: Vec4, den: Vec4, q: Vec4) -> Vec4 {
    let (dn, dd, den, q) = (dn.to_array(), dd.to_array(), den.to_array(), q.to_array());
    Vec4::from_array(core::array::from_fn(|k| {
        if q[k] >= f32::MIN_POSITIVE {
            finite_nonneg(dn[k] / q[k])
        } else {
            finite_nonneg((dn[k] / dd[k]) / den[k])
        }
    }))
}

/// The unpolarised Fresnel reflectance of two dielectric interfaces of
/// relative indices `eta = [η₀, η₁]` at `cos θd` (either side of 1; `1` in
/// total internal reflection), bit for bit [`Dielectric::eval`] of each,
/// its divisions and root taken once for both:
///
/// ```text
/// sin²θt = (1 − c²)/η²,   cos θt = √(1 − sin²θt)
/// r_p = (η c − cos θt)/(η c + cos θt),   r_s = (c − η cos θt)/(c + η cos θt)
/// F = (r_p² + r_s²)/2
/// ```
///
/// [`Dielectric::eval`]: super::Dielectric
#[inline(always)]
pub(crate) fn dielectric_pair(eta: [f32; 2], cos_theta_d: f32) -> [f32; 2] {
    let ci = clamp_cos(cos_theta_d);
    let e = Vec4::new(eta[0], eta[1], eta[0], eta[1]);
    let one = Vec4::ONE;
    let sin2_t = Vec4::splat(1.0 - ci * ci) / (e * e);
    let ct = sqrt4((one - sin2_t).max(Vec4::ZERO));
    let eci = e * Vec4::splat(ci);
    let ect = e * ct;
    // [n_p₀, n_p₁, n_s₀, n_s₁] / [d_p₀, d_p₁, d_s₀, d_s₁].
    let num = Vec4::new(eci.x - ct.x, eci.y - ct.y, ci - ect.x, ci - ect.y);
    let den = Vec4::new(eci.x + ct.x, eci.y + ct.y, ci + ect.x, ci + ect.y);
    let r = num / den;
    let rr = r * r;
    let f = (Vec4::splat(0.5) * (rr + rr.zwxy())).min(one).max(Vec4::ZERO);
    core::array::from_fn(|k| {
        // Total internal reflection, and the 0/0 limit at exact grazing with
        // η = 1, are 1 (as the scalar term returns them).
        if sin2_t[k] >= 1.0 || den[k] <= 0.0 || den[k + 2] <= 0.0 {
            1.0
        } else {
            f[k]
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::microfacet::{Dielectric, Fresnel, Ggx, HeightCorrelated, Microfacet, NoFresnel, is_unit};
    use radiometry::Brdf;

    fn rng(s: &mut u64) -> f32 {
        *s ^= *s << 13;
        *s ^= *s >> 7;
        *s ^= *s << 17;
        ((*s >> 40) as f32) / (1u64 << 24) as f32
    }

    fn dir(s: &mut u64) -> Vec3 {
        let z = rng(s);
        let phi = 2.0 * PI * rng(s);
        let r = radiometry::math::sqrtf((1.0 - z * z).max(0.0));
        Vec3::new(r * libm::cosf(phi), r * libm::sinf(phi), z)
    }

    /// Hard pairs: grazing, mirror configuration at grazing (the half
    /// vector's cancellation), opposite directions, the normal, below the
    /// horizon.
    fn hard_pairs() -> [(Vec3, Vec3); 7] {
        let g = Vec3::new(0.999_999_94, 0.0, 3.4e-4);
        [
            (Vec3::Z, Vec3::Z),
            (g, Vec3::new(-g.x, 1e-5, g.z)),
            (g, Vec3::new(-g.x, 0.0, g.z)),
            (g, g),
            (Vec3::new(0.6, 0.0, 0.8), Vec3::new(-0.6, 0.0, 0.8)),
            (Vec3::new(0.6, 0.0, -0.8), Vec3::Z),
            (Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0)),
        ]
    }

    /// Every lane is the lobe's own `eval` (with `F = 1`: `s`) and `pdf`, bit
    /// for bit, and `cos θd` is the one a Fresnel term of the lobe reads:
    /// random roughness pairs (the range's ends included) and unit pairs.
    #[test]
    fn lanes_are_each_lobes_own_terms() {
        let mut s = 0x9E37_79B9_7F4A_7C15u64;
        let alphas = |s: &mut u64| -> [f32; 2] {
            let pick = |s: &mut u64| match (rng(s) * 8.0) as u32 {
                0 => 1e-4,
                1 => 1.0,
                _ => 1e-4 + rng(s) * rng(s),
            };
            [pick(s), pick(s)]
        };
        let mut checked = 0;
        for n in 0..60_000 {
            let alpha = alphas(&mut s);
            let (wi, wo) = match hard_pairs().get(n % 50) {
                Some(&p) => p,
                None => (dir(&mut s), dir(&mut s)),
            };
            if !(is_unit(wi) && is_unit(wo)) {
                continue;
            }
            let t = ggx_pair(alpha, wi, wo);
            for (k, &a) in alpha.iter().enumerate() {
                let lobe = Microfacet::<_, HeightCorrelated, _>::new(Ggx::new(a).unwrap(), NoFresnel);
                assert_eq!(
                    t.s[k].to_bits(),
                    lobe.eval(wi, wo).to_bits(),
                    "s, α = {a}, {wi}, {wo}"
                );
                assert_eq!(
                    t.pdf[k].to_bits(),
                    lobe.pdf(wi, wo).to_bits(),
                    "pdf, α = {a}, {wi}, {wo}"
                );
            }
            // cos θd: a Fresnel term of index 1.5 reads the lane's argument.
            let d = Dielectric::new(1.5).unwrap();
            let lobe = Microfacet::<_, HeightCorrelated, _>::new(Ggx::new(alpha[0]).unwrap(), d);
            let f = lobe.eval(wi, wo);
            let expect = if t.s[0] == 0.0 {
                0.0
            } else {
                d.eval(t.cos_d) * t.s[0]
            };
            assert_eq!(f.to_bits(), expect.to_bits(), "F(cos θd) s, {wi}, {wo}");
            checked += 1;
        }
        assert!(checked > 50_000);
    }

    /// Each lane of [`dielectric_pair`] is [`Dielectric::eval`] bit for bit:
    /// random indices either side of 1 (total internal reflection included)
    /// and `η = 1`, at random cosines, 0, 1, and out-of-range and NaN input.
    #[test]
    fn dielectric_lanes_are_the_scalar_term() {
        let mut s = 0x2545_F491_4F6C_DD1Du64;
        let etas = |s: &mut u64| match (rng(s) * 6.0) as u32 {
            0 => 1.0,
            1 => 1.0 / (1.0 + 2.0 * rng(s)),
            _ => 1.0 + 2.0 * rng(s),
        };
        for n in 0..100_000 {
            let eta = [etas(&mut s), etas(&mut s)];
            let c = match n % 40 {
                0 => 0.0,
                1 => 1.0,
                2 => -0.3,
                3 => 1.5,
                4 => f32::NAN,
                5 => 1e-30,
                _ => rng(&mut s),
            };
            let f = dielectric_pair(eta, c);
            for (k, &e) in eta.iter().enumerate() {
                let d = Dielectric::new(e).unwrap();
                assert_eq!(f[k].to_bits(), d.eval(c).to_bits(), "η = {e}, c = {c}");
            }
        }
    }
}
