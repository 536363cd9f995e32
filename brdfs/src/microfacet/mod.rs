//! Isotropic microfacet reflection: GGX / Trowbridge–Reitz and Beckmann
//! normal distributions, Smith shadowing–masking (height-correlated or
//! separable) and Fresnel variants, each chosen by type.
//!
//! The BRDF is the Cook–Torrance / Walter et al. microfacet model
//! (Walter, Marschner, Li & Torrance 2007, "Microfacet Models for Refraction
//! through Rough Surfaces", EGSR, eq. 20):
//!
//! ```text
//! f_r(ωi, ωo) = D(h) · G2(ωi, ωo) · F(ωi·h) / (4 cos θi cos θo),   h = (ωi + ωo)/|ωi + ωo|
//! ```
//!
//! * `D` — [`Ggx`] or [`Beckmann`], implementing [`MicrofacetDistribution`];
//! * `G2` — [`HeightCorrelated`] (default; pbrt-v4) or [`Separable`]
//!   (Mitsuba 3), implementing [`ShadowingMasking`];
//! * `F` — [`NoFresnel`] (default, `F = 1`), [`Schlick`], [`Dielectric`],
//!   [`Conductor`] or the F82-tint metal term [`F82Tint`] (OpenPBR),
//!   implementing [`Fresnel`]; [`Achromatic`] puts a monochrome term on
//!   every channel of an RGB or spectral BRDF.
//!
//! Zero-sized choices (`NoFresnel`, `HeightCorrelated`, `Separable`) cost
//! nothing at run time: `NoFresnel::eval` is the constant `1.0` and inlines
//! away.
//!
//! Sampling draws a microfacet normal from the distribution of *visible*
//! normals of `ωo` (Heitz & d'Eon 2014) and reflects `ωo` about it. See
//! [`Microfacet`] for the pdf and the probability mass that is lost below the
//! horizon.
//!
//! ```
//! use radiometry::{Brdf, glam::Vec3};
//! use radiometry_brdfs::microfacet::{Ggx, Microfacet, NoFresnel, Separable};
//! # fn main() -> Result<(), radiometry_brdfs::BrdfError> {
//! let b = Microfacet::<_, Separable, _>::new(Ggx::new(0.3)?, NoFresnel);
//! let wo = Vec3::new(0.0, 0.6, 0.8);
//! let s = b.sample(wo, [0.3, 0.7]).unwrap();
//! assert!((s.pdf - b.pdf(s.wi, wo)).abs() <= 1e-4 * s.pdf);
//! # Ok(())
//! # }
//! ```

mod achromatic;
mod albedo_data;
mod albedo_table;
#[cfg(feature = "simd")]
mod batch;
mod beckmann;
mod beckmann_f32;
#[cfg(feature = "simd")]
mod beckmann_lanes;
mod beckmann_slope;
mod beckmann_slope_table;
mod beckmann_tail;
mod e1_average_data;
pub(crate) mod f82;
mod fresnel;
pub mod fresnel_table;
mod fresnel_table_data;
mod ggx;
pub(crate) mod ggx_pair;
mod kulla_conty;
pub(crate) mod ms_sampler;
#[doc(hidden)]
pub mod prepared;
mod smith;
mod special;
#[cfg(feature = "simd")]
mod special_lanes;
pub(crate) mod transmission_sampler;

#[cfg(test)]
mod tests;

pub use achromatic::Achromatic;
pub use albedo_table::{
    ALBEDO_TABLE_ERROR, ALPHA_REF, AlbedoReader, AlbedoTable, EnergyTable, EnergyTables, N_ALPHA, N_MU,
    alpha_node, mu_node, node_scale,
};
#[cfg(feature = "simd")]
#[doc(hidden)]
pub use batch::{DistributionKind, G2Kind};
pub use beckmann::Beckmann;
pub use f82::{F82Tint, MU_BAR};
pub use fresnel::{Conductor, Dielectric, Fresnel, FresnelForm, MAX_ETA, MAX_K, MIN_ETA, NoFresnel, Schlick};
pub use ggx::Ggx;
pub use kulla_conty::{KullaConty, LOSS_MARGIN};
pub use smith::{HeightCorrelated, Separable, ShadowingMasking};

use core::marker::PhantomData;
use fresnel_table::FRESNEL_TABLE_ERROR;
#[cfg(feature = "simd")]
use radiometry::batch::Vec3Soa;
use radiometry::frame::half_vector_sum;
use radiometry::glam::Vec3;
use radiometry::{Albedo, Brdf, BrdfSample, IsotropicBrdf, Spectrum};

/// Smallest accepted roughness `α` (pbrt-v4 uses the same floor). At this
/// value the GGX peak `D(+Z) = 1/(π α²) ≈ 3.2·10⁷` is still comfortably
/// finite in `f32`.
pub const MIN_ALPHA: f32 = 1e-4;

/// Largest accepted roughness `α`.
pub const MAX_ALPHA: f32 = 1.0;

/// An isotropic microfacet normal distribution with Smith masking.
///
/// Directions and normals are in the local frame (normal `+Z`); inputs need
/// not be unit length (they are normalised; the zero vector and non-finite
/// vectors are treated as degenerate and give `0`, or `+Z` for samplers).
///
/// Conventions shared by all implementors (Walter et al. 2007, §5;
/// Heitz 2014, "Understanding the Masking-Shadowing Function in
/// Microfacet-Based BRDFs", JCGT 3(2)):
/// * `∫_Ω D(m) cos θm dm = 1` (projected-area normalisation, eq. 4 of Walter);
/// * `G1(ω) = 1/(1 + Λ(ω))` (Smith; Heitz 2014 eq. 43), where `Λ` depends on
///   `|tan θ|` only, so `g1` and `lambda` are symmetric under `z → −z`;
/// * the visible-normal density `D_ωo(m) = G1(ωo) ⟨ωo·m⟩ D(m) / cos θo`
///   (Heitz 2014 eq. 38) integrates to 1 over the hemisphere of `m`.
///
/// ```
/// use radiometry::glam::Vec3;
/// use radiometry_brdfs::microfacet::{Beckmann, Ggx, MicrofacetDistribution};
/// fn check<D: MicrofacetDistribution>(d: &D) {
///     let wo = Vec3::new(0.6, 0.0, 0.8);
///     let m = d.sample_visible(wo, [0.25, 0.5]);
///     assert!(m.z >= 0.0 && (m.length() - 1.0).abs() < 1e-5);
///     assert!(d.visible_pdf(wo, m) > 0.0);
///     assert!((d.g1(wo) - 1.0 / (1.0 + d.lambda(wo))).abs() < 1e-6);
/// }
/// check(&Ggx::new(0.4).unwrap());
/// check(&Beckmann::new(0.4).unwrap());
/// ```
pub trait MicrofacetDistribution {
    /// The roughness `α ∈ [MIN_ALPHA, MAX_ALPHA]`.
    fn alpha(&self) -> f32;

    /// The normal distribution `D(m)` [sr⁻¹]; `0` for `cos θm ≤ 0`.
    fn d(&self, m: Vec3) -> f32;

