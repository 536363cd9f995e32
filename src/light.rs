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
//! | [`UniformSky`] | `L · ρ(ωo)`, `ρ` from the integrator on [`DirectionalAlbedo`] | one integration |
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
use crate::integrator::chunk::{brdf_eval_where, brdf_pdf_batch, brdf_sample_batch};
use crate::integrator::{
    CHUNK, DirectionalAlbedo, Estimate, Integrand, IntegrandSample, IntegrateError, Integrator, Status,
};
use crate::math::safe_sqrt;
use crate::radiometric;
use crate::spectrum::{Spectrum, WideSpectrum};
use crate::warp::{cosine_hemisphere_pdf, square_to_cosine_hemisphere, square_to_uniform_hemisphere};
use core::f32::consts::{FRAC_1_PI, FRAC_PI_2, TAU};
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
pub fn check_radiance<S: Spectrum>(s: S) -> Result<S, LightError> {
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
pub fn add_estimates<W: WideSpectrum>(a: Estimate<W>, b: Estimate<W>) -> Estimate<W> {
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
    /// zero here (their contribution is in [`Light::reflected_radiance`] and
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

    /// Irradiance as an [`Estimate`]: the closed form (zero error, zero
    /// evaluations) where one exists, otherwise an integration of
    /// `L(ω) cos θ` over the hemisphere with `integrator` and `budget`
    /// evaluations (per light that needs integration).
    fn irradiance_estimate<I: Integrator>(
        &self,
        integrator: &I,
        budget: u32,
    ) -> Result<WideEstimate<Self::Spectrum>, IntegrateError>;

    /// Reflected radiance `L_r(ωo) = ∫_H f_r(ωi, ωo) L(ωi) cos θi dωi` of
    /// this light off `brdf`, by the cheapest exact method for the light
    /// type (see the [module docs](self)). `wo` is the outgoing direction
    /// in the local frame (normalised here; zero or below the horizon gives
    /// an exact zero). `budget` is the evaluation budget of *each*
    /// integration a light needs; [`Estimate::evaluations`] counts all BRDF
    /// / integrand evaluations spent, and the error is the sum of the
    /// per-light errors.
    fn reflected_radiance<B, I>(
        &self,
        brdf: &B,
        wo: Vec3,
        integrator: &I,
        budget: u32,
    ) -> Result<WideEstimate<Self::Spectrum>, IntegrateError>
    where
        B: Brdf<Spectrum = Self::Spectrum>,
        I: Integrator;
}

/// Reflected radiance `L_r(ωo)` of `brdf` under `lights` (any [`Light`],
/// including sums), by the cheapest exact method per light:
/// [`Light::reflected_radiance`]. Reflection equation: Nicodemus et al.
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
    lights.reflected_radiance(brdf, wo, integrator, budget)
}

/// Irradiance on the surface from `lights`: closed forms where they exist,
/// integration (with `integrator`, `budget` per light) otherwise
/// ([`Light::irradiance_estimate`]).
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
    lights.irradiance_estimate(integrator, budget)
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

// ---------------------------------------------------------------------------
// Directional (delta) light
// ---------------------------------------------------------------------------

/// A directional (delta) light: parallel rays from unit direction `ωl`
/// (toward the light) with irradiance `E⊥` on a plane perpendicular to
/// them. Its irradiance on the surface is `E⊥ max(0, cos θl)` and its
/// reflected radiance `f_r(ωl, ωo) E⊥ cos θl` (the reflection equation with
/// `L_i = E⊥ δ(ω − ωl)`; PBR 4th ed. §12.4 "Distant lights").
///
/// ```
/// use radiometry::light::{Directional, Light};
/// use radiometry::glam::Vec3;
/// let d = Directional::new(Vec3::new(1.0, 0.0, 1.0), 2.0f32).unwrap();
/// assert!((d.irradiance() - 2.0 * core::f32::consts::FRAC_1_SQRT_2).abs() < 1e-6);
/// assert!(Directional::new(Vec3::ZERO, 1.0f32).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Directional<S> {
    direction: Vec3,
    irradiance: S,
}

impl<S: Spectrum> Directional<S> {
    /// A directional light toward `direction` (normalised here; must be
    /// finite and non-zero; may point below the horizon, then it
    /// contributes nothing) with perpendicular irradiance `e_perp` (each
    /// channel finite, in `[0, MAX_RADIANCE]`).
    pub fn new(direction: Vec3, e_perp: S) -> Result<Self, LightError> {
        let direction = try_normalize(direction).ok_or(LightError::InvalidDirection)?;
        Ok(Self {
            direction,
            irradiance: check_radiance(e_perp)?,
        })
    }

    /// The unit direction toward the light.
    pub fn direction(&self) -> Vec3 {
        self.direction
    }

    /// The perpendicular irradiance `E⊥`.
    pub fn normal_irradiance(&self) -> S {
        self.irradiance
    }

    /// Irradiance on the surface: `E⊥ max(0, cos θl)`
    /// ([`radiometric::directional_irradiance`]).
    pub fn irradiance(&self) -> S {
        radiometric::directional_irradiance(self.irradiance, self.direction.z)
    }
}

impl<S: Spectrum> Light for Directional<S> {
    type Spectrum = S;

    fn radiance(&self, _w: Vec3) -> S {
        S::zero()
    }

    fn has_delta(&self) -> bool {
        true
    }

    fn closed_form_irradiance(&self) -> Option<S> {
        Some(self.irradiance())
    }

    fn irradiance_estimate<I: Integrator>(&self, _: &I, _: u32) -> Result<WideEstimate<S>, IntegrateError> {
        Ok(exact(self.irradiance(), 0))
    }

