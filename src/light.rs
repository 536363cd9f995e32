//! Lights and illumination: directional (delta) lights, a uniform sky,
//! uniform spherical caps (sun, spherical lamp), general environment
//! functions, and heap-free sums of these; and the reflection equation
//! `L_r(ωo) = ∫_H f_r(ωi, ωo) L_i(ωi) cos θi dωi` (Nicodemus et al. 1977,
//! NBS Monograph 160; PBR 4th ed. §4.3.1 eq. 4.14) evaluated per light with
//! the cheapest *exact* method:
//!
//! | light | method | cost |
//! |---|---|---|
//! | [`Directional`] (delta) | `f_r(ωl, ωo) E⊥ cos θl` | one BRDF evaluation |
//! | [`UniformSky`] | `L · ρ(ωo)`, `ρ` from the integrator on [`DirectionalAlbedo`](crate::integrator::DirectionalAlbedo) | one integration |
//! | [`Cap`] | integration over the (horizon-clipped) cap only, [`CapIntegrand`] | one integration |
//! | [`Environment`] | full-hemisphere integration, [`EnvironmentIntegrand`] | one integration |
//!
//! Every light lives in the local shading frame (normal `+Z`); directions
//! point *away* from the surface, toward the light. Sums are tuples
//! (`(A, B)`, … up to 6), arrays `[L; N]` and slices `[L]`, all
//! implementing [`Light`] without allocation.
//!
//! ```
//! use radiometry::light::{Cap, Directional, Light, UniformSky, reflected_radiance};
//! use radiometry::integrator::GaussLegendre;
//! use radiometry::{Brdf, glam::Vec3};
//! use core::f32::consts::PI;
//!
//! struct Lambert(f32);
//! impl Brdf for Lambert {
//!     type Spectrum = f32;
//!     fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
//!         if wi.z > 0.0 && wo.z > 0.0 { self.0 / PI } else { 0.0 }
//!     }
//! }
//! let sun = Cap::new(Vec3::new(0.3, 0.0, 1.0), 0.00465, 2.0e7)?;
//! let sky = UniformSky::new(1.0e3)?;
//! let lamp = Directional::new(Vec3::Z, 10.0)?;
//! let lights = (sun, sky, lamp);
//! let wo = Vec3::new(0.0, 0.6, 0.8);
//! let lr = reflected_radiance(&Lambert(0.5), &lights, wo, &GaussLegendre::new(), 400)?;
//! // For a Lambertian surface L_r = ρ E / π, with E in closed form:
//! let e = lights.closed_form_irradiance().unwrap();
//! assert!((lr.value - 0.5 * e as f64 / core::f64::consts::PI).abs() <= 1e-5 * lr.value + lr.error);
//! # Ok::<(), Box<dyn core::error::Error>>(())
//! ```

use crate::brdf::Brdf;
use crate::frame::try_normalize;
use crate::integrator::{Estimate, IntegrateError, Integrator, Status};
use crate::spectrum::{Spectrum, WideSpectrum};
use core::fmt;
use glam::Vec3;

/// The `f64` result type of a light with spectrum `S`.
pub type WideEstimate<S> = Estimate<<S as Spectrum>::Wide>;

/// Largest radiance (and irradiance) a light accepts, per channel:
/// `10³⁰`. It leaves room for `π L`, BRDF values up to `10⁷ sr⁻¹` and the
/// `1/sin²σ` of tiny caps without overflowing `f32`. (The sun's luminance
/// is `≈ 1.6·10⁹ cd/m²`, its radiance `≈ 2·10⁷ W/(m² sr)`.)
pub const MAX_RADIANCE: f32 = 1e30;

/// Why a light could not be constructed.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum LightError {
    /// A radiance / irradiance channel is NaN or infinite.
    NonFiniteRadiance,
    /// A radiance / irradiance channel is negative.
    NegativeRadiance,
    /// A radiance / irradiance channel exceeds [`MAX_RADIANCE`].
    RadianceTooLarge,
    /// The cap half-angle (radians) is not in `(0, π/2]`.
    HalfAngleOutOfRange(f32),
    /// The direction / axis vector is zero or not finite.
    InvalidDirection,
}

