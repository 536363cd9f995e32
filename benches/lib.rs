//! Criterion benchmarks of the radiometry crates; see `throughput.rs`
//! (`cargo bench -p radiometry-benches`). The library is empty: the package
//! exists so that criterion is a dependency of the benches only, not of the
//! tests of the published crates.
