//! Monte Carlo and randomized quasi-Monte Carlo integrators: uniform,
//! cosine-weighted and integrand importance sampling, and multiple
//! importance sampling (MIS) of cosine + integrand sampling with the
//! balance or power heuristic, over any [`PointSet`].

use super::acc::{self, Moments, SampleDiagnostics};
use super::chunk::{CHUNK, head, head_mut, sample_weight};
use super::points::{
    Pcg32, PointSet, SOBOL_MAX_POINTS, fibonacci_point, jitter_grid, jittered_point, mix_seed,
    sobol_point_pairs, square_to_cosine_hemisphere_polar,
};
use super::probe::{self, PROBE_POINTS, Probe};
use super::{Estimate, Integrand, IntegrateError, Integrator, WideOf, check_finite};
use crate::spectrum::{Spectrum, WideSpectrum};
use crate::warp::{square_to_cosine_hemisphere, square_to_uniform_hemisphere};
use core::f64::consts::{FRAC_1_PI, TAU};
use glam::Vec3;

/// The MIS weighting heuristic (Veach 1997, PhD thesis, §9.2).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Heuristic {
    /// Balance heuristic `wᵢ = pᵢ / Σⱼ pⱼ` (Veach 1997, Eq. 9.10).
    Balance,
    /// Power heuristic with exponent β = 2, `wᵢ = pᵢ² / Σⱼ pⱼ²`
    /// (Veach 1997, Eq. 9.13).
    Power,
}

/// How directions are drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Strategy {
    /// Uniform over the hemisphere, `p = 1/(2π)`; estimator `2π g(ω)`.
    Uniform,
    /// Cosine-weighted, `p = cos θ/π` (Malley's method, PBRT 4th ed.
    /// §A.5.3); estimator `π g(ω)/cos θ` (0 at `cos θ = 0`, a null set).
    /// Its variance is infinite when `g` does not vanish at the horizon
    /// (the weight grows like `1/cos θ`): the standard error is then not
    /// reliable (measured: 94 % of runs within 3σ for `g = 1 + …` at 256
    /// samples); use it for integrands carrying a `cos θ` factor.
    Cosine,
    /// The integrand's own sampling map ([`Integrand::sample`]); estimator
    /// `g(ω)/p(ω)`, 0 where the map returns `None`.
    Integrand,
    /// Multi-sample MIS of [`Strategy::Cosine`] and [`Strategy::Integrand`]
    /// with one sample from each per draw (Veach 1997, Eq. 9.4 with
    /// `n₁ = n₂ = 1`): `F = w₁(X₁) g(X₁)/p₁(X₁) + w₂(X₂) g(X₂)/p₂(X₂)`.
    /// Each draw costs two evaluations.
    Mis(Heuristic),
}

impl Strategy {
    /// All strategies, in a fixed order.
    pub const ALL: [Strategy; 5] = [
        Strategy::Uniform,
        Strategy::Cosine,
        Strategy::Integrand,
        Strategy::Mis(Heuristic::Balance),
        Strategy::Mis(Heuristic::Power),
    ];

    fn index(self) -> usize {
        match self {
            Strategy::Uniform => 0,
            Strategy::Cosine => 1,
            Strategy::Integrand => 2,
            Strategy::Mis(Heuristic::Balance) => 3,
            Strategy::Mis(Heuristic::Power) => 4,
        }
    }

    const fn cost(self) -> u32 {
        if let Strategy::Mis(_) = self { 2 } else { 1 }
    }
}

const NAMES: [[&str; 4]; 5] = [
    [
        "mc-uniform-prng",
        "mc-uniform-stratified",
        "mc-uniform-sobol",
        "mc-uniform-fibonacci",
    ],
    [
        "mc-cosine-prng",
        "mc-cosine-stratified",
        "mc-cosine-sobol",
        "mc-cosine-fibonacci",
    ],
    [
        "mc-integrand-prng",
        "mc-integrand-stratified",
        "mc-integrand-sobol",
        "mc-integrand-fibonacci",
    ],
    [
        "mis-balance-prng",
        "mis-balance-stratified",
        "mis-balance-sobol",
        "mis-balance-fibonacci",
    ],
    [
        "mis-power-prng",
        "mis-power-stratified",
        "mis-power-sobol",
        "mis-power-fibonacci",
    ],
];

