//! Unit tests of the microfacet module.
//!
//! References are independent of the code under test: closed forms, and
//! `f64` composite-Simpson quadratures written here (with geometrically
//! graded θ panels around the specular peak, and the azimuthal integral of
//! the clamped cosine done in closed form or on its support only).

extern crate std;

use super::*;
use crate::phong::test_support::{grazing_mirror_pair, unit64};
use core::f64::consts::{FRAC_PI_2, PI as PI64, TAU as TAU64};
use radiometry::math::ONE_MINUS_EPSILON;
use std::println;
use std::vec::Vec;

const ALPHAS: [f32; 4] = [0.01, 0.1, 0.5, 1.0];

// ---------------------------------------------------------------- quadrature

/// Composite Simpson on `[a, b]` with `n` (even) intervals.
fn simpson(f: &mut dyn FnMut(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
    let h = (b - a) / n as f64;
    let mut s = f(a) + f(b);
    for i in 1..n {
        let w = if i % 2 == 1 { 4.0 } else { 2.0 };
        s += w * f(a + i as f64 * h);
    }
    s * h / 3.0
}

/// Panel boundaries on `[0, π/2]`, geometric around `θ ≈ scale`.
fn panels(scale: f64) -> Vec<f64> {
    let mut b = std::vec![0.0];
    let mut t = scale / 512.0;
    while t < FRAC_PI_2 {
        b.push(t);
        t *= 2.0;
    }
    b.push(FRAC_PI_2);
    b
}

/// `∫_0^{π/2} f(θ) dθ` on graded panels, `n` Simpson intervals per panel.
fn integrate_theta(scale: f64, n: usize, f: &mut dyn FnMut(f64) -> f64) -> f64 {
    let b = panels(scale);
    b.windows(2).map(|w| simpson(f, w[0], w[1], n)).sum()
}

/// `∫_a^b f` with sub-panels graded geometrically toward both ends (20
/// halvings each side, Simpson with 8 intervals per sub-panel), which handles
/// square-root endpoint behaviour.
fn graded(a: f64, b: f64, f: &mut dyn FnMut(f64) -> f64) -> f64 {
    let m = 0.5 * (a + b);
    let mut total = 0.0;
    let mut edges = std::vec![a, m, b];
    for k in 1..=20 {
        let s = 0.5f64.powi(k);
        edges.push(a + (m - a) * s);
        edges.push(b - (b - m) * s);
    }
    edges.sort_by(|x, y| x.partial_cmp(y).unwrap());
    for w in edges.windows(2) {
        if w[1] > w[0] {
            total += simpson(f, w[0], w[1], 8);
        }
    }
    total
}

fn dir(theta: f64, phi: f64) -> Vec3 {
    Vec3::new(
        (theta.sin() * phi.cos()) as f32,
        (theta.sin() * phi.sin()) as f32,
        theta.cos() as f32,
    )
}

/// Closed form of `∫_0^{2π} max(0, A + B cos φ) dφ` (B ≥ 0).
fn clamped_cos_phi_integral(a: f64, b: f64) -> f64 {
    if b <= a.abs() {
        return if a > 0.0 { TAU64 * a } else { 0.0 };
    }
    let phi0 = (-a / b).acos();
    2.0 * (a * phi0 + b * phi0.sin())
}

fn for_each_distribution(mut f: impl FnMut(&str, &dyn MicrofacetDistribution)) {
    for &a in &ALPHAS {
        f("ggx", &Ggx::new(a).unwrap());
        f("beckmann", &Beckmann::new(a).unwrap());
    }
}

// ---------------------------------------------------------------- distributions

#[test]
fn ndf_projected_area_is_one() {
    let mut worst = 0.0f64;
    for_each_distribution(|name, d| {
        let a = d.alpha() as f64;
        let v = integrate_theta(a, 64, &mut |t| {
            d.d(dir(t, 0.0)) as f64 * t.cos() * t.sin() * TAU64
        });
        worst = worst.max((v - 1.0).abs());
        assert!((v - 1.0).abs() < 2e-6, "{name} α={a}: ∫D cos = {v}");
    });
    println!("NDF normalisation: worst |∫D cos − 1| = {worst:.2e}");
}

/// Closed-form `D` (f64, written from Walter et al. 2007 eq. 25 / 33).
#[test]
fn ndf_matches_closed_form_and_extremes() {
    let mut worst = 0.0f64;
    for &a in &[1e-4f32, 1e-3, 0.01, 0.3, 1.0] {
        let (g, b) = (Ggx::new(a).unwrap(), Beckmann::new(a).unwrap());
        let a = a as f64;
        for i in 0..=200 {
            let t = (i as f64 / 200.0) * FRAC_PI_2 * 0.999;
            let m = dir(t, 1.0);
            let (c, tn) = (m.z as f64, (t.sin() / t.cos()));
            let c = c.max(1e-300);
            let gr = a * a / (PI64 * c.powi(4) * (a * a + tn * tn).powi(2));
            let br = (-(tn * tn) / (a * a)).exp() / (PI64 * a * a * c.powi(4));
            for (name, v, r) in [("ggx", g.d(m) as f64, gr), ("beckmann", b.d(m) as f64, br)] {
                assert!(v.is_finite() && v >= 0.0);
                if r > 1e-30 {
                    let e = (v - r).abs() / r;
                    worst = worst.max(e);
                    assert!(e < 1e-4, "{name} α={a} θ={t}: {v} vs {r}");
                }
            }
        }
        // Peak 1/(π α²): ≈ 3.2e7 at α = 1e-4, finite.
        for v in [g.d(Vec3::Z), b.d(Vec3::Z)] {
            let r = 1.0 / (PI64 * a * a);
            assert!(((v as f64) - r).abs() < 1e-5 * r, "peak {v} vs {r}");
        }
        // Grazing, below, degenerate, non-unit.
        for m in [
            Vec3::X,
            Vec3::new(1.0, 0.0, 1e-7),
            Vec3::new(0.0, 1.0, -0.2),
            Vec3::ZERO,
        ] {
            assert!(g.d(m).is_finite() && b.d(m).is_finite());
            assert!(g.d(m) >= 0.0 && b.d(m) >= 0.0);
        }
        assert_eq!(g.d(Vec3::X), 0.0);
        assert_eq!(b.d(Vec3::new(0.0, 0.0, -1.0)), 0.0);
        assert_eq!(g.d(Vec3::new(0.0, 0.0, 5.0)), g.d(Vec3::Z));
        assert_eq!(b.d(Vec3::new(0.0, 0.0, 1e-30)), b.d(Vec3::Z));
    }
    println!("D vs closed form: worst relative error {worst:.2e}");
}

/// f64 references for Λ: GGX closed form; Beckmann erf form in f64 written
/// with libm's f64 `erfc` (`erf − 1 = −erfc`), whose cancellation costs only
/// ~2a² f64 ulps — a different evaluation from the f32 continued fraction
/// the code uses for a ≥ 2.
fn lambda_ref(name: &str, alpha: f64, w: Vec3) -> f64 {
    let tn = (w.x as f64).hypot(w.y as f64) / w.z as f64;
    if name == "ggx" {
        return 0.5 * (-1.0 + (1.0 + alpha * alpha * tn * tn).sqrt());
    }
    let a = 1.0 / (alpha * tn);
    0.5 * ((-a * a).exp() / (a * PI64.sqrt()) - libm::erfc(a))
}

#[test]
fn lambda_and_g1_match_references() {
    let mut worst = 0.0f64;
    for_each_distribution(|name, d| {
        let al = d.alpha() as f64;
        for i in 1..400 {
            let t = i as f64 / 400.0 * FRAC_PI_2;
            let w = dir(t, 2.0);
            let r = lambda_ref(name, al, w);
            let v = d.lambda(w) as f64;
            // Conditioning: for Beckmann, Λ ∝ e^{−a²} near a → ∞, so the
            // f32 rounding of the input a alone moves Λ by ~2a² ε relative.
            let tn = (w.x as f64).hypot(w.y as f64) / w.z as f64;
            let a = 1.0 / (al * tn);
            let cond = if name == "ggx" { 1.0 } else { 1.0 + 2.0 * a * a };
            let e = (v - r).abs() / r.max(1e-30) / (cond * f32::EPSILON as f64);
            if r > 1e-30 {
                worst = worst.max(e);
                assert!(e < 16.0, "{name} α={al} θ={t}: Λ {v} vs {r} ({e} units)");
            }
            let g = d.g1(w) as f64;
            assert!((g - 1.0 / (1.0 + r)).abs() < 1e-6, "{name} G1");
        }
        // Grazing: Λ = ∞, G1 = 0; tiny cos: finite and in [0, 1].
        assert_eq!(d.lambda(Vec3::X), f32::INFINITY);
        assert_eq!(d.g1(Vec3::X), 0.0);
        assert_eq!(d.g1(Vec3::ZERO), 0.0);
        assert_eq!(d.lambda(Vec3::Z), 0.0);
        assert_eq!(d.g1(Vec3::Z), 1.0);
        for w in [Vec3::new(1.0, 0.0, 1e-7), Vec3::new(0.3, -0.2, 1e-30)] {
            let g = d.g1(w);
            assert!((0.0..=1.0).contains(&g), "{name} {w:?}: {g}");
        }
    });
    println!("Λ vs f64 reference: worst error {worst:.2} units of ε·(1 + 2a²)");
}

/// Smith weak white furnace `∫ G1(ωo) ⟨ωo·m⟩ D(m) dm = cos θo` (Heitz 2014,
/// eq. 18), with the φ integral of the clamped cosine in closed form.
#[test]
fn weak_white_furnace() {
    let mut worst = 0.0f64;
    for_each_distribution(|name, d| {
        let al = d.alpha() as f64;
        for &to in &[0.0f64, 0.3, 0.8, 1.2, 1.45, 1.55] {
            let wo = dir(to, 0.0);
            let (so, co) = ((wo.x as f64), (wo.z as f64));
            let proj = integrate_theta(al, 64, &mut |t| {
                d.d(dir(t, 0.0)) as f64 * clamped_cos_phi_integral(co * t.cos(), so * t.sin()) * t.sin()
            });
            let v = d.g1(wo) as f64 * proj;
            let e = (v - co).abs() / co;
            worst = worst.max(e);
            assert!(e < 2e-5, "{name} α={al} θo={to}: {v} vs {co}");
        }
    });
    println!("weak white furnace: worst relative error {worst:.2e}");
}

/// `visible_pdf` integrates to one over the hemisphere of `m` (2-D
/// quadrature; φ over the support of ⟨ωo·m⟩ only).
#[test]
fn visible_pdf_integrates_to_one() {
    let mut worst = 0.0f64;
    for_each_distribution(|name, d| {
        let al = d.alpha() as f64;
        for &(to, po) in &[(0.0f64, 0.0f64), (0.7, 1.0), (1.3, 4.0), (1.55, 2.5)] {
            let wo = dir(to, po);
            let total = integrate_theta(al, 32, &mut |t| {
                let (a, b) = (to.cos() * t.cos(), to.sin() * t.sin());
                let half = if b <= a.abs() {
                    if a > 0.0 { PI64 } else { 0.0 }
                } else {
                    (-a / b).acos()
                };
                if half == 0.0 {
                    return 0.0;
                }
                let inner = simpson(&mut |p| d.visible_pdf(wo, dir(t, po + p)) as f64, -half, half, 64);
                inner * t.sin()
            });
            worst = worst.max((total - 1.0).abs());
            assert!((total - 1.0).abs() < 1e-3, "{name} α={al} θo={to}: {total}");
        }
    });
    println!("∫ visible_pdf dm: worst |error| = {worst:.2e}");
}

/// Moments of `sample_visible` against quadrature of `visible_pdf`
/// (five test functions, 5σ tolerance), plus edge samples.
#[test]
fn visible_sampling_matches_density() {
    let n = 1 << 17;
    for_each_distribution(|name, d| {
        let al = d.alpha() as f64;
        for &(to, po) in &[(0.0f64, 0.0f64), (0.9, 0.5), (1.4, 2.0)] {
            let wo = dir(to, po);
            let gs: [fn(Vec3) -> f64; 5] = [
                |m| m.z as f64,
                |m| m.x as f64,
                |m| m.y as f64,
                |m| (m.z as f64).powi(8),
                |m| (m.x as f64) * (m.z as f64),
            ];
            // Quadrature references.
            let mut refs = [0.0f64; 5];
            for (k, g) in gs.iter().enumerate() {
                refs[k] = integrate_theta(al, 32, &mut |t| {
                    simpson(
                        &mut |p| d.visible_pdf(wo, dir(t, p)) as f64 * g(dir(t, p)),
                        0.0,
                        TAU64,
                        128,
                    ) * t.sin()
                });
            }
            // Stratified-by-row sample means (a simple (0,2)-ish grid).
            let side = 1 << 8;
            let mut sums = [0.0f64; 5];
            let mut sq = [0.0f64; 5];
            let mut state = 0x9e3779b97f4a7c15u64;
            for i in 0..n {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                let j = (state >> 40) as f32 / (1u64 << 24) as f32;
                let u = [
                    ((i % side) as f32 + j) / side as f32,
                    ((i / side) as f32 + 0.5) / (n / side) as f32,
                ];
                let m = d.sample_visible(wo, u);
                assert!(m.is_finite() && m.z >= 0.0 && (m.length() - 1.0).abs() < 1e-5);
                for (k, g) in gs.iter().enumerate() {
                    let v = g(m);
                    sums[k] += v;
                    sq[k] += v * v;
                }
            }
            for k in 0..5 {
                let mean = sums[k] / n as f64;
                let var = (sq[k] / n as f64 - mean * mean).max(0.0);
                let se = (var / n as f64).sqrt();
                assert!(
                    (mean - refs[k]).abs() < 5.0 * se + 2e-4,
                    "{name} α={al} θo={to} g{k}: mean {mean} vs {} (se {se})",
                    refs[k]
                );
            }
        }
        for &a in &[0.0f32, 1e-7, 0.5, ONE_MINUS_EPSILON, 1.0] {
            for &b in &[0.0f32, 1e-7, 0.5, ONE_MINUS_EPSILON, 1.0] {
                for wo in [
                    Vec3::Z,
                    Vec3::X,
                    Vec3::new(0.0, 1.0, 1e-7),
                    Vec3::new(0.3, 0.1, -0.5),
                ] {
                    let m = d.sample_visible(wo, [a, b]);
                    assert!(m.is_finite() && m.z >= 0.0, "{name} {wo:?} {a} {b}: {m:?}");
                    assert!((m.length() - 1.0).abs() < 1e-5);
                }
            }
        }
    });
}

// ---------------------------------------------------------------- Fresnel

/// Independent f64 dielectric Fresnel from Snell's law and the angle form
/// (Born & Wolf §1.5.2): ½ (sin²(θi−θt)/sin²(θi+θt) + tan²(θi−θt)/tan²(θi+θt)).
fn dielectric_ref(cos_i: f64, eta: f64) -> f64 {
    let ti = cos_i.acos();
    let st = ti.sin() / eta;
    if st >= 1.0 {
        return 1.0;
    }
    if ti == 0.0 {
        return ((eta - 1.0) / (eta + 1.0)).powi(2);
    }
    let tt = st.asin();
    let rs = ((ti - tt).sin() / (ti + tt).sin()).powi(2);
    let rp = ((ti - tt).tan() / (ti + tt).tan()).powi(2);
    0.5 * (rs + rp)
}

/// Independent f64 conductor Fresnel in the real `a² + b²` form
/// (PBR 3rd ed. §8.2.1, after Lazányi & Szirmay-Kalos 2005).
fn conductor_ref(cos_i: f64, eta: f64, k: f64) -> f64 {
    let c2 = cos_i * cos_i;
    let s2 = 1.0 - c2;
    let t0 = eta * eta - k * k - s2;
    let a2b2 = (t0 * t0 + 4.0 * eta * eta * k * k).sqrt();
    let a = (0.5 * (a2b2 + t0)).max(0.0).sqrt();
    let rs = (a2b2 + c2 - 2.0 * a * cos_i) / (a2b2 + c2 + 2.0 * a * cos_i);
    let t1 = c2 * a2b2 + s2 * s2;
    let t2 = 2.0 * a * cos_i * s2;
    let rp = rs * (t1 - t2) / (t1 + t2);
    0.5 * (rs + rp)
}

#[test]
fn fresnel_closed_forms() {
    // Schlick.
    let s = Schlick::new(Vec3::new(0.02, 0.5, 1.0)).unwrap();
    assert_eq!(s.eval(1.0), Vec3::new(0.02, 0.5, 1.0));
    assert_eq!(s.eval(0.0), Vec3::ONE);
    assert_eq!(s.eval(-0.3), Vec3::ONE);
    assert_eq!(s.eval(f32::NAN), Vec3::ONE);
    let s1 = Schlick::new(0.04f32).unwrap();
    assert!((s1.eval(0.5) - (0.04 + 0.96 * 0.5f32.powi(5))).abs() < 1e-7);
    // Dielectric.
    let mut worst_d = 0.0f64;
    for &eta in &[1.0f32, 1.33, 1.5, 2.4, 1.0 / 1.5, 0.2, 50.0] {
        let d = Dielectric::new(eta).unwrap();
        let f0 = ((eta as f64 - 1.0) / (eta as f64 + 1.0)).powi(2);
        assert!((d.eval(1.0) as f64 - f0).abs() < 1e-6, "η={eta}");
        assert_eq!(d.eval(0.0), 1.0, "grazing η={eta}");
        for i in 1..1000 {
            let c = i as f64 / 1000.0;
            let v = d.eval(c as f32) as f64;
            let r = dielectric_ref(c as f32 as f64, eta as f64);
            worst_d = worst_d.max((v - r).abs());
            assert!((v - r).abs() < 2e-5, "η={eta} cos={c}: {v} vs {r}");
        }
    }
    // Total internal reflection beyond the critical angle (η < 1).
    let tir = Dielectric::new(1.0 / 1.5).unwrap();
    let crit = (1.0f64 - (1.0 / 1.5f64).powi(2)).sqrt(); // cos θc
    for i in 0..100 {
        let c = crit * (i as f64 / 100.0) * 0.999;
        assert_eq!(tir.eval(c as f32), 1.0);
    }
    assert!(tir.eval((crit * 1.01) as f32) < 1.0);
    // Conductor.
    let mut worst_c = 0.0f64;
    for &(eta, k) in &[
        (0.2f32, 3.0f32),
        (1.5, 0.0),
        (0.05, 5.0),
        (2.5, 1.0),
        (1.0, 1e-3),
        (100.0, 500.0),
        // The corners of the accepted domain (largest and smallest |η + ik|).
        (1e-3, 0.0),
        (1e-3, 1e3),
        (1e3, 0.0),
        (1e3, 1e3),
    ] {
        let c = Conductor::new(eta, k).unwrap();
        let (e, kk) = (eta as f64, k as f64);
        let f0 = ((e - 1.0).powi(2) + kk * kk) / ((e + 1.0).powi(2) + kk * kk);
        assert!((c.eval(1.0) as f64 - f0).abs() < 1e-5, "η={eta} k={k}");
        assert!((c.eval(0.0) - 1.0).abs() < 1e-6, "grazing η={eta} k={k}");
        for i in 1..1000 {
            let ci = i as f64 / 1000.0;
            let v = c.eval(ci as f32) as f64;
            let r = conductor_ref(ci as f32 as f64, e, kk);
            worst_c = worst_c.max((v - r).abs());
            assert!((v - r).abs() < 5e-5, "η={eta} k={k} cos={ci}: {v} vs {r}");
        }
    }
    // A conductor with k = 0 is a dielectric, including TIR.
    let c = Conductor::new(1.0f32 / 1.5, 0.0).unwrap();
    for i in 0..=100 {
        let ci = i as f32 / 100.0;
        assert!((c.eval(ci) - tir.eval(ci)).abs() < 1e-5, "cos {ci}");
    }
    // Spectral conductor, channel-wise.
    let cv = Conductor::new(Vec3::new(0.2, 0.9, 1.1), Vec3::new(3.0, 2.5, 2.2)).unwrap();
    let v = cv.eval(0.7);
    assert!((v.y - Conductor::new(0.9f32, 2.5).unwrap().eval(0.7)).abs() < 1e-7);
    println!("Fresnel: worst |dielectric − ref| = {worst_d:.2e}, |conductor − ref| = {worst_c:.2e}");
}

/// A conductor of several channels evaluates them four at a time
/// (`fr_complex4`): each channel must be bit for bit the one-channel
/// conductor of that channel's `η`, `k` (RGB, 4 and 6 channels, a sweep of
/// cosines with the edges and out-of-range values).
#[test]
fn multichannel_conductor_is_the_one_channel_conductor_bit_for_bit() {
    use radiometry::SampledSpectrum;
    let etas = [0.2f32, 0.9, 1.1, 1.5, 1e-3, 1e3];
    let ks = [3.0f32, 2.5, 2.2, 0.0, 1e3, 0.5];
    let rgb = Conductor::new(
        Vec3::new(etas[0], etas[1], etas[2]),
        Vec3::new(ks[0], ks[1], ks[2]),
    )
    .unwrap();
    let s4 = Conductor::new(
        SampledSpectrum([etas[0], etas[3], etas[4], etas[5]]),
        SampledSpectrum([ks[0], ks[3], ks[4], ks[5]]),
    )
    .unwrap();
    let s6 = Conductor::new(SampledSpectrum(etas), SampledSpectrum(ks)).unwrap();
    let one = |i: usize, c: f32| Conductor::new(etas[i], ks[i]).unwrap().eval(c).to_bits();
    let mut cosines: std::vec::Vec<f32> = (0..=4000).map(|i| i as f32 / 4000.0).collect();
    cosines.extend([-0.5, 1.5, f32::NAN, 1e-30, 1.0 - f32::EPSILON]);
    for c in cosines {
        let v = rgb.eval(c);
        for (ch, i) in [(v.x, 0), (v.y, 1), (v.z, 2)] {
            assert_eq!(ch.to_bits(), one(i, c), "rgb channel {i} at cos {c}");
        }
        let v = s4.eval(c);
        for (j, i) in [0usize, 3, 4, 5].into_iter().enumerate() {
            assert_eq!(v.0[j].to_bits(), one(i, c), "4-channel lane {j} at cos {c}");
        }
        let v = s6.eval(c);
        for i in 0..6 {
            assert_eq!(v.0[i].to_bits(), one(i, c), "6-channel lane {i} at cos {c}");
        }
    }
}

#[test]
fn constructors_reject_invalid() {
    for a in [0.0f32, -0.1, 1e-5, 1.5, f32::NAN, f32::INFINITY] {
        assert!(Ggx::new(a).is_err(), "{a}");
        assert!(Beckmann::new(a).is_err(), "{a}");
    }
    assert!(Ggx::new(MIN_ALPHA).is_ok() && Beckmann::new(MAX_ALPHA).is_ok());
    assert!(Schlick::new(-0.1f32).is_err());
    assert!(Schlick::new(Vec3::new(0.5, f32::NAN, 0.5)).is_err());
    assert!(Dielectric::new(0.0).is_err() && Dielectric::new(f32::NAN).is_err());
    assert!(Conductor::new(0.0f32, 1.0).is_err());
    assert!(Conductor::new(1.0f32, -1.0).is_err());
    assert!(Conductor::new(1.0f32, f32::INFINITY).is_err());
    let e = Ggx::new(2.0).unwrap_err();
    assert_eq!(
        std::format!("{e}"),
        "parameter `alpha` = 2 is outside [0.0001, 1]"
    );
}

// ---------------------------------------------------------------- BRDF

type GgxHc = Microfacet<Ggx, HeightCorrelated, NoFresnel>;
type GgxSep = Microfacet<Ggx, Separable, NoFresnel>;

/// GGX α = 1 at normal incidence with F = 1: directional albedo
/// `∫ f cos θi dωi = 1 − ln 2`.
///
/// Derivation (ours): at ωo = +Z, α = 1, `D ≡ 1/π`, `Λ(ωo) = 0`, so both G2
/// variants reduce to `G1(ωi) = 2 cos θi / (1 + cos θi)` — the identity holds
/// for height-correlated AND separable Smith alike. With `θi = 2θm` and
/// `dωi = 4 cos θm dωm`: `ρ = ∫_0^{π/4} 2 cos 2θ tan θ dθ
/// = [2c² − 2 ln c]_{1/√2}^{1} = 1 − ln 2`.
/// Away from normal incidence they differ (checked: HC > separable).
#[test]
fn ggx_alpha1_normal_incidence_albedo_is_one_minus_ln2() {
    let expected = 1.0 - core::f64::consts::LN_2;
    let hc: GgxHc = Microfacet::new(Ggx::new(1.0).unwrap(), NoFresnel);
    let sep: GgxSep = Microfacet::new(Ggx::new(1.0).unwrap(), NoFresnel);
    let albedo = |b: &dyn Fn(Vec3) -> f32| {
        integrate_theta(1.0, 128, &mut |t| {
            simpson(&mut |p| b(dir(t, p)) as f64, 0.0, TAU64, 16) * t.cos() * t.sin()
        })
    };
    let a_hc = albedo(&|wi| hc.eval(wi, Vec3::Z));
    let a_sep = albedo(&|wi| sep.eval(wi, Vec3::Z));
    println!("GGX α=1 normal-incidence albedo: HC {a_hc:.7}, separable {a_sep:.7}, 1−ln2 = {expected:.7}");
    assert!((a_hc - expected).abs() < 1e-5, "{a_hc}");
    assert!((a_sep - expected).abs() < 1e-5, "{a_sep}");
    // Off normal incidence the two differ, with HC ≥ separable.
    let wo = dir(1.0, 0.0);
    let off_hc = albedo(&|wi| hc.eval(wi, wo));
    let off_sep = albedo(&|wi| sep.eval(wi, wo));
    assert!(off_hc > off_sep + 1e-3, "{off_hc} {off_sep}");
}

fn brdfs_under_test() -> Vec<(std::string::String, std::boxed::Box<dyn Brdf<Spectrum = f32>>)> {
    let mut v: Vec<(std::string::String, std::boxed::Box<dyn Brdf<Spectrum = f32>>)> = Vec::new();
    for &a in &[1e-4f32, 0.01, 0.1, 0.5, 1.0] {
        let g = Ggx::new(a).unwrap();
        let b = Beckmann::new(a).unwrap();
        v.push((
            std::format!("ggx-hc α={a}"),
            std::boxed::Box::new(GgxHc::new(g, NoFresnel)),
        ));
        v.push((
            std::format!("ggx-sep-diel α={a}"),
            std::boxed::Box::new(Microfacet::<_, Separable, _>::new(
                g,
                Dielectric::new(1.5).unwrap(),
            )),
        ));
        v.push((
            std::format!("beck-hc-cond α={a}"),
            std::boxed::Box::new(Microfacet::<_, HeightCorrelated, _>::new(
                b,
                Conductor::new(0.2f32, 3.0).unwrap(),
            )),
        ));
        v.push((
            std::format!("beck-sep-schlick α={a}"),
            std::boxed::Box::new(Microfacet::<_, Separable, _>::new(
                b,
                Schlick::new(0.04f32).unwrap(),
            )),
        ));
    }
    v
}

#[test]
fn sample_pdf_weight_consistency() {
    let mut worst_w = 0.0f64;
    let mut count = 0usize;
    for (name, b) in brdfs_under_test() {
        for &to in &[0.0f32, 0.5, 1.2, 1.5, core::f32::consts::FRAC_PI_2 - 1e-6] {
            let wo = dir(to as f64, 0.7);
            for i in 0..32 {
                for j in 0..32 {
                    let u = [(i as f32 + 0.5) / 32.0, (j as f32 + 0.37) / 32.0];
                    let Some(s) = b.sample(wo, u) else { continue };
                    count += 1;
                    assert!(s.pdf > 0.0 && s.pdf.is_finite(), "{name}");
                    assert!(s.wi.z > 0.0 && (s.wi.length() - 1.0).abs() < 1e-5);
                    assert_eq!(s.pdf, b.pdf(s.wi, wo), "{name}");
                    let f = b.eval(s.wi, wo) as f64;
                    let expect = f * s.wi.z as f64 / s.pdf as f64;
                    let e = (s.weight as f64 - expect).abs() / expect.max(1e-6);
                    worst_w = worst_w.max(e);
                    assert!(
                        e < 1e-4,
                        "{name} θo={to} u={u:?}: weight {} vs {expect}",
                        s.weight
                    );
                    assert!(s.weight >= 0.0 && s.weight <= 1.0 + 1e-6);
                }
            }
        }
    }
    println!("sample/pdf/weight: {count} samples, worst weight relative error {worst_w:.2e}");
}

/// `∫ pdf(ωi) dωi` over the upper hemisphere equals `1 − P_below`, where
/// `P_below` is computed separately as the visible-normal mass whose mirror
/// direction points below the horizon (quadrature over m, with the φ range
/// of that region found in closed form), and also equals the fraction of
/// `sample` calls that return `Some` (stratified, 512² samples).
#[test]
fn brdf_pdf_mass_matches_below_horizon_loss() {
    let mut worst = 0.0f64;
    for &a in &[0.1f32, 0.5, 1.0] {
        let g = GgxHc::new(Ggx::new(a).unwrap(), NoFresnel);
        let b = Microfacet::<_, HeightCorrelated, _>::new(Beckmann::new(a).unwrap(), NoFresnel);
        let list: [(&str, &dyn Brdf<Spectrum = f32>, &dyn MicrofacetDistribution); 2] =
            [("ggx", &g, &g.distribution), ("beckmann", &b, &b.distribution)];
        for (name, br, d) in list {
            for &to in &[0.0f64, 0.6, 1.1, 1.45] {
                let wo = dir(to, 0.0);
                let (so, co) = (wo.x as f64, wo.z as f64);
                // m = (sin t cos φ, sin t sin φ, cos t); ωo·m = A + B cos φ.
                // Visible: cos φ > c_lo = −A/B. Below: 2(ωo·m) cos t ≤ cos θo,
                // i.e. cos φ ≤ c_hi = (cos θo/(2 cos t) − A)/B.
                let bounds = |t: f64| -> (f64, f64) {
                    let (aa, bb) = (co * t.cos(), so * t.sin());
                    let lim = co / (2.0 * t.cos()) - aa;
                    if bb <= 1e-300 {
                        return if aa > 0.0 && lim >= 0.0 {
                            (-1.0, 1.0)
                        } else {
                            (1.0, -1.0)
                        };
                    }
                    (-aa / bb, lim / bb)
                };
                // The φ-range opens/closes with square-root behaviour where c_lo
                // or c_hi crosses ±1 or they cross each other: find those θm
                // and use them as panel edges, with panels graded toward them.
                let mut breaks = panels(a as f64);
                let events = |t: f64| {
                    let (l, h) = bounds(t);
                    [l + 1.0, l - 1.0, h + 1.0, h - 1.0, h - l]
                };
                let grid = 4000;
                for k in 0..grid {
                    let (t0, t1) = (
                        FRAC_PI_2 * k as f64 / grid as f64,
                        FRAC_PI_2 * (k + 1) as f64 / grid as f64,
                    );
                    let (e0, e1) = (events(t0), events(t1));
                    for q in 0..5 {
                        if e0[q].signum() != e1[q].signum() && e0[q].is_finite() && e1[q].is_finite() {
                            let (mut lo, mut hi) = (t0, t1);
                            for _ in 0..80 {
                                let mid = 0.5 * (lo + hi);
                                if events(mid)[q].signum() == e0[q].signum() {
                                    lo = mid
                                } else {
                                    hi = mid
                                }
                            }
                            breaks.push(0.5 * (lo + hi));
                        }
                    }
                }
                if to == 0.0 {
                    breaks.push(core::f64::consts::FRAC_PI_4);
                }
                breaks.sort_by(|x, y| x.partial_cmp(y).unwrap());
                let mut p_below = 0.0;
                for w in breaks.windows(2) {
                    p_below += graded(w[0], w[1], &mut |t| {
                        let (l, h) = bounds(t);
                        let (c_lo, c_hi) = (l.max(-1.0), h.min(1.0));
                        if c_hi <= c_lo {
                            return 0.0;
                        }
                        let (p0, p1) = (c_hi.acos(), c_lo.acos());
                        2.0 * simpson(&mut |p| d.visible_pdf(wo, dir(t, p)) as f64, p0, p1, 32) * t.sin()
                    });
                }
                let mass = pdf_mass(br, wo, to);
                let n = 1024;
                let mut some = 0usize;
                for i in 0..n {
                    for j in 0..n {
                        let u = [(i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32];
                        some += br.sample(wo, u).is_some() as usize;
                    }
                }
                let frac = some as f64 / (n * n) as f64;
                println!(
                    "{name} α={a} θo={to}: ∫pdf dωi = {mass:.7}, 1 − P_below = {:.7}, P(Some) = {frac:.6}",
                    1.0 - p_below
                );
                worst = worst.max((mass - (1.0 - p_below)).abs());
                assert!((mass - (1.0 - p_below)).abs() < 2e-5, "{name} α={a} θo={to}");
                // A midpoint grid misclassifies only cells cut by the region's
                // boundary in u-space: O(1/n).
                assert!((frac - (1.0 - p_below)).abs() < 2e-3, "{name} α={a} θo={to}");
                if to == 0.0 {
                    // Closed forms at normal incidence: P(θm ≤ π/4) under D cos θm.
                    let a2 = (a as f64) * (a as f64);
                    let exact = if name == "ggx" {
                        1.0 / (1.0 + a2)
                    } else {
                        1.0 - (-1.0 / a2).exp()
                    };
                    assert!((mass - exact).abs() < 2e-5, "{name} α={a}: {mass} vs {exact}");
                }
            }
        }
    }
    println!("pdf mass vs 1 − P_below: worst |error| = {worst:.2e}");
}

fn pdf_mass(b: &dyn Brdf<Spectrum = f32>, wo: Vec3, to: f64) -> f64 {
    // ωi integral on θ panels graded around the mirror direction; the lobe
    // is narrow in φ near grazing, hence the fine φ grid.
    let mut total = 0.0;
    let mut edges = std::vec![0.0];
    for k in -6..=6 {
        let t = to + (k as f64) * 0.05 * (k as f64).abs();
        if t > 0.0 && t < FRAC_PI_2 {
            edges.push(t);
        }
    }
    edges.push(FRAC_PI_2);
    edges.sort_by(|x, y| x.partial_cmp(y).unwrap());
    for w in edges.windows(2) {
        total += simpson(
            &mut |t| simpson(&mut |p| b.pdf(dir(t, p), wo) as f64, -PI64, PI64, 4096) * t.sin(),
            w[0],
            w[1],
            64,
        );
    }
    total
}

/// Monte Carlo directional albedo (mean sample weight, counting `None` as 0)
/// equals the quadrature of `f cos θi`: sampling is unbiased.
#[test]
fn sampled_albedo_matches_quadrature() {
    for &a in &[0.2f32, 0.7] {
        let b = Microfacet::<_, Separable, _>::new(Beckmann::new(a).unwrap(), Dielectric::new(1.5).unwrap());
        let g = GgxHc::new(Ggx::new(a).unwrap(), NoFresnel);
        let list: [(&str, &dyn Brdf<Spectrum = f32>); 2] = [("beckmann", &b), ("ggx", &g)];
        for (name, br) in list {
            for &to in &[0.3f64, 1.2] {
                let wo = dir(to, 0.0);
                let quad = integrate_theta(1.0, 64, &mut |t| {
                    simpson(&mut |p| br.eval(dir(t, p), wo) as f64, 0.0, TAU64, 512) * t.cos() * t.sin()
                });
                let n = 512usize;
                let mut sum = 0.0f64;
                for i in 0..n {
                    for j in 0..n {
                        let u = [(i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32];
                        if let Some(s) = br.sample(wo, u) {
                            sum += s.weight as f64;
                        }
                    }
                }
                let mc = sum / (n * n) as f64;
                println!("{name} α={a} θo={to}: albedo quad {quad:.5} sampled {mc:.5}");
                assert!((mc - quad).abs() < 2e-3, "{name} α={a} θo={to}: {mc} vs {quad}");
            }
        }
    }
}

#[test]
fn eval_is_robust_at_edges() {
    let eps = ONE_MINUS_EPSILON;
    let dirs = [
        Vec3::Z,
        Vec3::X,
        Vec3::new(1.0, 0.0, 1e-7),
        Vec3::new(0.0, -1.0, 1e-7),
        Vec3::new(-1.0, 0.0, 1e-7),
        Vec3::new(0.6, 0.0, 0.8) * 3.0,
        Vec3::new(0.6, 0.0, 0.8) * 1e-20,
        Vec3::new(0.0, 0.6, -0.8),
        Vec3::ZERO,
        Vec3::new(1e-30, 0.0, 1e-30),
        Vec3::new(1.0, 0.0, 1e-30),
        Vec3::new(-1.0, 0.0, 1e-30),
    ];
    for (name, b) in brdfs_under_test() {
        for &wi in &dirs {
            for &wo in &dirs {
                for (x, y) in [(wi, wo), (wi, -wi), (wi, wi)] {
                    let f = b.eval(x, y);
                    let p = b.pdf(x, y);
                    assert!(f.is_finite() && f >= 0.0, "{name} {x:?} {y:?}: f={f}");
                    assert!(p.is_finite() && p >= 0.0, "{name} {x:?} {y:?}: pdf={p}");
                    if x.z <= 0.0 || y.z <= 0.0 {
                        assert_eq!(f, 0.0);
                        assert_eq!(p, 0.0);
                    }
                }
            }
            for u0 in [0.0f32, 1e-7, 0.5, eps, 1.0] {
                for u1 in [0.0f32, 1e-7, 0.5, eps, 1.0] {
                    if let Some(s) = b.sample(wi, [u0, u1]) {
                        assert!(s.wi.is_finite() && s.pdf.is_finite() && s.pdf > 0.0, "{name}");
                        assert!(s.weight.is_finite() && s.weight >= 0.0, "{name}");
                    }
                }
            }
        }
        // wi = −wo: no half vector.
        let w = Vec3::new(0.3, 0.4, 0.866);
        assert_eq!(b.eval(-w, w), 0.0);
        // Reciprocity on a small grid.
        for &(a, c) in &[
            (0.2f64, 1.0f64),
            (1.4, 0.1),
            (FRAC_PI_2 - 1e-7, FRAC_PI_2 - 1e-7),
            (0.0, 0.7),
        ] {
            let (x, y) = (dir(a, 0.3), dir(c, 2.0));
            let (f1, f2) = (b.eval(x, y), b.eval(y, x));
            assert!(
                (f1 - f2).abs() <= 1e-5 * f1.max(f2) + 1e-30,
                "{name}: {f1} vs {f2}"
            );
        }
    }
}

#[test]
fn isotropic_form_matches_eval() {
    let b = Microfacet::<_, HeightCorrelated, _>::new(Ggx::new(0.3).unwrap(), Schlick::new(0.5f32).unwrap());
    for &(ti, to, dp) in &[(0.2f32, 0.5f32, 1.0f32), (1.0, 0.3, 3.0), (1.5, 1.5, 3.1)] {
        let direct = b.eval(
            radiometry::frame::spherical_direction(ti, 0.4),
            radiometry::frame::spherical_direction(to, 0.4 + dp),
        );
        let iso = b.eval_isotropic(ti, to, dp);
        assert!((direct - iso).abs() <= 1e-4 * direct.max(1e-6), "{direct} {iso}");
    }
}

/// Upper quantile of the χ² distribution with `k` degrees of freedom at
/// upper-tail probability `p` (Wilson & Hilferty 1931 cube-root normal
/// approximation; the normal quantile by bisection on libm's f64 `erfc`).
fn chi2_critical(k: f64, p: f64) -> f64 {
    let (mut lo, mut hi) = (0.0f64, 40.0f64);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        // upper tail of N(0,1) at mid is erfc(mid/√2)/2
        if 0.5 * libm::erfc(mid / core::f64::consts::SQRT_2) > p {
            lo = mid
        } else {
            hi = mid
        }
    }
    let z = 0.5 * (lo + hi);
    let c = 2.0 / (9.0 * k);
    k * (1.0 - c + z * c.sqrt()).powi(3)
}

/// χ² goodness of fit of `sample_visible` against cell integrals of
/// `visible_pdf` (2-D Simpson per cell). Cells: θm edges `atan(α s)` for a
/// fixed list of `s`, 16 φ sectors; cells with expected count < 5 pooled.
/// Significance 0.01 with Šidák correction over all cases.
#[test]
fn visible_sampling_chi_square() {
    let n = 200_000usize;
    let s_edges = [
        0.0f64,
        0.25,
        0.5,
        0.75,
        1.0,
        1.5,
        2.0,
        3.0,
        4.0,
        6.0,
        10.0,
        20.0,
        f64::INFINITY,
    ];
    let nphi = 16;
    let cases: Vec<(f32, f64)> = [0.01f32, 0.1, 0.5, 1.0]
        .iter()
        .flat_map(|&a| [0.0f64, 1.0, 1.5].into_iter().map(move |t| (a, t)))
        .collect();
    let n_tests = (cases.len() * 2) as f64;
    let alpha_sidak = 1.0 - (1.0 - 0.01f64).powf(1.0 / n_tests);
    let mut state = 0x2545f4914f6cdd1du64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 40) as f32 / (1u64 << 24) as f32
    };
    let mut min_margin = f64::INFINITY;
    for &(a, to) in &cases {
        let ds: [(&str, &dyn MicrofacetDistribution); 2] = [
            ("ggx", &Ggx::new(a).unwrap()),
            ("beckmann", &Beckmann::new(a).unwrap()),
        ];
        for (name, d) in ds {
            let wo = dir(to, 0.3);
            let th_edges: Vec<f64> = s_edges.iter().map(|&s| (a as f64 * s).atan()).collect();
            let nth = th_edges.len() - 1;
            let mut expected = std::vec![0.0f64; nth * nphi];
            for i in 0..nth {
                for j in 0..nphi {
                    let (p0, p1) = (
                        TAU64 * j as f64 / nphi as f64,
                        TAU64 * (j + 1) as f64 / nphi as f64,
                    );
                    expected[i * nphi + j] = n as f64
                        * simpson(
                            &mut |t| {
                                simpson(&mut |p| d.visible_pdf(wo, dir(t, p)) as f64, p0, p1, 16) * t.sin()
                            },
                            th_edges[i],
                            th_edges[i + 1],
                            32,
                        );
                }
            }
            let mut observed = std::vec![0.0f64; nth * nphi];
            for _ in 0..n {
                let m = d.sample_visible(wo, [next(), next()]);
                let t = (m.x as f64).hypot(m.y as f64).atan2(m.z as f64);
                let mut p = (m.y as f64).atan2(m.x as f64);
                if p < 0.0 {
                    p += TAU64;
                }
                let i = th_edges.partition_point(|&e| e <= t).clamp(1, nth) - 1;
                let j = ((p / TAU64 * nphi as f64) as usize).min(nphi - 1);
                observed[i * nphi + j] += 1.0;
            }
            // Pool small cells (in index order) until expected ≥ 5.
            let (mut chi2, mut dof) = (0.0f64, 0usize);
            let (mut eo, mut ee) = (0.0f64, 0.0f64);
            for k in 0..expected.len() {
                eo += observed[k];
                ee += expected[k];
                if ee >= 5.0 {
                    chi2 += (eo - ee).powi(2) / ee;
                    dof += 1;
                    eo = 0.0;
                    ee = 0.0;
                }
            }
            if ee > 0.0 || eo > 0.0 {
                // Remainder: fold into the statistic as its own cell if it has mass.
                if ee > 0.0 {
                    chi2 += (eo - ee).powi(2) / ee;
                    dof += 1;
                } else {
                    assert!(eo < 5.0, "{name}: samples where the density is zero");
                }
            }
            let crit = chi2_critical((dof - 1) as f64, alpha_sidak);
            min_margin = min_margin.min(crit - chi2);
            println!(
                "χ² {name} α={a} θo={to}: {chi2:.1} (dof {}), critical {crit:.1}",
                dof - 1
            );
            assert!(
                chi2 < crit,
                "{name} α={a} θo={to}: χ² = {chi2} ≥ {crit} (dof {})",
                dof - 1
            );
        }
    }
}

