//! The energy-preserving Oren–Nayar BRDF ("EON"): FON plus a closed-form
//! multiple-scattering lobe.
//!
//! # Formula
//!
//! ```text
//! f_r(ωi, ωo) = f_FON(ωi, ωo) + f_ms(ωi, ωo),
//! f_FON       = (ρ/π) A (1 + σ s/t)                                  (see Fon),
//! f_ms        = (ρ_ms/π) (1 − E_FON(μi)) (1 − E_FON(μo)) / (1 − Ē_FON),
//! ρ_ms        = ρ² Ē_FON / (1 − ρ (1 − Ē_FON)),
//! Ē_FON       = 2∫₀¹ E_FON(μ) μ dμ = A (1 + c₂σ),   c₂ = 2/3 − 28/(15π),
//! ```
//!
//! with `μ = cos θ`, `A = 1/(1 + c₁σ)`, `c₁ = 1/2 − 2/(3π)`, and the
//! **exact** FON albedo `E_FON(μ) = A (1 + σ G(μ)/π)`
//! ([`fon_albedo`](super::fon_albedo)). Directional albedo (exact):
//!
//! ```text
//! E(ωo) = ρ E_FON(μo) + ρ_ms (1 − E_FON(μo)),
//! ```
//!
//! because the lobe integrates to `ρ_ms (1 − E_FON(μo))` exactly when
//! `Ē_FON` is the true cosine-weighted average of the `E_FON` used. At
//! `ρ = 1`, `ρ_ms = 1` and `E(ωo) = 1` for every `ωo`: the white furnace
//! passes. With the paper's *fitted* `E_FON` (a cubic in `1 − μ`) in place of
//! the exact one the two no longer match and the furnace misses by about
//! `5·10⁻⁴`; this plugin uses the exact form only.
//!
//! Evaluation: since `1 − E_FON(μ) = A σ (c₁ − G(μ)/π)` and
//! `1 − Ē_FON = A σ (c₁ − c₂)`, the lobe is evaluated as
//! `(ρ_ms/π) A σ (c₁ − G(μi)/π)(c₁ − G(μo)/π)/(c₁ − c₂)` — the same number,
//! without the cancellation of `1 − E` at small σ and exactly 0 at `σ = 0`
//! (the paper's listing clamps each factor at `10⁻⁷` instead).
//!
//! Source: J. Portsmouth, P. Kutz & S. Hill, "EON: A practical
//! energy-preserving rough diffuse BRDF", JCGT 14(1), 2025
//! (arXiv:2410.18026), Listing 1 (`f_EON` with `exact = true`,
//! `E_FON_exact`). Note: the OpenPBR Surface specification v1.1.1 prints
//! `ρ_ms = (ρ²/π) …`, an extra `1/π` that the paper's listing does not have;
//! with it the albedo at `ρ = 1` falls below 1 (to `E_FON + (1 − E_FON)/π`),
//! and this crate's white-furnace test (albedo 1 within 10⁻⁴ at `ρ = 1` for
//! `σ ∈ [0, 1]`, `θo ∈ [0°, 89.9°]`) rejects it.
//!
//! # Parameters and domain
//!
//! * `rho` ρ: a spectrum with every channel in `[0, 1]`.
//! * `sigma` σ ∈ `[0, 1]`: **dimensionless** roughness, as for
//!   [`Fon`](super::Fon) (not radians).
//! * Directions: any finite vectors, as for [`Fon`](super::Fon).
//!
//! `E(ωo) ≤ ρ ≤ 1` for every `ωo` (since `ρ_ms ≤ ρ`).
//!
//! # Smoothness
//!
//! As FON: kinks at `s = 0` and `cos θi = cos θo`, so
//! [`is_smooth`](radiometry::Brdf::is_smooth) is true only at `σ = 0`.
//!
//! # Example
//!
//! ```
//! use radiometry::{Brdf, glam::Vec3};
//! use radiometry_brdfs::Eon;
//!
//! let white = Eon::new(1.0f32, 0.7)?;
//! for z in [1.0f32, 0.5, 0.01] {
//!     let wo = Vec3::new((1.0 - z * z).sqrt(), 0.0, z);
//!     assert!((white.directional_albedo(wo).value - 1.0).abs() < 2e-6);
//! }
//! let red = Eon::new(Vec3::new(0.9, 0.2, 0.1), 0.7)?;
//! let s = red.sample(Vec3::Z, [0.5, 0.25]).unwrap();
//! assert_eq!(s.pdf, red.pdf(s.wi, Vec3::Z));
//! # Ok::<(), radiometry_brdfs::BrdfError>(())
//! ```

