use super::*;
use crate::preview::colour::{AsGrey, Preset, PresetKind};
use radiometry_brdfs::Lambertian;

fn small() -> Options {
    Options {
        size: 16,
        samples: 16,
        progress: false,
        threads: 2,
        ..Options::default()
    }
}

/// Largest relative spread `max|c − mean|/mean` of a pixel's channels.
fn spread(p: [f32; 3]) -> f32 {
    let m = (p[0] + p[1] + p[2]) / 3.0;
    p.iter().fold(0.0f32, |a, &c| a.max((c - m).abs() / m))
}

#[test]
fn grey_ball_under_d65_is_neutral_for_the_observer() {
    // A grey Lambertian under a D65 sun and sky reflects k·D65(λ) at every point; D65 is the
    // sRGB white, so the observer's linear sRGB has R = G = B up to the hero-wavelength
    // error of the 10 nm trapezoid rule on the camera's grid: within 2·10⁻³ per pixel
    // (measured 5.9·10⁻⁴).
    let grey = Lambertian::new(0.5f32).unwrap();
    let cam = CameraOptions {
        noise: false,
        ..CameraOptions::default()
    };
    let r = render_camera(&AsGrey(&grey), &small(), &cam).unwrap();
    let mut worst = 0.0f32;
    let mut mean = [0.0f64; 3];
    let mut count = 0;
    for (p, c) in r.observer_raw.rgb().iter().zip(r.observer_raw.coverage()) {
        if *c == 1.0 {
            worst = worst.max(spread(*p));
            for k in 0..3 {
                mean[k] += p[k] as f64;
            }
            count += 1;
        }
    }
    assert!(count > 100);
    assert!(worst < 2e-3, "worst channel spread {worst}");
    let m = mean.map(|v| (v / count as f64) as f32);
    assert!(spread(m) < 2e-3, "mean over the ball {m:?}");
    // The camera, white balanced on the white diffuser, sees the grey ball neutral too
    // (noiseless: the raw values of a grey are the white's times one factor per photosite,
    // quantised to 12 bits): the mean over the ball's interior within 2·10⁻³.
    for kind in CameraKind::ALL {
        // Bilinear demosaicing is exact on a flat field but not on the shading of a 16-pixel
        // ball (measured: 3 % between channels); under the sky alone a Lambertian ball is flat.
        let opt = if kind == CameraKind::Bayer {
            Options {
                sun_irradiance: 0.0,
                ..small()
            }
        } else {
            small()
        };
        let r = render_camera(&AsGrey(&grey), &opt, &CameraOptions { kind, ..cam }).unwrap();
        let cov = r.camera.coverage();
        // Pixels whose 3 × 3 neighbourhood lies on the ball (bilinear demosaicing
        // at the silhouette mixes the sky into the missing channels).
        let inside = |i: usize| {
            let (x, y) = (i % 16, i / 16);
            (x >= 1 && y >= 1 && x <= 14 && y <= 14)
                && (0..9).all(|k| cov[(y + k / 3 - 1) * 16 + x + k % 3 - 1] == 1.0)
        };
        let mut mean = [0.0f64; 3];
        for (i, p) in r.camera.rgb().iter().enumerate() {
            if inside(i) {
                for k in 0..3 {
                    mean[k] += p[k] as f64;
                }
            }
        }
        let m = mean.map(|v| v as f32);
        assert!(spread(m) < 2e-3, "{kind:?}: {m:?}");
    }
}

