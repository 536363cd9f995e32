//! Sampling tests (issue 2): the harness itself (special functions, quadrature, χ² on toy samplers that
//! are right and deliberately wrong), then every plugin: `weight = f cos/pdf`, `pdf(sampled wi) =
//! returned pdf`, χ² goodness of fit at several roughnesses/exponents and incidence angles, and the
//! integral of the pdf (1, or the documented mass of visible-normal sampling).

use crate::common;

use common::chi2::{ChiSquare, chi_square};
use common::quad::{Adaptive, GaussLegendre, Tol, integrate_hemisphere};
use common::special::{chi2_sf, gamma_p, gamma_q, ln_gamma, sidak};
use radiometry::glam::{DVec3, Vec3};
use radiometry::{Brdf, BrdfSample};
use std::f32::consts::PI as PI32;
use std::f64::consts::{FRAC_PI_2, PI};

// ---------------------------------------------------------------- harness self-tests

#[test]
fn ln_gamma_matches_factorials_and_half_integers() {
    let mut fact = 1.0f64;
    for n in 1..30u32 {
        // Γ(n) = (n−1)!
        let rel = (ln_gamma(n as f64) - fact.ln()).abs() / fact.ln().abs().max(1.0);
        assert!(rel < 1e-13, "ln Γ({n})");
        fact *= n as f64;
    }
    // Γ(1/2) = √π, Γ(7/2) = 15√π/8.
    assert!((ln_gamma(0.5) - PI.sqrt().ln()).abs() < 1e-14);
    assert!((ln_gamma(3.5) - (15.0 * PI.sqrt() / 8.0).ln()).abs() < 1e-14);
}

/// Closed forms of the χ² survival function: even k, `e^{−x/2} Σ_{j<k/2} (x/2)^j / j!`; odd k from
/// `Q(1/2, x/2) = erfc(√(x/2))` and `Q(a+1, y) = Q(a, y) + y^a e^{−y} / Γ(a+1)` (A&S 6.5.21).
fn chi2_sf_closed(x: f64, k: usize) -> f64 {
    let y = x / 2.0;
    if k.is_multiple_of(2) {
        let mut term = 1.0;
        let mut sum = 1.0;
        for j in 1..k / 2 {
            term *= y / j as f64;
            sum += term;
        }
        (-y).exp() * sum
    } else {
        let mut q = libm::erfc(y.sqrt());
        let mut a = 0.5f64;
        while ((2.0 * a) as usize) < k {
            q += (a * y.ln() - y - ln_gamma(a + 1.0)).exp();
            a += 1.0;
        }
        q
    }
}

#[test]
fn chi2_survival_matches_closed_forms_and_tables() {
    for k in [1usize, 2, 3, 4, 5, 10, 11, 40, 99, 100, 400] {
        for &x in &[0.01, 0.5, 1.0, 3.0, 10.0, 50.0, 120.0, 400.0, 500.0] {
            let a = chi2_sf(x, k);
            let b = chi2_sf_closed(x, k);
            assert!(
                (a - b).abs() <= 1e-12 + 1e-9 * b,
                "k={k} x={x}: {a} vs closed form {b}"
            );
        }
    }
    // Table values (upper critical points, NIST/SEMATECH e-Handbook 1.3.6.7.4).
    for &(k, x, p) in &[
        (1usize, 3.841, 0.05),
        (1, 6.635, 0.01),
        (10, 23.209, 0.01),
        (10, 18.307, 0.05),
        (100, 135.807, 0.01),
        (100, 124.342, 0.05),
    ] {
        let got = chi2_sf(x, k);
        assert!(
            (got - p).abs() < 2e-4 * p.max(0.01) / 0.01,
            "k={k} x={x}: {got} vs {p}"
        );
    }
    assert!((gamma_p(2.5, 1.7) + gamma_q(2.5, 1.7) - 1.0).abs() < 1e-15);
    // Šidák: m tests at the corrected level reject none with probability exactly 1 − α.
    let a = sidak(0.01, 64);
    assert!(((1.0 - a).powi(64) - 0.99).abs() < 1e-12);
}

