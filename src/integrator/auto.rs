//! [`Auto`]: the integrator that picks its own parameterisation and reuses
//! its work between refinements.

use super::acc::{self, F32_FLOOR};
use super::chart::peak::ASPECT_RANGE;
use super::chart::{Chart, PeakChart, ProductChart};
use super::chunk::{self, CHUNK, head, head_mut};
use super::confirm;
use super::probe::{self, Probe};
use super::{
    Adaptive, Estimate, Integrand, IntegrateError, Integrator, Status, ToleranceOutcome, Unresolved, WideOf,
    check_tolerance_args,
};
use crate::spectrum::{Spectrum as _, WideSpectrum};

/// Finest Clenshaw–Curtis level in `μ`: `2⁷ + 1 = 129` nodes.
const MAX_A: u32 = 7;
/// Nodes of the finest `μ` level.
const NMU: usize = (1 << MAX_A) + 1;
/// Finest trapezoid level in `φ`: `2¹⁰ = 1024` nodes.
const MAX_B: u32 = 10;
/// First levels: 9 × 8 nodes.
const A0: u32 = 3;
const B0: u32 = 3;

/// Azimuth offset (in turns) of the trapezoid nodes, `(√5 − 1)/2`: no node
/// row lies on the symmetry lines `φ ∈ {0, π/2, π, 3π/2}` of a BRDF lobe.
const PHI_OFFSET: f64 = 0.618_033_988_749_894_9;

/// A pilot peakiness (see [`Auto`]) above this marks a lobe as narrow:
/// [`Auto`] then integrates on the sampling-map square (the plain grid
/// would need too many nodes). Measured on the report's GGX cases at
/// `10⁻⁶`: the grid needs fewer evaluations up to a peakiness of a few
/// hundred (α = 0.05 at θo ≤ 60°: 190–390), the warped rule from about
/// 2,000 (α = 0.05 at θo ≥ 85°, α ≤ 0.01).
pub const NARROW_PEAKINESS: f64 = 300.0;

/// A pilot peakiness above this integrates on the peak-centred chart
/// (see [`Auto`]) first.
const PEAK_CHART_PEAKINESS: f64 = 30.0;

/// Largest pilot peakiness for the peak-centred chart. Beyond it (GGX
/// α = 0.001 away from the horizon) the lobe is a few 10⁻³ rad wide and the
/// plugin's `f32` value near the peak carries a bias the grid cannot see
/// (`1 − cos² θ_h` from an `f32` half vector): GGX α = 0.001 at θo = 60°
/// answered 6·10⁻⁶ off with a claim of 6.5·10⁻⁷, where the warped rule —
/// whose weights `f cos θ / pdf` cancel the peak — is exact to 10⁻⁷.
const MAX_PEAK_CHART_PEAKINESS: f64 = 1e5;

/// Twins of a chart [`Auto`] tries to confirm a chart's grid (see
/// `Chart::twin`).
const CHART_TWINS: usize = 2;

/// A chart's grid that did not meet the tolerance still confirms one that
/// did when it is resolved, agrees within `tol`, and its own error estimate
/// is at most `NEAR_MET × tol` (on narrow grazing lobes the estimate of a
/// narrower chart carries the `f32` rounding of its nodes, about 10⁻⁶).
const NEAR_MET: f64 = 4.0;

/// Least budget left for a twin's grid.
const CHART_TWIN_MIN_BUDGET: u64 = 1024;

/// Smallest pole height `cos θ` (78.5°) at which [`Auto`] tries the
/// peak-centred chart: closer to the horizon a narrow lobe is cut by it
/// along a rapidly turning edge and the grid cost more than the warped
/// adaptive rule on the report's GGX cases (α = 0.05 and 0.01 at 85°).
const MIN_CHART_POLE_Z: f64 = 0.2;

/// The chart's squared width per inverse peakiness: `w² = W2_PER_PEAKINESS / P`
/// (a lobe `(w² + s²)⁻²` has `P = 1/w²`).
const W2_PER_PEAKINESS: f64 = 1.0;

/// The chart for the pilot's lobe, if it is peaked enough to need one: the
/// peak-centred chart when its pole is at least [`MIN_CHART_POLE_Z`] high,
/// the product chart below.
fn chart_for(p: &Pilot, smooth: bool) -> Option<Chart> {
    if !(smooth && p.peakiness > PEAK_CHART_PEAKINESS && p.peakiness.is_finite()) {
        return None;
    }
    let pole = p.pole?;
    let pts = p.probe.points();
    if (pole.z as f64) < MIN_CHART_POLE_Z {
        // Grazing: near the horizon `ω_z` is exact to its own relative
        // precision, and the product chart's lobes at 85°–89.9° came out
        // within 3·10⁻⁷ (GGX α = 0.001 included). Widths of the product chart: the medians of |μ − μ_p| and of the
        // wrapped |φ − φ_p| over the probe points, times √3 (the median of
        // |d| under the lobe marginal (w² + d²)^{−3/2} is w/√3).
        let (mu_p, phi_p) = (pole.z as f64, libm::atan2(pole.y as f64, pole.x as f64));
        let mut dm = [0.0f64; probe::PROBE_POINTS];
        let mut dp = [0.0f64; probe::PROBE_POINTS];
        let mut n = 0;
        for &(w, _) in pts {
            let d = libm::atan2(w.y as f64, w.x as f64) - phi_p;
            let d = libm::remainder(d, core::f64::consts::TAU);
            if let (Some(a), Some(b)) = (dm.get_mut(n), dp.get_mut(n)) {
                (*a, *b) = ((w.z as f64 - mu_p).abs(), d.abs());
                n += 1;
            }
        }
        let (m1, m2) = (median(dm.get(..n)?)?, median(dp.get(..n)?)?);
        let s3 = libm::sqrt(3.0);
        let floor = 1e-6;
        return ProductChart::new(mu_p, phi_p, (s3 * m1).max(floor), (s3 * m2).max(floor))
            .map(Chart::Product);
    }
    if p.peakiness > MAX_PEAK_CHART_PEAKINESS {
        return None;
    }
    // The lobe's aspect k = w₂/w₁ from the probe points' stereographic
    // coordinates about the pole, a_i = (ω·e_i)/(1 + ω·p): the ratio of the
    // medians of |a₂| and |a₁| (medians: GGX-like lobes have no variance).
    let c = PeakChart::new(pole, 1.0, 1.0)?;
    let (e1, e2) = c.frame();
    let pd = pole.as_dvec3().normalize();
    let mut a1 = [0.0f64; probe::PROBE_POINTS];
    let mut a2 = [0.0f64; probe::PROBE_POINTS];
    let mut n = 0;
    for &(w, _) in pts {
        let w = w.as_dvec3();
        let den = 1.0 + w.dot(pd);
        let (x1, x2) = (w.dot(e1) / den, w.dot(e2) / den);
        if den > 0.0
            && (x1 != 0.0 || x2 != 0.0)
            && let (Some(u), Some(v)) = (a1.get_mut(n), a2.get_mut(n))
        {
            (*u, *v) = (x1.abs(), x2.abs());
            n += 1;
        }
    }
    let k = match (median(a1.get(..n)?), median(a2.get(..n)?)) {
        (Some(m1), Some(m2)) if m1 > 0.0 && m2 > 0.0 => m2 / m1,
        _ => 1.0,
    };
    // P = 1/(w₁ w₂) for a lobe (w₁² + a₁² + (a₂ w₁/w₂)²)⁻²-like: w₁² = 1/(P k).
    PeakChart::new(
        pole,
        W2_PER_PEAKINESS / (p.peakiness * k.clamp(ASPECT_RANGE.0, ASPECT_RANGE.1)),
        k,
    )
    .map(Chart::Peak)
}

