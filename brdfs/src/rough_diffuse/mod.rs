//! Rough diffuse reflection: the Oren–Nayar family.
//!
//! Oren & Nayar (1994, "Generalization of Lambert's reflectance model",
//! SIGGRAPH) model a rough diffuse surface as V-cavities of Lambertian
//! facets: compared with Lambert it is flatter (less darkening toward the
//! rim) and brighter toward the light (back-scattering). All three plugins
//! here share the shape
//!
//! ```text
//! f_r(ωi, ωo) = (ρ/π) (A + B · s/t),   s = ωi·ωo − cos θi cos θo = sin θi sin θo cos(φi − φo),
//! ```
//!
//! differing in `A`, `B`, `t` and in what they add:
//!
//! | plugin | model | roughness parameter | albedo at `ρ = 1` | spec grammar |
//! |---|---|---|---|---|
//! | [`Fon<S>`](Fon) | Fujii's improved Oren–Nayar ("FON") in the form of Portsmouth, Kutz & Hill 2025: `A = 1/(1 + c₁σ)`, `B = σA`, `t = max(cos θi, cos θo)` where `s > 0`, else 1 | `σ ∈ [0, 1]`, dimensionless (the EON paper's and OpenPBR's `base_diffuse_roughness`) | `E_FON(μo) < 1` (loses up to 22 % at `σ = 1`) | `fon(rho=R, sigma=S)` |
//! | [`Eon<S>`](Eon) | FON plus the closed-form multiple-scattering lobe of the same paper ("EON") | `σ ∈ [0, 1]`, as FON | exactly 1 for every `θo` (white furnace) | `eon(rho=R, sigma=S)` |
//! | [`OrenNayar<S>`](OrenNayar) | the classic "qualitative" Oren–Nayar (QON) as pbrt-v3 has it: `A = 1 − σ²/(2(σ² + 0.33))`, `B = 0.45σ²/(σ² + 0.09)`, `s` replaced by `max(0, s)`, `t = max(cos θi, cos θo)` | `σ` **in radians** (standard deviation of the facet slope angle), `[0, π/2]` | up to 1.0152 at grazing view (an energy gain; `ρ` is limited so that the albedo stays ≤ 1, see [`OrenNayar::max_rho`]) | `oren-nayar(rho=R, sigma_rad=S)` |
//!
//! The two roughness conventions are different quantities: FON/EON's `σ` is
//! a dimensionless blend weight with `σ = 1` the roughest surface, QON's `σ`
//! is an angle (pbrt-v3 takes it in degrees; here radians). The names keep
//! them apart: `sigma` vs `sigma_rad`.
//!
//! # Shared pieces
//!
//! * The FON albedo function [`fon_albedo`] (exact, closed form; the paper's
//!   `E_FON_exact`), which EON's multiple-scattering lobe and every plugin's
//!   [`directional_albedo`](radiometry::Brdf::directional_albedo) use.
//! * **Sampling**: a one-sample mixture of cosine-weighted and uniform
//!   hemisphere sampling, with the probability of the uniform part
//!   `p_u = k (1 − cos θo)³/2` (`k = σ` for FON/EON, `min(1, B/A)` for QON),
//!   density
//!
//!   ```text
//!   pdf(ωi) = (1 − p_u) cos θi/π + p_u/(2π)
//!   ```
//!
//!   exactly (the `pdf` method computes it; `sample` returns that value bit
//!   for bit). Why not cosine sampling alone: its weight `π f_r` grows
//!   without bound as both directions approach the horizon
//!   (`s/t ~ 1/cos θo`), while the uniform part bounds the weight by
//!   `2π f_r cos θi/p_u`. The variance of the one-sample albedo estimate
//!   `f_r cos θi/pdf` (ρ = 1, `f64` quadrature in this module's tests, which
//!   print the table) at `σ = 1` falls from 1.26 to 0.46 at `θo = 89°` and
//!   from 0.76 to 0.45 at 85°; the cube keeps `p_u` near 0 up to 60°, where
//!   cosine sampling is already close to optimal (variance within 1 % of it;
//!   a linear `p_u` cost up to 16 % there). The paper's clipped-LTC sampler
//!   fits the lobe shape more closely but needs a fitted table; the mixture
//!   needs none, and its χ² tests pass (`tests/sampling.rs`).
//! * **Batches**: with the `simd` feature, vector kernels behind
//!   `eval_batch`, `eval_batch_soa`, `pdf_batch` and `sample_batch` of all
//!   three plugins return exactly the bits of `eval`, `pdf` and `sample`
//!   (EON's `G(μ)/π` with a bit-exact vector port of `libm`'s `acosf`; see
//!   the `simd` module).
//! * **Robustness**: one squared-length test per direction, a `#[cold]`
//!   robust normalisation otherwise; `t` is bounded below by the smallest
//!   normal `f32` (`f32::MIN_POSITIVE`), so `s/t` — which grows as
//!   `1/cos θ` when both directions graze (the model's own singularity;
//!   `f_r cos θi` stays bounded) — stays finite for every finite input.
//!
//! Sources: M. Oren & S. K. Nayar, SIGGRAPH 1994 (its "qualitative
//! model"); M. Pharr, W. Jakob & G. Humphreys, *Physically Based Rendering*
//! 3rd ed., the section "Oren–Nayar Diffuse Reflection" (`OrenNayar::f`); Y. Fujii, "A tiny improvement of
//! Oren–Nayar reflectance model" (2012, mimosa-pudica.net); J. Portsmouth,
//! P. Kutz & S. Hill, "EON: A practical energy-preserving rough diffuse
//! BRDF", JCGT 14(1), 2025 (arXiv:2410.18026): the FON form, the exact FON
//! albedo and the EON lobe as its Listing 1 defines them (`E_FON_exact`,
//! `f_EON`).
//!
//! ```
//! use radiometry::{Brdf, glam::Vec3};
//! use radiometry_brdfs::{Eon, Fon, OrenNayar};
//!
//! let wo = Vec3::new(0.8, 0.0, 0.6);
//! // EON at ρ = 1 reflects everything (white furnace), FON does not.
//! let eon = Eon::new(1.0f32, 1.0)?;
//! let fon = Fon::new(1.0f32, 1.0)?;
//! assert!((eon.directional_albedo(wo).value - 1.0).abs() < 1e-6);
//! assert!(fon.directional_albedo(wo).value < 0.9);
//! // The classic model takes radians, and limits ρ where it would gain energy.
//! assert!(OrenNayar::new(0.5f32, 20f32.to_radians()).is_ok());
//! assert!(OrenNayar::new(1.0f32, 0.2).is_err());
//! # Ok::<(), radiometry_brdfs::BrdfError>(())
//! ```