    /// One BRDF evaluation: `f_r(ωl, ωo) E⊥ cos θl`, exact up to the `f32`
    /// rounding of that evaluation (reported error 0).
    fn reflected_radiance<B, I>(
        &self,
        brdf: &B,
        wo: Vec3,
        _: &I,
        _: u32,
    ) -> Result<WideEstimate<S>, IntegrateError>
    where
        B: Brdf<Spectrum = S>,
        I: Integrator,
    {
        let Some(wo) = visible_wo(wo) else {
            return Ok(zero_estimate::<S>());
        };
        let c = self.direction.z;
        if c <= 0.0 {
            return Ok(zero_estimate::<S>());
        }
        let f = brdf.eval(self.direction, wo);
        // Multiply in f64 so that a large E⊥ times a large f_r cannot overflow.
        let v = <S::Wide as WideSpectrum>::from_fn(|i| {
            f.channel(i) as f64 * self.irradiance.channel(i) as f64 * c as f64
        });
        Ok(Estimate {
            value: v,
            error: <S::Wide as WideSpectrum>::splat(0.0),
            evaluations: 1,
            status: Status::Resolved,
        })
    }
}

// ---------------------------------------------------------------------------
// Uniform sky
// ---------------------------------------------------------------------------

/// A uniform sky: radiance `L` from every direction of the upper hemisphere.
/// Irradiance `π L` (PBR 4th ed. §4.1.3, eq. 4.8); reflected radiance
/// `L_r(ωo) = L ∫_H f_r cos θi dωi = L ρ(ωo)`, the directional albedo times
/// `L` (the reflection equation with constant `L_i`).
///
/// ```
/// use radiometry::light::UniformSky;
/// let sky = UniformSky::new(2.0f32).unwrap();
/// assert!((sky.irradiance() - 2.0 * core::f32::consts::PI).abs() < 1e-6);
/// assert!(UniformSky::new(-1.0f32).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UniformSky<S> {
    radiance: S,
}

impl<S: Spectrum> UniformSky<S> {
    /// A sky of radiance `radiance` (each channel finite, in
    /// `[0, MAX_RADIANCE]`).
    pub fn new(radiance: S) -> Result<Self, LightError> {
        Ok(Self {
            radiance: check_radiance(radiance)?,
        })
    }

    /// The sky radiance `L`.
    pub fn sky_radiance(&self) -> S {
        self.radiance
    }

    /// Irradiance `π L` ([`radiometric::sky_irradiance`]).
    pub fn irradiance(&self) -> S {
        radiometric::sky_irradiance(self.radiance)
    }
}

impl<S: Spectrum> Light for UniformSky<S> {
    type Spectrum = S;

    fn radiance(&self, _w: Vec3) -> S {
        self.radiance
    }

    fn closed_form_irradiance(&self) -> Option<S> {
        Some(self.irradiance())
    }

    fn irradiance_estimate<I: Integrator>(&self, _: &I, _: u32) -> Result<WideEstimate<S>, IntegrateError> {
        Ok(exact(self.irradiance(), 0))
    }

    /// `L · ρ(ωo)` with `ρ` from `integrator` on [`DirectionalAlbedo`];
    /// error `L · err(ρ)` channel-wise. A black sky costs nothing.
    fn reflected_radiance<B, I>(
        &self,
        brdf: &B,
        wo: Vec3,
        integrator: &I,
        budget: u32,
    ) -> Result<WideEstimate<S>, IntegrateError>
    where
        B: Brdf<Spectrum = S>,
        I: Integrator,
    {
        let Some(wo) = visible_wo(wo) else {
            return Ok(zero_estimate::<S>());
        };
        if self.radiance.is_black() {
            return Ok(zero_estimate::<S>());
        }
        let rho = integrator.integrate(&DirectionalAlbedo { brdf, wo }, budget)?;
        Ok(Estimate {
            value: scale_wide(rho.value, self.radiance),
            error: scale_wide(rho.error, self.radiance),
            evaluations: rho.evaluations,
            status: rho.status,
        })
    }
}

// ---------------------------------------------------------------------------
// Spherical cap
// ---------------------------------------------------------------------------

/// A uniform spherical cap light: radiance `L` from every direction within
/// half-angle `σ` of a unit axis `ωa` (a distant sphere such as the sun,
/// `σ ≈ 4.65·10⁻³ rad`, or a spherical lamp of radius `r` at distance `d`,
/// `sin σ = r/d`). Irradiance in closed form including a cap partly below
/// the horizon ([`radiometric::cap_irradiance`]; Snyder 1996, MSR-TR-96-11;
/// Lagarde & de Rousiers 2014 §4.7.2). Reflected radiance integrates over
/// the visible part of the cap only ([`CapIntegrand`]).
///
/// ```
/// use radiometry::light::Cap;
/// use radiometry::glam::Vec3;
/// // A cap whose axis lies on the horizon: half of it is visible.
/// let cap = Cap::new(Vec3::X, 0.3, 1.0f32).unwrap();
/// let e = cap.irradiance();
/// assert!((e - (0.3 - libm::sinf(0.3) * libm::cosf(0.3))).abs() < 1e-6);
/// assert!(Cap::new(Vec3::Z, 0.0, 1.0f32).is_err());
/// assert!(Cap::new(Vec3::Z, 1.6, 1.0f32).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cap<S> {
    axis: Vec3,
    half_angle: f32,
    /// `sin²σ` and `cos²σ` (clamped ≥ 0), cached for [`Cap::contains`].
    sin2: f32,
    cos2: f32,
    radiance: S,
}

