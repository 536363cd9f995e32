//! Gauss–Legendre quadrature: allocation-free nodes and weights, the
//! product rule over the hemisphere in `(cos θ, φ)` ([`GaussLegendre`]) and
//! the product rule on the unit square pulled through the integrand's
//! sampling map ([`WarpedGaussLegendre`]).

use super::acc::{F32_FLOOR, WideSum};
use super::chunk::{self, BatchFn, CHUNK};
use super::{Estimate, Integrand, IntegrateError, Integrator, WideOf};
use crate::spectrum::WideSpectrum;

/// Largest Gauss–Legendre order per axis (nodes live in fixed-size stack
/// arrays of this length).
pub const MAX_ORDER: usize = 1024;

/// Node `x` and weight `w` of the `i`-th largest root of `P_n` (`i < ⌈n/2⌉`),
/// on `[-1, 1]`.
///
/// Newton's method on the three-term recurrence
/// `j P_j = (2j − 1) x P_{j−1} − (j − 1) P_{j−2}` with
/// `P_n'(x) = n (x P_n − P_{n−1}) / (x² − 1)`, started from Tricomi's
/// approximation `x ≈ cos(π (i + ¾)/(n + ½))`; weight
/// `w = 2 / ((1 − x²) P_n'(x)²)` (Abramowitz & Stegun 25.4.29; Press et
/// al., *Numerical Recipes* 3rd ed. §4.6.1).
fn positive_root(n: usize, i: usize) -> (f64, f64) {
    let nf = n as f64;
    let mut x = libm::cos(core::f64::consts::PI * (i as f64 + 0.75) / (nf + 0.5));
    let mut dp = 1.0;
    for _ in 0..100 {
        let (mut p0, mut p1) = (1.0f64, x);
        for j in 2..=n {
            let jf = j as f64;
            let p2 = ((2.0 * jf - 1.0) * x * p1 - (jf - 1.0) * p0) / jf;
            p0 = p1;
            p1 = p2;
        }
        // p1 = P_n(x), p0 = P_{n-1}(x)  (n ≥ 1)
        dp = nf * (x * p1 - p0) / (x * x - 1.0);
        let dx = p1 / dp;
        x -= dx;
        if dx.abs() <= 1e-16 * (1.0 + x.abs()) {
            break;
        }
    }
    // Weight from the derivative at the converged root.
    let (mut p0, mut p1) = (1.0f64, x);
    for j in 2..=n {
        let jf = j as f64;
        let p2 = ((2.0 * jf - 1.0) * x * p1 - (jf - 1.0) * p0) / jf;
        p0 = p1;
        p1 = p2;
    }
    if n >= 1 {
        dp = nf * (x * p1 - p0) / (x * x - 1.0);
    }
    (x, 2.0 / ((1.0 - x * x) * dp * dp))
}

/// Fills `x[..n]`, `w[..n]` with the `n`-point Gauss–Legendre rule on
/// `[-1, 1]` (nodes ascending): `∫₋₁¹ f ≈ Σ wₖ f(xₖ)`, exact for
/// polynomials of degree `≤ 2n − 1` (Gauss 1814; A&S 25.4.29).
///
/// Nodes are found by Newton's method on the Legendre recurrence (see the
/// source); accuracy is a few ulps for `n ≤ 1024`, cost `O(n²)`. Uses no
/// allocation: the caller provides the storage.
///
/// Domain: `1 ≤ n ≤ min(x.len(), w.len())`; otherwise nothing is written and
/// `0` is returned. Returns `n` on success.
///
/// ```
/// use radiometry::integrator::gauss_legendre::gauss_legendre_rule;
/// let (mut x, mut w) = ([0.0; 3], [0.0; 3]);
/// assert_eq!(gauss_legendre_rule(3, &mut x, &mut w), 3);
/// assert!((x[2] - (0.6f64).sqrt()).abs() < 1e-15);
/// assert!((w[1] - 8.0 / 9.0).abs() < 1e-15);
/// ```
pub fn gauss_legendre_rule(n: usize, x: &mut [f64], w: &mut [f64]) -> usize {
    if n == 0 || n > x.len() || n > w.len() {
        return 0;
    }
    if n == 1 {
        x[0] = 0.0;
        w[0] = 2.0;
        return 1;
    }
    for i in 0..n.div_ceil(2) {
        let (xi, wi) = positive_root(n, i);
        // i-th largest root sits at ascending index n-1-i; its mirror at i.
        x[n - 1 - i] = xi;
        w[n - 1 - i] = wi;
        x[i] = -xi;
        w[i] = wi;
        if 2 * i + 1 == n {
            x[i] = 0.0;
        }
    }
    n
}

