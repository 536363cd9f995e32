//! Parser for the BRDF and light specifications of the radiometry tools.
//!
//! Grammar (whitespace is ignored between tokens):
//!
//! ```text
//! brdf  := call
//! light := call ('+' call)*
//! call  := NAME [ '(' [ arg (',' arg)* [','] ] ')' ]
//! arg   := KEY '=' value
//! value := NUMBER | call
//! ```
//!
//! The one exception is `tabulated(file=PATH)`, whose path is not a token
//! (it runs to the last `)`; see [`BrdfSpec::Tabulated`]).
//!
//! `NAME`/`KEY` are `[A-Za-z_][A-Za-z0-9_-]*`; numbers are decimal with an
//! optional sign, fraction and exponent. Angles are in **degrees**. Every
//! error carries the byte span of the offending token so that
//! [`SpecError`]'s `Display` can underline it with carets.
//!
//! Shared by the `radiometry` command-line tool and the Python module: one
//! grammar, one set of error messages, and one run-time BRDF
//! ([`AnyBrdf`], from [`build_brdf`]) and integrator ([`AnyIntegrator`],
//! from [`integrator_by_name`]) for every plugin and configuration.
//!
//! ```
//! use radiometry_spec::{BrdfSpec, parse_brdf};
//!
//! assert_eq!(parse_brdf("lambertian(albedo=0.5)")?, BrdfSpec::Lambertian { albedo: [0.5; 3] });
//! let e = parse_brdf("lambertian(albdo=0.5)").unwrap_err();
//! assert_eq!(&e.spec[e.start..e.end], "albdo");
//! // Display shows the message, the spec, and carets under the offending token.
//! assert!(e.to_string().ends_with("             ^^^^^"));
//! # Ok::<(), radiometry_spec::SpecError>(())
//! ```
#![forbid(unsafe_code)]
#![warn(missing_docs)]

mod angles;
mod args;
mod brdf;
mod call;
mod error;
mod lex;
mod light;
mod tabulated;

pub mod merl;
pub mod model;
pub mod mtlx;

pub use angles::parse_angles;
pub use brdf::{
    BRDF_SPEC_HELP, BrdfSpec, Distribution, FresnelSpec, G2Kind, MAX_ALPHA, MAX_EXPONENT, MIN_ALPHA,
    MultipleScattering, OPENPBR_PARAMS, OpenPbrSpec, is_grey_colour, luminance, parse_brdf,
};
pub use call::{Arg, Call, Value, parse_call, parse_sum};
pub use error::SpecError;
pub use light::{LIGHT_SPEC_HELP, LightSpec, parse_lights};
pub use model::{
    AnyBrdf, AnyBrdfRgb, AnyIntegrator, DynBrdf, RunTimeSpectrum, all_integrators, build_brdf, build_brdf_as,
    build_brdf_rgb, integrator_by_name,
};

/// The crate README's examples, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
