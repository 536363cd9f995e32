//! [`Coated`]: albedo-scaled layering of a top lobe over a base, in
//! OpenPBR's energy-conserving form or a reciprocal one ([`Layering`]).

use super::{
    CHUNK, ComposeError, Layering, finish_sample, mixture_pdf, pair_components, pair_sample, pair_weight,
    pick_and_sample, pick_first, pick_u, reciprocal_through, saturate, soa_chunks, soa_dirs,
};
use crate::batch::Vec3Soa;
use crate::brdf::{Albedo, Brdf, BrdfSample, IsotropicBrdf, clamp_albedo};
use crate::frame::{cos_theta, is_checked};
use crate::spectrum::Spectrum;
use glam::Vec3;

/// A coat: a top lobe (a clear or tinted dielectric interface, a sheen)
/// over a base, by albedo scaling (OpenPBR Surface 1.1, §"Layering"):
///
/// ```text
/// f(ωi, ωo) = K ⊙ f_T(ωi, ωo) + A(μi, μo) ⊙ τ(ωi, ωo) ⊙ f_B(ωi, ωo)
///
/// energy-conserving (default):  τ = t(ωo) = 1 − E_T(ωo)
/// reciprocal:                   τ = min(t(ωi) t(ωo)/(1 − Ē_T), t(ωi), t(ωo))
///
/// A(μi, μo) = C^{(1/μᵗi + 1/μᵗo)/2},   μᵗ = √(1 − (1 − μ²)/η²)
/// ```
///
/// per channel, with `E_T` the top's [directional
/// albedo](Brdf::directional_albedo) read at every call (the crate's lobes
/// report it in O(1) from global tables or closed forms, and
/// [`Coated::new`] keeps the top [prepared](Brdf::with_prepared_albedo) for
/// those reads; wrap a third-party top whose albedo is costly in
/// [`Precomputed`](super::Precomputed), which tabulates it once) and `Ē_T =
/// 2∫E_T μ dμ` its hemispherical average ([`Brdf::average_albedo`], read
/// once at construction).
///
/// * **Energy-conserving** ([`Layering::EnergyConserving`], OpenPBR's eq.
///   "non-reciprocal albedo scaling"): `E(ωo) = K E_T(ωo) + (1 − E_T(ωo))
///   ∫A f_B cos θi dωi ≤ 1` for every base with `E_B ≤ 1`, and `= 1` for a
///   white base under a clear, untinted top: the white furnace holds up to
///   the error of the top's reported albedo.
/// * **Reciprocal** ([`Layering::Reciprocal`], for bidirectional methods):
///   `τ` is symmetric in `(ωi, ωo)`. Without the caps it is the form of
///   Kelemen & Szirmay-Kalos (2001), exact for a Lambertian base (`∫ t(μi)
///   t(μo)/(1 − Ē) · ρ/π · μi dωi = ρ t(μo)`); the caps `τ ≤ t(μi), t(μo)`
///   keep `E ≤ 1` for every base (a mirror-like base sees at most the
///   one-sided `t(μo)`), and bind only where `E_T(μo) < Ē_T` (towards normal
///   incidence for a Fresnel top), where a white Lambertian base keeps
///   `E_T + 1 − Ē_T` instead of 1.
///
/// `A` is the coat's absorption with OpenPBR's parameters: `C` =
/// `coat_color`, the square of the transmittance at normal incidence, and
/// the path length through a coat of index `η` along the refracted
/// directions (OpenPBR §"Coat — view-dependent absorption"). Without
/// absorption ([`Coated::new`]) `A = 1`. `K` ([`Coated::with_top_tint`])
/// tints the top's reflection only.
///
/// Sampling picks the top with probability `Ē_T / (Ē_T + Ē_through)` at `ωo`
/// (`Ē_through` = the channel average of `A(μo, μo) t(ωo) E_B(ωo)`), with
/// the mixture density; `pdf(sample) == sample.pdf` bit for bit.
///
/// ```
/// use radiometry::compose::{Coated, Layering};
/// use radiometry::{Albedo, Brdf, glam::Vec3};
/// # struct Flat(f32);
/// # impl Brdf for Flat {
/// #     type Spectrum = f32;
/// #     fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
/// #         if wi.z > 0.0 && wo.z > 0.0 { self.0 * core::f32::consts::FRAC_1_PI } else { 0.0 }
/// #     }
/// #     fn directional_albedo(&self, wo: Vec3) -> Albedo<f32> {
/// #         if wo.z > 0.0 { Albedo::bounded(self.0, 0.0) } else { Albedo::zero() }
/// #     }
/// # }
/// let layer = Coated::new(Flat(0.1), Flat(1.0)); // energy-conserving
/// let wo = Vec3::new(0.0, 0.6, 0.8);
/// assert!((layer.directional_albedo(wo).value - 1.0).abs() < 1e-6); // white furnace
/// let both_ways = Coated::new(Flat(0.1), Flat(1.0)).with_layering(Layering::Reciprocal);
/// let wi = Vec3::new(0.6, 0.0, 0.8);
/// assert_eq!(both_ways.eval(wi, wo), both_ways.eval(wo, wi)); // reciprocal
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Coated<T: Brdf, B> {
    top: T,
    base: B,
    layering: Layering,
    /// `coat_color` (`C`) and the coat's index of refraction, if absorbing.
    absorption: Option<(T::Spectrum, f32)>,
    /// `1/(1 − Ē_T)` per channel (the reciprocal mode's normalisation).
    inv_average: T::Spectrum,
    /// The tint `K` of the top's reflection (1 unless set by
    /// [`with_top_tint`](Coated::with_top_tint)).
    tint: T::Spectrum,
}

