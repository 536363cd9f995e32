//! BRDF specs: `lambertian(...)`, `phong(...)`, `blinn-phong(...)`, `ggx(...)`, `beckmann(...)`,
//! `fon(...)`, `eon(...)`, `oren-nayar(...)`, `sheen(...)`, `ltc-sheen(...)`, and their compositions `A + B`, `mix(W, A, B)` and
//! `coated(TOP, BASE)`.

use crate::SpecError;
use crate::args::Args;
use crate::call::{Call, Parser};
use crate::error::err_span;
use crate::lex::Tok;
use radiometry_brdfs::metals::Metal;

/// Microfacet normal distribution.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Distribution {
    /// GGX / Trowbridge–Reitz.
    Ggx,
    /// Beckmann.
    Beckmann,
}

/// Smith shadowing–masking variant.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum G2Kind {
    /// `G2 = 1/(1+Λ(ωi)+Λ(ωo))`.
    HeightCorrelated,
    /// `G2 = G1(ωi) G1(ωo)`.
    Separable,
}

/// Multiple scattering of a microfacet BRDF.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MultipleScattering {
    /// Single scattering only (`ms=none`, the default).
    Single,
    /// Kulla & Conty 2017 energy compensation (`ms=kulla-conty`).
    KullaConty,
}

/// Fresnel term of a microfacet BRDF.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FresnelSpec {
    /// `F = 1`.
    None,
    /// Schlick's approximation with normal-incidence reflectance `f0`.
    Schlick {
        /// Reflectance at normal incidence.
        f0: f64,
    },
    /// Exact dielectric Fresnel with relative index `eta`.
    Dielectric {
        /// Relative index of refraction.
        eta: f64,
    },
    /// Exact conductor Fresnel with complex index `eta + i k`.
    Conductor {
        /// Real part of the index.
        eta: f64,
        /// Extinction coefficient.
        k: f64,
    },
    /// `conductor(metal=Au)`: the exact conductor Fresnel of a named metal's
    /// measured `η(λ), k(λ)`, reduced to the run-time BRDF's channels. RGB
    /// ([`build_brdf_rgb`](crate::model::build_brdf_rgb)): per channel the `η`, `k`
    /// whose Fresnel curve passes through the metal's spectral reflectance reduced
    /// to linear sRGB (CIE 1931 2° observer under D65) at normal incidence and at
    /// 82° (`Conductor::<Vec3>::metal` of `radiometry-brdfs`). Monochrome
    /// ([`build_brdf`](crate::build_brdf)): the same fit to the luminance `Y` of
    /// the reflectance (`Conductor::metal_luminance`).
    Metal {
        /// The metal (names case-insensitive).
        metal: Metal,
    },
    /// `f82(f0=…, f82=…)`: the F82-tint metal Fresnel of OpenPBR
    /// (Hoffman 2019), one channel.
    F82 {
        /// Reflectance at normal incidence, `[0, 1]`.
        f0: f64,
        /// Tint of the reflectance at 82°, `[0, 1]` (default 1: Schlick).
        f82: f64,
    },
}

/// A validated BRDF description (parameters as given; angles none).
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum BrdfSpec {
    /// `lambertian(albedo=1)`.
    Lambertian {
        /// Albedo ρ ∈ [0, 1] per channel (linear RGB; one number is grey).
        albedo: [f64; 3],
    },
    /// `phong(exponent=N, ks=1, kd=0)`: modified Phong (Lafortune & Willems 1994).
    Phong {
        /// Exponent n.
        exponent: f64,
        /// Specular coefficient.
        ks: f64,
        /// Diffuse coefficient.
        kd: f64,
    },
    /// `blinn-phong(exponent=N, ks=1, kd=0)`: normalised Blinn–Phong.
    BlinnPhong {
        /// Exponent n.
        exponent: f64,
        /// Specular coefficient.
        ks: f64,
        /// Diffuse coefficient.
        kd: f64,
    },
    /// `ggx(...)` / `beckmann(...)`.
    Microfacet {
        /// Distribution.
        distribution: Distribution,
        /// Roughness α.
        alpha: f64,
        /// Shadowing–masking variant.
        g: G2Kind,
        /// Fresnel term.
        fresnel: FresnelSpec,
        /// Multiple-scattering compensation.
        ms: MultipleScattering,
        /// Diffuse coefficient `kd ∈ [0, 1]` (`kd=`, default 0): the BRDF is
        /// `kd/π + f_microfacet`, the additive diffuse + specular form that
        /// `phong`'s `kd` already has (not a layered model: the sum may
        /// reflect more than 1 when `kd` and the specular albedo are both large).
        kd: f64,
    },
    /// `fon(rho=R, sigma=S)`: Fujii's improved Oren–Nayar (the EON paper's
    /// FON), σ ∈ [0, 1] dimensionless.
    Fon {
        /// Albedo colour ρ ∈ [0, 1] per channel (default 1).
        rho: [f64; 3],
        /// Roughness σ ∈ [0, 1] (dimensionless; required).
        sigma: f64,
    },
    /// `eon(rho=R, sigma=S)`: the energy-preserving Oren–Nayar (Portsmouth,
    /// Kutz & Hill 2025), σ ∈ [0, 1] dimensionless.
    Eon {
        /// Albedo colour ρ ∈ [0, 1] per channel (default 1).
        rho: [f64; 3],
        /// Roughness σ ∈ [0, 1] (dimensionless; required).
        sigma: f64,
    },
    /// `oren-nayar(rho=R, sigma_rad=S)`: the classic qualitative Oren–Nayar
    /// as pbrt-v3 has it, σ in **radians**; ρ at most
    /// `OrenNayar::max_rho(σ)` (it gains energy above).
    OrenNayar {
        /// Albedo colour ρ per channel (default 1).
        rho: [f64; 3],
        /// Roughness σ ∈ [0, π/2] in radians (required).
        sigma_rad: f64,
    },
    /// `sheen(color=1, roughness=R)`: the microfacet sheen of Estevez &
    /// Kulla 2017 (Charlie distribution, fitted `Λ`).
    Sheen {
        /// Colour, in `[0, 1]` per channel.
        color: [f64; 3],
        /// Roughness `r ∈ [MIN_SHEEN_ROUGHNESS, 1]`.
        roughness: f64,
    },
    /// `ltc-sheen(color=1, roughness=0.5)`: the LTC sheen of Zeltner, Burley & Chiang 2022
    /// (OpenPBR's recommended fuzz lobe; `radiometry_brdfs::LtcSheen`).
    LtcSheen {
        /// Colour, in `[0, 1]` per channel (default 1).
        color: [f64; 3],
        /// Roughness `r ∈ [0, 1]` (default 0.5).
        roughness: f64,
    },
    /// `openpbr(base_color=…, specular_roughness=…, …)`: the reflection layer of OpenPBR Surface
    /// (`radiometry_brdfs::OpenPbr`), OpenPBR's parameter names and defaults.
    OpenPbr(OpenPbrSpec),
    /// `tabulated(file=PATH)`: a MERL `.binary` file, read by the caller.
    Tabulated {
        /// Byte span `(start, end)` of the path in the spec text given to
        /// [`parse_brdf`]; [`BrdfSpec::file`] slices it.
        file: (usize, usize),
    },
    /// `A + B + …`: the sum of the lobes (`radiometry::compose::Sum`, lobes picked in proportion to
    /// their albedos).
    Sum(Vec<BrdfSpec>),
    /// `mix(W, A, B)`: `W f_A + (1 − W) f_B`, `W ∈ [0, 1]` (`radiometry::compose::Mix`).
    Mix {
        /// The weight `W` of `A`.
        weight: f64,
        /// Lobe `A`.
        a: Box<BrdfSpec>,
        /// Lobe `B`.
        b: Box<BrdfSpec>,
    },
    /// `coated(TOP, BASE, coat_color=1, coat_ior=1.5)`: `TOP` over `BASE` by albedo scaling
    /// (`radiometry::compose::Coated`); `coat_color < 1` absorbs in the coat (OpenPBR's `coat_color`,
    /// through a coat of index `coat_ior`).
    Coated {
        /// The top lobe.
        top: Box<BrdfSpec>,
        /// The base lobe.
        base: Box<BrdfSpec>,
        /// `coat_color ∈ [0, 1]` (1: no absorption).
        coat_color: f64,
        /// The coat's index of refraction `≥ 1` (for the path length of absorption).
        coat_ior: f64,
        /// `reciprocal=1`: the reciprocal layering (default: energy-conserving).
        reciprocal: bool,
    },
}

