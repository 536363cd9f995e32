//! Turning parsed specs into plugin BRDFs, integrators and light irradiances.
//!
//! The plugins are generic (`Microfacet<D, G, F>`), so every front end (the
//! CLI, the Python module, a renderer that picks its BRDF at run time)
//! erases their types behind [`AnyBrdf`] (a boxed trait object; one virtual call per
//! evaluation, or per batch through the batch methods the integrators use) and picks integrators through [`AnyIntegrator`] (an enum,
//! statically dispatched per variant).
//!
//! The run-time BRDF is generic over its spectrum ([`RunTimeSpectrum`]):
//! [`build_brdf`] builds the monochrome `AnyBrdf` (= `AnyBrdf<f32>`, the cheap
//! path: colours as their Rec. 709 luminance), [`build_brdf_rgb`] the linear-RGB
//! [`AnyBrdfRgb`] (= `AnyBrdf<Vec3>`: colours, named metals and MERL tables per
//! channel). Both come from one generic builder, [`build_brdf_as`]; a grey spec
//! ([`BrdfSpec::is_grey`]) gives the monochrome value on every RGB channel.

mod with_diffuse;

#[cfg(test)]
mod colour_tests;

use crate::{BrdfSpec, Distribution, FresnelSpec, G2Kind, LightSpec, MultipleScattering, SpecError};
use radiometry::BrdfSample;
use radiometry::batch::Vec3Soa;
use radiometry::compose::{Coated, Layering, Mix, Sum};
use radiometry::glam::Vec3;
use radiometry::integrator::{
    Adaptive, Auto, Estimate, GaussLegendre, Heuristic, Integrand, IntegrateError, Integrator, MonteCarlo,
    PointSet, Strategy, ToleranceOutcome, WarpedGaussLegendre, WideOf,
};
use radiometry::{Albedo, Brdf, Spectrum};
use radiometry_brdfs::metals::Metal;
use radiometry_brdfs::microfacet::Achromatic;
use radiometry_brdfs::{
    Beckmann, BlinnPhong, BrdfError, Conductor, Dielectric, Eon, F82Tint, Fon, Fresnel, Ggx,
    HeightCorrelated, KullaConty, Lambertian, LtcSheen, Microfacet, MicrofacetDistribution, ModifiedPhong,
    NoFresnel, OpenPbr, OpenPbrParams, OrenNayar, Schlick, Separable, ShadowingMasking, Sheen,
    microfacet::EnergyTable,
};

/// Object-safe view of a BRDF whose values are the spectrum `S` (`f32` by
/// default: monochrome; `Vec3`: linear RGB).
pub trait DynBrdf<S: Spectrum = f32>: Send + Sync {
    /// See [`Brdf::eval`].
    fn eval_dyn(&self, wi: Vec3, wo: Vec3) -> S;
    /// See [`Brdf::sample`].
    fn sample_dyn(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<S>>;
    /// See [`Brdf::pdf`].
    fn pdf_dyn(&self, wi: Vec3, wo: Vec3) -> f32;
    /// See [`Brdf::eval_batch`] (one virtual call per batch, so the
    /// plugin's vector kernel runs).
    fn eval_batch_dyn(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [S]);
    /// See [`Brdf::eval_batch_soa`].
    fn eval_batch_soa_dyn(&self, wi: Vec3Soa<'_>, wo: Vec3Soa<'_>, out: &mut [S]);
    /// See [`Brdf::pdf_batch`].
    fn pdf_batch_dyn(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]);
    /// See [`Brdf::sample_batch`].
    fn sample_batch_dyn(&self, wo: &[Vec3], u: &[[f32; 2]], out: &mut [Option<BrdfSample<S>>]);
    /// See [`Brdf::is_smooth`].
    fn is_smooth_dyn(&self) -> bool;
    /// See [`Brdf::sampling_components`].
    fn sampling_components_dyn(&self) -> usize;
    /// See [`Brdf::component_weight`].
    fn component_weight_dyn(&self, wo: Vec3, k: usize) -> f32;
    /// See [`Brdf::sample_component`].
    fn sample_component_dyn(&self, wo: Vec3, k: usize, u: [f32; 2]) -> Option<Vec3>;
    /// See [`Brdf::directional_albedo`].
    fn directional_albedo_dyn(&self, wo: Vec3) -> Albedo<S>;
    /// See [`Brdf::directional_albedo_batch`].
    fn directional_albedo_batch_dyn(&self, wo: &[Vec3], out: &mut [S]);
}

