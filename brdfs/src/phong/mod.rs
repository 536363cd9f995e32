//! The modified Phong BRDF of Lafortune & Willems (1994).
//!
//! # Formula
//!
//! ```text
//! f_r(ωi, ωo) = kd/π + ks · (n + 2)/(2π) · cos^n α        for cos θi > 0 and cos θo > 0,
//!             = 0                                          otherwise,
//! ```
//!
//! where `α` is the angle between `ωi` and the mirror direction
//! `ωr = (−ωo.x, −ωo.y, ωo.z)` of `ωo` about the normal `+Z`, and `cos^n α`
//! is taken as `0` when `cos α ≤ 0` (also for `n = 0`, so that the lobe is
//! the `n → 0⁺` limit and its support matches the sampler's).
//!
//! Source: E. P. Lafortune and Y. D. Willems, *Using the modified Phong
//! reflectance model for physically based rendering*, Technical Report
//! CW 197, Department of Computer Science, K.U. Leuven, 1994. The factor
//! `(n + 2)/(2π)` makes the lobe's directional albedo exactly 1 at normal
//! incidence (`∫ cos^n θ cos θ dω = 2π/(n + 2)`); away from normal
//! incidence part of the lobe falls below the horizon and the albedo is
//! smaller, so `kd + ks ≤ 1` (per channel) guarantees energy conservation.
//! The model is reciprocal: `cos α = ωi·ωr = ωo·ωi_r` is symmetric.
//!
//! # Parameters and domain
//!
//! * `kd`, `ks`: spectra with every channel in `[0, 1]` and
//!   `kd + ks ≤ 1` per channel (one `f32` rounding, `2⁻²³`, of slack in the
//!   sum is accepted so that e.g. `0.3 + 0.7` is valid).
//! * `n` (`exponent`): `0 ≤ n ≤` [`MAX_EXPONENT`] `= 1e7`.
//! * Directions: any finite vectors; they are normalised internally (the
//!   zero vector gives `f = 0`). Vectors that are already unit to rounding
//!   (`|‖ω‖² − 1| ≤ 4ε`) are used as given, without a square root or
//!   division.
//!
//! # Numerics
//!
//! `cos^n α` is evaluated as `exp(n · ln(1 − δ))` with
//! `δ = 1 − cos α = |ωi − ωr|²/2` computed from the difference vector and
//! `ln(1 − δ)` by `log1p`: this keeps full relative precision of `δ` near
//! the mirror direction, where `powf(cos α, n)` of a rounded cosine loses it
//! for large `n` (at `n = 10⁶` one ulp of `cos α` changes the lobe by 6 %).
//! The peak value `ks (n + 2)/(2π) ≤ 1.6·10⁶` stays finite for every
//! admissible `n`.
//!
//! # Sampling
//!
//! One-sample mixture (Veach 1997, §9.2.4): the cosine-weighted diffuse
//! strategy is chosen with probability `pd = kd̄/(kd̄ + ks̄)` and the lobe
//! strategy with `ps = ks̄/(kd̄ + ks̄)` (bars: [`Spectrum::average`]). The
//! lobe strategy draws `cos α = ξ^{1/(n+1)}`, `φ = 2π u₁` around `ωr` with
//! `ξ = 1 − u₀'` (same distribution as `u₀'`, but keeps `ln ξ` finite); its
//! density is `(n + 1)/(2π) cos^n α` (Lafortune & Willems 1994; Dutré,
//! *Global Illumination Compendium*, 2003). The reported density is the
//! mixture
//!
//! ```text
//! pdf(ωi, ωo) = pd · cos θi/π + ps · (n + 1)/(2π) · cos^n α      (cos θi > 0, cos θo > 0)
//! ```
//!
//! Lobe samples below the horizon are rejected (`sample` returns `None`),
//! so `∫_H pdf dω = pd + ps·(1 − lobe mass below the horizon) ≤ 1`, with
//! equality at normal incidence. When `kd = ks = 0` the BRDF is zero:
//! `sample` returns `None` and `pdf` returns `0`.
//!
//! # Example
//!
//! ```
//! use radiometry::{Brdf, glam::Vec3};
//! use radiometry_brdfs::ModifiedPhong;
//! use core::f32::consts::PI;
//!
//! let b = ModifiedPhong::new(0.2f32, 0.7, 20.0)?;
//! // At the mirror direction of normal incidence cos α = 1:
//! let f = b.eval(Vec3::Z, Vec3::Z);
//! assert!((f - (0.2 / PI + 0.7 * 22.0 / (2.0 * PI))).abs() < 1e-5);
//!
//! let wo = Vec3::new(0.6, 0.0, 0.8);
//! let s = b.sample(wo, [0.7, 0.3]).unwrap();
//! assert!((s.pdf - b.pdf(s.wi, wo)).abs() <= 1e-5 * s.pdf);
//! assert!(ModifiedPhong::new(0.5f32, 0.6, 1.0).is_err()); // kd + ks > 1
//! # Ok::<(), radiometry_brdfs::BrdfError>(())
//! ```