/// The parameters of `openpbr(...)`, with OpenPBR Surface 1.1's names and defaults (see
/// `radiometry_brdfs::openpbr`). Colours are `rgb(R, G, B)` or one number: the RGB run-time BRDF
/// ([`build_brdf_rgb`](crate::model::build_brdf_rgb)) keeps them, the monochrome one
/// ([`build_brdf`](crate::build_brdf)) uses each colour's Rec. 709 luminance ([`luminance`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OpenPbrSpec {
    /// `base_weight` (1).
    pub base_weight: f64,
    /// `base_color` (0.8).
    pub base_color: [f64; 3],
    /// `base_metalness` (0).
    pub base_metalness: f64,
    /// `base_diffuse_roughness` (0).
    pub base_diffuse_roughness: f64,
    /// `specular_weight` (1).
    pub specular_weight: f64,
    /// `specular_color` (1).
    pub specular_color: [f64; 3],
    /// `specular_roughness` (0.3).
    pub specular_roughness: f64,
    /// `specular_ior` (1.5).
    pub specular_ior: f64,
    /// `coat_weight` (0).
    pub coat_weight: f64,
    /// `coat_color` (1).
    pub coat_color: [f64; 3],
    /// `coat_roughness` (0).
    pub coat_roughness: f64,
    /// `coat_ior` (1.6).
    pub coat_ior: f64,
    /// `fuzz_weight` (0).
    pub fuzz_weight: f64,
    /// `fuzz_color` (1).
    pub fuzz_color: [f64; 3],
    /// `fuzz_roughness` (0.5).
    pub fuzz_roughness: f64,
    /// `coat_darkening` (1).
    pub coat_darkening: f64,
    /// `reciprocal=1`: the reciprocal layering (default 0: energy-conserving).
    pub reciprocal: bool,
}

/// The parameter names `openpbr(...)` accepts (OpenPBR Surface 1.1's reflection parameters).
pub const OPENPBR_PARAMS: [&str; 17] = [
    "base_weight",
    "base_color",
    "base_metalness",
    "base_diffuse_roughness",
    "specular_weight",
    "specular_color",
    "specular_roughness",
    "specular_ior",
    "coat_weight",
    "coat_color",
    "coat_roughness",
    "coat_ior",
    "coat_darkening",
    "fuzz_weight",
    "fuzz_color",
    "fuzz_roughness",
    "reciprocal",
];

/// OpenPBR parameters outside a reflection-only isotropic BRDF: named in the error message when a
/// spec uses one.
const OPENPBR_OUTSIDE: [&str; 11] = [
    "transmission_weight",
    "subsurface_weight",
    "specular_anisotropy",
    "coat_anisotropy",
    "thin_film_weight",
    "thin_film_thickness",
    "thin_film_ior",
    "emission_luminance",
    "geometry_opacity",
    "geometry_thin_walled",
    "base_subsurface",
];

/// The Rec. 709 / sRGB luminance `Y = 0.2126 R + 0.7152 G + 0.0722 B` of a linear colour (how a
/// colour enters the monochrome run-time BRDF, [`build_brdf`](crate::build_brdf); the RGB one,
/// [`build_brdf_rgb`](crate::model::build_brdf_rgb), keeps the channels).
/// A grey colour (three equal channels) is its value exactly.
pub fn luminance(c: [f64; 3]) -> f64 {
    if c[0] == c[1] && c[1] == c[2] {
        return c[0];
    }
    0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
}

/// Whether a colour is grey: its three channels are equal.
pub fn is_grey_colour(c: [f64; 3]) -> bool {
    c[0] == c[1] && c[1] == c[2]
}

impl BrdfSpec {
    /// Whether the spec is grey: every colour in it has three equal channels, and it names no
    /// metal (`conductor(metal=…)`, coloured by its spectral `η`, `k`) and no MERL file
    /// (`tabulated(file=…)`, three channels of data). A grey spec reflects every channel alike, so
    /// the monochrome run-time BRDF ([`build_brdf`](crate::build_brdf)) gives the value of each
    /// channel of the RGB one ([`build_brdf_rgb`](crate::model::build_brdf_rgb)): front ends print one
    /// value for it.
    ///
    /// ```
    /// use radiometry_spec::parse_brdf;
    /// assert!(parse_brdf("lambertian(albedo=rgb(0.5, 0.5, 0.5))")?.is_grey());
    /// assert!(!parse_brdf("lambertian(albedo=rgb(0.8, 0.1, 0.1))")?.is_grey());
    /// assert!(!parse_brdf("ggx(alpha=0.3, fresnel=conductor(metal=Au))")?.is_grey());
    /// assert!(parse_brdf("ggx(alpha=0.3, fresnel=conductor(eta=0.2, k=3.9))")?.is_grey());
    /// # Ok::<(), radiometry_spec::SpecError>(())
    /// ```
    pub fn is_grey(&self) -> bool {
        match self {
            BrdfSpec::Lambertian { albedo: c }
            | BrdfSpec::Fon { rho: c, .. }
            | BrdfSpec::Eon { rho: c, .. }
            | BrdfSpec::OrenNayar { rho: c, .. }
            | BrdfSpec::Sheen { color: c, .. }
            | BrdfSpec::LtcSheen { color: c, .. } => is_grey_colour(*c),
            BrdfSpec::Phong { .. } | BrdfSpec::BlinnPhong { .. } => true,
            BrdfSpec::Microfacet { fresnel, .. } => !matches!(fresnel, FresnelSpec::Metal { .. }),
            BrdfSpec::OpenPbr(p) => [p.base_color, p.specular_color, p.coat_color, p.fuzz_color]
                .into_iter()
                .all(is_grey_colour),
            BrdfSpec::Tabulated { .. } => false,
            BrdfSpec::Sum(parts) => parts.iter().all(BrdfSpec::is_grey),
            BrdfSpec::Mix { a, b, .. } => a.is_grey() && b.is_grey(),
            BrdfSpec::Coated { top, base, .. } => top.is_grey() && base.is_grey(),
        }
    }

