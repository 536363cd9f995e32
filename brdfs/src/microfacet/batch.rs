//! The vector kernels of [`Microfacet`] (feature `simd`): `eval_batch`,
//! `eval_batch_soa` and `pdf_batch`, lane for lane the scalar hot path
//! `f_r = D(h) V F(cos θd)` and `pdf = D(h)/(4 A(ωo))` of
//! [`Microfacet::eval`](radiometry::Brdf::eval) (Walter et al. 2007, eq. 20,
//! with `V = G2/(4 cos θi cos θo)` from the projected areas
//! `A(ω) = cos θ (1 + Λ(ω))`, Heitz 2014, eq. 16). See [`crate::simd`] for
//! the accuracy statement (0 ulp) and the handling of special inputs.
//!
//! The hidden hooks that select a kernel ([`DistributionKind`],
//! [`G2Kind`]) live here, next to the kernels they select; the shared vector
//! math comes from [`crate::simd`], which imports nothing from this module.

use super::{Fresnel, Microfacet, MicrofacetDistribution, ShadowingMasking};
use crate::simd::Vf;
use crate::simd::{Batch, Dirs, Kernel, LANES, SampleKernel, finite_nonneg, run_samples, sincos_turn};
use core::f32::consts::PI;
use radiometry::glam::Vec3;
use radiometry::{Brdf, BrdfSample, Spectrum};

/// Which batched kernel a [`MicrofacetDistribution`] supports (hidden hook;
/// not a stable API).
#[doc(hidden)]
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum DistributionKind {
    /// No kernel: the batch methods loop over `eval` / `pdf`.
    Scalar,
    /// GGX with this roughness.
    Ggx {
        /// The roughness `α`.
        alpha: f32,
    },
    /// Beckmann with this roughness.
    Beckmann {
        /// The roughness `α`.
        alpha: f32,
    },
}

/// Which batched visibility a [`ShadowingMasking`] supports (hidden hook;
/// not a stable API).
#[doc(hidden)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum G2Kind {
    /// No kernel: the batch methods loop over `eval`.
    Scalar,
    /// `V = 1/(4 (cos θo Ai + cos θi Ao − cos θi cos θo))`.
    HeightCorrelated,
    /// `V = 1/(4 Ai Ao)`.
    Separable,
}

/// The distribution half of a kernel: `D` as a quotient from the squares
/// `h_z²`, `h_x² + h_y²` of the un-normalised half vector, and the
/// projected area `A(cos θ, sin²θ)`, lane-wise and bit-identical to
/// [`MicrofacetDistribution::d_ratio`] / [`projected_area`](MicrofacetDistribution::projected_area).
trait DistV {
    /// `(num, den)`, `D = num/den`.
    fn d_ratio(&self, hz2: Vf, hxy2: Vf) -> (Vf, Vf);
    fn area(&self, cos_theta: Vf, sin2: Vf) -> Vf;
}

/// GGX: `D = α²/(π (α² cos²θh + sin²θh)²)` (Walter et al. 2007, eq. 33),
/// `A = (cos θ + √(cos²θ + α² sin²θ))/2`.
#[derive(Clone, Copy)]
struct GgxV {
    /// `α`.
    alpha: Vf,
    /// `α²`, rounded as `Ggx` rounds it.
    a2: Vf,
}

impl GgxV {
    #[inline(always)]
    fn new(alpha: f32) -> GgxV {
        GgxV {
            alpha: Vf::splat(alpha),
            a2: Vf::splat(alpha * alpha),
        }
    }
}

impl DistV for GgxV {
    #[inline(always)]
    fn d_ratio(&self, hz2: Vf, hxy2: Vf) -> (Vf, Vf) {
        let l = hz2 + hxy2;
        let t = self.a2 * hz2 + hxy2;
        ((self.a2 * l) * l, (Vf::splat(PI) * t) * t)
    }

