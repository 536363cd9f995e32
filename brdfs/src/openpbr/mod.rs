//! The reflection layer of OpenPBR Surface as one plugin: [`OpenPbr`], a
//! fixed, flat set of five lobes prepared once per view.
//!
//! # The lobes and their weights
//!
//! OpenPBR Surface 1.1 (Academy Software Foundation, 2024; §"Model") stacks
//! slabs and mixes them by weights. Restricted to reflection from an opaque,
//! isotropic surface and written out as a weighted sum of leaf lobes (the
//! "reduction to a mixture of lobes" of §"Model"):
//!
//! ```text
//! f = w_F f_fuzz
//!   + a_F(ωi, ωo) [ w_C f_coat
//!                 + U_s(ωi, ωo) (m ξ_s f_metal + (1 − m) C_s ⊙ f_spec)
//!                 + U_d(ωi, ωo) (1 − m) K(μi, μo) f_EON ]
//! ```
//!
//! | lobe | model |
//! |---|---|
//! | `f_fuzz` | the LTC sheen of Zeltner et al. 2022 ([`LtcSheen`], OpenPBR's recommendation); Charlie ([`Sheen`]) in the reciprocal mode |
//! | `f_coat` | GGX (`α_c = r_c²`), dielectric Fresnel of `coat_ior` |
//! | `f_metal` | GGX (`α_s = r_s²`), F82-tint (`f0 = w_B C_B`, tint `C_s`), and Kulla & Conty's multiple-scattering lobe from global tables |
//! | `f_spec` | GGX (`α_s`), dielectric Fresnel of the specular index ratio `η_s` |
//! | `f_EON` | energy-preserving Oren–Nayar, `ρ = w_B C_B`, `σ = r_D` |
//!
//! **Albedo scaling** ([`Layering`]): in the default
//! [`Layering::EnergyConserving`] mode every layer passes `1 − E_top(ωo)` of
//! the light to what lies beneath it — OpenPBR's eq. "non-reciprocal albedo
//! scaling", with the fuzz's **untinted** albedo `E_F` (§"Fuzz") — so a
//! white furnace is exact up to the tables' error:
//!
//! ```text
//! a_F = 1 − w_F E_F(μo)
//! U   = (1 − w_C) + w_C D A(μi, μo) (1 − E_C(μo))          (U_s = U_d)
//! ```
//!
//! The dielectric base keeps the reciprocal form of Kelemen & Szirmay-Kalos
//! (2001) in both modes, `K(μi, μo) = (1 − E_s(μi))(1 − E_s(μo))/(1 − Ē_s)`,
//! as Adobe's OpenPBR BSDF does: exact for a Lambertian body, where
//! OpenPBR's `E = E_s + (1 − E_s) C` holds at every `ωo`.
//!
//! [`Layering::Reciprocal`] (for bidirectional methods) replaces each
//! one-sided factor `t(μo) = 1 − E(μo)` of the coat and the fuzz by the
//! symmetric `τ = min(t(μi) t(μo)/(1 − Ē), t(μi), t(μo))`
//! ([`reciprocal_through`](radiometry::compose::reciprocal_through)): the
//! Kelemen form, capped under the specular lobes so that no base reflects
//! more than the one-sided form lets through (energy ≤ 1 for any lobe shape),
//! uncapped under the diffuse lobe (exact for a Lambertian body); the
//! darkening uses `K_s = F0` instead of `F(μo)`, and the fuzz is the
//! reciprocal Charlie sheen.
//!
//! `E_s`, `E_C` (directional albedos) and `Ē_s`, `Ē_C` (hemispherical
//! averages) of the dielectric lobes come from the crate's global tables
//! ([`fresnel_table`](crate::microfacet::fresnel_table)); the metal's from
//! its moment tables; nothing is integrated when a material is built.
//!
//! # Formulas from the specification
//!
//! * **Specular index ratio** (eq. "specular_ior_ratio" with the TIR rule of
//!   §"Coat — Total internal reflection"): `η_s = lerp(n_b, η_bc, w_C)`,
//!   `η_bc = n_c/n_b` if `n_c > n_b`, else `n_b/n_c`; then `specular_weight`
//!   scales its `F0` (eq. 26: `ε = sign(η − 1)√(min(ξ_s F0, 1))`,
//!   `η = (1 + ε)/(1 − ε)`).
//! * **Coat absorption** `A(μi, μo) = C_c^{(1/μᵗi + 1/μᵗo)/2}`, `μᵗ = √(1 − (1 −
//!   μ²)/η_c²)` (§"View-dependent absorption").
//! * **Coat roughening** (§"Roughening"): under a coat the base lobes use
//!   `r'_s = lerp(r_s, min(1, r_s⁴ + 2 r_c⁴)^¼, w_C)`.
//! * **Coat darkening** (§"Darkening"): the coated base is scaled by `D =
//!   lerp(1, Δ, δ)`, `Δ = (1 − K)/(1 − E_b K)` per channel, `K = lerp(K_s,
//!   K_r, r_b)`, `K_r = 1 − (1 − Ē_F(η_c))/η_c²`, `K_s = F(μo, η_c)`, `r_b =
//!   lerp(lerp(1, r_s, ξ_s F0_s), r_s, m)`, `E_b` the base's albedo at normal
//!   incidence; `δ = coat_darkening` (default 1).
//!
//! # Parameters
//!
//! [`OpenPbrParams`] has OpenPBR's names and defaults; colours are any
//! [`Spectrum`]. Domains (checked by [`OpenPbr::new`], [`BrdfError`]
//! otherwise): every weight, colour channel, roughness, `base_metalness` and
//! `coat_darkening` in `[0, 1]`; `specular_ior` and `coat_ior` in `[1,
//! 1000]`. Documented fallbacks: roughness 0 is raised to the microfacet
//! floor `α = 10⁻⁴`; `fuzz_roughness` below 0.07 to 0.07
//! ([`MIN_SHEEN_ROUGHNESS`]).
//!
//! Outside a reflection-only isotropic BRDF (each behaves as if at the value
//! in brackets): `transmission_weight`, `subsurface_weight` (0: the
//! dielectric body is the EON diffuse), `*_anisotropy` (0),
//! `thin_film_weight` (0), `geometry_*` (opaque, one-sided), `emission_*`
//! (0).
//!
//! # Cost
//!
//! [`OpenPbr::new`] validates and reads a few table entries. Every call
//! prepares the view once ([`OpenPbr::prepare`]: the layers' factors at `μo`
//! and the pick probabilities); `sample` picks one lobe in proportion to its
//! share of the layered albedo at `ωo`, samples it, then evaluates and takes
//! the mixture pdf in one pass over the lobes each. A renderer that shades
//! several directions at one hit calls [`OpenPbr::prepare`] once and then
//! [`OpenPbrView::eval`], [`OpenPbrView::pdf`] and [`OpenPbrView::sample`].
//!
//! ```
//! use radiometry::{Brdf, glam::Vec3};
//! use radiometry_brdfs::openpbr::{OpenPbr, OpenPbrParams};
//! let plastic = OpenPbr::new(OpenPbrParams::<Vec3> {
//!     base_color: Vec3::new(0.8, 0.1, 0.1),
//!     specular_roughness: 0.2,
//!     ..OpenPbrParams::default()
//! })?;
//! let wo = Vec3::new(0.6, 0.0, 0.8);
//! let s = plastic.sample(wo, [0.3, 0.6]).unwrap();
//! assert_eq!(s.pdf, plastic.pdf(s.wi, wo)); // bit for bit
//! let view = plastic.prepare(wo); // several directions at one hit
//! assert_eq!(view.eval(s.wi), plastic.eval(s.wi, wo));
//! assert!(plastic.directional_albedo(wo).value.max_element() < 1.0);
//! # Ok::<(), radiometry_brdfs::BrdfError>(())
//! ```

#[cfg(test)]
mod tests;

use crate::error::{BrdfError, check_range};
use crate::microfacet::AlbedoReader;
use crate::microfacet::fresnel_table::{
    DielectricAlbedoReader, MomentCell, RatioCells, dielectric_average, dielectric_average_inline,
};
use crate::microfacet::ggx_pair::{GgxPairTerms, dielectric_pair, ggx_pair};
use crate::microfacet::prepared::DielectricCells;
use crate::microfacet::transmission_sampler::TransmissionSampler;
use crate::microfacet::{
    Achromatic, AlbedoTable, Dielectric, EnergyTable, F82Tint, Fresnel, Ggx, HeightCorrelated, MAX_ETA,
    MIN_ALPHA, Microfacet, MicrofacetDistribution, is_unit,
};
use crate::rough_diffuse::Eon;
use crate::sheen::{LtcAt, LtcSheen, MIN_SHEEN_ROUGHNESS, Sheen, SheenAlbedoTable};
use radiometry::batch::Vec3Soa;
pub use radiometry::compose::Layering;
use radiometry::glam::Vec3;
use radiometry::math::ONE_MINUS_EPSILON;
use radiometry::warp::square_to_uniform_hemisphere;
use radiometry::{Albedo, Brdf, BrdfSample, IsotropicBrdf, Spectrum};

/// The parameters of [`OpenPbr`], with OpenPBR Surface 1.1's names and
/// defaults ([`Default`]). Plain data: [`OpenPbr::new`] validates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OpenPbrParams<S> {
    /// `base_weight` `w_B` (default 1): scales `base_color`.
    pub base_weight: f32,
    /// `base_color` `C_B` (default 0.8): the diffuse albedo and the metal's
    /// reflectance at normal incidence.
    pub base_color: S,
    /// `base_metalness` `m` (default 0): the mix of metal and glossy-diffuse.
    pub base_metalness: f32,
    /// `base_diffuse_roughness` `r_D` (default 0): EON's `σ`.
    pub base_diffuse_roughness: f32,
    /// `specular_weight` `ξ_s` (default 1): scales the dielectric's `F0`
    /// (through its index) and the metal lobe.
    pub specular_weight: f32,
    /// `specular_color` `C_s` (default 1): tints the dielectric's
    /// reflection; the metal's F82 tint.
    pub specular_color: S,
    /// `specular_roughness` `r_s` (default 0.3): `α_s = r_s²`.
    pub specular_roughness: f32,
    /// `specular_ior` `n_b` (default 1.5).
    pub specular_ior: f32,
    /// `coat_weight` `w_C` (default 0).
    pub coat_weight: f32,
    /// `coat_color` `C_c` (default 1): the coat's absorption (the square of
    /// its transmittance at normal incidence).
    pub coat_color: S,
    /// `coat_roughness` `r_c` (default 0): `α_c = r_c²`.
    pub coat_roughness: f32,
    /// `coat_ior` `n_c` (default 1.6).
    pub coat_ior: f32,
    /// `coat_darkening` `δ` (default 1): the darkening of the coated base by
    /// light trapped in the coat (0: the base is boosted to cancel it).
    pub coat_darkening: f32,
    /// `fuzz_weight` `w_F` (default 0).
    pub fuzz_weight: f32,
    /// `fuzz_color` `C_F` (default 1).
    pub fuzz_color: S,
    /// `fuzz_roughness` `r_F` (default 0.5).
    pub fuzz_roughness: f32,
}

impl<S: Spectrum> Default for OpenPbrParams<S> {
    /// OpenPBR Surface 1.1's defaults: a white-ish (0.8) dielectric base with
    /// a `r = 0.3`, `η = 1.5` specular layer; no coat, no fuzz.
    fn default() -> Self {
        Self {
            base_weight: 1.0,
            base_color: S::splat(0.8),
            base_metalness: 0.0,
            base_diffuse_roughness: 0.0,
            specular_weight: 1.0,
            specular_color: S::splat(1.0),
            specular_roughness: 0.3,
            specular_ior: 1.5,
            coat_weight: 0.0,
            coat_color: S::splat(1.0),
            coat_roughness: 0.0,
            coat_ior: 1.6,
            coat_darkening: 1.0,
            fuzz_weight: 0.0,
            fuzz_color: S::splat(1.0),
            fuzz_roughness: 0.5,
        }
    }
}

type DielectricLobe<S> = Microfacet<Ggx, HeightCorrelated, Achromatic<Dielectric, S>>;
type MetalSingle<S> = Microfacet<Ggx, HeightCorrelated, F82Tint<S>>;

/// The metal: single scattering (GGX, F82-tint) and the multiple-scattering
/// lobe of Kulla & Conty (2017) built in O(1) from global tables:
/// `f_ms = F_ms (1 − E₁(μi))(1 − E₁(μo)) / (π (1 − Ē₁))`, `F_ms = F̄² Ē₁ /
/// (1 − F̄ (1 − Ē₁))`, `F̄ = f0 + (1 − f0)/21 − a/126` (the hemispherical
/// average of the F82-tint polynomial, in closed form).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Metal<S: Spectrum> {
    single: MetalSingle<S>,
    /// `F_ms / (π (1 − Ē₁))` per channel (0 when `Ē₁` is 1 to `10⁻⁶`).
    ms_scale: S,
    /// `F_ms` per channel (0 likewise): the lobe's albedo is `F_ms (1 − E₁(μo))`.
    f_ms: S,
    /// `E₁(·, α)` of the global table at this roughness.
    e1: AlbedoReader,
    /// The row of the global sampler of the lobe (`microfacet::ms_sampler`).
    ms_row: u8,
    /// The roughness cell of the Fresnel-moment tables (the single
    /// scattering's albedo reads them at every view).
    moments: MomentCell,
}

