//! Every plugin configuration of `radiometry-brdfs` (monochrome `f32` spectra), behind one trait object,
//! with a proptest strategy for valid parameters and the angular width of each lobe (for quadrature
//! breakpoints and χ² grids).

use super::strategies::{alpha, exponent, kd_ks, log_uniform};
use proptest::prelude::*;
use radiometry::IsotropicBrdf;
use radiometry_brdfs::{
    Beckmann, BlinnPhong, BrdfError, Conductor, Dielectric, Eon, F82Tint, Fon, Ggx, HeightCorrelated,
    KullaConty, Lambertian, Microfacet, ModifiedPhong, NoFresnel, OrenNayar, Schlick, Separable, Sheen,
};

/// A plugin behind a trait object.
pub type Dyn = Box<dyn IsotropicBrdf<Spectrum = f32>>;

/// Normal distribution.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dist {
    /// GGX / Trowbridge–Reitz.
    Ggx,
    /// Beckmann.
    Beckmann,
}

/// Shadowing–masking.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shadow {
    /// Height-correlated Smith G2.
    HeightCorrelated,
    /// Separable Smith G2.
    Separable,
}

/// Fresnel term.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Fres {
    /// F = 1.
    None,
    /// Schlick.
    Schlick,
    /// Exact dielectric.
    Dielectric,
    /// Exact conductor.
    Conductor,
    /// F82-tint metal Fresnel (OpenPBR), `f0` and tint `f82` of [`Params`].
    F82,
}

/// A plugin configuration.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// `Lambertian`.
    Lambertian,
    /// `ModifiedPhong`.
    ModifiedPhong,
    /// `BlinnPhong`.
    BlinnPhong,
    /// `Microfacet<D, G, F>`.
    Micro(Dist, Shadow, Fres),
    /// `KullaConty<D, G, F>` (multiple-scattering compensation).
    KullaConty(Dist, Shadow, Fres),
    /// `Tabulated` over a fixed table (parameters unused).
    Tabulated(Table),
    /// `Fon` (Fujii's Oren–Nayar, σ ∈ [0, 1]).
    Fon,
    /// `Eon` (energy-preserving Oren–Nayar, σ ∈ [0, 1]).
    Eon,
    /// `OrenNayar` (classic, pbrt-v3) with `σ_rad = σ · π/2` and ρ capped at `OrenNayar::max_rho`.
    OrenNayar,
    /// `Sheen` (Estevez & Kulla 2017): colour `rho`, roughness `r = r_min + (1 − r_min) α` (so the
    /// strategy's `α ∈ [10⁻⁴, 1]` reaches both ends of `[r_min, 1]`).
    Sheen,
    /// A composite of plugins (`radiometry::compose`).
    Composite(Comp),
}

/// The composites of [`Kind::Composite`], built from the parameters of their parts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Comp {
    /// `Coated<GGX dielectric (α, η), Lambertian(ρ)>`: a plastic.
    Plastic,
    /// `Sum<Lambertian(kd), Scaled<GGX (α, F = 1), ks>>` with `kd + ks ≤ 1`.
    SumDiffuseSpecular,
    /// `Mix<Kulla–Conty GGX conductor (α, η, k), Lambertian(ρ)>` with weight `f0`.
    MixMetalDiffuse,
    /// `Coated<Beckmann dielectric (α, η), GGX conductor>` with coat colour `ρ` (absorbing): a coated metal.
    CoatedMetal,
    /// `OpenPbr` with every layer on: see [`openpbr_params`].
    OpenPbr,
    /// `Plastic` in the default, energy-conserving layering (not reciprocal).
    PlasticEnergy,
    /// `OpenPbr` in the default, energy-conserving layering (not reciprocal).
    OpenPbrEnergy,
}

impl Kind {
    /// Whether the kind promises reciprocity (every plugin and the
    /// reciprocal layerings; not the energy-conserving layerings, which pass
    /// `1 − E(ωo)` of the light to the base, nor the LTC sheen).
    pub fn reciprocal(self) -> bool {
        !matches!(self, Kind::Composite(Comp::PlasticEnergy | Comp::OpenPbrEnergy))
    }
}

