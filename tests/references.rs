//! Independent references (issue 2), each computed by the `f64` adaptive quadrature of
//! [`common::quad`] (written separately from the code under test) and compared with a closed form:
//!
//! * NDF normalisation `∫_{H+} D(m) cos θm dm = 1` (Walter et al. 2007, eq. 4) for GGX and Beckmann;
//! * the Smith weak white furnace `∫ G1(ωo, m) ⟨ωo·m⟩ D(m) dm = cos θo` (Heitz 2014, "Understanding the
//!   masking-shadowing function", eq. 20), with `G1(ωo, m) = G1(ωo) χ⁺(ωo·m)` for the Smith masking
//!   (the API's `g1(ωo)` times the Heaviside step);
//! * Lambertian directional albedo `= ρ` at every incidence;
//! * modified-Phong specular albedo `= 1` at normal incidence with `ks = 1` (Lafortune & Willems 1994:
//!   `∫ (n+2)/(2π) cos^n θ cos θ dω = 1`);
//! * GGX `α = 1`, `F = 1`, normal incidence: albedo `= 1 − ln 2`. Derivation (ours): at `α = 1`,
//!   `D(m) = 1/(π cos⁴θm (1 + tan²θm)²) = 1/π`, and `Λ(ω) = (√(1 + tan²θ) − 1)/2 = (1/cos θ − 1)/2`, so
//!   `G1(ω) = 2 cos θ / (1 + cos θ)`. At normal incidence `Λ(ωo) = 0`, so the height-correlated
//!   `1/(1 + Λi + Λo)` and the separable `G1(ωi) G1(ωo)` are the same, `G1(ωi)`. Then
//!   `ρ = ∫ D G2 /(4 cos θi cos θo) cos θi dωi = (1/4π) ∫ 2μ/(1+μ) dωi = ∫_0^1 2μ/(1+μ) dμ · (2π/4π)·…`
//!   `= ∫_0^1 μ/(1+μ) dμ · 2 · (1/2) = 1 − ln 2 ≈ 0.306853` — so the claimed value holds for BOTH G2
//!   variants (they differ only away from normal incidence).

use crate::common;

use common::plugins::{Dist, Fres, Kind, Params, Shadow, build, lobe_width};
use common::quad::{Adaptive, Integral, Tol, integrate_hemisphere, lobe_breaks};
use common::strategies::to_f32;
use radiometry::glam::{DVec3, Vec3};
use radiometry_brdfs::{Beckmann, Ggx, MicrofacetDistribution};
use std::f64::consts::{FRAC_PI_2, LN_2};

fn albedo(k: Kind, p: &Params, wo: Vec3, tol: Tol) -> Integral {
    let b = build(k, p).unwrap();
    let q = Adaptive::default();
    let pole = DVec3::new(-wo.x as f64, -wo.y as f64, wo.z as f64);
    integrate_hemisphere(&q, pole, &lobe_breaks(lobe_width(k, p)), tol, &mut |wi| {
        b.eval(to_f32(wi), wo) as f64 * wi.z
    })
}

fn ndf_norm<D: MicrofacetDistribution>(d: &D) -> Integral {
    let q = Adaptive::default();
    let tol = Tol {
        abs: 1e-7,
        rel: 1e-7,
        depth: 14,
    };
    integrate_hemisphere(&q, DVec3::Z, &lobe_breaks(d.alpha() as f64), tol, &mut |m| {
        d.d(to_f32(m)) as f64 * m.z
    })
}

const ALPHAS: [f32; 7] = [1e-4, 1e-3, 0.01, 0.05, 0.2, 0.6, 1.0];

#[test]
fn ndf_normalisation() {
    for &a in &ALPHAS {
        for (name, r) in [
            ("GGX", ndf_norm(&Ggx::new(a).unwrap())),
            ("Beckmann", ndf_norm(&Beckmann::new(a).unwrap())),
        ] {
            eprintln!("∫ D cos θm dm, {name} α={a}: {:.8} ± {:.1e}", r.value, r.err);
            // 1e-5: the f32 evaluation of D (a few ulps per factor) and the f32 rounding of m. The
            // reference must have converged to within that slack first (so the total is ≤ 2e-5).
            let r = r.converged(1e-5, format!("{name} α={a}"));
            assert!((r.value - 1.0).abs() <= r.err + 1e-5, "{name} α={a}: {r:?}");
        }
    }
}

