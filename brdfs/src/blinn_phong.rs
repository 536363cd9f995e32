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
//! with θo: checked by f64 quadrature in the unit tests for
//! `n ∈ {0.3, 1, 4, 11, 30, 100}` at seven θo up to 1.55, and for
//! `n = 1000` at θo = 0.5), so `kd + ks ≤ 1` conserves energy. The popular approximation
//! `(n + 8)/(8π)` (Akenine-Möller, Haines & Hoffman, *Real-Time Rendering*
//! 3rd ed., 2008, ch. 7) equals `N(n)` at `n = 0` but exceeds it for
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
//! * Directions: any finite vectors; normalised internally (vectors
//!   already unit to rounding, `|‖ω‖² − 1| ≤ 4ε`, are used as given). When
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
//! surfaces*) gives
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
    check_kd_ks, choose_strategy, finish_with, pow_one_minus, sample_cos_power, strategy_probabilities,
    strategy_reciprocals, unit_or_normalize,
};
use core::f32::consts::FRAC_1_PI;
#[cfg(feature = "simd")]
use radiometry::batch::Vec3Soa;
use radiometry::frame::half_vector;
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
    /// `1/(n + 1)`, the sampler's power `cos θ = ξ^{1/(n+1)}`.
    inv_n1: f32,
    /// `[1/pd, 1/ps]` ([`strategy_reciprocals`]).
    inv_p: [f32; 2],
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
            inv_n1: 1.0 / (exponent + 1.0),
            inv_p: strategy_reciprocals(p_diffuse, p_lobe),
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

    /// Unit `(ωi, ωo)` with both strictly above the horizon, or `None`
    /// ([`crate::phong::upper_pair`]: used as given when both are unit to
    /// rounding, else normalised).
    #[inline]
    fn upper_pair(wi: Vec3, wo: Vec3) -> Option<(Vec3, Vec3)> {
        crate::phong::upper_pair(wi, wo)
    }

    /// The lobe term `ps (n+1)/(2π) cos^n θh/(4 ωo·h)` of the pdf from
    /// `cos^n θh` for unit `wi`, `wo` above the horizon with a defined half
    /// vector (the arithmetic of [`Brdf::pdf`], shared with `sample`).
    #[inline(always)]
    fn lobe_pdf(&self, wi: Vec3, wo: Vec3, lobe: f32) -> f32 {
        // For unit ωi, ωo above the horizon, ωo·h = |ωi + ωo|/2
        // exactly; computing it that way (not as a dot product of
        // rounded vectors, which can be ~1e-30 for ωi ≈ −ωo) keeps
        // it ≥ 5·10⁻⁸ whenever h is defined, so the quotient is
        // ≤ 2·10¹³ (finite). Found by the `brdf_eval` fuzz target.
        let wo_h = 0.5 * (wi + wo).length();
        if wo_h > 0.0 {
            self.p_lobe * ((self.exponent + 1.0) * (0.5 * FRAC_1_PI)) * lobe / (4.0 * wo_h)
        } else {
            0.0
        }
    }

    /// `cos^n θh` of the unit half vector `h` (`h_z ≥ 0`).
    ///
    /// Near the pole (`cos θh ≥ 1/2`) it is `(1 − δ)^n` with
    /// `δ = (h_x² + h_y²)/(1 + h_z) = 1 − cos θh`, which keeps precision for
    /// huge `n`; away from it `cos θh = h_z` is itself accurate and is raised
    /// to the power directly, so a nearly horizontal `h` (`h_z ≈ 10⁻⁸`,
    /// where `1 − δ` rounds to 0) still gives `cos⁰ θh = 1` for `n = 0`.
    #[inline]
    fn lobe(&self, h: Vec3) -> f32 {
        if h.z >= 0.5 {
            let delta = (h.x * h.x + h.y * h.y) / (1.0 + h.z);
            pow_one_minus(delta, self.exponent)
        } else if h.z > 0.0 {
            libm::powf(h.z, self.exponent)
        } else {
            0.0
        }
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

    /// With the `simd` feature a vector kernel, bit-identical to
    /// [`Brdf::pdf`] (the arithmetic of the sampling kernel's pdf).
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
    /// is at or below the horizon, when `kd = ks = 0`, or when the
    /// reflected direction is at or below the horizon.
    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<S>> {
        let wo_n = unit_or_normalize(wo)?;
        if wo_n.z <= 0.0 {
            return None;
        }
        let (diffuse, u0) = choose_strategy(u[0], self.p_diffuse, self.p_lobe, self.inv_p)?;
        let wi = if diffuse {
            square_to_cosine_hemisphere([u0, u[1]])
        } else {
            let h = sample_cos_power([u0, u[1]], self.inv_n1);
            let wo_h = wo_n.dot(h);
            if wo_h.is_nan() || wo_h <= 0.0 {
                return None;
            }
            unit_or_normalize(2.0 * wo_h * h - wo_n)?
        };
        // `eval(wi, wo)` and `pdf(wi, wo)` with one `upper_pair`, one half
        // vector and one lobe evaluation: the same arithmetic on the same
        // values, so the returned pdf is bit-identical to `pdf(wi, wo)` and
        // the weight to `eval(wi, wo)/pdf · cos θi`.
        let (wi_n, wo_n) = Self::upper_pair(wi, wo)?;
        let h = half_vector(wi_n, wo_n);
        let lobe = h.map_or(0.0, |h| self.lobe(h));
        let lobe_pdf = if h.is_some() && self.p_lobe > 0.0 {
            self.lobe_pdf(wi_n, wo_n, lobe)
        } else {
            0.0
        };
        let pdf = self.p_diffuse * wi_n.z * FRAC_1_PI + lobe_pdf;
        finish_with(wi, pdf, self.kd * FRAC_1_PI + self.ks * (self.norm * lobe))
    }

    /// `pd cos θi/π + ps (n+1)/(2π) cos^n θh/(4 ωo·h)` [sr⁻¹]; zero unless
    /// both directions are above the horizon, and zero when `kd = ks = 0`.
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        let Some((wi, wo)) = Self::upper_pair(wi, wo) else {
            return 0.0;
        };
        let diffuse = self.p_diffuse * wi.z * FRAC_1_PI;
        let lobe = match half_vector(wi, wo) {
            Some(h) if self.p_lobe > 0.0 => self.lobe_pdf(wi, wo, self.lobe(h)),
            _ => 0.0,
        };
        diffuse + lobe
    }
}