impl<S: Spectrum> Cap<S> {
    /// A cap around `axis` (normalised here; finite, non-zero; may point
    /// below the horizon) of half-angle `half_angle ∈ (0, π/2]` radians
    /// (`π/2` as the `f32` constant [`core::f32::consts::FRAC_PI_2`] is
    /// accepted) and radiance `radiance` (each channel finite, in
    /// `[0, MAX_RADIANCE]`).
    pub fn new(axis: Vec3, half_angle: f32, radiance: S) -> Result<Self, LightError> {
        let axis = try_normalize(axis).ok_or(LightError::InvalidDirection)?;
        if half_angle.is_nan() || half_angle <= 0.0 || half_angle > FRAC_PI_2 {
            return Err(LightError::HalfAngleOutOfRange(half_angle));
        }
        let (sn, cs) = libm::sincosf(half_angle);
        let cs = cs.max(0.0);
        Ok(Self {
            axis,
            half_angle,
            sin2: sn * sn,
            cos2: cs * cs,
            radiance: check_radiance(radiance)?,
        })
    }

    /// A cap given by its irradiance at normal incidence `E⊥ = π L sin²σ`
    /// ([`radiometric::cap_normal_irradiance`]), i.e. radiance
    /// `L = E⊥ / (π sin²σ)`: the extended counterpart of
    /// [`Directional::new`]`(axis, E⊥)`. Fails with
    /// [`LightError::RadianceTooLarge`] if `L` would exceed
    /// [`MAX_RADIANCE`].
    pub fn from_normal_irradiance(axis: Vec3, half_angle: f32, e_perp: S) -> Result<Self, LightError> {
        let e_perp = check_radiance(e_perp)?;
        if half_angle.is_nan() || half_angle <= 0.0 || half_angle > FRAC_PI_2 {
            return Err(LightError::HalfAngleOutOfRange(half_angle));
        }
        let s = libm::sinf(half_angle);
        // s > 0, but s² underflows to 0 for σ ≲ 1e-19, making k infinite.
        let k = FRAC_1_PI / (s * s);
        if !k.is_finite() {
            return Err(LightError::RadianceTooLarge);
        }
        // Compute per channel in f64 to detect overflow before rounding.
        let mut ok = true;
        let l = S::from_fn(|i| {
            let v = e_perp.channel(i) as f64 * k as f64;
            if v > MAX_RADIANCE as f64 {
                ok = false;
            }
            v as f32
        });
        if !ok {
            return Err(LightError::RadianceTooLarge);
        }
        Self::new(axis, half_angle, l)
    }

    /// The unit axis.
    pub fn axis(&self) -> Vec3 {
        self.axis
    }

    /// The half-angle σ (radians).
    pub fn half_angle(&self) -> f32 {
        self.half_angle
    }

    /// The radiance `L`.
    pub fn cap_radiance(&self) -> S {
        self.radiance
    }

    /// Solid angle of the whole cap, `2π(1 − cos σ)`
    /// ([`radiometric::cap_solid_angle`]).
    pub fn solid_angle(&self) -> f32 {
        radiometric::cap_solid_angle(self.half_angle)
    }

    /// Irradiance on the surface, horizon-clipped closed form
    /// ([`radiometric::cap_irradiance`]).
    pub fn irradiance(&self) -> S {
        radiometric::cap_irradiance(self.radiance, self.axis.z, self.half_angle)
    }

    /// Whether direction `w` (any finite vector) lies in the cap:
    /// angle(w, axis) ≤ σ, tested as `|w × a|² cos²σ ≤ (w·a)² sin²σ`
    /// with `w·a ≥ 0`, which stays exact for tiny caps (no `1 − cos`).
    pub fn contains(&self, w: Vec3) -> bool {
        let d = w.dot(self.axis);
        if d.is_nan() || d < 0.0 {
            return false;
        }
        let cross2 = w.cross(self.axis).length_squared();
        let w2 = w.length_squared();
        if w2.is_nan() || w2 <= 0.0 || !w2.is_finite() {
            return false;
        }
        cross2 * self.cos2 <= d * d * self.sin2
    }
}

impl<S: Spectrum> Light for Cap<S> {
    type Spectrum = S;

    fn radiance(&self, w: Vec3) -> S {
        if self.contains(w) {
            self.radiance
        } else {
            S::zero()
        }
    }

    fn closed_form_irradiance(&self) -> Option<S> {
        Some(self.irradiance())
    }

    fn irradiance_estimate<I: Integrator>(&self, _: &I, _: u32) -> Result<WideEstimate<S>, IntegrateError> {
        Ok(exact(self.irradiance(), 0))
    }

    /// Integrates `f_r L cos θi` over the visible part of the cap only
    /// ([`CapIntegrand`]). A cap entirely below the horizon, or black,
    /// costs nothing.
    fn reflected_radiance<B, I>(
        &self,
        brdf: &B,
        wo: Vec3,
        integrator: &I,
        budget: u32,
    ) -> Result<WideEstimate<S>, IntegrateError>
    where
        B: Brdf<Spectrum = S>,
        I: Integrator,
    {
        let Some(wo) = visible_wo(wo) else {
            return Ok(zero_estimate::<S>());
        };
        if self.radiance.is_black()
            || radiometric::cap_projected_solid_angle(self.axis.z, self.half_angle) <= 0.0
        {
            return Ok(zero_estimate::<S>());
        }
        integrator.integrate(&CapIntegrand::new(brdf, wo, self), budget)
    }
}