    #[inline(always)]
    fn area(&self, cos_theta: Vf, sin2: Vf) -> Vf {
        Vf::splat(0.5) * (cos_theta + (cos_theta * cos_theta + self.a2 * sin2).sqrt())
    }
}

/// The visible-normal sampler of a distribution kernel, lane-wise and
/// bit-identical to [`MicrofacetDistribution::sample_visible`] for unit `ωo`.
trait SampleV: DistV {
    /// `(m, cold)`: the sampled normal, and the mask of the lanes whose
    /// scalar path leaves this kernel's branches (handed back).
    fn sample_visible(&self, wo: Dirs, u0: Vf, u1: Vf) -> (Dirs, Vf);
}

use super::beckmann_lanes::clamp01;

impl SampleV for GgxV {
    /// `Ggx::sample_visible` lane for lane: spherical caps (Dupuy & Benyoub
    /// 2023, §3) between the stretch and unstretch of Heitz 2018, with
    /// `radiometry::math::sincos_turn` as its bit-exact vector port.
    #[inline(always)]
    fn sample_visible(&self, wo: Dirs, u0: Vf, u1: Vf) -> (Dirs, Vf) {
        let a = self.alpha;
        let (zero, one) = (Vf::ZERO, Vf::ONE);
        let stretched = Dirs {
            x: a * wo.x,
            y: a * wo.y,
            z: wo.z.abs(),
        };
        let (v, cold_v) = stretched.unitize();
        let (u0, u1) = (clamp01(u0), clamp01(u1));
        let one_plus_vz = one + v.z;
        let one_minus_zc = u1 * one_plus_vz;
        let hz = (one - u1) * one_plus_vz;
        let one_plus_zc = hz + (one - v.z);
        let sin_c = (one_minus_zc * one_plus_zc).max(zero).sqrt();
        let (sp, cp) = sincos_turn(u0);
        let h = Dirs {
            x: a * (sin_c * cp + v.x),
            y: a * (sin_c * sp + v.y),
            z: hz.max(zero),
        };
        let (m, cold_m) = h.unitize();
        (m, cold_v | cold_m)
    }
}

/// Beckmann: `D = exp(−tan²θh/α²)/(π α² cos⁴θh)` (Walter et al. 2007,
/// eq. 25) with one `f32` exponential and `A = cos θ (1 + Λ)` (Heitz 2014,
/// eq. 80) through one fitted `f32` rational, both the scalar code lane for
/// lane (`super::beckmann_f32`, generic over `f32` and the lane type); no
/// lane is handed back.
struct BeckmannV {
    alpha: f32,
    /// `(1/α², 1/(πα²))` of `D`.
    d_consts: (f32, f32),
}

impl BeckmannV {
    #[inline(always)]
    fn new(alpha: f32) -> BeckmannV {
        BeckmannV {
            alpha,
            d_consts: super::beckmann_f32::d_consts(alpha),
        }
    }
}

impl DistV for BeckmannV {
    #[inline(always)]
    fn d_ratio(&self, hz2: Vf, hxy2: Vf) -> (Vf, Vf) {
        (super::beckmann::lanes::d(self.d_consts, hz2, hxy2), Vf::ONE)
    }

    #[inline(always)]
    fn area(&self, cos_theta: Vf, sin2: Vf) -> Vf {
        super::beckmann::lanes::projected_area(self.alpha, cos_theta, sin2)
    }
}

impl SampleV for BeckmannV {
    /// `Beckmann::sample_visible` lane for lane (Heitz & d'Eon 2014, §4:
    /// the visible-slope inversion with a bounded start and two Halley
    /// steps, `erfinv` for the second slope), see `beckmann_lanes`.
    #[inline(always)]
    fn sample_visible(&self, wo: Dirs, u0: Vf, u1: Vf) -> (Dirs, Vf) {
        super::beckmann_lanes::sample_visible(self.alpha, wo, u0, u1)
    }
}