use super::{C1, C2, RoughLobe, fon_deficit, g_over_pi, s_term, t_term};
use crate::error::{BrdfError, check_range};
use core::f32::consts::FRAC_1_PI;
use radiometry::glam::Vec3;
use radiometry::{Albedo, Brdf, BrdfSample, IsotropicBrdf, Spectrum};

/// `c₁ − c₂ = 6/(5π) − 1/6`, evaluated in `f64` and rounded: `0.2153052`.
const C1_MINUS_C2: f32 = 0.215_305_2;

/// The energy-preserving Oren–Nayar BRDF; see the [module documentation](self).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Eon<S: Spectrum = f32> {
    rho: S,
    sigma: f32,
    /// `A = 1/(1 + c₁σ)`.
    a: f32,
    /// `ρA/π`.
    k_ss: S,
    /// `ρ_ms`.
    rho_ms: S,
    /// `ρ_ms A σ/(π (c₁ − c₂))`.
    k_ms: S,
}

impl<S: Spectrum> Eon<S> {
    /// `ρ E_FON + ρ_ms (1 − E_FON)` from `G(μo)/π` = `g`: `E_FON = A (1 + σ
    /// g)`, `1 − E_FON = A σ (c₁ − g)⁺`.
    #[inline(always)]
    fn albedo_from_g(&self, g: f32) -> S {
        if self.sigma == 0.0 {
            // σ = 0: `E_FON = 1` and `ρ_ms (1 − E_FON) = +0`, the same bits
            // (`+ 0` as the general form adds it: ρ = −0 gives +0).
            return self.rho + S::zero();
        }
        let e_fon = self.a * (1.0 + self.sigma * g);
        let one_minus = self.a * self.sigma * (C1 - g).max(0.0);
        self.rho * e_fon + self.rho_ms * one_minus
    }

    /// The uniform share `p_u = ½ k max(1 − μo, 0)³` of [`Brdf::sample`]'s
    /// mixture at `μo = cos θo` (the rest is the cosine-weighted hemisphere).
    #[inline]
    pub(crate) fn uniform_share(&self, mu_o: f32) -> f32 {
        super::p_uniform(self.uniform_weight(), mu_o).clamp(0.0, 1.0)
    }

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
        Ok(Self::from_valid(rho, sigma))
    }

    /// The lobe of a `ρ` and `σ` the caller has checked (each in `[0, 1]`):
    /// a material built at every hit from parameters it validated.
    #[inline(always)]
    pub(crate) fn from_valid(rho: S, sigma: f32) -> Self {
        let a = 1.0 / (1.0 + C1 * sigma);
        let mean = a * (1.0 + C2 * sigma);
        let loss = a * sigma * C1_MINUS_C2; // 1 − Ē_FON
        // ρ_ms = ρ² Ē/(1 − ρ(1 − Ē)); the denominator is ≥ Ē ≥ 0.776.
        let rho_ms = rho.map(|r| r * r * mean / (1.0 - r * loss));
        Self {
            rho,
            sigma,
            a,
            k_ss: rho * (a * FRAC_1_PI),
            rho_ms,
            k_ms: rho_ms * (a * sigma * FRAC_1_PI / C1_MINUS_C2),
        }
    }

    /// The single-scattering albedo colour ρ.
    pub fn rho(&self) -> S {
        self.rho
    }

    /// The roughness σ ∈ `[0, 1]` (dimensionless).
    pub fn sigma(&self) -> f32 {
        self.sigma
    }

    /// The multiple-scattering albedo `ρ_ms = ρ² Ē_FON/(1 − ρ(1 − Ē_FON))`
    /// (equal to ρ² at σ = 0, where the lobe vanishes, and to 1 at ρ = 1).
    pub fn rho_ms(&self) -> S {
        self.rho_ms
    }
}

impl<S: Spectrum> RoughLobe for Eon<S> {
    type S = S;

    #[inline(always)]
    fn eval_unit(&self, wi: Vec3, wo: Vec3) -> S {
        if self.sigma == 0.0 {
            // Lambert, `ρ/π`: with σ = 0 the terms below are `k_ss · 1 + (+0)`
            // (unit directions: `s/t` and `ms` are finite), the same bits — the
            // `+ 0` included, which turns the `−0` of `ρ = −0` into `+0`.
            return self.k_ss + S::zero();
        }
        let s = s_term(wi, wo);
        let s_over_t = if s > 0.0 { s / t_term(wi, wo) } else { s };
        let ms = fon_deficit(wi.z) * fon_deficit(wo.z);
        // `1 + σ s ≥ 1 − σ ≥ 0` for unit vectors; the `max` keeps rounding (|s| a few ulp above 1
        // for opposite grazing directions) from making it negative.
        self.k_ss * (1.0 + self.sigma * s_over_t).max(0.0) + self.k_ms * ms
    }

