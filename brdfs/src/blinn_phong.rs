//! The normalized Blinn–Phong BRDF.
//!
//! # Formula
//!
//! ```text
//! f_r(ωi, ωo) = kd/π + ks · N(n) · cos^n θh        for cos θi > 0 and cos θo > 0,
//!             = 0                                   otherwise,
//!
//! N(n) = (n + 2)(n + 4) / (8π (n + 2^{−n/2}))
//! ```
//!
//! where `θh` is the angle between the half vector
//! `h = (ωi + ωo)/|ωi + ωo|` and the normal (Blinn 1977, *Models of light
//! reflection for computer synthesized pictures*, SIGGRAPH '77).
//!
//! ## Normalisation
//!
//! `N(n)` is the exact factor that makes the lobe's directional albedo
//! equal to 1 at normal incidence (F. Giesen, *Derivation of Phong and
//! Blinn-Phong BRDF normalization factors*, 2009). Derivation: at
//! `ωo = +Z`, `cos θi = 2cos²θh − 1`, `dωi = 4 cos θh dωh`, and the
//! horizon cuts the lobe at `cos θh = 1/√2`, so
//! `∫ cos^n θh cos θi dωi = 8π ∫_{1/√2}^1 c^{n+1}(2c² − 1) dc
//! = 8π (n + 2^{−n/2}) / ((n + 2)(n + 4))`.
//! Normal incidence is where the albedo peaks (it decreases monotonically
//! with θo; checked by quadrature in the tests for `n` from 0.05 to 1000),
//! so `kd + ks ≤ 1` conserves energy. The popular approximation
//! `(n + 8)/(8π)` (Akenine-Möller, Haines & Hoffman, *Real-Time Rendering*
//! 3rd ed., 2008, §7.6) equals `N(n)` at `n = 0` but exceeds it for
//! `n > 4` — by 7.4 % near `n = 11` — so with it `kd + ks ≤ 1` would not
//! bound the albedo by 1; this crate therefore uses the exact `N(n)`
//! ([`BlinnPhong::normalization`]). For large `n`, `N(n) ≈ (n + 6)/(8π)`.
//!
//! # Parameters and domain
//!
//! * `kd`, `ks`: every channel in `[0, 1]`, `kd + ks ≤ 1` per channel
//!   (with `2⁻²³` of rounding slack), as for
//!   [`ModifiedPhong`](crate::phong::ModifiedPhong).
//! * `n` (`exponent`): `0 ≤ n ≤` [`MAX_EXPONENT`] `= 1e7`.
//! * Directions: any finite vectors; normalised internally. When
//!   `|ωi + ωo| ≤ 10⁻⁷` the half vector is undefined
//!   ([`half_vector`]) and only the diffuse term remains (this needs both
//!   directions within 10⁻⁷ of the horizon and opposite).
//!
//! `cos^n θh` is evaluated as `exp(n · log1p(−δ))` with
//! `δ = 1 − cos θh = (h_x² + h_y²)/(1 + h_z)`, accurate near `h = +Z` even
//! for `n = 10⁷`.
//!
//! # Sampling
//!
//! One-sample mixture of cosine-weighted sampling (probability
//! `pd = kd̄/(kd̄ + ks̄)`) and half-vector sampling (probability `ps`):
//! `h` is drawn with density `(n + 1)/(2π) cos^n θh` (w.r.t. `ωh`;
//! `cos θh = ξ^{1/(n+1)}`, `ξ = 1 − u₀'`) and `ωi = 2(ωo·h)h − ωo`; the
//! change of variables `dωh/dωi = 1/(4 ωo·h)` (Torrance & Sparrow 1967;
//! Walter et al. 2007, *Microfacet models for refraction through rough
//! surfaces*, §4) gives
//!
//! ```text
//! pdf(ωi, ωo) = pd · cos θi/π + ps · (n + 1)/(2π) · cos^n θh / (4 ωo·h).
//! ```
//!
//! Reflected directions at or below the horizon are rejected (`None`), so
//! `∫_H pdf dω ≤ 1`; at normal incidence the rejected lobe mass is
//! `2^{−(n+1)/2}` (`cos θh ≤ 1/√2`). When `kd = ks = 0`, `sample` returns
//! `None` and `pdf` returns `0`.
//!
//! # Example
//!
//! ```
//! use radiometry::{Brdf, glam::Vec3};
//! use radiometry_brdfs::BlinnPhong;
//! use core::f32::consts::PI;
//!
//! let b = BlinnPhong::new(0.1f32, 0.9, 50.0)?;
//! // Mirror configuration: h = +Z.
//! let (wi, wo) = (Vec3::new(0.6, 0.0, 0.8), Vec3::new(-0.6, 0.0, 0.8));
//! let expect = 0.1 / PI + 0.9 * BlinnPhong::<f32>::normalization(50.0);
//! assert!((b.eval(wi, wo) - expect).abs() < 1e-5 * expect);
//! let s = b.sample(wo, [0.9, 0.1]).unwrap();
//! assert!((s.pdf - b.pdf(s.wi, wo)).abs() <= 1e-5 * s.pdf);
//! # Ok::<(), radiometry_brdfs::BrdfError>(())
//! ```

use crate::error::{BrdfError, check_range};
pub use crate::phong::MAX_EXPONENT;
use crate::phong::{
    check_kd_ks, choose_strategy, finish_sample, pow_one_minus, sample_cos_power, strategy_probabilities,
};
use core::f32::consts::FRAC_1_PI;
use radiometry::frame::{half_vector, try_normalize};
use radiometry::glam::Vec3;
use radiometry::warp::square_to_cosine_hemisphere;
use radiometry::{Brdf, BrdfSample, IsotropicBrdf, Spectrum};

