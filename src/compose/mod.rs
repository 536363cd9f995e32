//! Lobe combinators: sums, weighted mixes, scaled lobes and albedo-scaled
//! layering of any [`Brdf`]s — the plugins of `radiometry-brdfs` and
//! third-party ones alike.
//!
//! | type | BRDF | sampling |
//! |---|---|---|
//! | [`Sum<A, B>`](Sum) | `f_A + f_B` | lobe `A` with probability `Ē_A / (Ē_A + Ē_B)` |
//! | [`Mix<A, B>`](Mix) | `w f_A + (1 − w) f_B`, `w ∈ [0, 1]` | lobe `A` with probability `w Ē_A / (w Ē_A + (1 − w) Ē_B)` |
//! | [`Scaled<B, S>`](Scaled) | `s ⊙ f_B`, `s ≥ 0` per channel | that of `B` |
//! | [`Coated<T, B>`](Coated) | `f_T + τ(ωi, ωo) ⊙ f_B`, `τ` what the top lets through ([`Layering`]: energy-conserving or reciprocal) | top or base, by their albedos |
//! | [`Precomputed<B>`](Precomputed) | `f_B`, its albedo read once into a table | that of `B` |
//!
//! `Ē` is the channel average of a lobe's [directional
//! albedo](Brdf::directional_albedo) at `ωo`: lobes are picked in proportion
//! to the light they reflect, not by fixed weights, so a dim lobe costs few
//! samples. The density of a composite is the matching mixture
//! `p_A pdf_A + p_B pdf_B`; `sample` returns exactly `pdf(wi, wo)`, bit for
//! bit, because both compute the picking probabilities from `ωo` alone with
//! the same expression. Combinators nest (`Sum<Sum<A, B>, C>` is a
//! three-lobe sum) and cost nothing where they are not used.
//!
//! ```
//! use radiometry::compose::Sum;
//! use radiometry::{Brdf, glam::Vec3};
//! struct Flat(f32); // f = ρ/π
//! impl Brdf for Flat {
//!     type Spectrum = f32;
//!     fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
//!         if wi.z > 0.0 && wo.z > 0.0 { self.0 * core::f32::consts::FRAC_1_PI } else { 0.0 }
//!     }
//! }
//! let two = Sum::new(Flat(0.2), Flat(0.3));
//! let wo = Vec3::new(0.0, 0.6, 0.8);
//! let s = two.sample(wo, [0.7, 0.4]).unwrap();
//! assert_eq!(s.pdf, two.pdf(s.wi, wo)); // bit for bit
//! assert!((two.eval(s.wi, wo) - 0.5 * core::f32::consts::FRAC_1_PI).abs() < 1e-7);
//! ```

mod coated;
mod error;
mod mix;
mod precomputed;
mod scaled;
mod sum;

pub use coated::{Coated, CoatedView, coat_absorption};
pub use error::ComposeError;
pub use mix::Mix;
pub use precomputed::Precomputed;
pub use scaled::Scaled;
pub use sum::Sum;

use crate::brdf::{Albedo, Brdf, BrdfSample};
use crate::frame::cos_theta;
use crate::spectrum::Spectrum;
use glam::Vec3;

/// Elements per chunk of the composites' batch paths (two stack buffers of
/// this many values per lobe pair).
const CHUNK: usize = 32;

/// `out[k] = combine(wi[k], wo[k], f_A[k], f_B[k])` with `f_A`, `f_B` from
/// the lobes' own [`Brdf::eval_batch`] kernels, in chunks of [`CHUNK`]; the
/// [batch length rule](crate::batch::zero_tail) for the rest of `out`. Equal
/// to the scalar path element by element when each lobe's batch equals its
/// scalar `eval` (the plugins' batches do, bit for bit).
#[inline]
pub(crate) fn eval_batch_pair<S, A, B>(
    a: &A,
    b: &B,
    wi: &[Vec3],
    wo: &[Vec3],
    out: &mut [S],
    combine: impl Fn(Vec3, Vec3, S, S) -> S,
) where
    S: Spectrum,
    A: Brdf<Spectrum = S> + ?Sized,
    B: Brdf<Spectrum = S> + ?Sized,
{
    let mut fa = [S::zero(); CHUNK];
    let mut fb = [S::zero(); CHUNK];
    for ((wi, wo), out) in wi.chunks(CHUNK).zip(wo.chunks(CHUNK)).zip(out.chunks_mut(CHUNK)) {
        a.eval_batch(wi, wo, &mut fa);
        b.eval_batch(wi, wo, &mut fb);
        for ((o, (&x, &y)), (&i, &j)) in out.iter_mut().zip(fa.iter().zip(&fb)).zip(wi.iter().zip(wo)) {
            *o = combine(i, j, x, y);
        }
    }
    crate::batch::zero_tail(out, wi.len().min(wo.len()));
}

