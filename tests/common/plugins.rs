//! Every plugin configuration of `radiometry-brdfs` (monochrome `f32` spectra), behind one trait object,
//! with a proptest strategy for valid parameters and the angular width of each lobe (for quadrature
//! breakpoints and χ² grids).

use super::strategies::{alpha, exponent, kd_ks, log_uniform};
use proptest::prelude::*;
use radiometry::IsotropicBrdf;
use radiometry_brdfs::{
    Beckmann, BlinnPhong, BrdfError, Conductor, Dielectric, F82Tint, Ggx, HeightCorrelated, KullaConty,
    Lambertian, Microfacet, ModifiedPhong, NoFresnel, Schlick, Separable,
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

/// All 30 configurations (23 single-scattering, 5 compensated, 2 tabulated).
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
    v
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
            f82: 0.8,
        }
    }
}

/// Valid parameters, hitting the edges (α down to 1e-4, n up to 1e7, kd + ks = 1, ρ = 1, f0 ∈ {0, 1},
/// η < 1 for the dielectric (total internal reflection), F82 tint ∈ {0, 1}).
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
    }
}