/// The median of `v`; `None` when empty. By ranks (`v` has at most
/// [`probe::PROBE_POINTS`] elements), so that no sort and no index keeps a
/// panic path in the no-panic builds.
fn median(v: &[f64]) -> Option<f64> {
    let kth = |r: usize| {
        v.iter().copied().find(|&x| {
            let lt = v.iter().filter(|&&y| y < x).count();
            let le = v.iter().filter(|&&y| y <= x).count();
            lt <= r && r < le
        })
    };
    let n = v.len();
    let hi = kth(n / 2)?;
    Some(if n.is_multiple_of(2) {
        0.5 * (hi + kth(n / 2 - 1)?)
    } else {
        hi
    })
}

/// The `auto` integrator: for an integrand and a tolerance, the
/// parameterisation and rule that need the fewest evaluations, with the
/// work of each refinement kept for the next.
///
/// 0. **Kinked mixtures, fixed budget** (an integrand that is not
///    [smooth](Integrand::is_smooth) and samples through a mixture map, see
///    [`Integrand::sampling_components`]: the composites, the Oren–Nayar
///    family): with a fixed budget ([`Integrator::integrate`]) no pilot and
///    no grid — the plain [`Adaptive`] rule split at the integrand's
///    [kinks](Integrand::kinks) with half the budget, and only if it is
///    unresolved the warped rule (per component) with the rest (see
///    `plain_first`). To a tolerance the steps below apply to every
///    integrand.
/// 1. **Pilot** (with a sampling map): 16 draws of the map (the points of
///    the peak [`probe`]) give the lobe's *peakiness* `P = 2π max g / Î`,
///    `Î` the importance-sampled mean — the largest value of the plain-square
///    integrand `2π g` over its mean, about the inverse of the fraction of
///    the square the lobe covers (2 for a cosine lobe, 6–25 for GGX
///    `α = 0.3`, 5·10³–6·10⁵ for `α = 0.01`).
/// 2. **Broad lobes** (`P ≤` [`NARROW_PEAKINESS`], or no sampling map): a
///    nested product rule on the plain hemisphere `(μ = cos θ, φ)` —
///    Clenshaw–Curtis in `μ` (nodes `μ_j = (1 − cos(πj/n))/2`, `n = 2^a`;
///    Clenshaw & Curtis 1960; weights by the cosine series of Trefethen,
///    *Is Gauss quadrature better than Clenshaw–Curtis?*, SIAM Rev. 50(1),
///    2008, which also shows it converges about as fast as Gauss–Legendre
///    on analytic integrands) times the trapezoid rule in the periodic
///    azimuth (`m = 2^b` nodes, exponentially convergent for a smooth
///    periodic integrand; Trefethen & Weideman, SIAM Rev. 56(3), 2014).
///    Both families are nested: refining a dimension reuses every node
///    already evaluated. The rule keeps the two coarser rules `Q(a−1, b)`
///    and `Q(a, b−1)`; their differences from `Q(a, b)`, `d_μ` and `d_φ`,
///    estimate the error of each dimension's coarser rule, and the
///    dimension with the larger one is refined (dimension-adaptive, after
///    Gerstner & Griebel 2003). Where a dimension's last two indicators
///    show geometric convergence, its indicator is deflated to the next
///    term of that sequence (at least ×4 per level, divisor capped at 1,000; with
///    a fixed budget two successive ratios must show it). Error estimate: the two
///    (deflated) indicators plus the `f32` floor `2⁻²³ Σ|w g|`. The grid is
///    abandoned when two refinements in a row do not halve their
///    indicator (from 1,024 evaluations on; a lobe hugging the horizon,
///    whose azimuthal width shrinks with `μ`) or at 8,192 evaluations.
/// 3. **Peaked smooth lobes** (`P >` 30 and [`Integrand::is_smooth`]): the
///    same nested grid on a *chart* that makes a GGX-like lobe analytic and
///    keeps the horizon's discontinuity on the chart's edge, so the grid
///    converges exponentially where the plain grid and the warped rules see
///    a peak or a step (module `chart`):
///    * peak at most 78.5° from the normal and `P ≤ 10⁵`: polar coordinates
///      about the probe's brightest direction, radius
///      `y = tan²(θ'/2) = w² expm1(L x²)` logarithmic beyond the lobe's width
///      `w` (from `P`) and clipped at the horizon along every azimuth, the
///      azimuth stretched by the lobe's aspect (from the probe points);
///    * peak closer to the horizon: the plain `(μ, φ)` square with a sinh
///      warp of `μ` and a periodised sinh warp of `φ` about the peak, widths
///      from the probe points' spread.
///
///    Its error estimate adds the effect of rounding the nodes' directions
///    to `f32` (see each chart), deflates an indicator only on a ratio of at
///    least 16 and by at most 16, and it gives up at 32,768 evaluations.
/// 4. **Narrow lobes**, or a broad-lobe grid that cannot converge within its
///    finest levels (129 × 1024 nodes) or is not resolved (a probe value
///    more than [`probe::PEAK_RATIO`] × the largest node value: a peak
///    between the nodes; no support seen; too few effective nodes): the
///    staged [`Adaptive`] rule on the sampling-map square (or the plain
///    square without a map), which refines its own regions; to a tolerance
///    its value is confirmed as below.
///
/// To a tolerance ([`integrate_to_tolerance`](super::integrate_to_tolerance)),
/// the grid stops when `d_μ + d_φ + floor ≤ tol` at a level reached by
/// refinement (not the first one) and the status is resolved: the value
/// agrees within `tol` with two coarser rules made of a subset of its own
/// nodes. That value is a *candidate* only: a kink (the Oren–Nayar family at
/// `μi = μo`), a lobe cut by the horizon or the step of a mixture map fools
/// every level of a nested rule alike. It stands when a staged [`Adaptive`]
/// run from scratch on another parameterisation agrees within `tol` — the
/// plain `(μ, φ)` square split at the integrand's
/// [kinks](super::Integrand::kinks) after the plain grid, the sampling map's
/// square after a chart — or, if it does not, when any two such runs of
/// different rules (plain, warped, and the shifted twin of each; for an
/// integrand not declared smooth, one of each square or three of the plain
/// square) agree, each
/// method refining four times tighter on its next run (the narrow-lobe path
/// starts there with the warped rule). With a fixed budget
/// ([`Integrator::integrate`]) it refines until the budget cannot pay for
/// the next level; below the pilot's cost (a budget under
/// [`Auto::MIN_PILOT_BUDGET`]) it runs the plain [`GaussLegendre`](super::GaussLegendre)
/// product rule, bit for bit, which needs [`GaussLegendre::MIN_BUDGET`](super::GaussLegendre::MIN_BUDGET)
/// and converges at once on the integrands that few nodes resolve (a
/// Lambertian-like lobe: Oren–Nayar at normal view).
///
/// Stack: about `4 × 129` wide values (4 KiB for `f32`), plus the
/// [`Adaptive`] table when it falls back.
///
/// ```
/// use radiometry::integrator::{Auto, Integrand, integrate_to_tolerance, DEFAULT_MAX_BUDGET};
/// use radiometry::glam::Vec3;
/// struct Cos8;
/// impl Integrand for Cos8 {
///     type Spectrum = f32;
///     fn eval(&self, w: Vec3) -> f32 { w.z.powi(8) }
/// }
/// let out = integrate_to_tolerance(&Auto::new(), &Cos8, 1e-6, 64, DEFAULT_MAX_BUDGET).unwrap();
/// let exact = 2.0 * core::f64::consts::PI / 9.0;
/// assert!(out.reached());
/// assert!((out.estimate.value - exact).abs() <= 1e-6);
/// assert!(out.total_evaluations < 1000);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Auto {
    _private: (),
}

