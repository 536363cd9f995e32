//! OpenPBR Surface's reflection layer behind one plain C struct,
//! [`RadOpenPbr`]: the Rust `radiometry_brdfs::OpenPbr`, with OpenPBR's
//! parameter names and defaults in [`RadOpenPbrParams`] (colours per
//! channel, R, G, B). The monochrome calls (`rad_openpbr_eval`, …) build
//! `OpenPbr<f32>` from each colour's Rec. 709 luminance; the `_rgb` calls
//! build `OpenPbr<Vec3>` from the colours.
//!
//! Building an `OpenPbr` is O(1): the parameters' validation and a few reads
//! of the crate's global albedo tables. [`rad_openpbr_new`] validates the
//! parameters and keeps them in the caller's `RadOpenPbr` (plain data, 104
//! bytes: no pointers, no heap, no tables). Every call re-validates the
//! struct and builds the material from it with `OpenPbr::new` (or
//! `OpenPbr::with_layering` for the reciprocal mode): the values are the
//! Rust plugin's, bit for bit, and `rad_openpbr_pdf` at a sampled direction
//! equals the sample's pdf, bit for bit. Batch calls build once per batch.
//! During a call the built material lives on the stack.

use crate::brdf::{
    Channels, DynBrdf, Handle, eval_batch_rgb, eval_one, eval_one_rgb, luminance, pair_batch, pdf_one,
    pdf_one_rgb, sample_batch, sample_one, sample_one_rgb, soa_batch, soa_batch_rgb,
};
use crate::ptr::{as_mut, as_ref};
use crate::{RadBrdfSample, RadStatus, RadVec3};
use radiometry::glam::Vec3;
use radiometry_brdfs::openpbr::{Layering, OpenPbr, OpenPbrParams};

/// `RadOpenPbr::kind` of a handle filled in by [`rad_openpbr_new`]: OpenPBR
/// Surface 1.1's reflection layer.
pub const RAD_OPENPBR_REFLECTION: u32 = 1;

// The layouts the header documents.
const _: () = assert!(
    core::mem::size_of::<RadOpenPbrParams>() == 100 && core::mem::align_of::<RadOpenPbrParams>() == 4
);
const _: () = assert!(core::mem::size_of::<RadOpenPbr>() == 104 && core::mem::align_of::<RadOpenPbr>() == 4);

/// The parameters of OpenPBR Surface 1.1's reflection layer, with the
/// specification's names (every colour is a `float[3]`, R, G, B, linear
/// sRGB; the monochrome calls use its Rec. 709 luminance), and the layering
/// mode. Plain data (100 bytes: 24 `float`s and a `uint32_t`);
/// `rad_openpbr_default_params` fills in OpenPBR's defaults. Domains: every
/// weight, colour, roughness, `base_metalness` and `coat_darkening` in `[0,
/// 1]`; `specular_ior` and `coat_ior` in `[1, 1000]`; `reciprocal` 0 or 1.
/// A roughness of 0 is raised to the microfacet floor `α = 10⁻⁴`,
/// `fuzz_roughness` below 0.07 to 0.07 (the sheen tables' range).
/// OpenPBR's other parameters (transmission, subsurface, thin film,
/// anisotropy, emission, geometry) are outside a reflection-only isotropic
/// BRDF: the material behaves as if each were 0 (opaque, one-sided; see
/// docs/materials.md).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RadOpenPbrParams {
    /// `base_weight` (default 1): scales `base_color`.
    pub base_weight: f32,
    /// `base_color` (default 0.8): the diffuse albedo and the metal's
    /// reflectance at normal incidence.
    pub base_color: [f32; 3],
    /// `base_metalness` (default 0): the mix of metal and glossy-diffuse.
    pub base_metalness: f32,
    /// `base_diffuse_roughness` (default 0): the EON diffuse's `σ`.
    pub base_diffuse_roughness: f32,
    /// `specular_weight` (default 1): scales the dielectric's `F0` (through
    /// its index) and the metal lobe.
    pub specular_weight: f32,
    /// `specular_color` (default 1): tints the dielectric's reflection; the
    /// metal's F82 tint.
    pub specular_color: [f32; 3],
    /// `specular_roughness` (default 0.3): `α = r²`.
    pub specular_roughness: f32,
    /// `specular_ior` (default 1.5).
    pub specular_ior: f32,
    /// `coat_weight` (default 0).
    pub coat_weight: f32,
    /// `coat_color` (default 1): the coat's absorption (the square of its
    /// transmittance at normal incidence).
    pub coat_color: [f32; 3],
    /// `coat_roughness` (default 0): `α = r²`.
    pub coat_roughness: f32,
    /// `coat_ior` (default 1.6).
    pub coat_ior: f32,
    /// `coat_darkening` (default 1): the darkening of the coated base by
    /// light trapped in the coat (0: the base is boosted to cancel it).
    pub coat_darkening: f32,
    /// `fuzz_weight` (default 0).
    pub fuzz_weight: f32,
    /// `fuzz_color` (default 1).
    pub fuzz_color: [f32; 3],
    /// `fuzz_roughness` (default 0.5).
    pub fuzz_roughness: f32,
    /// The layering (not an OpenPBR parameter; default 0): 0 for OpenPBR's
    /// energy-conserving albedo scaling, 1 for the reciprocal form (for
    /// bidirectional methods; `Layering::Reciprocal`).
    pub reciprocal: u32,
}

