//! Unit tests of `ModifiedPhong`.

extern crate std;
use super::test_support::*;
use super::*;
use core::f64::consts::PI as PI64;
use radiometry::glam::Vec3 as V;
use std::string::ToString;

fn phong(kd: f32, ks: f32, n: f32) -> ModifiedPhong {
    ModifiedPhong::new(kd, ks, n).unwrap()
}

/// f at the mirror direction (cos α = 1) = kd/π + ks(n+2)/(2π), and in
/// the plane of incidence at angle α from the mirror direction
/// f = kd/π + ks(n+2)/(2π) cos^n α (closed form in f64).
#[test]
fn formula_spot_checks() {
    for &n in &[0.0f32, 1.0, 10.0, 1e3, 1e6, MAX_EXPONENT] {
        let b = phong(0.25, 0.75, n);
        let expect = 0.25 / PI64 + 0.75 * (n as f64 + 2.0) / (2.0 * PI64);
        let f = b.eval(V::Z, V::Z) as f64;
        assert!((f - expect).abs() <= 1e-6 * expect, "n={n}: {f} vs {expect}");
        // Mirror pair off normal: wi = reflect(wo).
        let wo = dir_xz(0.7);
        let wi = V::new(-wo.x, -wo.y, wo.z);
        let f = b.eval(wi, wo) as f64;
        assert!((f - expect).abs() <= 1e-5 * expect, "n={n}: {f} vs {expect}");
    }
    for &(theta_o, alpha, n) in &[
        (0.7f64, 0.1f64, 10.0f32),
        (0.3, 0.25, 3.5),
        (1.0, 0.02, 1000.0),
        (0.2, 0.6, 1.0),
    ] {
        let b = phong(0.1, 0.9, n);
        let wo = dir_xz(theta_o);
        // The mirror direction is at polar angle −θo; rotate by α in-plane.
        let wi = dir_xz(-theta_o + alpha);
        let expect =
            0.1 / PI64 + 0.9 * (n as f64 + 2.0) / (2.0 * PI64) * libm::pow(libm::cos(alpha), n as f64);
        let f = b.eval(wi, wo) as f64;
        assert!(
            (f - expect).abs() <= 1e-4 * expect,
            "{theta_o} {alpha} {n}: {f} vs {expect}"
        );
    }
    // cos α ≤ 0 (wi = wo far from normal): only the diffuse term, even for n = 0.
    for &n in &[0.0f32, 5.0] {
        let wo = dir_xz(1.2);
        let f = phong(0.3, 0.7, n).eval(wo, wo) as f64;
        assert!((f - 0.3 / PI64).abs() < 1e-7, "{f}");
    }
    // RGB: channel-wise.
    let rgb = ModifiedPhong::new(V::new(0.1, 0.2, 0.3), V::new(0.5, 0.4, 0.0), 4.0).unwrap();
    let f = rgb.eval(V::Z, V::Z);
    for (c, (kd, ks)) in [(0.1, 0.5), (0.2, 0.4), (0.3, 0.0)].into_iter().enumerate() {
        let e = kd / PI64 + ks * 6.0 / (2.0 * PI64);
        assert!((f.channel(c) as f64 - e).abs() < 1e-6, "{c}");
    }
}