/// The reflection integrand of a [`Cap`] light, reparametrised so that its
/// integral over the *hemisphere* equals the integral of
/// `f_r(ωi, ωo) L cos θi` over the *visible part of the cap only*; any
/// hemisphere [`Integrator`] then spends all its nodes on the cap.
///
/// Construction (a change of variables, PBR 4th ed. §2.4.1): with cap
/// coordinates `(α, β)` — α the angle from the axis, β the azimuth about
/// it — and `v = 1 − cos α = 2 sin²(α/2)`, the solid angle is
/// `dω = dv dβ`. For each β the visible α form an interval
/// `[α_lo(β), α_hi(β)] ⊆ [0, σ]` (the horizon `ω_z = 0` is
/// `cos θa cos α − sin θa cos β sin α = 0`, solved for α with `atan2`).
/// A hemisphere direction `ω' = (sin θ' cos φ', sin θ' sin φ', cos θ')`
/// maps to `β = φ'` (unclipped cap; see below for the clipped case) and
/// `v = v_lo + (1 − cos θ')(v_hi − v_lo)`, so
/// `dω = J dω'` with `J(β) = v_hi(β) − v_lo(β)` and
///
/// `∫_H g'(ω') dω' = ∫_{cap ∩ H} f_r L cos θ dω`, `g'(ω') = J f_r(ω(ω'), ωo) L cos θ(ω')`.
///
/// `g'` is smooth in `cos θ'`. In φ' it is smooth and periodic when the
/// cap is entirely above the horizon (`β = φ'`). When the horizon clips
/// the cap, `J(β)` has kinks at `β = ±β*`, `cos β* = cot σ cos θa / sin θa`
/// (where the horizon starts to cut the radial segments), and for an axis
/// at or below the horizon `J = 0` on `|β| < β*`. Then φ' is mapped
/// piecewise onto the visible β-pieces (`[−β*, β*]` on `φ' ∈ [0, π)`, the
/// rest on `[π, 2π)`; or only `|β| > β*` over all of φ'), each through
/// Sidi's sin²-transform (Sidi 1993), whose Jacobian vanishes to second
/// order at the piece ends, so the kinks no longer slow quadrature down
/// and no node is spent on the invisible part. The Jacobian `dβ/dφ'`
/// multiplies `g'`. Its sampling map is uniform on the hemisphere
/// (density `1/2π`). Using `v`
/// instead of `cos α` keeps full precision for tiny caps (the sun).
///
/// ```
/// use radiometry::light::{Cap, CapIntegrand};
/// use radiometry::integrator::{GaussLegendre, Integrator};
/// use radiometry::{Brdf, glam::Vec3};
/// struct One;
/// impl Brdf for One {
///     type Spectrum = f32;
///     fn eval(&self, _: Vec3, _: Vec3) -> f32 { 1.0 }
/// }
/// // With f_r = 1 the integral is the cap irradiance.
/// let cap = Cap::new(Vec3::new(1.0, 0.0, 0.1), 0.4, 1.0f32).unwrap();
/// let e = GaussLegendre::new().integrate(&CapIntegrand::new(One, Vec3::Z, &cap), 5000).unwrap();
/// assert!((e.value - cap.irradiance() as f64).abs() < 1e-5);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct CapIntegrand<B: Brdf> {
    brdf: B,
    wo: Vec3,
    radiance: B::Spectrum,
    /// Cap axis and its orthonormal complement (local frame).
    a: Vec3,
    e1: Vec3,
    e2: Vec3,
    /// cos θa, sin θa of the axis.
    c: f32,
    s: f32,
    sigma: f32,
    sin_sigma: f32,
    v_sigma: f32,
    azimuth: Azimuth,
}

/// How the hemisphere azimuth φ' maps to the cap azimuth β.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Azimuth {
    /// Cap fully above the horizon: `β = φ'`.
    Full,
    /// Axis above the horizon, cap partly below: `|β| < β*` is clipped from
    /// above, `|β| > β*` is whole; each half of φ' covers one piece.
    Split(f32),
    /// Axis at or below the horizon: only `|β| > β*` is visible (clipped
    /// from below); all of φ' covers it.
    Lower(f32),
}

/// Sidi's sin²-transform `S(t) = t − sin(2πt)/(2π)` on `[0, 1]` and its
/// derivative `S'(t) = 2 sin²(πt)` (Sidi 1993, "A new variable
/// transformation for numerical integration", Int. Ser. Numer. Math. 112):
/// it flattens the integrand at both ends of a piece, so a kink at a piece
/// boundary becomes a jump in a high derivative only.
#[inline]
fn sidi(t: f32) -> (f32, f32) {
    let t = t.clamp(0.0, 1.0);
    let (s2, _) = libm::sincosf(TAU * t);
    let s1 = libm::sinf(core::f32::consts::PI * t);
    ((t - s2 / TAU).clamp(0.0, 1.0), 2.0 * s1 * s1)
}

/// `v(α) = 1 − cos α = 2 sin²(α/2)` without cancellation.
#[inline]
fn versine(alpha: f32) -> f32 {
    let h = libm::sinf(0.5 * alpha);
    2.0 * h * h
}

impl<B: Brdf> CapIntegrand<B> {
    /// The integrand for `brdf`, outgoing direction `wo` (as given) and the
    /// cap `cap`.
    pub fn new(brdf: B, wo: Vec3, cap: &Cap<B::Spectrum>) -> Self {
        let a = cap.axis;
        let c = a.z.clamp(-1.0, 1.0);
        let s = libm::hypotf(a.x, a.y).min(1.0);
        let (cp, sp) = if s > 0.0 { (a.x / s, a.y / s) } else { (1.0, 0.0) };
        let e1 = Vec3::new(c * cp, c * sp, -s);
        let e2 = Vec3::new(-sp, cp, 0.0);
        let (ss, cs) = libm::sincosf(cap.half_angle);
        let (ss, cs) = (ss.clamp(0.0, 1.0), cs.clamp(0.0, 1.0));
        let azimuth = if c >= ss || s <= 0.0 {
            Azimuth::Full
        } else {
            // The azimuth where clipping starts: cos β* = −y, with
            // y = −cot σ · cos θa / sin θa (see radiometric::cap_projected_solid_angle).
            let y = (-(c / ss) * (cs / s)).clamp(-1.0, 1.0);
            let beta_star = libm::acosf(-y);
            if c > 0.0 {
                Azimuth::Split(beta_star)
            } else {
                Azimuth::Lower(beta_star)
            }
        };
        Self {
            brdf,
            wo,
            radiance: cap.radiance,
            a,
            e1,
            e2,
            c,
            s,
            sigma: cap.half_angle,
            sin_sigma: libm::sinf(cap.half_angle),
            v_sigma: versine(cap.half_angle),
            azimuth,
        }
    }

