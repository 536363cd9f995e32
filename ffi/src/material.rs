//! Compositions of BRDF plugins behind one plain C struct, [`RadMaterial`]:
//! a single lobe, a sum `A + B`, a mix `w A + (1 − w) B` and a coat
//! `coated(top, base)` — the lobe combinators of `radiometry::compose`
//! (`Sum`, `Mix`, `Coated`), where `A`, `B`, `top` and `base` are
//! [`RadBrdf`]s.
//!
//! Like a `RadBrdf`, a `RadMaterial` is caller-allocated plain data (no
//! pointers, no heap; 132 bytes, 4-byte aligned), filled in once by a
//! `rad_material_*` constructor. Every call re-validates it (the lobes'
//! parameters as for a `RadBrdf`, the weight and coat parameters) and
//! rebuilds the composite from it, in O(1): a coat reads its top's
//! directional albedo where it needs it (`Coated::new`, O(1) for the crate's
//! lobes through global tables), so nothing is tabulated per material.
//!
//! The values are those of the Rust composites over the same plugins, bit for
//! bit: `Sum`, `Mix` and `Coated` pick a lobe to sample in proportion to its
//! directional albedo at `ωo`, and `pdf` returns the mixture density the
//! sample reported, bit for bit.

use crate::brdf::{
    Channels, DynBrdf, Handle, check_rgb, eval_batch_rgb, eval_one, eval_one_rgb, pair_batch, pdf_one,
    pdf_one_rgb, sample_batch, sample_one, sample_one_rgb, soa_batch, soa_batch_rgb, with_plugin_shared,
};
use crate::ptr::{as_mut, as_ref};
use crate::{RadBrdf, RadBrdfSample, RadStatus, RadVec3};
use radiometry::batch::Vec3Soa;
use radiometry::compose::{Coated, Layering, Mix, Sum};
use radiometry::glam::Vec3;
use radiometry::{Albedo, Brdf, BrdfSample, Spectrum};

/// `RadMaterial::kind`: one lobe, `lobes[0]`.
pub const RAD_MATERIAL_BRDF: u32 = 1;
/// `RadMaterial::kind`: the sum `lobes[0] + lobes[1]`.
pub const RAD_MATERIAL_SUM: u32 = 2;
/// `RadMaterial::kind`: the mix `weight · lobes[0] + (1 − weight) · lobes[1]`.
pub const RAD_MATERIAL_MIX: u32 = 3;
/// `RadMaterial::kind`: `lobes[0]` (top) coated over `lobes[1]` (base).
pub const RAD_MATERIAL_COATED: u32 = 4;

// The layouts the header documents.
const _: () = assert!(core::mem::size_of::<RadBrdf>() == 56 && core::mem::align_of::<RadBrdf>() == 4);
const _: () =
    assert!(core::mem::size_of::<RadMaterial>() == 132 && core::mem::align_of::<RadMaterial>() == 4);

/// A material: one or two [`RadBrdf`] lobes and how they combine. Plain data
/// (132 bytes, 4-byte aligned: five 32-bit fields and two `RadBrdf`s, no
/// padding), filled in by `rad_material_brdf`, `rad_material_sum`,
/// `rad_material_mix`, `rad_material_coated` or
/// `rad_material_coated_reciprocal`; copy it
/// freely (it holds no pointers). Treat the fields as read-only; a zeroed
/// struct is an invalid handle (`RAD_STATUS_BAD_HANDLE`). Fields a kind does
/// not use are 0. Each call checks the fields the kind uses (the lobes as
/// `RadBrdf` calls do, the weight, the coat parameters) and rebuilds the
/// composite (O(1)).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RadMaterial {
    /// One of the `RAD_MATERIAL_*` kinds.
    pub kind: u32,
    /// `RAD_MATERIAL_MIX`: the weight `w ∈ [0, 1]` of `lobes[0]`.
    pub weight: f32,
    /// `RAD_MATERIAL_COATED`: the coat colour `C ∈ [0, 1]` (OpenPBR's
    /// `coat_color`, the square of the coat's transmittance at normal
    /// incidence; 1: a clear coat, no absorption).
    pub coat_color: f32,
    /// `RAD_MATERIAL_COATED`: the coat's index of refraction `≥ 1` (sets
    /// the path length of the absorption).
    pub coat_ior: f32,
    /// `RAD_MATERIAL_COATED`: the layering, 0 for OpenPBR's
    /// energy-conserving albedo scaling ([`rad_material_coated`]), 1 for the
    /// reciprocal form ([`rad_material_coated_reciprocal`]); any other value
    /// is `RAD_STATUS_BAD_HANDLE`.
    pub reciprocal: u32,
    /// The lobes: `A`, `B` (sum, mix), `top`, `base` (coated); `lobes[1]`
    /// zeroed for `RAD_MATERIAL_BRDF`.
    pub lobes: [RadBrdf; 2],
}