impl<S: Spectrum> Metal<S> {
    /// The metal at `ggx`'s roughness; `e1` is the reader of `E₁(·, α)` at
    /// that roughness (the specular lobe's, which the material shares) and
    /// `moments` the Fresnel-moment tables' cell of `α` (the specular
    /// lobe's ratio-table cell: the same grid).
    fn new(ggx: Ggx, f0: S, tint: S, e1: AlbedoReader, moments: MomentCell) -> Self {
        let fresnel = F82Tint::from_valid(f0, tint);
        // Ē₁ and the sampler's row on the reader's roughness coordinate (one
        // cube root for the three).
        let e_avg = crate::microfacet::fresnel_table::e1_average_at(e1.axis());
        let loss = 1.0 - e_avg;
        // F82-tint's a per channel: F(μ̄) = t F_S(μ̄) at μ̄ = 1/7.
        let w_bar = 7_776.0 / 16_807.0;
        let g_bar = 46_656.0 / 823_543.0;
        let f_ms = S::from_fn(|c| {
            let (f0, t) = (f0.channel(c), tint.channel(c));
            let a = (f0 + (1.0 - f0) * w_bar) * (1.0 - t) / g_bar;
            let f_avg = (f0 + (1.0 - f0) / 21.0 - a / 126.0).clamp(0.0, 1.0);
            if loss > 1e-6 {
                f_avg * f_avg * e_avg / (1.0 - f_avg * loss)
            } else {
                0.0
            }
        });
        let ms_scale = if loss > 1e-6 {
            f_ms * (core::f32::consts::FRAC_1_PI / loss)
        } else {
            S::zero()
        };
        Self {
            single: Microfacet::new(ggx, fresnel),
            ms_scale,
            f_ms,
            e1,
            ms_row: crate::microfacet::ms_sampler::row_index_at(e1.axis()),
            moments,
        }
    }

    /// The single-scattering lobe's directional albedo `E₁(μ) R_F(μ)` at
    /// `ωo` (unit, above the horizon): the roughness's table reader times
    /// the F82-tint ratio of the Fresnel moments
    /// ([`linear_fresnel_ratio`](crate::microfacet::fresnel_table::linear_fresnel_ratio)),
    /// as [`Brdf::directional_albedo`] of the lobe reads it (which it
    /// falls back to where the Fresnel term has a kink).
    #[inline]
    fn single_albedo(&self, wo: Vec3) -> S {
        self.single_albedo_with(wo, self.e1.albedo(e1_table(), wo.z))
    }

    /// [`single_albedo`](Self::single_albedo) with `E₁(μo)` already read
    /// (the moments through the cell the metal keeps: bit for bit
    /// [`fresnel_moments`](crate::microfacet::fresnel_table::fresnel_moments)).
    #[inline]
    fn single_albedo_with(&self, wo: Vec3, e1: f32) -> S {
        self.single_albedo_from(wo, e1, |c| c.moments(wo.z))
    }

    /// [`single_albedo_with`](Self::single_albedo_with) at the normal,
    /// bit for bit, without the moments' root ([`MomentCell::moments_at_normal`]).
    #[inline]
    fn single_albedo_at_normal(&self, e1: f32) -> S {
        self.single_albedo_from(Vec3::Z, e1, |c| c.moments_at_normal())
    }

    /// `E₁(μo) R_F(μo)` per channel from `E₁(μo)` and the moments at `μo`
    /// (`moments`, read through the metal's cell).
    #[inline(always)]
    fn single_albedo_from(&self, wo: Vec3, e1: f32, moments: impl Fn(&MomentCell) -> (f32, f32)) -> S {
        use crate::microfacet::fresnel_table::linear_fresnel_ratio;
        match self.single.fresnel.form() {
            crate::microfacet::FresnelForm::Linear { f0, a } => {
                let m = moments(&self.moments);
                S::from_fn(|c| (linear_fresnel_ratio(f0.channel(c), a.channel(c), m) * e1).clamp(0.0, 1.0))
            }
            _ => self.single.directional_albedo(wo).value,
        }
    }

    /// `1 − E₁(μ)`.
    #[inline]
    fn loss(&self, mu: f32) -> f32 {
        (1.0 - self.e1.albedo(e1_table(), mu)).clamp(0.0, 1.0)
    }

    /// A direction of the multiple-scattering lobe's sampler: the global
    /// row nearest this roughness, `∝ (1 − E₁(μi)) μi` per cell
    /// (`microfacet::ms_sampler`).
    #[inline]
    fn ms_sample(&self, u: [f32; 2]) -> Vec3 {
        crate::microfacet::ms_sampler::row(self.ms_row).sample(u[0], u[1])
    }

    /// The solid-angle density of [`ms_sample`](Self::ms_sample) at `μi`.
    #[inline]
    fn ms_pdf(&self, mu_i: f32) -> f32 {
        crate::microfacet::ms_sampler::row(self.ms_row).pdf(mu_i)
    }
}

/// Number of leaf lobes.
const LOBES: usize = 6;
const FUZZ: usize = 0;
const COAT: usize = 1;
const METAL: usize = 2;
const METAL_MS: usize = 3;
const SPEC: usize = 4;
const DIFFUSE: usize = 5;

/// The `F = 1` albedo table of GGX with the height-correlated `G2`.
fn e1_table() -> &'static AlbedoTable {
    <Ggx as EnergyTable<HeightCorrelated>>::TABLE
}

/// OpenPBR Surface's reflection: metal, glossy-diffuse (a dielectric
/// specular layer over EON), an optional coat and an optional fuzz, as a
/// flat list of five weighted lobes (see the [module docs](self) for the
/// weights, the formulas and what is outside a reflection-only BRDF).
///
/// A plain value built in O(1) (validation and a few table reads); a lobe
/// whose weight is 0 costs nothing per call.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OpenPbr<S: Spectrum = f32> {
    params: OpenPbrParams<S>,
    layering: Layering,
    /// The fuzz lobe of the energy-conserving mode (LTC sheen, OpenPBR's
    /// recommendation) and of the reciprocal mode (Charlie: the LTC sheen is
    /// not reciprocal).
    fuzz: Option<LtcSheen<S>>,
    fuzz_reciprocal: Option<Sheen<S>>,
    coat: DielectricLobe<S>,
    /// The metal lobe, built only when `base_metalness` and `specular_weight`
    /// are above 0 (its Kulla–Conty compensation reads a table row).
    metal: Option<Metal<S>>,
    spec: DielectricLobe<S>,
    diffuse: Eon<S>,
    /// The diffuse lobe's cosine-weighted sampler, shaped by the specular
    /// layer's transmission `1 − E_s(μi)` (`microfacet::transmission_sampler`).
    diffuse_sampler: TransmissionSampler,
    /// Which lobes are on (weight > 0).
    on: [bool; LOBES],
    /// `ξ_s` (the metal's weight).
    xi: f32,
    /// `(α_s, η_s)` and `(α_c, η_c)` for the tables.
    spec_ae: (f32, f32),
    coat_ae: (f32, f32),
    /// `1/(1 − Ē_s)`.
    inv_spec_avg: f32,
    /// Reciprocal mode: `1/(1 − Ē_C)`; the same for the fuzz (`w_F E_F`).
    coat_norm: f32,
    fuzz_norm: f32,
    /// Reciprocal mode, the diffuse lobe: `1/(2∫ t_F t_s μ dμ)` for the
    /// uncoated part and `1/(2∫ t_F t_C t_s μ dμ)` for the coated part
    /// (`t = 1 − E` of each layer present; `t_F = 1` without fuzz).
    joint_norm: [f32; 2],
    /// `Δ − 1` per channel with `K_s` left out: `(E_b, K_r, r_b)` to finish it
    /// per view.
    base_albedo_normal: S,
    k_r: f32,
    r_b: f32,
    /// `F0` of the coat (for the reciprocal mode's `K_s`).
    coat_f0: f32,
}

/// `E(μ)` of a dielectric lobe of roughness and index `(α, η)`
/// (`ae`) from the global tables, through the cells the lobe keeps once
/// [prepared](radiometry::Brdf::with_prepared_albedo) (the material
/// prepares its dielectric lobes at construction, and its lobes cannot be
/// changed afterwards), else through a reader built for the call.
#[inline(always)]
fn lobe_albedo<S: Spectrum>(lobe: &DielectricLobe<S>, ae: (f32, f32)) -> impl Fn(f32) -> f32 + '_ {
    let cells = lobe.fresnel.albedo_cells(lobe.distribution.alpha());
    move |mu| match cells {
        Some(c) => c.reader.albedo(mu),
        None => unprepared_albedo(ae, mu),
    }
}

/// `(E_s(μ), E₁(μ))` of the specular lobe `spec` (`(α, η)` = `ae`) and of
/// the metal at its roughness (1 without a metal): one read of `E₁` where
/// there is a metal and the lobe keeps its cells, each bit for bit its own
/// read ([`DielectricAlbedoReader::albedo_and_e1`]).
#[inline(always)]
fn spec_albedo_and_e1<S: Spectrum>(
    spec: &DielectricLobe<S>,
    ae: (f32, f32),
    metal: Option<&Metal<S>>,
    mu: f32,
) -> (f32, f32) {
    match (metal, spec.fresnel.albedo_cells(spec.distribution.alpha())) {
        (Some(_), Some(c)) => c.reader.albedo_and_e1(mu),
        _ => (
            lobe_albedo(spec, ae)(mu),
            metal.map_or(1.0, |x| x.e1.albedo(e1_table(), mu)),
        ),
    }
}

/// [`spec_albedo_and_e1`] at `μ = 1` (normal incidence), bit for bit,
/// without the coordinates' roots and division
/// ([`DielectricAlbedoReader::albedo_and_e1_at_normal`]): the darkening's
/// reads at construction.
#[inline]
fn spec_albedo_and_e1_at_normal<S: Spectrum>(
    spec: &DielectricLobe<S>,
    ae: (f32, f32),
    metal: Option<&Metal<S>>,
) -> (f32, f32) {
    match (metal, spec.fresnel.albedo_cells(spec.distribution.alpha())) {
        (Some(_), Some(c)) => c.reader.albedo_and_e1_at_normal(),
        (_, cells) => (
            cells.map_or_else(|| unprepared_albedo(ae, 1.0), |c| c.reader.albedo_at_normal()),
            metal.map_or(1.0, |x| x.e1.albedo_at_normal(e1_table())),
        ),
    }
}

/// [`lobe_albedo`] of a lobe without its cells (not one the material builds),
/// out of line so that the prepared read inlines into its callers.
#[cold]
#[inline(never)]
fn unprepared_albedo(ae: (f32, f32), mu: f32) -> f32 {
    DielectricAlbedoReader::new(ae.0, ae.1).albedo(mu)
}

/// The directions of one batch chunk (a multiple of the vector width).
const CHUNK: usize = 32;

/// A dielectric lobe's albedo read for one batch call: the lobe, its `(α,
/// η)`, and with the `simd` feature its prepared reader's combined rows
/// (`DielectricAlbedoRows`), built once for the call.
struct BatchRead<'a, S: Spectrum> {
    lobe: &'a DielectricLobe<S>,
    ae: (f32, f32),
    #[cfg(feature = "simd")]
    rows: Option<crate::microfacet::fresnel_table::DielectricAlbedoRows>,
}

impl<'a, S: Spectrum> BatchRead<'a, S> {
    /// The read of `lobe` (its rows built only if the layer is `on`).
    #[inline]
    fn new(lobe: &'a DielectricLobe<S>, ae: (f32, f32), on: bool) -> Self {
        #[cfg(not(feature = "simd"))]
        let _ = on;
        Self {
            lobe,
            ae,
            #[cfg(feature = "simd")]
            rows: if on {
                lobe.fresnel
                    .albedo_cells(lobe.distribution.alpha())
                    .and_then(|c| c.reader.rows())
            } else {
                None
            },
        }
    }