impl Auto {
    /// The `auto` integrator.
    pub const fn new() -> Self {
        Auto { _private: () }
    }

    /// Smallest fixed budget that pays for the pilot and the warped
    /// [`Adaptive`] rule after it (148); a smaller budget runs the plain
    /// Gauss–Legendre rule (see the type's docs).
    pub const MIN_PILOT_BUDGET: u32 = Adaptive::MIN_BUDGET_WARPED + probe::PROBE_POINTS as u32;
}

/// What the pilot found.
struct Pilot {
    /// The probe's points (direction, `max_channel |g|`), empty without a map.
    probe: Probe,
    /// Whether the lobe is narrow (see [`NARROW_PEAKINESS`]).
    narrow: bool,
    /// The pilot's peakiness `P` (∞ when the mean is zero, 0 without a map).
    peakiness: f64,
    /// The probe point with the largest value (the peak-centred chart's pole).
    pole: Option<glam::Vec3>,
    /// Evaluations spent.
    evals: u64,
}

fn pilot<I: Integrand>(g: &I) -> Result<Pilot, IntegrateError> {
    let empty = Probe {
        points: [(glam::Vec3::ZERO, 0.0); probe::PROBE_POINTS],
        len: 0,
    };
    if !g.has_sampling_map() {
        return Ok(Pilot {
            probe: empty,
            narrow: false,
            peakiness: 0.0,
            pole: None,
            evals: 0,
        });
    }
    let mut us = [[0.0f32; 2]; probe::PROBE_POINTS];
    for (k, u) in us.iter_mut().enumerate() {
        *u = probe::lattice_point(k, probe::PROBE_POINTS);
    }
    let mut ss: [Option<super::IntegrandSample<I::Spectrum>>; probe::PROBE_POINTS] =
        [None; probe::PROBE_POINTS];
    g.sample_batch(&us, &mut ss);
    let mut p = empty;
    let (mut peak, mut mean) = (0.0f64, 0.0f64);
    let mut pole = None;
    for s in ss.iter() {
        let Some(s) = s else { continue };
        let v = acc::max_abs(super::check_finite(s.value.to_wide())?);
        if !(s.pdf > 0.0 && s.pdf.is_finite()) {
            continue;
        }
        if v > peak {
            pole = Some(s.w);
        }
        peak = peak.max(v);
        mean += v / s.pdf as f64;
        if let Some(q) = p.points.get_mut(p.len) {
            *q = (s.w, v);
            p.len += 1;
        }
    }
    mean /= probe::PROBE_POINTS as f64;
    // Peakiness of the plain-square integrand `2π g`: its largest value
    // over its mean (the integral); ≈ 1/(the fraction of the square the
    // lobe covers).
    let peakiness = if mean > 0.0 {
        core::f64::consts::TAU * peak / mean
    } else {
        f64::INFINITY
    };
    let narrow = p.len < 2 || peakiness > NARROW_PEAKINESS;
    Ok(Pilot {
        probe: p,
        narrow,
        peakiness,
        pole,
        evals: probe::PROBE_POINTS as u64,
    })
}

/// `μ` of the node with finest index `i` (`0 ≤ i ≤ 128`).
fn mu(i: usize) -> f64 {
    0.5 * (1.0 - libm::cos(core::f64::consts::PI * i as f64 / (NMU - 1) as f64))
}

/// The Clenshaw–Curtis weight on `[0, 1]` for `n = 2^a` intervals at the
/// finest node index `i` (zero off the level): `w_j = (c_j / 2n) [1 −
/// Σ_{k=1}^{n/2} b_k cos(2πjk/n)/(4k² − 1)]` at `j = i / 2^(7−a)`,
/// `c_0 = c_n = 1`, else 2; `b_{n/2} = 1`, else 2 (Trefethen 2008, §2,
/// rescaled from `[−1, 1]`). One weight at a time: [`Grid::rules`] keeps no
/// weight tables on the stack.
fn cc_weight(a: u32, i: usize) -> f64 {
    let n = 1usize << a;
    let stride = (NMU - 1) >> a;
    if stride == 0 || !i.is_multiple_of(stride) || i / stride > n {
        return 0.0;
    }
    let j = i / stride;
    let mut s = 1.0;
    for k in 1..=n / 2 {
        let b = if 2 * k == n { 1.0 } else { 2.0 };
        let kk = (k * k) as f64;
        s -= b * libm::cos(core::f64::consts::TAU * (j * k) as f64 / n as f64) / (4.0 * kk - 1.0);
    }
    let c = if j == 0 || j == n { 1.0 } else { 2.0 };
    c * s / (2 * n) as f64
}

/// Rows of the grid's tables at budgets up to [`SMALL_GRID_BUDGET`]: the
/// rows of `μ` levels up to 6 (every other finest index).
const SMALL_GRID_ROWS: usize = (NMU - 1) / 2 + 1;

/// Largest grid budget run with tables of [`SMALL_GRID_ROWS`] rows: refining
/// `μ` to level 7 costs `2⁶ · 2^b ≥ 512` evaluations on top of the
/// `2⁶ · 2^b + 1 ≥ 513` of level 6, so a budget of 1,024 never reaches it and
/// the run is the same, bit for bit, as with all [`NMU`] rows (the stack
/// follows the budget: 2 KiB less for `f32`; the firmware configuration).
const SMALL_GRID_BUDGET: u64 = 1024;