impl<S: Spectrum, B: Brdf<Spectrum = S> + Send + Sync> DynBrdf<S> for B {
    fn eval_dyn(&self, wi: Vec3, wo: Vec3) -> S {
        self.eval(wi, wo)
    }
    fn sample_dyn(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<S>> {
        self.sample(wo, u)
    }
    fn pdf_dyn(&self, wi: Vec3, wo: Vec3) -> f32 {
        self.pdf(wi, wo)
    }
    fn eval_batch_dyn(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [S]) {
        self.eval_batch(wi, wo, out)
    }
    fn eval_batch_soa_dyn(&self, wi: Vec3Soa<'_>, wo: Vec3Soa<'_>, out: &mut [S]) {
        self.eval_batch_soa(wi, wo, out)
    }
    fn pdf_batch_dyn(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]) {
        self.pdf_batch(wi, wo, out)
    }
    fn sample_batch_dyn(&self, wo: &[Vec3], u: &[[f32; 2]], out: &mut [Option<BrdfSample<S>>]) {
        self.sample_batch(wo, u, out)
    }
    fn is_smooth_dyn(&self) -> bool {
        self.is_smooth()
    }
    fn sampling_components_dyn(&self) -> usize {
        self.sampling_components()
    }
    fn component_weight_dyn(&self, wo: Vec3, k: usize) -> f32 {
        self.component_weight(wo, k)
    }
    fn sample_component_dyn(&self, wo: Vec3, k: usize, u: [f32; 2]) -> Option<Vec3> {
        self.sample_component(wo, k, u)
    }
    fn directional_albedo_dyn(&self, wo: Vec3) -> Albedo<S> {
        self.directional_albedo(wo)
    }
    fn directional_albedo_batch_dyn(&self, wo: &[Vec3], out: &mut [S]) {
        self.directional_albedo_batch(wo, out)
    }
}

/// A type-erased plugin BRDF with values of the spectrum `S`: `AnyBrdf` (=
/// `AnyBrdf<f32>`, monochrome, from [`build_brdf`]) or [`AnyBrdfRgb`] (linear
/// RGB, from [`build_brdf_rgb`]).
pub struct AnyBrdf<S: Spectrum = f32>(Box<dyn DynBrdf<S>>);

/// The RGB run-time BRDF: every channel of a spec's colours, named metals and
/// MERL tables kept ([`build_brdf_rgb`]).
pub type AnyBrdfRgb = AnyBrdf<Vec3>;

impl<S: Spectrum> Brdf for AnyBrdf<S> {
    type Spectrum = S;
    #[inline]
    fn eval(&self, wi: Vec3, wo: Vec3) -> S {
        self.0.eval_dyn(wi, wo)
    }
    #[inline]
    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<S>> {
        self.0.sample_dyn(wo, u)
    }
    #[inline]
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        self.0.pdf_dyn(wi, wo)
    }
    #[inline]
    fn eval_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [S]) {
        self.0.eval_batch_dyn(wi, wo, out)
    }
    #[inline]
    fn eval_batch_soa(&self, wi: Vec3Soa<'_>, wo: Vec3Soa<'_>, out: &mut [S]) {
        self.0.eval_batch_soa_dyn(wi, wo, out)
    }
    #[inline]
    fn pdf_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]) {
        self.0.pdf_batch_dyn(wi, wo, out)
    }
    #[inline]
    fn sample_batch(&self, wo: &[Vec3], u: &[[f32; 2]], out: &mut [Option<BrdfSample<S>>]) {
        self.0.sample_batch_dyn(wo, u, out)
    }
    fn is_smooth(&self) -> bool {
        self.0.is_smooth_dyn()
    }
    fn sampling_components(&self) -> usize {
        self.0.sampling_components_dyn()
    }
    fn component_weight(&self, wo: Vec3, k: usize) -> f32 {
        self.0.component_weight_dyn(wo, k)
    }
    fn sample_component(&self, wo: Vec3, k: usize, u: [f32; 2]) -> Option<Vec3> {
        self.0.sample_component_dyn(wo, k, u)
    }
    fn directional_albedo(&self, wo: Vec3) -> Albedo<S> {
        self.0.directional_albedo_dyn(wo)
    }
    fn directional_albedo_batch(&self, wo: &[Vec3], out: &mut [S]) {
        self.0.directional_albedo_batch_dyn(wo, out)
    }
}

mod sealed {
    pub trait Sealed {}
    impl Sealed for f32 {}
    impl Sealed for radiometry::glam::Vec3 {}
}

