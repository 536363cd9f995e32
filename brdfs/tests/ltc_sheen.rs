//! The LTC sheen ([`LtcSheen`], Zeltner, Burley & Chiang 2022) against independent references:
//!
//! * `albedo_matches_quadrature`: the closed-form albedo `C R` against an `f64` composite
//!   Gauss–Legendre quadrature of `eval · cos θi` over `(cos θi, φ)` at `(μo, r)` off the table's
//!   nodes, within the error it states;
//! * `pdf_integrates_to_one`: the same quadrature of `pdf` (1 where the table has a lobe, 0 where not);
//! * `sample_pdf_is_bit_exact`: `pdf(sample.wi, wo) == sample.pdf` bit for bit over random `u` and
//!   `wo`, samples unit and above the horizon, `weight = f cos θi / pdf`;
//! * `sampler_chi_square`: Pearson's χ² of the sampler's histogram over `(cos θi, φ)` cells against the
//!   quadrature of `pdf` over each cell;
//! * `albedo_at_most_one`: `E + error ≤ 1` and `albedo_untinted` = the colour-1 albedo, over a sweep;
//! * `stable_on_hard_cases`: grazing, normal, degenerate and non-unit directions, `u` at the ends,
//!   roughness at the ends and at the edge of the table's empty rows;
//! * `matches_adobe_openpbr_bsdf`: `f cos θi`, `pdf` and `R` against Adobe's OpenPBR BSDF.

use super::kulla_conty::{gauss_legendre, refine_panels};
use core::f64::consts::PI;
use radiometry::glam::Vec3;
use radiometry::math::ONE_MINUS_EPSILON;
use radiometry::rng::Pcg32;
use radiometry::{Brdf, IsotropicBrdf};
use radiometry_brdfs::LtcSheen;

/// `∫_H g(ωi) dωi` for `ωo` at azimuth 0 (the lobe is even in `φi`): `2 ∫₀^π dφ ∫₀¹ dμi g`, `μi` in
/// pieces graded towards the horizon (cuts at `4⁻ⁱ`, `i = 1..10`: for small `a` the lobe lies within
/// `∼ a` of it), `φ` in two pieces, each piece `panels` panels of 12-point Gauss–Legendre.
fn hemisphere(panels: usize, g: &mut dyn FnMut(Vec3) -> f64) -> f64 {
    let gl = gauss_legendre(12);
    let mut mu_cuts: Vec<f64> = (1..=10).map(|i| 4f64.powi(-i)).collect();
    mu_cuts.extend([0.0, 1.0]);
    mu_cuts.sort_by(f64::total_cmp);
    let phi_cuts = [0.0, PI / 2.0, PI];
    let mut s = 0.0;
    for m in mu_cuts.windows(2) {
        let hm = (m[1] - m[0]) / panels as f64;
        for pm in 0..panels {
            for &(xm, wm) in &gl {
                let mu = m[0] + (pm as f64 + xm) * hm;
                let st = (1.0 - mu * mu).max(0.0).sqrt();
                for p in phi_cuts.windows(2) {
                    let hp = (p[1] - p[0]) / panels as f64;
                    for pp in 0..panels {
                        for &(xp, wp) in &gl {
                            let phi = p[0] + (pp as f64 + xp) * hp;
                            let wi = Vec3::new((st * phi.cos()) as f32, (st * phi.sin()) as f32, mu as f32);
                            s += wm * hm * wp * hp * g(wi);
                        }
                    }
                }
            }
        }
    }
    2.0 * s
}

fn wo_at(mu: f64) -> Vec3 {
    Vec3::new((1.0 - mu * mu).max(0.0).sqrt() as f32, 0.0, mu as f32)
}

/// Off-node `(μo, r)`: the table's nodes are `j/31`, `k/31`.
const MUS: [f64; 6] = [0.013, 0.1, 0.37, 0.71, 0.96, 0.999];
const RS: [f32; 6] = [0.11, 0.2, 0.3, 0.55, 0.83, 0.98];