#[test]
fn gauss_legendre_and_adaptive_quadrature_are_exact_on_known_integrals() {
    let gl = GaussLegendre::new(8);
    // Exact for degree ≤ 15.
    let (v, _) = gl.apply(0.0, 2.0, &mut |x| (x.powi(15), 0.0));
    assert!((v - 2f64.powi(16) / 16.0).abs() < 1e-9);
    let q = Adaptive::default();
    let tol = Tol {
        abs: 1e-12,
        rel: 1e-14,
        depth: 30,
    };
    // A sharp peak: ∫_0^1 ε/(π((x−1/3)²+ε²)) dx with ε = 1e-4.
    let e = 1e-4f64;
    let r = q.integrate(0.0, 1.0, tol, &mut |x| {
        (e / (PI * ((x - 1.0 / 3.0).powi(2) + e * e)), 0.0)
    });
    let exact = ((2.0 / 3.0) / e).atan() / PI + ((1.0 / 3.0) / e).atan() / PI;
    assert!((r.value - exact).abs() < 1e-10, "{r:?} vs {exact}");
    assert!(r.err < 1e-8 && r.err >= 0.0);
    // Honest error: with a depth limit too small to converge on a peak that the first rule does see
    // (width 1e-2), the error estimate still covers the actual error.
    let e = 1e-2f64;
    let exact = ((2.0 / 3.0) / e).atan() / PI + ((1.0 / 3.0) / e).atan() / PI;
    let shallow = Tol { depth: 2, ..tol };
    let r = q.integrate(0.0, 1.0, shallow, &mut |x| {
        (e / (PI * ((x - 1.0 / 3.0).powi(2) + e * e)), 0.0)
    });
    assert!(r.err > 1e-6, "not converged at depth 2: {r:?}");
    assert!((r.value - exact).abs() <= r.err, "{r:?} vs {exact}");
}

#[test]
fn hemisphere_quadrature_matches_closed_forms() {
    let q = Adaptive::default();
    let tol = Tol {
        abs: 1e-8,
        rel: 1e-10,
        depth: 12,
    };
    for &theta_p in &[0.0f64, 0.5, 1.2, FRAC_PI_2 - 1e-4, FRAC_PI_2 - 3e-8] {
        let pole = DVec3::new(theta_p.sin(), 0.0, theta_p.cos());
        // ∫ dω = 2π; ∫ cos θ dω = π; ∫ cos^n θ cos θ... and a narrow lobe around the pole.
        let r = integrate_hemisphere(&q, pole, &[0.3, 1.0], tol, &mut |_| 1.0);
        assert!((r.value - 2.0 * PI).abs() < 1e-7, "area, pole θ={theta_p}: {r:?}");
        let r = integrate_hemisphere(&q, pole, &[0.3, 1.0], tol, &mut |w| w.z);
        assert!((r.value - PI).abs() < 1e-7, "cos, pole θ={theta_p}: {r:?}");
        let n = 20.0;
        let r = integrate_hemisphere(&q, pole, &common::quad::lobe_breaks(0.2), tol, &mut |w| {
            w.z.powf(n)
        });
        assert!(
            (r.value - 2.0 * PI / (n + 1.0)).abs() < 1e-7,
            "cos^n, pole θ={theta_p}: {r:?}"
        );
    }
    // A lobe of width 1e-3 around a pole at 60°: ∫ (m+1)/(2π) max(0,ω·r)^m dω = 1 when the cap is whole.
    let m = 1e6;
    let pole = DVec3::new(0.8660254037844386, 0.0, 0.5);
    let tol = Tol {
        abs: 1e-8,
        rel: 1e-9,
        depth: 10,
    };
    let r = integrate_hemisphere(&q, pole, &common::quad::lobe_breaks(1e-3), tol, &mut |w| {
        (m + 1.0) / (2.0 * PI) * w.dot(pole).max(0.0).powf(m)
    });
    assert!((r.value - 1.0).abs() < 1e-7 && r.err < 1e-6, "{r:?}");
}