/// The spectra the run-time BRDF is built in: how a spec's colours, scalar
/// Fresnel terms, named metals and MERL tables become values of the spectrum.
/// Implemented (sealed) for `f32` (monochrome: each colour by its Rec. 709
/// luminance, [`crate::luminance`]; a metal fitted to the luminance of its
/// reflectance; a MERL table by the luminance of its channels) and `Vec3`
/// (linear RGB: the channels as given; a metal's spectral reflectance reduced
/// to linear sRGB under D65 with the CIE 1931 2° observer, per channel; a
/// MERL table's three channels).
///
/// One generic builder ([`build_brdf_as`]) serves both, so the two cannot
/// drift apart, and a grey spec builds, for `Vec3`, the same plugins with the
/// same scalar parameters on every channel.
pub trait RunTimeSpectrum: Spectrum + Send + Sync + sealed::Sealed + 'static {
    /// A monochrome Fresnel term (no Fresnel, Schlick, dielectric, a conductor
    /// of one `η`, `k`, F82) as a term of this spectrum: itself for `f32`,
    /// [`Achromatic`] for `Vec3`.
    type Achromatic<F: Fresnel<Spectrum = f32> + Send + Sync + 'static>: Fresnel<Spectrum = Self>
        + Send
        + Sync
        + 'static;
    /// Wraps a monochrome Fresnel term.
    fn achromatic<F: Fresnel<Spectrum = f32> + Send + Sync + 'static>(f: F) -> Self::Achromatic<F>;
    /// A linear RGB colour of a spec (channels in `[0, 1]`).
    fn colour(c: [f64; 3]) -> Self;
    /// The conductor of a named metal.
    fn metal(metal: Metal) -> Conductor<Self>;
    /// The MERL file at `path` (see [`crate::merl::load_tabulated`]).
    ///
    /// # Errors
    /// A message naming the file and what is wrong with it.
    fn tabulated(path: &str) -> Result<AnyBrdf<Self>, String>;
}

impl RunTimeSpectrum for f32 {
    type Achromatic<F: Fresnel<Spectrum = f32> + Send + Sync + 'static> = F;
    fn achromatic<F: Fresnel<Spectrum = f32> + Send + Sync + 'static>(f: F) -> F {
        f
    }
    fn colour(c: [f64; 3]) -> f32 {
        crate::brdf::luminance(c) as f32
    }
    fn metal(metal: Metal) -> Conductor<f32> {
        Conductor::metal_luminance(metal)
    }
    fn tabulated(path: &str) -> Result<AnyBrdf<f32>, String> {
        crate::merl::load_tabulated(path).map(boxed)
    }
}

impl RunTimeSpectrum for Vec3 {
    type Achromatic<F: Fresnel<Spectrum = f32> + Send + Sync + 'static> = Achromatic<F, Vec3>;
    fn achromatic<F: Fresnel<Spectrum = f32> + Send + Sync + 'static>(f: F) -> Achromatic<F, Vec3> {
        Achromatic::new(f)
    }
    fn colour(c: [f64; 3]) -> Vec3 {
        Vec3::new(c[0] as f32, c[1] as f32, c[2] as f32)
    }
    /// `Conductor::<Vec3>::metal`: per channel the `η`, `k` whose exact
    /// Fresnel reflectance equals the metal's measured spectral reflectance
    /// reduced to linear sRGB (CIE 1931 2°, D65, clamped to `[0, 1]`) at
    /// normal incidence and at 82°.
    fn metal(metal: Metal) -> Conductor<Vec3> {
        Conductor::metal(metal)
    }
    fn tabulated(path: &str) -> Result<AnyBrdf<Vec3>, String> {
        crate::merl::load_tabulated_rgb(path).map(boxed)
    }
}

/// The type-erased BRDF of `b`, [prepared](Brdf::with_prepared_albedo) first:
/// behind the box a layer or mixture can no longer prepare it, and a
/// dielectric leaf's albedo is what `coated(…)` reads at every `eval` (O(1),
/// the same values).
fn boxed<S: Spectrum, B: Brdf<Spectrum = S> + Send + Sync + 'static>(b: B) -> AnyBrdf<S> {
    AnyBrdf(Box::new(b.with_prepared_albedo()))
}

