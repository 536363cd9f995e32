//! Turning parsed specs into plugin BRDFs, integrators and light irradiances.
//!
//! The plugins are generic (`Microfacet<D, G, F>`), so every front end (the
//! CLI, the Python module, a renderer that picks its BRDF at run time)
//! erases their types behind [`AnyBrdf`] (a boxed trait object; one virtual call per
//! evaluation, or per batch through the batch methods the integrators use) and picks integrators through [`AnyIntegrator`] (an enum,
//! statically dispatched per variant).

mod with_diffuse;

use crate::{BrdfSpec, Distribution, FresnelSpec, G2Kind, LightSpec, MultipleScattering, SpecError};
use radiometry::BrdfSample;
use radiometry::compose::{Coated, Layering, Mix, Sum};
use radiometry::glam::Vec3;
use radiometry::integrator::{
    Adaptive, Auto, Estimate, GaussLegendre, Heuristic, Integrand, IntegrateError, Integrator, MonteCarlo,
    PointSet, Strategy, ToleranceOutcome, WarpedGaussLegendre, WideOf,
};
use radiometry::{Albedo, Brdf};
use radiometry_brdfs::{
    Beckmann, BlinnPhong, BrdfError, Conductor, Dielectric, Eon, F82Tint, Fon, Fresnel, Ggx,
    HeightCorrelated, KullaConty, Lambertian, LtcSheen, Microfacet, MicrofacetDistribution, ModifiedPhong,
    NoFresnel, OpenPbr, OpenPbrParams, OrenNayar, Schlick, Separable, ShadowingMasking, Sheen,
    microfacet::EnergyTable,
};

/// Object-safe view of a monochrome BRDF.
pub trait DynBrdf: Send + Sync {
    /// See [`Brdf::eval`].
    fn eval_dyn(&self, wi: Vec3, wo: Vec3) -> f32;
    /// See [`Brdf::sample`].
    fn sample_dyn(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<f32>>;
    /// See [`Brdf::pdf`].
    fn pdf_dyn(&self, wi: Vec3, wo: Vec3) -> f32;
    /// See [`Brdf::eval_batch`] (one virtual call per batch, so the
    /// plugin's vector kernel runs).
    fn eval_batch_dyn(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]);
    /// See [`Brdf::pdf_batch`].
    fn pdf_batch_dyn(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]);
    /// See [`Brdf::sample_batch`].
    fn sample_batch_dyn(&self, wo: &[Vec3], u: &[[f32; 2]], out: &mut [Option<BrdfSample<f32>>]);
    /// See [`Brdf::is_smooth`].
    fn is_smooth_dyn(&self) -> bool;
    /// See [`Brdf::sampling_components`].
    fn sampling_components_dyn(&self) -> usize;
    /// See [`Brdf::component_weight`].
    fn component_weight_dyn(&self, wo: Vec3, k: usize) -> f32;
    /// See [`Brdf::sample_component`].
    fn sample_component_dyn(&self, wo: Vec3, k: usize, u: [f32; 2]) -> Option<Vec3>;
    /// See [`Brdf::directional_albedo`].
    fn directional_albedo_dyn(&self, wo: Vec3) -> Albedo<f32>;
}

impl<B: Brdf<Spectrum = f32> + Send + Sync> DynBrdf for B {
    fn eval_dyn(&self, wi: Vec3, wo: Vec3) -> f32 {
        self.eval(wi, wo)
    }
    fn sample_dyn(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<f32>> {
        self.sample(wo, u)
    }
    fn pdf_dyn(&self, wi: Vec3, wo: Vec3) -> f32 {
        self.pdf(wi, wo)
    }
    fn eval_batch_dyn(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]) {
        self.eval_batch(wi, wo, out)
    }
    fn pdf_batch_dyn(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]) {
        self.pdf_batch(wi, wo, out)
    }
    fn sample_batch_dyn(&self, wo: &[Vec3], u: &[[f32; 2]], out: &mut [Option<BrdfSample<f32>>]) {
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
    fn directional_albedo_dyn(&self, wo: Vec3) -> Albedo<f32> {
        self.directional_albedo(wo)
    }
}

/// A type-erased plugin BRDF.
pub struct AnyBrdf(Box<dyn DynBrdf>);

impl Brdf for AnyBrdf {
    type Spectrum = f32;
    #[inline]
    fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
        self.0.eval_dyn(wi, wo)
    }
    #[inline]
    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<f32>> {
        self.0.sample_dyn(wo, u)
    }
    #[inline]
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        self.0.pdf_dyn(wi, wo)
    }
    #[inline]
    fn eval_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]) {
        self.0.eval_batch_dyn(wi, wo, out)
    }
    #[inline]
    fn pdf_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]) {
        self.0.pdf_batch_dyn(wi, wo, out)
    }
    #[inline]
    fn sample_batch(&self, wo: &[Vec3], u: &[[f32; 2]], out: &mut [Option<BrdfSample<f32>>]) {
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
    fn directional_albedo(&self, wo: Vec3) -> Albedo<f32> {
        self.0.directional_albedo_dyn(wo)
    }
}

fn boxed<B: Brdf<Spectrum = f32> + Send + Sync + 'static>(b: B) -> AnyBrdf {
    AnyBrdf(Box::new(b))
}

