//! The BRDF half of the C API, called as C would call it: constructors reject
//! bad parameters with a status (never a panic), eval matches closed forms,
//! sample / pdf / eval agree, batches match single calls, and bad pointers
//! are reported.
//!
//! Run with `cargo test --features std` (the `no_std` library needs std's
//! panic runtime under the test harness).

use core::f32::consts::PI;
use core::ptr::{null, null_mut};
use radiometry_ffi::brdf::*;
use radiometry_ffi::{RadBrdf, RadBrdfSample, RadStatus, RadVec3};

fn v(x: f32, y: f32, z: f32) -> RadVec3 {
    let n = (x * x + y * y + z * z).sqrt();
    RadVec3 {
        x: x / n,
        y: y / n,
        z: z / n,
    }
}

fn ggx(alpha: f32) -> RadBrdf {
    let mut b = RadBrdf::default();
    let s = unsafe {
        rad_brdf_microfacet(
            RAD_DISTRIBUTION_GGX,
            alpha,
            RAD_SHADOWING_HEIGHT_CORRELATED,
            RAD_FRESNEL_NONE,
            0.0,
            0.0,
            &mut b,
        )
    };
    assert_eq!(s, RadStatus::Ok);
    b
}

fn eval(b: &RadBrdf, wi: RadVec3, wo: RadVec3) -> f32 {
    let mut f = f32::NAN;
    assert_eq!(unsafe { rad_brdf_eval(b, wi, wo, &mut f) }, RadStatus::Ok);
    f
}

/// Every plugin kind the C API can build, with valid parameters.
fn all_plugins() -> Vec<RadBrdf> {
    let mut v = Vec::new();
    let mut b = RadBrdf::default();
    unsafe {
        assert_eq!(rad_brdf_lambertian(0.7, &mut b), RadStatus::Ok);
        v.push(b);
        assert_eq!(rad_brdf_phong(30.0, 0.6, 0.3, &mut b), RadStatus::Ok);
        v.push(b);
        assert_eq!(rad_brdf_blinn_phong(30.0, 0.6, 0.3, &mut b), RadStatus::Ok);
        v.push(b);
        assert_eq!(rad_brdf_eon(0.8, 0.5, &mut b), RadStatus::Ok);
        v.push(b);
        assert_eq!(rad_brdf_fon(0.8, 1.0, &mut b), RadStatus::Ok);
        v.push(b);
        assert_eq!(rad_brdf_oren_nayar(0.9, 0.35, &mut b), RadStatus::Ok);
        v.push(b);
        assert_eq!(rad_brdf_sheen(0.7, 0.4, &mut b), RadStatus::Ok);
        v.push(b);
        for d in [RAD_DISTRIBUTION_GGX, RAD_DISTRIBUTION_BECKMANN] {
            for g in [RAD_SHADOWING_HEIGHT_CORRELATED, RAD_SHADOWING_SEPARABLE] {
                for (f, a, k) in [
                    (RAD_FRESNEL_NONE, 0.0, 0.0),
                    (RAD_FRESNEL_SCHLICK, 0.04, 0.0),
                    (RAD_FRESNEL_DIELECTRIC, 1.5, 0.0),
                    (RAD_FRESNEL_CONDUCTOR, 0.2, 3.9),
                    (RAD_FRESNEL_F82, 0.9, 0.7),
                    (RAD_FRESNEL_METAL, RAD_METAL_CU as f32, 0.0),
                ] {
                    assert_eq!(rad_brdf_microfacet(d, 0.3, g, f, a, k, &mut b), RadStatus::Ok);
                    v.push(b);
                }
            }
        }
    }
    v
}

#[test]
fn lambertian_is_albedo_over_pi() {
    let mut b = RadBrdf::default();
    assert_eq!(unsafe { rad_brdf_lambertian(0.5, &mut b) }, RadStatus::Ok);
    let f = eval(&b, v(0.3, 0.2, 0.9), v(-0.5, 0.1, 0.7));
    assert!((f - 0.5 / PI).abs() < 1e-7, "{f}");
    // Below the horizon: zero.
    assert_eq!(eval(&b, v(0.3, 0.2, -0.9), v(-0.5, 0.1, 0.7)), 0.0);
}

#[test]
fn ggx_at_normal_incidence_is_one_over_four_pi_alpha_squared() {
    // h = n: D = 1/(π α²), G2 = 1, F = 1, cos θi = cos θo = 1
    // ⇒ f = 1/(4π α²) (Walter et al. 2007, eqs. 20 and 33).
    for alpha in [0.1f32, 0.5, 1.0] {
        let f = eval(&ggx(alpha), v(0.0, 0.0, 1.0), v(0.0, 0.0, 1.0)) as f64;
        let want = 1.0 / (4.0 * std::f64::consts::PI * (alpha as f64).powi(2));
        assert!((f - want).abs() < 2e-6 * want, "α={alpha}: {f} vs {want}");
    }
}