impl<T, B, S> Coated<T, B>
where
    T: Brdf<Spectrum = S>,
    B: Brdf<Spectrum = S>,
    S: Spectrum,
{
    /// `top` over `base`, clear (no absorption), energy-conserving. O(1):
    /// reads the top's [average albedo](Brdf::average_albedo) once and keeps
    /// the top [prepared](Brdf::with_prepared_albedo) for the reads of its
    /// directional albedo at every call.
    pub fn new(top: T, base: B) -> Self {
        let top = top.with_prepared_albedo();
        let avg = top.average_albedo();
        Self {
            top,
            base,
            layering: Layering::EnergyConserving,
            absorption: None,
            inv_average: avg.map(|a| 1.0 / (1.0 - a.clamp(0.0, 1.0)).max(1e-6)),
            tint: S::splat(1.0),
        }
    }

    /// This layer in the given [`Layering`] mode.
    pub fn with_layering(mut self, layering: Layering) -> Self {
        self.layering = layering;
        self
    }

    /// The layering mode.
    pub fn layering(&self) -> Layering {
        self.layering
    }

    /// Tints the top's reflection by `K ∈ [0, 1]` per channel, leaving what
    /// it lets through unchanged: `f = K ⊙ f_T + τ ⊙ f_B`, `τ` still from the
    /// untinted `E_T` (OpenPBR Surface 1.1, `specular_color`: "only the
    /// Fresnel reflection from above is tinted", an energy-removing
    /// convenience). Energy: `E ≤ K E_T + (1 − E_T) E_B ≤ 1`.
    ///
    /// # Errors
    /// [`ComposeError::TopTint`] for a channel outside `[0, 1]` or not finite.
    pub fn with_top_tint(mut self, tint: S) -> Result<Self, ComposeError> {
        for i in 0..S::CHANNELS {
            let c = tint.channel(i);
            if !(0.0..=1.0).contains(&c) {
                return Err(ComposeError::TopTint(c));
            }
        }
        self.tint = tint;
        Ok(self)
    }

    /// The top's albedo at `ω`, each channel clamped to `[0, 1]` (NaN → 0);
    /// through the top's checked read ([`Brdf::albedo_checked`], the same
    /// value) where `ω` is [checked](is_checked).
    #[inline]
    fn top_albedo(&self, w: Vec3) -> S {
        if is_checked(w) {
            self.top.albedo_checked(w)
        } else {
            clamp_albedo(self.top.directional_albedo(w).value)
        }
    }

    /// `to[k] = t(ωo,k) = 1 − E_T(ωo,k)` for a chunk of view directions,
    /// from the top's [`Brdf::directional_albedo_batch`] (clamped as
    /// [`top_albedo`](Self::top_albedo) clamps): the values the scalar path
    /// reads one by one.
    #[inline]
    fn through_chunk(&self, wo: &[Vec3], to: &mut [S]) {
        self.top.directional_albedo_batch(wo, to);
        for t in to.iter_mut() {
            *t = clamp_albedo(*t).map(|e| 1.0 - e);
        }
    }

    /// `K ⊙ f_T + A τ ⊙ f_B` of one batch element, or 0 unless both
    /// directions are above the horizon (as [`eval`](Brdf::eval)), with
    /// `t(ωo)` from [`through_chunk`](Self::through_chunk).
    #[inline]
    fn layer_element(&self, wi: Vec3, wo: Vec3, ft: S, fb: S, to: S) -> S {
        if Self::both_above(wi, wo) {
            self.layer_with(wi, wo, ft, fb, || to)
        } else {
            S::zero()
        }
    }

    /// `top` over `base` through an absorbing coat: `coat_color` (`C ∈ [0,
    /// 1]` per channel, the square of the normal-incidence transmittance) and
    /// the coat's index of refraction `ior ≥ 1` (relative to the outside).
    pub fn with_absorption(top: T, base: B, coat_color: S, ior: f32) -> Result<Self, ComposeError> {
        check_coat(coat_color, ior)?;
        Self::new(top, base).absorbing(coat_color, ior)
    }

    /// This layer with an absorbing coat, as [`Coated::with_absorption`]
    /// builds it (`coat_color ∈ [0, 1]` per channel, `ior ≥ 1`).
    pub fn absorbing(mut self, coat_color: S, ior: f32) -> Result<Self, ComposeError> {
        check_coat(coat_color, ior)?;
        self.absorption = Some((coat_color, ior));
        Ok(self)
    }

    /// The top lobe.
    pub fn top(&self) -> &T {
        &self.top
    }

    /// The base lobe.
    pub fn base(&self) -> &B {
        &self.base
    }

    /// The absorption factor `A(μi, μo)` (1 per channel without absorption).
    fn absorption(&self, mu_i: f32, mu_o: f32) -> S {
        match self.absorption {
            None => S::splat(1.0),
            Some((color, eta)) => coat_absorption(color, eta, mu_i, mu_o),
        }
    }

    /// `τ(ωi, ωo)` per channel (see the type's docs), from `t(ωo) = 1 −
    /// E_T(ωo)`.
    #[inline]
    fn through(&self, wi: Vec3, to: S) -> S {
        match self.layering {
            Layering::EnergyConserving => to,
            Layering::Reciprocal => {
                let ti = self.top_albedo(wi).map(|e| 1.0 - e);
                S::from_fn(|c| reciprocal_through(ti.channel(c), to.channel(c), self.inv_average.channel(c)))
            }
        }
    }

    /// Whether both directions are strictly above the horizon.
    #[inline]
    fn both_above(wi: Vec3, wo: Vec3) -> bool {
        let (mi, mo) = (cos_theta(wi), cos_theta(wo));
        !((mi.is_nan() || mi <= 0.0) || (mo.is_nan() || mo <= 0.0))
    }

    /// `K ⊙ f_T + A τ ⊙ f_B` from the lobes' values (both directions above
    /// the horizon), with `t(ωo) = 1 − E_T(ωo)` from `to` (called only when
    /// the base reflects).
    #[inline(always)]
    fn layer_with(&self, wi: Vec3, wo: Vec3, f_top: S, fb: S, to: impl FnOnce() -> S) -> S {
        let top = f_top * self.tint;
        if fb.is_black() {
            return top;
        }
        let tau = self.absorption(cos_theta(wi), cos_theta(wo)) * self.through(wi, to());
        saturate(top + tau * fb)
    }

    /// The probability of drawing from the top at `wo`.
    pub fn pick_probability(&self, wo: Vec3) -> f32 {
        let mu = cos_theta(wo);
        if mu.is_nan() || mu <= 0.0 {
            return 0.5;
        }
        self.pick_with(wo, mu, self.top_albedo(wo))
    }

    /// [`pick_probability`](Self::pick_probability) at `wo` above the
    /// horizon (`μ = cos θo > 0`) with the top's albedo `et` there.
    #[inline(always)]
    fn pick_with(&self, wo: Vec3, mu: f32, et: S) -> f32 {
        self.pick_from(mu, et, self.base.directional_albedo(wo).value)
    }

    /// [`pick_with`](Self::pick_with) with the base's albedo `eb` at `ωo`.
    #[inline(always)]
    fn pick_from(&self, mu: f32, et: S, eb: S) -> f32 {
        let through = self.absorption(mu, mu) * et.map(|e| (1.0 - e).clamp(0.0, 1.0)) * eb;
        pick_first((et * self.tint).average(), through.average())
    }

    /// The view terms of [`prepare`](Self::prepare) for a chunk of `wo`:
    /// `t(ωo)` and the pick probability, from the lobes'
    /// [`directional_albedo_batch`](Brdf::directional_albedo_batch) (equal
    /// to `prepare`'s, element by element). `to`, `pick`, `et` and `eb` are
    /// at least as long as `wo`.
    #[inline]
    fn views_chunk(&self, wo: &[Vec3], to: &mut [S], pick: &mut [f32], et: &mut [S], eb: &mut [S]) {
        self.top.directional_albedo_batch(wo, et);
        self.base.directional_albedo_batch(wo, eb);
        for ((((t, p), &e), &b), &w) in to
            .iter_mut()
            .zip(pick.iter_mut())
            .zip(et.iter())
            .zip(eb.iter())
            .zip(wo)
        {
            let mu = cos_theta(w);
            let above = !(mu.is_nan() || mu <= 0.0);
            let e = if above { clamp_albedo(e) } else { S::zero() };
            *t = e.map(|e| 1.0 - e);
            *p = if above { self.pick_from(mu, e, b) } else { 0.5 };
        }
    }

    /// Prepares the view `ωo` for any number of [`CoatedView::eval`],
    /// [`CoatedView::pdf`] and [`CoatedView::sample`] calls: the top's
    /// albedo `E_T(ωo)` is read once (the plain calls read it in each of
    /// them, twice in `sample`) and the pick probability computed once. The
    /// view's results equal [`Brdf::eval`], [`Brdf::pdf`] and
    /// [`Brdf::sample`] at `ωo` bit for bit.
    ///
    /// ```
    /// use radiometry::Brdf;
    /// use radiometry::compose::Coated;
    /// use radiometry::glam::Vec3;
    /// # #[derive(Clone, Copy)]
    /// # struct Flat(f32);
    /// # impl Brdf for Flat {
    /// #     type Spectrum = f32;
    /// #     fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
    /// #         if wi.z > 0.0 && wo.z > 0.0 { self.0 * core::f32::consts::FRAC_1_PI } else { 0.0 }
    /// #     }
    /// # }
    /// let layer = Coated::new(Flat(0.25), Flat(1.0));
    /// let wo = Vec3::new(0.6, 0.0, 0.8);
    /// let view = layer.prepare(wo); // a renderer's hit: one view, several calls
    /// let s = view.sample([0.3, 0.7]).unwrap();
    /// assert_eq!(Some(s), layer.sample(wo, [0.3, 0.7]));
    /// assert_eq!(view.pdf(s.wi), s.pdf);
    /// assert_eq!(view.eval(s.wi), layer.eval(s.wi, wo));
    /// ```
    #[inline]
    pub fn prepare(&self, wo: Vec3) -> CoatedView<'_, T, B> {
        let mu = cos_theta(wo);
        let above = !(mu.is_nan() || mu <= 0.0);
        let et = if above { self.top_albedo(wo) } else { S::zero() };
        CoatedView {
            layer: self,
            wo,
            to: et.map(|e| 1.0 - e),
            pick: if above { self.pick_with(wo, mu, et) } else { 0.5 },
        }
    }
}

