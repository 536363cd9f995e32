//! The [`Brdf`] trait: what every reflectance plugin implements.
//!
//! The bidirectional reflectance distribution function is
//! `f_r(ωi→ωo) = dL_o(ωo) / (L_i(ωi) cos θi dωi)` [sr⁻¹] (Nicodemus et al.
//! 1977, NBS Monograph 160), and the reflection equation
//! `L_r(ωo) = ∫_H f_r(ωi→ωo) L_i(ωi) cos θi dωi` uses it.
//!
//! A plugin needs only [`Brdf::eval`]; [`Brdf::sample`] and [`Brdf::pdf`]
//! default to cosine-weighted hemisphere sampling, which is exact (if not
//! efficient) for any BRDF.

use crate::batch::Vec3Soa;
use crate::frame::{cos_theta, spherical_direction};
use crate::spectrum::Spectrum;
use crate::warp::{cosine_hemisphere_pdf, square_to_cosine_hemisphere};
use glam::Vec3;

/// One importance sample of a BRDF, for a fixed `wo`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BrdfSample<S> {
    /// The sampled incident direction (unit, local frame).
    pub wi: Vec3,
    /// Its density with respect to solid angle [sr⁻¹]; always `> 0` and finite.
    pub pdf: f32,
    /// `f_r(wi, wo) · cos θi / pdf`: the Monte Carlo weight.
    pub weight: S,
}

/// A directional albedo `E(ωo) = ∫_H f_r(ωi, ωo) cos θi dωi` with its
/// stated error, as [`Brdf::directional_albedo`] reports it.
///
/// `E(ωo)` is the fraction of light arriving from `ωo` that the surface
/// reflects (by reciprocity, also the reflectance under a uniform sky seen
/// from `ωo`); lobe combinators pick lobes in proportion to it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Albedo<S> {
    /// The albedo per channel, finite and `≥ 0`.
    pub value: S,
    /// Its error, absolute, for every channel: a bound (`is_bound`) for
    /// closed forms and tables, an estimated standard error otherwise.
    /// Finite and `≥ 0`.
    pub error: f32,
    /// Whether `error` bounds `|value − E(ωo)|` (closed forms and tables) or
    /// only estimates it (the default sampling rule).
    pub is_bound: bool,
}

impl<S: Spectrum> Albedo<S> {
    /// An albedo known to within `error` (a bound).
    #[inline]
    pub fn bounded(value: S, error: f32) -> Self {
        Self {
            value,
            error,
            is_bound: true,
        }
    }

    /// The albedo of a direction at or below the horizon: exactly zero.
    #[inline]
    pub fn zero() -> Self {
        Self::bounded(S::zero(), 0.0)
    }
}

/// A bidirectional reflectance distribution function in the local shading
/// frame (normal `+Z`).
///
/// # Contract
/// * `eval(wi, wo)` is `f_r` in sr⁻¹: finite, `≥ 0`, and zero when either
///   direction is at or below the horizon (`cos θ ≤ 0`).
/// * `sample(wo, u)` for `u ∈ [0,1)²` returns `wi` with density `pdf`
///   (solid angle) and `weight = eval(wi, wo)·cos θi / pdf`, or `None` when
///   no valid direction results (e.g. `wo` below the horizon, or a
///   sampled microfacet reflects below the horizon). The returned `pdf`
///   equals `self.pdf(wi, wo)`.
/// * `pdf(wi, wo)` is the density `sample` uses; it is `≥ 0` and finite.
///   Its integral over the upper hemisphere is ≤ 1 (the deficit is the
///   probability that `sample` returns `None`).
/// * No method panics, or returns NaN or ∞, for any finite input, including
///   non-unit vectors and `wi = −wo`.
pub trait Brdf {
    /// The spectrum type of `f_r` (`f32`, `Vec3` or a sampled spectrum).
    type Spectrum: Spectrum;

    /// `f_r(wi → wo)` [sr⁻¹].
    fn eval(&self, wi: Vec3, wo: Vec3) -> Self::Spectrum;

    /// Importance-samples `wi` for the given `wo`. The default is
    /// cosine-weighted hemisphere sampling (density `cos θi/π`).
    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<Self::Spectrum>> {
        if cos_theta(wo) <= 0.0 {
            return None;
        }
        let wi = square_to_cosine_hemisphere(u);
        let pdf = cosine_hemisphere_pdf(wi);
        if pdf.is_nan() || pdf <= 0.0 {
            return None;
        }
        let f = self.eval(wi, wo);
        Some(BrdfSample {
            wi,
            pdf,
            weight: f * (cos_theta(wi) / pdf),
        })
    }

