//! The sheen lobe ([`Sheen`], Estevez & Kulla 2017) against an independent `f64` implementation of the
//! paper's formulas written here (not the crate's `f32` code, not its integrators):
//!
//! * `eval_matches_the_formulas`: `f = D(h) G / (4 cos θi cos θo)` with the Charlie `D`, the fitted
//!   `Λ` (Table 1, interpolated with `(1 − r)²`) and its grazing continuation, on a grid of directions
//!   and roughnesses;
//! * `table_entries_match_independent_quadrature`: a sample of the tabulated albedos `E(μ_j, r_k)`
//!   recomputed by a composite Gauss–Legendre product rule over `(cos θi, φ)`;
//! * `directional_albedo_is_within_its_stated_bound`: `Sheen::directional_albedo` at off-node
//!   `(μo, r)` against the same quadrature, within the error it states;
//! * `albedo_at_most_one`: `E + error ≤ 1` over a dense sweep (the measured maximum is printed);
//! * `uniform_sampling_beats_cosine`: the variance of the one-sample albedo estimate under uniform and
//!   cosine-weighted hemisphere sampling, by quadrature of the second moments.

use super::kulla_conty::{gauss_legendre, refine_panels};
use core::f64::consts::PI;
use radiometry::glam::Vec3;
use radiometry::{Brdf, IsotropicBrdf};
use radiometry_brdfs::Sheen;
use radiometry_brdfs::sheen::{
    MIN_SHEEN_ROUGHNESS, N_MU, N_R, SheenAlbedoTable, sheen_mu_node, sheen_r_node,
};

/// Table 1 of Estevez & Kulla 2017: `[a, b, c, d, e]` at `r = 0` and `r = 1`.
const P0: [f64; 5] = [25.3245, 3.32435, 0.16801, -1.27393, -4.85967];
const P1: [f64; 5] = [21.5473, 3.82987, 0.19823, -1.97760, -4.32054];

/// The reference model in `f64`.
struct Reference {
    r: f64,
    p: [f64; 5],
    mu_star: f64,
    mu_lambda_star: f64,
}

impl Reference {
    fn new(r: f64) -> Self {
        let t = (1.0 - r) * (1.0 - r);
        let p: [f64; 5] = core::array::from_fn(|k| t * P0[k] + (1.0 - t) * P1[k]);
        let mut m = Reference {
            r,
            p,
            mu_star: 0.0,
            mu_lambda_star: 0.0,
        };
        // μ*: the smaller root of a c y/(1 + y)² = 1, y = b μ^c (the documented continuation point).
        let k = p[0] * p[2] - 2.0;
        let y = (k - (k * k - 4.0).sqrt()) / 2.0;
        m.mu_star = (y / p[1]).powf(1.0 / p[2]);
        m.mu_lambda_star = m.mu_star * m.l(m.mu_star).exp();
        m
    }

    fn l(&self, x: f64) -> f64 {
        let [a, b, c, d, e] = self.p;
        a / (1.0 + b * x.powf(c)) + d * x + e
    }

    /// `Λ(μ)`: `exp L(μ)` below 1/2, `exp(2L(1/2) − L(1 − μ))` above, `μ*Λ(μ*)/μ` below `μ*`.
    fn lambda(&self, mu: f64) -> f64 {
        if mu < self.mu_star {
            self.mu_lambda_star / mu
        } else if mu < 0.5 {
            self.l(mu).exp()
        } else {
            (2.0 * self.l(0.5) - self.l(1.0 - mu)).exp()
        }
    }

    /// `D(h) = (2 + 1/r) sin^(1/r) θh / (2π)`.
    fn d(&self, sin_h: f64) -> f64 {
        (2.0 + 1.0 / self.r) * sin_h.powf(1.0 / self.r) / (2.0 * PI)
    }