    /// The visible `[v_lo, v_hi]` at azimuth with cosine `cos_b`, or `None`.
    #[inline]
    fn v_range(&self, cos_b: f32) -> Option<(f32, f32)> {
        let c = self.c;
        if c >= self.sin_sigma {
            return Some((0.0, self.v_sigma));
        }
        // Visible ⇔ c cos α − k sin α ≥ 0, α ∈ [0, σ].
        let k = self.s * cos_b;
        if k > 0.0 {
            if c <= 0.0 {
                return None;
            }
            let hi = libm::atan2f(c, k);
            if hi >= self.sigma {
                Some((0.0, self.v_sigma))
            } else {
                Some((0.0, versine(hi)))
            }
        } else if c >= 0.0 {
            Some((0.0, self.v_sigma))
        } else if k == 0.0 {
            None
        } else {
            let lo = libm::atan2f(-c, -k);
            if lo >= self.sigma {
                None
            } else {
                Some((versine(lo), self.v_sigma))
            }
        }
    }

    /// Cap azimuth β and `dβ/dφ'` for the hemisphere azimuth `φ' ∈ [0, 2π]`.
    #[inline]
    fn beta(&self, phi: f32) -> (f32, f32) {
        let pi = core::f32::consts::PI;
        match self.azimuth {
            Azimuth::Full => (phi, 1.0),
            Azimuth::Lower(bs) => {
                let width = TAU - 2.0 * bs;
                let (st, ds) = sidi(phi / TAU);
                (bs + width * st, width * ds / TAU)
            }
            Azimuth::Split(bs) => {
                if phi < pi {
                    let (st, ds) = sidi(phi / pi);
                    (-bs + 2.0 * bs * st, 2.0 * bs * ds / pi)
                } else {
                    let width = TAU - 2.0 * bs;
                    let (st, ds) = sidi((phi - pi) / pi);
                    (bs + width * st, width * ds / pi)
                }
            }
        }
    }

    /// Where `g'` at `u0 = 1 − cos θ' ∈ [0,1]` and hemisphere azimuth `φ'`
    /// needs the BRDF.
    #[inline]
    fn point_at(&self, u0: f32, phi: f32) -> CapPoint {
        let (beta, dbeta) = self.beta(phi);
        if dbeta <= 0.0 {
            return CapPoint { w: None, dbeta: None };
        }
        let (sb, cb) = libm::sincosf(beta);
        CapPoint {
            w: self.point_param(u0, cb, sb),
            dbeta: Some(dbeta),
        }
    }

    /// The direction `ω` and the factor `cos θ · J` of `g'` (without the
    /// azimuth Jacobian) at `u0 = 1 − cos θ' ∈ [0,1]` and cap azimuth
    /// `(cos β, sin β)`; `None` where `g'` is zero.
    #[inline]
    fn point_param(&self, u0: f32, cos_b: f32, sin_b: f32) -> Option<(Vec3, f32)> {
        let (v_lo, v_hi) = self.v_range(cos_b)?;
        let jac = v_hi - v_lo;
        if jac.is_nan() || jac <= 0.0 {
            return None;
        }
        let v = (v_lo + u0.clamp(0.0, 1.0) * jac).min(v_hi);
        let sin_a = safe_sqrt(v * (2.0 - v));
        let cos_a = 1.0 - v;
        let w = cos_a * self.a + sin_a * (cos_b * self.e1 + sin_b * self.e2);
        let cz = w.z;
        if cz.is_nan() || cz <= 0.0 {
            return None;
        }
        Some((w, cz * jac))
    }

    /// Where [`Integrand::eval`] at the hemisphere direction `w` needs the BRDF.
    #[inline]
    fn point(&self, w: Vec3) -> CapPoint {
        let u0 = 1.0 - w.z.clamp(0.0, 1.0);
        if self.azimuth == Azimuth::Full {
            // β = φ': no trigonometry needed.
            let r = libm::hypotf(w.x, w.y);
            let (cb, sb) = if r > 0.0 && r.is_finite() {
                (w.x / r, w.y / r)
            } else {
                (1.0, 0.0)
            };
            return CapPoint {
                w: self.point_param(u0, cb, sb),
                dbeta: None,
            };
        }
        self.point_at(u0, crate::frame::spherical_phi(w))
    }

    /// `g' = ((f_r L) · cos θ J) · dβ/dφ'` from `f = f_r(ω, ωo)` at `p`.
    #[inline]
    fn finish(&self, f: B::Spectrum, p: &CapPoint) -> B::Spectrum {
        let base = match p.w {
            Some((_, s)) => f * self.radiance * s,
            None => B::Spectrum::zero(),
        };
        match p.dbeta {
            Some(d) => base * d,
            None => base,
        }
    }

    /// `g'` at `p` (one BRDF evaluation where needed).
    #[inline]
    fn value(&self, p: &CapPoint) -> B::Spectrum {
        let f = match p.w {
            Some((w, _)) => self.brdf.eval(w, self.wo),
            None => B::Spectrum::zero(),
        };
        self.finish(f, p)
    }

    /// `out[k] = g'(p[k])` with one [`Brdf::eval_batch`] over the points
    /// that need the BRDF (`p.len() ≤ CHUNK`).
    fn values(&self, p: &[CapPoint], out: &mut [B::Spectrum]) {
        let mut wi = [None; CHUNK];
        let n = p.len().min(out.len()).min(CHUNK);
        for (d, p) in wi[..n].iter_mut().zip(p) {
            *d = p.w.map(|(w, _)| w);
        }
        brdf_eval_where(&self.brdf, self.wo, &wi[..n], &mut out[..n]);
        for (o, p) in out[..n].iter_mut().zip(p) {
            *o = self.finish(*o, p);
        }
    }
}