    /// Density of [`Brdf::sample`] [sr⁻¹]. The default matches the default
    /// `sample`: `cos θi / π` when both directions are above the horizon.
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        if cos_theta(wo) <= 0.0 {
            return 0.0;
        }
        cosine_hemisphere_pdf(wi)
    }

    /// Evaluates `out[k] = eval(wi[k], wo[k])` for `k < n = min(len)`;
    /// elements of `out` past `n` are set to zero (the
    /// [batch length rule](crate::batch::zero_tail): a mismatched call
    /// neither panics nor leaves stale output).
    ///
    /// The default loops over [`Brdf::eval`]; plugins may override it with a
    /// vectorised kernel (the plugins of `radiometry-brdfs` do, with its `simd`
    /// feature).
    fn eval_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [Self::Spectrum]) {
        for ((o, &a), &b) in out.iter_mut().zip(wi).zip(wo) {
            *o = self.eval(a, b);
        }
        crate::batch::zero_tail(out, wi.len().min(wo.len()));
    }

    /// Structure-of-arrays form of [`Brdf::eval_batch`]:
    /// `out[k] = eval(wi.get(k), wo.get(k))` for `k < min(wi.len(), wo.len(),
    /// out.len())`; elements of `out` past `n` are set to zero ([batch length rule](crate::batch::zero_tail)).
    ///
    /// The default loops over [`Brdf::eval`]; plugins with vector kernels
    /// override it (loads of 8 consecutive `x`, `y`, `z` need no shuffles).
    ///
    /// ```
    /// use radiometry::{Brdf, batch::Vec3Soa, glam::Vec3};
    /// struct Flat;
    /// impl Brdf for Flat {
    ///     type Spectrum = f32;
    ///     fn eval(&self, wi: Vec3, wo: Vec3) -> f32 { if wi.z > 0.0 && wo.z > 0.0 { 0.1 } else { 0.0 } }
    /// }
    /// let (x, y, z) = ([0.0f32, 0.0], [0.0f32, 0.0], [1.0f32, -1.0]);
    /// let w = Vec3Soa::new(&x, &y, &z);
    /// let mut out = [7.0f32; 2];
    /// Flat.eval_batch_soa(w, w, &mut out);
    /// assert_eq!(out, [0.1, 0.0]);
    /// ```
    fn eval_batch_soa(&self, wi: Vec3Soa<'_>, wo: Vec3Soa<'_>, out: &mut [Self::Spectrum]) {
        // Zipped iterators, not indexing: no bounds check (hence no panic path)
        // survives on any target, and the shortest slice ends the loop.
        let wi_xyz = wi.x.iter().zip(wi.y).zip(wi.z);
        let wo_xyz = wo.x.iter().zip(wo.y).zip(wo.z);
        for ((o, ((&ax, &ay), &az)), ((&bx, &by), &bz)) in out.iter_mut().zip(wi_xyz).zip(wo_xyz) {
            *o = self.eval(Vec3::new(ax, ay, az), Vec3::new(bx, by, bz));
        }
        crate::batch::zero_tail(out, wi.len().min(wo.len()));
    }

    /// `out[k] = pdf(wi[k], wo[k])` for `k < min(len)`; elements of `out` past `n` are
    /// set to zero ([batch length rule](crate::batch::zero_tail)). The default loops over [`Brdf::pdf`].
    fn pdf_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]) {
        for ((o, &a), &b) in out.iter_mut().zip(wi).zip(wo) {
            *o = self.pdf(a, b);
        }
        crate::batch::zero_tail(out, wi.len().min(wo.len()));
    }

    /// `out[k] = sample(wo[k], u[k])` for `k < min(len)`; elements of `out`
    /// past `n` are set to `None` ([batch length rule](crate::batch::zero_tail)). The default loops over [`Brdf::sample`].
    fn sample_batch(&self, wo: &[Vec3], u: &[[f32; 2]], out: &mut [Option<BrdfSample<Self::Spectrum>>]) {
        for ((o, &w), &v) in out.iter_mut().zip(wo).zip(u) {
            *o = self.sample(w, v);
        }
        crate::batch::zero_tail(out, wo.len().min(u.len()));
    }

    /// The number of components of the sampling map: [`Brdf::sample`] picks
    /// component `k < sampling_components()` with probability
    /// [`component_weight`](Brdf::component_weight)`(ωo, k)` (`c_k`) and then
    /// draws `ωi` from that component's own map
    /// [`sample_component`](Brdf::sample_component)`(ωo, k, ·)` (density
    /// `p_k`), so that
    ///
    /// ```text
    /// pdf(ωi, ωo) = Σ_k c_k(ωo) p_k(ωi, ωo),     Σ_k c_k(ωo) = 1.
    /// ```
    ///
    /// A mixture map (EON's cosine/uniform mixture, Kulla–Conty's
    /// microfacet/added-lobe mixture, the pick-a-lobe map of every
    /// composite of [`compose`](crate::compose)) is discontinuous at the
    /// pick thresholds `u₀ = c₀, c₀ + c₁, …`; each component's map is as
    /// smooth as the lobe. The warped [`Adaptive`](crate::integrator::Adaptive)
    /// rule integrates each component on its own unit square through the
    /// balance-heuristic decomposition (exact, the integral is linear):
    ///
    /// ```text
    /// ∫_H g dω = Σ_k c_k ∫_[0,1]² g(ω_k(u)) / pdf(ω_k(u)) du.
    /// ```
    ///
    /// The components are numbered in the order of `sample`'s pick: component
    /// `k` is what `sample` draws for `u₀ ∈ [c₀ + … + c_{k−1}, c₀ + … + c_k)`
    /// (rescaled onto `[0, 1)`), so `sample_component(ωo, k, u)` is
    /// `sample(ωo, [c₀ + … + c_{k−1} + c_k u₀, u₁])`'s direction up to the
    /// rounding of the rescaling; composites list their first lobe's
    /// components first.
    ///
    /// The default, 1, is the whole map as one component (weight 1,
    /// [`sample`](Brdf::sample)'s directions); a plugin that overrides one of
    /// the three methods overrides all three, consistently with its
    /// `sample` and `pdf`.
    fn sampling_components(&self) -> usize {
        1
    }

    /// The probability `c_k(ωo) ∈ [0, 1]` that [`Brdf::sample`] draws from
    /// component `k` (see [`sampling_components`](Brdf::sampling_components));
    /// the weights sum to 1 over `k < sampling_components()`, and are 0 for
    /// `k` out of range. The default: 1 for `k = 0`.
    fn component_weight(&self, wo: Vec3, k: usize) -> f32 {
        let _ = wo;
        if k == 0 { 1.0 } else { 0.0 }
    }

    /// The direction that component `k` of the sampling map draws from
    /// `u ∈ [0,1)²` (see [`sampling_components`](Brdf::sampling_components)),
    /// or `None` where it draws none (or `k` is out of range). Its density
    /// is the component's own `p_k`; [`Brdf::pdf`] is the mixture. The
    /// default: component 0 is [`sample`](Brdf::sample)'s direction.
    fn sample_component(&self, wo: Vec3, k: usize, u: [f32; 2]) -> Option<Vec3> {
        if k == 0 {
            self.sample(wo, u).map(|s| s.wi)
        } else {
            None
        }
    }

    /// Whether `f_r(ωi, ωo) cos θi` is a smooth (analytic) function of `ωi`
    /// on the open upper hemisphere for every fixed `ωo` — no kinks, steps
    /// or table cells. A promise the [`Auto`](crate::integrator::Auto)
    /// integrator relies on: it then integrates peaked lobes on charts whose
    /// error estimates assume the exponential convergence of a smooth
    /// integrand. Default `false` (the safe answer); closed-form lobes
    /// (Lambertian, microfacet single scattering) say `true`, tabulated data
    /// and interpolated compensation lobes do not.
    fn is_smooth(&self) -> bool {
        false
    }

    /// The directional albedo `E(ωo) = ∫_H f_r(ωi, ωo) cos θi dωi`, cheaply,
    /// with its stated error; zero (exactly) when `ωo` is at or below the
    /// horizon.
    ///
    /// Plugins override it with a closed form or a table (Lambertian: `ρ`,
    /// error 0). The default is a small fixed rule over the plugin's own
    /// sampler: the mean of the 16 weights `f cos θi / pdf` at the stratified
    /// points `u = ((i + ½)/4, (j + ½)/4)`, with their standard error as the
    /// (estimated, not bounded) error — 16 calls of [`Brdf::sample`].
    /// Deterministic: the same `ωo` gives the same bits, which the lobe
    /// combinators of [`compose`](crate::compose) rely on.
    ///
    /// ```
    /// use radiometry::{Brdf, glam::Vec3};
    /// struct Flat; // f = 0.2/π: albedo 0.2 at every ωo
    /// impl Brdf for Flat {
    ///     type Spectrum = f32;
    ///     fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
    ///         if wi.z > 0.0 && wo.z > 0.0 { 0.2 * core::f32::consts::FRAC_1_PI } else { 0.0 }
    ///     }
    /// }
    /// let e = Flat.directional_albedo(Vec3::new(0.0, 0.6, 0.8));
    /// assert!((e.value - 0.2).abs() < 1e-6 && !e.is_bound);
    /// assert_eq!(Flat.directional_albedo(-Vec3::Z).value, 0.0);
    /// ```
    fn directional_albedo(&self, wo: Vec3) -> Albedo<Self::Spectrum> {
        crate::compose::albedo_by_sampling(self, wo)
    }

    /// The value of [`directional_albedo`](Brdf::directional_albedo) at
    /// each of `wo`: `out[k] = directional_albedo(wo[k]).value` for `k < n =
    /// min(len)`; elements of `out` past `n` are set to zero ([batch length
    /// rule](crate::batch::zero_tail)). A layer that reads its top's albedo
    /// at every direction of a batch
    /// ([`compose::Coated`](crate::compose::Coated)'s batch paths) reads it
    /// here.
    ///
    /// The default loops over `directional_albedo`; a plugin whose albedo
    /// comes from a table may read the table in vector lanes (the GGX
    /// dielectric lobes of `radiometry-brdfs`, once
    /// [prepared](Brdf::with_prepared_albedo), with its `simd` feature:
    /// bit for bit the scalar values).
    ///
    /// ```
    /// use radiometry::{Brdf, glam::Vec3};
    /// struct Flat; // f = 0.2/π, E = 0.2 above the horizon
    /// impl Brdf for Flat {
    ///     type Spectrum = f32;
    ///     fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
    ///         if wi.z > 0.0 && wo.z > 0.0 { 0.2 * core::f32::consts::FRAC_1_PI } else { 0.0 }
    ///     }
    /// }
    /// let wo = [Vec3::new(0.0, 0.6, 0.8), -Vec3::Z];
    /// let mut out = [9.0f32; 3];
    /// Flat.directional_albedo_batch(&wo, &mut out);
    /// assert_eq!(out, [Flat.directional_albedo(wo[0]).value, 0.0, 0.0]);
    /// ```
    fn directional_albedo_batch(&self, wo: &[Vec3], out: &mut [Self::Spectrum]) {
        for (o, &w) in out.iter_mut().zip(wo) {
            *o = self.directional_albedo(w).value;
        }
        crate::batch::zero_tail(out, wo.len());
    }

    /// The hemispherical average of the directional albedo, `Ē = 2∫₀¹ E(μ) μ
    /// dμ` (the albedo under uniform light from every direction, the
    /// normalisation of a reciprocal layer, [`compose::Coated`](crate::compose::Coated)).
    ///
    /// The default is an 8-point Gauss–Legendre rule in `μ` over
    /// [`directional_albedo`](Brdf::directional_albedo) at `φo = 0` (8
    /// albedo queries; an isotropic lobe's albedo depends on `μ` alone).
    /// Plugins with a global table or a closed form override it.
    fn average_albedo(&self) -> Self::Spectrum {
        default_average_albedo(self)
    }

    /// This lobe with the part of [`directional_albedo`](Brdf::directional_albedo)
    /// that depends on its parameters alone done once: for a caller that reads
    /// `E(ωo)` at every call, as a layer reads its top's `E_T(μo)` at every
    /// `eval` ([`compose::Coated::new`](crate::compose::Coated::new) calls it on
    /// its top). A plugin that reads its albedo from a table stores the table
    /// cells and interpolation weights of its roughness and index here, so
    /// that a read at `ωo` is the one-dimensional interpolation in `μo` that
    /// is left.
    ///
    /// The lobe returned is the same BRDF: [`eval`](Brdf::eval),
    /// [`sample`](Brdf::sample), [`pdf`](Brdf::pdf) and the batch paths
    /// return the same bits, and `directional_albedo` the same value up to
    /// the rounding the plugin states (O(1): no integration). The default
    /// returns `self` unchanged.
    ///
    /// ```
    /// use radiometry::{Brdf, glam::Vec3};
    /// struct Flat; // f = 0.2/π: nothing to prepare
    /// impl Brdf for Flat {
    ///     type Spectrum = f32;
    ///     fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
    ///         if wi.z > 0.0 && wo.z > 0.0 { 0.2 * core::f32::consts::FRAC_1_PI } else { 0.0 }
    ///     }
    /// }
    /// let wo = Vec3::new(0.0, 0.6, 0.8);
    /// let e = Flat.directional_albedo(wo);
    /// assert_eq!(Flat.with_prepared_albedo().directional_albedo(wo), e);
    /// ```
    fn with_prepared_albedo(self) -> Self
    where
        Self: Sized,
    {
        self
    }

    /// Hidden hook (not a stable API): [`eval`](Brdf::eval) of directions
    /// the caller has [checked](crate::frame::is_checked) — both unit length
    /// to within `4ε` (`|‖w‖² − 1| ≤ 4ε`) and strictly above the horizon —
    /// the same bits, without the lobe's own tests of its input. For a layer
    /// that tests once for both its lobes ([`compose::Coated`](crate::compose::Coated)).
    /// Default: `eval`.
    #[doc(hidden)]
    #[inline(always)]
    fn eval_checked(&self, wi: Vec3, wo: Vec3) -> Self::Spectrum {
        self.eval(wi, wo)
    }

    /// Hidden hook (not a stable API): [`pdf`](Brdf::pdf) of
    /// [checked](crate::frame::is_checked) directions, as
    /// [`eval_checked`](Brdf::eval_checked) is `eval`'s. Default: `pdf`.
    #[doc(hidden)]
    #[inline(always)]
    fn pdf_checked(&self, wi: Vec3, wo: Vec3) -> f32 {
        self.pdf(wi, wo)
    }

    /// Hidden hook (not a stable API): [`directional_albedo`](Brdf::directional_albedo)'s
    /// value at a `wo` unit to within `4ε` and strictly above the horizon,
    /// each channel clamped to `[0, 1]` (non-finite → 0): what a layer reads
    /// of its top at every call. Default: that clamp of
    /// `directional_albedo(wo).value`.
    #[doc(hidden)]
    #[inline(always)]
    fn albedo_checked(&self, wo: Vec3) -> Self::Spectrum {
        clamp_albedo(self.directional_albedo(wo).value)
    }
}

