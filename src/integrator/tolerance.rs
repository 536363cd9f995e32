//! Refining any [`Integrator`] to an error tolerance by budget doubling.

use super::acc;
use super::{Estimate, Integrand, IntegrateError, Integrator, WideOf};
use crate::spectrum::WideSpectrum;

/// Default largest budget [`integrate_to_tolerance`] tries (`2²²`).
pub const DEFAULT_MAX_BUDGET: u32 = 1 << 22;

/// Why [`integrate_to_tolerance`] stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum StopReason {
    /// The tolerance was met on evidence that holds: a
    /// [`Status::Resolved`](super::Status::Resolved) estimate whose error
    /// estimate (every channel) is `≤ tol`, *confirmed* by a run whose
    /// value differs from it by `≤ tol` (see
    /// [`ToleranceOutcome::confirmation`]): for budget doubling the larger
    /// run; for [`Auto`](super::Auto) and the warped
    /// [`Adaptive`](super::Adaptive) rule a run from scratch of a rule with
    /// other nodes (the plain `(μ, φ)` square split at the integrand's
    /// [kinks](super::Integrand::kinks), the sampling map's square, or the
    /// shifted twin of either: other cuts, bent coordinates; where the
    /// integrand is not [smooth](super::Integrand::is_smooth), a rule of
    /// the other square or two more rules of the plain square), never a
    /// stage of the candidate's own refinement; for the plain [`Adaptive`](super::Adaptive) rule a run
    /// from scratch at twice the evaluations and an importance-sampled mean
    /// check. An unresolved estimate never counts as converged, however
    /// small its error, and neither does a single run, however confident.
    ToleranceReached,
    /// The run at `max_budget` did not reach the tolerance (or did not
    /// confirm it).
    MaxBudget,
    /// Doubling the budget no longer increased the evaluations spent: the
    /// integrator hit its own cap (or an adaptive rule its own tolerance).
    IntegratorCap,
    /// The tolerance is out of reach: for an integrator whose error falls
    /// no faster than a known rate ([`Integrator::error_decay`], `N^-½` for
    /// Monte Carlo), two resolved runs project more than
    /// [`OUT_OF_REACH_FACTOR`]` × max_budget` evaluations to reach it, so
    /// the driver stops instead of spending the maximum on a run that
    /// cannot.
    OutOfReach,
}

/// [`StopReason::OutOfReach`] fires when the projected evaluations exceed
/// this many times `max_budget`.
pub const OUT_OF_REACH_FACTOR: f64 = 4.0;

impl StopReason {
    /// `"tolerance reached"`, `"max budget reached"`, `"integrator cap
    /// reached"` or `"out of reach"` (the CLI's and the report's `stopped`
    /// column).
    pub const fn as_str(self) -> &'static str {
        match self {
            StopReason::ToleranceReached => "tolerance reached",
            StopReason::MaxBudget => "max budget reached",
            StopReason::IntegratorCap => "integrator cap reached",
            StopReason::OutOfReach => "out of reach",
        }
    }
}

/// Result of [`integrate_to_tolerance`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct ToleranceOutcome<W> {
    /// The estimate of the last (largest-budget) run.
    pub estimate: Estimate<W>,
    /// The budget of that run.
    pub budget: u32,
    /// Why refinement stopped; `ToleranceReached` iff the tolerance was met
    /// and confirmed.
    pub stop: StopReason,
    /// Evaluations spent over all runs (the doubling overhead included:
    /// at most about twice `estimate.evaluations`).
    pub total_evaluations: u64,
    /// With [`StopReason::ToleranceReached`]: `|value − value of the
    /// confirming run|` per channel (`≤ tol`), an error estimate of the
    /// *smaller* run that does not depend on either run's own estimate;
    /// `None` otherwise.
    pub confirmation: Option<W>,
    /// Integrator runs made (a staged [`Adaptive`](super::Adaptive) run
    /// counts once).
    pub runs: u32,
}

