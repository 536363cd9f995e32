//! Energy conservation of every plugin configuration (issue 2): the directional albedo
//! `ρ(ωo) = ∫_{H+} f(ωi, ωo) cos θi dωi` is at most `1 + ε` for every valid parameter set and `ωo`, and
//! every Fresnel term used is ≤ 1, so the bound applies to all configurations.
//!
//! Two estimators:
//! * `directional_albedo_at_most_one_every_plugin` (1,000 proptest cases × 39 configurations): importance
//!   sampling with the plugin's sampler, 4,096 jittered-stratified sample points each contributing
//!   `f(ωi, ωo) cos θi / pdf(ωi, ωo)` recomputed with `eval` and `pdf` (a `None` sample contributes 0).
//!   This is unbiased as long as the sampler draws from `pdf` — which `tests/sampling.rs` establishes
//!   with χ² tests — and `pdf > 0` wherever `f > 0`. `ε = 5 × (collapsed-strata standard error, which
//!   over-estimates the error of stratified sampling) + 1e-6` (the rounding of the `f32` values of `f`, a
//!   few ulps). When the standard error exceeds 0.02 the estimate is inconclusive (heavy-tailed weights,
//!   i.e. `pdf` far below `f cos` somewhere) and the quadrature below decides instead. At least 97 % of
//!   the checks see a 1 % gain (s.e. ≤ 1e-3; [`energy_check`] says why, and
//!   [`gain_check`], on its first 100 cases, shows it on plugins rescaled to albedo 1.01).
//! * `albedo_by_quadrature_hard_cases`: an independent `f64` adaptive quadrature ([`common::quad`])
//!   centred on the mirror direction with breakpoints graded to the lobe width, on a grid of hard
//!   parameters and angles; it must converge (error estimate ≤ 1e-3), then `ε` = its error estimate + 1e-6.

use crate::common;

use common::Worst;
use common::plugins::{Params, all_kinds, build, lobe_width, params};
use common::quad::{Adaptive, Integral, Tol, integrate_hemisphere, lobe_breaks};
use common::strategies::{to_f32, upper_dir};
use proptest::test_runner::TestCaseError;
use radiometry::IsotropicBrdf;
use radiometry::glam::{DVec3, Vec3};

const CASES: u32 = 500;
static WORST_ALBEDO: Worst = Worst::new();
static WORST_SE: Worst = Worst::new();
static WORST_QUAD: Worst = Worst::new();
static FALLBACKS: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
static SEES_ONE_PERCENT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
const QUAD_TOL: Tol = Tol {
    abs: 1e-4,
    rel: 1e-4,
    depth: 8,
};
/// First try of the fallback quadrature (see `directional_albedo_at_most_one_every_plugin`).
const LOOSE_TOL: Tol = Tol {
    abs: 1e-2,
    rel: 1e-2,
    depth: 8,
};

/// Directional albedo of `b` at `wo` by quadrature (lobe width `w`).
///
/// Peaked lobes (`w < π`) are integrated on rings around the mirror direction. Broad lobes (`w ≥ π`:
/// Lambertian and the rough diffuse models, which have no peak to centre on) are integrated on rings
/// around the normal, split at `θi = θo`: the rough diffuse models have a kink there (`s/max(cos θi,
/// cos θo)`), and at grazing `ωo` it closes a band `cos θi < cos θo` at the horizon where `f cos θi`
/// falls from `σA/π` to 0 — a feature no ring around the mirror direction resolves (FON, σ = 1,
/// `cos θo = 1e-3`: 0.9999838 with an error estimate of 4e-11, for the exact 0.9997527; see
/// `quadrature_resolves_the_rough_diffuse_band_at_grazing`).
pub fn albedo_quad(b: &dyn IsotropicBrdf<Spectrum = f32>, wo: Vec3, w: f64, tol: Tol) -> Integral {
    let q = Adaptive::default();
    let (pole, breaks) = if w >= std::f64::consts::PI {
        let wo64 = common::strategies::to_f64(wo).normalize();
        let mut breaks = lobe_breaks(w);
        breaks.push(wo64.z.clamp(-1.0, 1.0).acos());
        breaks.sort_by(|a, b| a.partial_cmp(b).unwrap());
        (DVec3::Z, breaks)
    } else {
        (
            DVec3::new(-wo.x as f64, -wo.y as f64, wo.z as f64),
            lobe_breaks(w),
        )
    };
    integrate_hemisphere(&q, pole, &breaks, tol, &mut |wi| {
        let v = b.eval(to_f32(wi), wo) as f64 * wi.z;
        if v.is_finite() { v } else { f64::NAN }
    })
}