/// The batch methods of a rough diffuse plugin: with the `simd` feature,
/// the vector kernels of [`batch`] (lane for lane equal to the scalar
/// methods, bit for bit); without it, the trait's scalar loops.
macro_rules! rough_batch_methods {
    () => {
        /// `eval`'s straight-line formula (no unit or horizon test).
        #[inline(always)]
        fn eval_checked(&self, wi: Vec3, wo: Vec3) -> S {
            super::RoughLobe::eval_unit(self, wi, wo)
        }

        /// `pdf`'s mixture density (no unit or horizon test).
        #[inline(always)]
        fn pdf_checked(&self, wi: Vec3, wo: Vec3) -> f32 {
            super::pdf_unit(self, wi, wo)
        }

        /// Two components, in the order of [`Brdf::sample`]'s pick
        /// (`u₀ < p_u`): the uniform hemisphere (0, weight `p_u`) and the
        /// cosine-weighted one (1, weight `1 − p_u`).
        fn sampling_components(&self) -> usize {
            2
        }

        /// `p_u` for the uniform component 0, `1 − p_u` for the
        /// cosine-weighted component 1 (`p_u = k (1 − cos θo)³/2`).
        fn component_weight(&self, wo: Vec3, k: usize) -> f32 {
            super::component_weight(self, wo, k)
        }

        /// The uniform (0) or cosine-weighted (1) hemisphere at `u`.
        fn sample_component(&self, wo: Vec3, k: usize, u: [f32; 2]) -> Option<Vec3> {
            super::sample_component(self, wo, k, u)
        }

        /// With the `simd` feature a vector kernel ([`crate::simd`]);
        /// results equal [`Brdf::eval`] bit for bit.
        #[cfg(feature = "simd")]
        #[inline]
        fn eval_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [S]) {
            crate::simd::Batch::Aos(wi, wo, out).run(&super::batch::Eval(self))
        }

        /// With the `simd` feature the kernel of
        /// [`eval_batch`](Brdf::eval_batch) on plain vector loads; results
        /// equal [`Brdf::eval`] bit for bit.
        #[cfg(feature = "simd")]
        #[inline]
        fn eval_batch_soa(
            &self,
            wi: radiometry::batch::Vec3Soa<'_>,
            wo: radiometry::batch::Vec3Soa<'_>,
            out: &mut [S],
        ) {
            crate::simd::Batch::Soa(wi, wo, out).run(&super::batch::Eval(self))
        }

        /// With the `simd` feature a vector kernel for the mixture density;
        /// results equal [`Brdf::pdf`] bit for bit.
        #[cfg(feature = "simd")]
        #[inline]
        fn pdf_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]) {
            crate::simd::Batch::Aos(wi, wo, out).run(&super::batch::Pdf(self))
        }

        /// With the `simd` feature a vector kernel for the cosine/uniform
        /// mixture sampler; results (`None`s included) equal
        /// [`Brdf::sample`] bit for bit.
        #[cfg(feature = "simd")]
        #[inline]
        fn sample_batch(&self, wo: &[Vec3], u: &[[f32; 2]], out: &mut [Option<BrdfSample<S>>]) {
            crate::simd::run_samples(&super::batch::Sample(self), wo, u, out)
        }
    };
}

