//! The reflection layer of OpenPBR Surface as one plugin: [`OpenPbr`], built
//! from this crate's lobes and `radiometry::compose`.
//!
//! # The layer stack
//!
//! OpenPBR Surface 1.1 (Academy Software Foundation, 2024; §"Model") stacks
//! slabs and mixes them by weights. Restricted to reflection from an opaque,
//! isotropic surface, the stack is
//!
//! ```text
//! f        = fuzz over coated                                   (weight w_F)
//! coated   = mix(w_C, coat over substrate, substrate)
//! substrate= mix(m, metal, glossy-diffuse)
//! metal    = ξ_s · f_GGX(α_s; F82-tint(f0 = w_B C_B, t = C_s)),  Kulla–Conty compensated
//! glossy   = C_s ⊙ f_GGX(α_s; dielectric η_s) over f_EON(ρ = w_B C_B, σ = r_D)
//! coat     = f_GGX(α_c; dielectric η_c), absorption C_c
//! fuzz     = w_F · f_sheen(C_F, r_F)
//! ```
//!
//! where `A over B` is [`Coated`]'s albedo-scaled layering (reciprocal:
//! `f_A + t(ωi) t(ωo)(1 − E_min) f_B`, see its docs) and `α = r²` for every
//! roughness `r` (OpenPBR §"Specular"). The dielectric's index comes from
//! `specular_ior` and `specular_weight` as the specification defines it:
//!
//! ```text
//! η   = specular_ior / (1 + w_C (coat_ior − 1))         (eq. 60: the base's index relative to the coat)
//! F0  = ((η − 1)/(η + 1))²
//! ε   = sign(η − 1) √(min(ξ_s, 1/F0) F0),   η_s = (1 + ε)/(1 − ε)   (eq. 26: ξ_s scales F0)
//! ```
//!
//! `specular_color` `C_s` tints only the dielectric's reflection from above
//! (the base below sees `1 − E` of the untinted layer:
//! [`Coated::with_top_tint`]) and is the F82 tint of the metal.
//!
//! # Parameters
//!
//! [`OpenPbrParams`] has OpenPBR's names and defaults; colours are any
//! [`Spectrum`] (`f32`, RGB as `glam::Vec3`, sampled). Domains (checked by
//! [`OpenPbr::new`], [`BrdfError`] otherwise): every weight, colour channel,
//! roughness and `base_metalness` in `[0, 1]`; `specular_ior` and `coat_ior`
//! in `[1, 1000]`. Documented fallbacks, as a renderer needs them:
//!
//! * roughness 0 (a perfect mirror; OpenPBR allows it) is raised to the
//!   microfacet floor `α = 10⁻⁴` (`r = 0.01`);
//! * `fuzz_roughness` below 0.07 is raised to 0.07, the smallest the sheen
//!   tables cover ([`MIN_SHEEN_ROUGHNESS`]).
//!
//! # Outside a reflection-only isotropic BRDF
//!
//! These OpenPBR parameters have no counterpart here, and the plugin behaves
//! as if each were at the value in brackets: `transmission_weight` (0: the
//! dielectric base is opaque, its body is the EON diffuse),
//! `subsurface_weight` (0: likewise), `specular_anisotropy` and
//! `coat_anisotropy` (0: isotropic), `thin_film_weight` (0), `geometry_*`
//! (opaque, one-sided), `emission_*` (0), `coat_darkening` (0: the base is not
//! darkened by light trapped in the coat — OpenPBR's default is 1), the coat's
//! roughening of the base lobes (not applied), and `fuzz_weight`'s layering is
//! `Coated`'s reciprocal form rather than the specification's one-sided
//! `(1 − w_F E_F(ωo))`.
//!
//! # Energy
//!
//! Every piece keeps `E ≤ 1` (EON, the Kulla–Conty metal, `Coated`, `Mix`),
//! up to the error of the tops' reported albedos that `Coated` reads (see its
//! docs): the defaults stay below 1 at every `θo`, and a white metal
//! (`base_metalness = 1`, `base_color = specular_color = 1`) keeps at least
//! 99 % at `r ≤ 0.7` (`α ≤ 0.5`).
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
//! let wi = Vec3::new(-0.3, 0.2, 0.93).normalize();
//! assert_eq!(plastic.eval(wi, wo), plastic.eval(wo, wi)); // reciprocal
//! let s = plastic.sample(wo, [0.3, 0.6]).unwrap();
//! assert_eq!(s.pdf, plastic.pdf(s.wi, wo)); // bit for bit
//! assert!(plastic.directional_albedo(wo).value.max_element() < 1.0);
//! # Ok::<(), radiometry_brdfs::BrdfError>(())
//! ```

