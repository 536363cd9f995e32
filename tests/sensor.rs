//! Sensor pixel model: every integration shortcut equals the full
//! integration; closed forms; response curves; hard cases.

use radiometry::sensor::response::{Gamma, Linear, Response, Srgb, TabulatedResponse};
use radiometry::sensor::{
    Aperture, FillFactor, FnAperture, FnField, Full, IrradianceField, Monochromatic, Pixel, Sampling,
    SensorError, SpectralSupport, UniformSpectral,
};
use radiometry::spectral::{self, FnCurve, Scaled, SpectralCurve};

const H: f64 = 6.626_070_15e-34;
const C: f64 = 299_792_458.0;

fn qe() -> FnCurve<impl Fn(f32) -> f32 + Copy> {
    // A smooth silicon-like QE peaking at 0.6 near 550 nm.
    FnCurve::new(300.0, 1100.0, |l| {
        0.6 * libm::expf(-((l - 550.0) / 200.0) * ((l - 550.0) / 200.0))
    })
}

fn pixel<A: Aperture>(a: A) -> Pixel<A, FnCurve<impl Fn(f32) -> f32 + Copy>> {
    Pixel::new(a, qe(), 25e-12, 0.01, Sampling::default()).unwrap()
}

fn rel(a: f32, b: f64) -> f64 {
    ((a as f64 - b) / b).abs()
}

#[test]
fn monochromatic_matches_closed_form_and_full_integration() {
    let px = pixel(FillFactor::new(0.6).unwrap());
    for l in [400.0f32, 550.0, 800.0] {
        let f = Monochromatic::new(l, 2e-3);
        let short = px.mean_electrons(&f).unwrap();
        // Closed form (f64): E A t η λ/(hc) · fill.
        let eta = 0.6 * (-((l as f64 - 550.0) / 200.0).powi(2)).exp();
        let want = 2e-3 * 25e-12 * 0.01 * eta * (l as f64 * 1e-9) / (H * C) * 0.6;
        assert!(rel(short, want) < 1e-4, "{l}: {short} vs {want}");
        let full = px.mean_electrons(&Full::new(f, 0.01)).unwrap();
        assert!(
            rel(full, short as f64) < 2e-4,
            "{l}: full {full} vs shortcut {short}"
        );
    }
}

#[test]
fn uniform_spectral_shortcut_equals_full() {
    let px = pixel(FillFactor::new(0.8).unwrap());
    let f = UniformSpectral(Scaled::new(spectral::d65(), 1e-4));
    let short = px.mean_electrons(&f).unwrap();
    let full = px.mean_electrons(&Full::new(f, 0.01)).unwrap();
    println!("D65 uniform: shortcut {short} e-, full {full} e-");
    assert!(rel(full, short as f64) < 1e-4);
    // Independent f64 reference: A t fill ∫ E η λ/(hc) dλ, trapezoid at 0.25 nm on the D65 table.
    let mut s = 0.0f64;
    let d = spectral::d65();
    let n = (480.0 / 0.25) as usize;
    for i in 0..=n {
        let l = 300.0 + 0.25 * i as f64;
        let w = if i == 0 || i == n { 0.5 } else { 1.0 };
        let eta = 0.6 * (-((l - 550.0) / 200.0).powi(2)).exp();
        s += w * 1e-4 * d.value(l as f32) as f64 * eta * l * 1e-9 / (H * C) * 0.25;
    }
    let want = s * 25e-12 * 0.01 * 0.8;
    assert!(rel(short, want) < 2e-4, "{short} vs {want}");
}

/// A lamp that is static and uniform but declares so; its `Full` wrapper integrates
/// everything.
struct Lamp;
impl IrradianceField for Lamp {
    const VARIES_IN_SPACE: bool = false;
    const VARIES_IN_TIME: bool = false;
    fn spectral(&self) -> SpectralSupport {
        SpectralSupport::Band { lo: 500.0, hi: 600.0 }
    }
    fn irradiance(&self, _x: f32, _y: f32, l: f32, _t: f32) -> f32 {
        1e-5 * (l - 450.0)
    }
}

#[test]
fn nonuniform_aperture_with_uniform_field_equals_full() {
    let ap = FnAperture(|x: f32, y: f32| if x < 0.5 { 1.0 } else { 0.25 * y });
    let px = pixel(ap);
    let short = px.mean_electrons(&Lamp).unwrap();
    let full = px.mean_electrons(&Full::new(Lamp, 0.01)).unwrap();
    assert!(rel(full, short as f64) < 1e-4, "{full} vs {short}");
    // ∫∫ s = 0.5 + 0.5·0.25·0.5 = 0.5625
    assert!((ap.mean(64) - 0.5625).abs() < 1e-5);
}

#[test]
fn space_and_time_varying_fields_match_closed_forms() {
    let px = pixel(FillFactor::new(1.0).unwrap());
    let mono = Monochromatic::new(550.0, 1e-3);
    let base = px.mean_electrons(&mono).unwrap() as f64;
    // E = E0·2x over the pixel: mean E0. E = E0·2t/T: mean E0. Both at 550 nm (narrow box).
    let ramp_x = FnField::new(549.5, 550.5, |x, _y, _l, _t| 1e-3 * 2.0 * x);
    let ramp_t = FnField::new(549.5, 550.5, |_x, _y, _l, t| 1e-3 * 2.0 * t / 0.01);
    let ex = px.mean_electrons(&ramp_x).unwrap();
    let et = px.mean_electrons(&ramp_t).unwrap();
    assert!(rel(ex, base) < 1e-4, "{ex} vs {base}");
    assert!(rel(et, base) < 1e-4, "{et} vs {base}");
    // A flash in the second half of the exposure gives half the electrons.
    let flash = FnField::new(549.5, 550.5, |_x, _y, _l, t| if t > 0.005 { 2e-3 } else { 0.0 });
    assert!(rel(px.mean_electrons(&flash).unwrap(), base) < 1e-4);
}

