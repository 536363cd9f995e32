//! The sheen BRDF `Sheen<S>`: the Charlie distribution in the microfacet
//! form, uniform hemisphere sampling, and the tabulated albedo.

use super::Charlie;
use super::albedo_table::{SHEEN_ALBEDO, TABLE_ERROR};
use crate::error::{BrdfError, check_range};
use crate::microfacet::{is_unit, unitize};
use core::f32::consts::FRAC_1_PI;
use radiometry::glam::Vec3;
use radiometry::warp::square_to_uniform_hemisphere;
use radiometry::{Albedo, Brdf, BrdfSample, IsotropicBrdf, Spectrum};

/// `1/(2π)`: the density of uniform hemisphere sampling.
const UNIFORM_PDF: f32 = 0.5 * FRAC_1_PI;

/// The microfacet sheen BRDF of Estevez & Kulla 2017 ("Production Friendly
/// Microfacet Sheen BRDF", Sony Pictures Imageworks), eq. 1 with `F = 1`:
///
/// ```text
/// f_r(ωi, ωo) = color · D(h) G(ωi, ωo) / (4 cos θi cos θo),
/// G(ωi, ωo)  = 1 / (1 + Λ(cos θi) + Λ(cos θo)),
/// ```
///
/// with `h = (ωi + ωo)/|ωi + ωo|`, the [`Charlie`] distribution `D` of
/// roughness `r` and its fitted `Λ` (height-correlated Smith form, as in
/// the paper). The paper's "terminator softening" (a non-physical
/// exponent on `Λ` of the *light* direction only) is **left out**: it
/// breaks reciprocity, and a BRDF here is a function of two directions
/// without a notion of which one carries the light.
///
/// # Parameters and domain
/// * `color`: a spectrum with every channel in `[0, 1]`; it scales `f_r`
///   (the paper's sheen colour). With `color = 1` the albedo is the
///   tabulated `E(μo, r)`: largest `0.9885`, at `r = 0.07`, `θo ≈ 89.7°`
///   (it falls with `r` and towards normal incidence; `0.16` at `r = 1`,
///   `θo = 0`), so `color ≤ 1` keeps it below 1 with its error.
/// * `roughness` `r ∈ [`[`MIN_SHEEN_ROUGHNESS`](super::MIN_SHEEN_ROUGHNESS)`, 1]`.
/// * Directions: any finite vectors (normalised; zero below the horizon,
///   at `ωi = −ωo` and for degenerate input). Where both cosines are so
///   small that `f_r` exceeds the `f32` range it saturates at `f32::MAX`
///   (`f_r cos θi` stays bounded).
///
/// # Sampling
/// Uniform on the hemisphere, density `1/(2π)`: `f_r cos θi =
/// color · D G/(4 cos θo)` carries no `cos θi` factor, and its `D` peaks
/// where `h` is horizontal, which covers the whole hemisphere of `ωi`
/// as `ωo` varies. (The test `uniform_sampling_beats_cosine` compares the
/// variance of the albedo estimate with cosine-weighted sampling.)
/// `pdf` is the constant `1/(2π)` above the horizon, so it equals the
/// returned pdf bit for bit.
///
/// # Smoothness
/// [`Brdf::is_smooth`] is `false`: `sin(θh)^(1/r)` has a cusp at the
/// mirror direction (`h = +Z`) unless `1/r` is an even integer, the fit's
/// `x^c` has an infinite slope at `cos θ = 1`, and the two branches of
/// `Λ` join with only a continuous first derivative at `cos θ = 1/2`.
///
/// ```
/// use radiometry::{Brdf, glam::Vec3};
/// use radiometry_brdfs::Sheen;
/// let s = Sheen::new(1.0f32, 0.5)?;
/// let wo = Vec3::new(0.8, 0.0, 0.6);
/// let wi = Vec3::new(-0.6, 0.0, 0.8);
/// assert!(s.eval(wi, wo) > 0.0 && s.eval(wi, wo) == s.eval(wo, wi));
/// let smp = s.sample(wo, [0.3, 0.7]).unwrap();
/// assert_eq!(smp.pdf, s.pdf(smp.wi, wo)); // bit for bit
/// let e = s.directional_albedo(wo);
/// assert!(e.value > 0.0 && e.value + e.error <= 1.0 && e.is_bound);
/// assert!(Sheen::new(1.0f32, 0.0).is_err() && Sheen::new(1.5f32, 0.5).is_err());
/// # Ok::<(), radiometry_brdfs::BrdfError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sheen<S: Spectrum = f32> {
    color: S,
    charlie: Charlie,
}

impl<S: Spectrum> Sheen<S> {
    /// The sheen lobe of colour `color` and roughness `roughness`.
    ///
    /// # Errors
    /// [`BrdfError::NotFinite`] for a NaN/∞ parameter,
    /// [`BrdfError::OutOfRange`] for a `color` channel outside `[0, 1]` or
    /// a `roughness` outside `[`[`MIN_SHEEN_ROUGHNESS`](super::MIN_SHEEN_ROUGHNESS)`, 1]`.
    pub fn new(color: S, roughness: f32) -> Result<Self, BrdfError> {
        for i in 0..S::CHANNELS {
            check_range("color", color.channel(i), 0.0, 1.0)?;
        }
        Ok(Self {
            color,
            charlie: Charlie::new(roughness)?,
        })
    }