#[test]
fn albedo_matches_quadrature() {
    let (mut worst, mut at) = (0.0f64, (0.0, 0.0));
    for &r in &RS {
        let s = LtcSheen::new(1.0f32, r).unwrap();
        for &mu in &MUS {
            let wo = wo_at(mu);
            let (q, qerr) = refine_panels(4, 1e-8, |panels| {
                hemisphere(panels, &mut |wi| s.eval(wi, wo) as f64 * wi.z as f64)
            });
            assert!(
                qerr < 1e-7,
                "quadrature not converged at μo = {mu}, r = {r}: {qerr:e}"
            );
            let e = s.directional_albedo(wo);
            let d = (e.value as f64 - q).abs();
            assert!(
                e.is_bound && d <= e.error as f64 + qerr,
                "μo = {mu}, r = {r}: C·R = {} vs quadrature {q} (± {qerr:e}), stated error {:e}",
                e.value,
                e.error
            );
            if d > worst * q.max(1e-30) {
                (worst, at) = (d / q.max(1e-30), (mu, r));
            }
        }
    }
    println!(
        "LTC sheen albedo vs f64 quadrature of eval: worst relative difference {worst:.2e} at (μo, r) = {at:?}"
    );
}

#[test]
fn pdf_integrates_to_one() {
    for &r in &RS {
        let s = LtcSheen::new(1.0f32, r).unwrap();
        for &mu in &MUS[..4] {
            let wo = wo_at(mu);
            let (q, _) = refine_panels(2, 1e-8, |panels| {
                hemisphere(panels, &mut |wi| s.pdf(wi, wo) as f64)
            });
            let want = if s.coefficients(mu as f32).a > 0.0 {
                1.0
            } else {
                0.0
            };
            assert!((q - want).abs() < 1e-5, "μo = {mu}, r = {r}: ∫ pdf = {q}");
        }
    }
    // No lobe (roughness 0 away from grazing): the pdf is 0 everywhere and there is no sample.
    let s = LtcSheen::new(1.0f32, 0.0).unwrap();
    let wo = wo_at(0.5);
    assert_eq!(hemisphere(1, &mut |wi| s.pdf(wi, wo) as f64), 0.0);
    assert!(s.sample(wo, [0.3, 0.3]).is_none());
}

#[test]
fn sample_pdf_is_bit_exact() {
    let mut rng = Pcg32::new(0x17C5);
    let (mut n, mut worst_w) = (0usize, 0.0f32);
    for &r in &[0.0f32, 0.05, 0.13, 0.4, 0.77, 1.0] {
        let s = LtcSheen::new(Vec3::new(1.0, 0.5, 0.25), r).unwrap();
        for k in 0..2000 {
            let mu = match k % 5 {
                0 => 1e-3 * rng.next_f32(),
                _ => rng.next_f32(),
            };
            let sin = (1.0 - mu * mu).max(0.0).sqrt();
            let p = core::f32::consts::TAU * rng.next_f32();
            let wo = Vec3::new(sin * p.cos(), sin * p.sin(), mu);
            for _ in 0..10 {
                let u = [rng.next_f32(), rng.next_f32()];
                let Some(smp) = s.sample(wo, u) else { continue };
                n += 1;
                assert_eq!(
                    smp.pdf.to_bits(),
                    s.pdf(smp.wi, wo).to_bits(),
                    "r = {r}, wo = {wo}, u = {u:?}"
                );
                assert!(smp.pdf > 0.0 && smp.pdf.is_finite() && smp.wi.z > 0.0);
                assert!((smp.wi.length() - 1.0).abs() < 1e-6);
                let f = s.eval(smp.wi, wo);
                let w = f * smp.wi.z / smp.pdf;
                let rel = ((w - smp.weight).abs() / smp.weight.max(Vec3::splat(1e-30))).max_element();
                worst_w = worst_w.max(rel);
                assert!(rel < 1e-4, "weight {} vs f cos/pdf {w}", smp.weight);
            }
        }
    }
    assert!(n > 80_000, "{n} samples");
    println!("LTC sheen: {n} samples, pdf bit-exact, worst |weight − f cos/pdf|/weight {worst_w:.1e}");
}

/// Wilson–Hilferty: the standard normal deviate of a χ² statistic with `k` degrees of freedom.
fn chi2_z(chi2: f64, k: f64) -> f64 {
    let v = 2.0 / (9.0 * k);
    ((chi2 / k).cbrt() - (1.0 - v)) / v.sqrt()
}