fn with_g<D, G>(d: D, f: FresnelSpec, ms: MultipleScattering) -> Result<AnyBrdf, BrdfError>
where
    D: MicrofacetDistribution + EnergyTable<G> + Send + Sync + 'static,
    G: ShadowingMasking + Send + Sync + 'static,
{
    fn mk<D, G, F>(d: D, f: F, ms: MultipleScattering) -> AnyBrdf
    where
        D: MicrofacetDistribution + EnergyTable<G> + Send + Sync + 'static,
        G: ShadowingMasking + Send + Sync + 'static,
        F: Fresnel<Spectrum = f32> + Send + Sync + 'static,
    {
        match ms {
            MultipleScattering::Single => boxed(Microfacet::<D, G, F>::new(d, f)),
            MultipleScattering::KullaConty => boxed(KullaConty::<D, G, F>::new(d, f)),
        }
    }
    Ok(match f {
        FresnelSpec::None => mk::<D, G, _>(d, NoFresnel, ms),
        FresnelSpec::Schlick { f0 } => mk::<D, G, _>(d, Schlick::new(f0 as f32)?, ms),
        FresnelSpec::Dielectric { eta } => mk::<D, G, _>(d, Dielectric::new(eta as f32)?, ms),
        FresnelSpec::Conductor { eta, k } => mk::<D, G, _>(d, Conductor::new(eta as f32, k as f32)?, ms),
        FresnelSpec::Metal { metal } => mk::<D, G, _>(d, Conductor::metal_luminance(metal), ms),
        FresnelSpec::F82 { f0, f82 } => mk::<D, G, _>(d, F82Tint::new(f0 as f32, f82 as f32)?, ms),
    })
}

fn with_d<D>(d: D, g: G2Kind, f: FresnelSpec, ms: MultipleScattering) -> Result<AnyBrdf, BrdfError>
where
    D: MicrofacetDistribution
        + EnergyTable<HeightCorrelated>
        + EnergyTable<Separable>
        + Send
        + Sync
        + 'static,
{
    match g {
        G2Kind::HeightCorrelated => with_g::<D, HeightCorrelated>(d, f, ms),
        G2Kind::Separable => with_g::<D, Separable>(d, f, ms),
    }
}

/// The monochrome `OpenPbr` parameters and layering of an `openpbr(...)`
/// spec (each colour by its Rec. 709 luminance).
pub fn openpbr_params(p: &crate::brdf::OpenPbrSpec) -> (OpenPbrParams<f32>, Layering) {
    let c = |v: [f64; 3]| crate::brdf::luminance(v) as f32;
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

/// Builds the plugin BRDF for a parsed spec. A constructor's [`BrdfError`]
/// is reported as a [`SpecError`] pointing at the parameter it names (or at
/// the whole spec).
pub fn build_brdf(text: &str, spec: &BrdfSpec) -> Result<AnyBrdf, SpecError> {
    let whole = |message: String| SpecError {
        spec: text.to_string(),
        start: 0,
        end: text.len(),
        message,
    };
    let r = match *spec {
        BrdfSpec::Sum(ref parts) => {
            let mut lobes = parts.iter().map(|p| build_brdf(text, p));
            let first = lobes.next().ok_or_else(|| whole("an empty sum".to_string()))??;
            return lobes.try_fold(first, |acc, b| Ok(boxed(Sum::new(acc, b?))));
        }
        BrdfSpec::Mix { weight, ref a, ref b } => {
            let (a, b) = (build_brdf(text, a)?, build_brdf(text, b)?);
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
            let (top, base) = (build_brdf(text, top)?, build_brdf(text, base)?);
            let layering = if reciprocal {
                Layering::Reciprocal
            } else {
                Layering::EnergyConserving
            };
            if coat_color >= 1.0 {
                return Ok(boxed(Coated::new(top, base).with_layering(layering)));
            }
            return Coated::with_absorption(top, base, coat_color as f32, coat_ior as f32)
                .map(|c| boxed(c.with_layering(layering)))
                .map_err(|e| whole(e.to_string()));
        }
        BrdfSpec::Tabulated { file: (start, end) } => {
            return crate::merl::load_tabulated(text.get(start..end).unwrap_or(""))
                .map(boxed)
                .map_err(|message| SpecError {
                    spec: text.to_string(),
                    start,
                    end,
                    message,
                });
        }
        BrdfSpec::Lambertian { albedo } => Lambertian::new(albedo as f32).map(boxed),
        BrdfSpec::Fon { rho, sigma } => Fon::new(rho as f32, sigma as f32).map(boxed),
        BrdfSpec::Eon { rho, sigma } => Eon::new(rho as f32, sigma as f32).map(boxed),
        BrdfSpec::OrenNayar { rho, sigma_rad } => OrenNayar::new(rho as f32, sigma_rad as f32).map(boxed),
        BrdfSpec::Sheen { color, roughness } => Sheen::new(color as f32, roughness as f32).map(boxed),
        BrdfSpec::LtcSheen { color, roughness } => LtcSheen::new(color as f32, roughness as f32).map(boxed),
        BrdfSpec::OpenPbr(ref p) => {
            let (params, layering) = openpbr_params(p);
            OpenPbr::with_layering(params, layering).map(boxed)
        }
        BrdfSpec::Phong { exponent, ks, kd } => {
            ModifiedPhong::new(kd as f32, ks as f32, exponent as f32).map(boxed)
        }
        BrdfSpec::BlinnPhong { exponent, ks, kd } => {
            BlinnPhong::new(kd as f32, ks as f32, exponent as f32).map(boxed)
        }
        BrdfSpec::Microfacet {
            distribution,
            alpha,
            g,
            fresnel,
            ms,
            kd,
        } => match distribution {
            Distribution::Ggx => Ggx::new(alpha as f32).and_then(|d| with_d(d, g, fresnel, ms)),
            Distribution::Beckmann => Beckmann::new(alpha as f32).and_then(|d| with_d(d, g, fresnel, ms)),
        }
        .and_then(|specular| {
            if kd > 0.0 {
                let diffuse = Lambertian::new(kd as f32)?;
                Ok(boxed(with_diffuse::WithDiffuse::new(diffuse, specular)))
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
            rho: 1.0,
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
