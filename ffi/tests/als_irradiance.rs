//! The ambient-light-sensor and irradiance half of the C API against closed
//! forms written out here: `E_v = (counts − dark)·lux_per_count_s·F/(g·t)`,
//! `F = 1` for a photopically matched detector, `E = πL` for a sky,
//! `E = E⊥ cos θ` for a directional light, `E = πL sin²σ cos θa` for a cap
//! above the horizon. Run with `cargo test --features std`.

use core::f32::consts::PI;
use core::ptr::{null, null_mut};
use radiometry_ffi::als::*;
use radiometry_ffi::irradiance::*;
use radiometry_ffi::spectrum::*;
use radiometry_ffi::{RadAlsCalibration, RadSpectrum, RadStatus, RadVec3};

fn spectrum(kind: u32) -> RadSpectrum {
    RadSpectrum {
        kind,
        temperature_k: 0.0,
        start_nm: 0.0,
        step_nm: 0.0,
        values: null(),
        len: 0,
    }
}

#[test]
fn lux_is_net_counts_times_calibration_over_gain_time() {
    let mut cal = RadAlsCalibration::default();
    assert_eq!(
        unsafe { rad_als_new(2.0, 0.005, 1.02, 65535, &mut cal) },
        RadStatus::Ok
    );
    let mut lux = 0.0;
    assert_eq!(
        unsafe { rad_als_lux(&cal, 1002, 4.0, 0.1, &mut lux) },
        RadStatus::Ok
    );
    let want = (1002.0 - 2.0) * 0.005 * 1.02 / (4.0 * 0.1);
    assert!((lux - want).abs() < 1e-5 * want, "{lux} vs {want}");
    // Below the dark level: 0 lx.
    assert_eq!(unsafe { rad_als_lux(&cal, 1, 1.0, 0.1, &mut lux) }, RadStatus::Ok);
    assert_eq!(lux, 0.0);
    unsafe {
        assert_eq!(rad_als_lux(&cal, 65535, 1.0, 0.1, &mut lux), RadStatus::Saturated);
        assert_eq!(rad_als_lux(&cal, 100, 0.0, 0.1, &mut lux), RadStatus::BadSetting);
        assert_eq!(
            rad_als_lux(&cal, 100, 1.0, f32::NAN, &mut lux),
            RadStatus::BadSetting
        );
        assert_eq!(
            rad_als_lux(null(), 100, 1.0, 0.1, &mut lux),
            RadStatus::NullPointer
        );
        assert_eq!(
            rad_als_lux(&cal, 100, 1.0, 0.1, null_mut()),
            RadStatus::NullPointer
        );
        let zeroed = RadAlsCalibration::default();
        assert_eq!(
            rad_als_lux(&zeroed, 100, 1.0, 0.1, &mut lux),
            RadStatus::BadHandle
        );
    }
}

#[test]
fn calibration_constructors_validate() {
    let mut cal = RadAlsCalibration::default();
    unsafe {
        assert_eq!(
            rad_als_new(f32::NAN, 0.005, 1.0, 100, &mut cal),
            RadStatus::NotFinite
        );
        assert_eq!(
            rad_als_new(-1.0, 0.005, 1.0, 100, &mut cal),
            RadStatus::OutOfRange
        );
        assert_eq!(rad_als_new(0.0, 0.0, 1.0, 100, &mut cal), RadStatus::OutOfRange);
        assert_eq!(rad_als_new(0.0, 0.005, 1.0, 0, &mut cal), RadStatus::OutOfRange);
        assert_eq!(cal, RadAlsCalibration::default(), "untouched on error");
        // Reading 1000 counts over a dark of 10 at gain 2, 50 ms under 300 lx:
        // lux_per_count_s = 300·2·0.05/990.
        assert_eq!(
            rad_als_from_reference(10.0, 1000.0, 2.0, 0.05, 300.0, 4095, &mut cal),
            RadStatus::Ok
        );
        let want = 300.0 * 2.0 * 0.05 / 990.0;
        assert!((cal.lux_per_count_s - want).abs() < 1e-6 * want);
        assert_eq!(cal.spectral_correction, 1.0);
        // The same reading gives the reference illuminance back.
        let mut lux = 0.0;
        assert_eq!(rad_als_lux(&cal, 1000, 2.0, 0.05, &mut lux), RadStatus::Ok);
        assert!((lux - 300.0).abs() < 1e-3, "{lux}");
        assert_eq!(
            rad_als_from_reference(10.0, 5.0, 2.0, 0.05, 300.0, 4095, &mut cal),
            RadStatus::OutOfRange
        );
        assert_eq!(
            rad_als_set_spectral_correction(&mut cal, 0.0),
            RadStatus::OutOfRange
        );
        assert_eq!(rad_als_set_spectral_correction(&mut cal, 1.25), RadStatus::Ok);
        assert_eq!(rad_als_lux(&cal, 1000, 2.0, 0.05, &mut lux), RadStatus::Ok);
        assert!((lux - 375.0).abs() < 1e-3, "{lux}");
    }
}