impl fmt::Display for LightError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LightError::NonFiniteRadiance => write!(f, "radiance must be finite (got NaN or infinity)"),
            LightError::NegativeRadiance => write!(f, "radiance must be non-negative"),
            LightError::RadianceTooLarge => {
                write!(f, "radiance exceeds the maximum of {MAX_RADIANCE:e}")
            }
            LightError::HalfAngleOutOfRange(a) => {
                write!(f, "cap half-angle must be in (0, π/2] radians, got {a}")
            }
            LightError::InvalidDirection => {
                write!(f, "light direction must be a finite, non-zero vector")
            }
        }
    }
}

impl core::error::Error for LightError {}

/// Checks that every channel is finite, non-negative and ≤ [`MAX_RADIANCE`].
pub(crate) fn check_radiance<S: Spectrum>(s: S) -> Result<S, LightError> {
    for i in 0..S::CHANNELS {
        let v = s.channel(i);
        if !v.is_finite() {
            return Err(LightError::NonFiniteRadiance);
        }
        if v < 0.0 {
            return Err(LightError::NegativeRadiance);
        }
        if v > MAX_RADIANCE {
            return Err(LightError::RadianceTooLarge);
        }
    }
    Ok(s)
}

/// An exact estimate (zero error).
#[inline]
fn exact<S: Spectrum>(value: S, evaluations: u64) -> WideEstimate<S> {
    Estimate {
        value: value.to_wide(),
        error: <S::Wide as WideSpectrum>::splat(0.0),
        evaluations,
        status: Status::Resolved,
    }
}

/// The zero estimate.
#[inline]
fn zero_estimate<S: Spectrum>() -> WideEstimate<S> {
    exact(S::zero(), 0)
}

/// Sum of two estimates: values add, errors add (a conservative bound that
/// holds whether the errors are quadrature bounds or standard errors),
/// evaluations add (saturating).
#[inline]
pub(crate) fn add_estimates<W: WideSpectrum>(a: Estimate<W>, b: Estimate<W>) -> Estimate<W> {
    Estimate {
        value: a.value.zip(b.value, |x, y| x + y),
        error: a.error.zip(b.error, |x, y| x + y),
        evaluations: a.evaluations.saturating_add(b.evaluations),
        status: a.status.combine(b.status),
    }
}

/// A light (or a sum of lights) illuminating a surface with normal `+Z`.
///
/// Implemented by [`Directional`], [`UniformSky`], [`Cap`], [`Environment`],
/// tuples of lights with the same spectrum (up to 6), arrays `[L; N]`,
/// slices `[L]` and references.
pub trait Light {
    /// The spectrum type of radiance and irradiance.
    type Spectrum: Spectrum;

    /// Incident radiance `L(ω)` arriving from direction `ω` (pointing away
    /// from the surface toward the light), for any finite `ω`; directions
    /// need not be unit. Delta lights have no finite radiance and return
    /// zero here (their contribution is in [`LightIntegrals::reflected_radiance`] and
    /// the irradiance methods). Below-horizon directions return the light's
    /// radiance there (it does not reach the surface: integrals are over
    /// the upper hemisphere only).
    fn radiance(&self, w: Vec3) -> Self::Spectrum;

    /// Whether the light contains a delta (directional) component, which
    /// [`Light::radiance`] cannot represent.
    fn has_delta(&self) -> bool {
        false
    }

    /// Irradiance `E = ∫_H L cos θ dω` on the surface in closed form, when
    /// one exists (every light except [`Environment`]); `None` otherwise.
    fn closed_form_irradiance(&self) -> Option<Self::Spectrum>;

    /// Calls `f` once for each component light, as one of the kinds the
    /// crate knows how to integrate exactly ([`LightPart`]); a sum visits
    /// its terms in order. This is what makes [`Light`] object-safe: the
    /// integrations of [`LightIntegrals`] are generic over the BRDF and the
    /// integrator, and run over the parts, so they work the same for a
    /// concrete light, a sum and a `&dyn Light`. A light of a new kind
    /// reports itself as [`LightPart::Environment`] (its
    /// [`Light::radiance`] integrated over the hemisphere).
    fn for_each_part(&self, f: &mut PartVisitor<'_, Self::Spectrum>) -> Result<(), IntegrateError>;
}

/// The callback of [`Light::for_each_part`]: called once per part; an
/// error stops the visit and is returned.
pub type PartVisitor<'v, S> = dyn FnMut(LightPart<'_, S>) -> Result<(), IntegrateError> + 'v;