/// A [`Coated`] prepared for one view direction `ωo` ([`Coated::prepare`]):
/// `t(ωo) = 1 − E_T(ωo)` and the pick probability, computed once.
#[derive(Clone, Copy, Debug)]
pub struct CoatedView<'a, T: Brdf, B> {
    layer: &'a Coated<T, B>,
    wo: Vec3,
    to: T::Spectrum,
    pick: f32,
}

impl<T, B, S> CoatedView<'_, T, B>
where
    T: Brdf<Spectrum = S>,
    B: Brdf<Spectrum = S>,
    S: Spectrum,
{
    /// `f_r(ωi, ωo)` ([`Brdf::eval`] at the view's `ωo`).
    #[inline]
    pub fn eval(&self, wi: Vec3) -> S {
        let (l, wo) = (self.layer, self.wo);
        if is_checked(wi) && is_checked(wo) {
            return l.layer_with(
                wi,
                wo,
                l.top.eval_checked(wi, wo),
                l.base.eval_checked(wi, wo),
                || self.to,
            );
        }
        if !Coated::<T, B>::both_above(wi, wo) {
            return S::zero();
        }
        l.layer_with(wi, wo, l.top.eval(wi, wo), l.base.eval(wi, wo), || self.to)
    }

    /// The mixture density of [`sample`](Self::sample) ([`Brdf::pdf`] at
    /// the view's `ωo`).
    #[inline]
    pub fn pdf(&self, wi: Vec3) -> f32 {
        let (l, wo) = (self.layer, self.wo);
        if is_checked(wi) && is_checked(wo) {
            return mixture_pdf(self.pick, l.top.pdf_checked(wi, wo), l.base.pdf_checked(wi, wo));
        }
        mixture_pdf(self.pick, l.top.pdf(wi, wo), l.base.pdf(wi, wo))
    }

    /// One sample ([`Brdf::sample`] at the view's `ωo`).
    #[inline]
    pub fn sample(&self, u: [f32; 2]) -> Option<BrdfSample<S>> {
        let (l, wo) = (self.layer, self.wo);
        let wi = pick_and_sample(self.pick, u, |v| l.top.sample(wo, v), |v| l.base.sample(wo, v))?;
        finish_sample(wi, self.eval(wi), self.pdf(wi))
    }
}

