//! The 8-wide kernels of [`Microfacet`] (feature `simd`): `eval_batch`,
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
use crate::simd::{Batch, Kernel8, LANES, V8, finite_nonneg};
use core::f32::consts::PI;
use radiometry::Brdf;
use radiometry::glam::Vec3;
use wide::f32x8;

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

/// The distribution half of a kernel: `D` from `cos²θh`, `sin²θh`, and the
/// projected area `A(cos θ, sin²θ)`, lane-wise and bit-identical to
/// [`MicrofacetDistribution::d_cos2`] / [`projected_area`](MicrofacetDistribution::projected_area).
trait DistX8 {
    fn d_cos2(&self, cos2: f32x8, sin2: f32x8) -> f32x8;
    fn area(&self, cos_theta: f32x8, sin2: f32x8) -> f32x8;
}

/// GGX: `D = α²/(π (α² cos²θh + sin²θh)²)` (Walter et al. 2007, eq. 33),
/// `A = (cos θ + √(cos²θ + α² sin²θ))/2`.
#[derive(Clone, Copy)]
struct GgxX8 {
    /// `α²`, rounded as `Ggx` rounds it.
    a2: f32x8,
}

impl GgxX8 {
    #[inline(always)]
    fn new(alpha: f32) -> GgxX8 {
        GgxX8 {
            a2: f32x8::splat(alpha * alpha),
        }
    }
}

impl DistX8 for GgxX8 {
    #[inline(always)]
    fn d_cos2(&self, cos2: f32x8, sin2: f32x8) -> f32x8 {
        let t = self.a2 * cos2 + sin2;
        finite_nonneg(self.a2 / (f32x8::splat(PI) * t * t))
    }

    #[inline(always)]
    fn area(&self, cos_theta: f32x8, sin2: f32x8) -> f32x8 {
        f32x8::splat(0.5) * (cos_theta + (cos_theta * cos_theta + self.a2 * sin2).sqrt())
    }
}

/// `Half::of` lane-wise: `(valid, |h|², cos²θh, sin²θh)` of `h = ωi + ωo`,
/// valid where both directions are strictly above the horizon and
/// `|h|² > 10⁻¹⁴` (NaN → invalid).
#[inline(always)]
fn half(wi: V8, wo: V8) -> (f32x8, f32x8, f32x8, f32x8) {
    let zero = f32x8::ZERO;
    let h = wi.add(wo);
    let len2 = h.length_squared();
    let valid = wi.z.simd_gt(zero) & wo.z.simd_gt(zero) & len2.simd_gt(f32x8::splat(1e-14));
    let inv = f32x8::ONE / len2;
    (valid, len2, (h.z * h.z) * inv, h.xy_length_squared() * inv)
}

/// Bit `k` set when lane `k` is not on the hot path (a direction that is
/// not unit to within `4ε`): the scalar method recomputes it.
#[inline(always)]
fn cold_lanes(wi: V8, wo: V8) -> u32 {
    (!(wi.is_unit() & wo.is_unit())).to_bitmask()
}

/// `eval` of `Microfacet<D, G, F>` with the distribution kernel `X`.
struct Eval<'a, D, G, F, X, const SEPARABLE: bool> {
    b: &'a Microfacet<D, G, F>,
    dist: X,
}

impl<D, G, F, X, const SEPARABLE: bool> Kernel8 for Eval<'_, D, G, F, X, SEPARABLE>
where
    D: MicrofacetDistribution,
    G: ShadowingMasking,
    F: Fresnel,
    X: DistX8,
{
    type Out = F::Spectrum;

    #[inline(always)]
    fn x8(&self, wi: V8, wo: V8, out: &mut [F::Spectrum; LANES]) {
        let cold = cold_lanes(wi, wo);
        let (valid, len2, cos2, sin2) = half(wi, wo);
        let d = self.dist.d_cos2(cos2, sin2);
        let ai = self.dist.area(wi.z, wi.xy_length_squared());
        let ao = self.dist.area(wo.z, wo.xy_length_squared());
        let four = f32x8::splat(4.0);
        let v = if SEPARABLE {
            f32x8::ONE / (four * (ai * ao))
        } else {
            f32x8::ONE / (four * ((wo.z * ai + wi.z * ao) - wi.z * wo.z))
        };
        let s = valid.select(finite_nonneg(d * v), f32x8::ZERO);
        // cos θd = |ωi + ωo|/2 (`Half::cos_theta_d`).
        let cos_d = (f32x8::splat(0.5) * len2.sqrt()).min(f32x8::ONE);
        self.b.fresnel.eval_scaled_x8(cos_d, s, out);
        if cold != 0 {
            self.fix_cold(cold, wi, wo, out);
        }
    }

    #[inline(always)]
    fn one(&self, wi: Vec3, wo: Vec3) -> F::Spectrum {
        self.b.eval(wi, wo)
    }
}

impl<D, G, F, X, const SEPARABLE: bool> Eval<'_, D, G, F, X, SEPARABLE>
where
    D: MicrofacetDistribution,
    G: ShadowingMasking,
    F: Fresnel,
{
    /// Recomputes the lanes in `cold` with the scalar `eval`.
    #[cold]
    #[inline(never)]
    fn fix_cold(&self, cold: u32, wi: V8, wo: V8, out: &mut [F::Spectrum; LANES]) {
        for (k, o) in out.iter_mut().enumerate() {
            if cold & (1 << k) != 0 {
                *o = self.b.eval(wi.lane(k), wo.lane(k));
            }
        }
    }
}

/// `pdf` of `Microfacet<D, G, F>` with the distribution kernel `X`:
/// `D(h)/(4 A(ωo))`.
struct Pdf<'a, D, G, F, X> {
    b: &'a Microfacet<D, G, F>,
    dist: X,
}

impl<D, G, F, X> Kernel8 for Pdf<'_, D, G, F, X>
where
    D: MicrofacetDistribution,
    G: ShadowingMasking,
    F: Fresnel,
    X: DistX8,
{
    type Out = f32;

    #[inline(always)]
    fn x8(&self, wi: V8, wo: V8, out: &mut [f32; LANES]) {
        let cold = cold_lanes(wi, wo);
        let (valid, _, cos2, sin2) = half(wi, wo);
        let d = self.dist.d_cos2(cos2, sin2);
        let ao = self.dist.area(wo.z, wo.xy_length_squared());
        let p = finite_nonneg(d / (f32x8::splat(4.0) * ao));
        *out = valid.select(p, f32x8::ZERO).to_array();
        if cold != 0 {
            for (k, o) in out.iter_mut().enumerate() {
                if cold & (1 << k) != 0 {
                    *o = self.b.pdf(wi.lane(k), wo.lane(k));
                }
            }
        }
    }

    #[inline(always)]
    fn one(&self, wi: Vec3, wo: Vec3) -> f32 {
        self.b.pdf(wi, wo)
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
            dist: GgxX8::new(alpha),
        }),
        (DistributionKind::Ggx { alpha }, G2Kind::Separable) => io.run(&Eval::<_, _, _, _, true> {
            b,
            dist: GgxX8::new(alpha),
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
            dist: GgxX8::new(alpha),
        }),
        _ => io.scalar(|wi, wo| b.pdf(wi, wo)),
    }
}