/// A Lambertian toy with the core crate's default (cosine-weighted) sampling.
struct ToyLambert(f32);
impl Brdf for ToyLambert {
    type Spectrum = f32;
    fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
        if wi.z > 0.0 && wo.z > 0.0 {
            self.0 / PI32
        } else {
            0.0
        }
    }
}

/// A deliberately wrong sampler: cosine-weighted samples, but `pdf` claims `max(0,cos θ)^p (p+1)/(2π)`.
struct WrongPdf(f32);
impl Brdf for WrongPdf {
    type Spectrum = f32;
    fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
        if wi.z > 0.0 && wo.z > 0.0 { 0.5 / PI32 } else { 0.0 }
    }
    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<f32>> {
        let s = ToyLambert(0.5).sample(wo, u)?;
        let pdf = self.pdf(s.wi, wo);
        (pdf > 0.0).then(|| BrdfSample {
            wi: s.wi,
            pdf,
            weight: self.eval(s.wi, wo) * s.wi.z / pdf,
        })
    }
    fn pdf(&self, wi: Vec3, _wo: Vec3) -> f32 {
        let p = self.0;
        (p + 1.0) / (2.0 * PI32) * wi.z.max(0.0).powf(p)
    }
}

/// A right sampler that drops 30 % of its samples: `None` when `u₀ < 0.3`, otherwise the cosine warp of
/// `((u₀ − 0.3)/0.7, u₁)`; density `0.7 cos θ / π`.
struct Lossy {
    /// Claimed loss probability (0.3 is right).
    claimed: f32,
}
impl Brdf for Lossy {
    type Spectrum = f32;
    fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
        if wi.z > 0.0 && wo.z > 0.0 { 0.5 / PI32 } else { 0.0 }
    }
    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<f32>> {
        if u[0] < 0.3 {
            return None;
        }
        let wi = radiometry::warp::square_to_cosine_hemisphere([(u[0] - 0.3) / 0.7, u[1]]);
        let pdf = self.pdf(wi, wo);
        (pdf > 0.0 && wi.z > 0.0).then(|| BrdfSample {
            wi,
            pdf,
            weight: self.eval(wi, wo) * wi.z / pdf,
        })
    }
    fn pdf(&self, wi: Vec3, _wo: Vec3) -> f32 {
        (1.0 - self.claimed) * wi.z.max(0.0) / PI32
    }
}

/// Significance of each of the 6 χ² tests of the harness self-test block.
fn harness_alpha() -> f64 {
    sidak(0.01, 6)
}

#[test]
fn chi_square_accepts_the_default_cosine_sampler() {
    for (k, &theta) in [0.0f32, 1.2].iter().enumerate() {
        let wo = Vec3::new(theta.sin(), 0.0, theta.cos());
        let cfg = ChiSquare::for_lobe(wo, 10.0, 11 + k as u64);
        let r = chi_square(&ToyLambert(0.8), wo, &cfg);
        eprintln!(
            "toy cosine sampler θo={theta}: χ²={:.1} dof={} p={:.4} mass={:.8}±{:.1e}",
            r.statistic, r.dof, r.p_value, r.mass.value, r.mass.err
        );
        assert!(r.passes(harness_alpha()), "{r:#?}");
        assert!((r.mass.value - 1.0).abs() < 1e-6 + r.mass.err, "{r:?}");
        assert!(r.worst_pdf_rel < 1e-6 && r.worst_weight_rel < 1e-6, "{r:?}");
        assert_eq!(r.none_observed, 0);
    }
}

#[test]
fn chi_square_rejects_mismatched_pdfs() {
    let wo = Vec3::new(0.0, 0.6, 0.8);
    // Grossly wrong (uniform claimed for cosine samples) and subtly wrong (cos^1.05 for cos^1).
    for (k, &p) in [0.0f32, 1.05].iter().enumerate() {
        let cfg = ChiSquare::for_lobe(wo, 10.0, 21 + k as u64);
        let r = chi_square(&WrongPdf(p), wo, &cfg);
        eprintln!(
            "wrong sampler p={p}: χ²={:.1} dof={} p={:.3e}",
            r.statistic, r.dof, r.p_value
        );
        assert!(!r.passes(harness_alpha()), "must reject, {r:#?}");
    }
}

