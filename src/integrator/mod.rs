//! Hemisphere integrators: estimate `∫_H g(ω) dω` and report an honest
//! error.
//!
//! An [`Integrand`] is a [`Spectrum`]-valued function on the upper
//! hemisphere that may offer an importance-sampling map. An
//! [`Integrator`] turns an integrand and an evaluation budget into an
//! [`Estimate`]: the value, an error estimate (standard error for Monte
//! Carlo, an a-posteriori bound for quadrature), and the number of
//! integrand evaluations actually spent. Integrators are deterministic for
//! a given configuration (including its seed), never allocate, and
//! accumulate in `f64` with compensated summation.
//!
//! Integrators (name strings for reports in parentheses):
//! * [`GaussLegendre`] (`"gauss-legendre"`): product rule in `(cos θ, φ)`;
//! * [`WarpedGaussLegendre`] (`"gauss-legendre-warped"`): the same on the
//!   unit square of the integrand's sampling map; with
//!   [`WarpedGaussLegendre::horizon_split`]
//!   (`"gauss-legendre-warped-split"`), split at the steps of the map's
//!   support (the horizon pre-image);
//! * [`Adaptive`] (`"adaptive"`, `"adaptive-warped"`): Genz–Malik adaptive
//!   cubature, to a tolerance;
//! * [`MonteCarlo`] (`"mc-{uniform,cosine,integrand}-{prng,stratified,sobol,fibonacci}"`,
//!   `"mis-{balance,power}-…"`): Monte Carlo and randomized QMC;
//! * [`Auto`] (`"auto"`): picks a parameterisation from what the integrand
//!   offers (a nested Clenshaw–Curtis × trapezoid grid on the plain
//!   hemisphere for broad lobes, the staged warped [`Adaptive`] rule for
//!   narrow ones) and reuses its work between refinements;
//! * [`integrate_to_tolerance`]: refinement to a tolerance for any of them,
//!   stopping only on a confirmed estimate.
//!
//! [`DirectionalAlbedo`] adapts a [`Brdf`] and an outgoing direction into
//! the integrand `g(ωi) = f_r(ωi, ωo) cos θi`, whose integral is the
//! directional albedo `ρ(ωo)`.
//!
//! Every integrator evaluates its nodes or sample points in chunks of
//! [`CHUNK`] through [`Integrand::eval_batch`], [`Integrand::sample_batch`]
//! and [`Integrand::pdf_batch`] (fixed-size stack buffers), and accumulates
//! the values in point order, so an estimate is the same, bit for bit, as
//! that of a point-by-point loop whenever the batch methods agree with the
//! scalar ones. [`DirectionalAlbedo`] and the light integrands of
//! [`crate::light`] forward the chunks to [`Brdf::eval_batch`] /
//! [`Brdf::sample_batch`] / [`Brdf::pdf_batch`], which is how vectorised
//! BRDF kernels reach integration.

use crate::brdf::Brdf;
use crate::frame::cos_theta;
use crate::spectrum::{Spectrum, WideSpectrum};
use chunk::{brdf_pdf_batch, brdf_sample_batch};
use core::fmt;
use glam::Vec3;

/// One draw from an integrand's importance-sampling map.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IntegrandSample<S> {
    /// The sampled direction (unit, upper hemisphere).
    pub w: Vec3,
    /// Its density w.r.t. solid angle, `> 0`.
    pub pdf: f32,
    /// `g(w)`: the integrand at the sample (so a sample costs one evaluation).
    pub value: S,
}

/// A function on the upper hemisphere to integrate with respect to solid
/// angle.
pub trait Integrand {
    /// The value type.
    type Spectrum: Spectrum;

    /// `g(ω)` for a unit `ω` with `ω.z ≥ 0`.
    fn eval(&self, w: Vec3) -> Self::Spectrum;

    /// Whether [`Integrand::sample`] and [`Integrand::pdf`] provide an
    /// importance-sampling map. Integrators that need one (importance
    /// sampling, MIS, warped quadrature) return
    /// [`IntegrateError::NoSamplingMap`] when this is `false`.
    fn has_sampling_map(&self) -> bool {
        false
    }

    /// Whether `g` is a smooth (analytic) function of `ω` on the open upper
    /// hemisphere (see [`Brdf::is_smooth`]): then
    /// [`Auto`] may integrate a peaked `g` on a chart centred on its peak.
    /// Default `false`.
    fn is_smooth(&self) -> bool {
        false
    }