/// A Gauss–Legendre rule on `[0, 1]` stored on the stack.
struct UnitRule {
    n: usize,
    x: [f64; MAX_ORDER],
    w: [f64; MAX_ORDER],
}

impl UnitRule {
    fn new(n: usize) -> Self {
        let mut r = UnitRule {
            n: 0,
            x: [0.0; MAX_ORDER],
            w: [0.0; MAX_ORDER],
        };
        r.n = gauss_legendre_rule(n.min(MAX_ORDER), &mut r.x, &mut r.w);
        for k in 0..r.n {
            r.x[k] = 0.5 * (r.x[k] + 1.0);
            r.w[k] *= 0.5;
        }
        r
    }
}

/// `Σᵢ Σⱼ wᵢ wⱼ f(aᵢ, bⱼ)` over `[0,1]²` with `na × nb` nodes, and the
/// channel-wise `Σ |wᵢ wⱼ f|` (for the rounding floor). Nodes go to `f` in
/// row-major order, [`CHUNK`] at a time; the sums are accumulated in that
/// order.
fn product_square<W: WideSpectrum>(
    na: usize,
    nb: usize,
    f: &mut impl BatchFn<W>,
) -> Result<(W, W), IntegrateError> {
    let ra = UnitRule::new(na);
    let rb = UnitRule::new(nb);
    let mut sum = WideSum::<W>::new();
    let mut abs = WideSum::<W>::new();
    let mut pts = [[0.0f64; 2]; CHUNK];
    let mut wts = [0.0f64; CHUNK];
    let mut vals = [W::splat(0.0); CHUNK];
    let total = ra.n * rb.n;
    let mut start = 0;
    while start < total {
        let n = (total - start).min(CHUNK);
        for k in 0..n {
            let (i, j) = ((start + k) / rb.n, (start + k) % rb.n);
            pts[k] = [ra.x[i], rb.x[j]];
            wts[k] = ra.w[i] * rb.w[j];
        }
        f(&pts[..n], &mut vals[..n])?;
        for (v, &wt) in vals[..n].iter().zip(&wts[..n]) {
            let v = v.map(|c| c * wt);
            sum.add(v);
            abs.add(v.map(f64::abs));
        }
        start += n;
    }
    Ok((sum.value(), abs.value()))
}

/// The orders of the rule and its comparison rules: `(na, nb)`, then
/// repeated halving `(⌈na/2ᵏ⌉, ⌈nb/2ᵏ⌉)`, `k = 1, 2, 3`, stopping early once
/// the orders no longer shrink. Returns the levels and their count.
fn levels(na: usize, nb: usize) -> ([(usize, usize); 4], usize) {
    let mut out = [(na, nb); 4];
    let mut count = 1;
    while count < 4 {
        let (a, b) = out[count - 1];
        let next = (a.div_ceil(2), b.div_ceil(2));
        if next == (a, b) {
            break;
        }
        out[count] = next;
        count += 1;
    }
    (out, count)
}

/// Total evaluations of [`levels`].
fn levels_cost(na: usize, nb: usize) -> usize {
    let (l, c) = levels(na, nb);
    l[..c].iter().map(|&(a, b)| a * b).sum()
}