#[test]
fn sampler_chi_square() {
    const N_MU: usize = 16;
    const N_PHI: usize = 16;
    const SAMPLES: usize = 200_000;
    let gl = gauss_legendre(6);
    // μ bins graded towards the horizon: edges (i/16)².
    let edge = |i: usize| (i as f64 / N_MU as f64).powi(2);
    for (case, &(r, mu, phi_o)) in [
        (0.2f32, 0.3f64, 0.4f64),
        (0.5, 0.05, 2.0),
        (0.9, 0.9, -1.0),
        (0.13, 0.01, 0.0),
    ]
    .iter()
    .enumerate()
    {
        let s = LtcSheen::new(1.0f32, r).unwrap();
        let st = (1.0 - mu * mu).sqrt();
        let wo = Vec3::new((st * phi_o.cos()) as f32, (st * phi_o.sin()) as f32, mu as f32);
        let mut counts = [[0u32; N_PHI]; N_MU];
        let mut rng = Pcg32::new(0xC41 + case as u64);
        let mut none = 0usize;
        for _ in 0..SAMPLES {
            let Some(smp) = s.sample(wo, [rng.next_f32(), rng.next_f32()]) else {
                none += 1;
                continue;
            };
            let z = smp.wi.z as f64;
            let i = (0..N_MU).rfind(|&i| z >= edge(i)).unwrap_or(0).min(N_MU - 1);
            let phi = (smp.wi.y as f64).atan2(smp.wi.x as f64).rem_euclid(2.0 * PI);
            let j = ((phi / (2.0 * PI) * N_PHI as f64) as usize).min(N_PHI - 1);
            counts[i][j] += 1;
        }
        assert!(none <= 2, "{none} samples missing");
        // Expected counts: the pdf integrated over each cell (6 × 6 Gauss–Legendre).
        let (mut chi2, mut cells, mut pooled_o, mut pooled_e) = (0.0, 0usize, 0.0, 0.0);
        for (i, row) in counts.iter().enumerate() {
            for (j, &count) in row.iter().enumerate() {
                let (m0, m1) = (edge(i), edge(i + 1));
                let (p0, p1) = (
                    2.0 * PI * j as f64 / N_PHI as f64,
                    2.0 * PI * (j + 1) as f64 / N_PHI as f64,
                );
                let mut e = 0.0;
                for &(xm, wm) in &gl {
                    let m = m0 + xm * (m1 - m0);
                    let sm = (1.0 - m * m).sqrt();
                    for &(xp, wp) in &gl {
                        let p = p0 + xp * (p1 - p0);
                        let wi = Vec3::new((sm * p.cos()) as f32, (sm * p.sin()) as f32, m as f32);
                        e += wm * wp * s.pdf(wi, wo) as f64;
                    }
                }
                let e = e * (m1 - m0) * (p1 - p0) * SAMPLES as f64;
                if e < 5.0 {
                    pooled_o += count as f64;
                    pooled_e += e;
                } else {
                    chi2 += (count as f64 - e).powi(2) / e;
                    cells += 1;
                }
            }
        }
        if pooled_e > 0.0 {
            chi2 += (pooled_o - pooled_e).powi(2) / pooled_e.max(1.0);
            cells += 1;
        }
        let z = chi2_z(chi2, (cells - 1) as f64);
        println!("LTC sheen χ² (r = {r}, μo = {mu}): {chi2:.1} over {cells} cells, z = {z:.2}");
        assert!(
            z < 4.0,
            "r = {r}, μo = {mu}: χ² = {chi2} over {cells} cells (z = {z})"
        );
    }
}

#[test]
fn albedo_at_most_one() {
    let mut largest = 0.0f32;
    for k in 0..=100 {
        let r = k as f32 / 100.0;
        let s = LtcSheen::new(1.0f32, r).unwrap();
        for j in 0..=200 {
            let mu = j as f32 / 200.0;
            let wo = Vec3::new((1.0 - mu * mu).sqrt(), 0.0, mu);
            let e = s.directional_albedo(wo);
            assert!(e.value >= 0.0 && e.value + e.error <= 1.0);
            assert_eq!(e.value, s.albedo_untinted(mu), "r = {r}, μ = {mu}");
            largest = largest.max(e.value + e.error);
        }
    }
    println!("LTC sheen: largest E + error = {largest}");
    assert!(largest < 0.76);
}

