//! BRDF plugins behind one plain C struct, [`RadBrdf`].
//!
//! A `RadBrdf` holds the plugin's validated parameters (no pointers, no heap);
//! each call rebuilds the concrete `radiometry-brdfs` type from them (a few
//! range comparisons — the struct lives in C memory, so it is re-checked rather
//! than trusted) and dispatches to it. Batched calls do this once per batch and
//! then run the plugin's own `eval_batch` / `pdf_batch` / `sample_batch`
//! kernels. Directions are in the local frame (normal +Z), pointing away from
//! the surface, unit length; `eval` is `f_r(ωi → ωo)` in 1/sr
//! (Nicodemus et al. 1977), zero when either direction is below the horizon.
//!
//! The formulas are those of the plugins: Lambertian `ρ/π`; modified Phong
//! (Lafortune & Willems 1994); normalised Blinn–Phong; microfacet
//! `D G2 F / (4 cos θi cos θo)` (Walter et al. 2007, eq. 20) with GGX or
//! Beckmann `D` and Smith `G2` (Heitz 2014, eqs. 98–99) and a Fresnel term
//! (Schlick, exact dielectric or conductor, F82-tint, a named metal); the
//! rough diffuse lobes EON and FON (Portsmouth, Kutz & Hill 2025) and the
//! classic Oren–Nayar (1994); the sheen of Estevez & Kulla (2017).
//! Compositions of these lobes are [`RadMaterial`](crate::RadMaterial)s.
//!
//! Colour: a `RadBrdf` keeps its colour parameters per channel (`rgb`, linear
//! sRGB) beside the monochrome ones (`params`, each colour as its Rec. 709
//! luminance; a named metal as the conductor fitted to the luminance of its
//! reflectance). `rad_brdf_eval`, `_pdf`, `_sample` and their batches run the
//! monochrome plugin (`f32`, the cheap path, today's values); the `_rgb`
//! functions run the RGB plugin (`glam::Vec3`) and write three floats per
//! value. A grey handle (every scalar constructor makes one) gives the
//! monochrome value on every channel.

use crate::ptr::{as_mut, as_ref, slice, slice_mut_disjoint, span};
use crate::{RadStatus, RadVec3};
use radiometry::batch::Vec3Soa;
use radiometry::glam::Vec3;
use radiometry::{Albedo, Brdf, BrdfSample, Spectrum};
use radiometry_brdfs::metals::Metal;
use radiometry_brdfs::microfacet::Achromatic;
use radiometry_brdfs::{
    Beckmann, BlinnPhong, Conductor, Dielectric, Eon, F82Tint, Fon, Fresnel, Ggx, HeightCorrelated,
    Lambertian, Microfacet, MicrofacetDistribution, ModifiedPhong, NoFresnel, OrenNayar, Schlick, Separable,
    ShadowingMasking, Sheen,
};

/// `RadBrdf::kind`: Lambertian, `params = {albedo}`.
pub const RAD_BRDF_LAMBERTIAN: u32 = 1;
/// `RadBrdf::kind`: modified Phong, `params = {kd, ks, exponent}`.
pub const RAD_BRDF_PHONG: u32 = 2;
/// `RadBrdf::kind`: normalised Blinn–Phong, `params = {kd, ks, exponent}`.
pub const RAD_BRDF_BLINN_PHONG: u32 = 3;
/// `RadBrdf::kind`: microfacet, `params = {alpha, fresnel_a, fresnel_b}`.
pub const RAD_BRDF_MICROFACET: u32 = 4;
/// `RadBrdf::kind`: energy-preserving Oren–Nayar (EON), `params = {rho, sigma}`.
pub const RAD_BRDF_EON: u32 = 5;
/// `RadBrdf::kind`: Fujii's improved Oren–Nayar (FON), `params = {rho, sigma}`.
pub const RAD_BRDF_FON: u32 = 6;
/// `RadBrdf::kind`: classic Oren–Nayar, `params = {rho, sigma_rad}`.
pub const RAD_BRDF_OREN_NAYAR: u32 = 7;
/// `RadBrdf::kind`: Charlie sheen, `params = {color, roughness}`.
pub const RAD_BRDF_SHEEN: u32 = 8;

/// Microfacet distribution: GGX / Trowbridge–Reitz.
pub const RAD_DISTRIBUTION_GGX: u32 = 0;
/// Microfacet distribution: Beckmann.
pub const RAD_DISTRIBUTION_BECKMANN: u32 = 1;
/// Smith shadowing–masking `G2 = 1/(1 + Λ(ωi) + Λ(ωo))`.
pub const RAD_SHADOWING_HEIGHT_CORRELATED: u32 = 0;
/// Smith shadowing–masking `G2 = G1(ωi) G1(ωo)`.
pub const RAD_SHADOWING_SEPARABLE: u32 = 1;
/// No Fresnel term (`F = 1`); `fresnel_a`, `fresnel_b` ignored.
pub const RAD_FRESNEL_NONE: u32 = 0;
/// Schlick's approximation; `fresnel_a = f0 ∈ [0, 1]`.
pub const RAD_FRESNEL_SCHLICK: u32 = 1;
/// Exact dielectric; `fresnel_a = η ∈ [1e-3, 1e3]`.
pub const RAD_FRESNEL_DIELECTRIC: u32 = 2;
/// Exact conductor; `fresnel_a = η ∈ [1e-3, 1e3]`, `fresnel_b = k ∈ [0, 1e3]`.
pub const RAD_FRESNEL_CONDUCTOR: u32 = 3;
/// F82-tint (OpenPBR's metal Fresnel, Hoffman 2019); `fresnel_a = f0 ∈ [0, 1]`
/// (reflectance at normal incidence), `fresnel_b = f82 ∈ [0, 1]` (the tint at
/// 82°; 1 is Schlick's approximation).
pub const RAD_FRESNEL_F82: u32 = 4;
/// Exact conductor of a named metal: `fresnel_a` = one of the `RAD_METAL_*`
/// ids (as a number: `(float)RAD_METAL_AU`), `fresnel_b` ignored. The
/// constructor fits the monochrome `η`, `k` whose Fresnel curve has the
/// luminance of the metal's measured reflectance at normal incidence and at
/// 82° (what the spec grammar's `conductor(metal=Au)` builds) and stores them
/// in `params[1]`, `params[2]`; per channel the `η`, `k` whose Fresnel curve
/// passes through the metal's reflectance reduced to linear sRGB (CIE 1931 2°
/// under D65) at the same two angles, in `rgb[0]` (`η`) and `rgb[1]` (`k`)
/// (`Conductor::<Vec3>::metal`); the id in `RadBrdf::metal`.
pub const RAD_FRESNEL_METAL: u32 = 5;

/// Gold (Johnson & Christy 1972), for [`RAD_FRESNEL_METAL`].
pub const RAD_METAL_AU: u32 = 1;
/// Silver (Johnson & Christy 1972).
pub const RAD_METAL_AG: u32 = 2;
/// Copper (Johnson & Christy 1972).
pub const RAD_METAL_CU: u32 = 3;
/// Aluminium (Rakić 1995).
pub const RAD_METAL_AL: u32 = 4;
/// Chromium (Johnson & Christy 1974).
pub const RAD_METAL_CR: u32 = 5;
/// Iron (Johnson & Christy 1974).
pub const RAD_METAL_FE: u32 = 6;
/// Nickel (Johnson & Christy 1974).
pub const RAD_METAL_NI: u32 = 7;
/// Titanium (Johnson & Christy 1974).
pub const RAD_METAL_TI: u32 = 8;
/// Platinum (Rakić et al. 1998).
pub const RAD_METAL_PT: u32 = 9;
/// Brass, Cu 70 % Zn 30 % (Querry 1985).
pub const RAD_METAL_BRASS: u32 = 10;

