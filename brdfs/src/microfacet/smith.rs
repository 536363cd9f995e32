//! Smith shadowing–masking `G2`, chosen by type.

use super::MicrofacetDistribution;
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
    /// `G2(ωi, ωo) ∈ [0, 1]` for directions in the upper hemisphere (the
    /// BRDF excludes the others before calling this).
    fn g2<D: MicrofacetDistribution>(d: &D, wi: Vec3, wo: Vec3) -> f32;

    /// The visibility term `V = G2(ωi, ωo) / (4 cos θi cos θo)` of unit
    /// directions strictly above the horizon, from their cosines and the
    /// projected areas `A(ω) = cos θ (1 + Λ(ω))` of the microsurface
    /// ([`MicrofacetDistribution::projected_area`]). With it the BRDF is
    /// `f_r = D(h) V F`, and the `1/cos` factors never appear on their own:
    /// `V` stays finite as either cosine goes to 0 (its limit is the
    /// grazing value of `f_r`, not a `0·∞`). Symmetric in `(i, o)` bit for bit.
    fn visibility(cos_i: f32, area_i: f32, cos_o: f32, area_o: f32) -> f32;

    /// `1/V = 4 cos θi cos θo / G2(ωi, ωo)` from the same inputs as
    /// [`visibility`](Self::visibility): the denominator the BRDF's hot path
    /// folds into its one division (`D/(1/V)`). Positive for directions
    /// strictly above the horizon; symmetric in `(i, o)` bit for bit. The
    /// default is `1/visibility`.
    #[inline]
    fn inverse_visibility(cos_i: f32, area_i: f32, cos_o: f32, area_o: f32) -> f32 {
        1.0 / Self::visibility(cos_i, area_i, cos_o, area_o)
    }

    /// Hidden hook of the `simd` feature: which vectorised `G2` (if any) the
    /// batched microfacet kernel may use. The default keeps the scalar loop.
    /// Not part of the stable API.
    /// This variant's table among a distribution's tabulated albedos
    /// ([`MicrofacetDistribution::energy_tables`]). Default `None`;
    /// [`HeightCorrelated`] and [`Separable`] pick theirs.
    fn select_table(tables: &super::EnergyTables) -> Option<&'static super::AlbedoTable> {
        let _ = tables;
        None
    }

    #[cfg(feature = "simd")]
    #[doc(hidden)]
    const BATCH_KIND: super::G2Kind = super::G2Kind::Scalar;
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
    fn select_table(tables: &super::EnergyTables) -> Option<&'static super::AlbedoTable> {
        Some(tables.height_correlated)
    }

    #[cfg(feature = "simd")]
    const BATCH_KIND: super::G2Kind = super::G2Kind::HeightCorrelated;

    #[inline]
    fn g2<D: MicrofacetDistribution>(d: &D, wi: Vec3, wo: Vec3) -> f32 {
        let s = 1.0 + d.lambda(wi) + d.lambda(wo);
        // s ≥ 1, possibly +∞ (→ 0); never NaN since Λ ≥ 0.
        if s >= 1.0 { 1.0 / s } else { 0.0 }
    }

    /// `V = 1 / (4 cos θi cos θo (1 + Λi + Λo))`, with
    /// `cos θi cos θo (1 + Λi + Λo) = cos θo Ai + cos θi Ao − cos θi cos θo`
    /// (each product is at least the subtracted one, so the difference loses
    /// at most a factor 2 in relative accuracy). For GGX it is the familiar
    /// `1 / (2 (cos θo √(cos²θi + α² sin²θi) + cos θi √(cos²θo + α² sin²θo)))`
    /// (Heitz 2014, eq. 99 divided through).
    #[inline(always)]
    fn visibility(cos_i: f32, area_i: f32, cos_o: f32, area_o: f32) -> f32 {
        1.0 / Self::inverse_visibility(cos_i, area_i, cos_o, area_o)
    }

    /// `1/V = 4 ((cos θo Ai + cos θi Ao) − cos θi cos θo)`.
    #[inline(always)]
    fn inverse_visibility(cos_i: f32, area_i: f32, cos_o: f32, area_o: f32) -> f32 {
        4.0 * ((cos_o * area_i + cos_i * area_o) - cos_i * cos_o)
    }
}

impl ShadowingMasking for Separable {
    fn select_table(tables: &super::EnergyTables) -> Option<&'static super::AlbedoTable> {
        Some(tables.separable)
    }

    #[cfg(feature = "simd")]
    const BATCH_KIND: super::G2Kind = super::G2Kind::Separable;

    #[inline]
    fn g2<D: MicrofacetDistribution>(d: &D, wi: Vec3, wo: Vec3) -> f32 {
        d.g1(wi) * d.g1(wo)
    }

    /// `V = G1(ωi) G1(ωo) / (4 cos θi cos θo) = 1 / (4 Ai Ao)`, since
    /// `G1(ω) = cos θ / A(ω)`.
    #[inline(always)]
    fn visibility(cos_i: f32, area_i: f32, cos_o: f32, area_o: f32) -> f32 {
        1.0 / Self::inverse_visibility(cos_i, area_i, cos_o, area_o)
    }

    /// `1/V = 4 Ai Ao`.
    #[inline(always)]
    fn inverse_visibility(_cos_i: f32, area_i: f32, _cos_o: f32, area_o: f32) -> f32 {
        4.0 * (area_i * area_o)
    }
}