/// An albedo with each channel clamped to `[0, 1]` (non-finite → 0): how
/// the layers and the default average read a lobe's albedo.
#[inline]
pub(crate) fn clamp_albedo<S: Spectrum>(e: S) -> S {
    e.map(|v| if v.is_finite() { v.clamp(0.0, 1.0) } else { 0.0 })
}

/// The default [`Brdf::average_albedo`]: 8-point Gauss–Legendre in `μ` over
/// the lobe's directional albedo at `φo = 0`.
pub fn default_average_albedo<B: Brdf + ?Sized>(b: &B) -> B::Spectrum {
    {
        const X: [f32; 4] = [0.183_434_65, 0.525_532_4, 0.796_666_5, 0.960_289_9];
        const W: [f32; 4] = [0.362_683_78, 0.313_706_65, 0.222_381_03, 0.101_228_54];
        let mut s = B::Spectrum::zero();
        for (x, w) in X.iter().zip(W) {
            for mu in [0.5 * (1.0 - x), 0.5 * (1.0 + x)] {
                let wo = Vec3::new(crate::math::sqrtf((1.0 - mu * mu).max(0.0)), 0.0, mu);
                let e = b.directional_albedo(wo).value;
                s += clamp_albedo(e) * (w * mu);
            }
        }
        s
    }
}

