//! Stability suite (issue 2): one named test per hard case. Each checks every plugin configuration
//! (28) under several parameter sets (typical, sharpest, roughest, extreme Fresnel): `eval`, `pdf`,
//! `eval_isotropic` and `sample` (weight, pdf, direction) are finite and non-negative, `sample`'s pdf is
//! `> 0`, and nothing panics. Invalid parameters are rejected at construction with a typed error whose
//! `Display` names the parameter.

use crate::common;

use common::plugins::{Dyn, Kind, Params, all_kinds, build};
use radiometry::glam::Vec3;
use radiometry_brdfs::{
    Beckmann, BlinnPhong, Conductor, Dielectric, Eon, Fon, Ggx, Lambertian, ModifiedPhong, OrenNayar, Schlick,
};
use std::f32::consts::{FRAC_PI_2, PI};

const ONE_MINUS_EPS: f32 = 0.99999994;

fn param_sets() -> Vec<Params> {
    let t = Params::typical();
    vec![
        t,
        Params {
            alpha: 1e-4,
            n: 1e7,
            kd: 0.0,
            ks: 1.0,
            rho: 1.0,
            sigma: 0.0,
            ..t
        },
        Params {
            alpha: 1.0,
            n: 0.0,
            kd: 1.0,
            ks: 0.0,
            rho: 0.0,
            sigma: 1.0,
            ..t
        },
        Params {
            f0: 1.0,
            eta_d: 1e-3,
            eta_c: 1e3,
            k_c: 1e3,
            alpha: 1e-3,
            n: 1e4,
            rho: 1.0,
            sigma: 1.0,
            ..t
        },
        Params {
            f0: 0.0,
            eta_d: 1e3,
            eta_c: 1e-3,
            k_c: 0.0,
            ..t
        },
    ]
}

const US: [[f32; 2]; 7] = [
    [0.0, 0.0],
    [ONE_MINUS_EPS, ONE_MINUS_EPS],
    [0.0, ONE_MINUS_EPS],
    [ONE_MINUS_EPS, 0.0],
    [0.5, 0.5],
    [1e-7, 0.5],
    [0.5, 1e-7],
];

fn check_eval(k: Kind, p: &Params, b: &Dyn, wi: Vec3, wo: Vec3) {
    let f = b.eval(wi, wo);
    assert!(
        f.is_finite() && f >= 0.0,
        "{k:?} {p:?} eval({wi:?}, {wo:?}) = {f}"
    );
    let pdf = b.pdf(wi, wo);
    assert!(
        pdf.is_finite() && pdf >= 0.0,
        "{k:?} {p:?} pdf({wi:?}, {wo:?}) = {pdf}"
    );
}

fn check_sample(k: Kind, p: &Params, b: &Dyn, wo: Vec3, u: [f32; 2]) {
    if let Some(s) = b.sample(wo, u) {
        let ctx = format!("{k:?} {p:?} sample({wo:?}, {u:?}) = {s:?}");
        assert!(s.wi.is_finite(), "{ctx}");
        assert!(s.pdf.is_finite() && s.pdf > 0.0, "{ctx}");
        assert!(s.weight.is_finite() && s.weight >= 0.0, "{ctx}");
        check_eval(k, p, b, s.wi, wo);
    }
}

/// Every configuration, every parameter set: eval/pdf at each pair, sample at each `wo` for every `u`.
fn check_all(pairs: &[(Vec3, Vec3)], us: &[[f32; 2]]) {
    for p in param_sets() {
        for k in all_kinds() {
            let b = build(k, &p).unwrap();
            for &(wi, wo) in pairs {
                check_eval(k, &p, &b, wi, wo);
                check_eval(k, &p, &b, wo, wi);
                for &u in us {
                    check_sample(k, &p, &b, wo, u);
                    check_sample(k, &p, &b, wi, u);
                }
            }
        }
    }
}

fn graze(c: f32, phi: f32) -> Vec3 {
    let s = (1.0 - (c as f64) * (c as f64)).sqrt() as f32;
    Vec3::new(s * phi.cos(), s * phi.sin(), c)
}

fn mirror(w: Vec3) -> Vec3 {
    Vec3::new(-w.x, -w.y, w.z)
}