impl Default for RadMaterial {
    /// A zeroed handle (invalid until a constructor fills it in).
    fn default() -> Self {
        RadMaterial {
            kind: 0,
            weight: 0.0,
            coat_color: 0.0,
            coat_ior: 0.0,
            reciprocal: 0,
            lobes: [RadBrdf::default(); 2],
        }
    }
}

/// A plugin behind the object-safe view, as a `Brdf` the combinators take.
struct Lobe<'a, S>(&'a dyn DynBrdf<S>);

impl<S> Clone for Lobe<'_, S> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<S> Copy for Lobe<'_, S> {}

impl<S: Spectrum> Brdf for Lobe<'_, S> {
    type Spectrum = S;
    #[inline]
    fn eval(&self, wi: Vec3, wo: Vec3) -> S {
        DynBrdf::eval(self.0, wi, wo)
    }
    #[inline]
    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<S>> {
        DynBrdf::sample(self.0, wo, u)
    }
    #[inline]
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        DynBrdf::pdf(self.0, wi, wo)
    }
    #[inline]
    fn eval_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [S]) {
        DynBrdf::eval_batch(self.0, wi, wo, out)
    }
    #[inline]
    fn eval_batch_soa(&self, wi: Vec3Soa<'_>, wo: Vec3Soa<'_>, out: &mut [S]) {
        DynBrdf::eval_batch_soa(self.0, wi, wo, out)
    }
    #[inline]
    fn pdf_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]) {
        DynBrdf::pdf_batch(self.0, wi, wo, out)
    }
    #[inline]
    fn sample_batch(&self, wo: &[Vec3], u: &[[f32; 2]], out: &mut [Option<BrdfSample<S>>]) {
        DynBrdf::sample_batch(self.0, wo, u, out)
    }
    #[inline]
    fn is_smooth(&self) -> bool {
        DynBrdf::is_smooth(self.0)
    }
    #[inline]
    fn directional_albedo(&self, wo: Vec3) -> Albedo<S> {
        DynBrdf::directional_albedo(self.0, wo)
    }
    #[inline]
    fn average_albedo(&self) -> S {
        DynBrdf::average_albedo(self.0)
    }
}

/// Builds both lobes of `m` and runs `f` on them.
fn two<S: Channels, R>(
    m: &RadMaterial,
    f: impl FnOnce(Lobe<'_, S>, Lobe<'_, S>) -> R,
) -> Result<R, RadStatus> {
    let [a, b] = &m.lobes;
    with_plugin_shared(a, |a| with_plugin_shared(b, |b| f(Lobe(a), Lobe(b))))?
}

/// Checks a coat's colour and index of refraction (as `Coated` does): the
/// colour in `[0, 1]`, the index finite and `≥ 1`.
fn check_coat(coat_color: f32, coat_ior: f32) -> Result<(), RadStatus> {
    if !coat_color.is_finite() || !coat_ior.is_finite() {
        return Err(RadStatus::NotFinite);
    }
    if !(0.0..=1.0).contains(&coat_color) || coat_ior < 1.0 {
        return Err(RadStatus::OutOfRange);
    }
    Ok(())
}

