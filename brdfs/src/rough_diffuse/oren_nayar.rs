//! The classic "qualitative" Oren–Nayar BRDF (QON), as pbrt-v3 has it.
//!
//! # Formula
//!
//! ```text
//! f_r(ωi, ωo) = (ρ/π) (A + B max(0, cos(φi − φo)) sin α tan β),   α = max(θi, θo), β = min(θi, θo),
//! A = 1 − σ²/(2(σ² + 0.33)),   B = 0.45 σ²/(σ² + 0.09),
//! ```
//!
//! for `cos θi > 0` and `cos θo > 0`, else 0, with `σ` the standard
//! deviation of the facet slope angle **in radians**. Since
//! `max(0, cos Δφ) sin α tan β = max(0, s)/max(cos θi, cos θo)` with
//! `s = ωi·ωo − cos θi cos θo = sin θi sin θo cos Δφ`, it is evaluated as
//! `(ρ/π)(A + B max(0, s)/t)`, `t = max(cos θi, cos θo)` — no trigonometric
//! functions, and the same value (pbrt-v3 additionally sets the `B` term to 0
//! when `sin θi` or `sin θo` is below 10⁻⁴, where it is below `10⁻⁴ B` anyway).
//!
//! Directional albedo (exact, closed form; derived here by integrating the
//! formula over `ωi`, checked against `f64` quadrature in the tests):
//!
//! ```text
//! E(ωo) = ρ (A + B H(μo)),   H(μ) = (1/π) [sin θ (θ − sin θ cos θ) + (2/3) (sin θ/cos θ)(1 − sin³θ)],
//! ```
//!
//! `θ = arccos μ`; `H` falls from `1/2` at grazing view to 0 at normal view.
//!
//! **Energy.** The qualitative model is not energy-conserving: at grazing
//! view its albedo tends to `ρ (A + B/2)`, which exceeds `ρ` for
//! `σ < 0.326` rad (18.7°) — by up to 1.52 % (at `σ ≈ 0.2` rad). This crate
//! keeps every plugin's albedo ≤ 1, so the constructor rejects
//! `ρ > 1/(A + B/2)` with [`BrdfError::EnergyGain`]
//! ([`OrenNayar::max_rho`] gives the bound); pbrt-v3 accepts such ρ and
//! reflects more than it receives there. For an energy-preserving rough
//! diffuse model use [`Eon`](super::Eon).
//!
//! Sources: M. Oren & S. K. Nayar, "Generalization of Lambert's reflectance
//! model", SIGGRAPH 1994 (its "qualitative model"); M. Pharr, W. Jakob &
//! G. Humphreys, *Physically Based Rendering* 3rd ed. (2016), the section
//! "Oren–Nayar Diffuse Reflection" (`OrenNayar::f`, σ given in degrees and
//! converted to radians).
//!
//! # Parameters and domain
//!
//! * `rho` ρ: a spectrum with every channel in `[0, min(1, 1/(A + B/2))]`.
//! * `sigma_rad` σ ∈ `[0, π/2]` **radians** (pbrt-v3's scene files give
//!   degrees: convert with `to_radians`). Not the dimensionless σ of
//!   [`Fon`](super::Fon)/[`Eon`](super::Eon).
//! * Directions: any finite vectors, as for [`Fon`](super::Fon) (same
//!   `1/cos θ` growth when both graze, same bound on `t`).
//!
//! # Smoothness
//!
//! `f_r cos θi` has kinks in `ωi` at `s = 0` (the `max(0, ·)`) and at
//! `cos θi = cos θo`, so [`is_smooth`](radiometry::Brdf::is_smooth) is true
//! only at `σ = 0` (Lambert).
//!
//! # Example
//!
//! ```
//! use radiometry::{Brdf, IsotropicBrdf};
//! use radiometry_brdfs::{BrdfError, OrenNayar};
//!
//! let sigma = 20f32.to_radians(); // pbrt-v3's `sigma 20`
//! let on = OrenNayar::new(0.5f32, sigma)?;
//! let (s2, pi) = (sigma * sigma, core::f32::consts::PI);
//! let (a, b) = (1.0 - s2 / (2.0 * (s2 + 0.33)), 0.45 * s2 / (s2 + 0.09));
//! // θi = 60°, θo = 30°, same azimuth: sin α tan β = sin 60° tan 30° = 1/2.
//! let f = on.eval_isotropic(60f32.to_radians(), 30f32.to_radians(), 0.0);
//! assert!((f - 0.5 / pi * (a + b * 0.5)).abs() < 1e-6);
//! // The classic model gains energy at small σ: ρ = 1 is rejected there.
//! assert!(matches!(OrenNayar::new(1.0f32, 0.2), Err(BrdfError::EnergyGain { .. })));
//! assert!(OrenNayar::new(OrenNayar::max_rho(0.2), 0.2).is_ok());
//! # Ok::<(), BrdfError>(())
//! ```