/// `Half::of` lane-wise: `(valid, |ωi + ωo|², h_z², h_x² + h_y²)`,
/// valid where both directions are strictly above the horizon and
/// `|h|² > 10⁻¹⁴` (NaN → invalid), the squares scaled by `2⁶⁴` where
/// `|h|² < 2⁻³²`.
///
/// `h` is the length-corrected sum of `Half::of`
/// ([`Dirs::half_vector_sum`]).
#[inline(always)]
fn half(wi: Dirs, wo: Dirs) -> (Vf, Vf, Vf, Vf) {
    let zero = Vf::ZERO;
    let (h, sum2) = wi.half_vector_sum(wo);
    let len2 = h.length_squared();
    let tiny = Vf::splat(1e-14);
    let valid = wi.z.simd_gt(zero) & wo.z.simd_gt(zero) & sum2.simd_gt(tiny) & len2.simd_gt(tiny);
    let scale = len2
        .simd_lt(Vf::splat(super::HALF_SQUARES_SMALL))
        .select(Vf::splat(super::HALF_SQUARES_SCALE), Vf::ONE);
    (valid, sum2, (h.z * h.z) * scale, h.xy_length_squared() * scale)
}

/// `d_quotient` of the scalar path lane-wise: `(num/(den_d den), cold)`,
/// `cold` where the product `den_d den` is not a normal `f32` (the
/// scalar's two-division `#[cold]` path; those lanes are handed back).
#[inline(always)]
fn d_quotient(num: Vf, den_d: Vf, den: Vf) -> (Vf, Vf) {
    let q = den_d * den;
    (finite_nonneg(num / q), !q.simd_ge(Vf::splat(f32::MIN_POSITIVE)))
}

/// `ShadowingMasking::inverse_visibility` lane-wise: `4 Ai Ao`
/// (separable) or `4 ((cos θo Ai + cos θi Ao) − cos θi cos θo)`.
#[inline(always)]
fn inverse_visibility<const SEPARABLE: bool>(cos_i: Vf, area_i: Vf, cos_o: Vf, area_o: Vf) -> Vf {
    let four = Vf::splat(4.0);
    if SEPARABLE {
        four * (area_i * area_o)
    } else {
        four * ((cos_o * area_i + cos_i * area_o) - cos_i * cos_o)
    }
}

/// Bit `k` set when lane `k` is not on the hot path (a direction that is
/// not unit to within `4ε`): the driver recomputes it with the scalar
/// method.
#[inline(always)]
fn cold_lanes(wi: Dirs, wo: Dirs) -> u32 {
    (!(wi.is_unit() & wo.is_unit())).to_bitmask()
}

/// `eval` of `Microfacet<D, G, F>` with the distribution kernel `X`.
struct Eval<'a, D, G, F, X, const SEPARABLE: bool> {
    b: &'a Microfacet<D, G, F>,
    dist: X,
}

impl<D, G, F, X, const SEPARABLE: bool> Kernel for Eval<'_, D, G, F, X, SEPARABLE>
where
    D: MicrofacetDistribution,
    G: ShadowingMasking,
    F: Fresnel,
    X: DistV,
{
    type Out = F::Spectrum;

    #[inline(always)]
    fn lanes(&self, wi: Dirs, wo: Dirs, out: &mut [F::Spectrum; LANES]) -> u32 {
        let (valid, len2, hz2, hxy2) = half(wi, wo);
        let (dn, dd) = self.dist.d_ratio(hz2, hxy2);
        let ai = self.dist.area(wi.z, wi.xy_length_squared());
        let ao = self.dist.area(wo.z, wo.xy_length_squared());
        let inv_v = inverse_visibility::<SEPARABLE>(wi.z, ai, wo.z, ao);
        let (s, d_cold) = d_quotient(dn, dd, inv_v);
        let s = valid.select(s, Vf::ZERO);
        // cos θd = |ωi + ωo|/2 (`Half::cos_theta_d`).
        // (`fast_min` differs from `min` only for NaN, which only cold lanes hold.)
        let cos_d = (Vf::splat(0.5) * len2.sqrt()).fast_min(Vf::ONE);
        self.b.fresnel.eval_scaled_lanes(cos_d, s, out);
        cold_lanes(wi, wo) | (valid & d_cold).to_bitmask()
    }

    #[inline(always)]
    fn one(&self, wi: Vec3, wo: Vec3) -> F::Spectrum {
        self.b.eval(wi, wo)
    }
}