impl<W> ToleranceOutcome<W> {
    /// Whether the error estimate reached the tolerance (and was confirmed).
    pub fn reached(&self) -> bool {
        self.stop == StopReason::ToleranceReached
    }
}

/// Checks the arguments of [`integrate_to_tolerance`]: `tol` finite and
/// `> 0`, `1 ≤ start_budget ≤ max_budget`.
pub fn check_tolerance_args(tol: f64, start_budget: u32, max_budget: u32) -> Result<(), IntegrateError> {
    if !(tol.is_finite() && tol > 0.0) {
        return Err(IntegrateError::InvalidConfig("tol must be finite and > 0"));
    }
    if start_budget == 0 || max_budget < start_budget {
        return Err(IntegrateError::InvalidConfig(
            "need 1 <= start_budget <= max_budget",
        ));
    }
    Ok(())
}

/// Refines `integrator` to the absolute tolerance `tol` (largest channel):
/// [`Integrator::to_tolerance`], which for most integrators is
/// [`by_doubling`] and for [`Adaptive`](super::Adaptive) one staged run that
/// refines its own regions instead of starting again.
///
/// It stops with [`StopReason::ToleranceReached`] only on evidence beyond one
/// run: a resolved estimate with error `≤ tol` whose value is within `tol`
/// of a confirming run's (see [`StopReason::ToleranceReached`]). One lucky
/// run — a rule whose nodes all fall on the flat part of a lobe, so that its
/// two embedded rules agree to `10⁻⁷` while the lobe's tail is missed by
/// `10⁻⁴` — is not enough: the next run sees the tail, moves by more than
/// `tol`, and refinement goes on. Nor is a refinement that confirms itself
/// where the integrand is not what its error estimate assumes (a kink, a
/// lobe cut by the horizon, the seam of a mixture sampling map at
/// `u₀ = p`): [`Auto`](super::Auto) and the warped rule then need an
/// unrelated rule on another parameterisation to agree.
///
/// Domain: `tol` finite and `> 0`, `start_budget ≥ 1`,
/// `max_budget ≥ start_budget` (use [`DEFAULT_MAX_BUDGET`] if unsure);
/// otherwise [`IntegrateError::InvalidConfig`]. Errors of the integrator
/// (non-finite integrand, no sampling map, a minimum above `max_budget`) are
/// passed through.
///
/// ```
/// use radiometry::integrator::{GaussLegendre, Integrand, integrate_to_tolerance, DEFAULT_MAX_BUDGET};
/// use radiometry::glam::Vec3;
/// struct Cos;
/// impl Integrand for Cos {
///     type Spectrum = f32;
///     fn eval(&self, w: Vec3) -> f32 { w.z }
/// }
/// let out = integrate_to_tolerance(&GaussLegendre::new(), &Cos, 1e-5, 16, DEFAULT_MAX_BUDGET).unwrap();
/// assert!(out.reached());
/// assert!(out.confirmation.unwrap() <= 1e-5);
/// assert!((out.estimate.value - core::f64::consts::PI).abs() < 1e-5);
/// ```
pub fn integrate_to_tolerance<T: Integrator, I: Integrand>(
    integrator: &T,
    g: &I,
    tol: f64,
    start_budget: u32,
    max_budget: u32,
) -> Result<ToleranceOutcome<WideOf<I>>, IntegrateError> {
    check_tolerance_args(tol, start_budget, max_budget)?;
    integrator.to_tolerance(g, tol, start_budget, max_budget)
}