/// Where the cap integrand needs the BRDF: the direction with the factor
/// `cos θ · J` (`None`: zero), and the azimuth Jacobian to apply (`None`:
/// none).
#[derive(Clone, Copy, Debug)]
struct CapPoint {
    w: Option<(Vec3, f32)>,
    dbeta: Option<f32>,
}

impl<B: Brdf> Integrand for CapIntegrand<B> {
    type Spectrum = B::Spectrum;

    #[inline]
    fn eval(&self, w: Vec3) -> B::Spectrum {
        self.value(&self.point(w))
    }

    fn has_sampling_map(&self) -> bool {
        true
    }

    /// Uniform on the hemisphere (`cos θ' = 1 − u₀`, `φ' = 2π u₁`), density
    /// `1/2π`; the value is computed from `u` directly.
    #[inline]
    fn sample(&self, u: [f32; 2]) -> Option<IntegrandSample<B::Spectrum>> {
        let u0 = u[0].clamp(0.0, 1.0);
        let w = square_to_uniform_hemisphere([1.0 - u0, u[1]]);
        Some(IntegrandSample {
            w,
            pdf: 0.5 * FRAC_1_PI,
            value: self.value(&self.point_at(u0, TAU * u[1].clamp(0.0, 1.0))),
        })
    }

    #[inline]
    fn pdf(&self, w: Vec3) -> f32 {
        if w.z >= 0.0 { 0.5 * FRAC_1_PI } else { 0.0 }
    }

    /// As [`Integrand::eval`], with one [`Brdf::eval_batch`] per chunk over
    /// the points inside the visible cap.
    fn eval_batch(&self, w: &[Vec3], out: &mut [B::Spectrum]) {
        let mut p = [CapPoint { w: None, dbeta: None }; CHUNK];
        for (w, out) in w.chunks(CHUNK).zip(out.chunks_mut(CHUNK)) {
            let n = w.len().min(out.len());
            for (p, &w) in p[..n].iter_mut().zip(w) {
                *p = self.point(w);
            }
            self.values(&p[..n], &mut out[..n]);
        }
    }

    /// As [`Integrand::sample`], with one [`Brdf::eval_batch`] per chunk.
    fn sample_batch(&self, u: &[[f32; 2]], out: &mut [Option<IntegrandSample<B::Spectrum>>]) {
        let mut p = [CapPoint { w: None, dbeta: None }; CHUNK];
        let mut v = [B::Spectrum::zero(); CHUNK];
        for (u, out) in u.chunks(CHUNK).zip(out.chunks_mut(CHUNK)) {
            let n = u.len().min(out.len());
            for (p, u) in p[..n].iter_mut().zip(u) {
                *p = self.point_at(u[0].clamp(0.0, 1.0), TAU * u[1].clamp(0.0, 1.0));
            }
            self.values(&p[..n], &mut v[..n]);
            for ((o, u), &value) in out[..n].iter_mut().zip(u).zip(&v[..n]) {
                let u0 = u[0].clamp(0.0, 1.0);
                *o = Some(IntegrandSample {
                    w: square_to_uniform_hemisphere([1.0 - u0, u[1]]),
                    pdf: 0.5 * FRAC_1_PI,
                    value,
                });
            }
        }
    }
}

// ---------------------------------------------------------------------------
// Environment
// ---------------------------------------------------------------------------

/// A general environment: radiance `L(ω)` given by a caller's function of
/// the direction (local frame, unit, toward the light). No closed form:
/// irradiance and reflected radiance integrate over the whole hemisphere
/// ([`EnvironmentIntegrand`]).
///
/// The function must return finite, non-negative radiance on the upper
/// hemisphere (it cannot be validated up front; a NaN/∞ value surfaces as
/// [`IntegrateError::NonFiniteIntegrand`] from the integrator).
///
/// ```
/// use radiometry::light::{Environment, Light};
/// use radiometry::integrator::GaussLegendre;
/// use radiometry::glam::Vec3;
/// // A sky brighter toward the zenith: L = 1 + cos θ, E = π + 2π/3.
/// let env = Environment::new(|w: Vec3| 1.0 + w.z);
/// let e = env.irradiance_estimate(&GaussLegendre::new(), 100).unwrap();
/// assert!((e.value - 5.0 * core::f64::consts::PI / 3.0).abs() < 1e-5);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Environment<F> {
    f: F,
}

impl<F> Environment<F> {
    /// Wraps a radiance function `L(ω)`.
    pub const fn new(f: F) -> Self {
        Self { f }
    }

    /// The wrapped function.
    pub fn function(&self) -> &F {
        &self.f
    }
}

impl<S: Spectrum, F: Fn(Vec3) -> S> Light for Environment<F> {
    type Spectrum = S;

    fn radiance(&self, w: Vec3) -> S {
        match try_normalize(w) {
            Some(w) => (self.f)(w),
            None => S::zero(),
        }
    }

    fn closed_form_irradiance(&self) -> Option<S> {
        None
    }

    /// `∫_H L(ω) cos θ dω` by `integrator`; the integrand's sampling map is
    /// cosine-weighted.
    fn irradiance_estimate<I: Integrator>(
        &self,
        integrator: &I,
        budget: u32,
    ) -> Result<WideEstimate<S>, IntegrateError> {
        integrator.integrate(&EnvironmentIrradiance { f: &self.f }, budget)
    }