    /// `out[k] = E(mu[k])`, the values of [`lobe_albedo`]: with the `simd`
    /// feature from the combined rows in vector lanes (bit for bit the scalar
    /// read), else one by one.
    #[inline]
    fn chunk(&self, mu: &[f32; CHUNK], out: &mut [f32; CHUNK]) {
        #[cfg(feature = "simd")]
        if let Some(rows) = &self.rows {
            use crate::simd::{LANES, Vf};
            for (m, o) in mu.chunks_exact(LANES).zip(out.chunks_exact_mut(LANES)) {
                let mut lanes = [0.0f32; LANES];
                for (l, &m) in lanes.iter_mut().zip(m) {
                    *l = m;
                }
                for (o, &e) in o.iter_mut().zip(&rows.albedo_lanes(Vf::from(lanes)).to_array()) {
                    *o = e;
                }
            }
            return;
        }
        let read = lobe_albedo(self.lobe, self.ae);
        for (o, &m) in out.iter_mut().zip(mu) {
            *o = read(m);
        }
    }
}

/// The coat's and the specular lobe's [`BatchRead`]s of one batch call.
struct BatchReads<'a, S: Spectrum> {
    coat: BatchRead<'a, S>,
    spec: BatchRead<'a, S>,
}

/// The unit directions of a chunk ([`unit`]) and `cos(k)` of each.
#[inline]
fn unit_chunk(w: &[Vec3], cos: impl Fn(Vec3) -> f32) -> ([Vec3; CHUNK], [f32; CHUNK]) {
    let (mut u, mut c) = ([Vec3::ZERO; CHUNK], [0.0f32; CHUNK]);
    for ((u, c), &w) in u.iter_mut().zip(c.iter_mut()).zip(w) {
        *u = unit(w);
        *c = cos(*u);
    }
    (u, c)
}

/// `μo` of a unit view direction as [`OpenPbr::view_at`] takes it (0
/// for a view it rejects, whose reads nobody uses).
#[inline]
fn view_cosine(w: Vec3) -> f32 {
    let valid = w.z.is_finite() && w.z > 0.0 && w.is_finite();
    if valid { w.z.min(1.0) } else { 0.0 }
}

/// `α = r²` clamped to `[10⁻⁴, 1]` (the clamp at 1 only catches a
/// roughened `r` that rounds above 1).
fn alpha(r: f32) -> f32 {
    (r * r).clamp(MIN_ALPHA, 1.0)
}

/// OpenPBR eq. 26: the index whose `F0` is `ξ F0(η)` (`ξ` capped at
/// `1/F0`), on the same side of 1 as `η`; clamped to the dielectric's
/// domain.
pub fn modulated_ior(eta: f32, xi: f32) -> f32 {
    let r = (eta - 1.0) / (eta + 1.0);
    let f0 = r * r;
    if f0 <= 0.0 || !f0.is_finite() {
        return 1.0;
    }
    let scaled = (xi.max(0.0) * f0).min(1.0);
    let eps = radiometry::math::sqrtf(scaled).copysign(eta - 1.0);
    ((1.0 + eps) / (1.0 - eps)).clamp(crate::microfacet::MIN_ETA, MAX_ETA)
}

/// OpenPBR's specular index ratio (eq. "specular_ior_ratio" with the TIR
/// rule): `lerp(n_b, η_bc, w_C)`, `η_bc = n_c/n_b` if `n_c > n_b`, else
/// `n_b/n_c` (never below 1 for `n_b, n_c ≥ 1`).
pub fn specular_ior_ratio(specular_ior: f32, coat_ior: f32, coat_weight: f32) -> f32 {
    let bc = if coat_ior > specular_ior {
        coat_ior / specular_ior
    } else {
        specular_ior / coat_ior
    };
    specular_ior + coat_weight * (bc - specular_ior)
}

fn colour<S: Spectrum>(name: &'static str, c: S) -> Result<S, BrdfError> {
    for i in 0..S::CHANNELS {
        in_range(name, c.channel(i), 0.0, 1.0)?;
    }
    Ok(c)
}

/// [`check_range`] for finite bounds `lo ≤ hi`, with the test a value in
/// range takes first: two comparisons (a NaN is in no range, and a finite
/// range holds no infinity); anything else gets `check_range`'s error, out
/// of line. A material built at every hit checks its fourteen parameters
/// and four colours on every build.
#[inline(always)]
fn in_range(name: &'static str, v: f32, lo: f32, hi: f32) -> Result<f32, BrdfError> {
    if v >= lo && v <= hi {
        Ok(v)
    } else {
        out_of_range(name, v, lo, hi)
    }
}

/// [`in_range`]'s failure: [`check_range`]'s error for `v`.
#[cold]
#[inline(never)]
fn out_of_range(name: &'static str, v: f32, lo: f32, hi: f32) -> Result<f32, BrdfError> {
    check_range(name, v, lo, hi)
}

/// `1/x` for `x` clamped to `[10⁻⁶, 1]`.
fn inv(x: f32) -> f32 {
    1.0 / x.clamp(1e-6, 1.0)
}

/// `F0 = ((η − 1)/(η + 1))²`.
fn f0_of(eta: f32) -> f32 {
    let r = (eta - 1.0) / (eta + 1.0);
    r * r
}

impl<S: Spectrum> OpenPbr<S> {
    /// The material of `p` in the default, energy-conserving layering.
    ///
    /// # Errors
    /// [`BrdfError::NotFinite`] / [`BrdfError::OutOfRange`] naming the
    /// OpenPBR parameter outside its domain (see the [module docs](self)).
    pub fn new(p: OpenPbrParams<S>) -> Result<Self, BrdfError> {
        Self::with_layering(p, Layering::EnergyConserving)
    }

    /// The material of `p` with the given [`Layering`] (reciprocal for
    /// bidirectional methods).
    ///
    /// # Errors
    /// As [`OpenPbr::new`].
    pub fn with_layering(p: OpenPbrParams<S>, layering: Layering) -> Result<Self, BrdfError> {
        let unit = |name, v| in_range(name, v, 0.0, 1.0);
        let base_weight = unit("base_weight", p.base_weight)?;
        let base_color = colour("base_color", p.base_color)?;
        let m = unit("base_metalness", p.base_metalness)?;
        let sigma = unit("base_diffuse_roughness", p.base_diffuse_roughness)?;
        let xi = unit("specular_weight", p.specular_weight)?;
        let spec_color = colour("specular_color", p.specular_color)?;
        let r_s = unit("specular_roughness", p.specular_roughness)?;
        let ior = in_range("specular_ior", p.specular_ior, 1.0, MAX_ETA)?;
        let w_c = unit("coat_weight", p.coat_weight)?;
        colour("coat_color", p.coat_color)?;
        let r_c = unit("coat_roughness", p.coat_roughness)?;
        let coat_ior = in_range("coat_ior", p.coat_ior, 1.0, MAX_ETA)?;
        unit("coat_darkening", p.coat_darkening)?;
        let w_f = unit("fuzz_weight", p.fuzz_weight)?;
        let fuzz_color = colour("fuzz_color", p.fuzz_color)?;
        let r_f = unit("fuzz_roughness", p.fuzz_roughness)?;

        let rho = base_color * base_weight;
        // The coat's roughening of the base lobes (§"Coat — Roughening"):
        // r'_s = lerp(r_s, min(1, r_s⁴ + 2 r_c⁴)^¼, w_C).
        let r_s = if w_c > 0.0 {
            let q = |r: f32| (r * r) * (r * r);
            let rough = radiometry::math::sqrtf(radiometry::math::sqrtf((q(r_s) + 2.0 * q(r_c)).min(1.0)));
            r_s + w_c * (rough - r_s)
        } else {
            r_s
        };
        let a_s = alpha(r_s);
        // Every lobe's parameter below is in its domain by construction (the
        // material's own checks above): the lobes are built without theirs.
        let ggx_s = Ggx::from_valid(a_s);
        let eta_s = modulated_ior(specular_ior_ratio(ior, coat_ior, w_c), xi);
        // The dielectric lobes keep their albedo's table cells (the reader of
        // `E_s`, `E_C`: `Brdf::with_prepared_albedo`); the coat's only when on.
        // One computation of the ratio table's cells of `(α_s, η_s)` serves the
        // lobe's albedo cells and the diffuse sampler's rows (the same grid);
        // the cells are `with_prepared_albedo`'s, bit for bit.
        let spec_cells = RatioCells::new(ggx_s.alpha(), eta_s);
        let spec = Microfacet::new(
            ggx_s,
            Achromatic::new(Dielectric::from_valid(eta_s).with_cells(DielectricCells::new_in(
                spec_cells,
                ggx_s.alpha(),
                eta_s,
            ))),
        );
        // The metal shares the specular lobe's roughness, so its `E₁` reader
        // is the one inside the specular lobe's cells.
        let metal = (m > 0.0 && xi > 0.0).then(|| {
            let a = ggx_s.alpha();
            let e1 = spec
                .fresnel
                .albedo_cells(a)
                .map_or_else(|| AlbedoReader::new(a), |c| *c.reader.e1_reader());
            Metal::new(ggx_s, rho, spec_color, e1, MomentCell::at(spec_cells.alpha))
        });
        let diffuse = Eon::from_valid(rho, sigma);
        let diffuse_sampler = TransmissionSampler::from_cells(&spec_cells, a_s, eta_s);
        let a_c = alpha(r_c);
        let ggx_c = Ggx::from_valid(a_c);
        // The coat's cells (only when on) serve its lobe's albedo cells and the
        // darkening's `Ē` at the smallest roughness.
        let coat_cells = (w_c > 0.0).then(|| RatioCells::new(ggx_c.alpha(), coat_ior));
        let coat_fresnel = Dielectric::from_valid(coat_ior);
        let coat_fresnel = match coat_cells {
            Some(c) => coat_fresnel.with_cells(DielectricCells::new_in(c, ggx_c.alpha(), coat_ior)),
            None => coat_fresnel,
        };
        let coat = Microfacet::new(ggx_c, Achromatic::new(coat_fresnel));
        let reciprocal = layering == Layering::Reciprocal;
        // Only the fuzz lobe of this mode, and only when the fuzz is on.
        let fuzz = if w_f > 0.0 && !reciprocal {
            Some(LtcSheen::from_valid(fuzz_color, r_f))
        } else {
            None
        };
        let r_f = r_f.max(MIN_SHEEN_ROUGHNESS);
        let fuzz_reciprocal = if w_f > 0.0 && reciprocal {
            Some(Sheen::new(fuzz_color, r_f)?)
        } else {
            None
        };

        let (spec_e, coat_e) = (
            lobe_albedo(&spec, (a_s, eta_s)),
            lobe_albedo(&coat, (a_c, coat_ior)),
        );
        // Ē_s, read with the specular lobe's cells (the same bits).
        let spec_avg = spec
            .fresnel
            .albedo_cells(a_s)
            .map_or_else(|| dielectric_average(a_s, eta_s), |c| c.average);
        let coat_norm = if reciprocal && w_c > 0.0 {
            inv(1.0 - dielectric_average(a_c, coat_ior))
        } else {
            1.0
        };
        // Reciprocal mode: `Ē_F` and the joint normalisations `2∫ Π t μ dμ` by
        // 8-point Gauss–Legendre in μ, each layer's albedo read once per node.
        let (fuzz_norm, joint_norm) = if reciprocal {
            let nodes = gauss_legendre_nodes();
            let t = SheenAlbedoTable::get();
            // `w_F E_F(μ)` (the fuzz's table reads) and `t = 1 − E` of each layer
            // present (`t = 1` for a layer that is off).
            let e_f = nodes.map(|mu| if w_f > 0.0 { w_f * t.albedo(mu, r_f) } else { 0.0 });
            let t_f = e_f.map(|e| if w_f > 0.0 { 1.0 - e } else { 1.0 });
            let t_s = nodes.map(|mu| 1.0 - spec_e(mu));
            let t_c = nodes.map(|mu| if w_c > 0.0 { 1.0 - coat_e(mu) } else { 1.0 });
            let fuzz_norm = if w_f > 0.0 {
                inv(1.0 - gauss_legendre_sum(e_f))
            } else {
                1.0
            };
            // `t_F t_s` and `t_F t_C t_s` at each node (zipped, not indexed).
            let (mut bare, mut coated) = ([0.0f32; 8], [0.0f32; 8]);
            for ((((b, c), f), s), t) in bare.iter_mut().zip(&mut coated).zip(t_f).zip(t_s).zip(t_c) {
                *b = f * s;
                *c = f * t * s;
            }
            let joint = [inv(gauss_legendre_sum(bare)), inv(gauss_legendre_sum(coated))];
            (fuzz_norm, joint)
        } else {
            (1.0, [1.0, 1.0])
        };
        // Coat darkening (§"Darkening"): E_b at normal incidence, K_r, r_b
        // (only read under a coat).
        let (base_albedo_normal, k_r) = if w_c > 0.0 {
            let n = Vec3::Z;
            // E_s(1) and, with a metal, E₁(1) — in one read where the specular
            // lobe keeps its cells (each bit for bit its own read).
            let (e_s1, metal_e1) = spec_albedo_and_e1_at_normal(&spec, (a_s, eta_s), metal.as_ref());
            let glossy = spec_color * e_s1 + diffuse.directional_albedo(n).value * (1.0 - e_s1);
            let metal_normal = metal.as_ref().map_or(S::zero(), |x| {
                // E₁(1), read once for the single scattering and the loss.
                x.single_albedo_at_normal(metal_e1)
                    + x.ms_scale * (core::f32::consts::PI * (1.0 - metal_e1).clamp(0.0, 1.0))
            });
            // (Inlined: the roughness cell of the constant α is folded.)
            let e_f_avg = coat_cells.map_or_else(
                || dielectric_average_inline(MIN_ALPHA, coat_ior),
                |c| c.average_at(MIN_ALPHA),
            );
            (
                metal_normal * (m * xi) + glossy * (1.0 - m),
                1.0 - (1.0 - e_f_avg) / (coat_ior * coat_ior),
            )
        } else {
            (S::zero(), 0.0)
        };
        let r_d = 1.0 + (r_s - 1.0) * (xi * f0_of(ior)).clamp(0.0, 1.0);
        let r_b = r_d + m * (r_s - r_d);
        let on = [
            w_f > 0.0,
            w_c > 0.0,
            m > 0.0 && xi > 0.0,
            m > 0.0 && xi > 0.0,
            m < 1.0,
            m < 1.0,
        ];
        Ok(Self {
            params: p,
            layering,
            fuzz,
            fuzz_reciprocal,
            coat,
            metal,
            spec,
            diffuse,
            diffuse_sampler,
            on,
            xi,
            spec_ae: (a_s, eta_s),
            coat_ae: (a_c, coat_ior),
            inv_spec_avg: inv(1.0 - spec_avg),
            coat_norm,
            fuzz_norm,
            joint_norm,
            base_albedo_normal,
            k_r,
            r_b,
            coat_f0: f0_of(coat_ior),
        })
    }