#[cfg(test)]
mod tests;

use crate::error::{BrdfError, check_range};
use crate::microfacet::{
    Achromatic, Dielectric, F82Tint, Ggx, HeightCorrelated, KullaConty, MAX_ETA, MIN_ALPHA, Microfacet,
};
use crate::rough_diffuse::Eon;
use crate::sheen::{MIN_SHEEN_ROUGHNESS, Sheen};
use radiometry::compose::{COATED_TABLE_NODES, Coated, ComposeError, Mix, Precomputed, Scaled};
use radiometry::glam::Vec3;
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
    /// `specular_ior` (default 1.5).
    pub specular_ior: f32,
    /// `coat_weight` `w_C` (default 0).
    pub coat_weight: f32,
    /// `coat_color` `C_c` (default 1): the coat's absorption (the square of
    /// its transmittance at normal incidence).
    pub coat_color: S,
    /// `coat_roughness` `r_c` (default 0): `α_c = r_c²`.
    pub coat_roughness: f32,
    /// `coat_ior` `η_c` (default 1.6).
    pub coat_ior: f32,
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
            fuzz_weight: 0.0,
            fuzz_color: S::splat(1.0),
            fuzz_roughness: 0.5,
        }
    }
}

type DielectricLobe<S> = Microfacet<Ggx, HeightCorrelated, Achromatic<Dielectric, S>>;
type Metal<S> = Precomputed<Scaled<KullaConty<Ggx, HeightCorrelated, F82Tint<S>>, S>>;
type Glossy<S> = Coated<DielectricLobe<S>, Eon<S>>;
type Substrate<S> = Mix<Metal<S>, Glossy<S>>;
type CoatMix<S> = Mix<Coated<DielectricLobe<S>, Substrate<S>>, Substrate<S>>;
type Stack<S> = Coated<Scaled<Sheen<S>, S>, CoatMix<S>>;

/// OpenPBR Surface's reflection: metal, glossy-diffuse (a dielectric
/// specular layer over EON), an optional coat and an optional fuzz, layered
/// by albedo scaling (see the [module docs](self) for the stack, the
/// formulas and what is outside a reflection-only BRDF).
///
/// Sampling picks layers and lobes in proportion to their albedos at `ωo`
/// (`radiometry::compose`), with the exact mixture density. A layer whose
/// weight is 0 costs nothing per call: `Mix` with weight 0 or 1 evaluates
/// one side, and a zero `fuzz_weight` skips the fuzz layer. Construction
/// tabulates each layer's top albedo once (three 128-node tables).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OpenPbr<S: Spectrum = f32> {
    params: OpenPbrParams<S>,
    stack: Stack<S>,
    fuzz: bool,
}

/// `α = max(r², 10⁻⁴)`.
fn alpha(r: f32) -> f32 {
    (r * r).max(MIN_ALPHA)
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
    let eps = libm::sqrtf(scaled).copysign(eta - 1.0);
    ((1.0 + eps) / (1.0 - eps)).clamp(crate::microfacet::MIN_ETA, MAX_ETA)
}

fn colour<S: Spectrum>(name: &'static str, c: S) -> Result<S, BrdfError> {
    for i in 0..S::CHANNELS {
        check_range(name, c.channel(i), 0.0, 1.0)?;
    }
    Ok(c)
}

fn composed(e: ComposeError) -> BrdfError {
    // Unreachable after the checks of `OpenPbr::new`; kept typed.
    let what = match e {
        ComposeError::CoatColor(_) => "coat_color outside [0, 1]",
        ComposeError::CoatIor(_) => "coat_ior below 1",
        _ => "a layer weight or colour outside [0, 1]",
    };
    BrdfError::Constraint { what }
}

/// The three albedo tables an [`OpenPbr`] reads at construction, as plain
/// data: each layer's top albedo at the [`COATED_TABLE_NODES`] nodes `μ_k =
/// (k/127)²` ([`Coated::table`]) and the largest error the top stated there
/// ([`Coated::top_error`]). [`OpenPbr::tables`] returns them,
/// [`OpenPbr::from_tables`] rebuilds the same material from them without
/// reading the tops' albedos again (the C API keeps them in its handle).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OpenPbrTables<S> {
    /// The glossy-diffuse layer's top: the dielectric specular lobe
    /// (`specular_roughness`, the index from `specular_ior`,
    /// `specular_weight` and `coat_weight`, `coat_ior`).
    pub specular: [S; COATED_TABLE_NODES],
    /// The largest error of [`specular`](Self::specular).
    pub specular_error: f32,
    /// The coat layer's top: the coat's dielectric lobe (`coat_roughness`,
    /// `coat_ior`).
    pub coat: [S; COATED_TABLE_NODES],
    /// The largest error of [`coat`](Self::coat).
    pub coat_error: f32,
    /// The fuzz layer's top: `fuzz_weight ·` the sheen lobe (`fuzz_color`,
    /// `fuzz_roughness`).
    pub fuzz: [S; COATED_TABLE_NODES],
    /// The largest error of [`fuzz`](Self::fuzz).
    pub fuzz_error: f32,
}

