//! General environment lights and their integrands.

use super::{Light, LightPart, PartVisitor};
use crate::brdf::Brdf;
use crate::frame::try_normalize;
use crate::integrator::chunk::{brdf_component_batch, brdf_eval_where, brdf_pdf_batch, brdf_sample_batch};
use crate::integrator::{CHUNK, Integrand, IntegrandSample, IntegrateError};
use crate::spectrum::Spectrum;
use crate::warp::{cosine_hemisphere_pdf, square_to_cosine_hemisphere};
use glam::Vec3;

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
/// use radiometry::light::{Environment, LightIntegrals};
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

    fn for_each_part(&self, f: &mut PartVisitor<'_, S>) -> Result<(), IntegrateError> {
        f(LightPart::Environment(self))
    }
}

/// `g(ω) = L(ω) cos θ` of a light's radiance, sampled cosine-weighted.
pub(crate) struct EnvironmentIrradiance<'a, L: ?Sized> {
    pub(crate) light: &'a L,
}

impl<S: Spectrum, L: Light<Spectrum = S> + ?Sized> Integrand for EnvironmentIrradiance<'_, L> {
    type Spectrum = S;

    fn eval(&self, w: Vec3) -> S {
        if w.z <= 0.0 {
            return S::zero();
        }
        self.light.radiance(w) * w.z
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
/// ([`Brdf::sample`]), as for [`DirectionalAlbedo`](crate::integrator::DirectionalAlbedo).
///
/// This is what [`Environment`] integrates; for other lights it is the
/// *brute-force* path that the shortcuts of [`LightIntegrals::reflected_radiance`](super::LightIntegrals::reflected_radiance)
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

    /// As [`DirectionalAlbedo`](crate::integrator::DirectionalAlbedo)'s,
    /// times the radiance at each direction.
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
        brdf_component_batch(&self.brdf, self.wo, k, u, out);
        for s in out.iter_mut().flatten() {
            s.value *= self.light.radiance(s.w);
        }
    }

    /// As [`Integrand::eval`]: [`Light::radiance`] point by point, then one
    /// [`Brdf::eval_batch`] per chunk over the points above the horizon
    /// with non-black radiance.
    fn eval_batch(&self, w: &[Vec3], out: &mut [B::Spectrum]) {
        crate::batch::zero_tail(out, w.len());
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
        crate::batch::zero_tail(out, u.len());
        brdf_sample_batch(&self.brdf, self.wo, u, out, |s| {
            s.weight * s.pdf * self.light.radiance(s.wi)
        });
    }

    /// [`Brdf::pdf_batch`] with `wo` broadcast.
    fn pdf_batch(&self, w: &[Vec3], out: &mut [f32]) {
        crate::batch::zero_tail(out, w.len());
        brdf_pdf_batch(&self.brdf, self.wo, w, out);
    }
}