    /// The Smith auxiliary function `Λ(ω) ∈ [0, +∞]`.
    ///
    /// `Λ = +∞` exactly at grazing (`cos θ = 0`, `tan² θ = ∞`) and where the
    /// true value exceeds the `f32` range; this is the only non-finite output
    /// of this module and it is deliberate (it is the limit; `g1` and the
    /// `G2` variants map it to 0).
    fn lambda(&self, w: Vec3) -> f32;

    /// Smith masking `G1(ω) = 1/(1 + Λ(ω)) ∈ [0, 1]`; `0` at grazing.
    fn g1(&self, w: Vec3) -> f32 {
        1.0 / (1.0 + self.lambda(w))
    }

    /// `D(m)` of a unit normal given `cos²θm` and `sin²θm` — the fast form
    /// behind [`d`](Self::d) that the BRDF's hot path calls once it has
    /// validated its input. The two squares are passed separately so that
    /// neither is formed by the cancelling difference `1 − other` (for the
    /// half vector `h ∝ ωi + ωo` they are `h_z²/|h|²` and `(h_x² + h_y²)/|h|²`).
    ///
    /// Contract: `cos2 ≥ 0`, `sin2 ≥ 0`, `cos2 + sin2 ≈ 1`, the normal in the
    /// upper hemisphere; returns a finite value `≥ 0` (0 where `cos2 = 0`).
    /// The default builds the unit vector `(sin θ, 0, cos θ)` and calls
    /// [`d`](Self::d) (exact for an isotropic distribution).
    #[inline]
    fn d_cos2(&self, cos2: f32, sin2: f32) -> f32 {
        self.d(Vec3::new(
            radiometry::math::sqrtf(sin2),
            0.0,
            radiometry::math::sqrtf(cos2),
        ))
    }

    /// `D` of the direction of a nonzero vector `h` that need not be unit,
    /// as a quotient `(num, den)`, `D = num/den`, given `hz2 = h_z²` and
    /// `hxy2 = h_x² + h_y²`. `D` is homogeneous of degree 0 in the two
    /// squares, so the BRDF's hot path passes those of the un-normalised half
    /// vector `h ∝ ωi + ωo` (no division to normalise it), and it divides
    /// once for `D V` or `D/(4A)` (the quotient is folded into that division).
    ///
    /// Contract: `hz2, hxy2 ≥ 0` with `hz2 + hxy2 ∈ [2⁻³², 2³²]` (the hot
    /// path has `hz2 > 0`); returns finite `num ≥ 0` and `den > 0` with
    /// `num/den` finite. The default normalises, calls [`d_cos2`](Self::d_cos2) and
    /// returns `(D, 1)`; [`Ggx`] and [`Beckmann`] evaluate their formulas in
    /// the squares directly.
    #[inline]
    fn d_ratio(&self, hz2: f32, hxy2: f32) -> (f32, f32) {
        let inv = 1.0 / (hz2 + hxy2);
        (self.d_cos2(hz2 * inv, hxy2 * inv), 1.0)
    }

    /// The projected area of the microsurface seen from a unit direction
    /// `ω` above the horizon, `A(ω) = ∫ ⟨ω·m⟩ D(m) dm = cos θ (1 + Λ(ω))`
    /// (Heitz 2014, eq. 16 with the Smith `Λ`), from `cos θ ≥ 0` and
    /// `sin²θ = x² + y²`. It is what the hot path uses instead of `Λ`:
    /// `G1 = cos θ / A`, and [`ShadowingMasking::visibility`] combines two of
    /// them without any `1/cos θ`. `A ≥ cos θ`, and `A > 0` even at grazing
    /// (where `cos θ Λ` has a finite limit).
    ///
    /// The default is `cos θ (1 + Λ)` through
    /// [`lambda_tan2`](Self::lambda_tan2) (`+∞` where `cos²θ` underflows,
    /// which makes the BRDF 0 there).
    #[inline]
    fn projected_area(&self, cos_theta: f32, sin2: f32) -> f32 {
        let c2 = cos_theta * cos_theta;
        let l = if c2 > 0.0 {
            self.lambda_tan2(sin2 / c2)
        } else {
            f32::INFINITY
        };
        if l < f32::INFINITY {
            cos_theta + cos_theta * l
        } else {
            f32::INFINITY
        }
    }

    /// `Λ` as a function of `tan²θ ∈ [0, +∞]` — the fast form behind
    /// [`lambda`](Self::lambda) (Λ of an isotropic distribution depends on
    /// `|tan θ|` only). `tan2 = +∞` (grazing) gives `+∞`; NaN is treated as
    /// grazing. The default calls [`lambda`](Self::lambda) on
    /// `(tan θ, 0, 1)` (its length does not matter to `Λ`).
    #[inline]
    fn lambda_tan2(&self, tan2: f32) -> f32 {
        if tan2 < f32::INFINITY {
            self.lambda(Vec3::new(radiometry::math::sqrtf(tan2.max(0.0)), 0.0, 1.0))
        } else {
            f32::INFINITY
        }
    }

    /// `G1 = 1/(1 + Λ)` as a function of `tan²θ` (see
    /// [`lambda_tan2`](Self::lambda_tan2)); `0` at grazing.
    #[inline]
    fn g1_tan2(&self, tan2: f32) -> f32 {
        1.0 / (1.0 + self.lambda_tan2(tan2))
    }

    /// Samples a microfacet normal `m` from the distribution of normals
    /// visible from `wo`, `D_ωo(m) = G1(ωo) max(0, ωo·m) D(m) / cos θo`.
    ///
    /// `u ∈ [0, 1]²` (any values are clamped into it, NaN to 0). A `wo`
    /// below the horizon is mirrored to `(x, y, |z|)` first (as
    /// [`visible_pdf`](Self::visible_pdf) does). Always returns a finite unit
    /// vector with `z ≥ 0`.
    fn sample_visible(&self, wo: Vec3, u: [f32; 2]) -> Vec3;

    /// The tabulated single-scattering albedos `E(μ, α)` (`F = 1`) of this
    /// distribution, one per Smith variant, if the crate has them: what
    /// [`Microfacet`]'s `directional_albedo` reads. Default `None` (a
    /// third-party distribution gets the sampling rule of
    /// [`Brdf::directional_albedo`]); [`Ggx`] and [`Beckmann`] return theirs.
    fn energy_tables(&self) -> Option<EnergyTables> {
        None
    }

    /// Hidden hook of the `simd` feature: which vectorised kernel (if any)
    /// the batch methods of [`Microfacet`] may use for this distribution.
    /// The default, `DistributionKind::Scalar`, keeps the scalar loop;
    /// [`Ggx`] and [`Beckmann`] override it. Not part of the stable API.
    #[cfg(feature = "simd")]
    #[doc(hidden)]
    #[inline]
    fn batch_kind(&self) -> DistributionKind {
        DistributionKind::Scalar
    }