#[test]
fn flat_patch_noise_follows_the_emva_prediction() {
    // 4096 readings of a flat patch at μ_e = 2000: the sample variance against
    // σ_y² = K²(μ_e + σ_d²) + 1/12. The sample variance of n readings has a relative
    // standard deviation √(2/(n − 1)) ≈ 2.2 % (near-Gaussian readings); the bound is 5 of those.
    let cam = CameraOptions::default();
    let s = SensorModel::new(&cam).unwrap();
    let mu = 2000.0;
    let n = 4096;
    let reads: Vec<f64> = (0..n).map(|i| s.read(mu, i) as f64).collect();
    let mean = reads.iter().sum::<f64>() / n as f64;
    let var = reads.iter().map(|r| (r - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
    let want = s.predicted_variance_dn(mu, cam.dark_noise_e) as f64;
    let rel = (var / want - 1.0).abs();
    assert!(
        rel < 5.0 * (2.0 / (n as f64 - 1.0)).sqrt(),
        "variance {var} vs EMVA {want}"
    );
    // The mean: offset + K μ_e within 5 standard errors.
    let k = s.gain() as f64;
    let want_mean = cam.dark_offset_dn as f64 + k * mu as f64;
    assert!(
        (mean - want_mean).abs() < 5.0 * (want / n as f64).sqrt(),
        "{mean} vs {want_mean}"
    );
    // Noiseless: every reading is the rounded mean, and normalise inverts it.
    let quiet = SensorModel::new(&CameraOptions { noise: false, ..cam }).unwrap();
    assert_eq!(quiet.read(mu, 7), quiet.read(mu, 8));
    assert!(
        (quiet.normalise(quiet.read(mu, 0)) - mu / cam.full_well_e).abs()
            < 1.0 / (k as f32 * cam.full_well_e)
    );
}

#[test]
fn the_camera_report_measures_something() {
    let gold = Preset::new(PresetKind::Gold).unwrap();
    let r = render_camera(&gold, &small(), &CameraOptions::default()).unwrap();
    let rep = r.report;
    assert!(rep.pixels > 50, "{rep:?}");
    assert!(rep.mean_delta_e.is_finite() && rep.mean_delta_e >= rep.mean_delta_e_noiseless * 0.5);
    assert!(rep.noise.iter().all(|&v| v > 0.0 && v < 0.5), "{rep:?}");
    for c in 0..3 {
        assert!(rep.noise_predicted[c] > 0.0, "{rep:?}");
    }
    assert!(
        rep.chart_delta_e > 0.0 && rep.chart_delta_e <= rep.chart_delta_e_max,
        "{rep:?}"
    );
    // 2500 e⁻, σ_d = 6 e⁻: SNR ≈ √2500 = 50.
    assert!((rep.white_snr - 49.6).abs() < 0.5, "{}", rep.white_snr);
}

#[test]
fn developed_noise_follows_the_emva_prediction_through_the_matrix() {
    // The developed noise is the EMVA 1288 variance of the raw readings (for the Bayer
    // sensor, of the bilinear averages of neighbouring photosites) through D·M, in expectation.
    // A grey ball under the sky alone (flat), 64 × 64: ~2,300 pixels; a Bayer channel is read
    // at ≥ 580 independent photosites, so ±12 % is about 4 standard errors of an RMS
    // (1/√(2·580) = 2.9 %). Measured: within 6 % (Bayer), 1.6 % (prism), 2.5 % (stacked).
    let grey = Lambertian::new(0.5f32).unwrap();
    let opt = Options {
        sun_irradiance: 0.0,
        size: 64,
        samples: 4,
        ..small()
    };
    for kind in CameraKind::ALL {
        let r = render_camera(
            &AsGrey(&grey),
            &opt,
            &CameraOptions {
                kind,
                ..CameraOptions::default()
            },
        )
        .unwrap();
        let rep = r.report;
        assert!(rep.pixels > 100, "{rep:?}");
        for c in 0..3 {
            let ratio = rep.noise[c] / rep.noise_predicted[c];
            assert!((ratio - 1.0).abs() < 0.12, "{kind:?} channel {c}: {rep:?}");
        }
    }
}

#[test]
fn a_black_body_at_6504_k_is_near_d65_and_a_cold_one_is_red() {
    // The observer's white diffuser, before white balance, under Planck light: near-neutral
    // at 6504 K (D65's correlated colour temperature; D65 is not Planckian, so only within
    // 10 %), red-heavy at 2000 K.
    let grey = Lambertian::new(1.0f32).unwrap();
    let opt = Options {
        sun_irradiance: 0.0,
        ..small()
    };
    let centre = |t: f32| {
        let cam = CameraOptions {
            illuminant: Illuminant::Planck(t),
            noise: false,
            ..CameraOptions::default()
        };
        let r = render_camera(&AsGrey(&grey), &opt, &cam).unwrap();
        r.observer_raw.rgb()[8 * 16 + 8]
    };
    let d = centre(6504.0);
    assert!(spread(d) < 0.1, "{d:?}");
    let warm = centre(2000.0);
    assert!(warm[0] > 2.0 * warm[2], "{warm:?}");
}

#[test]
fn bad_camera_options_are_typed_errors() {
    let grey = Lambertian::new(0.5f32).unwrap();
    for cam in [
        CameraOptions {
            exposure: 0.0,
            ..CameraOptions::default()
        },
        CameraOptions {
            exposure: f32::NAN,
            ..CameraOptions::default()
        },
        CameraOptions {
            bits: 4,
            ..CameraOptions::default()
        },
        CameraOptions {
            full_well_e: -1.0,
            ..CameraOptions::default()
        },
        CameraOptions {
            dark_noise_e: f32::INFINITY,
            ..CameraOptions::default()
        },
    ] {
        assert!(matches!(
            render_camera(&AsGrey(&grey), &small(), &cam),
            Err(PreviewError::Camera(_))
        ));
    }
    let bad_gamma = CameraOptions {
        response: ResponseCurve::Gamma(0.0),
        ..CameraOptions::default()
    };
    assert!(matches!(
        render_camera(&AsGrey(&grey), &small(), &bad_gamma),
        Err(PreviewError::Camera(_))
    ));
    // The curves: sRGB of 0.5 linear is 0.7354 (IEC 61966-2-1), γ = 2 is √, linear is itself.
    assert!((ResponseCurve::Srgb.apply(0.5) - 0.735_357).abs() < 1e-5);
    assert!((ResponseCurve::Gamma(2.0).apply(0.25) - 0.5).abs() < 1e-6);
    assert_eq!(ResponseCurve::Linear.apply(0.25), 0.25);
    let img = RgbImage::new(1, 1, vec![[0.5, 2.0, f32::NAN]], vec![1.0]).unwrap();
    assert_eq!(img.to_encoded8(ResponseCurve::Srgb), vec![188, 255, 0]);
    assert!(CameraKind::Bayer.sensitivities(f32::NAN) == [0.0; 3]);
    assert!(invert3([[1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0, 0.0, 1.0]]).is_none());
    let id = invert3([[2.0, 0.0, 0.0], [0.0, 4.0, 0.0], [0.0, 0.0, 8.0]]).unwrap();
    assert_eq!(id, [[0.5, 0.0, 0.0], [0.0, 0.25, 0.0], [0.0, 0.0, 0.125]]);
    // ΔE of a colour with itself is 0; of white and black, L* = 100.
    assert_eq!(delta_e([0.3, 0.2, 0.1], [0.3, 0.2, 0.1]), 0.0);
    assert!((delta_e([WHITE_LEVEL; 3], [0.0; 3]) - 100.0).abs() < 1e-3);
}