    /// Full-hemisphere integration of `f_r L cos θi` ([`EnvironmentIntegrand`]).
    fn reflected_radiance<B, I>(
        &self,
        brdf: &B,
        wo: Vec3,
        integrator: &I,
        budget: u32,
    ) -> Result<WideEstimate<S>, IntegrateError>
    where
        B: Brdf<Spectrum = S>,
        I: Integrator,
    {
        let Some(wo) = visible_wo(wo) else {
            return Ok(zero_estimate::<S>());
        };
        integrator.integrate(
            &EnvironmentIntegrand {
                brdf,
                wo,
                light: self,
            },
            budget,
        )
    }
}

/// `g(ω) = L(ω) cos θ` of an environment function, sampled cosine-weighted.
struct EnvironmentIrradiance<'a, F> {
    f: &'a F,
}

impl<S: Spectrum, F: Fn(Vec3) -> S> Integrand for EnvironmentIrradiance<'_, F> {
    type Spectrum = S;

    fn eval(&self, w: Vec3) -> S {
        if w.z <= 0.0 {
            return S::zero();
        }
        (self.f)(w) * w.z
    }

    fn has_sampling_map(&self) -> bool {
        true
    }

    fn sample(&self, u: [f32; 2]) -> Option<IntegrandSample<S>> {
        let w = square_to_cosine_hemisphere(u);
        let pdf = cosine_hemisphere_pdf(w);
        if pdf.is_nan() || pdf <= 0.0 {
            return None;
        }
        Some(IntegrandSample {
            w,
            pdf,
            value: self.eval(w),
        })
    }

    fn pdf(&self, w: Vec3) -> f32 {
        cosine_hemisphere_pdf(w)
    }
}

/// The full reflection integrand `g(ωi) = f_r(ωi, ωo) L(ωi) cos θi` of any
/// [`Light`] (through [`Light::radiance`], so delta components are
/// absent), over the whole hemisphere. Its sampling map is the BRDF's
/// ([`Brdf::sample`]), as for [`DirectionalAlbedo`].
///
/// This is what [`Environment`] integrates; for other lights it is the
/// *brute-force* path that the shortcuts of [`Light::reflected_radiance`]
/// agree with (exactly for smooth radiance; the hard cap edge makes
/// hemisphere quadrature of it converge slowly).
///
/// ```
/// use radiometry::light::{EnvironmentIntegrand, UniformSky};
/// use radiometry::integrator::{GaussLegendre, Integrator};
/// use radiometry::{Brdf, glam::Vec3};
/// struct Lambert;
/// impl Brdf for Lambert {
///     type Spectrum = f32;
///     fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
///         if wi.z > 0.0 && wo.z > 0.0 { 0.5 / core::f32::consts::PI } else { 0.0 }
///     }
/// }
/// let sky = UniformSky::new(2.0f32).unwrap();
/// let g = EnvironmentIntegrand { brdf: Lambert, wo: Vec3::Z, light: &sky };
/// let e = GaussLegendre::new().integrate(&g, 100).unwrap();
/// assert!((e.value - 1.0).abs() < 1e-6);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct EnvironmentIntegrand<'a, B, L: ?Sized> {
    /// The BRDF.
    pub brdf: B,
    /// Outgoing direction (local frame).
    pub wo: Vec3,
    /// The light whose [`Light::radiance`] is integrated.
    pub light: &'a L,
}

impl<B: Brdf, L: Light<Spectrum = B::Spectrum> + ?Sized> Integrand for EnvironmentIntegrand<'_, B, L> {
    type Spectrum = B::Spectrum;

    #[inline]
    fn eval(&self, w: Vec3) -> B::Spectrum {
        let c = w.z;
        if c <= 0.0 {
            return B::Spectrum::zero();
        }
        let l = self.light.radiance(w);
        if l.is_black() {
            return B::Spectrum::zero();
        }
        self.brdf.eval(w, self.wo) * l * c
    }

    fn has_sampling_map(&self) -> bool {
        true
    }

    #[inline]
    fn sample(&self, u: [f32; 2]) -> Option<IntegrandSample<B::Spectrum>> {
        let s = self.brdf.sample(self.wo, u)?;
        Some(IntegrandSample {
            w: s.wi,
            pdf: s.pdf,
            value: s.weight * s.pdf * self.light.radiance(s.wi),
        })
    }

    #[inline]
    fn pdf(&self, w: Vec3) -> f32 {
        self.brdf.pdf(w, self.wo)
    }

    /// As [`Integrand::eval`]: [`Light::radiance`] point by point, then one
    /// [`Brdf::eval_batch`] per chunk over the points above the horizon
    /// with non-black radiance.
    fn eval_batch(&self, w: &[Vec3], out: &mut [B::Spectrum]) {
        let mut l = [B::Spectrum::zero(); CHUNK];
        let mut wi = [None; CHUNK];
        for (w, out) in w.chunks(CHUNK).zip(out.chunks_mut(CHUNK)) {
            let n = w.len().min(out.len());
            for ((l, d), &w) in l[..n].iter_mut().zip(&mut wi[..n]).zip(w) {
                *d = None;
                if w.z <= 0.0 {
                    continue;
                }
                *l = self.light.radiance(w);
                if !l.is_black() {
                    *d = Some(w);
                }
            }
            brdf_eval_where(&self.brdf, self.wo, &wi[..n], &mut out[..n]);
            for (((o, l), d), &w) in out[..n].iter_mut().zip(&l[..n]).zip(&wi[..n]).zip(w) {
                *o = match d {
                    Some(_) => *o * *l * w.z,
                    None => B::Spectrum::zero(),
                };
            }
        }
    }

    /// [`Brdf::sample_batch`] with `wo` broadcast, then the radiance at each
    /// sampled direction, as [`Integrand::sample`].
    fn sample_batch(&self, u: &[[f32; 2]], out: &mut [Option<IntegrandSample<B::Spectrum>>]) {
        brdf_sample_batch(&self.brdf, self.wo, u, out, |s| {
            s.weight * s.pdf * self.light.radiance(s.wi)
        });
    }

    /// [`Brdf::pdf_batch`] with `wo` broadcast.
    fn pdf_batch(&self, w: &[Vec3], out: &mut [f32]) {
        brdf_pdf_batch(&self.brdf, self.wo, w, out);
    }
}