    /// `f cos θi = D G / (4 cos θo)` for unit directions above the horizon.
    fn f_cos(&self, wi: [f64; 3], wo: [f64; 3]) -> f64 {
        let h = [wi[0] + wo[0], wi[1] + wo[1], wi[2] + wo[2]];
        let n = (h[0] * h[0] + h[1] * h[1] + h[2] * h[2]).sqrt();
        let sin_h = ((h[0] * h[0] + h[1] * h[1]).sqrt() / n).min(1.0);
        let g = 1.0 / (1.0 + self.lambda(wi[2]) + self.lambda(wo[2]));
        self.d(sin_h) * g / (4.0 * wo[2])
    }

    fn f(&self, wi: [f64; 3], wo: [f64; 3]) -> f64 {
        self.f_cos(wi, wo) / wi[2]
    }
}

/// `∫ f` over the pieces between sorted `cuts`, each piece split into `panels` equal panels of `g`.
fn pieces(g: &[(f64, f64)], cuts: &[f64], panels: usize, f: &mut dyn FnMut(f64) -> f64) -> f64 {
    let mut s = 0.0;
    for c in cuts.windows(2) {
        let h = (c[1] - c[0]) / panels as f64;
        for p in 0..panels {
            for &(x, w) in g {
                s += w * h * f(c[0] + (p as f64 + x) * h);
            }
        }
    }
    s
}

/// `E(μo) = ∫_H f cos θi dωi = 2 ∫₀^π dφ ∫₀¹ dμi f cos θi` (symmetric in φ), with breakpoints in `μi` at
/// the kinks of `Λ` (`μ*`, 1/2), at `μo` (the cusp of `D` at the mirror direction) and graded towards
/// both ends (`G → 0` at grazing `ωi`; the fit's `x^c` at `μi = 1`), and in `φ` graded towards `π`.
fn albedo_ref(m: &Reference, mu_o: f64, panels: usize) -> f64 {
    let g = gauss_legendre(8);
    let so = (1.0 - mu_o * mu_o).max(0.0).sqrt();
    let wo = [so, 0.0, mu_o];
    let mut mu_cuts = vec![0.0, m.mu_star, 0.5, mu_o, 1.0];
    for i in 1..=12 {
        mu_cuts.push(4f64.powi(-i));
        mu_cuts.push(1.0 - 4f64.powi(-i));
    }
    mu_cuts.retain(|x| (0.0..=1.0).contains(x));
    mu_cuts.sort_by(f64::total_cmp);
    mu_cuts.dedup();
    let mut phi_cuts: Vec<f64> = (0..=6).map(|i| PI - PI * 0.25f64.powi(i)).collect();
    phi_cuts.push(PI);
    2.0 * pieces(&g, &mu_cuts, panels, &mut |mu_i| {
        let si = (1.0 - mu_i * mu_i).max(0.0).sqrt();
        pieces(&g, &phi_cuts, panels, &mut |phi| {
            m.f_cos([si * phi.cos(), si * phi.sin(), mu_i], wo)
        })
    })
}

/// The reference albedo and its error estimate (difference to half the panels): panels double (1, 2, 4)
/// until two rules agree to `2·10⁻⁷`, a tenth of the convergence the tests require (`2·10⁻⁶`).
fn albedo_ref_err(r: f64, mu_o: f64) -> (f64, f64) {
    let m = Reference::new(r);
    refine_panels(4, 2e-7, |panels| albedo_ref(&m, mu_o, panels))
}

fn dir(theta: f64, phi: f64) -> [f64; 3] {
    [theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos()]
}

fn v3(w: [f64; 3]) -> Vec3 {
    Vec3::new(w[0] as f32, w[1] as f32, w[2] as f32)
}

