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
//!
//! **Mean check** (large budgets). A peak seen at a node can still be
//! under-integrated: part of a lobe narrower than the node spacing sits in a
//! margin no node enters, the comparison rules agree on the deficit, and the
//! estimate converges to the wrong value with a small error (seen: plain
//! `adaptive` on Beckmann `α = 10⁻³` at `θo = 60°`, 1.4 % low with an
//! estimate of 1.5·10⁻⁴ at 10⁶ evaluations). At budgets of at least
//! [`MEAN_CHECK_MIN_BUDGET`] the blind rules also spend one evaluation in
//! [`MEAN_CHECK_SHARE`] (at most [`MEAN_CHECK_MAX_POINTS`]) on an
//! importance-sampled estimate through the same map (`n` points of a
//! rank-1 lattice, mean `P` of `g/p`, standard error `σ`), independent of
//! the rule's nodes. When that estimate is itself resolved (enough hits, no
//! heavy tail: the Monte Carlo criteria) and the rule's value `Q` misses `P`
//! by more than `error(Q) + 4σ + |P|/n` in some channel (`|P|/n`: what a
//! region of mass `1/n` of the map that no point entered could hide), one
//! of the two is wrong and the rule's estimate is marked
//! [`Unresolved::ProbeDisagrees`].

use super::acc::{self, WideSum, to_unit_f32};
use super::chunk::{CHUNK, sample_weight};
use super::{
    Integrand, IntegrandSample, IntegrateError, MIN_EFFECTIVE_SAMPLES, MIN_HITS, Status, Unresolved,
    check_finite,
};
use crate::spectrum::{Spectrum, WideSpectrum};
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

/// Point `k` of the `n`-point rank-1 lattice-like set of the probes:
/// `((k + ½)/n, frac((k + ½)/φ))`, `φ` the golden ratio.
pub(crate) fn lattice_point(k: usize, n: usize) -> [f32; 2] {
    const INV_GOLDEN: f64 = 0.618_033_988_749_894_8;
    let t = k as f64 + 0.5;
    let b = t * INV_GOLDEN;
    [to_unit_f32(t / n as f64), to_unit_f32(b - libm::floor(b))]
}

impl Probe {
    /// Draws the probe. A non-finite value is
    /// [`IntegrateError::NonFiniteIntegrand`].
    pub(crate) fn take<I: Integrand>(g: &I) -> Result<Self, IntegrateError> {
        let mut us = [[0.0f32; 2]; PROBE_POINTS];
        for (k, u) in us.iter_mut().enumerate() {
            *u = lattice_point(k, PROBE_POINTS);
        }
        let mut ss: [Option<IntegrandSample<I::Spectrum>>; PROBE_POINTS] = [None; PROBE_POINTS];
        g.sample_batch(&us, &mut ss);
        let mut probe = Probe {
            points: [(Vec3::ZERO, 0.0); PROBE_POINTS],
            len: 0,
        };
        for s in ss.iter().flatten() {
            let v = check_finite(s.value.to_wide())?;
            if let Some(p) = probe.points.get_mut(probe.len) {
                *p = (s.w, acc::max_abs(v));
                probe.len += 1;
            }
        }
        Ok(probe)
    }

    /// The probe's points and values.
    pub(crate) fn points(&self) -> &[(Vec3, f64)] {
        self.points.get(..self.len).unwrap_or_default()
    }

    /// The largest value of the probe (0 if it has no point).
    pub(crate) fn peak(&self) -> f64 {
        self.points().iter().fold(0.0, |m, p| m.max(p.1))
    }
}

/// One draw of the [mean check](self) per this many evaluations of the
/// budget, between [`MEAN_CHECK_MIN_POINTS`] and [`MEAN_CHECK_MAX_POINTS`]
/// draws.
pub const MEAN_CHECK_SHARE: u32 = 64;

/// Fewest draws of a mean check (below, `|P|/n` is too coarse to judge
/// anything).
pub const MEAN_CHECK_MIN_POINTS: u32 = 64;

/// Most draws of a mean check (`|P|/n` ≈ 10⁻³; the budget share falls to
/// 0.1 % at 2²⁰).
pub const MEAN_CHECK_MAX_POINTS: u32 = 1024;