#[test]
fn constructor_validation_and_messages() {
    let e = ModifiedPhong::new(f32::NAN, 0.1, 1.0).unwrap_err();
    assert_eq!(e, BrdfError::NotFinite { name: "kd" });
    assert_eq!(e.to_string(), "parameter `kd` must be finite");
    let e = ModifiedPhong::new(0.1f32, -0.1, 1.0).unwrap_err();
    assert_eq!(e.to_string(), "parameter `ks` = -0.1 is outside [0, 1]");
    let e = ModifiedPhong::new(0.5f32, 0.6, 1.0).unwrap_err();
    assert!(matches!(e, BrdfError::Constraint { .. }));
    assert_eq!(
        e.to_string(),
        "invalid parameters: kd + ks must not exceed 1 in any channel (energy conservation)"
    );
    let e = ModifiedPhong::new(0.1f32, 0.1, 2e7).unwrap_err();
    assert_eq!(
        e.to_string(),
        "parameter `exponent` = 20000000 is outside [0, 10000000]"
    );
    assert!(ModifiedPhong::new(0.1f32, 0.1, -1e-6).is_err());
    assert!(ModifiedPhong::new(0.1f32, 0.1, f32::INFINITY).is_err());
    // One bad channel of an RGB spectrum is enough.
    assert!(ModifiedPhong::new(V::new(0.1, 0.1, 0.9), V::splat(0.2), 1.0).is_err());
    assert!(ModifiedPhong::new(V::new(0.1, f32::NAN, 0.1), V::splat(0.2), 1.0).is_err());
    // Edges of the domain are accepted.
    assert!(ModifiedPhong::new(0.3f32, 0.7, 0.0).is_ok());
    assert!(ModifiedPhong::new(0.0f32, 1.0, MAX_EXPONENT).is_ok());
    assert!(ModifiedPhong::new(0.0f32, 0.0, 1.0).is_ok());
}

/// Lafortune & Willems: the lobe albedo at normal incidence is exactly 1
/// for ks = 1 (independent f64 quadrature of f cos θi).
#[test]
fn lobe_albedo_is_one_at_normal_incidence() {
    for &n in &[0.0f32, 1.0, 10.0, 100.0, 1000.0] {
        let a = albedo(&phong(0.0, 1.0, n), V::Z, 0, 4000, 16);
        std::eprintln!("phong lobe albedo n={n}: {a:.9} (err {:.2e})", a - 1.0);
        assert!((a - 1.0).abs() < 1e-4, "n={n}: {a}");
    }
    let a = albedo(&phong(0.35, 0.65, 30.0), V::Z, 0, 2000, 16);
    assert!((a - 1.0).abs() < 1e-4, "{a}");
}

/// Away from normal incidence the horizon clips the lobe: albedo ≤ 1.
#[test]
fn energy_at_most_one_off_normal() {
    for &n in &[0.0f32, 1.0, 10.0, 100.0] {
        for &t in &[0.2f64, 0.6, 1.0, 1.4, 1.55] {
            let a = albedo(&phong(0.0, 1.0, n), dir_xz(t), 0, 1500, 512);
            std::eprintln!("phong albedo n={n} θo={t}: {a:.6}");
            assert!(a <= 1.0 + 1e-4 && a > 0.0, "n={n} θo={t}: {a}");
        }
    }
    let a = albedo(&phong(0.0, 1.0, 1000.0), dir_xz(0.5), 0, 3000, 4096);
    assert!(a <= 1.0 + 1e-4 && a > 0.8, "{a}");
}

#[test]
fn sampling_matches_pdf_and_weight_on_grid() {
    let params = [
        (0.5f32, 0.5f32, 10.0f32),
        (0.0, 1.0, 0.0),
        (1.0, 0.0, 5.0),
        (0.2, 0.8, 1e6),
        (0.0, 1.0, MAX_EXPONENT),
    ];
    for &(kd, ks, n) in &params {
        let b = phong(kd, ks, n);
        for &t in &[0.0f64, 0.5, 1.2, 1.5706, core::f64::consts::FRAC_PI_2 - 1e-7] {
            let wo = dir_xz(t);
            let (some, ep, ew) = check_sampling(&b, wo);
            std::eprintln!(
                "phong sampling {kd} {ks} n={n} θo={t}: {some}/121 some, pdf err {ep:.1e}, weight err {ew:.1e}"
            );
            assert!(some > 0, "no sample for {kd} {ks} {n} {t}");
            assert!(check_sample_bits(&b, wo) > 0);
            // Non-unit wo gives the same samples.
            let s1 = b.sample(wo * 3.5, [0.3, 0.6]);
            let s2 = b.sample(wo, [0.3, 0.6]);
            assert_eq!(s1.is_some(), s2.is_some());
            if let (Some(a), Some(c)) = (s1, s2) {
                assert!((a.wi - c.wi).length() < 1e-5 && (a.pdf - c.pdf).abs() <= 1e-4 * c.pdf);
            }
        }
    }
}