#[test]
fn eval_matches_the_formulas() {
    let mut worst = 0.0f64;
    for &r in &[MIN_SHEEN_ROUGHNESS as f64, 0.1, 0.25, 0.5, 0.8, 1.0] {
        let s = Sheen::new(1.0f32, r as f32).unwrap();
        let m = Reference::new(r);
        for i in 0..24 {
            for j in 0..24 {
                for k in 0..6 {
                    let ti = (i as f64 + 0.5) / 24.0 * PI / 2.0;
                    let to = (j as f64 + 0.3) / 24.0 * PI / 2.0;
                    let wi = dir(ti, 0.0);
                    let wo = dir(to, k as f64 * PI / 5.0 + 0.1);
                    // The reference from the f32 directions the BRDF sees.
                    let (wi32, wo32) = (v3(wi), v3(wo));
                    let (a, b) = (wi32.as_dvec3().normalize(), wo32.as_dvec3().normalize());
                    let want = m.f([a.x, a.y, a.z], [b.x, b.y, b.z]);
                    let got = s.eval(wi32, wo32) as f64;
                    let rel = (got - want).abs() / want.max(1e-30);
                    worst = worst.max(rel);
                    assert!(rel < 2e-4, "r = {r}, θi = {ti}, θo = {to}: {got} vs {want}");
                }
            }
        }
    }
    // Λ: both branches, the continuation, and D at the horizon.
    for &r in &[0.07f32, 0.5, 1.0] {
        let c = radiometry_brdfs::sheen::Charlie::new(r).unwrap();
        let m = Reference::new(r as f64);
        for &mu in &[1e-7f64, 1e-5, 1e-4, 0.01, 0.3, 0.49, 0.51, 0.9, 0.999, 1.0] {
            let (got, want) = (c.lambda(mu as f32) as f64, m.lambda(mu));
            assert!(
                (got - want).abs() <= 2e-5 * want,
                "Λ r = {r}, μ = {mu}: {got} vs {want}"
            );
        }
        assert!((c.mu_star() as f64 - m.mu_star).abs() < 1e-5 * m.mu_star);
        assert!((c.d_sin2(1.0) as f64 - m.d(1.0)).abs() < 1e-6 * m.d(1.0));
    }
    println!("eval vs f64 formulas: largest relative difference {worst:.2e}");
}

/// The μ of column `j` as the generator evaluates it (column 0 stands for the limit μ → 0⁺).
fn column_mu(j: usize) -> f64 {
    if j == 0 { 1e-8 } else { sheen_mu_node(j) as f64 }
}

#[test]
fn table_entries_match_independent_quadrature() {
    let t = SheenAlbedoTable::get();
    let (mut worst, mut at, mut checked) = (0.0f64, (0, 0), 0);
    for k in (0..N_R).step_by(5).chain([N_R - 1]) {
        for j in (0..N_MU).step_by(7).chain([N_MU - 1]) {
            let (e, err) = albedo_ref_err(sheen_r_node(k) as f64, column_mu(j));
            assert!(err < 2e-6, "reference not converged at ({k}, {j}): {err:e}");
            let d = (t.values[k][j] as f64 - e).abs();
            if d > worst {
                (worst, at) = (d, (k, j));
            }
            checked += 1;
        }
    }
    println!("table: {checked} entries; largest |table − f64 quadrature| = {worst:.2e} at {at:?}");
    assert!(worst < 1e-5, "{worst:e} at {at:?}");
}

#[test]
fn directional_albedo_is_within_its_stated_bound() {
    let (mut worst, mut worst_ratio) = (0.0f64, 0.0f64);
    let mut n = 0;
    for i in 0..11 {
        // Off-node roughnesses, dense near r_min.
        let x = ((i as f64 + 0.37) / 11.0).powi(2);
        let r = MIN_SHEEN_ROUGHNESS as f64 + (1.0 - MIN_SHEEN_ROUGHNESS as f64) * x;
        let s = Sheen::new(1.0f32, r as f32).unwrap();
        for j in 0..19 {
            // cos θo log-spaced from 10⁻⁷ to 1, off the nodes.
            let mu = 10f64.powf(-7.0 + 7.0 * (j as f64 + 0.61) / 19.0).min(1.0);
            let wo = v3([(1.0 - mu * mu).sqrt(), 0.0, mu]);
            let a = s.directional_albedo(wo);
            let (e, err) = albedo_ref_err(r as f32 as f64, wo.z as f64);
            assert!(
                err < 2e-6,
                "reference not converged at r = {r}, μ = {mu}: {err:e}"
            );
            let d = (a.value as f64 - e).abs();
            assert!(
                a.is_bound && d <= a.error as f64 + err,
                "r = {r}, μ = {mu}: {} vs {e} (± {})",
                a.value,
                a.error
            );
            worst = worst.max(d);
            worst_ratio = worst_ratio.max(d / a.error as f64);
            n += 1;
        }
    }
    println!(
        "directional_albedo: {n} off-node points; largest |E − f64 quadrature| = {worst:.2e} ({:.0} % of the stated bound)",
        100.0 * worst_ratio
    );
}

