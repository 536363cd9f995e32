//! [`Sum`]: two lobes added.

use super::{
    add_albedo, eval_batch_pair, eval_batch_soa_pair, finish_sample, mixture_pdf, pair_components,
    pair_sample, pair_weight, pdf_batch_pair, pick_and_sample, pick_first, saturate,
};
use crate::batch::Vec3Soa;
use crate::brdf::{Albedo, Brdf, BrdfSample, IsotropicBrdf};
use crate::frame::is_checked;
use crate::spectrum::Spectrum;
use glam::Vec3;

/// The sum of two lobes,
///
/// ```text
/// f(ωi, ωo) = f_A(ωi, ωo) + f_B(ωi, ωo),      E(ωo) = E_A(ωo) + E_B(ωo),
/// ```
///
/// sampled by picking lobe `A` with probability `p_A = Ē_A / (Ē_A + Ē_B)`
/// (`Ē`: the channel average of the [directional
/// albedo](Brdf::directional_albedo) at `ωo`; `½` if both are 0), with the
/// mixture density `pdf = p_A pdf_A + (1 − p_A) pdf_B` — so the estimator
/// `f cos θi / pdf` stays unbiased whichever lobe drew `ωi`, and the light
/// each lobe reflects gets its share of the samples. A plastic is
/// `Sum::new(diffuse, specular)`; three or more lobes nest,
/// `Sum::new(Sum::new(a, b), c)`.
///
/// Energy: `E ≤ 1` only if `E_A + E_B ≤ 1` — a sum of lobes that each
/// conserve energy need not (use [`Coated`](super::Coated) to put one over
/// the other, or [`Mix`](super::Mix) to blend).
///
/// ```
/// use radiometry::compose::Sum;
/// use radiometry::{Brdf, glam::Vec3};
/// # struct Flat(f32);
/// # impl Brdf for Flat {
/// #     type Spectrum = f32;
/// #     fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
/// #         if wi.z > 0.0 && wo.z > 0.0 { self.0 * core::f32::consts::FRAC_1_PI } else { 0.0 }
/// #     }
/// # }
/// let b = Sum::new(Flat(0.25), Flat(0.5));
/// let wo = Vec3::Z;
/// assert!((b.directional_albedo(wo).value - 0.75).abs() < 1e-6);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sum<A, B> {
    /// The first lobe.
    pub a: A,
    /// The second lobe.
    pub b: B,
}

impl<A, B> Sum<A, B> {
    /// `f_A + f_B`.
    pub const fn new(a: A, b: B) -> Self {
        Self { a, b }
    }
}

impl<A, B, S> Sum<A, B>
where
    A: Brdf<Spectrum = S>,
    B: Brdf<Spectrum = S>,
    S: Spectrum,
{
    /// The probability that [`Brdf::sample`] draws from lobe `A` at `wo`.
    pub fn pick_probability(&self, wo: Vec3) -> f32 {
        pick_first(
            self.a.directional_albedo(wo).value.average(),
            self.b.directional_albedo(wo).value.average(),
        )
    }

    /// The mixture density with pick probability `p`, through the lobes'
    /// checked densities ([`Brdf::pdf_checked`], the same bits) where both
    /// directions are [checked](is_checked).
    #[inline]
    fn density(&self, p: f32, wi: Vec3, wo: Vec3) -> f32 {
        if is_checked(wi) && is_checked(wo) {
            mixture_pdf(p, self.a.pdf_checked(wi, wo), self.b.pdf_checked(wi, wo))
        } else {
            mixture_pdf(p, self.a.pdf(wi, wo), self.b.pdf(wi, wo))
        }
    }
}

impl<A, B, S> Brdf for Sum<A, B>
where
    A: Brdf<Spectrum = S>,
    B: Brdf<Spectrum = S>,
    S: Spectrum,
{
    type Spectrum = S;

    #[inline]
    /// Through the lobes' checked paths ([`eval_checked`](Brdf::eval_checked))
    /// where both directions are [checked](is_checked) (the same bits).
    fn eval(&self, wi: Vec3, wo: Vec3) -> S {
        if is_checked(wi) && is_checked(wo) {
            return self.eval_checked(wi, wo);
        }
        saturate(self.a.eval(wi, wo) + self.b.eval(wi, wo))
    }

    #[inline]
    fn eval_checked(&self, wi: Vec3, wo: Vec3) -> S {
        saturate(self.a.eval_checked(wi, wo) + self.b.eval_checked(wi, wo))
    }

    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<S>> {
        let p = self.pick_probability(wo);
        let wi = pick_and_sample(p, u, |v| self.a.sample(wo, v), |v| self.b.sample(wo, v))?;
        finish_sample(wi, self.eval(wi, wo), self.density(p, wi, wo))
    }

    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        self.density(self.pick_probability(wo), wi, wo)
    }

    #[inline]
    fn pdf_checked(&self, wi: Vec3, wo: Vec3) -> f32 {
        mixture_pdf(
            self.pick_probability(wo),
            self.a.pdf_checked(wi, wo),
            self.b.pdf_checked(wi, wo),
        )
    }

    /// The lobes' own batch kernels, summed (equal to [`eval`](Brdf::eval)
    /// element by element).
    fn eval_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [S]) {
        eval_batch_pair(&self.a, &self.b, wi, wo, out, |_, _, x, y| saturate(x + y));
    }

    fn eval_batch_soa(&self, wi: Vec3Soa<'_>, wo: Vec3Soa<'_>, out: &mut [S]) {
        eval_batch_soa_pair(&self.a, &self.b, wi, wo, out, |_, _, x, y| saturate(x + y));
    }

    /// The lobes' own `pdf_batch` kernels, mixed with the pick probability
    /// at each `ωo` (equal to [`pdf`](Brdf::pdf) element by element).
    fn pdf_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]) {
        pdf_batch_pair(Some(&self.a), Some(&self.b), wi, wo, out, |w, x, y| {
            mixture_pdf(self.pick_probability(w), x, y)
        });
    }

    /// The components of both lobes (flattened), lobe `A`'s first, weighted
    /// by the pick probability (see [`Brdf::sampling_components`]).
    fn sampling_components(&self) -> usize {
        pair_components(&self.a, &self.b)
    }

    fn component_weight(&self, wo: Vec3, k: usize) -> f32 {
        pair_weight(self.pick_probability(wo), &self.a, &self.b, wo, k)
    }

    fn sample_component(&self, wo: Vec3, k: usize, u: [f32; 2]) -> Option<Vec3> {
        pair_sample(&self.a, &self.b, wo, k, u)
    }

    fn is_smooth(&self) -> bool {
        self.a.is_smooth() && self.b.is_smooth()
    }

    fn directional_albedo(&self, wo: Vec3) -> Albedo<S> {
        add_albedo(self.a.directional_albedo(wo), self.b.directional_albedo(wo))
    }

    /// Both lobes' (the picks of `sample` and `pdf` read their albedos).
    fn with_prepared_albedo(self) -> Self {
        Self::new(self.a.with_prepared_albedo(), self.b.with_prepared_albedo())
    }
}

impl<A, B, S> IsotropicBrdf for Sum<A, B>
where
    A: IsotropicBrdf<Spectrum = S>,
    B: IsotropicBrdf<Spectrum = S>,
    S: Spectrum,
{
}