/// Runs the rule `Q₀` of order `(na, nb)` and the comparison rules
/// `Q₁, Q₂, Q₃` of [`levels`], with differences `e₁ = |Q₀ − Q₁|`,
/// `e₂ = |Q₁ − Q₂|`, `e₃ = |Q₂ − Q₃|` (channel-wise). Error estimate:
///
/// * `e₁` when the coarse levels converge fast (`e₂ ≤ e₃/16`: faster than
///   `O(n⁻⁴)` per halving, the smooth/spectral regime, in which `e₁`
///   — really the error of `Q₁` — already overstates the error of `Q₀`);
/// * otherwise (algebraic convergence, e.g. a discontinuity where the
///   sampling map returns `None`, where a single difference can be
///   accidentally small) `max(e₁, e₂·min(1, e₂/e₃))`: the error of `Q₁`
///   extrapolated from the observed rate `e₂/e₃`;
///
/// plus the `f32` rounding floor `2⁻²³ Σ|w g|`. (A rate-based safeguard
/// in the spirit of QUADPACK's error heuristics, Piessens et al. 1983,
/// §2.2.) The comparison rules cost ≈ 33 % extra.
fn with_comparison_rules<W: WideSpectrum>(
    na: usize,
    nb: usize,
    mut f: impl BatchFn<W>,
) -> Result<Estimate<W>, IntegrateError> {
    let (lv, count) = levels(na, nb);
    let (q0, abs) = product_square(na, nb, &mut f)?;
    let mut q = [q0; 4];
    for k in 1..count {
        q[k] = product_square(lv[k].0, lv[k].1, &mut f)?.0;
    }
    let error = W::from_fn(|i| {
        let c = |k: usize| q[k].channel(i);
        let e1 = if count > 1 {
            (c(0) - c(1)).abs()
        } else {
            c(0).abs()
        };
        let e2 = if count > 2 { (c(1) - c(2)).abs() } else { e1 };
        let e = if count > 3 {
            let e3 = (c(2) - c(3)).abs();
            if e2 <= e3 / 16.0 {
                e1
            } else {
                let rate = if e3 > 0.0 { (e2 / e3).min(1.0) } else { 1.0 };
                e1.max(e2 * rate)
            }
        } else {
            e1.max(e2)
        };
        e + abs.channel(i) * F32_FLOOR
    });
    Ok(Estimate {
        value: q0,
        error,
        evaluations: levels_cost(na, nb) as u64,
    })
}

/// Largest `n` with `levels_cost(n, k n) ≤ budget` and `k n ≤ MAX_ORDER`.
fn order_for_budget(budget: u32, k: usize) -> usize {
    let b = budget as usize;
    let mut n = libm::sqrt(b as f64 / (1.3 * k as f64)) as usize + 1;
    n = n.min(MAX_ORDER / k);
    while n > 0 && levels_cost(n, k * n) > b {
        n -= 1;
    }
    n
}

/// Gauss–Legendre product rule over the upper hemisphere in `(μ, φ)`,
/// `μ = cos θ ∈ [0,1]`, `φ ∈ [0, 2π)`:
///
/// `∫_H g dω = ∫₀¹ ∫₀^{2π} g(μ, φ) dφ dμ ≈ Σᵢ Σⱼ aᵢ bⱼ g(μᵢ, φⱼ)`
///
/// with `n_θ` Gauss–Legendre nodes in `μ` and `n_φ = 2 n_θ` in `φ` (both
/// mapped affinely from `[-1,1]`; Davis & Rabinowitz, *Methods of Numerical
/// Integration* 2nd ed. §5.6, product rules). Exact when `g` is a
/// polynomial of degree `≤ 2n_θ − 1` in `μ` and `≤ 4n_θ − 1` in `φ`;
/// spectrally convergent for integrands smooth in `(μ, φ)`, slow for narrow
/// lobes (use [`WarpedGaussLegendre`] there).
///
/// **Error estimate** (a-posteriori, see the private `with_comparison_rules`):
/// differences from the rules of half, quarter and eighth order,
/// `e₁ = |Q(n) − Q(n/2)|` (an estimate of the *lower* rule's error, hence
/// conservative while the rule converges), safeguarded by the observed
/// convergence rate when it is algebraic, plus the `f32` rounding floor
/// `2⁻²³ Σ|wₖ gₖ|` of the integrand. Like any quadrature estimate it cannot
/// see a feature that falls between all nodes of all rules (a lobe
/// narrower than the node spacing).
///
/// **Budget**: the largest `n_θ` whose rule plus comparison rules
/// (`n_θ·2n_θ + ⌈n_θ/2⌉·n_θ + …`, ≈ 33 % extra) fit the budget. Minimum
/// budget 11 (`n_θ = 2`); capped at `n_θ = 512`, `n_φ = 1024`
/// ([`MAX_ORDER`]), i.e. 696,320 evaluations, whatever the budget. Node
/// storage: two stack arrays of `MAX_ORDER` f64 per axis (32 KiB).
///
/// A NaN/∞ integrand value gives [`IntegrateError::NonFiniteIntegrand`].
///
/// ```
/// use radiometry::integrator::{GaussLegendre, Integrand, Integrator};
/// use radiometry::glam::Vec3;
/// struct Cos;
/// impl Integrand for Cos {
///     type Spectrum = f32;
///     fn eval(&self, w: Vec3) -> f32 { w.z }
/// }
/// let e = GaussLegendre::new().integrate(&Cos, 100).unwrap();
/// assert!((e.value - core::f64::consts::PI).abs() < 1e-6);
/// assert!(e.evaluations <= 100 && e.error < 1e-5);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct GaussLegendre {
    _private: (),
}

