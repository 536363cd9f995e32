//! The library half of the `radiometry` tool: the modules that other front
//! ends reuse (the Python module in `python/` builds BRDFs, integrators and the
//! accuracy-vs-time report through them). The binary (`src/main.rs`) adds the
//! command line, `bench` and `sensor`.
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod fit;
pub mod merl;
pub mod model;
pub mod reference;
pub mod tradeoff;

/// The spec grammar lives in the `radiometry-spec` crate; `crate::spec` keeps
/// its old path for the modules here.
pub use radiometry_spec as spec;
