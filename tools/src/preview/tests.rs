//! The preview's tests: the white furnace, the frame and background, the
//! estimator against the crate's exact reflection integrals, determinism.

use super::*;
use crate::spec::model::{AnyBrdf, build_brdf};
use crate::spec::parse_brdf;
use radiometry::integrator::Auto;
use radiometry::light::reflected_radiance;

fn brdf(spec: &str) -> AnyBrdf {
    build_brdf(spec, &parse_brdf(spec).expect("spec parses")).expect("spec builds")
}

fn quiet(size: u32, samples: u32) -> Options {
    Options {
        size,
        samples,
        progress: false,
        ..Options::default()
    }
}

/// Largest relative deviation from `sky` over the pixels whose every camera
/// sample hit the ball, and how many such pixels there are.
fn furnace_deviation(img: &Image, sky: f32) -> (f32, usize) {
    let mut worst = 0.0f32;
    let mut n = 0;
    for (&l, &c) in img.radiance().iter().zip(img.coverage()) {
        if c == 1.0 {
            n += 1;
            worst = worst.max((l - sky).abs() / sky);
        }
    }
    (worst, n)
}

/// Tolerance of the white furnace: relative, per pixel. A white Lambertian
/// ball under the sky alone is estimated with zero variance (both techniques
/// draw from `cos θ/π` and carry weight `ρ L`, and the two power-heuristic
/// weights sum to 1), so what is left is `f32` rounding of the weights and of
/// the per-sample `f32` results, ≤ a few ulps each: 10⁻⁵ is ~100 ulps.
const FURNACE_TOL: f32 = 1e-5;

#[test]
fn white_furnace_ball_disappears_into_the_sky() {
    let opt = Options {
        sun_irradiance: 0.0,
        ..quiet(24, 16)
    };
    let sky = opt.sky_radiance;
    for spec in [
        "lambertian(albedo=1)",
        "lambertian(albedo=0.5) + lambertian(albedo=0.5)",
        "mix(0.3, lambertian(albedo=1), lambertian)",
    ] {
        let img = render(&brdf(spec), &opt).unwrap();
        let (dev, n) = furnace_deviation(&img, sky);
        assert!(n > 200, "{spec}: only {n} pixels fully on the ball");
        assert!(dev <= FURNACE_TOL, "{spec}: furnace deviation {dev:e}");
        // After tone mapping the ball is invisible: every byte equals the sky's.
        let g = img.to_gray8(1.0);
        let want = tone_map(sky, 1.0);
        assert!(
            g.iter().all(|&b| b == want),
            "{spec}: ball visible in the 8-bit image"
        );
    }
    // The check has teeth: a ball that reflects half (ρ = 0.5) or 99.9 % fails it.
    for spec in ["lambertian(albedo=0.5)", "lambertian(albedo=0.999)"] {
        let (dev, _) = furnace_deviation(&render(&brdf(spec), &opt).unwrap(), sky);
        assert!(dev > FURNACE_TOL, "{spec}: {dev:e} passed the furnace");
    }
}

/// Mean radiance over the pixels fully on the ball, its standard error from the
/// spread between those pixels (independent estimates of one value when the
/// ball is uniform), and their number.
fn ball_mean(img: &Image) -> (f64, f64, usize) {
    let v: Vec<f64> = img
        .radiance()
        .iter()
        .zip(img.coverage())
        .filter(|&(_, &c)| c == 1.0)
        .map(|(&l, _)| l as f64)
        .collect();
    let n = v.len() as f64;
    let mean = v.iter().sum::<f64>() / n;
    let var = v.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / (n - 1.0);
    (mean, (var / n).sqrt(), v.len())
}

