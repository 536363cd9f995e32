//! # radiometry-brdfs
//!
//! BRDF plugins for [`radiometry`]: evaluation, importance sampling and pdfs
//! for renderers, sensor models and integrator benchmarks. `no_std`, no
//! `alloc`, no `unsafe`. Each plugin lives in its own module, uses only the
//! public trait API of `radiometry` (exactly what a third-party plugin would
//! do), validates its parameters at construction with a typed
//! [`BrdfError`], and cites the formula it implements.
//!
//! # Plugins and effects
//!
//! Every effect is chosen by type: the "off" choice is a zero-sized type
//! (`NoFresnel` is the constant 1 and inlines away), so a material pays only
//! for what it turns on.
//!
//! | plugin | model | Fresnel | shadowing–masking | multiple scattering | spectrum | sampling | SIMD batches (`simd`) |
//! |---|---|---|---|---|---|---|---|
//! | [`Lambertian<S>`](Lambertian) | `ρ/π` | — | — | — | any [`Spectrum`](radiometry::Spectrum) | cosine-weighted | `eval`, `pdf`, `sample` |
//! | [`ModifiedPhong<S>`](ModifiedPhong) | Lafortune & Willems 1994: diffuse `kd` + lobe `ks`, exponent `n ∈ [0, 10⁷]` | — | — | — | any | one-sample mixture of cosine and lobe | `eval`, `pdf`, `sample` |
//! | [`BlinnPhong<S>`](BlinnPhong) | Blinn 1977, exactly normalised | — | — | — | any | mixture of cosine and half-vector lobe | `eval`, `pdf`, `sample` |
//! | [`Microfacet<D, G, F>`](Microfacet) | Walter et al. 2007 with `D` = [`Ggx`] or [`Beckmann`], `α ∈ [10⁻⁴, 1]` | `F` = [`NoFresnel`], [`Schlick`], [`Dielectric`], [`Conductor`] (complex index, per channel; or a named metal: [`metals`]), [`F82Tint`] (OpenPBR's metal) | `G` = [`HeightCorrelated`] (pbrt-v4), [`Separable`] (Mitsuba 3) | — | that of `F` (`f32`, RGB, sampled) | visible normals (Heitz & d'Eon 2014) | `eval`, `pdf`, `sample` |
//! | [`KullaConty<D, G, F>`](KullaConty) | `Microfacet<D, G, F>` + the lobe of Kulla & Conty 2017 from tabulated albedos | as `Microfacet` (coloured `F_ms`) | as `Microfacet` | energy compensation: the furnace albedo is `1 − 6·10⁻⁴` | that of `F` | mixture of visible normals and cosine, exact pdf | scalar loops |
//! | [`Fon<S>`](Fon) | Fujii's improved Oren–Nayar `(ρ/π) A (1 + σ s/t)` (Portsmouth, Kutz & Hill 2025), `σ ∈ [0, 1]` dimensionless | — | — | — (albedo `ρ E_FON(μo)`, exact closed form) | any | mixture of cosine and uniform, exact pdf | `eval`, `pdf`, `sample` |
//! | [`Eon<S>`](Eon) | FON + the closed-form multiple-scattering lobe of Portsmouth, Kutz & Hill 2025 ("EON"), `σ ∈ [0, 1]` | — | — | energy-preserving: albedo 1 at `ρ = 1` for every `θo` (exact FON albedo) | any | mixture of cosine and uniform, exact pdf | `eval`, `pdf`, `sample` |
//! | [`OrenNayar<S>`](OrenNayar) | the classic qualitative Oren–Nayar as pbrt-v3 has it, `σ ∈ [0, π/2]` **radians**; `ρ ≤ 1/(A + B/2)` (it gains energy above) | — | — | — | any | mixture of cosine and uniform, exact pdf | `eval`, `pdf`, `sample` |
//! | [`Sheen<S>`](Sheen) | Estevez & Kulla 2017 cloth sheen: "Charlie" `D`, fitted Smith `Λ`, `r ∈ [0.07, 1]` | — (`F = 1`, scaled by `color`) | height-correlated, fitted `Λ` | — | any | uniform hemisphere, exact pdf `1/(2π)` | scalar loops |
//! | [`LtcSheen<S>`](LtcSheen) | Zeltner, Burley & Chiang 2022 multiple-scattering sheen: an LTC fitted to a volume of fibres, 32 × 32 table of `(a, b, R)` over `(cos θo, r)`, `r ∈ [0, 1]`; **not reciprocal** | — (scaled by `color`) | in the fit | in the fit (volumetric) | any | exact LTC sampling, pdf = the LTC density | scalar loops |
//! | [`OpenPbr<S>`](OpenPbr) | OpenPBR Surface 1.1's reflection layer: F82-tint metal, dielectric specular over EON, coat, fuzz (sheen), layered by `radiometry::compose` | dielectric ([`Achromatic`](microfacet::Achromatic)) and F82-tint | height-correlated | Kulla–Conty on the metal; EON | any | lobes and layers by albedo, exact mixture pdf | through the lobes' kernels |
//! | [`Tabulated<'a, S>`](tabulated::Tabulated) | measured isotropic data on a Rusinkiewicz grid (MERL layout), trilinear, borrowed from the caller | in the data | in the data | in the data | any | cosine, or half-vector density in a caller buffer ([`with_sampling`](tabulated::Tabulated::with_sampling)) | `eval`, `pdf` |
//!
//! **Directional albedo** ([`Brdf::directional_albedo`](radiometry::Brdf::directional_albedo),
//! what the lobe combinators of `radiometry::compose` pick lobes by): `Lambertian`
//! exactly; `Microfacet` and `KullaConty` from the Kulla–Conty tables times a
//! 16-point Fresnel average over the lobe, with a bound (the range of `F`
//! plus the table's `10⁻³`, [`microfacet::ALBEDO_TABLE_ERROR`]); `LtcSheen` exactly
//! (`color · R(μo, r)`, the fraction of the transformed cosine above the horizon being 1); the others by
//! the default 16-point sampling rule (an estimated error).
//!
//! **Metals** ([`metals`]): measured `η(λ) + i k(λ)` of Au, Ag, Cu, Al, Cr, Fe,
//! Ni, Ti, Pt and brass, evaluated at a renderer's wavelengths
//! ([`Conductor::metal_sampled`]) or reduced to RGB ([`Conductor::metal`],
//! [`F82Tint::metal`], [`metals::Metal::reflectance_rgb`]).
//!
//! Common to all: `eval` is zero below the horizon and never NaN, ∞ or a
//! panic for finite input (grazing angles, `ωi = −ωo`, `u = 1 − 2⁻²⁴`);
//! `pdf(ωi, ωo)` equals the pdf `sample` returned for that `ωi`, bit for
//! bit; every plugin is isotropic
//! ([`IsotropicBrdf`](radiometry::IsotropicBrdf)) and, except `LtcSheen`
//! (a fit of light leaving towards `ωo`, not reciprocal), reciprocal, and
//! its albedo stays ≤ 1 — each property tested on every plugin.
//!
//! **Feature `simd`**: 8-wide vector kernels (`wide`; 16 lanes when the
//! build has AVX-512) behind [`Brdf::eval_batch`](radiometry::Brdf::eval_batch),
//! [`eval_batch_soa`](radiometry::Brdf::eval_batch_soa),
//! [`pdf_batch`](radiometry::Brdf::pdf_batch) and
//! [`sample_batch`](radiometry::Brdf::sample_batch), returning exactly the
//! bits of the scalar methods (the table of kernels is in the `simd`
//! module). Without it, and for the plugins marked "scalar loops", the batch
//! methods loop over the scalar ones.
//!
//! # Example
//!
//! ```
//! use radiometry::frame::spherical_direction;
//! use radiometry::{Brdf, glam::Vec3};
//! use radiometry_brdfs::{Ggx, HeightCorrelated, KullaConty, Lambertian, Microfacet, NoFresnel, Schlick};
//!
//! // Rough plastic-like coat: GGX, height-correlated Smith, Schlick Fresnel in RGB.
//! let coat = Microfacet::<_, HeightCorrelated, _>::new(Ggx::new(0.2)?, Schlick::new(Vec3::splat(0.04))?);
//! let wo = spherical_direction(60f32.to_radians(), 0.0);
//! let s = coat.sample(wo, [0.3, 0.7]).expect("above the horizon");
//! assert_eq!(s.pdf, coat.pdf(s.wi, wo)); // bit for bit
//! assert!((s.weight - coat.eval(s.wi, wo) * s.wi.z / s.pdf).abs().max_element() < 1e-4);
//!
//! // The same rough metal with and without multiple-scattering compensation.
//! let single: Microfacet<Ggx> = Microfacet::new(Ggx::new(1.0)?, NoFresnel);
//! let compensated = KullaConty::from_single(single);
//! let wi = spherical_direction(30f32.to_radians(), 2.0);
//! assert!(compensated.eval(wi, wo) > single.eval(wi, wo));
//!
//! // Invalid parameters are rejected, never clamped.
//! assert!(Ggx::new(0.0).is_err() && Lambertian::new(-0.1f32).is_err());
//! assert_eq!(Lambertian::new(0.5f32)?.eval(-Vec3::Z, wo), 0.0); // below the horizon
//! # Ok::<(), radiometry_brdfs::BrdfError>(())
//! ```
#![no_std]
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod blinn_phong;
pub mod error;
pub mod lambertian;
pub mod metals;
pub mod microfacet;
pub mod openpbr;
pub mod phong;
pub mod rough_diffuse;
pub mod sheen;
#[cfg(feature = "simd")]
pub mod simd;
pub mod tabulated;
mod vec4;

#[cfg(test)]
mod batch_rule;
#[cfg(test)]
mod test_stream;

pub use error::BrdfError;
// -- re-exports: Lambertian / Phong family (keep this block for those modules)
pub use blinn_phong::BlinnPhong;
pub use lambertian::Lambertian;
pub use phong::ModifiedPhong;
pub use sheen::{LtcSheen, Sheen};
// -- end Lambertian / Phong family
// -- re-exports: microfacet (keep this block for that module)
pub use microfacet::{
    Beckmann, Conductor, Dielectric, F82Tint, Fresnel, Ggx, HeightCorrelated, KullaConty, Microfacet,
    MicrofacetDistribution, NoFresnel, Schlick, Separable, ShadowingMasking,
};
// -- end microfacet
// -- re-exports: OpenPBR
pub use openpbr::{Layering, OpenPbr, OpenPbrParams, OpenPbrView};
// -- end OpenPBR
// -- re-exports: rough diffuse (keep this block for that module)
pub use rough_diffuse::{Eon, Fon, OrenNayar};
// -- end rough diffuse

/// The README's example, compiled and run as a doctest.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