impl Handle for RadMaterial {
    fn with<S: Channels, R>(&self, f: impl FnOnce(&dyn DynBrdf<S>) -> R) -> Result<R, RadStatus> {
        match self.kind {
            RAD_MATERIAL_BRDF => {
                if self.lobes[1] != RadBrdf::default() {
                    return Err(RadStatus::BadHandle);
                }
                with_plugin_shared(&self.lobes[0], f)
            }
            RAD_MATERIAL_SUM => two(self, |a, b| f(&Sum::new(a, b))),
            RAD_MATERIAL_MIX => two(self, |a, b| Ok(f(&Mix::new(self.weight, a, b)?)))?,
            RAD_MATERIAL_COATED => {
                check_coat(self.coat_color, self.coat_ior)?;
                let layering = match self.reciprocal {
                    0 => Layering::EnergyConserving,
                    1 => Layering::Reciprocal,
                    _ => return Err(RadStatus::BadHandle),
                };
                two(self, |top, base| {
                    let layer = Coated::new(top, base).with_layering(layering);
                    // A clear coat is `Coated::new`'s layer (as the spec
                    // grammar builds `coat_color=1`).
                    Ok(if self.coat_color < 1.0 {
                        f(&layer.absorbing(S::splat(self.coat_color), self.coat_ior)?)
                    } else {
                        f(&layer)
                    })
                })?
            }
            _ => Err(RadStatus::BadHandle),
        }
    }
}

/// Copies the lobes (before `out` is borrowed: C may pass overlapping
/// pointers), builds the material, validates it and writes it to `out`.
///
/// # Safety
/// `a`, `b` are null or point to readable `RadBrdf`s; `out` is null or
/// points to a writable `RadMaterial`.
unsafe fn construct(
    a: *const RadBrdf,
    b: Option<*const RadBrdf>,
    out: *mut RadMaterial,
    fill: impl FnOnce(&mut RadMaterial) -> Result<(), RadStatus>,
) -> RadStatus {
    let r = (|| {
        // SAFETY: forwarded caller contract; the lobes are copied out before
        // `out` is borrowed.
        let a = unsafe { *as_ref(a)? };
        let b = match b {
            // SAFETY: as above.
            Some(b) => unsafe { *as_ref(b)? },
            None => RadBrdf::default(),
        };
        let mut m = RadMaterial {
            lobes: [a, b],
            ..RadMaterial::default()
        };
        fill(&mut m)?;
        m.with::<f32, _>(|_| ())?;
        // The lobes' colours (the composite's own parameters are checked above and are grey).
        check_rgb(&m.lobes[0])?;
        if m.lobes[1] != RadBrdf::default() {
            check_rgb(&m.lobes[1])?;
        }
        // SAFETY: forwarded caller contract.
        let out = unsafe { as_mut(out)? };
        *out = m;
        Ok(())
    })();
    r.err().unwrap_or(RadStatus::Ok)
}

/// A material of one lobe: the plugin `brdf` (so a renderer can hold every
/// surface as a `RadMaterial`). Same values as the `RadBrdf` calls.
///
/// # Safety
/// `brdf` is null or points to a readable `RadBrdf`; `out` is null or points
/// to a writable `RadMaterial` (unchanged on error).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_material_brdf(brdf: *const RadBrdf, out: *mut RadMaterial) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe {
        construct(brdf, None, out, |m| {
            m.kind = RAD_MATERIAL_BRDF;
            Ok(())
        })
    }
}

/// The sum of two lobes, `f = f_A + f_B` (`radiometry::compose::Sum`),
/// sampled by picking `A` with probability `Ē_A / (Ē_A + Ē_B)` (their
/// directional albedos at `ωo`) and the mixture density. A sum of
/// energy-conserving lobes need not conserve energy (a plastic is better
/// built with [`rad_material_coated`]).
///
/// # Safety
/// `a`, `b` are null or point to readable `RadBrdf`s; `out` is null or
/// points to a writable `RadMaterial` (unchanged on error).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_material_sum(
    a: *const RadBrdf,
    b: *const RadBrdf,
    out: *mut RadMaterial,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe {
        construct(a, Some(b), out, |m| {
            m.kind = RAD_MATERIAL_SUM;
            Ok(())
        })
    }
}