/// The composite configurations in [`all_kinds`].
pub const COMPOSITE_KINDS: [Kind; 7] = [
    Kind::Composite(Comp::Plastic),
    Kind::Composite(Comp::SumDiffuseSpecular),
    Kind::Composite(Comp::MixMetalDiffuse),
    Kind::Composite(Comp::CoatedMetal),
    Kind::Composite(Comp::OpenPbr),
    Kind::Composite(Comp::PlasticEnergy),
    Kind::Composite(Comp::OpenPbrEnergy),
];

/// The OpenPBR parameters of `Comp::OpenPbr` from a parameter set: base colour ρ, metalness `f0`,
/// diffuse roughness σ, specular and coat roughness `√α`, specular colour (the metal's F82 tint) `f82`,
/// specular IOR `max(η, 1)`, coat weight `kd`, coat colour `1 − ks/2`, coat IOR `1 + η/2`, fuzz weight
/// `ks` with colour ρ and roughness `√α`.
pub fn openpbr_params(p: &Params) -> radiometry_brdfs::OpenPbrParams<f32> {
    let r = p.alpha.sqrt();
    radiometry_brdfs::OpenPbrParams {
        base_color: p.rho,
        base_metalness: p.f0,
        base_diffuse_roughness: p.sigma,
        specular_color: p.f82,
        specular_roughness: r,
        specular_ior: p.eta_d.max(1.0),
        coat_weight: p.kd,
        coat_color: 1.0 - 0.5 * p.ks,
        coat_roughness: r,
        coat_ior: 1.0 + 0.5 * p.eta_d,
        fuzz_weight: p.ks,
        fuzz_color: p.rho,
        fuzz_roughness: r,
        ..Default::default()
    }
}

/// The top lobe of a coated composite (`None` for other kinds): its albedo error at `ωo` bounds how much
/// the layer can exceed an albedo of 1 (`radiometry::compose::Coated`).
pub fn coat_top(k: Kind, p: &Params) -> Option<Dyn> {
    Some(match k {
        Kind::Composite(Comp::Plastic | Comp::PlasticEnergy) => {
            Box::new(Microfacet::<_, HeightCorrelated, _>::new(
                Ggx::new(p.alpha).ok()?,
                Dielectric::new(p.eta_d).ok()?,
            ))
        }
        Kind::Composite(Comp::CoatedMetal) => Box::new(Microfacet::<_, HeightCorrelated, _>::new(
            Beckmann::new(p.alpha).ok()?,
            Dielectric::new(p.eta_d).ok()?,
        )),
        // Three tops (the specular layer, the coat, the fuzz): their errors add up (a `Sum`'s albedo
        // error is the sum of its lobes'), each through the layering below it.
        Kind::Composite(Comp::OpenPbr | Comp::OpenPbrEnergy) => {
            use radiometry::compose::Sum;
            let o = openpbr_params(p);
            let alpha = (o.specular_roughness * o.specular_roughness).max(1e-4);
            let eta = o.specular_ior / (1.0 + o.coat_weight * (o.coat_ior - 1.0));
            let eta = radiometry_brdfs::openpbr::modulated_ior(eta, o.specular_weight);
            let specular =
                Microfacet::<_, HeightCorrelated, _>::new(Ggx::new(alpha).ok()?, Dielectric::new(eta).ok()?);
            let coat = Microfacet::<_, HeightCorrelated, _>::new(
                Ggx::new(alpha).ok()?,
                Dielectric::new(o.coat_ior).ok()?,
            );
            let fuzz = Sheen::new(
                o.fuzz_color,
                o.fuzz_roughness.max(radiometry_brdfs::sheen::MIN_SHEEN_ROUGHNESS),
            )
            .ok()?;
            Box::new(Sum::new(specular, Sum::new(coat, fuzz)))
        }
        _ => return None,
    })
}

