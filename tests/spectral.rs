//! Tabulated curves: interpolation, out-of-range policy, validation.

use radiometry::spectral::{self, FnCurve, Irregular, SpectralCurve, SpectralError, Tabulated};

#[test]
fn tabulated_interpolates_linearly_and_hits_nodes() {
    const T: [f32; 4] = [1.0, 3.0, 2.0, 6.0];
    let t = Tabulated::new(400.0, 10.0, &T).unwrap();
    for (i, &v) in T.iter().enumerate() {
        assert_eq!(t.value(400.0 + 10.0 * i as f32), v);
    }
    assert!((t.value(405.0) - 2.0).abs() < 1e-6);
    assert!((t.value(427.5) - 5.0).abs() < 1e-6);
    assert_eq!(t.support(), (400.0, 430.0));
}

#[test]
fn out_of_range_is_zero_or_typed_error() {
    let v = spectral::photopic_v();
    for l in [
        359.99f32,
        830.01,
        -1.0,
        0.0,
        1e30,
        -1e30,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NAN,
    ] {
        assert_eq!(v.value(l), 0.0, "{l}");
        assert!(v.try_value(l).is_err(), "{l}");
    }
    assert_eq!(
        v.try_value(900.0),
        Err(SpectralError::OutOfRange {
            lambda: 900.0,
            min: 360.0,
            max: 830.0
        })
    );
    assert_eq!(v.try_value(f32::NAN), Err(SpectralError::NotFinite));
    assert!(v.try_value(360.0).is_ok() && v.try_value(830.0).is_ok());
    // Display is implemented and non-empty.
    assert!(!format!("{}", SpectralError::NotIncreasing).is_empty());
}

#[test]
fn invalid_tables_are_rejected() {
    assert_eq!(
        Tabulated::new(400.0, 0.0, &[1.0, 2.0]),
        Err(SpectralError::NotIncreasing)
    );
    assert_eq!(Tabulated::new(400.0, 5.0, &[1.0]), Err(SpectralError::BadLength));
    assert_eq!(
        Tabulated::new(f32::NAN, 5.0, &[1.0, 2.0]),
        Err(SpectralError::NotFinite)
    );
    assert_eq!(
        Tabulated::new(400.0, 5.0, &[1.0, f32::NAN]),
        Err(SpectralError::NotFinite)
    );
    assert_eq!(
        Irregular::new(&[400.0, 500.0], &[1.0]),
        Err(SpectralError::BadLength)
    );
    assert_eq!(
        Irregular::new(&[500.0, 400.0], &[1.0, 1.0]),
        Err(SpectralError::NotIncreasing)
    );
    assert_eq!(
        Irregular::new(&[400.0, f32::INFINITY], &[1.0, 1.0]),
        Err(SpectralError::NotFinite)
    );
}

#[test]
fn irregular_matches_uniform_on_same_nodes() {
    let l: [f32; 5] = [400.0, 450.0, 500.0, 550.0, 600.0];
    let v: [f32; 5] = [0.1, 0.5, 0.2, 0.9, 0.3];
    let a = Irregular::new(&l, &v).unwrap();
    let b = Tabulated::new(400.0, 50.0, &v).unwrap();
    for i in 0..=2000 {
        let x = 390.0 + i as f32 * 0.11;
        assert!((a.value(x) - b.value(x)).abs() < 1e-6, "{x}");
    }
    assert_eq!(a.value(f32::NAN), 0.0);
}

#[test]
fn integrate_product_matches_closed_form() {
    // ∫_400^700 (λ/100)² dλ = (700³ − 400³)/(3·10⁴) = 9300.
    let a = FnCurve::new(400.0, 700.0, |l| l / 100.0);
    let got = spectral::integrate_product(&a, &a, 0.5);
    assert!((got - 9300.0).abs() / 9300.0 < 1e-5, "{got}");
    // Disjoint supports integrate to zero.
    let b = FnCurve::new(800.0, 900.0, |_| 1.0);
    assert_eq!(spectral::integrate_product(&a, &b, 1.0), 0.0);
    // Silly steps fall back to 1 nm and stay finite.
    for s in [0.0, -1.0, f32::NAN, 1e-12] {
        assert!(spectral::integrate_product(&a, &a, s).is_finite());
    }
}