#[test]
fn stable_on_hard_cases() {
    let e = ONE_MINUS_EPSILON;
    let dirs = [
        Vec3::Z,
        Vec3::new(1e-20, 1e-20, 1.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, 1e-7),
        Vec3::new(0.6, -0.8, 1e-30),
        Vec3::new(1.0, 0.0, -0.0),
        Vec3::new(0.0, 0.0, -1.0),
        Vec3::new(0.3, 0.2, 0.5) * 1e-25,
        Vec3::new(0.3, 0.2, 0.5) * 1e25,
        Vec3::new(f32::MAX, 0.0, f32::MAX),
        Vec3::ZERO,
        Vec3::new(0.6, 0.0, 0.8),
        Vec3::new(-0.6, 0.0, 0.8),
    ];
    let us = [
        [0.0, 0.0],
        [e, e],
        [0.5, 0.5],
        [e, 0.0],
        [0.0, e],
        [0.5, e],
        [1e-30, 0.5],
    ];
    let rs = [
        0.0f32,
        1e-30,
        1e-10,
        0.5 / 31.0,
        1.0 / 31.0 + 1e-9,
        4.0 / 31.0,
        0.5,
        e,
        1.0,
    ];
    for &r in &rs {
        let s = LtcSheen::new(Vec3::ONE, r).unwrap();
        for &wo in &dirs {
            let a = s.directional_albedo(wo);
            assert!(a.value.is_finite() && a.value.min_element() >= 0.0 && a.error.is_finite());
            assert!((0.0..=1.0).contains(&s.albedo_untinted(wo.z)));
            for &wi in &dirs.iter().copied().chain([-wo, wo]).collect::<Vec<_>>() {
                let f = s.eval(wi, wo);
                let p = s.pdf(wi, wo);
                assert!(
                    f.is_finite() && f.min_element() >= 0.0,
                    "r = {r}: eval({wi}, {wo}) = {f}"
                );
                assert!(p.is_finite() && p >= 0.0, "r = {r}: pdf({wi}, {wo}) = {p}");
            }
            for &u in &us {
                if let Some(smp) = s.sample(wo, u) {
                    assert!(smp.wi.is_finite() && smp.wi.z > 0.0 && smp.pdf > 0.0 && smp.pdf.is_finite());
                    assert!(smp.weight.is_finite() && smp.weight.min_element() >= 0.0);
                    assert_eq!(smp.pdf.to_bits(), s.pdf(smp.wi, wo).to_bits());
                }
            }
        }
        assert!(s.eval_isotropic(1.0, 1.2, 3.0).is_finite());
    }
    for mu in [f32::NAN, -1.0, 0.0, -0.0, 2.0, f32::INFINITY] {
        let v = LtcSheen::new(1.0f32, 0.5).unwrap().albedo_untinted(mu);
        assert!((0.0..=1.0).contains(&v), "{mu}: {v}");
    }
}