/// Randomised sweep over extreme finite inputs (components drawn from
/// `{0, ±1e-38, ±1e-20, ±1e-7, ±0.3, ±1, ±1e20, ±3e38}`, any `u` in
/// `{0, 1e-7, 0.5, 1 − ε, 1}` or uniform): every output finite and
/// non-negative (Λ may be +∞ by contract), samplers return unit vectors.
#[test]
fn extreme_inputs_never_nan() {
    const MAGS: [f32; 8] = [0.0, 1e-38, 1e-20, 1e-7, 0.3, 1.0, 1e20, 3e38];
    const US: [f32; 5] = [0.0, 1e-7, 0.5, ONE_MINUS_EPSILON, 1.0];
    let mut state = 0x853c49e6748fea9bu64;
    let mut rnd = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    let vec = |r: &mut dyn FnMut() -> u64| {
        let mut c = [0.0f32; 3];
        for x in &mut c {
            let k = r();
            let m = MAGS[(k % 8) as usize];
            *x = if (k >> 8) & 1 == 1 { -m } else { m };
        }
        Vec3::from_array(c)
    };
    let mut cases = 0usize;
    for &a in &[1e-4f32, 1e-3, 0.5, 1.0] {
        let g = Ggx::new(a).unwrap();
        let b = Beckmann::new(a).unwrap();
        let brdfs: [&dyn Brdf<Spectrum = f32>; 4] = [
            &Microfacet::<_, HeightCorrelated, _>::new(g, NoFresnel),
            &Microfacet::<_, Separable, _>::new(g, Dielectric::new(0.5).unwrap()),
            &Microfacet::<_, HeightCorrelated, _>::new(b, Conductor::new(0.2f32, 3.0).unwrap()),
            &Microfacet::<_, Separable, _>::new(b, Schlick::new(0.04f32).unwrap()),
        ];
        let dists: [&dyn MicrofacetDistribution; 2] = [&g, &b];
        for _ in 0..5000 {
            let (wi, wo) = (vec(&mut rnd), vec(&mut rnd));
            let u = [
                if rnd() % 2 == 0 {
                    US[(rnd() % 5) as usize]
                } else {
                    (rnd() >> 40) as f32 / 16777216.0
                },
                if rnd() % 2 == 0 {
                    US[(rnd() % 5) as usize]
                } else {
                    (rnd() >> 40) as f32 / 16777216.0
                },
            ];
            cases += 1;
            for d in dists {
                for v in [d.d(wi), d.g1(wi), d.visible_pdf(wo, wi)] {
                    assert!(v.is_finite() && v >= 0.0, "{wi:?} {wo:?}: {v}");
                }
                assert!(d.lambda(wi) >= 0.0);
                let m = d.sample_visible(wo, u);
                assert!(
                    m.is_finite() && m.z >= 0.0 && (m.length() - 1.0).abs() < 1e-5,
                    "{wo:?} {u:?}"
                );
            }
            for br in brdfs {
                let f = br.eval(wi, wo);
                let p = br.pdf(wi, wo);
                assert!(f.is_finite() && f >= 0.0, "{wi:?} {wo:?}: f = {f}");
                assert!(p.is_finite() && p >= 0.0, "{wi:?} {wo:?}: pdf = {p}");
                if let Some(s) = br.sample(wo, u) {
                    assert!(s.wi.is_finite() && s.wi.z > 0.0, "{wo:?} {u:?}");
                    assert!(s.pdf.is_finite() && s.pdf > 0.0);
                    assert!(s.weight.is_finite() && s.weight >= 0.0);
                }
            }
        }
    }
    println!("extreme inputs: {cases} cases × (2 distributions + 4 BRDFs)");
}

