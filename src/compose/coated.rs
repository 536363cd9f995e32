//! [`Coated`]: albedo-scaled layering of a top lobe over a base, in a
//! reciprocal, energy-safe form.

use super::{
    ComposeError, eval_batch_pair, finish_sample, mixture_pdf, pdf_batch_pair, pick_and_sample, pick_first,
};
use crate::brdf::{Albedo, Brdf, BrdfSample, IsotropicBrdf};
use crate::frame::cos_theta;
use crate::spectrum::Spectrum;
use glam::Vec3;

/// Number of nodes of the top's albedo table of a [`Coated`]: `μ_k =
/// (k/127)²`, `k = 0..128` (`μ_0` raised to `10⁻⁶`), dense near the horizon
/// where a lobe's albedo changes fastest (see [`Coated::table`] and
/// [`Coated::from_table`]).
pub const COATED_TABLE_NODES: usize = 128;
const TOP_NODES: usize = COATED_TABLE_NODES;

/// Smallest `μ` at which the top's albedo is read (the horizon itself has
/// albedo 0 by convention).
const MIN_NODE_MU: f32 = 1e-6;

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
/// top's smallest albedo over all directions (from the table of the top's
/// albedo read at construction); dividing by `1 − E_min` gives back the light that the
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
/// Cost: [`Coated::new`] reads the top's albedo at 128 directions into a
/// table (the top must be isotropic: its albedo a function of `μ` alone);
/// each `eval` then reads it twice — two square roots and four loads —
/// besides evaluating both lobes.
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
    /// The top's albedo at the nodes `μ_k = (k/127)²` (read once, at
    /// construction).
    table: [T::Spectrum; TOP_NODES],
    /// The largest error the top stated at the nodes.
    top_error: f32,
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
    /// `top` over `base`, clear (no absorption). Reads the top's albedo at
    /// 128 directions (`μ_k = (k/127)²`; the top is isotropic) into a table
    /// that `eval` reads (interpolated so as never to fall below the two values around `μ`), and takes
    /// `E_min` (the smallest tabulated value) and `E_avg` from it.
    pub fn new(top: T, base: B) -> Self {
        let mut table = [S::zero(); TOP_NODES];
        let mut top_error = 0.0f32;
        for (k, e) in table.iter_mut().enumerate() {
            let x = k as f32 / (TOP_NODES - 1) as f32;
            let mu = (x * x).max(MIN_NODE_MU);
            let s = libm::sqrtf((1.0 - mu * mu).max(0.0));
            let a = top.directional_albedo(Vec3::new(s, 0.0, mu));
            *e = a
                .value
                .map(|v| if v.is_finite() { v.clamp(0.0, 1.0) } else { 0.0 });
            if a.error.is_finite() {
                top_error = top_error.max(a.error);
            }
        }
        Self::from_valid_table(top, base, table, top_error)
    }

    /// `top` over `base` (clear) from a table of the top's albedo that
    /// [`Coated::new`] read before ([`Coated::table`], [`Coated::top_error`]):
    /// no albedo query, so a caller that keeps the table (the C API, which
    /// rebuilds the layer from plain data on every call) skips the 128
    /// queries. `table[k]` is the top's albedo at `μ_k = (k/127)²` (`μ_0 =
    /// 10⁻⁶`), each channel finite and in `[0, 1]`; `top_error` finite and
    /// `≥ 0`; otherwise [`ComposeError::AlbedoTable`] with the offending
    /// value. With the table and error of [`Coated::new`] the layer is equal
    /// to it (same `E_min`, `E_avg`, bit for bit). A table that is not the
    /// top's keeps every guarantee but energy (the layer is reciprocal and
    /// finite; its energy bound holds for the albedo the table states).
    /// [`Coated::absorbing`] adds a coat's absorption.
    pub fn from_table(top: T, base: B, table: [S; TOP_NODES], top_error: f32) -> Result<Self, ComposeError> {
        for e in &table {
            for c in 0..S::CHANNELS {
                let v = e.channel(c);
                if !(0.0..=1.0).contains(&v) {
                    return Err(ComposeError::AlbedoTable(v));
                }
            }
        }
        if !(top_error.is_finite() && top_error >= 0.0) {
            return Err(ComposeError::AlbedoTable(top_error));
        }
        Ok(Self::from_valid_table(top, base, table, top_error))
    }

    /// The layer of a validated table: `E_min` and `E_avg` from it.
    fn from_valid_table(top: T, base: B, table: [S; TOP_NODES], top_error: f32) -> Self {
        let e_min = table
            .iter()
            .fold(1.0f32, |m, e| m.min(e.min_channel()))
            .clamp(0.0, 0.999);
        // E_avg = 2∫E μ dμ by the trapezoid rule over the nodes.
        let mut average = 0.0f32;
        let mut prev = (0.0f32, 0.0f32);
        for (k, e) in table.iter().enumerate() {
            let x = k as f32 / (TOP_NODES - 1) as f32;
            let mu = x * x;
            let cur = (mu, 2.0 * e.average() * mu);
            if k > 0 {
                average += 0.5 * (cur.1 + prev.1) * (cur.0 - prev.0);
            }
            prev = cur;
        }
        Self {
            top,
            base,
            absorption: None,
            gain: 1.0 / (1.0 - e_min),
            average: average.clamp(0.0, 1.0),
            table,
            top_error,
            tint: S::splat(1.0),
        }
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

    /// The top's albedo at `μ` as the layer uses it: with nodes uniform in
    /// `x = 127 √μ` and `Ê_k = max(E_{k−1}, E_k, E_{k+1})` (the table
    /// dilated by one node), the linear interpolation of `Ê` — per channel,
    /// for `x ∈ [k, k + 1]`:
    ///
    /// ```text
    /// E_used(μ) = Ê_k + (x − k)(Ê_{k+1} − Ê_k)  ≥  max(E_k, E_{k+1})
    /// ```
    ///
    /// At least the larger of the two table values around `μ` (both `Ê_k` and
    /// `Ê_{k+1}` are), which keeps the energy bound where the albedo jumps
    /// between nodes (a smooth dielectric coat with `η < 1` turns to total
    /// internal reflection within a hair of its critical angle), and
    /// continuous in `μ`, so the layer's integrand has kinks, not steps, at
    /// the nodes (quadrature converges on it). In smooth parts it lets
    /// through at most about two node steps less than the table.
    #[inline]
    fn top_albedo(&self, mu: f32) -> S {
        let x = libm::sqrtf(mu.clamp(0.0, 1.0)) * (TOP_NODES - 1) as f32;
        let i = (x as usize).min(TOP_NODES - 2);
        let f = (x - i as f32).clamp(0.0, 1.0);
        let at = |k: usize| self.table.get(k).copied();
        // Ê_k needs k − 1 and k + 1; at the ends the missing neighbour is
        // left out.
        let dilated = |k: usize| {
            let mid = at(k)?;
            let lo = k.checked_sub(1).and_then(at).unwrap_or(mid);
            let hi = at(k + 1).unwrap_or(mid);
            Some(S::from_fn(|c| {
                lo.channel(c).max(mid.channel(c)).max(hi.channel(c))
            }))
        };
        match (dilated(i), dilated(i + 1)) {
            (Some(a), Some(b)) => S::from_fn(|c| {
                let (a, b) = (a.channel(c), b.channel(c));
                // Kept within [min, max] of the two (rounding), so ≥ the
                // larger table value as argued above. (`max`/`min` rather
                // than `clamp`, which checks its bounds at run time.)
                (a + (b - a) * f).max(a.min(b)).min(a.max(b))
            }),
            _ => S::zero(),
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
    /// builds it (`coat_color ∈ [0, 1]` per channel, `ior ≥ 1`): for a layer
    /// made by [`Coated::from_table`].
    pub fn absorbing(mut self, coat_color: S, ior: f32) -> Result<Self, ComposeError> {
        check_coat(coat_color, ior)?;
        self.absorption = Some((coat_color, ior));
        Ok(self)
    }

    /// The top's albedo at the nodes `μ_k = (k/127)²`, `k = 0..128`, as
    /// [`Coated::new`] read it (each channel in `[0, 1]`); with
    /// [`Coated::top_error`], what [`Coated::from_table`] takes back.
    pub fn table(&self) -> &[S; TOP_NODES] {
        &self.table
    }

    /// The largest error the top stated for its albedo at the table's nodes.
    pub fn top_error(&self) -> f32 {
        self.top_error
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
        self.top_albedo(cos_theta(w))
            .map(|v| ((1.0 - v).clamp(0.0, 1.0) * self.gain).min(1.0))
    }

    /// Whether both directions are strictly above the horizon.
    #[inline]
    fn both_above(wi: Vec3, wo: Vec3) -> bool {
        let (mi, mo) = (cos_theta(wi), cos_theta(wo));
        !((mi.is_nan() || mi <= 0.0) || (mo.is_nan() || mo <= 0.0))
    }

    /// `K ⊙ f_T + τ ⊙ f_B` from the lobes' values (both directions above the
    /// horizon).
    #[inline]
    fn layer(&self, wi: Vec3, wo: Vec3, f_top: S, fb: S) -> S {
        let top = f_top * self.tint;
        if fb.is_black() {
            return top;
        }
        let tau = self.absorption(cos_theta(wi), cos_theta(wo))
            * (self.through_scaled(wi) * self.through_scaled(wo))
            * (1.0 / self.gain);
        top + tau * fb
    }

    /// The probability of drawing from the top at `wo`.
    pub fn pick_probability(&self, wo: Vec3) -> f32 {
        let mu = cos_theta(wo);
        if mu.is_nan() || mu <= 0.0 {
            return 0.5;
        }
        let et = self.top_albedo(mu);
        let through = self.absorption(mu, mu)
            * et.map(|e| (1.0 - e).clamp(0.0, 1.0))
            * self.base.directional_albedo(wo).value;
        pick_first((et * self.tint).average(), through.average())
    }
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

    fn eval(&self, wi: Vec3, wo: Vec3) -> S {
        if !Self::both_above(wi, wo) {
            return S::zero();
        }
        self.layer(wi, wo, self.top.eval(wi, wo), self.base.eval(wi, wo))
    }

    /// The lobes' own batch kernels, layered as [`eval`](Brdf::eval) layers
    /// them (element by element equal).
    fn eval_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [S]) {
        eval_batch_pair(&self.top, &self.base, wi, wo, out, |i, o, ft, fb| {
            if Self::both_above(i, o) {
                self.layer(i, o, ft, fb)
            } else {
                S::zero()
            }
        });
    }

    /// The lobes' own `pdf_batch` kernels, mixed with the pick probability
    /// at each `ωo` (element by element equal to [`pdf`](Brdf::pdf)).
    fn pdf_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]) {
        pdf_batch_pair(Some(&self.top), Some(&self.base), wi, wo, out, |w, x, y| {
            mixture_pdf(self.pick_probability(w), x, y)
        });
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
        let et = self.top_albedo(mu);
        let eb = self.base.directional_albedo(wo);
        let through = et.map(|e| (1.0 - e).clamp(0.0, 1.0));
        let upper = through * eb.value; // g · X ≤ E_B
        let est = upper * self.absorption(mu, mu) * (self.gain * (1.0 - self.average)).min(1.0);
        let spread = (upper - est).max_channel().max(est.max_channel());
        Albedo {
            value: et * self.tint + est,
            error: self.top_error * (1.0 + eb.value.max_channel()) + eb.error + spread,
            // The table's interpolation error is not bounded.
            is_bound: false,
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
    }

    #[test]
    fn from_table_rebuilds_the_layer_bit_for_bit_and_rejects_bad_tables() {
        let layer = Coated::new(Tilted(0.3), Tilted(0.9));
        assert!(
            layer.table().iter().any(|&e| e != layer.table()[127]),
            "the table varies with μ"
        );
        let again = Coated::from_table(Tilted(0.3), Tilted(0.9), *layer.table(), layer.top_error()).unwrap();
        assert_eq!(again, layer);
        let (wi, wo) = (Vec3::new(0.6, 0.0, 0.8), Vec3::new(0.0, -0.28, 0.96));
        assert_eq!(again.eval(wi, wo).to_bits(), layer.eval(wi, wo).to_bits());
        assert_eq!(again.pdf(wi, wo).to_bits(), layer.pdf(wi, wo).to_bits());
        let tinted = Coated::with_absorption(Tilted(0.3), Tilted(0.9), 0.6, 1.5).unwrap();
        assert_eq!(again.absorbing(0.6, 1.5), Ok(tinted));
        assert!(matches!(again.absorbing(0.6, 0.5), Err(ComposeError::CoatIor(_))));
        for bad in [-0.1, 1.5, f32::NAN, f32::INFINITY] {
            let mut t = *layer.table();
            t[17] = bad;
            let e = Coated::from_table(Tilted(0.3), Tilted(0.9), t, 0.0).unwrap_err();
            assert!(
                matches!(e, ComposeError::AlbedoTable(v) if v.to_bits() == bad.to_bits()),
                "{e:?}"
            );
        }
        for bad in [-1.0, f32::NAN] {
            assert!(matches!(
                Coated::from_table(Tilted(0.3), Tilted(0.9), *layer.table(), bad),
                Err(ComposeError::AlbedoTable(_))
            ));
        }
    }
}
