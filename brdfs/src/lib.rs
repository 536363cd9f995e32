//! # radiometry-brdfs
//!
//! BRDF plugins for [`radiometry`]. Each plugin lives in its own module,
//! uses only the public trait API of `radiometry` (exactly what a
//! third-party plugin would do), validates its parameters at construction
//! and documents the formula it implements.
#![no_std]
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod error;

pub use error::BrdfError;