#[test]
fn grazing_cos_1e_minus_7() {
    let wo = graze(1e-7, 0.3);
    let pairs = [
        (Vec3::Z, wo),
        (mirror(wo), wo),
        (graze(1e-7, 2.0), wo),
        (graze(0.5, 1.0), wo),
        (graze(1e-7, 0.3 + PI), wo),
    ];
    check_all(&pairs, &US);
}

#[test]
fn grazing_exactly_zero() {
    let wo = Vec3::new(1.0, 0.0, 0.0);
    let pairs = [
        (Vec3::Z, wo),
        (mirror(wo), wo),
        (Vec3::new(0.0, 1.0, 0.0), wo),
        (graze(0.5, 1.0), wo),
        (graze(1e-7, 0.0), wo),
    ];
    check_all(&pairs, &US);
}

fn one_param_set_all_kinds(p: Params, pairs: &[(Vec3, Vec3)]) {
    for k in all_kinds() {
        let b = build(k, &p).unwrap();
        for &(wi, wo) in pairs {
            check_eval(k, &p, &b, wi, wo);
            for &u in &US {
                check_sample(k, &p, &b, wo, u);
            }
        }
        // The 3-parameter form at the edges of its domain.
        for &(ti, to, dphi) in &[
            (0.0f32, 0.0f32, 0.0f32),
            (FRAC_PI_2, FRAC_PI_2, PI),
            (0.3, 0.3, PI),
            (FRAC_PI_2, 0.0, 0.0),
        ] {
            let f = b.eval_isotropic(ti, to, dphi);
            assert!(
                f.is_finite() && f >= 0.0,
                "{k:?} {p:?} eval_isotropic({ti}, {to}, {dphi}) = {f}"
            );
        }
    }
}

fn generic_pairs() -> Vec<(Vec3, Vec3)> {
    let mut v = Vec::new();
    for &c in &[1.0f32, 0.7, 0.1, 1e-4, 1e-7] {
        let wo = graze(c, 0.7);
        v.push((mirror(wo), wo));
        v.push((wo, wo));
        v.push((Vec3::Z, wo));
        v.push((graze(0.3, 2.5), wo));
    }
    v
}

#[test]
fn alpha_1e_minus_4() {
    let p = Params {
        alpha: 1e-4,
        ..Params::typical()
    };
    one_param_set_all_kinds(p, &generic_pairs());
}

#[test]
fn alpha_1() {
    let p = Params {
        alpha: 1.0,
        ..Params::typical()
    };
    one_param_set_all_kinds(p, &generic_pairs());
}

#[test]
fn wi_equals_minus_wo() {
    let mut pairs = Vec::new();
    for &c in &[1.0f32, 0.5, 1e-4, 1e-7, 0.0] {
        let wo = graze(c, 0.4);
        pairs.push((-wo, wo));
        // Both just above the horizon, opposite azimuths: ωi + ωo ≈ 0 (half vector nearly undefined).
        pairs.push((Vec3::new(-wo.x, -wo.y, wo.z), wo));
    }
    check_all(&pairs, &US);
    // eval is zero when one direction is below the horizon.
    for p in param_sets() {
        for k in all_kinds() {
            let b = build(k, &p).unwrap();
            let wo = graze(0.5, 0.4);
            assert_eq!(b.eval(-wo, wo), 0.0, "{k:?} {p:?}");
        }
    }
}

#[test]
fn wi_equals_wo_at_grazing() {
    let mut pairs = Vec::new();
    for &c in &[1e-4f32, 1e-7, 0.0] {
        let w = graze(c, 1.1);
        pairs.push((w, w));
    }
    check_all(&pairs, &US);
}

#[test]
fn phong_exponent_1e6() {
    for &(kd, ks) in &[(0.0f32, 1.0f32), (0.5, 0.5)] {
        let p = Params {
            n: 1e6,
            kd,
            ks,
            ..Params::typical()
        };
        one_param_set_all_kinds(p, &generic_pairs());
    }
}

#[test]
fn sample_u_zero() {
    let wos: Vec<Vec3> = [1.0f32, 0.5, 1e-4, 1e-7, 0.0]
        .iter()
        .map(|&c| graze(c, 0.2))
        .collect();
    let pairs: Vec<_> = wos.iter().map(|&w| (w, w)).collect();
    check_all(&pairs, &[[0.0, 0.0], [0.0, 0.5], [0.5, 0.0]]);
}