/// [`eval_batch_pair`] for structure-of-arrays input: the lobes' own
/// [`Brdf::eval_batch_soa`] kernels in chunks of [`CHUNK`], then `combine`
/// element by element; equal to the scalar path element by element when each
/// lobe's SoA batch equals its scalar `eval` (the plugins' do, bit for bit).
#[inline]
pub(crate) fn eval_batch_soa_pair<S, A, B>(
    a: &A,
    b: &B,
    wi: crate::batch::Vec3Soa<'_>,
    wo: crate::batch::Vec3Soa<'_>,
    out: &mut [S],
    combine: impl Fn(Vec3, Vec3, S, S) -> S,
) where
    S: Spectrum,
    A: Brdf<Spectrum = S> + ?Sized,
    B: Brdf<Spectrum = S> + ?Sized,
{
    let mut fa = [S::zero(); CHUNK];
    let mut fb = [S::zero(); CHUNK];
    soa_chunks(wi, wo, out, |ci, co, oc| {
        a.eval_batch_soa(ci, co, &mut fa);
        b.eval_batch_soa(ci, co, &mut fb);
        for ((o, (&x, &y)), (i, j)) in oc
            .iter_mut()
            .zip(fa.iter().zip(&fb))
            .zip(soa_dirs(ci).zip(soa_dirs(co)))
        {
            *o = combine(i, j, x, y);
        }
    });
}

/// Calls `f(wi_chunk, wo_chunk, out_chunk)` on consecutive chunks of at most
/// [`CHUNK`] elements of the first `n = min(len)` directions, after the
/// [batch length rule](crate::batch::zero_tail) for the rest of `out`.
pub(crate) fn soa_chunks<S: Spectrum>(
    wi: crate::batch::Vec3Soa<'_>,
    wo: crate::batch::Vec3Soa<'_>,
    out: &mut [S],
    mut f: impl FnMut(crate::batch::Vec3Soa<'_>, crate::batch::Vec3Soa<'_>, &mut [S]),
) {
    let n = wi.len().min(wo.len()).min(out.len());
    crate::batch::zero_tail(out, n);
    // Chunks by checked splits (no division by the chunk size, no slice
    // index that could panic).
    let (mut ri, mut ro, mut rest) = (wi, wo, out);
    let mut done = 0;
    while done < n {
        let k = CHUNK.min(n - done);
        let (Some((ci, ni)), Some((co, no))) = (split_soa(ri, k), split_soa(ro, k)) else {
            break;
        };
        let Some((oc, on)) = core::mem::take(&mut rest).split_at_mut_checked(k) else {
            break;
        };
        f(ci, co, oc);
        (ri, ro, rest) = (ni, no, on);
        done += k;
    }
}

/// The first `k` directions of a structure-of-arrays view and the rest
/// (`None` if a component is shorter than `k`).
fn split_soa(
    v: crate::batch::Vec3Soa<'_>,
    k: usize,
) -> Option<(crate::batch::Vec3Soa<'_>, crate::batch::Vec3Soa<'_>)> {
    let (x0, x1) = v.x.split_at_checked(k)?;
    let (y0, y1) = v.y.split_at_checked(k)?;
    let (z0, z1) = v.z.split_at_checked(k)?;
    Some((
        crate::batch::Vec3Soa::new(x0, y0, z0),
        crate::batch::Vec3Soa::new(x1, y1, z1),
    ))
}

/// The directions of a structure-of-arrays view.
fn soa_dirs(v: crate::batch::Vec3Soa<'_>) -> impl Iterator<Item = Vec3> + '_ {
    v.x.iter()
        .zip(v.y)
        .zip(v.z)
        .map(|((&x, &y), &z)| Vec3::new(x, y, z))
}

/// `out[k] = mix(wo[k], pdf_A[k], pdf_B[k])` with the lobes' densities from
/// their [`Brdf::pdf_batch`] kernels (`None` for a lobe skips it: its
/// density is taken as 0), in chunks; the batch length rule for the rest.
#[inline]
pub(crate) fn pdf_batch_pair<A, B>(
    a: Option<&A>,
    b: Option<&B>,
    wi: &[Vec3],
    wo: &[Vec3],
    out: &mut [f32],
    mix: impl Fn(Vec3, f32, f32) -> f32,
) where
    A: Brdf + ?Sized,
    B: Brdf + ?Sized,
{
    let mut pa = [0.0f32; CHUNK];
    let mut pb = [0.0f32; CHUNK];
    for ((wi, wo), out) in wi.chunks(CHUNK).zip(wo.chunks(CHUNK)).zip(out.chunks_mut(CHUNK)) {
        if let Some(a) = a {
            a.pdf_batch(wi, wo, &mut pa);
        }
        if let Some(b) = b {
            b.pdf_batch(wi, wo, &mut pb);
        }
        for ((o, (&x, &y)), &w) in out.iter_mut().zip(pa.iter().zip(&pb)).zip(wo) {
            *o = mix(w, x, y);
        }
    }
    crate::batch::zero_tail(out, wi.len().min(wo.len()));
}

/// How a layer ([`Coated`], `radiometry_brdfs::OpenPbr`) scales the light
/// that reaches what lies beneath its top.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Layering {
    /// OpenPBR's albedo scaling, `1 − E_T(ωo)` (the default): a white base
    /// under a clear top keeps all its energy. Not reciprocal.
    #[default]
    EnergyConserving,
    /// A symmetric factor in `(ωi, ωo)` ([`reciprocal_through`]), for
    /// bidirectional methods; energy ≤ 1 for every base.
    Reciprocal,
}

