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
use crate::microfacet::is_unit;
use core::f32::consts::FRAC_1_PI;
#[cfg(feature = "simd")]
use radiometry::batch::Vec3Soa;
use radiometry::frame::{Frame, reflect_z, try_normalize};
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

/// The vector `eval` kernel (feature `simd`):
/// `f = kd/π + ks (n+2)/(2π) cos^n α`, zero unless both directions are
/// strictly above the horizon, on the hot path of `upper_pair` (both unit
/// to within `4ε`; the other lanes are recomputed by the scalar method), with
/// `cos^n α = exp(n log1p(−δ))`, `δ = |ωi − reflect_z(ωo)|²/2`.
///
/// Bit-identical to `eval`: the same operations in the same order, and
/// `exp`/`log1p` are the bit-exact ports [`crate::simd::expf`] /
/// [`crate::simd::log1pf`] of `libm`'s.
///
/// The `sample` kernel ([`batch::Sample`]) and the vector forms of the
/// sampler's steps shared with [`BlinnPhong`](crate::BlinnPhong)
/// (`choose_strategy`, the two warps, the finishing) live here too.
#[cfg(feature = "simd")]
pub(crate) mod batch {
    use super::ModifiedPhong;
    use crate::simd::Vf;
    use crate::simd::{
        Dirs, Kernel, LANES, SampleKernel, cold_lanes, expm1f, logf, pow_one_minus, sincos_turn, store,
    };
    use core::f32::consts::FRAC_1_PI;
    use radiometry::glam::Vec3;
    use radiometry::math::ONE_MINUS_EPSILON;
    use radiometry::{Brdf, BrdfSample, Spectrum};

    /// `(up, cold, cos^n α)`: the hot path of `upper_pair` (both directions
    /// used as given, both strictly above the horizon; `cold` marks the
    /// lanes where one is not unit to within `4ε`, which the driver
    /// recomputes with the scalar method) and the lobe `(1 − δ)^n`,
    /// `δ = |ωi − reflect_z(ωo)|²/2 = 1 − cos α`, as the scalar `lobe`.
    #[inline(always)]
    fn upper_lobe<S: Spectrum>(b: &ModifiedPhong<S>, a: Dirs, c: Dirs) -> (Vf, u32, Vf) {
        let zero = Vf::ZERO;
        let cold = cold_lanes(a, c);
        let up = a.z.simd_gt(zero) & c.z.simd_gt(zero);
        let d = Dirs {
            x: a.x - (-c.x),
            y: a.y - (-c.y),
            z: a.z - c.z,
        };
        let delta = Vf::splat(0.5) * d.length_squared();
        (up, cold, pow_one_minus(delta, b.exponent))
    }