impl GaussLegendre {
    /// The product rule (no parameters: orders follow from the budget).
    pub const fn new() -> Self {
        Self { _private: () }
    }

    /// Smallest accepted budget.
    pub const MIN_BUDGET: u32 = 11;

    /// `(n_θ, n_φ)` used for a budget (`(0, 0)` below [`Self::MIN_BUDGET`]).
    pub fn orders(budget: u32) -> (usize, usize) {
        let n = order_for_budget(budget, 2);
        if n < 2 { (0, 0) } else { (n, 2 * n) }
    }
}

impl Integrator for GaussLegendre {
    fn integrate<I: Integrand>(&self, g: &I, budget: u32) -> Result<Estimate<WideOf<I>>, IntegrateError> {
        let (nt, np) = Self::orders(budget);
        if nt == 0 {
            return Err(IntegrateError::BudgetTooSmall {
                minimum: Self::MIN_BUDGET,
            });
        }
        with_comparison_rules(nt, np, |p: &[[f64; 2]], out: &mut [WideOf<I>]| {
            chunk::hemisphere_values(g, p, |b| b, out)
        })
    }

    fn name(&self) -> &'static str {
        "gauss-legendre"
    }
}

/// Gauss–Legendre on the unit square pulled through the integrand's
/// importance-sampling map `u ↦ ω(u)` with density `p`:
///
/// `∫_H g dω = ∫_{[0,1]²} g(ω(u)) / p(ω(u)) du ≈ Σᵢ Σⱼ aᵢ aⱼ g(ωᵢⱼ)/p(ωᵢⱼ)`
///
/// (change of variables; valid when the map is injective on the support of
/// `g`; points where [`Integrand::sample`] returns `None` contribute 0).
/// The change of variables is that of primary-sample space (Veach 1997,
/// PhD thesis, §8.2; Kelemen et al. 2002); Mitsuba 3 (Jakob et al. 2022)
/// computes directional albedos the same way, with Gauss–Legendre nodes on
/// the sample square. Narrow lobes become smooth functions of `u`, so few
/// nodes suffice.
///
/// `n × n` nodes plus the comparison rules of half, quarter and eighth
/// order; the error estimate is built as for [`GaussLegendre`]. Where the
/// map returns `None` on part of the square (e.g. grazing microfacet
/// reflections below the horizon) the warped integrand is discontinuous and
/// convergence is only algebraic.
///
/// Needs [`Integrand::has_sampling_map`] (else
/// [`IntegrateError::NoSamplingMap`]). Minimum budget 5 (`n = 2`); capped
/// at `n = 1024` ([`MAX_ORDER`]): 1,392,640 evaluations. Sample draws count
/// as evaluations. A NaN/∞ value or density gives
/// [`IntegrateError::NonFiniteIntegrand`].
///
/// ```
/// use radiometry::integrator::{DirectionalAlbedo, Integrator, WarpedGaussLegendre};
/// use radiometry::{Brdf, glam::Vec3};
/// struct Lambert;
/// impl Brdf for Lambert {
///     type Spectrum = f32;
///     fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
///         if wi.z > 0.0 && wo.z > 0.0 { 0.8 / core::f32::consts::PI } else { 0.0 }
///     }
/// }
/// let g = DirectionalAlbedo { brdf: Lambert, wo: Vec3::Z };
/// let e = WarpedGaussLegendre::new().integrate(&g, 64).unwrap();
/// assert!((e.value - 0.8).abs() < 1e-6);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct WarpedGaussLegendre {
    _private: (),
}