/// A coat's absorption on the way in and out, OpenPBR Surface 1.1
/// §"Coat — view-dependent absorption":
///
/// ```text
/// A(μi, μo) = C^{(1/μᵗi + 1/μᵗo)/2},   μᵗ = √(1 − (1 − μ²)/η²)
/// ```
///
/// per channel, with `C = coat_color` (the square of the transmittance at
/// normal incidence, `[0, 1]`) and `η` the coat's index (`≥ 1`). A channel
/// of `C = 1` is exactly 1; where a refracted cosine is 0 (or NaN) the path
/// is infinitely long and every other channel is 0. Finite, in `[0, 1]`.
#[inline]
pub fn coat_absorption<S: Spectrum>(color: S, eta: f32, mu_i: f32, mu_o: f32) -> S {
    if (0..S::CHANNELS).all(|c| color.channel(c) >= 1.0) {
        // A clear coat (OpenPBR's default colour): every channel is 1 on
        // every path, the refracted cosines unread.
        return S::splat(1.0);
    }
    let refracted = |mu: f32| {
        let s2 = (1.0 - mu * mu).max(0.0) / (eta * eta);
        crate::math::sqrtf((1.0 - s2).max(0.0))
    };
    let (ti, to) = (refracted(mu_i), refracted(mu_o));
    if (ti.is_nan() || ti <= 0.0) || (to.is_nan() || to <= 0.0) {
        return color.map(|c| if c >= 1.0 { 1.0 } else { 0.0 });
    }
    let e = 0.5 * (1.0 / ti + 1.0 / to);
    color.map(|c| {
        if c >= 1.0 {
            1.0
        } else {
            let v = libm::powf(c, e);
            if v.is_finite() { v } else { 0.0 }
        }
    })
}

