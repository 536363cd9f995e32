//! Ambient-light sensors: raw ADC counts → illuminance in lux
//! (`radiometry::sensor::als`).
//!
//! Model: `counts = dark + g·t·k ∫E(λ) s(λ) dλ` (gain `g`, integration time
//! `t`); a calibration against a reference source fixes lux per
//! `count/(g·t)`, and the spectral mismatch correction factor of CIE S 023/E:2013
//! `F = [∫E_X V / ∫E_X s] / [∫E_A V / ∫E_A s]` corrects for a source `X`
//! other than the calibration source `A`. Then
//! `E_v = max(counts − dark, 0) · lux_per_count_s · F / (g·t)`.
//! `f32` throughout; no heap.

use crate::ptr::{as_mut, as_ref};
use crate::{RadSpectrum, RadStatus};
use radiometry::sensor::als::{self, AlsCalibration};

/// The calibration of one ambient-light sensor (plain data; fill it with
/// `rad_als_new` or `rad_als_from_reference`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RadAlsCalibration {
    /// Reading in darkness, ≥ 0.
    pub dark_counts: f32,
    /// Lux per (count / (gain · seconds)) under the calibration source, > 0.
    pub lux_per_count_s: f32,
    /// Spectral mismatch correction factor for the measured source, > 0
    /// (1 for the calibration source).
    pub spectral_correction: f32,
    /// ADC full scale: a reading ≥ this is saturated. > 0.
    pub max_count: u32,
}

impl RadAlsCalibration {
    fn rust(&self) -> Result<AlsCalibration, RadStatus> {
        AlsCalibration::new(
            self.dark_counts,
            self.lux_per_count_s,
            self.spectral_correction,
            self.max_count,
        )
        .map_err(|_| RadStatus::BadHandle)
    }
}

impl From<AlsCalibration> for RadAlsCalibration {
    fn from(c: AlsCalibration) -> Self {
        RadAlsCalibration {
            dark_counts: c.dark_counts(),
            lux_per_count_s: c.lux_per_count_s(),
            spectral_correction: c.spectral_correction(),
            max_count: c.max_count(),
        }
    }
}

fn status(r: Result<(), RadStatus>) -> RadStatus {
    r.err().unwrap_or(RadStatus::Ok)
}

/// A calibration from its four numbers (ranges as the fields of
/// [`RadAlsCalibration`]).
///
/// # Safety
/// `out` is null or points to a writable `RadAlsCalibration` (unchanged on
/// error).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_als_new(
    dark_counts: f32,
    lux_per_count_s: f32,
    spectral_correction: f32,
    max_count: u32,
    out: *mut RadAlsCalibration,
) -> RadStatus {
    status((|| {
        // SAFETY: forwarded caller contract.
        let out = unsafe { as_mut(out)? };
        *out = AlsCalibration::new(dark_counts, lux_per_count_s, spectral_correction, max_count)?.into();
        Ok(())
    })())
}

/// Calibrates from one reading `counts` (at `gain`, `integration_s`) of a
/// reference source of known illuminance `reference_lux`:
/// `lux_per_count_s = lux · g · t / (counts − dark)`, correction 1.
///
/// # Safety
/// As [`rad_als_new`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_als_from_reference(
    dark_counts: f32,
    counts: f32,
    gain: f32,
    integration_s: f32,
    reference_lux: f32,
    max_count: u32,
    out: *mut RadAlsCalibration,
) -> RadStatus {
    status((|| {
        // SAFETY: forwarded caller contract.
        let out = unsafe { as_mut(out)? };
        let c = AlsCalibration::from_reference(
            dark_counts,
            counts,
            gain,
            integration_s,
            reference_lux,
            max_count,
        )?;
        *out = c.into();
        Ok(())
    })())
}

/// Replaces the spectral correction factor of `cal` (finite, > 0).
///
/// # Safety
/// `cal` is null or points to a readable and writable `RadAlsCalibration`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_als_set_spectral_correction(
    cal: *mut RadAlsCalibration,
    factor: f32,
) -> RadStatus {
    status((|| {
        // SAFETY: forwarded caller contract.
        let cal = unsafe { as_mut(cal)? };
        *cal = cal.rust()?.with_spectral_correction(factor)?.into();
        Ok(())
    })())
}