fn weak_furnace<D: MicrofacetDistribution>(d: &D, wo: Vec3) -> Integral {
    let q = Adaptive::default();
    let tol = Tol {
        abs: 1e-7,
        rel: 1e-7,
        depth: 14,
    };
    let g1 = d.g1(wo) as f64;
    let wo64 = DVec3::new(wo.x as f64, wo.y as f64, wo.z as f64);
    // Pole at ωo: the kink of ⟨ωo·m⟩ is the ring θ' = π/2; the lobe of D (around the normal) is
    // resolved by the graded breakpoints of the horizon and of the lobe.
    let mut breaks = vec![FRAC_PI_2];
    breaks.extend(lobe_breaks(d.alpha() as f64));
    breaks.sort_by(|a, b| a.partial_cmp(b).unwrap());
    let r = integrate_hemisphere(&q, wo64, &breaks, tol, &mut |m| {
        let c = m.dot(wo64);
        if c > 0.0 { d.d(to_f32(m)) as f64 * c } else { 0.0 }
    });
    Integral {
        value: g1 * r.value,
        err: g1 * r.err,
        evals: r.evals,
    }
}

#[test]
fn smith_weak_white_furnace() {
    for &a in &[0.05f32, 0.2, 0.6, 1.0] {
        for &deg in &[0.0f32, 30.0, 60.0, 80.0, 89.0] {
            let t = deg.to_radians();
            let wo = Vec3::new(t.sin(), 0.0, t.cos());
            let ggx = weak_furnace(&Ggx::new(a).unwrap(), wo);
            let beck = weak_furnace(&Beckmann::new(a).unwrap(), wo);
            for (name, r) in [("GGX", ggx), ("Beckmann", beck)] {
                // Slack 1e-5 cos θo + 1e-7 (f32 evaluation); the reference's error may at most
                // double it.
                let r = r.converged(1e-5 * wo.z as f64 + 1e-7, format!("{name} α={a} θo={deg}°"));
                let rel = (r.value - wo.z as f64).abs() / wo.z as f64;
                eprintln!(
                    "weak furnace {name} α={a} θo={deg}°: {:.7} vs cos θo {:.7} (rel {rel:.1e}, err {:.1e})",
                    r.value, wo.z, r.err
                );
                assert!(
                    (r.value - wo.z as f64).abs() <= r.err + 1e-5 * wo.z as f64 + 1e-7,
                    "{name} α={a} θo={deg}°: {r:?} vs {}",
                    wo.z
                );
            }
        }
    }
}

fn tol() -> Tol {
    Tol {
        abs: 1e-7,
        rel: 1e-7,
        depth: 14,
    }
}

#[test]
fn lambertian_albedo_is_rho() {
    for &rho in &[0.0f32, 0.3, 1.0] {
        for &deg in &[0.0f32, 45.0, 89.9] {
            let t = deg.to_radians();
            let wo = Vec3::new(t.sin(), 0.0, t.cos());
            let p = Params {
                rho,
                ..Params::typical()
            };
            let r = albedo(Kind::Lambertian, &p, wo, tol()).converged(1e-6, format!("ρ={rho} θo={deg}"));
            assert!(
                (r.value - rho as f64).abs() <= r.err + 1e-6,
                "ρ={rho} θo={deg}: {r:?}"
            );
        }
    }
}

#[test]
fn modified_phong_specular_albedo_is_one_at_normal_incidence() {
    for &n in &[0.0f32, 1.0, 10.0, 100.0, 1e3, 1e4, 1e5] {
        let p = Params {
            kd: 0.0,
            ks: 1.0,
            n,
            ..Params::typical()
        };
        let r = albedo(Kind::ModifiedPhong, &p, Vec3::Z, tol());
        eprintln!("modified Phong ks=1 n={n}: albedo {:.8} ± {:.1e}", r.value, r.err);
        let r = r.converged(1e-5, format!("n={n}"));
        assert!((r.value - 1.0).abs() <= r.err + 1e-5, "n={n}: {r:?}");
    }
}

#[test]
fn ggx_alpha_one_albedo_at_normal_incidence_is_one_minus_ln2() {
    let exact = 1.0 - LN_2;
    let p = Params {
        alpha: 1.0,
        ..Params::typical()
    };
    for g in [Shadow::HeightCorrelated, Shadow::Separable] {
        let r = albedo(Kind::Micro(Dist::Ggx, g, Fres::None), &p, Vec3::Z, tol());
        eprintln!(
            "GGX α=1 {g:?} normal incidence: {:.8} ± {:.1e} vs 1 − ln 2 = {exact:.8}",
            r.value, r.err
        );
        let r = r.converged(1e-6, format!("{g:?}"));
        assert!((r.value - exact).abs() <= r.err + 1e-6, "{g:?}: {r:?} vs {exact}");
    }
    // Sanity of the quadrature on the same integrand written here in f64: (1/4π) ∫ 2μ/(1+μ) dω.
    let q = Adaptive::default();
    let r = integrate_hemisphere(&q, DVec3::Z, &[], tol(), &mut |w| {
        2.0 * w.z / (1.0 + w.z) / (4.0 * std::f64::consts::PI)
    });
    assert!((r.value - exact).abs() < 1e-9, "{r:?}");
}