impl<S: Spectrum> IsotropicBrdf for BlinnPhong<S> {}

/// The vector kernels (feature `simd`). `eval`: `f = kd/π + ks N(n) cos^n θh`
/// with the scalar code's input handling (the hot path of `upper_pair`:
/// both directions unit to within `4ε` and used as given, the other lanes
/// recomputed by the scalar method; `half_vector`:
/// `h = (ωi + ωo)/√|ωi + ωo|²`, undefined for `|ωi + ωo|² ≤ 10⁻¹⁴`) and
/// its two forms of the lobe:
/// `(1 − δ)^n = exp(n log1p(−δ))`, `δ = (h_x² + h_y²)/(1 + h_z)`, for
/// `h_z ≥ 1/2`, and `powf(h_z, n)` below. `sample`: the mixture sampler,
/// with the reflection `ωi = 2(ωo·h)h − ωo` of the sampled half vector
/// and the same lobe evaluation for the pdf and the weight.
///
/// `pdf`: the sampling kernel's pdf of the given pair.
///
/// Bit-identical to `eval` / `pdf` / `sample`: the same operations in the same
/// order, and the bit-exact ports [`crate::simd::expf`],
/// [`crate::simd::log1pf`], [`crate::simd::powf`] (and for sampling `logf`,
/// `expm1f`) of `libm`'s functions and `sincos_turn` of the scalar one.
#[cfg(feature = "simd")]
mod batch {
    use super::BlinnPhong;
    use crate::phong::batch::{choose_strategy, finish, warp};
    use crate::simd::Vf;
    use crate::simd::{Dirs, Kernel, LANES, SampleKernel, cold_lanes, pow_one_minus, powf, store};
    use core::f32::consts::FRAC_1_PI;
    use radiometry::glam::Vec3;
    use radiometry::{Brdf, BrdfSample, Spectrum};