fn point_index(p: PointSet) -> usize {
    match p {
        PointSet::Prng => 0,
        PointSet::Stratified => 1,
        PointSet::Sobol => 2,
        PointSet::Fibonacci => 3,
    }
}

/// Most evaluations any [`MonteCarlo`] run spends (`2²⁰` = 1,048,576);
/// larger budgets are capped (and `evaluations` says what was spent).
pub const MAX_MC_EVALUATIONS: u32 = 1 << 20;

/// Default number of independent randomizations for RQMC point sets.
pub const DEFAULT_REPLICATES: u32 = 16;

/// Monte Carlo / randomized QMC estimator of `∫_H g dω`.
///
/// * `PointSet::Prng`: `N` i.i.d. draws; value = sample mean of the
///   estimator `F` (see [`Strategy`]), error = the standard error `s/√N`
///   (Owen, *Monte Carlo theory, methods and examples*, 2013, §2.1).
/// * `Stratified`, `Sobol`, `Fibonacci` (randomized QMC): `K` independent
///   randomizations (fresh jitter / Owen scramble seed / toroidal shift;
///   default `K = 16`), each with `⌊N/K⌋` points; value = mean of the `K`
///   replicate means, error = their standard error `s_K/√K` (Owen 2013,
///   §17.2; L'Ecuyer & Lemieux 2002). With `K = 16` the ratio
///   (true error)/(error) follows roughly Student's t with 15 degrees of
///   freedom, so `|error| ≤ 3σ` holds ≈ 99.1 % of the time (vs 99.7 % for
///   the normal limit of `Prng`).
/// * Both add two floors to the error, for what no variance estimate can
///   see: the `f32` rounding floor `2⁻²³ · mean|F|` (each integrand value
///   is an `f32` carrying up to about an ulp of systematic rounding; the
///   quadrature rules add the same floor) and the resolution floor
///   `mean|F| / N` over `N` draws (an event of probability `p ≲ 1/N` is
///   likely never drawn and then moves the mean by `≈ p · mean` unseen —
///   e.g. the sliver where an importance-sampling map leaves the
///   hemisphere while every other weight is ≈ 1).
/// * Status ([`super::Status`]): no non-zero draw → `NoSupportSeen`; fewer
///   than [`super::MIN_HITS`] → `FewHits`; effective sample size
///   `(Σ|F|)²/ΣF²` below [`super::MIN_EFFECTIVE_SAMPLES`] → `HeavyTail`.
///   The blind strategies (`Uniform`, `Cosine`) also take the peak probe of
///   [`super::probe`] when the integrand has a sampling map (at budgets
///   ≥ [`super::probe::PROBE_MIN_BUDGET`]; its [`super::probe::PROBE_POINTS`]
///   evaluations come out of the budget): a probe value above
///   [`super::probe::PEAK_RATIO`] × the largest `|g|` at any draw →
///   `UnseenPeak` (a lobe the draws never came near: their mean converges
///   to the tails with a small standard error).
///
/// Sobol: one scramble holds at most `2¹⁶` points ([`super::points::SOBOL_MAX_POINTS`]), so when
/// `⌊N/K⌋ > 2¹⁶` the number of scrambles grows to `⌈N/2¹⁶⌉` (≤ 16 under
/// the cap). Jittered grids use `⌊√n⌋ × ⌊n/⌊√n⌋⌋ ≤ n` cells per replicate.
/// Cosine sampling uses the concentric map of [`crate::warp`] except with
/// the Fibonacci lattice, which uses the polar map (making it the
/// spherical Fibonacci set of Marques et al. 2013).
///
/// Budget: each draw costs 1 evaluation (2 for MIS); at most
/// [`MAX_MC_EVALUATIONS`] are spent. Minimum budget: 2 draws for `Prng`,
/// `K` draws otherwise ([`IntegrateError::BudgetTooSmall`] below). A NaN/∞
/// integrand value, sampled value or density gives
/// [`IntegrateError::NonFiniteIntegrand`]. Deterministic for
/// `(strategy, points, seed, replicates)`.
///
/// ```
/// use radiometry::integrator::{Integrand, Integrator, MonteCarlo, PointSet, Strategy};
/// use radiometry::glam::Vec3;
/// struct Cos2;
/// impl Integrand for Cos2 {
///     type Spectrum = f32;
///     fn eval(&self, w: Vec3) -> f32 { w.z * w.z }
/// }
/// let mc = MonteCarlo::new(Strategy::Cosine, PointSet::Sobol, 7);
/// assert_eq!(mc.name(), "mc-cosine-sobol");
/// let e = mc.integrate(&Cos2, 4096).unwrap();
/// let exact = 2.0 * core::f64::consts::PI / 3.0;
/// assert!((e.value - exact).abs() < 5.0 * e.error + 1e-9);
/// assert_eq!(e.evaluations, 4096);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct MonteCarlo {
    /// Sampling strategy.
    pub strategy: Strategy,
    /// Point set on the unit square.
    pub points: PointSet,
    /// Seed of every random choice.
    pub seed: u64,
    replicates: u32,
}