fn with_g<S, D, G>(d: D, f: FresnelSpec, ms: MultipleScattering) -> Result<AnyBrdf<S>, BrdfError>
where
    S: RunTimeSpectrum,
    D: MicrofacetDistribution + EnergyTable<G> + Send + Sync + 'static,
    G: ShadowingMasking + Send + Sync + 'static,
{
    fn mk<S, D, G, F>(d: D, f: F, ms: MultipleScattering) -> AnyBrdf<S>
    where
        S: RunTimeSpectrum,
        D: MicrofacetDistribution + EnergyTable<G> + Send + Sync + 'static,
        G: ShadowingMasking + Send + Sync + 'static,
        F: Fresnel<Spectrum = S> + Send + Sync + 'static,
    {
        match ms {
            MultipleScattering::Single => boxed(Microfacet::<D, G, F>::new(d, f)),
            MultipleScattering::KullaConty => boxed(KullaConty::<D, G, F>::new(d, f)),
        }
    }
    Ok(match f {
        FresnelSpec::None => mk::<S, D, G, _>(d, S::achromatic(NoFresnel), ms),
        FresnelSpec::Schlick { f0 } => mk::<S, D, G, _>(d, S::achromatic(Schlick::new(f0 as f32)?), ms),
        FresnelSpec::Dielectric { eta } => {
            mk::<S, D, G, _>(d, S::achromatic(Dielectric::new(eta as f32)?), ms)
        }
        FresnelSpec::Conductor { eta, k } => {
            mk::<S, D, G, _>(d, S::achromatic(Conductor::new(eta as f32, k as f32)?), ms)
        }
        FresnelSpec::Metal { metal } => mk::<S, D, G, _>(d, S::metal(metal), ms),
        FresnelSpec::F82 { f0, f82 } => {
            mk::<S, D, G, _>(d, S::achromatic(F82Tint::new(f0 as f32, f82 as f32)?), ms)
        }
    })
}

fn with_d<S, D>(d: D, g: G2Kind, f: FresnelSpec, ms: MultipleScattering) -> Result<AnyBrdf<S>, BrdfError>
where
    S: RunTimeSpectrum,
    D: MicrofacetDistribution
        + EnergyTable<HeightCorrelated>
        + EnergyTable<Separable>
        + Send
        + Sync
        + 'static,
{
    match g {
        G2Kind::HeightCorrelated => with_g::<S, D, HeightCorrelated>(d, f, ms),
        G2Kind::Separable => with_g::<S, D, Separable>(d, f, ms),
    }
}

/// The monochrome `OpenPbr` parameters and layering of an `openpbr(...)`
/// spec (each colour by its Rec. 709 luminance).
pub fn openpbr_params(p: &crate::brdf::OpenPbrSpec) -> (OpenPbrParams<f32>, Layering) {
    openpbr_params_as::<f32>(p)
}

/// The `OpenPbr` parameters and layering of an `openpbr(...)` spec in the
/// spectrum `S` (monochrome: each colour by its Rec. 709 luminance; RGB: the
/// colours as given).
pub fn openpbr_params_as<S: RunTimeSpectrum>(p: &crate::brdf::OpenPbrSpec) -> (OpenPbrParams<S>, Layering) {
    let c = S::colour;
    let layering = if p.reciprocal {
        Layering::Reciprocal
    } else {
        Layering::EnergyConserving
    };
    (
        OpenPbrParams {
            base_weight: p.base_weight as f32,
            base_color: c(p.base_color),
            base_metalness: p.base_metalness as f32,
            base_diffuse_roughness: p.base_diffuse_roughness as f32,
            specular_weight: p.specular_weight as f32,
            specular_color: c(p.specular_color),
            specular_roughness: p.specular_roughness as f32,
            specular_ior: p.specular_ior as f32,
            coat_weight: p.coat_weight as f32,
            coat_color: c(p.coat_color),
            coat_roughness: p.coat_roughness as f32,
            coat_ior: p.coat_ior as f32,
            coat_darkening: p.coat_darkening as f32,
            fuzz_weight: p.fuzz_weight as f32,
            fuzz_color: c(p.fuzz_color),
            fuzz_roughness: p.fuzz_roughness as f32,
        },
        layering,
    )
}

/// Builds the monochrome plugin BRDF for a parsed spec: each colour enters as
/// its Rec. 709 luminance, a named metal as the conductor fitted to the
/// luminance of its reflectance, a MERL file as the luminance of its
/// channels (the cheap path; for a grey spec, see [`BrdfSpec::is_grey`], it
/// is every channel of [`build_brdf_rgb`]). A constructor's [`BrdfError`] is
/// reported as a [`SpecError`] pointing at the parameter it names (or at the
/// whole spec).
pub fn build_brdf(text: &str, spec: &BrdfSpec) -> Result<AnyBrdf, SpecError> {
    build_brdf_as::<f32>(text, spec)
}