/// Directional albedo by importance sampling over a jittered `m × m` grid of sample points (one
/// uniform point per cell, `m` even, `m ≤ 64` or a multiple of 64): (mean, standard error).
///
/// The standard error is the collapsed-strata estimate of stratified sampling (Cochran 1977, *Sampling
/// Techniques*, 3rd ed., § 5A.12): the cells are paired along the second coordinate, `(i, 2l)` with
/// `(i, 2l + 1)`, and `Var(mean) ≈ Σ_pairs (y_a − y_b)² / n²`. Its expectation is
/// `Var(mean) + Σ_pairs (μ_a − μ_b)² / n² ≥ Var(mean)` (`μ` the cell means): conservative, yet, unlike the
/// i.i.d. formula `s/√n` (which ignores the stratification and reports the full spread of the weights —
/// and let a 5σ test pass a 10 % gain at its former cut-off of 0.02), it shrinks
/// with the variance the stratification removes.
///
/// Each row of the grid goes through the batch methods (`sample_batch`, then `pdf_batch` and
/// `eval_batch` at the sampled directions), which return what `sample`, `pdf` and `eval` return point
/// by point (the plugins' batch contract, tested in radiometry-brdfs) — only faster where a plugin has
/// vector kernels.
pub fn albedo_is(b: &dyn IsotropicBrdf<Spectrum = f32>, wo: Vec3, m: u32, seed: u64) -> (f64, f64) {
    const ROW: usize = 64;
    assert!(m.is_multiple_of(2) && (m as usize <= ROW || (m as usize).is_multiple_of(ROW)));
    let mut rng = common::rng::Rng::new(seed);
    let (mut s1, mut pairs2) = (0.0f64, 0.0f64);
    let n = (m * m) as f64;
    let wos = [wo; ROW];
    let mut us = [[0.0f32; 2]; ROW];
    let mut samples = [None; ROW];
    let mut wis = [Vec3::ZERO; ROW];
    let mut cell = [0usize; ROW];
    let (mut pdfs, mut fs) = ([0.0f32; ROW], [0.0f32; ROW]);
    let mut y = [0.0f64; ROW];
    let m_us = (m as usize).min(ROW);
    for r in 0..m * (m / m_us as u32) {
        // Row `i` of the grid, columns `j0 .. j0 + m_us`.
        let (i, j0) = (r / (m / m_us as u32), (r % (m / m_us as u32)) * m_us as u32);
        for (j, u) in us[..m_us].iter_mut().enumerate() {
            *u = [
                ((i as f32 + rng.f32()) / m as f32).min(0.99999994),
                ((j0 as f32 + j as f32 + rng.f32()) / m as f32).min(0.99999994),
            ];
        }
        b.sample_batch(&wos[..m_us], &us[..m_us], &mut samples[..m_us]);
        let mut k = 0;
        for (j, s) in samples[..m_us].iter().enumerate() {
            if let Some(s) = s {
                wis[k] = s.wi;
                cell[k] = j;
                k += 1;
            }
        }
        b.pdf_batch(&wis[..k], &wos[..k], &mut pdfs[..k]);
        b.eval_batch(&wis[..k], &wos[..k], &mut fs[..k]);
        // `None` samples contribute 0 (they still count in n).
        y[..m_us].fill(0.0);
        for (((wi, &pdf), &f), &j) in wis[..k].iter().zip(&pdfs[..k]).zip(&fs[..k]).zip(&cell[..k]) {
            let pdf = pdf as f64;
            y[j] = if pdf > 0.0 {
                f as f64 * wi.z.max(0.0) as f64 / pdf
            } else {
                0.0
            };
        }
        for p in y[..m_us].chunks_exact(2) {
            s1 += p[0] + p[1];
            pairs2 += (p[0] - p[1]) * (p[0] - p[1]);
        }
    }
    (s1 / n, pairs2.sqrt() / n)
}