/// The reciprocal layering's through-factor of a top whose albedo leaves
/// `ti = 1 − E_T(μi)` and `to = 1 − E_T(μo)`, with `inv_avg = 1/(1 − Ē_T)`:
///
/// ```text
/// τ = min(ti to / (1 − Ē_T), ti, to)
/// ```
///
/// Symmetric; the Kelemen & Szirmay-Kalos (2001) form, under which a
/// Lambertian base keeps exactly `ρ (1 − E_T(μo))`, where the caps do not
/// bind (`E_T(μo) ≥ Ē_T`); the caps keep `∫τ f_B cos θi dωi ≤ to E_B(ωo)`
/// for every base, so `E ≤ 1` whenever `E_T, E_B ≤ 1`.
#[inline]
pub fn reciprocal_through(ti: f32, to: f32, inv_avg: f32) -> f32 {
    let v = (ti * to * inv_avg).min(ti).min(to);
    if v.is_finite() { v.max(0.0) } else { 0.0 }
}

/// The largest `f32` below 1: remapped sample coordinates stay in `[0, 1)`.
const ONE_MINUS_EPS: f32 = 1.0 - f32::EPSILON / 2.0;

/// The default [`Brdf::directional_albedo`]: the mean of the 16 sample
/// weights `f cos θi / pdf` of `b`'s own sampler at the stratified points
/// `u = ((i + ½)/4, (j + ½)/4)`, `i, j ∈ 0..4` (a missing sample counts as
/// 0), with the standard error of that mean as an estimated error.
///
/// Exact for a lobe its sampler matches exactly (constant weights); zero
/// when `ωo` is at or below the horizon.
pub fn albedo_by_sampling<B: Brdf + ?Sized>(b: &B, wo: Vec3) -> Albedo<B::Spectrum> {
    if !cos_theta(wo).is_finite() || cos_theta(wo) <= 0.0 {
        return Albedo::zero();
    }
    let mut sum = B::Spectrum::zero();
    let mut averages = [0.0f32; 16];
    for (k, a) in (0..16u8).zip(averages.iter_mut()) {
        let u = [(f32::from(k % 4) + 0.5) / 4.0, (f32::from(k / 4) + 0.5) / 4.0];
        if let Some(s) = b.sample(wo, u)
            && s.weight.is_finite()
        {
            let w = s.weight.map(|v| v.max(0.0));
            sum += w;
            *a = w.average();
        }
    }
    let mean = sum / 16.0;
    let m = mean.average();
    // Two-pass sample variance of the channel averages, over 16 · 15.
    let var = averages.iter().map(|a| (a - m) * (a - m)).sum::<f32>() / (16.0 * 15.0);
    let error = crate::math::sqrtf(var);
    Albedo {
        value: mean,
        error: if error.is_finite() { error } else { 0.0 },
        is_bound: false,
    }
}

/// A composite's value with every channel saturated at `f32::MAX` (NaN →
/// 0): a lobe reports at most `f32::MAX` where `1/(μi μo)` overflows at
/// subnormal cosines, and a sum of two such values must stay finite.
#[inline(always)]
pub(crate) fn saturate<S: Spectrum>(v: S) -> S {
    v.map(|x| if x.is_nan() { 0.0 } else { x.min(f32::MAX) })
}

/// Probability of picking the first of two lobes whose (weighted) albedo
/// averages at `ωo` are `a` and `b`: `a / (a + b)`, or `½` when neither
/// reflects anything (or an input is not finite).
#[inline]
pub(crate) fn pick_first(a: f32, b: f32) -> f32 {
    let a = if a.is_finite() { a.max(0.0) } else { 0.0 };
    let b = if b.is_finite() { b.max(0.0) } else { 0.0 };
    let t = a + b;
    if t > 0.0 && t.is_finite() {
        (a / t).clamp(0.0, 1.0)
    } else {
        0.5
    }
}

