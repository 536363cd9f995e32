//! Ambient-light sensors (photodiode + ADC, as on phones and sensor
//! boards): raw counts → illuminance in lux, with a dark offset, gain and
//! integration-time scaling, and a spectral mismatch correction for a
//! known source. `f32` only, no allocation, no panics — for firmware.
//!
//! Model. A detector of relative spectral responsivity `s(λ)` under a
//! spectral irradiance `E(λ)` produces
//! `counts = dark + g · t · k ∫ E(λ) s(λ) dλ`
//! (gain `g`, integration time `t`, responsivity `k`). Calibrating
//! against a reference source `A` of known illuminance fixes
//! `lux per (count/(g·t))`. Under another source `X` the detector's
//! mismatch to V(λ) biases the reading; the spectral mismatch correction
//! factor (CIE S 023/E:2013 = ISO/CIE 19476:2014, "spectral mismatch
//! correction factor"; section numbers not checked here)
//!
//! `F(X) = [∫ E_X V dλ / ∫ E_X s dλ] / [∫ E_A V dλ / ∫ E_A s dλ]`
//!
//! multiplies the calibrated reading.
//!
//! ```
//! use radiometry::sensor::als::AlsCalibration;
//! // 2 counts dark, 0.05 lx per count at gain 1 and 100 ms, source correction 1.02.
//! let cal = AlsCalibration::new(2.0, 0.05 * 0.1, 1.02, 65535).unwrap();
//! let lux = cal.lux(1002, 1.0, 0.1).unwrap();
//! assert!((lux - 1000.0 * 0.05 * 1.02).abs() < 1e-3);
//! ```

use super::SensorError;
use crate::spectral::{SpectralCurve, integrate_product, photometry, photopic_v};
use core::fmt;

/// Why a reading could not be converted.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum AlsError {
    /// The raw count is at the ADC maximum: the true illuminance is
    /// unknown (≥ the returned bound); lower the gain or integration time.
    Saturated,
    /// Gain or integration time not finite and > 0.
    BadSetting,
}

impl fmt::Display for AlsError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Saturated => write!(f, "ambient-light sensor saturated"),
            Self::BadSetting => write!(f, "gain and integration time must be finite and > 0"),
        }
    }
}

impl core::error::Error for AlsError {}

/// The calibration of one ambient-light sensor.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AlsCalibration {
    dark_counts: f32,
    lux_per_count_s: f32,
    spectral_correction: f32,
    max_count: u32,
}

impl AlsCalibration {
    /// * `dark_counts ≥ 0`: reading in darkness (at the gain/time it was
    ///   measured with — firmware usually measures it per setting);
    /// * `lux_per_count_s > 0`: lux per (count / (gain · seconds)), from a
    ///   calibration under the reference source;
    /// * `spectral_correction > 0`: [`spectral_correction`] for the source
    ///   being measured (1 for the calibration source itself);
    /// * `max_count`: the ADC full scale (readings at it are saturated).
    pub fn new(
        dark_counts: f32,
        lux_per_count_s: f32,
        spectral_correction: f32,
        max_count: u32,
    ) -> Result<Self, SensorError> {
        if !(dark_counts.is_finite() && lux_per_count_s.is_finite() && spectral_correction.is_finite()) {
            return Err(SensorError::NotFinite);
        }
        if dark_counts < 0.0 || lux_per_count_s <= 0.0 || spectral_correction <= 0.0 || max_count == 0 {
            return Err(SensorError::BadParameter(
                "dark ≥ 0, lux per count > 0, correction > 0, max count > 0",
            ));
        }
        Ok(Self {
            dark_counts,
            lux_per_count_s,
            spectral_correction,
            max_count,
        })
    }

    /// Calibrates from one reading `counts` (at `gain`, `integration_s`)
    /// of a reference source of known illuminance `reference_lux > 0`
    /// after subtracting `dark_counts`:
    /// `lux_per_count_s = lux · g · t / (counts − dark)`.
    pub fn from_reference(
        dark_counts: f32,
        counts: f32,
        gain: f32,
        integration_s: f32,
        reference_lux: f32,
        max_count: u32,
    ) -> Result<Self, SensorError> {
        let net = counts - dark_counts;
        if !(net.is_finite() && gain.is_finite() && integration_s.is_finite() && reference_lux.is_finite()) {
            return Err(SensorError::NotFinite);
        }
        if net <= 0.0 || gain <= 0.0 || integration_s <= 0.0 || reference_lux <= 0.0 {
            return Err(SensorError::BadParameter(
                "reference reading must exceed dark; gain, time, lux > 0",
            ));
        }
        Self::new(
            dark_counts,
            reference_lux * gain * integration_s / net,
            1.0,
            max_count,
        )
    }

