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
//! A module of the one integration-test binary (`tests/integration.rs`); each test module uses a part of it.
#![allow(dead_code)]

pub mod batch;
pub mod chi2;
pub mod plugins;
pub mod quad;
pub mod rng;
pub mod special;
pub mod strategies;

use radiometry::glam::Vec3;

/// Nudges every component of `w` by `steps` ulps (`f32::next_up`/`next_down`), sign pattern `mask`.
pub fn nudge(w: Vec3, mask: u32) -> Vec3 {
    let f = |x: f32, bit: u32| {
        if mask >> bit & 1 == 1 {
            x.next_up()
        } else {
            x.next_down()
        }
    };
    Vec3::new(f(w.x, 0), f(w.y, 1), f(w.z, 2))
}

/// Sensitivity of `g` to the rounding of its inputs: the largest `|g(wi', wo') − g(wi, wo)|` over
/// inputs nudged by one ulp per component (8 sign patterns each for `wi` and `wo`, paired). The inputs
/// of a BRDF are only known to `f32` rounding, so two mathematically equal evaluations at
/// differently-rounded inputs can differ by this much without any bug.
pub fn sensitivity(g: &dyn Fn(Vec3, Vec3) -> f32, wi: Vec3, wo: Vec3) -> f32 {
    let base = g(wi, wo);
    let mut m = 0.0f32;
    for mask in 0..8 {
        for mask2 in [mask, 7 - mask] {
            let v = g(nudge(wi, mask), nudge(wo, mask2));
            if v.is_finite() {
                m = m.max((v - base).abs());
            }
        }
    }
    m
}

/// Keeps the maximum of a non-negative `f64` statistic across threads (bit patterns of non-negative
/// floats order like the floats).
pub struct Worst(std::sync::atomic::AtomicU64, std::sync::Mutex<String>);

impl Worst {
    /// Zero.
    pub const fn new() -> Self {
        Worst(
            std::sync::atomic::AtomicU64::new(0),
            std::sync::Mutex::new(String::new()),
        )
    }
    /// Records `v` with a description of where it happened.
    pub fn record(&self, v: f64, what: impl FnOnce() -> String) {
        if v.is_nan() || v < 0.0 {
            return;
        }
        let prev = self
            .0
            .fetch_max(v.to_bits(), std::sync::atomic::Ordering::Relaxed);
        if v.to_bits() > prev {
            *self.1.lock().unwrap() = what();
        }
    }
    /// The maximum so far and where.
    pub fn get(&self) -> (f64, String) {
        (
            f64::from_bits(self.0.load(std::sync::atomic::Ordering::Relaxed)),
            self.1.lock().unwrap().clone(),
        )
    }
}

/// Proptest configuration: `cases` cases, no failure-persistence files (the regression seeds are in the
/// failure message).
pub fn config(cases: u32) -> proptest::test_runner::Config {
    proptest::test_runner::Config {
        cases,
        failure_persistence: None,
        ..proptest::test_runner::Config::default()
    }
}

/// A proptest runner with `cases` cases and a fixed seed, so that every run (and CI) checks the same
/// cases and a failure is reproducible.
pub fn runner(cases: u32) -> proptest::test_runner::TestRunner {
    let cfg = config(cases);
    let rng = proptest::test_runner::TestRng::deterministic_rng(cfg.rng_algorithm);
    proptest::test_runner::TestRunner::new_with_rng(cfg, rng)
}
