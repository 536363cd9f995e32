//! Firmware-style ambient-light sensor: raw counts → lux.
//!
//! Everything except `main` is written as it would run on a Cortex-M class
//! board: `f32` only, no allocation, no panics, constant tables. `main` uses
//! `std` only to print. Run with `cargo run --example ambient_light_sensor`.
//!
//! Flow:
//! 1. Factory: read the sensor in darkness (dark offset) and under CIE
//!    illuminant A at a known illuminance (gain calibration).
//! 2. Install: the device knows it lives under white-LED lighting, so it
//!    computes the spectral mismatch correction for that source once, on the
//!    device, from constant tables (CIE S 023 / ISO/CIE 19476 correction
//!    factor).
//! 3. Run: every sample is converted to lux; on saturation or on a weak
//!    signal the gain is switched (auto-ranging) and the sample retaken.

use radiometry::sensor::als::{AlsCalibration, AlsError, simulate_counts, spectral_correction};
use radiometry::spectral::{FnCurve, IlluminantA, Scaled, SpectralCurve, Tabulated, photometry};

/// Relative spectral responsivity of the photodiode + filter, 380–1100 nm
/// every 40 nm (an illustrative datasheet curve: green-peaked, with the
/// infrared leak typical of cheap ALS filters).
const ALS_RESPONSE: [f32; 19] = [
    0.02, 0.10, 0.35, 0.75, 1.00, 0.80, 0.40, 0.15, 0.08, 0.10, 0.22, 0.30, 0.22, 0.10, 0.05, 0.03, 0.02,
    0.01, 0.0,
];

/// The responsivity as a curve (validated at compile time by `new` in a const).
const RESPONSE: Tabulated<'static> = match Tabulated::new(380.0, 40.0, &ALS_RESPONSE) {
    Ok(t) => t,
    Err(_) => panic!("invalid ALS table"), // compile-time only: a bad table fails the build
};

/// ADC full scale (16-bit).
const MAX_COUNT: u32 = 65_535;
/// Available analog gains.
const GAINS: [f32; 4] = [1.0, 4.0, 16.0, 64.0];
/// Integration time, s.
const T_INT: f32 = 0.1;

/// A white LED (blue die + phosphor) as a closed form, relative units.
fn white_led(l: f32) -> f32 {
    let g = |c: f32, s: f32| libm::expf(-0.5 * ((l - c) / s) * ((l - c) / s));
    g(450.0, 10.0) + 1.4 * g(570.0, 55.0)
}

/// The simulated hardware: counts for a scene (detector model with k counts per s
/// per W/m² of responsivity-weighted irradiance, 40 dark counts).
fn hardware(scene: &impl SpectralCurve, gi: usize) -> u32 {
    simulate_counts(
        &RESPONSE,
        scene,
        4.0e3,
        GAINS[gi.min(GAINS.len() - 1)],
        T_INT,
        40.0,
        MAX_COUNT,
    )
}

/// Factory step: calibration from a dark reading and a reading under
/// illuminant A of `ref_lux`, at gain index `gi`.
fn factory_calibrate(
    dark_counts: u32,
    ref_counts: u32,
    gi: usize,
    ref_lux: f32,
) -> Result<AlsCalibration, ()> {
    let gain = GAINS.get(gi).copied().ok_or(())?;
    AlsCalibration::from_reference(
        dark_counts as f32,
        ref_counts as f32,
        gain,
        T_INT,
        ref_lux,
        MAX_COUNT,
    )
    .map_err(|_| ())
}

/// Install step: correction for white-LED lighting relative to illuminant A.
fn led_correction() -> f32 {
    let led = FnCurve::new(380.0, 780.0, white_led);
    spectral_correction(&RESPONSE, &led, &IlluminantA).unwrap_or(1.0)
}

/// Run-time state: calibration and the current gain index.
struct AmbientLight {
    cal: AlsCalibration,
    gain_index: usize,
}

/// What one conversion produced.
#[derive(Clone, Copy, Debug)]
enum Sample {
    /// Illuminance, lux, and the gain used.
    Lux(f32, f32),
    /// Gain changed; take the sample again.
    Retry,
    /// Saturated at the lowest gain: at least this many lux.
    AtLeast(f32),
}

impl AmbientLight {
    /// Converts one raw reading; adjusts the gain when out of range.
    fn on_sample(&mut self, raw: u32) -> Sample {
        let gain = GAINS[self.gain_index.min(GAINS.len() - 1)];
        match self.cal.lux(raw, gain, T_INT) {
            Err(AlsError::Saturated) if self.gain_index > 0 => {
                self.gain_index -= 1;
                Sample::Retry
            }
            Err(_) => Sample::AtLeast(self.cal.lux(MAX_COUNT - 1, gain, T_INT).unwrap_or(0.0)),
            Ok(_) if raw < MAX_COUNT / 64 && self.gain_index + 1 < GAINS.len() => {
                self.gain_index += 1;
                Sample::Retry
            }
            Ok(lux) => Sample::Lux(lux, gain),
        }
    }
}

fn main() {
    // The "hardware" is `hardware()` below: the detector model itself.
    // 1. Factory: dark and 1000 lx of illuminant A at gain ×4.
    let a_1000 = Scaled::new(IlluminantA, 1000.0 / photometry::illuminance_lux(&IlluminantA));
    let dark_counts = hardware(&FnCurve::new(380.0, 780.0, |_| 0.0), 1);
    let ref_counts = hardware(&a_1000, 1);
    let cal = factory_calibrate(dark_counts, ref_counts, 1, 1000.0).expect("factory calibration");
    println!("factory: dark {dark_counts} counts, 1000 lx of illuminant A → {ref_counts} counts");

    // 2. Install under LED lighting.
    let f = led_correction();
    println!("install: spectral correction for white LED vs illuminant A: F = {f:.4}");
    let led_cal = cal.with_spectral_correction(f).expect("finite correction");

    // 3. Run: a day of LED lighting levels.
    let led = FnCurve::new(380.0, 780.0, white_led);
    let led_lux_per_unit = photometry::illuminance_lux(&led);
    for true_lux in [0.5f32, 20.0, 300.0, 2000.0, 20_000.0, 200_000.0] {
        let scene = Scaled::new(led, true_lux / led_lux_per_unit);
        let mut fw = AmbientLight {
            cal: led_cal,
            gain_index: 2,
        };
        let mut uncorrected = AmbientLight { cal, gain_index: 2 };
        let mut out = Sample::Retry;
        for _ in 0..8 {
            out = fw.on_sample(hardware(&scene, fw.gain_index));
            if !matches!(out, Sample::Retry) {
                break;
            }
        }
        let mut raw_out = Sample::Retry;
        for _ in 0..8 {
            raw_out = uncorrected.on_sample(hardware(&scene, uncorrected.gain_index));
            if !matches!(raw_out, Sample::Retry) {
                break;
            }
        }
        let show = |s: Sample| match s {
            Sample::Lux(l, g) => format!("{l:>10.2} lx (gain {g:>2})"),
            Sample::AtLeast(l) => format!("≥ {l:.0} lx (saturated)"),
            Sample::Retry => "no stable gain".to_string(),
        };
        println!(
            "true {true_lux:>9.1} lx → corrected {}, without spectral correction {}",
            show(out),
            show(raw_out)
        );
    }
}