#[test]
fn hard_cases() {
    let px = pixel(FillFactor::new(1.0).unwrap());
    // Zero exposure collects nothing.
    let z = px.with_exposure(0.0).unwrap();
    assert_eq!(z.mean_electrons(&Monochromatic::new(550.0, 1.0)).unwrap(), 0.0);
    assert!(px.with_exposure(-1.0).is_err());
    assert!(matches!(px.with_exposure(f32::NAN), Err(SensorError::NotFinite)));
    // Zero and negative irradiance: 0 and the negated value (documented).
    assert_eq!(px.mean_electrons(&Monochromatic::new(550.0, 0.0)).unwrap(), 0.0);
    let p = px.mean_electrons(&Monochromatic::new(550.0, 1e-3)).unwrap();
    let n = px.mean_electrons(&Monochromatic::new(550.0, -1e-3)).unwrap();
    assert_eq!(n, -p);
    // NaN field → typed error.
    assert_eq!(
        px.mean_electrons(&Monochromatic::new(550.0, f32::NAN)),
        Err(SensorError::NotFinite)
    );
    let nanf = FnField::new(400.0, 500.0, |_, _, _, _| f32::NAN);
    assert_eq!(px.mean_electrons(&nanf), Err(SensorError::NotFinite));
    // Light outside the QE support: 0. NaN wavelength: typed error.
    assert_eq!(px.mean_electrons(&Monochromatic::new(1500.0, 1.0)).unwrap(), 0.0);
    assert_eq!(
        px.mean_electrons(&Monochromatic::new(f32::NAN, 1.0)),
        Err(SensorError::NotFinite)
    );
    let ir = UniformSpectral(FnCurve::new(1200.0, 1300.0, |_| 1.0));
    assert_eq!(px.mean_electrons(&ir).unwrap(), 0.0);
    // Invalid pixels.
    assert!(Pixel::new(FillFactor::new(1.0).unwrap(), qe(), 0.0, 1.0, Sampling::default()).is_err());
    let bad = Sampling {
        space: 0,
        ..Sampling::default()
    };
    assert!(Pixel::new(FillFactor::new(1.0).unwrap(), qe(), 1e-12, 1.0, bad).is_err());
    assert!(FillFactor::new(0.0).is_err() && FillFactor::new(f32::NAN).is_err());
    assert!(!format!("{}", SensorError::NotMonotonic).is_empty());
}

fn roundtrip(r: &impl Response, name: &str, tol: f32) {
    let mut worst = 0.0f32;
    for i in 0..=10_000 {
        let x = i as f32 / 10_000.0;
        let y = r.apply(x);
        assert!(y.is_finite());
        worst = worst.max((r.inverse(y) - x).abs());
        worst = worst.max((r.apply(r.inverse(x)) - x).abs());
    }
    println!("{name}: worst round-trip error {worst:e}");
    assert!(worst < tol, "{name}: {worst}");
    for v in [f32::NAN, -1.0, 2.0, f32::INFINITY, f32::NEG_INFINITY, -0.0, 1e-30] {
        assert!(r.apply(v).is_finite() && r.inverse(v).is_finite(), "{name} {v}");
    }
    assert_eq!(r.apply(2.0), r.apply(1.0));
    assert_eq!(r.apply(-1.0), r.apply(0.0));
}

#[test]
fn response_curves_round_trip() {
    roundtrip(&Linear, "linear", 1e-7);
    for g in [0.45f32, 1.0, 2.2, 4.0] {
        roundtrip(&Gamma::new(g).unwrap(), "gamma", 2e-5);
    }
    roundtrip(&Srgb, "srgb", 2e-6);
    const T: [f32; 6] = [0.0, 0.35, 0.6, 0.78, 0.9, 1.0];
    roundtrip(&TabulatedResponse::new(&T).unwrap(), "tabulated", 1e-6);
}

#[test]
fn srgb_matches_iec_formula_in_f64() {
    for i in 0..=1000 {
        let x = i as f64 / 1000.0;
        let want = if x <= 0.0031308 {
            12.92 * x
        } else {
            1.055 * x.powf(1.0 / 2.4) - 0.055
        };
        assert!((Srgb.apply(x as f32) as f64 - want).abs() < 2e-6);
    }
    // Continuity at the breakpoint (IEC 61966-2-1: 0.0031308 ↔ 0.04045).
    assert!((Srgb.apply(0.0031308) - 0.04045).abs() < 1e-5);
    assert!(Gamma::new(f32::NAN).is_err() && Gamma::new(-2.0).is_err());
}

#[test]
fn non_monotonic_tables_are_rejected() {
    assert_eq!(
        TabulatedResponse::new(&[0.0, 0.5, 0.5, 1.0]),
        Err(SensorError::NotMonotonic)
    );
    assert_eq!(
        TabulatedResponse::new(&[0.0, 0.6, 0.4, 1.0]),
        Err(SensorError::NotMonotonic)
    );
    assert_eq!(
        TabulatedResponse::new(&[1.0, 0.0]),
        Err(SensorError::NotMonotonic)
    );
    assert_eq!(TabulatedResponse::new(&[0.0]), Err(SensorError::BadBuffer));
    assert_eq!(
        TabulatedResponse::new(&[0.0, f32::NAN]),
        Err(SensorError::NotFinite)
    );
}