#[test]
fn photopic_detector_needs_no_correction() {
    // s = V ⇒ F = [∫E_X V/∫E_X V]/[∫E_A V/∫E_A V] = 1 for any sources.
    let v = spectrum(RAD_SPECTRUM_PHOTOPIC_V);
    let a = spectrum(RAD_SPECTRUM_A);
    let mut bb = spectrum(RAD_SPECTRUM_BLACKBODY);
    bb.temperature_k = 6500.0;
    let mut f = 0.0;
    assert_eq!(
        unsafe { rad_spectral_correction(&v, &bb, &a, &mut f) },
        RadStatus::Ok
    );
    assert!((f - 1.0).abs() < 1e-5, "{f}");
}

#[test]
fn flat_detector_correction_against_band_integrals() {
    // A detector flat over 380–780 nm, sources that are boxes: X = 1 on
    // [540, 560] nm, A = 1 on [590, 610] nm (tabulated at 10 nm: linear
    // interpolation makes each a trapezoid with 10 nm ramps). Then
    // F = [∫X V / ∫X] / [∫A V / ∫A] = ∫X V / ∫A V (equal box areas). V from
    // the CIE 1924 table at 5 nm (CIE 015:2018), linearly interpolated,
    // integrated at 1 nm by the trapezoid rule here.
    const V: [(f32, f32); 21] = [
        (530.0, 0.862),
        (535.0, 0.914_85),
        (540.0, 0.954),
        (545.0, 0.980_3),
        (550.0, 0.994_950),
        (555.0, 1.000_0),
        (560.0, 0.995_0),
        (565.0, 0.978_6),
        (570.0, 0.952_0),
        (575.0, 0.915_4),
        (580.0, 0.870_0),
        (585.0, 0.816_3),
        (590.0, 0.757_0),
        (595.0, 0.694_9),
        (600.0, 0.631_0),
        (605.0, 0.566_8),
        (610.0, 0.503_0),
        (615.0, 0.441_2),
        (620.0, 0.381_0),
        (625.0, 0.321_0),
        (630.0, 0.265_0),
    ];
    let vv = |l: f64| -> f64 {
        let i = V.iter().position(|&(x, _)| x as f64 > l).unwrap() - 1;
        let (x0, y0) = (V[i].0 as f64, V[i].1 as f64);
        let y1 = V[i + 1].1 as f64;
        y0 + (y1 - y0) * (l - x0) / 5.0
    };
    let boxed = |lo: f64, l: f64| -> f64 {
        ((l - (lo - 10.0)) / 10.0)
            .clamp(0.0, 1.0)
            .min(((lo + 30.0 - l) / 10.0).clamp(0.0, 1.0))
    };
    let integral = |lo: f64| -> f64 {
        let g = |l: f64| boxed(lo, l) * vv(l);
        (530..=625)
            .map(|k| k as f64)
            .collect::<Vec<_>>()
            .windows(2)
            .map(|w| 0.5 * (g(w[0]) + g(w[1])))
            .sum()
    };
    let want = integral(540.0) / integral(590.0);
    let xs = [0.0f32, 1.0, 1.0, 1.0, 0.0];
    let flat = [1.0f32; 41];
    let tab = |start: f32, step: f32, v: &[f32]| RadSpectrum {
        kind: RAD_SPECTRUM_TABULATED,
        temperature_k: 0.0,
        start_nm: start,
        step_nm: step,
        values: v.as_ptr(),
        len: v.len(),
    };
    let (s, x, a) = (
        tab(380.0, 10.0, &flat),
        tab(530.0, 10.0, &xs),
        tab(580.0, 10.0, &xs),
    );
    let mut f = 0.0;
    assert_eq!(
        unsafe { rad_spectral_correction(&s, &x, &a, &mut f) },
        RadStatus::Ok
    );
    assert!(((f as f64) - want).abs() < 2e-3 * want, "{f} vs {want}");
    assert!(want > 1.3, "the bands differ: {want}");
    // No overlap with the detector: singular.
    let blue = tab(300.0, 10.0, &xs);
    assert_eq!(
        unsafe { rad_spectral_correction(&s, &blue, &a, &mut f) },
        RadStatus::Singular
    );
    // Bad descriptions.
    let short = tab(380.0, 10.0, &flat[..1]);
    assert_eq!(
        unsafe { rad_spectral_correction(&short, &x, &a, &mut f) },
        RadStatus::OutOfRange
    );
    let mut odd = spectrum(99);
    assert_eq!(
        unsafe { rad_spectral_correction(&odd, &x, &a, &mut f) },
        RadStatus::UnknownKind
    );
    odd.kind = RAD_SPECTRUM_BLACKBODY;
    assert_eq!(
        unsafe { rad_spectral_correction(&s, &odd, &a, &mut f) },
        RadStatus::OutOfRange
    );
}