/// Largest standard error at which the importance-sampled estimate decides a case; above it the
/// quadrature decides (see [`energy_check`]).
const SE_MAX: f64 = 0.02;
/// Standard error up to which the importance-sampled check sees a 1 % gain (see [`energy_check`]).
const SE_ONE_PERCENT: f64 = 1e-3;
/// Largest error estimate of the quadrature that decides a case the importance sampling could not
/// (it is asked for `QUAD_TOL.abs` = 1e-4; grazing `α ≈ 1e-3` lobes reach 2e-3 within the depth limit).
const FALLBACK_QUAD_ERR_MAX: f64 = 1e-2;
/// Largest error estimate of the quadrature of `albedo_by_quadrature_hard_cases`.
const QUAD_ERR_MAX: f64 = 1e-3;

/// How [`energy_check`] decided a case.
#[derive(Clone, Copy, Debug)]
pub struct Verdict {
    /// The albedo estimate.
    pub albedo: f64,
    /// Its standard error (importance sampling) or error estimate / 5 (quadrature).
    pub se: f64,
    /// Which estimator decided.
    pub how: &'static str,
}

/// The energy check of one plugin at one `ωo` (lobe width `w`): `Err` with a description when the
/// directional albedo is shown to exceed 1, or an estimate is not finite.
///
/// What it detects. The importance-sampled estimate `a` ([`albedo_is`]: 64² stratified points, 128² or
/// 256² where the standard error is above `SE_ONE_PERCENT`) fails the
/// case when `a > 1 + 5 se + 1e-6` (`1e-6`: the rounding of the `f32` values of `f`, a few ulps). Where
/// its standard error `se ≤ SE_ONE_PERCENT = 1e-3` it passes only up to `1.005`, while a plugin whose
/// albedo is `1.01` gives `a ≥ 1.01 − 5 se_true ≥ 1.005` except with probability below 3e-7 — a 1 % gain
/// is seen. `directional_albedo_at_most_one_every_plugin` asserts that this holds for at least 97 % of
/// its checks (the rest: grazing `ωo` with sharp lobes, where the weights are heavy-tailed; a gain
/// below 10 % is seen where `se ≤ 0.02`), and [`gain_check`] rejects every
/// such configuration rescaled to albedo 1.01. Above `se = SE_MAX = 0.02` (`pdf` far below `f cos`
/// somewhere) the independent `f64` quadrature, which does not use `pdf`, decides: a loose one is
/// accepted only when it shows the albedo ≤ 1 *including* its error estimate; else a tight one must
/// converge to an error estimate `≤ FALLBACK_QUAD_ERR_MAX = 1e-2` and fails the case when
/// `value > 1 + err + 1e-6`.
pub fn energy_check(
    b: &dyn IsotropicBrdf<Spectrum = f32>,
    wo: Vec3,
    w: f64,
    seed: u64,
) -> Result<Verdict, String> {
    energy_check_allowing(b, wo, w, seed, 0.0)
}