    /// The path of a `tabulated(file=PATH)` spec, sliced from `text` (the
    /// string that was parsed); `None` for other BRDFs or a span that does
    /// not fit `text`.
    pub fn file<'a>(&self, text: &'a str) -> Option<&'a str> {
        match *self {
            BrdfSpec::Tabulated { file: (a, b) } => text.get(a..b),
            _ => None,
        }
    }
}

/// Largest accepted Phong / Blinn–Phong exponent (the plugins' `MAX_EXPONENT`).
pub const MAX_EXPONENT: f64 = 1e7;
/// Smallest accepted microfacet roughness (the plugins' `MIN_ALPHA`).
pub const MIN_ALPHA: f64 = 1e-4;
/// Largest accepted microfacet roughness (the plugins' `MAX_ALPHA`).
pub const MAX_ALPHA: f64 = 1.0;
/// Smallest accepted sheen roughness (the plugin's `MIN_SHEEN_ROUGHNESS`,
/// below which the paper's fitted `Λ` lets the lobe reflect more than it
/// receives).
pub const MIN_SHEEN_ROUGHNESS: f64 = 0.07;

/// Help text describing the BRDF spec language (used by `--help`).
pub const BRDF_SPEC_HELP: &str = "BRDF spec, e.g. `lambertian(albedo=0.5)`, `phong(exponent=100, ks=1, kd=0)`, \
`blinn-phong(exponent=100, ks=1, kd=0)`, `ggx(alpha=0.1, g=height-correlated|separable, \
fresnel=none|schlick(f0=0.04)|dielectric(eta=1.5)|conductor(eta=0.2,k=3.9)|conductor(metal=Au)|f82(f0=0.9,f82=0.8), \
ms=none|kulla-conty, kd=0)` (metals: Au, Ag, Cu, Al, Cr, Fe, Ni, Ti, Pt, Brass, \
reduced to linear sRGB under D65, or to their luminance in monochrome; a colour is one number or rgb(R, G, B), linear; \
a spec with a colour, a named metal or a MERL file is evaluated per channel, or as its Rec. 709 luminance in monochrome), \
`beckmann(...)` (same parameters as ggx), `tabulated(file=PATH)` (a MERL .binary file; the path runs to the last `)`), \
`eon(rho=1, sigma=0.5)` (energy-preserving Oren–Nayar), `fon(rho=1, sigma=0.5)` (Fujii's Oren–Nayar), \
`oren-nayar(rho=0.9, sigma_rad=0.35)` (classic, pbrt-v3), `sheen(color=1, roughness=0.5)` (Estevez & Kulla 2017 \
cloth sheen; roughness ∈ [0.07, 1] is required), `ltc-sheen(color=1, roughness=0.5)` (Zeltner, Burley & Chiang \
2022 LTC sheen, OpenPBR's fuzz; roughness ∈ [0, 1], its defaults shown; not reciprocal), \
`openpbr(base_weight=1, base_color=0.8, base_metalness=0, base_diffuse_roughness=0, specular_weight=1, \
specular_color=1, specular_roughness=0.3, specular_ior=1.5, coat_weight=0, coat_color=1, coat_roughness=0, \
coat_ior=1.6, coat_darkening=1, fuzz_weight=0, fuzz_color=1, fuzz_roughness=0.5, reciprocal=0)` (OpenPBR Surface's reflection layer, its defaults shown); \
compositions: `A + B` (sum), `mix(W, A, B)` (W·A + (1−W)·B), `coated(TOP, BASE, coat_color=1, coat_ior=1.5, reciprocal=0)` \
(TOP over BASE by albedo scaling; reciprocal=1 for the reciprocal layering), e.g. `coated(ggx(alpha=0.1, fresnel=dielectric(eta=1.5)), lambertian(albedo=0.8))`. Defaults: albedo=1, rho=1, ks=1, kd=0, g=height-correlated, fresnel=none, \
ms=none (kulla-conty adds the Kulla–Conty 2017 multiple-scattering lobe); a microfacet kd adds a diffuse kd/π; \
exponent ∈ [0, 1e7] and alpha ∈ [1e-4, 1] are required; kd + ks ≤ 1; eon/fon take sigma ∈ [0, 1] (dimensionless), \
oren-nayar takes sigma_rad ∈ [0, π/2] in radians and rho ≤ 1/(A + B/2) (its albedo exceeds 1 above).";

/// Parses and validates a BRDF spec.
pub fn parse_brdf(spec: &str) -> Result<BrdfSpec, SpecError> {
    if let Some(r) = crate::tabulated::parse(spec) {
        return r;
    }
    let mut p = Parser::new(spec)?;
    let b = expr(spec, &mut p, 0)?;
    p.finish()?;
    Ok(b)
}

/// `expr := term ('+' term)*`.
fn expr(spec: &str, p: &mut Parser<'_>, depth: usize) -> Result<BrdfSpec, SpecError> {
    let mut parts = vec![term(spec, p, depth)?];
    while p.peek().tok == Tok::Plus {
        p.bump();
        parts.push(term(spec, p, depth)?);
    }
    Ok(if parts.len() == 1 {
        parts.pop().expect("one part")
    } else {
        BrdfSpec::Sum(parts)
    })
}