#[test]
fn chi_square_checks_the_none_frequency() {
    let wo = Vec3::new(0.0, 0.6, 0.8);
    let cfg = ChiSquare::for_lobe(wo, 10.0, 31);
    let right = chi_square(&Lossy { claimed: 0.3 }, wo, &cfg);
    eprintln!(
        "lossy sampler: χ²={:.1} dof={} p={:.4} none {} vs {:.0}",
        right.statistic, right.dof, right.p_value, right.none_observed, right.none_expected
    );
    assert!(right.passes(harness_alpha()), "{right:#?}");
    assert!((right.mass.value - 0.7).abs() < 1e-6 + right.mass.err);
    // Claiming a 29 % loss with a 30 % loss is a 1.4 % density error: must be rejected.
    let wrong = chi_square(&Lossy { claimed: 0.29 }, wo, &cfg);
    assert!(!wrong.passes(harness_alpha()), "{wrong:#?}");
}

// ---------------------------------------------------------------- every plugin

use common::plugins::{Dist, Fres, Kind, Params, Shadow, all_kinds, build, lobe_width, params};
use common::{Worst, sensitivity};

static WORST_PDF: Worst = Worst::new();
static WORST_WEIGHT: Worst = Worst::new();
static UNDERFLOWED: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);

/// `pdf(sampled ωi, ωo)` equals the returned pdf and `weight = f cos θi / pdf`, 1,000 cases × 38
/// configurations, `u` including 0 and `1 − 2⁻²⁴`. Tolerance: `1e-4` relative plus the sensitivity of
/// `pdf` (resp. `f cos/pdf`) to one-ulp changes of its inputs (the sampled `ωi` is rounded to `f32`
/// before `pdf` sees it). The weight is compared only where `f` and `pdf` are ≥ 1e-30 (see below).
#[test]
fn weight_and_pdf_match_eval_and_pdf_every_plugin() {
    use proptest::prelude::*;
    let mut runner = common::runner(1000);
    let kinds = all_kinds();
    let u = prop_oneof![4 => 0.0f32..1.0, 1 => Just(0.0f32), 1 => Just(0.99999994f32)];
    runner
        .run(
            &(params(), common::strategies::upper_dir(), [u.clone(), u]),
            |(p, wo, u)| {
                let wo = common::strategies::to_f32(wo);
                for &k in &kinds {
                    let b = build(k, &p).unwrap();
                    let Some(s) = b.sample(wo, u) else { continue };
                    let ctx = || format!("{k:?} {p:?} wo={wo:?} u={u:?}: {s:?}");
                    if !(s.pdf > 0.0 && s.pdf.is_finite() && s.weight.is_finite() && s.weight >= 0.0) {
                        return Err(TestCaseError::fail(format!("invalid sample {}", ctx())));
                    }
                    let pdf = |x: Vec3, y: Vec3| b.pdf(x, y);
                    let p2 = b.pdf(s.wi, wo);
                    let sp = sensitivity(&pdf, s.wi, wo);
                    let tol = 1e-4 * s.pdf.max(p2) + sp;
                    WORST_PDF.record(((p2 - s.pdf).abs() / s.pdf) as f64, ctx);
                    if (p2 - s.pdf).abs() > tol {
                        return Err(TestCaseError::fail(format!(
                            "pdf(wi) = {p2:e} (tol {tol:e}): {}",
                            ctx()
                        )));
                    }
                    let w = |x: Vec3, y: Vec3| b.eval(x, y) * x.z / s.pdf;
                    let expect = w(s.wi, wo);
                    // f and pdf are products of several factors (D, G, F, 1/cos, …); within 1e8 of
                    // f32::MIN_POSITIVE the intermediate products are subnormal and carry no relative
                    // precision (deep tails of sharp lobes, grazing ωo). There, the plugin's analytic
                    // weight (e.g. G2/G1·F) is the accurate one and f·cos/pdf is not: only finiteness is
                    // required (counted in UNDERFLOWED).
                    let f = b.eval(s.wi, wo);
                    if f < 1e-30 || s.pdf < 1e-30 {
                        UNDERFLOWED.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                        continue;
                    }
                    let tol = 1e-4 * expect.max(s.weight) + sensitivity(&w, s.wi, wo);
                    let m = expect.max(s.weight);
                    WORST_WEIGHT.record(((expect - s.weight).abs() / m) as f64, ctx);
                    if (expect - s.weight).abs() > tol {
                        return Err(TestCaseError::fail(format!(
                            "weight vs f cos/pdf = {expect:e}: {}",
                            ctx()
                        )));
                    }
                }
                Ok(())
            },
        )
        .unwrap();
    let (a, wa) = WORST_PDF.get();
    let (b, wb) = WORST_WEIGHT.get();
    eprintln!(
        "sampling: 1000 cases x {} plugins; worst |pdf(wi) - returned pdf|/pdf {a:.3e} at {wa}",
        kinds.len()
    );
    eprintln!("sampling: worst |weight - f cos/pdf|/weight {b:.3e} at {wb}");
    eprintln!(
        "sampling: {} samples with f or pdf < 1e-30 (weight compared for finiteness only)",
        UNDERFLOWED.load(std::sync::atomic::Ordering::Relaxed)
    );
}