    /// The GGX terms of the coat and of the specular roughness at the unit
    /// pair `(wi, wo)` side by side ([`ggx_pair`]), and with `value` their
    /// dielectric Fresnel factors `[F_C, F_s]` at `cos θd`
    /// ([`dielectric_pair`]; `[0, 0]` without). Out of line: the pass of a
    /// material without a coat does not carry it.
    #[inline(never)]
    fn coat_pair(&self, wi: Vec3, wo: Vec3, value: bool) -> (GgxPairTerms, [f32; 2]) {
        let t = ggx_pair(
            [self.coat.distribution.alpha(), self.spec.distribution.alpha()],
            wi,
            wo,
        );
        let f = if value {
            dielectric_pair([self.coat_ae.1, self.spec_ae.1], t.cos_d)
        } else {
            [0.0; 2]
        };
        (t, f)
    }

    /// The parameters it was built from.
    pub fn params(&self) -> &OpenPbrParams<S> {
        &self.params
    }

    /// The layering mode.
    pub fn layering(&self) -> Layering {
        self.layering
    }

    /// `(E_s(μ), E₁(μ))`: the specular lobe's albedo (0 with the layer off)
    /// and the `F = 1` albedo at its roughness, the metal's (1 without a
    /// metal), from one read of `E₁` where both are on and the lobe keeps
    /// its cells — each bit for bit its own read.
    #[inline]
    fn spec_and_e1(&self, mu: f32) -> (f32, f32) {
        if !self.on[SPEC] {
            return (
                0.0,
                self.metal.as_ref().map_or(1.0, |x| x.e1.albedo(e1_table(), mu)),
            );
        }
        spec_albedo_and_e1(&self.spec, self.spec_ae, self.metal.as_ref(), mu)
    }

    /// `E_C(μ)`: the coat lobe's albedo.
    #[inline]
    fn e_coat(&self, mu: f32) -> f32 {
        lobe_albedo(&self.coat, self.coat_ae)(mu)
    }

    /// `w_F E_F(μ)`: the fuzz's untinted albedo, weighted.
    #[inline]
    fn e_fuzz(&self, mu: f32) -> f32 {
        self.params.fuzz_weight
            * match self.layering {
                Layering::EnergyConserving => self.fuzz.as_ref().map_or(0.0, |f| f.albedo_untinted(mu)),
                Layering::Reciprocal => self
                    .fuzz_reciprocal
                    .as_ref()
                    .map_or(0.0, |f| SheenAlbedoTable::get().albedo(mu, f.roughness())),
            }
    }

    /// The fuzz lobe's value, density, sample and albedo in this mode.
    #[inline]
    fn fuzz_eval(&self, wi: Vec3, wo: Vec3) -> S {
        match self.layering {
            Layering::EnergyConserving => self.fuzz.as_ref().map_or(S::zero(), |f| f.eval(wi, wo)),
            Layering::Reciprocal => self
                .fuzz_reciprocal
                .as_ref()
                .map_or(S::zero(), |f| f.eval(wi, wo)),
        }
    }