/// The metal of a `RAD_METAL_*` id.
fn metal(id: u32) -> Option<Metal> {
    Some(match id {
        RAD_METAL_AU => Metal::Au,
        RAD_METAL_AG => Metal::Ag,
        RAD_METAL_CU => Metal::Cu,
        RAD_METAL_AL => Metal::Al,
        RAD_METAL_CR => Metal::Cr,
        RAD_METAL_FE => Metal::Fe,
        RAD_METAL_NI => Metal::Ni,
        RAD_METAL_TI => Metal::Ti,
        RAD_METAL_PT => Metal::Pt,
        RAD_METAL_BRASS => Metal::Brass,
        _ => return None,
    })
}

/// A BRDF plugin: plain data (56 bytes, 4-byte aligned: fourteen 32-bit
/// fields), filled in by one of the `rad_brdf_*` constructors. Treat the
/// fields as read-only; a zeroed struct is an invalid handle
/// (`RAD_STATUS_BAD_HANDLE`). Every call re-validates the fields it uses (a
/// few range comparisons: `params` for the monochrome calls, `params` and
/// `rgb` for the `_rgb` calls) and rebuilds the plugin from them.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RadBrdf {
    /// One of the `RAD_BRDF_*` kinds.
    pub kind: u32,
    /// `RAD_DISTRIBUTION_*` (microfacet only).
    pub distribution: u32,
    /// `RAD_SHADOWING_*` (microfacet only).
    pub shadowing: u32,
    /// `RAD_FRESNEL_*` (microfacet only).
    pub fresnel: u32,
    /// `RAD_METAL_*` with `RAD_FRESNEL_METAL`; 0 otherwise.
    pub metal: u32,
    /// The monochrome parameters, by kind (see the `RAD_BRDF_*` constants;
    /// unused slots 0): a colour as its Rec. 709 luminance.
    pub params: [f32; 3],
    /// The colour parameters per channel (R, G, B, linear sRGB), for the
    /// `_rgb` calls: `rgb[0]` the albedo (Lambertian), `rho` (EON, FON,
    /// Oren–Nayar), the colour (sheen), `kd` (Phong, Blinn–Phong) or the
    /// Fresnel's first parameter (`f0`, `η`) of a microfacet BRDF; `rgb[1]`
    /// `ks` (Phong, Blinn–Phong) or the Fresnel's second parameter (`k`, the
    /// F82 tint). The scalar parameters (roughness, exponent, `σ`) are
    /// `params`' for both. Slots a kind does not use are 0, except that a
    /// microfacet BRDF without a coloured Fresnel term (none, dielectric)
    /// repeats its `fresnel_a`, `fresnel_b` there (unread).
    pub rgb: [[f32; 3]; 2],
}

/// One importance sample: `wi` drawn with density `pdf` (per steradian) and
/// Monte Carlo weight `weight = f_r(wi, wo) cos θi / pdf` per channel (R, G,
/// B; the monochrome calls write their one weight to all three). `pdf = 0`
/// (and `wi = weight = 0`) means the plugin returned no sample for this `wo,
/// u` (e.g. `wo` below the horizon).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RadBrdfSample {
    /// The sampled incident direction (unit, local frame).
    pub wi: RadVec3,
    /// Its solid-angle density (> 0 for a valid sample).
    pub pdf: f32,
    /// `f_r · cos θi / pdf`, per channel.
    pub weight: [f32; 3],
}

impl<S: Spectrum> From<Option<BrdfSample<S>>> for RadBrdfSample {
    #[inline]
    fn from(s: Option<BrdfSample<S>>) -> Self {
        s.map_or(RadBrdfSample::default(), |s| RadBrdfSample {
            wi: s.wi.into(),
            pdf: s.pdf,
            weight: [0, 1, 2].map(|c| s.weight.channel(c.min(S::CHANNELS - 1))),
        })
    }
}

/// The spectra the C API evaluates in: `f32` (monochrome, the handles'
/// `params`) and `Vec3` (RGB, their `rgb`).
pub(crate) trait Channels: Spectrum {
    /// A monochrome Fresnel term in this spectrum (itself, or on every channel).
    type Achromatic<F: Fresnel<Spectrum = f32>>: Fresnel<Spectrum = Self>;
    /// Wraps a monochrome Fresnel term.
    fn achromatic<F: Fresnel<Spectrum = f32>>(f: F) -> Self::Achromatic<F>;
    /// A colour parameter: the monochrome value or the channels.
    fn colour(mono: f32, rgb: [f32; 3]) -> Self;
}

impl Channels for f32 {
    type Achromatic<F: Fresnel<Spectrum = f32>> = F;
    #[inline]
    fn achromatic<F: Fresnel<Spectrum = f32>>(f: F) -> F {
        f
    }
    #[inline]
    fn colour(mono: f32, _: [f32; 3]) -> f32 {
        mono
    }
}

impl Channels for Vec3 {
    type Achromatic<F: Fresnel<Spectrum = f32>> = Achromatic<F, Vec3>;
    #[inline]
    fn achromatic<F: Fresnel<Spectrum = f32>>(f: F) -> Achromatic<F, Vec3> {
        Achromatic::new(f)
    }
    #[inline]
    fn colour(_: f32, rgb: [f32; 3]) -> Vec3 {
        Vec3::from_array(rgb)
    }
}

/// The Rec. 709 luminance `0.2126 R + 0.7152 G + 0.0722 B` of a linear
/// colour in `f32` (a grey colour is its value exactly): the monochrome value
/// of an RGB parameter.
#[inline]
pub(crate) fn luminance(c: [f32; 3]) -> f32 {
    if c[0] == c[1] && c[1] == c[2] {
        c[0]
    } else {
        0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
    }
}

/// Object-safe view of a plugin of spectrum `S` (one virtual call per C call).
pub(crate) trait DynBrdf<S = f32> {
    fn is_smooth(&self) -> bool;
    fn directional_albedo(&self, wo: Vec3) -> Albedo<S>;
    fn average_albedo(&self) -> S;
    fn eval(&self, wi: Vec3, wo: Vec3) -> S;
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32;
    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<S>>;
    fn eval_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [S]);
    fn eval_batch_soa(&self, wi: Vec3Soa<'_>, wo: Vec3Soa<'_>, out: &mut [S]);
    fn pdf_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]);
    fn sample_batch(&self, wo: &[Vec3], u: &[[f32; 2]], out: &mut [Option<BrdfSample<S>>]);
}

impl<S: Spectrum, B: Brdf<Spectrum = S>> DynBrdf<S> for B {
    fn is_smooth(&self) -> bool {
        Brdf::is_smooth(self)
    }
    fn directional_albedo(&self, wo: Vec3) -> Albedo<S> {
        Brdf::directional_albedo(self, wo)
    }
    fn average_albedo(&self) -> S {
        Brdf::average_albedo(self)
    }
    fn eval(&self, wi: Vec3, wo: Vec3) -> S {
        Brdf::eval(self, wi, wo)
    }
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        Brdf::pdf(self, wi, wo)
    }
    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<S>> {
        Brdf::sample(self, wo, u)
    }
    fn eval_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [S]) {
        Brdf::eval_batch(self, wi, wo, out)
    }
    fn eval_batch_soa(&self, wi: Vec3Soa<'_>, wo: Vec3Soa<'_>, out: &mut [S]) {
        Brdf::eval_batch_soa(self, wi, wo, out)
    }
    fn pdf_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]) {
        Brdf::pdf_batch(self, wi, wo, out)
    }
    fn sample_batch(&self, wo: &[Vec3], u: &[[f32; 2]], out: &mut [Option<BrdfSample<S>>]) {
        Brdf::sample_batch(self, wo, u, out)
    }
}