impl MonteCarlo {
    /// A Monte Carlo integrator with [`DEFAULT_REPLICATES`] randomizations
    /// for RQMC point sets.
    pub const fn new(strategy: Strategy, points: PointSet, seed: u64) -> Self {
        Self {
            strategy,
            points,
            seed,
            replicates: DEFAULT_REPLICATES,
        }
    }

    /// Sets the number `K` of independent randomizations used by RQMC
    /// point sets (ignored by `Prng`). Valid: `2 ≤ K ≤ 64`, else
    /// [`IntegrateError::InvalidConfig`].
    pub const fn with_replicates(mut self, k: u32) -> Result<Self, IntegrateError> {
        if k < 2 || k > 64 {
            return Err(IntegrateError::InvalidConfig("replicates must be in 2..=64"));
        }
        self.replicates = k;
        Ok(self)
    }

    /// The number of RQMC randomizations `K`.
    pub const fn replicates(&self) -> u32 {
        self.replicates
    }

    /// Smallest accepted budget.
    pub const fn min_budget(&self) -> u32 {
        let draws = match self.points {
            PointSet::Prng => 2,
            _ => self.replicates,
        };
        draws * self.strategy.cost()
    }
}

/// The estimators `out[k] = F(u1[k], u2[k])` (see [`Strategy`]) of a chunk
/// of draws (`n = u1.len() ≤ CHUNK`, `u2` and `out` at least as long; `u2`
/// is used by MIS only), through the batch methods of the integrand; the
/// first non-finite value in draw order is reported. (The cosine strategy
/// evaluates `g` at `cos θ = 0` too, where `p = 0`, and ignores it there.)
fn draw_batch<I: Integrand>(
    g: &I,
    strategy: Strategy,
    polar: bool,
    u1: &[[f32; 2]],
    u2: &[[f32; 2]],
    out: &mut [WideOf<I>],
    peak: &mut f64,
) -> Result<(), IntegrateError> {
    let n = u1.len().min(CHUNK);
    let (u1, u2, out) = (head(u1, n), head(u2, n), head_mut(out, n));
    let zero = WideOf::<I>::splat(0.0);
    let mut dirs = [Vec3::ZERO; CHUNK];
    let mut vals = [I::Spectrum::zero(); CHUNK];
    let cosine_dirs = |dirs: &mut [Vec3]| {
        for (d, &u) in dirs.iter_mut().zip(u1) {
            *d = if polar {
                square_to_cosine_hemisphere_polar(u)
            } else {
                square_to_cosine_hemisphere(u)
            };
        }
    };
    match strategy {
        Strategy::Uniform => {
            for (d, &u) in head_mut(&mut dirs, n).iter_mut().zip(u1) {
                *d = square_to_uniform_hemisphere(u);
            }
            g.eval_batch(head(&dirs, n), head_mut(&mut vals, n));
            for (o, v) in out.iter_mut().zip(head(&vals, n)) {
                let v = check_finite(v.to_wide())?;
                *peak = peak.max(acc::max_abs(v));
                *o = v.map(|v| v * TAU);
            }
        }
        Strategy::Cosine => {
            cosine_dirs(head_mut(&mut dirs, n));
            g.eval_batch(head(&dirs, n), head_mut(&mut vals, n));
            for ((o, v), w) in out.iter_mut().zip(head(&vals, n)).zip(head(&dirs, n)) {
                let p = w.z as f64 * FRAC_1_PI;
                *o = if p <= 0.0 {
                    zero
                } else {
                    let v = check_finite(v.to_wide())?;
                    *peak = peak.max(acc::max_abs(v));
                    v.map(|v| v / p)
                };
            }
        }
        Strategy::Integrand => {
            let mut samples = [None; CHUNK];
            g.sample_batch(u1, head_mut(&mut samples, n));
            for (o, &s) in out.iter_mut().zip(head(&samples, n)) {
                *o = match sample_weight(s)? {
                    Some((_, _, weight)) => weight,
                    None => zero,
                };
            }
        }
        Strategy::Mis(h) => {
            let pw = |p: f64| match h {
                Heuristic::Balance => p,
                Heuristic::Power => p * p,
            };
            // Strategy 1 (cosine) values and the other technique's density
            // there; strategy 2 (the integrand's map) draws.
            cosine_dirs(head_mut(&mut dirs, n));
            let mut pdfs = [0.0f32; CHUNK];
            let mut samples = [None; CHUNK];
            g.eval_batch(head(&dirs, n), head_mut(&mut vals, n));
            g.pdf_batch(head(&dirs, n), head_mut(&mut pdfs, n));
            g.sample_batch(u2, head_mut(&mut samples, n));
            // `out` holds the `n` draws: the zip visits `k < n`.
            for ((((o, d), v), &q), &s) in out.iter_mut().zip(&dirs).zip(&vals).zip(&pdfs).zip(&samples) {
                let p1 = d.z as f64 * FRAC_1_PI;
                let mut total = zero;
                if p1 > 0.0 {
                    let f = check_finite(v.to_wide())?;
                    if !q.is_finite() {
                        return Err(IntegrateError::NonFiniteIntegrand);
                    }
                    let q = (q as f64).max(0.0);
                    // w₁ f/p₁ = f · pw(p₁)/p₁ / (pw(p₁) + pw(q))
                    let k1 = (pw(p1) / p1) / (pw(p1) + pw(q));
                    total = f.map(|v| v * k1);
                }
                if let Some((w2, p2, weight)) = sample_weight(s)? {
                    let c = (w2.z as f64 * FRAC_1_PI).max(0.0);
                    let k2 = pw(p2) / (pw(p2) + pw(c));
                    total = acc::add(total, weight.map(|v| v * k2));
                }
                *o = total;
            }
        }
    }
    Ok(())
}