impl Default for RadOpenPbrParams {
    /// OpenPBR Surface 1.1's defaults (those of `OpenPbrParams::default`).
    fn default() -> Self {
        OpenPbrParams::<f32>::default().into()
    }
}

impl From<RadOpenPbrParams> for OpenPbrParams<f32> {
    /// The monochrome parameters: each colour's Rec. 709 luminance (a grey
    /// colour exactly its value).
    #[inline]
    fn from(p: RadOpenPbrParams) -> Self {
        p.params::<f32>()
    }
}

impl From<RadOpenPbrParams> for OpenPbrParams<Vec3> {
    /// The RGB parameters: the colours as given.
    #[inline]
    fn from(p: RadOpenPbrParams) -> Self {
        p.params::<Vec3>()
    }
}

impl RadOpenPbrParams {
    /// The parameters in the spectrum `S` (`f32`: each colour's Rec. 709
    /// luminance; `Vec3`: the colours).
    #[inline]
    fn params<S: Channels>(&self) -> OpenPbrParams<S> {
        let p = self;
        let c = |v: [f32; 3]| S::colour(luminance(v), v);
        OpenPbrParams {
            base_weight: p.base_weight,
            base_color: c(p.base_color),
            base_metalness: p.base_metalness,
            base_diffuse_roughness: p.base_diffuse_roughness,
            specular_weight: p.specular_weight,
            specular_color: c(p.specular_color),
            specular_roughness: p.specular_roughness,
            specular_ior: p.specular_ior,
            coat_weight: p.coat_weight,
            coat_color: c(p.coat_color),
            coat_roughness: p.coat_roughness,
            coat_ior: p.coat_ior,
            coat_darkening: p.coat_darkening,
            fuzz_weight: p.fuzz_weight,
            fuzz_color: c(p.fuzz_color),
            fuzz_roughness: p.fuzz_roughness,
        }
    }
}

impl From<OpenPbrParams<f32>> for RadOpenPbrParams {
    /// The parameters (each colour grey), in the energy-conserving layering
    /// (`reciprocal` 0).
    #[inline]
    fn from(p: OpenPbrParams<f32>) -> Self {
        RadOpenPbrParams {
            base_weight: p.base_weight,
            base_color: [p.base_color; 3],
            base_metalness: p.base_metalness,
            base_diffuse_roughness: p.base_diffuse_roughness,
            specular_weight: p.specular_weight,
            specular_color: [p.specular_color; 3],
            specular_roughness: p.specular_roughness,
            specular_ior: p.specular_ior,
            coat_weight: p.coat_weight,
            coat_color: [p.coat_color; 3],
            coat_roughness: p.coat_roughness,
            coat_ior: p.coat_ior,
            coat_darkening: p.coat_darkening,
            fuzz_weight: p.fuzz_weight,
            fuzz_color: [p.fuzz_color; 3],
            fuzz_roughness: p.fuzz_roughness,
            reciprocal: 0,
        }
    }
}