/// The mix `f = w f_A + (1 − w) f_B`, `w ∈ [0, 1]` (OpenPBR's `mix`;
/// `radiometry::compose::Mix`): `E = w E_A + (1 − w) E_B`, so a mix of
/// energy-conserving lobes conserves energy. Sampled by picking `A` with
/// probability `w Ē_A / (w Ē_A + (1 − w) Ē_B)`.
///
/// # Safety
/// As [`rad_material_sum`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_material_mix(
    weight: f32,
    a: *const RadBrdf,
    b: *const RadBrdf,
    out: *mut RadMaterial,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe {
        construct(a, Some(b), out, |m| {
            m.kind = RAD_MATERIAL_MIX;
            m.weight = weight;
            Ok(())
        })
    }
}

/// `top` coated over `base` by albedo scaling, in OpenPBR's
/// energy-conserving form (`radiometry::compose::Coated::new` /
/// `Coated::with_absorption`; OpenPBR Surface 1.1 §"Layering"):
///
/// ```text
/// f(ωi, ωo) = f_T(ωi, ωo) + A(μi, μo) (1 − E_T(ωo)) f_B(ωi, ωo)
/// A(μi, μo) = C^((1/μᵗi + 1/μᵗo)/2),   μᵗ = √(1 − (1 − μ²)/η²)
/// ```
///
/// with `E_T` the top's directional albedo (read at every call: O(1) for
/// the crate's lobes, from global tables or closed forms), `C = coat_color ∈
/// [0, 1]` (1: clear) and `η = coat_ior ≥ 1`. `E ≤ 1` for every base with
/// `E_B ≤ 1`, and a white base under a clear top keeps all its energy. Only
/// the lobes and the coat parameters are stored. A plastic is a dielectric
/// microfacet top (`RAD_FRESNEL_DIELECTRIC`, `η = 1.5`) over a diffuse
/// base. Sampling picks the top with probability `Ē_T / (Ē_T + Ē_through)`
/// at `ωo`.
///
/// # Safety
/// `top`, `base` are null or point to readable `RadBrdf`s; `out` is null or
/// points to a writable `RadMaterial` (unchanged on error).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_material_coated(
    top: *const RadBrdf,
    base: *const RadBrdf,
    coat_color: f32,
    coat_ior: f32,
    out: *mut RadMaterial,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { coated(top, base, coat_color, coat_ior, 0, out) }
}

/// [`rad_material_coated`] in the reciprocal layering
/// (`Coated::with_layering(Layering::Reciprocal)`, for bidirectional
/// methods): the through-factor `(1 − E_T(ωo))` becomes
///
/// ```text
/// τ(ωi, ωo) = min(t(ωi) t(ωo) / (1 − Ē_T), t(ωi), t(ωo)),   t(ω) = 1 − E_T(ω)
/// ```
///
/// with `Ē_T` the top's hemispherical average albedo: `f(ωi, ωo) = f(ωo,
/// ωi)`, and `E ≤ 1` for every base with `E_B ≤ 1` (a white Lambertian base
/// keeps `E_T + 1 − Ē_T` where `E_T(ωo) < Ē_T`, instead of 1).
///
/// # Safety
/// As [`rad_material_coated`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_material_coated_reciprocal(
    top: *const RadBrdf,
    base: *const RadBrdf,
    coat_color: f32,
    coat_ior: f32,
    out: *mut RadMaterial,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { coated(top, base, coat_color, coat_ior, 1, out) }
}