#[test]
fn sample_u_one_minus_epsilon() {
    let wos: Vec<Vec3> = [1.0f32, 0.5, 1e-4, 1e-7, 0.0]
        .iter()
        .map(|&c| graze(c, 0.2))
        .collect();
    let pairs: Vec<_> = wos.iter().map(|&w| (w, w)).collect();
    check_all(
        &pairs,
        &[
            [ONE_MINUS_EPS, ONE_MINUS_EPS],
            [ONE_MINUS_EPS, 0.5],
            [0.5, ONE_MINUS_EPS],
            [ONE_MINUS_EPS, 0.0],
        ],
    );
}

#[test]
fn below_horizon_directions() {
    let up = graze(0.5, 0.3);
    let down = Vec3::new(0.3, 0.2, -0.93).normalize();
    let pairs = [
        (down, up),
        (up, down),
        (down, down),
        (-Vec3::Z, -Vec3::Z),
        (graze(-1e-7, 1.0), up),
    ];
    check_all(&pairs, &US);
    for p in param_sets() {
        for k in all_kinds() {
            let b = build(k, &p).unwrap();
            for &(wi, wo) in &pairs {
                assert_eq!(b.eval(wi, wo), 0.0, "{k:?} {p:?} eval({wi:?}, {wo:?}) must be 0");
            }
            for &u in &US {
                assert!(
                    b.sample(down, u).is_none(),
                    "{k:?} {p:?}: sample with ωo below the horizon"
                );
            }
        }
    }
}

#[test]
fn not_quite_unit_vectors() {
    let mut pairs = Vec::new();
    for &s in &[0.999f32, 1.001, 1.0 - 1e-6, 1.0 + 1e-6, 0.5, 2.0] {
        for &c in &[1.0f32, 0.6, 1e-4] {
            let wo = graze(c, 0.9);
            pairs.push((mirror(wo) * s, wo));
            pairs.push((graze(0.4, 2.0), wo * s));
            pairs.push((wo * s, wo * (2.0 - s)));
        }
    }
    check_all(&pairs, &US);
    // Tiny and zero vectors too.
    check_all(
        &[
            (Vec3::ZERO, Vec3::Z),
            (Vec3::Z, Vec3::ZERO),
            (Vec3::splat(1e-30), Vec3::Z),
        ],
        &US,
    );
}

#[test]
fn invalid_parameters_rejected() {
    let nan = f32::NAN;
    let inf = f32::INFINITY;
    let mut errs = Vec::new();
    for v in [nan, inf, -inf, -0.1, 1.1] {
        errs.push(Lambertian::new(v).err());
    }
    for (kd, ks, n) in [
        (nan, 0.5, 1.0),
        (0.5, nan, 1.0),
        (0.5, 0.5, nan),
        (-0.1, 0.5, 1.0),
        (0.5, -0.1, 1.0),
        (0.5, 0.5, -1.0),
        (0.6, 0.5, 1.0),
        (0.5, 0.5, 2e7),
        (0.5, 0.5, inf),
    ] {
        errs.push(ModifiedPhong::new(kd, ks, n).err());
        errs.push(BlinnPhong::new(kd, ks, n).err());
    }
    for a in [nan, inf, 0.0, -0.1, 5e-5, 1.0001] {
        errs.push(Ggx::new(a).err());
        errs.push(Beckmann::new(a).err());
    }
    for f0 in [nan, -0.1, 1.1] {
        errs.push(Schlick::new(f0).err());
    }
    for eta in [nan, inf, 0.0, -1.5] {
        errs.push(Dielectric::new(eta).err());
        errs.push(Conductor::new(eta, 1.0).err());
    }
    for k in [nan, inf, -1.0] {
        errs.push(Conductor::new(1.0, k).err());
    }
    for (rho, sigma) in [
        (nan, 0.5),
        (0.5, nan),
        (-0.1, 0.5),
        (1.1, 0.5),
        (0.5, -0.1),
        (0.5, 1.1),
        (0.5, inf),
    ] {
        errs.push(Fon::new(rho, sigma).err());
        errs.push(Eon::new(rho, sigma).err());
        // The classic model takes radians: [0, π/2].
        errs.push(OrenNayar::new(rho, if sigma == 1.1 { 1.6 } else { sigma }).err());
    }
    // The classic model gains energy at small σ with ρ = 1: rejected (typed).
    errs.push(OrenNayar::new(1.0f32, 0.2).err());
    for (i, e) in errs.iter().enumerate() {
        let e = e
            .as_ref()
            .unwrap_or_else(|| panic!("invalid parameter set #{i} was accepted"));
        let msg = e.to_string();
        assert!(!msg.is_empty(), "#{i}: empty Display");
    }
    // The edges of the valid ranges are accepted.
    assert!(Lambertian::new(0.0f32).is_ok() && Lambertian::new(1.0f32).is_ok());
    assert!(ModifiedPhong::new(0.0f32, 1.0, 1e7).is_ok() && BlinnPhong::new(1.0f32, 0.0, 0.0).is_ok());
    assert!(Ggx::new(1e-4).is_ok() && Ggx::new(1.0).is_ok() && Beckmann::new(1e-4).is_ok());
    assert!(Schlick::new(0.0f32).is_ok() && Conductor::new(0.2f32, 0.0).is_ok());
    assert!(Fon::new(1.0f32, 0.0).is_ok() && Eon::new(0.0f32, 1.0).is_ok() && Eon::new(1.0f32, 1.0).is_ok());
    assert!(OrenNayar::new(1.0f32, 0.0).is_ok() && OrenNayar::new(1.0f32, FRAC_PI_2).is_ok());
}