/// Builds the linear-RGB plugin BRDF for a parsed spec: colours keep their
/// channels, a named metal is evaluated per channel (its measured spectral
/// reflectance reduced to linear sRGB under D65 with the CIE 1931 2° observer,
/// see [`FresnelSpec::Metal`]), a MERL file keeps its three channels. The
/// same plugins as [`build_brdf`], in `Vec3`; a grey spec
/// ([`BrdfSpec::is_grey`]) gives the monochrome values on every channel.
///
/// ```
/// use radiometry::Brdf;
/// use radiometry::glam::Vec3;
/// use radiometry_spec::{model::build_brdf_rgb, parse_brdf};
/// let text = "ggx(alpha=0.3, fresnel=conductor(metal=Au))";
/// let gold = build_brdf_rgb(text, &parse_brdf(text)?)?;
/// let f = gold.eval(Vec3::new(0.5, 0.0, 0.866_025_4), Vec3::new(-0.5, 0.0, 0.866_025_4));
/// assert!(f.x > f.y && f.y > f.z); // gold: red above green above blue
/// # Ok::<(), radiometry_spec::SpecError>(())
/// ```
///
/// # Errors
/// As [`build_brdf`].
pub fn build_brdf_rgb(text: &str, spec: &BrdfSpec) -> Result<AnyBrdfRgb, SpecError> {
    build_brdf_as::<Vec3>(text, spec)
}

/// Builds the plugin BRDF for a parsed spec in the spectrum `S` (`f32`:
/// [`build_brdf`]; `Vec3`: [`build_brdf_rgb`]).
///
/// # Errors
/// A constructor's [`BrdfError`] as a [`SpecError`] pointing at the parameter
/// it names (or at the whole spec); an unreadable MERL file as a [`SpecError`]
/// on its path.
pub fn build_brdf_as<S: RunTimeSpectrum>(text: &str, spec: &BrdfSpec) -> Result<AnyBrdf<S>, SpecError> {
    let whole = |message: String| SpecError {
        spec: text.to_string(),
        start: 0,
        end: text.len(),
        message,
    };
    let c = S::colour;
    let r = match *spec {
        BrdfSpec::Sum(ref parts) => {
            let mut lobes = parts.iter().map(|p| build_brdf_as::<S>(text, p));
            let first = lobes.next().ok_or_else(|| whole("an empty sum".to_string()))??;
            return lobes.try_fold(first, |acc, b| Ok(boxed(Sum::new(acc, b?))));
        }
        BrdfSpec::Mix { weight, ref a, ref b } => {
            let (a, b) = (build_brdf_as::<S>(text, a)?, build_brdf_as::<S>(text, b)?);
            return Mix::new(weight as f32, a, b)
                .map(boxed)
                .map_err(|e| whole(e.to_string()));
        }
        BrdfSpec::Coated {
            ref top,
            ref base,
            coat_color,
            coat_ior,
            reciprocal,
        } => {
            let (top, base) = (build_brdf_as::<S>(text, top)?, build_brdf_as::<S>(text, base)?);
            let layering = if reciprocal {
                Layering::Reciprocal
            } else {
                Layering::EnergyConserving
            };
            if coat_color >= 1.0 {
                return Ok(boxed(Coated::new(top, base).with_layering(layering)));
            }
            return Coated::with_absorption(top, base, S::splat(coat_color as f32), coat_ior as f32)
                .map(|c| boxed(c.with_layering(layering)))
                .map_err(|e| whole(e.to_string()));
        }
        BrdfSpec::Tabulated { file: (start, end) } => {
            return S::tabulated(text.get(start..end).unwrap_or("")).map_err(|message| SpecError {
                spec: text.to_string(),
                start,
                end,
                message,
            });
        }
        BrdfSpec::Lambertian { albedo } => Lambertian::new(c(albedo)).map(boxed),
        BrdfSpec::Fon { rho, sigma } => Fon::new(c(rho), sigma as f32).map(boxed),
        BrdfSpec::Eon { rho, sigma } => Eon::new(c(rho), sigma as f32).map(boxed),
        BrdfSpec::OrenNayar { rho, sigma_rad } => OrenNayar::new(c(rho), sigma_rad as f32).map(boxed),
        BrdfSpec::Sheen { color, roughness } => Sheen::new(c(color), roughness as f32).map(boxed),
        BrdfSpec::LtcSheen { color, roughness } => LtcSheen::new(c(color), roughness as f32).map(boxed),
        BrdfSpec::OpenPbr(ref p) => {
            let (params, layering) = openpbr_params_as::<S>(p);
            OpenPbr::with_layering(params, layering).map(boxed)
        }
        BrdfSpec::Phong { exponent, ks, kd } => {
            ModifiedPhong::new(S::splat(kd as f32), S::splat(ks as f32), exponent as f32).map(boxed)
        }
        BrdfSpec::BlinnPhong { exponent, ks, kd } => {
            BlinnPhong::new(S::splat(kd as f32), S::splat(ks as f32), exponent as f32).map(boxed)
        }
        BrdfSpec::Microfacet {
            distribution,
            alpha,
            g,
            fresnel,
            ms,
            kd,
        } => match distribution {
            Distribution::Ggx => Ggx::new(alpha as f32).and_then(|d| with_d::<S, _>(d, g, fresnel, ms)),
            Distribution::Beckmann => {
                Beckmann::new(alpha as f32).and_then(|d| with_d::<S, _>(d, g, fresnel, ms))
            }
        }
        .and_then(|specular| {
            if kd > 0.0 {
                let diffuse = Lambertian::new(S::splat(kd as f32))?;
                Ok(boxed(with_diffuse::WithDiffuse::new(
                    diffuse, kd as f32, specular,
                )))
            } else {
                Ok(specular)
            }
        }),
    };
    r.map_err(|e| {
        let name = match e {
            BrdfError::NotFinite { name }
            | BrdfError::OutOfRange { name, .. }
            | BrdfError::EnergyGain { name, .. } => Some(name),
            _ => None,
        };
        let (start, end) = name.and_then(|n| find_param(text, n)).unwrap_or((0, text.len()));
        SpecError {
            spec: text.to_string(),
            start,
            end,
            message: e.to_string(),
        }
    })
}

