//! C API of the radiometry crates, for sensor-board firmware and C renderers.
//!
//! `no_std`, no heap: every object is a plain C struct that the caller owns (on
//! the stack, in a static, anywhere), filled in by a constructor that validates
//! its parameters and returns a [`RadStatus`]. Nothing here aborts or panics on
//! bad input: null or misaligned pointers, overlapping buffers, NaN and
//! out-of-range parameters, and handles the caller has scribbled over are all
//! reported as a status code.
//!
//! * BRDF plugins ([`RadBrdf`]): Lambertian, modified Phong, Blinn–Phong, the
//!   microfacet family (GGX / Beckmann × Smith height-correlated / separable ×
//!   Fresnel none / Schlick / dielectric / conductor / F82-tint / a named
//!   metal), the rough diffuse EON, FON and classic Oren–Nayar, and sheen;
//!   `eval`, `pdf`, `sample`, single and batched ([`brdf`]).
//! * Materials ([`RadMaterial`]): a sum, a mix or a coat of two plugins
//!   (a plastic, a coated metal), built once, evaluated like a plugin
//!   ([`material`]).
//! * OpenPBR Surface's reflection layer ([`RadOpenPbr`]): the 15 OpenPBR
//!   parameters in [`RadOpenPbrParams`], built once (three albedo tables
//!   kept in the struct), evaluated like a plugin ([`openpbr`]).
//! * Ambient-light sensors: raw counts → lux with dark offset, calibration and
//!   spectral mismatch correction ([`als`]).
//! * Irradiance closed forms: uniform sky, directional light, spherical cap
//!   ([`irradiance`]).
//!
//! Colour: every handle holds its colours per channel (R, G, B, linear sRGB)
//! beside their monochrome values. The `rad_*_eval`, `_pdf`, `_sample` calls
//! and their batches are monochrome (`f32`, each colour by its Rec. 709
//! luminance: the cheap path); the `rad_*_eval_rgb`, `_pdf_rgb`,
//! `_sample_rgb` calls and their batches evaluate per channel
//! (`RadBrdfSample::weight` is `float[3]` in both; a batch of RGB values is
//! `3n` floats). A grey handle gives the monochrome value on each channel.
//!
//! The header `include/radiometry.h` is generated from this crate by cbindgen
//! (`cbindgen --config cbindgen.toml --output include/radiometry.h` in `ffi/`).
//!
//! ```c
//! RadBrdf ggx;
//! if (rad_brdf_microfacet(RAD_DISTRIBUTION_GGX, 1.0f, RAD_SHADOWING_HEIGHT_CORRELATED,
//!                         RAD_FRESNEL_NONE, 0.0f, 0.0f, &ggx) != RAD_STATUS_OK) { ... }
//! float f;
//! rad_brdf_eval(&ggx, (RadVec3){0, 0, 1}, (RadVec3){0, 0, 1}, &f); // f = 1/π
//! ```
#![no_std]
#![deny(unsafe_op_in_unsafe_fn)]
#![warn(missing_docs)]

#[cfg(any(test, feature = "std"))]
extern crate std;

pub mod als;
pub mod brdf;
pub mod irradiance;
pub mod material;
pub mod openpbr;
mod ptr;
pub mod spectrum;
mod status;

pub use als::RadAlsCalibration;
pub use brdf::{RadBrdf, RadBrdfSample};
pub use material::RadMaterial;
pub use openpbr::{RadOpenPbr, RadOpenPbrParams};
pub use spectrum::RadSpectrum;
pub use status::{RadStatus, rad_status_message};

/// A 3-vector of `f32` (a direction in the local shading frame: normal on +Z,
/// pointing away from the surface). Same layout as `float[3]`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RadVec3 {
    /// x component.
    pub x: f32,
    /// y component.
    pub y: f32,
    /// z component (along the normal).
    pub z: f32,
}

impl From<RadVec3> for radiometry::glam::Vec3 {
    #[inline]
    fn from(v: RadVec3) -> Self {
        radiometry::glam::Vec3::new(v.x, v.y, v.z)
    }
}

impl From<radiometry::glam::Vec3> for RadVec3 {
    #[inline]
    fn from(v: radiometry::glam::Vec3) -> Self {
        RadVec3 {
            x: v.x,
            y: v.y,
            z: v.z,
        }
    }
}

/// Builds without std: a panic (there is no reachable one in the public
/// functions, which return status codes; see `size-check/`, whose proof
/// covers every exported function) aborts, never spins: the C library's
/// `abort()` on hosted targets, a permanently undefined instruction (a
/// HardFault, the firmware's abort) on bare-metal Arm.
#[cfg(all(not(test), not(feature = "std"), not(feature = "prove-no-panic")))]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    abort_now()
}

#[cfg(all(
    not(test),
    not(feature = "std"),
    not(feature = "prove-no-panic"),
    not(target_os = "none")
))]
fn abort_now() -> ! {
    unsafe extern "C" {
        fn abort() -> !;
    }
    // SAFETY: the C library's `abort` takes no arguments and never returns.
    unsafe { abort() }
}

#[cfg(all(
    not(test),
    not(feature = "std"),
    not(feature = "prove-no-panic"),
    target_os = "none"
))]
fn abort_now() -> ! {
    #[cfg(target_arch = "arm")]
    // SAFETY: `udf` raises an undefined-instruction exception (HardFault on
    // Cortex-M); it touches no memory and does not return to this code.
    unsafe {
        core::arch::asm!("udf #0", options(noreturn, nomem, nostack));
    }
    #[cfg(not(target_arch = "arm"))]
    loop {
        core::hint::spin_loop();
    }
}

// With `prove-no-panic`, the panic handler calls a function that exists
// nowhere: an executable that uses the library links only if the optimiser
// removed every panic path from the functions it calls (see size-check/).
#[cfg(all(not(test), not(feature = "std"), feature = "prove-no-panic"))]
unsafe extern "C" {
    fn radiometry_ffi_panic_path_survived_optimisation() -> !;
}

#[cfg(all(not(test), not(feature = "std"), feature = "prove-no-panic"))]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    // SAFETY: never called in an image that links; see above.
    unsafe { radiometry_ffi_panic_path_survived_optimisation() }
}

// The precompiled `core` refers to the unwinding personality routine even
// under `panic = "abort"`, so a hosted program or shared library that links
// this `no_std` library needs a definition (never called: nothing unwinds).
// It is a *weak* symbol: beside another Rust library (whose std defines the
// routine) the linker takes that definition instead of reporting a duplicate.
// Linux on x86_64 and AArch64; other hosted targets keep a plain definition.
#[cfg(all(
    not(test),
    not(feature = "std"),
    target_os = "linux",
    any(target_arch = "x86_64", target_arch = "aarch64")
))]
core::arch::global_asm!(
    ".pushsection .text.rust_eh_personality,\"ax\",%progbits",
    ".weak rust_eh_personality",
    ".type rust_eh_personality,%function",
    ".hidden rust_eh_personality",
    "rust_eh_personality:",
    "ret",
    ".size rust_eh_personality, . - rust_eh_personality",
    ".popsection",
);

#[cfg(all(
    not(test),
    not(feature = "std"),
    not(target_os = "none"),
    not(all(target_os = "linux", any(target_arch = "x86_64", target_arch = "aarch64")))
))]
#[unsafe(no_mangle)]
extern "C" fn rust_eh_personality() {}