    /// Where `g` may fail to be smooth on the plain hemisphere, if it says:
    /// the line `μ = cos θ = mu` and the azimuths with `cos(φ − phi) = 0`.
    /// The plain [`Adaptive`] rule puts its first cuts there, so that no
    /// region straddles them. Default `None`.
    fn kinks(&self) -> Option<Kinks> {
        None
    }

    /// Maps `u ∈ [0,1)²` to a direction with its density and the integrand
    /// value there, or `None` where the map produces no valid direction
    /// (a zero-contribution sample). Default: `None`.
    fn sample(&self, u: [f32; 2]) -> Option<IntegrandSample<Self::Spectrum>> {
        let _ = u;
        None
    }

    /// The number of components of the sampling map, `K ≥ 1`: a mixture map
    /// picks component `k` with probability
    /// [`component_weight`](Integrand::component_weight)`(k)` (`c_k`, summing
    /// to 1) and draws from that component's own map
    /// ([`component_sample_batch`](Integrand::component_sample_batch)), so
    /// that [`Integrand::pdf`] is `Σ_k c_k p_k` (see
    /// [`Brdf::sampling_components`]). The warped [`Adaptive`] rule then
    /// integrates `Σ_k c_k ∫ g(ω_k(u))/pdf(ω_k(u)) du`, each term on its own
    /// smooth square, instead of the whole map with its seams. Default 1
    /// (the whole map).
    fn sampling_components(&self) -> usize {
        1
    }

    /// The weight `c_k ∈ [0, 1]` of component `k` of the sampling map (see
    /// [`sampling_components`](Integrand::sampling_components)); 0 for `k`
    /// out of range. Default: 1 for `k = 0`.
    fn component_weight(&self, k: usize) -> f64 {
        if k == 0 { 1.0 } else { 0.0 }
    }

    /// [`Integrand::sample_batch`] through component `k` of the sampling map:
    /// `out[j]` is the draw of component `k` at `u[j]` with its direction
    /// `w`, the *mixture* density `pdf = pdf(w)` (not the component's own)
    /// and `value = g(w)`, or `None` where the component draws no direction
    /// (or the mixture density there is not positive); elements past
    /// `u.len()` are set to `None`. Default: component 0 is
    /// [`Integrand::sample_batch`], every other `None`.
    fn component_sample_batch(
        &self,
        k: usize,
        u: &[[f32; 2]],
        out: &mut [Option<IntegrandSample<Self::Spectrum>>],
    ) {
        if k == 0 {
            self.sample_batch(u, out);
        } else {
            crate::batch::zero_tail(out, 0);
        }
    }

    /// Density of [`Integrand::sample`] at `w` [sr⁻¹]. Default: `0`.
    fn pdf(&self, w: Vec3) -> f32 {
        let _ = w;
        0.0
    }

    /// `out[k] = g(w[k])` for `k < min(w.len(), out.len())`; elements of
    /// `out` past `w.len()` are set to zero (the
    /// [batch length rule](crate::batch::zero_tail)).
    ///
    /// The integrators evaluate through this method, [`CHUNK`] points at a
    /// time, so an integrand wrapping a vectorised kernel (such as
    /// [`Brdf::eval_batch`]) hands the whole chunk on. An override must
    /// return what [`Integrand::eval`] returns at each point (bit for bit
    /// where the kernel allows: estimates then do not depend on batching).
    /// The default loops over [`Integrand::eval`].
    ///
    /// ```
    /// use radiometry::integrator::Integrand;
    /// use radiometry::glam::Vec3;
    /// struct Cos;
    /// impl Integrand for Cos {
    ///     type Spectrum = f32;
    ///     fn eval(&self, w: Vec3) -> f32 { w.z }
    /// }
    /// let mut out = [9.0f32; 3];
    /// Cos.eval_batch(&[Vec3::Z, Vec3::X], &mut out);
    /// assert_eq!(out, [1.0, 0.0, 0.0]);
    /// ```
    fn eval_batch(&self, w: &[Vec3], out: &mut [Self::Spectrum]) {
        for (o, &v) in out.iter_mut().zip(w) {
            *o = self.eval(v);
        }
        crate::batch::zero_tail(out, w.len());
    }

    /// `out[k] = sample(u[k])` for `k < min(u.len(), out.len())`; elements
    /// of `out` past `u.len()` are set to `None`. Same contract as
    /// [`Integrand::eval_batch`] (agree with [`Integrand::sample`] at every
    /// point). The default loops over [`Integrand::sample`].
    fn sample_batch(&self, u: &[[f32; 2]], out: &mut [Option<IntegrandSample<Self::Spectrum>>]) {
        for (o, &v) in out.iter_mut().zip(u) {
            *o = self.sample(v);
        }
        crate::batch::zero_tail(out, u.len());
    }