fn composite(c: Comp, p: &Params) -> Result<Dyn, BrdfError> {
    use radiometry::compose::{Coated, Mix, Scaled, Sum};
    let ggx = Ggx::new(p.alpha)?;
    let conductor = Conductor::new(p.eta_c, p.k_c)?;
    let unwrap =
        |e: radiometry::compose::ComposeError| -> BrdfError { panic!("valid composite parameters: {e}") };
    use radiometry::compose::Layering;
    Ok(match c {
        Comp::Plastic => Box::new(
            Coated::new(
                Microfacet::<_, HeightCorrelated, _>::new(ggx, Dielectric::new(p.eta_d)?),
                Lambertian::new(p.rho)?,
            )
            .with_layering(Layering::Reciprocal),
        ),
        Comp::PlasticEnergy => Box::new(Coated::new(
            Microfacet::<_, HeightCorrelated, _>::new(ggx, Dielectric::new(p.eta_d)?),
            Lambertian::new(p.rho)?,
        )),
        Comp::SumDiffuseSpecular => Box::new(Sum::new(
            Lambertian::new(p.kd)?,
            Scaled::new(Microfacet::<_, HeightCorrelated, _>::new(ggx, NoFresnel), p.ks).map_err(unwrap)?,
        )),
        Comp::MixMetalDiffuse => Box::new(
            Mix::new(
                p.f0,
                KullaConty::<_, HeightCorrelated, _>::new(ggx, conductor),
                Lambertian::new(p.rho)?,
            )
            .map_err(unwrap)?,
        ),
        Comp::OpenPbr => Box::new(radiometry_brdfs::OpenPbr::with_layering(
            openpbr_params(p),
            Layering::Reciprocal,
        )?),
        Comp::OpenPbrEnergy => Box::new(radiometry_brdfs::OpenPbr::new(openpbr_params(p))?),
        Comp::CoatedMetal => Box::new(
            Coated::with_absorption(
                Microfacet::<_, HeightCorrelated, _>::new(Beckmann::new(p.alpha)?, Dielectric::new(p.eta_d)?),
                Microfacet::<_, HeightCorrelated, _>::new(ggx, conductor),
                p.rho,
                p.eta_d.max(1.0),
            )
            .map_err(unwrap)?
            .with_layering(Layering::Reciprocal),
        ),
    })
}

/// The fixed tables of the `Tabulated` configurations.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Table {
    /// GGX α = 0.3, F = 1, height-correlated, on the MERL grid (the test case).
    GgxMerl,
    /// `0.5/π + 0.5 · GGX(α = 0.1)` on a coarse 32 × 32 × 16 grid (a diffuse base under a sharp peak, and a
    /// non-MERL resolution).
    DiffuseGgxCoarse,
}

/// The `Tabulated` configurations in [`all_kinds`].
pub const TABULATED_KINDS: [Kind; 2] = [
    Kind::Tabulated(Table::GgxMerl),
    Kind::Tabulated(Table::DiffuseGgxCoarse),
];

/// The plugin over a fixed table, with half-vector sampling; tables and sampling buffers are built
/// once per test binary and leaked (`'static` borrows).
fn tabulated(t: Table) -> radiometry_brdfs::tabulated::Tabulated<'static, f32> {
    use radiometry::Brdf;
    use radiometry_brdfs::tabulated::{RusinkiewiczGrid, Tabulated};
    use std::sync::OnceLock;
    static TABLES: [OnceLock<Tabulated<'static, f32>>; 2] = [OnceLock::new(), OnceLock::new()];
    let make = |grid: RusinkiewiczGrid, f: &dyn Fn(radiometry::glam::Vec3, radiometry::glam::Vec3) -> f32| {
        let mut v = vec![0.0f32; grid.len()];
        let [nh, nd, np] = grid.dims();
        for i in 0..nh {
            for j in 0..nd {
                for k in 0..np {
                    let (wi, wo) = grid.node_directions(i, j, k);
                    v[grid.index(i, j, k)] = f(wi, wo);
                }
            }
        }
        let values: &'static [f32] = Vec::leak(v);
        let buf = Vec::leak(vec![0.0f32; Tabulated::<f32>::sampling_buffer_len(&grid)]);
        Tabulated::new(grid, values).unwrap().with_sampling(buf).unwrap()
    };
    match t {
        Table::GgxMerl => *TABLES[0].get_or_init(|| {
            let g = Microfacet::<Ggx, HeightCorrelated, NoFresnel>::new(Ggx::new(0.3).unwrap(), NoFresnel);
            make(RusinkiewiczGrid::MERL, &|wi, wo| g.eval(wi, wo))
        }),
        Table::DiffuseGgxCoarse => *TABLES[1].get_or_init(|| {
            let g = Microfacet::<Ggx, HeightCorrelated, NoFresnel>::new(Ggx::new(0.1).unwrap(), NoFresnel);
            let l = Lambertian::new(0.5f32).unwrap();
            make(RusinkiewiczGrid::new(32, 32, 16).unwrap(), &|wi, wo| {
                l.eval(wi, wo) + 0.5 * g.eval(wi, wo)
            })
        }),
    }
}

