//! The uniform sky.

use super::{
    Light, LightError, LightPart, PartVisitor, WideEstimate, check_radiance, scale_wide, visible_wo,
    zero_estimate,
};
use crate::brdf::Brdf;
use crate::integrator::{DirectionalAlbedo, Estimate, IntegrateError, Integrator};
use crate::radiometric;
use crate::spectrum::Spectrum;
use glam::Vec3;

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

    fn for_each_part(&self, f: &mut PartVisitor<'_, S>) -> Result<(), IntegrateError> {
        f(LightPart::Sky(self))
    }
}

impl<S: Spectrum> UniformSky<S> {
    /// `L · ρ(ωo)` with `ρ` from `integrator` on [`DirectionalAlbedo`];
    /// error `L · err(ρ)` channel-wise. A black sky costs nothing.
    pub(crate) fn reflect<B, I>(
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
