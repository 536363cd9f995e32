//! [`Coated`]: albedo-scaled layering of a top lobe over a base, in a
//! reciprocal, energy-safe form.

use super::{ComposeError, finish_sample, mixture_pdf, pick_and_sample, pick_first};
use crate::brdf::{Albedo, Brdf, BrdfSample, IsotropicBrdf};
use crate::frame::cos_theta;
use crate::spectrum::Spectrum;
use glam::Vec3;

/// Number of `μ` nodes (midpoints of 32 equal cells, plus `μ = 1`) at which
/// [`Coated::new`] reads the top's albedo for `E_min` and `E_avg`.
const ALBEDO_NODES: u8 = 32;

/// Subtracted from the smallest albedo seen at the nodes, so that
/// `E_min` stays below the top's true minimum between nodes (the energy
/// guarantee needs `E_top ≥ E_min` everywhere).
const MIN_ALBEDO_MARGIN: f32 = 1e-3;

/// A coat: a top lobe (a clear or tinted dielectric interface, a sheen)
/// over a base, by albedo scaling (OpenPBR Surface 1.1, §"Layering"):
///
/// ```text
/// f(ωi, ωo) = f_T(ωi, ωo) + τ(ωi, ωo) ⊙ f_B(ωi, ωo)
/// τ(ωi, ωo) = A(μi, μo) ⊙ t(ωi) ⊙ t(ωo) (1 − E_min)
/// t(ω)      = min((1 − E_T(ω)) / (1 − E_min), 1)
/// A(μi, μo) = C^{(1/μᵗi + 1/μᵗo)/2},   μᵗ = √(1 − (1 − μ²)/η²)
/// ```
///
/// `E_T` is the top's [directional albedo](Brdf::directional_albedo) (its
/// value, not the upper end of its error: the plugins' bounds for Fresnel
/// tops are wide, and the base would go dark under them): light
/// the top reflects never reaches the base, once on the way in and once on
/// the way out — a product, so `τ` is symmetric and the layer stays
/// **reciprocal** (OpenPBR's `(1 − E_T(ωo))` alone is not). `E_min` is the
/// top's smallest albedo over all directions (read at construction, less a
/// margin of `10⁻³`); dividing by `1 − E_min` gives back the light that the
/// two-way product would lose to the top's *average* reflectance, as far
/// as that is safe:
///
/// * **Energy**: `t ≤ 1`, so `E(ωo) ≤ E_T(ωo) + (1 − E_T(ωo)) E_B(ωo) ≤ 1`
///   for any base with `E_B ≤ 1` and any top with `E_T ≤ 1` — with `E_T` the
///   value the top reports; where that value is below the top's true
///   albedo, the layer can exceed 1 by at most the difference times `E_B`
///   (so by at most the top's stated albedo error).
/// * **Furnace**: with a white Lambertian base and a clear coat,
///   `E(ωo) = 1 − (1 − E_T(ωo)) (E_avg − E_min)/(1 − E_min)`, where
///   `E_avg = 2∫E_T μ dμ` — a smooth dielectric coat of η = 1.5 keeps
///   about 95 % (the light internal reflections would return is not
///   modelled; see OpenPBR's "coat darkening", which a caller applies to the
///   base with [`Scaled`](super::Scaled)).
///
/// `A` is the coat's absorption with OpenPBR's parameters: `C` =
/// `coat_color`, the square of the transmittance at normal incidence, and
/// the path length through a coat of index `η` along the refracted
/// directions (OpenPBR §"Coat — view-dependent absorption"). Without
/// absorption ([`Coated::new`]) `A = 1`.
///
/// Sampling picks the top with probability `Ē_T / (Ē_T + Ē_through)` at `ωo`
/// (`Ē_through` = the channel average of `A(μo, μo)(1 − E_T(ωo)) E_B(ωo)`),
/// with the mixture density; `pdf(sample) == sample.pdf` bit for bit.
///
/// Cost: each `eval` asks the top for its albedo at `ωi` and `ωo` — cheap for
/// the plugins (closed forms and tables), 16 samples each for a lobe that
/// keeps the default [`Brdf::directional_albedo`].
///
/// ```
/// use radiometry::compose::Coated;
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
/// let layer = Coated::new(Flat(0.1), Flat(1.0));
/// let wo = Vec3::new(0.0, 0.6, 0.8);
/// let e = layer.directional_albedo(wo);
/// assert!(e.value <= 1.0 + e.error);
/// let wi = Vec3::new(0.6, 0.0, 0.8);
/// assert_eq!(layer.eval(wi, wo), layer.eval(wo, wi)); // reciprocal
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Coated<T: Brdf, B> {
    top: T,
    base: B,
    /// `coat_color` (`C`) and the coat's index of refraction, if absorbing.
    absorption: Option<(T::Spectrum, f32)>,
    /// `1 / (1 − E_min)`.
    gain: f32,
    /// `E_avg = 2∫E_T μ dμ` (for the albedo estimate).
    average: f32,
}