/// Adobe's OpenPBR BSDF (<https://github.com/adobe/openpbr-bsdf>, commit a29da96), fuzz lobe with
/// tint 1 and presence 1, printed by a small C++ program kept outside this repository:
///
/// ```text
/// g++ -std=c++17 -O1 -I/path/to/openpbr-bsdf check.cpp -o check && ./check
/// ```
///
/// where `check.cpp` includes `<glm/glm.hpp>` and `openpbr.h`, and for each roughness `r`, angles
/// `θi`, `θo` (degrees) and `Δφ = φo − φi` (degrees), with `φo = 0.7` rad, `ωo = (sin θo cos φo,
/// sin θo sin φo, cos θo)` and `ωi` likewise at `φi = φo − Δφ` (all in `f32`), prints
/// `openpbr_disney_sheen_f(lobe, ωo, ωi).x` (`f cos θi`), `openpbr_disney_sheen_pdf(lobe, ωo, ωi)`
/// and `openpbr_proportion_reflected(lobe, ωo)` (`R`).
/// Rows: `(r, θi, θo, Δφ, f cos θi, pdf, R)`.
/// Nine significant digits: each `f32` exactly as printed.
#[rustfmt::skip]
#[allow(clippy::excessive_precision)]
const ADOBE: [(f32, f32, f32, f32, f32, f32, f32); 144] = [
    (0.0, 10.0, 0.0, 0.0, 0.0, 0.0, 0.0),
    (0.0, 10.0, 0.0, 60.0, 0.0, 0.0, 0.0),
    (0.0, 10.0, 0.0, 180.0, 0.0, 0.0, 0.0),
    (0.0, 10.0, 30.0, 0.0, 0.0, 0.0, 0.0),
    (0.0, 10.0, 30.0, 60.0, 0.0, 0.0, 0.0),
    (0.0, 10.0, 30.0, 180.0, 0.0, 0.0, 0.0),
    (0.0, 10.0, 60.0, 0.0, 0.0, 0.0, 0.0),
    (0.0, 10.0, 60.0, 60.0, 0.0, 0.0, 0.0),
    (0.0, 10.0, 60.0, 180.0, 0.0, 0.0, 0.0),
    (0.0, 10.0, 89.5, 0.0, 2.59022997e-10, 3.55080629e-05, 7.29476551e-06),
    (0.0, 10.0, 89.5, 60.0, 2.59023386e-10, 3.55081174e-05, 7.29476551e-06),
    (0.0, 10.0, 89.5, 180.0, 2.59024607e-10, 3.55082848e-05, 7.29476551e-06),
    (0.0, 45.0, 0.0, 0.0, 0.0, 0.0, 0.0),
    (0.0, 45.0, 0.0, 60.0, 0.0, 0.0, 0.0),
    (0.0, 45.0, 0.0, 180.0, 0.0, 0.0, 0.0),
    (0.0, 45.0, 30.0, 0.0, 0.0, 0.0, 0.0),
    (0.0, 45.0, 30.0, 60.0, 0.0, 0.0, 0.0),
    (0.0, 45.0, 30.0, 180.0, 0.0, 0.0, 0.0),
    (0.0, 45.0, 60.0, 0.0, 0.0, 0.0, 0.0),
    (0.0, 45.0, 60.0, 60.0, 0.0, 0.0, 0.0),
    (0.0, 45.0, 60.0, 180.0, 0.0, 0.0, 0.0),
    (0.0, 45.0, 89.5, 0.0, 6.99586611e-10, 9.59025492e-05, 7.29476551e-06),
    (0.0, 45.0, 89.5, 60.0, 6.99592995e-10, 9.59034223e-05, 7.29476551e-06),
    (0.0, 45.0, 89.5, 180.0, 6.9961209e-10, 9.59060417e-05, 7.29476551e-06),
    (0.0, 89.0, 0.0, 0.0, 0.0, 0.0, 0.0),
    (0.0, 89.0, 0.0, 60.0, 0.0, 0.0, 0.0),
    (0.0, 89.0, 0.0, 180.0, 0.0, 0.0, 0.0),
    (0.0, 89.0, 30.0, 0.0, 0.0, 0.0, 0.0),
    (0.0, 89.0, 30.0, 60.0, 0.0, 0.0, 0.0),
    (0.0, 89.0, 30.0, 180.0, 0.0, 0.0, 0.0),
    (0.0, 89.0, 60.0, 0.0, 0.0, 0.0, 0.0),
    (0.0, 89.0, 60.0, 60.0, 0.0, 0.0, 0.0),
    (0.0, 89.0, 60.0, 180.0, 0.0, 0.0, 0.0),
    (0.0, 89.0, 89.5, 0.0, 2.55285395e-05, 3.49956965, 7.29476551e-06),
    (0.0, 89.0, 89.5, 60.0, 2.55383293e-05, 3.50091171, 7.29476551e-06),
    (0.0, 89.0, 89.5, 180.0, 2.55677351e-05, 3.50494266, 7.29476551e-06),
    (0.129999995, 10.0, 0.0, 0.0, 7.25857944e-07, 0.0704716668, 1.02999966e-05),
    (0.129999995, 10.0, 0.0, 60.0, 7.26014548e-07, 0.0704868734, 1.02999966e-05),
    (0.129999995, 10.0, 0.0, 180.0, 7.24496999e-07, 0.0703395382, 1.02999966e-05),
    (0.129999995, 10.0, 30.0, 0.0, 6.07881304e-07, 0.0570997298, 1.06459574e-05),
    (0.129999995, 10.0, 30.0, 60.0, 6.0553333e-07, 0.0568791777, 1.06459574e-05),
    (0.129999995, 10.0, 30.0, 180.0, 5.98570182e-07, 0.0562251173, 1.06459574e-05),
    (0.129999995, 10.0, 60.0, 0.0, 6.53853817e-07, 0.00703447219, 9.29499438e-05),
    (0.129999995, 10.0, 60.0, 60.0, 6.52989058e-07, 0.00702516921, 9.29499438e-05),
    (0.129999995, 10.0, 60.0, 180.0, 6.50405639e-07, 0.00699737528, 9.29499438e-05),
    (0.129999995, 10.0, 89.5, 0.0, 0.000374195108, 0.000645902182, 0.57933712),
    (0.129999995, 10.0, 89.5, 60.0, 0.000373691873, 0.00064503355, 0.57933712),
    (0.129999995, 10.0, 89.5, 180.0, 0.000372188224, 0.00064243807, 0.57933712),
    (0.129999995, 45.0, 0.0, 0.0, 1.35278344e-06, 0.131338239, 1.02999966e-05),
    (0.129999995, 45.0, 0.0, 60.0, 1.35415723e-06, 0.131471619, 1.02999966e-05),
    (0.129999995, 45.0, 0.0, 180.0, 1.34089726e-06, 0.130184248, 1.02999966e-05),
    (0.129999995, 45.0, 30.0, 0.0, 1.24546204e-06, 0.116989195, 1.06459574e-05),
    (0.129999995, 45.0, 30.0, 60.0, 1.22197002e-06, 0.114782535, 1.06459574e-05),
    (0.129999995, 45.0, 30.0, 180.0, 1.15534874e-06, 0.108524643, 1.06459574e-05),
    (0.129999995, 45.0, 60.0, 0.0, 1.71701618e-06, 0.0184724815, 9.29499438e-05),
    (0.129999995, 45.0, 60.0, 60.0, 1.70437852e-06, 0.0183365196, 9.29499438e-05),
    (0.129999995, 45.0, 60.0, 180.0, 1.66729217e-06, 0.017937528, 9.29499438e-05),
    (0.129999995, 45.0, 89.5, 0.0, 0.00101982837, 0.00176033657, 0.57933712),
    (0.129999995, 45.0, 89.5, 60.0, 0.00101205218, 0.001746914, 0.57933712),
    (0.129999995, 45.0, 89.5, 180.0, 0.000989250839, 0.00170755654, 0.57933712),
    (0.129999995, 89.0, 0.0, 0.0, 2.66793222e-07, 0.0259022638, 1.02999966e-05),
    (0.129999995, 89.0, 0.0, 60.0, 2.66819967e-07, 0.0259048603, 1.02999966e-05),
    (0.129999995, 89.0, 0.0, 180.0, 2.66560619e-07, 0.0258796792, 1.02999966e-05),
    (0.129999995, 89.0, 30.0, 0.0, 3.44216829e-07, 0.0323331021, 1.06459574e-05),
    (0.129999995, 89.0, 30.0, 60.0, 3.4344913e-07, 0.0322609916, 1.06459574e-05),
    (0.129999995, 89.0, 30.0, 180.0, 3.41160955e-07, 0.0320460573, 1.06459574e-05),
    (0.129999995, 89.0, 60.0, 0.0, 2.40800746e-05, 0.259064972, 9.29499438e-05),
    (0.129999995, 89.0, 60.0, 60.0, 2.39324982e-05, 0.257477283, 9.29499438e-05),
    (0.129999995, 89.0, 60.0, 180.0, 2.34978088e-05, 0.252800673, 9.29499438e-05),
    (0.129999995, 89.0, 89.5, 0.0, 1.38612711, 2.39260888, 0.57933712),
    (0.129999995, 89.0, 89.5, 60.0, 1.30300856, 2.24913692, 0.57933712),
    (0.129999995, 89.0, 89.5, 180.0, 1.09402835, 1.88841403, 0.57933712),
    (0.5, 10.0, 0.0, 0.0, 0.00196342706, 0.105305791, 0.0186450053),
    (0.5, 10.0, 0.0, 60.0, 0.00196341518, 0.10530515, 0.0186450053),
    (0.5, 10.0, 0.0, 180.0, 0.00196352811, 0.105311215, 0.0186450053),
    (0.5, 10.0, 30.0, 0.0, 0.00325872214, 0.0951711163, 0.0342406631),
    (0.5, 10.0, 30.0, 60.0, 0.00323629077, 0.0945160091, 0.0342406631),
    (0.5, 10.0, 30.0, 180.0, 0.00317037222, 0.0925908536, 0.0342406631),
    (0.5, 10.0, 60.0, 0.0, 0.0114306221, 0.0742863119, 0.15387252),
    (0.5, 10.0, 60.0, 60.0, 0.011339277, 0.073692672, 0.15387252),
    (0.5, 10.0, 60.0, 180.0, 0.0110717257, 0.0719538853, 0.15387252),
    (0.5, 10.0, 89.5, 0.0, 0.012432158, 0.0182124767, 0.682617664),
    (0.5, 10.0, 89.5, 60.0, 0.0122569883, 0.017955862, 0.682617664),
    (0.5, 10.0, 89.5, 180.0, 0.0117531409, 0.0172177516, 0.682617664),
    (0.5, 45.0, 0.0, 0.0, 0.00309417676, 0.165952042, 0.0186450053),
    (0.5, 45.0, 0.0, 60.0, 0.00309409667, 0.16594775, 0.0186450053),
    (0.5, 45.0, 0.0, 180.0, 0.00309486687, 0.165989056, 0.0186450053),
    (0.5, 45.0, 30.0, 0.0, 0.005676792, 0.165790945, 0.0342406631),
    (0.5, 45.0, 30.0, 60.0, 0.00550205214, 0.16068767, 0.0342406631),
    (0.5, 45.0, 30.0, 180.0, 0.00502365408, 0.146716028, 0.0342406631),
    (0.5, 45.0, 60.0, 0.0, 0.0222267155, 0.144448891, 0.15387252),
    (0.5, 45.0, 60.0, 60.0, 0.0213912614, 0.13901937, 0.15387252),
    (0.5, 45.0, 60.0, 180.0, 0.0191492327, 0.124448679, 0.15387252),
    (0.5, 45.0, 89.5, 0.0, 0.0344522931, 0.0504708514, 0.682617664),
    (0.5, 45.0, 89.5, 60.0, 0.0317980945, 0.0465825833, 0.682617664),
    (0.5, 45.0, 89.5, 180.0, 0.025445655, 0.0372765847, 0.682617664),
    (0.5, 89.0, 0.0, 0.0, 0.000320906402, 0.0172113869, 0.0186450053),
    (0.5, 89.0, 0.0, 60.0, 0.000320905849, 0.0172113571, 0.0186450053),
    (0.5, 89.0, 0.0, 180.0, 0.000320911495, 0.0172116607, 0.0186450053),
    (0.5, 89.0, 30.0, 0.0, 0.000663831306, 0.019387221, 0.0342406631),
    (0.5, 89.0, 30.0, 60.0, 0.000662245147, 0.019340897, 0.0342406631),
    (0.5, 89.0, 30.0, 180.0, 0.000657520548, 0.019202916, 0.0342406631),
    (0.5, 89.0, 60.0, 0.0, 0.00384469982, 0.0249862671, 0.15387252),
    (0.5, 89.0, 60.0, 60.0, 0.00383099564, 0.0248972047, 0.15387252),
    (0.5, 89.0, 60.0, 180.0, 0.00379032223, 0.024632873, 0.15387252),
    (0.5, 89.0, 89.5, 0.0, 0.0698581636, 0.102338642, 0.682617664),
    (0.5, 89.0, 89.5, 60.0, 0.0680851117, 0.0997412056, 0.682617664),
    (0.5, 89.0, 89.5, 180.0, 0.0631527677, 0.0925155729, 0.682617664),
    (1.0, 10.0, 0.0, 0.0, 0.0840534568, 0.24586384, 0.34186995),
    (1.0, 10.0, 0.0, 60.0, 0.0840532035, 0.245863095, 0.34186995),
    (1.0, 10.0, 0.0, 180.0, 0.0840558186, 0.245870739, 0.34186995),
    (1.0, 10.0, 30.0, 0.0, 0.0915441737, 0.244319707, 0.374690086),
    (1.0, 10.0, 30.0, 60.0, 0.0915453434, 0.244322836, 0.374690086),
    (1.0, 10.0, 30.0, 180.0, 0.0915489197, 0.244332388, 0.374690086),
    (1.0, 10.0, 60.0, 0.0, 0.11806123, 0.236709505, 0.498759985),
    (1.0, 10.0, 60.0, 60.0, 0.118060142, 0.23670733, 0.498759985),
    (1.0, 10.0, 60.0, 180.0, 0.118057013, 0.236701056, 0.498759985),
    (1.0, 10.0, 89.5, 0.0, 0.128082186, 0.171733782, 0.745818198),
    (1.0, 10.0, 89.5, 60.0, 0.128081992, 0.171733528, 0.745818198),
    (1.0, 10.0, 89.5, 180.0, 0.128081471, 0.171732828, 0.745818198),
    (1.0, 45.0, 0.0, 0.0, 0.0756912604, 0.221403658, 0.34186995),
    (1.0, 45.0, 0.0, 60.0, 0.0756904706, 0.221401349, 0.34186995),
    (1.0, 45.0, 0.0, 180.0, 0.0756981522, 0.221423835, 0.34186995),
    (1.0, 45.0, 30.0, 0.0, 0.0828837454, 0.221206143, 0.374690086),
    (1.0, 45.0, 30.0, 60.0, 0.0828872994, 0.221215621, 0.374690086),
    (1.0, 45.0, 30.0, 180.0, 0.0828979164, 0.221243948, 0.374690086),
    (1.0, 45.0, 60.0, 0.0, 0.109836489, 0.220219135, 0.498759985),
    (1.0, 45.0, 60.0, 60.0, 0.109833241, 0.220212609, 0.498759985),
    (1.0, 45.0, 60.0, 180.0, 0.10982345, 0.220192984, 0.498759985),
    (1.0, 45.0, 89.5, 0.0, 0.152248085, 0.204135656, 0.745818198),
    (1.0, 45.0, 89.5, 60.0, 0.152247265, 0.204134554, 0.745818198),
    (1.0, 45.0, 89.5, 180.0, 0.152244911, 0.204131395, 0.745818198),
    (1.0, 89.0, 0.0, 0.0, 0.00245435163, 0.00717919646, 0.34186995),
    (1.0, 89.0, 0.0, 60.0, 0.0024543507, 0.00717919413, 0.34186995),
    (1.0, 89.0, 0.0, 180.0, 0.00245436118, 0.0071792244, 0.34186995),
    (1.0, 89.0, 30.0, 0.0, 0.00270776032, 0.00722666644, 0.374690086),
    (1.0, 89.0, 30.0, 60.0, 0.00270776544, 0.00722668041, 0.374690086),
    (1.0, 89.0, 30.0, 180.0, 0.00270777894, 0.00722671626, 0.374690086),
    (1.0, 89.0, 60.0, 0.0, 0.00372601626, 0.00747055979, 0.498759985),
    (1.0, 89.0, 60.0, 60.0, 0.00372601207, 0.00747055141, 0.498759985),
    (1.0, 89.0, 60.0, 180.0, 0.00372599857, 0.0074705244, 0.498759985),
    (1.0, 89.0, 89.5, 0.0, 0.00777650252, 0.0104268072, 0.745818198),
    (1.0, 89.0, 89.5, 60.0, 0.00777649973, 0.0104268035, 0.745818198),
    (1.0, 89.0, 89.5, 180.0, 0.00777649274, 0.0104267942, 0.745818198),
];