/// A BRDF invariant under rotation about the normal: `f_r` depends only on
/// `(θi, θo, φo − φi)`.
///
/// Implementing it is a promise (tested for every plugin in
/// `tests/isotropy.rs`); the provided 3-parameter form builds the two
/// directions and calls [`Brdf::eval`].
pub trait IsotropicBrdf: Brdf {
    /// `f_r(θi, θo, Δφ)` with angles in radians and `Δφ = φo − φi`.
    ///
    /// ```
    /// use radiometry::{Brdf, IsotropicBrdf, glam::Vec3};
    /// struct Flat;
    /// impl Brdf for Flat {
    ///     type Spectrum = f32;
    ///     fn eval(&self, wi: Vec3, wo: Vec3) -> f32 { if wi.z > 0.0 && wo.z > 0.0 { 0.1 } else { 0.0 } }
    /// }
    /// impl IsotropicBrdf for Flat {}
    /// assert_eq!(Flat.eval_isotropic(0.2, 0.4, 1.0), 0.1);
    /// ```
    fn eval_isotropic(&self, theta_i: f32, theta_o: f32, delta_phi: f32) -> Self::Spectrum {
        let wi = spherical_direction(theta_i, 0.0);
        let wo = spherical_direction(theta_o, delta_phi);
        self.eval(wi, wo)
    }
}

