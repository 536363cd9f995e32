//! Tabulated (measured) isotropic BRDFs on a Rusinkiewicz half/difference
//! grid.
//!
//! * [`RusinkiewiczGrid`]: the `(θh, θd, φd)` grid (MERL layout and other
//!   resolutions) and the change of variables of Rusinkiewicz 1998.
//! * [`Tabulated`]: the BRDF plugin over a table borrowed from the caller,
//!   trilinear interpolation, and importance sampling with an exact pdf
//!   from a half-vector distribution built into a caller-provided buffer
//!   (module [`sampling`]).
//!
//! Reading and writing MERL `.binary` files is std-side work (the
//! `radiometry-spec` crate, module `merl`).

#[cfg(feature = "simd")]
mod batch;
mod coords;
pub mod error;
pub mod grid;
pub mod sampling;
mod table;

pub use error::TabulatedError;
pub use grid::RusinkiewiczGrid;
pub use sampling::HalfVectorDistribution;
pub use table::Tabulated;

/// Largest table value accepted (per channel, after the caller's scaling):
/// a convex combination of values `≤ 10³⁰` cannot overflow `f32`.
pub const MAX_VALUE: f32 = 1e30;