/// The cheap path equals the full path where both apply: `NoFresnel` vs
/// `Schlick(f0 = 1)`; an RGB Schlick/Conductor BRDF vs three `f32` BRDFs;
/// height-correlated vs separable G2 at normal incidence (`Λ(+Z) = 0`).
#[test]
fn cheap_paths_match_full_paths() {
    let g = Ggx::new(0.35).unwrap();
    let b = Beckmann::new(0.2).unwrap();
    let plain = Microfacet::<_, HeightCorrelated, _>::new(g, NoFresnel);
    let one = Microfacet::<_, HeightCorrelated, _>::new(g, Schlick::new(1.0f32).unwrap());
    let f0 = Vec3::new(0.1, 0.5, 0.9);
    let (eta, k) = (Vec3::new(0.2, 0.9, 1.5), Vec3::new(3.0, 2.5, 0.5));
    let rgb = Microfacet::<_, Separable, _>::new(b, Schlick::new(f0).unwrap());
    let rgb_c = Microfacet::<_, Separable, _>::new(b, Conductor::new(eta, k).unwrap());
    let hc = Microfacet::<_, HeightCorrelated, _>::new(b, NoFresnel);
    let sep = Microfacet::<_, Separable, _>::new(b, NoFresnel);
    for i in 0..40 {
        for j in 0..40 {
            let wi = dir(i as f64 / 40.0 * FRAC_PI_2, j as f64 * 0.3);
            let wo = dir(j as f64 / 40.0 * FRAC_PI_2, 1.0 + i as f64 * 0.2);
            assert_eq!(plain.eval(wi, wo), one.eval(wi, wo));
            let v = rgb.eval(wi, wo);
            let vc = rgb_c.eval(wi, wo);
            for c in 0..3 {
                let single = Microfacet::<_, Separable, _>::new(b, Schlick::new(f0[c]).unwrap());
                assert_eq!(v[c], single.eval(wi, wo));
                let single_c = Microfacet::<_, Separable, _>::new(b, Conductor::new(eta[c], k[c]).unwrap());
                assert_eq!(vc[c], single_c.eval(wi, wo));
            }
            assert!((hc.eval(wi, Vec3::Z) - sep.eval(wi, Vec3::Z)).abs() <= 1e-6 * hc.eval(wi, Vec3::Z));
            let u = [i as f32 / 40.0, j as f32 / 40.0];
            match (plain.sample(wo, u), one.sample(wo, u)) {
                (Some(x), Some(y)) => assert_eq!(x, y),
                (None, None) => {}
                other => panic!("{other:?}"),
            }
        }
    }
}