fn microfacet_g<S, D, G, R>(d: D, h: &RadBrdf, f: impl FnOnce(&dyn DynBrdf<S>) -> R) -> Result<R, RadStatus>
where
    S: Channels,
    D: MicrofacetDistribution,
    G: ShadowingMasking,
{
    fn run<S, D: MicrofacetDistribution, G: ShadowingMasking, F: Fresnel<Spectrum = S>, R>(
        d: D,
        fr: F,
        f: impl FnOnce(&dyn DynBrdf<S>) -> R,
    ) -> R
    where
        S: Channels,
    {
        f(&Microfacet::<D, G, F>::new(d, fr))
    }
    let [_, a, b] = h.params;
    let (ca, cb) = (S::colour(a, h.rgb[0]), S::colour(b, h.rgb[1]));
    Ok(match h.fresnel {
        RAD_FRESNEL_NONE => run::<S, D, G, _, R>(d, S::achromatic(NoFresnel), f),
        RAD_FRESNEL_SCHLICK => run::<S, D, G, _, R>(d, Schlick::new(ca)?, f),
        RAD_FRESNEL_DIELECTRIC => run::<S, D, G, _, R>(d, S::achromatic(Dielectric::new(a)?), f),
        RAD_FRESNEL_CONDUCTOR | RAD_FRESNEL_METAL => run::<S, D, G, _, R>(d, Conductor::new(ca, cb)?, f),
        RAD_FRESNEL_F82 => run::<S, D, G, _, R>(d, F82Tint::new(ca, cb)?, f),
        _ => return Err(RadStatus::UnknownKind),
    })
}

fn microfacet_d<S: Channels, D: MicrofacetDistribution, R>(
    d: D,
    h: &RadBrdf,
    f: impl FnOnce(&dyn DynBrdf<S>) -> R,
) -> Result<R, RadStatus> {
    // The metal id goes with the metal Fresnel only (its η, k are in `a`, `b`).
    if (h.fresnel == RAD_FRESNEL_METAL) != metal(h.metal).is_some() {
        return Err(RadStatus::BadHandle);
    }
    match h.shadowing {
        RAD_SHADOWING_HEIGHT_CORRELATED => microfacet_g::<S, D, HeightCorrelated, R>(d, h, f),
        RAD_SHADOWING_SEPARABLE => microfacet_g::<S, D, Separable, R>(d, h, f),
        _ => Err(RadStatus::UnknownKind),
    }
}

/// Builds the plugin that `h` describes in the spectrum `S` (validating every
/// parameter it uses: `params`, and `rgb` for `Vec3`) and runs `f` on it;
/// the plugin's constructor error otherwise.
pub(crate) fn with_plugin<S: Channels, R>(
    h: &RadBrdf,
    f: impl FnOnce(&dyn DynBrdf<S>) -> R,
) -> Result<R, RadStatus> {
    let [p0, p1, p2] = h.params;
    let (c0, c1) = (S::colour(p0, h.rgb[0]), S::colour(p1, h.rgb[1]));
    if h.kind != RAD_BRDF_MICROFACET && h.metal != 0 {
        return Err(RadStatus::BadHandle);
    }
    match h.kind {
        RAD_BRDF_LAMBERTIAN => Ok(f(&Lambertian::new(c0)?)),
        RAD_BRDF_EON => Ok(f(&Eon::new(c0, p1)?)),
        RAD_BRDF_FON => Ok(f(&Fon::new(c0, p1)?)),
        RAD_BRDF_OREN_NAYAR => Ok(f(&OrenNayar::new(c0, p1)?)),
        RAD_BRDF_SHEEN => Ok(f(&Sheen::new(c0, p1)?)),
        RAD_BRDF_PHONG => Ok(f(&ModifiedPhong::new(c0, c1, p2)?)),
        RAD_BRDF_BLINN_PHONG => Ok(f(&BlinnPhong::new(c0, c1, p2)?)),
        RAD_BRDF_MICROFACET => match h.distribution {
            RAD_DISTRIBUTION_GGX => microfacet_d(Ggx::new(p0)?, h, f),
            RAD_DISTRIBUTION_BECKMANN => microfacet_d(Beckmann::new(p0)?, h, f),
            _ => Err(RadStatus::UnknownKind),
        },
        _ => Err(RadStatus::BadHandle),
    }
}

/// Checks the colour parameters of a handle whose monochrome form is valid
/// (`with_plugin::<f32>` succeeded): the RGB plugin's constructor per kind, as
/// `with_plugin::<Vec3>` would run it, without building the plugin behind a
/// `dyn` (a monochrome-only firmware image then links no `Vec3` plugin
/// methods, only their parameter checks).
pub(crate) fn check_rgb(h: &RadBrdf) -> Result<(), RadStatus> {
    let [_, p1, p2] = h.params;
    let (c0, c1) = (Vec3::from_array(h.rgb[0]), Vec3::from_array(h.rgb[1]));
    match h.kind {
        RAD_BRDF_LAMBERTIAN => Lambertian::new(c0).map(drop)?,
        RAD_BRDF_EON => Eon::new(c0, p1).map(drop)?,
        RAD_BRDF_FON => Fon::new(c0, p1).map(drop)?,
        RAD_BRDF_OREN_NAYAR => OrenNayar::new(c0, p1).map(drop)?,
        RAD_BRDF_SHEEN => Sheen::new(c0, p1).map(drop)?,
        RAD_BRDF_PHONG => ModifiedPhong::new(c0, c1, p2).map(drop)?,
        RAD_BRDF_BLINN_PHONG => BlinnPhong::new(c0, c1, p2).map(drop)?,
        RAD_BRDF_MICROFACET => match h.fresnel {
            RAD_FRESNEL_SCHLICK => Schlick::new(c0).map(drop)?,
            RAD_FRESNEL_CONDUCTOR | RAD_FRESNEL_METAL => Conductor::new(c0, c1).map(drop)?,
            RAD_FRESNEL_F82 => F82Tint::new(c0, c1).map(drop)?,
            _ => (),
        },
        _ => return Err(RadStatus::BadHandle),
    }
    Ok(())
}

/// As [`with_plugin`], through one shared instance of the plugin tree (the
/// callback behind `&mut dyn FnMut`): for callers with many closures (the
/// materials), where a copy of the tree per closure would cost firmware
/// flash. [`with_plugin`] itself is generic so that a `RadBrdf` call runs
/// its plugin's methods directly (and links only the methods it calls).
pub(crate) fn with_plugin_shared<S: Channels, R>(
    h: &RadBrdf,
    f: impl FnOnce(&dyn DynBrdf<S>) -> R,
) -> Result<R, RadStatus> {
    let (mut f, mut out) = (Some(f), None);
    let visit: &mut dyn FnMut(&dyn DynBrdf<S>) = &mut |b| {
        if let Some(f) = f.take() {
            out = Some(f(b));
        }
    };
    with_plugin(h, visit)?;
    // `with_plugin` calls back exactly once when it succeeds.
    out.ok_or(RadStatus::BadHandle)
}