    /// `(up, cold, defined, |ωi + ωo|², cos^n θh)`: the hot path of
    /// `upper_pair` (`up`: both strictly above the horizon; `cold`: the
    /// lanes where a direction is not unit to within `4ε`, recomputed by the
    /// driver with the scalar method), `half_vector` (`defined`; its flip
    /// to the upper hemisphere never applies to a pair above the horizon,
    /// whose `h_z > 0`) and `lobe(h)` (`0` where `h` is undefined), as the
    /// scalar code.
    #[inline(always)]
    fn upper_half_lobe<S: Spectrum>(b: &BlinnPhong<S>, wi: Dirs, wo: Dirs) -> (Vf, u32, Vf, Vf, Vf) {
        let (zero, one) = (Vf::ZERO, Vf::ONE);
        let cold = cold_lanes(wi, wo);
        let up = wi.z.simd_gt(zero) & wo.z.simd_gt(zero);
        let (h, sum2) = wi.half_vector_sum(wo);
        let len2 = h.length_squared();
        let tiny = Vf::splat(1e-14);
        let defined = sum2.simd_gt(tiny) & len2.simd_gt(tiny) & len2.is_finite();
        let h = h.div(len2.sqrt());
        // `lobe(h)`: `(1 − δ)^n` near the pole, `powf(h_z, n)` below
        // `h_z = 1/2` (computed only when some lane is there).
        let pole = h.z.simd_ge(Vf::splat(0.5));
        let delta = h.xy_length_squared() / (one + h.z);
        let near = pow_one_minus(delta, b.exponent);
        let below = !pole & h.z.simd_gt(zero);
        let far = if below.any() { powf(h.z, b.exponent) } else { zero };
        let lobe = pole.select(near, below.select(far, zero));
        (up, cold, defined, sum2, defined.select(lobe, zero))
    }

    /// `pd cos θi/π + lobe_pdf`, `lobe_pdf = ps (n+1)/(2π) cos^n θh/(4 ωo·h)`
    /// with `ωo·h = |ωi + ωo|/2` where `h` is defined (else 0): the pdf of
    /// the scalar `pdf` and `sample` from the values of [`upper_half_lobe`].
    #[inline(always)]
    fn pdf_of<S: Spectrum>(b: &BlinnPhong<S>, wi_z: Vf, defined: Vf, sum2: Vf, lobe: Vf) -> Vf {
        let zero = Vf::ZERO;
        let lobe_pdf = if b.p_lobe > 0.0 {
            let wo_h = Vf::splat(0.5) * sum2.sqrt();
            let k = Vf::splat(b.p_lobe * ((b.exponent + 1.0) * (0.5 * FRAC_1_PI)));
            let p = k * lobe / (Vf::splat(4.0) * wo_h);
            (defined & wo_h.simd_gt(zero)).select(p, zero)
        } else {
            zero
        };
        Vf::splat(b.p_diffuse) * wi_z * Vf::splat(FRAC_1_PI) + lobe_pdf
    }