/// Smallest budget with a mean check (4,096: 64 draws, 1.6 % of it).
pub const MEAN_CHECK_MIN_BUDGET: u32 = MEAN_CHECK_MIN_POINTS * MEAN_CHECK_SHARE;

/// Draws of the mean check at `budget` (0 below [`MEAN_CHECK_MIN_BUDGET`]
/// or without a sampling map).
pub(crate) fn mean_check_points<I: Integrand>(g: &I, budget: u32) -> u32 {
    if g.has_sampling_map() && budget >= MEAN_CHECK_MIN_BUDGET {
        (budget / MEAN_CHECK_SHARE).min(MEAN_CHECK_MAX_POINTS)
    } else {
        0
    }
}

/// The importance-sampled estimate of the [mean check](self): `mean` of
/// `g/p` over `n` draws of the integrand's map at the rank-1 lattice points
/// `((k + ½)/n, frac((k + ½)/φ))` (draws without a direction count as 0),
/// with its standard error `sigma` (channel-wise).
#[derive(Clone, Copy, Debug)]
pub(crate) struct MeanCheck<W> {
    pub(crate) mean: W,
    pub(crate) sigma: W,
    pub(crate) n: u32,
    /// The check is itself resolved by the Monte Carlo criteria (at least
    /// [`MIN_HITS`] non-zero draws and an effective sample size
    /// `(Σ|x|)²/Σx² ≥` [`MIN_EFFECTIVE_SAMPLES`] in every channel): only
    /// then can it contradict the rule.
    pub(crate) usable: bool,
}

impl<W: WideSpectrum> MeanCheck<W> {
    /// Draws the check (`n ≥ 1`), in chunks of [`CHUNK`] through
    /// [`Integrand::sample_batch`]. A non-finite value is
    /// [`IntegrateError::NonFiniteIntegrand`].
    pub(crate) fn take<I: Integrand<Spectrum = S>, S: Spectrum<Wide = W>>(
        g: &I,
        n: u32,
    ) -> Result<Self, IntegrateError> {
        Self::take_each(g, n, |_, _| {})
    }

    /// [`MeanCheck::take`], passing every draw that gives a direction to
    /// `each` with `max_channel |g|` there (the draws double as a larger
    /// peak probe: see [`Adaptive`](super::Adaptive)).
    pub(crate) fn take_each<I: Integrand<Spectrum = S>, S: Spectrum<Wide = W>>(
        g: &I,
        n: u32,
        mut each: impl FnMut(Vec3, f64),
    ) -> Result<Self, IntegrateError> {
        let mut sum = WideSum::<W>::new();
        let mut sq = WideSum::<W>::new();
        let mut abs = WideSum::<W>::new();
        let mut hits = 0u64;
        let mut us = [[0.0f32; 2]; CHUNK];
        let mut ss: [Option<IntegrandSample<S>>; CHUNK] = [None; CHUNK];
        let mut k = 0u32;
        while k < n {
            let m = ((n - k) as usize).min(CHUNK);
            for (j, u) in us[..m].iter_mut().enumerate() {
                *u = lattice_point(k as usize + j, n as usize);
            }
            g.sample_batch(&us[..m], &mut ss[..m]);
            for s in &ss[..m] {
                if let Some((d, p, w)) = sample_weight(*s)? {
                    each(d, acc::max_abs(w) * p);
                    sum.add(w);
                    sq.add(w.map(|x| x * x));
                    abs.add(w.map(f64::abs));
                    hits += u64::from(acc::nonzero(&w));
                }
            }
            k += m as u32;
        }
        let nf = n as f64;
        let mean = sum.value().map(|x| x / nf);
        let sigma = sq.value().zip(mean, |s2, m| {
            let var = (s2 / nf - m * m).max(0.0) * nf / (nf - 1.0).max(1.0);
            libm::sqrt(var / nf)
        });
        let (a, q) = (abs.value(), sq.value());
        let usable = hits >= MIN_HITS
            && (0..W::CHANNELS).all(|i| {
                let (a, q) = (a.channel(i), q.channel(i));
                q <= 0.0 || a * a / q >= MIN_EFFECTIVE_SAMPLES
            });
        Ok(MeanCheck {
            mean,
            sigma,
            n,
            usable,
        })
    }