use crate::error::{BrdfError, check_range};
use core::f32::consts::FRAC_1_PI;
#[cfg(feature = "simd")]
use radiometry::batch::Vec3Soa;
use radiometry::frame::reflect_z;
use radiometry::glam::Vec3;
use radiometry::warp::square_to_cosine_hemisphere;
use radiometry::{Brdf, BrdfSample, IsotropicBrdf, Spectrum};

#[cfg(feature = "simd")]
pub(crate) mod batch;
mod family;
#[cfg(test)]
pub(crate) mod test_support;
#[cfg(test)]
mod tests;

pub(crate) use family::*;

/// Largest accepted Phong exponent `n` (also used by
/// [`BlinnPhong`](crate::blinn_phong::BlinnPhong)). At `n = 10⁷` the lobe
/// is about `0.03°` wide and its peak `(n + 2)/(2π) ≈ 1.6·10⁶` is still far
/// from `f32` overflow.
pub const MAX_EXPONENT: f32 = 1e7;

/// The modified Phong BRDF `kd/π + ks (n+2)/(2π) cos^n α` (Lafortune &
/// Willems 1994); see the [module documentation](self) for the formula,
/// domain, numerics and sampling.
///
/// ```
/// use radiometry::{Brdf, IsotropicBrdf, glam::Vec3};
/// use radiometry_brdfs::ModifiedPhong;
///
/// let rgb = ModifiedPhong::new(Vec3::new(0.5, 0.3, 0.1), Vec3::splat(0.4), 100.0)?;
/// let f = rgb.eval_isotropic(0.3, 0.3, core::f32::consts::PI); // the mirror configuration
/// assert!(f.x > f.z && f.z > 0.0);
/// assert_eq!(rgb.eval(Vec3::Z, -Vec3::Z), Vec3::ZERO); // below the horizon
/// # Ok::<(), radiometry_brdfs::BrdfError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModifiedPhong<S: Spectrum = f32> {
    kd: S,
    ks: S,
    exponent: f32,
    /// Probability of choosing the diffuse strategy, `kd̄/(kd̄ + ks̄)`
    /// (0 when both are zero).
    p_diffuse: f32,
    /// `ks̄/(kd̄ + ks̄)` (0 when both are zero).
    p_lobe: f32,
    /// `1/(n + 1)`, the sampler's power `cos θ = ξ^{1/(n+1)}`.
    inv_n1: f32,
    /// `[1/pd, 1/ps]` ([`strategy_reciprocals`]).
    inv_p: [f32; 2],
}

impl<S: Spectrum> ModifiedPhong<S> {
    /// Builds the BRDF after validating the parameters.
    ///
    /// # Errors
    /// * [`BrdfError::NotFinite`] if a channel of `kd`/`ks` or `exponent` is
    ///   NaN or infinite;
    /// * [`BrdfError::OutOfRange`] if a channel of `kd`/`ks` is outside
    ///   `[0, 1]` or `exponent ∉ [0, MAX_EXPONENT]`;
    /// * [`BrdfError::Constraint`] if `kd + ks > 1` in some channel.
    pub fn new(kd: S, ks: S, exponent: f32) -> Result<Self, BrdfError> {
        check_kd_ks(kd, ks)?;
        let exponent = check_range("exponent", exponent, 0.0, MAX_EXPONENT)?;
        let (p_diffuse, p_lobe) = strategy_probabilities(kd, ks);
        Ok(Self {
            kd,
            ks,
            exponent,
            p_diffuse,
            p_lobe,
            inv_n1: 1.0 / (exponent + 1.0),
            inv_p: strategy_reciprocals(p_diffuse, p_lobe),
        })
    }

    /// Diffuse reflectance `kd`.
    pub fn kd(&self) -> S {
        self.kd
    }

    /// Specular reflectance `ks` (the lobe's albedo at normal incidence).
    pub fn ks(&self) -> S {
        self.ks
    }

    /// Phong exponent `n`.
    pub fn exponent(&self) -> f32 {
        self.exponent
    }

    /// `cos^n α` for unit `wi`, `wo` (0 when `cos α ≤ 0`), via
    /// `δ = |ωi − ωr|²/2 = 1 − cos α`.
    #[inline]
    fn lobe(&self, wi: Vec3, wo: Vec3) -> f32 {
        let delta = 0.5 * (wi - reflect_z(wo)).length_squared();
        pow_one_minus(delta, self.exponent)
    }

    /// `f` from `cos^n α` (the arithmetic of [`Brdf::eval`], shared with
    /// `sample`): `kd/π + ks ((n + 2)/(2π) · cos^n α)`.
    #[inline(always)]
    fn f_of_lobe(&self, lobe: f32) -> S {
        let norm = (self.exponent + 2.0) * (0.5 * FRAC_1_PI);
        self.kd * FRAC_1_PI + self.ks * (norm * lobe)
    }

