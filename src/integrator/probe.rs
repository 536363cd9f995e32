//! The peak probe of the blind quadrature rules (and of uniform and
//! cosine-weighted Monte Carlo, whose draws are as blind: see
//! [`MonteCarlo`](super::MonteCarlo)).
//!
//! [`GaussLegendre`](super::GaussLegendre) and [`Adaptive`](super::Adaptive)
//! (not warped) place their nodes in `(μ, φ)` without looking at the
//! integrand. A lobe narrower than their node spacing — a glossy peak at a
//! grazing mirror direction, say — is then seen only through its tails, and
//! the comparison rules, which see the same tails, agree with each other:
//! the estimate converges, to the wrong value, with a small error estimate.
//! No rule on a fixed grid can detect what lies between all its nodes. The
//! integrand often can: where it has an importance-sampling map
//! ([`Integrand::has_sampling_map`]), a handful of points drawn through the
//! map land on the peak. If the largest integrand value among them exceeds
//! the largest value the rule saw at any node by more than [`PEAK_RATIO`],
//! the rule missed a peak and its estimate is marked
//! [`Unresolved::UnseenPeak`].
//!
//! Why a factor 2 leaves resolved estimates alone: a rule that resolves a
//! lobe of width `σ` (standard deviation of a Gaussian-like peak) has nodes
//! at most about `1.7 σ` apart across it, so one node lies within `0.85 σ`
//! of the maximum on each axis, where the lobe keeps
//! `e^{-2 · 0.85²/2} ≈ 0.49` of its peak value or more; nodes farther apart
//! sample the lobe too coarsely for a 10⁻⁴ estimate anyway. (The probe's
//! largest value is itself at most the peak value.)
//!
//! Cost: [`PROBE_POINTS`] draws of the sampling map, taken from the budget
//! (so the rule itself gets that many fewer evaluations) at budgets of at
//! least [`PROBE_MIN_BUDGET`]; below it, and for integrands without a
//! sampling map, no probe is made.

use super::acc::{self, to_unit_f32};
use super::{Integrand, IntegrandSample, IntegrateError, Status, Unresolved, check_finite};
use crate::spectrum::Spectrum;
use glam::Vec3;

/// Draws of the integrand's sampling map per probe: the points
/// `uₖ = ((k + ½)/16, frac((k + ½)/φ))`, `φ` the golden ratio (a
/// rank-1 lattice-like set spread over the square).
pub const PROBE_POINTS: usize = 16;

/// A probe value above `PEAK_RATIO ×` the largest node value marks the
/// estimate unresolved (see the module docs for the choice of 2).
pub const PEAK_RATIO: f64 = 2.0;

/// Smallest budget at which the blind rules probe (the probe's
/// [`PROBE_POINTS`] evaluations come out of the budget).
pub const PROBE_MIN_BUDGET: u32 = 64;

/// The budget left for the rule after the probe, and whether to probe:
/// only with a sampling map, at budgets ≥ [`PROBE_MIN_BUDGET`] that leave
/// the rule at least its own minimum `rule_min`.
pub(crate) fn split_budget<I: Integrand>(g: &I, budget: u32, rule_min: u32) -> (u32, bool) {
    if g.has_sampling_map() && budget >= PROBE_MIN_BUDGET.max(rule_min.saturating_add(PROBE_POINTS as u32)) {
        (budget - PROBE_POINTS as u32, true)
    } else {
        (budget, false)
    }
}

/// The probe: up to [`PROBE_POINTS`] directions drawn through the
/// integrand's sampling map, each with `max_channel |g(ω)|` (draws where the
/// map gives no direction are left out).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Probe {
    pub(crate) points: [(Vec3, f64); PROBE_POINTS],
    pub(crate) len: usize,
}

