//! Smith shadowing–masking `G2`, chosen by type.

use super::{MicrofacetDistribution, tan2_theta_robust};
use radiometry::glam::Vec3;

/// How shadowing (of `ωi`) and masking (of `ωo`) combine into `G2`.
///
/// Implemented by the zero-sized [`HeightCorrelated`] and [`Separable`];
/// both are Smith models built from the distribution's `Λ` (Heitz 2014,
/// "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs",
/// JCGT 3(2), §6). Both return values in `[0, 1]`, and `0` when either
/// direction is grazing (`Λ = ∞`).
///
/// ```
/// use radiometry::glam::Vec3;
/// use radiometry_brdfs::microfacet::{Ggx, HeightCorrelated, Separable, ShadowingMasking};
/// let d = Ggx::new(0.5).unwrap();
/// let (wi, wo) = (Vec3::new(0.6, 0.0, 0.8), Vec3::new(0.0, 0.8, 0.6));
/// // Height correlation removes double-counted occlusion: G2 is larger.
/// assert!(HeightCorrelated::g2(&d, wi, wo) >= Separable::g2(&d, wi, wo));
/// ```
pub trait ShadowingMasking {
    /// `G2 ∈ [0, 1]` from `tan²θi` and `tan²θo` (each in `[0, +∞]`, `+∞`
    /// at grazing): the fast form the BRDF's hot path calls. Symmetric in its
    /// arguments bit for bit.
    fn g2_tan2<D: MicrofacetDistribution>(d: &D, tan2_i: f32, tan2_o: f32) -> f32;

    /// `G2(ωi, ωo) ∈ [0, 1]` for directions in the upper hemisphere (the
    /// BRDF excludes the others before calling this). Inputs of any length
    /// are normalised robustly; degenerate ones count as grazing (`G2 = 0`).
    #[inline]
    fn g2<D: MicrofacetDistribution>(d: &D, wi: Vec3, wo: Vec3) -> f32 {
        Self::g2_tan2(d, tan2_theta_robust(wi), tan2_theta_robust(wo))
    }

    /// Hidden hook of the `simd` feature: which vectorised `G2` (if any) the
    /// batched microfacet kernel may use. The default keeps the scalar loop.
    /// Not part of the stable API.
    #[cfg(feature = "simd")]
    #[doc(hidden)]
    const BATCH_KIND: crate::simd::G2Kind = crate::simd::G2Kind::Scalar;
}

/// Height-correlated Smith `G2 = 1/(1 + Λ(ωi) + Λ(ωo))` (Heitz 2014,
/// eq. 99; used by pbrt-v4, PBR 4th ed. §9.6.3).
///
/// ```
/// use radiometry::glam::Vec3;
/// use radiometry_brdfs::microfacet::{Beckmann, HeightCorrelated, ShadowingMasking};
/// let d = Beckmann::new(0.2).unwrap();
/// assert_eq!(HeightCorrelated::g2(&d, Vec3::Z, Vec3::Z), 1.0);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct HeightCorrelated;

/// Separable (uncorrelated) Smith `G2 = G1(ωi) G1(ωo)` (Walter et al. 2007,
/// eq. 23; Heitz 2014, eq. 98; used by Mitsuba 3).
///
/// ```
/// use radiometry::glam::Vec3;
/// use radiometry_brdfs::microfacet::{Ggx, Separable, ShadowingMasking};
/// let d = Ggx::new(0.2).unwrap();
/// assert_eq!(Separable::g2(&d, Vec3::X, Vec3::Z), 0.0); // grazing ωi
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Separable;

impl ShadowingMasking for HeightCorrelated {
    #[cfg(feature = "simd")]
    const BATCH_KIND: crate::simd::G2Kind = crate::simd::G2Kind::HeightCorrelated;

    #[inline]
    fn g2_tan2<D: MicrofacetDistribution>(d: &D, tan2_i: f32, tan2_o: f32) -> f32 {
        // 1 + (Λi + Λo): the inner sum commutes exactly, so G2 is reciprocal
        // bit for bit. s ≥ 1, possibly +∞ (→ 0); never NaN since Λ ≥ 0.
        let s = 1.0 + (d.lambda_tan2(tan2_i) + d.lambda_tan2(tan2_o));
        if s >= 1.0 { 1.0 / s } else { 0.0 }
    }
}

impl ShadowingMasking for Separable {
    #[cfg(feature = "simd")]
    const BATCH_KIND: crate::simd::G2Kind = crate::simd::G2Kind::Separable;

    #[inline]
    fn g2_tan2<D: MicrofacetDistribution>(d: &D, tan2_i: f32, tan2_o: f32) -> f32 {
        d.g1_tan2(tan2_i) * d.g1_tan2(tan2_o)
    }
}