#[cfg(feature = "simd")]
pub(crate) mod batch;
pub mod eon;
pub mod fon;
pub mod oren_nayar;
#[cfg(test)]
mod tests;

pub use eon::Eon;
pub use fon::Fon;
pub use oren_nayar::OrenNayar;

use crate::microfacet::{is_unit, unitize};
use core::f32::consts::FRAC_1_PI;
use radiometry::glam::Vec3;
use radiometry::math::ONE_MINUS_EPSILON;
use radiometry::warp::{square_to_cosine_hemisphere, square_to_uniform_hemisphere};
use radiometry::{Albedo, BrdfSample, Spectrum};

/// `c₁ = 1/2 − 2/(3π)`: FON's `A = 1/(1 + c₁σ)`; also `G(0)/π`, so the FON
/// albedo at grazing view is exactly 1.
pub(crate) const C1: f32 = 0.287_793_4;
/// `c₂ = 2/3 − 28/(15π)`: the cosine-weighted average of `G(μ)/π`,
/// `2∫₀¹ (G(μ)/π) μ dμ`, so FON's average albedo is `A (1 + c₂σ)`.
pub(crate) const C2: f32 = 0.072_488_21;
/// `2/(3π)`: what the `s ≤ 0` half of FON adds to the albedo function, per
/// `sin θo` (the classic model clamps that half to 0).
const TWO_OVER_3PI: f32 = 0.212_206_59;

/// `G(μ)/π` for `μ = cos θ ∈ [0, 1]` (clamped): the roughness-dependent part
/// of the exact FON albedo, `E_FON(μ) = A (1 + σ G(μ)/π)`, with
///
/// ```text
/// G(μ) = sin θ (θ − sin θ cos θ) + (2/3) ((sin θ/cos θ)(1 − sin³θ) − sin θ)
/// ```
///
/// (Portsmouth, Kutz & Hill 2025, Listing 1, `E_FON_exact`). The quotient
/// `(1 − sin³θ)/cos θ` is evaluated as `cos θ (1 + sin θ + sin²θ)/(1 + sin θ)`
/// (from `1 − sin θ = cos²θ/(1 + sin θ)`), finite at `μ = 0` (the listing's
/// form is `0/0` there) and free of cancellation near it. `G(0)/π = c₁`,
/// `G(1) = 0`.
#[inline]
pub(crate) fn g_over_pi(mu: f32) -> f32 {
    let mu = mu.clamp(0.0, 1.0);
    let sin2 = (1.0 - mu) * (1.0 + mu);
    let sin = radiometry::math::sqrtf(sin2);
    let theta = libm::acosf(mu);
    let g = sin * (theta - sin * mu) + (2.0 / 3.0) * sin * (mu * (1.0 + sin + sin2) / (1.0 + sin) - 1.0);
    g * FRAC_1_PI
}