/// The coat constructors.
///
/// # Safety
/// As [`rad_material_coated`].
unsafe fn coated(
    top: *const RadBrdf,
    base: *const RadBrdf,
    coat_color: f32,
    coat_ior: f32,
    reciprocal: u32,
    out: *mut RadMaterial,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe {
        construct(top, Some(base), out, |m| {
            check_coat(coat_color, coat_ior)?;
            m.kind = RAD_MATERIAL_COATED;
            m.coat_color = coat_color;
            m.coat_ior = coat_ior;
            m.reciprocal = reciprocal;
            Ok(())
        })
    }
}

/// `*out = f_r(wi → wo)` of the material, in 1/sr.
///
/// # Safety
/// `material` is null or points to a readable `RadMaterial`; `out` is null
/// or points to a writable `float`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_material_eval(
    material: *const RadMaterial,
    wi: RadVec3,
    wo: RadVec3,
    out: *mut f32,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { eval_one(material, wi, wo, out) }
}

/// `*out` = the solid-angle density with which [`rad_material_sample`] draws
/// `wi` given `wo` (the mixture density of the lobes).
///
/// # Safety
/// As [`rad_material_eval`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_material_pdf(
    material: *const RadMaterial,
    wi: RadVec3,
    wo: RadVec3,
    out: *mut f32,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { pdf_one(material, wi, wo, out) }
}

/// Importance-samples `wi` for `wo` from `(u0, u1) ∈ [0, 1)²`: a lobe picked
/// by albedo with `u0` (rescaled and reused), then that lobe's sample; the
/// returned pdf is the mixture density, equal to [`rad_material_pdf`] bit for
/// bit. `pdf = 0` means no sample (see `RadBrdfSample`).
///
/// # Safety
/// `material` is null or points to a readable `RadMaterial`; `out` is null
/// or points to a writable `RadBrdfSample`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_material_sample(
    material: *const RadMaterial,
    wo: RadVec3,
    u0: f32,
    u1: f32,
    out: *mut RadBrdfSample,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { sample_one(material, wo, [u0, u1], out) }
}

/// `out[k] = f_r(wi[k] → wo[k])` for `k < n` (validates the material once
/// per batch).
///
/// # Safety
/// `material` points to a readable `RadMaterial`; `wi`, `wo` to `n` readable
/// `RadVec3`; `out` to `n` writable `float`s not overlapping the inputs
/// (checked: `RAD_STATUS_OVERLAP`). Null pointers are reported, not
/// dereferenced; `n = 0` reads nothing.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_material_eval_batch(
    material: *const RadMaterial,
    wi: *const RadVec3,
    wo: *const RadVec3,
    out: *mut f32,
    n: usize,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe {
        pair_batch::<_, f32>(material, wi, wo, out, n, |b, wi, wo, out| {
            b.eval_batch(wi, wo, out)
        })
    }
}

/// `out[k] = pdf(wi[k], wo[k])` for `k < n`.
///
/// # Safety
/// As [`rad_material_eval_batch`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_material_pdf_batch(
    material: *const RadMaterial,
    wi: *const RadVec3,
    wo: *const RadVec3,
    out: *mut f32,
    n: usize,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe {
        pair_batch::<_, f32>(material, wi, wo, out, n, |b, wi, wo, out| {
            b.pdf_batch(wi, wo, out)
        })
    }
}

/// Structure-of-arrays form of [`rad_material_eval_batch`]: direction `k` is
/// `(wi_x[k], wi_y[k], wi_z[k])`.
///
/// # Safety
/// Each of the six input pointers points to `n` readable `float`s, `out` to
/// `n` writable `float`s overlapping none of them (checked).
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn rad_material_eval_batch_soa(
    material: *const RadMaterial,
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
    unsafe { soa_batch(material, wi_x, wi_y, wi_z, wo_x, wo_y, wo_z, out, n) }
}

/// Samples for `n` pairs: `out[k]` from `wo[k]` and `u[2k], u[2k+1]`, each
/// equal to [`rad_material_sample`]'s.
///
/// # Safety
/// `material` points to a readable `RadMaterial`, `wo` to `n` readable
/// `RadVec3`, `u` to `2n` readable `float`s, `out` to `n` writable
/// `RadBrdfSample`s overlapping neither input (checked).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_material_sample_batch(
    material: *const RadMaterial,
    wo: *const RadVec3,
    u: *const f32,
    out: *mut RadBrdfSample,
    n: usize,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { sample_batch::<_, f32>(material, wo, u, out, n) }
}

