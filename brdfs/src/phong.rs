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
//!   zero vector gives `f = 0`).
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
use core::f32::consts::{FRAC_1_PI, TAU};
use radiometry::frame::{Frame, reflect_z, spherical_direction_sc, try_normalize};
use radiometry::glam::Vec3;
use radiometry::math::{ONE_MINUS_EPSILON, safe_sqrt};
use radiometry::warp::square_to_cosine_hemisphere;
use radiometry::{Brdf, BrdfSample, IsotropicBrdf, Spectrum};

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

    /// Normalised directions with both strictly above the horizon, or `None`.
    #[inline]
    fn upper_pair(wi: Vec3, wo: Vec3) -> Option<(Vec3, Vec3)> {
        let wi = try_normalize(wi)?;
        let wo = try_normalize(wo)?;
        (wi.z > 0.0 && wo.z > 0.0).then_some((wi, wo))
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
        let norm = (self.exponent + 2.0) * (0.5 * FRAC_1_PI);
        self.kd * FRAC_1_PI + self.ks * (norm * self.lobe(wi, wo))
    }

    /// Mixture sampling (see the module documentation). `None` when `wo`
    /// is at or below the horizon, when `kd = ks = 0`, or when the lobe
    /// sample falls at or below the horizon.
    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<S>> {
        let wo_n = try_normalize(wo)?;
        if wo_n.z <= 0.0 {
            return None;
        }
        let (diffuse, u0) = choose_strategy(u[0], self.p_diffuse, self.p_lobe)?;
        let wi = if diffuse {
            square_to_cosine_hemisphere([u0, u[1]])
        } else {
            let local = sample_cos_power([u0, u[1]], self.exponent);
            let frame = Frame::from_normal(reflect_z(wo_n))?;
            try_normalize(frame.to_world(local))?
        };
        finish_sample(self, wi, wo)
    }

    /// The mixture density `pd cos θi/π + ps (n+1)/(2π) cos^n α` [sr⁻¹];
    /// zero unless both directions are above the horizon, and zero when
    /// `kd = ks = 0`.
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        let Some((wi, wo)) = Self::upper_pair(wi, wo) else {
            return 0.0;
        };
        let diffuse = self.p_diffuse * wi.z * FRAC_1_PI;
        let lobe = if self.p_lobe > 0.0 {
            self.p_lobe * ((self.exponent + 1.0) * (0.5 * FRAC_1_PI)) * self.lobe(wi, wo)
        } else {
            0.0
        };
        diffuse + lobe
    }
}

impl<S: Spectrum> IsotropicBrdf for ModifiedPhong<S> {}

// ---------------------------------------------------------------------------
// Helpers shared with `blinn_phong` (crate-private).
// ---------------------------------------------------------------------------

/// Validates `kd`, `ks ∈ [0, 1]` per channel and `kd + ks ≤ 1 + 2⁻²³`.
pub(crate) fn check_kd_ks<S: Spectrum>(kd: S, ks: S) -> Result<(), BrdfError> {
    for i in 0..S::CHANNELS {
        check_range("kd", kd.channel(i), 0.0, 1.0)?;
        check_range("ks", ks.channel(i), 0.0, 1.0)?;
    }
    for i in 0..S::CHANNELS {
        if kd.channel(i) + ks.channel(i) > 1.0 + f32::EPSILON {
            return Err(BrdfError::Constraint {
                what: "kd + ks must not exceed 1 in any channel (energy conservation)",
            });
        }
    }
    Ok(())
}

/// `(kd̄/(kd̄+ks̄), ks̄/(kd̄+ks̄))`, or `(0, 0)` when both averages are 0.
pub(crate) fn strategy_probabilities<S: Spectrum>(kd: S, ks: S) -> (f32, f32) {
    let (a, b) = (kd.average(), ks.average());
    let total = a + b;
    if total > 0.0 {
        let pd = a / total;
        (pd, 1.0 - pd)
    } else {
        (0.0, 0.0)
    }
}

