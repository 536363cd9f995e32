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
//! Beckmann `D` and Smith `G2` (Heitz 2014, eqs. 98–99).

use crate::ptr::{as_mut, as_ref, slice, slice_mut_disjoint, span};
use crate::{RadStatus, RadVec3};
use radiometry::batch::Vec3Soa;
use radiometry::glam::Vec3;
use radiometry::{Brdf, BrdfSample};
use radiometry_brdfs::{
    Beckmann, BlinnPhong, Conductor, Dielectric, Fresnel, Ggx, HeightCorrelated, Lambertian, Microfacet,
    MicrofacetDistribution, ModifiedPhong, NoFresnel, Schlick, Separable, ShadowingMasking,
};

/// `RadBrdf::kind`: Lambertian, `params = {albedo}`.
pub const RAD_BRDF_LAMBERTIAN: u32 = 1;
/// `RadBrdf::kind`: modified Phong, `params = {kd, ks, exponent}`.
pub const RAD_BRDF_PHONG: u32 = 2;
/// `RadBrdf::kind`: normalised Blinn–Phong, `params = {kd, ks, exponent}`.
pub const RAD_BRDF_BLINN_PHONG: u32 = 3;
/// `RadBrdf::kind`: microfacet, `params = {alpha, fresnel_a, fresnel_b}`.
pub const RAD_BRDF_MICROFACET: u32 = 4;

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

/// A BRDF plugin: plain data, filled in by `rad_brdf_lambertian`,
/// `rad_brdf_phong`, `rad_brdf_blinn_phong` or `rad_brdf_microfacet`. Treat the
/// fields as read-only; a zeroed struct is an invalid handle
/// (`RAD_STATUS_BAD_HANDLE`).
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
    /// The parameters, by kind (see the `RAD_BRDF_*` constants).
    pub params: [f32; 3],
}

/// One importance sample: `wi` drawn with density `pdf` (per steradian) and
/// Monte Carlo weight `weight = f_r(wi, wo) cos θi / pdf`. `pdf = 0` (and
/// `wi = weight = 0`) means the plugin returned no sample for this `wo, u`
/// (e.g. `wo` below the horizon).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RadBrdfSample {
    /// The sampled incident direction (unit, local frame).
    pub wi: RadVec3,
    /// Its solid-angle density (> 0 for a valid sample).
    pub pdf: f32,
    /// `f_r · cos θi / pdf`.
    pub weight: f32,
}

impl From<Option<BrdfSample<f32>>> for RadBrdfSample {
    #[inline]
    fn from(s: Option<BrdfSample<f32>>) -> Self {
        s.map_or(RadBrdfSample::default(), |s| RadBrdfSample {
            wi: s.wi.into(),
            pdf: s.pdf,
            weight: s.weight,
        })
    }
}

/// Object-safe view of a monochrome plugin (one virtual call per C call).
trait DynBrdf {
    fn eval(&self, wi: Vec3, wo: Vec3) -> f32;
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32;
    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<f32>>;
    fn eval_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]);
    fn eval_batch_soa(&self, wi: Vec3Soa<'_>, wo: Vec3Soa<'_>, out: &mut [f32]);
    fn pdf_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]);
    fn sample_batch(&self, wo: &[Vec3], u: &[[f32; 2]], out: &mut [Option<BrdfSample<f32>>]);
}

impl<B: Brdf<Spectrum = f32>> DynBrdf for B {
    fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
        Brdf::eval(self, wi, wo)
    }
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        Brdf::pdf(self, wi, wo)
    }
    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<f32>> {
        Brdf::sample(self, wo, u)
    }
    fn eval_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]) {
        Brdf::eval_batch(self, wi, wo, out)
    }
    fn eval_batch_soa(&self, wi: Vec3Soa<'_>, wo: Vec3Soa<'_>, out: &mut [f32]) {
        Brdf::eval_batch_soa(self, wi, wo, out)
    }
    fn pdf_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]) {
        Brdf::pdf_batch(self, wi, wo, out)
    }
    fn sample_batch(&self, wo: &[Vec3], u: &[[f32; 2]], out: &mut [Option<BrdfSample<f32>>]) {
        Brdf::sample_batch(self, wo, u, out)
    }
}

