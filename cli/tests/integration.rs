//! The integration tests of `radiometry-cli`: one test binary, each suite a module.
//! Run one suite with `cargo test -p radiometry-cli --test integration fit::`.
//!
//! `Cargo.toml` sets `autotests = false` and names this file as the only test target.

mod analytic;
mod auto_vs_quadpack;
mod bench;
mod cli;
mod fit;
mod fit_cli;
mod merl;
mod preview;
mod sensor;