#[test]
fn albedo_at_most_one() {
    let mut max = (0.0f32, 0.0f32, 0.0f32);
    for i in 0..=200 {
        let r = MIN_SHEEN_ROUGHNESS + (1.0 - MIN_SHEEN_ROUGHNESS) * (i as f32 / 200.0).powi(2);
        let s = Sheen::new(1.0f32, r).unwrap();
        for j in 0..=400 {
            let mu = 10f32.powf(-9.0 + 9.0 * j as f32 / 400.0);
            let a = s.directional_albedo(Vec3::new((1.0 - mu * mu).max(0.0).sqrt(), 0.0, mu));
            assert!(
                a.value + a.error <= 1.0,
                "r = {r}, μ = {mu}: {} + {}",
                a.value,
                a.error
            );
            if a.value > max.0 {
                max = (a.value, r, mu);
            }
        }
    }
    let t = SheenAlbedoTable::get();
    let table_max = t.values.iter().flatten().fold(0.0f32, |m, &v| m.max(v));
    println!(
        "largest albedo (colour 1): {:.5} at r = {}, μo = {:e}; largest table entry {table_max:.5}",
        max.0, max.1, max.2
    );
}

#[test]
fn grazing_column_is_the_limit() {
    for &r in &[MIN_SHEEN_ROUGHNESS as f64, 0.5, 1.0] {
        let (a, _) = albedo_ref_err(r, 1e-8);
        let (b, _) = albedo_ref_err(r, 1e-10);
        assert!((a - b).abs() < 1e-6, "r = {r}: {a} vs {b}");
    }
}

/// Second moments of the one-sample albedo estimator: uniform `2π ∫ (f cos)² dω`, cosine
/// `π ∫ (f cos)²/cos θi dω`, by the same product rule as the albedo.
#[test]
fn uniform_sampling_beats_cosine() {
    let g = gauss_legendre(8);
    let (mut sum_u, mut sum_c, mut worse) = (0.0f64, 0.0f64, 0);
    let mut rows = Vec::new();
    for &r in &[MIN_SHEEN_ROUGHNESS as f64, 0.25, 0.5, 1.0] {
        let m = Reference::new(r);
        for &theta_deg in &[0.0f64, 30.0, 60.0, 80.0, 89.0] {
            let mu_o = theta_deg.to_radians().cos();
            let wo = [(1.0 - mu_o * mu_o).sqrt(), 0.0, mu_o];
            let mut mu_cuts: Vec<f64> = vec![0.0, m.mu_star, 0.5, mu_o, 1.0];
            mu_cuts.extend((1..=12).map(|i| 4f64.powi(-i)));
            mu_cuts.sort_by(f64::total_cmp);
            mu_cuts.dedup();
            let phi_cuts = [0.0, PI / 2.0, 3.0 * PI / 4.0, PI];
            let moment = |weight: &dyn Fn(f64) -> f64| {
                2.0 * pieces(&g, &mu_cuts, 4, &mut |mu_i| {
                    let si = (1.0 - mu_i * mu_i).max(0.0).sqrt();
                    pieces(&g, &phi_cuts, 4, &mut |phi| {
                        let v = m.f_cos([si * phi.cos(), si * phi.sin(), mu_i], wo);
                        v * v * weight(mu_i)
                    })
                })
            };
            let e = albedo_ref(&m, mu_o, 4);
            let var_u = 2.0 * PI * moment(&|_| 1.0) - e * e;
            let var_c = PI * moment(&|mu_i| 1.0 / mu_i) - e * e;
            rows.push(format!("r = {r:.2}, θo = {theta_deg:>4}°: E = {e:.4}, variance uniform {var_u:.3e}, cosine {var_c:.3e}"));
            sum_u += var_u / (e * e);
            sum_c += var_c / (e * e);
            if var_u > var_c {
                worse += 1;
            }
        }
    }
    for row in &rows {
        println!("{row}");
    }
    println!(
        "summed relative variance: uniform {sum_u:.3}, cosine {sum_c:.3}; uniform worse in {worse} of 20 cases"
    );
    assert!(sum_u < sum_c);
}