/// The lobe sampler follows cos^n α even for huge n: KS distance of
/// `δ = 1 − cos α` (from the returned directions, in f64) to the closed
/// form CDF, with stratified u₀ (m = 4000: D = 1/(2m) = 1.25e-4 when exact;
/// the bound 5e-4 leaves room for f32 rounding of ωi).
#[test]
fn lobe_samples_follow_closed_form_cdf() {
    let m = 4000;
    for &n in &[1.0f32, 100.0, 1e4, 1e6, MAX_EXPONENT] {
        let b = phong(0.0, 1.0, n);
        // The n = 1 lobe reaches below the horizon unless wo = +Z.
        let wo = if n < 10.0 { V::Z } else { dir_xz(0.5) };
        let r = [-(wo.x as f64), -(wo.y as f64), wo.z as f64];
        let mut deltas = std::vec::Vec::with_capacity(m);
        for i in 0..m {
            let u = [(i as f32 + 0.5) / m as f32, 0.37];
            let s = b.sample(wo, u).unwrap();
            let w = [s.wi.x as f64, s.wi.y as f64, s.wi.z as f64];
            let l = libm::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
            let d2: f64 = (0..3).map(|k| (w[k] / l - r[k]) * (w[k] / l - r[k])).sum();
            deltas.push(0.5 * d2);
        }
        let d = ks_distance_cos_power(&mut deltas, n as f64);
        std::eprintln!("phong lobe KS n={n}: D = {d:.2e}");
        assert!(d < 5e-4, "n={n}: D = {d}");
    }
}

/// kd = ks = 0: sample → None, pdf → 0 (documented).
#[test]
fn black_brdf_has_no_samples() {
    let b = phong(0.0, 0.0, 10.0);
    assert_eq!(b.pdf(V::Z, V::Z), 0.0);
    assert!(b.sample(V::Z, [0.5, 0.5]).is_none());
    assert_eq!(b.eval(V::Z, V::Z), 0.0);
}

/// Below-horizon lobe mass for a lobe around the mirror direction at
/// polar angle θo, by 1D f64 quadrature in α of
/// `(n+1) cos^n α sin α · acos(min(1, cot α cot θo))/π` (the fraction
/// of azimuths around ωr with z ≤ 0).
fn below_horizon_mass(n: f64, theta_o: f64) -> f64 {
    let m = 200_000;
    let h = core::f64::consts::FRAC_PI_2 / m as f64;
    let cot_o = libm::cos(theta_o) / libm::sin(theta_o);
    let mut sum = 0.0;
    for i in 0..m {
        let a = (i as f64 + 0.5) * h;
        let c = libm::cos(a) / libm::sin(a) * cot_o;
        let frac = if c >= 1.0 { 0.0 } else { libm::acos(c) / PI64 };
        sum += (n + 1.0) * libm::pow(libm::cos(a), n) * libm::sin(a) * frac * h;
    }
    sum
}

/// ∫_H pdf = 1 at normal incidence; elsewhere pd + ps (1 − below-horizon
/// lobe mass).
#[test]
fn pdf_integrates_to_expected_mass() {
    for &n in &[0.0f32, 1.0, 10.0, 1000.0] {
        for &(kd, ks) in &[(0.0f32, 1.0f32), (0.5, 0.5)] {
            let m = pdf_mass(&phong(kd, ks, n), V::Z, 4000, 16);
            std::eprintln!("phong pdf mass n={n} kd={kd} normal: err {:.2e}", m - 1.0);
            assert!((m - 1.0).abs() < 1e-4, "n={n} kd={kd}: {m}");
        }
    }
    for &n in &[1.0f32, 10.0, 100.0] {
        for &t in &[0.5f64, 1.0, 1.4] {
            let (kd, ks) = (0.3f32, 0.6f32);
            let pd = kd as f64 / (kd as f64 + ks as f64);
            let expect = pd + (1.0 - pd) * (1.0 - below_horizon_mass(n as f64, t));
            let m = pdf_mass(&phong(kd, ks, n), dir_xz(t), 1500, 512);
            std::eprintln!(
                "phong pdf mass n={n} θo={t}: {m:.6} expect {expect:.6} err {:.2e}",
                m - expect
            );
            assert!((m - expect).abs() < 2e-4, "n={n} θo={t}: {m} vs {expect}");
            assert!(m <= 1.0 + 1e-4);
        }
    }
}