/// GGX with height-correlated `G2` and `F = 1` in `f64` (Walter et al. 2007,
/// eqs. 20, 33; Heitz 2014, eqs. 86, 99) at the *normalised* directions of
/// the given `f32` vectors, written in the `tan²` forms that do not cancel.
fn ggx_hc_ref(alpha: f64, wi: Vec3, wo: Vec3) -> f64 {
    let (i, o) = (unit64(wi), unit64(wo));
    let h = [i[0] + o[0], i[1] + o[1], i[2] + o[2]];
    let t2 = (h[0] * h[0] + h[1] * h[1]) / (h[2] * h[2]);
    let c2 = h[2] * h[2] / (h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
    let d = 1.0 / (PI64 * alpha * alpha * c2 * c2 * (1.0 + t2 / (alpha * alpha)).powi(2));
    let lambda = |w: [f64; 3]| {
        let x = alpha * alpha * (w[0] * w[0] + w[1] * w[1]) / (w[2] * w[2]);
        0.5 * x / ((1.0 + x).sqrt() + 1.0)
    };
    d / (1.0 + lambda(i) + lambda(o)) / (4.0 * i[2] * o[2])
}

/// Near the mirror configuration with both directions grazing, `ωi + ωo`
/// cancels to a vector of length `2 cos θ`, and the length error every `f32`
/// direction carries (up to half an ulp per component) would move the half
/// vector by a large fraction of a narrow lobe. `eval` corrects `h` for the
/// input lengths (`Half::of`); checked against the `f64` BRDF of the same
/// `f32` inputs normalised in `f64`, across the lobe (without the
/// correction the worst error here is 10⁻²).
#[test]
fn grazing_mirror_pairs_are_exact_to_f32() {
    let mut worst = 0.0f64;
    for &alpha in &[0.01f64, 1e-3] {
        let brdf = GgxHc::new(Ggx::new(alpha as f32).unwrap(), NoFresnel);
        for &theta_deg in &[89.0f64, 89.9, 89.99] {
            let theta = theta_deg.to_radians();
            for k in 0..400 {
                // wo at azimuth φo, wi around the mirror direction: offsets
                // across a few lobe widths in azimuth and in elevation.
                let Some((wi, wo)) = grazing_mirror_pair(theta, 2.0 * alpha, 8.0, k) else {
                    continue;
                };
                let reference = ggx_hc_ref(alpha, wi, wo);
                if reference < 1e-30 {
                    continue;
                }
                let got = brdf.eval(wi, wo) as f64;
                let err = (got - reference).abs() / reference;
                worst = worst.max(err);
                assert!(
                    err < 2e-5,
                    "α={alpha} θ={theta_deg}° wi={wi:?} wo={wo:?}: {got:e} vs {reference:e} ({err:e})"
                );
            }
        }
    }
    println!("grazing mirror pairs: worst relative error {worst:.2e}");
}

/// `eval` and `pdf` divide once (`D V = num/(den_D · 1/V)`); where that
/// product of denominators underflows — `ωi ≈ −ωo` both grazing, so that
/// `h` is short and along the normal, with the smallest `α` — they fall back
/// to two divisions. The values there are large but finite: checked against
/// the `f64` BRDF ([`ggx_hc_ref`]) and the `f64` pdf `D(h)/(4 A(ωo))`, and
/// the batch kernels (feature `simd`) hand those lanes back to the scalar
/// method, so they agree bit for bit.
#[test]
fn one_division_falls_back_where_the_denominators_underflow() {
    let alpha = 1e-4f64;
    let brdf = GgxHc::new(Ggx::new(alpha as f32).unwrap(), NoFresnel);
    let mut pairs = std::vec::Vec::new();
    for &z in &[1e-5f32, 3e-6, 1e-6, 3e-5, 1e-4] {
        let s = (1.0 - z * z).sqrt();
        for &phi in &[0.0f32, 0.7, 2.0] {
            let (c, sn) = (phi.cos(), phi.sin());
            pairs.push((Vec3::new(s * c, s * sn, z), Vec3::new(-s * c, -s * sn, z)));
        }
    }
    let mut fallbacks = 0;
    for &(wi, wo) in &pairs {
        let reference = ggx_hc_ref(alpha, wi, wo);
        let got = brdf.eval(wi, wo) as f64;
        assert!(
            reference.is_finite() && reference > 1e10,
            "{wi:?} {wo:?}: {reference:e}"
        );
        let err = (got - reference).abs() / reference;
        assert!(
            err < 1e-4,
            "wi={wi:?} wo={wo:?}: {got:e} vs {reference:e} ({err:e})"
        );
        // The pdf D(h)/(4 A(ωo)) with A = cos θ (1 + Λ), in f64.
        let (i, o) = (unit64(wi), unit64(wo));
        let h = [i[0] + o[0], i[1] + o[1], i[2] + o[2]];
        let (hz2, hxy2) = (h[2] * h[2], h[0] * h[0] + h[1] * h[1]);
        let a2 = alpha * alpha;
        let t = a2 * hz2 + hxy2;
        let d = a2 * (hz2 + hxy2).powi(2) / (PI64 * t * t);
        let area_o = 0.5 * (o[2] + (o[2] * o[2] + a2 * (o[0] * o[0] + o[1] * o[1])).sqrt());
        let pdf_ref = d / (4.0 * area_o);
        let pdf = brdf.pdf(wi, wo) as f64;
        assert!(
            (pdf - pdf_ref).abs() < 1e-4 * pdf_ref,
            "pdf {pdf:e} vs {pdf_ref:e}"
        );
        // Whether this pair took the two-division path: the f32 product of
        // the denominators (π t² · 4 (cos θo Ai + cos θi Ao − cos θi cos θo))
        // is below the normal range.
        let inv_v64 = 4.0 * (o[2] * 2.0 * area_o - o[2] * o[2]);
        if PI64 * t * t * inv_v64 < f32::MIN_POSITIVE as f64 {
            fallbacks += 1;
        }
    }
    assert!(fallbacks >= 6, "only {fallbacks} pairs exercise the fallback");
    #[cfg(feature = "simd")]
    {
        let wi: std::vec::Vec<Vec3> = pairs.iter().map(|p| p.0).collect();
        let wo: std::vec::Vec<Vec3> = pairs.iter().map(|p| p.1).collect();
        let mut out = std::vec![0.0f32; pairs.len()];
        brdf.eval_batch(&wi, &wo, &mut out);
        let mut pdfs = std::vec![0.0f32; pairs.len()];
        brdf.pdf_batch(&wi, &wo, &mut pdfs);
        for (k, &(a, b)) in pairs.iter().enumerate() {
            assert_eq!(out[k].to_bits(), brdf.eval(a, b).to_bits(), "eval_batch lane {k}");
            assert_eq!(pdfs[k].to_bits(), brdf.pdf(a, b).to_bits(), "pdf_batch lane {k}");
        }
    }
}

/// The hot-path hooks over their whole documented domain: `d_ratio` of
/// the squares of a vector of any length `|h|² ∈ [2⁻³², 2³²]` (with
/// `h_z > 0`) returns a finite `num ≥ 0` and `den > 0` whose quotient is `D`
/// of the vector's direction — checked against Walter et al. 2007 eqs. 25
/// and 33 in `f64` from the same `f32` squares — and `inverse_visibility`
/// of finite positive cosines and areas is finite and positive.
#[test]
fn hot_path_hooks_hold_their_contracts() {
    let mut worst = 0.0f64;
    for &a in &[1e-4f32, 0.01, 0.3, 1.0] {
        let (g, b) = (Ggx::new(a).unwrap(), Beckmann::new(a).unwrap());
        let a2 = a as f64 * a as f64;
        for k in -32..=32 {
            let len2 = libm::exp2(k as f64);
            for i in 1..=60 {
                let t = (i as f64 / 61.0) * FRAC_PI_2;
                let (hz2, hxy2) = ((len2 * t.cos().powi(2)) as f32, (len2 * t.sin().powi(2)) as f32);
                let (c2, s2) = (
                    hz2 as f64 / (hz2 as f64 + hxy2 as f64),
                    hxy2 as f64 / (hz2 as f64 + hxy2 as f64),
                );
                let tan2 = s2 / c2;
                let gr = a2 / (PI64 * c2 * c2 * (a2 + tan2).powi(2));
                let br = (-tan2 / a2).exp() / (PI64 * a2 * c2 * c2);
                for (name, (num, den), r) in [
                    ("ggx", g.d_ratio(hz2, hxy2), gr),
                    ("beckmann", b.d_ratio(hz2, hxy2), br),
                ] {
                    assert!(
                        num.is_finite() && num >= 0.0 && den.is_finite() && den > 0.0,
                        "{name} {hz2} {hxy2}: {num} / {den}"
                    );
                    let v = num as f64 / den as f64;
                    if r > 1e-30 && (tan2 / a2) < 80.0 {
                        let e = (v - r).abs() / r;
                        worst = worst.max(e);
                        assert!(
                            e < 1e-5 * (1.0 + tan2 / a2),
                            "{name} α={a} |h|²=2^{k} θ={t}: {v} vs {r}"
                        );
                    }
                }
            }
        }
    }
    for &(ci, ai, co, ao) in &[
        (1.0f32, 1.0f32, 1.0f32, 1.0f32),
        (1e-30, 1e-5, 0.5, 0.6),
        (0.3, 0.35, 1e-20, 2e-5),
    ] {
        for v in [
            HeightCorrelated::inverse_visibility(ci, ai, co, ao),
            Separable::inverse_visibility(ci, ai, co, ao),
        ] {
            assert!(v.is_finite() && v > 0.0, "{ci} {ai} {co} {ao}: {v}");
        }
    }
    println!("d_ratio vs f64: worst relative error {worst:.2e}");
}

/// `eval_pdf` is `(eval, pdf)` bit for bit, whatever it is asked for: GGX and
/// Beckmann, both shadowing terms, dielectric (both sides of 1), F82-style
/// conductor and no Fresnel; unit, non-unit and below-horizon directions.
#[test]
fn eval_pdf_is_eval_and_pdf() {
    use radiometry::Brdf;
    let mut u = crate::test_stream::uniforms(0x7f4a_7c15_9e37_79b9);
    let mut dir = |n: usize| {
        let v = Vec3::new(2.0 * u() - 1.0, 2.0 * u() - 1.0, 2.0 * u() - 1.0);
        if n.is_multiple_of(4) {
            v * 2.5
        } else {
            v.normalize_or(Vec3::Z)
        }
    };
    fn check<B: Brdf<Spectrum = S>, S: radiometry::Spectrum>(
        b: &B,
        f: impl Fn(Vec3, Vec3, bool, bool) -> (S, f32),
        wi: Vec3,
        wo: Vec3,
    ) {
        for (v, d) in [(true, true), (true, false), (false, true)] {
            let (e, p) = f(wi, wo, v, d);
            if v {
                let r = b.eval(wi, wo);
                assert!(
                    (0..S::CHANNELS).all(|c| e.channel(c).to_bits() == r.channel(c).to_bits()),
                    "{wi} {wo}"
                );
            }
            if d {
                assert_eq!(p.to_bits(), b.pdf(wi, wo).to_bits(), "{wi} {wo}");
            }
        }
    }
    for n in 0..3000 {
        let (wi, wo) = (dir(n), dir(n + 1));
        let a = 1e-4 + (n % 17) as f32 / 17.0;
        let g =
            Microfacet::<_, HeightCorrelated, _>::new(Ggx::new(a).unwrap(), Dielectric::new(1.5).unwrap());
        check(&g, |i, o, v, d| g.eval_pdf(i, o, v, d), wi, wo);
        let g = Microfacet::<_, Separable, _>::new(Ggx::new(a).unwrap(), Dielectric::new(0.7).unwrap());
        check(&g, |i, o, v, d| g.eval_pdf(i, o, v, d), wi, wo);
        let c = Microfacet::<_, HeightCorrelated, _>::new(
            Ggx::new(a).unwrap(),
            Conductor::new(Vec3::new(0.2, 0.9, 1.1), Vec3::new(3.9, 2.4, 1.6)).unwrap(),
        );
        check(&c, |i, o, v, d| c.eval_pdf(i, o, v, d), wi, wo);
        let b = Microfacet::<_, HeightCorrelated, _>::new(Beckmann::new(a).unwrap(), NoFresnel);
        check(&b, |i, o, v, d| b.eval_pdf(i, o, v, d), wi, wo);
    }
}