/// The nested grid: per `μ` node (finest index `i`, kept in row
/// `i / ((NMU − 1)/(R − 1))` of tables of `R` rows), sums over the current
/// azimuth level `b` and over level `b − 1` of `2π g`, of `|2π g|` and of
/// `(2π g)²`.
struct Grid<W, const R: usize> {
    s: [W; R],
    s_prev: [W; R],
    abs: [W; R],
    sq: [W; R],
    a: u32,
    b: u32,
    /// Largest `max_channel |2π g|` at any node.
    peak: f64,
    evals: u64,
    /// `None`: the plain hemisphere `(μ, φ)`; else the peak-centred chart,
    /// whose radial coordinate is `x = 1 − μ(i)` (the pole at `i = NMU − 1`,
    /// as for the plain chart).
    chart: Option<Chart>,
}

/// The hemisphere at `(μ, frac(b + offset))`: `2π g`.
fn turn(b: f64) -> f64 {
    let s = b + PHI_OFFSET;
    if s >= 1.0 { s - 1.0 } else { s }
}

impl<W: WideSpectrum, const R: usize> Grid<W, R> {
    fn new(chart: Option<Chart>) -> Self {
        let z = W::splat(0.0);
        Grid {
            chart,
            s: [z; R],
            s_prev: [z; R],
            abs: [z; R],
            sq: [z; R],
            a: A0,
            b: B0,
            peak: 0.0,
            evals: 0,
        }
    }

    /// The table row of finest index `i` (`None` for an index the tables
    /// do not keep: never asked for within their budget).
    fn row(i: usize) -> Option<usize> {
        let spacing = (NMU - 1) / R.saturating_sub(1).max(1);
        (spacing > 0 && i.is_multiple_of(spacing)).then(|| i / spacing.max(1))
    }

    /// Evaluates row `i` at the azimuth nodes `k/m` (`m = 2^b`) with
    /// `k ≡ first (mod step)`, adding `2π g` to the row's sums; returns the
    /// sum over the nodes with even `k` (the level `b − 1` nodes) when
    /// `first = 0, step = 1`.
    fn eval_row<I: Integrand<Spectrum = S>, S: crate::spectrum::Spectrum<Wide = W>>(
        &mut self,
        g: &I,
        i: usize,
        first: usize,
        step: usize,
    ) -> Result<W, IntegrateError> {
        let m = 1usize << self.b;
        let x = mu(i);
        let mut even = W::splat(0.0);
        let (mut sum, mut abs, mut sq) = (W::splat(0.0), W::splat(0.0), W::splat(0.0));
        if let Some(c) = self.chart {
            // A chart: `g(ω) J`, one evaluation for the pole row (every
            // azimuth is the pole, with its own Jacobian).
            let mut dirs = [glam::Vec3::ZERO; CHUNK];
            let mut jac = [0.0f64; CHUNK];
            let mut vals = [I::Spectrum::zero(); CHUNK];
            let pole = if i == NMU - 1 {
                let mut v = [I::Spectrum::zero()];
                g.eval_batch(&[c.pole()], &mut v);
                self.evals += 1;
                let v = super::check_finite(v[0].to_wide())?;
                self.peak = self.peak.max(core::f64::consts::TAU * acc::max_abs(v));
                Some(v)
            } else {
                None
            };
            let mut ks = (first..m).step_by(step.max(1)).peekable();
            while ks.peek().is_some() {
                let mut n = 0;
                let mut kept = [0usize; CHUNK];
                for ((d, j), kk) in dirs.iter_mut().zip(jac.iter_mut()).zip(kept.iter_mut()) {
                    let Some(k) = ks.next() else { break };
                    (*d, *j) = c.map(x, turn(k as f64 / m as f64));
                    *kk = k;
                    n += 1;
                }
                let mut wide = [W::splat(0.0); CHUNK];
                if let Some(v) = pole {
                    for w in head_mut(&mut wide, n).iter_mut() {
                        *w = v;
                    }
                } else {
                    g.eval_batch(head(&dirs, n), head_mut(&mut vals, n));
                    self.evals += n as u64;
                    for (w, v) in head_mut(&mut wide, n).iter_mut().zip(head(&vals, n)) {
                        *w = super::check_finite(v.to_wide())?;
                        self.peak = self.peak.max(core::f64::consts::TAU * acc::max_abs(*w));
                    }
                }
                for ((&v, &j), &k) in head(&wide, n).iter().zip(head(&jac, n)).zip(head(&kept, n)) {
                    let v = v.map(|y| y * j);
                    sum = acc::add(sum, v);
                    abs = acc::add(abs, v.map(f64::abs));
                    sq = acc::add(sq, v.map(|y| y * y));
                    if k % 2 == 0 {
                        even = acc::add(even, v);
                    }
                }
            }
        } else if i == NMU - 1 {
            // The pole: every azimuth is the same direction.
            let mut v = [W::splat(0.0)];
            chunk::hemisphere_values(g, &[[x, 0.0]], turn, &mut v)?;
            self.evals += 1;
            let count = (first..m).step_by(step.max(1)).count() as f64;
            let evens = (first..m).step_by(step.max(1)).filter(|k| k % 2 == 0).count() as f64;
            let v = v[0];
            self.peak = self.peak.max(acc::max_abs(v));
            sum = v.map(|y| y * count);
            abs = v.map(|y| y.abs() * count);
            sq = v.map(|y| y * y * count);
            even = v.map(|y| y * evens);
        } else {
            let mut pts = [[0.0f64; 2]; CHUNK];
            let mut vals = [W::splat(0.0); CHUNK];
            let mut ks = (first..m).step_by(step.max(1)).peekable();
            while ks.peek().is_some() {
                let mut n = 0;
                let mut kept = [0usize; CHUNK];
                for (p, kk) in pts.iter_mut().zip(kept.iter_mut()) {
                    let Some(k) = ks.next() else { break };
                    *p = [x, k as f64 / m as f64];
                    *kk = k;
                    n += 1;
                }
                chunk::hemisphere_values(g, head(&pts, n), turn, head_mut(&mut vals, n))?;
                self.evals += n as u64;
                for (&v, &k) in head(&vals, n).iter().zip(head(&kept, n)) {
                    self.peak = self.peak.max(acc::max_abs(v));
                    sum = acc::add(sum, v);
                    abs = acc::add(abs, v.map(f64::abs));
                    sq = acc::add(sq, v.map(|y| y * y));
                    if k % 2 == 0 {
                        even = acc::add(even, v);
                    }
                }
            }
        }
        let r = Self::row(i).unwrap_or(R);
        if let (Some(s), Some(a), Some(q)) = (self.s.get_mut(r), self.abs.get_mut(r), self.sq.get_mut(r)) {
            *s = acc::add(*s, sum);
            *a = acc::add(*a, abs);
            *q = acc::add(*q, sq);
        }
        Ok(even)
    }

    /// Evaluates the first level (`a0 × b0`).
    fn start<I: Integrand<Spectrum = S>, S: crate::spectrum::Spectrum<Wide = W>>(
        &mut self,
        g: &I,
    ) -> Result<(), IntegrateError> {
        let stride = (NMU - 1) >> self.a;
        for i in (0..NMU).step_by(stride.max(1)) {
            let even = self.eval_row(g, i, 0, 1)?;
            if let Some(p) = self.s_prev.get_mut(Self::row(i).unwrap_or(R)) {
                *p = even;
            }
        }
        Ok(())
    }