    /// The density of [`sample_visible`](Self::sample_visible) with respect to
    /// solid angle of `m`: `G1(ωo) max(0, ωo·m) D(m) / cos θo` (Heitz &
    /// d'Eon 2014, eq. 2), with `ωo` mirrored to the upper hemisphere; `0` at
    /// grazing `ωo` and for `cos θm ≤ 0`.
    fn visible_pdf(&self, wo: Vec3, m: Vec3) -> f32 {
        let (Some(wo), Some(m)) = (unitize(wo), unitize(m)) else {
            return 0.0;
        };
        let wo = Vec3::new(wo.x, wo.y, wo.z.abs());
        let dot = wo.dot(m);
        if wo.z <= 0.0 || dot <= 0.0 {
            return 0.0;
        }
        let g1 = self.g1(wo);
        if g1 <= 0.0 {
            return 0.0;
        }
        // G1/cos θo stays bounded (≈ 2/α for GGX) as cos θo → 0.
        finite_nonneg(g1 * (dot / wo.z) * self.d(m))
    }
}

/// Normalises `w` robustly: rescales by its largest component first, so tiny
/// (even subnormal) and huge finite vectors work. `None` for zero or
/// non-finite input.
#[inline]
pub(crate) fn unitize(w: Vec3) -> Option<Vec3> {
    let l2 = w.length_squared();
    // Already unit to within a few ulp: return it unchanged, which makes
    // `unitize` idempotent (so `sample` and `pdf` see bit-identical vectors).
    if (l2 - 1.0).abs() <= 4.0 * f32::EPSILON {
        return Some(w);
    }
    if (1e-30..=1e30).contains(&l2) {
        return Some(w * (1.0 / radiometry::math::sqrtf(l2)));
    }
    let s = w.abs().max_element();
    if !(s > 0.0 && s.is_finite()) {
        return None;
    }
    let v = w / s;
    let l2 = v.length_squared();
    if l2 > 0.0 && l2.is_finite() {
        Some(v * (1.0 / radiometry::math::sqrtf(l2)))
    } else {
        None
    }
}

/// `cos θ` of the direction of `w` (`unitize` leaves a unit vector as it
/// is); 0 for a degenerate one (a zero albedo, as the full read gives).
#[inline(always)]
fn unit_cos_theta(w: Vec3) -> f32 {
    if is_unit(w) {
        w.z
    } else {
        unitize(w).map_or(0.0, |w| w.z)
    }
}

/// Whether `w` is unit length to within the tolerance [`unitize`] leaves
/// unchanged (`|‖w‖² − 1| ≤ 4ε`): the one test the hot paths make per
/// direction. False for NaN and infinite components.
#[inline(always)]
pub(crate) fn is_unit(w: Vec3) -> bool {
    (w.length_squared() - 1.0).abs() <= 4.0 * f32::EPSILON
}

/// `tan²θ = (x² + y²)/z²` of a direction of any (non-degenerate, in-range)
/// length; `+∞` when `z² = 0`.
#[inline(always)]
pub(crate) fn tan2_theta_unit(w: Vec3) -> f32 {
    let c2 = w.z * w.z;
    let s2 = w.x * w.x + w.y * w.y;
    if c2 > 0.0 { s2 / c2 } else { f32::INFINITY }
}

/// [`tan2_theta_unit`] after robust normalisation; `+∞` for degenerate input
/// (which Λ maps to `+∞` and `G1` to 0, as at grazing).
#[inline]
pub(crate) fn tan2_theta_robust(w: Vec3) -> f32 {
    match unitize(w) {
        Some(w) => tan2_theta_unit(w),
        None => f32::INFINITY,
    }
}

pub(crate) use radiometry::math::clamp01;

/// Maps NaN to 0 and saturates `+∞` at `f32::MAX` (used only where the
/// exact value exceeds the `f32` range).
#[inline]
pub(crate) fn finite_nonneg(x: f32) -> f32 {
    if x > 0.0 { x.min(f32::MAX) } else { 0.0 }
}

/// An isotropic microfacet reflection BRDF
/// `f_r = D(h) G2(ωi, ωo) F(ωi·h) / (4 cos θi cos θo)` (Walter et al. 2007,
/// eq. 20; Cook & Torrance 1982), with the distribution `D`, the
/// shadowing–masking `G` and the Fresnel term `F` chosen by type.
///
/// * `eval`: zero when either direction is at or below the horizon, or when
///   the half vector is undefined (`ωi = −ωo`). Inputs need not be unit
///   length. Where the exact value exceeds `f32::MAX` (both cosines below
///   ~10⁻¹⁹ in a mirror configuration) it saturates at `f32::MAX`.
/// * `sample`: `m ~ D_ωo` ([`MicrofacetDistribution::sample_visible`]),
///   `ωi = 2(ωo·m)m − ωo`; returns `None` when `ωi` falls at or below the
///   horizon. The weight is `F(ωi·h) G2(ωi, ωo) / G1(ωo)`, which equals
///   `f_r cos θi / pdf`.
/// * `pdf(ωi, ωo) = D_ωo(h) / (4 |ωo·h|) = G1(ωo) D(h) / (4 cos θo)`
///   (Heitz & d'Eon 2014, eq. 5 with the reflection Jacobian of Walter et al.
///   2007, eq. 14). Its integral over the upper hemisphere of `ωi` is
///   `1 − P_below(ωo)`, where `P_below(ωo)` is the probability that the
///   mirror reflection of `ωo` about a visible normal points below the
///   horizon. At normal incidence it is `P(θm > π/4)`, in closed form
///   `α²/(1 + α²)` for GGX and `e^{−1/α²}` for Beckmann (so 0.5 and 0.37 at
///   `α = 1`, 0.0099 and ≈ 0 at `α = 0.1`); measured values at other angles
///   (GGX `α = 1`: 0.45 at θo = 0.6, 0.31 at 1.1, 0.11 at 1.45 rad) are in
///   the unit test `brdf_pdf_mass_matches_below_horizon_loss`.
///
/// ```
/// use radiometry::{Brdf, IsotropicBrdf, glam::Vec3};
/// use radiometry_brdfs::microfacet::{Beckmann, Dielectric, HeightCorrelated, Microfacet};
/// # fn main() -> Result<(), radiometry_brdfs::BrdfError> {
/// let b = Microfacet::<_, HeightCorrelated, _>::new(Beckmann::new(0.2)?, Dielectric::new(1.5)?);
/// let wo = Vec3::new(0.6, 0.0, 0.8);
/// let wi = Vec3::new(-0.6, 0.0, 0.8); // mirror direction
/// let f = b.eval(wi, wo);
/// assert!(f > 0.0 && f.is_finite());
/// assert_eq!(b.eval(-wo, wo), 0.0); // ωi = −ωo: no half vector
/// let iso = b.eval_isotropic(0.6435, 0.6435, core::f32::consts::PI);
/// assert!((iso - f).abs() <= 1e-3 * f);
/// # Ok(())
/// # }
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Microfacet<D, G = HeightCorrelated, F = NoFresnel> {
    /// The normal distribution (already validated by its constructor).
    pub distribution: D,
    /// The Fresnel term (already validated by its constructor).
    pub fresnel: F,
    /// The shadowing–masking choice (zero-sized marker).
    pub shadowing: PhantomData<G>,
}