/// [`energy_check`] with a documented `allowance` above 1: a `Coated` layer conserves energy up to its
/// top's albedo error at `ωo` (its base is weighted by what the top's reported albedo lets through;
/// `radiometry::compose::Coated`), so its check allows the top's stated error there.
pub fn energy_check_allowing(
    b: &dyn IsotropicBrdf<Spectrum = f32>,
    wo: Vec3,
    w: f64,
    seed: u64,
    allowance: f64,
) -> Result<Verdict, String> {
    // 64² stratified points; where that leaves `se > SE_ONE_PERCENT`, 128² and then 256² (the
    // collapsed-strata error falls at least as 1/m for a square-integrable weight).
    let mut m = 64;
    let (mut a, mut se) = albedo_is(b, wo, m, seed);
    while se > SE_ONE_PERCENT && m < 256 && a.is_finite() && se.is_finite() {
        m *= 2;
        (a, se) = albedo_is(b, wo, m, seed.wrapping_add(m as u64));
    }
    if !(a.is_finite() && se.is_finite()) {
        return Err(format!("non-finite estimate {a} ± {se}"));
    }
    let v = if se <= SE_MAX {
        Verdict {
            albedo: a,
            se,
            how: "IS",
        }
    } else {
        FALLBACKS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let loose = albedo_quad(b, wo, w, LOOSE_TOL);
        if !(loose.value.is_finite() && loose.err.is_finite()) {
            return Err(format!("non-finite quadrature {loose:?}"));
        }
        if loose.value + loose.err <= 1.0 + 1e-6 {
            Verdict {
                albedo: loose.value,
                se: loose.err / 5.0,
                how: "loose quadrature (albedo + error <= 1)",
            }
        } else {
            let q = albedo_quad(b, wo, w, QUAD_TOL);
            if !(q.value.is_finite() && q.err.is_finite() && q.err <= FALLBACK_QUAD_ERR_MAX) {
                return Err(format!(
                    "quadrature did not converge: {q:?} (IS {a} ± {se:.2e}), required error <= {FALLBACK_QUAD_ERR_MAX:e}"
                ));
            }
            Verdict {
                albedo: q.value,
                se: q.err / 5.0,
                how: "quadrature",
            }
        }
    };
    if v.albedo > 1.0 + allowance + 5.0 * v.se + 1e-6 {
        return Err(format!(
            "energy gain: albedo {:.8} ± {:.2e} ({}), allowance {allowance:.2e}",
            v.albedo, v.se, v.how
        ));
    }
    Ok(v)
}

/// The composites (`Kind::Composite`) are checked on every `COMPOSITE_EVERY`-th case of
/// `directional_albedo_at_most_one_every_plugin` (250 of 500), the other configurations on every case.
/// A composite's energy bound follows from its parts' (a sum with weights summing to at most 1, a convex
/// mix, a coat `E ≤ E_T + (1 − E_T) E_B`), and those parts are checked on all 500 cases; the composites
/// were 44 % of this test's time (its slowest configuration, the coated metal, 20 %), and 250 random
/// parameter sets still put each edge value of the strategies (drawn with weight ≥ 1/5) into dozens of
/// composite checks. Each check keeps its power (a 1 % gain seen where s.e. ≤ 1e-3, [`energy_check`]).
const COMPOSITE_EVERY: u64 = 2;
/// The energy checks done (a composite is skipped on some cases).
static CHECKS: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);

/// Cases of `directional_albedo_at_most_one_every_plugin` whose plugins are also rescaled to an albedo of
/// 1.01 and checked again ([`gain_check`]).
const GAIN_CASES: u64 = 100;