#[test]
fn constructors_reject_bad_parameters_with_a_status() {
    let mut b = RadBrdf::default();
    let before = b;
    unsafe {
        assert_eq!(rad_brdf_lambertian(f32::NAN, &mut b), RadStatus::NotFinite);
        assert_eq!(rad_brdf_lambertian(1.5, &mut b), RadStatus::OutOfRange);
        assert_eq!(rad_brdf_phong(10.0, 0.7, 0.5, &mut b), RadStatus::Constraint);
        assert_eq!(
            rad_brdf_phong(f32::INFINITY, 0.5, 0.5, &mut b),
            RadStatus::NotFinite
        );
        assert_eq!(
            rad_brdf_blinn_phong(-1.0, 0.5, 0.5, &mut b),
            RadStatus::OutOfRange
        );
        for (d, a, g, f) in [
            (RAD_DISTRIBUTION_GGX, 0.0, 0, 0),
            (RAD_DISTRIBUTION_GGX, f32::NAN, 0, 0),
            (7, 0.3, 0, 0),
            (RAD_DISTRIBUTION_BECKMANN, 0.3, 9, 0),
            (RAD_DISTRIBUTION_BECKMANN, 0.3, 0, 9),
        ] {
            let s = rad_brdf_microfacet(d, a, g, f, 0.0, 0.0, &mut b);
            assert_ne!(s, RadStatus::Ok, "{d} {a} {g} {f}");
        }
        assert_eq!(
            rad_brdf_microfacet(0, 0.3, 0, RAD_FRESNEL_DIELECTRIC, 0.0, 0.0, &mut b),
            RadStatus::OutOfRange
        );
        assert_eq!(rad_brdf_lambertian(0.5, null_mut()), RadStatus::NullPointer);
    }
    assert_eq!(b, before, "output untouched on error");
}

#[test]
fn bad_handles_and_pointers_are_reported() {
    let zeroed = RadBrdf::default();
    let mut f = 0.0f32;
    let (wi, wo) = (v(0.0, 0.0, 1.0), v(0.0, 0.0, 1.0));
    unsafe {
        assert_eq!(rad_brdf_eval(&zeroed, wi, wo, &mut f), RadStatus::BadHandle);
        let mut scribbled = ggx(0.3);
        scribbled.params[0] = -4.0;
        assert_eq!(rad_brdf_eval(&scribbled, wi, wo, &mut f), RadStatus::OutOfRange);
        let b = ggx(0.3);
        assert_eq!(rad_brdf_eval(null(), wi, wo, &mut f), RadStatus::NullPointer);
        assert_eq!(rad_brdf_pdf(&b, wi, wo, null_mut()), RadStatus::NullPointer);
        // A float pointer one byte off.
        let mut buf = [0u8; 16];
        let odd = buf.as_mut_ptr().add(1).cast::<f32>();
        assert_eq!(rad_brdf_eval(&b, wi, wo, odd), RadStatus::Misaligned);
        // Output overlapping the input.
        let mut dirs = [wi; 8];
        let out = dirs.as_mut_ptr().cast::<f32>();
        assert_eq!(
            rad_brdf_eval_batch(&b, dirs.as_ptr(), dirs.as_ptr(), out, 8),
            RadStatus::Overlap
        );
        assert_eq!(
            rad_brdf_eval_batch(&b, null(), dirs.as_ptr(), &mut f, 1),
            RadStatus::NullPointer
        );
        // n = 0: nothing to read, any pointers.
        assert_eq!(
            rad_brdf_eval_batch(&b, null(), null(), null_mut(), 0),
            RadStatus::Ok
        );
        assert_eq!(
            rad_brdf_eval_batch(&b, dirs.as_ptr(), dirs.as_ptr(), &mut f, usize::MAX / 4),
            RadStatus::TooLong
        );
    }
}

/// Deterministic directions over the upper hemisphere (and a few below).
fn directions(n: usize) -> Vec<RadVec3> {
    (0..n)
        .map(|k| {
            let a = (k as f32 * 0.618_034).fract();
            let b = (k as f32 * 0.754_878).fract();
            let z = if k % 17 == 0 { -0.3 } else { 0.02 + 0.98 * a };
            let r = (1.0 - z * z).max(0.0).sqrt();
            let p = 2.0 * PI * b;
            RadVec3 {
                x: r * p.cos(),
                y: r * p.sin(),
                z,
            }
        })
        .collect()
}