impl<D, G, F> Microfacet<D, G, F> {
    /// Combines a validated distribution and Fresnel term. The
    /// shadowing–masking variant is the type parameter `G`, e.g.
    /// `Microfacet::<_, Separable, _>::new(d, f)`; with a type annotation
    /// `let b: Microfacet<Ggx> = Microfacet::new(d, NoFresnel);` the default
    /// [`HeightCorrelated`] applies.
    ///
    /// ```
    /// use radiometry_brdfs::microfacet::{Ggx, Microfacet, MicrofacetDistribution, NoFresnel};
    /// let b: Microfacet<Ggx> = Microfacet::new(Ggx::new(0.5).unwrap(), NoFresnel);
    /// assert_eq!(b.distribution.alpha(), 0.5);
    /// ```
    pub const fn new(distribution: D, fresnel: F) -> Self {
        Microfacet {
            distribution,
            fresnel,
            shadowing: PhantomData,
        }
    }
}

/// The half-vector quantities of a valid reflection pair of unit directions
/// above the horizon: `|ωi + ωo|²`, and the squares `h_z²`, `h_x² + h_y²`
/// of the un-normalised, length-corrected half vector `h` (see
/// [`Half::of`]), the input of [`MicrofacetDistribution::d_ratio`].
#[derive(Clone, Copy)]
struct Half {
    len2: f32,
    hz2: f32,
    hxy2: f32,
}

/// Below `|h|² = 2⁻³²` [`Half::of`] scales the squares of `h` by
/// [`HALF_SQUARES_SCALE`] `= 2⁶⁴` (exact), which keeps them inside the
/// range [`MicrofacetDistribution::d_ratio`] accepts (`|h|² > 10⁻¹⁴`
/// for every valid pair).
pub(crate) const HALF_SQUARES_SMALL: f32 = 2.328_306_4e-10;

/// `2⁶⁴`, see [`HALF_SQUARES_SMALL`].
pub(crate) const HALF_SQUARES_SCALE: f32 = 1.844_674_4e19;

impl Half {
    /// `None` when either direction is at or below the horizon or the half
    /// vector is undefined (`|ωi + ωo|² ≤ 10⁻¹⁴`, i.e. `ωi ≈ −ωo`, the
    /// threshold of [`radiometry::frame::half_vector`]). `h` itself is
    /// never normalised: `D` takes the squares of its components
    /// ([`MicrofacetDistribution::d_ratio`]), scaled by `2⁶⁴` where
    /// `|h|² < 2⁻³²` (pairs near `ωi = −ωo` at grazing).
    ///
    /// `h` is [`radiometry::frame::half_vector_sum`]: it points along the
    /// sum of the *normalised* inputs, corrected where `ωi + ωo` cancels
    /// (GGX α = 0.01, both directions at 89.9°: 1.4·10⁻⁴ relative error in
    /// the reflected radiance of a sun-sized cap without the correction,
    /// 10⁻⁸ with it). `cos θd` keeps the plain `|ωi + ωo|/2`: `F` is
    /// insensitive to the correction (≤ 10⁻⁶ absolute), and near `θd = 0` an
    /// `f32` `cos θd` carries a rounding of half an ulp either way.
    #[inline(always)]
    fn of(wi: Vec3, wo: Vec3) -> Option<Half> {
        if !(wi.z > 0.0 && wo.z > 0.0) {
            return None;
        }
        let (h, sum2) = half_vector_sum(wi, wo);
        let len2 = h.length_squared();
        // (Both comparisons are false for NaN.)
        if !(sum2 > 1e-14 && len2 > 1e-14) {
            return None;
        }
        let (hz2, hxy2) = (h.z * h.z, h.x * h.x + h.y * h.y);
        let (hz2, hxy2) = if len2 < HALF_SQUARES_SMALL {
            (hz2 * HALF_SQUARES_SCALE, hxy2 * HALF_SQUARES_SCALE)
        } else {
            (hz2, hxy2)
        };
        Some(Half {
            len2: sum2,
            hz2,
            hxy2,
        })
    }

    /// `cos θd = ωi·h = ωo·h = |ωi + ωo|/2` for unit `ωi`, `ωo` (since
    /// `|ωi + ωo|² = 2 + 2 ωi·ωo = 4 cos² θd`), clamped to 1.
    ///
    /// Unlike the dot product `ωi·h` with the rounded half vector, this is
    /// symmetric in its arguments bit for bit (the component sums commute
    /// exactly), so `F(cos θd)` — and the BRDF — stay exactly reciprocal even
    /// for `ωi ≈ −ωo` at grazing, where `ωi + ωo` nearly cancels and `ωi·h`
    /// can round to 0 in one order and not in the other.
    #[inline(always)]
    fn cos_theta_d(&self) -> f32 {
        (0.5 * radiometry::math::sqrtf(self.len2)).min(1.0)
    }
}

/// `(num/den_d)/den` for the quotient `num/den_d` of
/// [`MicrofacetDistribution::d_ratio`] and a positive denominator `den`
/// (`4 A(ωo)` or `1/V`), as one division `num/(den_d den)`, NaN mapped to 0
/// and `+∞` saturated ([`finite_nonneg`]). Where the product `den_d den`
/// is not a normal `f32` (both directions grazing at once, or `h` along the
/// normal with tiny `α` and `|h|`), the two quotients are taken one after
/// the other in a `#[cold]` path, so no intermediate underflows.
#[inline(always)]
fn d_quotient(num: f32, den_d: f32, den: f32) -> f32 {
    let q = den_d * den;
    if q >= f32::MIN_POSITIVE {
        finite_nonneg(num / q)
    } else {
        d_quotient_cold(num, den_d, den)
    }
}

/// The two-division form of [`d_quotient`].
#[cold]
#[inline(never)]
fn d_quotient_cold(num: f32, den_d: f32, den: f32) -> f32 {
    finite_nonneg((num / den_d) / den)
}

/// Both directions normalised by the robust [`unitize`], or `None` for a
/// degenerate one: the cold path of every method (the hot path has checked
/// [`is_unit`] and skips this).
#[cold]
#[inline(never)]
fn unitize_pair(wi: Vec3, wo: Vec3) -> Option<(Vec3, Vec3)> {
    Some((unitize(wi)?, unitize(wo)?))
}