/// Validates `h` and, on success, writes it to `out`.
///
/// # Safety
/// `out` is null or points to a writable `RadBrdf`.
unsafe fn construct(h: RadBrdf, out: *mut RadBrdf) -> RadStatus {
    // SAFETY: forwarded caller contract.
    let out = match unsafe { as_mut(out) } {
        Ok(o) => o,
        Err(s) => return s,
    };
    // Both forms: the monochrome parameters and the channels.
    match with_plugin::<f32, _>(&h, |_| ()).and_then(|()| check_rgb(&h)) {
        Ok(()) => {
            *out = h;
            RadStatus::Ok
        }
        Err(s) => s,
    }
}

/// Reads the three floats of an RGB colour argument.
///
/// # Safety
/// `p` is null or points to 3 readable `float`s.
unsafe fn rgb_arg(p: *const f32) -> Result<[f32; 3], RadStatus> {
    // SAFETY: forwarded caller contract.
    let s = unsafe { slice(p, 3)? };
    match *s {
        [r, g, b] => Ok([r, g, b]),
        _ => Err(RadStatus::NullPointer),
    }
}

/// A handle of `kind` with the colour `rgb` (its luminance in `params[0]`)
/// and the scalar `p1`, validated and written to `out`.
///
/// # Safety
/// `rgb` is null or points to 3 readable `float`s; `out` is null or points to
/// a writable `RadBrdf`.
unsafe fn construct_rgb(kind: u32, rgb: *const f32, p1: f32, out: *mut RadBrdf) -> RadStatus {
    // SAFETY: forwarded caller contract (the colour is copied before `out` is borrowed).
    let c = match unsafe { rgb_arg(rgb) } {
        Ok(c) => c,
        Err(s) => return s,
    };
    let h = RadBrdf {
        kind,
        params: [luminance(c), p1, 0.0],
        rgb: [c, [0.0; 3]],
        ..RadBrdf::default()
    };
    // SAFETY: forwarded caller contract.
    unsafe { construct(h, out) }
}

/// Lambertian BRDF `f_r = ρ/π` (Lambert 1760), albedo `ρ ∈ [0, 1]`.
///
/// # Safety
/// `out` is null or points to a writable `RadBrdf` (unchanged on error).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_brdf_lambertian(albedo: f32, out: *mut RadBrdf) -> RadStatus {
    let h = RadBrdf {
        kind: RAD_BRDF_LAMBERTIAN,
        params: [albedo, 0.0, 0.0],
        rgb: [[albedo; 3], [0.0; 3]],
        ..RadBrdf::default()
    };
    // SAFETY: forwarded caller contract.
    unsafe { construct(h, out) }
}

/// Modified Phong (Lafortune & Willems 1994):
/// `f_r = kd/π + ks (n+2)/(2π) max(0, ωi·r(ωo))ⁿ`, `exponent n ∈ [0, 1e7]`,
/// `kd, ks ∈ [0, 1]`, `kd + ks ≤ 1`.
///
/// # Safety
/// `out` is null or points to a writable `RadBrdf` (unchanged on error).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_brdf_phong(exponent: f32, ks: f32, kd: f32, out: *mut RadBrdf) -> RadStatus {
    let h = RadBrdf {
        kind: RAD_BRDF_PHONG,
        params: [kd, ks, exponent],
        rgb: [[kd; 3], [ks; 3]],
        ..RadBrdf::default()
    };
    // SAFETY: forwarded caller contract.
    unsafe { construct(h, out) }
}

/// Normalised Blinn–Phong, `kd/π + ks · c(n) · cos θhⁿ` with the exact
/// energy normalisation `c(n)` of the plugin (`radiometry_brdfs::BlinnPhong`);
/// same ranges as [`rad_brdf_phong`].
///
/// # Safety
/// `out` is null or points to a writable `RadBrdf` (unchanged on error).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_brdf_blinn_phong(
    exponent: f32,
    ks: f32,
    kd: f32,
    out: *mut RadBrdf,
) -> RadStatus {
    let h = RadBrdf {
        kind: RAD_BRDF_BLINN_PHONG,
        params: [kd, ks, exponent],
        rgb: [[kd; 3], [ks; 3]],
        ..RadBrdf::default()
    };
    // SAFETY: forwarded caller contract.
    unsafe { construct(h, out) }
}

/// Microfacet BRDF `D(h) G2(ωi, ωo) F(ωo·h) / (4 cos θi cos θo)` (Walter et al.
/// 2007, eq. 20): `distribution` = `RAD_DISTRIBUTION_GGX | _BECKMANN` with
/// roughness `alpha ∈ [1e-4, 1]`, `shadowing` = `RAD_SHADOWING_*`, `fresnel` =
/// `RAD_FRESNEL_*` with its parameters in `fresnel_a`, `fresnel_b` (see the
/// constants): e.g. `RAD_FRESNEL_F82` with `f0, f82`, or `RAD_FRESNEL_METAL`
/// with `fresnel_a = RAD_METAL_AU` (an unknown id is
/// `RAD_STATUS_UNKNOWN_KIND`). A named metal is fitted here, once (a few
/// hundred Fresnel evaluations over the metal's measured spectrum); the
/// handle keeps the fitted `η`, `k`.
///
/// # Safety
/// `out` is null or points to a writable `RadBrdf` (unchanged on error).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_brdf_microfacet(
    distribution: u32,
    alpha: f32,
    shadowing: u32,
    fresnel: u32,
    fresnel_a: f32,
    fresnel_b: f32,
    out: *mut RadBrdf,
) -> RadStatus {
    let mut h = RadBrdf {
        kind: RAD_BRDF_MICROFACET,
        distribution,
        shadowing,
        fresnel,
        metal: 0,
        params: [alpha, fresnel_a, fresnel_b],
        rgb: [[fresnel_a; 3], [fresnel_b; 3]],
    };
    if fresnel == RAD_FRESNEL_METAL {
        if !fresnel_a.is_finite() {
            return RadStatus::NotFinite;
        }
        // An integral id in 1..=10; `as` saturates, so any other value
        // either fails the round trip or names no metal.
        let id = fresnel_a as u32;
        let Some(m) = metal(id).filter(|_| id as f32 == fresnel_a) else {
            return RadStatus::UnknownKind;
        };
        let c = Conductor::metal_luminance(m);
        let rgb = Conductor::<Vec3>::metal(m);
        h.metal = id;
        h.params = [alpha, c.eta(), c.k()];
        h.rgb = [rgb.eta().to_array(), rgb.k().to_array()];
    }
    // SAFETY: forwarded caller contract.
    unsafe { construct(h, out) }
}

/// Energy-preserving Oren–Nayar, "EON" (Portsmouth, Kutz & Hill, JCGT 14(1),
/// 2025, listing 1 with the exact FON albedo; as OpenPBR Surface 1.1
/// specifies it, without the printed spec's extra `1/π` in `ρ_ms`):
///
/// ```text
/// f    = f_FON + (ρ_ms/π) (1 − E_FON(μi)) (1 − E_FON(μo)) / (1 − Ē_FON)
/// ρ_ms = ρ² Ē_FON / (1 − ρ (1 − Ē_FON)),   Ē_FON = A (1 + (2/3 − 28/(15π)) σ)
/// ```
///
/// (`f_FON` as [`rad_brdf_fon`]), albedo colour `rho ∈ [0, 1]`, roughness
/// `sigma ∈ [0, 1]` (dimensionless, OpenPBR's `base_diffuse_roughness`).
/// With `rho = 1` its directional albedo is 1 at every view.
///
/// # Safety
/// `out` is null or points to a writable `RadBrdf` (unchanged on error).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_brdf_eon(rho: f32, sigma: f32, out: *mut RadBrdf) -> RadStatus {
    let h = RadBrdf {
        kind: RAD_BRDF_EON,
        params: [rho, sigma, 0.0],
        rgb: [[rho; 3], [0.0; 3]],
        ..RadBrdf::default()
    };
    // SAFETY: forwarded caller contract.
    unsafe { construct(h, out) }
}

