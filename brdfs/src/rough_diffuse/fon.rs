//! Fujii's improved Oren–Nayar BRDF ("FON"), single scattering only.
//!
//! # Formula
//!
//! ```text
//! f_r(ωi, ωo) = (ρ/π) A (1 + σ s/t),      A = 1/(1 + c₁σ),   c₁ = 1/2 − 2/(3π),
//! s = ωi·ωo − cos θi cos θo,               t = max(cos θi, cos θo) if s > 0, else 1,
//! ```
//!
//! for `cos θi > 0` and `cos θo > 0`, else 0. Directional albedo (exact,
//! closed form):
//!
//! ```text
//! E(ωo) = ρ E_FON(cos θo),   E_FON(μ) = A (1 + σ G(μ)/π),
//! G(μ) = sin θ (θ − sin θ cos θ) + (2/3) ((sin θ/cos θ)(1 − sin³θ) − sin θ),   θ = arccos μ,
//! ```
//!
//! ([`fon_albedo`](super::fon_albedo)); `E_FON` falls from 1 at grazing view
//! to `A` at normal view: FON loses energy (22 % at `σ = 1`, normal view),
//! which [`Eon`](super::Eon) puts back.
//!
//! Source: Y. Fujii, "A tiny improvement of Oren–Nayar reflectance model"
//! (2012), in the normalisation of J. Portsmouth, P. Kutz & S. Hill, "EON:
//! A practical energy-preserving rough diffuse BRDF", JCGT 14(1), 2025
//! (arXiv:2410.18026), Listing 1 (`f_EON`'s single-scattering term and
//! `E_FON_exact`); the same form as OpenPBR Surface v1.1's `f_ON`.
//!
//! # Parameters and domain
//!
//! * `rho` ρ: a spectrum with every channel in `[0, 1]` (the single-scattering
//!   albedo colour).
//! * `sigma` σ ∈ `[0, 1]`: **dimensionless** roughness (the EON paper's and
//!   OpenPBR's `base_diffuse_roughness`), `0` = Lambert, `1` = roughest. Not
//!   an angle — the classic model's radians are [`OrenNayar`](super::OrenNayar)'s.
//! * Directions: any finite vectors (normalised first when not unit). `s/t`
//!   grows as `1/cos θ` when both directions graze (the model's own
//!   singularity, `f_r cos θi` stays bounded); `t` is bounded below by
//!   `f32::MIN_POSITIVE`, so `eval` is finite for every finite input; and
//!   `1 + σ s/t` (exactly `≥ 1 − σ ≥ 0`) is clamped at 0, since for opposite
//!   grazing directions the rounded `s` can fall a few ulp below −1.
//!
//! # Smoothness
//!
//! `f_r cos θi` has kinks in `ωi` where `s = 0` (the slope in `s` jumps from
//! `σ` to `σ/t`) and where `cos θi = cos θo` (the `max`), so
//! [`is_smooth`](radiometry::Brdf::is_smooth) is true only at `σ = 0`
//! (Lambert).
//!
//! # Example
//!
//! ```
//! use radiometry::{Brdf, glam::Vec3};
//! use radiometry_brdfs::Fon;
//!
//! let fon = Fon::new(0.8f32, 0.5)?;
//! let (wi, wo) = (Vec3::new(0.6, 0.0, 0.8), Vec3::new(-0.6, 0.0, 0.8));
//! // Opposite azimuths: s = −0.36 ≤ 0, t = 1.
//! let a = 1.0 / (1.0 + 0.2877934 * 0.5);
//! let expect = 0.8 / core::f32::consts::PI * a * (1.0 - 0.5 * 0.36);
//! assert!((fon.eval(wi, wo) - expect).abs() < 1e-6);
//! let s = fon.sample(wo, [0.3, 0.6]).unwrap();
//! assert_eq!(s.pdf, fon.pdf(s.wi, wo)); // bit for bit
//! assert!(Fon::new(0.8f32, 1.5).is_err()); // σ is not in radians
//! # Ok::<(), radiometry_brdfs::BrdfError>(())
//! ```

use super::{C1, RoughLobe, g_over_pi, s_term, t_term};
use crate::error::{BrdfError, check_range};
use core::f32::consts::FRAC_1_PI;
use radiometry::glam::Vec3;
use radiometry::{Albedo, Brdf, BrdfSample, IsotropicBrdf, Spectrum};

/// Fujii's improved Oren–Nayar BRDF; see the [module documentation](self).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fon<S: Spectrum = f32> {
    rho: S,
    sigma: f32,
    /// `A = 1/(1 + c₁σ)`.
    a: f32,
    /// `ρA/π`.
    k: S,
}