impl<D, G, F> Microfacet<D, G, F>
where
    D: MicrofacetDistribution,
    G: ShadowingMasking,
    F: Fresnel,
{
    /// `(f_r, pdf)` of the pair as [`Brdf::eval`] and [`Brdf::pdf`] return
    /// them (bit for bit), each only if asked for (0 otherwise); both at once
    /// share the half vector, `D(h)` and `A(ωo)` — for a material whose
    /// `sample` evaluates its value and mixture density in one pass.
    #[inline]
    pub(crate) fn eval_pdf(&self, wi: Vec3, wo: Vec3, value: bool, density: bool) -> (F::Spectrum, f32) {
        if !(value && density) {
            return (
                if value {
                    self.eval(wi, wo)
                } else {
                    F::Spectrum::zero()
                },
                if density { self.pdf(wi, wo) } else { 0.0 },
            );
        }
        let (wi, wo) = if is_unit(wi) && is_unit(wo) {
            (wi, wo)
        } else {
            match unitize_pair(wi, wo) {
                Some(p) => p,
                None => return (F::Spectrum::zero(), 0.0),
            }
        };
        let Some(h) = Half::of(wi, wo) else {
            return (F::Spectrum::zero(), 0.0);
        };
        let (dn, dd) = self.distribution.d_ratio(h.hz2, h.hxy2);
        let ao = self.area(wo);
        let pdf = d_quotient(dn, dd, 4.0 * ao);
        let inv_v = G::inverse_visibility(wi.z, self.area(wi), wo.z, ao);
        let s = d_quotient(dn, dd, inv_v);
        let f = if s == 0.0 {
            F::Spectrum::zero()
        } else {
            self.fresnel.eval(h.cos_theta_d()) * s
        };
        (f, pdf)
    }

    /// [`eval_pdf`](Self::eval_pdf) of this lobe and of the lobe with the
    /// same distribution and shadowing and the Fresnel term `other`:
    /// `(f_r, f_r', pdf)`, each value bit for bit its lobe's [`Brdf::eval`]
    /// (0 unless `value`) and the density its [`Brdf::pdf`] (the same for
    /// both; 0 unless `density`). The half vector, `D(h)`, the visibility
    /// and the density are computed once — for a material with two lobes of
    /// one roughness (OpenPBR's metal and dielectric specular lobes).
    #[inline]
    pub(crate) fn eval_pdf_pair<F2>(
        &self,
        other: &F2,
        wi: Vec3,
        wo: Vec3,
        value: bool,
        density: bool,
    ) -> (F::Spectrum, F::Spectrum, f32)
    where
        F2: Fresnel<Spectrum = F::Spectrum>,
    {
        let zero = F::Spectrum::zero();
        if !value {
            return (zero, zero, if density { self.pdf(wi, wo) } else { 0.0 });
        }
        let (wi, wo) = if is_unit(wi) && is_unit(wo) {
            (wi, wo)
        } else {
            match unitize_pair(wi, wo) {
                Some(p) => p,
                None => return (zero, zero, 0.0),
            }
        };
        let Some(h) = Half::of(wi, wo) else {
            return (zero, zero, 0.0);
        };
        let (dn, dd) = self.distribution.d_ratio(h.hz2, h.hxy2);
        let ao = self.area(wo);
        let pdf = if density {
            d_quotient(dn, dd, 4.0 * ao)
        } else {
            0.0
        };
        let inv_v = G::inverse_visibility(wi.z, self.area(wi), wo.z, ao);
        let s = d_quotient(dn, dd, inv_v);
        if s == 0.0 {
            return (zero, zero, pdf);
        }
        let c = h.cos_theta_d();
        (self.fresnel.eval(c) * s, other.eval(c) * s, pdf)
    }

    /// `f_r = D(h) V F(cos θd)` for unit `wi`, `wo` (the straight-line part
    /// of `eval`), with the visibility `V = G2/(4 cos θi cos θo)`.
    #[inline(always)]
    fn eval_unit(&self, wi: Vec3, wo: Vec3) -> F::Spectrum {
        let Some(h) = Half::of(wi, wo) else {
            return F::Spectrum::zero();
        };
        let (dn, dd) = self.distribution.d_ratio(h.hz2, h.hxy2);
        let inv_v = G::inverse_visibility(wi.z, self.area(wi), wo.z, self.area(wo));
        let s = d_quotient(dn, dd, inv_v);
        if s == 0.0 {
            return F::Spectrum::zero();
        }
        self.fresnel.eval(h.cos_theta_d()) * s
    }

    /// [`MicrofacetDistribution::projected_area`] of a unit direction.
    #[inline(always)]
    fn area(&self, w: Vec3) -> f32 {
        self.distribution.projected_area(w.z, w.x * w.x + w.y * w.y)
    }

    /// The cold path of `eval`: non-unit, degenerate or non-finite input.
    #[cold]
    #[inline(never)]
    fn eval_cold(&self, wi: Vec3, wo: Vec3) -> F::Spectrum {
        match unitize_pair(wi, wo) {
            Some((wi, wo)) => self.eval_unit(wi, wo),
            None => F::Spectrum::zero(),
        }
    }

    /// The lobe's mean Fresnel factor `E_F/E₁` at `μo` from the global
    /// tables ([`fresnel_table`]) when they cover this lobe: GGX with the
    /// height-correlated `G2` (`table` is its `F = 1` table) and a Fresnel
    /// term whose [`form`](Fresnel::form) they read (a real dielectric
    /// index, or linear in the moments). `None` otherwise (and for `F = 1`,
    /// whose albedo is the `F = 1` table itself, with its bound).
    #[inline]
    pub(crate) fn tabulated_fresnel_ratio(&self, table: &AlbedoTable, mu: f32) -> Option<(F::Spectrum, f32)> {
        if !core::ptr::eq(table, &albedo_data::GGX_HEIGHT_CORRELATED) {
            return None;
        }
        let alpha = self.distribution.alpha();
        match self.fresnel.form() {
            // F = 1: the F = 1 table itself, with its bound (the caller's other path).
            FresnelForm::One => None,
            FresnelForm::Dielectric(eta) => Some((
                F::Spectrum::splat(fresnel_table::dielectric_ratio(mu, alpha, eta)),
                fresnel_table::dielectric_error(alpha, eta),
            )),
            FresnelForm::Linear { f0, a } => {
                let m = fresnel_table::fresnel_moments(mu, alpha);
                Some((
                    F::Spectrum::from_fn(|c| {
                        fresnel_table::linear_fresnel_ratio(f0.channel(c), a.channel(c), m)
                    }),
                    FRESNEL_TABLE_ERROR,
                ))
            }
            FresnelForm::Other => None,
        }
    }

    /// The hemispherical average `Ē = 2∫E(μ) μ dμ` of this lobe's albedo
    /// from the global tables, for a GGX (height-correlated) dielectric
    /// interface; `None` for other lobes.
    pub fn tabulated_average_albedo(&self) -> Option<f32> {
        let table = self
            .distribution
            .energy_tables()
            .and_then(|t| G::select_table(&t))?;
        if !core::ptr::eq(table, &albedo_data::GGX_HEIGHT_CORRELATED) {
            return None;
        }
        match self.fresnel.form() {
            FresnelForm::Dielectric(eta) => {
                let alpha = self.distribution.alpha();
                // A prepared lobe read it with its cells (the same bits).
                Some(
                    self.fresnel
                        .albedo_cells(alpha)
                        .map_or_else(|| fresnel_table::dielectric_average(alpha, eta), |c| c.average),
                )
            }
            _ => None,
        }
    }

    /// The Fresnel factor over the lobe at `ωo`: the average
    /// `F̄(ωo) = Σ F(ωo·m_k) G2_k / Σ G2_k` over the 16 visible normals `m_k`
    /// of the stratified points `u = ((i + ½)/4, (j + ½)/4)` whose reflection
    /// stays above the horizon (`G2_k = G2(ωi,k, ωo)`; the `F = 1` weight of
    /// a visible-normal sample is `G2/G1(ωo)`, and `G1(ωo)` cancels), and the
    /// range of `F` over those normals and four more in the lobe's tails
    /// (`u ∈ {1/256, 255/256}²`). When no point reflects above the
    /// horizon: `F(cos θo)` and the range of `F` over all of `[0, 1]`
    /// ([`Fresnel::bounds`]). `wo` unit, above the horizon.
    pub(crate) fn fresnel_spread(&self, wo: Vec3) -> FresnelSpread<F::Spectrum> {
        // The lobe is isotropic: average at the azimuth φo = 0, so that the
        // stratified points (fixed in the local frame) give the same value
        // for every rotation of `wo` about the normal.
        let wo = Vec3::new(radiometry::math::sqrtf((1.0 - wo.z * wo.z).max(0.0)), 0.0, wo.z);
        let mut sum = F::Spectrum::zero();
        let mut weight = 0.0f32;
        let mut lo = F::Spectrum::splat(f32::INFINITY);
        let mut hi = F::Spectrum::splat(f32::NEG_INFINITY);
        // 16 stratified points for the average, then 4 points near the
        // corners of the square (the lobe's tails, u = 1/256 and 255/256)
        // for the range only.
        const TAIL: [[f32; 2]; 4] = [
            [1.0 / 256.0, 1.0 / 256.0],
            [255.0 / 256.0, 1.0 / 256.0],
            [1.0 / 256.0, 255.0 / 256.0],
            [255.0 / 256.0, 255.0 / 256.0],
        ];
        for k in 0..20u8 {
            let u = match TAIL.get(usize::from(k).wrapping_sub(16)) {
                Some(&t) => t,
                None => [(f32::from(k % 4) + 0.5) / 4.0, (f32::from(k / 4) + 0.5) / 4.0],
            };
            let m = self.distribution.sample_visible(wo, u);
            let dot = wo.dot(m);
            let wi = 2.0 * dot * m - wo;
            // (False for NaN.)
            let valid = dot > 0.0 && wi.z > 0.0;
            let g = if valid {
                G::g2(&self.distribution, wi, wo)
            } else {
                0.0
            };
            if g > 0.0 && g.is_finite() {
                let f = self.fresnel.eval(dot);
                if k < 16 {
                    sum += f * g;
                    weight += g;
                }
                lo = F::Spectrum::from_fn(|c| lo.channel(c).min(f.channel(c)));
                hi = F::Spectrum::from_fn(|c| hi.channel(c).max(f.channel(c)));
            }
        }
        if weight > 0.0 {
            // The sampled range is a bound only when F is constant (checked
            // over all of [0, 1] only when the samples already agree).
            let same = (0..F::Spectrum::CHANNELS).all(|c| lo.channel(c) == hi.channel(c));
            let is_bound = same && {
                let (a, b) = self.fresnel.bounds();
                (0..F::Spectrum::CHANNELS).all(|c| a.channel(c) == b.channel(c))
            };
            FresnelSpread {
                mean: sum / weight,
                lo,
                hi,
                is_bound,
            }
        } else {
            let (lo, hi) = self.fresnel.bounds();
            FresnelSpread {
                mean: self.fresnel.eval(wo.z),
                lo,
                hi,
                is_bound: true,
            }
        }
    }

    /// `pdf` for unit `wi`, `wo`:
    /// `D_ωo(h)/(4 ωo·h) = G1(ωo) D(h)/(4 cos θo) = D(h)/(4 A(ωo))`.
    #[inline(always)]
    fn pdf_unit(&self, wi: Vec3, wo: Vec3) -> f32 {
        let Some(h) = Half::of(wi, wo) else {
            return 0.0;
        };
        // ωo·h = |ωi + ωo|/2 > 0 for every pair `Half::of` accepts.
        let (dn, dd) = self.distribution.d_ratio(h.hz2, h.hxy2);
        d_quotient(dn, dd, 4.0 * self.area(wo))
    }

    /// The cold path of `pdf`.
    #[cold]
    #[inline(never)]
    fn pdf_cold(&self, wi: Vec3, wo: Vec3) -> f32 {
        match unitize_pair(wi, wo) {
            Some((wi, wo)) => self.pdf_unit(wi, wo),
            None => 0.0,
        }
    }

    /// `(wi, pdf, weight)` of the pair `(wi, wo)`, the density exactly as
    /// `pdf` computes it (same normalisation decisions, so bit-identical),
    /// the weight `F(cos θd) G2(ωi, ωo)/G1(ωo) = F · 4 V cos θi A(ωo)`
    /// (divided by `1/V`).
    #[inline(always)]
    fn pdf_and_weight(&self, wi: Vec3, wo: Vec3) -> Option<(Vec3, f32, F::Spectrum)> {
        let (wi, wo) = if is_unit(wi) && is_unit(wo) {
            (wi, wo)
        } else {
            unitize_pair(wi, wo)?
        };
        let h = Half::of(wi, wo)?;
        let (dn, dd) = self.distribution.d_ratio(h.hz2, h.hxy2);
        let (ai, ao) = (self.area(wi), self.area(wo));
        let pdf = d_quotient(dn, dd, 4.0 * ao);
        if !(pdf > 0.0 && pdf < f32::INFINITY) {
            return None;
        }
        let inv_v = G::inverse_visibility(wi.z, ai, wo.z, ao);
        let ratio = ((4.0 * wi.z) * ao / inv_v).clamp(0.0, 1.0);
        Some((wi, pdf, self.fresnel.eval(h.cos_theta_d()) * ratio))
    }
}