/// The five compensated configurations in [`all_kinds`]: every `(D, G)` once, two with `F = 1` (where
/// the compensation matters most) and two with a coloured conductor, plus GGX with the F82-tint metal
/// Fresnel (OpenPBR's metal).
pub const KULLA_CONTY_KINDS: [Kind; 5] = [
    Kind::KullaConty(Dist::Ggx, Shadow::HeightCorrelated, Fres::None),
    Kind::KullaConty(Dist::Ggx, Shadow::Separable, Fres::Conductor),
    Kind::KullaConty(Dist::Beckmann, Shadow::HeightCorrelated, Fres::Conductor),
    Kind::KullaConty(Dist::Beckmann, Shadow::Separable, Fres::None),
    Kind::KullaConty(Dist::Ggx, Shadow::HeightCorrelated, Fres::F82),
];

/// The rough diffuse configurations in [`all_kinds`].
pub const ROUGH_DIFFUSE_KINDS: [Kind; 3] = [Kind::Fon, Kind::Eon, Kind::OrenNayar];

/// All 39 configurations (23 single-scattering, 5 compensated, 2 tabulated, 3 rough diffuse, sheen, 5 composites).
pub fn all_kinds() -> Vec<Kind> {
    let mut v = vec![Kind::Lambertian, Kind::ModifiedPhong, Kind::BlinnPhong];
    for d in [Dist::Ggx, Dist::Beckmann] {
        for g in [Shadow::HeightCorrelated, Shadow::Separable] {
            for f in [
                Fres::None,
                Fres::Schlick,
                Fres::Dielectric,
                Fres::Conductor,
                Fres::F82,
            ] {
                v.push(Kind::Micro(d, g, f));
            }
        }
    }
    v.extend(KULLA_CONTY_KINDS);
    v.extend(TABULATED_KINDS);
    v.extend(ROUGH_DIFFUSE_KINDS);
    v.push(Kind::Sheen);
    v.extend(COMPOSITE_KINDS);
    v
}

/// The sheen roughness of the parameter set `p`: `r_min + (1 − r_min) α`.
pub fn sheen_roughness(p: &Params) -> f32 {
    use radiometry_brdfs::sheen::MIN_SHEEN_ROUGHNESS;
    (MIN_SHEEN_ROUGHNESS + (1.0 - MIN_SHEEN_ROUGHNESS) * p.alpha).min(1.0)
}

/// Parameters for every plugin (each uses its own subset).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Params {
    /// Lambertian albedo ρ.
    pub rho: f32,
    /// Phong diffuse weight.
    pub kd: f32,
    /// Phong specular weight.
    pub ks: f32,
    /// Phong exponent.
    pub n: f32,
    /// Microfacet roughness.
    pub alpha: f32,
    /// Schlick f0.
    pub f0: f32,
    /// Dielectric relative IOR.
    pub eta_d: f32,
    /// Conductor η.
    pub eta_c: f32,
    /// Conductor k.
    pub k_c: f32,
    /// Rough diffuse roughness σ ∈ [0, 1] (FON/EON as is; the classic Oren–Nayar takes `σ · π/2` radians).
    pub sigma: f32,
    /// F82 tint (with `f0` as the F82-tint term's normal-incidence reflectance).
    pub f82: f32,
}