    /// The colour.
    #[inline]
    pub fn color(&self) -> S {
        self.color
    }

    /// The roughness `r`.
    #[inline]
    pub fn roughness(&self) -> f32 {
        self.charlie.roughness()
    }

    /// The distribution (with its fitted `Λ`).
    #[inline]
    pub fn distribution(&self) -> &Charlie {
        &self.charlie
    }

    /// `D(h) G / 4` of a pair of unit directions above the horizon, `0`
    /// otherwise (and at `ωi = −ωo`): `f_r = color · dg4 / (cos θi cos θo)`.
    /// Symmetric in its arguments bit for bit (every sum and product is
    /// formed in an order-independent way).
    #[inline(always)]
    fn dg4(&self, wi: Vec3, wo: Vec3) -> f32 {
        if !(wi.z > 0.0 && wo.z > 0.0) {
            return 0.0;
        }
        let h = wi + wo;
        let hxy2 = h.x * h.x + h.y * h.y;
        let len2 = hxy2 + h.z * h.z;
        // |h|² > 0 whenever both z > 0; the floor keeps the quotient
        // meaningful (and NaN fails it).
        if len2.is_nan() || len2 <= 1e-30 {
            return 0.0;
        }
        let d = self.charlie.d_sin2(hxy2 / len2);
        let lam = self.charlie.lambda(wi.z) + self.charlie.lambda(wo.z);
        d / (4.0 + 4.0 * lam)
    }

    /// `f_r / color` of unit directions.
    #[inline(always)]
    fn scalar_unit(&self, wi: Vec3, wo: Vec3) -> f32 {
        let q = self.dg4(wi, wo);
        if q == 0.0 {
            return 0.0;
        }
        let c = wi.z * wo.z;
        let f = if c >= f32::MIN_POSITIVE {
            q / c
        } else {
            (q / wi.z) / wo.z
        };
        if f > 0.0 { f.min(f32::MAX) } else { 0.0 }
    }

    /// The cold path of `eval`: non-unit, degenerate or non-finite input.
    #[cold]
    #[inline(never)]
    fn scalar_cold(&self, wi: Vec3, wo: Vec3) -> f32 {
        match (unitize(wi), unitize(wo)) {
            (Some(wi), Some(wo)) => self.scalar_unit(wi, wo),
            _ => 0.0,
        }
    }
}

impl<S: Spectrum> Brdf for Sheen<S> {
    type Spectrum = S;

    /// `false`: see the type's documentation (cusp at the mirror
    /// direction, the fit's non-analytic points).
    fn is_smooth(&self) -> bool {
        false
    }

    /// `color · D(h) G(ωi, ωo) / (4 cos θi cos θo)` (Estevez & Kulla 2017,
    /// eq. 1). Hot path: one squared-length test per direction.
    #[inline]
    fn eval(&self, wi: Vec3, wo: Vec3) -> S {
        let f = if is_unit(wi) && is_unit(wo) {
            self.scalar_unit(wi, wo)
        } else {
            self.scalar_cold(wi, wo)
        };
        self.color * f
    }

    /// Uniform hemisphere sampling: `wi` from
    /// [`square_to_uniform_hemisphere`], `pdf = 1/(2π)`, `weight =
    /// color · 2π D G/(4 cos θo)`. `None` when `wo` is at or below the
    /// horizon or degenerate, or `wi` lands on the horizon (`u₀ = 0`).
    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<S>> {
        let wo_unit = if is_unit(wo) { wo } else { unitize(wo)? };
        if wo_unit.z <= 0.0 {
            return None;
        }
        let wi = square_to_uniform_hemisphere(u);
        let pdf = self.pdf(wi, wo);
        if pdf <= 0.0 {
            return None;
        }
        let w = self.dg4(wi, wo_unit) / (wo_unit.z * UNIFORM_PDF);
        let w = if w > 0.0 { w.min(f32::MAX) } else { 0.0 };
        Some(BrdfSample {
            wi,
            pdf,
            weight: self.color * w,
        })
    }

    /// `1/(2π)` when `wo` and `wi` (normalised) are above the horizon,
    /// else 0.
    #[inline]
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        let above = |w: Vec3| {
            if is_unit(w) {
                w.z > 0.0
            } else {
                unitize(w).is_some_and(|w| w.z > 0.0)
            }
        };
        if above(wi) && above(wo) { UNIFORM_PDF } else { 0.0 }
    }

    /// `color · E(cos θo, r)` from the tabulated albedo
    /// ([`SheenAlbedoTable`](super::SheenAlbedoTable)), with the stated
    /// bound `max(color) · (table + interpolation error)`; exactly zero at
    /// or below the horizon.
    fn directional_albedo(&self, wo: Vec3) -> Albedo<S> {
        let wo = if is_unit(wo) { Some(wo) } else { unitize(wo) };
        match wo {
            Some(w) if w.z > 0.0 => {
                let e = SHEEN_ALBEDO.albedo(w.z, self.roughness());
                Albedo::bounded(self.color * e, self.color.max_channel() * TABLE_ERROR)
            }
            _ => Albedo::zero(),
        }
    }
}

impl<S: Spectrum> IsotropicBrdf for Sheen<S> {}
