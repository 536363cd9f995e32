//! The error type of [`Tabulated`](super::Tabulated) and
//! [`RusinkiewiczGrid`](super::RusinkiewiczGrid) constructors.

use core::fmt;

/// A table, grid or sampling buffer that cannot be used. `Display` names
/// what is wrong and where.
///
/// ```
/// use radiometry_brdfs::tabulated::{RusinkiewiczGrid, TabulatedError};
/// let e = TabulatedError::Length { expected: RusinkiewiczGrid::MERL.len(), found: 10 };
/// assert_eq!(e.to_string(), "table has 10 values per channel, the grid needs 1458000");
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum TabulatedError {
    /// Grid dimensions out of range (an axis with 0 or more than
    /// [`MAX_AXIS`](super::grid::MAX_AXIS) nodes, or more than
    /// [`MAX_LEN`](super::grid::MAX_LEN) nodes in total).
    BadDims {
        /// `[n_theta_h, n_theta_d, n_phi_d]` as given.
        dims: [usize; 3],
    },
    /// The value slice does not have one entry per grid node.
    Length {
        /// `grid.len()`.
        expected: usize,
        /// The slice length.
        found: usize,
    },
    /// A channel of a value is NaN or infinite.
    NotFinite {
        /// Flat index of the value.
        index: usize,
        /// The channel.
        channel: usize,
    },
    /// A channel of a value is negative (missing measurements must be
    /// replaced by the caller, e.g. by 0, before building the table) or
    /// above [`MAX_VALUE`](super::MAX_VALUE) (so that interpolation cannot
    /// overflow).
    OutOfRange {
        /// Flat index of the value.
        index: usize,
        /// The channel.
        channel: usize,
        /// The rejected value.
        value: f32,
    },
    /// The sampling buffer is shorter than
    /// [`Tabulated::sampling_buffer_len`](super::Tabulated::sampling_buffer_len).
    Buffer {
        /// Entries needed.
        needed: usize,
        /// Entries given.
        found: usize,
    },
    /// The cosine-lobe weight of the sampling mixture is not in `(0, 1]`.
    CosineWeight {
        /// The rejected weight.
        value: f32,
    },
}

impl fmt::Display for TabulatedError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            TabulatedError::BadDims { dims: [a, b, c] } => write!(
                f,
                "grid dimensions {a} x {b} x {c} are invalid (each axis 1..=4096 nodes, at most 2^28 in total)"
            ),
            TabulatedError::Length { expected, found } => {
                write!(
                    f,
                    "table has {found} values per channel, the grid needs {expected}"
                )
            }
            TabulatedError::NotFinite { index, channel } => {
                write!(f, "table value {index} (channel {channel}) is not finite")
            }
            TabulatedError::OutOfRange {
                index,
                channel,
                value,
            } => {
                write!(
                    f,
                    "table value {index} (channel {channel}) = {value} is outside [0, {}]",
                    super::MAX_VALUE
                )
            }
            TabulatedError::Buffer { needed, found } => {
                write!(f, "sampling buffer has {found} entries, needs {needed}")
            }
            TabulatedError::CosineWeight { value } => {
                write!(f, "cosine-lobe weight {value} is outside (0, 1]")
            }
        }
    }
}

impl core::error::Error for TabulatedError {}
