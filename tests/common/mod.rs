//! Shared harness of the cross-plugin test suites (issue 2, "What it must show").
//!
//! Everything here is written independently of the code under test and in `f64`:
//! * [`rng`]: a seeded SplitMix64 generator (Steele, Lea & Flood 2014) for sample points in `[0,1)`;
//! * [`special`]: `ln Γ`, the regularized incomplete gamma functions and the χ² survival function;
//! * [`quad`]: Gauss–Legendre rules (nodes by Newton's method on `P_n`) and an adaptive, error-estimating
//!   1-D / spherical quadrature in a frame whose pole is chosen by the caller (e.g. the mirror direction);
//! * [`chi2`]: the χ² goodness-of-fit test of a [`radiometry::Brdf`] sampler against its own `pdf`;
//! * [`strategies`]: proptest strategies that deliberately hit the edges of the parameter domains;
//! * [`plugins`]: the list of every plugin configuration of `radiometry-brdfs`, built behind one trait object.
//!
//! Each test file includes it with `mod common;` and uses only a part of it.
#![allow(dead_code)]

pub mod chi2;
pub mod quad;
pub mod rng;
pub mod special;
pub mod strategies;
