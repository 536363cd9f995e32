//! [`RadSpectrum`]: a spectral curve described in C (a built-in CIE table, a
//! black body, or the caller's own uniformly tabulated values).

use crate::RadStatus;
use crate::ptr::slice;
use radiometry::spectral::{Blackbody, IlluminantA, SpectralCurve, Tabulated, d65, photopic_v};

/// `RadSpectrum::kind`: CIE standard illuminant D65 (relative SPD, 300–830 nm,
/// CIE 015:2018 Table T.1).
pub const RAD_SPECTRUM_D65: u32 = 1;
/// `RadSpectrum::kind`: CIE standard illuminant A (relative SPD, 100 at 560 nm;
/// CIE 015:2018 eq. 4.1).
pub const RAD_SPECTRUM_A: u32 = 2;
/// `RadSpectrum::kind`: Planck's law at `temperature_k` (spectral radiance,
/// W m⁻² sr⁻¹ nm⁻¹).
pub const RAD_SPECTRUM_BLACKBODY: u32 = 3;
/// `RadSpectrum::kind`: the CIE 1924 photopic luminous efficiency V(λ)
/// (e.g. the responsivity of an ideal, photopically matched detector).
pub const RAD_SPECTRUM_PHOTOPIC_V: u32 = 4;
/// `RadSpectrum::kind`: `len ≥ 2` caller values at `start_nm + i·step_nm`,
/// linearly interpolated, zero outside (the `values` memory must stay valid
/// for the call that uses the spectrum).
pub const RAD_SPECTRUM_TABULATED: u32 = 5;

/// A spectral curve: set `kind` and the fields it uses (others are ignored;
/// zero them).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct RadSpectrum {
    /// One of the `RAD_SPECTRUM_*` kinds.
    pub kind: u32,
    /// Black-body temperature in kelvin (`RAD_SPECTRUM_BLACKBODY`), > 0.
    pub temperature_k: f32,
    /// First wavelength in nm (`RAD_SPECTRUM_TABULATED`).
    pub start_nm: f32,
    /// Wavelength step in nm, > 0 (`RAD_SPECTRUM_TABULATED`).
    pub step_nm: f32,
    /// The tabulated values (`RAD_SPECTRUM_TABULATED`), finite.
    pub values: *const f32,
    /// Number of values, ≥ 2 (`RAD_SPECTRUM_TABULATED`).
    pub len: usize,
}

/// The Rust curve a [`RadSpectrum`] describes.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Curve<'a> {
    Table(Tabulated<'a>),
    A,
    Planck(Blackbody),
}

impl SpectralCurve for Curve<'_> {
    #[inline]
    fn value(&self, lambda_nm: f32) -> f32 {
        match self {
            Curve::Table(t) => t.value(lambda_nm),
            Curve::A => IlluminantA.value(lambda_nm),
            Curve::Planck(b) => b.value(lambda_nm),
        }
    }
    fn support(&self) -> (f32, f32) {
        match self {
            Curve::Table(t) => t.support(),
            Curve::A => IlluminantA.support(),
            Curve::Planck(b) => b.support(),
        }
    }
}

impl RadSpectrum {
    /// Validates the description and returns the curve.
    ///
    /// # Safety
    /// For `RAD_SPECTRUM_TABULATED`, `values` is null or points to `len`
    /// readable floats valid for `'a`.
    pub(crate) unsafe fn curve<'a>(&self) -> Result<Curve<'a>, RadStatus> {
        Ok(match self.kind {
            RAD_SPECTRUM_D65 => Curve::Table(d65()),
            RAD_SPECTRUM_A => Curve::A,
            RAD_SPECTRUM_BLACKBODY => Curve::Planck(Blackbody::new(self.temperature_k)?),
            RAD_SPECTRUM_PHOTOPIC_V => Curve::Table(photopic_v()),
            RAD_SPECTRUM_TABULATED => {
                if self.len < 2 {
                    return Err(RadStatus::OutOfRange);
                }
                // SAFETY: forwarded caller contract.
                let v = unsafe { slice(self.values, self.len)? };
                Curve::Table(Tabulated::new(self.start_nm, self.step_nm, v)?)
            }
            _ => return Err(RadStatus::UnknownKind),
        })
    }
}
