//! # radiometry
//!
//! `no_std` radiometry and reflectance math: the local shading frame, spectra,
//! the [`Brdf`] trait that BRDF plugins implement, sampling warps with their
//! densities, and radiometric closed forms.
//!
//! The crate never allocates and never panics on finite input. Evaluation is
//! `f32` (renderers, firmware); reference computations and integrators
//! accumulate in `f64`.
//!
//! Conventions: every BRDF works in a local frame whose
//! normal is `+Z`; directions are unit vectors pointing *away* from the
//! surface, `wi` toward the light and `wo` toward the viewer.
//!
//! ```
//! use radiometry::{Brdf, BrdfSample, frame, glam::Vec3};
//!
//! /// A user-defined BRDF needs only `eval`; sampling defaults to cosine-weighted.
//! struct Constant(f32);
//! impl Brdf for Constant {
//!     type Spectrum = f32;
//!     fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
//!         if frame::cos_theta(wi) <= 0.0 || frame::cos_theta(wo) <= 0.0 { 0.0 } else { self.0 }
//!     }
//! }
//! let b = Constant(0.5 / core::f32::consts::PI);
//! let s: BrdfSample<f32> = b.sample(Vec3::Z, [0.3, 0.7]).unwrap();
//! assert!((s.weight - 0.5).abs() < 1e-6); // f·cosθ/pdf = ρ for a Lambertian
//! ```
#![no_std]
#![deny(unsafe_code)]
#![warn(missing_docs)]

pub use glam;
/// The RNG interface of [`rng::Pcg32`] and of the sensor noise models
/// (`rand_core` 0.10), re-exported so callers name the same version.
pub use rand_core;

pub mod batch;
pub mod brdf;
pub mod compose;
pub mod frame;
pub mod integrator;
pub mod light;
pub mod math;
pub mod prelude;
pub mod radiometric;
pub mod rng;
pub mod sensor;
pub mod spectral;
pub mod spectrum;
pub mod warp;

pub use brdf::{Albedo, Brdf, BrdfSample, IsotropicBrdf};
pub use frame::Frame;
pub use integrator::{Estimate, Integrand, IntegrateError, Integrator};
pub use spectrum::{SampledSpectrum, Spectrum, WideSpectrum};

/// The README's examples, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;

/// The Rust examples of `docs/rust.md`, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../docs/rust.md")]
pub struct DocsRustDoctests;

/// The Rust examples of `docs/firmware.md`, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../docs/firmware.md")]
pub struct DocsFirmwareDoctests;

/// The Rust examples of `docs/materials.md`, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../docs/materials.md")]
pub struct DocsMaterialsDoctests;

/// The Rust examples of `docs/measured.md`, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../docs/measured.md")]
pub struct DocsMeasuredDoctests;