    /// `out[k] = pdf(w[k])` [sr⁻¹] for `k < min(w.len(), out.len())`; elements
    /// of `out` past `w.len()` are set to zero. Same contract as
    /// [`Integrand::eval_batch`]. The default loops over [`Integrand::pdf`].
    fn pdf_batch(&self, w: &[Vec3], out: &mut [f32]) {
        for (o, &v) in out.iter_mut().zip(w) {
            *o = self.pdf(v);
        }
        crate::batch::zero_tail(out, w.len());
    }
}

/// A reference to an integrand is an integrand, so `&dyn Integrand` (chosen
/// at run time) goes through every integrator's generic entry point:
///
/// ```
/// use radiometry::integrator::{GaussLegendre, Integrand, Integrator};
/// use radiometry::glam::Vec3;
/// struct Cos;
/// impl Integrand for Cos {
///     type Spectrum = f32;
///     fn eval(&self, w: Vec3) -> f32 { w.z }
/// }
/// let g: &dyn Integrand<Spectrum = f32> = &Cos;
/// let e = GaussLegendre::new().integrate(&g, 256).unwrap();
/// // ∫_H cos θ dω = π.
/// assert!((e.value - core::f64::consts::PI).abs() < 1e-6);
/// ```
impl<T: Integrand + ?Sized> Integrand for &T {
    type Spectrum = T::Spectrum;
    #[inline]
    fn eval(&self, w: Vec3) -> Self::Spectrum {
        (**self).eval(w)
    }
    #[inline]
    fn has_sampling_map(&self) -> bool {
        (**self).has_sampling_map()
    }
    #[inline]
    fn is_smooth(&self) -> bool {
        (**self).is_smooth()
    }
    #[inline]
    fn kinks(&self) -> Option<Kinks> {
        (**self).kinks()
    }
    #[inline]
    fn sample(&self, u: [f32; 2]) -> Option<IntegrandSample<Self::Spectrum>> {
        (**self).sample(u)
    }
    #[inline]
    fn sampling_components(&self) -> usize {
        (**self).sampling_components()
    }
    #[inline]
    fn component_weight(&self, k: usize) -> f64 {
        (**self).component_weight(k)
    }
    #[inline]
    fn component_sample_batch(
        &self,
        k: usize,
        u: &[[f32; 2]],
        out: &mut [Option<IntegrandSample<Self::Spectrum>>],
    ) {
        (**self).component_sample_batch(k, u, out)
    }
    #[inline]
    fn pdf(&self, w: Vec3) -> f32 {
        (**self).pdf(w)
    }
    #[inline]
    fn eval_batch(&self, w: &[Vec3], out: &mut [Self::Spectrum]) {
        (**self).eval_batch(w, out)
    }
    #[inline]
    fn sample_batch(&self, u: &[[f32; 2]], out: &mut [Option<IntegrandSample<Self::Spectrum>>]) {
        (**self).sample_batch(u, out)
    }
    #[inline]
    fn pdf_batch(&self, w: &[Vec3], out: &mut [f32]) {
        (**self).pdf_batch(w, out)
    }
}

/// Lines of the plain `(μ, φ)` hemisphere where an integrand may have a
/// kink ([`Integrand::kinks`]): `μ = mu` and `cos(φ − phi) = 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Kinks {
    /// The polar cosine of the kink line `μ = mu`.
    pub mu: f64,
    /// The azimuth (radians) whose perpendiculars `phi ± π/2` are kink lines.
    pub phi: f64,
}

/// The result of an integration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Estimate<W> {
    /// The estimate of `∫_H g dω`, per channel.
    pub value: W,
    /// Error estimate per channel: the standard error for Monte Carlo and
    /// randomized QMC, an a-posteriori estimate for quadrature.
    pub error: W,
    /// Integrand evaluations spent (sampling-map draws count as one each).
    pub evaluations: u64,
    /// Whether the integrator stands behind `error` (see [`Status`]).
    pub status: Status,
}

impl<W> Estimate<W> {
    /// Whether the estimate is [`Status::Resolved`].
    #[inline]
    pub fn is_resolved(&self) -> bool {
        self.status.is_resolved()
    }
}

/// Why an integration could not produce an estimate.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum IntegrateError {
    /// The budget is too small for this integrator (e.g. zero); `minimum`
    /// is the smallest budget it accepts.
    BudgetTooSmall {
        /// Smallest accepted budget.
        minimum: u32,
    },
    /// The integrator needs an importance-sampling map and the integrand
    /// has none.
    NoSamplingMap,
    /// The integrand returned NaN or ±∞ at some point; no estimate is
    /// reported (a NaN never leaks into a result).
    NonFiniteIntegrand,
    /// The configuration is invalid (message names the field).
    InvalidConfig(&'static str),
}