/// The Fresnel factor of a microfacet lobe at one `ωo`
/// ([`Microfacet::fresnel_spread`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct FresnelSpread<S> {
    /// The lobe's average `F̄`, per channel.
    mean: S,
    /// Smallest `F` seen, per channel.
    lo: S,
    /// Largest `F` seen, per channel.
    hi: S,
    /// Whether `[lo, hi]` holds every value of `F` (a constant `F`, or
    /// [`Fresnel::bounds`] over every `cos θd`), not only the sampled ones.
    is_bound: bool,
}

/// The single-scattering albedo with Fresnel term `F` from the tabulated
/// albedo `e ≈ E_ss(μo)` (`F = 1`, known to within
/// `δ =` [`ALBEDO_TABLE_ERROR`]) and the lobe's Fresnel spread: value
/// `e F̄`, error
///
/// ```text
/// m e + t e max(F̄, 1 − F̄) + δ (m + F̄),   m = max(F̄ − F_lo, F_hi − F̄),
/// ```
///
/// (largest over the channels), with `[F_lo, F_hi]` the range of `F` over the
/// lobe's 20 sampled normals (16 for the average, 4 in the tails at
/// `u ∈ {1/256, 255/256}²`) and `t = 1 − (127/128)²` the sample-space mass
/// outside those tail points, where `F` may take any value in `[0, 1]`.
/// The exact albedo is `E_F = ∫ w F(cos θd) dωi` with the `F = 1` integrand
/// `w ≥ 0` (`∫ w = E_ss`, `|E_ss − e| ≤ δ`), so `E_F/E_ss` is an average of
/// `F` over the lobe. For a constant `F` (`NoFresnel`) the error is the
/// bound `δ` (`t` drops out: `m = 0`, and the tail term is not needed), and
/// with [`Fresnel::bounds`] (the fallback) it is a bound too; otherwise it
/// is an estimate (the range over 20 normals stands for the range over the
/// central part of the lobe), which `brdfs/tests/microfacet_albedo.rs`
/// finds above the actual error at every point of its grid.
#[inline]
pub(crate) fn fresnel_albedo<S: Spectrum>(e: f32, f: FresnelSpread<S>) -> Albedo<S> {
    let e = clamp01(e);
    /// `1 − (127/128)²`: the sample-space mass outside the tail points.
    const TAIL_MASS: f32 = 255.0 / 16_384.0;
    let mut error = 0.0f32;
    for c in 0..S::CHANNELS {
        let (fc, lo, hi) = (f.mean.channel(c), f.lo.channel(c), f.hi.channel(c));
        let m = (fc - lo).max(hi - fc).max(0.0);
        let tail = if f.is_bound {
            0.0
        } else {
            TAIL_MASS * e * fc.max(1.0 - fc)
        };
        error = error.max(m * e + tail + ALBEDO_TABLE_ERROR * (m + fc));
    }
    Albedo {
        value: f.mean * e,
        error: if error.is_finite() { error } else { 1.0 },
        is_bound: f.is_bound,
    }
}