impl<T, B, S> Coated<T, B>
where
    T: Brdf<Spectrum = S>,
    B: Brdf<Spectrum = S>,
    S: Spectrum,
{
    /// `top` over `base`, clear (no absorption). Reads the top's albedo at
    /// 33 directions for `E_min` and `E_avg`.
    pub fn new(top: T, base: B) -> Self {
        let (gain, average) = top_albedo_summary(&top);
        Self {
            top,
            base,
            absorption: None,
            gain,
            average,
        }
    }

    /// `top` over `base` through an absorbing coat: `coat_color` (`C ∈ [0,
    /// 1]` per channel, the square of the normal-incidence transmittance) and
    /// the coat's index of refraction `ior ≥ 1` (relative to the outside).
    pub fn with_absorption(top: T, base: B, coat_color: S, ior: f32) -> Result<Self, ComposeError> {
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
        let mut c = Self::new(top, base);
        c.absorption = Some((coat_color, ior));
        Ok(c)
    }

    /// The top lobe.
    pub fn top(&self) -> &T {
        &self.top
    }

    /// The base lobe.
    pub fn base(&self) -> &B {
        &self.base
    }

    /// `1/(1 − E_min)`, the factor that hands the base back what the top's
    /// least reflective direction would lose twice.
    pub fn gain(&self) -> f32 {
        self.gain
    }

    /// The absorption factor `A(μi, μo)` (1 per channel without absorption).
    fn absorption(&self, mu_i: f32, mu_o: f32) -> S {
        match self.absorption {
            None => S::splat(1.0),
            Some((color, eta)) => {
                let refracted = |mu: f32| {
                    let s2 = (1.0 - mu * mu).max(0.0) / (eta * eta);
                    libm::sqrtf((1.0 - s2).max(0.0))
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
        }
    }

    /// `min(g (1 − E_T(ω)), 1)` per channel: what the top lets through,
    /// scaled by the gain `g = 1/(1 − E_min)` and capped at 1 (the cap keeps
    /// the energy bound where the top's albedo dips below `E_min` between
    /// the nodes it was read at).
    #[inline]
    fn through_scaled(&self, w: Vec3) -> S {
        let e = self.top.directional_albedo(w);
        e.value.map(|v| ((1.0 - v).clamp(0.0, 1.0) * self.gain).min(1.0))
    }

    /// The probability of drawing from the top at `wo`.
    pub fn pick_probability(&self, wo: Vec3) -> f32 {
        let et = self.top.directional_albedo(wo).value;
        let mu = cos_theta(wo);
        let through = self.absorption(mu, mu)
            * et.map(|e| (1.0 - e).clamp(0.0, 1.0))
            * self.base.directional_albedo(wo).value;
        pick_first(et.average(), through.average())
    }
}

/// `(1/(1 − E_min), E_avg)` of a top lobe from its albedo at `μ = 1` and the
/// midpoints of 32 cells of `[0, 1]`.
fn top_albedo_summary<T: Brdf + ?Sized>(top: &T) -> (f32, f32) {
    let at = |mu: f32| {
        let s = libm::sqrtf((1.0 - mu * mu).max(0.0));
        let e = top.directional_albedo(Vec3::new(s, 0.0, mu));
        let lo = (e.value.min_channel() - e.error).max(0.0);
        let avg = e.value.average();
        (
            if lo.is_finite() { lo } else { 0.0 },
            if avg.is_finite() { avg } else { 0.0 },
        )
    };
    let (mut e_min, _) = at(1.0);
    let mut avg = 0.0f32;
    for k in 0..ALBEDO_NODES {
        let mu = (f32::from(k) + 0.5) / f32::from(ALBEDO_NODES);
        let (lo, a) = at(mu);
        e_min = e_min.min(lo);
        avg += 2.0 * a * mu / f32::from(ALBEDO_NODES);
    }
    let e_min = (e_min - MIN_ALBEDO_MARGIN).clamp(0.0, 0.999);
    (1.0 / (1.0 - e_min), avg.clamp(0.0, 1.0))
}

impl<T, B, S> Brdf for Coated<T, B>
where
    T: Brdf<Spectrum = S>,
    B: Brdf<Spectrum = S>,
    S: Spectrum,
{
    type Spectrum = S;

    fn eval(&self, wi: Vec3, wo: Vec3) -> S {
        let (mi, mo) = (cos_theta(wi), cos_theta(wo));
        if (mi.is_nan() || mi <= 0.0) || (mo.is_nan() || mo <= 0.0) {
            return S::zero();
        }
        let fb = self.base.eval(wi, wo);
        let top = self.top.eval(wi, wo);
        if fb.is_black() {
            return top;
        }
        let tau =
            self.absorption(mi, mo) * (self.through_scaled(wi) * self.through_scaled(wo)) * (1.0 / self.gain);
        top + tau * fb
    }

    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<S>> {
        let p = self.pick_probability(wo);
        let wi = pick_and_sample(p, u, |v| self.top.sample(wo, v), |v| self.base.sample(wo, v))?;
        let pdf = mixture_pdf(p, self.top.pdf(wi, wo), self.base.pdf(wi, wo));
        finish_sample(wi, self.eval(wi, wo), pdf)
    }

    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        let p = self.pick_probability(wo);
        mixture_pdf(p, self.top.pdf(wi, wo), self.base.pdf(wi, wo))
    }

    /// `false`: `τ` reads the top's albedo at `ωi`, which the plugins take
    /// from interpolated tables (and the default rule from samples that may
    /// fall below the horizon) — not an analytic function of `ωi`.
    fn is_smooth(&self) -> bool {
        false
    }

    /// `E = E_T(ωo) + (1 − E_T(ωo)) g X`, `X = ∫(1 − E_T(ωi)) A f_B cos θi dωi`,
    /// estimated as `X ≈ (1 − E_avg) A(μo, μo) E_B(ωo)` (exact for a
    /// Lambertian base under a clear coat); `0 ≤ X ≤ E_B/g` bounds the error.
    fn directional_albedo(&self, wo: Vec3) -> Albedo<S> {
        let mu = cos_theta(wo);
        if mu.is_nan() || mu <= 0.0 {
            return Albedo::zero();
        }
        let et = self.top.directional_albedo(wo);
        let eb = self.base.directional_albedo(wo);
        let through = et.value.map(|e| (1.0 - e).clamp(0.0, 1.0));
        let upper = through * eb.value; // g · X ≤ E_B
        let est = upper * self.absorption(mu, mu) * (self.gain * (1.0 - self.average)).min(1.0);
        let spread = (upper - est).max_channel().max(est.max_channel());
        Albedo {
            value: et.value + est,
            error: et.error * (1.0 + eb.value.max_channel()) + eb.error + spread,
            is_bound: et.is_bound && eb.is_bound,
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