/// Fujii's improved Oren–Nayar, "FON" (Fujii 2012, in the normalisation of
/// Portsmouth, Kutz & Hill 2025, listing 1 — EON's single-scattering term):
///
/// ```text
/// f = (ρ/π) A (1 + σ s/t),   A = 1/(1 + (1/2 − 2/(3π)) σ),
/// s = ωi·ωo − μi μo,         t = max(μi, μo) if s > 0, else 1,
/// ```
///
/// `rho ∈ [0, 1]`, `sigma ∈ [0, 1]` (dimensionless). Loses energy with
/// roughness (22 % at `σ = 1`, normal view), which EON gives back.
///
/// # Safety
/// `out` is null or points to a writable `RadBrdf` (unchanged on error).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_brdf_fon(rho: f32, sigma: f32, out: *mut RadBrdf) -> RadStatus {
    let h = RadBrdf {
        kind: RAD_BRDF_FON,
        params: [rho, sigma, 0.0],
        rgb: [[rho; 3], [0.0; 3]],
        ..RadBrdf::default()
    };
    // SAFETY: forwarded caller contract.
    unsafe { construct(h, out) }
}

/// The classic qualitative Oren–Nayar (Oren & Nayar 1994, as pbrt-v3 has it):
/// `f = ρ/π (A + B max(0, cos(φi − φo)) sin α tan β)`, `A = 1 − σ²/(2(σ² +
/// 0.33))`, `B = 0.45 σ²/(σ² + 0.09)`, with the roughness `sigma_rad ∈ [0,
/// π/2]` in **radians** (the standard deviation of the facet slope angle; not
/// EON's dimensionless σ) and `rho ∈ [0, 1]` at most `1/(A + B/2)` (above,
/// its albedo exceeds 1 at grazing view: `RAD_STATUS_CONSTRAINT`).
///
/// # Safety
/// `out` is null or points to a writable `RadBrdf` (unchanged on error).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_brdf_oren_nayar(rho: f32, sigma_rad: f32, out: *mut RadBrdf) -> RadStatus {
    let h = RadBrdf {
        kind: RAD_BRDF_OREN_NAYAR,
        params: [rho, sigma_rad, 0.0],
        rgb: [[rho; 3], [0.0; 3]],
        ..RadBrdf::default()
    };
    // SAFETY: forwarded caller contract.
    unsafe { construct(h, out) }
}

/// Microfacet sheen (Estevez & Kulla 2017, "Production Friendly Microfacet
/// Sheen BRDF", eq. 1 with `F = 1`): `f = color · D(h) / (4 μi μo (1 +
/// Λ(μi) + Λ(μo)))` with the "Charlie" distribution `D = (2 + 1/r)
/// sin(θh)^(1/r) / (2π)` and the paper's fitted `Λ` (without its
/// non-reciprocal terminator softening); `color ∈ [0, 1]`, `roughness r ∈
/// [0.07, 1]` (the range of the lobe's albedo table). Sampled uniformly
/// over the hemisphere.
///
/// # Safety
/// `out` is null or points to a writable `RadBrdf` (unchanged on error).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_brdf_sheen(color: f32, roughness: f32, out: *mut RadBrdf) -> RadStatus {
    let h = RadBrdf {
        kind: RAD_BRDF_SHEEN,
        params: [color, roughness, 0.0],
        rgb: [[color; 3], [0.0; 3]],
        ..RadBrdf::default()
    };
    // SAFETY: forwarded caller contract.
    unsafe { construct(h, out) }
}

/// [`rad_brdf_lambertian`] with an RGB albedo `albedo[3]`, each channel in
/// `[0, 1]` (the monochrome calls use its Rec. 709 luminance).
///
/// # Safety
/// `albedo` is null or points to 3 readable `float`s; `out` is null or points
/// to a writable `RadBrdf` (unchanged on error).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_brdf_lambertian_rgb(albedo: *const f32, out: *mut RadBrdf) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { construct_rgb(RAD_BRDF_LAMBERTIAN, albedo, 0.0, out) }
}

/// [`rad_brdf_microfacet`] with coloured Fresnel parameters: `fresnel` is
/// `RAD_FRESNEL_SCHLICK` (`fresnel_a[3]` = `f0` per channel, `fresnel_b`
/// unused, may be null), `RAD_FRESNEL_CONDUCTOR` (`fresnel_a[3]` = `η`,
/// `fresnel_b[3]` = `k` per channel, as RGB renderers tabulate metals) or
/// `RAD_FRESNEL_F82` (`f0[3]`, the tint `f82[3]`); any other Fresnel is
/// `RAD_STATUS_UNKNOWN_KIND` (`rad_brdf_microfacet` takes them, and
/// `RAD_FRESNEL_METAL` for a measured metal). The monochrome calls use the
/// Rec. 709 luminance of each parameter triple (for a conductor a stand-in,
/// not a reduction of its reflectance: prefer `RAD_FRESNEL_METAL` where the
/// monochrome value matters).
///
/// # Safety
/// `fresnel_a` is null or points to 3 readable `float`s, as `fresnel_b`
/// (null allowed with Schlick); `out` is null or points to a writable
/// `RadBrdf` (unchanged on error).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_brdf_microfacet_rgb(
    distribution: u32,
    alpha: f32,
    shadowing: u32,
    fresnel: u32,
    fresnel_a: *const f32,
    fresnel_b: *const f32,
    out: *mut RadBrdf,
) -> RadStatus {
    if !matches!(
        fresnel,
        RAD_FRESNEL_SCHLICK | RAD_FRESNEL_CONDUCTOR | RAD_FRESNEL_F82
    ) {
        return RadStatus::UnknownKind;
    }
    // SAFETY: forwarded caller contract (the colours are copied before `out` is borrowed).
    let a = match unsafe { rgb_arg(fresnel_a) } {
        Ok(c) => c,
        Err(s) => return s,
    };
    let b = if fresnel == RAD_FRESNEL_SCHLICK && fresnel_b.is_null() {
        [0.0; 3]
    } else {
        // SAFETY: as above.
        match unsafe { rgb_arg(fresnel_b) } {
            Ok(c) => c,
            Err(s) => return s,
        }
    };
    let h = RadBrdf {
        kind: RAD_BRDF_MICROFACET,
        distribution,
        shadowing,
        fresnel,
        metal: 0,
        params: [alpha, luminance(a), luminance(b)],
        rgb: [a, b],
    };
    // SAFETY: forwarded caller contract.
    unsafe { construct(h, out) }
}

/// [`rad_brdf_eon`] with an RGB albedo colour `rho[3]` (each channel a lobe).
///
/// # Safety
/// As [`rad_brdf_lambertian_rgb`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_brdf_eon_rgb(rho: *const f32, sigma: f32, out: *mut RadBrdf) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { construct_rgb(RAD_BRDF_EON, rho, sigma, out) }
}

/// [`rad_brdf_fon`] with an RGB albedo colour `rho[3]`.
///
/// # Safety
/// As [`rad_brdf_lambertian_rgb`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_brdf_fon_rgb(rho: *const f32, sigma: f32, out: *mut RadBrdf) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { construct_rgb(RAD_BRDF_FON, rho, sigma, out) }
}

