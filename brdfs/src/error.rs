//! The error type of BRDF constructors.

use core::fmt;

/// A BRDF parameter outside its domain. Returned by every validating
/// constructor in this crate; `Display` names the parameter, the value and
/// the accepted range.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum BrdfError {
    /// A parameter is NaN or infinite.
    NotFinite {
        /// Parameter name.
        name: &'static str,
    },
    /// A parameter lies outside `[min, max]`.
    OutOfRange {
        /// Parameter name.
        name: &'static str,
        /// The rejected value.
        value: f32,
        /// Smallest accepted value.
        min: f32,
        /// Largest accepted value.
        max: f32,
    },
    /// A combination of parameters violates a constraint (e.g. `kd + ks ≤ 1`).
    Constraint {
        /// What is violated.
        what: &'static str,
    },
    /// A parameter would make the directional albedo exceed 1 somewhere (a
    /// model that gains energy there, e.g. the classic Oren–Nayar at small
    /// roughness and grazing view): `value` is above `max`, the largest value
    /// that keeps the albedo ≤ 1 for the other parameters given.
    EnergyGain {
        /// Parameter name.
        name: &'static str,
        /// The rejected value.
        value: f32,
        /// Largest accepted value for the other parameters given.
        max: f32,
    },
    /// A wavelength outside the range of a tabulated spectrum (e.g. the
    /// `η`, `k` table of a [`Metal`](crate::metals::Metal)).
    WavelengthOutOfRange {
        /// The requested wavelength, nm.
        lambda_nm: f32,
        /// Smallest tabulated wavelength, nm.
        min_nm: f32,
        /// Largest tabulated wavelength, nm.
        max_nm: f32,
    },
    /// A saved table of a layer's top albedo (e.g. one of
    /// an OpenPBR material) holds a value that
    /// no top reports: a node outside `[0, 1]` or not finite, or a negative
    /// or non-finite error. The table was not read from the layer it is
    /// given back to, or was overwritten since.
    AlbedoTable {
        /// The table (the layer whose top it describes).
        name: &'static str,
        /// The rejected value.
        value: f32,
    },
}

impl fmt::Display for BrdfError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            BrdfError::NotFinite { name } => write!(f, "parameter `{name}` must be finite"),
            BrdfError::OutOfRange {
                name,
                value,
                min,
                max,
            } => {
                write!(f, "parameter `{name}` = {value} is outside [{min}, {max}]")
            }
            BrdfError::Constraint { what } => write!(f, "invalid parameters: {what}"),
            BrdfError::EnergyGain { name, value, max } => write!(
                f,
                "parameter `{name}` = {value} makes the albedo exceed 1 (energy gain); at these parameters it must be ≤ {max}"
            ),
            BrdfError::WavelengthOutOfRange {
                lambda_nm,
                min_nm,
                max_nm,
            } => write!(
                f,
                "wavelength {lambda_nm} nm is outside the table's range [{min_nm}, {max_nm}] nm"
            ),
            BrdfError::AlbedoTable { name, value } => write!(
                f,
                "albedo table `{name}` holds {value}: a top's albedo is finite and in [0, 1], its error finite and ≥ 0"
            ),
        }
    }
}

impl core::error::Error for BrdfError {}

/// Checks `min ≤ value ≤ max` (and finiteness), naming the parameter.
pub fn check_range(name: &'static str, value: f32, min: f32, max: f32) -> Result<f32, BrdfError> {
    if !value.is_finite() {
        return Err(BrdfError::NotFinite { name });
    }
    if value < min || value > max {
        return Err(BrdfError::OutOfRange {
            name,
            value,
            min,
            max,
        });
    }
    Ok(value)
}

#[cfg(test)]
mod tests {
    use super::{BrdfError, check_range};

    /// The error kinds of every input class: in range (the bounds
    /// included), below, above, NaN and both infinities, for finite bounds
    /// and for an unbounded side (where `∞` is in range but not finite).
    #[test]
    fn check_range_names_each_failure() {
        let name = "p";
        for (min, max) in [(0.0, 1.0), (1.0, f32::INFINITY), (f32::NEG_INFINITY, 0.0)] {
            for v in [min, max, 0.5 * (min + max), 0.0, 1.0] {
                if v.is_finite() && (min..=max).contains(&v) {
                    assert_eq!(check_range(name, v, min, max), Ok(v), "{v} in [{min}, {max}]");
                }
            }
            for v in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
                assert_eq!(
                    check_range(name, v, min, max),
                    Err(BrdfError::NotFinite { name }),
                    "{v} in [{min}, {max}]"
                );
            }
            for v in [min - 1.0, max + 1.0, -2.0, 2.0] {
                if v.is_finite() && !(min..=max).contains(&v) {
                    assert_eq!(
                        check_range(name, v, min, max),
                        Err(BrdfError::OutOfRange {
                            name,
                            value: v,
                            min,
                            max
                        }),
                        "{v} in [{min}, {max}]"
                    );
                }
            }
        }
    }
}