    /// The mixture density from `cos θi` and `cos^n α` (the arithmetic of
    /// [`Brdf::pdf`], shared with `sample`): `pd cos θi/π + ps (n+1)/(2π)
    /// cos^n α`, the lobe term `0` when `ps = 0`.
    #[inline(always)]
    fn pdf_of_lobe(&self, cos_i: f32, lobe: f32) -> f32 {
        let diffuse = self.p_diffuse * cos_i * FRAC_1_PI;
        let lobe = if self.p_lobe > 0.0 {
            self.p_lobe * ((self.exponent + 1.0) * (0.5 * FRAC_1_PI)) * lobe
        } else {
            0.0
        };
        diffuse + lobe
    }

    /// Unit directions with both strictly above the horizon, or `None`
    /// ([`upper_pair`]).
    #[inline]
    fn upper_pair(wi: Vec3, wo: Vec3) -> Option<(Vec3, Vec3)> {
        upper_pair(wi, wo)
    }
}

impl<S: Spectrum> Brdf for ModifiedPhong<S> {
    type Spectrum = S;

    /// `kd/π + ks (n+2)/(2π) cos^n α` (Lafortune & Willems 1994), zero
    /// unless both directions are strictly above the horizon.
    fn eval(&self, wi: Vec3, wo: Vec3) -> S {
        let Some((wi, wo)) = Self::upper_pair(wi, wo) else {
            return S::zero();
        };
        self.f_of_lobe(self.lobe(wi, wo))
    }

    /// With the `simd` feature a vector kernel ([`crate::simd`]),
    /// bit-identical to [`Brdf::eval`].
    #[cfg(feature = "simd")]
    #[inline]
    fn eval_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [S]) {
        crate::simd::Batch::Aos(wi, wo, out).run(&batch::Eval(self))
    }

    /// The kernel of [`eval_batch`](Brdf::eval_batch) on plain vector loads
    /// (bit-identical to [`Brdf::eval`]).
    #[cfg(feature = "simd")]
    #[inline]
    fn eval_batch_soa(&self, wi: Vec3Soa<'_>, wo: Vec3Soa<'_>, out: &mut [S]) {
        crate::simd::Batch::Soa(wi, wo, out).run(&batch::Eval(self))
    }

    /// With the `simd` feature a vector kernel for the mixture density,
    /// bit-identical to [`Brdf::pdf`].
    #[cfg(feature = "simd")]
    #[inline]
    fn pdf_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]) {
        crate::simd::Batch::Aos(wi, wo, out).run(&batch::Pdf(self))
    }

    /// With the `simd` feature a vector kernel for the mixture sampler,
    /// bit-identical to [`Brdf::sample`] (the same `None`s; 0 ulp in `wi`,
    /// pdf and weight).
    #[cfg(feature = "simd")]
    #[inline]
    fn sample_batch(&self, wo: &[Vec3], u: &[[f32; 2]], out: &mut [Option<BrdfSample<S>>]) {
        crate::simd::run_samples(&batch::Sample(self), wo, u, out)
    }

    /// Mixture sampling (see the module documentation). `None` when `wo`
    /// is at or below the horizon, when `kd = ks = 0`, or when the lobe
    /// sample falls at or below the horizon.
    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<S>> {
        let wo_n = unit_or_normalize(wo)?;
        if wo_n.z <= 0.0 {
            return None;
        }
        let (diffuse, u0) = choose_strategy(u[0], self.p_diffuse, self.p_lobe, self.inv_p)?;
        let wi = if diffuse {
            square_to_cosine_hemisphere([u0, u[1]])
        } else {
            let local = sample_cos_power([u0, u[1]], self.inv_n1);
            unit_or_normalize(frame_around_upper(reflect_z(wo_n)).to_world(local))?
        };
        // `eval(wi, wo)` and `pdf(wi, wo)` with one `upper_pair` and one
        // lobe evaluation: the same arithmetic on the same values, so the
        // returned pdf is bit-identical to `pdf(wi, wo)` and the weight to
        // `eval(wi, wo)/pdf · cos θi`.
        let (wi_n, wo_n) = Self::upper_pair(wi, wo)?;
        let lobe = self.lobe(wi_n, wo_n);
        finish_with(wi, self.pdf_of_lobe(wi_n.z, lobe), self.f_of_lobe(lobe))
    }

    /// The mixture density `pd cos θi/π + ps (n+1)/(2π) cos^n α` [sr⁻¹];
    /// zero unless both directions are above the horizon, and zero when
    /// `kd = ks = 0`.
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        let Some((wi, wo)) = Self::upper_pair(wi, wo) else {
            return 0.0;
        };
        let lobe = if self.p_lobe > 0.0 { self.lobe(wi, wo) } else { 0.0 };
        self.pdf_of_lobe(wi.z, lobe)
    }
}

impl<S: Spectrum> IsotropicBrdf for ModifiedPhong<S> {}