/// Number of χ² tests over the plugins below (for the Šidák correction).
const PLUGIN_CHI2_TESTS: usize = 4 + 17 + 17 + 16 + 16 + 2 + 10 + 8;
const THETAS_DEG: [f32; 4] = [0.0, 30.0, 70.0, 85.0];

fn plugin_alpha() -> f64 {
    sidak(0.01, PLUGIN_CHI2_TESTS)
}

/// Runs the χ² test of one configuration at every incidence angle; returns failure descriptions.
fn chi2_plugin(k: Kind, p: &Params, thetas: &[f32], seed: u64) -> Vec<String> {
    chi2_plugin_at(k, p, thetas, seed, plugin_alpha())
}

/// [`chi2_plugin`] at significance `alpha` per test.
fn chi2_plugin_at(k: Kind, p: &Params, thetas: &[f32], seed: u64, alpha: f64) -> Vec<String> {
    let b = build(k, p).unwrap();
    let mut fails = Vec::new();
    for (i, &deg) in thetas.iter().enumerate() {
        let t = deg.to_radians();
        let wo = Vec3::new(t.sin(), 0.0, t.cos());
        let cfg = ChiSquare::for_lobe(wo, lobe_width(k, p), seed * 100 + i as u64);
        let r = chi_square(b.as_ref(), wo, &cfg);
        eprintln!(
            "χ² {k:?} n={} α={} kd={} σ={} θo={deg}°: χ²={:.1} dof={} p={:.4} mass={:.6}±{:.1e} None {} vs {:.1} | pdf rel {:.1e} weight rel {:.1e} | quadrature χ² {:.1e}",
            p.n,
            p.alpha,
            p.kd,
            p.sigma,
            r.statistic,
            r.dof,
            r.p_value,
            r.mass.value,
            r.mass.err,
            r.none_observed,
            r.none_expected,
            r.worst_pdf_rel,
            r.worst_weight_rel,
            r.quadrature_chi2
        );
        let mass_ok = r.mass.value <= 1.0 + r.mass.err + 1e-5;
        if !r.passes(alpha) || !mass_ok {
            fails.push(format!(
                "{k:?} {p:?} θo={deg}°: p={:e} (α={:e}), bad samples {} ({:?}), zero-pdf hits {}, quadrature χ² {:.1e}, mass {:?}, top cells {:?}",
                r.p_value,
                alpha,
                r.bad_samples,
                r.first_bad,
                r.zero_pdf_hits,
                r.quadrature_chi2,
                r.mass,
                r.top_cells
            ));
        }
    }
    fails
}

#[test]
fn chi_square_lambertian() {
    let p = Params::typical();
    let fails = chi2_plugin(Kind::Lambertian, &p, &THETAS_DEG, 1);
    assert!(fails.is_empty(), "{fails:#?}");
}

