//! EMVA 1288 camera model: Poisson sampler, photon transfer, saturation,
//! quantisation, fixed-pattern noise.

use radiometry::sensor::noise::{Pcg32, poisson, standard_normal};
use radiometry::sensor::{Emva1288, FillFactor, Monochromatic, Pixel, Sampling, Sensor};
use radiometry::spectral::FnCurve;

type Qe = FnCurve<fn(f32) -> f32>;
fn half(_: f32) -> f32 {
    0.5
}
fn pixel() -> Pixel<FillFactor, Qe> {
    Pixel::new(
        FillFactor::new(1.0).unwrap(),
        FnCurve::new(300.0, 1100.0, half as fn(f32) -> f32),
        25e-12,
        0.01,
        Sampling::default(),
    )
    .unwrap()
}

/// ln of the Poisson pmf, f64, via a directly summed ln k!.
fn ln_pmf(k: u32, mu: f64) -> f64 {
    let mut lf = 0.0;
    for i in 2..=k {
        lf += (i as f64).ln();
    }
    k as f64 * mu.ln() - mu - lf
}

#[test]
fn poisson_moments_small_and_large_means() {
    let mut rng = Pcg32::new(2024);
    let n = 200_000;
    for mu in [0.05f32, 0.7, 3.0, 9.99, 10.0, 25.0, 400.0, 1.0e5] {
        let (mut s, mut s2) = (0.0f64, 0.0f64);
        for _ in 0..n {
            let k = poisson(&mut rng, mu) as f64;
            assert!(k >= 0.0 && k.fract() == 0.0);
            s += k;
            s2 += k * k;
        }
        let mean = s / n as f64;
        let var = s2 / n as f64 - mean * mean;
        let m = mu as f64;
        // SE of the mean √(μ/n); SE of the variance ≈ √((2μ² + μ)/n) for a Poisson.
        let zm = (mean - m) / (m / n as f64).sqrt();
        let zv = (var - m) / ((2.0 * m * m + m) / n as f64).sqrt();
        println!("Poisson μ={mu}: mean {mean:.5} (z={zm:.2}), var {var:.5} (z={zv:.2})");
        assert!(
            zm.abs() < 5.0 && zv.abs() < 5.0,
            "μ={mu}: z_mean={zm}, z_var={zv}"
        );
    }
    assert_eq!(poisson(&mut rng, 0.0), 0.0);
    assert_eq!(poisson(&mut rng, -3.0), 0.0);
    assert_eq!(poisson(&mut rng, f32::NAN), 0.0);
    assert!(poisson(&mut rng, f32::INFINITY).is_finite());
}

#[test]
fn poisson_pmf_chi_square() {
    // Pearson χ² against the exact pmf, for both branches (inversion, PTRS).
    let mut rng = Pcg32::new(77);
    for mu in [3.0f32, 30.0] {
        let n = 200_000u32;
        let m = mu as f64;
        let kmax = (m + 8.0 * m.sqrt() + 10.0) as usize;
        let mut hist = vec![0u32; kmax + 1];
        for _ in 0..n {
            let k = (poisson(&mut rng, mu) as usize).min(kmax);
            hist[k] += 1;
        }
        // Pool bins with expected count < 5 at both ends.
        let p: Vec<f64> = (0..=kmax).map(|k| ln_pmf(k as u32, m).exp()).collect();
        let (mut chi2, mut dof, mut eo, mut ee) = (0.0, 0i32, 0.0, 0.0);
        for k in 0..=kmax {
            eo += hist[k] as f64;
            ee += p[k] * n as f64;
            if ee >= 5.0 {
                chi2 += (eo - ee) * (eo - ee) / ee;
                dof += 1;
                eo = 0.0;
                ee = 0.0;
            }
        }
        dof -= 1;
        // 99.9 % quantile of χ²_dof ≈ dof + 3.09·√(2 dof) + 2 (Wilson–Hilferty is tighter; this is generous).
        let crit = dof as f64 + 3.09 * (2.0 * dof as f64).sqrt() + 4.0;
        println!("Poisson μ={mu}: χ² = {chi2:.1} on {dof} dof (crit {crit:.1})");
        assert!(chi2 < crit, "μ={mu}: χ²={chi2} dof={dof}");
    }
}

#[test]
fn normal_moments() {
    let mut rng = Pcg32::new(5);
    let n = 200_000;
    let (mut s, mut s2) = (0.0f64, 0.0f64);
    for _ in 0..n {
        let z = standard_normal(&mut rng) as f64;
        s += z;
        s2 += z * z;
    }
    let mean = s / n as f64;
    let var = s2 / n as f64 - mean * mean;
    assert!(mean.abs() < 5.0 / (n as f64).sqrt());
    assert!((var - 1.0).abs() < 5.0 * (2.0 / n as f64).sqrt());
}