fn microfacet_g<D, G, R>(
    d: D,
    fresnel: u32,
    a: f32,
    b: f32,
    f: impl FnOnce(&dyn DynBrdf) -> R,
) -> Result<R, RadStatus>
where
    D: MicrofacetDistribution,
    G: ShadowingMasking,
{
    fn run<D: MicrofacetDistribution, G: ShadowingMasking, F: Fresnel<Spectrum = f32>, R>(
        d: D,
        fr: F,
        f: impl FnOnce(&dyn DynBrdf) -> R,
    ) -> R {
        f(&Microfacet::<D, G, F>::new(d, fr))
    }
    Ok(match fresnel {
        RAD_FRESNEL_NONE => run::<D, G, _, R>(d, NoFresnel, f),
        RAD_FRESNEL_SCHLICK => run::<D, G, _, R>(d, Schlick::new(a)?, f),
        RAD_FRESNEL_DIELECTRIC => run::<D, G, _, R>(d, Dielectric::new(a)?, f),
        RAD_FRESNEL_CONDUCTOR => run::<D, G, _, R>(d, Conductor::new(a, b)?, f),
        _ => return Err(RadStatus::UnknownKind),
    })
}

fn microfacet_d<D: MicrofacetDistribution, R>(
    d: D,
    h: &RadBrdf,
    f: impl FnOnce(&dyn DynBrdf) -> R,
) -> Result<R, RadStatus> {
    let [_, a, b] = h.params;
    match h.shadowing {
        RAD_SHADOWING_HEIGHT_CORRELATED => microfacet_g::<D, HeightCorrelated, R>(d, h.fresnel, a, b, f),
        RAD_SHADOWING_SEPARABLE => microfacet_g::<D, Separable, R>(d, h.fresnel, a, b, f),
        _ => Err(RadStatus::UnknownKind),
    }
}

/// Builds the plugin that `h` describes (validating every parameter) and
/// runs `f` on it; the plugin's constructor error otherwise.
fn with_plugin<R>(h: &RadBrdf, f: impl FnOnce(&dyn DynBrdf) -> R) -> Result<R, RadStatus> {
    let [p0, p1, p2] = h.params;
    match h.kind {
        RAD_BRDF_LAMBERTIAN => Ok(f(&Lambertian::new(p0)?)),
        RAD_BRDF_PHONG => Ok(f(&ModifiedPhong::new(p0, p1, p2)?)),
        RAD_BRDF_BLINN_PHONG => Ok(f(&BlinnPhong::new(p0, p1, p2)?)),
        RAD_BRDF_MICROFACET => match h.distribution {
            RAD_DISTRIBUTION_GGX => microfacet_d(Ggx::new(p0)?, h, f),
            RAD_DISTRIBUTION_BECKMANN => microfacet_d(Beckmann::new(p0)?, h, f),
            _ => Err(RadStatus::UnknownKind),
        },
        _ => Err(RadStatus::BadHandle),
    }
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
    match with_plugin(&h, |_| ()) {
        Ok(()) => {
            *out = h;
            RadStatus::Ok
        }
        Err(s) => s,
    }
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
        ..RadBrdf::default()
    };
    // SAFETY: forwarded caller contract.
    unsafe { construct(h, out) }
}

/// Microfacet BRDF `D(h) G2(ωi, ωo) F(ωo·h) / (4 cos θi cos θo)` (Walter et al.
/// 2007, eq. 20): `distribution` = `RAD_DISTRIBUTION_GGX | _BECKMANN` with
/// roughness `alpha ∈ [1e-4, 1]`, `shadowing` = `RAD_SHADOWING_*`, `fresnel` =
/// `RAD_FRESNEL_*` with its parameters in `fresnel_a`, `fresnel_b` (see the
/// constants).
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
    let h = RadBrdf {
        kind: RAD_BRDF_MICROFACET,
        distribution,
        shadowing,
        fresnel,
        params: [alpha, fresnel_a, fresnel_b],
    };
    // SAFETY: forwarded caller contract.
    unsafe { construct(h, out) }
}

