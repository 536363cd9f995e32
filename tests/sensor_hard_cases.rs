//! Property tests: no panic, no NaN/inf from the sensor and spectral API on arbitrary
//! (including non-finite) input; invalid parameters are typed errors.

use proptest::prelude::*;
use radiometry::sensor::als::AlsCalibration;
use radiometry::sensor::calibration::{PolynomialInverseResponse, mitsunaga_nayar};
use radiometry::sensor::color::{
    BayerPattern, DichroicPrism, StackedLayers, demosaic_bilinear, demosaic_malvar,
};
use radiometry::sensor::noise::{Pcg32, poisson};
use radiometry::sensor::response::{Gamma, Linear, Response, Srgb, TabulatedResponse};
use radiometry::sensor::{Emva1288, FillFactor, Monochromatic, Pixel, Sampling};
use radiometry::spectral::{self, Blackbody, FnCurve, IlluminantA, SpectralCurve, photometry};

fn any_f32() -> impl Strategy<Value = f32> {
    prop_oneof![
        proptest::num::f32::ANY,
        Just(0.0f32),
        Just(-0.0f32),
        Just(f32::NAN),
        Just(f32::INFINITY),
        Just(f32::NEG_INFINITY),
        Just(1e-38f32),
        Just(f32::MAX),
        Just(0.99999994f32),
        300.0f32..900.0,
        -2.0f32..2.0,
    ]
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 2000,
        // Failures are saved to, and replayed from, `sensor_hard_cases.proptest-regressions` next to this
        // file (named explicitly: the default location depends on the name of the harness file).
        failure_persistence: Some(Box::new(
            proptest::test_runner::FileFailurePersistence::WithSource("proptest-regressions"),
        )),
        ..ProptestConfig::default()
    })]

    #[test]
    fn spectral_curves_are_total(l in any_f32(), t in any_f32(), e in any_f32()) {
        for v in [spectral::photopic_v().value(l), spectral::d65().value(l), spectral::x_bar().value(l),
                  IlluminantA.value(l), photometry::illuminance_monochromatic(l, e)] {
            prop_assert!(v.is_finite());
        }
        if let Ok(b) = Blackbody::new(t) {
            prop_assert!(b.value(l).is_finite() && b.value(l) >= 0.0);
        }
        let _ = spectral::photopic_v().try_value(l);
        prop_assert!(photometry::xyz_to_linear_srgb([l, t, e]).iter().all(|v| v.is_finite()));
        if let Some(c) = photometry::chromaticity([l, t, e]) {
            prop_assert!(c[0].is_finite() && c[1].is_finite());
        }
    }

    #[test]
    fn responses_are_total(x in any_f32(), g in any_f32()) {
        for (a, b) in [(Linear.apply(x), Linear.inverse(x)), (Srgb.apply(x), Srgb.inverse(x))] {
            prop_assert!((0.0..=1.0).contains(&a) && (0.0..=1.0).contains(&b));
        }
        if let Ok(gm) = Gamma::new(g) {
            prop_assert!(gm.apply(x).is_finite() && gm.inverse(x).is_finite());
        }
        let t = TabulatedResponse::new(&[0.0, 0.3, 0.8, 1.0]).unwrap();
        prop_assert!(t.apply(x).is_finite() && t.inverse(x).is_finite());
    }

    #[test]
    fn polynomial_responses_are_total(c in proptest::array::uniform4(any_f32()), lo in any_f32(), x in any_f32()) {
        if let Ok(p) = PolynomialInverseResponse::new(c, lo) {
            prop_assert!(p.apply(x).is_finite() && p.inverse(x).is_finite());
        }
    }

    #[test]
    fn calibration_never_panics(r in proptest::collection::vec(any_f32(), 6..30), t in proptest::array::uniform3(any_f32())) {
        let n = r.len() / 3 * 3;
        if let Ok(g) = mitsunaga_nayar::<4>(&r[..n], &t, 0.02, 0.98) {
            prop_assert!(g.inverse(0.5).is_finite());
        }
    }

    #[test]
    fn camera_is_total(mu in any_f32(), l in any_f32(), e in any_f32(), seed in any::<u64>()) {
        let mut rng = Pcg32::new(seed);
        let k = poisson(&mut rng, mu);
        prop_assert!(k.is_finite() && k >= 0.0);
        let px = Pixel::new(FillFactor::new(0.5).unwrap(), FnCurve::new(300.0, 1100.0, |_| 0.5), 1e-11, 0.01,
                            Sampling::default()).unwrap();
        let cam = Emva1288::ideal(px, 0.3, 1e4, 12).unwrap().with_shot_noise().with_dark_noise(2.0).unwrap()
            .with_fixed_pattern(1.0, 0.01, 3).unwrap();
        let dn = cam.digitize(mu, seed as u32, &mut rng);
        prop_assert!((0.0..=4095.0).contains(&dn) && dn.fract() == 0.0);
        if let Ok(m) = px.mean_electrons(&Monochromatic::new(l, e)) {
            prop_assert!(m.is_finite());
        }
    }

    #[test]
    fn als_and_colour_are_total(c in any::<u32>(), g in any_f32(), t in any_f32(), l in any_f32()) {
        let cal = AlsCalibration::new(5.0, 0.1, 1.1, 65535).unwrap();
        if let Ok(v) = cal.lux(c, g, t) {
            prop_assert!(v.is_finite() && v >= 0.0);
        }
        let p = DichroicPrism::new(490.0, 590.0, 5.0).unwrap();
        prop_assert!(p.transmittances(l).iter().all(|v| (0.0..=1.0).contains(v)));
        prop_assert!(StackedLayers::foveon().fractions(l).iter().all(|v| (0.0..=1.0).contains(v)));
    }

    #[test]
    fn demosaic_is_finite_on_finite_input(raw in proptest::collection::vec(-1e30f32..1e30, 12), p in 0usize..4) {
        let pat = BayerPattern::ALL[p];
        let mut out = [[0.0f32; 3]; 12];
        demosaic_bilinear(&raw, 4, 3, pat, &mut out).unwrap();
        prop_assert!(out.iter().flatten().all(|v| v.is_finite()));
        demosaic_malvar(&raw, 4, 3, pat, &mut out).unwrap();
        prop_assert!(out.iter().flatten().all(|v| v.is_finite()));
    }
}