/// `term := mix(NUM, expr, expr) | coated(expr, expr [, key=NUM]*) | call`.
fn term(spec: &str, p: &mut Parser<'_>, depth: usize) -> Result<BrdfSpec, SpecError> {
    if depth > 8 {
        return Err(p.expected("a shallower nesting of compositions"));
    }
    let is = |p: &Parser<'_>, name: &str| matches!(&p.peek().tok, Tok::Ident(n) if n == name);
    if is(p, "mix") || is(p, "coated") {
        let mix = is(p, "mix");
        p.bump();
        expect(p, Tok::LParen, "`(`")?;
        if mix {
            let t = p.peek().clone();
            let Tok::Num(w) = t.tok else {
                return Err(p.expected("the mix weight (a number in [0, 1])"));
            };
            if !(0.0..=1.0).contains(&w) {
                return Err(p.err_at(&t, format!("mix weight {w} must lie in [0, 1]")));
            }
            p.bump();
            expect(p, Tok::Comma, "`,`")?;
            let a = expr(spec, p, depth + 1)?;
            expect(p, Tok::Comma, "`,`")?;
            let b = expr(spec, p, depth + 1)?;
            expect(p, Tok::RParen, "`)`")?;
            return Ok(BrdfSpec::Mix {
                weight: w,
                a: Box::new(a),
                b: Box::new(b),
            });
        }
        let top = expr(spec, p, depth + 1)?;
        expect(p, Tok::Comma, "`,`")?;
        let base = expr(spec, p, depth + 1)?;
        let (mut coat_color, mut coat_ior, mut reciprocal) = (1.0, 1.5, false);
        while p.peek().tok == Tok::Comma {
            p.bump();
            let kt = p.peek().clone();
            let key = match &kt.tok {
                Tok::Ident(k) if k == "coat_color" || k == "coat_ior" || k == "reciprocal" => k.clone(),
                _ => return Err(p.expected("`coat_color=`, `coat_ior=` or `reciprocal=`")),
            };
            p.bump();
            expect(p, Tok::Eq, "`=`")?;
            let vt = p.peek().clone();
            let Tok::Num(v) = vt.tok else {
                return Err(p.expected(&format!("a number for `{key}`")));
            };
            let ok = match key.as_str() {
                "coat_color" => (0.0..=1.0).contains(&v),
                "reciprocal" => v == 0.0 || v == 1.0,
                _ => (1.0..=1e3).contains(&v),
            };
            if !ok {
                let range = match key.as_str() {
                    "coat_color" => "[0, 1]",
                    "reciprocal" => "{0, 1}",
                    _ => "[1, 1000]",
                };
                return Err(p.err_at(&vt, format!("{key} = {v} must lie in {range}")));
            }
            p.bump();
            match key.as_str() {
                "coat_color" => coat_color = v,
                "reciprocal" => reciprocal = v == 1.0,
                _ => coat_ior = v,
            }
        }
        expect(p, Tok::RParen, "`)`")?;
        return Ok(BrdfSpec::Coated {
            top: Box::new(top),
            base: Box::new(base),
            coat_color,
            coat_ior,
            reciprocal,
        });
    }
    let call = p.call(0)?;
    plugin(spec, &call)
}

fn expect(p: &mut Parser<'_>, tok: Tok, what: &str) -> Result<(), SpecError> {
    if p.peek().tok == tok {
        p.bump();
        Ok(())
    } else {
        Err(p.expected(what))
    }
}