#[test]
fn batches_match_single_calls() {
    let n = 203; // not a multiple of any vector width or of the sample chunk
    let wi = directions(n);
    let wo: Vec<RadVec3> = directions(n + 7)[7..].to_vec();
    let u: Vec<f32> = (0..2 * n).map(|k| (k as f32 * 0.377_3).fract()).collect();
    let soa = |d: &[RadVec3]| -> [Vec<f32>; 3] {
        [
            d.iter().map(|v| v.x).collect(),
            d.iter().map(|v| v.y).collect(),
            d.iter().map(|v| v.z).collect(),
        ]
    };
    let (si, so) = (soa(&wi), soa(&wo));
    for b in all_plugins() {
        let mut fe = vec![0.0f32; n];
        let mut fs = vec![0.0f32; n];
        let mut pb = vec![0.0f32; n];
        let mut sb = vec![RadBrdfSample::default(); n];
        unsafe {
            assert_eq!(
                rad_brdf_eval_batch(&b, wi.as_ptr(), wo.as_ptr(), fe.as_mut_ptr(), n),
                RadStatus::Ok
            );
            assert_eq!(
                rad_brdf_eval_batch_soa(
                    &b,
                    si[0].as_ptr(),
                    si[1].as_ptr(),
                    si[2].as_ptr(),
                    so[0].as_ptr(),
                    so[1].as_ptr(),
                    so[2].as_ptr(),
                    fs.as_mut_ptr(),
                    n
                ),
                RadStatus::Ok
            );
            assert_eq!(
                rad_brdf_pdf_batch(&b, wi.as_ptr(), wo.as_ptr(), pb.as_mut_ptr(), n),
                RadStatus::Ok
            );
            assert_eq!(
                rad_brdf_sample_batch(&b, wo.as_ptr(), u.as_ptr(), sb.as_mut_ptr(), n),
                RadStatus::Ok
            );
        }
        for k in 0..n {
            let f1 = eval(&b, wi[k], wo[k]);
            let tol = 1e-6 * f1.abs().max(1e-3);
            assert!((fe[k] - f1).abs() <= tol, "{b:?} k={k}: batch {} vs {f1}", fe[k]);
            assert!((fs[k] - f1).abs() <= tol, "{b:?} k={k}: soa {} vs {f1}", fs[k]);
            let mut p1 = 0.0;
            assert_eq!(unsafe { rad_brdf_pdf(&b, wi[k], wo[k], &mut p1) }, RadStatus::Ok);
            assert!((pb[k] - p1).abs() <= 1e-6 * p1.abs().max(1e-3), "{b:?} k={k}");
            let mut s1 = RadBrdfSample::default();
            assert_eq!(
                unsafe { rad_brdf_sample(&b, wo[k], u[2 * k], u[2 * k + 1], &mut s1) },
                RadStatus::Ok
            );
            assert_eq!(sb[k], s1, "{b:?} k={k}");
        }
    }
}

#[test]
fn samples_agree_with_pdf_and_eval() {
    let wo = directions(64);
    for b in all_plugins() {
        let mut valid = 0;
        for (k, &wo) in wo.iter().enumerate() {
            let (u0, u1) = ((k as f32 * 0.41).fract(), (k as f32 * 0.73).fract());
            let mut s = RadBrdfSample::default();
            assert_eq!(unsafe { rad_brdf_sample(&b, wo, u0, u1, &mut s) }, RadStatus::Ok);
            if s.pdf == 0.0 {
                assert_eq!(s, RadBrdfSample::default(), "no-sample convention");
                continue;
            }
            valid += 1;
            assert!(
                s.pdf.is_finite() && s.weight.iter().all(|w| w.is_finite() && *w >= 0.0),
                "{b:?} {s:?}"
            );
            let len = (s.wi.x * s.wi.x + s.wi.y * s.wi.y + s.wi.z * s.wi.z).sqrt();
            assert!((len - 1.0).abs() < 1e-5, "unit wi");
            let mut p = 0.0;
            assert_eq!(unsafe { rad_brdf_pdf(&b, s.wi, wo, &mut p) }, RadStatus::Ok);
            assert!(
                (p - s.pdf).abs() <= 1e-4 * s.pdf,
                "{b:?}: pdf {p} vs sample's {}",
                s.pdf
            );
            let want = eval(&b, s.wi, wo) * s.wi.z.max(0.0) / s.pdf;
            // The monochrome call writes its one weight to every channel.
            assert_eq!(s.weight, [s.weight[0]; 3]);
            assert!(
                (s.weight[0] - want).abs() <= 1e-4 * want.max(1e-3),
                "{b:?}: weight {:?} vs {want}",
                s.weight
            );
        }
        assert!(valid > 40, "{b:?}: only {valid} samples");
    }
}