/// [`rad_brdf_oren_nayar`] with an RGB albedo colour `rho[3]` (every channel
/// within the energy bound).
///
/// # Safety
/// As [`rad_brdf_lambertian_rgb`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_brdf_oren_nayar_rgb(
    rho: *const f32,
    sigma_rad: f32,
    out: *mut RadBrdf,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { construct_rgb(RAD_BRDF_OREN_NAYAR, rho, sigma_rad, out) }
}

/// [`rad_brdf_sheen`] with an RGB colour `color[3]`.
///
/// # Safety
/// As [`rad_brdf_lambertian_rgb`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_brdf_sheen_rgb(
    color: *const f32,
    roughness: f32,
    out: *mut RadBrdf,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { construct_rgb(RAD_BRDF_SHEEN, color, roughness, out) }
}

fn status(r: Result<(), RadStatus>) -> RadStatus {
    r.err().unwrap_or(RadStatus::Ok)
}

/// A C handle that describes a BRDF ([`RadBrdf`],
/// [`RadMaterial`](crate::RadMaterial), [`RadOpenPbr`](crate::RadOpenPbr)):
/// validates its fields, rebuilds the BRDF in the spectrum `S` (`f32`:
/// monochrome; `Vec3`: RGB) and runs `f` on it.
pub(crate) trait Handle {
    fn with<S: Channels, R>(&self, f: impl FnOnce(&dyn DynBrdf<S>) -> R) -> Result<R, RadStatus>;
}

impl Handle for RadBrdf {
    #[inline]
    fn with<S: Channels, R>(&self, f: impl FnOnce(&dyn DynBrdf<S>) -> R) -> Result<R, RadStatus> {
        with_plugin(self, f)
    }
}

/// The body of `rad_*_eval`.
///
/// # Safety
/// `h` is null or points to a readable `H`; `out` is null or points to a
/// writable `float`.
pub(crate) unsafe fn eval_one<H: Handle>(h: *const H, wi: RadVec3, wo: RadVec3, out: *mut f32) -> RadStatus {
    status((|| {
        // SAFETY: forwarded caller contract.
        let (h, out) = unsafe { (as_ref(h)?, as_mut(out)?) };
        *out = h.with::<f32, _>(|b| b.eval(wi.into(), wo.into()))?;
        Ok(())
    })())
}

/// The body of `rad_*_pdf`.
///
/// # Safety
/// As [`eval_one`].
pub(crate) unsafe fn pdf_one<H: Handle>(h: *const H, wi: RadVec3, wo: RadVec3, out: *mut f32) -> RadStatus {
    status((|| {
        // SAFETY: forwarded caller contract.
        let (h, out) = unsafe { (as_ref(h)?, as_mut(out)?) };
        *out = h.with::<f32, _>(|b| b.pdf(wi.into(), wo.into()))?;
        Ok(())
    })())
}

/// The body of `rad_*_sample`.
///
/// # Safety
/// `h` is null or points to a readable `H`; `out` is null or points to a
/// writable `RadBrdfSample`.
pub(crate) unsafe fn sample_one<H: Handle>(
    h: *const H,
    wo: RadVec3,
    u: [f32; 2],
    out: *mut RadBrdfSample,
) -> RadStatus {
    status((|| {
        // SAFETY: forwarded caller contract.
        let (h, out) = unsafe { (as_ref(h)?, as_mut(out)?) };
        *out = h.with::<f32, _>(|b| b.sample(wo.into(), u))?.into();
        Ok(())
    })())
}

/// `*out = f_r(wi → wo)` in 1/sr.
///
/// # Safety
/// `brdf` is null or points to a readable `RadBrdf`; `out` is null or points
/// to a writable `float`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_brdf_eval(
    brdf: *const RadBrdf,
    wi: RadVec3,
    wo: RadVec3,
    out: *mut f32,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { eval_one(brdf, wi, wo, out) }
}

/// `*out` = the solid-angle density with which [`rad_brdf_sample`] draws `wi`
/// given `wo`.
///
/// # Safety
/// As [`rad_brdf_eval`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_brdf_pdf(
    brdf: *const RadBrdf,
    wi: RadVec3,
    wo: RadVec3,
    out: *mut f32,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { pdf_one(brdf, wi, wo, out) }
}

/// Importance-samples `wi` for `wo` from the uniform pair `(u0, u1) ∈ [0, 1)²`
/// (see [`RadBrdfSample`] for the no-sample convention).
///
/// # Safety
/// `brdf` is null or points to a readable `RadBrdf`; `out` is null or points
/// to a writable `RadBrdfSample`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_brdf_sample(
    brdf: *const RadBrdf,
    wo: RadVec3,
    u0: f32,
    u1: f32,
    out: *mut RadBrdfSample,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { sample_one(brdf, wo, [u0, u1], out) }
}

/// Views `[RadVec3]` as `[Vec3]`.
fn as_vec3(v: &[RadVec3]) -> &[Vec3] {
    // SAFETY: `RadVec3` and `glam::Vec3` are both `#[repr(C)]` structs of
    // three `f32` named x, y, z in that order (size and alignment asserted
    // equal in `ptr.rs`), so the pointer and length describe the same
    // initialised memory as `[Vec3]`; the lifetime is carried over.
    unsafe { core::slice::from_raw_parts(v.as_ptr().cast::<Vec3>(), v.len()) }
}

/// Shared argument handling of the two-direction batch calls
/// (`rad_*_eval_batch`, `rad_*_pdf_batch`).
///
/// # Safety
/// As [`rad_brdf_eval_batch`].
pub(crate) unsafe fn pair_batch<H: Handle, S: Channels>(
    h: *const H,
    wi: *const RadVec3,
    wo: *const RadVec3,
    out: *mut f32,
    n: usize,
    run: impl FnOnce(&dyn DynBrdf<S>, &[Vec3], &[Vec3], &mut [f32]),
) -> RadStatus {
    status((|| {
        // SAFETY: forwarded caller contract.
        let (h, wi, wo) = unsafe { (as_ref(h)?, slice(wi, n)?, slice(wo, n)?) };
        // SAFETY: forwarded caller contract; `out` is checked to overlap
        // neither input.
        let out = unsafe { slice_mut_disjoint(out, n, &[span(wi), span(wo)])? };
        h.with::<S, _>(|b| run(b, as_vec3(wi), as_vec3(wo), out))
    })())
}

/// `[f32]` of `3n` floats viewed as `[Vec3]` of `n` (RGB values).
fn as_rgb_mut(v: &mut [f32]) -> &mut [Vec3] {
    let n = v.len() / 3;
    // SAFETY: `glam::Vec3` is a `#[repr(C)]` struct of three `f32` (size 12,
    // alignment 4, asserted in `ptr.rs`), so `3n` initialised, exclusively
    // borrowed floats are `n` `Vec3`s; the lifetime is carried over.
    unsafe { core::slice::from_raw_parts_mut(v.as_mut_ptr().cast::<Vec3>(), n) }
}

/// The body of `rad_*_eval_batch_rgb`: `out` holds `3n` floats (R, G, B of
/// each value).
///
/// # Safety
/// As [`rad_brdf_eval_batch_rgb`].
pub(crate) unsafe fn eval_batch_rgb<H: Handle>(
    h: *const H,
    wi: *const RadVec3,
    wo: *const RadVec3,
    out: *mut f32,
    n: usize,
) -> RadStatus {
    status((|| {
        // SAFETY: forwarded caller contract.
        let (h, wi, wo) = unsafe { (as_ref(h)?, slice(wi, n)?, slice(wo, n)?) };
        let len = n.checked_mul(3).ok_or(RadStatus::TooLong)?;
        // SAFETY: forwarded caller contract; `out` is checked to overlap
        // neither input.
        let out = unsafe { slice_mut_disjoint(out, len, &[span(wi), span(wo)])? };
        h.with::<Vec3, _>(|b| b.eval_batch(as_vec3(wi), as_vec3(wo), as_rgb_mut(out)))
    })())
}