// ---------------------------------------------------------------------------
// Sums
// ---------------------------------------------------------------------------

impl<L: Light + ?Sized> Light for &L {
    type Spectrum = L::Spectrum;
    fn radiance(&self, w: Vec3) -> Self::Spectrum {
        (**self).radiance(w)
    }
    fn has_delta(&self) -> bool {
        (**self).has_delta()
    }
    fn closed_form_irradiance(&self) -> Option<Self::Spectrum> {
        (**self).closed_form_irradiance()
    }
    fn irradiance_estimate<I: Integrator>(
        &self,
        integrator: &I,
        budget: u32,
    ) -> Result<WideEstimate<Self::Spectrum>, IntegrateError> {
        (**self).irradiance_estimate(integrator, budget)
    }
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
        (**self).reflected_radiance(brdf, wo, integrator, budget)
    }
}

/// A homogeneous sum of lights (e.g. several suns). Empty: no light.
impl<L: Light> Light for [L] {
    type Spectrum = L::Spectrum;
    fn radiance(&self, w: Vec3) -> Self::Spectrum {
        self.iter()
            .fold(L::Spectrum::zero(), |acc, l| acc + l.radiance(w))
    }
    fn has_delta(&self) -> bool {
        self.iter().any(|l| l.has_delta())
    }
    fn closed_form_irradiance(&self) -> Option<Self::Spectrum> {
        self.iter().try_fold(L::Spectrum::zero(), |acc, l| {
            Some(acc + l.closed_form_irradiance()?)
        })
    }
    fn irradiance_estimate<I: Integrator>(
        &self,
        integrator: &I,
        budget: u32,
    ) -> Result<WideEstimate<Self::Spectrum>, IntegrateError> {
        let mut acc = zero_estimate::<L::Spectrum>();
        for l in self {
            acc = add_estimates(acc, l.irradiance_estimate(integrator, budget)?);
        }
        Ok(acc)
    }
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
        let mut acc = zero_estimate::<L::Spectrum>();
        for l in self {
            acc = add_estimates(acc, l.reflected_radiance(brdf, wo, integrator, budget)?);
        }
        Ok(acc)
    }
}

impl<L: Light, const N: usize> Light for [L; N] {
    type Spectrum = L::Spectrum;
    fn radiance(&self, w: Vec3) -> Self::Spectrum {
        self.as_slice().radiance(w)
    }
    fn has_delta(&self) -> bool {
        self.as_slice().has_delta()
    }
    fn closed_form_irradiance(&self) -> Option<Self::Spectrum> {
        self.as_slice().closed_form_irradiance()
    }
    fn irradiance_estimate<I: Integrator>(
        &self,
        integrator: &I,
        budget: u32,
    ) -> Result<WideEstimate<Self::Spectrum>, IntegrateError> {
        self.as_slice().irradiance_estimate(integrator, budget)
    }
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
        self.as_slice().reflected_radiance(brdf, wo, integrator, budget)
    }
}

macro_rules! tuple_light {
    ($first:ident $(, $rest:ident)*) => {
        /// A heterogeneous sum of lights with the same spectrum.
        impl<$first: Light, $($rest: Light<Spectrum = $first::Spectrum>),*> Light for ($first, $($rest,)*) {
            type Spectrum = $first::Spectrum;
            #[allow(non_snake_case)]
            fn radiance(&self, w: Vec3) -> Self::Spectrum {
                let ($first, $($rest,)*) = self;
                $first.radiance(w) $(+ $rest.radiance(w))*
            }
            #[allow(non_snake_case)]
            fn has_delta(&self) -> bool {
                let ($first, $($rest,)*) = self;
                $first.has_delta() $(|| $rest.has_delta())*
            }
            #[allow(non_snake_case, clippy::needless_question_mark)]
            fn closed_form_irradiance(&self) -> Option<Self::Spectrum> {
                let ($first, $($rest,)*) = self;
                Some($first.closed_form_irradiance()? $(+ $rest.closed_form_irradiance()?)*)
            }
            #[allow(non_snake_case)]
            fn irradiance_estimate<I: Integrator>(
                &self,
                integrator: &I,
                budget: u32,
            ) -> Result<WideEstimate<Self::Spectrum>, IntegrateError> {
                let ($first, $($rest,)*) = self;
                let acc = $first.irradiance_estimate(integrator, budget)?;
                $(let acc = add_estimates(acc, $rest.irradiance_estimate(integrator, budget)?);)*
                Ok(acc)
            }
            #[allow(non_snake_case)]
            fn reflected_radiance<Br, I>(
                &self,
                brdf: &Br,
                wo: Vec3,
                integrator: &I,
                budget: u32,
            ) -> Result<WideEstimate<Self::Spectrum>, IntegrateError>
            where
                Br: Brdf<Spectrum = Self::Spectrum>,
                I: Integrator,
            {
                let ($first, $($rest,)*) = self;
                let acc = $first.reflected_radiance(brdf, wo, integrator, budget)?;
                $(let acc = add_estimates(acc, $rest.reflected_radiance(brdf, wo, integrator, budget)?);)*
                Ok(acc)
            }
        }
    };
}

tuple_light!(A);
tuple_light!(A, B);
tuple_light!(A, B, C);
tuple_light!(A, B, C, D);
tuple_light!(A, B, C, D, E);
tuple_light!(A, B, C, D, E, F);

mod cap_sampling;
pub use cap_sampling::{CapSampled, CapStrategy};