#[test]
fn photon_transfer_relation_holds() {
    let (k, sigma_d, offset) = (0.5f32, 3.0f32, 20.0f32);
    let cam = Emva1288::ideal(pixel(), k, 20_000.0, 14)
        .unwrap()
        .with_shot_noise()
        .with_dark_noise(sigma_d)
        .unwrap()
        .with_dark_offset(offset)
        .unwrap();
    let mut rng = Pcg32::new(99);
    let n = 40_000;
    let mut pts = Vec::new();
    for mu_e in [0.0f32, 20.0, 100.0, 500.0, 2000.0, 8000.0] {
        let (mut s, mut s2) = (0.0f64, 0.0f64);
        for _ in 0..n {
            let y = cam.digitize(mu_e, 0, &mut rng) as f64;
            s += y;
            s2 += y * y;
        }
        let mean = s / n as f64;
        let var = (s2 - s * s / n as f64) / (n - 1) as f64;
        pts.push((mu_e as f64, mean, var));
    }
    let (_, mu_dark, var_dark) = pts[0];
    let kk = k as f64;
    let var_dark_model = kk * kk * (sigma_d as f64).powi(2) + 1.0 / 12.0;
    println!("dark: μ_y.dark = {mu_dark:.4}, σ²_y.dark = {var_dark:.4} (model {var_dark_model:.4})");
    assert!((mu_dark - offset as f64).abs() < 5.0 * (var_dark / n as f64).sqrt());
    assert!((var_dark - var_dark_model).abs() < 5.0 * var_dark_model * (2.0 / n as f64).sqrt());
    // σ_y² = K²σ_d² + σ_q² + K(μ_y − μ_y.dark) at every level.
    let (mut sxy, mut sxx) = (0.0, 0.0);
    for &(mu_e, mean, var) in &pts[1..] {
        assert!(
            (mean - mu_dark - kk * mu_e).abs() < 5.0 * (var / n as f64).sqrt() + 0.01,
            "{mu_e}: {mean}"
        );
        let model = var_dark_model + kk * (mean - mu_dark);
        let tol = 5.0 * model * (2.0 / n as f64).sqrt();
        println!("μ_e={mu_e}: μ_y={mean:.3} σ²_y={var:.3} model {model:.3} (±{tol:.3})");
        assert!((var - model).abs() < tol, "μ_e={mu_e}: σ²={var}, model {model}");
        let (x, y) = (mean - mu_dark, var - var_dark);
        sxy += x * y;
        sxx += x * x;
    }
    // Photon-transfer slope (least squares through the origin) = K.
    let slope = sxy / sxx;
    println!("photon transfer fit: K = {slope:.5} (true {k})");
    assert!((slope - kk).abs() / kk < 0.01);
}

#[test]
fn saturation_and_quantisation_limits() {
    let cam = Emva1288::ideal(pixel(), 0.1, 1000.0, 8).unwrap();
    let mut rng = Pcg32::new(1);
    assert_eq!(cam.digitize(0.0, 0, &mut rng), 0.0); // zero light
    assert_eq!(cam.digitize(1000.0, 0, &mut rng), 100.0); // full well
    assert_eq!(cam.digitize(1e9, 0, &mut rng), 100.0); // beyond full well: clipped at the full well
    assert_eq!(cam.digitize(34.0, 0, &mut rng), 3.0); // round(3.4)
    assert_eq!(cam.digitize(36.0, 0, &mut rng), 4.0); // round(3.6)
    assert_eq!(cam.digitize(-5.0, 0, &mut rng), 0.0);
    assert_eq!(cam.digitize(f32::NAN, 0, &mut rng), 0.0);
    assert_eq!(cam.digitize(f32::INFINITY, 0, &mut rng), 100.0);
    // ADC clipping: a high gain saturates the 8-bit range at 255 DN.
    let hot = Emva1288::ideal(pixel(), 10.0, 1000.0, 8).unwrap();
    assert_eq!(hot.digitize(1000.0, 0, &mut rng), 255.0);
    assert_eq!(hot.max_dn(), 255.0);
    // Invalid parameters.
    assert!(Emva1288::ideal(pixel(), 0.0, 1000.0, 8).is_err());
    assert!(Emva1288::ideal(pixel(), 1.0, f32::NAN, 8).is_err());
    assert!(Emva1288::ideal(pixel(), 1.0, 1000.0, 0).is_err());
    assert!(Emva1288::ideal(pixel(), 1.0, 1000.0, 33).is_err());
    assert!(cam.with_dark_noise(-1.0).is_err());
    // The Sensor trait reads a field end to end: 1 mW/m² at 550 nm, 10 ms → 345.8 e⁻ → 34.6 → 35 DN.
    assert_eq!(
        cam.read(&Monochromatic::new(550.0, 1e-3), &mut rng).unwrap(),
        35.0
    );
    assert!(cam.read(&Monochromatic::new(550.0, f32::NAN), &mut rng).is_err());
}

#[test]
fn fixed_pattern_is_stable_and_has_the_stated_spread() {
    let cam = Emva1288::ideal(pixel(), 1.0, 1e5, 16)
        .unwrap()
        .with_dark_offset(100.0)
        .unwrap()
        .with_fixed_pattern(2.0, 0.01, 7)
        .unwrap();
    let mut rng = Pcg32::new(3);
    let n = 20_000u32;
    let (mut s, mut s2) = (0.0f64, 0.0f64);
    for i in 0..n {
        let a = cam.digitize(0.0, i, &mut rng);
        assert_eq!(a, cam.digitize(0.0, i, &mut rng)); // same pixel, same pattern (no temporal noise)
        s += a as f64;
        s2 += (a as f64).powi(2);
    }
    let var = s2 / n as f64 - (s / n as f64).powi(2);
    // DSNU variance 4 DN² plus the rounding 1/12.
    let model = 4.0 + 1.0 / 12.0;
    println!("DSNU: spatial variance {var:.3} DN² (model {model:.3})");
    assert!((var - model).abs() < 5.0 * model * (2.0 / n as f64).sqrt());
    // PRNU: at 10⁴ e⁻, relative spread ≈ 1 %.
    let (mut s, mut s2) = (0.0f64, 0.0f64);
    for i in 0..n {
        let a = cam.digitize(10_000.0, i, &mut rng) as f64 - 100.0;
        s += a;
        s2 += a * a;
    }
    let mean = s / n as f64;
    let var = s2 / n as f64 - mean * mean;
    let model = (0.01f64 * 10_000.0).powi(2) + 4.0 + 1.0 / 12.0;
    assert!(
        (var - model).abs() < 5.0 * model * (2.0 / n as f64).sqrt(),
        "{var} vs {model}"
    );
}