impl<D, G, F> Brdf for Microfacet<D, G, F>
where
    D: MicrofacetDistribution,
    G: ShadowingMasking,
    F: Fresnel,
{
    type Spectrum = F::Spectrum;

    /// `D` and `G2` (Smith's `Λ` in closed form) are analytic in `ωi` above
    /// the horizon; so is the BRDF when its Fresnel term is.
    fn is_smooth(&self) -> bool {
        self.fresnel.is_smooth()
    }

    /// `D(h) G2(ωi, ωo) F(ωi·h) / (4 cos θi cos θo)` (Walter et al. 2007, eq. 20).
    ///
    /// Hot path: one squared-length test per direction, then straight-line
    /// arithmetic on `h = ωi + ωo` (never normalised: `D` comes as a quotient
    /// of the squares of its components, [`MicrofacetDistribution::d_ratio`]),
    /// evaluated as `D(h) V F` with the visibility
    /// `V = G2/(4 cos θi cos θo)` of [`ShadowingMasking::inverse_visibility`]
    /// in one division, `num_D/(den_D · 1/V)`. Non-unit,
    /// degenerate or non-finite input goes to a `#[cold]` path that
    /// normalises robustly first.
    #[inline(always)]
    fn eval(&self, wi: Vec3, wo: Vec3) -> F::Spectrum {
        if is_unit(wi) && is_unit(wo) {
            self.eval_unit(wi, wo)
        } else {
            self.eval_cold(wi, wo)
        }
    }

    /// `eval`'s straight-line path (no unit test).
    #[inline(always)]
    fn eval_checked(&self, wi: Vec3, wo: Vec3) -> F::Spectrum {
        self.eval_unit(wi, wo)
    }

    /// `pdf`'s straight-line path (no unit test).
    #[inline(always)]
    fn pdf_checked(&self, wi: Vec3, wo: Vec3) -> f32 {
        self.pdf_unit(wi, wo)
    }

    /// A prepared dielectric lobe's read at `μo = ωo.z` (no unit test, no
    /// horizon branch); otherwise the table read of `directional_albedo`.
    #[inline(always)]
    fn albedo_checked(&self, wo: Vec3) -> F::Spectrum {
        if let Some(cells) = self.fresnel.albedo_cells(self.distribution.alpha())
            && self.reads_ggx_height_correlated()
        {
            return F::Spectrum::splat(clamp01(cells.reader.albedo(wo.z)));
        }
        self.tabulated_albedo(wo.x, wo.y, wo.z)
            .value
            .map(|v| if v.is_finite() { v.clamp(0.0, 1.0) } else { 0.0 })
    }

    /// With the `simd` feature, GGX with either shadowing–masking variant
    /// (any Fresnel term) uses a vector kernel ([`crate::simd`]) that
    /// returns exactly the bits [`Brdf::eval`] returns; other combinations
    /// loop over `eval`.
    #[cfg(feature = "simd")]
    #[inline]
    fn eval_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [F::Spectrum]) {
        batch::eval(self, crate::simd::Batch::Aos(wi, wo, out))
    }

    /// As [`eval_batch`](Brdf::eval_batch), loading [`LANES`](crate::simd::LANES) `x`, `y`, `z`
    /// components at a time straight from the slices (bit-identical to
    /// `eval`).
    #[cfg(feature = "simd")]
    #[inline]
    fn eval_batch_soa(&self, wi: Vec3Soa<'_>, wo: Vec3Soa<'_>, out: &mut [F::Spectrum]) {
        batch::eval(self, crate::simd::Batch::Soa(wi, wo, out))
    }

    /// With the `simd` feature, GGX (either `G`, any `F`) uses a vector
    /// kernel for `D(h)/(4 A(ωo))`, bit-identical to [`Brdf::pdf`].
    #[cfg(feature = "simd")]
    #[inline]
    fn pdf_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]) {
        batch::pdf(self, crate::simd::Batch::Aos(wi, wo, out))
    }

    /// With the `simd` feature, GGX and Beckmann with either
    /// shadowing–masking variant (any Fresnel term) use a vector kernel that
    /// returns exactly what [`Brdf::sample`] returns (the same `None`
    /// decisions; `wi`, `pdf` and `weight` bit for bit, so the pdf is also
    /// `pdf_batch` of the returned `wi` bit for bit); other combinations
    /// loop over `sample`.
    #[cfg(feature = "simd")]
    #[inline]
    fn sample_batch(&self, wo: &[Vec3], u: &[[f32; 2]], out: &mut [Option<BrdfSample<F::Spectrum>>]) {
        batch::sample(self, wo, u, out)
    }

    /// Visible-normal sampling (Heitz & d'Eon 2014) followed by mirror
    /// reflection about the sampled normal.
    #[inline]
    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<F::Spectrum>> {
        let wo_unit = if is_unit(wo) { wo } else { unitize(wo)? };
        if wo_unit.z <= 0.0 {
            return None;
        }
        let m = self.distribution.sample_visible(wo_unit, u);
        let dot = wo_unit.dot(m);
        if dot.is_nan() || dot <= 0.0 {
            return None;
        }
        let wi = 2.0 * dot * m - wo_unit;
        let wi = if is_unit(wi) { wi } else { unitize(wi)? };
        if wi.z <= 0.0 {
            return None;
        }
        // The density and weight of the pair exactly as `Brdf::pdf(wi, wo)`
        // computes them (from the caller's `wo`), so the returned pdf equals
        // `pdf(wi, wo)` bit for bit.
        let (wi, pdf, weight) = self.pdf_and_weight(wi, wo)?;
        Some(BrdfSample { wi, pdf, weight })
    }

    /// `G1(ωo) D(h) / (4 cos θo)` for a valid reflection pair, else 0.
    #[inline(always)]
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        if is_unit(wi) && is_unit(wo) {
            self.pdf_unit(wi, wo)
        } else {
            self.pdf_cold(wi, wo)
        }
    }

    /// The Kulla–Conty table of `(D, G)` ([`AlbedoTable::albedo`], `F = 1`)
    /// times a Fresnel average `F̄` over the lobe (16 stratified
    /// visible-normal points weighted by `G2`; `F̄ = 1` exactly for
    /// [`NoFresnel`]), with the error `m E_tab + δ (m + F̄)`,
    /// `m = max(F̄ − F_lo, F_hi − F̄)` over the channels, `[F_lo, F_hi]` the
    /// range of `F` over those normals and `δ =` [`ALBEDO_TABLE_ERROR`]
    /// (`fresnel_albedo` in this module's source). A bound (`is_bound`) for
    /// a constant `F` (`10⁻³` with `NoFresnel`); otherwise an estimate,
    /// measured above the actual error at every point of the grid of
    /// `brdfs/tests/microfacet_albedo.rs`. A distribution or shadowing term
    /// without a table falls back to the default sampling rule. Zero at or
    /// below the horizon.
    /// From the global table for a GGX (height-correlated) dielectric
    /// interface ([`fresnel_table::dielectric_average`]); the default rule
    /// otherwise.
    fn average_albedo(&self) -> F::Spectrum {
        match self.tabulated_average_albedo() {
            Some(a) => F::Spectrum::splat(a),
            None => radiometry::brdf::default_average_albedo(self),
        }
    }

    ///
    /// A [prepared](Brdf::with_prepared_albedo) GGX (height-correlated `G2`)
    /// dielectric lobe reads the same tables through the cells and weights
    /// its [`Dielectric`] term keeps: the same operations on the same
    /// entries, so the same value (tested).
    #[inline(always)]
    fn directional_albedo(&self, wo: Vec3) -> Albedo<F::Spectrum> {
        // The prepared read inline (a layer's `eval` makes it at every call),
        // the unprepared one's branch with the reader in place of the
        // roughness and index work; everything else out of line.
        if let Some(cells) = self.fresnel.albedo_cells(self.distribution.alpha())
            && self.reads_ggx_height_correlated()
        {
            let mu = unit_cos_theta(wo);
            return if mu > 0.0 {
                Albedo {
                    value: F::Spectrum::splat(clamp01(cells.reader.albedo(mu))),
                    error: cells.error,
                    is_bound: false,
                }
            } else {
                Albedo::zero()
            };
        }
        self.tabulated_albedo(wo.x, wo.y, wo.z)
    }

    /// A [prepared](Brdf::with_prepared_albedo) GGX (height-correlated
    /// `G2`) dielectric lobe with the `simd` feature reads its cells in
    /// vector lanes (bit for bit [`directional_albedo`](Brdf::directional_albedo)'s
    /// value, tested); every other lobe loops over `directional_albedo`.
    fn directional_albedo_batch(&self, wo: &[Vec3], out: &mut [F::Spectrum]) {
        #[cfg(feature = "simd")]
        if let Some(cells) = self.fresnel.albedo_cells(self.distribution.alpha())
            && self.reads_ggx_height_correlated()
            && let Some(rows) = cells.reader.rows()
        {
            batch::dielectric_albedo(&cells.reader, &rows, wo, out);
            return;
        }
        for (o, &w) in out.iter_mut().zip(wo) {
            *o = self.directional_albedo(w).value;
        }
        radiometry::batch::zero_tail(out, wo.len());
    }

    /// The lobe with its albedo's roughness and index cells located once:
    /// for GGX (height-correlated `G2`) with a [`Dielectric`] term (also
    /// through [`Achromatic`]), the term keeps a
    /// [`DielectricAlbedoReader`](fresnel_table::DielectricAlbedoReader)
    /// for the lobe's roughness (104 bytes); other lobes are returned as
    /// they are. O(1) (a cube root, a few square roots and divisions);
    /// `eval`, `sample` and `pdf` are untouched. A lobe whose roughness is
    /// changed afterwards (the public field) reads the full tables again.
    ///
    /// ```
    /// use radiometry::{Brdf, glam::Vec3};
    /// use radiometry_brdfs::microfacet::{Dielectric, Ggx, HeightCorrelated, Microfacet};
    /// # fn main() -> Result<(), radiometry_brdfs::BrdfError> {
    /// let coat = Microfacet::<_, HeightCorrelated, _>::new(Ggx::new(0.1)?, Dielectric::new(1.5)?);
    /// let prepared = coat.with_prepared_albedo();
    /// let wo = Vec3::new(0.6, 0.0, 0.8);
    /// assert_eq!(prepared.directional_albedo(wo), coat.directional_albedo(wo));
    /// assert_eq!(prepared, coat); // the same BRDF
    /// # Ok(())
    /// # }
    /// ```
    fn with_prepared_albedo(self) -> Self {
        if !self.reads_ggx_height_correlated() || !matches!(self.fresnel.form(), FresnelForm::Dielectric(_)) {
            return self;
        }
        Self {
            fresnel: self.fresnel.with_albedo_cells(self.distribution.alpha()),
            ..self
        }
    }
}