/// The energy check on `CASES` proptest cases × every configuration; on the first `GAIN_CASES` cases
/// each configuration is also rescaled to an albedo of 1.01 and must be rejected (the check's power,
/// see [`gain_check`]). Both run in one pass over the same cases, so the check of a configuration's
/// own albedo, which the rescaling starts from, is computed once.
#[test]
fn directional_albedo_at_most_one_every_plugin() {
    let mut runner = common::runner(CASES);
    let kinds = all_kinds();
    let case = std::sync::atomic::AtomicU64::new(0);
    let rejected = std::sync::atomic::AtomicU64::new(0);
    runner
        .run(&(params(), upper_dir(), 0u64..u64::MAX), |(p, wo, seed)| {
            let wo = to_f32(wo);
            let i = case.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            let gain = i < GAIN_CASES;
            for &k in &kinds {
                // Composites on every second case (see `COMPOSITE_EVERY`).
                if matches!(k, common::plugins::Kind::Composite(_)) && !i.is_multiple_of(COMPOSITE_EVERY) {
                    continue;
                }
                CHECKS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                let b = build(k, &p).unwrap();
                let allowance = common::plugins::coat_top(k, &p)
                    .map_or(0.0, |t| f64::from(t.directional_albedo(wo).error));
                let w = lobe_width(k, &p);
                let v = energy_check_allowing(b.as_ref(), wo, w, seed, allowance)
                    .map_err(|e| TestCaseError::fail(format!("{k:?} {p:?} wo={wo:?}: {e}")))?;
                let ctx = || {
                    format!(
                        "{k:?} {p:?} wo={wo:?}: albedo {:.8} ± {:.2e} ({})",
                        v.albedo, v.se, v.how
                    )
                };
                WORST_ALBEDO.record(v.albedo, ctx);
                WORST_SE.record(v.se, ctx);
                if v.how == "IS" && v.se <= SE_ONE_PERCENT {
                    SEES_ONE_PERCENT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                }
                if gain
                    && gain_check(b.as_ref(), wo, w, seed, &v)
                        .map_err(|e| TestCaseError::fail(format!("{k:?} {p:?} wo={wo:?}: {e}")))?
                {
                    rejected.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                }
            }
            Ok(())
        })
        .unwrap();
    let (a, wa) = WORST_ALBEDO.get();
    let (e, we) = WORST_SE.get();
    eprintln!(
        "energy (IS): {CASES} cases x {} plugins; largest albedo {a:.8} at {wa}",
        kinds.len()
    );
    eprintln!("energy (IS): largest standard error {e:.2e} at {we}");
    let total = CHECKS.load(std::sync::atomic::Ordering::Relaxed);
    let seen = SEES_ONE_PERCENT.load(std::sync::atomic::Ordering::Relaxed);
    eprintln!(
        "energy (IS): {} plugin evaluations fell back to quadrature (s.e. > {SE_MAX:e}); {seen} of {total} checks would see a 1 % gain (s.e. <= {SE_ONE_PERCENT:e})",
        FALLBACKS.load(std::sync::atomic::Ordering::Relaxed)
    );
    // 18,783 of 19,000 (98.9 %) with these seeds when every case checked the composites (500 random
    // configurations; the statistical power of each check is what the assertion is about).
    assert!(
        100 * seen >= 97 * total,
        "only {seen} of {total} checks see a 1 % gain"
    );
    // The check's power, on the first GAIN_CASES cases.
    let rejected = rejected.into_inner();
    eprintln!("energy: {rejected} plugin configurations rescaled to albedo 1.01 rejected");
    assert!(rejected >= 200, "{rejected}");
}

/// `c · f` for a plugin `f`: its sampler and `pdf`, its values and sample weights scaled by `c`.
struct Gain<'a>(&'a dyn IsotropicBrdf<Spectrum = f32>, f32);

impl radiometry::Brdf for Gain<'_> {
    type Spectrum = f32;
    fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
        self.1 * self.0.eval(wi, wo)
    }
    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<radiometry::BrdfSample<f32>> {
        self.0.sample(wo, u).map(|mut s| {
            s.weight *= self.1;
            s
        })
    }
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        self.0.pdf(wi, wo)
    }
}

impl IsotropicBrdf for Gain<'_> {}

/// The check sees a 1 % energy gain (run on the first `GAIN_CASES` cases of
/// `directional_albedo_at_most_one_every_plugin`): every plugin configuration with
/// an albedo of at least 0.9 (so the rescaling, and with it the standard error, grows by at most 12 %) and
/// an importance-sampled standard error `≤ SE_ONE_PERCENT`, rescaled by `1.01 / albedo` to an albedo of
/// 1.01 (the albedo `v` as [`energy_check`] estimated it; the rescaled copy is checked with other sample
/// points), is rejected. `Ok(true)`: rescaled and rejected; `Ok(false)`: not rescaled, or passed where the
/// check reports that it cannot see 1 %; `Err`: passed although the check claims it would see 1 %.
fn gain_check(
    b: &dyn IsotropicBrdf<Spectrum = f32>,
    wo: Vec3,
    w: f64,
    seed: u64,
    a: &Verdict,
) -> Result<bool, String> {
    if a.albedo < 0.9 || a.how != "IS" || a.se > SE_ONE_PERCENT {
        return Ok(false);
    }
    let c = (1.01 / a.albedo) as f32;
    let gained = Gain(b, c);
    match energy_check(&gained, wo, w, seed ^ 0x0005_DEEC_E66D) {
        // Passing is allowed only where the check reports that it cannot see 1 % (a
        // heavy-tailed case whose error estimate at these sample points is above
        // `SE_ONE_PERCENT`; counted in the 3 % of `directional_albedo_at_most_one_every_plugin`).
        Ok(v) if v.how == "IS" && v.se <= SE_ONE_PERCENT => Err(format!(
            "albedo {a:?} rescaled by {c} to ~1.01 passed the check: {v:?}"
        )),
        Ok(_) => Ok(false),
        Err(_) => Ok(true),
    }
}