impl WarpedGaussLegendre {
    /// The warped product rule (orders follow from the budget).
    pub const fn new() -> Self {
        Self { _private: () }
    }

    /// Smallest accepted budget.
    pub const MIN_BUDGET: u32 = 5;

    /// Order `n` (per axis) used for a budget (`0` below [`Self::MIN_BUDGET`]).
    pub fn order(budget: u32) -> usize {
        let n = order_for_budget(budget, 1);
        if n < 2 { 0 } else { n }
    }
}

impl Integrator for WarpedGaussLegendre {
    fn integrate<I: Integrand>(&self, g: &I, budget: u32) -> Result<Estimate<WideOf<I>>, IntegrateError> {
        if !g.has_sampling_map() {
            return Err(IntegrateError::NoSamplingMap);
        }
        let n = Self::order(budget);
        if n == 0 {
            return Err(IntegrateError::BudgetTooSmall {
                minimum: Self::MIN_BUDGET,
            });
        }
        with_comparison_rules(n, n, |p: &[[f64; 2]], out: &mut [WideOf<I>]| {
            chunk::warped_values(g, p, out)
        })
    }

    fn name(&self) -> &'static str {
        "gauss-legendre-warped"
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rule_integrates_polynomials_exactly() {
        let (mut x, mut w) = ([0.0; 64], [0.0; 64]);
        for n in [1usize, 2, 3, 7, 20, 64] {
            assert_eq!(gauss_legendre_rule(n, &mut x, &mut w), n);
            for deg in 0..(2 * n) {
                let q: f64 = (0..n).map(|k| w[k] * libm::pow(x[k], deg as f64)).sum();
                let exact = if deg % 2 == 1 {
                    0.0
                } else {
                    2.0 / (deg as f64 + 1.0)
                };
                assert!((q - exact).abs() < 1e-13, "n={n} deg={deg} q={q}");
            }
            for k in 1..n {
                assert!(x[k] > x[k - 1]);
            }
        }
        assert_eq!(gauss_legendre_rule(0, &mut x, &mut w), 0);
        assert_eq!(gauss_legendre_rule(65, &mut x, &mut w), 0);
    }

    #[test]
    fn high_order_rule_is_accurate() {
        let mut x = [0.0; MAX_ORDER];
        let mut w = [0.0; MAX_ORDER];
        assert_eq!(gauss_legendre_rule(MAX_ORDER, &mut x, &mut w), MAX_ORDER);
        let s: f64 = w.iter().sum();
        assert!((s - 2.0).abs() < 1e-12, "{s}");
        // ∫₋₁¹ cos(20x) dx = sin(20)/10
        let q: f64 = (0..MAX_ORDER).map(|k| w[k] * libm::cos(20.0 * x[k])).sum();
        assert!((q - libm::sin(20.0) / 10.0).abs() < 1e-13);
    }

    #[test]
    fn orders_fit_budget() {
        for b in [0u32, 9, 10, 11, 100, 4096, 65536, 1 << 20, u32::MAX] {
            let (nt, np) = GaussLegendre::orders(b);
            assert!(levels_cost(nt, np) as u64 <= b as u64, "{b}");
            assert!(np <= MAX_ORDER);
            let n = WarpedGaussLegendre::order(b);
            assert!(levels_cost(n, n) as u64 <= b as u64);
        }
        assert_eq!(GaussLegendre::orders(11), (2, 4));
        assert_eq!(GaussLegendre::orders(10), (0, 0));
        assert_eq!(levels_cost(512, 1024), 696_320);
        assert_eq!(levels_cost(1024, 1024), 1_392_640);
        assert_eq!(GaussLegendre::orders(u32::MAX), (512, 1024));
    }
}