/// `*lux = max(counts − dark, 0) · lux_per_count_s · F / (gain · t)`.
/// `RAD_STATUS_SATURATED` when `counts ≥ max_count`,
/// `RAD_STATUS_BAD_SETTING` unless gain and time are finite and > 0.
///
/// # Safety
/// `cal` is null or points to a readable `RadAlsCalibration`; `lux` is null
/// or points to a writable `float`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_als_lux(
    cal: *const RadAlsCalibration,
    counts: u32,
    gain: f32,
    integration_s: f32,
    lux: *mut f32,
) -> RadStatus {
    status((|| {
        // SAFETY: forwarded caller contract.
        let (cal, lux) = unsafe { (as_ref(cal)?, as_mut(lux)?) };
        *lux = cal.rust()?.lux(counts, gain, integration_s)?;
        Ok(())
    })())
}

/// The spectral mismatch correction factor (CIE S 023/E:2013)
/// `F = [∫E_X V / ∫E_X s] / [∫E_A V / ∫E_A s]` of a detector with relative
/// responsivity `s = responsivity` for `source` (X), calibrated under
/// `reference` (A); trapezoid rule at 1 nm. `RAD_STATUS_SINGULAR` when a
/// source gives the detector or the eye no signal.
///
/// # Safety
/// Each pointer is null or points to a readable `RadSpectrum` whose
/// tabulated values (if any) are readable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_spectral_correction(
    responsivity: *const RadSpectrum,
    source: *const RadSpectrum,
    reference: *const RadSpectrum,
    out: *mut f32,
) -> RadStatus {
    status((|| {
        // SAFETY: forwarded caller contract.
        let (s, x, a, out) = unsafe {
            (
                as_ref(responsivity)?,
                as_ref(source)?,
                as_ref(reference)?,
                as_mut(out)?,
            )
        };
        // SAFETY: forwarded caller contract.
        let (s, x, a) = unsafe { (s.curve()?, x.curve()?, a.curve()?) };
        *out = als::spectral_correction(&s, &x, &a)?;
        Ok(())
    })())
}

/// Illuminance in lux of a spectral irradiance in W m⁻² nm⁻¹:
/// `E_v = 683 lm/W · ∫ E(λ) V(λ) dλ` (CIE 015:2018; trapezoid rule at 1 nm).
///
/// # Safety
/// `spectral_irradiance` is null or points to a readable `RadSpectrum`;
/// `out` is null or points to a writable `float`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_source_lux(spectral_irradiance: *const RadSpectrum, out: *mut f32) -> RadStatus {
    status((|| {
        // SAFETY: forwarded caller contract.
        let (e, out) = unsafe { (as_ref(spectral_irradiance)?, as_mut(out)?) };
        // SAFETY: forwarded caller contract.
        let e = unsafe { e.curve()? };
        *out = als::source_lux(&e);
        Ok(())
    })())
}

/// Predicted mean raw count of an ideal (noiseless) sensor:
/// `dark + g·t·k ∫E(λ) s(λ) dλ`, rounded and clipped to `[0, max_count]`
/// (for simulation and tests); `k` in counts per second per unit of
/// `∫E s dλ`.
///
/// # Safety
/// `responsivity` and `spectral_irradiance` are null or point to readable
/// `RadSpectrum`s; `out` is null or points to a writable `uint32_t`.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn rad_als_simulate_counts(
    responsivity: *const RadSpectrum,
    spectral_irradiance: *const RadSpectrum,
    k: f32,
    gain: f32,
    integration_s: f32,
    dark_counts: f32,
    max_count: u32,
    out: *mut u32,
) -> RadStatus {
    status((|| {
        // SAFETY: forwarded caller contract.
        let (s, e, out) = unsafe { (as_ref(responsivity)?, as_ref(spectral_irradiance)?, as_mut(out)?) };
        if !(k.is_finite() && gain.is_finite() && integration_s.is_finite() && dark_counts.is_finite()) {
            return Err(RadStatus::NotFinite);
        }
        if k < 0.0 || gain <= 0.0 || integration_s <= 0.0 || dark_counts < 0.0 || max_count == 0 {
            return Err(RadStatus::OutOfRange);
        }
        // SAFETY: forwarded caller contract.
        let (s, e) = unsafe { (s.curve()?, e.curve()?) };
        *out = als::simulate_counts(&s, &e, k, gain, integration_s, dark_counts, max_count);
        Ok(())
    })())
}