/// `pdf` of `Microfacet<D, G, F>` with the distribution kernel `X`:
/// `D(h)/(4 A(ωo))`.
struct Pdf<'a, D, G, F, X> {
    b: &'a Microfacet<D, G, F>,
    dist: X,
}

impl<D, G, F, X> Kernel for Pdf<'_, D, G, F, X>
where
    D: MicrofacetDistribution,
    G: ShadowingMasking,
    F: Fresnel,
    X: DistV,
{
    type Out = f32;

    #[inline(always)]
    fn lanes(&self, wi: Dirs, wo: Dirs, out: &mut [f32; LANES]) -> u32 {
        let (valid, _, hz2, hxy2) = half(wi, wo);
        let (dn, dd) = self.dist.d_ratio(hz2, hxy2);
        let ao = self.dist.area(wo.z, wo.xy_length_squared());
        let (p, d_cold) = d_quotient(dn, dd, Vf::splat(4.0) * ao);
        *out = valid.select(p, Vf::ZERO).to_array();
        cold_lanes(wi, wo) | (valid & d_cold).to_bitmask()
    }

    #[inline(always)]
    fn one(&self, wi: Vec3, wo: Vec3) -> f32 {
        self.b.pdf(wi, wo)
    }
}

/// `sample` of `Microfacet<D, G, F>` with the distribution kernel `X`: the
/// scalar [`Microfacet::sample`](radiometry::Brdf::sample) lane for lane —
/// `m ~ D_ωo`, `ωi = 2(ωo·m)m − ωo` normalised as the scalar normalises it
/// (twice: once after the reflection, once in the pdf), then the pdf
/// `D(h)/(4 A(ωo))` and the weight `F(cos θd) · clamp(4 V cos θi A(ωo), 0, 1)`
/// (= `F G2/G1`), with the same `None` decisions.
struct Sample<'a, D, G, F, X, const SEPARABLE: bool> {
    b: &'a Microfacet<D, G, F>,
    dist: X,
}

impl<D, G, F, X, const SEPARABLE: bool> SampleKernel for Sample<'_, D, G, F, X, SEPARABLE>
where
    D: MicrofacetDistribution,
    G: ShadowingMasking,
    F: Fresnel,
    X: SampleV,
{
    type Out = Option<BrdfSample<F::Spectrum>>;

    #[inline(always)]
    fn lanes(&self, wo: Dirs, u0: Vf, u1: Vf, out: &mut [Self::Out; LANES]) -> u32 {
        let (zero, one, four) = (Vf::ZERO, Vf::ONE, Vf::splat(4.0));
        let (m, cold_m) = self.dist.sample_visible(wo, u0, u1);
        let dot = wo.dot(m);
        let two_dot = Vf::splat(2.0) * dot;
        let reflected = Dirs {
            x: two_dot * m.x - wo.x,
            y: two_dot * m.y - wo.y,
            z: two_dot * m.z - wo.z,
        };
        let (wi1, cold_1) = reflected.unitize();
        let (wi, cold_2) = wi1.unitize_again();
        let (valid, len2, hz2, hxy2) = half(wi, wo);
        let (dn, dd) = self.dist.d_ratio(hz2, hxy2);
        let ai = self.dist.area(wi.z, wi.xy_length_squared());
        let ao = self.dist.area(wo.z, wo.xy_length_squared());
        let (pdf, d_cold) = d_quotient(dn, dd, four * ao);
        let inv_v = inverse_visibility::<SEPARABLE>(wi.z, ai, wo.z, ao);
        // `f32::clamp(0, 1)`, NaN kept.
        let r = (four * wi.z) * ao / inv_v;
        let ratio = r.simd_lt(zero).select(zero, r.simd_gt(one).select(one, r));
        let ok = wo.z.simd_gt(zero)
            & dot.simd_gt(zero)
            & wi1.z.simd_gt(zero)
            & valid
            & pdf.simd_gt(zero)
            & pdf.simd_lt(Vf::splat(f32::INFINITY));
        let cos_d = (Vf::splat(0.5) * len2.sqrt()).fast_min(one);
        let mut weight = [F::Spectrum::zero(); LANES];
        self.b.fresnel.eval_scaled_lanes(cos_d, ratio, &mut weight);
        let (x, y, z, p) = (wi.x.to_array(), wi.y.to_array(), wi.z.to_array(), pdf.to_array());
        let ok = ok.to_bitmask();
        for (k, o) in out.iter_mut().enumerate() {
            *o = if ok & (1 << k) != 0 {
                Some(BrdfSample {
                    wi: Vec3::new(x[k], y[k], z[k]),
                    pdf: p[k],
                    weight: weight[k],
                })
            } else {
                None
            };
        }
        (!wo.is_unit() | cold_m | cold_1 | cold_2 | (valid & d_cold)).to_bitmask()
    }

    #[inline(always)]
    fn one(&self, wo: Vec3, u: [f32; 2]) -> Self::Out {
        self.b.sample(wo, u)
    }
}