/// One plugin call, validated.
fn plugin(spec: &str, call: &Call) -> Result<BrdfSpec, SpecError> {
    let name = call.name.as_str();
    match name {
        "lambertian" | "lambert" => {
            let mut a = Args::new(spec, call, &["albedo"])?;
            let albedo = a.colour("albedo", Some(1.0))?;
            Ok(BrdfSpec::Lambertian { albedo })
        }
        "phong" | "blinn-phong" => {
            let mut a = Args::new(spec, call, &["exponent", "ks", "kd"])?;
            let exponent = a.num("exponent", None, 0.0, MAX_EXPONENT, false)?;
            let ks = a.num("ks", Some(1.0), 0.0, 1.0, false)?;
            let kd = a.num("kd", Some(0.0), 0.0, 1.0, false)?;
            if kd + ks > 1.0 + 1e-12 {
                let span = call
                    .args
                    .iter()
                    .find(|x| x.key == "ks")
                    .or_else(|| call.args.iter().find(|x| x.key == "kd"))
                    .map_or(call.span, |x| (x.key_span.0, x.value.span().1));
                return Err(err_span(spec, span, format!("kd + ks = {} must be ≤ 1", kd + ks)));
            }
            Ok(if name == "phong" {
                BrdfSpec::Phong { exponent, ks, kd }
            } else {
                BrdfSpec::BlinnPhong { exponent, ks, kd }
            })
        }
        "ggx" | "beckmann" => {
            let mut a = Args::new(spec, call, &["alpha", "g", "fresnel", "ms", "kd"])?;
            let alpha = a.num("alpha", None, MIN_ALPHA, MAX_ALPHA, false)?;
            let kd = a.num("kd", Some(0.0), 0.0, 1.0, false)?;
            let g = match a.call_value("g")? {
                None => G2Kind::HeightCorrelated,
                Some(c) => {
                    Args::new(spec, c, &[])?;
                    match c.name.as_str() {
                        "height-correlated" => G2Kind::HeightCorrelated,
                        "separable" | "uncorrelated" => G2Kind::Separable,
                        other => {
                            return Err(err_span(
                                spec,
                                c.name_span,
                                format!(
                                    "unknown shadowing-masking `{other}` (expected height-correlated or separable)"
                                ),
                            ));
                        }
                    }
                }
            };
            let fresnel = match a.call_value("fresnel")? {
                None => FresnelSpec::None,
                Some(c) => parse_fresnel(spec, c)?,
            };
            let ms = match a.call_value("ms")? {
                None => MultipleScattering::Single,
                Some(c) => {
                    Args::new(spec, c, &[])?;
                    match c.name.as_str() {
                        "none" | "single" => MultipleScattering::Single,
                        "kulla-conty" => MultipleScattering::KullaConty,
                        other => {
                            return Err(err_span(
                                spec,
                                c.name_span,
                                format!(
                                    "unknown multiple scattering `{other}` (expected none or kulla-conty)"
                                ),
                            ));
                        }
                    }
                }
            };
            let distribution = if name == "ggx" {
                Distribution::Ggx
            } else {
                Distribution::Beckmann
            };
            Ok(BrdfSpec::Microfacet {
                distribution,
                alpha,
                g,
                fresnel,
                ms,
                kd,
            })
        }
        "fon" | "eon" => {
            let mut a = Args::new(spec, call, &["rho", "sigma"])?;
            let rho = a.colour("rho", Some(1.0))?;
            let sigma = a.num("sigma", None, 0.0, 1.0, false)?;
            Ok(if name == "fon" {
                BrdfSpec::Fon { rho, sigma }
            } else {
                BrdfSpec::Eon { rho, sigma }
            })
        }
        "oren-nayar" => {
            let mut a = Args::new(spec, call, &["rho", "sigma_rad"])?;
            let rho = a.colour("rho", Some(1.0))?;
            let sigma_rad = a.num("sigma_rad", None, 0.0, core::f64::consts::FRAC_PI_2, false)?;
            let max = radiometry_brdfs::OrenNayar::max_rho(sigma_rad as f32) as f64;
            // Each channel is one Oren–Nayar lobe: the brightest must keep the bound.
            if let Some(&rho) = rho.iter().find(|&&v| v as f32 as f64 > max) {
                let span = call
                    .args
                    .iter()
                    .find(|x| x.key == "rho")
                    .map_or(call.name_span, |x| x.value.span());
                return Err(err_span(
                    spec,
                    span,
                    format!(
                        "`rho` = {rho} makes the classic Oren–Nayar reflect more than it receives at grazing view \
                         (energy gain); at sigma_rad = {sigma_rad} it must be ≤ {max} (or use eon)"
                    ),
                ));
            }
            Ok(BrdfSpec::OrenNayar { rho, sigma_rad })
        }
        "openpbr" => {
            if let Some(x) = call
                .args
                .iter()
                .find(|x| OPENPBR_OUTSIDE.contains(&x.key.as_str()))
            {
                return Err(err_span(
                    spec,
                    x.key_span,
                    format!(
                        "`{}` is an OpenPBR parameter outside a reflection-only, isotropic BRDF (see docs/materials.md)",
                        x.key
                    ),
                ));
            }
            let mut allowed = OPENPBR_PARAMS.to_vec();
            allowed.extend(["file", "material"]);
            let mut a = Args::new(spec, call, &allowed)?;
            // `file="doc.mtlx"` (and `material="Name"`): the document's
            // material gives the defaults of every parameter below.
            let d = match a.string("file")? {
                Some((path, span)) => {
                    let material = a.string("material")?.map(|(m, _)| m);
                    let xml = std::fs::read_to_string(path)
                        .map_err(|e| err_span(spec, span, format!("cannot read `{path}`: {e}")))?;
                    crate::mtlx::read_openpbr(&xml, material)
                        .map_err(|e| err_span(spec, span, format!("{path}: {e}")))?
                        .params
                }
                None => {
                    if let Some((_, span)) = a.string("material")? {
                        return Err(err_span(spec, span, "`material` needs `file`".into()));
                    }
                    crate::mtlx::openpbr_defaults()
                }
            };
            let unit = |a: &mut Args<'_>, k: &str, d: f64| a.num(k, Some(d), 0.0, 1.0, false);
            let colour = |a: &mut Args<'_>, k: &str, d: [f64; 3]| -> Result<[f64; 3], SpecError> {
                if a.has(k) { a.colour(k, None) } else { Ok(d) }
            };
            Ok(BrdfSpec::OpenPbr(OpenPbrSpec {
                base_weight: unit(&mut a, "base_weight", d.base_weight)?,
                base_color: colour(&mut a, "base_color", d.base_color)?,
                base_metalness: unit(&mut a, "base_metalness", d.base_metalness)?,
                base_diffuse_roughness: unit(&mut a, "base_diffuse_roughness", d.base_diffuse_roughness)?,
                specular_weight: unit(&mut a, "specular_weight", d.specular_weight)?,
                specular_color: colour(&mut a, "specular_color", d.specular_color)?,
                specular_roughness: unit(&mut a, "specular_roughness", d.specular_roughness)?,
                specular_ior: a.num("specular_ior", Some(d.specular_ior), 1.0, 1e3, false)?,
                coat_weight: unit(&mut a, "coat_weight", d.coat_weight)?,
                coat_color: colour(&mut a, "coat_color", d.coat_color)?,
                coat_roughness: unit(&mut a, "coat_roughness", d.coat_roughness)?,
                coat_ior: a.num("coat_ior", Some(d.coat_ior), 1.0, 1e3, false)?,
                fuzz_weight: unit(&mut a, "fuzz_weight", d.fuzz_weight)?,
                fuzz_color: colour(&mut a, "fuzz_color", d.fuzz_color)?,
                fuzz_roughness: unit(&mut a, "fuzz_roughness", d.fuzz_roughness)?,
                coat_darkening: unit(&mut a, "coat_darkening", d.coat_darkening)?,
                reciprocal: a.num("reciprocal", Some(0.0), 0.0, 1.0, true)? == 1.0,
            }))
        }
        "sheen" => {
            let mut a = Args::new(spec, call, &["color", "roughness"])?;
            let color = a.colour("color", Some(1.0))?;
            let roughness = a.num("roughness", None, MIN_SHEEN_ROUGHNESS, 1.0, false)?;
            Ok(BrdfSpec::Sheen { color, roughness })
        }
        "ltc-sheen" => {
            let mut a = Args::new(spec, call, &["color", "roughness"])?;
            let color = a.colour("color", Some(1.0))?;
            let roughness = a.num("roughness", Some(0.5), 0.0, 1.0, false)?;
            Ok(BrdfSpec::LtcSheen { color, roughness })
        }
        other => Err(err_span(
            spec,
            call.name_span,
            format!(
                "unknown BRDF `{other}` (expected lambertian, phong, blinn-phong, ggx, beckmann, eon, fon, oren-nayar, sheen, ltc-sheen, openpbr, tabulated, mix or coated)"
            ),
        )),
    }
}

