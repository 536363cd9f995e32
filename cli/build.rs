//! Records the build profile for the header of `radiometry bench`.

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    for var in ["PROFILE", "OPT_LEVEL"] {
        let v = std::env::var(var).unwrap_or_else(|_| "unknown".into());
        println!("cargo:rustc-env=RADIOMETRY_BUILD_{var}={v}");
    }
}