impl RadOpenPbrParams {
    /// The material: the parameters checked in the order of the fields (the
    /// first bad one gives the status), `reciprocal` last.
    fn build<S: Channels>(&self) -> Result<OpenPbr<S>, RadStatus> {
        let layering = match self.reciprocal {
            0 => Some(Layering::EnergyConserving),
            1 => Some(Layering::Reciprocal),
            _ => None,
        };
        let m = OpenPbr::with_layering(self.params::<S>(), layering.unwrap_or_default())?;
        if layering.is_none() {
            return Err(RadStatus::OutOfRange);
        }
        Ok(m)
    }
}

/// An OpenPBR Surface reflection material: its parameters, checked. Plain
/// data (72 bytes, 4-byte aligned: a `uint32_t` and a `RadOpenPbrParams`, no
/// padding); copy it freely (it holds no pointers). Treat the fields as
/// read-only; a zeroed struct is an invalid handle (`RAD_STATUS_BAD_HANDLE`).
/// Each call checks the parameters as `rad_openpbr_new` does
/// (`RAD_STATUS_NOT_FINITE` / `_OUT_OF_RANGE`) and builds the material (O(1):
/// a batch call does it once per batch).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RadOpenPbr {
    /// [`RAD_OPENPBR_REFLECTION`].
    pub kind: u32,
    /// The parameters it was built from.
    pub params: RadOpenPbrParams,
}

impl Default for RadOpenPbr {
    /// A zeroed handle (invalid until [`rad_openpbr_new`] fills it in).
    fn default() -> Self {
        RadOpenPbr {
            kind: 0,
            params: RadOpenPbrParams {
                base_weight: 0.0,
                base_color: [0.0; 3],
                base_metalness: 0.0,
                base_diffuse_roughness: 0.0,
                specular_weight: 0.0,
                specular_color: [0.0; 3],
                specular_roughness: 0.0,
                specular_ior: 0.0,
                coat_weight: 0.0,
                coat_color: [0.0; 3],
                coat_roughness: 0.0,
                coat_ior: 0.0,
                coat_darkening: 0.0,
                fuzz_weight: 0.0,
                fuzz_color: [0.0; 3],
                fuzz_roughness: 0.0,
                reciprocal: 0,
            },
        }
    }
}

impl Handle for RadOpenPbr {
    #[inline]
    fn with<S: Channels, R>(&self, f: impl FnOnce(&dyn DynBrdf<S>) -> R) -> Result<R, RadStatus> {
        if self.kind != RAD_OPENPBR_REFLECTION {
            return Err(RadStatus::BadHandle);
        }
        let m = self.params.build::<S>()?;
        Ok(f(&m))
    }
}

/// Writes OpenPBR Surface 1.1's default parameters to `*out`: a white-ish
/// (`base_color` 0.8) dielectric base with a `specular_roughness` 0.3,
/// `specular_ior` 1.5 specular layer, no coat (`coat_ior` 1.6,
/// `coat_color` 1, `coat_roughness` 0), no fuzz (`fuzz_color` 1,
/// `fuzz_roughness` 0.5); `base_weight`, `specular_weight`,
/// `specular_color`, `coat_darkening` 1, `base_metalness`,
/// `base_diffuse_roughness` 0; `reciprocal` 0 (energy-conserving).
///
/// # Safety
/// `out` is null or points to a writable `RadOpenPbrParams`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_openpbr_default_params(out: *mut RadOpenPbrParams) -> RadStatus {
    // SAFETY: forwarded caller contract.
    match unsafe { as_mut(out) } {
        Ok(out) => {
            *out = RadOpenPbrParams::default();
            RadStatus::Ok
        }
        Err(s) => s,
    }
}