fn parse_fresnel(spec: &str, c: &Call) -> Result<FresnelSpec, SpecError> {
    match c.name.as_str() {
        "none" => {
            Args::new(spec, c, &[])?;
            Ok(FresnelSpec::None)
        }
        "schlick" => {
            let mut a = Args::new(spec, c, &["f0"])?;
            Ok(FresnelSpec::Schlick {
                f0: a.num("f0", Some(0.04), 0.0, 1.0, false)?,
            })
        }
        "dielectric" => {
            let mut a = Args::new(spec, c, &["eta"])?;
            Ok(FresnelSpec::Dielectric {
                eta: a.num("eta", Some(1.5), 0.0, 1e3, true)?,
            })
        }
        "conductor" => {
            let mut a = Args::new(spec, c, &["eta", "k", "metal"])?;
            if let Some(m) = a.call_value("metal")? {
                if let Some(x) = c.args.iter().find(|x| x.key != "metal") {
                    return Err(err_span(
                        spec,
                        x.key_span,
                        format!(
                            "`{}` cannot be given with `metal` (the metal's table sets η and k)",
                            x.key
                        ),
                    ));
                }
                Args::new(spec, m, &[])?;
                let metal = Metal::from_name(&m.name).ok_or_else(|| {
                    let names: Vec<&str> = Metal::ALL.iter().map(|x| x.name()).collect();
                    err_span(
                        spec,
                        m.name_span,
                        format!(
                            "unknown metal `{}` (expected one of: {})",
                            m.name,
                            names.join(", ")
                        ),
                    )
                })?;
                return Ok(FresnelSpec::Metal { metal });
            }
            Ok(FresnelSpec::Conductor {
                eta: a.num("eta", None, 0.0, 1e3, true)?,
                k: a.num("k", None, 0.0, 1e3, false)?,
            })
        }
        "f82" | "f82-tint" => {
            let mut a = Args::new(spec, c, &["f0", "f82"])?;
            Ok(FresnelSpec::F82 {
                f0: a.num("f0", None, 0.0, 1.0, false)?,
                f82: a.num("f82", Some(1.0), 0.0, 1.0, false)?,
            })
        }
        other => Err(err_span(
            spec,
            c.name_span,
            format!("unknown fresnel `{other}` (expected none, schlick, dielectric, conductor or f82)"),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn caret_of(e: &SpecError) -> &str {
        &e.spec[e.start..e.end]
    }

    #[test]
    fn compositions_parse_with_carets_on_errors() {
        let l = |albedo| BrdfSpec::Lambertian { albedo: [albedo; 3] };
        assert_eq!(
            parse_brdf("lambertian(albedo=0.2) + lambertian(albedo=0.3)+lambertian").unwrap(),
            BrdfSpec::Sum(vec![l(0.2), l(0.3), l(1.0)])
        );
        assert_eq!(
            parse_brdf("mix(0.25, lambertian, lambertian(albedo=0.5) + lambertian(albedo=0.1))").unwrap(),
            BrdfSpec::Mix {
                weight: 0.25,
                a: Box::new(l(1.0)),
                b: Box::new(BrdfSpec::Sum(vec![l(0.5), l(0.1)])),
            }
        );
        assert_eq!(
            parse_brdf(
                "coated(lambertian(albedo=0.1), mix(1, lambertian, lambertian), coat_ior=1.6, coat_color=0.5, reciprocal=1)"
            )
            .unwrap(),
            BrdfSpec::Coated {
                top: Box::new(l(0.1)),
                base: Box::new(BrdfSpec::Mix {
                    weight: 1.0,
                    a: Box::new(l(1.0)),
                    b: Box::new(l(1.0))
                }),
                coat_color: 0.5,
                coat_ior: 1.6,
                reciprocal: true,
            }
        );
        for (t, bad) in [
            ("mix(2, lambertian, lambertian)", "2"),
            ("mix(lambertian, lambertian)", "lambertian"),
            ("mix(0.5, lambertian)", ")"),
            ("coated(lambertian, lambertian, coat_color=1.5)", "1.5"),
            ("coated(lambertian, lambertian, coat_ior=0.5)", "0.5"),
            ("coated(lambertian, lambertian, thickness=1)", "thickness"),
            ("lambertian + nope", "nope"),
            ("lambertian +", ""),
            ("coated(lambertian, lambertian(albedo=2))", "2"),
        ] {
            let e = parse_brdf(t).expect_err(t);
            assert_eq!(caret_of(&e), bad, "{t}: {e}");
        }
    }

    #[test]
    fn metal_and_f82_fresnel() {
        let fresnel_of = |s: &str| match parse_brdf(s).unwrap() {
            BrdfSpec::Microfacet { fresnel, .. } => fresnel,
            other => panic!("{other:?}"),
        };
        assert_eq!(
            fresnel_of("ggx(alpha=0.3, fresnel=conductor(metal=Au))"),
            FresnelSpec::Metal { metal: Metal::Au }
        );
        for (name, m) in [
            ("au", Metal::Au),
            ("AG", Metal::Ag),
            ("brass", Metal::Brass),
            ("Pt", Metal::Pt),
        ] {
            let s = format!("beckmann(alpha=0.1, fresnel=conductor(metal={name}))");
            assert_eq!(fresnel_of(&s), FresnelSpec::Metal { metal: m }, "{s}");
        }
        assert_eq!(
            fresnel_of("ggx(alpha=0.3, fresnel=f82(f0=0.9, f82=0.7))"),
            FresnelSpec::F82 { f0: 0.9, f82: 0.7 }
        );
        assert_eq!(
            fresnel_of("ggx(alpha=0.3, fresnel=f82(f0=0.5))"),
            FresnelSpec::F82 { f0: 0.5, f82: 1.0 }
        );
        let e = parse_brdf("ggx(alpha=0.1, fresnel=conductor(metal=steel))").unwrap_err();
        let msg = e.to_string();
        assert!(
            msg.contains("unknown metal `steel`") && msg.contains("Au, Ag, Cu"),
            "{msg}"
        );
    }

    #[test]
    fn brdf_examples_from_the_issue() {
        assert_eq!(
            parse_brdf("lambertian(albedo=0.5)").unwrap(),
            BrdfSpec::Lambertian { albedo: [0.5; 3] }
        );
        assert_eq!(
            parse_brdf("phong(exponent=100, ks=1, kd=0)").unwrap(),
            BrdfSpec::Phong {
                exponent: 100.0,
                ks: 1.0,
                kd: 0.0
            }
        );
        assert_eq!(
            parse_brdf("blinn-phong(exponent=20,ks=0.5,kd=0.5)").unwrap(),
            BrdfSpec::BlinnPhong {
                exponent: 20.0,
                ks: 0.5,
                kd: 0.5
            }
        );
        assert_eq!(
            parse_brdf("ggx(alpha=0.1, g=separable, fresnel=conductor(eta=0.2,k=3.9))").unwrap(),
            BrdfSpec::Microfacet {
                distribution: Distribution::Ggx,
                alpha: 0.1,
                g: G2Kind::Separable,
                fresnel: FresnelSpec::Conductor { eta: 0.2, k: 3.9 },
                ms: MultipleScattering::Single,
                kd: 0.0
            }
        );
        assert_eq!(
            parse_brdf("beckmann(alpha=1e-2, g=height-correlated, fresnel=schlick(f0=0.04))").unwrap(),
            BrdfSpec::Microfacet {
                distribution: Distribution::Beckmann,
                alpha: 0.01,
                g: G2Kind::HeightCorrelated,
                fresnel: FresnelSpec::Schlick { f0: 0.04 },
                ms: MultipleScattering::Single,
                kd: 0.0
            }
        );
        assert_eq!(
            parse_brdf("  ggx ( alpha = .3 , fresnel = dielectric ( eta = 1.5 ) , ) ").unwrap(),
            BrdfSpec::Microfacet {
                distribution: Distribution::Ggx,
                alpha: 0.3,
                g: G2Kind::HeightCorrelated,
                fresnel: FresnelSpec::Dielectric { eta: 1.5 },
                ms: MultipleScattering::Single,
                kd: 0.0
            }
        );
        assert_eq!(
            parse_brdf("ggx(alpha=1, ms=kulla-conty)").unwrap(),
            BrdfSpec::Microfacet {
                distribution: Distribution::Ggx,
                alpha: 1.0,
                g: G2Kind::HeightCorrelated,
                fresnel: FresnelSpec::None,
                ms: MultipleScattering::KullaConty,
                kd: 0.0
            }
        );
        assert_eq!(
            parse_brdf("lambertian").unwrap(),
            BrdfSpec::Lambertian { albedo: [1.0; 3] }
        );
        assert_eq!(
            parse_brdf("ggx(alpha=1, fresnel=none)").unwrap(),
            BrdfSpec::Microfacet {
                distribution: Distribution::Ggx,
                alpha: 1.0,
                g: G2Kind::HeightCorrelated,
                fresnel: FresnelSpec::None,
                ms: MultipleScattering::Single,
                kd: 0.0
            }
        );
    }

    #[test]
    fn errors_point_at_the_offending_token() {
        let cases: &[(&str, &str)] = &[
            ("lambertain(albedo=0.5)", "lambertain"),
            ("lambertian(albdo=0.5)", "albdo"),
            ("lambertian(albedo=1.5)", "1.5"),
            ("lambertian(albedo=-0.1)", "-0.1"),
            ("lambertian(albedo=0.5", ""),
            ("lambertian(albedo=0.5))", ")"),
            ("lambertian(albedo 0.5)", "0.5"),
            ("lambertian(albedo=)", ")"),
            ("lambertian(albedo=0.5, albedo=0.2)", "albedo"),
            ("phong(ks=1)", "phong"),
            ("phong(exponent=1e8)", "1e8"),
            ("ggx(alpha=0.1, g=sep)", "sep"),
            ("ggx(alpha=0.1, ms=kula-conty)", "kula-conty"),
            ("ggx(alpha=0.1, ms=kulla-conty(x=1))", "x"),
            ("ggx(alpha=0.1, g=1)", "1"),
            ("ggx(alpha=0.1, fresnel=schlik(f0=0.04))", "schlik"),
            ("ggx(alpha=0.1, fresnel=schlick(f=0.04))", "f"),
            ("ggx(alpha=0.1, fresnel=conductor(eta=0.2))", "conductor"),
            ("ggx(alpha=0.1, fresnel=conductor(metal=Steel))", "Steel"),
            ("ggx(alpha=0.1, fresnel=conductor(metal=Au, k=3))", "k"),
            ("ggx(alpha=0.1, fresnel=conductor(eta=1, metal=Au))", "eta"),
            ("ggx(alpha=0.1, fresnel=conductor(metal=1))", "1"),
            ("ggx(alpha=0.1, fresnel=conductor(metal=Au(x=1)))", "x"),
            ("ggx(alpha=0.1, fresnel=f82(f82=0.5))", "f82"),
            ("ggx(alpha=0.1, fresnel=f82(f0=1.2))", "1.2"),
            ("ggx(alpha=0.1, fresnel=f82(f0=0.9, f82=-0.1))", "-0.1"),
            ("ggx(alpha=0.1, fresnel=f82(f0=0.9, tint=1))", "tint"),
            ("ggx(alpha=0)", "0"),
            ("ggx(alpha=1x)", "1x"),
            ("ggx(alpha=0.1) junk", "junk"),
            ("ggx(alpha=0.1; g=separable)", ";"),
            ("ggx(alpha=nan)", "nan"),
            ("ggx(alpha=1e999)", "1e999"),
            ("ggx(alpha=0.1, g=separable(x=1))", "x"),
            ("", ""),
            ("(", "("),
            ("ggx(alpha=0.1é)", "é"),
        ];
        for (spec, bad) in cases {
            let e = parse_brdf(spec).expect_err(spec);
            assert_eq!(caret_of(&e), *bad, "spec {spec:?}: {e}");
            let shown = e.to_string();
            assert!(shown.contains('^'), "{shown}");
            assert!(shown.contains(spec.trim_end()) || spec.is_empty(), "{shown}");
        }
    }

    #[test]
    fn openpbr_spec_has_openpbr_names_defaults_and_rgb_colours() {
        let BrdfSpec::OpenPbr(d) = parse_brdf("openpbr").unwrap() else {
            panic!("not openpbr")
        };
        assert_eq!(
            (d.base_weight, d.base_color, d.base_metalness),
            (1.0, [0.8; 3], 0.0)
        );
        assert_eq!(
            (d.specular_roughness, d.specular_ior, d.coat_ior),
            (0.3, 1.5, 1.6)
        );
        assert_eq!((d.coat_weight, d.fuzz_weight, d.fuzz_roughness), (0.0, 0.0, 0.5));
        let BrdfSpec::OpenPbr(p) = parse_brdf(
            "openpbr(base_color=rgb(0.9, 0.5, 0.1), base_metalness=1, specular_color=0.7, coat_weight=0.5, \
             coat_color=rgb(1, 0.9, 0.8), fuzz_weight=0.25, fuzz_color=rgb(0.2,0.3,0.4), specular_ior=1.4)",
        )
        .unwrap() else {
            panic!("not openpbr")
        };
        assert_eq!(p.base_color, [0.9, 0.5, 0.1]);
        assert_eq!(p.specular_color, [0.7; 3]);
        assert_eq!(p.coat_color, [1.0, 0.9, 0.8]);
        assert_eq!(p.fuzz_color, [0.2, 0.3, 0.4]);
        assert_eq!(
            (p.base_metalness, p.coat_weight, p.fuzz_weight, p.specular_ior),
            (1.0, 0.5, 0.25, 1.4)
        );
        // Errors point at the offending value or name.
        for (spec, caret) in [
            ("openpbr(base_color=rgb(0.9, 1.5, 0.1))", "rgb(0.9, 1.5, 0.1)"),
            ("openpbr(base_color=rgb(0.9, 0.5))", ")"),
            ("openpbr(base_color=rgb(0.9, 0.5, 0.1, 0.2))", ","),
            ("openpbr(base_weight=rgb(1, 1, 1))", "rgb(1, 1, 1)"),
            ("openpbr(specular_ior=0.5)", "0.5"),
            ("openpbr(transmission_weight=1)", "transmission_weight"),
            ("openpbr(reciprocal=2)", "2"),
            ("openpbr(base_colour=0.5)", "base_colour"),
            ("openpbr(fuzz_weight=2)", "2"),
        ] {
            let e = parse_brdf(spec).unwrap_err();
            assert_eq!(caret_of(&e), caret, "{spec}: {e}");
        }
        assert!(
            parse_brdf("openpbr(transmission_weight=1)")
                .unwrap_err()
                .to_string()
                .contains("outside a reflection-only")
        );
    }

    #[test]
    fn plugin_colours_stay_colours() {
        assert_eq!(
            parse_brdf("lambertian(albedo=rgb(0.5, 0.5, 0.5))").unwrap(),
            BrdfSpec::Lambertian { albedo: [0.5; 3] }
        );
        let BrdfSpec::Eon { rho, .. } = parse_brdf("eon(rho=rgb(1, 0, 0), sigma=0.5)").unwrap() else {
            panic!()
        };
        assert_eq!(rho, [1.0, 0.0, 0.0]);
        assert_eq!(luminance([0.3; 3]), 0.3);
        assert!((luminance([1.0, 1.0, 0.0]) - 0.9278).abs() < 1e-12);
        assert!(parse_brdf("sheen(color=rgb(1, 1, 2), roughness=0.5)").is_err());
    }

    #[test]
    fn sheen_spec() {
        assert_eq!(
            parse_brdf("sheen(color=1, roughness=0.5)").unwrap(),
            BrdfSpec::Sheen {
                color: [1.0; 3],
                roughness: 0.5
            }
        );
        assert_eq!(
            parse_brdf("sheen(roughness=1)").unwrap(),
            BrdfSpec::Sheen {
                color: [1.0; 3],
                roughness: 1.0
            }
        );
        for (spec, bad) in [
            ("sheen(color=1)", "sheen"),
            ("sheen(roughness=0.01)", "0.01"),
            ("sheen(roughness=0)", "0"),
            ("sheen(color=1.5, roughness=0.5)", "1.5"),
            ("sheen(colour=1, roughness=0.5)", "colour"),
            ("sheen(roughness=0.5, alpha=0.1)", "alpha"),
        ] {
            let e = parse_brdf(spec).expect_err(spec);
            assert_eq!(caret_of(&e), bad, "spec {spec:?}: {e}");
        }
    }

    #[test]
    fn ltc_sheen_spec() {
        assert_eq!(
            parse_brdf("ltc-sheen(color=0.8, roughness=0.3)").unwrap(),
            BrdfSpec::LtcSheen {
                color: [0.8; 3],
                roughness: 0.3
            }
        );
        assert_eq!(
            parse_brdf("ltc-sheen()").unwrap(),
            BrdfSpec::LtcSheen {
                color: [1.0; 3],
                roughness: 0.5
            }
        );
        // Both ends of the roughness are accepted.
        for r in ["0", "1"] {
            assert!(parse_brdf(&format!("ltc-sheen(roughness={r})")).is_ok(), "{r}");
        }
        for (spec, bad) in [
            ("ltc-sheen(roughness=1.5)", "1.5"),
            ("ltc-sheen(roughness=-0.1)", "-0.1"),
            ("ltc-sheen(color=1.5)", "1.5"),
            ("ltc-sheen(colour=1)", "colour"),
            ("ltc-sheen(roughness=0.5, alpha=0.1)", "alpha"),
            ("ltc_sheen(roughness=0.5)", "ltc_sheen"),
        ] {
            let e = parse_brdf(spec).expect_err(spec);
            assert_eq!(caret_of(&e), bad, "spec {spec:?}: {e}");
        }
    }

    #[test]
    fn caret_is_aligned_under_the_token() {
        let e = parse_brdf("ggx(alpha=0.1, g=sep)").unwrap_err();
        let s = e.to_string();
        let lines: Vec<&str> = s.lines().collect();
        assert_eq!(lines.len(), 3);
        let col = lines[2].find('^').unwrap();
        assert_eq!(&lines[1][col..col + 3], "sep");
        assert_eq!(lines[2].trim(), "^^^");
    }

    /// `kd=` on a microfacet spec adds the diffuse lobe `kd/π` (the form
    /// `radiometry fit --diffuse` prints); specs without it keep `kd = 0`.
    #[test]
    fn microfacet_kd() {
        assert_eq!(
            parse_brdf("ggx(alpha=0.3, fresnel=schlick(f0=0.9), kd=0.25)").unwrap(),
            BrdfSpec::Microfacet {
                distribution: Distribution::Ggx,
                alpha: 0.3,
                g: G2Kind::HeightCorrelated,
                fresnel: FresnelSpec::Schlick { f0: 0.9 },
                ms: MultipleScattering::Single,
                kd: 0.25
            }
        );
        for (spec, bad) in [
            ("ggx(alpha=0.1, kd=1.5)", "1.5"),
            ("beckmann(alpha=0.1, kd=-0.1)", "-0.1"),
            ("ggx(alpha=0.1, kd=0.1, kd=0.2)", "kd"),
            ("ggx(alpha=0.1, kd=nan)", "nan"),
        ] {
            let e = parse_brdf(spec).expect_err(spec);
            assert_eq!(caret_of(&e), bad, "spec {spec:?}: {e}");
        }
    }

    /// The rough diffuse plugins: names and parameters as scripts call them,
    /// the two roughness conventions kept apart, caret errors for bad values.
    #[test]
    fn rough_diffuse_specs() {
        assert_eq!(
            parse_brdf("eon(rho=0.8, sigma=0.5)").unwrap(),
            BrdfSpec::Eon {
                rho: [0.8; 3],
                sigma: 0.5
            }
        );
        assert_eq!(
            parse_brdf("fon(sigma=1)").unwrap(),
            BrdfSpec::Fon {
                rho: [1.0; 3],
                sigma: 1.0
            }
        );
        assert_eq!(
            parse_brdf("oren-nayar(rho=0.9, sigma_rad=0.35)").unwrap(),
            BrdfSpec::OrenNayar {
                rho: [0.9; 3],
                sigma_rad: 0.35
            }
        );
        assert_eq!(
            parse_brdf("oren-nayar(sigma_rad=1.2)").unwrap(),
            BrdfSpec::OrenNayar {
                rho: [1.0; 3],
                sigma_rad: 1.2
            }
        );
        for (spec, bad) in [
            ("eon(rho=0.5, sigma=1.5)", "1.5"),
            ("eon(rho=1.2, sigma=0.5)", "1.2"),
            ("fon(rho=0.5, sigma=-0.1)", "-0.1"),
            ("eon(rho=0.5)", "eon"),
            ("eon(rho=0.5, sigma_rad=0.3)", "sigma_rad"),
            ("fon(rho=0.5, sigma=nan)", "nan"),
            ("oren-nayar(rho=0.5, sigma=0.3)", "sigma"),
            ("oren-nayar(rho=0.5, sigma_rad=2)", "2"),
            ("oren-nayar(rho=1, sigma_rad=0.2)", "1"),
            ("oren-nayar(sigma_rad=0.2)", "oren-nayar"),
            ("oren_nayar(sigma_rad=0.2)", "oren_nayar"),
        ] {
            let e = parse_brdf(spec).expect_err(spec);
            assert_eq!(caret_of(&e), bad, "spec {spec:?}: {e}");
            assert!(e.to_string().contains('^'), "{e}");
        }
        let e = parse_brdf("oren-nayar(rho=1, sigma_rad=0.2)").unwrap_err();
        assert!(
            e.message.contains("energy gain") && e.message.contains("0.985"),
            "{e}"
        );
        // At the bound it is accepted.
        let max = radiometry_brdfs::OrenNayar::max_rho(0.2);
        assert!(parse_brdf(&format!("oren-nayar(rho={max}, sigma_rad=0.2)")).is_ok());
    }

    #[test]
    fn kd_plus_ks_constraint() {
        let e = parse_brdf("phong(exponent=10, ks=0.7, kd=0.5)").unwrap_err();
        assert!(e.message.contains("kd + ks"), "{e}");
        assert!(parse_brdf("phong(exponent=10, ks=0.5, kd=0.5)").is_ok());
    }
}