/// The configurations that read neither `kd` nor `ks` (nor `n`) of [`Params`]; a configuration not
/// listed here (a new one) is integrated for every `(kd, ks)` pair.
fn ignores_kd_ks(k: common::plugins::Kind) -> bool {
    use common::plugins::{Comp, Kind};
    matches!(
        k,
        Kind::Lambertian
            | Kind::Micro(..)
            | Kind::KullaConty(..)
            | Kind::Tabulated(_)
            | Kind::Fon
            | Kind::Eon
            | Kind::OrenNayar
            | Kind::Sheen
            | Kind::Composite(Comp::Plastic | Comp::MixMetalDiffuse | Comp::CoatedMetal)
    )
}

#[test]
fn albedo_by_quadrature_hard_cases() {
    let tol = QUAD_TOL;
    let kinds = all_kinds();
    let mut count = 0;
    // (α = 1e-4 at grazing incidence needs ~10⁸ evaluations per albedo: left to the IS test above.)
    for &(alpha, n, grazing) in &[(1e-4f32, 1e7f32, false), (0.1, 100.0, true), (1.0, 0.0, true)] {
        for &(kd, ks) in &[(0.0f32, 1.0f32), (0.5, 0.5)] {
            let p = Params {
                rho: 1.0,
                kd,
                ks,
                n,
                alpha,
                f0: 1.0,
                eta_d: 0.5,
                eta_c: 0.05,
                k_c: 5.0,
                sigma: 1.0,
                f82: 1.0,
            };
            for &ct in &[1.0f64, 0.5, 1e-3, 1e-6] {
                if !grazing && ct < 0.1 {
                    continue;
                }
                let wo = to_f32(common::strategies::dir(ct, 0.3));
                for &k in &kinds {
                    // A fixed table ignores the parameters: one parameter set (the grazing one) is enough.
                    if matches!(k, common::plugins::Kind::Tabulated(_)) && !(alpha == 1.0 && kd == 0.0) {
                        continue;
                    }
                    // The second (kd, ks) pair would repeat the same integral for a configuration that
                    // reads neither (every parameter it reads is the same in both).
                    if kd != 0.0 && ignores_kd_ks(k) {
                        continue;
                    }
                    let b = build(k, &p).unwrap();
                    let t0 = std::time::Instant::now();
                    // A table's cell edges are kinks the rule cannot place: asked for 1e-4 it spends
                    // ~4·10⁷ evaluations at grazing `ωo`; asked for what is asserted below
                    // (`QUAD_ERR_MAX`) it converges in far fewer.
                    let tol = match k {
                        common::plugins::Kind::Tabulated(_) => Tol {
                            abs: QUAD_ERR_MAX / 2.0,
                            ..tol
                        },
                        _ => tol,
                    };
                    let a = albedo_quad(b.as_ref(), wo, lobe_width(k, &p), tol);
                    if t0.elapsed().as_secs_f64() > 0.5 {
                        eprintln!(
                            "slow: {k:?} α={alpha} n={n} cos θo={ct}: {:?} {:?}",
                            t0.elapsed(),
                            a
                        );
                    }
                    count += 1;
                    let ctx = || format!("{k:?} {p:?} wo={wo:?}: albedo {:.8} ± {:.2e}", a.value, a.err);
                    assert!(a.value.is_finite() && a.err.is_finite(), "{}", ctx());
                    // Converged first (asked for 1e-4; at most 1e-3 accepted), so the slack `err`
                    // below cannot hide a gain above 0.2 %.
                    let a = a.converged(QUAD_ERR_MAX, ctx());
                    // A coated layer may exceed 1 by its top's albedo error (see `energy_check_allowing`).
                    let allowance = common::plugins::coat_top(k, &p)
                        .map_or(0.0, |t| f64::from(t.directional_albedo(wo).error));
                    if allowance == 0.0 {
                        WORST_QUAD.record(a.value, ctx);
                    }
                    assert!(
                        a.value <= 1.0 + allowance + a.err + 1e-6,
                        "energy gain: {} (allowance {allowance:.2e})",
                        ctx()
                    );
                }
            }
        }
    }
    let (a, wa) = WORST_QUAD.get();
    eprintln!("energy (quadrature): {count} cases; largest albedo {a:.8} at {wa}");
}