impl Probe {
    /// Draws the probe. A non-finite value is
    /// [`IntegrateError::NonFiniteIntegrand`].
    pub(crate) fn take<I: Integrand>(g: &I) -> Result<Self, IntegrateError> {
        const INV_GOLDEN: f64 = 0.618_033_988_749_894_8;
        let mut us = [[0.0f32; 2]; PROBE_POINTS];
        for (k, u) in us.iter_mut().enumerate() {
            let t = k as f64 + 0.5;
            let b = t * INV_GOLDEN;
            *u = [
                to_unit_f32(t / PROBE_POINTS as f64),
                to_unit_f32(b - libm::floor(b)),
            ];
        }
        let mut ss: [Option<IntegrandSample<I::Spectrum>>; PROBE_POINTS] = [None; PROBE_POINTS];
        g.sample_batch(&us, &mut ss);
        let mut probe = Probe {
            points: [(Vec3::ZERO, 0.0); PROBE_POINTS],
            len: 0,
        };
        for s in ss.iter().flatten() {
            let v = check_finite(s.value.to_wide())?;
            probe.points[probe.len] = (s.w, acc::max_abs(v));
            probe.len += 1;
        }
        Ok(probe)
    }

    /// The probe's points and values.
    pub(crate) fn points(&self) -> &[(Vec3, f64)] {
        &self.points[..self.len]
    }

    /// The largest value of the probe (0 if it has no point).
    pub(crate) fn peak(&self) -> f64 {
        self.points().iter().fold(0.0, |m, p| m.max(p.1))
    }
}

/// `status` unless it is resolved and the probe found a value above
/// [`PEAK_RATIO`] × `node_peak` (the largest `max_channel |g|` at the
/// rule's nodes): then [`Unresolved::UnseenPeak`].
pub(crate) fn judge(status: Status, node_peak: f64, probe: f64) -> Status {
    if probe > PEAK_RATIO * node_peak {
        status.combine(Status::Unresolved(Unresolved::UnseenPeak))
    } else {
        status
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A lobe of width `w` about the direction `c`, with a sampling map that
    /// always returns the lobe's centre.
    struct Spike;
    impl Integrand for Spike {
        type Spectrum = f32;
        fn eval(&self, w: Vec3) -> f32 {
            let c = Vec3::new(0.6, 0.0, 0.8);
            let d = (w - c).length_squared();
            libm::expf(-d / 1e-6)
        }
        fn has_sampling_map(&self) -> bool {
            true
        }
        fn sample(&self, _u: [f32; 2]) -> Option<IntegrandSample<f32>> {
            let w = Vec3::new(0.6, 0.0, 0.8);
            Some(IntegrandSample {
                w,
                pdf: 1.0,
                value: self.eval(w),
            })
        }
        fn pdf(&self, _w: Vec3) -> f32 {
            1.0
        }
    }

    #[test]
    fn probe_sees_the_peak_and_judges() {
        let probe = Probe::take(&Spike).unwrap();
        assert_eq!(probe.points().len(), PROBE_POINTS);
        let p = probe.peak();
        assert!((p - 1.0).abs() < 1e-6, "{p}");
        assert_eq!(
            judge(Status::Resolved, 0.4, p),
            Status::Unresolved(Unresolved::UnseenPeak)
        );
        assert_eq!(judge(Status::Resolved, 0.6, p), Status::Resolved);
        assert_eq!(judge(Status::Resolved, 0.3, 0.59), Status::Resolved);
        assert_eq!(
            judge(Status::Resolved, 0.3, 0.61),
            Status::Unresolved(Unresolved::UnseenPeak)
        );
        // An earlier reason is kept.
        let few = Status::Unresolved(Unresolved::FewNodes);
        assert_eq!(judge(few, 0.0, p), few);
    }

    #[test]
    fn budget_split() {
        assert_eq!(split_budget(&Spike, 63, 11), (63, false));
        assert_eq!(split_budget(&Spike, 64, 11), (48, true));
        assert_eq!(split_budget(&Spike, 70, 68), (70, false));
        assert_eq!(split_budget(&Spike, 84, 68), (68, true));
    }
}