/// Builds OpenPBR Surface's reflection layer from `*params` into `*out`
/// (`radiometry_brdfs::OpenPbr`: a metal, a dielectric specular layer over
/// an EON diffuse, an optional absorbing coat and an optional fuzz, layered
/// by albedo scaling; see docs/materials.md): checks the parameters (in the
/// order of the struct's fields; the first bad one gives the status:
/// `RAD_STATUS_NOT_FINITE` for NaN or ±∞, `RAD_STATUS_OUT_OF_RANGE` outside
/// its domain) and stores them. O(1); each call builds the material from
/// the struct again (also O(1); a batch call once per batch).
///
/// # Safety
/// `params` is null or points to a readable `RadOpenPbrParams`; `out` is
/// null or points to a writable `RadOpenPbr` (unchanged on error).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_openpbr_new(params: *const RadOpenPbrParams, out: *mut RadOpenPbr) -> RadStatus {
    let r = (|| {
        // SAFETY: forwarded caller contract; the parameters are copied out
        // before `out` is borrowed (C may pass overlapping pointers).
        let p = unsafe { *as_ref(params)? };
        p.build::<f32>()?;
        p.build::<Vec3>()?;
        // SAFETY: forwarded caller contract.
        let out = unsafe { as_mut(out)? };
        *out = RadOpenPbr {
            kind: RAD_OPENPBR_REFLECTION,
            params: p,
        };
        Ok(())
    })();
    r.err().unwrap_or(RadStatus::Ok)
}

/// `*out = f_r(wi → wo)` of the material, in 1/sr.
///
/// # Safety
/// `material` is null or points to a readable `RadOpenPbr`; `out` is null or
/// points to a writable `float`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_openpbr_eval(
    material: *const RadOpenPbr,
    wi: RadVec3,
    wo: RadVec3,
    out: *mut f32,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { eval_one(material, wi, wo, out) }
}

/// `*out` = the solid-angle density with which [`rad_openpbr_sample`] draws
/// `wi` given `wo` (the mixture density of the layers and lobes).
///
/// # Safety
/// As [`rad_openpbr_eval`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_openpbr_pdf(
    material: *const RadOpenPbr,
    wi: RadVec3,
    wo: RadVec3,
    out: *mut f32,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { pdf_one(material, wi, wo, out) }
}

/// Importance-samples `wi` for `wo` from `(u0, u1) ∈ [0, 1)²`: layers and
/// lobes picked in proportion to their directional albedos at `wo`, then
/// the picked lobe's sample; the returned pdf is the mixture density, equal
/// to [`rad_openpbr_pdf`] bit for bit. `pdf = 0` means no sample (see
/// `RadBrdfSample`).
///
/// # Safety
/// `material` is null or points to a readable `RadOpenPbr`; `out` is null or
/// points to a writable `RadBrdfSample`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_openpbr_sample(
    material: *const RadOpenPbr,
    wo: RadVec3,
    u0: f32,
    u1: f32,
    out: *mut RadBrdfSample,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { sample_one(material, wo, [u0, u1], out) }
}

/// `out[k] = f_r(wi[k] → wo[k])` for `k < n`, through the layers' batch
/// kernels (validates and builds the material once per batch).
///
/// # Safety
/// `material` points to a readable `RadOpenPbr`; `wi`, `wo` to `n` readable
/// `RadVec3`; `out` to `n` writable `float`s not overlapping the inputs
/// (checked: `RAD_STATUS_OVERLAP`). Null pointers are reported, not
/// dereferenced; `n = 0` reads nothing.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_openpbr_eval_batch(
    material: *const RadOpenPbr,
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
/// As [`rad_openpbr_eval_batch`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_openpbr_pdf_batch(
    material: *const RadOpenPbr,
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