/// `Coated::new(top, base)`, or from the saved `table` (checked).
fn layer<T, B, S>(
    top: T,
    base: B,
    saved: Option<(&'static str, &[S; COATED_TABLE_NODES], f32)>,
) -> Result<Coated<T, B>, BrdfError>
where
    T: Brdf<Spectrum = S>,
    B: Brdf<Spectrum = S>,
    S: Spectrum,
{
    match saved {
        None => Ok(Coated::new(top, base)),
        Some((name, table, error)) => Coated::from_table(top, base, *table, error).map_err(|e| match e {
            ComposeError::AlbedoTable(value) => BrdfError::AlbedoTable { name, value },
            e => composed(e),
        }),
    }
}

impl<S: Spectrum> OpenPbr<S> {
    /// Builds the stack from `p`, reading each layer's top albedo at the
    /// [`COATED_TABLE_NODES`] nodes (three tables: about 1.7 ms with coat
    /// and fuzz on; [`OpenPbr::from_tables`] skips it).
    ///
    /// # Errors
    /// [`BrdfError::NotFinite`] / [`BrdfError::OutOfRange`] naming the
    /// OpenPBR parameter outside its domain (see the [module docs](self)).
    pub fn new(p: OpenPbrParams<S>) -> Result<Self, BrdfError> {
        Self::build(p, None)
    }

    /// The material [`OpenPbr::new`] builds from `p`, with the tops' albedo
    /// tables taken from `tables` (what [`OpenPbr::tables`] returned for
    /// the same parameters) instead of read again: equal to it, bit for bit,
    /// for about a tenth of the cost. What remains is the checks of `p` and
    /// of the 3 × 128 table entries, and the lobes' constructors, of which
    /// the metal's Kulla–Conty compensation (64 reads of the microfacet
    /// albedo table) is most: about 53 µs against 0.6 ms for `new`
    /// (monochrome, every layer on, release build on a loaded 2-core Xeon).
    ///
    /// Tables read for other parameters keep every guarantee but energy
    /// (the material is reciprocal and finite, and `pdf` matches `sample`;
    /// its energy bound holds for the albedos the tables state).
    ///
    /// # Errors
    /// As [`OpenPbr::new`] for `p`; [`BrdfError::AlbedoTable`] (`name` =
    /// `"specular"`, `"coat"` or `"fuzz"`) for a table value outside `[0,
    /// 1]` or NaN, or an error that is negative or not finite.
    pub fn from_tables(p: OpenPbrParams<S>, tables: &OpenPbrTables<S>) -> Result<Self, BrdfError> {
        Self::build(p, Some(tables))
    }

    /// The three tables of the tops' albedos this material read (or was
    /// given), for [`OpenPbr::from_tables`].
    pub fn tables(&self) -> OpenPbrTables<S> {
        let glossy = self.coated().second().second();
        let coat = self.coated().first();
        OpenPbrTables {
            specular: *glossy.table(),
            specular_error: glossy.top_error(),
            coat: *coat.table(),
            coat_error: coat.top_error(),
            fuzz: *self.stack.table(),
            fuzz_error: self.stack.top_error(),
        }
    }

    /// [`OpenPbr::new`] (`tables = None`) and [`OpenPbr::from_tables`].
    fn build(p: OpenPbrParams<S>, tables: Option<&OpenPbrTables<S>>) -> Result<Self, BrdfError> {
        let saved = |name, t: fn(&OpenPbrTables<S>) -> (&[S; COATED_TABLE_NODES], f32)| {
            tables.map(|tables| {
                let (table, error) = t(tables);
                (name, table, error)
            })
        };
        let unit = |name, v| check_range(name, v, 0.0, 1.0);
        let base_weight = unit("base_weight", p.base_weight)?;
        let base_color = colour("base_color", p.base_color)?;
        let metalness = unit("base_metalness", p.base_metalness)?;
        let sigma = unit("base_diffuse_roughness", p.base_diffuse_roughness)?;
        let xi = unit("specular_weight", p.specular_weight)?;
        let spec_color = colour("specular_color", p.specular_color)?;
        let r_s = unit("specular_roughness", p.specular_roughness)?;
        let ior = check_range("specular_ior", p.specular_ior, 1.0, MAX_ETA)?;
        let coat_weight = unit("coat_weight", p.coat_weight)?;
        let coat_color = colour("coat_color", p.coat_color)?;
        let r_c = unit("coat_roughness", p.coat_roughness)?;
        let coat_ior = check_range("coat_ior", p.coat_ior, 1.0, MAX_ETA)?;
        let fuzz_weight = unit("fuzz_weight", p.fuzz_weight)?;
        let fuzz_color = colour("fuzz_color", p.fuzz_color)?;
        let r_f = unit("fuzz_roughness", p.fuzz_roughness)?;

        let rho = base_color * base_weight;
        let ggx_s = Ggx::new(alpha(r_s))?;
        // The metal's albedo (a Fresnel average over 20 visible normals)
        // is read at every pick of every layer above it: tabulated once.
        let metal = Precomputed::new(
            Scaled::new(
                KullaConty::new(ggx_s, F82Tint::new(rho, spec_color)?),
                S::splat(xi),
            )
            .map_err(composed)?,
        );
        let eta = ior / (1.0 + coat_weight * (coat_ior - 1.0));
        let specular = Microfacet::new(ggx_s, Achromatic::new(Dielectric::new(modulated_ior(eta, xi))?));
        let glossy = layer(
            specular,
            Eon::new(rho, sigma)?,
            saved("specular", |t| (&t.specular, t.specular_error)),
        )?
        .with_top_tint(spec_color)
        .map_err(composed)?;
        let substrate = Mix::new(metalness, metal, glossy).map_err(composed)?;
        let coat = Microfacet::new(Ggx::new(alpha(r_c))?, Achromatic::new(Dielectric::new(coat_ior)?));
        // `Coated::with_absorption` is `Coated::new(..).absorbing(..)`.
        let coat_layer = layer(coat, substrate, saved("coat", |t| (&t.coat, t.coat_error)))?
            .absorbing(coat_color, coat_ior)
            .map_err(composed)?;
        let coated = Mix::new(coat_weight, coat_layer, substrate).map_err(composed)?;
        let fuzz = Scaled::new(
            Sheen::new(fuzz_color, r_f.max(MIN_SHEEN_ROUGHNESS))?,
            S::splat(fuzz_weight),
        )
        .map_err(composed)?;
        Ok(Self {
            params: p,
            stack: layer(fuzz, coated, saved("fuzz", |t| (&t.fuzz, t.fuzz_error)))?,
            fuzz: fuzz_weight > 0.0,
        })
    }

    /// The parameters it was built from.
    pub fn params(&self) -> &OpenPbrParams<S> {
        &self.params
    }

    /// The layers below the fuzz (the whole BRDF when `fuzz_weight = 0`).
    fn coated(&self) -> &CoatMix<S> {
        self.stack.base()
    }
}

impl<S: Spectrum> Brdf for OpenPbr<S> {
    type Spectrum = S;

    #[inline]
    fn eval(&self, wi: Vec3, wo: Vec3) -> S {
        if self.fuzz {
            self.stack.eval(wi, wo)
        } else {
            self.coated().eval(wi, wo)
        }
    }

    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<S>> {
        if self.fuzz {
            self.stack.sample(wo, u)
        } else {
            self.coated().sample(wo, u)
        }
    }

    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        if self.fuzz {
            self.stack.pdf(wi, wo)
        } else {
            self.coated().pdf(wi, wo)
        }
    }

    /// The layers' own batch kernels (equal to [`eval`](Brdf::eval) element
    /// by element).
    fn eval_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [S]) {
        if self.fuzz {
            self.stack.eval_batch(wi, wo, out)
        } else {
            self.coated().eval_batch(wi, wo, out)
        }
    }

    /// The layers' own `pdf_batch` kernels (equal to [`pdf`](Brdf::pdf)
    /// element by element).
    fn pdf_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]) {
        if self.fuzz {
            self.stack.pdf_batch(wi, wo, out)
        } else {
            self.coated().pdf_batch(wi, wo, out)
        }
    }

    /// `false`: `Coated` reads its tops' albedos from tables.
    fn is_smooth(&self) -> bool {
        false
    }

    fn directional_albedo(&self, wo: Vec3) -> Albedo<S> {
        if self.fuzz {
            self.stack.directional_albedo(wo)
        } else {
            self.coated().directional_albedo(wo)
        }
    }
}

impl<S: Spectrum> IsotropicBrdf for OpenPbr<S> {}