/// One component of a light, as [`Light::for_each_part`] reports it: the
/// kind decides the exact method of the reflection equation (module table).
#[derive(Clone, Copy)]
#[non_exhaustive]
pub enum LightPart<'a, S: Spectrum> {
    /// A delta light: one BRDF evaluation.
    Directional(&'a Directional<S>),
    /// A uniform sky: `L · ρ(ωo)`, one albedo integration.
    Sky(&'a UniformSky<S>),
    /// A uniform cap: an integration over the visible cap only.
    Cap(&'a Cap<S>),
    /// Any radiance function: a full-hemisphere integration of
    /// [`Light::radiance`] ([`EnvironmentIntegrand`]).
    Environment(&'a dyn Light<Spectrum = S>),
}

impl<S: Spectrum> fmt::Debug for LightPart<'_, S> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LightPart::Directional(d) => f.debug_tuple("Directional").field(d).finish(),
            LightPart::Sky(s) => f.debug_tuple("Sky").field(s).finish(),
            LightPart::Cap(c) => f.debug_tuple("Cap").field(c).finish(),
            LightPart::Environment(_) => f.write_str("Environment(..)"),
        }
    }
}

/// The integrals of any [`Light`] (also `dyn Light`, slices and sums):
/// irradiance and reflected radiance, per [part](Light::for_each_part) by
/// the cheapest exact method, summed (values and errors add; evaluations
/// add). Implemented for every light; bring it into scope (it is in the
/// [prelude](crate::prelude)) to call the methods.
///
/// ```
/// use radiometry::light::{Directional, Light, LightIntegrals, UniformSky};
/// use radiometry::integrator::GaussLegendre;
/// use radiometry::{Brdf, glam::Vec3};
/// struct Lambert;
/// impl Brdf for Lambert {
///     type Spectrum = f32;
///     fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
///         if wi.z > 0.0 && wo.z > 0.0 { 0.5 / core::f32::consts::PI } else { 0.0 }
///     }
/// }
/// // Lights chosen at run time, behind `&dyn Light`.
/// let sky = UniformSky::new(2.0f32)?;
/// let sun = Directional::new(Vec3::Z, 3.0f32)?;
/// let lights: [&dyn Light<Spectrum = f32>; 2] = [&sky, &sun];
/// let e = lights.irradiance_estimate(&GaussLegendre::new(), 100)?;
/// assert!((e.value - (2.0 * core::f64::consts::PI + 3.0)).abs() < 1e-5);
/// let lr = lights.reflected_radiance(&Lambert, Vec3::Z, &GaussLegendre::new(), 400)?;
/// assert!((lr.value - 0.5 * e.value / core::f64::consts::PI).abs() < 1e-5);
/// # Ok::<(), Box<dyn core::error::Error>>(())
/// ```
pub trait LightIntegrals: Light {
    /// Irradiance as an [`Estimate`]: the closed form (zero error, zero
    /// evaluations) where one exists, otherwise an integration of
    /// `L(ω) cos θ` over the hemisphere with `integrator` and `budget`
    /// evaluations (per part that needs integration).
    fn irradiance_estimate<I: Integrator>(
        &self,
        integrator: &I,
        budget: u32,
    ) -> Result<WideEstimate<Self::Spectrum>, IntegrateError> {
        let mut acc = zero_estimate::<Self::Spectrum>();
        self.for_each_part(&mut |part| {
            let e = match part {
                LightPart::Directional(d) => exact(d.irradiance(), 0),
                LightPart::Sky(s) => exact(s.irradiance(), 0),
                LightPart::Cap(c) => exact(c.irradiance(), 0),
                LightPart::Environment(l) => {
                    integrator.integrate(&environment::EnvironmentIrradiance { light: l }, budget)?
                }
            };
            acc = add_estimates(acc, e);
            Ok(())
        })?;
        Ok(acc)
    }