/// The mixture density `p pdf_A + (1 − p) pdf_B` — the one expression every
/// two-lobe combinator's `sample` and `pdf` share, so the two agree bit for bit.
#[inline]
pub(crate) fn mixture_pdf(p: f32, pdf_a: f32, pdf_b: f32) -> f32 {
    let v = p * pdf_a + (1.0 - p) * pdf_b;
    if v.is_finite() && v > 0.0 { v } else { 0.0 }
}

/// Draws from lobe `a` with probability `p`, else from lobe `b`, reusing
/// `u[0]` (rescaled into `[0, 1)`) for the chosen lobe; `None` when the lobe
/// returns none. The caller computes the mixture pdf and weight.
#[inline]
pub(crate) fn pick_and_sample<S: Spectrum>(
    p: f32,
    u: [f32; 2],
    a: impl FnOnce([f32; 2]) -> Option<BrdfSample<S>>,
    b: impl FnOnce([f32; 2]) -> Option<BrdfSample<S>>,
) -> Option<Vec3> {
    let (first, v) = pick_u(p, u);
    let s = if first { a(v) } else { b(v) }?;
    Some(s.wi)
}

/// The pick of [`pick_and_sample`]: whether `u[0]` draws lobe `a` (with
/// probability `p`) and the sample point `[u₀', u[1]]` for the chosen lobe,
/// `u₀` rescaled into `[0, 1)`.
#[inline]
pub(crate) fn pick_u(p: f32, u: [f32; 2]) -> (bool, [f32; 2]) {
    let u0 = if u[0].is_finite() {
        u[0].clamp(0.0, ONE_MINUS_EPS)
    } else {
        0.0
    };
    if u0 < p {
        (true, [(u0 / p).min(ONE_MINUS_EPS), u[1]])
    } else {
        (false, [((u0 - p) / (1.0 - p)).clamp(0.0, ONE_MINUS_EPS), u[1]])
    }
}

/// The sample of a composite with value `f` and mixture density `pdf` at the
/// drawn `wi`: `None` unless `pdf > 0` (then `weight = f cos θi / pdf`).
#[inline]
pub(crate) fn finish_sample<S: Spectrum>(wi: Vec3, f: S, pdf: f32) -> Option<BrdfSample<S>> {
    if (pdf.is_nan() || pdf <= 0.0) || !pdf.is_finite() {
        return None;
    }
    let weight = f * (cos_theta(wi).max(0.0) / pdf);
    if !weight.is_finite() {
        return None;
    }
    Some(BrdfSample { wi, pdf, weight })
}

/// [`Brdf::sampling_components`] of a two-lobe mixture: the components of
/// lobe `a`, then those of lobe `b` (flattened: nested composites list
/// their leaves' components).
#[inline]
pub(crate) fn pair_components<A: Brdf + ?Sized, B: Brdf + ?Sized>(a: &A, b: &B) -> usize {
    a.sampling_components().saturating_add(b.sampling_components())
}

/// [`Brdf::component_weight`] of a two-lobe mixture that picks `a` with
/// probability `p` (the pick probability its `sample` and `pdf` use): `p`
/// times `a`'s weight of component `k`, or `1 − p` times `b`'s weight of
/// component `k − n_a` — so `Σ c_k p_k = p pdf_A + (1 − p) pdf_B`, the
/// mixture density.
#[inline]
pub(crate) fn pair_weight<A, B>(p: f32, a: &A, b: &B, wo: Vec3, k: usize) -> f32
where
    A: Brdf + ?Sized,
    B: Brdf + ?Sized,
{
    let na = a.sampling_components();
    if k < na {
        p * a.component_weight(wo, k)
    } else {
        (1.0 - p) * b.component_weight(wo, k - na)
    }
}

/// [`Brdf::sample_component`] of a two-lobe mixture: component `k` of `a`,
/// or component `k − n_a` of `b`.
#[inline]
pub(crate) fn pair_sample<A, B>(a: &A, b: &B, wo: Vec3, k: usize, u: [f32; 2]) -> Option<Vec3>
where
    A: Brdf + ?Sized,
    B: Brdf + ?Sized,
{
    let na = a.sampling_components();
    if k < na {
        a.sample_component(wo, k, u)
    } else {
        b.sample_component(wo, k - na, u)
    }
}

/// Sum of two albedos with their errors (bounded only if both are).
#[inline]
pub(crate) fn add_albedo<S: Spectrum>(a: Albedo<S>, b: Albedo<S>) -> Albedo<S> {
    Albedo {
        value: a.value + b.value,
        error: a.error + b.error,
        is_bound: a.is_bound && b.is_bound,
    }
}

#[cfg(test)]
mod tests;