    /// Evaluations the next refinement of `μ` (`true`: `n` new rows of
    /// `m` nodes) or `φ` (`m` new nodes on each of `n + 1` rows, the pole's
    /// row free) costs, at most.
    fn cost(&self, in_mu: bool) -> u64 {
        let (n, m) = (1u64 << self.a, 1u64 << self.b);
        if in_mu { n * m } else { n * m + 1 }
    }

    /// Refines `μ`: the new rows (odd indices of level `a + 1`) at every
    /// azimuth node of level `b`.
    fn refine_mu<I: Integrand<Spectrum = S>, S: crate::spectrum::Spectrum<Wide = W>>(
        &mut self,
        g: &I,
    ) -> Result<(), IntegrateError> {
        self.a += 1;
        let stride = (NMU - 1) >> self.a;
        for i in (stride..NMU).step_by((2 * stride).max(1)) {
            let even = self.eval_row(g, i, 0, 1)?;
            if let Some(p) = self.s_prev.get_mut(Self::row(i).unwrap_or(R)) {
                *p = even;
            }
        }
        Ok(())
    }

    /// Refines `φ`: every row at the odd azimuth nodes of level `b + 1`.
    fn refine_phi<I: Integrand<Spectrum = S>, S: crate::spectrum::Spectrum<Wide = W>>(
        &mut self,
        g: &I,
    ) -> Result<(), IntegrateError> {
        self.b += 1;
        let stride = (NMU - 1) >> self.a;
        for i in (0..NMU).step_by(stride.max(1)) {
            let r = Self::row(i).unwrap_or(R);
            if let (Some(p), Some(&s)) = (self.s_prev.get_mut(r), self.s.get(r)) {
                *p = s;
            }
            self.eval_row(g, i, 1, 2)?;
        }
        Ok(())
    }

    /// `(Q(a, b), d_μ, d_φ, Σ|w g|, effective node count)`.
    fn rules(&self) -> (W, W, W, W, f64, W) {
        let (m, mp) = ((1u64 << self.b) as f64, (1u64 << (self.b - 1)) as f64);
        let z = W::splat(0.0);
        let (mut q, mut qa, mut qb, mut ab, mut sq) = (z, z, z, z, z);
        for i in 0..NMU {
            let (w, wcoarse) = (cc_weight(self.a, i), cc_weight(self.a - 1, i));
            if w == 0.0 && wcoarse == 0.0 {
                continue;
            }
            let r = Self::row(i).unwrap_or(R);
            let (Some(&s), Some(&sp), Some(&a), Some(&qq)) =
                (self.s.get(r), self.s_prev.get(r), self.abs.get(r), self.sq.get(r))
            else {
                continue;
            };
            q = acc::add(q, s.map(|x| x * w / m));
            qa = acc::add(qa, s.map(|x| x * wcoarse / m));
            qb = acc::add(qb, sp.map(|x| x * w / mp));
            ab = acc::add(ab, a.map(|x| x * w / m));
            sq = acc::add(sq, qq.map(|x| x * (w / m) * (w / m)));
        }
        let eff = super::gauss_legendre::effective_nodes(ab, sq);
        (q, acc::abs_diff(q, qa), acc::abs_diff(q, qb), ab, eff, sq)
    }

    fn status(&self, abs: W, eff: f64, probe: &Probe) -> Status {
        if acc::max_abs(abs) <= 0.0 {
            Status::Unresolved(Unresolved::NoSupportSeen)
        } else if eff < 16.0 {
            Status::Unresolved(Unresolved::FewNodes)
        } else if probe
            .points()
            .iter()
            .any(|&(_, v)| v * core::f64::consts::TAU > probe::PEAK_RATIO * self.peak)
        {
            Status::Unresolved(Unresolved::UnseenPeak)
        } else {
            Status::Resolved
        }
    }
}

/// The error of a dimension's current rule from its indicator `d` (the
/// difference to the rule one level coarser in that dimension, an estimate
/// of the *coarser* rule's error) and the indicator `p1` one level before:
/// where the two show geometric convergence by a factor `r = p1/d ≥
/// DEFLATE_MIN_RATIO`, the current rule's error is estimated as `d / r`
/// (the next term of the observed geometric sequence; the error estimate of
/// Romberg and Clenshaw–Curtis codes, e.g. Gander & Gautschi 2000, "Adaptive
/// quadrature — revisited", BIT 40(1), §3), but never below
/// `d / DEFLATE_MAX_RATIO`; otherwise `d` itself. Per channel. A
/// pre-asymptotic drop can fool it (12× on GGX α = 0.3 at θo = 89.5° with a
/// grid stopped at its cap): an abandoned grid's estimate is never returned
/// (the adaptive rule takes over), and to a tolerance the grid must still
/// meet `tol` with the deflated indicators of a refined level. With a fixed
/// budget (`two`), which stops wherever the budget ends, both of the last
/// two ratios must show it and the slower one is used: with one ratio, grids
/// stopped by the budget understated by up to 21× (Phong n = 1 at
/// θo = 89.5°, 4,096 evaluations); to a tolerance, two ratios changed no
/// claim's honesty on the report's suite and cost the broad-lobe cases 2–11×
/// more evaluations.
fn deflate_at_most<W: WideSpectrum>(d: W, hist: History<W>, two: bool, (min, cap): (f64, f64)) -> W {
    d.zip(deflate_factor(d, hist, two), |d, r| {
        if r >= min { d / r.min(cap) } else { d }
    })
}

/// Smallest and largest factor [`deflate_at_most`] divides an indicator by
/// on a chart. Largest: its levels converge fast enough that one jump of a
/// few hundred between pre-asymptotic levels looked geometric (GGX α = 0.05
/// at θo = 0: 6.3·10⁻³ → 1.9·10⁻⁵, deflated to 6·10⁻⁸ against a true error of
/// 7·10⁻⁶). Smallest: a chart is chosen for lobes it makes analytic, where
/// successive levels gain far more than 4×; a ratio below 16 is the
/// algebraic convergence of a kink the chart did not straighten (the
/// Kulla–Conty lobe, linear between its table's cells: Beckmann α = 0.05 at
/// 85° claimed 6·10⁻⁶ for a true error of 2.6·10⁻⁵ with the plain grid's
/// threshold of 4), and the indicator is taken as it is.
const CHART_DEFLATE: (f64, f64) = (16.0, 16.0);
/// The same on the plain grid.
const GRID_DEFLATE: (f64, f64) = (DEFLATE_MIN_RATIO, DEFLATE_MAX_RATIO);

/// Per channel, the divisor of [`deflate`] (`1` where it does not apply).
fn deflate_factor<W: WideSpectrum>(d: W, hist: History<W>, two: bool) -> W {
    let Some(p1) = hist[0] else {
        return d.map(|_| 1.0);
    };
    let r1 = p1.zip(d, |p, d| if d > 0.0 { p / d } else { 0.0 });
    let r = match (two, hist[1]) {
        (false, _) => r1,
        (true, Some(p2)) => r1.zip(p2.zip(p1, |p, q| if q > 0.0 { p / q } else { 0.0 }), f64::min),
        (true, None) => return d.map(|_| 1.0),
    };
    r.map(|r| {
        if r >= DEFLATE_MIN_RATIO {
            r.min(DEFLATE_MAX_RATIO)
        } else {
            1.0
        }
    })
}