impl<S: Spectrum> Fon<S> {
    /// Builds the BRDF.
    ///
    /// # Errors
    /// [`BrdfError::NotFinite`] for a NaN/infinite parameter,
    /// [`BrdfError::OutOfRange`] for a channel of `rho` or `sigma` outside
    /// `[0, 1]`.
    pub fn new(rho: S, sigma: f32) -> Result<Self, BrdfError> {
        for i in 0..S::CHANNELS {
            check_range("rho", rho.channel(i), 0.0, 1.0)?;
        }
        let sigma = check_range("sigma", sigma, 0.0, 1.0)?;
        let a = 1.0 / (1.0 + C1 * sigma);
        Ok(Self {
            rho,
            sigma,
            a,
            k: rho * (a * FRAC_1_PI),
        })
    }

    /// The single-scattering albedo colour ρ.
    pub fn rho(&self) -> S {
        self.rho
    }

    /// The roughness σ ∈ `[0, 1]` (dimensionless).
    pub fn sigma(&self) -> f32 {
        self.sigma
    }
}

impl<S: Spectrum> RoughLobe for Fon<S> {
    type S = S;

    #[inline(always)]
    fn eval_unit(&self, wi: Vec3, wo: Vec3) -> S {
        let s = s_term(wi, wo);
        let s_over_t = if s > 0.0 { s / t_term(wi, wo) } else { s };
        // `1 + σ s ≥ 1 − σ ≥ 0` for unit vectors; the `max` keeps rounding (|s| a few ulp above 1
        // for opposite grazing directions) from making it negative.
        self.k * (1.0 + self.sigma * s_over_t).max(0.0)
    }

    #[inline(always)]
    fn uniform_weight(&self) -> f32 {
        self.sigma
    }

    #[inline]
    fn albedo_at(&self, mu_o: f32) -> S {
        self.rho * (self.a * (1.0 + self.sigma * g_over_pi(mu_o)))
    }

    #[inline]
    fn albedo_error(&self) -> f32 {
        2e-6 * self.rho.max_channel()
    }

    /// `max(1 + σ s/t, 0)`.
    #[cfg(feature = "simd")]
    type Lanes = crate::simd::Vf;

    #[cfg(feature = "simd")]
    #[inline(always)]
    fn unit_lanes(&self, wi: crate::simd::Dirs, wo: crate::simd::Dirs) -> crate::simd::Vf {
        use crate::simd::Vf;
        let (pos, s, q) = super::batch::s_over_t(wi, wo);
        let s_over_t = pos.select(q, s);
        super::batch::max0(Vf::ONE + Vf::splat(self.sigma) * s_over_t)
    }

    #[cfg(feature = "simd")]
    #[inline(always)]
    fn channel_lanes(&self, c: usize, x: &crate::simd::Vf) -> crate::simd::Vf {
        crate::simd::Vf::splat(self.k.channel(c)) * *x
    }
}

impl<S: Spectrum> Brdf for Fon<S> {
    type Spectrum = S;

    /// True only at `σ = 0` (then `f_r = ρ/π`); otherwise `f_r cos θi` has
    /// kinks at `s = 0` and `cos θi = cos θo`.
    fn is_smooth(&self) -> bool {
        self.sigma == 0.0
    }

    /// `ρ E_FON(cos θo)` in closed form (module docs), zero at or below the
    /// horizon. Stated error `2·10⁻⁶ · max ρ`, a bound on the `f32`
    /// rounding of the closed form (measured ≤ 3·10⁻⁷ against `f64`
    /// quadrature of the paper's BRDF).
    fn directional_albedo(&self, wo: Vec3) -> Albedo<S> {
        super::directional_albedo(self, wo)
    }

    /// `(ρ/π) A (1 + σ s/t)` when both directions are above the horizon, else 0.
    #[inline]
    fn eval(&self, wi: Vec3, wo: Vec3) -> S {
        super::eval(self, wi, wo)
    }

    /// The cosine/uniform mixture of the [module documentation](super),
    /// `p_u = σ (1 − cos θo)³/2`.
    #[inline]
    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<S>> {
        super::sample(self, wo, u)
    }

    /// `(1 − p_u) cos θi/π + p_u/(2π)`, `p_u = σ (1 − cos θo)³/2`.
    #[inline]
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        super::pdf(self, wi, wo)
    }

    rough_batch_methods!();
}

impl<S: Spectrum> IsotropicBrdf for Fon<S> {}