impl fmt::Display for IntegrateError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            IntegrateError::BudgetTooSmall { minimum } => {
                write!(
                    f,
                    "budget too small: this integrator needs at least {minimum} evaluations"
                )
            }
            IntegrateError::NoSamplingMap => {
                write!(
                    f,
                    "this integrator needs an integrand with an importance-sampling map"
                )
            }
            IntegrateError::NonFiniteIntegrand => {
                write!(f, "the integrand returned NaN or infinity")
            }
            IntegrateError::InvalidConfig(m) => write!(f, "invalid integrator configuration: {m}"),
        }
    }
}

impl core::error::Error for IntegrateError {}

/// The wide (f64) value type of an integrand's spectrum.
pub type WideOf<I> = <<I as Integrand>::Spectrum as Spectrum>::Wide;

/// Estimates `∫_H g(ω) dω` within an evaluation budget.
pub trait Integrator {
    /// Integrates `g` spending at most `budget` evaluations (an integrator
    /// may spend fewer, e.g. a product rule rounds down to a square; the
    /// spent count is in [`Estimate::evaluations`]).
    fn integrate<I: Integrand>(&self, g: &I, budget: u32) -> Result<Estimate<WideOf<I>>, IntegrateError>;

    /// A short, stable name for reports (`"gauss-legendre"`, `"mc-cosine"`, …).
    fn name(&self) -> &'static str;

    /// The slowest rate `r` at which this integrator's error estimate falls
    /// with the evaluations `N` (`∝ N^-r`) once its status is resolved, if
    /// one is guaranteed: `0.5` for Monte Carlo (the standard error), `None`
    /// (the default) for quadrature, whose error can stall and then drop.
    /// [`by_doubling`] uses it to stop early when a tolerance is out of reach.
    fn error_decay(&self) -> Option<f64> {
        None
    }

    /// The most evaluations any run of this integrator spends, whatever
    /// its budget, if it has such a cap (Monte Carlo: 2²⁰). [`by_doubling`]
    /// stops at the cap instead of repeating the capped run. Default: `None`.
    fn max_evaluations(&self) -> Option<u64> {
        None
    }

    /// Refines to the absolute tolerance `tol` (largest channel), spending
    /// at most `max_budget` evaluations in the last run; called by
    /// [`integrate_to_tolerance`] (which checks the arguments first). The
    /// default is the confirming budget-doubling driver [`by_doubling`]; an
    /// integrator that can refine its own work (as [`Adaptive`] does)
    /// overrides it. An override must keep the contract of
    /// [`StopReason::ToleranceReached`]: a resolved estimate with error
    /// `≤ tol`, confirmed beyond one run.
    fn to_tolerance<I: Integrand>(
        &self,
        g: &I,
        tol: f64,
        start_budget: u32,
        max_budget: u32,
    ) -> Result<ToleranceOutcome<WideOf<I>>, IntegrateError>
    where
        Self: Sized,
    {
        by_doubling(self, g, tol, start_budget, max_budget)
    }
}

/// The integrand `g(ωi) = f_r(ωi, ωo) cos θi` whose integral over the
/// hemisphere is the directional albedo `ρ(ωo) = ∫_H f_r(ωi,ωo) cos θi dωi`
/// (reflectance for uniform incident radiance). Its sampling map is the
/// BRDF's own [`Brdf::sample`].
#[derive(Clone, Copy, Debug)]
pub struct DirectionalAlbedo<B> {
    /// The BRDF.
    pub brdf: B,
    /// The outgoing (viewing) direction, local frame.
    pub wo: Vec3,
}

impl<B: Brdf> Integrand for DirectionalAlbedo<B> {
    type Spectrum = B::Spectrum;

    #[inline]
    fn eval(&self, w: Vec3) -> B::Spectrum {
        let c = cos_theta(w);
        if c <= 0.0 {
            return B::Spectrum::zero();
        }
        self.brdf.eval(w, self.wo) * c
    }

    fn has_sampling_map(&self) -> bool {
        true
    }

    /// `f_r cos θi` is as smooth as the BRDF says.
    fn is_smooth(&self) -> bool {
        self.brdf.is_smooth()
    }