/// `out[0..3] = f_r(wi → wo)` of the material per channel (R, G, B) in 1/sr,
/// from its RGB form (a grey material gives [`rad_material_eval`]'s value on each channel).
///
/// # Safety
/// `material` is null or points to a readable `RadMaterial`; `out` is null or
/// points to 3 writable `float`s.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_material_eval_rgb(
    material: *const RadMaterial,
    wi: RadVec3,
    wo: RadVec3,
    out: *mut f32,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { eval_one_rgb(material, wi, wo, out) }
}

/// `*out` = the solid-angle density with which [`rad_material_sample_rgb`] draws
/// `wi` given `wo` (the lobes picked by their per-channel albedos).
///
/// # Safety
/// As [`rad_material_eval`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_material_pdf_rgb(
    material: *const RadMaterial,
    wi: RadVec3,
    wo: RadVec3,
    out: *mut f32,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { pdf_one_rgb(material, wi, wo, out) }
}

/// [`rad_material_sample`] of the RGB form: the weight per channel; its pdf is
/// [`rad_material_pdf_rgb`]'s.
///
/// # Safety
/// As [`rad_material_sample`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_material_sample_rgb(
    material: *const RadMaterial,
    wo: RadVec3,
    u0: f32,
    u1: f32,
    out: *mut RadBrdfSample,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { sample_one_rgb(material, wo, [u0, u1], out) }
}

/// `out[3k..3k+3] = f_r(wi[k] → wo[k])` per channel for `k < n` (RGB form).
///
/// # Safety
/// `material` points to a readable `RadMaterial`; `wi`, `wo` to `n` readable
/// `RadVec3`; `out` to `3n` writable `float`s not overlapping the inputs
/// (checked: `RAD_STATUS_OVERLAP`).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_material_eval_batch_rgb(
    material: *const RadMaterial,
    wi: *const RadVec3,
    wo: *const RadVec3,
    out: *mut f32,
    n: usize,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { eval_batch_rgb(material, wi, wo, out, n) }
}

/// `out[k] = pdf(wi[k], wo[k])` of the RGB form for `k < n`.
///
/// # Safety
/// As [`rad_material_eval_batch`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_material_pdf_batch_rgb(
    material: *const RadMaterial,
    wi: *const RadVec3,
    wo: *const RadVec3,
    out: *mut f32,
    n: usize,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe {
        pair_batch::<_, Vec3>(material, wi, wo, out, n, |b, wi, wo, out| {
            b.pdf_batch(wi, wo, out)
        })
    }
}

/// [`rad_material_sample_batch`] of the RGB form: the weights per channel.
///
/// # Safety
/// As [`rad_material_sample_batch`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_material_sample_batch_rgb(
    material: *const RadMaterial,
    wo: *const RadVec3,
    u: *const f32,
    out: *mut RadBrdfSample,
    n: usize,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { sample_batch::<_, Vec3>(material, wo, u, out, n) }
}

/// Structure-of-arrays form of [`rad_material_eval_batch_rgb`]: direction `k` is
/// `(wi_x[k], wi_y[k], wi_z[k])`, its value per channel goes to `out_r[k]`,
/// `out_g[k]`, `out_b[k]`.
///
/// # Safety
/// `material` points to a readable `RadMaterial`; each of the six input pointers to `n`
/// readable `float`s; `out_r`, `out_g`, `out_b` to `n` writable `float`s each,
/// overlapping no input and no other output (checked: `RAD_STATUS_OVERLAP`).
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn rad_material_eval_batch_soa_rgb(
    material: *const RadMaterial,
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
    unsafe {
        soa_batch_rgb(
            material, wi_x, wi_y, wi_z, wo_x, wo_y, wo_z, out_r, out_g, out_b, n,
        )
    }
}
