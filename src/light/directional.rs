//! Directional (delta) lights.

use super::{
    Light, LightError, LightPart, PartVisitor, WideEstimate, check_radiance, visible_wo, zero_estimate,
};
use crate::brdf::Brdf;
use crate::frame::try_normalize;
use crate::integrator::{Estimate, IntegrateError, Integrator, Status};
use crate::radiometric;
use crate::spectrum::{Spectrum, WideSpectrum};
use glam::Vec3;

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

    fn for_each_part(&self, f: &mut PartVisitor<'_, S>) -> Result<(), IntegrateError> {
        f(LightPart::Directional(self))
    }
}

impl<S: Spectrum> Directional<S> {
    /// One BRDF evaluation: `f_r(ωl, ωo) E⊥ cos θl`, exact up to the `f32`
    /// rounding of that evaluation (reported error 0).
    pub(crate) fn reflect<B, I>(
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
