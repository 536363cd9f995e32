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
use crate::simd::{Batch, Dirs, Kernel, LANES, finite_nonneg};
use core::f32::consts::PI;
use radiometry::Brdf;
use radiometry::glam::Vec3;

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

/// The distribution half of a kernel: `D` from `cos²θh`, `sin²θh`, and the
/// projected area `A(cos θ, sin²θ)`, lane-wise and bit-identical to
/// [`MicrofacetDistribution::d_cos2`] / [`projected_area`](MicrofacetDistribution::projected_area).
trait DistV {
    /// `(D, cold)`: `cold` masks the lanes this kernel does not evaluate
    /// (handed back to the scalar method).
    fn d_cos2(&self, cos2: Vf, sin2: Vf) -> (Vf, Vf);
    fn area(&self, cos_theta: Vf, sin2: Vf) -> Vf;
}

/// GGX: `D = α²/(π (α² cos²θh + sin²θh)²)` (Walter et al. 2007, eq. 33),
/// `A = (cos θ + √(cos²θ + α² sin²θ))/2`.
#[derive(Clone, Copy)]
struct GgxV {
    /// `α²`, rounded as `Ggx` rounds it.
    a2: Vf,
}

impl GgxV {
    #[inline(always)]
    fn new(alpha: f32) -> GgxV {
        GgxV {
            a2: Vf::splat(alpha * alpha),
        }
    }
}

impl DistV for GgxV {
    #[inline(always)]
    fn d_cos2(&self, cos2: Vf, sin2: Vf) -> (Vf, Vf) {
        let t = self.a2 * cos2 + sin2;
        (finite_nonneg(self.a2 / (Vf::splat(PI) * t * t)), Vf::ZERO)
    }

    #[inline(always)]
    fn area(&self, cos_theta: Vf, sin2: Vf) -> Vf {
        Vf::splat(0.5) * (cos_theta + (cos_theta * cos_theta + self.a2 * sin2).sqrt())
    }
}

/// Beckmann: `D = exp(−tan²θh/α²)/(π α² cos⁴θh)` (Walter et al. 2007,
/// eq. 25) and `A = cos θ (1 + Λ)` with the loop-free `Λ` (Heitz 2014,
/// eq. 80 through a fitted `T(a)`), both the scalar code lane for lane
/// (`super::beckmann::lanes`); lanes with `cos²θh < 10⁻⁸` (the scalar `D`'s
/// other form) are handed back.
struct BeckmannV {
    alpha: f32,
}

impl DistV for BeckmannV {
    #[inline(always)]
    fn d_cos2(&self, cos2: Vf, sin2: Vf) -> (Vf, Vf) {
        super::beckmann::lanes::d_cos2(self.alpha, cos2, sin2)
    }

    #[inline(always)]
    fn area(&self, cos_theta: Vf, sin2: Vf) -> Vf {
        super::beckmann::lanes::projected_area(self.alpha, cos_theta, sin2)
    }
}

/// `Half::of` lane-wise: `(valid, |h|², cos²θh, sin²θh)` of `h = ωi + ωo`,
/// valid where both directions are strictly above the horizon and
/// `|h|² > 10⁻¹⁴` (NaN → invalid).
#[inline(always)]
fn half(wi: Dirs, wo: Dirs) -> (Vf, Vf, Vf, Vf) {
    let zero = Vf::ZERO;
    let h = wi.add(wo);
    let len2 = h.length_squared();
    let valid = wi.z.simd_gt(zero) & wo.z.simd_gt(zero) & len2.simd_gt(Vf::splat(1e-14));
    let inv = Vf::ONE / len2;
    (valid, len2, (h.z * h.z) * inv, h.xy_length_squared() * inv)
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
        let (valid, len2, cos2, sin2) = half(wi, wo);
        let (d, d_cold) = self.dist.d_cos2(cos2, sin2);
        let ai = self.dist.area(wi.z, wi.xy_length_squared());
        let ao = self.dist.area(wo.z, wo.xy_length_squared());
        let four = Vf::splat(4.0);
        let v = if SEPARABLE {
            Vf::ONE / (four * (ai * ao))
        } else {
            Vf::ONE / (four * ((wo.z * ai + wi.z * ao) - wi.z * wo.z))
        };
        let s = valid.select(finite_nonneg(d * v), Vf::ZERO);
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
        let (valid, _, cos2, sin2) = half(wi, wo);
        let (d, d_cold) = self.dist.d_cos2(cos2, sin2);
        let ao = self.dist.area(wo.z, wo.xy_length_squared());
        let p = finite_nonneg(d / (Vf::splat(4.0) * ao));
        *out = valid.select(p, Vf::ZERO).to_array();
        cold_lanes(wi, wo) | (valid & d_cold).to_bitmask()
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
            dist: GgxV::new(alpha),
        }),
        (DistributionKind::Ggx { alpha }, G2Kind::Separable) => io.run(&Eval::<_, _, _, _, true> {
            b,
            dist: GgxV::new(alpha),
        }),
        (DistributionKind::Beckmann { alpha }, G2Kind::HeightCorrelated) => {
            io.run(&Eval::<_, _, _, _, false> {
                b,
                dist: BeckmannV { alpha },
            })
        }
        (DistributionKind::Beckmann { alpha }, G2Kind::Separable) => io.run(&Eval::<_, _, _, _, true> {
            b,
            dist: BeckmannV { alpha },
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
            dist: BeckmannV { alpha },
        }),
        _ => io.scalar(|wi, wo| b.pdf(wi, wo)),
    }
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
