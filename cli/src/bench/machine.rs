//! What `radiometry bench` reports about the machine and the build: the
//! CPU model, the SIMD target features compiled in and detected, the build
//! profile.

/// A SIMD-relevant target feature.
#[derive(Clone, Copy, Debug)]
pub(super) struct Feature {
    pub(super) name: &'static str,
    /// Enabled at compile time (`cfg!(target_feature = ...)`).
    pub(super) compiled: bool,
    /// The CPU has it (run-time detection; `None` where not available).
    pub(super) cpu: Option<bool>,
}

/// The SIMD-relevant target features of this architecture.
pub(super) fn simd_features() -> Vec<Feature> {
    #[allow(unused_mut)]
    let mut v = Vec::new();
    #[cfg(target_arch = "x86_64")]
    {
        macro_rules! f {
            ($name:tt) => {
                v.push(Feature {
                    name: $name,
                    compiled: cfg!(target_feature = $name),
                    cpu: Some(std::arch::is_x86_feature_detected!($name)),
                })
            };
        }
        f!("sse2");
        f!("sse4.1");
        f!("avx");
        f!("avx2");
        f!("fma");
        f!("avx512f");
    }
    #[cfg(target_arch = "aarch64")]
    {
        v.push(Feature {
            name: "neon",
            compiled: cfg!(target_feature = "neon"),
            cpu: Some(std::arch::is_aarch64_feature_detected!("neon")),
        });
    }
    v
}

/// `model name` from `/proc/cpuinfo`, or `"unknown"`.
pub(super) fn cpu_model() -> String {
    std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split_once(':'))
                .map(|(_, v)| v.trim().to_string())
        })
        .filter(|s| !s.is_empty())
        .unwrap_or_else(|| "unknown".into())
}

/// Build profile as recorded by `build.rs` (`PROFILE`, `OPT_LEVEL`).
pub(super) fn profile() -> (&'static str, &'static str) {
    (
        option_env!("RADIOMETRY_BUILD_PROFILE").unwrap_or("unknown"),
        option_env!("RADIOMETRY_BUILD_OPT_LEVEL").unwrap_or("unknown"),
    )
}