/// Span of the value of `name=` in `text`, if present.
fn find_param(text: &str, name: &str) -> Option<(usize, usize)> {
    let b = text.as_bytes();
    let mut from = 0;
    while let Some(p) = text[from..].find(name) {
        let s = from + p;
        let before_ok = s == 0 || !(b[s - 1].is_ascii_alphanumeric() || b[s - 1] == b'_' || b[s - 1] == b'-');
        let mut e = s + name.len();
        while e < b.len() && b[e] == b' ' {
            e += 1;
        }
        if before_ok && e < b.len() && b[e] == b'=' {
            let mut v = e + 1;
            while v < b.len() && b[v] == b' ' {
                v += 1;
            }
            let mut w = v;
            while w < b.len() && !matches!(b[w], b',' | b')' | b' ') {
                w += 1;
            }
            return Some((v, w.max(v + 1).min(b.len())));
        }
        from = s + name.len();
    }
    None
}

/// Every integrator the CLI offers, by its report name.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AnyIntegrator {
    /// Gauss–Legendre product rule in (cos θ, φ).
    GaussLegendre(GaussLegendre),
    /// Gauss–Legendre on the sampling-map square.
    Warped(WarpedGaussLegendre),
    /// Adaptive cubature (plain or warped).
    Adaptive(Adaptive),
    /// Monte Carlo / randomized QMC.
    MonteCarlo(MonteCarlo),
    /// The integrator that picks its own parameterisation.
    Auto(Auto),
}

impl Integrator for AnyIntegrator {
    fn integrate<I: Integrand>(&self, g: &I, budget: u32) -> Result<Estimate<WideOf<I>>, IntegrateError> {
        match self {
            AnyIntegrator::GaussLegendre(i) => i.integrate(g, budget),
            AnyIntegrator::Warped(i) => i.integrate(g, budget),
            AnyIntegrator::Adaptive(i) => i.integrate(g, budget),
            AnyIntegrator::MonteCarlo(i) => i.integrate(g, budget),
            AnyIntegrator::Auto(i) => i.integrate(g, budget),
        }
    }
    fn max_evaluations(&self) -> Option<u64> {
        match self {
            AnyIntegrator::GaussLegendre(i) => i.max_evaluations(),
            AnyIntegrator::Warped(i) => i.max_evaluations(),
            AnyIntegrator::Adaptive(i) => i.max_evaluations(),
            AnyIntegrator::MonteCarlo(i) => i.max_evaluations(),
            AnyIntegrator::Auto(i) => i.max_evaluations(),
        }
    }
    fn error_decay(&self) -> Option<f64> {
        match self {
            AnyIntegrator::GaussLegendre(i) => i.error_decay(),
            AnyIntegrator::Warped(i) => i.error_decay(),
            AnyIntegrator::Adaptive(i) => i.error_decay(),
            AnyIntegrator::MonteCarlo(i) => i.error_decay(),
            AnyIntegrator::Auto(i) => i.error_decay(),
        }
    }
    fn to_tolerance<I: Integrand>(
        &self,
        g: &I,
        tol: f64,
        start_budget: u32,
        max_budget: u32,
    ) -> Result<ToleranceOutcome<WideOf<I>>, IntegrateError> {
        match self {
            AnyIntegrator::GaussLegendre(i) => i.to_tolerance(g, tol, start_budget, max_budget),
            AnyIntegrator::Warped(i) => i.to_tolerance(g, tol, start_budget, max_budget),
            AnyIntegrator::Adaptive(i) => i.to_tolerance(g, tol, start_budget, max_budget),
            AnyIntegrator::MonteCarlo(i) => i.to_tolerance(g, tol, start_budget, max_budget),
            AnyIntegrator::Auto(i) => i.to_tolerance(g, tol, start_budget, max_budget),
        }
    }
    fn name(&self) -> &'static str {
        match self {
            AnyIntegrator::GaussLegendre(i) => i.name(),
            AnyIntegrator::Warped(i) => i.name(),
            AnyIntegrator::Adaptive(i) => i.name(),
            AnyIntegrator::MonteCarlo(i) => i.name(),
            AnyIntegrator::Auto(i) => i.name(),
        }
    }
}