/// `c₁ − G(μ)/π ≥ 0`, so that `1 − E_FON(μ) = A σ (c₁ − G(μ)/π)` (EON's
/// lobe uses it; written this way it has no cancellation at small σ and is
/// exactly 0 at σ = 0). Clamped at 0 against rounding near grazing.
#[inline]
pub(crate) fn fon_deficit(mu: f32) -> f32 {
    (C1 - g_over_pi(mu)).max(0.0)
}

/// The exact directional albedo of FON at `ρ = 1`,
/// `E_FON(μ) = A (1 + σ G(μ)/π)` with `A = 1/(1 + c₁σ)` (Portsmouth, Kutz &
/// Hill 2025, Listing 1, `E_FON_exact`; `G` as in the [`Fon`] docs), for
/// `μ = cos θo` (clamped to `[0, 1]`) and `σ ∈ [0, 1]` (clamped). It lies in
/// `[1/(1 + c₁σ), 1]`, equal to 1 at grazing view. Accuracy: within
/// `2·10⁻⁶` of the exact value (f32 rounding; measured ≤ 3·10⁻⁷ against
/// `f64` quadrature in this module's tests).
///
/// ```
/// use radiometry_brdfs::rough_diffuse::fon_albedo;
/// assert_eq!(fon_albedo(1.0, 0.0), 1.0); // σ = 0: Lambert
/// assert!((fon_albedo(1.0, 1.0) - 1.0 / (1.0 + 0.2877934)).abs() < 1e-6);
/// assert!((fon_albedo(0.0, 1.0) - 1.0).abs() < 1e-6);
/// ```
pub fn fon_albedo(mu: f32, sigma: f32) -> f32 {
    let sigma = sigma.clamp(0.0, 1.0);
    let a = 1.0 / (1.0 + C1 * sigma);
    a * (1.0 + sigma * g_over_pi(mu))
}

/// `QON` albedo function `H(μ) = G(μ)/π + (2/(3π)) sin θ`: the classic
/// model's `E(μo)/ρ = A + B H(μo)`; `H(0) = 1/2`, `H(1) = 0`, decreasing.
#[inline]
pub(crate) fn qon_h(mu: f32) -> f32 {
    let mu = mu.clamp(0.0, 1.0);
    let sin = radiometry::math::sqrtf((1.0 - mu) * (1.0 + mu));
    g_over_pi(mu) + TWO_OVER_3PI * sin
}

/// `s = ωi·ωo − cos θi cos θo`, evaluated as `xi xo + yi yo` (the same
/// number for unit vectors, without the cancellation of the difference).
#[inline(always)]
pub(crate) fn s_term(wi: Vec3, wo: Vec3) -> f32 {
    wi.x * wo.x + wi.y * wo.y
}

/// `t = max(cos θi, cos θo, f32::MIN_POSITIVE)`: the denominator of `s/t`,
/// bounded below so that `1/t` is finite.
#[inline(always)]
pub(crate) fn t_term(wi: Vec3, wo: Vec3) -> f32 {
    wi.z.max(wo.z).max(f32::MIN_POSITIVE)
}

/// The robust normalisation of a direction pair (the cold path).
#[cold]
#[inline(never)]
fn unitize_pair(wi: Vec3, wo: Vec3) -> Option<(Vec3, Vec3)> {
    Some((unitize(wi)?, unitize(wo)?))
}