/// The furnace: EON with ρ = 1 keeps all energy (its albedo is 1
/// within 10⁻⁴ at every θo), so under the sky alone the ball is the sky. EON is
/// not sampled exactly in proportion to `f cos`, so pixels are noisy: the test
/// is on the mean over the ball, within 4 standard errors (from the spread
/// between pixels) plus the albedo's 10⁻⁴ (measured at 48 px and 512 samples:
/// −1·10⁻⁵ ± 2·10⁻⁴ at σ = 0.5, −1.6·10⁻⁴ ± 3·10⁻⁴ at σ = 1, relative);
/// ρ = 0.99 is rejected by the same test.
#[test]
fn white_furnace_eon_ball_matches_the_sky_on_average() {
    let opt = Options {
        sun_irradiance: 0.0,
        ..quiet(32, 128)
    };
    let sky = opt.sky_radiance as f64;
    let within = |spec: &str| {
        let (mean, se, n) = ball_mean(&render(&brdf(spec), &opt).unwrap());
        assert!(n > 200, "{spec}: {n}");
        ((mean - sky).abs() <= 4.0 * se + 1e-4 * sky, mean, se)
    };
    for spec in [
        "eon(rho=1, sigma=0)",
        "eon(rho=1, sigma=0.5)",
        "eon(rho=1, sigma=1)",
    ] {
        let (ok, mean, se) = within(spec);
        assert!(ok, "{spec}: ball {mean} ± {se} vs sky {sky}");
    }
    let (ok, mean, se) = within("eon(rho=0.99, sigma=1)");
    assert!(!ok, "ρ = 0.99 passed: {mean} ± {se}");
}

#[test]
fn image_has_the_requested_size_and_shows_the_sky_around_the_ball() {
    let opt = quiet(20, 8);
    let img = render(&brdf("ggx(alpha=0.3, fresnel=dielectric(eta=1.5))"), &opt).unwrap();
    assert_eq!(img.size(), 20);
    assert_eq!(img.radiance().len(), 400);
    assert_eq!(img.to_gray8(1.0).len(), 400);
    assert_eq!(img.get(20, 0), None);
    // The corners miss the ball and see the sky (the sun is behind the camera).
    for (x, y) in [(0, 0), (19, 0), (0, 19), (19, 19)] {
        let k = (y * 20 + x) as usize;
        assert_eq!(img.coverage()[k], 0.0);
        assert_eq!(img.get(x, y), Some(opt.sky_radiance));
    }
    // The centre is on the ball, which is lit: brighter than a black ball.
    let c = (10 * 20 + 10) as usize;
    assert_eq!(img.coverage()[c], 1.0);
    assert!(img.radiance()[c] > 0.0);
    // The ball covers π r² of the frame: r = tan(14.48°)/tan(16.7°) of the half-width.
    let covered: f32 = img.coverage().iter().sum();
    let r = (1.0f32 / CAMERA_DISTANCE).asin().tan() / (0.5 * FIELD_OF_VIEW_DEG).to_radians().tan();
    let want = PI * r * r * 100.0;
    assert!((covered - want).abs() < 0.03 * want, "{covered} vs {want}");
}

/// The estimator of [`Lighting::shade`] averages to the reflected radiance
/// that the core crate computes by its exact per-light methods
/// ([`reflected_radiance`]: cap integration, sky albedo), within 4 standard
/// errors, for diffuse, glossy and layered BRDFs, a sun high, low and
/// straddling the local horizon.
#[test]
fn shading_estimator_is_unbiased() {
    let opt = Options {
        sun_radius: 3.0,
        ..quiet(1, 1)
    };
    let lighting = Lighting::new(&opt).unwrap();
    let sun = lighting.sun();
    let wo = Vec3::new(0.2, 0.3, 1.0).normalize();
    let normals = [
        Vec3::new(0.0, 0.0, 1.0),
        (sun.axis() + Vec3::new(0.0, 0.0, 0.5)).normalize(),
        // The sun's axis 1.5° below the local horizon: the top of its 3° cap is visible.
        {
            let a = sun.axis();
            let p = (wo - wo.dot(a) * a).normalize();
            let t = 1.5f32.to_radians();
            (t.cos() * p - t.sin() * a).normalize()
        },
    ];
    for spec in [
        "lambertian(albedo=0.8)",
        "ggx(alpha=0.2, fresnel=dielectric(eta=1.5))",
        "coated(ggx(alpha=0.1, fresnel=dielectric(eta=1.5)), lambertian(albedo=0.8))",
    ] {
        let b = brdf(spec);
        for &n in &normals {
            let frame = Frame::from_normal(n).unwrap();
            if frame.to_local(wo).z < 0.1 {
                continue;
            }
            let local_sun =
                Cap::new(frame.to_local(sun.axis()), sun.half_angle(), sun.cap_radiance()).unwrap();
            let exact = reflected_radiance(
                &b,
                &(local_sun, *lighting.sky()),
                frame.to_local(wo),
                &Auto::new(),
                1 << 16,
            )
            .unwrap();
            let mut rng = Pcg32::with_stream(3, 1);
            let m = 40_000;
            let (mut s, mut s2) = (0.0f64, 0.0f64);
            for _ in 0..m {
                let u = [
                    rng.next_f32(),
                    rng.next_f32(),
                    rng.next_f32(),
                    rng.next_f32(),
                    rng.next_f32(),
                ];
                let v = lighting.shade(&b, n, wo, u) as f64;
                s += v;
                s2 += v * v;
            }
            let mean = s / m as f64;
            let se = ((s2 / m as f64 - mean * mean).max(0.0) / m as f64).sqrt();
            let err = (mean - exact.value).abs();
            assert!(
                err <= 4.0 * se + exact.error + 1e-5 * exact.value,
                "{spec} n={n}: {mean} ± {se} vs exact {} ± {}",
                exact.value,
                exact.error
            );
        }
    }
}