    pub(super) struct Eval<'a, S: Spectrum>(pub(super) &'a ModifiedPhong<S>);

    impl<S: Spectrum> Kernel for Eval<'_, S> {
        type Out = S;

        #[inline(always)]
        fn lanes(&self, wi: Dirs, wo: Dirs, out: &mut [S; LANES]) -> u32 {
            let b = self.0;
            let zero = Vf::ZERO;
            let (up, cold, lobe) = upper_lobe(b, wi, wo);
            let norm = (b.exponent + 2.0) * (0.5 * FRAC_1_PI);
            let lobe = Vf::splat(norm) * lobe;
            let diffuse = b.kd * FRAC_1_PI;
            store(out, |ch| {
                let f = Vf::splat(diffuse.channel(ch)) + Vf::splat(b.ks.channel(ch)) * lobe;
                up.select(f, zero)
            });
            cold
        }

        #[inline(always)]
        fn one(&self, wi: Vec3, wo: Vec3) -> S {
            self.0.eval(wi, wo)
        }
    }

    /// `pdf = pd cos θi/π + ps (n+1)/(2π) cos^n α` where both directions are
    /// above the horizon, else 0.
    pub(super) struct Pdf<'a, S: Spectrum>(pub(super) &'a ModifiedPhong<S>);

    impl<S: Spectrum> Kernel for Pdf<'_, S> {
        type Out = f32;

        #[inline(always)]
        fn lanes(&self, wi: Dirs, wo: Dirs, out: &mut [f32; LANES]) -> u32 {
            let b = self.0;
            let (up, cold, lobe) = upper_lobe(b, wi, wo);
            let diffuse = Vf::splat(b.p_diffuse) * wi.z * Vf::splat(FRAC_1_PI);
            let lobe = if b.p_lobe > 0.0 {
                Vf::splat(b.p_lobe * ((b.exponent + 1.0) * (0.5 * FRAC_1_PI))) * lobe
            } else {
                Vf::ZERO
            };
            *out = up.select(diffuse + lobe, Vf::ZERO).to_array();
            cold
        }

        #[inline(always)]
        fn one(&self, wi: Vec3, wo: Vec3) -> f32 {
            self.0.pdf(wi, wo)
        }
    }

    /// `sample` of [`ModifiedPhong`] lane for lane: the strategy choice,
    /// the cosine-weighted warp or `cos θ = ξ^{1/(n+1)}` around
    /// `ωr = reflect_z(ωo)` (rotated by `frame_around_upper(ωr)`), then
    /// `pdf = pd cos θi/π + ps (n+1)/(2π) cos^n α` and
    /// `weight = f cos θi/pdf` with one evaluation of the lobe, as the
    /// scalar `sample`.
    ///
    /// Lanes handed back to the scalar method: `ωo` not unit to within `4ε`
    /// (the scalar normalises it, and `upper_pair` sees the original), and a
    /// sampled `ωi` not unit to within `4ε` (the scalar's `try_normalize`,
    /// or `upper_pair`'s cold path for a diffuse sample).
    pub(super) struct Sample<'a, S: Spectrum>(pub(super) &'a ModifiedPhong<S>);

    impl<S: Spectrum> SampleKernel for Sample<'_, S> {
        type Out = Option<BrdfSample<S>>;

        #[inline(always)]
        fn lanes(&self, wo: Dirs, u0: Vf, u1: Vf, out: &mut [Self::Out; LANES]) -> u32 {
            let b = self.0;
            let Some((diffuse, v)) = choose_strategy(u0, b.p_diffuse, b.p_lobe, b.inv_p) else {
                out.fill(None);
                return 0;
            };
            let local = warp(diffuse, v, u1, b.inv_n1);
            // Lobe lanes: `frame_around_upper(reflect_z(ωo)).to_world(local)`.
            let wi = if diffuse.all() {
                local
            } else {
                let n = Dirs {
                    x: -wo.x,
                    y: -wo.y,
                    z: wo.z,
                };
                let a = Vf::splat(-1.0) / (Vf::ONE + n.z);
                let bb = n.x * n.y * a;
                let s = Dirs {
                    x: Vf::ONE + n.x * n.x * a,
                    y: bb,
                    z: -n.x,
                };
                let t = Dirs {
                    x: bb,
                    y: Vf::ONE + n.y * n.y * a,
                    z: -n.y,
                };
                let l = local;
                let world = Dirs {
                    x: l.x * s.x + l.y * t.x + l.z * n.x,
                    y: l.x * s.y + l.y * t.y + l.z * n.y,
                    z: l.x * s.z + l.y * t.z + l.z * n.z,
                };
                Dirs {
                    x: diffuse.select(l.x, world.x),
                    y: diffuse.select(l.y, world.y),
                    z: diffuse.select(l.z, world.z),
                }
            };
            // `unit_or_normalize(ωi)` and `upper_pair(ωi, ωo)`: hot where
            // both are unit to within 4ε, else handed back.
            let (up, cold, lobe) = upper_lobe(b, wi, wo);
            let diffuse_pdf = Vf::splat(b.p_diffuse) * wi.z * Vf::splat(FRAC_1_PI);
            let lobe_pdf = if b.p_lobe > 0.0 {
                Vf::splat(b.p_lobe * ((b.exponent + 1.0) * (0.5 * FRAC_1_PI))) * lobe
            } else {
                Vf::ZERO
            };
            let norm = (b.exponent + 2.0) * (0.5 * FRAC_1_PI);
            finish(
                b.kd,
                b.ks,
                Vf::splat(norm) * lobe,
                wi,
                diffuse_pdf + lobe_pdf,
                up,
                out,
            );
            cold
        }

        #[inline(always)]
        fn one(&self, wo: Vec3, u: [f32; 2]) -> Self::Out {
            self.0.sample(wo, u)
        }
    }

    /// `clamp_unit`: `x > 0 ? min(x, 1 − 2⁻²⁴) : 0` (NaN → 0).
    #[inline(always)]
    fn clamp_unit(x: Vf) -> Vf {
        x.simd_gt(Vf::ZERO)
            .select(x.min(Vf::splat(ONE_MINUS_EPSILON)), Vf::ZERO)
    }

    /// `radiometry::math::clamp01`: `x > 0 ? min(x, 1) : 0` (NaN → 0).
    #[inline(always)]
    fn clamp01(x: Vf) -> Vf {
        x.simd_gt(Vf::ZERO).select(x.min(Vf::ONE), Vf::ZERO)
    }

    /// `f32::clamp(x, lo, hi)` by its comparisons (`x < lo → lo`,
    /// `x > hi → hi`; NaN and `−0` pass through).
    #[inline(always)]
    fn clamp(x: Vf, lo: f32, hi: f32) -> Vf {
        let x = x.simd_lt(Vf::splat(lo)).select(Vf::splat(lo), x);
        x.simd_gt(Vf::splat(hi)).select(Vf::splat(hi), x)
    }

    /// `radiometry::math::safe_sqrt` (`√max(x, 0)`) lane-wise. The sign of
    /// `max(±0, 0)` is not fixed by IEEE 754 (`maxNum` may return either
    /// zero), so lanes with `x = ±0` take the scalar function itself: its
    /// `√(−0) = −0` or `+0`, whichever the scalar code gives.
    #[inline(always)]
    pub(crate) fn safe_sqrt(x: Vf) -> Vf {
        let r = x.max(Vf::ZERO).sqrt();
        if !x.simd_eq(Vf::ZERO).any() {
            return r;
        }
        let (xs, rs) = (x.to_array(), r.to_array());
        Vf::new(core::array::from_fn(|k| {
            if xs[k] == 0.0 {
                radiometry::math::safe_sqrt(xs[k])
            } else {
                rs[k]
            }
        }))
    }

    /// `choose_strategy(u₀, pd, ps, inv)` lane-wise: `None` (for every
    /// lane) when `pd + ps ≤ 0` or either is NaN, else the mask of the
    /// diffuse lanes (`u₀ < pd`, or every lane when `ps ≤ 0`, none when
    /// `pd ≤ 0`) and the rescaled `clamp_unit(u₀/pd)` or
    /// `clamp_unit((u₀ − pd)/ps)` (as products with `inv`).
    #[inline(always)]
    pub(crate) fn choose_strategy(u0: Vf, pd: f32, ps: f32, inv: [f32; 2]) -> Option<(Vf, Vf)> {
        if pd.is_nan() || ps.is_nan() || pd + ps <= 0.0 {
            return None;
        }
        let u = clamp_unit(u0);
        let all = Vf::ZERO.simd_eq(Vf::ZERO);
        let (diffuse, v) = if ps <= 0.0 {
            (all, u)
        } else if pd <= 0.0 {
            (!all, u)
        } else {
            let d = u.simd_lt(Vf::splat(pd));
            let pd = Vf::splat(pd);
            (d, d.select(u * Vf::splat(inv[0]), (u - pd) * Vf::splat(inv[1])))
        };
        Some((diffuse, clamp_unit(v)))
    }

    /// The sampler's two warps, one per lane (one `sincos_turn` for both):
    /// `square_to_cosine_hemisphere([v, u₁])` on the `diffuse` lanes
    /// (Shirley & Chiu's concentric map, `r = ±o`, `θ/2π = o_y/o_x / 8` or
    /// `1/4 − o_x/o_y / 8`, lifted by `z = √(1 − |d|²)`), and
    /// `sample_cos_power([v, u₁], 1/(n+1))` on the others
    /// (`1 − cos θ = −expm1(ln ξ/(n+1))`, `ξ = 1 − v`, `φ = 2π u₁`, with
    /// the bit-exact ports [`logf`], [`expm1f`] and [`sincos_turn`]); the
    /// operations and clamps of the scalar functions, in their order.
    #[inline(always)]
    pub(crate) fn warp(diffuse: Vf, v: Vf, u1: Vf, inv_n1: f32) -> Dirs {
        let (zero, one) = (Vf::ZERO, Vf::ONE);
        let any_lobe = !diffuse.all();
        let any_diffuse = diffuse.any();
        // Concentric map: (ox, oy) ∈ [−1, 1]², radius r and angle θ.
        let ox = Vf::splat(2.0) * clamp01(v) - one;
        let oy = Vf::splat(2.0) * clamp01(u1) - one;
        let center = ox.simd_eq(zero) & oy.simd_eq(zero);
        let horiz = ox.abs().simd_gt(oy.abs());
        let (r, angle) = if any_diffuse {
            // One division: o_y/o_x where |o_x| > |o_y|, else o_x/o_y.
            let ratio = horiz.select(oy, ox) / horiz.select(ox, oy);
            // θ/2π = o_y/o_x / 8 or 1/4 − o_x/o_y / 8 (turns).
            let q = Vf::splat(0.125) * ratio;
            let turns = horiz.select(q, Vf::splat(0.25) - q);
            (horiz.select(ox, oy), center.select(zero, turns))
        } else {
            (zero, zero)
        };
        let (sn, cs) = sincos_turn(diffuse.select(angle, clamp_unit(u1)));
        // Cosine-weighted hemisphere (the centre maps to (0, 0, 1)).
        let dx = center.select(zero, r * cs);
        let dy = center.select(zero, r * sn);
        let dz = safe_sqrt(one - (dx * dx + dy * dy));
        if !any_lobe {
            return Dirs { x: dx, y: dy, z: dz };
        }
        // cos^n lobe around +Z.
        let xi = one - clamp_unit(v);
        let delta = clamp(-expm1f(logf(xi) * Vf::splat(inv_n1)), 0.0, 1.0);
        let sin_t = clamp(safe_sqrt(delta * (Vf::splat(2.0) - delta)), -1.0, 1.0);
        Dirs {
            x: diffuse.select(dx, sin_t * cs),
            y: diffuse.select(dy, sin_t * sn),
            z: diffuse.select(dz, clamp(one - delta, -1.0, 1.0)),
        }
    }

    /// `finish_with(ωi, pdf, f)` lane-wise, with `f = kd/π + ks · ls`
    /// (`ls` the scaled lobe, `N cos^n`): `Some` where `valid` and
    /// `0 < pdf < ∞` and every channel of `weight = (f/pdf) cos θi` is
    /// finite, else `None`.
    #[inline(always)]
    pub(crate) fn finish<S: Spectrum>(
        kd: S,
        ks: S,
        ls: Vf,
        wi: Dirs,
        pdf: Vf,
        valid: Vf,
        out: &mut [Option<BrdfSample<S>>; LANES],
    ) {
        let diffuse = kd * FRAC_1_PI;
        let mut ok = valid & pdf.is_finite() & pdf.simd_gt(Vf::ZERO);
        let mut weight = [S::zero(); LANES];
        store(&mut weight, |ch| {
            let f = Vf::splat(diffuse.channel(ch)) + Vf::splat(ks.channel(ch)) * ls;
            let w = (f / pdf) * wi.z;
            ok &= w.is_finite();
            w
        });
        let (x, y, z, p) = (wi.x.to_array(), wi.y.to_array(), wi.z.to_array(), pdf.to_array());
        let ok = ok.to_bitmask();
        for (k, o) in out.iter_mut().enumerate() {
            *o = (ok & (1 << k) != 0).then(|| BrdfSample {
                wi: Vec3::new(x[k], y[k], z[k]),
                pdf: p[k],
                weight: weight[k],
            });
        }
    }
}

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