/// `wo` as the methods see it: unchanged when unit to within 4ε, else
/// normalised robustly; `None` for zero or non-finite input.
#[inline(always)]
fn unit(w: Vec3) -> Option<Vec3> {
    if is_unit(w) { Some(w) } else { unitize(w) }
}

/// What the three plugins share: the straight-line formula for unit
/// directions above the horizon, the uniform-mixture weight `k` of the
/// sampler, and the closed-form albedo.
pub(crate) trait RoughLobe {
    /// The spectrum of `f_r`.
    type S: Spectrum;
    /// `f_r` for unit `wi`, `wo` with `cos θ > 0` both.
    fn eval_unit(&self, wi: Vec3, wo: Vec3) -> Self::S;
    /// `k ∈ [0, 1]` of `p_u = k (1 − cos θo)³/2`.
    fn uniform_weight(&self) -> f32;
    /// `E(μo)` for `μo ∈ (0, 1]`.
    fn albedo_at(&self, mu_o: f32) -> Self::S;
    /// The stated error of [`RoughLobe::albedo_at`] (absolute, a bound).
    fn albedo_error(&self) -> f32;
    /// What [`RoughLobe::eval_unit`] shares between channels, for
    /// [`LANES`](crate::simd::LANES) pairs.
    #[cfg(feature = "simd")]
    type Lanes;
    /// [`RoughLobe::eval_unit`]'s channel-independent part, lane-wise, for
    /// unit directions (the lanes with a cosine `≤ 0` are masked by the
    /// caller).
    #[cfg(feature = "simd")]
    fn unit_lanes(&self, wi: crate::simd::Dirs, wo: crate::simd::Dirs) -> Self::Lanes;
    /// Channel `c` of [`RoughLobe::eval_unit`] from
    /// [`unit_lanes`](RoughLobe::unit_lanes), bit for bit.
    #[cfg(feature = "simd")]
    fn channel_lanes(&self, c: usize, t: &Self::Lanes) -> crate::simd::Vf;
}

/// `f_r(wi, wo)`: zero unless both (normalised) directions are above the
/// horizon; non-unit, degenerate or non-finite input takes the cold path.
#[inline(always)]
pub(crate) fn eval<L: RoughLobe>(l: &L, wi: Vec3, wo: Vec3) -> L::S {
    let (wi, wo) = if is_unit(wi) && is_unit(wo) {
        (wi, wo)
    } else {
        match unitize_pair(wi, wo) {
            Some(p) => p,
            None => return L::S::zero(),
        }
    };
    if wi.z > 0.0 && wo.z > 0.0 {
        l.eval_unit(wi, wo)
    } else {
        L::S::zero()
    }
}

/// Probability of the uniform part of the sampling mixture for `cos θo = mu_o`,
/// `0.5 k max(1 − cos θo, 0)³`: a nearly-unit `wo` accepted as unit can have
/// `cos θo` a rounding above 1, which must not make the probability negative.
#[inline(always)]
pub(crate) fn p_uniform(k: f32, mu_o: f32) -> f32 {
    let c = (1.0 - mu_o).max(0.0);
    0.5 * k * (c * c * c)
}

/// The mixture density `(1 − p_u) cos θi/π + p_u/(2π)` of the normalised
/// `wi`, zero unless both directions are above the horizon.
#[inline]
pub(crate) fn pdf<L: RoughLobe>(l: &L, wi: Vec3, wo: Vec3) -> f32 {
    let (Some(wi), Some(wo)) = (unit(wi), unit(wo)) else {
        return 0.0;
    };
    if wi.z <= 0.0 || wo.z <= 0.0 {
        return 0.0;
    }
    pdf_unit(l, wi, wo)
}

/// [`pdf`] of unit directions above the horizon:
/// `(1 − p_u) cos θi/π + p_u/(2π)`.
#[inline(always)]
pub(crate) fn pdf_unit<L: RoughLobe>(l: &L, wi: Vec3, wo: Vec3) -> f32 {
    let p_u = p_uniform(l.uniform_weight(), wo.z);
    (1.0 - p_u) * (wi.z * FRAC_1_PI) + p_u * (0.5 * FRAC_1_PI)
}

