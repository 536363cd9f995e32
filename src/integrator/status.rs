//! Whether an [`Estimate`](super::Estimate) can be trusted.
//!
//! Every integrator attaches a [`Status`] to its estimate. `Resolved` means
//! the integrator saw what it needs to stand behind its error estimate;
//! `Unresolved` carries the reason it cannot (the value and error are still
//! reported, finite, but a benchmark or a tolerance loop must not treat
//! them as converged: [`integrate_to_tolerance`](super::integrate_to_tolerance)
//! never stops with `ToleranceReached` on an unresolved estimate).

use core::fmt;

/// Whether an estimate can be trusted, and if not, why.
///
/// ```
/// use radiometry::integrator::{Status, Unresolved};
/// assert!(Status::Resolved.is_resolved());
/// let s = Status::Unresolved(Unresolved::NoSupportSeen);
/// assert_eq!(s.combine(Status::Resolved), s);
/// assert_eq!(s.as_str(), "unresolved");
/// assert_eq!(s.reason(), "no-support-seen");
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Status {
    /// The integrator stands behind its error estimate.
    #[default]
    Resolved,
    /// The estimate cannot be trusted; the reason says why.
    Unresolved(Unresolved),
}

/// Why an estimate is [`Status::Unresolved`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Unresolved {
    /// Every node or sample returned zero: the integrand's support (a
    /// narrow lobe, a small light) may lie between them, so the estimate
    /// `0 ± 0` says nothing.
    NoSupportSeen,
    /// Quadrature: the comparison rules do not show convergence (the
    /// differences between successive rules do not shrink), so the
    /// a-posteriori error estimate is not backed by an observed rate.
    NotConverging,
    /// Quadrature: the integrand's value changed from zero to non-zero
    /// between the nodes of the coarsest comparison rules in a way the
    /// rules could not locate (a step the error estimate cannot see).
    UnlocatedStep,
    /// Quadrature: the estimate rests on a handful of nodes (effective node
    /// count `(Σ|w g|)²/Σ(w g)²` below 16): a lobe narrower than the node
    /// spacing, which the comparison rules cannot measure either.
    FewNodes,
    /// Monte Carlo: too few samples hit the support (fewer than
    /// [`MIN_HITS`]), so the sample variance — and the standard error —
    /// is itself unreliable.
    FewHits,
    /// Monte Carlo: the estimate is dominated by a few samples (effective
    /// sample size `(Σx)²/Σx²` below [`MIN_EFFECTIVE_SAMPLES`]): a
    /// heavy-tailed weight distribution whose standard error understates.
    HeavyTail,
    /// Quadrature on a fixed grid (`gauss-legendre`, `adaptive`) or
    /// uniform / cosine Monte Carlo: points drawn through the integrand's
    /// own sampling map found values more than
    /// [`PEAK_RATIO`](super::probe::PEAK_RATIO) times the largest value at
    /// any node or draw — a peak seen only through its tails (see
    /// [`probe`](super::probe)).
    UnseenPeak,
    /// Quadrature on a fixed grid (`gauss-legendre`, `adaptive`), budgets
    /// ≥ [`MEAN_CHECK_MIN_BUDGET`](super::probe::MEAN_CHECK_MIN_BUDGET): an
    /// importance-sampled estimate through the integrand's own map, drawn
    /// beside the rule, differs from the rule's value by more than both
    /// errors allow — part of the integral lies where the rule's nodes do
    /// not reach (see [`probe`](super::probe)).
    ProbeDisagrees,
    /// An integrator outside this crate (a user integrator in a report)
    /// declared its estimate unresolved.
    External,
}

/// Fewest non-zero Monte Carlo samples for a [`Status::Resolved`] estimate.
pub const MIN_HITS: u64 = 32;

/// Smallest effective sample size `(Σx)²/Σx²` (per channel) of a resolved
/// Monte Carlo estimate (Kong 1992; Owen, *Monte Carlo theory, methods and
/// examples*, 2013, §9.3).
pub const MIN_EFFECTIVE_SAMPLES: f64 = 16.0;

impl Status {
    /// Whether the estimate is resolved.
    #[inline]
    pub const fn is_resolved(self) -> bool {
        matches!(self, Status::Resolved)
    }

    /// The status of a combination of two estimates (a sum over lights, say):
    /// unresolved if either is, with the first reason.
    #[inline]
    pub const fn combine(self, other: Status) -> Status {
        match self {
            Status::Resolved => other,
            s => s,
        }
    }

    /// `"resolved"` or `"unresolved"` (the CSV/JSON `status` column).
    pub const fn as_str(self) -> &'static str {
        match self {
            Status::Resolved => "resolved",
            Status::Unresolved(_) => "unresolved",
        }
    }

    /// The reason as a short kebab-case string (the CSV/JSON
    /// `status_reason` column); empty when resolved.
    pub const fn reason(self) -> &'static str {
        match self {
            Status::Resolved => "",
            Status::Unresolved(r) => r.as_str(),
        }
    }
}

impl Unresolved {
    /// A short kebab-case name (`"no-support-seen"`, …).
    pub const fn as_str(self) -> &'static str {
        match self {
            Unresolved::NoSupportSeen => "no-support-seen",
            Unresolved::NotConverging => "not-converging",
            Unresolved::UnlocatedStep => "unlocated-step",
            Unresolved::FewNodes => "few-nodes",
            Unresolved::FewHits => "few-hits",
            Unresolved::HeavyTail => "heavy-tail",
            Unresolved::UnseenPeak => "unseen-peak",
            Unresolved::ProbeDisagrees => "probe-disagrees",
            Unresolved::External => "external",
        }
    }
}

impl fmt::Display for Status {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Status::Resolved => f.write_str("resolved"),
            Status::Unresolved(r) => write!(f, "unresolved ({})", r.as_str()),
        }
    }
}