/// `[1/pd, 1/ps]` for [`choose_strategy`], at most `f32::MAX` (so that the
/// rescaled `u₀` is never NaN; it is clamped anyway); a component is `0`
/// where its probability is not positive (it is then never used).
pub(crate) fn strategy_reciprocals(pd: f32, ps: f32) -> [f32; 2] {
    let inv = |p: f32| if p > 0.0 { (1.0 / p).min(f32::MAX) } else { 0.0 };
    [inv(pd), inv(ps)]
}

/// Picks a strategy from `u₀` and rescales it to `[0, 1 − 2⁻²⁴]`:
/// `Some((true, u₀/pd))` for the diffuse strategy (`u₀ < pd`),
/// `Some((false, (u₀ − pd)/ps))` for the lobe, `None` when both
/// probabilities are zero. NaN maps to 0. `inv` is
/// [`strategy_reciprocals`]`(pd, ps)`: the rescaling multiplies by it
/// (the result may differ from the quotient by an ulp, which only moves
/// the sample by as much; the clamp keeps it in range).
#[inline]
pub(crate) fn choose_strategy(u0: f32, pd: f32, ps: f32, inv: [f32; 2]) -> Option<(bool, f32)> {
    if pd.is_nan() || ps.is_nan() || pd + ps <= 0.0 {
        return None;
    }
    let u0 = clamp_unit(u0);
    let (diffuse, v) = if ps <= 0.0 {
        (true, u0)
    } else if pd <= 0.0 {
        (false, u0)
    } else if u0 < pd {
        (true, u0 * inv[0])
    } else {
        (false, (u0 - pd) * inv[1])
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
/// `n`. `u` is expected in `[0, 1 − 2⁻²⁴]` (clamped otherwise); `inv_n1`
/// is `1/(n + 1)` (precomputed: a multiplication instead of a division).
#[inline]
pub(crate) fn sample_cos_power(u: [f32; 2], inv_n1: f32) -> Vec3 {
    let xi = 1.0 - clamp_unit(u[0]); // in [2⁻²⁴, 1]
    let delta = (-libm::expm1f(libm::logf(xi) * inv_n1)).clamp(0.0, 1.0);
    let sin_t = safe_sqrt(delta * (2.0 - delta));
    let (sp, cp) = radiometry::math::sincos_turn(clamp_unit(u[1]));
    // The clamps of `spherical_direction_sc`.
    let (s, c) = (sin_t.clamp(-1.0, 1.0), (1.0 - delta).clamp(-1.0, 1.0));
    Vec3::new(s * cp, s * sp, c)
}

/// `(ωi, ωo)` as unit vectors with both strictly above the horizon, or
/// `None` (the input handling of `eval` and `pdf` of the Phong family).
///
/// Hot path: when both are already unit to rounding
/// ([`is_unit`]: `|‖w‖² − 1| ≤ 4ε`, so `|‖w‖ − 1| ≤ 2ε`, the accuracy a
/// normalised vector has anyway) they are used as given — no square root
/// or division. Otherwise (`#[cold]`) both are normalised by
/// [`try_normalize`]; a zero or non-finite vector gives `None`. The
/// vector kernels (feature `simd`) take the hot path lane-wise and hand the
/// other lanes to the scalar method.
#[inline]
pub(crate) fn upper_pair(wi: Vec3, wo: Vec3) -> Option<(Vec3, Vec3)> {
    let (wi, wo) = if is_unit(wi) && is_unit(wo) {
        (wi, wo)
    } else {
        normalize_pair_cold(wi, wo)?
    };
    (wi.z > 0.0 && wo.z > 0.0).then_some((wi, wo))
}

#[cold]
#[inline(never)]
fn normalize_pair_cold(wi: Vec3, wo: Vec3) -> Option<(Vec3, Vec3)> {
    Some((try_normalize(wi)?, try_normalize(wo)?))
}

/// Completes a sample from `wi`, its density `pdf` (computed by the
/// caller with exactly the arithmetic of `Brdf::pdf(wi, wo)`) and
/// `f = Brdf::eval(wi, wo)` (likewise): `weight = (f/pdf)·cos θi`, and
/// `None` for a non-positive or non-finite pdf or a non-finite weight
/// (possible only when the pdf underflows).
#[inline]
pub(crate) fn finish_with<S: Spectrum>(wi: Vec3, pdf: f32, f: S) -> Option<BrdfSample<S>> {
    if !pdf.is_finite() || pdf <= 0.0 {
        return None;
    }
    let weight = (f / pdf) * wi.z;
    weight.is_finite().then_some(BrdfSample { wi, pdf, weight })
}

/// `w` itself when it is already unit to rounding (`||w|² − 1| ≤ 4ε`, so
/// `||w| − 1| ≤ 2ε`: the accuracy a sampler's rotated or reflected unit
/// vector has anyway), else [`try_normalize`] (the `#[cold]` path: zero,
/// non-finite or clearly non-unit input).
#[inline]
pub(crate) fn unit_or_normalize(w: Vec3) -> Option<Vec3> {
    let l2 = w.length_squared();
    if (l2 - 1.0).abs() <= 4.0 * f32::EPSILON {
        Some(w)
    } else {
        normalize_cold(w)
    }
}

#[cold]
#[inline(never)]
fn normalize_cold(w: Vec3) -> Option<Vec3> {
    try_normalize(w)
}

/// The orthonormal basis around the unit `n` with `n.z > 0`: the
/// `sign = +1` branch of [`Frame::from_normal`] (Duff et al. 2017,
/// *Building an Orthonormal Basis, Revisited*, JCGT 6(1)), without its
/// renormalisation of an already-unit `n` and with `1 + n.z ∈ (1, 2]`, so
/// the one division is always well-conditioned.
#[inline]
fn frame_around_upper(n: Vec3) -> Frame {
    let a = -1.0 / (1.0 + n.z);
    let b = n.x * n.y * a;
    Frame {
        s: Vec3::new(1.0 + n.x * n.x * a, b, -n.x),
        t: Vec3::new(b, 1.0 + n.y * n.y * a, -n.y),
        n,
    }
}

/// Test support shared by the Lambertian / Phong-family unit tests:
/// reference quadratures written independently of the code under test
/// (f64, own spherical parameterisation) and a sampling checker.
#[cfg(test)]
pub(crate) mod test_support {
    extern crate std;
    use core::f64::consts::{FRAC_PI_2, TAU};
    use radiometry::glam::Vec3;
    use radiometry::math::ONE_MINUS_EPSILON;
    use radiometry::{Brdf, Spectrum};

    /// `f32` direction pairs near the mirror configuration with `ωo` at
    /// `theta` from the normal (`k`-th of a sequence over `φo`): `ωi` at the
    /// mirror direction offset by up to `±spread · width · cos θ` in azimuth
    /// and `±spread · width` (scaled by `1/cos θ`) in elevation, where
    /// `width` is the lobe's angular width. `None` where `ωi` would fall
    /// below the horizon. For the grazing-precision tests.
    pub fn grazing_mirror_pair(theta: f64, width: f64, spread: f64, k: usize) -> Option<(Vec3, Vec3)> {
        let phi_o = 0.37 + 0.011 * k as f64;
        let s = (k as f64 * 0.618_033_988_749_895).fract() - 0.5;
        let t = (k as f64 * 0.754_877_666_246_693).fract() - 0.5;
        let lobe = width * libm::cos(theta);
        let ti = theta + spread * t * lobe / libm::cos(theta).max(1e-3);
        let pi = core::f64::consts::PI + phi_o + spread * s * lobe;
        if ti >= FRAC_PI_2 {
            return None;
        }
        let dir = |th: f64, ph: f64| {
            Vec3::new(
                (libm::sin(th) * libm::cos(ph)) as f32,
                (libm::sin(th) * libm::sin(ph)) as f32,
                libm::cos(th) as f32,
            )
        };
        Some((dir(ti, pi), dir(theta, phi_o)))
    }

    /// The `f32` vector `w` normalised in `f64`: the direction it stands for.
    pub fn unit64(w: Vec3) -> [f64; 3] {
        let v = [w.x as f64, w.y as f64, w.z as f64];
        let l = libm::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        [v[0] / l, v[1] / l, v[2] / l]
    }

    /// `∫_H g(ω) dω` by the midpoint rule in `(s, φ)` with `θ = (π/2) s²`
    /// (cells crowd toward the pole, where narrow lobes at normal incidence
    /// live; the horizon is a cell boundary). `dω = sin θ · π s ds dφ`.
    pub fn hemisphere_integral(n_s: usize, n_phi: usize, mut g: impl FnMut(Vec3) -> f64) -> f64 {
        let mut total = 0.0f64;
        let dphi = TAU / n_phi as f64;
        let trig: std::vec::Vec<(f64, f64)> = (0..n_phi)
            .map(|j| {
                let phi = (j as f64 + 0.5) * dphi;
                (libm::cos(phi), libm::sin(phi))
            })
            .collect();
        for i in 0..n_s {
            let s = (i as f64 + 0.5) / n_s as f64;
            let theta = FRAC_PI_2 * s * s;
            let dtheta = 2.0 * FRAC_PI_2 * s / n_s as f64;
            let (st, ct) = (libm::sin(theta), libm::cos(theta));
            let mut ring = 0.0f64;
            for &(cp, sp) in &trig {
                ring += g(Vec3::new((st * cp) as f32, (st * sp) as f32, ct as f32));
            }
            total += ring * dphi * st * dtheta;
        }
        total
    }

    /// Unit direction at polar angle `theta` in the x–z plane (f64 → f32).
    pub fn dir_xz(theta: f64) -> Vec3 {
        Vec3::new(libm::sin(theta) as f32, 0.0, libm::cos(theta) as f32)
    }

    /// Directional albedo of channel `c`, `∫_H f(ωi, ωo) cos θi dωi`.
    pub fn albedo<B: Brdf>(b: &B, wo: Vec3, c: usize, n_s: usize, n_phi: usize) -> f64 {
        hemisphere_integral(n_s, n_phi, |wi| b.eval(wi, wo).channel(c) as f64 * wi.z as f64)
    }

    /// `∫_H pdf(ωi, ωo) dωi`.
    pub fn pdf_mass<B: Brdf>(b: &B, wo: Vec3, n_s: usize, n_phi: usize) -> f64 {
        hemisphere_integral(n_s, n_phi, |wi| b.pdf(wi, wo) as f64)
    }

    /// Sample coordinates that include both edges of `[0, 1)`.
    pub const U_GRID: [f32; 11] = [
        0.0,
        1e-7,
        0.01,
        0.1,
        0.25,
        0.5,
        0.75,
        0.9,
        0.99,
        0.9999,
        ONE_MINUS_EPSILON,
    ];

    /// Checks every sample on `U_GRID²`: finite, unit, above the horizon,
    /// `pdf == brdf.pdf(wi, wo)` (relative 1e-5) and `weight == f cos θi / pdf`
    /// (relative 1e-5, recomputed in f64). Returns the number of `Some`s and
    /// the worst relative pdf / weight mismatches.
    pub fn check_sampling<B: Brdf>(b: &B, wo: Vec3) -> (usize, f64, f64) {
        let (mut some, mut worst_pdf, mut worst_w) = (0, 0.0f64, 0.0f64);
        for &u0 in &U_GRID {
            for &u1 in &U_GRID {
                let Some(s) = b.sample(wo, [u0, u1]) else { continue };
                some += 1;
                assert!(
                    s.wi.is_finite() && (s.wi.length() - 1.0).abs() < 1e-5,
                    "{wo:?} {u0} {u1} {s:?}"
                );
                assert!(s.wi.z > 0.0, "below horizon: {s:?}");
                assert!(s.pdf > 0.0 && s.pdf.is_finite(), "{s:?}");
                assert!(s.weight.is_finite() && s.weight.min_channel() >= 0.0, "{s:?}");
                let p = b.pdf(s.wi, wo) as f64;
                let e = (s.pdf as f64 - p).abs() / p;
                worst_pdf = worst_pdf.max(e);
                assert!(e <= 1e-5, "pdf mismatch {e}: {wo:?} {u0} {u1} {s:?} {p}");
                let f = b.eval(s.wi, wo);
                for c in 0..B::Spectrum::CHANNELS {
                    let expect = f.channel(c) as f64 * s.wi.z as f64 / s.pdf as f64;
                    let got = s.weight.channel(c) as f64;
                    let e = (got - expect).abs() / expect.abs().max(1e-30);
                    worst_w = worst_w.max(if expect == 0.0 && got == 0.0 { 0.0 } else { e });
                    assert!(
                        e <= 1e-5 || (expect == 0.0 && got == 0.0),
                        "weight {got} vs {expect}: {s:?}"
                    );
                }
            }
        }
        (some, worst_pdf, worst_w)
    }

    /// Kolmogorov–Smirnov distance between the samples `δ = 1 − cos`
    /// (of a lobe with density `(n+1)/(2π) cos^n` around its axis) and the
    /// closed-form CDF `P(δ' ≤ δ) = 1 − (1 − δ)^{n+1}` (f64).
    pub fn ks_distance_cos_power(deltas: &mut [f64], n: f64) -> f64 {
        deltas.sort_by(|a, b| a.total_cmp(b));
        let m = deltas.len() as f64;
        let mut d = 0.0f64;
        for (k, &x) in deltas.iter().enumerate() {
            let cdf = -libm::expm1((n + 1.0) * libm::log1p(-x.min(1.0)));
            d = d
                .max((cdf - k as f64 / m).abs())
                .max((cdf - (k + 1) as f64 / m).abs());
        }
        d
    }

    /// The fused `sample` reports exactly `pdf(wi, wo)` (bit-identical, not
    /// just close) and `weight = (eval(wi, wo)/pdf)·cos θi` exactly, for
    /// `wo` and `3.5·wo` (the non-unit, cold input path) on `U_GRID²`.
    /// Returns the number of `Some`s.
    pub fn check_sample_bits<B: Brdf>(b: &B, wo: Vec3) -> usize {
        let mut some = 0;
        for wo in [wo, wo * 3.5] {
            for &u0 in &U_GRID {
                for &u1 in &U_GRID {
                    let Some(s) = b.sample(wo, [u0, u1]) else { continue };
                    some += 1;
                    assert_eq!(
                        s.pdf.to_bits(),
                        b.pdf(s.wi, wo).to_bits(),
                        "{wo:?} {u0} {u1} {s:?}"
                    );
                    assert_eq!(s.weight, (b.eval(s.wi, wo) / s.pdf) * s.wi.z, "{wo:?} {u0} {u1}");
                }
            }
        }
        some
    }

    /// Stratified (m × m midpoint grid) estimate of the albedo of channel 0
    /// from `sample` weights (`None` counts as 0): unbiased iff the samples
    /// follow `pdf`.
    pub fn sampled_albedo<B: Brdf>(b: &B, wo: Vec3, m: usize) -> f64 {
        let mut sum = 0.0f64;
        for i in 0..m {
            for j in 0..m {
                let u = [(i as f32 + 0.5) / m as f32, (j as f32 + 0.5) / m as f32];
                if let Some(s) = b.sample(wo, u) {
                    sum += s.weight.channel(0) as f64;
                }
            }
        }
        sum / (m * m) as f64
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::test_support::*;
    use super::*;
    use core::f64::consts::PI as PI64;
    use radiometry::glam::Vec3 as V;
    use std::string::ToString;

    fn phong(kd: f32, ks: f32, n: f32) -> ModifiedPhong {
        ModifiedPhong::new(kd, ks, n).unwrap()
    }

    /// f at the mirror direction (cos α = 1) = kd/π + ks(n+2)/(2π), and in
    /// the plane of incidence at angle α from the mirror direction
    /// f = kd/π + ks(n+2)/(2π) cos^n α (closed form in f64).
    #[test]
    fn formula_spot_checks() {
        for &n in &[0.0f32, 1.0, 10.0, 1e3, 1e6, MAX_EXPONENT] {
            let b = phong(0.25, 0.75, n);
            let expect = 0.25 / PI64 + 0.75 * (n as f64 + 2.0) / (2.0 * PI64);
            let f = b.eval(V::Z, V::Z) as f64;
            assert!((f - expect).abs() <= 1e-6 * expect, "n={n}: {f} vs {expect}");
            // Mirror pair off normal: wi = reflect(wo).
            let wo = dir_xz(0.7);
            let wi = V::new(-wo.x, -wo.y, wo.z);
            let f = b.eval(wi, wo) as f64;
            assert!((f - expect).abs() <= 1e-5 * expect, "n={n}: {f} vs {expect}");
        }
        for &(theta_o, alpha, n) in &[
            (0.7f64, 0.1f64, 10.0f32),
            (0.3, 0.25, 3.5),
            (1.0, 0.02, 1000.0),
            (0.2, 0.6, 1.0),
        ] {
            let b = phong(0.1, 0.9, n);
            let wo = dir_xz(theta_o);
            // The mirror direction is at polar angle −θo; rotate by α in-plane.
            let wi = dir_xz(-theta_o + alpha);
            let expect =
                0.1 / PI64 + 0.9 * (n as f64 + 2.0) / (2.0 * PI64) * libm::pow(libm::cos(alpha), n as f64);
            let f = b.eval(wi, wo) as f64;
            assert!(
                (f - expect).abs() <= 1e-4 * expect,
                "{theta_o} {alpha} {n}: {f} vs {expect}"
            );
        }
        // cos α ≤ 0 (wi = wo far from normal): only the diffuse term, even for n = 0.
        for &n in &[0.0f32, 5.0] {
            let wo = dir_xz(1.2);
            let f = phong(0.3, 0.7, n).eval(wo, wo) as f64;
            assert!((f - 0.3 / PI64).abs() < 1e-7, "{f}");
        }
        // RGB: channel-wise.
        let rgb = ModifiedPhong::new(V::new(0.1, 0.2, 0.3), V::new(0.5, 0.4, 0.0), 4.0).unwrap();
        let f = rgb.eval(V::Z, V::Z);
        for (c, (kd, ks)) in [(0.1, 0.5), (0.2, 0.4), (0.3, 0.0)].into_iter().enumerate() {
            let e = kd / PI64 + ks * 6.0 / (2.0 * PI64);
            assert!((f.channel(c) as f64 - e).abs() < 1e-6, "{c}");
        }
    }

    #[test]
    fn constructor_validation_and_messages() {
        let e = ModifiedPhong::new(f32::NAN, 0.1, 1.0).unwrap_err();
        assert_eq!(e, BrdfError::NotFinite { name: "kd" });
        assert_eq!(e.to_string(), "parameter `kd` must be finite");
        let e = ModifiedPhong::new(0.1f32, -0.1, 1.0).unwrap_err();
        assert_eq!(e.to_string(), "parameter `ks` = -0.1 is outside [0, 1]");
        let e = ModifiedPhong::new(0.5f32, 0.6, 1.0).unwrap_err();
        assert!(matches!(e, BrdfError::Constraint { .. }));
        assert_eq!(
            e.to_string(),
            "invalid parameters: kd + ks must not exceed 1 in any channel (energy conservation)"
        );
        let e = ModifiedPhong::new(0.1f32, 0.1, 2e7).unwrap_err();
        assert_eq!(
            e.to_string(),
            "parameter `exponent` = 20000000 is outside [0, 10000000]"
        );
        assert!(ModifiedPhong::new(0.1f32, 0.1, -1e-6).is_err());
        assert!(ModifiedPhong::new(0.1f32, 0.1, f32::INFINITY).is_err());
        // One bad channel of an RGB spectrum is enough.
        assert!(ModifiedPhong::new(V::new(0.1, 0.1, 0.9), V::splat(0.2), 1.0).is_err());
        assert!(ModifiedPhong::new(V::new(0.1, f32::NAN, 0.1), V::splat(0.2), 1.0).is_err());
        // Edges of the domain are accepted.
        assert!(ModifiedPhong::new(0.3f32, 0.7, 0.0).is_ok());
        assert!(ModifiedPhong::new(0.0f32, 1.0, MAX_EXPONENT).is_ok());
        assert!(ModifiedPhong::new(0.0f32, 0.0, 1.0).is_ok());
    }

    /// Lafortune & Willems: the lobe albedo at normal incidence is exactly 1
    /// for ks = 1 (independent f64 quadrature of f cos θi).
    #[test]
    fn lobe_albedo_is_one_at_normal_incidence() {
        for &n in &[0.0f32, 1.0, 10.0, 100.0, 1000.0] {
            let a = albedo(&phong(0.0, 1.0, n), V::Z, 0, 4000, 16);
            std::eprintln!("phong lobe albedo n={n}: {a:.9} (err {:.2e})", a - 1.0);
            assert!((a - 1.0).abs() < 1e-4, "n={n}: {a}");
        }
        let a = albedo(&phong(0.35, 0.65, 30.0), V::Z, 0, 2000, 16);
        assert!((a - 1.0).abs() < 1e-4, "{a}");
    }

    /// Away from normal incidence the horizon clips the lobe: albedo ≤ 1.
    #[test]
    fn energy_at_most_one_off_normal() {
        for &n in &[0.0f32, 1.0, 10.0, 100.0] {
            for &t in &[0.2f64, 0.6, 1.0, 1.4, 1.55] {
                let a = albedo(&phong(0.0, 1.0, n), dir_xz(t), 0, 1500, 512);
                std::eprintln!("phong albedo n={n} θo={t}: {a:.6}");
                assert!(a <= 1.0 + 1e-4 && a > 0.0, "n={n} θo={t}: {a}");
            }
        }
        let a = albedo(&phong(0.0, 1.0, 1000.0), dir_xz(0.5), 0, 3000, 4096);
        assert!(a <= 1.0 + 1e-4 && a > 0.8, "{a}");
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
            let b = phong(kd, ks, n);
            for &t in &[0.0f64, 0.5, 1.2, 1.5706, core::f64::consts::FRAC_PI_2 - 1e-7] {
                let wo = dir_xz(t);
                let (some, ep, ew) = check_sampling(&b, wo);
                std::eprintln!(
                    "phong sampling {kd} {ks} n={n} θo={t}: {some}/121 some, pdf err {ep:.1e}, weight err {ew:.1e}"
                );
                assert!(some > 0, "no sample for {kd} {ks} {n} {t}");
                assert!(check_sample_bits(&b, wo) > 0);
                // Non-unit wo gives the same samples.
                let s1 = b.sample(wo * 3.5, [0.3, 0.6]);
                let s2 = b.sample(wo, [0.3, 0.6]);
                assert_eq!(s1.is_some(), s2.is_some());
                if let (Some(a), Some(c)) = (s1, s2) {
                    assert!((a.wi - c.wi).length() < 1e-5 && (a.pdf - c.pdf).abs() <= 1e-4 * c.pdf);
                }
            }
        }
    }

    /// The lobe sampler follows cos^n α even for huge n: KS distance of
    /// `δ = 1 − cos α` (from the returned directions, in f64) to the closed
    /// form CDF, with stratified u₀ (m = 4000: D = 1/(2m) = 1.25e-4 when exact;
    /// the bound 5e-4 leaves room for f32 rounding of ωi).
    #[test]
    fn lobe_samples_follow_closed_form_cdf() {
        let m = 4000;
        for &n in &[1.0f32, 100.0, 1e4, 1e6, MAX_EXPONENT] {
            let b = phong(0.0, 1.0, n);
            // The n = 1 lobe reaches below the horizon unless wo = +Z.
            let wo = if n < 10.0 { V::Z } else { dir_xz(0.5) };
            let r = [-(wo.x as f64), -(wo.y as f64), wo.z as f64];
            let mut deltas = std::vec::Vec::with_capacity(m);
            for i in 0..m {
                let u = [(i as f32 + 0.5) / m as f32, 0.37];
                let s = b.sample(wo, u).unwrap();
                let w = [s.wi.x as f64, s.wi.y as f64, s.wi.z as f64];
                let l = libm::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
                let d2: f64 = (0..3).map(|k| (w[k] / l - r[k]) * (w[k] / l - r[k])).sum();
                deltas.push(0.5 * d2);
            }
            let d = ks_distance_cos_power(&mut deltas, n as f64);
            std::eprintln!("phong lobe KS n={n}: D = {d:.2e}");
            assert!(d < 5e-4, "n={n}: D = {d}");
        }
    }

    /// kd = ks = 0: sample → None, pdf → 0 (documented).
    #[test]
    fn black_brdf_has_no_samples() {
        let b = phong(0.0, 0.0, 10.0);
        assert_eq!(b.pdf(V::Z, V::Z), 0.0);
        assert!(b.sample(V::Z, [0.5, 0.5]).is_none());
        assert_eq!(b.eval(V::Z, V::Z), 0.0);
    }

    /// Below-horizon lobe mass for a lobe around the mirror direction at
    /// polar angle θo, by 1D f64 quadrature in α of
    /// `(n+1) cos^n α sin α · acos(min(1, cot α cot θo))/π` (the fraction
    /// of azimuths around ωr with z ≤ 0).
    fn below_horizon_mass(n: f64, theta_o: f64) -> f64 {
        let m = 200_000;
        let h = core::f64::consts::FRAC_PI_2 / m as f64;
        let cot_o = libm::cos(theta_o) / libm::sin(theta_o);
        let mut sum = 0.0;
        for i in 0..m {
            let a = (i as f64 + 0.5) * h;
            let c = libm::cos(a) / libm::sin(a) * cot_o;
            let frac = if c >= 1.0 { 0.0 } else { libm::acos(c) / PI64 };
            sum += (n + 1.0) * libm::pow(libm::cos(a), n) * libm::sin(a) * frac * h;
        }
        sum
    }

    /// ∫_H pdf = 1 at normal incidence; elsewhere pd + ps (1 − below-horizon
    /// lobe mass).
    #[test]
    fn pdf_integrates_to_expected_mass() {
        for &n in &[0.0f32, 1.0, 10.0, 1000.0] {
            for &(kd, ks) in &[(0.0f32, 1.0f32), (0.5, 0.5)] {
                let m = pdf_mass(&phong(kd, ks, n), V::Z, 4000, 16);
                std::eprintln!("phong pdf mass n={n} kd={kd} normal: err {:.2e}", m - 1.0);
                assert!((m - 1.0).abs() < 1e-4, "n={n} kd={kd}: {m}");
            }
        }
        for &n in &[1.0f32, 10.0, 100.0] {
            for &t in &[0.5f64, 1.0, 1.4] {
                let (kd, ks) = (0.3f32, 0.6f32);
                let pd = kd as f64 / (kd as f64 + ks as f64);
                let expect = pd + (1.0 - pd) * (1.0 - below_horizon_mass(n as f64, t));
                let m = pdf_mass(&phong(kd, ks, n), dir_xz(t), 1500, 512);
                std::eprintln!(
                    "phong pdf mass n={n} θo={t}: {m:.6} expect {expect:.6} err {:.2e}",
                    m - expect
                );
                assert!((m - expect).abs() < 2e-4, "n={n} θo={t}: {m} vs {expect}");
                assert!(m <= 1.0 + 1e-4);
            }
        }
    }

    /// E[weight] over stratified samples equals the quadrature albedo: the
    /// sampler follows its pdf.
    #[test]
    fn sampling_is_unbiased() {
        for &(kd, ks, n, t) in &[
            (0.3f32, 0.6f32, 10.0f32, 0.8f64),
            (0.0, 1.0, 100.0, 1.2),
            (0.5, 0.5, 1.0, 0.0),
        ] {
            let b = phong(kd, ks, n);
            let wo = dir_xz(t);
            let reference = albedo(&b, wo, 0, 1500, 512);
            let mc = sampled_albedo(&b, wo, 1024);
            std::eprintln!(
                "phong MC albedo {kd} {ks} n={n} θo={t}: {mc:.6} vs {reference:.6} rel {:.2e}",
                mc / reference - 1.0
            );
            assert!(
                (mc - reference).abs() < 5e-3 * reference,
                "{kd} {ks} {n} {t}: {mc} vs {reference}"
            );
        }
    }

    /// Hard inputs: finite, non-negative, no panic.
    #[test]
    fn stability_hard_cases() {
        let b = phong(0.2, 0.8, MAX_EXPONENT);
        let cases = [
            (V::Z, -V::Z),
            (V::new(1.0, 0.0, 1e-7), V::new(-1.0, 0.0, 1e-7)),
            (V::new(1.0, 0.0, 1e-7), V::new(1.0, 0.0, 1e-7)),
            (V::new(1.0, 0.0, 0.0), V::new(-1.0, 0.0, 0.0)),
            (V::ZERO, V::Z),
            (V::new(3.0, 1.0, 2.0), V::new(-0.001, 0.0, 0.002)),
            (V::new(0.0, 0.0, 1e-30), V::Z),
        ];
        for &(wi, wo) in &cases {
            for bb in [b, phong(0.0, 1.0, 0.0), phong(0.5, 0.5, 1e6)] {
                for (x, y) in [(wi, wo), (wo, wi)] {
                    let f = bb.eval(x, y);
                    let p = bb.pdf(x, y);
                    assert!(
                        f.is_finite() && f >= 0.0 && p.is_finite() && p >= 0.0,
                        "{x:?} {y:?} {f} {p}"
                    );
                    // Reciprocity is exact (symmetric formula).
                    assert_eq!(bb.eval(x, y), bb.eval(y, x));
                }
            }
        }
        // Zero at and below the horizon.
        assert_eq!(b.eval(V::new(1.0, 0.0, 0.0), V::Z), 0.0);
        assert_eq!(b.eval(V::Z, V::new(0.6, 0.0, -0.8)), 0.0);
        assert!(b.sample(V::new(0.6, 0.0, -0.8), [0.5, 0.5]).is_none());
        // Non-unit input equals normalised input.
        let (wi, wo) = (dir_xz(-0.5), dir_xz(0.5));
        let b = phong(0.2, 0.8, 50.0);
        let (f1, f2) = (b.eval(wi, wo), b.eval(wi * 7.0, wo * 0.01));
        assert!((f1 - f2).abs() <= 1e-4 * f1, "{f1} {f2}");
        // Peak at n = 1e7 is finite and equals the closed form.
        let f = phong(0.0, 1.0, MAX_EXPONENT).eval(V::Z, V::Z) as f64;
        let e = (1e7 + 2.0) / (2.0 * PI64);
        assert!((f - e).abs() < 1e-6 * e);
    }
}
