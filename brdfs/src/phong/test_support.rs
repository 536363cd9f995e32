//! Test support shared by the Lambertian / Phong-family unit tests:
//! reference quadratures written independently of the code under test
//! (f64, own spherical parameterisation) and a sampling checker.

extern crate std;
use core::f64::consts::{FRAC_PI_2, TAU};
use radiometry::glam::Vec3;
use radiometry::math::ONE_MINUS_EPSILON;
use radiometry::{Brdf, Spectrum};

/// `f32` direction pairs near the mirror configuration with `ωo` at
/// `theta` from the normal (`k`-th of a sequence over `φo`): `ωi` at the
/// mirror direction offset by up to `±spread · width · cos θ` in azimuth
/// and `±spread · width` (scaled by `1/cos θ`) in elevation, where
/// `width` is the lobe's angular width. `None` where `ωi` would fall
/// below the horizon. For the grazing-precision tests.
pub fn grazing_mirror_pair(theta: f64, width: f64, spread: f64, k: usize) -> Option<(Vec3, Vec3)> {
    let phi_o = 0.37 + 0.011 * k as f64;
    let s = (k as f64 * 0.618_033_988_749_895).fract() - 0.5;
    let t = (k as f64 * 0.754_877_666_246_693).fract() - 0.5;
    let lobe = width * libm::cos(theta);
    let ti = theta + spread * t * lobe / libm::cos(theta).max(1e-3);
    let pi = core::f64::consts::PI + phi_o + spread * s * lobe;
    if ti >= FRAC_PI_2 {
        return None;
    }
    let dir = |th: f64, ph: f64| {
        Vec3::new(
            (libm::sin(th) * libm::cos(ph)) as f32,
            (libm::sin(th) * libm::sin(ph)) as f32,
            libm::cos(th) as f32,
        )
    };
    Some((dir(ti, pi), dir(theta, phi_o)))
}

/// The `f32` vector `w` normalised in `f64`: the direction it stands for.
pub fn unit64(w: Vec3) -> [f64; 3] {
    let v = [w.x as f64, w.y as f64, w.z as f64];
    let l = libm::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    [v[0] / l, v[1] / l, v[2] / l]
}

/// `∫_H g(ω) dω` by the midpoint rule in `(s, φ)` with `θ = (π/2) s²`
/// (cells crowd toward the pole, where narrow lobes at normal incidence
/// live; the horizon is a cell boundary). `dω = sin θ · π s ds dφ`.
pub fn hemisphere_integral(n_s: usize, n_phi: usize, mut g: impl FnMut(Vec3) -> f64) -> f64 {
    let mut total = 0.0f64;
    let dphi = TAU / n_phi as f64;
    let trig: std::vec::Vec<(f64, f64)> = (0..n_phi)
        .map(|j| {
            let phi = (j as f64 + 0.5) * dphi;
            (libm::cos(phi), libm::sin(phi))
        })
        .collect();
    for i in 0..n_s {
        let s = (i as f64 + 0.5) / n_s as f64;
        let theta = FRAC_PI_2 * s * s;
        let dtheta = 2.0 * FRAC_PI_2 * s / n_s as f64;
        let (st, ct) = (libm::sin(theta), libm::cos(theta));
        let mut ring = 0.0f64;
        for &(cp, sp) in &trig {
            ring += g(Vec3::new((st * cp) as f32, (st * sp) as f32, ct as f32));
        }
        total += ring * dphi * st * dtheta;
    }
    total
}

/// Unit direction at polar angle `theta` in the x–z plane (f64 → f32).
pub fn dir_xz(theta: f64) -> Vec3 {
    Vec3::new(libm::sin(theta) as f32, 0.0, libm::cos(theta) as f32)
}

/// Directional albedo of channel `c`, `∫_H f(ωi, ωo) cos θi dωi`.
pub fn albedo<B: Brdf>(b: &B, wo: Vec3, c: usize, n_s: usize, n_phi: usize) -> f64 {
    hemisphere_integral(n_s, n_phi, |wi| b.eval(wi, wo).channel(c) as f64 * wi.z as f64)
}

/// `∫_H pdf(ωi, ωo) dωi`.
pub fn pdf_mass<B: Brdf>(b: &B, wo: Vec3, n_s: usize, n_phi: usize) -> f64 {
    hemisphere_integral(n_s, n_phi, |wi| b.pdf(wi, wo) as f64)
}

/// Sample coordinates that include both edges of `[0, 1)`.
pub const U_GRID: [f32; 11] = [
    0.0,
    1e-7,
    0.01,
    0.1,
    0.25,
    0.5,
    0.75,
    0.9,
    0.99,
    0.9999,
    ONE_MINUS_EPSILON,
];