impl AnyIntegrator {
    /// Whether the integrator is deterministic quadrature (no random points).
    pub fn is_deterministic(&self) -> bool {
        !matches!(self, AnyIntegrator::MonteCarlo(_))
    }
}

/// Default seed of the Monte Carlo integrators.
pub const DEFAULT_SEED: u64 = 0x5EED;

/// All integrators, deterministic ones first. `abs_tol` configures the
/// adaptive rules (`0`: refine until the budget is spent).
pub fn all_integrators(seed: u64, abs_tol: f64) -> Vec<AnyIntegrator> {
    let adaptive = Adaptive::new(0.0, abs_tol).unwrap_or_else(|_| Adaptive::new(0.0, 0.0).expect("valid"));
    let mut v = vec![
        AnyIntegrator::GaussLegendre(GaussLegendre::new()),
        AnyIntegrator::Warped(WarpedGaussLegendre::new()),
        AnyIntegrator::Warped(WarpedGaussLegendre::horizon_split()),
        AnyIntegrator::Adaptive(adaptive),
        AnyIntegrator::Adaptive(adaptive.warped()),
        AnyIntegrator::Auto(Auto::new()),
    ];
    for s in [
        Strategy::Uniform,
        Strategy::Cosine,
        Strategy::Integrand,
        Strategy::Mis(Heuristic::Balance),
        Strategy::Mis(Heuristic::Power),
    ] {
        for p in PointSet::ALL {
            v.push(AnyIntegrator::MonteCarlo(MonteCarlo::new(s, p, seed)));
        }
    }
    v
}

/// The integrator called `name` (see [`all_integrators`]).
pub fn integrator_by_name(name: &str, seed: u64, abs_tol: f64) -> Option<AnyIntegrator> {
    all_integrators(seed, abs_tol)
        .into_iter()
        .find(|i| i.name() == name)
}