impl<B: Brdf + ?Sized> Brdf for &B {
    type Spectrum = B::Spectrum;
    #[inline]
    fn eval(&self, wi: Vec3, wo: Vec3) -> Self::Spectrum {
        (**self).eval(wi, wo)
    }
    #[inline]
    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<Self::Spectrum>> {
        (**self).sample(wo, u)
    }
    #[inline]
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        (**self).pdf(wi, wo)
    }
    #[inline]
    fn eval_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [Self::Spectrum]) {
        (**self).eval_batch(wi, wo, out)
    }
    #[inline]
    fn eval_batch_soa(&self, wi: Vec3Soa<'_>, wo: Vec3Soa<'_>, out: &mut [Self::Spectrum]) {
        (**self).eval_batch_soa(wi, wo, out)
    }
    #[inline]
    fn pdf_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]) {
        (**self).pdf_batch(wi, wo, out)
    }
    #[inline]
    fn sample_batch(&self, wo: &[Vec3], u: &[[f32; 2]], out: &mut [Option<BrdfSample<Self::Spectrum>>]) {
        (**self).sample_batch(wo, u, out)
    }
    #[inline]
    fn sampling_components(&self) -> usize {
        (**self).sampling_components()
    }
    #[inline]
    fn component_weight(&self, wo: Vec3, k: usize) -> f32 {
        (**self).component_weight(wo, k)
    }
    #[inline]
    fn sample_component(&self, wo: Vec3, k: usize, u: [f32; 2]) -> Option<Vec3> {
        (**self).sample_component(wo, k, u)
    }
    #[inline]
    fn is_smooth(&self) -> bool {
        (**self).is_smooth()
    }
    #[inline]
    fn directional_albedo(&self, wo: Vec3) -> Albedo<Self::Spectrum> {
        (**self).directional_albedo(wo)
    }
    #[inline]
    fn directional_albedo_batch(&self, wo: &[Vec3], out: &mut [Self::Spectrum]) {
        (**self).directional_albedo_batch(wo, out)
    }
    fn average_albedo(&self) -> Self::Spectrum {
        (**self).average_albedo()
    }
    #[inline(always)]
    fn eval_checked(&self, wi: Vec3, wo: Vec3) -> Self::Spectrum {
        (**self).eval_checked(wi, wo)
    }
    #[inline(always)]
    fn pdf_checked(&self, wi: Vec3, wo: Vec3) -> f32 {
        (**self).pdf_checked(wi, wo)
    }
    #[inline(always)]
    fn albedo_checked(&self, wo: Vec3) -> Self::Spectrum {
        (**self).albedo_checked(wo)
    }
}