/// The body of `rad_*_eval_rgb`: `out` holds 3 floats.
///
/// # Safety
/// `h` is null or points to a readable `H`; `out` is null or points to 3
/// writable `float`s.
pub(crate) unsafe fn eval_one_rgb<H: Handle>(
    h: *const H,
    wi: RadVec3,
    wo: RadVec3,
    out: *mut f32,
) -> RadStatus {
    status((|| {
        // SAFETY: forwarded caller contract.
        let (h, out) = unsafe { (as_ref(h)?, slice_mut_disjoint(out, 3, &[])?) };
        let f = h.with::<Vec3, _>(|b| b.eval(wi.into(), wo.into()))?;
        out.copy_from_slice(&f.to_array());
        Ok(())
    })())
}

/// The body of `rad_*_pdf_rgb`: the density of the RGB form's sampling.
///
/// # Safety
/// As [`eval_one`].
pub(crate) unsafe fn pdf_one_rgb<H: Handle>(
    h: *const H,
    wi: RadVec3,
    wo: RadVec3,
    out: *mut f32,
) -> RadStatus {
    status((|| {
        // SAFETY: forwarded caller contract.
        let (h, out) = unsafe { (as_ref(h)?, as_mut(out)?) };
        *out = h.with::<Vec3, _>(|b| b.pdf(wi.into(), wo.into()))?;
        Ok(())
    })())
}

/// The body of `rad_*_sample_rgb`.
///
/// # Safety
/// As [`sample_one`].
pub(crate) unsafe fn sample_one_rgb<H: Handle>(
    h: *const H,
    wo: RadVec3,
    u: [f32; 2],
    out: *mut RadBrdfSample,
) -> RadStatus {
    status((|| {
        // SAFETY: forwarded caller contract.
        let (h, out) = unsafe { (as_ref(h)?, as_mut(out)?) };
        *out = h.with::<Vec3, _>(|b| b.sample(wo.into(), u))?.into();
        Ok(())
    })())
}

/// `out[k] = f_r(wi[k] → wo[k])` for `k < n`, through the plugin's batch
/// kernel (the SIMD one when the library is built with `simd`).
///
/// # Safety
/// `brdf` points to a readable `RadBrdf`; `wi`, `wo` to `n` readable
/// `RadVec3`; `out` to `n` writable `float`s not overlapping the inputs
/// (checked: `RAD_STATUS_OVERLAP`). Null pointers are reported, not
/// dereferenced.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_brdf_eval_batch(
    brdf: *const RadBrdf,
    wi: *const RadVec3,
    wo: *const RadVec3,
    out: *mut f32,
    n: usize,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { pair_batch::<_, f32>(brdf, wi, wo, out, n, |b, wi, wo, out| b.eval_batch(wi, wo, out)) }
}

/// `out[k] = pdf(wi[k], wo[k])` for `k < n`.
///
/// # Safety
/// As [`rad_brdf_eval_batch`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_brdf_pdf_batch(
    brdf: *const RadBrdf,
    wi: *const RadVec3,
    wo: *const RadVec3,
    out: *mut f32,
    n: usize,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { pair_batch::<_, f32>(brdf, wi, wo, out, n, |b, wi, wo, out| b.pdf_batch(wi, wo, out)) }
}

/// The body of `rad_*_eval_batch_soa`.
///
/// # Safety
/// As [`rad_brdf_eval_batch_soa`].
#[allow(clippy::too_many_arguments)]
pub(crate) unsafe fn soa_batch<H: Handle>(
    h: *const H,
    wi_x: *const f32,
    wi_y: *const f32,
    wi_z: *const f32,
    wo_x: *const f32,
    wo_y: *const f32,
    wo_z: *const f32,
    out: *mut f32,
    n: usize,
) -> RadStatus {
    status((|| {
        // SAFETY: forwarded caller contract.
        let h = unsafe { as_ref(h)? };
        // SAFETY: forwarded caller contract.
        let s = |p| unsafe { slice(p, n) };
        let wi = Vec3Soa {
            x: s(wi_x)?,
            y: s(wi_y)?,
            z: s(wi_z)?,
        };
        let wo = Vec3Soa {
            x: s(wo_x)?,
            y: s(wo_y)?,
            z: s(wo_z)?,
        };
        let inputs = [wi.x, wi.y, wi.z, wo.x, wo.y, wo.z].map(span);
        // SAFETY: forwarded caller contract; `out` is checked to overlap no input.
        let out = unsafe { slice_mut_disjoint(out, n, &inputs)? };
        h.with::<f32, _>(|b| b.eval_batch_soa(wi, wo, out))
    })())
}

/// The body of `rad_*_eval_batch_soa_rgb`: the RGB values of the SoA
/// directions into three arrays (R, G, B), through a stack buffer of 64
/// values at a time (no heap).
///
/// # Safety
/// As [`rad_brdf_eval_batch_soa_rgb`].
#[allow(clippy::too_many_arguments)]
pub(crate) unsafe fn soa_batch_rgb<H: Handle>(
    h: *const H,
    wi_x: *const f32,
    wi_y: *const f32,
    wi_z: *const f32,
    wo_x: *const f32,
    wo_y: *const f32,
    wo_z: *const f32,
    out_r: *mut f32,
    out_g: *mut f32,
    out_b: *mut f32,
    n: usize,
) -> RadStatus {
    status((|| {
        // SAFETY: forwarded caller contract.
        let h = unsafe { as_ref(h)? };
        // SAFETY: forwarded caller contract.
        let s = |p| unsafe { slice(p, n) };
        let (ix, iy, iz, ox, oy, oz) = (s(wi_x)?, s(wi_y)?, s(wi_z)?, s(wo_x)?, s(wo_y)?, s(wo_z)?);
        let inputs = [ix, iy, iz, ox, oy, oz].map(span);
        // SAFETY: forwarded caller contract; each output is checked to overlap no input and no other output.
        let r = unsafe { slice_mut_disjoint(out_r, n, &inputs)? };
        let with_r = [
            inputs[0],
            inputs[1],
            inputs[2],
            inputs[3],
            inputs[4],
            inputs[5],
            span(r),
        ];
        // SAFETY: as above.
        let g = unsafe { slice_mut_disjoint(out_g, n, &with_r)? };
        let with_g = [
            inputs[0],
            inputs[1],
            inputs[2],
            inputs[3],
            inputs[4],
            inputs[5],
            with_r[6],
            span(g),
        ];
        // SAFETY: as above.
        let b = unsafe { slice_mut_disjoint(out_b, n, &with_g)? };
        h.with::<Vec3, _>(|brdf| {
            // Chunk iterators and zips, not indexing: no panic path (the
            // no-panic proof covers this function).
            const CHUNK: usize = 64;
            let mut buf = [Vec3::ZERO; CHUNK];
            let wi = ix.chunks(CHUNK).zip(iy.chunks(CHUNK)).zip(iz.chunks(CHUNK));
            let wo = ox.chunks(CHUNK).zip(oy.chunks(CHUNK)).zip(oz.chunks(CHUNK));
            let out = r
                .chunks_mut(CHUNK)
                .zip(g.chunks_mut(CHUNK))
                .zip(b.chunks_mut(CHUNK));
            for ((((ax, ay), az), ((bx, by), bz)), ((r, g), b)) in wi.zip(wo).zip(out) {
                let Some(vals) = buf.get_mut(..ax.len()) else {
                    break;
                };
                brdf.eval_batch_soa(
                    Vec3Soa { x: ax, y: ay, z: az },
                    Vec3Soa { x: bx, y: by, z: bz },
                    vals,
                );
                for (((v, r), g), b) in vals.iter().zip(r.iter_mut()).zip(g.iter_mut()).zip(b.iter_mut()) {
                    (*r, *g, *b) = (v.x, v.y, v.z);
                }
            }
        })
    })())
}