#[test]
fn simulated_counts_read_back_as_the_source_illuminance() {
    // An ideal photopic detector calibrated under A reads D65 correctly with
    // F = 1: counts = g·t·k·∫E V, lux = 683 ∫E V.
    let v = spectrum(RAD_SPECTRUM_PHOTOPIC_V);
    let d65 = spectrum(RAD_SPECTRUM_D65);
    let mut counts = 0u32;
    let (k, g, t) = (50.0f32, 1.0f32, 0.1f32);
    assert_eq!(
        unsafe { rad_als_simulate_counts(&v, &d65, k, g, t, 0.0, 1 << 20, &mut counts) },
        RadStatus::Ok
    );
    let mut lux_d65 = 0.0;
    assert_eq!(unsafe { rad_source_lux(&d65, &mut lux_d65) }, RadStatus::Ok);
    // lux per count/(g t) = 683 / k.
    let mut cal = RadAlsCalibration::default();
    assert_eq!(
        unsafe { rad_als_new(0.0, 683.0 / k, 1.0, 1 << 20, &mut cal) },
        RadStatus::Ok
    );
    let mut lux = 0.0;
    assert_eq!(
        unsafe { rad_als_lux(&cal, counts, g, t, &mut lux) },
        RadStatus::Ok
    );
    // Counts are rounded to integers: relative error ≤ 0.5/counts.
    assert!(counts > 1000, "{counts}");
    assert!(
        (lux - lux_d65).abs() <= lux_d65 * (0.5 / counts as f32 + 1e-5),
        "{lux} vs {lux_d65}"
    );
}

#[test]
fn irradiance_closed_forms() {
    let mut e = 0.0;
    unsafe {
        assert_eq!(rad_irradiance_sky(2.0, &mut e), RadStatus::Ok);
        assert!((e - 2.0 * PI).abs() < 1e-6);
        let th = 0.6f32;
        let dir = RadVec3 {
            x: th.sin(),
            y: 0.0,
            z: th.cos(),
        };
        assert_eq!(rad_irradiance_directional(dir, 3.0, &mut e), RadStatus::Ok);
        assert!((e - 3.0 * th.cos()).abs() < 1e-6);
        // Not normalised on input: normalised by the library.
        let long = RadVec3 {
            x: 2.0 * dir.x,
            y: 0.0,
            z: 2.0 * dir.z,
        };
        assert_eq!(rad_irradiance_directional(long, 3.0, &mut e), RadStatus::Ok);
        assert!((e - 3.0 * th.cos()).abs() < 1e-6);
        // A cap fully above the horizon: π L sin²σ cos θa.
        let sigma = 0.2f32;
        assert_eq!(rad_irradiance_cap(dir, sigma, 5.0, &mut e), RadStatus::Ok);
        let want = PI * 5.0 * sigma.sin().powi(2) * th.cos();
        assert!((e - want).abs() < 1e-5 * want, "{e} vs {want}");
        // Axis on the horizon: half of the projected disc, L (σ − sin σ cos σ).
        let horizon = RadVec3 {
            x: 1.0,
            y: 0.0,
            z: 0.0,
        };
        assert_eq!(rad_irradiance_cap(horizon, sigma, 1.0, &mut e), RadStatus::Ok);
        let want = sigma - sigma.sin() * sigma.cos();
        assert!((e - want).abs() < 1e-6, "{e} vs {want}");
        assert!((rad_cap_solid_angle(core::f32::consts::FRAC_PI_2) - 2.0 * PI).abs() < 1e-5);
        // Bad lights.
        assert_eq!(rad_irradiance_sky(-1.0, &mut e), RadStatus::OutOfRange);
        assert_eq!(rad_irradiance_sky(f32::NAN, &mut e), RadStatus::NotFinite);
        assert_eq!(
            rad_irradiance_directional(RadVec3::default(), 1.0, &mut e),
            RadStatus::OutOfRange
        );
        assert_eq!(rad_irradiance_cap(dir, 2.0, 1.0, &mut e), RadStatus::OutOfRange);
        assert_eq!(rad_irradiance_sky(1.0, null_mut()), RadStatus::NullPointer);
    }
}