impl<B: IsotropicBrdf + ?Sized> IsotropicBrdf for &B {}

#[cfg(test)]
mod tests {
    use super::*;

    struct Const;
    impl Brdf for Const {
        type Spectrum = f32;
        fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
            if wi.z > 0.0 && wo.z > 0.0 { 0.25 } else { 0.0 }
        }
    }

    #[test]
    fn default_sampling_is_consistent() {
        let wo = Vec3::new(0.0, 0.6, 0.8);
        for &u in &[[0.1, 0.2], [0.5, 0.5], [0.9, 0.3]] {
            let s = Const.sample(wo, u).unwrap();
            assert!((s.pdf - Const.pdf(s.wi, wo)).abs() < 1e-6);
            let expect = 0.25 * s.wi.z / s.pdf;
            assert!((s.weight - expect).abs() < 1e-5);
        }
        assert!(Const.sample(-wo, [0.5, 0.5]).is_none());
    }

    #[test]
    fn batch_matches_scalar() {
        let wi = [Vec3::Z, Vec3::new(0.0, 0.0, -1.0)];
        let wo = [Vec3::Z, Vec3::Z];
        let mut out = [9.0f32; 3];
        Const.eval_batch(&wi, &wo, &mut out);
        // The batch length rule: outputs past the inputs are zeroed.
        assert_eq!(out, [0.25, 0.0, 0.0]);
    }
}
