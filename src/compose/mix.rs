//! [`Mix`]: a weighted blend of two lobes.

use super::{
    ComposeError, eval_batch_pair, eval_batch_soa_pair, finish_sample, mixture_pdf, pair_components,
    pair_sample, pair_weight, pdf_batch_pair, pick_and_sample, pick_first, saturate,
};
use crate::batch::Vec3Soa;
use crate::brdf::{Albedo, Brdf, BrdfSample, IsotropicBrdf};
use crate::frame::is_checked;
use crate::spectrum::Spectrum;
use glam::Vec3;

/// A weighted blend of two lobes (OpenPBR's `mix`: patches of two materials
/// in proportion `w`),
///
/// ```text
/// f(ωi, ωo) = w f_A(ωi, ωo) + (1 − w) f_B(ωi, ωo),   w ∈ [0, 1],
/// E(ωo)     = w E_A(ωo) + (1 − w) E_B(ωo)  ≤ max(E_A, E_B),
/// ```
///
/// sampled by picking lobe `A` with probability
/// `p_A = w Ē_A / (w Ē_A + (1 − w) Ē_B)` (albedo-proportional, as
/// [`Sum`](super::Sum)) and the mixture density `p_A pdf_A + (1 − p_A) pdf_B`.
/// A mix of energy-conserving lobes conserves energy.
///
/// ```
/// use radiometry::compose::Mix;
/// use radiometry::{Brdf, glam::Vec3};
/// # struct Flat(f32);
/// # impl Brdf for Flat {
/// #     type Spectrum = f32;
/// #     fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
/// #         if wi.z > 0.0 && wo.z > 0.0 { self.0 * core::f32::consts::FRAC_1_PI } else { 0.0 }
/// #     }
/// # }
/// let m = Mix::new(0.25, Flat(1.0), Flat(0.2))?;
/// assert!((m.directional_albedo(Vec3::Z).value - (0.25 + 0.75 * 0.2)).abs() < 1e-6);
/// assert!(Mix::new(1.5, Flat(1.0), Flat(0.2)).is_err());
/// # Ok::<(), radiometry::compose::ComposeError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mix<A, B> {
    w: f32,
    a: A,
    b: B,
}

impl<A, B> Mix<A, B> {
    /// `w f_A + (1 − w) f_B`; `w` must lie in `[0, 1]`.
    pub fn new(w: f32, a: A, b: B) -> Result<Self, ComposeError> {
        if !(0.0..=1.0).contains(&w) {
            return Err(ComposeError::Weight(w));
        }
        Ok(Self { w, a, b })
    }

    /// The weight `w` of lobe `A`.
    pub fn weight(&self) -> f32 {
        self.w
    }

    /// Lobe `A` (weight `w`).
    pub fn first(&self) -> &A {
        &self.a
    }

    /// Lobe `B` (weight `1 − w`).
    pub fn second(&self) -> &B {
        &self.b
    }
}

impl<A, B, S> Mix<A, B>
where
    A: Brdf<Spectrum = S>,
    B: Brdf<Spectrum = S>,
    S: Spectrum,
{
    /// The probability that [`Brdf::sample`] draws from lobe `A` at `wo`.
    pub fn pick_probability(&self, wo: Vec3) -> f32 {
        if self.w == 0.0 {
            return 0.0;
        }
        if self.w == 1.0 {
            return 1.0;
        }
        pick_first(
            self.w * self.a.directional_albedo(wo).value.average(),
            (1.0 - self.w) * self.b.directional_albedo(wo).value.average(),
        )
    }
}

impl<A, B, S> Mix<A, B>
where
    A: Brdf<Spectrum = S>,
    B: Brdf<Spectrum = S>,
    S: Spectrum,
{
    /// The mixture density at pick probability `p`; one expression for
    /// `sample` and `pdf`. With `w = 0` (`p = 0`) or `w = 1` (`p = 1`) the
    /// unused lobe's density is not computed (its term is `0 · pdf = 0`).
    /// Through the lobes' checked densities ([`Brdf::pdf_checked`], the
    /// same bits) where both directions are [checked](is_checked).
    #[inline]
    fn density(&self, p: f32, wi: Vec3, wo: Vec3) -> f32 {
        if is_checked(wi) && is_checked(wo) {
            self.density_of(p, || self.a.pdf_checked(wi, wo), || self.b.pdf_checked(wi, wo))
        } else {
            self.density_of(p, || self.a.pdf(wi, wo), || self.b.pdf(wi, wo))
        }
    }

    /// `sat(w f_A + (1 − w) f_B)` from the lobes' values `fa`, `fb`. `w = 0`
    /// or `1` leave one lobe: the formula's value (`0 · f + 1 · g = g` for
    /// finite `f`) without evaluating the other.
    #[inline(always)]
    fn value_of(&self, fa: impl FnOnce() -> S, fb: impl FnOnce() -> S) -> S {
        if self.w == 0.0 {
            return fb();
        }
        if self.w == 1.0 {
            return fa();
        }
        saturate(fa() * self.w + fb() * (1.0 - self.w))
    }

    /// [`density`](Self::density) from the lobes' densities `pa`, `pb`.
    #[inline(always)]
    fn density_of(&self, p: f32, pa: impl FnOnce() -> f32, pb: impl FnOnce() -> f32) -> f32 {
        if self.w == 0.0 {
            return mixture_pdf(p, 0.0, pb());
        }
        if self.w == 1.0 {
            return mixture_pdf(p, pa(), 0.0);
        }
        mixture_pdf(p, pa(), pb())
    }
}