fn status(r: Result<(), RadStatus>) -> RadStatus {
    r.err().unwrap_or(RadStatus::Ok)
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
    status((|| {
        // SAFETY: forwarded caller contract.
        let (h, out) = unsafe { (as_ref(brdf)?, as_mut(out)?) };
        *out = with_plugin(h, |b| b.eval(wi.into(), wo.into()))?;
        Ok(())
    })())
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
    status((|| {
        // SAFETY: forwarded caller contract.
        let (h, out) = unsafe { (as_ref(brdf)?, as_mut(out)?) };
        *out = with_plugin(h, |b| b.pdf(wi.into(), wo.into()))?;
        Ok(())
    })())
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
    status((|| {
        // SAFETY: forwarded caller contract.
        let (h, out) = unsafe { (as_ref(brdf)?, as_mut(out)?) };
        *out = with_plugin(h, |b| b.sample(wo.into(), [u0, u1]))?.into();
        Ok(())
    })())
}

/// Views `[RadVec3]` as `[Vec3]`.
fn as_vec3(v: &[RadVec3]) -> &[Vec3] {
    // SAFETY: `RadVec3` and `glam::Vec3` are both `#[repr(C)]` structs of
    // three `f32` named x, y, z in that order (size and alignment asserted
    // equal in `ptr.rs`), so the pointer and length describe the same
    // initialised memory as `[Vec3]`; the lifetime is carried over.
    unsafe { core::slice::from_raw_parts(v.as_ptr().cast::<Vec3>(), v.len()) }
}

/// Shared argument handling of the two-direction batch calls.
///
/// # Safety
/// As [`rad_brdf_eval_batch`].
unsafe fn pair_batch(
    brdf: *const RadBrdf,
    wi: *const RadVec3,
    wo: *const RadVec3,
    out: *mut f32,
    n: usize,
    run: impl FnOnce(&dyn DynBrdf, &[Vec3], &[Vec3], &mut [f32]),
) -> RadStatus {
    status((|| {
        // SAFETY: forwarded caller contract.
        let (h, wi, wo) = unsafe { (as_ref(brdf)?, slice(wi, n)?, slice(wo, n)?) };
        // SAFETY: forwarded caller contract; `out` is checked to overlap
        // neither input.
        let out = unsafe { slice_mut_disjoint(out, n, &[span(wi), span(wo)])? };
        with_plugin(h, |b| run(b, as_vec3(wi), as_vec3(wo), out))
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
    unsafe { pair_batch(brdf, wi, wo, out, n, |b, wi, wo, out| b.eval_batch(wi, wo, out)) }
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
    unsafe { pair_batch(brdf, wi, wo, out, n, |b, wi, wo, out| b.pdf_batch(wi, wo, out)) }
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
    status((|| {
        // SAFETY: forwarded caller contract.
        let h = unsafe { as_ref(brdf)? };
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
        with_plugin(h, |b| b.eval_batch_soa(wi, wo, out))
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
    status((|| {
        // SAFETY: forwarded caller contract; `[f32; 2]` has the size of two
        // `f32` and the alignment of one, so `2n` floats are `n` pairs.
        let (h, wo, u) = unsafe { (as_ref(brdf)?, slice(wo, n)?, slice(u.cast::<[f32; 2]>(), n)?) };
        // SAFETY: forwarded caller contract; `out` is checked to overlap
        // neither input.
        let out = unsafe { slice_mut_disjoint(out, n, &[span(wo), span(u)])? };
        with_plugin(h, |b| {
            // The plugin writes `Option<BrdfSample>`s; go through a stack
            // buffer (no heap) in chunks.
            const CHUNK: usize = 64;
            let mut buf = [None; CHUNK];
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