/// Structure-of-arrays form of [`rad_brdf_eval_batch`] (wavefront
/// renderers): direction `k` is `(wi_x[k], wi_y[k], wi_z[k])`.
///
/// # Safety
/// Each of the six input pointers points to `n` readable `float`s, `out` to
/// `n` writable `float`s overlapping none of them (checked).
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn rad_brdf_eval_batch_soa(
    brdf: *const RadBrdf,
    wi_x: *const f32,
    wi_y: *const f32,
    wi_z: *const f32,
    wo_x: *const f32,
    wo_y: *const f32,
    wo_z: *const f32,
    out: *mut f32,
    n: usize,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { soa_batch(brdf, wi_x, wi_y, wi_z, wo_x, wo_y, wo_z, out, n) }
}

/// The body of `rad_*_sample_batch`.
///
/// # Safety
/// As [`rad_brdf_sample_batch`].
pub(crate) unsafe fn sample_batch<H: Handle, S: Channels>(
    h: *const H,
    wo: *const RadVec3,
    u: *const f32,
    out: *mut RadBrdfSample,
    n: usize,
) -> RadStatus {
    status((|| {
        // SAFETY: forwarded caller contract; `[f32; 2]` has the size of two
        // `f32` and the alignment of one, so `2n` floats are `n` pairs.
        let (h, wo, u) = unsafe { (as_ref(h)?, slice(wo, n)?, slice(u.cast::<[f32; 2]>(), n)?) };
        // SAFETY: forwarded caller contract; `out` is checked to overlap
        // neither input.
        let out = unsafe { slice_mut_disjoint(out, n, &[span(wo), span(u)])? };
        h.with::<S, _>(|b| {
            // The plugin writes `Option<BrdfSample>`s; go through a stack
            // buffer (no heap) in chunks.
            const CHUNK: usize = 64;
            let mut buf: [Option<BrdfSample<S>>; CHUNK] = [None; CHUNK];
            let wo = as_vec3(wo);
            for ((wo, u), out) in wo.chunks(CHUNK).zip(u.chunks(CHUNK)).zip(out.chunks_mut(CHUNK)) {
                let buf = &mut buf[..wo.len()];
                b.sample_batch(wo, u, buf);
                for (o, s) in out.iter_mut().zip(buf.iter()) {
                    *o = (*s).into();
                }
            }
        })
    })())
}

/// Samples for `n` pairs: `out[k]` from `wo[k]` and `u[2k], u[2k+1]`.
///
/// # Safety
/// `brdf` points to a readable `RadBrdf`, `wo` to `n` readable `RadVec3`,
/// `u` to `2n` readable `float`s, `out` to `n` writable `RadBrdfSample`s
/// overlapping neither input (checked).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_brdf_sample_batch(
    brdf: *const RadBrdf,
    wo: *const RadVec3,
    u: *const f32,
    out: *mut RadBrdfSample,
    n: usize,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { sample_batch::<_, f32>(brdf, wo, u, out, n) }
}

/// `out[0..3] = f_r(wi → wo)` per channel (R, G, B) in 1/sr, from the RGB
/// form of the handle (its `rgb` colours; a grey handle gives the value of
/// [`rad_brdf_eval`] on each channel).
///
/// # Safety
/// `brdf` is null or points to a readable `RadBrdf`; `out` is null or points
/// to 3 writable `float`s.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_brdf_eval_rgb(
    brdf: *const RadBrdf,
    wi: RadVec3,
    wo: RadVec3,
    out: *mut f32,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { eval_one_rgb(brdf, wi, wo, out) }
}

/// `*out` = the solid-angle density with which [`rad_brdf_sample_rgb`] draws
/// `wi` given `wo`.
///
/// # Safety
/// As [`rad_brdf_eval`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_brdf_pdf_rgb(
    brdf: *const RadBrdf,
    wi: RadVec3,
    wo: RadVec3,
    out: *mut f32,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { pdf_one_rgb(brdf, wi, wo, out) }
}

/// [`rad_brdf_sample`] of the RGB form: the weight per channel.
///
/// # Safety
/// As [`rad_brdf_sample`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_brdf_sample_rgb(
    brdf: *const RadBrdf,
    wo: RadVec3,
    u0: f32,
    u1: f32,
    out: *mut RadBrdfSample,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { sample_one_rgb(brdf, wo, [u0, u1], out) }
}

/// `out[3k..3k+3] = f_r(wi[k] → wo[k])` per channel for `k < n` (RGB form).
///
/// # Safety
/// `brdf` points to a readable `RadBrdf`; `wi`, `wo` to `n` readable
/// `RadVec3`; `out` to `3n` writable `float`s not overlapping the inputs
/// (checked: `RAD_STATUS_OVERLAP`).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_brdf_eval_batch_rgb(
    brdf: *const RadBrdf,
    wi: *const RadVec3,
    wo: *const RadVec3,
    out: *mut f32,
    n: usize,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { eval_batch_rgb(brdf, wi, wo, out, n) }
}

/// `out[k] = pdf(wi[k], wo[k])` of the RGB form for `k < n`.
///
/// # Safety
/// As [`rad_brdf_eval_batch`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_brdf_pdf_batch_rgb(
    brdf: *const RadBrdf,
    wi: *const RadVec3,
    wo: *const RadVec3,
    out: *mut f32,
    n: usize,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { pair_batch::<_, Vec3>(brdf, wi, wo, out, n, |b, wi, wo, out| b.pdf_batch(wi, wo, out)) }
}

/// [`rad_brdf_sample_batch`] of the RGB form: the weights per channel.
///
/// # Safety
/// As [`rad_brdf_sample_batch`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_brdf_sample_batch_rgb(
    brdf: *const RadBrdf,
    wo: *const RadVec3,
    u: *const f32,
    out: *mut RadBrdfSample,
    n: usize,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { sample_batch::<_, Vec3>(brdf, wo, u, out, n) }
}

/// Structure-of-arrays form of [`rad_brdf_eval_batch_rgb`]: direction `k` is
/// `(wi_x[k], wi_y[k], wi_z[k])`, its value per channel goes to `out_r[k]`,
/// `out_g[k]`, `out_b[k]`.
///
/// # Safety
/// `brdf` points to a readable `RadBrdf`; each of the six input pointers to `n`
/// readable `float`s; `out_r`, `out_g`, `out_b` to `n` writable `float`s each,
/// overlapping no input and no other output (checked: `RAD_STATUS_OVERLAP`).
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn rad_brdf_eval_batch_soa_rgb(
    brdf: *const RadBrdf,
    wi_x: *const f32,
    wi_y: *const f32,
    wi_z: *const f32,
    wo_x: *const f32,
    wo_y: *const f32,
    wo_z: *const f32,
    out_r: *mut f32,
    out_g: *mut f32,
    out_b: *mut f32,
    n: usize,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { soa_batch_rgb(brdf, wi_x, wi_y, wi_z, wo_x, wo_y, wo_z, out_r, out_g, out_b, n) }
}