/// The domain of a coat's absorption parameters.
fn check_coat<S: Spectrum>(coat_color: S, ior: f32) -> Result<(), ComposeError> {
    for i in 0..S::CHANNELS {
        let c = coat_color.channel(i);
        if !c.is_finite() || c < 0.0 {
            return Err(ComposeError::Scale(c));
        }
        if c > 1.0 {
            return Err(ComposeError::CoatColor(c));
        }
    }
    if !ior.is_finite() || ior < 1.0 {
        return Err(ComposeError::CoatIor(ior));
    }
    Ok(())
}

impl<T, B, S> Brdf for Coated<T, B>
where
    T: Brdf<Spectrum = S>,
    B: Brdf<Spectrum = S>,
    S: Spectrum,
{
    type Spectrum = S;

    /// Both directions [checked](is_checked) once for both lobes and the
    /// top's albedo (their checked paths: the same bits); the general path
    /// otherwise.
    #[inline]
    fn eval(&self, wi: Vec3, wo: Vec3) -> S {
        if is_checked(wi) && is_checked(wo) {
            return self.eval_checked(wi, wo);
        }
        if !Self::both_above(wi, wo) {
            return S::zero();
        }
        let to = self.top_albedo(wo).map(|e| 1.0 - e);
        let (ft, fb) = (self.top.eval(wi, wo), self.base.eval(wi, wo));
        self.layer_with(wi, wo, ft, fb, || to)
    }

    /// The lobes' own batch kernels and the top's
    /// [`directional_albedo_batch`](Brdf::directional_albedo_batch) (a
    /// prepared GGX dielectric top reads its table in vector lanes), in
    /// chunks, layered as [`eval`](Brdf::eval) layers them (element by element
    /// equal).
    fn eval_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [S]) {
        let mut ft = [S::zero(); CHUNK];
        let mut fb = [S::zero(); CHUNK];
        let mut to = [S::zero(); CHUNK];
        for ((wi, wo), out) in wi.chunks(CHUNK).zip(wo.chunks(CHUNK)).zip(out.chunks_mut(CHUNK)) {
            self.top.eval_batch(wi, wo, &mut ft);
            self.base.eval_batch(wi, wo, &mut fb);
            self.through_chunk(wo, &mut to);
            for ((o, (&i, &j)), ((&x, &y), &t)) in out
                .iter_mut()
                .zip(wi.iter().zip(wo))
                .zip(ft.iter().zip(&fb).zip(&to))
            {
                *o = self.layer_element(i, j, x, y, t);
            }
        }
        crate::batch::zero_tail(out, wi.len().min(wo.len()));
    }

    /// [`eval_batch`](Brdf::eval_batch) for structure-of-arrays input: the
    /// lobes' own SoA kernels (equal to [`eval`](Brdf::eval) element by
    /// element).
    fn eval_batch_soa(&self, wi: Vec3Soa<'_>, wo: Vec3Soa<'_>, out: &mut [S]) {
        let mut ft = [S::zero(); CHUNK];
        let mut fb = [S::zero(); CHUNK];
        let mut to = [S::zero(); CHUNK];
        let mut wo_aos = [Vec3::ZERO; CHUNK];
        soa_chunks(wi, wo, out, |ci, co, oc| {
            self.top.eval_batch_soa(ci, co, &mut ft);
            self.base.eval_batch_soa(ci, co, &mut fb);
            for (a, w) in wo_aos.iter_mut().zip(soa_dirs(co)) {
                *a = w;
            }
            self.through_chunk(wo_aos.get(..oc.len()).unwrap_or(&wo_aos), &mut to);
            for ((o, (i, j)), ((&x, &y), &t)) in oc
                .iter_mut()
                .zip(soa_dirs(ci).zip(wo_aos.iter().copied()))
                .zip(ft.iter().zip(&fb).zip(&to))
            {
                *o = self.layer_element(i, j, x, y, t);
            }
        });
    }

    /// The lobes' own `pdf_batch` kernels, mixed with the pick probability
    /// at each `ωo` from the lobes' albedo batches (element by element equal
    /// to [`pdf`](Brdf::pdf)).
    fn pdf_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]) {
        let mut pt = [0.0f32; CHUNK];
        let mut pb = [0.0f32; CHUNK];
        let mut pick = [0.0f32; CHUNK];
        let (mut to, mut et, mut eb) = ([S::zero(); CHUNK], [S::zero(); CHUNK], [S::zero(); CHUNK]);
        for ((wi, wo), out) in wi.chunks(CHUNK).zip(wo.chunks(CHUNK)).zip(out.chunks_mut(CHUNK)) {
            self.top.pdf_batch(wi, wo, &mut pt);
            self.base.pdf_batch(wi, wo, &mut pb);
            self.views_chunk(wo, &mut to, &mut pick, &mut et, &mut eb);
            for (o, ((&x, &y), &p)) in out.iter_mut().zip(pt.iter().zip(&pb).zip(&pick)) {
                *o = mixture_pdf(p, x, y);
            }
        }
        crate::batch::zero_tail(out, wi.len().min(wo.len()));
    }

    /// [`sample`](Brdf::sample) in chunks: the view terms from the lobes'
    /// albedo batches, each lobe's `sample_batch` over the elements that
    /// pick it, then the lobes' `eval_batch` and `pdf_batch` at the drawn
    /// directions, layered and mixed as `sample` does (element by element
    /// equal to it: the same `None`s, bit-identical `wi`, pdf and weight).
    fn sample_batch(&self, wo: &[Vec3], u: &[[f32; 2]], out: &mut [Option<BrdfSample<S>>]) {
        let (mut to, mut et, mut eb) = ([S::zero(); CHUNK], [S::zero(); CHUNK], [S::zero(); CHUNK]);
        let (mut ft, mut fb) = ([S::zero(); CHUNK], [S::zero(); CHUNK]);
        let (mut pick, mut pt, mut pb) = ([0.0f32; CHUNK], [0.0f32; CHUNK], [0.0f32; CHUNK]);
        // Per lobe: the elements that pick it, their `ωo` and sample points.
        let mut idx = [[0usize; CHUNK]; 2];
        let mut wo_sub = [[Vec3::ZERO; CHUNK]; 2];
        let mut u_sub = [[[0.0f32; 2]; CHUNK]; 2];
        let mut drawn: [Option<BrdfSample<S>>; CHUNK] = [None; CHUNK];
        let mut wi = [Vec3::ZERO; CHUNK];
        let mut ok = [false; CHUNK];
        for ((wo, u), out) in wo.chunks(CHUNK).zip(u.chunks(CHUNK)).zip(out.chunks_mut(CHUNK)) {
            let m = wo.len().min(u.len());
            self.views_chunk(wo, &mut to, &mut pick, &mut et, &mut eb);
            let mut count = [0usize; 2];
            for (k, (&p, (&w, &v))) in pick.iter().zip(wo.iter().zip(u)).enumerate() {
                let (first, v) = pick_u(p, v);
                let lobe = usize::from(!first);
                let c = count[lobe];
                if let (Some(i), Some(o), Some(s)) = (
                    idx[lobe].get_mut(c),
                    wo_sub[lobe].get_mut(c),
                    u_sub[lobe].get_mut(c),
                ) {
                    (*i, *o, *s) = (k, w, v);
                    count[lobe] = c + 1;
                }
            }
            ok.fill(false);
            for (lobe, ((idx, w), v)) in idx.iter().zip(&wo_sub).zip(&u_sub).enumerate() {
                let c = count[lobe];
                let (Some(idx), Some(w), Some(v), Some(d)) =
                    (idx.get(..c), w.get(..c), v.get(..c), drawn.get_mut(..c))
                else {
                    continue;
                };
                if lobe == 0 {
                    self.top.sample_batch(w, v, d);
                } else {
                    self.base.sample_batch(w, v, d);
                }
                for (&k, s) in idx.iter().zip(d.iter()) {
                    if let (Some(s), Some(d), Some(f)) = (s, wi.get_mut(k), ok.get_mut(k)) {
                        (*d, *f) = (s.wi, true);
                    }
                }
            }
            let wi = wi.get(..m).unwrap_or(&[]);
            self.top.eval_batch(wi, wo, &mut ft);
            self.base.eval_batch(wi, wo, &mut fb);
            self.top.pdf_batch(wi, wo, &mut pt);
            self.base.pdf_batch(wi, wo, &mut pb);
            let values = ft.iter().zip(&fb).zip(&to);
            let densities = pick.iter().zip(&pt).zip(&pb);
            for ((((o, &good), (&i, &w)), ((&x, &y), &t)), ((&p, &a), &b)) in out
                .iter_mut()
                .zip(&ok)
                .zip(wi.iter().zip(wo))
                .zip(values)
                .zip(densities)
            {
                *o = if good {
                    finish_sample(i, self.layer_element(i, w, x, y, t), mixture_pdf(p, a, b))
                } else {
                    None
                };
            }
        }
        crate::batch::zero_tail(out, wo.len().min(u.len()));
    }

    /// Through one [`prepare`](Coated::prepare)d view: the top's albedo at
    /// `ωo` read once for the pick and the value.
    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<S>> {
        self.prepare(wo).sample(u)
    }

    /// Checked once for both lobes where both directions are, as
    /// [`eval`](Brdf::eval).
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        if is_checked(wi) && is_checked(wo) {
            return self.pdf_checked(wi, wo);
        }
        let p = self.pick_probability(wo);
        mixture_pdf(p, self.top.pdf(wi, wo), self.base.pdf(wi, wo))
    }

    #[inline]
    fn eval_checked(&self, wi: Vec3, wo: Vec3) -> S {
        let to = self.top.albedo_checked(wo).map(|e| 1.0 - e);
        let (ft, fb) = (self.top.eval_checked(wi, wo), self.base.eval_checked(wi, wo));
        self.layer_with(wi, wo, ft, fb, || to)
    }

    #[inline]
    fn pdf_checked(&self, wi: Vec3, wo: Vec3) -> f32 {
        let p = self.pick_with(wo, wo.z, self.top.albedo_checked(wo));
        mixture_pdf(p, self.top.pdf_checked(wi, wo), self.base.pdf_checked(wi, wo))
    }

    /// `false`: `τ` reads the top's albedo, which the plugins take from
    /// interpolated tables — not an analytic function of the directions.
    /// The components of both lobes (flattened), lobe `A`'s first, weighted
    /// by the pick probability (see [`Brdf::sampling_components`]).
    fn sampling_components(&self) -> usize {
        pair_components(&self.top, &self.base)
    }

    fn component_weight(&self, wo: Vec3, k: usize) -> f32 {
        pair_weight(self.pick_probability(wo), &self.top, &self.base, wo, k)
    }

    fn sample_component(&self, wo: Vec3, k: usize, u: [f32; 2]) -> Option<Vec3> {
        pair_sample(&self.top, &self.base, wo, k, u)
    }

    fn is_smooth(&self) -> bool {
        false
    }

    /// `E = K E_T(ωo) + X`, `X = ∫τ A f_B cos θi dωi`, estimated as
    /// `X ≈ A(μo, μo) t(ωo) E_B(ωo)` (exact for the energy-conserving mode
    /// without absorption); `0 ≤ X ≤ t(ωo) E_B(ωo)` bounds its error.
    fn directional_albedo(&self, wo: Vec3) -> Albedo<S> {
        let mu = cos_theta(wo);
        if mu.is_nan() || mu <= 0.0 {
            return Albedo::zero();
        }
        let top = self.top.directional_albedo(wo);
        let et = clamp_albedo(top.value);
        let eb = self.base.directional_albedo(wo);
        let upper = et.map(|e| 1.0 - e) * eb.value;
        let est = upper * self.absorption(mu, mu);
        let exact = self.absorption.is_none() && self.layering == Layering::EnergyConserving;
        let spread = if exact {
            0.0
        } else {
            (upper - est).max_channel().max(est.max_channel())
        };
        Albedo {
            value: et * self.tint + est,
            error: top.error * (1.0 + eb.value.max_channel()) + eb.error + spread,
            is_bound: exact && top.is_bound && eb.is_bound,
        }
    }

    /// `K Ē_T + (1 − Ē_T) Ē_B` for a clear layer (an estimate: exact for a
    /// base whose albedo is the same at every `μ`); with absorption, the
    /// default rule.
    fn average_albedo(&self) -> S {
        if self.absorption.is_some() {
            return crate::brdf::default_average_albedo(self);
        }
        let t = self.top.average_albedo();
        t * self.tint + t.map(|v| 1.0 - v) * self.base.average_albedo()
    }

    /// The base's (the top is prepared at construction already): the
    /// layer's own albedo and pick read both.
    fn with_prepared_albedo(self) -> Self {
        Self {
            base: self.base.with_prepared_albedo(),
            ..self
        }
    }
}