/// Irradiance on a surface with normal +Z from one light, by the closed forms
/// of `radiometry::radiometric` (sky: πL; directional: E⊥ max(0, cos θ);
/// cap: L Ω⊥ with the horizon-clipped projected solid angle).
pub fn irradiance_of(l: &LightSpec) -> (&'static str, f32) {
    use radiometry::radiometric::{cap_irradiance, directional_irradiance, sky_irradiance};
    match *l {
        LightSpec::Sky { radiance } => ("sky", sky_irradiance(radiance as f32)),
        LightSpec::Directional {
            theta, irradiance, ..
        } => (
            "directional",
            directional_irradiance(irradiance as f32, theta.to_radians().cos() as f32),
        ),
        LightSpec::Cap {
            axis_theta,
            half_angle,
            radiance,
            ..
        } => (
            "cap",
            cap_irradiance(
                radiance as f32,
                axis_theta.to_radians().cos() as f32,
                half_angle.to_radians() as f32,
            ),
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parse_brdf;

    #[test]
    fn integrator_names_are_unique() {
        let all = all_integrators(1, 0.0);
        let mut names: Vec<_> = all.iter().map(|i| i.name()).collect();
        names.sort();
        names.dedup();
        assert_eq!(names.len(), all.len());
        assert!(integrator_by_name("gauss-legendre-warped", 1, 0.0).is_some());
        assert!(integrator_by_name("nope", 1, 0.0).is_none());
    }

    #[test]
    fn metal_and_f82_specs_build_the_plugins() {
        let build = |t: &str| build_brdf(t, &parse_brdf(t).unwrap()).unwrap();
        let (wi, wo) = (
            Vec3::new(0.3, 0.1, 0.948_683_3),
            Vec3::new(-0.5, 0.0, 0.866_025_4),
        );
        // A white tint is Schlick's approximation.
        let f82 = build("ggx(alpha=0.3, fresnel=f82(f0=0.6, f82=1))").eval(wi, wo);
        let schlick = build("ggx(alpha=0.3, fresnel=schlick(f0=0.6))").eval(wi, wo);
        assert!((f82 - schlick).abs() <= 1e-6 * schlick, "{f82} vs {schlick}");
        // Gold is the monochrome conductor fitted to the luminance of its reflectance.
        let gold = build("ggx(alpha=0.3, fresnel=conductor(metal=au))");
        let c = Conductor::metal_luminance(radiometry_brdfs::metals::Metal::Au);
        let direct = Microfacet::<Ggx, HeightCorrelated, _>::new(Ggx::new(0.3).unwrap(), c);
        assert_eq!(gold.eval(wi, wo), direct.eval(wi, wo));
        assert!(
            build("beckmann(alpha=0.5, fresnel=conductor(metal=Brass), ms=kulla-conty)").eval(wi, wo) > 0.0
        );
    }

    #[test]
    fn plugin_constructor_errors_point_at_the_parameter() {
        // The parser accepts η > 0; the plugin requires η ≥ MIN_ETA = 1e-3.
        let text = "ggx(alpha=0.1, fresnel=dielectric(eta=0.0001))";
        let e = build_brdf(text, &parse_brdf(text).unwrap())
            .err()
            .expect("plugin rejects η = 1e-4");
        assert_eq!(&text[e.start..e.end], "0.0001", "{e}");
        assert_eq!(find_param("phong(exponent=5, ks=0.5)", "ks"), Some((21, 24)));
        // The classic Oren–Nayar's energy bound, reached through a spec built by hand.
        let text = "oren-nayar(rho=1, sigma_rad=0.2)";
        let spec = BrdfSpec::OrenNayar {
            rho: [1.0; 3],
            sigma_rad: 0.2,
        };
        let e = build_brdf(text, &spec).err().expect("energy gain rejected");
        assert_eq!(&text[e.start..e.end], "1", "{e}");
    }

    /// `ltc-sheen(...)` builds `LtcSheen`: the same values as the plugin, its closed-form albedo.
    #[test]
    fn ltc_sheen_spec_builds() {
        let text = "ltc-sheen(color=0.5, roughness=0.3)";
        let b = build_brdf(text, &parse_brdf(text).unwrap()).unwrap();
        let direct = LtcSheen::new(0.5f32, 0.3).unwrap();
        let (wi, wo) = (Vec3::new(-0.6, 0.0, 0.8), Vec3::new(0.8, 0.0, 0.6));
        assert_eq!(b.eval(wi, wo), direct.eval(wi, wo));
        assert_eq!(b.directional_albedo(wo), direct.directional_albedo(wo));
        assert!(b.directional_albedo(wo).is_bound);
    }

    /// The rough diffuse specs build the plugins: EON's white furnace through
    /// the run-time BRDF, FON below it, the classic model with σ in radians.
    #[test]
    fn rough_diffuse_specs_build() {
        let wo = Vec3::new(0.8, 0.0, 0.6);
        let albedo = |text: &str| {
            let b = build_brdf(text, &parse_brdf(text).unwrap()).unwrap();
            let a = b.directional_albedo(wo);
            // The microfacet plugins' albedo is still the sampled estimate: only closed forms are bounds.
            assert!(
                a.is_bound || text.starts_with("coated") || text.starts_with("openpbr"),
                "{text}"
            );
            a.value
        };
        assert!((albedo("eon(rho=1, sigma=0.5)") - 1.0).abs() < 2e-6);
        assert!(albedo("fon(rho=1, sigma=1)") < 0.9);
        let on = albedo("oren-nayar(rho=0.5, sigma_rad=0.35)");
        assert!(on > 0.45 && on < 0.5, "{on}");
        assert_eq!(albedo("eon(rho=0.7, sigma=0)"), albedo("fon(rho=0.7, sigma=0)"));
        // In compositions: a plastic over EON, and a sum.
        let plastic = albedo("coated(ggx(alpha=0.1, fresnel=dielectric(eta=1.5)), eon(rho=1, sigma=0.5))");
        assert!(plastic > 0.5 && plastic <= 1.0, "{plastic}");
        // OpenPBR's defaults: a white-ish dielectric, albedo below 1; an rgb colour enters as its luminance.
        let d = albedo("openpbr");
        assert!(d > 0.5 && d < 1.0, "{d}");
        assert_eq!(albedo("openpbr(base_color=rgb(0.8, 0.8, 0.8))"), d);
        let red = albedo("openpbr(base_color=rgb(1, 0, 0))");
        let lum = albedo("openpbr(base_color=0.2126)");
        assert_eq!(red, lum);
        let sum = albedo("eon(rho=0.5, sigma=1) + lambertian(albedo=0.25)");
        let eon = albedo("eon(rho=0.5, sigma=1)");
        assert!(eon < 0.5 && (sum - (eon + 0.25)).abs() < 1e-6, "{sum} {eon}");
    }
}
