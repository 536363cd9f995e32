//! The integration tests of `radiometry`: one test binary, each suite a module
//! (one binary links and starts once; ~20 binaries made the first `cargo test`
//! compile-bound). Run one suite with `cargo test -p radiometry --test integration energy::`.
//!
//! `Cargo.toml` sets `autotests = false` and names this file as the only test target, so
//! the files below are not compiled as binaries of their own.

mod common;

mod energy;
mod honesty;
mod illumination;
mod integrators;
mod isotropy;
mod photometry;
mod reciprocity;
mod references;
mod sampling;
mod sensor;
mod sensor_als;
mod sensor_calibration;
mod sensor_color;
mod sensor_emva;
mod sensor_hard_cases;
mod spectral;
mod stability;