/// Evaluations from which two stalled refinements in a row abandon the grid.
const GRID_STALL_MIN: u64 = 1024;
/// Evaluations from which the grid is abandoned for the adaptive rule.
const GRID_CAP: u64 = 8192;
/// The same on a chart (the lobes it takes need more nodes: GGX α = 0.01 at
/// θo = 85° converges at 65 × 256).
const CHART_GRID_CAP: u64 = 32768;

/// Smallest observed convergence factor between successive levels of a
/// dimension for [`deflate`] to trust it.
const DEFLATE_MIN_RATIO: f64 = 4.0;
/// Largest factor [`deflate`] divides an indicator by.
const DEFLATE_MAX_RATIO: f64 = 1000.0;

/// A dimension's indicators before its last two refinements (latest first).
type History<W> = [Option<W>; 2];

/// How the grid path ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum GridEnd {
    /// `tol` met at a refined level, resolved.
    Met,
    /// The budget (or the finest levels) stopped it: the estimate is the
    /// grid's best.
    Budget,
    /// Abandoned (stalled refinements or [`GRID_CAP`]): hand over to the
    /// adaptive rule.
    Abandoned,
}

/// The grid path: refines until `d_μ + d_φ + floor ≤ tol` (at a refined
/// level, resolved) or the budget / finest levels stop it, or abandons it.
/// Returns the last estimate and how it ended.
/// `two`: deflate only on two successive geometric ratios (the fixed-budget
/// path, which stops wherever the budget ends, pre-asymptotic or not).
fn grid<I: Integrand>(
    g: &I,
    tol: f64,
    budget: u64,
    probe: &Probe,
    two: bool,
    chart: Option<Chart>,
) -> Result<(Estimate<WideOf<I>>, GridEnd), IntegrateError> {
    if budget <= SMALL_GRID_BUDGET {
        grid_with::<I, SMALL_GRID_ROWS>(g, tol, budget, probe, two, chart)
    } else {
        grid_with::<I, NMU>(g, tol, budget, probe, two, chart)
    }
}

/// [`grid`] with tables of `R` rows. Never inlined: each table size keeps its
/// own stack frame.
#[inline(never)]
fn grid_with<I: Integrand, const R: usize>(
    g: &I,
    tol: f64,
    budget: u64,
    probe: &Probe,
    two: bool,
    chart: Option<Chart>,
) -> Result<(Estimate<WideOf<I>>, GridEnd), IntegrateError> {
    let mut gr = Grid::<WideOf<I>, R>::new(chart);
    gr.start(g)?;
    let mut refined = false;
    // Each dimension's indicators before its last two refinements.
    let mut hist_mu: History<WideOf<I>> = [None; 2];
    let mut hist_phi: History<WideOf<I>> = [None; 2];
    // The dimension refined last (`true`: μ).
    let mut just: Option<bool> = None;
    // Successive refinements whose indicator did not halve.
    let mut strikes = 0u32;
    let cap = if chart.is_some() {
        CHART_DEFLATE
    } else {
        GRID_DEFLATE
    };
    loop {
        let (q, dmu, dphi, abs, eff, sq) = gr.rules();
        let err = acc::add(
            acc::add(
                deflate_at_most(dmu, hist_mu, two, cap),
                deflate_at_most(dphi, hist_phi, two, cap),
            ),
            abs.map(|x| x * F32_FLOOR),
        );
        // On a chart, the nodes' directions rounded to f32 move them by
        // ~6e-8 rad: a relative change of the lobe's value of about
        // `c = chart.rounding()`, pseudo-random from node to node, so
        // `c √Σ(w g)²` (the rule's weights fit the unrounded nodes; the
        // plain chart's f32 floor covers a broad lobe).
        let err = match gr.chart {
            Some(c) => acc::add(err, sq.map(|x| c.rounding() * libm::sqrt(x))),
            None => err,
        };
        let status = gr.status(abs, eff, probe);
        let est = Estimate {
            value: q,
            error: err,
            evaluations: gr.evals,
            status,
        };
        let done = refined && status.is_resolved() && acc::max_abs(err) <= tol;
        // The refined dimension's indicator did not fall by half: the grid is
        // not converging geometrically there (e.g. a lobe hugging the
        // horizon, whose azimuthal width shrinks with μ) — give up early.
        let stalled = match just {
            Some(true) => hist_mu[0].is_some_and(|p| acc::max_abs(dmu) > 0.5 * acc::max_abs(p)),
            Some(false) => hist_phi[0].is_some_and(|p| acc::max_abs(dphi) > 0.5 * acc::max_abs(p)),
            None => false,
        };
        strikes = if stalled { strikes + 1 } else { 0 };
        if done {
            return Ok((est, GridEnd::Met));
        }
        if (strikes >= 2 && gr.evals >= GRID_STALL_MIN)
            || gr.evals
                >= if gr.chart.is_some() {
                    CHART_GRID_CAP
                } else {
                    GRID_CAP
                }
        {
            return Ok((est, GridEnd::Abandoned));
        }
        let in_mu = acc::max_abs(dmu) >= acc::max_abs(dphi);
        let in_mu = if in_mu && gr.a >= MAX_A {
            false
        } else if !in_mu && gr.b >= MAX_B {
            true
        } else {
            in_mu
        };
        if (in_mu && gr.a >= MAX_A) || (!in_mu && gr.b >= MAX_B) || gr.evals + gr.cost(in_mu) > budget {
            return Ok((est, GridEnd::Budget));
        }
        if in_mu {
            hist_mu = [Some(dmu), hist_mu[0]];
            gr.refine_mu(g)?;
        } else {
            hist_phi = [Some(dphi), hist_phi[0]];
            gr.refine_phi(g)?;
        }
        just = Some(in_mu);
        refined = true;
    }
}

/// The fixed-budget path of an integrand that is not smooth and samples
/// through a mixture map (composites, the Oren–Nayar family): the plain
/// [`Adaptive`] rule, whose square is split at the integrand's
/// [kinks](Integrand::kinks) and never sees the map's seams, with half the
/// budget; if it cannot stand behind its estimate (unresolved), the warped
/// rule (each component of the map on its own square) with the rest, whose
/// estimate is returned when it is resolved.
///
/// Why not the grid or the warped rule first: a kink (`μi = μo`,
/// `cos Δφ = 0`, a clamp) and the seam of a mixture map slow every nested
/// grid and every warped rule to algebraic convergence, while the plain
/// rule's regions stop at the kink lines. On the report's composites the
/// plain rule reaches `10⁻⁶` with 254–16,354 evaluations where the grid and
/// the warped rule (the earlier path) needed 65,000–1,000,000.
fn plain_first<I: Integrand>(g: &I, budget: u32) -> Result<Estimate<WideOf<I>>, IntegrateError> {
    let a = Adaptive::new(0.0, 0.0)?;
    // Half the budget, when the half still pays for the plain rule's
    // kink-line checks; else all of it (no fallback): a run of a few
    // regions at 128 evaluations answered a sum at `θo = 80°` 2.05× its
    // albedo, resolved, with an estimate of 0.1.
    let half = budget / 2;
    let first = if g.has_sampling_map() && half >= super::adaptive::KINK_CHECK_MIN_BUDGET {
        half
    } else {
        budget
    };
    let e = a.integrate_unchecked(g, first)?;
    let left = (budget as u64).saturating_sub(e.evaluations);
    let w = a.warped();
    if e.is_resolved() || !g.has_sampling_map() || left < w.min_budget() as u64 {
        return Ok(e);
    }
    let mut f = w.integrate(g, left.min(u32::MAX as u64) as u32)?;
    f.evaluations += e.evaluations;
    if f.is_resolved() {
        Ok(f)
    } else {
        Ok(Estimate {
            evaluations: f.evaluations,
            ..e
        })
    }
}