#[test]
fn matches_adobe_openpbr_bsdf() {
    let d2r = core::f32::consts::PI / 180.0;
    let phi_o = 0.7f32;
    let (mut worst, mut at) = (0.0f32, 0usize);
    for (n, &(r, ti, to, dphi, f_cos, pdf, refl)) in ADOBE.iter().enumerate() {
        let s = LtcSheen::new(1.0f32, r).unwrap();
        let phi_i = phi_o - dphi * d2r;
        let wo = Vec3::new(
            (to * d2r).sin() * phi_o.cos(),
            (to * d2r).sin() * phi_o.sin(),
            (to * d2r).cos(),
        );
        let wi = Vec3::new(
            (ti * d2r).sin() * phi_i.cos(),
            (ti * d2r).sin() * phi_i.sin(),
            (ti * d2r).cos(),
        );
        let got = [s.eval(wi, wo) * wi.z, s.pdf(wi, wo), s.albedo_untinted(wo.z)];
        for (g, w) in got.into_iter().zip([f_cos, pdf, refl]) {
            let rel = (g - w).abs() / w.abs().max(1e-30);
            if w == 0.0 {
                assert_eq!(g, 0.0, "row {n}");
            } else if rel > worst {
                (worst, at) = (rel, n);
            }
        }
    }
    println!("LTC sheen vs Adobe's OpenPBR BSDF: worst relative difference {worst:.2e} (row {at})");
    assert!(
        worst < 1e-4,
        "worst relative difference {worst:e} at row {at}: {:?}",
        ADOBE[at]
    );
}