/// The budget-doubling driver (the default [`Integrator::to_tolerance`]):
/// runs `integrator` with budgets `b₀, 2b₀, 4b₀, …` (`b₀ = start_budget`,
/// raised to the integrator's minimum if it reports
/// [`IntegrateError::BudgetTooSmall`]; the last doubling is clipped to
/// `max_budget`). It stops with [`StopReason::ToleranceReached`] at the
/// first run that is resolved, has `max_c error_c ≤ tol`, and whose value is
/// within `tol` of the previous run's value (every channel); with
/// [`StopReason::IntegratorCap`] when doubling no longer increases the
/// evaluations spent; with [`StopReason::MaxBudget`] after the run at
/// `max_budget`. Each run is independent (the rules are not nested);
/// doubling makes the total at most ≈ 2× the final run.
pub fn by_doubling<T: Integrator + ?Sized, I: Integrand>(
    integrator: &T,
    g: &I,
    tol: f64,
    start_budget: u32,
    max_budget: u32,
) -> Result<ToleranceOutcome<WideOf<I>>, IntegrateError> {
    check_tolerance_args(tol, start_budget, max_budget)?;
    let mut budget = start_budget;
    let mut total = 0u64;
    let mut runs = 0u32;
    let mut last: Option<Estimate<WideOf<I>>> = None;
    loop {
        let e = match integrator.integrate(g, budget) {
            Ok(e) => e,
            Err(IntegrateError::BudgetTooSmall { minimum }) if last.is_none() && minimum > budget => {
                if minimum > max_budget {
                    return Err(IntegrateError::BudgetTooSmall { minimum });
                }
                budget = minimum;
                continue;
            }
            Err(err) => return Err(err),
        };
        total += e.evaluations;
        runs += 1;
        let stalled = last.is_some_and(|p| e.evaluations <= p.evaluations);
        let done = |stop, confirmation| ToleranceOutcome {
            estimate: e,
            budget,
            stop,
            total_evaluations: total,
            confirmation,
            runs,
        };
        if let Some(p) = last
            && !stalled
            && e.is_resolved()
            && acc::max_abs(e.error) <= tol
        {
            let d = acc::abs_diff(e.value, p.value);
            if acc::max_abs(d) <= tol {
                return Ok(done(StopReason::ToleranceReached, Some(d)));
            }
        }
        // The integrator's own cap: a larger budget would repeat this run.
        let capped = integrator.max_evaluations().is_some_and(|c| e.evaluations >= c);
        if stalled || (capped && budget < max_budget) {
            return Ok(done(StopReason::IntegratorCap, None));
        }
        // The projection is measured against `max_budget`, not the
        // integrator's cap: randomized QMC can beat the N^-½ rate the
        // projection assumes, and a tighter threshold stopped runs that
        // would have reached the tolerance at the cap.
        if let (Some(p), Some(rate)) = (last, integrator.error_decay())
            && out_of_reach(&p, &e, rate, tol, max_budget)
        {
            return Ok(done(StopReason::OutOfReach, None));
        }
        if budget >= max_budget {
            return Ok(done(StopReason::MaxBudget, None));
        }
        last = Some(e);
        budget = budget.saturating_mul(2).min(max_budget);
    }
}

/// Whether two successive resolved runs `p`, `e` project more than
/// [`OUT_OF_REACH_FACTOR`]` × max_budget` evaluations to reach `tol`: with
/// the observed decay rate `r = ln(err_p/err_e) / ln(N_e/N_p)`, never taken
/// below the integrator's guaranteed `rate`, the projection is
/// `N_e (err_e/tol)^(1/r)` (largest channel).
fn out_of_reach<W: WideSpectrum>(
    p: &Estimate<W>,
    e: &Estimate<W>,
    rate: f64,
    tol: f64,
    max_budget: u32,
) -> bool {
    let (ep, ee) = (acc::max_abs(p.error), acc::max_abs(e.error));
    if !(p.is_resolved() && e.is_resolved() && ee > tol && ep > 0.0 && rate > 0.0) {
        return false;
    }
    let (np, ne) = (p.evaluations as f64, e.evaluations as f64);
    if !(ne > np && np > 0.0) {
        return false;
    }
    let observed = libm::log(ep / ee) / libm::log(ne / np);
    let r = if observed.is_finite() {
        observed.max(rate)
    } else {
        rate
    };
    let need = ne * libm::pow(ee / tol, 1.0 / r);
    need > OUT_OF_REACH_FACTOR * max_budget as f64
}