impl Params {
    /// A typical parameter set.
    pub fn typical() -> Self {
        Params {
            rho: 0.8,
            kd: 0.3,
            ks: 0.7,
            n: 50.0,
            alpha: 0.3,
            f0: 0.04,
            eta_d: 1.5,
            eta_c: 0.2,
            k_c: 3.0,
            sigma: 0.5,
            f82: 0.8,
        }
    }
}

/// Valid parameters, hitting the edges (α down to 1e-4, n up to 1e7, kd + ks = 1, ρ = 1, f0 ∈ {0, 1},
/// η < 1 for the dielectric (total internal reflection), F82 tint ∈ {0, 1}, σ ∈ {0, 1}).
///
/// σ takes the value drawn for `f0` (same distribution, `[0, 1]` with both edges; no plugin uses both).
pub fn params() -> impl Strategy<Value = Params> + Clone {
    (
        prop_oneof![3 => 0.0f32..=1.0, 1 => Just(1.0f32), 1 => Just(0.0f32)],
        kd_ks(),
        exponent(),
        alpha(),
        prop_oneof![3 => 0.0f32..=1.0, 1 => Just(1.0f32), 1 => Just(0.0f32)],
        log_uniform(0.2, 5.0),
        log_uniform(0.01, 10.0),
        prop_oneof![3 => 0.0f64..=10.0, 1 => Just(0.0)],
        prop_oneof![3 => 0.0f32..=1.0, 1 => Just(1.0f32), 1 => Just(0.0f32)],
    )
        .prop_map(|(rho, (kd, ks), n, alpha, f0, eta_d, eta_c, k_c, f82)| Params {
            rho,
            kd,
            ks,
            n,
            alpha,
            f0,
            eta_d: eta_d as f32,
            eta_c: eta_c as f32,
            k_c: k_c as f32,
            sigma: f0,
            f82,
        })
}

fn micro<D, G>(d: D, f: Fres, p: &Params) -> Result<Dyn, BrdfError>
where
    D: radiometry_brdfs::MicrofacetDistribution + core::fmt::Debug + 'static,
    G: radiometry_brdfs::ShadowingMasking + 'static,
{
    Ok(match f {
        Fres::None => Box::new(Microfacet::<D, G, NoFresnel>::new(d, NoFresnel)),
        Fres::Schlick => Box::new(Microfacet::<D, G, _>::new(d, Schlick::new(p.f0)?)),
        Fres::Dielectric => Box::new(Microfacet::<D, G, _>::new(d, Dielectric::new(p.eta_d)?)),
        Fres::Conductor => Box::new(Microfacet::<D, G, _>::new(d, Conductor::new(p.eta_c, p.k_c)?)),
        Fres::F82 => Box::new(Microfacet::<D, G, _>::new(d, F82Tint::new(p.f0, p.f82)?)),
    })
}

fn compensated<D, G>(d: D, f: Fres, p: &Params) -> Result<Dyn, BrdfError>
where
    D: radiometry_brdfs::MicrofacetDistribution
        + radiometry_brdfs::microfacet::EnergyTable<G>
        + core::fmt::Debug
        + 'static,
    G: radiometry_brdfs::ShadowingMasking + 'static,
{
    Ok(match f {
        Fres::None => Box::new(KullaConty::<D, G, NoFresnel>::new(d, NoFresnel)),
        Fres::Schlick => Box::new(KullaConty::<D, G, _>::new(d, Schlick::new(p.f0)?)),
        Fres::Dielectric => Box::new(KullaConty::<D, G, _>::new(d, Dielectric::new(p.eta_d)?)),
        Fres::Conductor => Box::new(KullaConty::<D, G, _>::new(d, Conductor::new(p.eta_c, p.k_c)?)),
        Fres::F82 => Box::new(KullaConty::<D, G, _>::new(d, F82Tint::new(p.f0, p.f82)?)),
    })
}

