//! The `std` tools of the radiometry crates, shared by the `radiometry`
//! command-line tool and the Python module:
//!
//! | module | what it does |
//! |---|---|
//! | [`tradeoff`] | the accuracy-vs-time report: every integrator over a ladder of budgets and to a tolerance, on a suite of directional albedos and product integrals, against independent references (CSV, `summary.md`, SVG plots with the `plot` feature) |
//! | [`reference`](mod@reference) | independent `f64` references: the BRDF models re-implemented from their papers, integrated by nested adaptive Gauss–Kronrod quadrature |
//! | [`preview`] | a material-ball renderer: a sphere with any BRDF under a sun and a sky, by BRDF sampling, light sampling and multiple importance sampling (PNG / SVG with the `plot` feature) |
//! | [`energy_tables`] | the generator of the global energy tables of GGX with a Fresnel factor (`radiometry_brdfs::microfacet::fresnel_table`) |
//! | [`fit`] | fitting a microfacet model (+ Fresnel, + diffuse) to a tabulated BRDF |
//! | [`merl`], [`model`], [`spec`] | re-exported from `radiometry-spec`: MERL I/O, the run-time BRDF and integrator, the spec grammar |
//!
//! ```
//! use radiometry_tools::reference::{RefModel, albedo};
//!
//! // The directional albedo of a Lambertian surface is its albedo.
//! let r = albedo(&RefModel::Lambertian { albedo: 0.5 }, 0.3);
//! assert!((r.value - 0.5).abs() <= r.bound + 1e-12);
//! ```
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod energy_tables;
pub mod fit;
pub mod preview;
pub mod reference;
pub mod tradeoff;

pub use radiometry_spec as spec;
pub use radiometry_spec::{merl, model};

/// The crate README's examples, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