    #[inline(always)]
    fn uniform_weight(&self) -> f32 {
        self.sigma
    }

    #[inline]
    fn albedo_at(&self, mu_o: f32) -> S {
        if self.sigma == 0.0 {
            return self.albedo_from_g(0.0);
        }
        self.albedo_from_g(g_over_pi(mu_o))
    }

    #[inline]
    fn albedo_error(&self) -> f32 {
        2e-6 * self.rho.max_channel()
    }

    /// `(max(1 + σ s/t, 0), (c₁ − G(μi)/π)⁺ (c₁ − G(μo)/π)⁺)`.
    #[cfg(feature = "simd")]
    type Lanes = (crate::simd::Vf, crate::simd::Vf);

    #[cfg(feature = "simd")]
    #[inline(always)]
    fn unit_lanes(&self, wi: crate::simd::Dirs, wo: crate::simd::Dirs) -> Self::Lanes {
        use super::batch::{fon_deficit, max0, s_over_t};
        use crate::simd::Vf;
        if self.sigma == 0.0 {
            // Lambert, as in `eval_unit`: `k_ss · 1 + 0 · 0`, the same bits.
            return (Vf::ONE, Vf::splat(0.0));
        }
        let (pos, s, q) = s_over_t(wi, wo);
        let s_over_t = pos.select(q, s);
        let ms = fon_deficit(wi.z) * fon_deficit(wo.z);
        (max0(Vf::ONE + Vf::splat(self.sigma) * s_over_t), ms)
    }

    #[cfg(feature = "simd")]
    #[inline(always)]
    fn channel_lanes(&self, c: usize, t: &Self::Lanes) -> crate::simd::Vf {
        use crate::simd::Vf;
        Vf::splat(self.k_ss.channel(c)) * t.0 + Vf::splat(self.k_ms.channel(c)) * t.1
    }
}

impl<S: Spectrum> Brdf for Eon<S> {
    type Spectrum = S;

    /// True only at `σ = 0` (then `f_r = ρ/π`); otherwise `f_r cos θi` has
    /// kinks at `s = 0` and `cos θi = cos θo`.
    fn is_smooth(&self) -> bool {
        self.sigma == 0.0
    }

    /// `ρ E_FON(μo) + ρ_ms (1 − E_FON(μo))` in closed form (module docs),
    /// zero at or below the horizon; 1 at `ρ = 1` (to `f32` rounding).
    /// Stated error `2·10⁻⁶ · max ρ`, a bound on the `f32` rounding of the
    /// closed form (measured ≤ 3·10⁻⁷ against `f64` quadrature of the
    /// paper's BRDF).
    fn directional_albedo(&self, wo: Vec3) -> Albedo<S> {
        super::directional_albedo(self, wo)
    }

    /// With the `simd` feature, `G(μo)/π` in vector lanes (its `acos` the
    /// crate's bit-exact vector port), the rest per element: bit for bit
    /// [`directional_albedo`](Brdf::directional_albedo)'s value.
    #[cfg(feature = "simd")]
    fn directional_albedo_batch(&self, wo: &[Vec3], out: &mut [S]) {
        use crate::simd::{LANES, Vf};
        let lanes = |w: &[Vec3], o: &mut [S]| {
            let (mut mu, mut above) = ([0.0f32; LANES], [false; LANES]);
            for ((m, a), &w) in mu.iter_mut().zip(&mut above).zip(w) {
                if let Some(u) = super::unit(w)
                    && u.z > 0.0
                {
                    (*m, *a) = (u.z, true);
                }
            }
            // σ = 0 does not read `G` (`albedo_from_g` returns ρ).
            let g = if self.sigma == 0.0 {
                [0.0; LANES]
            } else {
                super::batch::g_over_pi(Vf::from(mu)).to_array()
            };
            for ((o, &g), &a) in o.iter_mut().zip(&g).zip(&above) {
                *o = if a { self.albedo_from_g(g) } else { S::zero() };
            }
        };
        crate::simd::albedo_chunks(wo, out, lanes, |w| self.directional_albedo(w).value);
    }

    /// `f_FON + f_ms` when both directions are above the horizon, else 0.
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

impl<S: Spectrum> IsotropicBrdf for Eon<S> {}