/// Builds the plugin `kind` with parameters `p`.
pub fn build(kind: Kind, p: &Params) -> Result<Dyn, BrdfError> {
    Ok(match kind {
        Kind::Lambertian => Box::new(Lambertian::new(p.rho)?),
        Kind::ModifiedPhong => Box::new(ModifiedPhong::new(p.kd, p.ks, p.n)?),
        Kind::BlinnPhong => Box::new(BlinnPhong::new(p.kd, p.ks, p.n)?),
        Kind::Micro(Dist::Ggx, Shadow::HeightCorrelated, f) => {
            micro::<_, HeightCorrelated>(Ggx::new(p.alpha)?, f, p)?
        }
        Kind::Micro(Dist::Ggx, Shadow::Separable, f) => micro::<_, Separable>(Ggx::new(p.alpha)?, f, p)?,
        Kind::Micro(Dist::Beckmann, Shadow::HeightCorrelated, f) => {
            micro::<_, HeightCorrelated>(Beckmann::new(p.alpha)?, f, p)?
        }
        Kind::Micro(Dist::Beckmann, Shadow::Separable, f) => {
            micro::<_, Separable>(Beckmann::new(p.alpha)?, f, p)?
        }
        Kind::KullaConty(Dist::Ggx, Shadow::HeightCorrelated, f) => {
            compensated::<_, HeightCorrelated>(Ggx::new(p.alpha)?, f, p)?
        }
        Kind::KullaConty(Dist::Ggx, Shadow::Separable, f) => {
            compensated::<_, Separable>(Ggx::new(p.alpha)?, f, p)?
        }
        Kind::KullaConty(Dist::Beckmann, Shadow::HeightCorrelated, f) => {
            compensated::<_, HeightCorrelated>(Beckmann::new(p.alpha)?, f, p)?
        }
        Kind::KullaConty(Dist::Beckmann, Shadow::Separable, f) => {
            compensated::<_, Separable>(Beckmann::new(p.alpha)?, f, p)?
        }
        Kind::Tabulated(t) => Box::new(tabulated(t)),
        Kind::Fon => Box::new(Fon::new(p.rho, p.sigma)?),
        Kind::Eon => Box::new(Eon::new(p.rho, p.sigma)?),
        Kind::OrenNayar => {
            let sigma_rad = p.sigma * std::f32::consts::FRAC_PI_2;
            Box::new(OrenNayar::new(
                p.rho.min(OrenNayar::max_rho(sigma_rad)),
                sigma_rad,
            )?)
        }
        Kind::Composite(c) => composite(c, p)?,
        Kind::Sheen => Box::new(Sheen::new(p.rho, sheen_roughness(p))?),
    })
}

/// Angular width (radians) of the lobe around the mirror direction: broad (10) for Lambertian,
/// `1/√(n+1)` for modified Phong (cos^n α ≈ e^{−nα²/2}), `2/√(n+1)` for Blinn–Phong (θh ≈ θ/2), `2α` for
/// microfacets (D has width α in the half vector, doubled by reflection).
pub fn lobe_width(kind: Kind, p: &Params) -> f64 {
    match kind {
        Kind::Lambertian => 10.0,
        Kind::ModifiedPhong => 1.0 / (p.n as f64 + 1.0).sqrt(),
        Kind::BlinnPhong => 2.0 / (p.n as f64 + 1.0).sqrt(),
        Kind::Micro(..) => 2.0 * p.alpha as f64,
        // The narrow single-scattering lobe sets the breakpoints; the added lobe is as broad as Lambert's.
        Kind::KullaConty(..) => 2.0 * p.alpha as f64,
        Kind::Tabulated(Table::GgxMerl) => 0.6,
        Kind::Tabulated(Table::DiffuseGgxCoarse) => 0.2,
        Kind::Fon | Kind::Eon | Kind::OrenNayar => 10.0,
        // The narrowest part sets the breakpoints.
        Kind::Composite(_) => 2.0 * p.alpha as f64,
        // A broad lobe (D of width ~√r in cos θh), zero at the mirror direction.
        Kind::Sheen => 1.0,
    }
}