impl<T, B, S> IsotropicBrdf for Coated<T, B>
where
    T: IsotropicBrdf<Spectrum = S>,
    B: IsotropicBrdf<Spectrum = S>,
    S: Spectrum,
{
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `f = ρ (1 + μi μo)/(2π)`: an albedo that varies with `μ`.
    #[derive(Clone, Copy, Debug, PartialEq)]
    struct Tilted(f32);
    impl Brdf for Tilted {
        type Spectrum = f32;
        fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
            if wi.z > 0.0 && wo.z > 0.0 {
                self.0 * 0.5 * (1.0 + wi.z * wo.z) * core::f32::consts::FRAC_1_PI
            } else {
                0.0
            }
        }
        /// `ρ (1 + μo/2)/2` (closed form: `∫ μi dω/(2π) = ½`, `∫ μi² dω/(2π) = ⅓`).
        fn directional_albedo(&self, wo: Vec3) -> Albedo<f32> {
            if wo.z > 0.0 {
                Albedo::bounded(self.0 * 0.5 * (1.0 + wo.z * 2.0 / 3.0), 0.0)
            } else {
                Albedo::zero()
            }
        }
    }

    #[test]
    fn reciprocal_mode_is_symmetric_and_never_exceeds_the_one_sided_through_factor() {
        let layer = Coated::new(Tilted(0.3), Tilted(0.9)).with_layering(Layering::Reciprocal);
        let one_sided = Coated::new(Tilted(0.3), Tilted(0.9));
        for (wi, wo) in [
            (Vec3::new(0.6, 0.0, 0.8), Vec3::new(0.0, -0.28, 0.96)),
            (Vec3::new(0.0, 0.995, 0.0998), Vec3::Z),
        ] {
            assert_eq!(layer.eval(wi, wo).to_bits(), layer.eval(wo, wi).to_bits());
            // τ ≤ t(ωo): the reciprocal layer never passes more than the one-sided one.
            assert!(layer.eval(wi, wo) <= one_sided.eval(wi, wo) * (1.0 + 1e-6));
        }
    }
}