/// Draws pushed into the moments at a time ([`Moments::push_chunk`]: its
/// per-chunk partial sums are part of the estimate's bits, so this stays 64
/// whatever the batch size [`CHUNK`] of the integrand calls).
const DRAWS: usize = 64;

/// Buffers the unit-square points of up to [`DRAWS`] draws, evaluates them
/// with [`draw_batch`], [`CHUNK`] at a time, when full (or on
/// [`Draws::flush`]) and pushes the estimators into the moments in draw order.
struct Draws<'g, I> {
    g: &'g I,
    strategy: Strategy,
    polar: bool,
    n: usize,
    u1: [[f32; 2]; DRAWS],
    u2: [[f32; 2]; DRAWS],
    /// The largest `max_channel |g|` at a drawn direction (uniform and
    /// cosine strategies; compared with the peak probe).
    peak: f64,
}

impl<'g, I: Integrand> Draws<'g, I> {
    fn new(g: &'g I, strategy: Strategy, polar: bool) -> Self {
        Self {
            g,
            strategy,
            polar,
            n: 0,
            u1: [[0.0; 2]; DRAWS],
            u2: [[0.0; 2]; DRAWS],
            peak: 0.0,
        }
    }

    /// Queues the draw `(u1, u2)`.
    #[inline]
    fn push(&mut self, u1: [f32; 2], u2: [f32; 2], m: &mut Moments<WideOf<I>>) -> Result<(), IntegrateError> {
        // `n < DRAWS` between calls (a full queue is flushed at once); the
        // checked writes keep the code free of panic paths.
        if let (Some(a), Some(b)) = (self.u1.get_mut(self.n), self.u2.get_mut(self.n)) {
            *a = u1;
            *b = u2;
            self.n += 1;
        }
        if self.n >= DRAWS { self.flush(m) } else { Ok(()) }
    }

