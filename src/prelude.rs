//! The names most code needs, in one import:
//!
//! ```
//! use radiometry::prelude::*;
//!
//! struct Half;
//! impl Brdf for Half {
//!     type Spectrum = f32;
//!     fn eval(&self, _wi: Vec3, _wo: Vec3) -> f32 { 0.5 / core::f32::consts::PI }
//! }
//! let frame = Frame::from_normal(Vec3::new(0.0, 1.0, 1.0)).unwrap();
//! let wo = frame.to_local(Vec3::new(0.0, 0.6, 0.8));
//! let albedo = DirectionalAlbedo { brdf: Half, wo };
//! let e = Adaptive::new(0.0, 1e-6).unwrap().integrate(&albedo, 1024).unwrap();
//! assert!((e.value - 0.5).abs() < 1e-4);
//! ```
//!
//! | name | what it is |
//! |---|---|
//! | [`Brdf`], [`IsotropicBrdf`], [`BrdfSample`] | the BRDF traits and a sample |
//! | [`Frame`], [`Vec3`] | the local shading frame and glam's vector |
//! | [`Spectrum`], [`SampledSpectrum`] | value types (`f32`, RGB `Vec3`, sampled) |
//! | [`Integrand`], [`Integrator`], [`Estimate`], [`IntegrateError`], [`Status`] | hemisphere integration |
//! | [`Adaptive`], [`Auto`], [`GaussLegendre`], [`WarpedGaussLegendre`], [`MonteCarlo`] | the integrators |
//! | [`DirectionalAlbedo`], [`integrate_to_tolerance`] | the albedo integrand and the tolerance driver |
//! | [`Light`], [`LightIntegrals`], [`reflected_radiance`] | lights (also as `&dyn Light`) and the reflection equation |
//! | [`Pcg32`] | the crate's random number generator |

pub use crate::brdf::{Brdf, BrdfSample, IsotropicBrdf};
pub use crate::frame::Frame;
pub use crate::integrator::{
    Adaptive, Auto, DirectionalAlbedo, Estimate, GaussLegendre, Integrand, IntegrateError, Integrator,
    MonteCarlo, Status, WarpedGaussLegendre, integrate_to_tolerance,
};
pub use crate::light::{Light, LightIntegrals, reflected_radiance};
pub use crate::rng::Pcg32;
pub use crate::spectrum::{SampledSpectrum, Spectrum};
pub use glam::Vec3;