/// Checks every sample on `U_GRID²`: finite, unit, above the horizon,
/// `pdf == brdf.pdf(wi, wo)` (relative 1e-5) and `weight == f cos θi / pdf`
/// (relative 1e-5, recomputed in f64). Returns the number of `Some`s and
/// the worst relative pdf / weight mismatches.
pub fn check_sampling<B: Brdf>(b: &B, wo: Vec3) -> (usize, f64, f64) {
    let (mut some, mut worst_pdf, mut worst_w) = (0, 0.0f64, 0.0f64);
    for &u0 in &U_GRID {
        for &u1 in &U_GRID {
            let Some(s) = b.sample(wo, [u0, u1]) else { continue };
            some += 1;
            assert!(
                s.wi.is_finite() && (s.wi.length() - 1.0).abs() < 1e-5,
                "{wo:?} {u0} {u1} {s:?}"
            );
            assert!(s.wi.z > 0.0, "below horizon: {s:?}");
            assert!(s.pdf > 0.0 && s.pdf.is_finite(), "{s:?}");
            assert!(s.weight.is_finite() && s.weight.min_channel() >= 0.0, "{s:?}");
            let p = b.pdf(s.wi, wo) as f64;
            let e = (s.pdf as f64 - p).abs() / p;
            worst_pdf = worst_pdf.max(e);
            assert!(e <= 1e-5, "pdf mismatch {e}: {wo:?} {u0} {u1} {s:?} {p}");
            let f = b.eval(s.wi, wo);
            for c in 0..B::Spectrum::CHANNELS {
                let expect = f.channel(c) as f64 * s.wi.z as f64 / s.pdf as f64;
                let got = s.weight.channel(c) as f64;
                let e = (got - expect).abs() / expect.abs().max(1e-30);
                worst_w = worst_w.max(if expect == 0.0 && got == 0.0 { 0.0 } else { e });
                assert!(
                    e <= 1e-5 || (expect == 0.0 && got == 0.0),
                    "weight {got} vs {expect}: {s:?}"
                );
            }
        }
    }
    (some, worst_pdf, worst_w)
}

/// Kolmogorov–Smirnov distance between the samples `δ = 1 − cos`
/// (of a lobe with density `(n+1)/(2π) cos^n` around its axis) and the
/// closed-form CDF `P(δ' ≤ δ) = 1 − (1 − δ)^{n+1}` (f64).
pub fn ks_distance_cos_power(deltas: &mut [f64], n: f64) -> f64 {
    deltas.sort_by(|a, b| a.total_cmp(b));
    let m = deltas.len() as f64;
    let mut d = 0.0f64;
    for (k, &x) in deltas.iter().enumerate() {
        let cdf = -libm::expm1((n + 1.0) * libm::log1p(-x.min(1.0)));
        d = d
            .max((cdf - k as f64 / m).abs())
            .max((cdf - (k + 1) as f64 / m).abs());
    }
    d
}

/// The fused `sample` reports exactly `pdf(wi, wo)` (bit-identical, not
/// just close) and `weight = (eval(wi, wo)/pdf)·cos θi` exactly, for
/// `wo` and `3.5·wo` (the non-unit, cold input path) on `U_GRID²`.
/// Returns the number of `Some`s.
pub fn check_sample_bits<B: Brdf>(b: &B, wo: Vec3) -> usize {
    let mut some = 0;
    for wo in [wo, wo * 3.5] {
        for &u0 in &U_GRID {
            for &u1 in &U_GRID {
                let Some(s) = b.sample(wo, [u0, u1]) else { continue };
                some += 1;
                assert_eq!(
                    s.pdf.to_bits(),
                    b.pdf(s.wi, wo).to_bits(),
                    "{wo:?} {u0} {u1} {s:?}"
                );
                assert_eq!(s.weight, (b.eval(s.wi, wo) / s.pdf) * s.wi.z, "{wo:?} {u0} {u1}");
            }
        }
    }
    some
}

/// Stratified (m × m midpoint grid) estimate of the albedo of channel 0
/// from `sample` weights (`None` counts as 0): unbiased iff the samples
/// follow `pdf`.
pub fn sampled_albedo<B: Brdf>(b: &B, wo: Vec3, m: usize) -> f64 {
    let mut sum = 0.0f64;
    for i in 0..m {
        for j in 0..m {
            let u = [(i as f32 + 0.5) / m as f32, (j as f32 + 0.5) / m as f32];
            if let Some(s) = b.sample(wo, u) {
                sum += s.weight.channel(0) as f64;
            }
        }
    }
    sum / (m * m) as f64
}