/// `eval_batch` / `eval_batch_soa` of [`Microfacet`]: a kernel when `D` and
/// `G` opt in through the hidden hooks, else the scalar loop.
#[inline]
pub(crate) fn eval<D, G, F>(b: &Microfacet<D, G, F>, io: Batch<'_, F::Spectrum>)
where
    D: MicrofacetDistribution,
    G: ShadowingMasking,
    F: Fresnel,
{
    match (b.distribution.batch_kind(), G::BATCH_KIND) {
        (DistributionKind::Ggx { alpha }, G2Kind::HeightCorrelated) => io.run(&Eval::<_, _, _, _, false> {
            b,
            dist: GgxV::new(alpha),
        }),
        (DistributionKind::Ggx { alpha }, G2Kind::Separable) => io.run(&Eval::<_, _, _, _, true> {
            b,
            dist: GgxV::new(alpha),
        }),
        (DistributionKind::Beckmann { alpha }, G2Kind::HeightCorrelated) => {
            io.run(&Eval::<_, _, _, _, false> {
                b,
                dist: BeckmannV::new(alpha),
            })
        }
        (DistributionKind::Beckmann { alpha }, G2Kind::Separable) => io.run(&Eval::<_, _, _, _, true> {
            b,
            dist: BeckmannV::new(alpha),
        }),
        _ => io.scalar(|wi, wo| b.eval(wi, wo)),
    }
}

/// `pdf_batch` of [`Microfacet`] (the pdf does not depend on `G`).
#[inline]
pub(crate) fn pdf<D, G, F>(b: &Microfacet<D, G, F>, io: Batch<'_, f32>)
where
    D: MicrofacetDistribution,
    G: ShadowingMasking,
    F: Fresnel,
{
    match b.distribution.batch_kind() {
        DistributionKind::Ggx { alpha } => io.run(&Pdf {
            b,
            dist: GgxV::new(alpha),
        }),
        DistributionKind::Beckmann { alpha } => io.run(&Pdf {
            b,
            dist: BeckmannV::new(alpha),
        }),
        _ => io.scalar(|wi, wo| b.pdf(wi, wo)),
    }
}

/// `sample_batch` of [`Microfacet`]: a kernel when `D` and `G` opt in
/// through the hidden hooks, else the scalar loop.
#[inline]
pub(crate) fn sample<D, G, F>(
    b: &Microfacet<D, G, F>,
    wo: &[Vec3],
    u: &[[f32; 2]],
    out: &mut [Option<BrdfSample<F::Spectrum>>],
) where
    D: MicrofacetDistribution,
    G: ShadowingMasking,
    F: Fresnel,
{
    match (b.distribution.batch_kind(), G::BATCH_KIND) {
        (DistributionKind::Ggx { alpha }, G2Kind::HeightCorrelated) => run_samples(
            &Sample::<_, _, _, _, false> {
                b,
                dist: GgxV::new(alpha),
            },
            wo,
            u,
            out,
        ),
        (DistributionKind::Ggx { alpha }, G2Kind::Separable) => run_samples(
            &Sample::<_, _, _, _, true> {
                b,
                dist: GgxV::new(alpha),
            },
            wo,
            u,
            out,
        ),
        (DistributionKind::Beckmann { alpha }, G2Kind::HeightCorrelated) => run_samples(
            &Sample::<_, _, _, _, false> {
                b,
                dist: BeckmannV::new(alpha),
            },
            wo,
            u,
            out,
        ),
        (DistributionKind::Beckmann { alpha }, G2Kind::Separable) => run_samples(
            &Sample::<_, _, _, _, true> {
                b,
                dist: BeckmannV::new(alpha),
            },
            wo,
            u,
            out,
        ),
        _ => {
            for ((o, &w), &v) in out.iter_mut().zip(wo).zip(u) {
                *o = b.sample(w, v);
            }
            radiometry::batch::zero_tail(out, wo.len().min(u.len()));
        }
    }
}

/// [`Brdf::directional_albedo_batch`] of a prepared GGX dielectric lobe:
/// `out[k] = E_F(μo,k)` (0 at or below the horizon), `μo` as the scalar read
/// takes it ([`unit_cos_theta`](super::unit_cos_theta), per element), the
/// table read in [`LANES`] lanes from the reader's combined `rows`; a tail of `len % LANES` through the scalar
/// read. Lane for lane the scalar value.
pub(crate) fn dielectric_albedo<S: Spectrum>(
    reader: &super::fresnel_table::DielectricAlbedoReader,
    rows: &super::fresnel_table::DielectricAlbedoRows,
    wo: &[Vec3],
    out: &mut [S],
) {
    let lanes = |w: &[Vec3], o: &mut [S]| {
        // `unit_cos_theta` per lane: `z` where every lane passes `is_unit`
        // (`Dirs::is_unit`, the scalar test lane-wise), else lane by lane.
        let mu = match <&[Vec3; LANES]>::try_from(w) {
            Ok(w8) => {
                let d = crate::simd::Dirs::from_aos(w8);
                if d.is_unit().all() {
                    d.z
                } else {
                    Vf::from(w8.map(super::unit_cos_theta))
                }
            }
            Err(_) => Vf::ZERO,
        };
        let e = clamp01(rows.albedo_lanes(mu));
        let e = mu.simd_gt(Vf::ZERO).select(e, Vf::ZERO).to_array();
        for (o, &e) in o.iter_mut().zip(&e) {
            *o = S::splat(e);
        }
    };
    let one = |w: Vec3| {
        let mu = super::unit_cos_theta(w);
        S::splat(if mu > 0.0 {
            radiometry::math::clamp01(reader.albedo(mu))
        } else {
            0.0
        })
    };
    crate::simd::albedo_chunks(wo, out, lanes, one);
}

#[cfg(test)]
mod wiring_tests {
    use super::DistributionKind;
    use crate::microfacet::{Beckmann, Ggx, MicrofacetDistribution};

    /// Both built-in distributions opt into their vector kernels (a lost
    /// `batch_kind` override would silently fall back to the scalar loop,
    /// which the bit-identity tests cannot notice).
    #[test]
    fn builtin_distributions_select_their_kernels() {
        assert!(matches!(
            Ggx::new(0.3).unwrap().batch_kind(),
            DistributionKind::Ggx { .. }
        ));
        assert!(matches!(
            Beckmann::new(0.3).unwrap().batch_kind(),
            DistributionKind::Beckmann { .. }
        ));
    }
}