    #[inline]
    fn fuzz_pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        match self.layering {
            Layering::EnergyConserving => self.fuzz.as_ref().map_or(0.0, |f| f.pdf(wi, wo)),
            Layering::Reciprocal => self.fuzz_reciprocal.as_ref().map_or(0.0, |f| f.pdf(wi, wo)),
        }
    }

    fn fuzz_sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<S>> {
        match self.layering {
            Layering::EnergyConserving => self.fuzz.as_ref().and_then(|f| f.sample(wo, u)),
            Layering::Reciprocal => self.fuzz_reciprocal.as_ref().and_then(|f| f.sample(wo, u)),
        }
    }

    fn fuzz_albedo(&self, wo: Vec3) -> S {
        match self.layering {
            Layering::EnergyConserving => self
                .fuzz
                .as_ref()
                .map_or(S::zero(), |f| f.directional_albedo(wo).value),
            Layering::Reciprocal => self
                .fuzz_reciprocal
                .as_ref()
                .map_or(S::zero(), |f| f.directional_albedo(wo).value),
        }
    }

    /// The coat's absorption `A(μi, μo)` per channel
    /// ([`coat_absorption`](radiometry::compose::coat_absorption)).
    #[inline]
    fn absorption(&self, mu_i: f32, mu_o: f32) -> S {
        radiometry::compose::coat_absorption(self.params.coat_color, self.coat_ae.1, mu_i, mu_o)
    }

    /// The coat's and the specular lobe's albedo reads for one batch call
    /// (rows built only for the layers that are on).
    #[inline]
    fn batch_reads(&self) -> BatchReads<'_, S> {
        BatchReads {
            coat: BatchRead::new(&self.coat, self.coat_ae, self.on[COAT]),
            spec: BatchRead::new(&self.spec, self.spec_ae, self.on[SPEC]),
        }
    }

    /// What the views of a chunk read at `μo` (`mu_o`, of the unit `wo_u`)
    /// for their picks: `E_C(μo)` and `E_s(μo)` through
    /// [`BatchRead::chunk`] and the diffuse lobe's albedo from its batch
    /// (each 0 where its layer is off).
    #[inline]
    fn view_reads(
        &self,
        r: &BatchReads<'_, S>,
        wo_u: &[Vec3],
        mu_o: &[f32; CHUNK],
    ) -> ([f32; CHUNK], [f32; CHUNK], [S; CHUNK]) {
        let (mut coat_o, mut spec_o) = ([0.0f32; CHUNK], [0.0f32; CHUNK]);
        let mut diffuse = [S::zero(); CHUNK];
        if self.on[COAT] {
            r.coat.chunk(mu_o, &mut coat_o);
        }
        if self.on[SPEC] {
            r.spec.chunk(mu_o, &mut spec_o);
            self.diffuse.directional_albedo_batch(wo_u, &mut diffuse);
        }
        (coat_o, spec_o, diffuse)
    }

    /// [`Brdf::eval`] of one chunk of at most [`CHUNK`] pairs (`out` as long
    /// as the shorter of `wi`, `wo`): the lobes' own batch kernels at the
    /// unit directions, the layers' albedos at `μo` and `μi` through
    /// [`BatchRead::chunk`], then the views and [`OpenPbrView::value_of`]
    /// element by element — bit for bit `eval`.
    fn eval_chunk(&self, r: &BatchReads<'_, S>, wi: &[Vec3], wo: &[Vec3], out: &mut [S]) {
        let (wi_u, mu_i) = unit_chunk(wi, |a| a.z.min(1.0));
        let (wo_u, mu_o) = unit_chunk(wo, view_cosine);
        let n = wi.len().min(wo.len()).min(out.len()).min(CHUNK);
        let (wi_u, wo_u) = (wi_u.get(..n).unwrap_or(&[]), wo_u.get(..n).unwrap_or(&[]));
        let (mut coat_o, mut spec_o, mut es_i) = ([0.0f32; CHUNK], [0.0f32; CHUNK], [0.0f32; CHUNK]);
        if self.on[COAT] {
            r.coat.chunk(&mu_o, &mut coat_o);
        }
        if self.on[SPEC] {
            r.spec.chunk(&mu_o, &mut spec_o);
            r.spec.chunk(&mu_i, &mut es_i);
        }
        let mut fc = [S::zero(); CHUNK];
        let mut fm = [S::zero(); CHUNK];
        let mut fs = [S::zero(); CHUNK];
        let mut fd = [S::zero(); CHUNK];
        if self.on[COAT] {
            self.coat.eval_batch(wi_u, wo_u, &mut fc);
        }
        if let Some(metal) = &self.metal {
            metal.single.eval_batch(wi_u, wo_u, &mut fm);
        }
        if self.on[SPEC] {
            self.spec.eval_batch(wi_u, wo_u, &mut fs);
            self.diffuse.eval_batch(wi_u, wo_u, &mut fd);
        }
        let lobes = fc.iter().zip(&fm).zip(fs.iter().zip(&fd));
        let reads = coat_o.iter().zip(&spec_o).zip(&es_i);
        for ((((o, &w), &i), (((&c, &m), (&s, &d)), ((&co, &so), &e))), &raw_o) in
            out.iter_mut().zip(wi_u).zip(&mu_i).zip(lobes.zip(reads)).zip(wo)
        {
            let reads = PreRead {
                coat_o: co,
                spec_o: so,
                diffuse: None,
            };
            let view = self.view_at(raw_o, false, Some(reads));
            *o = if !view.valid || w.z.is_nan() || w.z <= 0.0 || !w.is_finite() {
                S::zero()
            } else {
                let v = LobeValues {
                    fuzz: if self.on[FUZZ] {
                        view.fuzz_eval_pdf(w).0
                    } else {
                        S::zero()
                    },
                    coat: c,
                    metal: m,
                    spec: s,
                    diffuse: d,
                    es_i: e,
                };
                view.value_of(i, &v)
            };
        }
    }

    /// [`Brdf::pdf`] of one chunk of at most [`CHUNK`] pairs: the lobes' own
    /// `pdf_batch` kernels at the unit directions, the albedos the picks need
    /// at `μo` from the lobes' batches and lanes, then the views and
    /// [`OpenPbrView::pdf_of`] element by element — bit for bit `pdf`.
    fn pdf_chunk(&self, r: &BatchReads<'_, S>, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]) {
        let (wi_u, _) = unit_chunk(wi, |_| 0.0);
        let (wo_u, mu_o) = unit_chunk(wo, view_cosine);
        let n = wi.len().min(wo.len()).min(out.len()).min(CHUNK);
        let (wi_u, wo_u) = (wi_u.get(..n).unwrap_or(&[]), wo_u.get(..n).unwrap_or(&[]));
        let (coat_o, spec_o, diffuse) = self.view_reads(r, wo_u, &mu_o);
        let (mut dc, mut dm, mut ds) = ([0.0f32; CHUNK], [0.0f32; CHUNK], [0.0f32; CHUNK]);
        if self.on[COAT] {
            self.coat.pdf_batch(wi_u, wo_u, &mut dc);
        }
        if self.on[SPEC] {
            self.spec.pdf_batch(wi_u, wo_u, &mut ds);
        }
        if let Some(metal) = &self.metal {
            // The metal's density is the specular lobe's (one roughness).
            if self.on[SPEC] {
                dm = ds;
            } else {
                metal.single.pdf_batch(wi_u, wo_u, &mut dm);
            }
        }
        let dens = dc.iter().zip(&dm).zip(&ds);
        let reads = coat_o.iter().zip(&spec_o).zip(&diffuse);
        for (((o, &w), (((&c, &m), &s), ((&co, &so), &d))), &raw_o) in
            out.iter_mut().zip(wi_u).zip(dens.zip(reads)).zip(wo)
        {
            let reads = PreRead {
                coat_o: co,
                spec_o: so,
                diffuse: Some(d),
            };
            let view = self.view_at(raw_o, true, Some(reads));
            *o = view.pdf_of(w, [c, m, s], None);
        }
    }

    /// [`Brdf::sample`] of one chunk of at most [`CHUNK`] elements: the
    /// views (their albedos from the lobes' batches and lanes), each GGX
    /// lobe's `sample_batch` over the elements that pick it (the fuzz, the
    /// metal's multiple scattering and the diffuse lobe draw one by one),
    /// then the lobes' `eval_batch` and `pdf_batch` at the drawn directions,
    /// layered and mixed as `sample` does — bit for bit `sample`.
    fn sample_chunk(
        &self,
        r: &BatchReads<'_, S>,
        wo: &[Vec3],
        u: &[[f32; 2]],
        out: &mut [Option<BrdfSample<S>>],
    ) {
        let n = wo.len().min(u.len()).min(out.len()).min(CHUNK);
        let (Some(wo), Some(u), Some(out)) = (wo.get(..n), u.get(..n), out.get_mut(..n)) else {
            return;
        };
        let (wo_u, mu_o) = unit_chunk(wo, view_cosine);
        let wo_u = wo_u.get(..n).unwrap_or(&[]);
        let (coat_o, spec_o, diffuse) = self.view_reads(r, wo_u, &mu_o);
        // The views and the picks; the GGX lobes' draws grouped per lobe.
        let mut views: [Option<OpenPbrView<'_, S>>; CHUNK] = [None; CHUNK];
        let mut wi: [Option<Vec3>; CHUNK] = [None; CHUNK];
        let mut idx = [[0usize; CHUNK]; 3];
        let mut wo_sub = [[Vec3::ZERO; CHUNK]; 3];
        let mut u_sub = [[[0.0f32; 2]; CHUNK]; 3];
        let mut count = [0usize; 3];
        for (k, (((view, w), &o), &v)) in views.iter_mut().zip(wi.iter_mut()).zip(wo).zip(u).enumerate() {
            let reads = PreRead {
                coat_o: coat_o.get(k).copied().unwrap_or(0.0),
                spec_o: spec_o.get(k).copied().unwrap_or(0.0),
                diffuse: diffuse.get(k).copied(),
            };
            let vw = self.view_at(o, true, Some(reads));
            *view = Some(vw);
            if !vw.valid {
                continue;
            }
            let polar_part = vw.diffuse_polar(v);
            let (lobe, uu) = vw.pick(v);
            let group = match lobe {
                COAT => Some(0),
                METAL if self.metal.is_some() => Some(1),
                METAL => None,
                SPEC => Some(2),
                FUZZ => {
                    *w = vw.fuzz_direction(uu);
                    None
                }
                _ => {
                    *w = vw.direction_of(lobe, uu, polar_part);
                    None
                }
            };
            if let Some(g) = group {
                let c = count[g];
                if let (Some(i), Some(ws), Some(us)) =
                    (idx[g].get_mut(c), wo_sub[g].get_mut(c), u_sub[g].get_mut(c))
                {
                    (*i, *ws, *us) = (k, vw.wo, uu);
                    count[g] = c + 1;
                }
            }
        }
        let mut drawn: [Option<BrdfSample<S>>; CHUNK] = [None; CHUNK];
        for (g, ((idx, ws), us)) in idx.iter().zip(&wo_sub).zip(&u_sub).enumerate() {
            let c = count[g];
            let (Some(idx), Some(ws), Some(us), Some(d)) =
                (idx.get(..c), ws.get(..c), us.get(..c), drawn.get_mut(..c))
            else {
                continue;
            };
            match g {
                0 => self.coat.sample_batch(ws, us, d),
                1 => {
                    if let Some(metal) = &self.metal {
                        metal.single.sample_batch(ws, us, d);
                    }
                }
                _ => self.spec.sample_batch(ws, us, d),
            }
            for (&k, s) in idx.iter().zip(d.iter()) {
                if let Some(w) = wi.get_mut(k) {
                    *w = s.map(|s| s.wi);
                }
            }
        }
        // The value and the mixture density at the drawn directions.
        let mut wi_u = [Vec3::Z; CHUNK];
        let mut mu_i = [0.0f32; CHUNK];
        for ((a, mi), w) in wi_u.iter_mut().zip(mu_i.iter_mut()).zip(&wi) {
            if let Some(w) = w {
                *a = unit(*w);
                *mi = a.z.min(1.0);
            }
        }
        let wi_u = wi_u.get(..n).unwrap_or(&[]);
        let mut es_i = [0.0f32; CHUNK];
        let (mut fc, mut fm, mut fs, mut fd) = (
            [S::zero(); CHUNK],
            [S::zero(); CHUNK],
            [S::zero(); CHUNK],
            [S::zero(); CHUNK],
        );
        let (mut dc, mut dm, mut ds) = ([0.0f32; CHUNK], [0.0f32; CHUNK], [0.0f32; CHUNK]);
        if self.on[COAT] {
            self.coat.eval_batch(wi_u, wo_u, &mut fc);
            self.coat.pdf_batch(wi_u, wo_u, &mut dc);
        }
        if self.on[SPEC] {
            self.spec.eval_batch(wi_u, wo_u, &mut fs);
            self.spec.pdf_batch(wi_u, wo_u, &mut ds);
            self.diffuse.eval_batch(wi_u, wo_u, &mut fd);
            r.spec.chunk(&mu_i, &mut es_i);
        }
        if let Some(metal) = &self.metal {
            metal.single.eval_batch(wi_u, wo_u, &mut fm);
            // The metal's density is the specular lobe's (one roughness).
            if self.on[SPEC] {
                dm = ds;
            } else {
                metal.single.pdf_batch(wi_u, wo_u, &mut dm);
            }
        }
        for (k, o) in out.iter_mut().enumerate() {
            *o = match (
                views.get(k).copied().flatten(),
                wi.get(k).copied().flatten(),
                wi_u.get(k),
            ) {
                (Some(view), Some(raw), Some(&w)) => {
                    if !view.valid || w.z.is_nan() || w.z <= 0.0 || !w.is_finite() {
                        None
                    } else {
                        let (fuzz, fuzz_d) = match (self.on[FUZZ], &self.fuzz) {
                            (false, _) => (S::zero(), None),
                            (true, Some(_)) => {
                                let (v, d) = view.fuzz_eval_pdf(w);
                                (v, Some(d))
                            }
                            (true, None) => (self.fuzz_eval(w, view.wo), None),
                        };
                        let at = |a: &[S; CHUNK]| a.get(k).copied().unwrap_or(S::zero());
                        let at1 = |a: &[f32; CHUNK]| a.get(k).copied().unwrap_or(0.0);
                        let v = LobeValues {
                            fuzz,
                            coat: at(&fc),
                            metal: at(&fm),
                            spec: at(&fs),
                            diffuse: at(&fd),
                            es_i: at1(&es_i),
                        };
                        let f = view.value_of(at1(&mu_i), &v);
                        let pdf = view.pdf_of(w, [at1(&dc), at1(&dm), at1(&ds)], fuzz_d);
                        finish(raw, f, pdf)
                    }
                }
                _ => None,
            };
        }
    }

    /// Prepares the view `ωo`: the layers' factors at `μo` and the lobes'
    /// pick probabilities, for any number of [`OpenPbrView::eval`],
    /// [`OpenPbrView::pdf`] and [`OpenPbrView::sample`] calls.
    pub fn prepare(&self, wo: Vec3) -> OpenPbrView<'_, S> {
        self.prepare_with(wo, true, None)
    }

    /// [`view_at`](Self::view_at), inlined where the optimiser chooses (the
    /// scalar `prepare`).
    #[inline]
    fn prepare_with(&self, wo: Vec3, picks: bool, reads: Option<PreRead<S>>) -> OpenPbrView<'_, S> {
        self.view_at(wo, picks, reads)
    }

    /// [`prepare`](Self::prepare), with the pick probabilities only when
    /// `picks` (the value alone does not need them: `eval` skips the lobes'
    /// albedos), and `E_C(μo)`, `E_s(μo)` from `reads` where a batch read
    /// them already (the same values: [`BatchRead::chunk`]).
    ///
    /// Always inlined: the batches' chunk loops and the scalar `eval` build a
    /// view per element, and a call there keeps the view in memory and the
    /// layers' switches unhoisted (the batches ran 1.3× slower).
    #[inline(always)]
    fn view_at(&self, wo: Vec3, picks: bool, reads: Option<PreRead<S>>) -> OpenPbrView<'_, S> {
        let wo = unit(wo);
        let mu_o = wo.z;
        let valid = mu_o.is_finite() && mu_o > 0.0 && wo.is_finite();
        let mut view = OpenPbrView {
            m: self,
            wo,
            valid,
            mu_o: if valid { mu_o.min(1.0) } else { 0.0 },
            fuzz_o: 0.0,
            fuzz_at: None,
            coat_o: 0.0,
            spec_o: 0.0,
            darkening: S::splat(1.0),
            metal_loss_o: 0.0,
            diffuse_pu: 0.0,
            cdf: [0.0; LOBES],
        };
        if !valid {
            return view;
        }
        let mu = view.mu_o;
        let p = &self.params;
        if self.on[FUZZ] {
            // Energy mode: `E_F(μo)` is the `R` of the LTC's state at `ωo`
            // (the same read), where that state holds one.
            view.fuzz_at = self.fuzz.as_ref().map(|f| f.at(wo));
            view.fuzz_o = match &view.fuzz_at {
                Some(at) if at.is_above() => p.fuzz_weight * at.albedo_untinted(),
                _ => self.e_fuzz(mu),
            };
        }
        if self.on[COAT] {
            view.coat_o = reads.map_or_else(|| self.e_coat(mu), |r| r.coat_o);
            // D = lerp(1, Δ, δ), Δ = (1 − K)/(1 − E_b K), K = lerp(K_s, K_r, r_b).
            let k_s = match self.layering {
                Layering::EnergyConserving => Dielectric::new(self.coat_ae.1).map_or(0.0, |d| d.eval(mu)),
                Layering::Reciprocal => self.coat_f0,
            };
            let k = k_s + self.r_b * (self.k_r - k_s);
            let delta = p.coat_darkening;
            view.darkening = self.base_albedo_normal.map(|eb| {
                let d = (1.0 - k) / (1.0 - eb * k).max(1e-6);
                1.0 + delta * (d.clamp(0.0, 1.0) - 1.0)
            });
        }
        // E_s(μo), and E₁(μo) of the metal, read once for its loss and its
        // albedo (with the specular layer on, in the same read as E_s).
        let metal_e1_o = match reads {
            Some(r) => {
                if self.on[SPEC] {
                    view.spec_o = r.spec_o;
                }
                self.metal
                    .as_ref()
                    .map_or(1.0, |metal| metal.e1.albedo(e1_table(), mu))
            }
            None => {
                let (e_s, e1) = self.spec_and_e1(mu);
                view.spec_o = e_s;
                e1
            }
        };
        if self.metal.is_some() {
            view.metal_loss_o = (1.0 - metal_e1_o).clamp(0.0, 1.0);
        }
        view.diffuse_pu = self.diffuse.uniform_share(mu);
        if !picks {
            return view;
        }
        // Pick probabilities ∝ each lobe's share of the layered albedo at ωo.
        let mut share = [0.0f32; LOBES];
        if self.on[FUZZ] {
            // The fuzz's albedo is its colour times the untinted read of `fuzz_o`.
            share[FUZZ] = view.fuzz_o * p.fuzz_color.average();
        }
        let a_f = view.fuzz_factor_o(Leaf::Specular);
        if self.on[COAT] {
            share[COAT] = a_f * p.coat_weight * view.coat_o;
        }
        let under = |leaf| (view.coat_factor(mu, view.layers_o(), leaf) * view.fuzz_factor_o(leaf)).average();
        let u_s = under(Leaf::Specular);
        if let Some(metal) = &self.metal {
            let w = u_s * p.base_metalness * self.xi;
            share[METAL] = w * metal.single_albedo_with(wo, metal_e1_o).average();
            share[METAL_MS] = w * metal.f_ms.average() * view.metal_loss_o;
        }
        if self.on[SPEC] {
            share[SPEC] = u_s * (1.0 - p.base_metalness) * p.specular_color.average() * view.spec_o;
            share[DIFFUSE] = under(Leaf::Diffuse)
                * (1.0 - p.base_metalness)
                * (1.0 - view.spec_o)
                * reads
                    .and_then(|r| r.diffuse)
                    .unwrap_or_else(|| self.diffuse.directional_albedo(wo).value)
                    .average();
        }
        // The running sums of the shares (negative and non-finite ones as 0),
        // then each times one reciprocal of the total: no chain of normalised
        // additions after the reciprocal (the picks sit on a sample's
        // critical path).
        let mut acc = 0.0f32;
        let mut running = [0.0f32; LOBES];
        for (r, s) in running.iter_mut().zip(share) {
            acc += if s.is_finite() { s.max(0.0) } else { 0.0 };
            *r = acc;
        }
        let total = acc;
        if total >= f32::MIN_POSITIVE && total.is_finite() {
            let inv_total = 1.0 / total;
            view.cdf = running.map(|r| r * inv_total);
        } else if total > 0.0 && total.is_finite() {
            // A subnormal total divides (its reciprocal overflows).
            view.cdf = running.map(|r| r / total);
        } else {
            // Nothing reflects: the diffuse lobe's sampler (its value is 0).
            view.cdf = [0.0, 0.0, 0.0, 0.0, 0.0, 1.0];
        }
        view.cdf[LOBES - 1] = 1.0;
        view
    }
}