impl<A, B, S> Brdf for Mix<A, B>
where
    A: Brdf<Spectrum = S>,
    B: Brdf<Spectrum = S>,
    S: Spectrum,
{
    type Spectrum = S;

    /// Through the lobes' checked paths ([`eval_checked`](Brdf::eval_checked))
    /// where both directions are [checked](is_checked) (the same bits).
    #[inline]
    fn eval(&self, wi: Vec3, wo: Vec3) -> S {
        if is_checked(wi) && is_checked(wo) {
            return self.eval_checked(wi, wo);
        }
        self.value_of(|| self.a.eval(wi, wo), || self.b.eval(wi, wo))
    }

    #[inline]
    fn eval_checked(&self, wi: Vec3, wo: Vec3) -> S {
        self.value_of(|| self.a.eval_checked(wi, wo), || self.b.eval_checked(wi, wo))
    }

    #[inline]
    fn pdf_checked(&self, wi: Vec3, wo: Vec3) -> f32 {
        let p = self.pick_probability(wo);
        self.density_of(p, || self.a.pdf_checked(wi, wo), || self.b.pdf_checked(wi, wo))
    }

    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<S>> {
        let p = self.pick_probability(wo);
        let wi = pick_and_sample(p, u, |v| self.a.sample(wo, v), |v| self.b.sample(wo, v))?;
        finish_sample(wi, self.eval(wi, wo), self.density(p, wi, wo))
    }

    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        self.density(self.pick_probability(wo), wi, wo)
    }

    /// The lobes' own batch kernels, mixed (equal to [`eval`](Brdf::eval)
    /// element by element; a zero-weight side is not evaluated).
    fn eval_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [S]) {
        if self.w == 0.0 {
            return self.b.eval_batch(wi, wo, out);
        }
        if self.w == 1.0 {
            return self.a.eval_batch(wi, wo, out);
        }
        let w = self.w;
        eval_batch_pair(&self.a, &self.b, wi, wo, out, |_, _, x, y| {
            saturate(x * w + y * (1.0 - w))
        });
    }

    fn eval_batch_soa(&self, wi: Vec3Soa<'_>, wo: Vec3Soa<'_>, out: &mut [S]) {
        if self.w == 0.0 {
            return self.b.eval_batch_soa(wi, wo, out);
        }
        if self.w == 1.0 {
            return self.a.eval_batch_soa(wi, wo, out);
        }
        let w = self.w;
        eval_batch_soa_pair(&self.a, &self.b, wi, wo, out, |_, _, x, y| {
            saturate(x * w + y * (1.0 - w))
        });
    }

    /// The lobes' own `pdf_batch` kernels, mixed as [`pdf`](Brdf::pdf) mixes
    /// them (element by element equal).
    fn pdf_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]) {
        let pick = |w| self.pick_probability(w);
        if self.w == 0.0 {
            pdf_batch_pair(None::<&A>, Some(&self.b), wi, wo, out, |w, _, y| {
                mixture_pdf(pick(w), 0.0, y)
            });
        } else if self.w == 1.0 {
            pdf_batch_pair(Some(&self.a), None::<&B>, wi, wo, out, |w, x, _| {
                mixture_pdf(pick(w), x, 0.0)
            });
        } else {
            pdf_batch_pair(Some(&self.a), Some(&self.b), wi, wo, out, |w, x, y| {
                mixture_pdf(pick(w), x, y)
            });
        }
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
        if self.w == 0.0 {
            return self.b.directional_albedo(wo);
        }
        if self.w == 1.0 {
            return self.a.directional_albedo(wo);
        }
        let (ea, eb) = (self.a.directional_albedo(wo), self.b.directional_albedo(wo));
        Albedo {
            value: ea.value * self.w + eb.value * (1.0 - self.w),
            error: ea.error * self.w + eb.error * (1.0 - self.w),
            is_bound: ea.is_bound && eb.is_bound,
        }
    }

    /// Both lobes' (the picks of `sample` and `pdf` read their albedos).
    fn with_prepared_albedo(self) -> Self {
        Self {
            a: self.a.with_prepared_albedo(),
            b: self.b.with_prepared_albedo(),
            ..self
        }
    }
}

impl<A, B, S> IsotropicBrdf for Mix<A, B>
where
    A: IsotropicBrdf<Spectrum = S>,
    B: IsotropicBrdf<Spectrum = S>,
    S: Spectrum,
{
}