fn chi2_phong_family(k: Kind, seed: u64) {
    let mut fails = Vec::new();
    for (j, &n) in [1.0f32, 10.0, 100.0, 1000.0].iter().enumerate() {
        let p = Params {
            kd: 0.0,
            ks: 1.0,
            n,
            ..Params::typical()
        };
        fails.extend(chi2_plugin(k, &p, &THETAS_DEG, seed + j as u64));
    }
    // The one-sample mixture of cosine and lobe sampling.
    let p = Params {
        kd: 0.4,
        ks: 0.5,
        n: 100.0,
        ..Params::typical()
    };
    fails.extend(chi2_plugin(k, &p, &[30.0], seed + 10));
    assert!(fails.is_empty(), "{fails:#?}");
}

#[test]
fn chi_square_modified_phong() {
    chi2_phong_family(Kind::ModifiedPhong, 10);
}

#[test]
fn chi_square_blinn_phong() {
    chi2_phong_family(Kind::BlinnPhong, 30);
}

fn chi2_microfacet(d: Dist, seed: u64) {
    let mut fails = Vec::new();
    for (j, &alpha) in [0.05f32, 0.2, 0.6, 1.0].iter().enumerate() {
        let p = Params {
            alpha,
            ..Params::typical()
        };
        let k = Kind::Micro(d, Shadow::HeightCorrelated, Fres::None);
        fails.extend(chi2_plugin(k, &p, &THETAS_DEG, seed + j as u64));
    }
    // Sampling does not depend on G2 or F, but the weight does: one more configuration.
    let p = Params {
        alpha: 0.2,
        ..Params::typical()
    };
    fails.extend(chi2_plugin(
        Kind::Micro(d, Shadow::Separable, Fres::Conductor),
        &p,
        &[70.0],
        seed + 10,
    ));
    assert!(fails.is_empty(), "{fails:#?}");
}

#[test]
fn chi_square_ggx() {
    chi2_microfacet(Dist::Ggx, 50);
}

#[test]
fn chi_square_beckmann() {
    chi2_microfacet(Dist::Beckmann, 70);
}

/// The Kulla–Conty mixture sampler (single-scattering lobe or cosine lobe, chosen with probability
/// `1 − E(μo)`): GGX with F = 1 at two roughnesses × 4 angles, Beckmann with a conductor at 2 angles.
#[test]
fn chi_square_kulla_conty() {
    // The three groups in parallel (the compensated pdf makes these the slowest χ² tests, ~70 s in one
    // thread); each keeps its own seeds, so the outcome does not depend on the threads.
    let ggx = |j: usize, alpha: f32| {
        move || {
            let p = Params {
                alpha,
                ..Params::typical()
            };
            let k = Kind::KullaConty(Dist::Ggx, Shadow::HeightCorrelated, Fres::None);
            chi2_plugin(k, &p, &THETAS_DEG, 90 + j as u64)
        }
    };
    let beckmann = || {
        let p = Params {
            alpha: 0.5,
            ..Params::typical()
        };
        chi2_plugin(
            Kind::KullaConty(Dist::Beckmann, Shadow::Separable, Fres::Conductor),
            &p,
            &[0.0, 70.0],
            95,
        )
    };
    let fails: Vec<_> = std::thread::scope(|s| {
        let a = s.spawn(ggx(0, 0.3));
        let b = s.spawn(ggx(1, 1.0));
        let c = s.spawn(beckmann);
        [a, b, c].into_iter().flat_map(|h| h.join().unwrap()).collect()
    });
    assert!(fails.is_empty(), "{fails:#?}");
}

/// The `Tabulated` half-vector sampler mixed with a cosine lobe (exact pdf): both fixed tables (GGX α = 0.3
/// on the MERL grid; diffuse + GGX α = 0.1 on a coarse grid) at 4 angles.
#[test]
fn chi_square_tabulated() {
    use common::plugins::TABULATED_KINDS;
    let p = Params::typical();
    let mut fails = Vec::new();
    for (j, &k) in TABULATED_KINDS.iter().enumerate() {
        fails.extend(chi2_plugin(k, &p, &THETAS_DEG, 110 + j as u64));
    }
    assert!(fails.is_empty(), "{fails:#?}");
}

