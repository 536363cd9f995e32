//! The integration tests of `radiometry-brdfs`: one test binary, each suite a module.
//! Run one suite with `cargo test -p radiometry-brdfs --test integration batch::`
//! (add `--features simd` for the vector kernels).
//!
//! `Cargo.toml` sets `autotests = false` and names this file as the only test target.

mod batch;
mod checked;
mod kulla_conty;
mod ltc_sheen;
mod microfacet_albedo;
mod mixture;
mod openpbr_conformance;
mod sample_batch;
mod sheen;
mod tabulated;