/// Structure-of-arrays form of [`rad_openpbr_eval_batch`]: direction `k` is
/// `(wi_x[k], wi_y[k], wi_z[k])`.
///
/// # Safety
/// Each of the six input pointers points to `n` readable `float`s, `out` to
/// `n` writable `float`s overlapping none of them (checked).
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn rad_openpbr_eval_batch_soa(
    material: *const RadOpenPbr,
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
/// equal to [`rad_openpbr_sample`]'s.
///
/// # Safety
/// `material` points to a readable `RadOpenPbr`, `wo` to `n` readable
/// `RadVec3`, `u` to `2n` readable `float`s, `out` to `n` writable
/// `RadBrdfSample`s overlapping neither input (checked).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_openpbr_sample_batch(
    material: *const RadOpenPbr,
    wo: *const RadVec3,
    u: *const f32,
    out: *mut RadBrdfSample,
    n: usize,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { sample_batch::<_, f32>(material, wo, u, out, n) }
}

/// `out[0..3] = f_r(wi → wo)` of the material per channel (R, G, B) in 1/sr,
/// from its RGB form (a grey material gives [`rad_openpbr_eval`]'s value on each channel).
///
/// # Safety
/// `material` is null or points to a readable `RadOpenPbr`; `out` is null or
/// points to 3 writable `float`s.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_openpbr_eval_rgb(
    material: *const RadOpenPbr,
    wi: RadVec3,
    wo: RadVec3,
    out: *mut f32,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { eval_one_rgb(material, wi, wo, out) }
}

/// `*out` = the solid-angle density with which [`rad_openpbr_sample_rgb`] draws
/// `wi` given `wo` (the lobes picked by their per-channel albedos).
///
/// # Safety
/// As [`rad_openpbr_eval`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_openpbr_pdf_rgb(
    material: *const RadOpenPbr,
    wi: RadVec3,
    wo: RadVec3,
    out: *mut f32,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { pdf_one_rgb(material, wi, wo, out) }
}

/// [`rad_openpbr_sample`] of the RGB form: the weight per channel; its pdf is
/// [`rad_openpbr_pdf_rgb`]'s.
///
/// # Safety
/// As [`rad_openpbr_sample`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_openpbr_sample_rgb(
    material: *const RadOpenPbr,
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
/// `material` points to a readable `RadOpenPbr`; `wi`, `wo` to `n` readable
/// `RadVec3`; `out` to `3n` writable `float`s not overlapping the inputs
/// (checked: `RAD_STATUS_OVERLAP`).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_openpbr_eval_batch_rgb(
    material: *const RadOpenPbr,
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
/// As [`rad_openpbr_eval_batch`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_openpbr_pdf_batch_rgb(
    material: *const RadOpenPbr,
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

/// [`rad_openpbr_sample_batch`] of the RGB form: the weights per channel.
///
/// # Safety
/// As [`rad_openpbr_sample_batch`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_openpbr_sample_batch_rgb(
    material: *const RadOpenPbr,
    wo: *const RadVec3,
    u: *const f32,
    out: *mut RadBrdfSample,
    n: usize,
) -> RadStatus {
    // SAFETY: forwarded caller contract.
    unsafe { sample_batch::<_, Vec3>(material, wo, u, out, n) }
}

/// Structure-of-arrays form of [`rad_openpbr_eval_batch_rgb`]: direction `k` is
/// `(wi_x[k], wi_y[k], wi_z[k])`, its value per channel goes to `out_r[k]`,
/// `out_g[k]`, `out_b[k]`.
///
/// # Safety
/// `material` points to a readable `RadOpenPbr`; each of the six input pointers to `n`
/// readable `float`s; `out_r`, `out_g`, `out_b` to `n` writable `float`s each,
/// overlapping no input and no other output (checked: `RAD_STATUS_OVERLAP`).
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn rad_openpbr_eval_batch_soa_rgb(
    material: *const RadOpenPbr,
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