use super::{RoughLobe, qon_h, s_term, t_term};
use crate::error::{BrdfError, check_range};
use core::f32::consts::{FRAC_1_PI, FRAC_PI_2};
use radiometry::glam::Vec3;
use radiometry::{Albedo, Brdf, BrdfSample, IsotropicBrdf, Spectrum};

/// The classic Oren–Nayar BRDF (pbrt-v3); see the [module documentation](self).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OrenNayar<S: Spectrum = f32> {
    rho: S,
    sigma_rad: f32,
    a: f32,
    b: f32,
    /// `ρA/π`.
    k_a: S,
    /// `ρB/π`.
    k_b: S,
}

/// `(A, B)` of the qualitative model for `σ` in radians.
#[inline]
fn coefficients(sigma_rad: f32) -> (f32, f32) {
    let s2 = sigma_rad * sigma_rad;
    (1.0 - s2 / (2.0 * (s2 + 0.33)), 0.45 * s2 / (s2 + 0.09))
}

impl OrenNayar<f32> {
    /// The largest ρ whose albedo stays ≤ 1 at every `ωo`:
    /// `min(1, 1/(A + B/2))` (the albedo is largest at grazing view, where it
    /// tends to `ρ (A + B/2)`). Below 1 only for `σ < 0.326` rad; smallest,
    /// `0.98505`, at `σ ≈ 0.2` rad. `σ` is clamped to `[0, π/2]`.
    ///
    /// ```
    /// use radiometry_brdfs::OrenNayar;
    /// assert_eq!(OrenNayar::max_rho(0.0), 1.0);
    /// assert!((OrenNayar::max_rho(0.2) - 0.98505).abs() < 1e-4);
    /// assert_eq!(OrenNayar::max_rho(0.5), 1.0);
    /// ```
    pub fn max_rho(sigma_rad: f32) -> f32 {
        let sigma_rad = if sigma_rad.is_nan() {
            0.0
        } else {
            sigma_rad.clamp(0.0, FRAC_PI_2)
        };
        let (a, b) = coefficients(sigma_rad);
        (1.0 / (a + 0.5 * b)).min(1.0)
    }
}

impl<S: Spectrum> OrenNayar<S> {
    /// Builds the BRDF.
    ///
    /// # Errors
    /// [`BrdfError::NotFinite`] for a NaN/infinite parameter,
    /// [`BrdfError::OutOfRange`] for a channel of `rho` outside `[0, 1]` or
    /// `sigma_rad` outside `[0, π/2]`, [`BrdfError::EnergyGain`] for a
    /// channel of `rho` above [`OrenNayar::max_rho`]`(sigma_rad)`.
    pub fn new(rho: S, sigma_rad: f32) -> Result<Self, BrdfError> {
        for i in 0..S::CHANNELS {
            check_range("rho", rho.channel(i), 0.0, 1.0)?;
        }
        let sigma_rad = check_range("sigma_rad", sigma_rad, 0.0, FRAC_PI_2)?;
        let max = OrenNayar::max_rho(sigma_rad);
        let value = rho.max_channel();
        if value > max {
            return Err(BrdfError::EnergyGain {
                name: "rho",
                value,
                max,
            });
        }
        let (a, b) = coefficients(sigma_rad);
        Ok(Self {
            rho,
            sigma_rad,
            a,
            b,
            k_a: rho * (a * FRAC_1_PI),
            k_b: rho * (b * FRAC_1_PI),
        })
    }