/// `[u₁, u₀]`: the point at which the lobes whose first coordinate sets the
/// polar angle (the diffuse lobe's two maps, the metal's multiple-scattering
/// lobe) draw for a sample point `u` whose `u₀` the pick rescaled.
///
/// The pick's `u₀` waits for the picks (the layers' albedos at `ωo`); `u₁`
/// does not. With `u₁` on the polar angle — the maps' cell search, roots and
/// division — only the azimuth's sine and cosine wait for the pick, and the
/// polar part runs beside the picks: a mispredicted pick (random `u`) no
/// longer exposes it (`docs/performance.md`). The GGX lobes' visible-normal
/// draw already takes its azimuth from `u₀`. Each map is measure-preserving
/// either way, so the densities are unchanged.
#[inline(always)]
fn polar_first(u: [f32; 2]) -> [f32; 2] {
    [u[1], u[0]]
}

/// The sample at `wi` with the material's value `f` and mixture density
/// `pdf` there: `None` unless `pdf > 0` and the weight `f cos θi / pdf` is
/// finite.
#[inline]
fn finish<S: Spectrum>(wi: Vec3, f: S, pdf: f32) -> Option<BrdfSample<S>> {
    if pdf.is_nan() || pdf <= 0.0 {
        return None;
    }
    let weight = f * (wi.z.max(0.0) / pdf);
    if !weight.is_finite() {
        return None;
    }
    Some(BrdfSample { wi, pdf, weight })
}

/// `w` itself when unit (to `10⁻⁵` in the squared length), else normalised
/// (the cold path; a zero or non-finite `w` stays as it is and is rejected
/// by the callers' `z > 0` and finiteness checks).
#[inline]
fn unit(w: Vec3) -> Vec3 {
    let l2 = w.length_squared();
    if (l2 - 1.0).abs() <= 1e-5 {
        w
    } else {
        renormalise(w, l2)
    }
}

#[cold]
#[inline(never)]
fn renormalise(w: Vec3, l2: f32) -> Vec3 {
    if l2.is_finite() && l2 > 0.0 {
        let s = w / radiometry::math::sqrtf(l2);
        if s.is_finite() { s } else { Vec3::ZERO }
    } else {
        let m = w.abs().max_element();
        if m.is_finite() && m > 0.0 {
            let s = w / m;
            s / radiometry::math::sqrtf(s.length_squared())
        } else {
            Vec3::ZERO
        }
    }
}

/// `2∫₀¹ e(μ) μ dμ` by 8-point Gauss–Legendre.
/// The abscissae and weights of 4-point Gauss–Legendre on `[−1, 1]`
/// (positive half), mapped to `μ ∈ [0, 1]` as `½(1 ∓ x)`.
const GL_X: [f32; 4] = [0.183_434_65, 0.525_532_4, 0.796_666_5, 0.960_289_9];
const GL_W: [f32; 4] = [0.362_683_78, 0.313_706_65, 0.222_381_03, 0.101_228_54];

/// The eight nodes `μ_k` of [`gauss_legendre_sum`], in its order: `½(1 −
/// x)`, `½(1 + x)` for each abscissa (no indexing: no panic path).
#[inline]
fn gauss_legendre_nodes() -> [f32; 8] {
    let [a, b, c, d] = GL_X;
    [
        0.5 * (1.0 - a),
        0.5 * (1.0 + a),
        0.5 * (1.0 - b),
        0.5 * (1.0 + b),
        0.5 * (1.0 - c),
        0.5 * (1.0 + c),
        0.5 * (1.0 - d),
        0.5 * (1.0 + d),
    ]
}

/// `2∫₀¹ e(μ) μ dμ` from `e` at the [nodes](gauss_legendre_nodes),
/// `Σ_k ½ w_k · 2 μ_k e(μ_k)` in the nodes' order, clamped to `[0, 1]`.
#[inline]
fn gauss_legendre_sum(e: [f32; 8]) -> f32 {
    let nodes = gauss_legendre_nodes();
    let mut s = 0.0;
    for ((mu, v), w) in nodes.chunks_exact(2).zip(e.chunks_exact(2)).zip(GL_W) {
        for (mu, v) in mu.iter().zip(v) {
            s += 0.5 * w * 2.0 * mu * v;
        }
    }
    s.clamp(0.0, 1.0)
}

/// The reciprocal mode's through-factor of a layer for a base lobe: the
/// Kelemen form `ti to/(1 − Ē)` under the diffuse lobe (exact for a
/// Lambertian body, which cannot concentrate light where the form would
/// overshoot), capped by `ti` and `to` under the specular lobes
/// ([`reciprocal_through`](radiometry::compose::reciprocal_through)).
#[inline]
fn through(leaf: Leaf, ti: f32, to: f32, inv_avg: f32) -> f32 {
    match leaf {
        Leaf::Diffuse => {
            let v = ti * to * inv_avg;
            if v.is_finite() { v.max(0.0) } else { 0.0 }
        }
        Leaf::Specular => radiometry::compose::reciprocal_through(ti, to, inv_avg),
    }
}

/// The layers' albedos at one cosine that the reciprocal mode's factors
/// read: `w_F E_F(μ)` and `E_C(μ)` (0 for a layer that is off).
#[derive(Clone, Copy, Debug)]
struct LayersAt {
    fuzz: f32,
    coat: f32,
}

/// The two kinds of base lobe the reciprocal mode normalises apart.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Leaf {
    Specular,
    Diffuse,
}

/// What a batch read for [`OpenPbr::view_at`] in lanes: `E_C(μo)`,
/// `E_s(μo)` and, for the picks, the diffuse lobe's albedo at `ωo` — the
/// values `view_at` would read.
#[derive(Clone, Copy)]
struct PreRead<S> {
    coat_o: f32,
    spec_o: f32,
    diffuse: Option<S>,
}

/// The lobes' values at one `(ωi, ωo)` (0 for a lobe that is off) and the
/// specular layer's albedo `E_s(μi)`: what [`OpenPbrView::value_of`] layers.
#[derive(Clone, Copy, Default)]
struct LobeValues<S> {
    fuzz: S,
    coat: S,
    metal: S,
    spec: S,
    diffuse: S,
    es_i: f32,
}

/// An [`OpenPbr`] prepared for one view direction `ωo` ([`OpenPbr::prepare`]).
#[derive(Clone, Copy, Debug)]
pub struct OpenPbrView<'a, S: Spectrum> {
    m: &'a OpenPbr<S>,
    wo: Vec3,
    valid: bool,
    mu_o: f32,
    /// `w_F E_F(μo)`, `E_C(μo)`, `E_s(μo)`.
    fuzz_o: f32,
    /// The LTC fuzz's state at `ωo` (energy mode, fuzz on): its
    /// coefficients at `μo` and `ωo`'s azimuth, read once per view.
    fuzz_at: Option<LtcAt>,
    coat_o: f32,
    spec_o: f32,
    /// The coat darkening `D` per channel.
    darkening: S,
    /// `1 − E₁(μo)` of the metal's multiple-scattering lobe.
    metal_loss_o: f32,
    /// The diffuse lobe's uniform share `p_u(μo)` (EON's sampler; the rest
    /// is the transmission-shaped cosine lobe).
    diffuse_pu: f32,
    /// Cumulative pick probabilities of the lobes.
    cdf: [f32; LOBES],
}