    pub(super) struct Eval<'a, S: Spectrum>(pub(super) &'a BlinnPhong<S>);

    impl<S: Spectrum> Kernel for Eval<'_, S> {
        type Out = S;

        #[inline(always)]
        fn lanes(&self, wi: Dirs, wo: Dirs, out: &mut [S; LANES]) -> u32 {
            let b = self.0;
            let (up, cold, _, _, lobe) = upper_half_lobe(b, wi, wo);
            let lobe = Vf::splat(b.norm) * lobe;
            let diffuse = b.kd * FRAC_1_PI;
            store(out, |ch| {
                let f = Vf::splat(diffuse.channel(ch)) + Vf::splat(b.ks.channel(ch)) * lobe;
                up.select(f, Vf::ZERO)
            });
            cold
        }

        #[inline(always)]
        fn one(&self, wi: Vec3, wo: Vec3) -> S {
            self.0.eval(wi, wo)
        }
    }

    /// `pdf`: [`pdf_of`] where both directions are above the horizon, else 0.
    pub(super) struct Pdf<'a, S: Spectrum>(pub(super) &'a BlinnPhong<S>);

    impl<S: Spectrum> Kernel for Pdf<'_, S> {
        type Out = f32;

        #[inline(always)]
        fn lanes(&self, wi: Dirs, wo: Dirs, out: &mut [f32; LANES]) -> u32 {
            let (up, cold, defined, sum2, lobe) = upper_half_lobe(self.0, wi, wo);
            *out = up
                .select(pdf_of(self.0, wi.z, defined, sum2, lobe), Vf::ZERO)
                .to_array();
            cold
        }

        #[inline(always)]
        fn one(&self, wi: Vec3, wo: Vec3) -> f32 {
            self.0.pdf(wi, wo)
        }
    }

    /// `sample` of [`BlinnPhong`] lane for lane: the strategy choice, the
    /// cosine-weighted warp or a half vector `h` with `cos θh = ξ^{1/(n+1)}`
    /// reflected to `ωi = 2(ωo·h)h − ωo` (`None` where `ωo·h` is NaN or
    /// `≤ 0`), then `pdf = pd cos θi/π + ps (n+1)/(2π) cos^n θh/(4 ωo·h)`
    /// with `ωo·h = |ωi + ωo|/2`, and `weight = f cos θi/pdf`, as the scalar
    /// `sample`.
    ///
    /// Lanes handed back to the scalar method: `ωo` not unit to within `4ε`,
    /// and a sampled `ωi` not unit to within `4ε` (the scalar's
    /// `unit_or_normalize`, or `upper_pair`'s cold path for a diffuse
    /// sample).
    pub(super) struct Sample<'a, S: Spectrum>(pub(super) &'a BlinnPhong<S>);

    impl<S: Spectrum> SampleKernel for Sample<'_, S> {
        type Out = Option<BrdfSample<S>>;

        #[inline(always)]
        fn lanes(&self, wo: Dirs, u0: Vf, u1: Vf, out: &mut [Self::Out; LANES]) -> u32 {
            let b = self.0;
            let zero = Vf::ZERO;
            let Some((diffuse, v)) = choose_strategy(u0, b.p_diffuse, b.p_lobe, b.inv_p) else {
                out.fill(None);
                return 0;
            };
            let local = warp(diffuse, v, u1, b.inv_n1);
            // Lobe lanes: `ωi = 2(ωo·h)h − ωo`, rejected where `ωo·h` is NaN
            // or not positive.
            let (wi, rejected) = if diffuse.all() {
                (local, !diffuse)
            } else {
                let h = local;
                let wo_h = wo.dot(h);
                let two = Vf::splat(2.0) * wo_h;
                let wi = Dirs {
                    x: diffuse.select(h.x, two * h.x - wo.x),
                    y: diffuse.select(h.y, two * h.y - wo.y),
                    z: diffuse.select(h.z, two * h.z - wo.z),
                };
                (wi, !diffuse & !wo_h.simd_gt(zero))
            };
            let (up, cold, defined, sum2, lobe) = upper_half_lobe(b, wi, wo);
            let pdf = pdf_of(b, wi.z, defined, sum2, lobe);
            let ls = Vf::splat(b.norm) * lobe;
            finish(b.kd, b.ks, ls, wi, pdf, up & !rejected, out);
            cold
        }

        #[inline(always)]
        fn one(&self, wo: Vec3, u: [f32; 2]) -> Self::Out {
            self.0.sample(wo, u)
        }
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::phong::test_support::*;
    use core::f64::consts::{FRAC_PI_2, PI as PI64, TAU};
    use std::string::ToString;

    fn bp(kd: f32, ks: f32, n: f32) -> BlinnPhong {
        BlinnPhong::new(kd, ks, n).unwrap()
    }

    /// Reference normalisation, typed in f64 from the closed form
    /// `(n+2)(n+4)/(8π(n + 2^{−n/2}))`.
    fn norm_ref(n: f64) -> f64 {
        (n + 2.0) * (n + 4.0) / (8.0 * PI64 * (n + libm::pow(2.0, -n / 2.0)))
    }

    /// Grazing near-mirror pairs: the half vector is corrected for the
    /// lengths of the `f32` inputs (`frame::half_vector_sum`), so the lobe
    /// matches `N cos^n θh` in `f64` at the normalised inputs (without the
    /// correction: 2.6·10⁻³ here).
    #[test]
    fn grazing_mirror_pairs_are_exact_to_f32() {
        let mut worst = 0.0f64;
        for &n in &[1e3f32, 1e5] {
            let b = bp(0.0, 1.0, n);
            let norm = norm_ref(n as f64);
            let width = 1.0 / (n as f64).sqrt();
            for &theta_deg in &[89.0f64, 89.9, 89.99] {
                let theta = theta_deg.to_radians();
                for k in 0..400 {
                    let Some((wi, wo)) = grazing_mirror_pair(theta, 2.0 * width, 4.0, k) else {
                        continue;
                    };
                    let (i, o) = (unit64(wi), unit64(wo));
                    let h = [i[0] + o[0], i[1] + o[1], i[2] + o[2]];
                    // 1 − cos θh = |h_xy|² / (|h| (|h| + h_z)), no cancellation.
                    let l = (h[0] * h[0] + h[1] * h[1] + h[2] * h[2]).sqrt();
                    let one_minus = (h[0] * h[0] + h[1] * h[1]) / (l * (l + h[2]));
                    let reference = norm * (n as f64 * libm::log1p(-one_minus)).exp();
                    if reference < 1e-20 * norm {
                        continue;
                    }
                    let got = b.eval(wi, wo) as f64;
                    let err = (got - reference).abs() / reference;
                    worst = worst.max(err);
                    assert!(
                        err < 1e-5,
                        "n={n} θ={theta_deg}° {wi:?} {wo:?}: {got:e} vs {reference:e}"
                    );
                }
            }
        }
        std::println!("Blinn-Phong grazing mirror pairs: worst relative error {worst:.2e}");
    }

    #[test]
    fn normalization_closed_form_and_limits() {
        assert!((BlinnPhong::<f32>::normalization(0.0) as f64 - 1.0 / PI64).abs() < 1e-7);
        for &n in &[0.5f32, 1.0, 11.0, 1e3, 1e6, MAX_EXPONENT] {
            let (got, e) = (BlinnPhong::<f32>::normalization(n) as f64, norm_ref(n as f64));
            assert!((got - e).abs() <= 1e-6 * e, "{n}: {got} vs {e}");
        }
        // Large-n asymptote (n + 6)/(8π) and finiteness at the maximum.
        let n = 1e6f64;
        assert!((norm_ref(n) - (n + 6.0) / (8.0 * PI64)).abs() < 1e-5);
        assert!(BlinnPhong::<f32>::normalization(f32::NAN).is_finite());
    }

    /// f = kd/π + ks N(n) cos^n θh with θh known in closed form for
    /// in-plane directions: wo at +a, wi at −b (polar angles) → θh = |a − b|/2.
    #[test]
    fn formula_spot_checks() {
        for &n in &[0.0f32, 1.0, 50.0, 1e6, MAX_EXPONENT] {
            let b = bp(0.1, 0.9, n);
            let expect = 0.1 / PI64 + 0.9 * norm_ref(n as f64);
            for &(wi, wo) in &[(Vec3::Z, Vec3::Z), (dir_xz(-0.8), dir_xz(0.8))] {
                let f = b.eval(wi, wo) as f64;
                assert!((f - expect).abs() <= 1e-5 * expect, "{n}: {f} vs {expect}");
            }
        }
        for &(a, bb, n) in &[
            (0.8f64, 0.5f64, 10.0f32),
            (0.3, 0.0, 2.5),
            (1.2, 1.0, 300.0),
            (0.4, -0.4, 1.0),
        ] {
            let b = bp(0.2, 0.8, n);
            let th = 0.5 * (a - bb).abs();
            let expect = 0.2 / PI64 + 0.8 * norm_ref(n as f64) * libm::pow(libm::cos(th), n as f64);
            let f = b.eval(dir_xz(-bb), dir_xz(a)) as f64;
            assert!(
                (f - expect).abs() <= 1e-4 * expect,
                "{a} {bb} {n}: {f} vs {expect}"
            );
        }
        // n = 0: a constant (kd + ks)/π in the upper hemisphere.
        let f = bp(0.25, 0.5, 0.0).eval(dir_xz(1.3), dir_xz(1.4)) as f64;
        assert!((f - 0.75 / PI64).abs() < 1e-7);
    }

    #[test]
    fn constructor_validation_and_messages() {
        let e = BlinnPhong::new(0.1f32, f32::NAN, 1.0).unwrap_err();
        assert_eq!(e.to_string(), "parameter `ks` must be finite");
        let e = BlinnPhong::new(-0.5f32, 0.1, 1.0).unwrap_err();
        assert_eq!(e.to_string(), "parameter `kd` = -0.5 is outside [0, 1]");
        let e = BlinnPhong::new(0.7f32, 0.7, 1.0).unwrap_err();
        assert_eq!(
            e.to_string(),
            "invalid parameters: kd + ks must not exceed 1 in any channel (energy conservation)"
        );
        let e = BlinnPhong::new(0.1f32, 0.1, 1.5e7).unwrap_err();
        assert_eq!(
            e.to_string(),
            "parameter `exponent` = 15000000 is outside [0, 10000000]"
        );
        assert!(BlinnPhong::new(0.1f32, 0.1, f32::NAN).is_err());
        assert!(BlinnPhong::new(Vec3::new(0.1, 0.6, 0.1), Vec3::new(0.1, 0.6, 0.1), 1.0).is_err());
        assert!(BlinnPhong::new(0.3f32, 0.7, 0.0).is_ok());
        assert!(BlinnPhong::new(0.0f32, 1.0, MAX_EXPONENT).is_ok());
    }

    /// The lobe albedo at normal incidence is 1 for ks = 1 (independent
    /// f64 quadrature over ωi), which is what N(n) is derived for.
    #[test]
    fn lobe_albedo_is_one_at_normal_incidence() {
        for &n in &[0.0f32, 0.5, 1.0, 11.0, 100.0, 1000.0] {
            let a = albedo(&bp(0.0, 1.0, n), Vec3::Z, 0, 4000, 16);
            std::eprintln!("blinn lobe albedo n={n}: {a:.9} (err {:.2e})", a - 1.0);
            assert!((a - 1.0).abs() < 1e-4, "n={n}: {a}");
        }
    }

    /// Energy conservation: albedo ≤ 1 at every θo (it peaks at normal
    /// incidence), for ks = 1 and for kd + ks = 1.
    #[test]
    fn energy_at_most_one() {
        for &n in &[0.3f32, 1.0, 4.0, 11.0, 30.0, 100.0] {
            let mut prev = 1.0 + 1e-4;
            for &t in &[0.0f64, 0.1, 0.3, 0.6, 1.0, 1.4, 1.55] {
                let a = albedo(&bp(0.0, 1.0, n), dir_xz(t), 0, 1500, 512);
                std::eprintln!("blinn albedo n={n} θo={t}: {a:.6}");
                assert!(a <= 1.0 + 1e-4 && a > 0.0, "n={n} θo={t}: {a}");
                assert!(
                    a <= prev + 1e-4,
                    "not decreasing in θo: n={n} θo={t}: {a} > {prev}"
                );
                prev = a;
            }
            let a = albedo(&bp(0.4, 0.6, n), dir_xz(0.2), 0, 1500, 512);
            assert!(a <= 1.0 + 1e-4, "{a}");
        }
        let a = albedo(&bp(0.0, 1.0, 1000.0), dir_xz(0.5), 0, 3000, 4096);
        assert!(a <= 1.0 + 1e-4 && a > 0.7, "{a}");
    }

    #[test]
    fn sampling_matches_pdf_and_weight_on_grid() {
        let params = [
            (0.5f32, 0.5f32, 10.0f32),
            (0.0, 1.0, 0.0),
            (1.0, 0.0, 5.0),
            (0.2, 0.8, 1e6),
            (0.0, 1.0, MAX_EXPONENT),
        ];
        for &(kd, ks, n) in &params {
            let b = bp(kd, ks, n);
            for &t in &[0.0f64, 0.5, 1.2, 1.5706, FRAC_PI_2 - 1e-7] {
                let (some, ep, ew) = check_sampling(&b, dir_xz(t));
                std::eprintln!(
                    "blinn sampling {kd} {ks} n={n} θo={t}: {some}/121 some, pdf err {ep:.1e}, weight err {ew:.1e}"
                );
                assert!(some > 0, "no sample for {kd} {ks} {n} {t}");
                assert!(check_sample_bits(&b, dir_xz(t)) > 0);
            }
        }
        let b = bp(0.0, 0.0, 3.0);
        assert!(b.sample(Vec3::Z, [0.5, 0.5]).is_none());
        assert_eq!(b.pdf(Vec3::Z, Vec3::Z), 0.0);
    }

    /// Mass of half vectors h (density (n+1)/(2π) cos^n θh) whose
    /// reflection of ωo = (sin θo, 0, cos θo) is at or below the horizon;
    /// f64 midpoint quadrature over h written here (in h-space, so it also
    /// checks the 1/(4 ωo·h) Jacobian of the code under test).
    fn rejected_lobe_mass(n: f64, theta_o: f64) -> f64 {
        let (n_t, n_p) = (3000, 2048);
        let wo = [libm::sin(theta_o), 0.0, libm::cos(theta_o)];
        let cos_phi: std::vec::Vec<f64> = (0..n_p)
            .map(|j| libm::cos((j as f64 + 0.5) / n_p as f64 * TAU))
            .collect();
        let mut sum = 0.0;
        for i in 0..n_t {
            let th = (i as f64 + 0.5) / n_t as f64 * FRAC_PI_2;
            let (st, ct) = (libm::sin(th), libm::cos(th));
            let mut ring = 0.0;
            for &cp in &cos_phi {
                // h = (st cos φ, st sin φ, ct); wo has no y component.
                let h = [st * cp, 0.0, ct];
                let d = wo[0] * h[0] + wo[1] * h[1] + wo[2] * h[2];
                let wi_z = 2.0 * d * h[2] - wo[2];
                if d <= 0.0 || wi_z <= 0.0 {
                    ring += 1.0;
                }
            }
            sum +=
                ring / n_p as f64 * TAU * (n + 1.0) / TAU * libm::pow(ct, n) * st * (FRAC_PI_2 / n_t as f64);
        }
        sum
    }

    /// ∫_H pdf = pd + ps (1 − rejected lobe mass); at normal incidence the
    /// rejected mass is 2^{−(n+1)/2} in closed form.
    #[test]
    fn pdf_integrates_to_expected_mass() {
        for &n in &[0.0f32, 1.0, 10.0, 1000.0] {
            for &(kd, ks) in &[(0.0f32, 1.0f32), (0.5, 0.5)] {
                let pd = kd as f64 / (kd + ks) as f64;
                let expect = pd + (1.0 - pd) * (1.0 - libm::pow(2.0, -(n as f64 + 1.0) / 2.0));
                let m = pdf_mass(&bp(kd, ks, n), Vec3::Z, 4000, 16);
                std::eprintln!("blinn pdf mass n={n} kd={kd} normal: {m:.7} expect {expect:.7}");
                assert!((m - expect).abs() < 1e-4, "n={n} kd={kd}: {m} vs {expect}");
            }
        }
        for &n in &[1.0f32, 10.0, 100.0] {
            for &t in &[0.5f64, 1.0, 1.4] {
                let (kd, ks) = (0.3f32, 0.6f32);
                let pd = kd as f64 / (kd + ks) as f64;
                let expect = pd + (1.0 - pd) * (1.0 - rejected_lobe_mass(n as f64, t));
                let m = pdf_mass(&bp(kd, ks, n), dir_xz(t), 1500, 512);
                std::eprintln!(
                    "blinn pdf mass n={n} θo={t}: {m:.6} expect {expect:.6} err {:.2e}",
                    m - expect
                );
                assert!((m - expect).abs() < 5e-4, "n={n} θo={t}: {m} vs {expect}");
            }
        }
    }

    /// The half vectors of lobe samples follow cos^n θh even for huge n:
    /// KS distance of `δ = 1 − cos θh` (recomputed in f64 from the returned
    /// ωi and ωo) to the closed-form CDF `1 − (1 − δ)^{n+1}`.
    #[test]
    fn half_vectors_follow_closed_form_cdf() {
        let m = 4000;
        for &n in &[1.0f32, 100.0, 1e4, 1e6, MAX_EXPONENT] {
            let b = bp(0.0, 1.0, n);
            let wo = dir_xz(0.3);
            let mut deltas = std::vec::Vec::with_capacity(m);
            let mut rejected = 0;
            for i in 0..m {
                let u = [(i as f32 + 0.5) / m as f32, 0.37];
                let Some(s) = b.sample(wo, u) else {
                    rejected += 1;
                    continue;
                };
                let h = [
                    (s.wi.x + wo.x) as f64,
                    (s.wi.y + wo.y) as f64,
                    (s.wi.z + wo.z) as f64,
                ];
                let l = libm::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
                let (hx, hy, hz) = (h[0] / l, h[1] / l, h[2] / l);
                deltas.push((hx * hx + hy * hy) / (1.0 + hz));
            }
            // Only the broad n = 1 lobe can reflect below the horizon at θo = 0.3.
            assert!(n <= 1.0 || rejected == 0, "{n}: {rejected}");
            if rejected == 0 {
                let d = ks_distance_cos_power(&mut deltas, n as f64);
                std::eprintln!("blinn half-vector KS n={n}: D = {d:.2e}");
                assert!(d < 5e-4, "n={n}: D = {d}");
            }
        }
    }

    /// E[weight] over stratified samples equals the quadrature albedo.
    #[test]
    fn sampling_is_unbiased() {
        for &(kd, ks, n, t) in &[
            (0.3f32, 0.6f32, 10.0f32, 0.8f64),
            (0.0, 1.0, 100.0, 1.2),
            (0.5, 0.5, 1.0, 0.0),
        ] {
            let b = bp(kd, ks, n);
            let wo = dir_xz(t);
            let reference = albedo(&b, wo, 0, 1500, 512);
            let mc = sampled_albedo(&b, wo, 1024);
            std::eprintln!(
                "blinn MC albedo {kd} {ks} n={n} θo={t}: {mc:.6} vs {reference:.6} rel {:.2e}",
                mc / reference - 1.0
            );
            assert!(
                (mc - reference).abs() < 5e-3 * reference,
                "{kd} {ks} {n} {t}: {mc} vs {reference}"
            );
        }
    }

    #[test]
    fn stability_hard_cases() {
        let cases = [
            (Vec3::Z, -Vec3::Z),
            (Vec3::new(1.0, 0.0, 1e-7), Vec3::new(-1.0, 0.0, 1e-7)),
            (Vec3::new(1.0, 0.0, 1e-7), Vec3::new(1.0, 0.0, 1e-7)),
            (Vec3::new(1.0, 0.0, 0.0), Vec3::new(-1.0, 0.0, 0.0)),
            (Vec3::new(1.0, 0.0, 1e-20), Vec3::new(-1.0, 0.0, 1e-20)),
            (Vec3::ZERO, Vec3::Z),
            (Vec3::new(3.0, 1.0, 2.0), Vec3::new(-0.001, 0.0, 0.002)),
        ];
        for bb in [bp(0.2, 0.8, MAX_EXPONENT), bp(0.0, 1.0, 0.0), bp(0.5, 0.5, 1e6)] {
            for &(wi, wo) in &cases {
                for (x, y) in [(wi, wo), (wo, wi)] {
                    let (f, p) = (bb.eval(x, y), bb.pdf(x, y));
                    assert!(
                        f.is_finite() && f >= 0.0 && p.is_finite() && p >= 0.0,
                        "{x:?} {y:?} {f} {p}"
                    );
                    assert_eq!(bb.eval(x, y), bb.eval(y, x));
                }
            }
            for &u in &[[0.0, 0.0], [ONE, ONE], [0.0, ONE], [ONE, 0.0]] {
                for wo in [
                    Vec3::Z,
                    Vec3::new(1.0, 0.0, 1e-7),
                    Vec3::new(0.3, 0.1, 0.0),
                    Vec3::new(0.0, 0.0, -1.0),
                ] {
                    if let Some(s) = bb.sample(wo, u) {
                        assert!(s.pdf.is_finite() && s.pdf > 0.0 && s.weight.is_finite() && s.wi.z > 0.0);
                    }
                }
            }
        }
        let (wi, wo) = (dir_xz(-0.45), dir_xz(0.5));
        let b = bp(0.2, 0.8, 50.0);
        let (f1, f2) = (b.eval(wi, wo), b.eval(wi * 7.0, wo * 0.01));
        assert!((f1 - f2).abs() <= 1e-4 * f1, "{f1} {f2}");
    }

    const ONE: f32 = radiometry::math::ONE_MINUS_EPSILON;
}
