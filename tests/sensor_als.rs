//! Ambient-light sensor: counts → lux with dark offset, gain, integration time and
//! spectral mismatch correction.

use radiometry::sensor::SensorError;
use radiometry::sensor::als::{AlsCalibration, AlsError, simulate_counts, spectral_correction};
use radiometry::spectral::{self, FnCurve, IlluminantA, Scaled, SpectralCurve, tables};

/// A photodiode + filter that only roughly follows V(λ), with an infrared leak.
fn als_response() -> FnCurve<impl Fn(f32) -> f32 + Copy> {
    FnCurve::new(350.0, 1100.0, |l| {
        let g = |c: f32, s: f32| libm::expf(-0.5 * ((l - c) / s) * ((l - c) / s));
        g(560.0, 50.0) + 0.3 * g(850.0, 40.0)
    })
}

/// f64 lux of `k·S(λ)` by CIE 5 nm summation against the V(λ) table, written here.
fn lux_f64(s: &impl SpectralCurve, k: f64) -> f64 {
    (0..tables::CIE_PHOTOPIC_V.len())
        .map(|i| {
            let l = 360.0 + 5.0 * i as f64;
            683.0 * k * s.value(l as f32) as f64 * tables::CIE_PHOTOPIC_V[i] as f64 * 5.0
        })
        .sum()
}

fn white_led(l: f32) -> f32 {
    let g = |c: f32, s: f32| libm::expf(-0.5 * ((l - c) / s) * ((l - c) / s));
    g(450.0, 10.0) + 1.4 * g(570.0, 55.0)
}

#[test]
fn calibrated_under_a_reads_other_sources_after_correction() {
    let s = als_response();
    let (gain, t, k, dark, max) = (4.0f32, 0.1f32, 2.0e5f32, 12.0f32, 1u32 << 24);
    // Calibrate under illuminant A at 500 lx.
    let ka = 500.0 / lux_f64(&IlluminantA, 1.0);
    let a = Scaled::new(IlluminantA, ka as f32);
    let ca = simulate_counts(&s, &a, k, gain, t, dark, max);
    let cal = AlsCalibration::from_reference(dark, ca as f32, gain, t, 500.0, max).unwrap();
    assert!((cal.lux(ca, gain, t).unwrap() - 500.0).abs() < 0.05);
    // Measure D65 and a white LED at 300 lx, at another gain/time.
    let led = FnCurve::new(380.0, 780.0, white_led);
    let kd = 300.0 / lux_f64(&spectral::d65(), 1.0);
    let kl = 300.0 / lux_f64(&led, 1.0);
    let d65 = Scaled::new(spectral::d65(), kd as f32);
    let led = Scaled::new(led, kl as f32);
    for (name, fx) in [
        ("D65", spectral_correction(&s, &d65, &a).unwrap()),
        ("LED", spectral_correction(&s, &led, &a).unwrap()),
    ] {
        let src: &dyn Fn(f32) -> f32 = if name == "D65" {
            &|l| d65.value(l)
        } else {
            &|l| led.value(l)
        };
        let src = FnCurve::new(300.0, 830.0, src);
        let c = simulate_counts(&s, &src, k, 16.0, 0.05, dark, max);
        let raw = cal.lux(c, 16.0, 0.05).unwrap();
        let corrected = cal
            .with_spectral_correction(fx)
            .unwrap()
            .lux(c, 16.0, 0.05)
            .unwrap();
        println!(
            "ALS {name} at 300 lx ({c} counts; reference {ca} counts): uncorrected {raw:.2} lx ({:+.2} %), F = {fx:.4}, corrected {corrected:.3} lx ({:+.3} %)",
            (raw / 300.0 - 1.0) * 100.0,
            (corrected / 300.0 - 1.0) * 100.0
        );
        assert!(
            (raw / 300.0 - 1.0).abs() > 0.01,
            "the mismatch should matter for this detector"
        );
        assert!((corrected / 300.0 - 1.0).abs() < 1e-3, "{name}: {corrected}");
    }
}

#[test]
fn limits_and_hard_cases() {
    let cal = AlsCalibration::new(10.0, 0.5, 1.0, 65535).unwrap();
    assert_eq!(cal.lux(0, 1.0, 1.0).unwrap(), 0.0); // below dark → 0 lx
    assert_eq!(cal.lux(10, 1.0, 1.0).unwrap(), 0.0);
    assert_eq!(cal.lux(20, 2.0, 0.5).unwrap(), 5.0); // (20−10)·0.5/(2·0.5)
    assert_eq!(cal.lux(65535, 1.0, 1.0), Err(AlsError::Saturated));
    assert_eq!(cal.lux(100, 0.0, 1.0), Err(AlsError::BadSetting));
    assert_eq!(cal.lux(100, 1.0, f32::NAN), Err(AlsError::BadSetting));
    assert_eq!(cal.lux(100, f32::INFINITY, 1.0), Err(AlsError::BadSetting));
    assert!(cal.lux(65534, 1e-30, 1e-30).unwrap().is_finite());
    assert!(AlsCalibration::new(f32::NAN, 1.0, 1.0, 10).is_err());
    assert!(AlsCalibration::new(0.0, 0.0, 1.0, 10).is_err());
    assert!(AlsCalibration::new(0.0, 1.0, 1.0, 0).is_err());
    assert!(cal.with_spectral_correction(-1.0).is_err());
    assert_eq!(
        AlsCalibration::from_reference(10.0, 10.0, 1.0, 1.0, 100.0, 10),
        Err(SensorError::BadParameter(
            "reference reading must exceed dark; gain, time, lux > 0"
        ))
    );
    assert!(AlsCalibration::from_reference(0.0, f32::NAN, 1.0, 1.0, 100.0, 10).is_err());
    // No light at all, or light the detector cannot see: the correction is undefined.
    let s = als_response();
    let dark = FnCurve::new(380.0, 780.0, |_| 0.0);
    assert_eq!(
        spectral_correction(&s, &dark, &IlluminantA),
        Err(SensorError::Singular)
    );
    let uv = FnCurve::new(200.0, 300.0, |_| 1.0);
    assert_eq!(
        spectral_correction(&s, &uv, &IlluminantA),
        Err(SensorError::Singular)
    );
    // Zero exposure and NaN scene give the dark count / 0.
    assert_eq!(simulate_counts(&s, &IlluminantA, 1.0, 1.0, 0.0, 7.0, 100), 7);
    let nan = FnCurve::new(380.0, 780.0, |_| f32::NAN);
    assert_eq!(simulate_counts(&s, &nan, 1.0, 1.0, 1.0, 7.0, 100), 7);
    assert_eq!(simulate_counts(&s, &IlluminantA, 1e30, 1.0, 1.0, 0.0, 100), 100);
    assert!(!format!("{}", AlsError::Saturated).is_empty());
}