impl<S: Spectrum> OpenPbrView<'_, S> {
    /// The fuzz lobe's value and density at `wi` (`ωo` the view's): from
    /// the LTC's state at `ωo` in the energy mode, else the lobe's own calls.
    #[inline(always)]
    fn fuzz_eval_pdf(&self, wi: Vec3) -> (S, f32) {
        match (&self.m.fuzz, &self.fuzz_at) {
            (Some(f), Some(at)) => f.eval_pdf_at(at, wi),
            _ => (self.m.fuzz_eval(wi, self.wo), self.m.fuzz_pdf(wi, self.wo)),
        }
    }

    /// The direction the fuzz lobe draws at `uu` (energy mode: from the
    /// LTC's state at `ωo`, bit for bit the lobe's own draw; its value and
    /// density come from the pass over every lobe).
    #[inline]
    fn fuzz_direction(&self, uu: [f32; 2]) -> Option<Vec3> {
        match &self.fuzz_at {
            Some(at) if at.is_above() => at.direction(uu),
            _ => self.m.fuzz_sample(self.wo, uu).map(|s| s.wi),
        }
    }

    /// The fuzz lobe's density at `wi` alone (as [`fuzz_eval_pdf`](Self::fuzz_eval_pdf)).
    #[inline(always)]
    fn fuzz_pdf_at(&self, wi: Vec3) -> f32 {
        match (&self.m.fuzz, &self.fuzz_at) {
            (Some(f), Some(at)) => f.eval_pdf_at(at, wi).1,
            _ => self.m.fuzz_pdf(wi, self.wo),
        }
    }

    /// The layers' albedos at `μo` ([`LayersAt`]): the view's own.
    #[inline(always)]
    fn layers_o(&self) -> LayersAt {
        LayersAt {
            fuzz: self.fuzz_o,
            coat: self.coat_o,
        }
    }

    /// The layers' albedos at `μi` that the reciprocal mode's factors read
    /// ([`LayersAt`]), each read once per pass: the view's where `μi = μo`
    /// (and in the energy mode, whose factors read none at `μi`), 0 for a
    /// layer that is off.
    #[inline]
    fn layers_at(&self, mu_i: f32) -> LayersAt {
        let m = self.m;
        if m.layering == Layering::EnergyConserving || mu_i == self.mu_o {
            return self.layers_o();
        }
        LayersAt {
            fuzz: if m.on[FUZZ] { m.e_fuzz(mu_i) } else { 0.0 },
            coat: if m.on[COAT] { m.e_coat(mu_i) } else { 0.0 },
        }
    }

    /// The fuzz's factor at `ωo` alone (energy mode: `1 − w_F E_F(μo)`).
    #[inline]
    fn fuzz_factor_o(&self, leaf: Leaf) -> f32 {
        self.fuzz_factor(self.layers_o(), leaf)
    }

    /// The fuzz's factor for `(μi, μo)`, `at` the layers' albedos at `μi`.
    #[inline]
    fn fuzz_factor(&self, at: LayersAt, leaf: Leaf) -> f32 {
        if !self.m.on[FUZZ] {
            return 1.0;
        }
        match self.m.layering {
            Layering::EnergyConserving => 1.0 - self.fuzz_o,
            Layering::Reciprocal => through(leaf, 1.0 - at.fuzz, 1.0 - self.fuzz_o, self.m.fuzz_norm),
        }
    }

    /// What the layers pass to the diffuse lobe, per channel. Energy mode:
    /// `a_F(μo) U(μi, μo) K(μi, μo)`. Reciprocal mode: the product of every
    /// layer's `t(μi) t(μo)` over the joint normalisation `2∫ Π t μ dμ`, per
    /// coverage part — exact for a Lambertian body under any stack of clear
    /// layers (`∫ Π t(μi) t(μo)/N · ρ/π · μi dωi = ρ Π t(μo)`).
    #[inline]
    fn diffuse_factor(&self, mu_i: f32, at: LayersAt, es_i: f32) -> S {
        let m = self.m;
        let ts = (1.0 - es_i) * (1.0 - self.spec_o);
        match m.layering {
            Layering::EnergyConserving => {
                self.coat_factor(mu_i, at, Leaf::Diffuse)
                    * (self.fuzz_factor(at, Leaf::Diffuse) * ts * m.inv_spec_avg)
            }
            Layering::Reciprocal => {
                let tf = if m.on[FUZZ] {
                    (1.0 - at.fuzz) * (1.0 - self.fuzz_o)
                } else {
                    1.0
                };
                let bare = S::splat(ts * tf * m.joint_norm[0]);
                if !m.on[COAT] {
                    return bare;
                }
                let w_c = m.params.coat_weight;
                let tc = (1.0 - at.coat) * (1.0 - self.coat_o);
                let coated =
                    m.absorption(mu_i, self.mu_o) * self.darkening * (ts * tf * tc * m.joint_norm[1] * w_c);
                coated + bare * (1.0 - w_c)
            }
        }
    }

    /// `U = (1 − w_C) + w_C D A(μi, μo) T_C(μi, μo)` per channel.
    #[inline(always)]
    fn coat_factor(&self, mu_i: f32, at: LayersAt, leaf: Leaf) -> S {
        let m = self.m;
        if !m.on[COAT] {
            return S::splat(1.0);
        }
        let w_c = m.params.coat_weight;
        let t = match m.layering {
            Layering::EnergyConserving => 1.0 - self.coat_o,
            Layering::Reciprocal => through(leaf, 1.0 - at.coat, 1.0 - self.coat_o, m.coat_norm),
        };
        let a = m.absorption(mu_i, self.mu_o);
        (a * self.darkening * (w_c * t)).map(|v| v + (1.0 - w_c))
    }

    /// The diffuse lobe's density: EON's uniform share `p_u/(2π)` plus the
    /// rest drawn in proportion to the specular layer's transmission,
    /// `(1 − p_u) p_T(μi)` ([`TransmissionSampler`]) — the lobe's value
    /// carries `1 − E_s(μi)`, which a cosine lobe would leave in the weight.
    #[inline]
    fn diffuse_pdf(&self, mu_i: f32) -> f32 {
        let pu = self.diffuse_pu;
        pu * (0.5 * core::f32::consts::FRAC_1_PI) + (1.0 - pu) * self.m.diffuse_sampler.pdf(mu_i)
    }

    /// The diffuse lobe's transmission-shaped polar part at the sample
    /// point `u` — from `u₁` alone ([`polar_first`]), so that `sample` and
    /// `sample_batch` draw it ahead of the pick — or `None` where the lobe is
    /// off.
    #[inline(always)]
    fn diffuse_polar(&self, u: [f32; 2]) -> Option<(f32, f32)> {
        self.m.on[SPEC].then(|| self.m.diffuse_sampler.polar(u[1]))
    }

    /// The direction the diffuse lobe draws at `u`, or `None` on the
    /// horizon: `u₀` picks the component (`u₀ < p_u`: the uniform
    /// hemisphere, else the transmission-shaped lobe) and, rescaled to it,
    /// sets the azimuth; `u₁` sets the polar angle ([`polar_first`]).
    ///
    /// `polar_part`: the transmission-shaped map's polar part at `u₁` where
    /// the caller drew it already ([`TransmissionSampler::polar`]).
    #[inline]
    fn diffuse_direction(&self, u: [f32; 2], polar_part: Option<(f32, f32)>) -> Option<Vec3> {
        let pu = self.diffuse_pu;
        let wi = if u[0] < pu {
            square_to_uniform_hemisphere(polar_first([(u[0] / pu).min(ONE_MINUS_EPSILON), u[1]]))
        } else {
            // `p_u = 0` (σ = 0, OpenPBR's default) skips the division: `u₀/1`.
            let v = if pu <= 0.0 {
                u[0]
            } else if pu < 1.0 {
                (u[0] - pu) / (1.0 - pu)
            } else {
                0.0
            };
            let [polar, azimuth] = polar_first([v.clamp(0.0, ONE_MINUS_EPSILON), u[1]]);
            let polar = polar_part.unwrap_or_else(|| self.m.diffuse_sampler.polar(polar));
            TransmissionSampler::direction(polar, azimuth)
        };
        (wi.z > 0.0 && wi.is_finite()).then_some(wi)
    }

    /// `(E_s(μi), 1 − E₁(μi))`, what the value reads at `μi`: the view's
    /// reads where `μi = μo`, else [`OpenPbr::spec_and_e1`] (0 for a layer
    /// that is off).
    #[inline]
    fn reads_at(&self, mu_i: f32) -> (f32, f32) {
        if mu_i == self.mu_o {
            return (self.spec_o, self.metal_loss_o);
        }
        let (e_s, e1) = self.m.spec_and_e1(mu_i);
        let loss = if self.m.metal.is_some() {
            (1.0 - e1).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (e_s, loss)
    }

    /// The lobes' values at `ωi` with their layer weights, and the mixture
    /// pdf of the lobes' densities with the pick probabilities.
    #[inline]
    fn eval_inner(&self, wi: Vec3, want_value: bool, want_pdf: bool) -> (S, f32) {
        let m = self.m;
        let wi = unit(wi);
        if !self.valid || wi.z.is_nan() || wi.z <= 0.0 || !wi.is_finite() {
            return (S::zero(), 0.0);
        }
        let wo = self.wo;
        let mu_i = wi.z.min(1.0);
        let p = &m.params;
        let mut f = S::zero();
        let mut pdf = 0.0f32;
        let prob = |k: usize| self.prob(k);
        if m.on[FUZZ] {
            match (&m.fuzz, &self.fuzz_at) {
                // Energy mode: the LTC's state at ωo (table read and frame
                // once per view), value and density in one pass.
                (Some(fuzz), Some(at)) => {
                    let (v, d) = fuzz.eval_pdf_at(at, wi);
                    if want_value {
                        f += v * p.fuzz_weight;
                    }
                    if want_pdf {
                        pdf += prob(FUZZ) * d;
                    }
                }
                _ => {
                    if want_value {
                        f += m.fuzz_eval(wi, wo) * p.fuzz_weight;
                    }
                    if want_pdf {
                        pdf += prob(FUZZ) * m.fuzz_pdf(wi, wo);
                    }
                }
            }
        }
        // The layers' albedos at μi (reciprocal mode), read once for the pass.
        let at = if want_value {
            self.layers_at(mu_i)
        } else {
            self.layers_o()
        };
        // With the coat and a lobe of the specular roughness both on, their
        // GGX terms side by side in vector lanes, and the two dielectric
        // Fresnel factors likewise (each lane bit for bit its lobe's own
        // term, `microfacet::ggx_pair`); the lobes' own calls otherwise and
        // for a pair not unit to within 4ε (their cold paths).
        let zero = S::zero();
        let (lanes, fresnel) =
            if m.on[COAT] && (m.metal.is_some() || m.on[SPEC]) && is_unit(wi) && is_unit(wo) {
                let (t, f) = m.coat_pair(wi, wo, want_value);
                (Some(t), f)
            } else {
                (None, [0.0; 2])
            };
        // Lane `k`'s `(s, pdf)` as the lobe's `eval_pdf` masks them.
        let lane = |t: &GgxPairTerms, k: usize| {
            (
                if want_value { t.s[k] } else { 0.0 },
                if want_pdf { t.pdf[k] } else { 0.0 },
            )
        };
        if m.on[COAT] {
            let (v, d) = match &lanes {
                Some(t) => {
                    let (s, d) = lane(t, 0);
                    (if s == 0.0 { zero } else { S::splat(fresnel[0]) * s }, d)
                }
                None => m.coat.eval_pdf(wi, wo, want_value, want_pdf),
            };
            if want_value {
                f += v * (self.fuzz_factor(at, Leaf::Specular) * p.coat_weight);
            }
            if want_pdf {
                pdf += prob(COAT) * d;
            }
        }
        let under_s = if want_value && (m.on[METAL] || m.on[SPEC]) {
            self.coat_factor(mu_i, at, Leaf::Specular) * self.fuzz_factor(at, Leaf::Specular)
        } else {
            S::zero()
        };
        let (es_i, metal_loss_i) = if want_value {
            self.reads_at(mu_i)
        } else {
            (0.0, 0.0)
        };
        // The metal and the dielectric specular lobe share the specular
        // roughness: where both are on, one pass of the microfacet terms
        // serves both (each value and density bit for bit its lobe's).
        let spec_pair = match &m.metal {
            Some(metal) if m.on[SPEC] => Some(match &lanes {
                Some(t) => {
                    let (s, d) = lane(t, 1);
                    if s == 0.0 {
                        (zero, zero, d)
                    } else {
                        (
                            metal.single.fresnel.eval(t.cos_d) * s,
                            S::splat(fresnel[1]) * s,
                            d,
                        )
                    }
                }
                None => metal
                    .single
                    .eval_pdf_pair(&m.spec.fresnel, wi, wo, want_value, want_pdf),
            }),
            _ => None,
        };
        if let Some(metal) = &m.metal {
            let (v, d) = match (spec_pair, &lanes) {
                (Some((v, _, d)), _) => (v, d),
                (None, Some(t)) => {
                    let (s, d) = lane(t, 1);
                    (
                        if s == 0.0 {
                            zero
                        } else {
                            metal.single.fresnel.eval(t.cos_d) * s
                        },
                        d,
                    )
                }
                (None, None) => metal.single.eval_pdf(wi, wo, want_value, want_pdf),
            };
            if want_value {
                let ms = metal.ms_scale * (metal_loss_i * self.metal_loss_o);
                f += (v + ms) * under_s * (p.base_metalness * m.xi);
            }
            if want_pdf {
                pdf += prob(METAL) * d + prob(METAL_MS) * metal.ms_pdf(mu_i);
            }
        }
        if m.on[SPEC] {
            let dielectric = 1.0 - p.base_metalness;
            let (v, d) = match (spec_pair, &lanes) {
                (Some((_, v, d)), _) => (v, d),
                (None, Some(t)) => {
                    let (s, d) = lane(t, 1);
                    (if s == 0.0 { zero } else { S::splat(fresnel[1]) * s }, d)
                }
                (None, None) => m.spec.eval_pdf(wi, wo, want_value, want_pdf),
            };
            if want_value {
                f += v * p.specular_color * under_s * dielectric;
                // Kelemen: (1 − E_s(μi))(1 − E_s(μo))/(1 − Ē_s).
                f += m.diffuse.eval(wi, wo) * self.diffuse_factor(mu_i, at, es_i) * dielectric;
            }
            if want_pdf {
                pdf += prob(SPEC) * d + prob(DIFFUSE) * self.diffuse_pdf(mu_i);
            }
        }
        let pdf = if pdf.is_finite() && pdf > 0.0 { pdf } else { 0.0 };
        (f.map(|v| if v.is_finite() { v.max(0.0) } else { 0.0 }), pdf)
    }

    /// The mixture density at the unit direction `wi` from the GGX lobes'
    /// densities `[coat, metal, specular]` (0 for a lobe that is off): the
    /// batches' form of [`eval_inner`](Self::eval_inner)'s density,
    /// operation for operation (held equal bit for bit by the batch tests).
    /// `fuzz_d` is the fuzz's density where the caller took it together with
    /// its value (as `sample`'s pass does), else `None`.
    #[inline(always)]
    fn pdf_of(&self, wi: Vec3, d: [f32; 3], fuzz_d: Option<f32>) -> f32 {
        let m = self.m;
        if !self.valid || wi.z.is_nan() || wi.z <= 0.0 || !wi.is_finite() {
            return 0.0;
        }
        let mu_i = wi.z.min(1.0);
        let mut pdf = 0.0f32;
        let prob = |k: usize| self.prob(k);
        if m.on[FUZZ] {
            pdf += prob(FUZZ) * fuzz_d.unwrap_or_else(|| self.fuzz_pdf_at(wi));
        }
        if m.on[COAT] {
            pdf += prob(COAT) * d[0];
        }
        if let Some(metal) = &m.metal {
            pdf += prob(METAL) * d[1] + prob(METAL_MS) * metal.ms_pdf(mu_i);
        }
        if m.on[SPEC] {
            pdf += prob(SPEC) * d[2] + prob(DIFFUSE) * self.diffuse_pdf(mu_i);
        }
        if pdf.is_finite() && pdf > 0.0 { pdf } else { 0.0 }
    }

    /// `f_r` from the lobes' values at `(ωi, ωo)` (`ωi` above the horizon,
    /// `μi = cos θi`), each with its layer weights: the fuzz, the coat over
    /// the fuzz, the metal and the dielectric specular lobe under both, and
    /// the diffuse lobe under every layer (Kelemen's `1 − E_s(μi)` from
    /// `v.es_i`); negative and non-finite channels to 0. The batches' form
    /// of [`eval_inner`](Self::eval_inner)'s value, operation for operation
    /// (the scalar path keeps its own, interleaved with the densities: it
    /// runs faster that way for RGB); the batch tests hold the two equal bit
    /// for bit.
    #[inline(always)]
    fn value_of(&self, mu_i: f32, v: &LobeValues<S>) -> S {
        let m = self.m;
        let p = &m.params;
        let mut f = S::zero();
        if m.on[FUZZ] {
            f += v.fuzz * p.fuzz_weight;
        }
        let at = self.layers_at(mu_i);
        if m.on[COAT] {
            f += v.coat * (self.fuzz_factor(at, Leaf::Specular) * p.coat_weight);
        }
        let under_s = if m.on[METAL] || m.on[SPEC] {
            self.coat_factor(mu_i, at, Leaf::Specular) * self.fuzz_factor(at, Leaf::Specular)
        } else {
            S::zero()
        };
        if let Some(metal) = &m.metal {
            let ms = metal.ms_scale * (metal.loss(mu_i) * self.metal_loss_o);
            f += (v.metal + ms) * under_s * (p.base_metalness * m.xi);
        }
        if m.on[SPEC] {
            let dielectric = 1.0 - p.base_metalness;
            f += v.spec * p.specular_color * under_s * dielectric;
            // Kelemen: (1 − E_s(μi))(1 − E_s(μo))/(1 − Ē_s).
            f += v.diffuse * self.diffuse_factor(mu_i, at, v.es_i) * dielectric;
        }
        f.map(|v| if v.is_finite() { v.max(0.0) } else { 0.0 })
    }

    /// `f_r(ωi, ωo)` per channel.
    pub fn eval(&self, wi: Vec3) -> S {
        self.eval_inner(wi, true, false).0
    }

    /// The density `sample` draws `ωi` with: `Σ_k p_k pdf_k(ωi, ωo)`.
    pub fn pdf(&self, wi: Vec3) -> f32 {
        self.eval_inner(wi, false, true).1
    }

    /// Picks a lobe with `u[0]` (rescaled), samples it with the rest, then
    /// evaluates the material and its mixture pdf at the drawn `ωi` in one
    /// pass over the lobes.
    pub fn sample(&self, u: [f32; 2]) -> Option<BrdfSample<S>> {
        if !self.valid {
            return None;
        }
        let m = self.m;
        let polar_part = self.diffuse_polar(u);
        let (k, uu) = self.pick(u);
        let wo = self.wo;
        let s = match k {
            FUZZ => self.fuzz_direction(uu).map(|wi| BrdfSample {
                wi,
                pdf: 0.0,
                weight: S::zero(),
            }),
            COAT => m.coat.sample(wo, uu),
            METAL => m.metal.as_ref().and_then(|x| x.single.sample(wo, uu)),
            SPEC => m.spec.sample(wo, uu),
            _ => self.direction_of(k, uu, polar_part).map(|wi| BrdfSample {
                wi,
                pdf: 0.0,
                weight: S::zero(),
            }),
        }?;
        let (f, pdf) = self.eval_inner(s.wi, true, true);
        finish(s.wi, f, pdf)
    }

    /// The lobe `k` that `u[0]` picks from the cumulative probabilities, and
    /// the sample point `[u₀', u[1]]` for it (`u₀` rescaled to the lobe's
    /// interval).
    #[inline]
    fn pick(&self, u: [f32; 2]) -> (usize, [f32; 2]) {
        let u0 = if u[0].is_finite() {
            u[0].clamp(0.0, 1.0 - f32::EPSILON / 2.0)
        } else {
            0.0
        };
        let mut k = LOBES - 1;
        for (i, &c) in self.cdf.iter().enumerate() {
            if u0 < c {
                k = i;
                break;
            }
        }
        let lo = k
            .checked_sub(1)
            .and_then(|i| self.cdf.get(i))
            .copied()
            .unwrap_or(0.0);
        let width = self.cdf.get(k).copied().unwrap_or(1.0) - lo;
        let v = if width > 0.0 {
            ((u0 - lo) / width).clamp(0.0, 1.0 - f32::EPSILON / 2.0)
        } else {
            0.0
        };
        (k, [v, u[1]])
    }

    /// The direction the metal's multiple-scattering lobe (`k =
    /// METAL_MS`) or the diffuse lobe (any other `k` outside the GGX lobes and
    /// the fuzz) draws at `uu`: the direction alone, its value and density
    /// come from the pass over every lobe. `polar_part`: the diffuse map's
    /// polar part where the caller drew it ahead of the pick
    /// ([`diffuse_direction`](Self::diffuse_direction)).
    #[inline]
    fn direction_of(&self, k: usize, uu: [f32; 2], polar_part: Option<(f32, f32)>) -> Option<Vec3> {
        if k == METAL_MS {
            self.m.metal.as_ref().and_then(|x| {
                let wi = x.ms_sample(polar_first(uu));
                (wi.z > 0.0).then_some(wi)
            })
        } else {
            self.diffuse_direction(uu, polar_part)
        }
    }

    /// The number of components of the sampling map
    /// ([`Brdf::sampling_components`]): the fuzz, the coat, the metal's
    /// single scattering, the metal's multiple-scattering lobe, the
    /// dielectric specular lobe, and the diffuse lobe's two (EON's uniform
    /// hemisphere, and the cosine-weighted one shaped by the specular layer's
    /// transmission `1 − E_s(μi)`) — in the order of [`sample`](Self::sample)'s pick.
    pub const COMPONENTS: usize = LOBES + 1;

    /// The pick probability of lobe `k` where the mixture density counts it
    /// (the `prob(k)` of [`pdf`](Self::pdf)), else 0.
    fn lobe_weight(&self, k: usize) -> f32 {
        let m = self.m;
        let counted = match k {
            FUZZ | COAT => m.on.get(k).copied().unwrap_or(false),
            METAL | METAL_MS => m.metal.is_some(),
            _ => m.on[SPEC],
        };
        if !self.valid || !counted {
            return 0.0;
        }
        self.prob(k)
    }

    /// The width of lobe `k`'s interval of the cumulative pick
    /// probabilities (0 for `k` out of range).
    #[inline]
    fn prob(&self, k: usize) -> f32 {
        let lo = k
            .checked_sub(1)
            .and_then(|i| self.cdf.get(i))
            .copied()
            .unwrap_or(0.0);
        (self.cdf.get(k).copied().unwrap_or(0.0) - lo).max(0.0)
    }

    /// The weight of component `k` (see [`COMPONENTS`](Self::COMPONENTS)):
    /// the lobe's pick probability, times the diffuse lobe's own component
    /// weight for the last two — the weights [`pdf`](Self::pdf) mixes with.
    pub fn component_weight(&self, k: usize) -> f32 {
        match k {
            DIFFUSE | LOBES => {
                self.lobe_weight(DIFFUSE) * self.m.diffuse.component_weight(self.wo, k - DIFFUSE)
            }
            k if k < DIFFUSE => self.lobe_weight(k),
            _ => 0.0,
        }
    }

    /// The direction component `k` draws at `u` (the lobe's own sampler, as
    /// [`sample`](Self::sample) draws it from its rescaled `u₀`; the diffuse
    /// lobe's maps and the metal's multiple-scattering lobe at `[u₁, u₀]`,
    /// polar angle first), or `None`.
    pub fn sample_component(&self, k: usize, u: [f32; 2]) -> Option<Vec3> {
        if !self.valid {
            return None;
        }
        let m = self.m;
        let wo = self.wo;
        let u = [u[0].clamp(0.0, 1.0 - f32::EPSILON / 2.0), u[1]];
        let wi = match k {
            FUZZ => m.fuzz_sample(wo, u)?.wi,
            COAT => m.coat.sample(wo, u)?.wi,
            METAL => m.metal.as_ref().and_then(|x| x.single.sample(wo, u))?.wi,
            METAL_MS => m.metal.as_ref()?.ms_sample(polar_first(u)),
            SPEC => m.spec.sample(wo, u)?.wi,
            DIFFUSE => square_to_uniform_hemisphere(polar_first(u)),
            LOBES => {
                let [polar, azimuth] = polar_first(u);
                m.diffuse_sampler.sample(polar, azimuth)
            }
            _ => return None,
        };
        (wi.z > 0.0).then_some(wi)
    }

    /// The material's directional albedo at `ωo`, estimated from the lobes'
    /// albedos and the layers' factors at `μo` (the diffuse lobe's `1 − E_s`
    /// and the coat's absorption taken at `μo`).
    pub fn albedo(&self) -> Albedo<S> {
        if !self.valid {
            return Albedo::zero();
        }
        let m = self.m;
        let p = &m.params;
        let wo = self.wo;
        let mu = self.mu_o;
        let mut e = S::zero();
        if m.on[FUZZ] {
            e += m.fuzz_albedo(wo) * p.fuzz_weight;
        }
        if m.on[COAT] {
            e += S::splat(self.fuzz_factor(self.layers_o(), Leaf::Specular) * p.coat_weight * self.coat_o);
        }
        let o = self.layers_o();
        let under_s = self.coat_factor(mu, o, Leaf::Specular) * self.fuzz_factor(o, Leaf::Specular);
        if let Some(metal) = m.metal.as_ref().filter(|_| m.on[METAL]) {
            let ms = metal.f_ms * self.metal_loss_o;
            e += (metal.single_albedo(wo) + ms) * under_s * (p.base_metalness * m.xi);
        }
        if m.on[SPEC] {
            let d = 1.0 - p.base_metalness;
            e += p.specular_color * under_s * (d * self.spec_o);
            let under_d = self.coat_factor(mu, o, Leaf::Diffuse) * self.fuzz_factor(o, Leaf::Diffuse);
            e += m.diffuse.directional_albedo(wo).value * under_d * (d * (1.0 - self.spec_o));
        }
        Albedo {
            value: e,
            // The tables' error, the absorption and Kelemen factors taken at μo.
            error: 1e-2,
            is_bound: false,
        }
    }
}