    /// The albedo colour ρ.
    pub fn rho(&self) -> S {
        self.rho
    }

    /// The roughness σ in radians.
    pub fn sigma_rad(&self) -> f32 {
        self.sigma_rad
    }

    /// The coefficients `(A, B)`.
    pub fn coefficients(&self) -> (f32, f32) {
        (self.a, self.b)
    }
}

impl<S: Spectrum> RoughLobe for OrenNayar<S> {
    type S = S;

    #[inline(always)]
    fn eval_unit(&self, wi: Vec3, wo: Vec3) -> S {
        let s = s_term(wi, wo);
        if s > 0.0 {
            self.k_a + self.k_b * (s / t_term(wi, wo))
        } else {
            self.k_a
        }
    }

    #[inline(always)]
    fn uniform_weight(&self) -> f32 {
        (self.b / self.a).min(1.0)
    }

    #[inline]
    fn albedo_at(&self, mu_o: f32) -> S {
        self.rho * (self.a + self.b * qon_h(mu_o))
    }

    #[inline]
    fn albedo_error(&self) -> f32 {
        2e-6 * self.rho.max_channel()
    }

    /// `(s > 0, s/t)`.
    #[cfg(feature = "simd")]
    type Lanes = (crate::simd::Vf, crate::simd::Vf);

    #[cfg(feature = "simd")]
    #[inline(always)]
    fn unit_lanes(&self, wi: crate::simd::Dirs, wo: crate::simd::Dirs) -> Self::Lanes {
        let (pos, _, q) = super::batch::s_over_t(wi, wo);
        (pos, q)
    }

    #[cfg(feature = "simd")]
    #[inline(always)]
    fn channel_lanes(&self, c: usize, t: &Self::Lanes) -> crate::simd::Vf {
        use crate::simd::Vf;
        let k_a = Vf::splat(self.k_a.channel(c));
        t.0.select(k_a + Vf::splat(self.k_b.channel(c)) * t.1, k_a)
    }
}

impl<S: Spectrum> Brdf for OrenNayar<S> {
    type Spectrum = S;

    /// True only at `σ = 0` (then `f_r = ρ/π`); otherwise `f_r cos θi` has
    /// kinks at `s = 0` and `cos θi = cos θo`.
    fn is_smooth(&self) -> bool {
        self.sigma_rad == 0.0
    }

    /// `ρ (A + B H(cos θo))` in closed form (module docs), zero at or below
    /// the horizon. Stated error `2·10⁻⁶ · max ρ`, a bound on the `f32`
    /// rounding of the closed form (measured ≤ 3·10⁻⁷ against `f64`
    /// quadrature of pbrt-v3's formula).
    fn directional_albedo(&self, wo: Vec3) -> Albedo<S> {
        super::directional_albedo(self, wo)
    }

    /// `(ρ/π)(A + B max(0, s)/t)` when both directions are above the
    /// horizon, else 0.
    #[inline]
    fn eval(&self, wi: Vec3, wo: Vec3) -> S {
        super::eval(self, wi, wo)
    }

    /// The cosine/uniform mixture of the [module documentation](super),
    /// `p_u = min(1, B/A)(1 − cos θo)³/2`.
    #[inline]
    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<S>> {
        super::sample(self, wo, u)
    }

    /// `(1 − p_u) cos θi/π + p_u/(2π)`, `p_u = min(1, B/A)(1 − cos θo)³/2`.
    #[inline]
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        super::pdf(self, wi, wo)
    }

    rough_batch_methods!();
}

impl<S: Spectrum> IsotropicBrdf for OrenNayar<S> {}