    /// `status` unless it is resolved, the check is usable and
    /// `value ± error` (the rule's estimate) misses the check's mean by more
    /// than `error + 4σ + |mean|/n` in some channel: then
    /// [`Unresolved::ProbeDisagrees`].
    pub(crate) fn judge(&self, status: Status, value: W, error: W) -> Status {
        let n = self.n as f64;
        let off = self.usable
            && (0..W::CHANNELS).any(|i| {
                let (m, s) = (self.mean.channel(i), self.sigma.channel(i));
                (value.channel(i) - m).abs() > error.channel(i) + 4.0 * s + m.abs() / n
            });
        if off {
            status.combine(Status::Unresolved(Unresolved::ProbeDisagrees))
        } else {
            status
        }
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

    /// `g = 1` with the uniform map (`g/p = 2π` everywhere), no direction
    /// for `u₀ < ½`.
    struct HalfUniform;
    impl Integrand for HalfUniform {
        type Spectrum = f32;
        fn eval(&self, _w: Vec3) -> f32 {
            1.0
        }
        fn has_sampling_map(&self) -> bool {
            true
        }
        fn sample(&self, u: [f32; 2]) -> Option<IntegrandSample<f32>> {
            (u[0] >= 0.5).then_some(IntegrandSample {
                w: Vec3::Z,
                pdf: 1.0 / core::f32::consts::TAU,
                value: 1.0,
            })
        }
        fn pdf(&self, _w: Vec3) -> f32 {
            1.0 / core::f32::consts::TAU
        }
    }

    #[test]
    fn mean_check_estimates_and_judges() {
        use core::f64::consts::PI;
        assert_eq!(mean_check_points(&HalfUniform, MEAN_CHECK_MIN_BUDGET - 1), 0);
        assert_eq!(mean_check_points(&HalfUniform, 4096), 64);
        assert_eq!(mean_check_points(&HalfUniform, 1 << 20), 1024);
        let n = 200;
        let m = MeanCheck::take(&HalfUniform, n).unwrap();
        // Half the lattice points (u₀ = (k + ½)/n < ½ for k < n/2) give no
        // direction: mean = 2π · ½ (the `f32` pdf rounds 1/2π).
        let tau32 = 1.0 / (1.0 / core::f32::consts::TAU) as f64;
        assert!((m.mean - tau32 / 2.0).abs() < 1e-12, "{m:?}");
        // Standard error of n draws of a two-point distribution {0, 2π}.
        let sd = (tau32 * tau32 / 4.0 * n as f64 / (n - 1) as f64).sqrt();
        assert!((m.sigma - sd / (n as f64).sqrt()).abs() < 1e-12, "{m:?}");
        // Within error + 4σ + |P|/n: kept; beyond: flagged.
        let tol = 4.0 * m.sigma + m.mean / n as f64;
        assert_eq!(m.judge(Status::Resolved, PI + 0.9 * tol, 0.0), Status::Resolved);
        assert_eq!(
            m.judge(Status::Resolved, PI + 0.9 * tol + 1.0, 1.0),
            Status::Resolved
        );
        assert_eq!(
            m.judge(Status::Resolved, PI - 1.1 * tol, 0.0),
            Status::Unresolved(Unresolved::ProbeDisagrees)
        );
        let few = Status::Unresolved(Unresolved::FewNodes);
        assert_eq!(m.judge(few, 0.0, 0.0), few);
        // 40 draws, 20 hits (< MIN_HITS): the check cannot judge.
        let m = MeanCheck::take(&HalfUniform, 40).unwrap();
        assert!(!m.usable);
        assert_eq!(m.judge(Status::Resolved, 0.0, 0.0), Status::Resolved);
    }

    #[test]
    fn budget_split() {
        assert_eq!(split_budget(&Spike, 63, 11), (63, false));
        assert_eq!(split_budget(&Spike, 64, 11), (48, true));
        assert_eq!(split_budget(&Spike, 70, 68), (70, false));
        assert_eq!(split_budget(&Spike, 84, 68), (68, true));
    }
}
