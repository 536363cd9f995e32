//! [`RadStatus`]: the return code of every fallible C function.

use radiometry::compose::ComposeError;
use radiometry::light::LightError;
use radiometry::sensor::SensorError;
use radiometry::sensor::als::AlsError;
use radiometry::spectral::SpectralError;
use radiometry_brdfs::BrdfError;

/// What a C API call did. `RAD_STATUS_OK` (0) is success; every other value
/// says why nothing was written to the output.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RadStatus {
    /// Success: the outputs are written.
    Ok = 0,
    /// A required pointer is null.
    NullPointer = 1,
    /// A pointer is not aligned for its type (4 bytes for `float`).
    Misaligned = 2,
    /// An output buffer overlaps an input buffer.
    Overlap = 3,
    /// A parameter is NaN or infinite.
    NotFinite = 4,
    /// A parameter is outside its documented range.
    OutOfRange = 5,
    /// A combination of parameters violates a constraint (e.g. `kd + ks ≤ 1`,
    /// or a classic Oren–Nayar `rho` that would reflect more than 1).
    Constraint = 6,
    /// A selector (`kind`, distribution, shadowing, Fresnel) has no meaning.
    UnknownKind = 7,
    /// A handle's fields do not describe a valid object (not made by its
    /// constructor, or overwritten since).
    BadHandle = 8,
    /// The sensor reading is at the ADC full scale: the light is brighter than
    /// the sensor can tell. Lower the gain or the integration time.
    Saturated = 9,
    /// Gain or integration time is not finite and > 0.
    BadSetting = 10,
    /// A spectral integral is zero (the detector or the eye sees nothing of a
    /// source), so the correction factor does not exist.
    Singular = 11,
    /// A buffer length is too large for the address space.
    TooLong = 12,
}

impl From<BrdfError> for RadStatus {
    fn from(e: BrdfError) -> Self {
        match e {
            BrdfError::NotFinite { .. } => RadStatus::NotFinite,
            BrdfError::OutOfRange { .. } => RadStatus::OutOfRange,
            BrdfError::Constraint { .. } | BrdfError::EnergyGain { .. } => RadStatus::Constraint,
            // A saved albedo table that fails its check was not written by
            // `rad_openpbr_new` (or was overwritten since).
            BrdfError::AlbedoTable { .. } => RadStatus::BadHandle,
            // The Rust error enums are #[non_exhaustive]: a variant added
            // later maps to the generic out-of-range status.
            _ => RadStatus::OutOfRange,
        }
    }
}

impl From<ComposeError> for RadStatus {
    fn from(e: ComposeError) -> Self {
        let value = match e {
            // A saved albedo table that fails its check was not written by
            // `rad_material_coated` (or was overwritten since).
            ComposeError::AlbedoTable(_) => return RadStatus::BadHandle,
            ComposeError::Weight(v)
            | ComposeError::Scale(v)
            | ComposeError::CoatColor(v)
            | ComposeError::CoatIor(v) => v,
            _ => return RadStatus::OutOfRange,
        };
        if value.is_finite() {
            RadStatus::OutOfRange
        } else {
            RadStatus::NotFinite
        }
    }
}

impl From<SensorError> for RadStatus {
    fn from(e: SensorError) -> Self {
        match e {
            SensorError::NotFinite => RadStatus::NotFinite,
            SensorError::BadParameter(_) => RadStatus::OutOfRange,
            SensorError::NotMonotonic => RadStatus::Constraint,
            SensorError::BadBuffer => RadStatus::OutOfRange,
            SensorError::Singular => RadStatus::Singular,
            _ => RadStatus::OutOfRange,
        }
    }
}

impl From<AlsError> for RadStatus {
    fn from(e: AlsError) -> Self {
        match e {
            AlsError::Saturated => RadStatus::Saturated,
            AlsError::BadSetting => RadStatus::BadSetting,
            _ => RadStatus::OutOfRange,
        }
    }
}

impl From<SpectralError> for RadStatus {
    fn from(e: SpectralError) -> Self {
        match e {
            SpectralError::NotFinite => RadStatus::NotFinite,
            _ => RadStatus::OutOfRange,
        }
    }
}

impl From<LightError> for RadStatus {
    fn from(e: LightError) -> Self {
        match e {
            LightError::NonFiniteRadiance => RadStatus::NotFinite,
            LightError::NegativeRadiance
            | LightError::RadianceTooLarge
            | LightError::HalfAngleOutOfRange(_)
            | LightError::InvalidDirection => RadStatus::OutOfRange,
            _ => RadStatus::OutOfRange,
        }
    }
}

/// A static, NUL-terminated English description of a status code (any
/// integer: unknown codes get "unknown status"). Never null.
#[unsafe(no_mangle)]
pub extern "C" fn rad_status_message(status: i32) -> *const core::ffi::c_char {
    let s: &'static core::ffi::CStr = match status {
        0 => c"ok",
        1 => c"a required pointer is null",
        2 => c"a pointer is not aligned for its type",
        3 => c"an output buffer overlaps an input buffer",
        4 => c"a parameter is NaN or infinite",
        5 => c"a parameter is outside its range",
        6 => c"parameters violate a constraint (e.g. kd + ks <= 1)",
        7 => c"unknown kind / distribution / shadowing / fresnel selector",
        8 => c"the handle does not describe a valid object",
        9 => c"sensor saturated: lower the gain or integration time",
        10 => c"gain and integration time must be finite and > 0",
        11 => c"spectral integral is zero: correction undefined",
        12 => c"buffer length too large",
        _ => c"unknown status",
    };
    s.as_ptr()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_status_has_its_own_message() {
        let mut seen = std::vec::Vec::new();
        for code in 0..=12 {
            // SAFETY: rad_status_message returns a pointer to a static C string.
            let m = unsafe { core::ffi::CStr::from_ptr(rad_status_message(code)) };
            assert_ne!(m.to_bytes(), b"unknown status", "code {code}");
            assert!(!seen.contains(&m), "code {code} repeats a message");
            seen.push(m);
        }
        // SAFETY: as above.
        let m = unsafe { core::ffi::CStr::from_ptr(rad_status_message(-3)) };
        assert_eq!(m.to_bytes(), b"unknown status");
    }
}
