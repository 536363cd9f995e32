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
//! * `F` — [`NoFresnel`] (default, `F = 1`), [`Schlick`], [`Dielectric`] or
//!   [`Conductor`], implementing [`Fresnel`].
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

mod beckmann;
mod fresnel;
mod ggx;
mod smith;
mod special;

#[cfg(test)]
mod tests;

pub use beckmann::Beckmann;
pub use fresnel::{Conductor, Dielectric, Fresnel, MAX_ETA, MAX_K, MIN_ETA, NoFresnel, Schlick};
pub use ggx::Ggx;
pub use smith::{HeightCorrelated, Separable, ShadowingMasking};

use core::marker::PhantomData;
use radiometry::glam::Vec3;
use radiometry::{Brdf, BrdfSample, IsotropicBrdf, Spectrum};

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

    /// Samples a microfacet normal `m` from the distribution of normals
    /// visible from `wo`, `D_ωo(m) = G1(ωo) max(0, ωo·m) D(m) / cos θo`.
    ///
    /// `u ∈ [0, 1]²` (any values are clamped into it, NaN to 0). A `wo`
    /// below the horizon is mirrored to `(x, y, |z|)` first (as
    /// [`visible_pdf`](Self::visible_pdf) does). Always returns a finite unit
    /// vector with `z ≥ 0`.
    fn sample_visible(&self, wo: Vec3, u: [f32; 2]) -> Vec3;

    /// Hidden hook of the `simd` feature: which vectorised kernel (if any)
    /// [`Brdf::eval_batch`] of [`Microfacet`] may use for this distribution.
    /// The default, [`DistributionKind::Scalar`](crate::simd::DistributionKind),
    /// keeps the scalar loop; only [`Ggx`] overrides it. Not part of the
    /// stable API.
    #[cfg(feature = "simd")]
    #[doc(hidden)]
    #[inline]
    fn batch_kind(&self) -> crate::simd::DistributionKind {
        crate::simd::DistributionKind::Scalar
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
        return Some(w / libm::sqrtf(l2));
    }
    let s = w.abs().max_element();
    if !(s > 0.0 && s.is_finite()) {
        return None;
    }
    let v = w / s;
    let l2 = v.length_squared();
    if l2 > 0.0 && l2.is_finite() {
        Some(v / libm::sqrtf(l2))
    } else {
        None
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

impl<D, G, F> Microfacet<D, G, F>
where
    D: MicrofacetDistribution,
    G: ShadowingMasking,
    F: Fresnel,
{
    /// `(cos θi, cos θo, h)` for a valid reflection pair, else `None`.
    #[inline]
    fn geometry(wi: Vec3, wo: Vec3) -> Option<(Vec3, Vec3, Vec3)> {
        let wi = unitize(wi)?;
        let wo = unitize(wo)?;
        if wi.z <= 0.0 || wo.z <= 0.0 {
            return None;
        }
        let h = radiometry::frame::half_vector(wi, wo)?;
        Some((wi, wo, h))
    }
}

/// `cos θd = ωi·h = ωo·h` for unit `ωi`, `ωo`, computed as `|ωi + ωo|/2`
/// (since `|ωi + ωo|² = 2 + 2 ωi·ωo = 4 cos² θd`), clamped to 1.
///
/// Unlike the dot product `ωi·h` with the rounded half vector, this is
/// symmetric in its arguments bit for bit (the component sums commute
/// exactly), so `F(cos θd)` — and the BRDF — stay exactly reciprocal even
/// for `ωi ≈ −ωo` at grazing, where `ωi + ωo` nearly cancels and `ωi·h`
/// can round to 0 in one order and not in the other.
#[inline]
fn cos_theta_d(wi: Vec3, wo: Vec3) -> f32 {
    (0.5 * (wi + wo).length()).min(1.0)
}

impl<D, G, F> Brdf for Microfacet<D, G, F>
where
    D: MicrofacetDistribution,
    G: ShadowingMasking,
    F: Fresnel,
{
    type Spectrum = F::Spectrum;

    /// `D(h) G2(ωi, ωo) F(ωi·h) / (4 cos θi cos θo)` (Walter et al. 2007, eq. 20).
    #[inline]
    fn eval(&self, wi: Vec3, wo: Vec3) -> F::Spectrum {
        let Some((wi, wo, h)) = Self::geometry(wi, wo) else {
            return F::Spectrum::zero();
        };
        let d = self.distribution.d(h);
        if d <= 0.0 {
            return F::Spectrum::zero();
        }
        let g = G::g2(&self.distribution, wi, wo);
        let s = finite_nonneg(d * g / (4.0 * wi.z * wo.z));
        if s == 0.0 {
            return F::Spectrum::zero();
        }
        self.fresnel.eval(cos_theta_d(wi, wo)) * s
    }

    /// With the `simd` feature, GGX with either shadowing–masking variant
    /// (any Fresnel term) uses the 8-wide kernel of [`crate::simd`], which
    /// returns exactly what [`Brdf::eval`] returns; other combinations loop
    /// over `eval`.
    #[cfg(feature = "simd")]
    #[inline]
    fn eval_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [F::Spectrum]) {
        crate::simd::microfacet_eval_batch(self, wi, wo, out)
    }

    /// Visible-normal sampling (Heitz & d'Eon 2014) followed by mirror
    /// reflection about the sampled normal.
    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<F::Spectrum>> {
        let wo = unitize(wo)?;
        if wo.z <= 0.0 {
            return None;
        }
        let m = self.distribution.sample_visible(wo, u);
        let dot = wo.dot(m);
        if dot <= 0.0 {
            return None;
        }
        let wi = unitize(2.0 * dot * m - wo)?;
        if wi.z <= 0.0 {
            return None;
        }
        // Recompute the geometry from (wi, wo) exactly as `Brdf::pdf` does, so
        // that the returned pdf equals `pdf(wi, wo)` bit for bit.
        let (wi, wo, h) = Self::geometry(wi, wo)?;
        let pdf = self.pdf_h(wo, h);
        if !(pdf > 0.0 && pdf.is_finite()) {
            return None;
        }
        let g1o = self.distribution.g1(wo);
        if g1o <= 0.0 {
            return None;
        }
        let ratio = (G::g2(&self.distribution, wi, wo) / g1o).clamp(0.0, 1.0);
        let weight = self.fresnel.eval(cos_theta_d(wi, wo)) * ratio;
        Some(BrdfSample { wi, pdf, weight })
    }

    /// `G1(ωo) D(h) / (4 cos θo)` for a valid reflection pair, else 0.
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        match Self::geometry(wi, wo) {
            Some((_, wo, h)) => self.pdf_h(wo, h),
            None => 0.0,
        }
    }
}

impl<D, G, F> Microfacet<D, G, F>
where
    D: MicrofacetDistribution,
    G: ShadowingMasking,
    F: Fresnel,
{
    /// `D_ωo(h)/(4 ωo·h) = G1(ωo) D(h)/(4 cos θo)` for unit `wo` (z > 0) and `h`.
    #[inline]
    fn pdf_h(&self, wo: Vec3, h: Vec3) -> f32 {
        if wo.dot(h) <= 0.0 {
            return 0.0;
        }
        let g1 = self.distribution.g1(wo);
        if g1 <= 0.0 {
            return 0.0;
        }
        finite_nonneg(g1 / (4.0 * wo.z) * self.distribution.d(h))
    }
}

impl<D, G, F> IsotropicBrdf for Microfacet<D, G, F>
where
    D: MicrofacetDistribution,
    G: ShadowingMasking,
    F: Fresnel,
{
}