    /// A copy with another spectral correction factor (for another
    /// source); error unless finite and > 0.
    pub fn with_spectral_correction(mut self, factor: f32) -> Result<Self, SensorError> {
        if !factor.is_finite() {
            return Err(SensorError::NotFinite);
        }
        if factor <= 0.0 {
            return Err(SensorError::BadParameter("spectral correction must be > 0"));
        }
        self.spectral_correction = factor;
        Ok(self)
    }

    /// The dark reading (counts).
    pub fn dark_counts(&self) -> f32 {
        self.dark_counts
    }

    /// Lux per (count / (gain · seconds)) under the calibration source.
    pub fn lux_per_count_s(&self) -> f32 {
        self.lux_per_count_s
    }

    /// The spectral correction factor applied by [`Self::lux`].
    pub fn spectral_correction(&self) -> f32 {
        self.spectral_correction
    }

    /// The ADC full scale.
    pub fn max_count(&self) -> u32 {
        self.max_count
    }

    /// Illuminance from a raw reading:
    /// `E_v = max(counts − dark, 0) · lux_per_count_s · F / (g · t)`.
    ///
    /// Counts below the dark level give 0 lx (noise around zero light).
    /// A reading at `max_count` is [`AlsError::Saturated`].
    pub fn lux(&self, counts: u32, gain: f32, integration_s: f32) -> Result<f32, AlsError> {
        if !(gain.is_finite() && integration_s.is_finite() && gain > 0.0 && integration_s > 0.0) {
            return Err(AlsError::BadSetting);
        }
        if counts >= self.max_count {
            return Err(AlsError::Saturated);
        }
        let net = (counts as f32 - self.dark_counts).max(0.0);
        let v = net * self.lux_per_count_s * self.spectral_correction / (gain * integration_s);
        Ok(if v.is_finite() { v } else { 0.0 })
    }
}

/// Spectral mismatch correction factor of a detector with relative
/// spectral responsivity `responsivity` for `source`, relative to the
/// calibration source `reference` (see the module docs; CIE S 023:2013):
/// `F = [∫E_X V / ∫E_X s] / [∫E_A V / ∫E_A s]`, integrals by the
/// trapezoid rule at 1 nm. Returns [`SensorError::Singular`] when either
/// source gives the detector or the eye no signal.
pub fn spectral_correction(
    responsivity: &impl SpectralCurve,
    source: &impl SpectralCurve,
    reference: &impl SpectralCurve,
) -> Result<f32, SensorError> {
    let v = photopic_v();
    let xv = integrate_product(source, &v, 1.0);
    let xs = integrate_product(source, responsivity, 1.0);
    let av = integrate_product(reference, &v, 1.0);
    let as_ = integrate_product(reference, responsivity, 1.0);
    if !(xv > 0.0 && xs > 0.0 && av > 0.0 && as_ > 0.0) {
        return Err(SensorError::Singular);
    }
    let f = (xv / xs) / (av / as_);
    if f.is_finite() {
        Ok(f)
    } else {
        Err(SensorError::Singular)
    }
}

/// Predicted mean raw count of an ideal (noiseless) ALS:
/// `dark + g · t · k ∫ E(λ) s(λ) dλ`, rounded and clipped to
/// `[0, max_count]`; for simulation and tests. `k` is in counts per
/// second per unit of `∫E s dλ` (W/m² for a relative `s`).
pub fn simulate_counts(
    responsivity: &impl SpectralCurve,
    spectral_irradiance: &impl SpectralCurve,
    k: f32,
    gain: f32,
    integration_s: f32,
    dark_counts: f32,
    max_count: u32,
) -> u32 {
    let signal = integrate_product(spectral_irradiance, responsivity, 1.0);
    let c = dark_counts + gain * integration_s * k * signal;
    if c.is_nan() {
        0
    } else {
        libm::roundf(crate::math::clamp_to(c, 0.0, max_count as f32)) as u32
    }
}

/// Illuminance of a source in lux (re-exported convenience for firmware
/// that computes its correction on the device):
/// [`photometry::illuminance_lux`].
pub fn source_lux(spectral_irradiance: &impl SpectralCurve) -> f32 {
    photometry::illuminance_lux(spectral_irradiance)
}