    /// Reflected radiance `L_r(ωo) = ∫_H f_r(ωi, ωo) L(ωi) cos θi dωi` of
    /// this light off `brdf`, by the cheapest exact method per part (see the
    /// [module docs](self)). `wo` is the outgoing direction in the local
    /// frame (normalised here; zero or below the horizon gives an exact
    /// zero). `budget` is the evaluation budget of *each* integration a part
    /// needs; [`Estimate::evaluations`] counts all BRDF / integrand
    /// evaluations spent, and the error is the sum of the per-part errors.
    fn reflected_radiance<B, I>(
        &self,
        brdf: &B,
        wo: Vec3,
        integrator: &I,
        budget: u32,
    ) -> Result<WideEstimate<Self::Spectrum>, IntegrateError>
    where
        B: Brdf<Spectrum = Self::Spectrum>,
        I: Integrator,
    {
        let mut acc = zero_estimate::<Self::Spectrum>();
        self.for_each_part(&mut |part| {
            let e = match part {
                LightPart::Directional(d) => d.reflect(brdf, wo, integrator, budget)?,
                LightPart::Sky(s) => s.reflect(brdf, wo, integrator, budget)?,
                LightPart::Cap(c) => c.reflect(brdf, wo, integrator, budget)?,
                LightPart::Environment(l) => match visible_wo(wo) {
                    Some(wo) => integrator.integrate(&EnvironmentIntegrand { brdf, wo, light: l }, budget)?,
                    None => zero_estimate::<Self::Spectrum>(),
                },
            };
            acc = add_estimates(acc, e);
            Ok(())
        })?;
        Ok(acc)
    }
}

impl<L: Light + ?Sized> LightIntegrals for L {}

/// Reflected radiance `L_r(ωo)` of `brdf` under `lights` (any [`Light`],
/// including sums), by the cheapest exact method per light:
/// [`LightIntegrals::reflected_radiance`]. Reflection equation: Nicodemus et al.
/// 1977; PBR 4th ed. §4.3.1, eq. 4.14.
///
/// Domain: `wo` any finite vector (normalised; zero or `wo.z ≤ 0` gives
/// zero); `budget` per integrated light. Errors are the integrator's
/// ([`IntegrateError`]), e.g. a budget below its minimum.
#[inline]
pub fn reflected_radiance<B, L, I>(
    brdf: &B,
    lights: &L,
    wo: Vec3,
    integrator: &I,
    budget: u32,
) -> Result<WideEstimate<B::Spectrum>, IntegrateError>
where
    B: Brdf,
    L: Light<Spectrum = B::Spectrum> + ?Sized,
    I: Integrator,
{
    LightIntegrals::reflected_radiance(lights, brdf, wo, integrator, budget)
}

/// Irradiance on the surface from `lights`: closed forms where they exist,
/// integration (with `integrator`, `budget` per light) otherwise
/// ([`LightIntegrals::irradiance_estimate`]).
#[inline]
pub fn irradiance<L, I>(
    lights: &L,
    integrator: &I,
    budget: u32,
) -> Result<WideEstimate<L::Spectrum>, IntegrateError>
where
    L: Light + ?Sized,
    I: Integrator,
{
    LightIntegrals::irradiance_estimate(lights, integrator, budget)
}

/// Normalises `wo`; `None` when it is zero, non-finite or at/below the
/// horizon (where every BRDF is zero by the [`Brdf`] contract).
#[inline]
fn visible_wo(wo: Vec3) -> Option<Vec3> {
    let wo = try_normalize(wo)?;
    if wo.z > 0.0 { Some(wo) } else { None }
}

/// Channel-wise product of a wide value and an `f32` spectrum.
#[inline]
fn scale_wide<S: Spectrum>(w: S::Wide, s: S) -> S::Wide {
    <S::Wide as WideSpectrum>::from_fn(|i| w.channel(i) * s.channel(i) as f64)
}

mod cap;
mod directional;
mod environment;
mod sums;
mod uniform_sky;

pub use cap::{Cap, CapIntegrand};
pub use directional::Directional;
pub use environment::{Environment, EnvironmentIntegrand};
pub use uniform_sky::UniformSky;
mod cap_sampling;
pub use cap_sampling::{CapSampled, CapStrategy};