/// Composites whose lobes each report a value near `f32::MAX` (subnormal
/// cosines, where `1/(μi μo)` overflows and EON's `s/t` grows without
/// bound) saturate at `f32::MAX` instead of summing to infinity, in `eval`
/// and in both batch paths (found by the `brdf_eval` fuzz target).
#[test]
fn composites_saturate_where_their_lobes_overflow() {
    use radiometry::Brdf;
    use radiometry::batch::Vec3Soa;
    use radiometry::compose::{Coated, Mix, Sum};
    use radiometry_brdfs::{HeightCorrelated, Microfacet};
    let wi = Vec3::new(0.25, 0.25, 3.57e-43);
    let wo = Vec3::new(0.25, 1.5046327e-36, 8.4e-44);
    let top =
        Microfacet::<_, HeightCorrelated, _>::new(Ggx::new(0.49999).unwrap(), Dielectric::new(0.25).unwrap());
    let base = Eon::new(0.25f32, 0.25).unwrap();
    // The lobes' own values are finite and huge: their sum is not.
    let (ft, fb) = (top.eval(wi, wo), base.eval(wi, wo));
    assert!(
        ft.is_finite() && fb.is_finite() && ft > 1e36 && fb > 1e35,
        "{ft} {fb}"
    );
    let check =
        |name: &str, b: &dyn Fn(Vec3, Vec3) -> f32, batch: &dyn Fn(&mut [f32]), soa: &dyn Fn(&mut [f32])| {
            let v = b(wi, wo);
            assert!(v.is_finite() && v >= 0.0, "{name}: {v}");
            let (mut a, mut s) = ([0.0f32; 3], [0.0f32; 3]);
            batch(&mut a);
            soa(&mut s);
            assert!(
                a.iter().chain(&s).all(|x| x.to_bits() == v.to_bits()),
                "{name}: {v} vs {a:?} {s:?}"
            );
        };
    let (wis, wos) = ([wi; 3], [wo; 3]);
    let (xi, yi, zi) = (wis.map(|w| w.x), wis.map(|w| w.y), wis.map(|w| w.z));
    let (xo, yo, zo) = (wos.map(|w| w.x), wos.map(|w| w.y), wos.map(|w| w.z));
    let soa_i = || Vec3Soa::new(&xi, &yi, &zi);
    let soa_o = || Vec3Soa::new(&xo, &yo, &zo);
    let coated = Coated::new(top, base);
    check(
        "coated",
        &|i, o| coated.eval(i, o),
        &|out| coated.eval_batch(&wis, &wos, out),
        &|out| coated.eval_batch_soa(soa_i(), soa_o(), out),
    );
    let sum = Sum::new(top, base);
    check(
        "sum",
        &|i, o| sum.eval(i, o),
        &|out| sum.eval_batch(&wis, &wos, out),
        &|out| sum.eval_batch_soa(soa_i(), soa_o(), out),
    );
    let mix = Mix::new(0.5, top, base).unwrap();
    check(
        "mix",
        &|i, o| mix.eval(i, o),
        &|out| mix.eval_batch(&wis, &wos, out),
        &|out| mix.eval_batch_soa(soa_i(), soa_o(), out),
    );
}