    /// Evaluates the queued draws into `m`.
    fn flush(&mut self, m: &mut Moments<WideOf<I>>) -> Result<(), IntegrateError> {
        let n = core::mem::replace(&mut self.n, 0).min(DRAWS);
        let mut vals = [WideOf::<I>::splat(0.0); DRAWS];
        // In draw order, CHUNK at a time: the first non-finite value in draw
        // order is reported, as one call over all the draws would.
        let parts = head(&self.u1, n)
            .chunks(CHUNK)
            .zip(head(&self.u2, n).chunks(CHUNK))
            .zip(head_mut(&mut vals, n).chunks_mut(CHUNK));
        for ((u1, u2), out) in parts {
            draw_batch(self.g, self.strategy, self.polar, u1, u2, out, &mut self.peak)?;
        }
        m.push_chunk(head(&vals, n));
        Ok(())
    }
}

impl Integrator for MonteCarlo {
    /// `0.5`: the standard error of `N` draws falls like `N^-½` (randomized
    /// QMC may do better, never worse in expectation).
    fn error_decay(&self) -> Option<f64> {
        Some(0.5)
    }

    /// [`MAX_MC_EVALUATIONS`].
    fn max_evaluations(&self) -> Option<u64> {
        Some(MAX_MC_EVALUATIONS as u64)
    }

    fn integrate<I: Integrand>(&self, g: &I, budget: u32) -> Result<Estimate<WideOf<I>>, IntegrateError> {
        if matches!(self.strategy, Strategy::Integrand | Strategy::Mis(_)) && !g.has_sampling_map() {
            return Err(IntegrateError::NoSamplingMap);
        }
        if budget < self.min_budget() {
            return Err(IntegrateError::BudgetTooSmall {
                minimum: self.min_budget(),
            });
        }
        let cost = self.strategy.cost();
        // The blind strategies (uniform, cosine) probe the integrand's own
        // sampling map for a peak their draws never came near.
        let blind = matches!(self.strategy, Strategy::Uniform | Strategy::Cosine);
        let (budget, probing) = if blind {
            probe::split_budget(g, budget.min(MAX_MC_EVALUATIONS), self.min_budget())
        } else {
            (budget, false)
        };
        let probe = if probing { Some(Probe::take(g)?) } else { None };
        let judge = |status, peak: f64| match &probe {
            Some(p) => probe::judge(status, peak, p.peak()),
            None => status,
        };
        let extra = if probing { PROBE_POINTS as u64 } else { 0 };
        let draws = budget.min(MAX_MC_EVALUATIONS) / cost;
        let polar = self.points == PointSet::Fibonacci;
        let mut batch = Draws::new(g, self.strategy, polar);

        if self.points == PointSet::Prng {
            let mut rng = Pcg32::with_stream(self.seed, 0x5851_f42d);
            let mut m = Moments::<WideOf<I>>::new();
            for _ in 0..draws {
                let u1 = [rng.next_f32(), rng.next_f32()];
                let u2 = if cost == 2 {
                    [rng.next_f32(), rng.next_f32()]
                } else {
                    [0.0; 2]
                };
                batch.push(u1, u2, &mut m)?;
            }
            batch.flush(&mut m)?;
            return Ok(Estimate {
                value: m.mean(),
                error: acc::add(m.standard_error(), m.diag.floors(m.count())),
                evaluations: m.count() * cost as u64 + extra,
                status: judge(m.diag.status(), batch.peak),
            });
        }

        // `replicates ≥ 2` (checked by `with_replicates`); `max(1)` keeps the
        // division free of a panic path by construction.
        let mut k = self.replicates.max(1);
        if self.points == PointSet::Sobol {
            k = k.max(draws.div_ceil(SOBOL_MAX_POINTS));
        }
        let n = draws / k;
        let mut reps = Moments::<WideOf<I>>::new();
        let mut diag = SampleDiagnostics::<WideOf<I>>::new();
        let mut spent = 0u64;
        for r in 0..k {
            let rseed = mix_seed(self.seed, r as u64);
            let mut rng = Pcg32::with_stream(rseed, 0xda3e_39cb);
            let mut m = Moments::<WideOf<I>>::new();
            match self.points {
                PointSet::Stratified => {
                    let (nx, ny) = jitter_grid(n);
                    for i in 0..nx * ny {
                        let u1 = jittered_point(i, nx, ny, [rng.next_f32(), rng.next_f32()]);
                        let u2 = if cost == 2 {
                            jittered_point(i, nx, ny, [rng.next_f32(), rng.next_f32()])
                        } else {
                            [0.0; 2]
                        };
                        batch.push(u1, u2, &mut m)?;
                    }
                }
                PointSet::Sobol => {
                    let sseed = (rseed ^ (rseed >> 32)) as u32;
                    for i in 0..n.min(SOBOL_MAX_POINTS) {
                        // One four-dimensional draw: pairs 0 (u₁) and 1 (u₂).
                        let [u1, u2] = sobol_point_pairs(i, sseed);
                        let u2 = if cost == 2 { u2 } else { [0.0; 2] };
                        batch.push(u1, u2, &mut m)?;
                    }
                }
                PointSet::Fibonacci | PointSet::Prng => {
                    let sh1 = [rng.next_f64(), rng.next_f64()];
                    let sh2 = [rng.next_f64(), rng.next_f64()];
                    for i in 0..n {
                        let u1 = fibonacci_point(i, n, sh1);
                        let u2 = if cost == 2 {
                            fibonacci_point(i, n, sh2)
                        } else {
                            [0.0; 2]
                        };
                        batch.push(u1, u2, &mut m)?;
                    }
                }
            }
            batch.flush(&mut m)?;
            spent += m.count() * cost as u64;
            reps.push(m.mean());
            diag.merge(&m.diag);
        }
        Ok(Estimate {
            value: reps.mean(),
            error: acc::add(reps.standard_error(), diag.floors(spent / cost as u64)),
            evaluations: spent + extra,
            status: judge(diag.status(), batch.peak),
        })
    }