/// The classic pitfall of normalised Blinn–Phong: with the approximate factor `(n+8)/(8π)` (Akenine-Möller
/// et al.) the lobe albedo at normal incidence is `(n+8)/4 ∫_0^1 ((1+μ)/2)^{n/2} μ dμ`, which exceeds 1
/// for every `n > 0` (1.075 at `n = 8`; our own f64 evaluation). A plugin that conserves energy must stay
/// ≤ 1 here; the same check for modified Phong, where the exact value is 1 (Lafortune & Willems 1994).
#[test]
fn phong_family_lobe_albedo_at_normal_incidence_at_most_one() {
    for k in [
        common::plugins::Kind::BlinnPhong,
        common::plugins::Kind::ModifiedPhong,
    ] {
        for &n in &[0.5f32, 1.0, 2.0, 4.0, 8.0, 20.0, 100.0] {
            let p = Params {
                kd: 0.0,
                ks: 1.0,
                n,
                ..Params::typical()
            };
            let b = build(k, &p).unwrap();
            let tol = Tol {
                abs: 1e-7,
                rel: 1e-7,
                depth: 10,
            };
            let a = albedo_quad(b.as_ref(), Vec3::Z, lobe_width(k, &p), tol);
            eprintln!(
                "{k:?} ks=1 n={n} normal incidence: albedo {:.7} ± {:.1e}",
                a.value, a.err
            );
            // The classic pitfall is a 7.5 % gain at n = 8: the reference must have converged to
            // 1e-6 (it is asked for 1e-7) before its error is used as slack.
            let a = a.converged(1e-6, format!("{k:?} n={n}"));
            assert!(a.value <= 1.0 + a.err + 1e-6, "{k:?} n={n}: {a:?}");
        }
    }
}

/// Regression for a finding of this suite: rings around the mirror direction do not resolve the band
/// `cos θi < cos θo` at the horizon of the rough diffuse models at grazing `ωo` (the quadrature converged,
/// error estimate 4e-11, to a value 2.3e-4 too high — an "energy gain" of EON that was not there).
/// [`albedo_quad`] now integrates broad lobes around the normal with a break at `θo`; it must reproduce
/// FON's exact albedo `E_FON(μo) = (1 + σ G(μo)/π)/(1 + c₁σ)` (Portsmouth, Kutz & Hill 2025; our own
/// `f64` copy of the formula) at ρ = 1, σ = 1, and EON's 1.
#[test]
fn quadrature_resolves_the_rough_diffuse_band_at_grazing() {
    use common::plugins::Kind;
    use std::f64::consts::PI;
    let e_fon = |mu: f64| {
        let si = (1.0 - mu * mu).sqrt();
        let g = si * (mu.acos() - si * mu) + (2.0 / 3.0) * ((si / mu) * (1.0 - si * si * si) - si);
        (1.0 + g / PI) / (1.0 + 0.5 - 2.0 / (3.0 * PI))
    };
    let p = Params {
        rho: 1.0,
        sigma: 1.0,
        ..Params::typical()
    };
    let tol = Tol {
        abs: 1e-7,
        rel: 1e-7,
        depth: 12,
    };
    for &ct in &[1e-3f64, 1e-2, 0.5] {
        let wo = to_f32(common::strategies::dir(ct, 0.3));
        let mu = common::strategies::to_f64(wo).normalize().z;
        for (k, want) in [(Kind::Fon, e_fon(mu)), (Kind::Eon, 1.0)] {
            let b = build(k, &p).unwrap();
            let a =
                albedo_quad(b.as_ref(), wo, lobe_width(k, &p), tol).converged(1e-6, format!("{k:?} {ct}"));
            assert!(
                (a.value - want).abs() < 1e-6,
                "{k:?} cos θo = {ct}: {a:?} vs {want}"
            );
        }
    }
}