/// The normalized Blinn–Phong BRDF `kd/π + ks N(n) cos^n θh`; see the
/// [module documentation](self) for the normalisation, domain and sampling.
///
/// ```
/// use radiometry::{Brdf, glam::Vec3};
/// use radiometry_brdfs::BlinnPhong;
///
/// let b = BlinnPhong::new(Vec3::splat(0.2), Vec3::new(0.8, 0.7, 0.6), 1e6)?;
/// let f = b.eval(Vec3::Z, Vec3::Z);
/// assert!(f.is_finite() && f.x > f.z);
/// assert!(BlinnPhong::new(0.0f32, 0.5, f32::NAN).is_err());
/// # Ok::<(), radiometry_brdfs::BrdfError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BlinnPhong<S: Spectrum = f32> {
    kd: S,
    ks: S,
    exponent: f32,
    /// `N(n)`.
    norm: f32,
    p_diffuse: f32,
    p_lobe: f32,
}

impl<S: Spectrum> BlinnPhong<S> {
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
            norm: Self::normalization(exponent),
            p_diffuse,
            p_lobe,
        })
    }

    /// The lobe normalisation `N(n) = (n + 2)(n + 4)/(8π (n + 2^{−n/2}))`
    /// (Giesen 2009; derived in the module documentation), evaluated in
    /// `f64` and rounded. Domain: `n ∈ [0, MAX_EXPONENT]` (values outside
    /// are clamped to it; NaN is treated as 0).
    pub fn normalization(exponent: f32) -> f32 {
        let n = if exponent > 0.0 {
            exponent.min(MAX_EXPONENT) as f64
        } else {
            0.0
        };
        let v = (n + 2.0) * (n + 4.0) / (8.0 * core::f64::consts::PI * (n + libm::exp2(-0.5 * n)));
        v as f32
    }

    /// Diffuse reflectance `kd`.
    pub fn kd(&self) -> S {
        self.kd
    }

    /// Specular reflectance `ks` (the lobe's albedo at normal incidence).
    pub fn ks(&self) -> S {
        self.ks
    }

    /// Blinn–Phong exponent `n`.
    pub fn exponent(&self) -> f32 {
        self.exponent
    }

    /// Normalised `(ωi, ωo)` with both strictly above the horizon, or `None`.
    #[inline]
    fn upper_pair(wi: Vec3, wo: Vec3) -> Option<(Vec3, Vec3)> {
        let wi = try_normalize(wi)?;
        let wo = try_normalize(wo)?;
        (wi.z > 0.0 && wo.z > 0.0).then_some((wi, wo))
    }

    /// `cos^n θh` of the unit half vector `h` (`h_z ≥ 0`).
    #[inline]
    fn lobe(&self, h: Vec3) -> f32 {
        let delta = (h.x * h.x + h.y * h.y) / (1.0 + h.z);
        pow_one_minus(delta, self.exponent)
    }
}

impl<S: Spectrum> Brdf for BlinnPhong<S> {
    type Spectrum = S;

    /// `kd/π + ks N(n) cos^n θh`, zero unless both directions are strictly
    /// above the horizon.
    fn eval(&self, wi: Vec3, wo: Vec3) -> S {
        let Some((wi, wo)) = Self::upper_pair(wi, wo) else {
            return S::zero();
        };
        let lobe = half_vector(wi, wo).map_or(0.0, |h| self.lobe(h));
        self.kd * FRAC_1_PI + self.ks * (self.norm * lobe)
    }

    /// Mixture sampling (see the module documentation). `None` when `wo`
    /// is at or below the horizon, when `kd = ks = 0`, or when the
    /// reflected direction is at or below the horizon.
    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<S>> {
        let wo_n = try_normalize(wo)?;
        if wo_n.z <= 0.0 {
            return None;
        }
        let (diffuse, u0) = choose_strategy(u[0], self.p_diffuse, self.p_lobe)?;
        let wi = if diffuse {
            square_to_cosine_hemisphere([u0, u[1]])
        } else {
            let h = sample_cos_power([u0, u[1]], self.exponent);
            let wo_h = wo_n.dot(h);
            if wo_h.is_nan() || wo_h <= 0.0 {
                return None;
            }
            try_normalize(2.0 * wo_h * h - wo_n)?
        };
        finish_sample(self, wi, wo)
    }

    /// `pd cos θi/π + ps (n+1)/(2π) cos^n θh/(4 ωo·h)` [sr⁻¹]; zero unless
    /// both directions are above the horizon, and zero when `kd = ks = 0`.
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        let Some((wi, wo)) = Self::upper_pair(wi, wo) else {
            return 0.0;
        };
        let diffuse = self.p_diffuse * wi.z * FRAC_1_PI;
        let lobe = match half_vector(wi, wo) {
            Some(h) if self.p_lobe > 0.0 => {
                let wo_h = wo.dot(h);
                if wo_h > 0.0 {
                    // wo·h = |ωi + ωo|/2 ≥ 5·10⁻⁸ when h is defined, so the
                    // quotient is ≤ 2·10¹³ (finite).
                    self.p_lobe * ((self.exponent + 1.0) * (0.5 * FRAC_1_PI)) * self.lobe(h) / (4.0 * wo_h)
                } else {
                    0.0
                }
            }
            _ => 0.0,
        };
        diffuse + lobe
    }
}

impl<S: Spectrum> IsotropicBrdf for BlinnPhong<S> {}