impl Integrator for Auto {
    /// With a fixed budget: the pilot, then the grid refined until the
    /// budget cannot pay for its next level (broad lobes), or the warped
    /// [`Adaptive`] rule with the rest of the budget (narrow lobes, or a
    /// grid that is not resolved).
    fn integrate<I: Integrand>(&self, g: &I, budget: u32) -> Result<Estimate<WideOf<I>>, IntegrateError> {
        let min = Self::MIN_PILOT_BUDGET;
        if budget < min {
            // No pilot: the cheapest rule with a nested estimate and its
            // own checks (errors below its own minimum, 11).
            return super::GaussLegendre::new().integrate(g, budget);
        }
        if !g.is_smooth() && g.sampling_components() > 1 {
            return plain_first(g, budget);
        }
        let p = pilot(g)?;
        let rest = budget as u64 - p.evals;
        let mut spent = p.evals;
        // With a fixed budget, only the peak-centred chart: the product chart
        // converges or not within a few levels (to a tolerance it gives up
        // and hands over), and a budget that stops it early left GGX
        // α = 0.05 at 89.9° at 1.6·10⁻³ where the warped rule gets 10⁻⁴.
        let chart = chart_for(&p, g.is_smooth()).filter(|c| matches!(c, Chart::Peak(_)));
        if !p.narrow || chart.is_some() {
            let (mut e, end) = grid(g, 0.0, rest, &p.probe, true, chart)?;
            let left = rest.saturating_sub(e.evaluations);
            let fallback = end == GridEnd::Abandoned || !e.is_resolved();
            if !(fallback && g.has_sampling_map() && left >= min as u64) {
                e.evaluations += p.evals;
                return Ok(e);
            }
            spent += e.evaluations;
        }
        let a = Adaptive::new(0.0, 0.0)?;
        let a = if g.has_sampling_map() { a.warped() } else { a };
        let left = (budget as u64).saturating_sub(spent).max(a.min_budget() as u64);
        let mut e = a.integrate(g, left.min(u32::MAX as u64) as u32)?;
        e.evaluations += spent;
        Ok(e)
    }

