//! [`Scaled`]: a lobe times a non-negative spectrum.

use super::ComposeError;
use crate::batch::Vec3Soa;
use crate::brdf::{Albedo, Brdf, BrdfSample, IsotropicBrdf};
use crate::spectrum::Spectrum;
use glam::Vec3;

/// A lobe scaled per channel by a colour or weight `s ≥ 0`,
///
/// ```text
/// f(ωi, ωo) = s ⊙ f_B(ωi, ωo),   E(ωo) = s ⊙ E_B(ωo),
/// ```
///
/// sampled exactly as `B` (same `ωi` and density; the weight times `s`).
/// OpenPBR's `fuzz_color`, `specular_color` and layer weights are such
/// factors; energy is conserved when every channel of `s` is `≤ 1`.
///
/// ```
/// use radiometry::compose::Scaled;
/// use radiometry::{Brdf, glam::Vec3};
/// # struct Flat;
/// # impl Brdf for Flat {
/// #     type Spectrum = Vec3;
/// #     fn eval(&self, wi: Vec3, wo: Vec3) -> Vec3 {
/// #         if wi.z > 0.0 && wo.z > 0.0 { Vec3::splat(core::f32::consts::FRAC_1_PI) } else { Vec3::ZERO }
/// #     }
/// # }
/// let red = Scaled::new(Flat, Vec3::new(0.8, 0.1, 0.1))?;
/// assert!((red.eval(Vec3::Z, Vec3::Z).x - 0.8 * core::f32::consts::FRAC_1_PI).abs() < 1e-7);
/// assert!(Scaled::new(Flat, Vec3::new(-0.1, 0.0, 0.0)).is_err());
/// # Ok::<(), radiometry::compose::ComposeError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scaled<B, S> {
    lobe: B,
    scale: S,
}

impl<B: Brdf<Spectrum = S>, S: Spectrum> Scaled<B, S> {
    /// `s ⊙ f_B`; every channel of `s` must be finite and `≥ 0`.
    pub fn new(lobe: B, scale: S) -> Result<Self, ComposeError> {
        for i in 0..S::CHANNELS {
            let c = scale.channel(i);
            if !c.is_finite() || c < 0.0 {
                return Err(ComposeError::Scale(c));
            }
        }
        Ok(Self { lobe, scale })
    }

    /// The scaled lobe.
    pub fn lobe(&self) -> &B {
        &self.lobe
    }

    /// The factor `s`.
    pub fn scale(&self) -> S {
        self.scale
    }
}

impl<B: Brdf<Spectrum = S>, S: Spectrum> Brdf for Scaled<B, S> {
    type Spectrum = S;

    #[inline]
    fn eval(&self, wi: Vec3, wo: Vec3) -> S {
        self.lobe.eval(wi, wo) * self.scale
    }

    #[inline]
    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<S>> {
        let mut s = self.lobe.sample(wo, u)?;
        s.weight *= self.scale;
        s.weight.is_finite().then_some(s)
    }

    #[inline]
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        self.lobe.pdf(wi, wo)
    }

    #[inline]
    fn eval_checked(&self, wi: Vec3, wo: Vec3) -> S {
        self.lobe.eval_checked(wi, wo) * self.scale
    }

    #[inline]
    fn pdf_checked(&self, wi: Vec3, wo: Vec3) -> f32 {
        self.lobe.pdf_checked(wi, wo)
    }

    /// The lobe's own batch kernel, scaled.
    fn eval_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [S]) {
        self.lobe.eval_batch(wi, wo, out);
        for o in out.iter_mut() {
            *o *= self.scale;
        }
    }

    /// The lobe's own batch kernel, scaled.
    fn eval_batch_soa(&self, wi: Vec3Soa<'_>, wo: Vec3Soa<'_>, out: &mut [S]) {
        self.lobe.eval_batch_soa(wi, wo, out);
        for o in out.iter_mut() {
            *o *= self.scale;
        }
    }

    /// The lobe's own `pdf_batch`.
    fn pdf_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]) {
        self.lobe.pdf_batch(wi, wo, out);
    }

    #[inline]
    fn sampling_components(&self) -> usize {
        self.lobe.sampling_components()
    }

    #[inline]
    fn component_weight(&self, wo: Vec3, k: usize) -> f32 {
        self.lobe.component_weight(wo, k)
    }

    #[inline]
    fn sample_component(&self, wo: Vec3, k: usize, u: [f32; 2]) -> Option<Vec3> {
        self.lobe.sample_component(wo, k, u)
    }

    fn is_smooth(&self) -> bool {
        self.lobe.is_smooth()
    }

    fn directional_albedo(&self, wo: Vec3) -> Albedo<S> {
        let e = self.lobe.directional_albedo(wo);
        Albedo {
            value: e.value * self.scale,
            error: e.error * self.scale.max_channel(),
            is_bound: e.is_bound,
        }
    }

    /// The lobe's own (the scale needs nothing).
    fn with_prepared_albedo(self) -> Self {
        Self {
            lobe: self.lobe.with_prepared_albedo(),
            ..self
        }
    }
}

impl<B: IsotropicBrdf<Spectrum = S>, S: Spectrum> IsotropicBrdf for Scaled<B, S> {}