/// Regression for a finding of this suite (energy test, heavy-tailed weights): Blinn–Phong at grazing
/// `ωo` and `ωi ≈ −ωo` (both just above the horizon, opposite azimuths). There `h ≈ +Z`, so the lobe
/// `f ≈ ks (n+…) cos^n θh` is at its peak, and the lobe sampler's density `(n+1)/(2π) cos^n θh / (4 ωo·h)`
/// is huge; but `pdf` computes `ωo·h` from a half vector dominated by rounding, finds it ≤ 0 and drops
/// the lobe term, returning only the diffuse part — so `f cos/pdf` reaches 6.6e5 and `pdf` is not the
/// density of `sample` there. Expected: the lobe term evaluated with `ωo·h = |ω̂i + ω̂o|/2` (our f64
/// value below, from the f32 inputs).
#[test]
fn blinn_phong_pdf_includes_lobe_at_near_opposite_grazing() {
    let (kd, ks, n) = (0.6092879f32, 0.39071205f32, 1e7f32);
    let b = radiometry_brdfs::BlinnPhong::new(kd, ks, n).unwrap();
    let wi = Vec3::new(-0.7147365, 0.69939387, 0.0002987285);
    let wo = Vec3::new(0.7147365, -0.6993938, 1.181356e-8);
    let (a, c) = (
        common::strategies::to_f64(wi).normalize(),
        common::strategies::to_f64(wo).normalize(),
    );
    let s = a + c;
    let h = s.normalize();
    let wo_h = 0.5 * s.length();
    let p_lobe = ks as f64 / (kd + ks) as f64;
    let lobe = p_lobe * (n as f64 + 1.0) / (2.0 * PI) * h.z.powf(n as f64) / (4.0 * wo_h);
    let got = b.pdf(wi, wo) as f64;
    assert!(got >= 0.5 * lobe, "pdf = {got:e}, lobe density alone = {lobe:e}");
}

/// Number of χ² tests in [`chi_square_rough_diffuse`]: a family of its own (Šidák-corrected to 1 % on its
/// own), so the significance of the tests above stays what it was.
const ROUGH_DIFFUSE_CHI2_TESTS: usize = 5 * 5;

/// The rough diffuse plugins' cosine/uniform mixture (exact pdf): FON and EON at σ = 0.5 and 1, the
/// classic Oren–Nayar at its roughest (σ = π/2 rad), each at 0°, 30°, 70°, 85° and 89.5° (where the
/// uniform part of the mixture is largest).
#[test]
fn chi_square_rough_diffuse() {
    let alpha = sidak(0.01, ROUGH_DIFFUSE_CHI2_TESTS);
    let thetas = [0.0f32, 30.0, 70.0, 85.0, 89.5];
    let mut fails = Vec::new();
    for (j, (k, sigma)) in [
        (Kind::Fon, 0.5f32),
        (Kind::Fon, 1.0),
        (Kind::Eon, 0.5),
        (Kind::Eon, 1.0),
        (Kind::OrenNayar, 1.0),
    ]
    .into_iter()
    .enumerate()
    {
        let p = Params {
            sigma,
            rho: 1.0,
            ..Params::typical()
        };
        fails.extend(chi2_plugin_at(k, &p, &thetas, 130 + j as u64, alpha));
    }
    assert!(fails.is_empty(), "{fails:#?}");
}

/// A two-lobe composite sampled with a *fixed* 50/50 lobe choice: the same `eval` as `inner`, the
/// mixture density `½ pdf_T + ½ pdf_B` — the scheme albedo-proportional picking replaces.
struct FiftyFifty<'a, T: Brdf<Spectrum = f32>, B: Brdf<Spectrum = f32>>(
    &'a radiometry::compose::Coated<T, B>,
);