    fn name(&self) -> &'static str {
        NAMES[self.strategy.index()][point_index(self.points)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    struct Poly;
    impl Integrand for Poly {
        type Spectrum = f32;
        fn eval(&self, w: Vec3) -> f32 {
            1.0 + w.x * w.x + 2.0 * w.z * w.z * w.z
        }
    }

    #[test]
    fn names_are_unique_and_budgets_respected() {
        let mut seen = [""; 20];
        let mut c = 0;
        for s in Strategy::ALL {
            for p in PointSet::ALL {
                let mc = MonteCarlo::new(s, p, 1);
                let n = mc.name();
                assert!(!seen[..c].contains(&n), "{n}");
                seen[c] = n;
                c += 1;
                if matches!(s, Strategy::Uniform | Strategy::Cosine) {
                    let e = mc.integrate(&Poly, 1000).unwrap();
                    assert!(
                        e.evaluations <= 1000 && e.evaluations >= 500,
                        "{n} {}",
                        e.evaluations
                    );
                    // ∫(1 + x² + 2z³) dω = 2π + 2π/3 + π
                    let exact = TAU + TAU / 3.0 + core::f64::consts::PI;
                    assert!((e.value - exact).abs() < 6.0 * e.error + 1e-9, "{n} {e:?}");
                }
            }
        }
    }

    #[test]
    fn deterministic_per_seed() {
        let mc = MonteCarlo::new(Strategy::Uniform, PointSet::Sobol, 3);
        assert_eq!(mc.integrate(&Poly, 256), mc.integrate(&Poly, 256));
        let other = MonteCarlo::new(Strategy::Uniform, PointSet::Sobol, 4);
        assert_ne!(mc.integrate(&Poly, 256), other.integrate(&Poly, 256));
        assert!(
            MonteCarlo::new(Strategy::Uniform, PointSet::Sobol, 4)
                .with_replicates(1)
                .is_err()
        );
    }
}