    /// `μi = μo` and `cos(φi − φo) = 0`: where the isotropic lobes of the
    /// Oren–Nayar family switch terms (`max(0, cos Δφ)`, `min`/`max` of
    /// `μi`, `μo`; Oren & Nayar 1994, Eq. 30; Fujii 2012; Portsmouth et al.
    /// 2025), and the lines through the mirror direction `(μo, φo + π)` of
    /// every isotropic lobe.
    fn kinks(&self) -> Option<Kinks> {
        Some(Kinks {
            mu: self.wo.z as f64,
            phi: libm::atan2(self.wo.y as f64, self.wo.x as f64),
        })
    }

    #[inline]
    fn sample(&self, u: [f32; 2]) -> Option<IntegrandSample<B::Spectrum>> {
        let s = self.brdf.sample(self.wo, u)?;
        Some(IntegrandSample {
            w: s.wi,
            pdf: s.pdf,
            value: s.weight * s.pdf,
        })
    }

    #[inline]
    fn pdf(&self, w: Vec3) -> f32 {
        self.brdf.pdf(w, self.wo)
    }

    /// The BRDF's components ([`Brdf::sampling_components`]).
    fn sampling_components(&self) -> usize {
        self.brdf.sampling_components()
    }

    /// [`Brdf::component_weight`] at `ωo`.
    fn component_weight(&self, k: usize) -> f64 {
        let c = self.brdf.component_weight(self.wo, k);
        if c.is_finite() {
            c.clamp(0.0, 1.0) as f64
        } else {
            0.0
        }
    }

    /// [`Brdf::sample_component`]'s directions above the horizon, then one
    /// [`Brdf::eval_batch`] and one [`Brdf::pdf_batch`] per [`CHUNK`] over
    /// them (`value = f_r cos θi`, `pdf` the mixture's). A BRDF of one
    /// component: [`Integrand::sample_batch`].
    fn component_sample_batch(
        &self,
        k: usize,
        u: &[[f32; 2]],
        out: &mut [Option<IntegrandSample<B::Spectrum>>],
    ) {
        if self.brdf.sampling_components() <= 1 {
            if k == 0 {
                self.sample_batch(u, out);
            } else {
                crate::batch::zero_tail(out, 0);
            }
            return;
        }
        chunk::brdf_component_batch(&self.brdf, self.wo, k, u, out);
    }

    /// [`Brdf::eval_batch`] with `wo` broadcast, then `· cos θi` (zero at
    /// and below the horizon), as [`Integrand::eval`] does.
    fn eval_batch(&self, w: &[Vec3], out: &mut [B::Spectrum]) {
        crate::batch::zero_tail(out, w.len());
        let wo = [self.wo; CHUNK];
        for (w, out) in w.chunks(CHUNK).zip(out.chunks_mut(CHUNK)) {
            let n = w.len().min(out.len());
            self.brdf.eval_batch(&w[..n], &wo[..n], &mut out[..n]);
            for (o, &wi) in out[..n].iter_mut().zip(w) {
                let c = cos_theta(wi);
                *o = if c <= 0.0 { B::Spectrum::zero() } else { *o * c };
            }
        }
    }

    /// [`Brdf::sample_batch`] with `wo` broadcast; value `weight · pdf` as
    /// in [`Integrand::sample`].
    fn sample_batch(&self, u: &[[f32; 2]], out: &mut [Option<IntegrandSample<B::Spectrum>>]) {
        brdf_sample_batch(&self.brdf, self.wo, u, out, |s| s.weight * s.pdf);
    }

    /// [`Brdf::pdf_batch`] with `wo` broadcast.
    fn pdf_batch(&self, w: &[Vec3], out: &mut [f32]) {
        brdf_pdf_batch(&self.brdf, self.wo, w, out);
    }
}

/// Checks that every channel of `v` is finite.
#[inline]
pub(crate) fn check_finite<W: WideSpectrum>(v: W) -> Result<W, IntegrateError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(IntegrateError::NonFiniteIntegrand)
    }
}

mod acc;
pub(crate) mod chunk;
mod confirm;
pub mod gauss_legendre;
pub mod points;
mod sobol;
mod sobol_table;

pub use gauss_legendre::{GaussLegendre, WarpedGaussLegendre};
pub mod monte_carlo;

pub use monte_carlo::{Heuristic, MonteCarlo, Strategy};
pub use points::PointSet;
pub mod adaptive;

pub use adaptive::Adaptive;
pub mod auto;
pub use auto::Auto;
mod chart;
pub use chunk::CHUNK;
pub mod probe;
mod status;
mod tolerance;

pub use status::{MIN_EFFECTIVE_SAMPLES, MIN_HITS, Status, Unresolved};

pub use tolerance::{
    DEFAULT_MAX_BUDGET, OUT_OF_REACH_FACTOR, StopReason, ToleranceOutcome, by_doubling, check_tolerance_args,
    integrate_to_tolerance,
};