impl<D, G, F> Microfacet<D, G, F>
where
    D: MicrofacetDistribution,
    G: ShadowingMasking,
    F: Fresnel,
{
    /// Whether this lobe's `F = 1` albedo is GGX's height-correlated table,
    /// the one the ratio tables go with (a constant for each `D`, `G`).
    #[inline(always)]
    fn reads_ggx_height_correlated(&self) -> bool {
        self.distribution
            .energy_tables()
            .and_then(|t| G::select_table(&t))
            .is_some_and(|t| core::ptr::eq(t, &albedo_data::GGX_HEIGHT_CORRELATED))
    }

    /// [`Brdf::directional_albedo`] without prepared cells: the roughness
    /// and index work of every table read, then the read.
    /// (`ωo` by its components: passed in registers, so that an inlined
    /// caller keeps its `ωo` out of memory.)
    #[inline(never)]
    fn tabulated_albedo(&self, x: f32, y: f32, z: f32) -> Albedo<F::Spectrum> {
        let wo = Vec3::new(x, y, z);
        let Some(table) = self
            .distribution
            .energy_tables()
            .and_then(|t| G::select_table(&t))
        else {
            return radiometry::compose::albedo_by_sampling(self, wo);
        };
        match unitize(wo) {
            Some(w) if w.z > 0.0 => {
                let e1 = table.albedo(w.z, self.distribution.alpha());
                match self.tabulated_fresnel_ratio(table, w.z) {
                    Some((ratio, error)) => Albedo {
                        value: (ratio * e1).map(clamp01),
                        error,
                        is_bound: false,
                    },
                    // F = 1: the table itself, with its bound (what the
                    // Fresnel average of a constant 1 gives, without the 20
                    // visible-normal samples).
                    None if matches!(self.fresnel.form(), FresnelForm::One) => Albedo {
                        value: F::Spectrum::splat(clamp01(e1)),
                        error: ALBEDO_TABLE_ERROR,
                        is_bound: true,
                    },
                    None => fresnel_albedo(e1, self.fresnel_spread(w)),
                }
            }
            _ => Albedo::zero(),
        }
    }
}

impl<D, G, F> IsotropicBrdf for Microfacet<D, G, F>
where
    D: MicrofacetDistribution,
    G: ShadowingMasking,
    F: Fresnel,
{
}
