//! # radiometry-brdfs
//!
//! BRDF plugins for [`radiometry`]. Each plugin lives in its own module,
//! uses only the public trait API of `radiometry` (exactly what a
//! third-party plugin would do), validates its parameters at construction
//! and documents the formula it implements.
#![no_std]
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod blinn_phong;
pub mod error;
pub mod lambertian;
pub mod microfacet;
pub mod phong;
#[cfg(feature = "simd")]
pub mod simd;
pub mod tabulated;
mod vec4;

pub use error::BrdfError;
// -- re-exports: Lambertian / Phong family (keep this block for those modules)
pub use blinn_phong::BlinnPhong;
pub use lambertian::Lambertian;
pub use phong::ModifiedPhong;
// -- end Lambertian / Phong family
// -- re-exports: microfacet (keep this block for that module)
pub use microfacet::{
    Beckmann, Conductor, Dielectric, Fresnel, Ggx, HeightCorrelated, KullaConty, Microfacet,
    MicrofacetDistribution, NoFresnel, Schlick, Separable, ShadowingMasking,
};
// -- end microfacet