    fn name(&self) -> &'static str {
        "auto"
    }

    /// The pilot, the grid to `tol` (broad lobes and peaked smooth ones),
    /// whose value is a candidate, then staged [`Adaptive`] runs on other
    /// parameterisations until two agree within `tol` (see the type's docs);
    /// evaluations of every stage are counted, and `max_budget` bounds
    /// their sum.
    fn to_tolerance<I: Integrand>(
        &self,
        g: &I,
        tol: f64,
        start_budget: u32,
        max_budget: u32,
    ) -> Result<ToleranceOutcome<WideOf<I>>, IntegrateError> {
        check_tolerance_args(tol, start_budget, max_budget)?;
        let p = pilot(g)?;

        let mut spent = p.evals;
        let chart = chart_for(&p, g.is_smooth());
        let mut first = None;
        let mut last = None;
        let mut runs = 0u32;
        if !p.narrow || chart.is_some() {
            // The grid may use a quarter of the budget before the fallback.
            let quarter = max_budget as u64 / 4;
            let (e, end) = grid(g, tol, quarter, &p.probe, false, chart)?;
            spent += e.evaluations;
            runs += 1;
            last = Some(e);
            // The grid's own confirmation (two coarser rules made of its
            // nodes) is a candidate only: a kink or a lobe cut by the
            // horizon fools its nested estimate at every level alike.
            first = (end == GridEnd::Met).then_some(confirm::Candidate {
                estimate: e,
                family: if chart.is_some() {
                    confirm::Family::Chart
                } else {
                    confirm::Family::Grid
                },
            });
            // On a chart (smooth integrands only), grids on its twins —
            // the widths scaled by 1/φ and 1/φ², so other nodes — confirm a
            // value two of them meet `tol` on and agree on within `tol`
            // (with the mean check through the sampling map): the narrow
            // lobes near the horizon that only a chart resolves to 10⁻⁶
            // (GGX α = 10⁻³ and 10⁻² at 89.9°: the warped rules stall at
            // a few 10⁻⁶ there).
            // Each chart's estimate when resolved with its own error at most
            // `NEAR_MET × tol`, and whether its grid met `tol`.
            let near = |e: &Estimate<WideOf<I>>| e.is_resolved() && acc::max_abs(e.error) <= NEAR_MET * tol;
            let mut seen: [Option<(Estimate<WideOf<I>>, bool)>; CHART_TWINS + 1] = [None; CHART_TWINS + 1];
            if let (Some(s0), Some(_)) = (seen.first_mut(), chart)
                && near(&e)
            {
                *s0 = Some((e, end == GridEnd::Met));
            }
            let mut cur = chart;
            for k in 1..=CHART_TWINS {
                let Some(tw) = cur.and_then(|c| c.twin()) else {
                    break;
                };
                cur = Some(tw);
                let left = quarter.saturating_sub(spent);
                if left < CHART_TWIN_MIN_BUDGET {
                    break;
                }
                let (t, tend) = grid(g, tol, left, &p.probe, false, Some(tw))?;
                spent += t.evaluations;
                runs += 1;
                if !near(&t) {
                    continue;
                }
                let t_met = tend == GridEnd::Met;
                for &(prior, prior_met) in seen.iter().take(k).flatten() {
                    let d = acc::abs_diff(prior.value, t.value);
                    if !(t_met || prior_met) || acc::max_abs(d) > tol {
                        continue;
                    }
                    let mut sp = confirm::Spent {
                        evaluations: spent,
                        runs,
                    };
                    let best = if acc::max_abs(t.error) <= acc::max_abs(prior.error) {
                        t
                    } else {
                        prior
                    };
                    if confirm::mean_check_agrees(g, &best, tol, &mut sp)? {
                        return Ok(confirm::reached(best, d, d, sp, max_budget));
                    }
                    spent = sp.evaluations;
                }
                if let Some(m) = seen.get_mut(k) {
                    *m = Some((t, t_met));
                }
                if first.is_none() && t_met {
                    first = Some(confirm::Candidate {
                        estimate: t,
                        family: confirm::Family::Chart,
                    });
                }
            }
        }
        let spent = confirm::Spent {
            evaluations: spent,
            runs,
        };
        confirm::cross_confirm(g, tol, max_budget, first, last, spent, !p.narrow)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    /// The weights of a level, indexed by the finest node index.
    fn cc_weights(a: u32) -> [f64; NMU] {
        core::array::from_fn(|i| cc_weight(a, i))
    }

    /// Clenshaw–Curtis with `n + 1` nodes integrates polynomials of degree
    /// `≤ n` exactly (Trefethen 2008, Thm. 1): `∫₀¹ μ^k dμ = 1/(k + 1)`.
    #[test]
    fn clenshaw_curtis_weights_are_exact_for_polynomials() {
        for a in 1..=MAX_A {
            let w = cc_weights(a);
            let n = 1u32 << a;
            for k in 0..=n.min(40) {
                let q: f64 = (0..NMU).map(|i| w[i] * libm::pow(mu(i), k as f64)).sum();
                let exact = 1.0 / (k as f64 + 1.0);
                assert!((q - exact).abs() < 1e-13, "a={a} k={k}: {q} vs {exact}");
            }
            // Positive weights (Imhof 1963), zero off the level.
            let stride = (NMU - 1) >> a;
            for (i, &x) in w.iter().enumerate() {
                assert_eq!(x > 0.0, i % stride == 0, "a={a} i={i}");
            }
        }
    }

    struct CosPow(i32);
    impl Integrand for CosPow {
        type Spectrum = f32;
        fn eval(&self, w: Vec3) -> f32 {
            w.z.max(0.0).powi(self.0)
        }
    }

    /// The grid's tables of every other row give the same results, bit for
    /// bit, as all rows, up to [`SMALL_GRID_BUDGET`] (a lobe that refines `μ`
    /// first, and a tilted one that refines both).
    #[test]
    fn small_grid_tables_give_the_same_bits() {
        let c = Vec3::new(0.5, 0.0, 0.866_025_4).normalize();
        for g in [Tilted(40.0, Vec3::Z), Tilted(20.0, c)] {
            let p = pilot(&g).unwrap();
            for budget in [100, 513, 700, 1000, SMALL_GRID_BUDGET] {
                for (tol, two) in [(0.0, true), (1e-12, false)] {
                    let all = grid_with::<_, NMU>(&g, tol, budget, &p.probe, two, None).unwrap();
                    let half = grid_with::<_, SMALL_GRID_ROWS>(&g, tol, budget, &p.probe, two, None).unwrap();
                    assert_eq!(half, all, "{budget}");
                }
            }
        }
    }

    /// A lobe `max(0, ω·c)^n` about `c` (no sampling map).
    struct Tilted(f32, Vec3);
    impl Integrand for Tilted {
        type Spectrum = f32;
        fn eval(&self, w: Vec3) -> f32 {
            libm::powf(w.dot(self.1).max(0.0), self.0) * w.z.max(0.0)
        }
    }

    #[test]
    fn the_grid_refines_the_dimension_that_needs_it() {
        // Azimuthally symmetric: the grid never needs to refine φ, and the
        // value is within the tolerance of ∫ cos⁸ = 2π/9 (10⁻⁸ would be below
        // the f32 floor 2⁻²³ · 0.7).
        let out = Auto::new().to_tolerance(&CosPow(8), 1e-6, 64, 1 << 20).unwrap();
        let exact = core::f64::consts::TAU / 9.0;
        assert!(out.reached(), "{out:?}");
        assert!((out.estimate.value - exact).abs() < 1e-6, "{out:?}");
        assert!(out.total_evaluations < 2000, "{out:?}");
    }

    /// A tilted lobe without a sampling map goes to the grid; its estimate
    /// covers the true error (reference: the lobe's mass by a fine
    /// composite rule in f64 written here, a 2000 × 4000 midpoint rule in
    /// (μ, φ) — exponentially accurate in φ, second order in μ, enough for
    /// 10⁻⁷ at this smoothness).
    #[test]
    fn a_tilted_lobe_without_a_map_is_honest() {
        let c = Vec3::new(0.5, 0.0, 0.866_025_4).normalize();
        let g = Tilted(20.0, c);
        let (nm, np) = (2000usize, 4000usize);
        let mut r = 0.0f64;
        for i in 0..nm {
            let m = (i as f64 + 0.5) / nm as f64;
            let s = libm::sqrt(1.0 - m * m);
            for k in 0..np {
                let p = core::f64::consts::TAU * (k as f64 + 0.5) / np as f64;
                let d = s * libm::cos(p) * c.x as f64 + s * libm::sin(p) * c.y as f64 + m * c.z as f64;
                r += libm::pow(d.max(0.0), 20.0) * m;
            }
        }
        let exact = r * core::f64::consts::TAU / (nm * np) as f64;
        for tol in [1e-3, 1e-5, 1e-6] {
            let out = Auto::new().to_tolerance(&g, tol, 64, 1 << 20).unwrap();
            let err = (out.estimate.value - exact).abs();
            assert!(out.reached(), "{tol}: {out:?}");
            assert!(
                err <= 10.0 * out.estimate.error.max(tol),
                "{tol}: {out:?} vs {exact} ({err:e})"
            );
        }
    }

    #[test]
    fn the_median_is_the_middle_rank() {
        assert_eq!(median(&[]), None);
        assert_eq!(median(&[3.0]), Some(3.0));
        assert_eq!(median(&[5.0, 1.0, 3.0]), Some(3.0));
        assert_eq!(median(&[4.0, 1.0, 3.0, 2.0]), Some(2.5));
        assert_eq!(median(&[2.0, 2.0, 1.0, 2.0]), Some(2.0));
    }

    #[test]
    fn fixed_budgets_are_respected() {
        // Below the pilot's cost: the plain Gauss–Legendre rule, bit for
        // bit, down to its own minimum.
        assert_eq!(
            Auto::new().integrate(&CosPow(1), super::super::GaussLegendre::MIN_BUDGET - 1),
            Err(IntegrateError::BudgetTooSmall {
                minimum: super::super::GaussLegendre::MIN_BUDGET
            })
        );
        for b in [11u32, 50, 100, Auto::MIN_PILOT_BUDGET - 1] {
            let e = Auto::new().integrate(&CosPow(3), b).unwrap();
            assert_eq!(
                Ok(e),
                super::super::GaussLegendre::new().integrate(&CosPow(3), b),
                "{b}"
            );
            assert!(e.evaluations <= b as u64, "{b}: {e:?}");
        }
        assert_eq!(
            Auto::MIN_PILOT_BUDGET,
            Adaptive::MIN_BUDGET_WARPED + probe::PROBE_POINTS as u32
        );
        for b in [148u32, 300, 1000, 5000, 100_000] {
            let e = Auto::new().integrate(&CosPow(3), b).unwrap();
            assert!(e.evaluations <= b as u64, "{b}: {e:?}");
            assert!(
                (e.value - core::f64::consts::TAU / 4.0).abs() <= 10.0 * e.error + 1e-6,
                "{b}: {e:?}"
            );
        }
    }
}