#[test]
fn sampling_pdf_is_bit_identical_and_weights_match() {
    for &r in &[MIN_SHEEN_ROUGHNESS, 0.3, 1.0] {
        let s = Sheen::new(Vec3::new(0.9, 0.5, 0.1), r).unwrap();
        for &wo in &[
            Vec3::Z,
            Vec3::new(0.6, 0.0, 0.8),
            Vec3::new(0.0, 0.9999, 0.01414),
            Vec3::new(3.0, 0.0, 1.0),
        ] {
            for i in 0..16 {
                for j in 0..16 {
                    let u = [(i as f32 + 0.5) / 16.0, (j as f32 + 0.5) / 16.0];
                    let smp = s.sample(wo, u).unwrap();
                    assert_eq!(smp.pdf.to_bits(), s.pdf(smp.wi, wo).to_bits());
                    let want = s.eval(smp.wi, wo) * (smp.wi.z / smp.pdf);
                    assert!((smp.weight - want).abs().max_element() <= 1e-5 * want.max_element().max(1e-6));
                }
            }
        }
        // Reciprocal bit for bit, isotropic.
        let (a, b) = (Vec3::new(0.3, 0.4, 0.8660254), Vec3::new(-0.8, 0.1, 0.591608));
        assert_eq!(s.eval(a, b), s.eval(b, a));
        let iso = s.eval_isotropic(0.4, 1.1, 2.0);
        assert!(iso.is_finite() && iso.min_element() >= 0.0);
    }
}

#[test]
fn hard_inputs_are_finite() {
    let s = Sheen::new(1.0f32, MIN_SHEEN_ROUGHNESS).unwrap();
    let dirs = [
        Vec3::Z,
        -Vec3::Z,
        Vec3::X,
        Vec3::new(1.0, 0.0, 1e-30),
        Vec3::new(1.0, 0.0, f32::MIN_POSITIVE),
        Vec3::new(1.0, 0.0, 1e-45),
        Vec3::new(-1.0, 0.0, 1e-30),
        Vec3::new(1e30, 1e30, 1e30),
        Vec3::new(1e-30, 0.0, 1e-30),
        Vec3::ZERO,
        Vec3::new(0.0, 0.0, 5.0),
    ];
    for &a in &dirs {
        for &b in &dirs {
            let f = s.eval(a, b);
            assert!(f.is_finite() && f >= 0.0, "{a} {b}: {f}");
            assert_eq!(f, s.eval(b, a));
            let p = s.pdf(a, b);
            assert!(p.is_finite() && p >= 0.0);
        }
        for u in [[0.0, 0.0], [1.0 - f32::EPSILON / 2.0; 2], [0.5, 1.0]] {
            if let Some(smp) = s.sample(a, u) {
                assert!(smp.weight.is_finite() && smp.pdf > 0.0 && smp.pdf.is_finite());
            }
        }
        let e = s.directional_albedo(a);
        assert!(e.value.is_finite() && e.value >= 0.0 && e.error.is_finite());
    }
    assert_eq!(s.eval(Vec3::new(0.6, 0.0, 0.8), Vec3::new(-0.6, 0.0, -0.8)), 0.0);
}