/// The direction [`sample`] draws (and its normalised form), without its
/// pdf and value: for a caller that evaluates its own mixture at it.
#[inline]
pub(crate) fn sample_direction<L: RoughLobe>(l: &L, wo: Vec3, u: [f32; 2]) -> Option<(Vec3, Vec3)> {
    let wo_unit = unit(wo)?;
    if wo_unit.z <= 0.0 {
        return None;
    }
    let p_u = p_uniform(l.uniform_weight(), wo_unit.z);
    let wi = if u[0] < p_u {
        square_to_uniform_hemisphere([(u[0] / p_u).min(ONE_MINUS_EPSILON), u[1]])
    } else {
        square_to_cosine_hemisphere([((u[0] - p_u) / (1.0 - p_u)).min(ONE_MINUS_EPSILON), u[1]])
    };
    let wi_unit = unit(wi)?;
    (wi_unit.z > 0.0).then_some((wi, wi_unit))
}

/// One sample of the mixture: the uniform hemisphere with probability `p_u`
/// (`u₀ < p_u`, rescaled to `[0, 1)`), else the cosine-weighted one; the pdf
/// is [`pdf`] of the returned direction (bit for bit), the weight
/// `f_r cos θi/pdf`. `None` when `wo` is not above the horizon (or not
/// finite) or the direction lands on the horizon.
#[inline]
pub(crate) fn sample<L: RoughLobe>(l: &L, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<L::S>> {
    let (wi, wi_unit) = sample_direction(l, wo, u)?;
    let pdf = pdf(l, wi, wo);
    if pdf.is_nan() || pdf <= 0.0 {
        return None;
    }
    let weight = eval(l, wi, wo) * (wi_unit.z / pdf);
    Some(BrdfSample { wi, pdf, weight })
}

/// The weight of component `k` of the mixture sampler ([`sample`]), in the
/// order of its pick: `p_u` for the uniform hemisphere (`k = 0`), `1 − p_u`
/// for the cosine-weighted one (`k = 1`), 0 otherwise; at a degenerate `wo`
/// the cosine component alone.
#[inline]
pub(crate) fn component_weight<L: RoughLobe>(l: &L, wo: Vec3, k: usize) -> f32 {
    let p_u = match unit(wo) {
        Some(w) if w.z > 0.0 => p_uniform(l.uniform_weight(), w.z).clamp(0.0, 1.0),
        _ => 0.0,
    };
    match k {
        0 => p_u,
        1 => 1.0 - p_u,
        _ => 0.0,
    }
}

/// The direction of component `k` of the mixture sampler at `u` (the map
/// [`sample`] applies to its rescaled `u₀`): the uniform hemisphere (`k = 0`)
/// or the cosine-weighted one (`k = 1`); `None` when `wo` is not above the
/// horizon, the direction lands on the horizon or `k > 1`.
#[inline]
pub(crate) fn sample_component<L: RoughLobe>(l: &L, wo: Vec3, k: usize, u: [f32; 2]) -> Option<Vec3> {
    let _ = l;
    let wo_unit = unit(wo)?;
    if wo_unit.z <= 0.0 {
        return None;
    }
    let u = [u[0].clamp(0.0, ONE_MINUS_EPSILON), u[1]];
    let wi = match k {
        0 => square_to_uniform_hemisphere(u),
        1 => square_to_cosine_hemisphere(u),
        _ => return None,
    };
    let wi_unit = unit(wi)?;
    (wi_unit.z > 0.0).then_some(wi)
}

/// The closed-form albedo at the normalised `wo`; exactly zero at or below
/// the horizon.
#[inline]
pub(crate) fn directional_albedo<L: RoughLobe>(l: &L, wo: Vec3) -> Albedo<L::S> {
    match unit(wo) {
        Some(w) if w.z > 0.0 => Albedo::bounded(l.albedo_at(w.z), l.albedo_error()),
        _ => Albedo::zero(),
    }
}