impl<T: Brdf<Spectrum = f32>, B: Brdf<Spectrum = f32>> Brdf for FiftyFifty<'_, T, B> {
    type Spectrum = f32;
    fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
        self.0.eval(wi, wo)
    }
    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<f32>> {
        let s = if u[0] < 0.5 {
            self.0.top().sample(wo, [2.0 * u[0], u[1]])
        } else {
            self.0
                .base()
                .sample(wo, [(2.0 * u[0] - 1.0).min(1.0 - f32::EPSILON), u[1]])
        }?;
        let pdf = self.pdf(s.wi, wo);
        (pdf > 0.0).then(|| BrdfSample {
            wi: s.wi,
            pdf,
            weight: self.eval(s.wi, wo) * s.wi.z / pdf,
        })
    }
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        0.5 * self.0.top().pdf(wi, wo) + 0.5 * self.0.base().pdf(wi, wo)
    }
}

/// Variance of the 256-sample albedo estimate `mean(weight)` over `runs` independent estimates.
fn albedo_estimate_variance<B: Brdf<Spectrum = f32>>(b: &B, wo: Vec3, runs: u64) -> (f64, f64) {
    let mut rng = radiometry::rng::Pcg32::new(0x5eed);
    let (mut s1, mut s2) = (0.0f64, 0.0f64);
    for _ in 0..runs {
        let mut e = 0.0f64;
        for _ in 0..256 {
            let u = [rng.next_f32(), rng.next_f32()];
            e += b.sample(wo, u).map_or(0.0, |s| f64::from(s.weight)) / 256.0;
        }
        s1 += e;
        s2 += e * e;
    }
    let n = runs as f64;
    let mean = s1 / n;
    (mean, (s2 / n - mean * mean) * n / (n - 1.0))
}

/// Albedo-proportional lobe picking (what `Sum`, `Mix` and `Coated` do) against a fixed 50/50 choice,
/// at θo = 60° with 256 samples per estimate, on a plastic (GGX α = 0.1 dielectric η = 1.5 over a
/// Lambertian ρ = 0.8) and a coated metal (the same coat over a GGX α = 0.3 gold-like conductor). Both
/// schemes are unbiased (same mean within 4σ); the target is a variance ratio ≥ 1.5 on the
/// plastic.
#[test]
fn albedo_proportional_lobe_picking_beats_fifty_fifty() {
    use radiometry::compose::Coated;
    use radiometry_brdfs::{Conductor, Dielectric, Ggx, HeightCorrelated, Lambertian, Microfacet};
    let coat =
        Microfacet::<_, HeightCorrelated, _>::new(Ggx::new(0.1).unwrap(), Dielectric::new(1.5).unwrap());
    let plastic = Coated::new(coat, Lambertian::new(0.8f32).unwrap());
    let metal =
        Microfacet::<_, HeightCorrelated, _>::new(Ggx::new(0.3).unwrap(), Conductor::new(0.2, 3.0).unwrap());
    let coated_metal = Coated::new(coat, metal);
    let wo = Vec3::new(60f32.to_radians().sin(), 0.0, 60f32.to_radians().cos());
    let runs = 400;
    let mut ratios = Vec::new();
    for (name, ratio_min) in [("plastic", 1.5), ("coated metal", 1.0)] {
        let ((m_a, v_a), (m_f, v_f)) = if name == "plastic" {
            (
                albedo_estimate_variance(&plastic, wo, runs),
                albedo_estimate_variance(&FiftyFifty(&plastic), wo, runs),
            )
        } else {
            (
                albedo_estimate_variance(&coated_metal, wo, runs),
                albedo_estimate_variance(&FiftyFifty(&coated_metal), wo, runs),
            )
        };
        let ratio = v_f / v_a;
        eprintln!(
            "lobe picking, {name} θo=60°, 256 samples: albedo {m_a:.5} (albedo-proportional) vs {m_f:.5} (50/50); \
             variance {v_a:.3e} vs {v_f:.3e}: 50/50 has {ratio:.2}× the variance"
        );
        let se = ((v_a + v_f) / runs as f64).sqrt();
        assert!(
            (m_a - m_f).abs() < 4.0 * se,
            "{name}: means {m_a} vs {m_f} differ by > 4σ ({se:e})"
        );
        ratios.push((name, ratio, ratio_min));
    }
    for (name, ratio, min) in ratios {
        assert!(
            ratio >= min,
            "{name}: albedo-proportional picking lowers the variance only {ratio:.2}×"
        );
    }
}