impl<S: Spectrum> Brdf for OpenPbr<S> {
    type Spectrum = S;

    #[inline]
    fn eval(&self, wi: Vec3, wo: Vec3) -> S {
        self.view_at(wo, false, None).eval(wi)
    }

    /// In chunks: the lobes' own batch kernels (vector kernels with the
    /// `simd` feature), the layers' albedos in vector lanes, the layering
    /// per element — element by element equal to [`eval`](Brdf::eval).
    fn eval_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [S]) {
        let r = self.batch_reads();
        for ((wi, wo), out) in wi.chunks(CHUNK).zip(wo.chunks(CHUNK)).zip(out.chunks_mut(CHUNK)) {
            self.eval_chunk(&r, wi, wo, out);
        }
        radiometry::batch::zero_tail(out, wi.len().min(wo.len()));
    }

    /// [`eval_batch`](Brdf::eval_batch) for structure-of-arrays input.
    fn eval_batch_soa(&self, wi: Vec3Soa<'_>, wo: Vec3Soa<'_>, out: &mut [S]) {
        let n = wi.len().min(wo.len()).min(out.len());
        radiometry::batch::zero_tail(out, n);
        let (mut ci, mut co) = ([Vec3::ZERO; CHUNK], [Vec3::ZERO; CHUNK]);
        let r = self.batch_reads();
        let mut start = 0;
        for out in out.chunks_mut(CHUNK) {
            let k = out.len().min(n.saturating_sub(start));
            if k == 0 {
                break;
            }
            for (j, (a, b)) in ci.iter_mut().zip(co.iter_mut()).enumerate().take(k) {
                (*a, *b) = (
                    wi.get(start + j).unwrap_or(Vec3::ZERO),
                    wo.get(start + j).unwrap_or(Vec3::ZERO),
                );
            }
            self.eval_chunk(&r, ci.get(..k).unwrap_or(&[]), co.get(..k).unwrap_or(&[]), out);
            start += k;
        }
    }

    /// In chunks: each GGX lobe's `sample_batch` over the elements that pick
    /// it, then the lobes' `eval_batch` and `pdf_batch` at the drawn
    /// directions (element by element equal to [`sample`](Brdf::sample):
    /// the same `None`s, bit-identical `wi`, pdf and weight).
    fn sample_batch(&self, wo: &[Vec3], u: &[[f32; 2]], out: &mut [Option<BrdfSample<S>>]) {
        let r = self.batch_reads();
        for ((wo, u), out) in wo.chunks(CHUNK).zip(u.chunks(CHUNK)).zip(out.chunks_mut(CHUNK)) {
            self.sample_chunk(&r, wo, u, out);
        }
        radiometry::batch::zero_tail(out, wo.len().min(u.len()));
    }

    /// In chunks, as [`eval_batch`](Brdf::eval_batch): the lobes' own
    /// `pdf_batch` kernels and the albedos of the picks in lanes (element by
    /// element equal to [`pdf`](Brdf::pdf)).
    fn pdf_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]) {
        let r = self.batch_reads();
        for ((wi, wo), out) in wi.chunks(CHUNK).zip(wo.chunks(CHUNK)).zip(out.chunks_mut(CHUNK)) {
            self.pdf_chunk(&r, wi, wo, out);
        }
        radiometry::batch::zero_tail(out, wi.len().min(wo.len()));
    }

    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<S>> {
        self.prepare(wo).sample(u)
    }

    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        self.prepare(wo).pdf(wi)
    }

    /// `false`: the layers read tabulated albedos.
    fn is_smooth(&self) -> bool {
        false
    }
    /// Seven components: the six lobes, the diffuse one as EON's two
    /// ([`OpenPbrView::component_weight`]).
    fn sampling_components(&self) -> usize {
        OpenPbrView::<S>::COMPONENTS
    }

    fn component_weight(&self, wo: Vec3, k: usize) -> f32 {
        self.prepare(wo).component_weight(k)
    }

    fn sample_component(&self, wo: Vec3, k: usize, u: [f32; 2]) -> Option<Vec3> {
        self.prepare(wo).sample_component(k, u)
    }

    fn directional_albedo(&self, wo: Vec3) -> Albedo<S> {
        self.prepare(wo).albedo()
    }
}

impl<S: Spectrum> IsotropicBrdf for OpenPbr<S> {}