/// E[weight] over stratified samples equals the quadrature albedo: the
/// sampler follows its pdf.
#[test]
fn sampling_is_unbiased() {
    for &(kd, ks, n, t) in &[
        (0.3f32, 0.6f32, 10.0f32, 0.8f64),
        (0.0, 1.0, 100.0, 1.2),
        (0.5, 0.5, 1.0, 0.0),
    ] {
        let b = phong(kd, ks, n);
        let wo = dir_xz(t);
        let reference = albedo(&b, wo, 0, 1500, 512);
        let mc = sampled_albedo(&b, wo, 1024);
        std::eprintln!(
            "phong MC albedo {kd} {ks} n={n} θo={t}: {mc:.6} vs {reference:.6} rel {:.2e}",
            mc / reference - 1.0
        );
        assert!(
            (mc - reference).abs() < 5e-3 * reference,
            "{kd} {ks} {n} {t}: {mc} vs {reference}"
        );
    }
}

/// Hard inputs: finite, non-negative, no panic.
#[test]
fn stability_hard_cases() {
    let b = phong(0.2, 0.8, MAX_EXPONENT);
    let cases = [
        (V::Z, -V::Z),
        (V::new(1.0, 0.0, 1e-7), V::new(-1.0, 0.0, 1e-7)),
        (V::new(1.0, 0.0, 1e-7), V::new(1.0, 0.0, 1e-7)),
        (V::new(1.0, 0.0, 0.0), V::new(-1.0, 0.0, 0.0)),
        (V::ZERO, V::Z),
        (V::new(3.0, 1.0, 2.0), V::new(-0.001, 0.0, 0.002)),
        (V::new(0.0, 0.0, 1e-30), V::Z),
    ];
    for &(wi, wo) in &cases {
        for bb in [b, phong(0.0, 1.0, 0.0), phong(0.5, 0.5, 1e6)] {
            for (x, y) in [(wi, wo), (wo, wi)] {
                let f = bb.eval(x, y);
                let p = bb.pdf(x, y);
                assert!(
                    f.is_finite() && f >= 0.0 && p.is_finite() && p >= 0.0,
                    "{x:?} {y:?} {f} {p}"
                );
                // Reciprocity is exact (symmetric formula).
                assert_eq!(bb.eval(x, y), bb.eval(y, x));
            }
        }
    }
    // Zero at and below the horizon.
    assert_eq!(b.eval(V::new(1.0, 0.0, 0.0), V::Z), 0.0);
    assert_eq!(b.eval(V::Z, V::new(0.6, 0.0, -0.8)), 0.0);
    assert!(b.sample(V::new(0.6, 0.0, -0.8), [0.5, 0.5]).is_none());
    // Non-unit input equals normalised input.
    let (wi, wo) = (dir_xz(-0.5), dir_xz(0.5));
    let b = phong(0.2, 0.8, 50.0);
    let (f1, f2) = (b.eval(wi, wo), b.eval(wi * 7.0, wo * 0.01));
    assert!((f1 - f2).abs() <= 1e-4 * f1, "{f1} {f2}");
    // Peak at n = 1e7 is finite and equals the closed form.
    let f = phong(0.0, 1.0, MAX_EXPONENT).eval(V::Z, V::Z) as f64;
    let e = (1e7 + 2.0) / (2.0 * PI64);
    assert!((f - e).abs() < 1e-6 * e);
}
