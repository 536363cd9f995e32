//! Refining any [`Integrator`] to an error tolerance by budget doubling.

use super::acc;
use super::{Estimate, Integrand, IntegrateError, Integrator, WideOf};

/// Default largest budget [`integrate_to_tolerance`] tries (`2²²`).
pub const DEFAULT_MAX_BUDGET: u32 = 1 << 22;

/// Why [`integrate_to_tolerance`] stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum StopReason {
    /// The error estimate (every channel) fell to `≤ tol` on a
    /// [`Status::Resolved`](super::Status::Resolved) estimate (an unresolved
    /// estimate never counts as converged, however small its error).
    ToleranceReached,
    /// The run at `max_budget` did not reach the tolerance.
    MaxBudget,
    /// Doubling the budget no longer increased the evaluations spent: the
    /// integrator hit its own cap (or an adaptive rule its own tolerance).
    IntegratorCap,
}

/// Result of [`integrate_to_tolerance`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ToleranceOutcome<W> {
    /// The estimate of the last (largest-budget) run.
    pub estimate: Estimate<W>,
    /// The budget of that run.
    pub budget: u32,
    /// Why refinement stopped; `ToleranceReached` iff the tolerance was met.
    pub stop: StopReason,
    /// Evaluations spent over all runs (the doubling overhead included:
    /// at most about twice `estimate.evaluations`).
    pub total_evaluations: u64,
}

impl<W> ToleranceOutcome<W> {
    /// Whether the error estimate reached the tolerance.
    pub fn reached(&self) -> bool {
        self.stop == StopReason::ToleranceReached
    }
}

/// Runs `integrator` with budgets `b₀, 2b₀, 4b₀, …` (`b₀ = start_budget`,
/// raised to the integrator's minimum if it reports
/// [`IntegrateError::BudgetTooSmall`]) until the error estimate satisfies
/// `max_c error_c ≤ tol` (absolute, largest channel), a run at `max_budget`
/// (the last doubling is clipped to it; use [`DEFAULT_MAX_BUDGET`] if
/// unsure) has not met it, or the spent
/// evaluations stop growing. Each run is independent (quadrature rules are
/// not nested); the last estimate is returned with the reason. Doubling
/// makes the total cost at most ≈ 2× the final run (a geometric series).
///
/// Domain: `tol` finite and `> 0`, `start_budget ≥ 1`,
/// `max_budget ≥ start_budget`; otherwise [`IntegrateError::InvalidConfig`].
/// Errors of the integrator (non-finite integrand, no sampling map, a
/// minimum above `max_budget`) are passed through.
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
/// assert!((out.estimate.value - core::f64::consts::PI).abs() < 1e-5);
/// ```
pub fn integrate_to_tolerance<T: Integrator, I: Integrand>(
    integrator: &T,
    g: &I,
    tol: f64,
    start_budget: u32,
    max_budget: u32,
) -> Result<ToleranceOutcome<WideOf<I>>, IntegrateError> {
    if !(tol.is_finite() && tol > 0.0) {
        return Err(IntegrateError::InvalidConfig("tol must be finite and > 0"));
    }
    if start_budget == 0 || max_budget < start_budget {
        return Err(IntegrateError::InvalidConfig(
            "need 1 <= start_budget <= max_budget",
        ));
    }
    let mut budget = start_budget;
    let mut total = 0u64;
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
        let stalled = last.is_some_and(|p| e.evaluations <= p.evaluations);
        let done = |stop| ToleranceOutcome {
            estimate: e,
            budget,
            stop,
            total_evaluations: total,
        };
        if acc::max_abs(e.error) <= tol && e.is_resolved() {
            return Ok(done(StopReason::ToleranceReached));
        }
        if stalled {
            return Ok(done(StopReason::IntegratorCap));
        }
        if budget >= max_budget {
            return Ok(done(StopReason::MaxBudget));
        }
        last = Some(e);
        budget = budget.saturating_mul(2).min(max_budget);
    }
}