/// Picks a strategy from `u₀` and rescales it to `[0, 1 − 2⁻²⁴]`:
/// `Some((true, u₀/pd))` for the diffuse strategy (`u₀ < pd`),
/// `Some((false, (u₀ − pd)/ps))` for the lobe, `None` when both
/// probabilities are zero. NaN maps to 0.
pub(crate) fn choose_strategy(u0: f32, pd: f32, ps: f32) -> Option<(bool, f32)> {
    if pd.is_nan() || ps.is_nan() || pd + ps <= 0.0 {
        return None;
    }
    let u0 = clamp_unit(u0);
    let (diffuse, v) = if ps <= 0.0 {
        (true, u0)
    } else if pd <= 0.0 {
        (false, u0)
    } else if u0 < pd {
        (true, u0 / pd)
    } else {
        (false, (u0 - pd) / ps)
    };
    Some((diffuse, clamp_unit(v)))
}

/// Clamps to `[0, ONE_MINUS_EPSILON]`, NaN → 0.
#[inline]
fn clamp_unit(x: f32) -> f32 {
    if x > 0.0 { x.min(ONE_MINUS_EPSILON) } else { 0.0 }
}

/// `(1 − δ)^n` for `δ = 1 − cos`, computed as `exp(n · log1p(−δ))`;
/// `0` when `δ ≥ 1` (cosine ≤ 0) or NaN, `1` when `δ ≤ 0`.
#[inline]
pub(crate) fn pow_one_minus(delta: f32, n: f32) -> f32 {
    if delta.is_nan() || delta >= 1.0 {
        0.0
    } else if delta <= 0.0 {
        1.0
    } else {
        libm::expf(n * libm::log1pf(-delta))
    }
}

/// Direction around `+Z` with density `(n+1)/(2π) cos^n θ`:
/// `cos θ = ξ^{1/(n+1)}`, `ξ = 1 − u₀`, `φ = 2π u₁`. `1 − cos θ` is formed
/// as `−expm1(ln ξ/(n+1))` so that it keeps its relative precision for huge
/// `n`. `u` is expected in `[0, 1 − 2⁻²⁴]` (clamped otherwise).
#[inline]
pub(crate) fn sample_cos_power(u: [f32; 2], n: f32) -> Vec3 {
    let xi = 1.0 - clamp_unit(u[0]); // in [2⁻²⁴, 1]
    let delta = (-libm::expm1f(libm::logf(xi) / (n + 1.0))).clamp(0.0, 1.0);
    let sin_t = safe_sqrt(delta * (2.0 - delta));
    spherical_direction_sc(sin_t, 1.0 - delta, TAU * clamp_unit(u[1]))
}

/// Completes a sample: rejects `wi` at or below the horizon, reports
/// `pdf = brdf.pdf(wi, wo)` and `weight = (f/pdf)·cos θi`, and rejects
/// non-positive pdfs or non-finite weights (possible only when the pdf
/// underflows).
pub(crate) fn finish_sample<B: Brdf>(brdf: &B, wi: Vec3, wo: Vec3) -> Option<BrdfSample<B::Spectrum>> {
    if wi.z.is_nan() || wi.z <= 0.0 {
        return None;
    }
    let pdf = brdf.pdf(wi, wo);
    if !pdf.is_finite() || pdf <= 0.0 {
        return None;
    }
    let weight = (brdf.eval(wi, wo) / pdf) * wi.z;
    weight.is_finite().then_some(BrdfSample { wi, pdf, weight })
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::f64::consts::PI as PI64;
    use radiometry::frame::spherical_direction;

    #[test]
    fn compiles_and_evaluates() {
        let b = ModifiedPhong::new(0.2f32, 0.7, 20.0).unwrap();
        let f = b.eval(Vec3::Z, Vec3::Z);
        let expect = 0.2 / PI64 + 0.7 * 22.0 / (2.0 * PI64);
        assert!((f as f64 - expect).abs() < 1e-6 * expect);
        let _ = spherical_direction(0.1, 0.2);
    }
}
