//! The library half of the `radiometry` tool, kept so that code written
//! against `radiometry_cli::…` paths keeps compiling: the modules live in the
//! library crates `radiometry-spec` (the spec grammar, the run-time BRDF and
//! integrator, MERL I/O) and `radiometry-tools` (the report, the references,
//! fitting), which other front ends (the Python module in `python/`) use
//! directly. The binary (`src/main.rs`) adds the command line, `bench`,
//! `furnace`, `tabulate` and `sensor`.
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub use radiometry_spec as spec;
pub use radiometry_spec::{merl, model};
pub use radiometry_tools::{fit, reference, tradeoff};