#[test]
fn images_do_not_depend_on_the_thread_count() {
    let b = brdf("coated(ggx(alpha=0.1, fresnel=dielectric(eta=1.5)), lambertian(albedo=0.8))");
    let one = render(
        &b,
        &Options {
            threads: 1,
            ..quiet(9, 3)
        },
    )
    .unwrap();
    let two = render(
        &b,
        &Options {
            threads: 3,
            ..quiet(9, 3)
        },
    )
    .unwrap();
    assert_eq!(one, two);
    let other_seed = render(
        &b,
        &Options {
            seed: 2,
            ..quiet(9, 3)
        },
    )
    .unwrap();
    assert_ne!(one, other_seed);
}

#[test]
fn bad_options_are_rejected() {
    let b = brdf("lambertian");
    assert!(matches!(render(&b, &quiet(0, 1)), Err(PreviewError::Size(0))));
    assert!(matches!(render(&b, &quiet(4, 0)), Err(PreviewError::Samples(0))));
    for o in [
        Options {
            sun_radius: 0.0,
            ..quiet(4, 1)
        },
        Options {
            sun_elevation: f32::NAN,
            ..quiet(4, 1)
        },
        Options {
            sun_elevation: 91.0,
            ..quiet(4, 1)
        },
    ] {
        assert!(matches!(render(&b, &o), Err(PreviewError::Angle(..))), "{o:?}");
    }
    for o in [
        Options {
            sky_radiance: -1.0,
            ..quiet(4, 1)
        },
        Options {
            sun_irradiance: f32::INFINITY,
            ..quiet(4, 1)
        },
    ] {
        assert!(matches!(render(&b, &o), Err(PreviewError::Light(_))), "{o:?}");
    }
}

#[cfg(feature = "plot")]
#[test]
fn png_and_svg_hold_the_picture() {
    let img = render(&brdf("lambertian"), &quiet(6, 2)).unwrap();
    let png = img.encode_png(1.0, "lambertian & <co>").unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    let dec = png::Decoder::new(std::io::Cursor::new(&png));
    let mut r = dec.read_info().unwrap();
    let mut buf = vec![0; r.output_buffer_size().unwrap()];
    let info = r.next_frame(&mut buf).unwrap();
    assert_eq!((info.width, info.height), (6, 6));
    assert_eq!(&buf[..info.buffer_size()], &img.to_gray8(1.0)[..]);
    let svg = img.to_svg(1.0, "lambertian & <co>").unwrap();
    assert!(svg.starts_with("<svg") && svg.contains("data:image/png;base64,iVBORw0KGgo"));
    assert!(svg.contains("<title>lambertian &amp; &lt;co&gt;</title>"));
}

/// The sun's share `q` takes the unclipped closed form where the cap is above
/// the horizon: it agrees with the clipped formula of the core crate.
#[test]
fn sun_share_matches_the_clipped_cap_irradiance() {
    let l = Lighting::new(&Options {
        sun_radius: 5.0,
        ..quiet(1, 1)
    })
    .unwrap();
    let sun = l.sun();
    for k in 0..=400 {
        let theta = (k as f32 / 400.0) * PI;
        let n = Frame::from_normal(sun.axis())
            .unwrap()
            .to_world(Vec3::new(theta.sin(), 0.0, theta.cos()));
        let f = Frame::from_normal(n).unwrap();
        let e =
            radiometry::radiometric::cap_irradiance(sun.cap_radiance(), n.dot(sun.axis()), sun.half_angle());
        let sky = PI * l.sky().sky_radiance();
        let want = if e + sky > 0.0 { e / (e + sky) } else { 0.0 };
        assert!(
            (l.sun_share(&f) - want).abs() <= 1e-5,
            "θ = {theta}: {} vs {want}",
            l.sun_share(&f)
        );
    }
}
